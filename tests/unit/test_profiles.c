/* Line profiles: Shepard sampling of a linear field, time averaging, the CSV file, and strict
 * keys. */
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

#include "ryushi/csv.h"
#include "ryushi/sim.h"

#define RY_TMPDIR_PREFIX "ryushi_profiles_"
#include "tmpdir.h"
#include "ryushi/probes.h"
#include "ryushi/run.h"

/* A 1 x 1 box of fluid at rest (scheme `static`), 40 x 40 particles, with two profiles. */
static const char *case_text(char *buf, size_t size, const char *profiles) {
    snprintf(buf, size,
             "dimension: 2\nspacing: 0.025\n"
             "materials: [{name: water, density: 1000}]\n"
             "bodies: [{type: box, lo: [0, 0], hi: [1, 1]}]\n"
             "scheme: {name: static}\n"
             "time: {end: 1, output_interval: 0.5}\n"
             "output: {vtk: false}\n"
             "%s",
             profiles);
    return buf;
}

static ry_status setup(ry_sim *sim, ry_case **c, const char *profiles, ry_error *err) {
    char text[2048];
    memset(sim, 0, sizeof *sim);
    RY_TRY(ry_case_load_string(c, "profiles.yaml", case_text(text, sizeof text, profiles), err));
    return ry_sim_setup(sim, *c, tmpdir, err);
}

/* u = 2 + 3 y, v = -x, p = 10 x: the Shepard sum is exact for constants and, in the interior of
 * a uniform lattice (symmetric neighbourhoods), for linear fields. */
static void set_fields(ry_sim *sim, double scale) {
    ry_particles *ps = &sim->ps;
    for (size_t i = 0; i < ps->n; ++i) {
        double x = ps->f[RY_F_X][i], y = ps->f[RY_F_Y][i];
        ps->f[RY_F_VX][i] = scale * (2 + 3 * y);
        ps->f[RY_F_VY][i] = -scale * x;
        ps->f[RY_F_P][i] = scale * 10 * x;
    }
}

static void test_linear_field_and_average(void **state) {
    (void)state;
    ry_sim sim;
    ry_case *c = NULL;
    ry_error err = {0};
    ry_status st = setup(&sim, &c,
                         "profiles:\n"
                         "  - {name: vertical, from: [0.5, 0.2], to: [0.5, 0.8], points: 7}\n"
                         "  - {name: avg, from: [0.2, 0.5], to: [0.8, 0.5], points: 4, "
                         "average_from: 0.5}\n",
                         &err);
    if (st != RY_OK) fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(st, RY_OK);
    assert_int_equal(sim.nprofiles, 2);
    assert_int_equal(ry_sim_open_output(&sim, c, &err), RY_OK);

    /* t = 0: the instantaneous profile is sampled; the averaged one has not started. */
    set_fields(&sim, 1.0);
    assert_int_equal(ry_output_write(&sim, &err), RY_OK);
    const ry_profile *vert = ry_profile_find(&sim, "vertical");
    const ry_profile *avg = ry_profile_find(&sim, "avg");
    assert_non_null(vert);
    assert_non_null(avg);
    assert_null(ry_profile_find(&sim, "none"));
    assert_int_equal(vert->nsamples, 1);
    assert_int_equal(avg->nsamples, 0);
    for (int k = 0; k < vert->npoints; ++k) {
        double x[3];
        ry_profile_point(&sim, vert, k, x);
        assert_true(fabs(x[0] - 0.5) < 1e-15 && fabs(x[1] - (0.2 + 0.1 * k)) < 1e-12);
        assert_true(fabs(ry_profile_mean(&sim, vert, k, 0) - (2 + 3 * x[1])) < 1e-9);
        assert_true(fabs(ry_profile_mean(&sim, vert, k, 1) + 0.5) < 1e-9);
        assert_true(fabs(ry_profile_mean(&sim, vert, k, 2) - 5.0) < 1e-8);
        assert_true(fabs(ry_profile_mean(&sim, vert, k, 3) - 1000.0) < 1e-9); /* density */
    }

    /* t = 0.5 and 1: the averaged profile takes both; the instantaneous one only the last. */
    sim.t = 0.5;
    set_fields(&sim, 2.0);
    assert_int_equal(ry_output_write(&sim, &err), RY_OK);
    sim.t = 1.0;
    set_fields(&sim, 4.0);
    assert_int_equal(ry_output_write(&sim, &err), RY_OK);
    assert_int_equal(vert->nsamples, 1);
    assert_int_equal(avg->nsamples, 2);
    for (int k = 0; k < avg->npoints; ++k) {
        double x[3];
        ry_profile_point(&sim, avg, k, x);
        assert_true(fabs(ry_profile_mean(&sim, avg, k, 1) + 3.0 * x[0]) < 1e-9); /* (2+4)/2 */
    }
    assert_true(fabs(ry_profile_mean(&sim, vert, 0, 0) - 4 * (2 + 3 * 0.2)) < 1e-9);

    /* The file holds the mean so far, with a header. */
    char path[600];
    snprintf(path, sizeof path, "%s/profile_avg.csv", tmpdir);
    ry_table t;
    assert_int_equal(ry_table_read(&t, path, &err), RY_OK);
    assert_int_equal(t.nrows, 4);
    int cs = ry_table_col(&t, "s"), cv = ry_table_col(&t, "v"), cn = ry_table_col(&t, "samples");
    assert_true(cs >= 0 && cv >= 0 && cn >= 0 && ry_table_col(&t, "rho") >= 0);
    assert_true(fabs(ry_table_at(&t, 3, cs) - 0.6) < 1e-9);
    assert_true(fabs(ry_table_at(&t, 3, cv) + 3.0 * 0.8) < 1e-6);
    assert_true(ry_table_at(&t, 0, cn) == 2);
    ry_table_free(&t);
    ry_sim_free(&sim);
    ry_case_free(c);
}

