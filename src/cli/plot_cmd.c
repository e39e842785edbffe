/* ryushi plot: figures the project draws itself. */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "ryushi/plot.h"

int ry_cli_plot(int argc, char **argv) {
    const char *what = argc > 2 ? argv[2] : NULL;
    const char *out = NULL;
    for (int i = 3; i < argc; ++i) {
        if ((strcmp(argv[i], "-o") == 0 || strcmp(argv[i], "--output") == 0) && i + 1 < argc)
            out = argv[++i];
        else {
            fprintf(stderr, "ryushi: plot: unexpected argument '%s'\n", argv[i]);
            return 2;
        }
    }
    if (!what || strcmp(what, "kernels") != 0) {
        fprintf(stderr, "ryushi: plot: expected 'kernels' (ryushi plot kernels -o FILE.png)\n");
        return 2;
    }
    if (!out) out = "kernels_lucy_gaussian.png";
    ry_error err = {0};
    if (ry_plot_kernel_comparison(out, &err) != RY_OK) {
        fprintf(stderr, "ryushi: %s: %s\n", ry_status_name(err.code), err.msg);
        return ry_status_exit_code(err.code);
    }
    printf("wrote %s\n", out);
    return 0;
}
