/* Unit tests of the wall boundary condition of Adami, Hu & Adams (2012)
 * (src/boundary/walls_adami2012.h), the pair function and finish shared by WCSPH, IISPH and
 * MPS.
 *
 * Set-up: a 2D or 3D lattice of fluid particles (spacing dx = 0.1 m, shifted off the wall
 * particle by a non-symmetric fraction of dx) above one wall particle; weights from the
 * Wendland C2 kernel (h = 1.3 dx) or the MPS weight of Koshizuka (r_e = 2.1 dx).
 *
 * Tolerances:
 *   - a fluid at rest in any gravity field, p_f = p_0 + rho g . (x_f - x_s), gives the exact
 *     hydrostatic wall pressure p_0 + rho g . (x_w - x_s) for any weights (eq. 27 is exact for
 *     pressures linear along g): 1e-12 relative to the pressure scale rho |g| H;
 *   - a uniform fluid velocity u and a wall velocity v_w give a ghost velocity whose mean with
 *     u is v_w (no slip): 1e-12 m/s;
 *   - a linear velocity field v_0 + A x gives v~_w = v_0 + A x_bar, x_bar the weighted mean
 *     position of the neighbours, summed here independently in a plain loop: 1e-12 m/s. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "boundary/walls_adami2012.h"
#include "ryushi/kernel.h"

enum { n_side = 7 };
static const double dx = 0.1, rho = 1000.0, p0 = 2.5e3;
static const double shift[3] = {0.031, 0.017, 0.043};
static const double tol = 1e-12;

/* Fluid lattice point (i, j, k): above the wall particle at the origin in the last axis. */
static void lattice_point(int dim, int i, int j, int k, double *x) {
    int idx[3] = {i - n_side / 2, j - n_side / 2, k - n_side / 2};
    for (int d = 0; d < dim; ++d) x[d] = idx[d] * dx + shift[d];
    x[dim - 1] = (idx[dim - 1] + n_side / 2 + 0.5) * dx + shift[dim - 1];
}

typedef double (*weight_fn)(const void *ctx, double r);

static double weight_kernel(const void *ctx, double r) {
    const ry_kernel *k = ctx;
    return r < k->radius ? ry_kernel_w(k, r) : 0.0;
}
static double weight_mps(const void *ctx, double r) {
    return ry_mps_weight_koshizuka(r, *(const double *)ctx);
}

/* Sums of the wall particle at x_w over the lattice: pressures p_0 + rho g . (x_f - x_s)
 * with x_s = 0, velocities v_0 + A x_f. Also the independent sums of W and x W. */
static int wall_sums(int dim, weight_fn wf, const void *ctx, const double *g, const double *xw,
                     const double *v0, const double A[3][3], ry_adami_sums *s, double *sw,
                     double *sx) {
    memset(s, 0, sizeof *s);
    *sw = 0;
    for (int d = 0; d < 3; ++d) sx[d] = 0;
    int n = 0, nk = dim == 3 ? n_side : 1;
    for (int i = 0; i < n_side; ++i)
        for (int j = 0; j < n_side; ++j)
            for (int k = 0; k < nk; ++k) {
                double xf[3] = {0, 0, 0}, dxwf[3] = {0, 0, 0}, v[3] = {0, 0, 0}, r2 = 0;
                lattice_point(dim, i, j, k, xf);
                for (int d = 0; d < dim; ++d) {
                    dxwf[d] = xw[d] - xf[d];
                    r2 += dxwf[d] * dxwf[d];
                }
                double w = wf(ctx, sqrt(r2));
                if (w <= 0) continue;
                double pf = p0;
                for (int d = 0; d < dim; ++d) pf += rho * g[d] * xf[d];
                for (int d = 0; d < dim; ++d) {
                    v[d] = v0[d];
                    for (int e = 0; e < dim; ++e) v[d] += A[d][e] * xf[e];
                }
                ry_adami_add_pressure(s, w, pf, ry_adami_head(g, dxwf, dim, rho));
                ry_adami_add_velocity(s, w, v, dim);
                *sw += w;
                for (int d = 0; d < dim; ++d) sx[d] += xf[d] * w;
                ++n;
            }
    return n;
}

