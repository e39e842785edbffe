/* Unit tests of the SPH kernels and MPS weight functions (include/ryushi/kernel.h).
 *
 * Tolerances (h = 1 throughout unless stated):
 *   - radial integral S_d * int_0^kappa W(q) q^(d-1) dq = 1 by composite Simpson: 1e-10;
 *   - lattice sums on a Cartesian lattice with dx = h / 20, shifted by a non-symmetric
 *     fraction of dx so that nothing cancels by symmetry (d = 1, 2, 3):
 *       sum dx^d W = 1 within 2e-7 (largest seen: 7e-8, Wendland C2 in 1D);
 *       sum dx^d grad W = 0 within 5e-5 / h (largest seen: 1.9e-5 / h, Wendland C2 in 1D: the
 *         gradient sum is the derivative of the lattice sum of W with respect to the lattice
 *         offset, so it is about 2 pi h / dx times larger);
 *       sum dx^d x_a dW/dx_b = -delta_ab within 1e-6 (largest seen: 4e-7, Lucy in 2D);
 *     the truncated Gaussian jumps by e^-9 sigma_d at q = 3, so its first moment is compared
 *     with -delta_ab (1 - V_d(3) sigma_d e^-9), the surface term of the jump (V_d(3) the volume
 *     of the ball of radius 3), within 1e-5 (largest seen: 4.9e-6 in 2D): the jump makes the
 *     lattice error first order in dx;
 *   - analytic dW/dr against a central difference (step 1e-6 h): 1e-7 of max |dW/dr|. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "ryushi/kernel.h"

#define PI 3.14159265358979323846

enum { lattice_h_over_dx = 20 };
static const double tol_sum = 2e-7;
static const double tol_grad = 5e-5;
static const double tol_moment = 1e-6;
static const double tol_moment_gaussian = 1e-5;

static ry_kernel make_kernel(ry_kernel_type t, int dim, double h) {
    ry_kernel k;
    ry_error err;
    ry_error_clear(&err);
    assert_int_equal(ry_kernel_init(&k, t, dim, h, &err), RY_OK);
    return k;
}

static double unit_sphere_area(int dim) {
    return dim == 1 ? 2.0 : dim == 2 ? 2.0 * PI : 4.0 * PI;
}

static double ball_volume(int dim, double r) {
    return dim == 1 ? 2.0 * r : dim == 2 ? PI * r * r : 4.0 / 3.0 * PI * r * r * r;
}

/* Composite Simpson of S_d W(q) q^(d-1) over [a, b] with n (even) intervals. */
static double simpson_piece(const ry_kernel *k, double a, double b, int n) {
    double step = (b - a) / n, sum = 0.0;
    for (int i = 0; i <= n; i++) {
        double q = a + i * step;
        /* Evaluate just inside the piece at its ends so the truncated Gaussian's end counts. */
        double qe = i == n ? q - 1e-14 : q;
        double w = ry_kernel_w(k, qe) * pow(qe, k->dim - 1);
        sum += (i == 0 || i == n ? 1.0 : i % 2 ? 4.0 : 2.0) * w;
    }
    return sum * step / 3.0 * unit_sphere_area(k->dim);
}

static void test_radial_normalisation(void **state) {
    (void)state;
    for (int t = 0; t < RY_KERNEL_COUNT; t++) {
        for (int dim = 1; dim <= 3; dim++) {
            ry_kernel k = make_kernel((ry_kernel_type)t, dim, 1.0);
            double total = 0.0;
            /* Pieces between the integer knots so Simpson integrates each polynomial exactly. */
            for (int a = 0; a < (int)k.kappa; a++) total += simpson_piece(&k, a, a + 1, 2000);
            if (fabs(total - 1.0) > 1e-10)
                fail_msg("%s %dD: radial integral %.15g", ry_kernel_name(k.type), dim, total);
        }
    }
}

/* Sums over the lattice x = (i + off) dx: W, grad W and x_a dW/dx_b. */
typedef struct lattice_sums {
    double w;
    double grad[3];
    double moment[3][3];
} lattice_sums;

