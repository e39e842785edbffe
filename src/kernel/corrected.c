/* Corrected SPH: Shepard and linear-reproducing kernel and gradient corrections (see
 * include/ryushi/corrected.h for the formulas). */
#include "ryushi/corrected.h"

#include <math.h>
#include <string.h>

ry_status ry_mat_inverse(int dim, const double *a, double *inv, ry_error *err) {
    double scale = 1.0;
    for (int r = 0; r < dim; ++r) {
        double s = 0;
        for (int c = 0; c < dim; ++c) s += a[3 * r + c] * a[3 * r + c];
        scale *= sqrt(s);
    }
    double det;
    memset(inv, 0, 9 * sizeof *inv);
    if (dim == 1) {
        det = a[0];
    } else if (dim == 2) {
        det = a[0] * a[4] - a[1] * a[3];
    } else {
        det = a[0] * (a[4] * a[8] - a[5] * a[7]) - a[1] * (a[3] * a[8] - a[5] * a[6]) +
              a[2] * (a[3] * a[7] - a[4] * a[6]);
    }
    RY_CHECK(err, isfinite(det) && fabs(det) > 1e-12 * scale && scale > 0, RY_ERR_RANGE,
             "singular %dx%d matrix (det %g)", dim, dim, det);
    const double id = 1.0 / det;
    if (dim == 1) {
        inv[0] = id;
    } else if (dim == 2) {
        inv[0] = a[4] * id;
        inv[1] = -a[1] * id;
        inv[3] = -a[3] * id;
        inv[4] = a[0] * id;
    } else {
        inv[0] = (a[4] * a[8] - a[5] * a[7]) * id;
        inv[1] = (a[2] * a[7] - a[1] * a[8]) * id;
        inv[2] = (a[1] * a[5] - a[2] * a[4]) * id;
        inv[3] = (a[5] * a[6] - a[3] * a[8]) * id;
        inv[4] = (a[0] * a[8] - a[2] * a[6]) * id;
        inv[5] = (a[2] * a[3] - a[0] * a[5]) * id;
        inv[6] = (a[3] * a[7] - a[4] * a[6]) * id;
        inv[7] = (a[1] * a[6] - a[0] * a[7]) * id;
        inv[8] = (a[0] * a[4] - a[1] * a[3]) * id;
    }
    return RY_OK;
}

/* d = xi - xj, r = |d|. */
static double separation(int dim, const double *xi, const double *xj, double *d) {
    double r2 = 0;
    for (int a = 0; a < 3; ++a) {
        d[a] = a < dim ? xi[a] - xj[a] : 0.0;
        r2 += d[a] * d[a];
    }
    return sqrt(r2);
}

/* grad_i W_ij = dW/dr d / r. */
static void kernel_grad(const ry_kernel *k, int dim, const double *d, double r, double *g) {
    double f = r > 0 ? ry_kernel_dwdr(k, r) / r : 0.0;
    for (int a = 0; a < 3; ++a) g[a] = a < dim ? f * d[a] : 0.0;
}

static void point_of(const double *const x[3], int dim, size_t j, double *p) {
    for (int a = 0; a < 3; ++a) p[a] = a < dim ? x[a][j] : 0.0;
}

