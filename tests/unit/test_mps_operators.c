/* Unit tests of the MPS operators: the gradient (src/physics/gradient_mps_koshizuka1996.h),
 * shared by the MPS pressure correction, MPS rheology and the surface-tension curvature, and
 * the Laplacian's coefficient (src/physics/laplacian_mps_koshizuka1996.h):
 *
 *   - the corrected form on hand-placed, one-sided neighbourhoods (2D and 3D, Tamai's weight,
 *     re = 2.1 l0) recovers the gradient of a linear field exactly: within 1e-12 relative (a
 *     few roundings of the 2x2 or 3x3 solve);
 *   - the standard form d/n0 sum_j (f_j - f_i) x_ji / r^2 w_ij on the full square and cubic
 *     lattice within re, n0 the lattice's (ry_mps_lattice), is exact for a linear field too
 *     (the lattice's moment matrix is n0 / d times the identity): within 1e-12;
 *   - with the neighbours on one line the moment matrix is singular and the pressure form
 *     falls back to the standard one: d/n0 sum_j (w/r^2) df x_ji, computed here by hand (in
 *     another order), within 1e-14 relative;
 *   - the divergence d/n0 sum_j (u_j - u_i) . x_ji / r^2 w_ij of a linear field u = A x on the
 *     full lattice within re is tr A (the lattice's moment matrix is n0 / d times the
 *     identity): within 1e-12;
 *   - the Laplacian 2d/(lambda n0) sum_j (f_j - f_i) w_ij of f = a x^2 + b y^2 (+ c z^2) on the
 *     full square and cubic lattice within re = 3.1 l0, with the lattice's n0 and lambda, is
 *     2 (a + b + c), exact for a quadratic (lambda is defined so): within 1e-12. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "physics/gradient_mps_koshizuka1996.h"
#include "physics/laplacian_mps_koshizuka1996.h"
#include "ryushi/mps.h"

static const double l0 = 0.01, re = 2.1 * 0.01;

/* f = 2 + a . x */
static double field(const double *a, const double *x, int dim) {
    double f = 2.0;
    for (int d = 0; d < dim; ++d) f += a[d] * x[d];
    return f;
}

/* The pressure form over the neighbours xs[k] of a particle at the origin. */
static void gradient(const double (*xs)[3], int nk, const double *a, int dim, double n0,
                     int corrected, double *out) {
    double m[3][3] = {{0}}, g[3] = {0, 0, 0};
    const double o[3] = {0, 0, 0};
    for (int k = 0; k < nk; ++k) {
        double r2 = 0;
        for (int d = 0; d < dim; ++d) r2 += xs[k][d] * xs[k][d];
        const double wr = ry_mps_weight_tamai(sqrt(r2), re) / r2;
        ry_grad_value_add(g, wr, field(a, xs[k], dim) - field(a, o, dim), xs[k], dim);
        ry_grad_moment_add(m, wr, xs[k], dim);
    }
    ry_mps_pressure_gradient(m, g, dim, n0, corrected, out);
}

static void test_corrected_one_sided(void **state) {
    (void)state;
    /* 2D: neighbours on the right and above only, unevenly spaced. */
    const double xs2[][3] = {{l0, 0, 0},
                             {1.3 * l0, 0.9 * l0, 0},
                             {0.2 * l0, 1.1 * l0, 0},
                             {1.7 * l0, -0.6 * l0, 0},
                             {0.5 * l0, 1.8 * l0, 0}};
    const double a2[3] = {3.0, -5.0, 0};
    double out[3];
    gradient(xs2, 5, a2, 2, 1.0, 1, out);
    for (int d = 0; d < 2; ++d) assert_true(fabs(out[d] - a2[d]) <= 1e-12 * fabs(a2[d]));
    /* 3D: one octant and a little beyond. */
    const double xs3[][3] = {{l0, 0, 0},
                             {0, l0, 0},
                             {0, 0, l0},
                             {l0, l0, 0.3 * l0},
                             {0.4 * l0, 0, 1.5 * l0},
                             {1.2 * l0, 0.7 * l0, 0.9 * l0},
                             {-0.3 * l0, 1.4 * l0, 0.2 * l0}};
    const double a3[3] = {-1.5, 0.25, 4.0};
    gradient(xs3, 7, a3, 3, 1.0, 1, out);
    for (int d = 0; d < 3; ++d) assert_true(fabs(out[d] - a3[d]) <= 1e-12 * fabs(a3[d]));
}

