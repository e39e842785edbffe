/* Elastic solids (scheme `solid`) against beam theory: short versions of `ryushi validate
 * cantilever` (full tables in docs/validation.md). The beam of cases/cantilever.yaml: L = 1,
 * EI = 1, L/t = 20, plane stress, nu = 0.3, Wendland C2, static solution by dynamic relaxation
 * to a relative residual of 1e-6. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "solid_test.h"
#include "manifest_tol.h"
#include "ryushi/run.h"

static const double t_beam = 0.05, E_beam = 96000.0, nu_beam = 0.3;

/* Tolerance `key` of validation/cantilever.yaml. */
static double tol(const char *key) {
    return manifest_tol(root, "cantilever", key);
}

/* Runs cases/cantilever.yaml with overrides (plus the clamp column on the root face for the
 * spacing) and keeps the final state. */
static void run_beam(int n_thick, int nset, const char *const *sets, const char *sub, ry_sim *sim) {
    char sp[64], lo[96], hi[96];
    const char *all[16];
    const double dx = t_beam / n_thick;
    snprintf(sp, sizeof sp, "spacing=%.17g", dx);
    snprintf(lo, sizeof lo, "bodies[1].lo=[%.17g, %.17g]", -0.5 * dx, -0.5 * t_beam);
    snprintf(hi, sizeof hi, "bodies[1].hi=[%.17g, %.17g]", 0.5 * dx, 0.5 * t_beam);
    all[0] = sp;
    all[1] = lo;
    all[2] = hi;
    all[3] = "output.vtk=false";
    for (int i = 0; i < nset; ++i) all[4 + i] = sets[i];
    run_solid_case("cantilever.yaml", 4 + nset, all, sub, sim, NULL);
}

static double deflection(const ry_sim *sim, double x, double q) {
    double d[3];
    ry_error err;
    assert_int_equal(ry_beam_centreline(sim, x, NULL, d, &err), RY_OK);
    return -d[1] / q;
}

/* Timoshenko deflection of the beam for intensity 1. */
static double reference(ry_beam_load load, double x) {
    const double EI = E_beam * t_beam * t_beam * t_beam / 12;
    const double kGA = 5.0 / 6.0 * E_beam / (2 * (1 + nu_beam)) * t_beam;
    return ry_beam_deflection_eb(load, 1.0, EI, x) + ry_beam_deflection_shear(load, 1.0, kGA, x);
}

/* End load P = 0.01 (the tip moves 0.34 % of L), results per unit load, 4 particles across the
 * thickness: tip deflection against Timoshenko's 0.33398 and w(1/2) against 0.10449 (at
 * t/dx = 6: +0.55 % and +0.83 %), the relaxation converged (validation/cantilever.yaml). */
static void test_cantilever_end_load(void **state) {
    (void)state;
    const char *sets[] = {"scheme.load.type=end", "scheme.load.intensity=0.01"};
    ry_sim sim;
    run_beam(4, 2, sets, "end", &sim);
    double wt = deflection(&sim, 1.0, 0.01), wh = deflection(&sim, 0.5, 0.01);
    double rt = reference(RY_BEAM_LOAD_END, 1.0), rh = reference(RY_BEAM_LOAD_END, 0.5);
    printf("end load, t/dx = 4: w(1) = %.5f (Timoshenko %.5f, %+.2f %%), w(0.5) = %.5f (%.5f, "
           "%+.2f %%), residual %.1e\n",
           wt, rt, 100 * (wt - rt) / rt, wh, rh, 100 * (wh - rh) / rh,
           ry_sim_stat_value(&sim, "residual"));
    assert_true(fabs(wt - rt) / rt <= tol("end_tip"));
    assert_true(fabs(wh - rh) / rh <= tol("end_midspan"));
    assert_true(ry_sim_stat_value(&sim, "residual") < tol("residual"));
    ry_sim_free(&sim);
}

/* Quarter-cosine load q = q0 cos(pi x / 2), t/dx = 4: the tip against Timoshenko's 0.04810
 * (the linear load q0 x gives +0.89 %, in `ryushi validate cantilever`). */
static void test_cantilever_cosine(void **state) {
    (void)state;
    const char *sets[] = {"scheme.load.type=cosine", "scheme.load.intensity=0.01"};
    ry_sim sim;
    run_beam(4, 2, sets, "cosine", &sim);
    double wt = deflection(&sim, 1.0, 0.01), rt = reference(RY_BEAM_LOAD_COSINE, 1.0);
    printf("cosine load: w(1) = %.5f (Timoshenko %.5f, %+.2f %%)\n", wt, rt, 100 * (wt - rt) / rt);
    assert_true(fabs(wt - rt) / rt <= tol("cosine_tip"));
    ry_sim_free(&sim);
}