static void check_case(int dim, weight_fn wf, const void *ctx) {
    static const double gs[3][3] = {{0, -9.81, 0}, {3.0, -9.0, 0}, {1.5, 2.0, -9.5}};
    const double xw[3] = {0, 0, 0};
    const double v0[3] = {0.2, -0.1, 0.05};
    const double A[3][3] = {{0.5, 1.2, -0.3}, {-0.7, 0.1, 0.4}, {0.25, -0.6, 0.9}};
    const double zero[3][3] = {{0}};
    for (int c = 0; c < 3; ++c) {
        const double *g = gs[c];
        ry_adami_sums s;
        double sw, sx[3];
        /* hydrostatics and a linear velocity field */
        int n = wall_sums(dim, wf, ctx, g, xw, v0, A, &s, &sw, sx);
        assert_true(n >= (dim == 2 ? 5 : 10));
        double gnorm = 0;
        for (int d = 0; d < dim; ++d) gnorm += g[d] * g[d];
        double scale = rho * sqrt(gnorm) * n_side * dx + p0;
        double expect = p0;
        for (int d = 0; d < dim; ++d) expect += rho * g[d] * xw[d];
        assert_true(s.sw > 0);
        assert_true(fabs(ry_adami_pressure(&s) - expect) <= tol * scale);
        for (int d = 0; d < dim; ++d) {
            double vbar = v0[d];
            for (int e = 0; e < dim; ++e) vbar += A[d][e] * sx[e] / sw;
            double vw = 0.3 * (d + 1);
            assert_true(fabs(ry_adami_ghost_velocity(&s, d, vw) - (2 * vw - vbar)) <= tol);
        }
        /* a uniform velocity: no slip, (ghost + u) / 2 = v_w */
        wall_sums(dim, wf, ctx, g, xw, v0, zero, &s, &sw, sx);
        for (int d = 0; d < dim; ++d) {
            double vw = -0.4 + 0.25 * d;
            double ghost = ry_adami_ghost_velocity(&s, d, vw);
            assert_true(fabs(0.5 * (ghost + v0[d]) - vw) <= tol);
        }
    }
}

/* The SPH kernel's weights in 2D and 3D. */
static void test_kernel(void **state) {
    (void)state;
    for (int dim = 2; dim <= 3; ++dim) {
        ry_kernel k;
        ry_error err;
        assert_int_equal(ry_kernel_init(&k, RY_KERNEL_WENDLAND_C2, dim, 1.3 * dx, &err), RY_OK);
        check_case(dim, weight_kernel, &k);
    }
}

static void test_mps_weight_2d(void **state) {
    (void)state;
    double re = 2.1 * dx;
    check_case(2, weight_mps, &re);
}

/* The weight-only path (ry_adami_add_weight, used where the pressure is not summed) counts
 * the same sum W as ry_adami_add_pressure. */
static void test_weight_only(void **state) {
    (void)state;
    ry_adami_sums a = {0}, b = {0};
    const double w[4] = {0.3, 1.7, 0.05, 2.2};
    const double v[3] = {1.0, -2.0, 0.5};
    for (int i = 0; i < 4; ++i) {
        ry_adami_add_pressure(&a, w[i], 100.0 * i, 0.0);
        ry_adami_add_velocity(&a, w[i], v, 3);
        ry_adami_add_weight(&b, w[i]);
        ry_adami_add_velocity(&b, w[i], v, 3);
    }
    assert_true(a.sw == b.sw);
    for (int d = 0; d < 3; ++d)
        assert_true(ry_adami_ghost_velocity(&a, d, 0) == ry_adami_ghost_velocity(&b, d, 0));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_kernel),
        cmocka_unit_test(test_mps_weight_2d),
        cmocka_unit_test(test_weight_only),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