ry_status ry_corr_build(ry_corr *c, ry_correction type, const ry_kernel *k, const double *xi,
                        double v_self, size_t nn, const uint32_t *nbr, const double *const x[3],
                        const double *vol, ry_error *err) {
    const int dim = k->dim;
    memset(c, 0, sizeof *c);
    c->type = type;
    c->dim = dim;
    c->alpha = 1.0;
    for (int a = 0; a < dim; ++a) c->L[4 * a] = 1.0;
    if (type == RY_CORRECTION_NONE) return RY_OK;

    double m0 = v_self * ry_kernel_w(k, 0.0), m1[3] = {0, 0, 0}, m2[9] = {0}, b[9] = {0};
    for (size_t q = 0; q < nn; ++q) {
        double xj[3], d[3], g[3];
        point_of(x, dim, nbr[q], xj);
        double r = separation(dim, xi, xj, d);
        if (r >= k->radius) continue;
        double vw = vol[nbr[q]] * ry_kernel_w(k, r);
        kernel_grad(k, dim, d, r, g);
        m0 += vw;
        for (int a = 0; a < dim; ++a) {
            m1[a] += vw * d[a];
            for (int e = 0; e < dim; ++e) {
                m2[3 * a + e] += vw * d[a] * d[e];
                b[3 * a + e] -= vol[nbr[q]] * g[a] * d[e]; /* grad W (x) (x_j - x_i) */
            }
        }
    }
    RY_CHECK(err, m0 > 0, RY_ERR_RANGE,
             "corrected SPH: no neighbour within the kernel support at (%g, %g, %g)", xi[0],
             dim > 1 ? xi[1] : 0.0, dim > 2 ? xi[2] : 0.0);
    if (type == RY_CORRECTION_SHEPARD) {
        c->alpha = 1.0 / m0;
        for (int a = 0; a < dim; ++a) c->L[4 * a] = c->alpha;
        return RY_OK;
    }
    double m2i[9];
    ry_status st = ry_mat_inverse(dim, m2, m2i, err);
    if (st == RY_OK) st = ry_mat_inverse(dim, b, c->L, err);
    if (st != RY_OK) {
        ry_error_prefix(err, "corrected SPH at (%g, %g, %g), %zu neighbours: ", xi[0],
                        dim > 1 ? xi[1] : 0.0, dim > 2 ? xi[2] : 0.0, nn);
        return st;
    }
    for (int a = 0; a < dim; ++a) {
        double s = 0;
        for (int e = 0; e < dim; ++e) s += m2i[3 * a + e] * m1[e];
        c->beta[a] = -s;
    }
    /* alpha = 1 / sum V (1 + beta . d) W = 1 / (m0 + beta . m1) */
    double den = m0;
    for (int a = 0; a < dim; ++a) den += c->beta[a] * m1[a];
    RY_CHECK(err, den > 0 && isfinite(den), RY_ERR_RANGE,
             "corrected SPH at (%g, %g, %g): non-positive normalisation %g", xi[0],
             dim > 1 ? xi[1] : 0.0, dim > 2 ? xi[2] : 0.0, den);
    c->alpha = 1.0 / den;
    return RY_OK;
}

double ry_corr_w(const ry_corr *c, const ry_kernel *k, const double *xi, const double *xj) {
    double d[3];
    double r = separation(c->dim, xi, xj, d);
    double lin = 1.0;
    for (int a = 0; a < c->dim; ++a) lin += c->beta[a] * d[a];
    return c->alpha * lin * ry_kernel_w(k, r);
}

void ry_corr_grad_w(const ry_corr *c, const ry_kernel *k, const double *xi, const double *xj,
                    double *g) {
    double d[3], g0[3];
    double r = separation(c->dim, xi, xj, d);
    kernel_grad(k, c->dim, d, r, g0);
    for (int a = 0; a < 3; ++a) {
        double s = 0;
        if (a < c->dim)
            for (int e = 0; e < c->dim; ++e) s += c->L[3 * a + e] * g0[e];
        g[a] = s;
    }
}

ry_status ry_corr_field(ry_correction type, const ry_kernel *k, size_t i, size_t nn,
                        const uint32_t *nbr, const double *const x[3], const double *vol,
                        const double *f, double *value, double *grad, ry_error *err) {
    const int dim = k->dim;
    double xi[3];
    point_of(x, dim, i, xi);
    ry_corr c;
    RY_TRY(ry_corr_build(&c, type, k, xi, vol[i], nn, nbr, x, vol, err));
    double val = vol[i] * c.alpha * ry_kernel_w(k, 0.0) * f[i], gr[3] = {0, 0, 0};
    for (size_t q = 0; q < nn; ++q) {
        const size_t j = nbr[q];
        double xj[3], g[3];
        point_of(x, dim, j, xj);
        val += vol[j] * ry_corr_w(&c, k, xi, xj) * f[j];
        ry_corr_grad_w(&c, k, xi, xj, g);
        const double df = type == RY_CORRECTION_NONE ? f[j] : f[j] - f[i];
        for (int a = 0; a < dim; ++a) gr[a] += vol[j] * df * g[a];
    }
    if (value) *value = val;
    if (grad)
        for (int a = 0; a < 3; ++a) grad[a] = a < dim ? gr[a] : 0.0;
    return RY_OK;
}

