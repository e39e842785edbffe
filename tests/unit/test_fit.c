/* ry_fit_oscillation: a damped cosine fitted to a series built by hand. Without noise the
 * period and decay rate come back to the grid's resolution (1e-4 relative asked); with a
 * deterministic noise of 3 % of the amplitude, within 1 % (period) and 10 % (decay rate).
 * ry_drop_shape_fit: the same on a shape moment whose first quarter period is no cosine. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

#include "ryushi/validate.h"

#define PI 3.14159265358979323846

/* w(t) = 3.4 + e^(-150 t)(0.35 cos(2 pi t / 5 ms) - 0.12 sin(...)) + noise, every 0.2 ms to
 * 12.4 ms. */
static void series(ry_table *t, double noise) {
    static char cname_t[] = "t", cname_w[] = "width";
    static char *names[2] = {cname_t, cname_w};
    const size_t n = 63;
    t->ncols = 2;
    t->nrows = n;
    t->names = names;
    t->data = malloc(2 * n * sizeof *t->data);
    assert_non_null(t->data);
    for (size_t r = 0; r < n; ++r) {
        const double s = 2e-4 * (double)r, w = 2 * PI / 5e-3;
        t->data[2 * r] = s;
        t->data[2 * r + 1] = 3.4 + exp(-150 * s) * (0.35 * cos(w * s) - 0.12 * sin(w * s)) +
                             noise * sin(12345.678 * (double)(r + 1));
    }
}

static void test_fit_exact(void **state) {
    (void)state;
    ry_table t;
    series(&t, 0.0);
    const ry_oscillation_fit f = ry_fit_oscillation(&t, "width", 0, 1, 2e-3, 12e-3, 1000);
    assert_int_equal(f.rows, 63);
    assert_true(fabs(f.period / 5e-3 - 1) < 1e-4);
    assert_true(fabs(f.decay / 150 - 1) < 1e-3);
    assert_true(fabs(f.mean - 3.4) < 1e-4);
    assert_true(fabs(f.amplitude - hypot(0.35, 0.12)) < 1e-3);
    assert_true(f.rms < 1e-4);
    /* too few rows: no fit */
    const ry_oscillation_fit g = ry_fit_oscillation(&t, "width", 0, 8e-4, 2e-3, 12e-3, 1000);
    assert_true(isnan(g.period) && g.rows == 0);
    free(t.data);
}

static void test_fit_noisy(void **state) {
    (void)state;
    ry_table t;
    series(&t, 0.03 * hypot(0.35, 0.12));
    const ry_oscillation_fit f = ry_fit_oscillation(&t, "width", 0, 1, 2e-3, 12e-3, 1000);
    assert_true(fabs(f.period / 5e-3 - 1) < 0.01);
    assert_true(fabs(f.decay / 150 - 1) < 0.10);
    free(t.data);
}

/* shape_m4 every 0.1 ms to 8 ms: from the cube's -0.127 a ramp up to T/4 (Lamb's T = 3.7927
 * ms), then 0.04 e^(-100 t) cos(2 pi t / (1.05 T) + 0.3): the fit starts at T/4 and finds
 * the drop's 1.05 T. */
static void test_drop_shape_fit(void **state) {
    (void)state;
    static char cname_t[] = "t", cname_m[] = "shape_m4";
    static char *names[2] = {cname_t, cname_m};
    const double T = 3.7927e-3, Tm = 1.05 * T;
    const size_t n = 81;
    ry_table t = {.ncols = 2, .nrows = n, .names = names};
    t.data = malloc(2 * n * sizeof *t.data);
    assert_non_null(t.data);
    for (size_t r = 0; r < n; ++r) {
        const double s = 1e-4 * (double)r;
        t.data[2 * r] = s;
        t.data[2 * r + 1] =
            s < 0.25 * T ? -0.127 + 0.5 * s / T : 0.04 * exp(-100 * s) * cos(2 * PI * s / Tm + 0.3);
    }
    const ry_oscillation_fit f = ry_drop_shape_fit(&t, T);
    assert_int_equal(f.rows, 71);
    assert_true(fabs(f.period / Tm - 1) < 1e-3);
    assert_true(fabs(f.decay / 100 - 1) < 0.02);
    assert_true(fabs(f.mean) < 1e-4);
    free(t.data);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_fit_exact),
        cmocka_unit_test(test_fit_noisy),
        cmocka_unit_test(test_drop_shape_fit),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
