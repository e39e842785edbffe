/* Runs a case of the project for a physics test: the case file root/case_rel with overrides,
 * output in dir/sub; asserts success and reads its series.csv. The including file defines the
 * globals `root` (project folder) and `tmpdir` (tmpdir.h) and includes cmocka.h. */
#ifndef RYUSHI_TESTS_RUN_CASE_H
#define RYUSHI_TESTS_RUN_CASE_H

#include <stdio.h>

#include "ryushi/validate.h"

static void run(const char *case_rel, const char *sub, int nset, const char *const *sets,
                ry_table *series, ry_sim *keep) {
    char cp[4096], od[512], sp[600];
    snprintf(cp, sizeof cp, "%s/%s", root, case_rel);
    snprintf(od, sizeof od, "%s/%s", tmpdir, sub);
    ry_sim sim;
    ry_run_stats stats;
    ry_error err = {0};
    ry_status st = ry_run_case_file(cp, nset, sets, od, &sim, &stats, &err);
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
