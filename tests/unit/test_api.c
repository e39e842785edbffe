/* The library's public interface (include/ryushi/ryushi.h): a run taken step by step is the run
 * taken whole, bitwise; advancing lands on the time asked for; fields, names, units, probes and
 * statistics; errors come back as the exit-code class with the message; outputs, checkpoints
 * and a restart through the handle; with a symmetry plane, the fields of the part simulated and
 * the probes of the whole. The seed's dam break at 20 x 40 particles. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <cmocka.h>

#include "ryushi/ryushi.h"

static char tmp[64];
static char dam[4096];

static int setup(void **state) {
    (void)state;
    snprintf(tmp, sizeof tmp, "/tmp/ryushi_api_XXXXXX");
    if (!mkdtemp(tmp)) return -1;
    const char *src = getenv("RY_SOURCE_DIR");
    snprintf(dam, sizeof dam, "%s/cases/dam_break_seed.yaml", src ? src : RY_SOURCE_DIR);
    return 0;
}

static int teardown(void **state) {
    (void)state;
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf %s", tmp);
    return system(cmd) == 0 ? 0 : -1;
}

static ry_sim *load(const char *out, const char *extra) {
    char dir[256];
    snprintf(dir, sizeof dir, "%s/%s", tmp, out);
    const char *sets[] = {"spacing=0.0125", "output.vtk=false", "time.end=0.05", extra};
    ry_sim *sim = NULL;
    const int rc = ry_sim_load(&sim, dam, extra ? 4 : 3, sets, dir);
    if (rc) fprintf(stderr, "%s\n", ry_last_error());
    assert_int_equal(rc, 0);
    assert_non_null(sim);
    return sim;
}

static void assert_same_field(const ry_sim *a, const ry_sim *b, const char *name) {
    const double *x, *y;
    size_t n, m;
    assert_int_equal(ry_sim_field(a, name, &x, &n), 0);
    assert_int_equal(ry_sim_field(b, name, &y, &m), 0);
    assert_int_equal(n, m);
    assert_memory_equal(x, y, n * sizeof *x);
}

/* 30 calls of ry_sim_step give bitwise the state of a run of 30 steps. */
static void test_steps_are_the_run(void **state) {
    (void)state;
    ry_sim *whole = load("whole", "time.max_steps=30"), *steps = load("steps", NULL);
    assert_int_equal(ry_sim_run(whole), 0);
    double dt, sum = 0;
    for (int k = 0; k < 30; ++k) {
        assert_int_equal(ry_sim_step(steps, &dt), 0);
        assert_true(dt > 0);
        sum += dt;
    }
    assert_int_equal(ry_sim_step_count(whole), 30);
    assert_int_equal(ry_sim_step_count(steps), 30);
    assert_true(ry_sim_time(whole) == ry_sim_time(steps));
    assert_true(fabs(sum - ry_sim_time(steps)) < 1e-15);
    assert_same_field(whole, steps, "x");
    assert_same_field(whole, steps, "vy");
    assert_same_field(whole, steps, "density");
    double v;
    assert_int_equal(ry_sim_stat(steps, "steps", &v), 0);
    assert_true(v == 1.0); /* of the last call */
    ry_sim_destroy(whole);
    ry_sim_destroy(steps);
}

/* ry_sim_advance_to lands on the time; at the end a step does nothing. */
static void test_advance_and_end(void **state) {
    (void)state;
    ry_sim *sim = load("adv", NULL);
    assert_int_equal(ry_sim_advance_to(sim, 0.0123), 0);
    assert_true(fabs(ry_sim_time(sim) - 0.0123) < 1e-15);
    assert_int_equal(ry_sim_run(sim), 0);
    assert_true(fabs(ry_sim_time(sim) - ry_sim_end_time(sim)) < 1e-15);
    double dt = 1;
    const long steps = ry_sim_step_count(sim);
    assert_int_equal(ry_sim_step(sim, &dt), 0);
    assert_true(dt == 0.0);
    assert_int_equal(ry_sim_step_count(sim), steps);
    ry_sim_destroy(sim);
}

/* Names, units, integer fields, probes and statistics; unknown names are input errors. */
static void test_fields_and_probes(void **state) {
    (void)state;
    ry_sim *sim = load("fields", NULL);
    const char *names[64];
    const int n = ry_sim_field_names(sim, names, 64);
    assert_true(n > 10 && n <= 64);
    int seen = 0;
    for (int k = 0; k < n; ++k)
        seen |= (strcmp(names[k], "density") == 0) | (strcmp(names[k], "kind") == 0) << 1;
    assert_int_equal(seen, 3);
    assert_string_equal(ry_sim_field_unit(sim, "density"), "kg/m^3");
    assert_string_equal(ry_sim_field_unit(sim, "vx"), "m/s");
    assert_null(ry_sim_field_unit(sim, "nope"));
    assert_int_equal(ry_sim_dimension(sim), 2);
    assert_int_equal(ry_sim_count(sim), 1340);
    const int64_t *kind, *id;
    size_t nk, ni;
    assert_int_equal(ry_sim_int_field(sim, "kind", &kind, &nk), 0);
    assert_int_equal(ry_sim_int_field(sim, "id", &id, &ni), 0);
    assert_int_equal(nk, 1340);
    size_t fluid = 0;
    for (size_t i = 0; i < nk; ++i) fluid += kind[i] == 0;
    assert_int_equal(fluid, 800); /* 20 x 40 */
    double mass;
    assert_int_equal(ry_sim_probe(sim, "mass", &mass), 0);
    assert_true(fabs(mass - 125.0) < 1e-9); /* 1000 kg/m^3 x 0.25 m x 0.5 m */
    const double *d;
    size_t nd;
    assert_int_equal(ry_sim_field(sim, "nope", &d, &nd), 2);
    assert_non_null(strstr(ry_last_error(), "'nope'"));
    assert_string_equal(ry_last_error_kind(), "input error");
    assert_int_equal(ry_sim_probe(sim, "nope", &mass), 2);
    double v;
    assert_int_equal(ry_sim_stat(sim, "bytes_per_particle", &v), 0);
    assert_true(v > 50);
    assert_int_equal(ry_sim_stat(sim, "nope", &v), 2);
    assert_string_equal(ry_sim_scheme(sim), "wcsph");
    ry_sim_destroy(sim);
}

