/* Draws the kernel comparison figure (Lucy and Gaussian kernels, 1D) to the PNG given. */
#include <stdio.h>

#include "ryushi/plot.h"

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: %s OUTPUT.png\n", argv[0]);
        return 2;
    }
    ry_error err;
    ry_error_clear(&err);
    ry_status st = ry_plot_kernel_comparison(argv[1], &err);
    if (st != RY_OK) {
        fprintf(stderr, "plot_kernels: %s\n", err.msg);
        return ry_status_exit_code(st);
    }
    return 0;
}
