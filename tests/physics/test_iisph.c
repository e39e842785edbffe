/* IISPH (scheme iisph) against references: short versions of the validation cases. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ryushi/validate.h"

static char root[2048], tmpdir[256];

/* Runs a case into tmpdir/sub and reads its series (sim kept when keep is set). */
static void run(const char *case_rel, const char *sub, int nset, const char *const *sets,
                ry_table *series, ry_sim *keep, ry_run_stats *stats) {
    char cp[4096], od[512], sp[600];
    snprintf(cp, sizeof cp, "%s/%s", root, case_rel);
    snprintf(od, sizeof od, "%s/%s", tmpdir, sub);
    ry_sim sim;
    ry_error err = {0};
    ry_status st = ry_run_case_file(cp, nset, sets, od, &sim, stats, &err);
    if (st != RY_OK) fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(st, RY_OK);
    snprintf(sp, sizeof sp, "%s/series.csv", od);
    assert_int_equal(ry_table_read(series, sp, &err), RY_OK);
    if (keep)
        *keep = sim;
    else
        ry_sim_free(&sim);
}

/* Largest value of a column over the rows with t >= t0. */
static double column_max_from(const ry_table *s, const char *name, double t0) {
    int c = -1, ct = -1;
    for (int k = 0; k < s->ncols; ++k) {
        if (strcmp(s->names[k], name) == 0) c = k;
        if (strcmp(s->names[k], "t") == 0) ct = k;
    }
    assert_true(c >= 0 && ct >= 0);
    double m = -INFINITY;
    for (size_t r = 0; r < s->nrows; ++r)
        if (s->data[r * s->ncols + ct] >= t0) m = fmax(m, s->data[r * s->ncols + c]);
    return m;
}

/* Water at rest in a tank (cases/hydrostatic_iisph.yaml, H = 0.2 m, dx = 5 mm, started with
 * zero pressure): after 0.5 s the pressure of the lowest fluid layer, away from the side walls,
 * is rho g (H - y) within 3 % (measured 2.5 %); the water stays at rest: from t = 0.25 s the
 * kinetic energy is below 1e-3 of M g H (measured about 1.5e-4; what moves are single
 * free-surface particles at the corners, max speed reported); the solver reports its
 * iterations. */
static void test_hydrostatic(void **state) {
    (void)state;
    const char *sets[] = {"time.end=0.5", "output.vtk=false", "time.output_interval=0.05"};
    ry_sim sim;
    ry_run_stats stats;
    ry_table s;
    run("cases/hydrostatic_iisph.yaml", "hydro", 3, sets, &s, &sim, &stats);
    const double H = 0.2, g = 9.81, M = 1000.0 * 0.4 * H;
    double psum = 0, ysum = 0;
    int count = 0;
    for (size_t i = 0; i < sim.ps.n; ++i) {
        if (sim.ps.kind[i] != RY_KIND_FLUID) continue;
        double x = sim.ps.f[RY_F_X][i], y = sim.ps.f[RY_F_Y][i];
        if (y < 0.005 && x > 0.1 && x < 0.3) {
            psum += sim.ps.f[RY_F_P][i];
            ysum += y;
            ++count;
        }
    }
    assert_true(count > 10);
    double p = psum / count, y = ysum / count, pexp = 1000.0 * g * (H - y);
    double ke = column_max_from(&s, "kinetic_energy", 0.25) / (M * g * H);
    double vmax = column_max_from(&s, "max_speed", 0.25);
    double iters = ry_column_max(&s, "iisph_iterations_mean");
    printf("IISPH hydrostatic: bottom pressure %.1f Pa, expected %.1f Pa (%.2f %%), kinetic "
           "energy / MgH %.2e, max speed %.4f m/s, mean iterations %.2f\n",
           p, pexp, 100 * (p / pexp - 1), ke, vmax, iters);
    assert_true(fabs(p / pexp - 1) < 0.03);
    assert_true(ke < 1e-3);
    assert_true(iters >= 2);
    assert_true(ry_mass_drift(&s) <= 1e-12);
    ry_sim_free(&sim);
    ry_table_free(&s);
}

/* Martin & Moyce column at a/20 with IISPH: the surge front within 0.45 (max) and 0.35 (RMS)
 * of the experiment in Z = front/a for T <= 3 (measured 0.37 and 0.28: the incompressible
 * front leaves at once, while the experiment's gate takes time to lift); with the time origin
 * fitted (shift dT in [0.05, 0.3], measured 0.23) the RMS is within 0.06 (measured 0.033);
 * mass exact, no particle outside. */
static void test_martin_moyce(void **state) {
    (void)state;
    const char *sets[] = {"time.end=0.18", "time.output_interval=0.001", "output.vtk=false"};
    ry_table s, ref;
    ry_run_stats stats;
    run("cases/dam_break_mm_iisph.yaml", "mm", 3, sets, &s, NULL, &stats);
    char rp[4096];
    ry_error err;
    snprintf(rp, sizeof rp, "%s/data/reference/martin_moyce1952_n2_2_surge_front_table2.csv", root);
    assert_int_equal(ry_table_read(&ref, rp, &err), RY_OK);
    ry_front_cmp cmp;
    assert_int_equal(ry_compare_front(&s, &ref, 0.05715, 9.81, 3.0, &cmp, &err), RY_OK);
    printf("IISPH Martin & Moyce a/20: %d points, max |dZ| %.3f, rms %.3f; shift %.3f: max %.3f, "
           "rms %.3f; %ld steps, mean iterations %.2f\n",
           cmp.npoints, cmp.max_dev, cmp.rms_dev, cmp.shift, cmp.max_dev_shifted,
           cmp.rms_dev_shifted, stats.steps, ry_column_max(&s, "iisph_iterations_mean"));
    assert_true(cmp.npoints >= 13);
    assert_true(cmp.max_dev <= 0.45);
    assert_true(cmp.rms_dev <= 0.35);
    assert_true(cmp.rms_dev_shifted <= 0.06);
    assert_true(cmp.shift >= 0.05 && cmp.shift <= 0.3);
    assert_true(ry_mass_drift(&s) <= 1e-12);
    assert_true(ry_column_max(&s, "outside") == 0);
    ry_table_free(&s);
    ry_table_free(&ref);
}

int main(void) {
    const char *src = getenv("RY_SOURCE_DIR");
    snprintf(root, sizeof root, "%s", src ? src : ".");
    snprintf(tmpdir, sizeof tmpdir, "/tmp/ryushi_iisph_XXXXXX");
    if (!mkdtemp(tmpdir)) return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hydrostatic),
        cmocka_unit_test(test_martin_moyce),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