/* With a symmetry plane through the column's middle: the count and the fields are the
 * simulated half's, the probes the whole problem's (the column's whole mass), also after
 * steps (when the mirror copies exist). */
static void test_symmetry_planes(void **state) {
    (void)state;
    char dir[256];
    snprintf(dir, sizeof dir, "%s/sym", tmp);
    const char *sets[] = {"spacing=0.0125", "output.vtk=false", "time.end=0.05",
                          "domain.lo=[0.125,-0.1]", "domain.symmetry=[x_lo]"};
    ry_sim *sim = NULL;
    assert_int_equal(ry_sim_load(&sim, dam, 5, sets, dir), 0);
    for (int k = 0; k < 2; ++k) {
        const int64_t *kind;
        size_t nk, fluid = 0;
        assert_int_equal(ry_sim_int_field(sim, "kind", &kind, &nk), 0);
        assert_int_equal(nk, ry_sim_count(sim));
        for (size_t i = 0; i < nk; ++i) fluid += kind[i] == 0;
        assert_int_equal(fluid, 400); /* 10 x 40 */
        const double *x;
        size_t nx;
        assert_int_equal(ry_sim_field(sim, "x", &x, &nx), 0);
        assert_int_equal(nx, nk);
        for (size_t i = 0; i < nx; ++i) assert_true(x[i] > 0.125);
        double mass;
        assert_int_equal(ry_sim_probe(sim, "mass", &mass), 0);
        assert_true(fabs(mass - 125.0) < 1e-9); /* the whole column: 1000 x 0.25 x 0.5 */
        double dt;
        for (int s = 0; k == 0 && s < 5; ++s) assert_int_equal(ry_sim_step(sim, &dt), 0);
    }
    ry_sim_destroy(sim);
}

/* A missing file is an i/o error naming it; a bad key an input error naming it. */
static void test_errors(void **state) {
    (void)state;
    ry_sim *sim = (ry_sim *)1;
    assert_int_equal(ry_sim_load(&sim, "/nonexistent/case.yaml", 0, NULL, NULL), 3);
    assert_null(sim);
    assert_non_null(strstr(ry_last_error(), "/nonexistent/case.yaml"));
    const char *sets[] = {"time.nonsense=1"};
    assert_int_equal(ry_sim_load(&sim, dam, 1, sets, tmp), 2);
    assert_non_null(strstr(ry_last_error(), "time.nonsense"));
    assert_int_equal(
        ry_sim_create(&sim, "dimension: 2\nspacing: 0.1\nnonsense: 1\n", "t.yaml", 0, NULL, tmp),
        2);
    assert_non_null(strstr(ry_last_error(), "t.yaml"));
    ry_sim_destroy(NULL);
}

/* An output and a checkpoint on request; a second handle restarts from it at its step. */
static void test_output_checkpoint_restart(void **state) {
    (void)state;
    ry_sim *sim = load("ck", NULL);
    for (int k = 0; k < 5; ++k) assert_int_equal(ry_sim_step(sim, NULL), 0);
    double before, after;
    assert_int_equal(ry_sim_stat(sim, "outputs", &before), 0);
    assert_int_equal(ry_sim_write_output(sim), 0);
    assert_int_equal(ry_sim_stat(sim, "outputs", &after), 0);
    assert_true(after == before + 1);
    assert_int_equal(ry_sim_checkpoint(sim), 0);
    char path[512];
    snprintf(path, sizeof path, "%s/checkpoints/checkpoint_0000000005.ryc", ry_sim_output_dir(sim));
    struct stat st;
    assert_int_equal(stat(path, &st), 0);
    ry_sim *again = load("ck2", NULL);
    char used[4300];
    assert_int_equal(ry_sim_restart(again, ry_sim_output_dir(sim), used, sizeof used, NULL, 0), 0);
    assert_string_equal(used, path);
    assert_int_equal(ry_sim_step_count(again), 5);
    assert_true(ry_sim_time(again) == ry_sim_time(sim));
    assert_same_field(sim, again, "x");
    ry_sim_destroy(sim);
    ry_sim_destroy(again);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_steps_are_the_run),         cmocka_unit_test(test_advance_and_end),
        cmocka_unit_test(test_fields_and_probes),         cmocka_unit_test(test_errors),
        cmocka_unit_test(test_output_checkpoint_restart), cmocka_unit_test(test_symmetry_planes),
    };
    return cmocka_run_group_tests(tests, setup, teardown);
}
