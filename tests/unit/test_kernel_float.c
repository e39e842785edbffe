/* Unit tests of the single-precision kernel shapes of the pair loops in floats
 * (src/kernel/kernel_float.h) against the double-precision ones of
 * include/ryushi/kernel_shapes.h, for every kernel, at 4001 values of q spread over
 * [0, kappa), computed in a SIMD loop of eight lanes as the pair loops do.
 *
 * Tolerance: 4e-6 of the function's largest magnitude on [0, kappa), about 30 roundings of
 * single precision (2^-24 = 6e-8 each), which the few multiplications and one division of each
 * form stay well within (largest seen: 1.5e-6, the quintic's f, whose three
 * terms cancel in part). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "kernel/kernel_float.h"

enum { npoints = 4001 };

static void check_kernel(ry_kernel_type kt) {
    const double kappa = ry_kernel_kappa(kt);
    double fmax = 0, gmax = 0, ef = 0, eg = 0;
    for (int i = 0; i < npoints; ++i) {
        const double q = kappa * i / (double)npoints;
        fmax = fmax < fabs(ry_kernel_shape(kt, q)) ? fabs(ry_kernel_shape(kt, q)) : fmax;
        const double g = fabs(ry_kernel_dshape_over_q(kt, q));
        gmax = gmax < g ? g : gmax;
    }
    for (int i0 = 0; i0 < npoints; i0 += 8) {
        float q[8], f[8], g[8];
        for (int k = 0; k < 8; ++k) {
            const int i = i0 + k < npoints ? i0 + k : npoints - 1;
            q[k] = (float)(kappa * i / (double)npoints);
        }
#pragma omp simd
        for (int k = 0; k < 8; ++k) {
            f[k] = ry_kshapef(kt, q[k]);
            g[k] = ry_kdshape_over_qf(kt, q[k]);
        }
        for (int k = 0; k < 8; ++k) {
            const double qd = q[k]; /* the same q as the lanes saw */
            const double df = fabs(f[k] - ry_kernel_shape(kt, qd));
            /* (at q = 0 the double form returns 0 where it has no closed form) */
            const double dg = qd > 0 ? fabs(g[k] - ry_kernel_dshape_over_q(kt, qd)) : 0.0;
            ef = ef > df ? ef : df;
            eg = eg > dg ? eg : dg;
        }
    }
    print_message("%-12s f: %.1e, f'/q: %.1e of the largest value\n", ry_kernel_name(kt), ef / fmax,
                  eg / gmax);
    assert_true(ef <= 4e-6 * fmax);
    assert_true(eg <= 4e-6 * gmax);
}

static void test_every_kernel(void **state) {
    (void)state;
    for (int kt = 0; kt < RY_KERNEL_COUNT; ++kt) check_kernel((ry_kernel_type)kt);
}

/* At q = 0 (a particle and itself, inside the support) the forms are finite: the pair terms
 * multiply f'/q by x_ij or r^2 there, which gives 0 only from a finite value. */
static void test_origin_finite(void **state) {
    (void)state;
    for (int kt = 0; kt < RY_KERNEL_COUNT; ++kt) {
        const float f = ry_kshapef((ry_kernel_type)kt, 0.0f);
        const float g = ry_kdshape_over_qf((ry_kernel_type)kt, 0.0f);
        assert_true(isfinite(f) && isfinite(g));
    }
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_every_kernel),
        cmocka_unit_test(test_origin_finite),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