static lattice_sums lattice_sum(const ry_kernel *k, double dx) {
    static const double off[3] = {0.31, 0.17, 0.23};
    lattice_sums s = {0};
    int n = (int)ceil(k->radius / dx) + 1;
    int lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int a = 0; a < k->dim; a++) {
        lo[a] = -n;
        hi[a] = n;
    }
    double vol = pow(dx, k->dim);
    for (int i = lo[0]; i <= hi[0]; i++) {
        for (int j = lo[1]; j <= hi[1]; j++) {
            for (int l = lo[2]; l <= hi[2]; l++) {
                double x[3] = {(i + off[0]) * dx, (j + off[1]) * dx, (l + off[2]) * dx};
                for (int a = k->dim; a < 3; a++) x[a] = 0.0;
                double r = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
                if (r >= k->radius) continue;
                s.w += vol * ry_kernel_w(k, r);
                double g = vol * ry_kernel_dwdr(k, r) / r;
                for (int b = 0; b < 3; b++) {
                    s.grad[b] += g * x[b];
                    for (int a = 0; a < 3; a++) s.moment[a][b] += g * x[a] * x[b];
                }
            }
        }
    }
    return s;
}

static void test_lattice_sums(void **state) {
    (void)state;
    for (int t = 0; t < RY_KERNEL_COUNT; t++) {
        for (int dim = 1; dim <= 3; dim++) {
            for (int hi = 0; hi < 2; hi++) {
                double h = hi ? 0.37 : 1.0; /* the sums are scale free */
                ry_kernel k = make_kernel((ry_kernel_type)t, dim, h);
                const char *name = ry_kernel_name(k.type);
                double tol_m = t == RY_KERNEL_GAUSSIAN ? tol_moment_gaussian : tol_moment;
                double jump = 0.0; /* surface term of the Gaussian's truncation */
                if (t == RY_KERNEL_GAUSSIAN)
                    jump = ball_volume(dim, 3.0) * k.norm * pow(h, dim) * exp(-9.0);
                lattice_sums s = lattice_sum(&k, h / lattice_h_over_dx);
                if (fabs(s.w - 1.0) > tol_sum)
                    fail_msg("%s %dD h=%g: sum W dV = %.12g", name, dim, h, s.w);
                for (int b = 0; b < dim; b++) {
                    if (fabs(s.grad[b]) * h > tol_grad)
                        fail_msg("%s %dD h=%g: sum dW/dx_%d dV = %.3g", name, dim, h, b, s.grad[b]);
                    for (int a = 0; a < dim; a++) {
                        double want = a == b ? -(1.0 - jump) : 0.0;
                        if (fabs(s.moment[a][b] - want) > tol_m)
                            fail_msg("%s %dD h=%g: sum x_%d dW/dx_%d dV = %.12g, want %.12g", name,
                                     dim, h, a, b, s.moment[a][b], want);
                    }
                }
            }
        }
    }
}

static void test_derivative_vs_finite_difference(void **state) {
    (void)state;
    const double step = 1e-6;
    for (int t = 0; t < RY_KERNEL_COUNT; t++) {
        for (int dim = 1; dim <= 3; dim++) {
            double h = dim == 2 ? 0.8 : 1.3;
            ry_kernel k = make_kernel((ry_kernel_type)t, dim, h);
            double gmax = 0.0;
            for (int i = 0; i <= 1000; i++)
                gmax = fmax(gmax, fabs(ry_kernel_dwdr(&k, k.radius * i / 1000.0)));
            for (int i = 1; i < 997; i++) {
                double r = k.radius * (i + 0.5) / 1000.0;
                double fd = (ry_kernel_w(&k, r + step * h) - ry_kernel_w(&k, r - step * h)) /
                            (2.0 * step * h);
                double an = ry_kernel_dwdr(&k, r);
                if (fabs(fd - an) > 1e-7 * gmax)
                    fail_msg("%s %dD r=%g: dW/dr %.12g, finite difference %.12g",
                             ry_kernel_name(k.type), dim, r, an, fd);
            }
        }
    }
}

static void test_shape_values(void **state) {
    (void)state;
    /* Peak values and a few hand-computed points of f(q). */
    assert_float_equal(ry_kernel_shape(RY_KERNEL_CUBIC, 0.0), 1.0, 1e-15);
    assert_float_equal(ry_kernel_shape(RY_KERNEL_CUBIC, 1.0), 0.25, 1e-15);
    assert_float_equal(ry_kernel_shape(RY_KERNEL_QUINTIC, 0.0), 66.0, 1e-12);
    assert_float_equal(ry_kernel_shape(RY_KERNEL_QUINTIC, 1.0), 26.0, 1e-12);
    assert_float_equal(ry_kernel_shape(RY_KERNEL_QUINTIC, 2.0), 1.0, 1e-12);
    assert_float_equal(ry_kernel_shape(RY_KERNEL_WENDLAND_C2, 1.0), 3.0 / 16.0, 1e-15);
    assert_float_equal(ry_kernel_shape(RY_KERNEL_WENDLAND_C4, 1.0),
                       (1.0 / 64.0) * (1.0 + 3.0 + 35.0 / 12.0), 1e-15);
    assert_float_equal(ry_kernel_shape(RY_KERNEL_LUCY, 1.0), 2.5 / 8.0, 1e-15);
    assert_float_equal(ry_kernel_shape(RY_KERNEL_GAUSSIAN, 1.0), exp(-1.0), 1e-15);
    for (int t = 0; t < RY_KERNEL_COUNT; t++) {
        assert_float_equal(ry_kernel_dshape((ry_kernel_type)t, 0.0), 0.0, 1e-15);
        if (t != RY_KERNEL_QUINTIC)
            assert_float_equal(ry_kernel_shape((ry_kernel_type)t, 0.0), 1.0, 1e-15);
    }
    assert_float_equal(ry_kernel_shape(RY_KERNEL_COUNT, 0.5), 0.0, 0.0);
    assert_float_equal(ry_kernel_dshape(RY_KERNEL_COUNT, 0.5), 0.0, 0.0);
}

