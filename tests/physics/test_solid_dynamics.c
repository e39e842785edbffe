/* Elastic solids in motion: short version of `ryushi validate plate` (full table in
 * docs/validation.md). */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>

#include "solid_test.h"
#include "manifest_tol.h"
#include "ryushi/run.h"

/* Tolerance `key` of validation/plate.yaml. */
static double tol(const char *key) {
    return manifest_tol(root, "plate", key);
}

/* Thin-plate period of the plate of cases/oscillating_plate.yaml: 0.25403 s. */
static double plate_period(void) {
    return 2 * 3.14159265358979323846 / ry_plate_omega(2.0e6, 0.3975, 1000.0, 0.02, 0.2);
}

/* Updated-Lagrangian SPH with artificial stress, 4 particles across the plate, 2.2 periods:
 * the period against thin-plate theory (the form converges slowly, see docs/validation.md),
 * the energy over the last period against the first, and no tensile clumping (the smallest
 * pair distance over the spacing; tolerances and measured values: validation/plate.yaml). */
static void test_plate_updated_lagrangian(void **state) {
    (void)state;
    const char *sets[] = {"spacing=0.005", "time.end=0.56"};
    ry_sim sim;
    ry_table t;
    run_solid_case("oscillating_plate.yaml", 2, sets, "plate_ul", &sim, &t);
    ry_oscillation o = ry_series_oscillation(&t, "tip_deflection");
    const double T = plate_period(), msp = ry_column_min(&t, "min_spacing");
    printf("plate, UL, H/dx = 4: period %.5f s (theory %.5f, %+.2f %%), energy first %.5f last "
           "%.5f J, min r/dx %.3f\n",
           o.period, T, 100 * (o.period - T) / T, o.energy_first, o.energy_last, msp);
    assert_true(o.crossings >= tol("crossings_min"));
    assert_true(fabs(o.period - T) / T <= tol("ul_period_4"));
    assert_true(o.energy_last <= o.energy_first * (1 + tol("energy_growth")));
    assert_true(msp >= tol("ul_min_spacing"));
    ry_table_free(&t);
    ry_sim_free(&sim);
}

/* Total-Lagrangian SPH (quadratic correction, clamp on the root face, a quarter of the CFL
 * step), 4 particles across, 2.2 periods: the period against thin-plate theory and the energy
 * conserved (no dissipation in this form; validation/plate.yaml). */
static void test_plate_total_lagrangian(void **state) {
    (void)state;
    const char *sets[] = {"spacing=0.005", "time.end=0.56", "bodies[1].lo=[-0.0025, -0.01]",
                          "bodies[1].hi=[0.0025, 0.01]"};
    ry_sim sim;
    ry_table t;
    run_solid_case("oscillating_plate_tl.yaml", 4, sets, "plate_tl", &sim, &t);
    ry_oscillation o = ry_series_oscillation(&t, "tip_deflection");
    const double T = plate_period();
    printf("plate, TL, H/dx = 4: period %.5f s (theory %.5f, %+.2f %%), energy %.5f -> %.5f J\n",
           o.period, T, 100 * (o.period - T) / T, o.energy_first, o.energy_last);
    assert_true(o.crossings >= tol("crossings_min"));
    assert_true(fabs(o.period - T) / T <= tol("tl_period"));
    assert_true(fabs(o.energy_last - o.energy_first) <= tol("tl_energy") * o.energy_first);
    ry_table_free(&t);
    ry_sim_free(&sim);
}

/* Case errors name the key: an unknown formulation, an unknown initial velocity, a UL-only key
 * with the total-Lagrangian form. */
static void test_case_errors(void **state) {
    (void)state;
    char cp[4096];
    snprintf(cp, sizeof cp, "%s/cases/oscillating_plate.yaml", root);
    ry_sim sim;
    ry_run_stats stats;
    ry_error err = {0};
    const char *bad1[] = {"scheme.formulation=eulerian"};
    assert_int_equal(ry_run_case_file(cp, 1, bad1, tmpdir, &sim, &stats, &err), RY_ERR_INPUT);
    assert_non_null(strstr(err.msg, "scheme.formulation"));
    const char *bad2[] = {"scheme.initial_velocity.type=second_mode"};
    assert_int_equal(ry_run_case_file(cp, 1, bad2, tmpdir, &sim, &stats, &err), RY_ERR_INPUT);
    assert_non_null(strstr(err.msg, "scheme.initial_velocity.type"));
    const char *bad3[] = {"scheme.artificial_stress.epsilon=2"};
    assert_int_not_equal(ry_run_case_file(cp, 1, bad3, tmpdir, &sim, &stats, &err), RY_OK);
    assert_non_null(strstr(err.msg, "scheme.artificial_stress.epsilon"));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_case_errors),
        cmocka_unit_test(test_plate_total_lagrangian),
        cmocka_unit_test(test_plate_updated_lagrangian),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