/* Axial end load P = 0.01 on the strip: the tip moves P L / (E A) = 2.083e-6. */
static void test_axial(void **state) {
    (void)state;
    const char *sets[] = {"scheme.load.type=end", "scheme.load.intensity=0.01",
                          "scheme.load.direction=[1.0, 0.0]"};
    ry_sim a;
    run_beam(4, 3, sets, "axial", &a);
    double d[3];
    ry_error err;
    assert_int_equal(ry_beam_centreline(&a, 1.0, NULL, d, &err), RY_OK);
    const double ref = 0.01 / (E_beam * t_beam);
    printf("axial load: tip %.5e (P L/EA = %.5e, %+.2f %%)\n", d[0], ref, 100 * (d[0] - ref) / ref);
    assert_true(fabs(d[0] - ref) / ref <= tol("axial_tip"));
    ry_sim_free(&a);
}

/* 24 particles across the thickness (11 544 particles, enough for the loops to run in
 * parallel), 100 steps of the end-loaded beam: bitwise the same on 1 and 2 threads. */
static void test_threads_bitwise(void **state) {
    (void)state;
    const char *sets[] = {"scheme.load.type=end", "scheme.load.intensity=0.01",
                          "time.max_steps=100"};
    ry_sim a, b;
    omp_set_num_threads(1);
    run_beam(24, 3, sets, "threads1", &a);
    omp_set_num_threads(2);
    run_beam(24, 3, sets, "threads2", &b);
    assert_true(a.ps.n > 8192);
    assert_int_equal(a.ps.n, b.ps.n);
    assert_int_equal(a.step, 100);
    assert_int_equal(b.step, 100);
    double moved = 0;
    for (size_t i = 0; i < a.ps.n; ++i)
        for (int c = 0; c < 2; ++c) {
            assert_true(a.ps.f[RY_F_X + c][i] == b.ps.f[RY_F_X + c][i]);
            assert_true(a.ps.f[RY_F_VX + c][i] == b.ps.f[RY_F_VX + c][i]);
            moved = fmax(moved, fabs(a.ps.f[RY_F_VX + c][i]));
        }
    assert_true(moved > 0);
    ry_sim_free(&a);
    ry_sim_free(&b);
}

/* Large deflection, P L^2 / EI = 1, t/dx = 4: the tip against the elastica (x, y) =
 * (0.94357, 0.30172) (measured: (0.94270, 0.30440)). */
static void test_elastica(void **state) {
    (void)state;
    const char *sets[] = {"scheme.load.type=end", "scheme.load.intensity=1.0"};
    ry_sim sim;
    run_beam(4, 2, sets, "elastica", &sim);
    double d[3], ex, ey, eth;
    ry_error err;
    assert_int_equal(ry_beam_centreline(&sim, 1.0, NULL, d, &err), RY_OK);
    ry_elastica_end_load(1.0, &ex, &ey, &eth);
    double xt = 1 + d[0], yt = -d[1];
    printf("elastica: tip (%.5f, %.5f), exact (%.5f, %.5f), distance %.2f %% of L\n", xt, yt, ex,
           ey, 100 * hypot(xt - ex, yt - ey));
    assert_true(hypot(xt - ex, yt - ey) <= tol("elastica_4"));
    ry_sim_free(&sim);
}

/* Case errors name the key: a solid material without moduli, an unknown scheme key. */
static void test_case_errors(void **state) {
    (void)state;
    char cp[4096];
    snprintf(cp, sizeof cp, "%s/cases/cantilever.yaml", root);
    ry_sim sim;
    ry_run_stats stats;
    ry_error err = {0};
    const char *bad1[] = {"materials[0].youngs_modulus=-1"};
    ry_status st = ry_run_case_file(cp, 1, bad1, tmpdir, &sim, &stats, &err);
    assert_true(st == RY_ERR_INPUT || st == RY_ERR_RANGE);
    assert_non_null(strstr(err.msg, "materials[0].youngs_modulus"));
    const char *bad2[] = {"scheme.stiffness=3"};
    assert_int_equal(ry_run_case_file(cp, 1, bad2, tmpdir, &sim, &stats, &err), RY_ERR_INPUT);
    assert_non_null(strstr(err.msg, "scheme.stiffness"));
    const char *bad3[] = {"scheme.load.type=twist"};
    assert_int_equal(ry_run_case_file(cp, 1, bad3, tmpdir, &sim, &stats, &err), RY_ERR_INPUT);
    assert_non_null(strstr(err.msg, "scheme.load.type"));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_case_errors),       cmocka_unit_test(test_axial),
        cmocka_unit_test(test_threads_bitwise),   cmocka_unit_test(test_cantilever_end_load),
        cmocka_unit_test(test_cantilever_cosine), cmocka_unit_test(test_elastica),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