static void test_standard_on_lattice(void **state) {
    (void)state;
    for (int dim = 2; dim <= 3; ++dim) {
        double n0, lambda;
        ry_mps_lattice(dim, l0, re, &n0, &lambda);
        double xs[125][3];
        int nk = 0;
        for (int i = -2; i <= 2; ++i)
            for (int j = -2; j <= 2; ++j)
                for (int k = (dim > 2 ? -2 : 0); k <= (dim > 2 ? 2 : 0); ++k) {
                    const double r = l0 * sqrt((double)(i * i + j * j + k * k));
                    if ((i || j || k) && r < re) {
                        xs[nk][0] = i * l0;
                        xs[nk][1] = j * l0;
                        xs[nk][2] = k * l0;
                        ++nk;
                    }
                }
        const double a[3] = {3.0, -5.0, 0.5};
        double out[3];
        gradient((const double(*)[3])xs, nk, a, dim, n0, 0, out);
        print_message("%dD lattice, %d neighbours: standard gradient (%.15g, %.15g, %.15g)\n", dim,
                      nk, out[0], out[1], dim > 2 ? out[2] : 0.0);
        for (int d = 0; d < dim; ++d) assert_true(fabs(out[d] - a[d]) <= 1e-12 * fabs(a[d]));
    }
}

static void test_fallback_when_singular(void **state) {
    (void)state;
    /* 2D, all neighbours on the x axis: C_i has no yy part. */
    const double xs[][3] = {{l0, 0, 0}, {-l0, 0, 0}, {2 * l0, 0, 0}};
    const double a[3] = {3.0, -5.0, 0}, n0 = 6.5;
    double want[2] = {0, 0};
    for (int k = 0; k < 3; ++k) {
        const double r = fabs(xs[k][0]), s = r / re - 1.0, wr = s * s / (r * r);
        want[0] += 2.0 / n0 * wr * (a[0] * xs[k][0]) * xs[k][0];
    }
    double out[3];
    gradient(xs, 3, a, 2, n0, 1, out);
    print_message("collinear: (%.15g, %.15g), by hand (%.15g, 0)\n", out[0], out[1], want[0]);
    assert_true(fabs(out[0] - want[0]) <= 1e-14 * fabs(want[0]));
    assert_true(out[1] == 0.0);
}

static void test_divergence_on_lattice(void **state) {
    (void)state;
    const double A[3][3] = {{0.7, -1.0, 0.3}, {2.0, -0.2, 0.5}, {0.1, 0.4, 1.1}};
    for (int dim = 2; dim <= 3; ++dim) {
        double n0, lambda;
        ry_mps_lattice(dim, l0, re, &n0, &lambda);
        double s = 0, tr = 0;
        for (int d = 0; d < dim; ++d) tr += A[d][d];
        for (int i = -2; i <= 2; ++i)
            for (int j = -2; j <= 2; ++j)
                for (int k = (dim > 2 ? -2 : 0); k <= (dim > 2 ? 2 : 0); ++k) {
                    const double x[3] = {i * l0, j * l0, k * l0};
                    const double r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
                    if (r2 == 0 || sqrt(r2) >= re) continue;
                    double du = 0; /* (u_j - u_i) . x_ji with u_i = 0 */
                    for (int a = 0; a < dim; ++a)
                        for (int b = 0; b < dim; ++b) du += A[a][b] * x[b] * x[a];
                    s += ry_mps_divergence_term(du, r2, ry_mps_weight_tamai(sqrt(r2), re));
                }
        const double div = ry_mps_divergence(s, dim, n0);
        print_message("%dD lattice: divergence %.15g, tr A %.15g\n", dim, div, tr);
        assert_true(fabs(div - tr) <= 1e-12 * fabs(tr));
    }
}

static void test_laplacian_on_lattice(void **state) {
    (void)state;
    const double rl = 3.1 * l0, c[3] = {1.5, -0.5, 2.0};
    for (int dim = 2; dim <= 3; ++dim) {
        double n0, lambda;
        ry_mps_lattice(dim, l0, rl, &n0, &lambda);
        double s = 0;
        for (int i = -3; i <= 3; ++i)
            for (int j = -3; j <= 3; ++j)
                for (int k = (dim > 2 ? -3 : 0); k <= (dim > 2 ? 3 : 0); ++k) {
                    const double x[3] = {i * l0, j * l0, k * l0};
                    const double r = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
                    if (r == 0 || r >= rl) continue;
                    double f = 0; /* f_j - f_i, f_i = 0 at the origin */
                    for (int d = 0; d < dim; ++d) f += c[d] * x[d] * x[d];
                    s += f * ry_mps_weight_tamai(r, rl);
                }
        const double lap = ry_mps_laplacian_coefficient(dim, lambda, n0) * s;
        const double want = 2.0 * (c[0] + c[1] + (dim > 2 ? c[2] : 0.0));
        print_message("%dD lattice: Laplacian %.15g, exact %.15g\n", dim, lap, want);
        assert_true(fabs(lap - want) <= 1e-12 * fabs(want));
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_corrected_one_sided),    cmocka_unit_test(test_standard_on_lattice),
        cmocka_unit_test(test_fallback_when_singular), cmocka_unit_test(test_divergence_on_lattice),
        cmocka_unit_test(test_laplacian_on_lattice),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
