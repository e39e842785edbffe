/* A small symmetric system (the moment matrices of corrected MPS operators). */
#ifndef RYUSHI_MPS_SMALL_H
#define RYUSHI_MPS_SMALL_H

#include <math.h>

#include "util/hd.h"

/* Solves the symmetric d x d system m x = g (d = 2, 3); 0 when m is nearly singular. */
RY_HD static inline int ry_solve_small(int dim, double m[3][3], const double *g, double *x) {
    const double scale = m[0][0] + m[1][1] + (dim > 2 ? m[2][2] : 0.0);
    if (!(scale > 0)) return 0;
    if (dim == 2) {
        const double det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        if (fabs(det) < 1e-3 * scale * scale / 4) return 0;
        x[0] = (m[1][1] * g[0] - m[0][1] * g[1]) / det;
        x[1] = (m[0][0] * g[1] - m[1][0] * g[0]) / det;
        return 1;
    }
    const double c00 = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    const double c01 = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    const double c02 = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    const double det = m[0][0] * c00 + m[0][1] * c01 + m[0][2] * c02;
    if (fabs(det) < 1e-3 * scale * scale * scale / 27) return 0;
    const double c11 = m[0][0] * m[2][2] - m[0][2] * m[2][0];
    const double c12 = m[0][1] * m[2][0] - m[0][0] * m[2][1];
    const double c22 = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    /* m symmetric: the inverse is the cofactor matrix over det. */
    x[0] = (c00 * g[0] + c01 * g[1] + c02 * g[2]) / det;
    x[1] = (c01 * g[0] + c11 * g[1] + c12 * g[2]) / det;
    x[2] = (c02 * g[0] + c12 * g[1] + c22 * g[2]) / det;
    return 1;
}

/* Solves m x_c = g_c for the nc rows of g into x (x may be g); 0 when m is singular, and the
 * rows of x are then zero. */
static inline int ry_solve_rows(int dim, double m[3][3], int nc, double (*g)[3], double (*x)[3]) {
    int ok = 1;
    for (int c = 0; c < nc; ++c) {
        double y[3] = {0, 0, 0};
        ok = ok && ry_solve_small(dim, m, g[c], y);
        for (int b = 0; b < 3; ++b) x[c][b] = ok ? y[b] : 0.0;
    }
    return ok;
}

#endif