static void test_support_continuity_sign(void **state) {
    (void)state;
    for (int t = 0; t < RY_KERNEL_COUNT; t++) {
        for (int dim = 1; dim <= 3; dim++) {
            ry_kernel k = make_kernel((ry_kernel_type)t, dim, 0.5);
            const char *name = ry_kernel_name(k.type);
            double w0 = ry_kernel_w(&k, 0.0);
            assert_true(w0 > 0.0);
            assert_float_equal(k.radius, k.kappa * k.h, 1e-15);
            assert_float_equal(k.kappa, ry_kernel_kappa(k.type), 0.0);
            /* Zero at and beyond the support. */
            assert_float_equal(ry_kernel_w(&k, k.radius), 0.0, 0.0);
            assert_float_equal(ry_kernel_dwdr(&k, k.radius), 0.0, 0.0);
            assert_float_equal(ry_kernel_w(&k, 1.5 * k.radius), 0.0, 0.0);
            /* Just inside the support: continuous to zero, except the truncated Gaussian,
             * whose jump is exactly e^-9 of the peak. */
            double inside = ry_kernel_w(&k, k.radius * (1.0 - 1e-9));
            if (t == RY_KERNEL_GAUSSIAN)
                assert_float_equal(inside / w0, exp(-9.0), 1e-12);
            else if (inside > 1e-20 * w0)
                fail_msg("%s %dD: W just inside the support = %g", name, dim, inside);
            /* Continuous across the interior knots and everywhere on a fine grid. */
            double prev = w0;
            for (int i = 1; i <= 30000; i++) {
                double r = k.radius * i / 30000.0 * (1.0 - 1e-12);
                double w = ry_kernel_w(&k, r), g = ry_kernel_dwdr(&k, r);
                if (!(w >= 0.0)) fail_msg("%s %dD: W(%g) = %g < 0", name, dim, r, w);
                if (!(g <= 0.0)) fail_msg("%s %dD: dW/dr(%g) = %g > 0", name, dim, r, g);
                if (fabs(w - prev) > 1e-3 * w0)
                    fail_msg("%s %dD: W jumps near r = %g", name, dim, r);
                prev = w;
            }
            for (int knot = 1; knot < (int)k.kappa; knot++) {
                double r = knot * k.h, e = 1e-12 * k.h;
                assert_float_equal(ry_kernel_w(&k, r - e), ry_kernel_w(&k, r + e), 1e-9 * w0);
            }
        }
    }
}

static void test_init_rejects_bad_input(void **state) {
    (void)state;
    ry_kernel k;
    ry_error err;
    ry_error_clear(&err);
    assert_int_equal(ry_kernel_init(&k, (ry_kernel_type)-1, 2, 1.0, &err), RY_ERR_INPUT);
    assert_true(err.msg[0] != '\0');
    assert_int_equal(ry_kernel_init(&k, RY_KERNEL_COUNT, 2, 1.0, &err), RY_ERR_INPUT);
    ry_error_clear(&err);
    assert_int_equal(ry_kernel_init(&k, RY_KERNEL_CUBIC, 0, 1.0, &err), RY_ERR_RANGE);
    assert_non_null(strstr(err.msg, "dimension"));
    assert_int_equal(ry_kernel_init(&k, RY_KERNEL_CUBIC, 4, 1.0, &err), RY_ERR_RANGE);
    const double bad_h[] = {0.0, -1.0, NAN, INFINITY, -INFINITY};
    for (size_t i = 0; i < sizeof bad_h / sizeof bad_h[0]; i++) {
        ry_error_clear(&err);
        assert_int_equal(ry_kernel_init(&k, RY_KERNEL_LUCY, 3, bad_h[i], &err), RY_ERR_RANGE);
        assert_non_null(strstr(err.msg, "smoothing length"));
    }
    /* h so small that sigma / h^3 overflows. */
    assert_int_equal(ry_kernel_init(&k, RY_KERNEL_CUBIC, 3, 1e-200, &err), RY_ERR_RANGE);
    /* A NULL error context is allowed. */
    assert_int_equal(ry_kernel_init(&k, RY_KERNEL_CUBIC, 5, 1.0, NULL), RY_ERR_RANGE);
    assert_int_equal(ry_kernel_init(&k, RY_KERNEL_CUBIC, 3, 1e-3, NULL), RY_OK);
}

