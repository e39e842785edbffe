/* Euler buckling of a clamped-free filament (a microtubule in SI units): short version of
 * `ryushi validate buckling` (full table in docs/validation.md). */
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

/* Tolerance `key` of validation/buckling.yaml. */
static double tol(const char *key) {
    return manifest_tol(root, "buckling", key);
}

/* The filament of cases/filament_buckling.yaml: EI = 2.2e-23 N m^2, t = 0.25 um. */
static const double fil_t = 0.25e-6, fil_EI = 2.2e-23;

/* Tip position (x, lateral) in units of L at P = ratio P_cr, P_cr = pi^2 EI / (4 L^2), for a
 * filament of length fil_L. */
static void run_filament(double fil_L, double ratio, const char *sub, double *x, double *w) {
    char li[96], hi[96];
    const double pcr =
        3.14159265358979323846 * 3.14159265358979323846 * fil_EI / (4 * fil_L * fil_L);
    snprintf(li, sizeof li, "scheme.load.intensity=%.17g", ratio * pcr / fil_t);
    snprintf(hi, sizeof hi, "bodies[0].hi=[%.17g, %.17g]", fil_L, 0.5 * fil_t);
    const char *sets[] = {li, hi, "output.vtk=false"};
    ry_sim sim;
    run_solid_case("filament_buckling.yaml", 3, sets, sub, &sim, NULL);
    double pos[3];
    ry_error err;
    assert_int_equal(ry_beam_centreline(&sim, fil_L, pos, NULL, &err), RY_OK);
    assert_true(ry_sim_stat_value(&sim, "residual") < 1e-5);
    *x = pos[0] / fil_L;
    *w = -pos[1] / fil_L;
    ry_sim_free(&sim);
}

/* Below the critical load (0.5 and 0.7 P_cr, load tilted by 1e-3 rad), Southwell's line
 * w / P = w / P_cr + const gives P_cr against Euler's (validation/buckling.yaml). Shortened
 * to L = 2.5 um (L/t = 10) to keep the test short (shear alone lowers P_cr by 0.6 % here). */
static void test_filament_critical_load(void **state) {
    (void)state;
    double x1, w1, x2, w2;
    run_filament(2.5e-6, 0.5, "fil05", &x1, &w1);
    run_filament(2.5e-6, 0.7, "fil07", &x2, &w2);
    const double pcr = (w2 - w1) / (w2 / 0.7 - w1 / 0.5);
    printf("filament, L/t = 10: w/L = %.3e at 0.5 P_cr, %.3e at 0.7 P_cr: Southwell P_cr = %.4f "
           "x Euler\n",
           w1, w2, pcr);
    assert_true(w1 > 0 && w2 > w1);
    assert_true(fabs(pcr - 1) <= tol("critical_load"));
}

/* Above it (1.2 P_cr, L = 5 um, L/t = 20) the filament buckles and its tip lies near Euler's
 * elastica (0.6739, 0.6488) (measured (0.6538, 0.6630); validation/buckling.yaml). */
static void test_filament_post_buckled(void **state) {
    (void)state;
    double x, w, ex, ey, eth;
    run_filament(5e-6, 1.2, "fil12", &x, &w);
    ry_elastica_column(1.2, &ex, &ey, &eth);
    const double d = hypot(x - ex, w - ey);
    printf("filament, L/t = 20, 1.2 P_cr: tip (%.4f, %.4f), elastica (%.4f, %.4f), distance %.2f "
           "%% of L\n",
           x, w, ex, ey, 100 * d);
    assert_true(w > tol("buckled_min"));
    assert_true(d <= tol("tip_distance"));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_filament_critical_load),
        cmocka_unit_test(test_filament_post_buckled),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
