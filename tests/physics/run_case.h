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

#endif