static void test_names(void **state) {
    (void)state;
    static const char *const names[] = {"cubic",       "quintic", "wendland_c2",
                                        "wendland_c4", "lucy",    "gaussian"};
    for (int t = 0; t < RY_KERNEL_COUNT; t++) {
        assert_string_equal(ry_kernel_name((ry_kernel_type)t), names[t]);
        assert_int_equal(ry_kernel_type_from_name(names[t]), t);
    }
    assert_int_equal(ry_kernel_type_from_name("Cubic"), -1);
    assert_int_equal(ry_kernel_type_from_name(""), -1);
    assert_int_equal(ry_kernel_type_from_name(NULL), -1);
    assert_string_equal(ry_kernel_name(RY_KERNEL_COUNT), "unknown");
    assert_float_equal(ry_kernel_kappa(RY_KERNEL_COUNT), 0.0, 0.0);
    assert_float_equal(ry_kernel_kappa(RY_KERNEL_QUINTIC), 3.0, 0.0);
    assert_float_equal(ry_kernel_kappa(RY_KERNEL_GAUSSIAN), 3.0, 0.0);
    assert_float_equal(ry_kernel_kappa(RY_KERNEL_WENDLAND_C4), 2.0, 0.0);
}

static void test_mps_weights(void **state) {
    (void)state;
    const double re = 2.1, step = 1e-6;
    /* Values. */
    assert_float_equal(ry_mps_weight_koshizuka(1.05, re), 1.0, 1e-15);
    assert_float_equal(ry_mps_weight_koshizuka(re, re), 0.0, 0.0);
    assert_float_equal(ry_mps_weight_koshizuka(3.0, re), 0.0, 0.0);
    assert_float_equal(ry_mps_weight_tamai(0.0, re), 1.0, 1e-15);
    assert_float_equal(ry_mps_weight_tamai(1.05, re), 0.25, 1e-15);
    assert_float_equal(ry_mps_weight_tamai(re, re), 0.0, 0.0);
    assert_float_equal(ry_mps_weight_tamai(3.0, re), 0.0, 0.0);
    assert_float_equal(ry_mps_dweight_koshizuka(3.0, re), 0.0, 0.0);
    assert_float_equal(ry_mps_dweight_tamai(3.0, re), 0.0, 0.0);
    /* Both vanish continuously at re. */
    assert_true(ry_mps_weight_koshizuka(re * (1.0 - 1e-12), re) < 1e-11);
    assert_true(ry_mps_weight_tamai(re * (1.0 - 1e-9), re) < 1e-17);
    /* Derivatives against central differences. */
    for (int i = 1; i < 200; i++) {
        double r = re * (i + 0.37) / 200.0;
        if (r + step >= re) break;
        double fdk =
            (ry_mps_weight_koshizuka(r + step, re) - ry_mps_weight_koshizuka(r - step, re)) /
            (2.0 * step);
        double fdt =
            (ry_mps_weight_tamai(r + step, re) - ry_mps_weight_tamai(r - step, re)) / (2.0 * step);
        double dk = ry_mps_dweight_koshizuka(r, re), dt = ry_mps_dweight_tamai(r, re);
        if (fabs(fdk - dk) > 1e-6 * fabs(dk))
            fail_msg("Koshizuka weight r=%g: derivative %.12g, finite difference %.12g", r, dk,
                     fdk);
        if (fabs(fdt - dt) > 1e-8)
            fail_msg("Tamai weight r=%g: derivative %.12g, finite difference %.12g", r, dt, fdt);
        assert_true(dk < 0.0 && dt <= 0.0);
        assert_true(ry_mps_weight_koshizuka(r, re) > 0.0 && ry_mps_weight_tamai(r, re) > 0.0);
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_radial_normalisation),
        cmocka_unit_test(test_lattice_sums),
        cmocka_unit_test(test_derivative_vs_finite_difference),
        cmocka_unit_test(test_shape_values),
        cmocka_unit_test(test_support_continuity_sign),
        cmocka_unit_test(test_init_rejects_bad_input),
        cmocka_unit_test(test_names),
        cmocka_unit_test(test_mps_weights),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
