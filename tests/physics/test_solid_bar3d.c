/* The 3D cantilever bar of cases/cantilever_3d.yaml (square section, L/t = 10, EI = 1 N m^2):
 * short version of the 3D rows of `ryushi validate cantilever`. */
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

/* End load P = 0.01 N, 4 particles across the thickness: the tip deflection per unit load
 * within 2.5 % of Euler-Bernoulli plus Timoshenko shear, 1/3 + L / (kappa G A) with Cowper's
 * kappa = 10 (1 + nu) / (12 + 11 nu) for a square: 0.33588 (measured 0.34031, +1.32 %). */
static void test_bar3d_end_load(void **state) {
    (void)state;
    const char *sets[] = {"output.vtk=false"};
    ry_sim sim;
    run_solid_case("cantilever_3d.yaml", 1, sets, "bar3d", &sim, NULL);
    double d[3];
    ry_error err;
    assert_int_equal(ry_beam_centreline(&sim, 1.0, NULL, d, &err), RY_OK);
    const double t = 0.1, E = 120000.0, nu = 0.3, P = 0.01;
    const double kGA = 10 * (1 + nu) / (12 + 11 * nu) * E / (2 * (1 + nu)) * t * t;
    const double ref = ry_beam_deflection_eb(RY_BEAM_LOAD_END, 1.0, E * t * t * t * t / 12, 1.0) +
                       ry_beam_deflection_shear(RY_BEAM_LOAD_END, 1.0, kGA, 1.0);
    const double w = -d[2] / P;
    printf("3D bar, t/dx = 4: tip %.5f per unit load (Timoshenko %.5f, %+.2f %%), residual %.1e\n",
           w, ref, 100 * (w - ref) / ref, ry_sim_stat_value(&sim, "residual"));
    assert_true(fabs(w - ref) / ref <= manifest_tol(root, "cantilever", "bar3d"));
    assert_true(ry_sim_stat_value(&sim, "residual") < manifest_tol(root, "cantilever", "residual"));
    ry_sim_free(&sim);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_bar3d_end_load)};
    return cmocka_run_group_tests(tests, setup, teardown);
}
