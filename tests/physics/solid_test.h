/* Shared by the physics tests of the scheme `solid`: a temporary output folder and a runner for
 * the cases in cases/ with overrides. */
#ifndef RYUSHI_TEST_SOLID_TEST_H
#define RYUSHI_TEST_SOLID_TEST_H

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ryushi/solid.h"
#include "ryushi/validate.h"
#include "ryushi/run.h"

static char root[2048], tmpdir[256];

/* Runs cases/CASE with nset overrides into tmpdir/sub; keeps the final state in sim and reads
 * series.csv into series (when not NULL). Fails the test on any error. */
static void run_solid_case(const char *case_file, int nset, const char *const *sets,
                           const char *sub, ry_sim *sim, ry_table *series) {
    char cp[4096], od[512], sp[700];
    snprintf(cp, sizeof cp, "%s/cases/%s", root, case_file);
    snprintf(od, sizeof od, "%s/%s", tmpdir, sub);
    ry_run_stats stats;
    ry_error err = {0};
    ry_status st = ry_run_case_file(cp, nset, sets, od, sim, &stats, &err);
    if (st != RY_OK) fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(st, RY_OK);
    if (!series) return;
    snprintf(sp, sizeof sp, "%s/series.csv", od);
    st = ry_table_read(series, sp, &err);
    if (st != RY_OK) fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(st, RY_OK);
}

static int setup(void **state) {
    (void)state;
    const char *r = getenv("RY_SOURCE_DIR");
    snprintf(root, sizeof root, "%s", r && *r ? r : RY_SOURCE_DIR);
    snprintf(tmpdir, sizeof tmpdir, "/tmp/ryushi_test_solid_XXXXXX");
    return mkdtemp(tmpdir) ? 0 : -1;
}

static int teardown(void **state) {
    (void)state;
    char cmd[400];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    return system(cmd) == 0 ? 0 : -1;
}

#endif