/* Inverse of an n x n matrix (n <= 9) by Gauss-Jordan elimination with partial pivoting. */
static int invert_n(int n, double *a, double *inv) {
    double amax = 0;
    for (int r = 0; r < n * n; ++r) amax = fmax(amax, fabs(a[r]));
    for (int r = 0; r < n; ++r)
        for (int c = 0; c < n; ++c) inv[n * r + c] = r == c;
    for (int c = 0; c < n; ++c) {
        int piv = c;
        for (int r = c + 1; r < n; ++r)
            if (fabs(a[n * r + c]) > fabs(a[n * piv + c])) piv = r;
        if (!(fabs(a[n * piv + c]) > 1e-12 * amax)) return -1;
        if (piv != c)
            for (int k = 0; k < n; ++k) {
                double t = a[n * c + k];
                a[n * c + k] = a[n * piv + k];
                a[n * piv + k] = t;
                t = inv[n * c + k];
                inv[n * c + k] = inv[n * piv + k];
                inv[n * piv + k] = t;
            }
        const double d = 1.0 / a[n * c + c];
        for (int k = 0; k < n; ++k) {
            a[n * c + k] *= d;
            inv[n * c + k] *= d;
        }
        for (int r = 0; r < n; ++r) {
            if (r == c) continue;
            const double f = a[n * r + c];
            if (f == 0) continue;
            for (int k = 0; k < n; ++k) {
                a[n * r + k] -= f * a[n * c + k];
                inv[n * r + k] -= f * inv[n * c + k];
            }
        }
    }
    return 0;
}

/* Monomials of d / h: d_a, then d_a d_b / 2 (a == b) or d_a d_b (a < b); returns the count. */
static int quad_basis(int dim, const double *d, double ih, double *p) {
    int m = 0;
    for (int a = 0; a < dim; ++a) p[m++] = d[a] * ih;
    for (int a = 0; a < dim; ++a)
        for (int b = a; b < dim; ++b) p[m++] = (a == b ? 0.5 : 1.0) * d[a] * d[b] * ih * ih;
    return m;
}

ry_status ry_corr_quadratic_gradient(const ry_kernel *k, const double *xi, size_t nn,
                                     const uint32_t *nbr, const double *const x[3],
                                     const double *vol, double *G, double *H, ry_error *err) {
    const int dim = k->dim;
    const double ih = k->inv_h;
    double M[81] = {0}, Mi[81], p[9];
    int nb = 0;
    for (size_t q = 0; q < nn; ++q) {
        double xj[3], d[3];
        point_of(x, dim, nbr[q], xj);
        double r = separation(dim, xj, xi, d); /* d = x_j - x_i */
        if (r >= k->radius) continue;
        const double vw = vol[nbr[q]] * ry_kernel_w(k, r);
        nb = quad_basis(dim, d, ih, p);
        for (int a = 0; a < nb; ++a)
            for (int b = 0; b < nb; ++b) M[nb * a + b] += vw * p[a] * p[b];
    }
    RY_CHECK(err, nb > 0 && invert_n(nb, M, Mi) == 0, RY_ERR_RANGE,
             "corrected SPH (quadratic) at (%g, %g, %g), %zu neighbours: singular moment matrix",
             xi[0], dim > 1 ? xi[1] : 0.0, dim > 2 ? xi[2] : 0.0, nn);
    for (size_t q = 0; q < nn; ++q) {
        double xj[3], d[3];
        point_of(x, dim, nbr[q], xj);
        double r = separation(dim, xj, xi, d);
        const double vw = r < k->radius ? vol[nbr[q]] * ry_kernel_w(k, r) : 0.0;
        quad_basis(dim, d, ih, p);
        for (int a = 0; a < dim; ++a) {
            double t = 0;
            for (int b = 0; b < nb; ++b) t += Mi[nb * a + b] * p[b];
            G[(size_t)dim * q + (size_t)a] = vw * t * ih;
        }
        if (!H) continue;
        double *Hq = H + (size_t)dim * (size_t)dim * q;
        int m = dim;
        for (int a = 0; a < dim; ++a)
            for (int b = a; b < dim; ++b, ++m) {
                double t = 0;
                for (int c = 0; c < nb; ++c) t += Mi[nb * m + c] * p[c];
                Hq[dim * a + b] = Hq[dim * b + a] = vw * t * ih * ih;
            }
    }
    return RY_OK;
}