/* Bad profiles stop with the file, line and key. */
static void test_bad_profiles(void **state) {
    (void)state;
    static const struct {
        const char *yaml, *expect;
    } bad[] = {
        {"profiles:\n  - {name: a, from: [0, 0]}\n", "profiles[0].to"},
        {"profiles:\n  - {name: a, from: [0, 0], to: [1, 1], points: 1}\n", "profiles[0].points"},
        {"profiles:\n  - {name: a, from: [0, 0], to: [1, 1]}\n  - {name: a, from: [0, 0], to: [1, "
         "0]}\n",
         "used twice"},
        {"profiles:\n  - {name: 'a b', from: [0, 0], to: [1, 1]}\n", "profiles[0].name"},
        {"profiles:\n  - {name: a, from: [0, 0], to: [1, 1], average_from: -1}\n",
         "profiles[0].average_from"},
        {"profiles:\n  - {name: a, from: [0, 0], to: [1, 1], colour: red}\n", "colour"},
    };
    for (size_t i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
        ry_sim sim;
        ry_case *c = NULL;
        ry_error err = {0};
        ry_status st = setup(&sim, &c, bad[i].yaml, &err);
        if (st == RY_OK) st = ry_case_check_unused(c, &err);
        if (st != RY_ERR_INPUT && st != RY_ERR_RANGE)
            fail_msg("case %zu: status %d, '%s'", i, (int)st, err.msg);
        if (!strstr(err.msg, bad[i].expect) || !strstr(err.msg, "profiles.yaml:"))
            fail_msg("case %zu: message '%s' lacks '%s'", i, err.msg, bad[i].expect);
        ry_sim_free(&sim);
        ry_case_free(c);
    }
}

static void write_text(const char *path, const char *text) {
    FILE *fp = fopen(path, "w");
    assert_non_null(fp);
    fputs(text, fp);
    fclose(fp);
}

/* The table reader: an empty field is NAN (a series' rows from before a restart that added a
 * measurement), a field that is not a number or a short row stops with the file, line and
 * column. */
static void test_table_empty_fields(void **state) {
    (void)state;
    char path[600];
    snprintf(path, sizeof path, "%s/table.csv", tmpdir);
    write_text(path, "t,a,b\n0,1,\n0.5,,2\n1,3,4\n");
    ry_error err = {0};
    ry_table t;
    assert_int_equal(ry_table_read(&t, path, &err), RY_OK);
    assert_int_equal(t.nrows, 3);
    assert_true(ry_table_at(&t, 0, 1) == 1 && isnan(ry_table_at(&t, 0, 2)));
    assert_true(isnan(ry_table_at(&t, 1, 1)) && ry_table_at(&t, 1, 2) == 2);
    assert_true(ry_table_at(&t, 2, 0) == 1 && ry_table_at(&t, 2, 2) == 4);
    ry_table_free(&t);
    write_text(path, "t,a,b\n0,1,2\n0.5,x,2\n");
    assert_int_equal(ry_table_read(&t, path, &err), RY_ERR_INPUT);
    assert_non_null(strstr(err.msg, "table.csv:3: column 'a'"));
    write_text(path, "t,a,b\n0,1\n");
    assert_int_equal(ry_table_read(&t, path, &err), RY_ERR_INPUT);
    assert_non_null(strstr(err.msg, "table.csv:2: column"));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_linear_field_and_average),
        cmocka_unit_test(test_bad_profiles),
        cmocka_unit_test(test_table_empty_fields),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
