/* ryushi validate: the full-resolution validation cases, compared with their references,
 * with plots. Results are recorded in docs/validation.md. */
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "ryushi/atomic_file.h"

/* A validation by name; `all` runs those marked in_all, in this order. */
typedef struct validation {
    const char *name;
    int (*run)(const char *root, const char *out, int quick, int *failures);
    int in_all;
} validation;

static const validation validations[] = {
    {"dam_break", ry_cli_validate_dam_break, 1},
    {"cavity", ry_cli_validate_cavity, 1},
    {"channel", ry_cli_validate_channel, 1},
    {"cantilever", ry_cli_validate_cantilever, 1},
    {"plate", ry_cli_validate_plate, 1},
    {"buckling", ry_cli_validate_buckling, 1},
    {"mps", ry_cli_validate_mps, 1},
    {"rheology", ry_cli_validate_rheology, 1},
    {"iisph", ry_cli_validate_iisph, 1},
    {"rt", ry_cli_validate_rt, 0},
    {"air", ry_cli_validate_air, 0},
    {"eye", ry_cli_validate_eye, 0},
    {"eye_positions", ry_cli_validate_eye_positions, 0},
    {"eye_clinical", ry_cli_validate_eye_clinical, 0},
    {"embolization", ry_cli_validate_embolization, 0},
    {"embolization3d", ry_cli_validate_embolization3d, 0},
    {"embolization3d_all", ry_cli_validate_embolization3d_all, 0},
    {"embolization3d_wide", ry_cli_validate_embolization3d_wide, 0},
    {"wetting", ry_cli_validate_wetting, 0},
};
enum { NVALIDATIONS = sizeof validations / sizeof validations[0] };

int ry_cli_validate(int argc, char **argv) {
    const char *root = RY_SOURCE_DIR, *out = "out/validate";
    int quick = 0, failures = 0;
    const char *root_env = getenv("RY_SOURCE_DIR");
    if (root_env && *root_env) root = root_env;
    const char *what = "all";
    for (int i = 2; i < argc; ++i) {
        if (strcmp(argv[i], "--quick") == 0)
            quick = 1;
        else if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
            out = argv[++i];
        else if (strcmp(argv[i], "--root") == 0 && i + 1 < argc)
            root = argv[++i];
        else if (strcmp(argv[i], "--threads") == 0 && i + 1 < argc)
            omp_set_num_threads(atoi(argv[++i]) > 0 ? atoi(argv[i]) : 1);
        else if (argv[i][0] != '-')
            what = argv[i];
        else {
            fprintf(stderr, "ryushi: validate: unknown option '%s'\n", argv[i]);
            return 2;
        }
    }
    const int all = strcmp(what, "all") == 0;
    const validation *one = NULL;
    for (int k = 0; k < NVALIDATIONS; ++k)
        if (strcmp(what, validations[k].name) == 0) one = &validations[k];
    if (!all && !one) {
        fprintf(stderr, "ryushi: validate: expected ");
        for (int k = 0; k < NVALIDATIONS; ++k) fprintf(stderr, "%s, ", validations[k].name);
        fprintf(stderr, "or all, got '%s'\n", what);
        return 2;
    }
    ry_error err = {0};
    if (ry_mkdir_p(out, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        return 3;
    }
    for (int k = 0; k < NVALIDATIONS; ++k)
        if (all ? validations[k].in_all : &validations[k] == one)
            validations[k].run(root, out, quick, &failures);
    printf("validate: %s (%d failure(s)); output in %s\n", failures ? "FAILED" : "passed", failures,
           out);
    return failures ? 1 : 0;
}
