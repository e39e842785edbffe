/* The kernel comparison figure: W and dW/dx of the Lucy and Gaussian kernels in 1D (the two
 * kernels compared in seed 000), with the cubic B-spline for reference. */
#include "ryushi/kernel.h"
#include "ryushi/plot.h"

#include <stdlib.h>

enum { FIG_POINTS = 1281 };

ry_status ry_plot_kernel_comparison(const char *png_path, ry_error *err) {
    static const struct {
        ry_kernel_type type;
        const char *label;
        int color;
        ry_plot_dash dash;
    } curves[] = {
        {RY_KERNEL_LUCY, "Lucy (quartic, support 2h)", 0, RY_PLOT_DASH_SOLID},
        {RY_KERNEL_GAUSSIAN, "Gaussian (truncated at 3h)", 3, RY_PLOT_DASH_SOLID},
        {RY_KERNEL_CUBIC, "cubic B-spline (reference)", 7, RY_PLOT_DASH_DASHED},
    };
    const double xmax = 3.2;
    double *x = malloc(3 * FIG_POINTS * sizeof *x);
    if (!x) return ry_error_set(err, RY_ERR_NOMEM, "kernel figure: out of memory");
    double *w = x + FIG_POINTS, *dw = w + FIG_POINTS;
    ry_plot *p = NULL;
    ry_status st = ry_plot_new(&p, 1, 2, 1500, 620, err);
    if (st == RY_OK) st = ry_plot_title(p, "Lucy and Gaussian smoothing kernels, 1D, h = 1", err);
    if (st == RY_OK) st = ry_plot_panel(p, 0, "Kernel W(x)", "x / h", "W", err);
    if (st == RY_OK) st = ry_plot_panel(p, 1, "Derivative dW/dx", "x / h", "dW/dx", err);
    for (int c = 0; c < 2 && st == RY_OK; c++) {
        st = ry_plot_xrange(p, c, -xmax, xmax, err);
    }
    for (size_t k = 0; k < sizeof curves / sizeof curves[0] && st == RY_OK; k++) {
        ry_kernel ker;
        st = ry_kernel_init(&ker, curves[k].type, 1, 1.0, err);
        if (st != RY_OK) break;
        for (int i = 0; i < FIG_POINTS; i++) {
            double xi = -xmax + 2.0 * xmax * i / (FIG_POINTS - 1);
            double r = xi < 0.0 ? -xi : xi;
            x[i] = xi;
            w[i] = ry_kernel_w(&ker, r);
            dw[i] = (xi < 0.0 ? -1.0 : 1.0) * ry_kernel_dwdr(&ker, r); /* d/dx W(|x|) */
        }
        ry_plot_style style = ry_plot_style_line();
        style.color = curves[k].color;
        style.dash = curves[k].dash;
        style.line_width = curves[k].dash == RY_PLOT_DASH_SOLID ? 2.5 : 2.0;
        st = ry_plot_series(p, 0, curves[k].label, FIG_POINTS, x, w, style, err);
        if (st == RY_OK) st = ry_plot_series(p, 1, curves[k].label, FIG_POINTS, x, dw, style, err);
    }
    if (st == RY_OK) st = ry_plot_write_png(p, png_path, err);
    ry_plot_free(p);
    free(x);
    return st;
}
