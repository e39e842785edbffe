/* Shared by physics tests of the fluid schemes: the project folder and a temporary output
 * folder (set by main), and a runner for the cases in cases/ with overrides. Include after
 * cmocka.h. */
#ifndef RYUSHI_TEST_RUN_CASE_H
#define RYUSHI_TEST_RUN_CASE_H

#include <stdio.h>

#include "ryushi/validate.h"

#ifndef RY_TMPDIR_PREFIX
#define RY_TMPDIR_PREFIX "ryushi_test_"
#endif
#include "tmpdir.h" /* tmpdir, and make_tmpdir / remove_tmpdir for group set-up */
#include "ryushi/run.h"

static char root[2048];

/* Runs case_rel (relative to the project folder) with nset overrides into tmpdir/sub and reads
 * its series.csv; keeps the final state in *keep (or frees it) and the run's statistics in
 * *stats (both may be NULL). Fails the test on any error. */
static void run_case(const char *case_rel, const char *sub, int nset, const char *const *sets,
                     ry_table *series, ry_sim *keep, ry_run_stats *stats) {
    char cp[4096], od[512], sp[600];
    snprintf(cp, sizeof cp, "%s/%s", root, case_rel);
    snprintf(od, sizeof od, "%s/%s", tmpdir, sub);
    ry_sim sim;
    ry_run_stats local;
    ry_error err = {0};
    ry_status st = ry_run_case_file(cp, nset, sets, od, &sim, stats ? stats : &local, &err);
    if (st != RY_OK) fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(st, RY_OK);
    snprintf(sp, sizeof sp, "%s/series.csv", od);
    assert_int_equal(ry_table_read(series, sp, &err), RY_OK);
    if (keep)
        *keep = sim;
    else
        ry_sim_free(&sim);
}

/* Free-surface tension (seed 003 fluid, sigma = 0.0728 N/m): the circular drop at rest of
 * case_rel (R = 2 mm) keeps the mean of drop_pressure from t0 within tol of sigma / R and its
 * largest speed from t0 below vlim. */
static inline void free_drop_at_rest(const char *case_rel, const char *sub, int nset,
                                     const char *const *sets, double t0, double tol, double vlim) {
    ry_table s;
    run_case(case_rel, sub, nset, sets, &s, NULL, NULL);
    int cnt;
    const double p = ry_column_mean_from(&s, "drop_pressure", t0, &cnt), jump = 0.0728 / 2e-3;
    const double vmax = ry_column_max_from(&s, "max_speed", t0);
    printf("%s: p inside %.2f Pa, sigma/R %.2f Pa (%+.1f %%), largest speed %.4f m/s\n", case_rel,
           p, jump, 100 * (p / jump - 1), vmax);
    assert_true(cnt >= 10);
    assert_true(fabs(p / jump - 1) <= tol);
    assert_true(vmax < vlim);
    ry_table_free(&s);
}

/* The oscillating square of case_rel (side a = 4 mm, 15 ms): its period (ry_drop_periods_measure)
 * within tol of Lamb's mode 4, T = 2 pi / sqrt(60 sigma / (rho R^3)), R = a / sqrt(pi). */
static inline void free_square_period(const char *case_rel, const char *sub, double tol) {
    const char *sets[] = {"time.end=0.015", "output.vtk=false"};
    ry_table s;
    run_case(case_rel, sub, 2, sets, &s, NULL, NULL);
    const double pi = 3.14159265358979323846, R = 4e-3 / sqrt(pi);
    const double T = 2 * pi / sqrt(60 * 0.0728 / (1e3 * R * R * R));
    const ry_drop_periods m = ry_drop_periods_measure(&s, "width_x");
    printf("%s: half period %.2f ms, period %.2f ms, Lamb %.2f ms (%+.1f %%)\n", case_rel,
           1e3 * m.half, 1e3 * m.period, 1e3 * T, 100 * (m.period / T - 1));
    assert_true(fabs(m.period / T - 1) <= tol);
    ry_table_free(&s);
}

#endif
