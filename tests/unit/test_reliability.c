/* Guarded runs and checkpoint files: a non-finite value or fluid leaving the domain stops the
 * run within a step, naming the particle, and the last good state is written; a checkpoint
 * cut at any length or with any byte changed is rejected with a message, never read. */
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

#include "ryushi/checkpoint.h"
#include "ryushi/sim.h"

#define RY_TMPDIR_PREFIX "ryushi_guard_"
#include "tmpdir.h"
#include "ryushi/clock.h"
#include "ryushi/probes.h"
#include "ryushi/run.h"

/* A small WCSPH dam break: 20 x 40 fluid particles in an open tank. */
static ry_status setup(ry_sim *sim, ry_case **c, ry_error *err) {
    static const char text[] =
        "dimension: 2\nspacing: 0.0125\n"
        "materials: [{name: water, density: 1000, viscosity: 1e-6}]\n"
        "gravity: [0, -9.81]\n"
        "bodies:\n"
        "  - {type: box, lo: [0, 0], hi: [0.25, 0.5]}\n"
        "  - {type: tank, lo: [0, 0], hi: [1, 0.55], layers: 3, open_top: true}\n"
        "domain: {lo: [-0.1, -0.1], hi: [1.1, 1.5]}\n"
        "scheme: {name: wcsph, sound_speed: 30, artificial_viscosity: {alpha: 0.02}}\n"
        "time: {end: 0.05, output_interval: 0.01, cfl: 0.3}\n"
        "output: {vtk: false}\n";
    memset(sim, 0, sizeof *sim);
    RY_TRY(ry_case_load_string(c, "guard.yaml", text, err));
    RY_TRY(ry_sim_setup(sim, *c, tmpdir, err));
    return ry_sim_open_output(sim, *c, err);
}

static size_t first_fluid(const ry_sim *sim, size_t k) {
    for (size_t i = 0; i < sim->ps.n; ++i)
        if (sim->ps.kind[i] == RY_KIND_FLUID && k-- == 0) return i;
    return sim->ps.n;
}

static void test_nan_stops_within_a_step(void **state) {
    (void)state;
    ry_sim sim;
    ry_case *c = NULL;
    ry_error err = {0};
    assert_int_equal(setup(&sim, &c, &err), RY_OK);
    sim.max_steps = 20;
    ry_run_stats stats;
    assert_int_equal(ry_run(&sim, NULL, &stats, &err), RY_OK);
    long good = sim.step;
    /* Poison one particle's velocity, then continue: caught before any step is taken. */
    size_t i = first_fluid(&sim, 100);
    long long id = (long long)sim.ps.id[i];
    sim.ps.f[RY_F_VX][i] = NAN;
    sim.max_steps = 1000;
    ry_status st = ry_run(&sim, NULL, &stats, &err);
    assert_int_equal(st, RY_ERR_UNSTABLE);
    char want[128];
    snprintf(want, sizeof want, "unstable at step %ld,", good);
    assert_non_null(strstr(err.msg, want));
    snprintf(want, sizeof want, "first: particle id %lld (fluid)", id);
    assert_non_null(strstr(err.msg, want));
    assert_non_null(strstr(err.msg, "velocity is not finite"));
    assert_int_equal(sim.step, good);
    ry_sim_free(&sim);
    ry_case_free(c);
}

static void test_fluid_leaving_the_domain(void **state) {
    (void)state;
    ry_sim sim;
    ry_case *c = NULL;
    ry_error err = {0};
    assert_int_equal(setup(&sim, &c, &err), RY_OK);
    assert_int_equal(ry_sim_check(&sim, &err), RY_OK);
    /* 1 % of the fluid may leave (guard.max_outside_fraction); 2 % may not. */
    size_t nf = 0;
    for (size_t i = 0; i < sim.ps.n; ++i) nf += sim.ps.kind[i] == RY_KIND_FLUID;
    size_t k = nf / 100;
    for (size_t q = 0; q < k; ++q) sim.ps.f[RY_F_Y][first_fluid(&sim, q)] = 2.0;
    assert_int_equal(ry_sim_check(&sim, &err), RY_OK);
    for (size_t q = k; q < 2 * k + 1; ++q) sim.ps.f[RY_F_Y][first_fluid(&sim, q)] = 2.0;
    assert_int_equal(ry_sim_check(&sim, &err), RY_ERR_UNSTABLE);
    assert_non_null(strstr(err.msg, "have left the domain"));
    ry_sim_free(&sim);
    ry_case_free(c);
}

/* A checkpoint of the dam break, written and read back into a fresh set-up: every particle
 * array but the scratch ones and the clock come back exactly. */
static void test_checkpoint_round_trip(void **state) {
    (void)state;
    ry_sim a, b;
    ry_case *ca = NULL, *cb = NULL;
    ry_error err = {0};
    assert_int_equal(setup(&a, &ca, &err), RY_OK);
    a.max_steps = 30;
    assert_int_equal(ry_run(&a, NULL, NULL, &err), RY_OK);
    char path[512];
    snprintf(path, sizeof path, "%s/round.ryc", tmpdir);
    assert_int_equal(ry_sim_checkpoint_write(&a, path, &err), RY_OK);
    assert_int_equal(setup(&b, &cb, &err), RY_OK);
    ry_status st = ry_sim_checkpoint_read(&b, path, &err);
    if (st != RY_OK) fail_msg("%s", err.msg);
    assert_int_equal(b.ps.n, a.ps.n);
    assert_int_equal(b.step, a.step);
    assert_true(b.t == a.t);
    /* every field but the scratch ones (rewritten within each step before they are read) */
    for (int f = 0; f < a.ps.nfields; ++f)
        if (a.ps.f[f] && !(a.ps.info[f].flags & RY_FIELD_SCRATCH))
            assert_memory_equal(a.ps.f[f], b.ps.f[f], a.ps.n * sizeof(double));
    assert_memory_equal(a.ps.id, b.ps.id, a.ps.n * sizeof *a.ps.id);
    ry_sim_free(&a);
    ry_sim_free(&b);
    ry_case_free(ca);
    ry_case_free(cb);
}

/* Every prefix of a checkpoint, and the file with any one byte changed, is rejected. */
/* The progress hook's remaining time comes from the run's own pace: a run continued from
 * part-way counts only the simulated time it has covered itself. */
typedef struct eta_probe {
    double wall0, t_begin, eta, expect;
    int calls;
} eta_probe;

static void record_eta(void *ctx, const ry_sim *sim, double rate, double eta) {
    (void)rate;
    eta_probe *p = ctx;
    double elapsed = ry_wall_time() - p->wall0;
    p->eta = eta;
    p->expect = elapsed * (sim->t_end - sim->t) / (sim->t - p->t_begin);
    p->calls++;
}

static void test_eta_of_a_continued_run(void **state) {
    (void)state;
    ry_sim sim;
    ry_case *c = NULL;
    ry_error err = {0};
    assert_int_equal(setup(&sim, &c, &err), RY_OK);
    sim.max_steps = 40;
    assert_int_equal(ry_run(&sim, NULL, NULL, &err), RY_OK);
    assert_true(sim.t > 0 && sim.t < 0.5 * sim.t_end);
    eta_probe p = {.t_begin = sim.t};
    ry_run_hooks hooks = {.progress = record_eta, .ctx = &p, .progress_interval_s = 0};
    sim.max_steps = 80;
    p.wall0 = ry_wall_time();
    assert_int_equal(ry_run(&sim, &hooks, NULL, &err), RY_OK);
    assert_true(p.calls > 0);
    /* Counted from t = 0, the estimate would be (t - t_begin) / t, about half, of this. */
    assert_true(p.eta > 0.8 * p.expect && p.eta < 1.25 * p.expect);
    ry_sim_free(&sim);
    ry_case_free(c);
}

static void test_damaged_checkpoints_rejected(void **state) {
    (void)state;
    ry_error err = {0};
    char path[512];
    snprintf(path, sizeof path, "%s/small.ryc", tmpdir);
    ry_ck_writer w;
    const double xs[3] = {1.5, -2.0, 3.25};
    assert_int_equal(ry_ck_begin(&w, path, &err), RY_OK);
    assert_int_equal(ry_ck_put(&w, "field/x", RY_CK_F64, xs, 3, &err), RY_OK);
    assert_int_equal(ry_ck_put_i64(&w, "time/step", 42, &err), RY_OK);
    assert_int_equal(ry_ck_put_text(&w, "meta/scheme", "wcsph", 5, &err), RY_OK);
    assert_int_equal(ry_ck_commit(&w, &err), RY_OK);
    FILE *fp = fopen(path, "rb");
    assert_non_null(fp);
    unsigned char buf[512];
    size_t size = fread(buf, 1, sizeof buf, fp);
    fclose(fp);
    assert_true(size > 40 && size < sizeof buf);

    ry_ck_reader r;
    assert_int_equal(ry_ck_open_memory(&r, "small.ryc", buf, size, &err), RY_OK);
    int64_t step;
    double x[3];
    assert_int_equal(ry_ck_get_i64(&r, "time/step", &step, &err), RY_OK);
    assert_int_equal(step, 42);
    assert_int_equal(ry_ck_get(&r, "field/x", RY_CK_F64, 3, x, &err), RY_OK);
    assert_memory_equal(x, xs, sizeof xs);
    assert_int_equal(ry_ck_get(&r, "field/x", RY_CK_F64, 4, x, &err), RY_ERR_INPUT);
    assert_non_null(strstr(err.msg, "record 'field/x' holds 3 f64 value(s), expected 4 f64"));
    assert_int_equal(ry_ck_get_i64(&r, "time/t", &step, &err), RY_ERR_INPUT);
    assert_non_null(strstr(err.msg, "record 'time/t' is missing"));
    ry_ck_close(&r);

    for (size_t len = 0; len < size; ++len) {
        assert_int_equal(ry_ck_open_memory(&r, "cut.ryc", buf, len, &err), RY_ERR_INPUT);
        assert_non_null(strstr(err.msg, "checkpoint cut.ryc: "));
    }
    for (size_t at = 0; at < size; ++at) {
        unsigned char copy[512];
        memcpy(copy, buf, size);
        copy[at] ^= 0x5a;
        assert_int_not_equal(ry_ck_open_memory(&r, "flip.ryc", copy, size, &err), RY_OK);
    }
}

/* The in_wall probe reads the current positions, whatever the last neighbour search saw: a fluid
 * particle moved into the floor of the tank (within dx/2 of a wall particle in every direction)
 * is counted, and one moved just outside that cell is not. */
static void test_in_wall_counts_current_positions(void **state) {
    (void)state;
    ry_sim sim;
    ry_case *c = NULL;
    ry_error err = {0};
    assert_int_equal(setup(&sim, &c, &err), RY_OK);
    sim.max_steps = 2;
    ry_run_stats stats;
    assert_int_equal(ry_run(&sim, NULL, &stats, &err), RY_OK);
    const ry_probe *probe = NULL;
    for (const ry_probe *const *p = ry_probes(); *p; ++p)
        if (strcmp((*p)->name, "in_wall") == 0) probe = *p;
    assert_non_null(probe);
    double v = -1;
    assert_int_equal(probe->eval(&sim, &v, &err), RY_OK);
    assert_true(v == 0);
    size_t w = sim.ps.n; /* the top layer of the floor under the middle of the tank */
    for (size_t i = 0; i < sim.ps.n; ++i)
        if (sim.ps.kind[i] == RY_KIND_WALL && fabs(sim.ps.f[RY_F_X][i] - 0.5) < 0.007 &&
            sim.ps.f[RY_F_Y][i] < 0 && (w == sim.ps.n || sim.ps.f[RY_F_Y][i] > sim.ps.f[RY_F_Y][w]))
            w = i;
    assert_true(w < sim.ps.n);
    const size_t i = first_fluid(&sim, 0);
    sim.ps.f[RY_F_X][i] = sim.ps.f[RY_F_X][w] + 0.3 * sim.dx;
    sim.ps.f[RY_F_Y][i] = sim.ps.f[RY_F_Y][w] - 0.2 * sim.dx;
    assert_int_equal(probe->eval(&sim, &v, &err), RY_OK);
    assert_true(v == 1);
    sim.ps.f[RY_F_Y][i] = sim.ps.f[RY_F_Y][w] + 0.55 * sim.dx; /* just above the wall surface */
    assert_int_equal(probe->eval(&sim, &v, &err), RY_OK);
    assert_true(v == 0);
    ry_sim_free(&sim);
    ry_case_free(c);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_nan_stops_within_a_step),
        cmocka_unit_test(test_fluid_leaving_the_domain),
        cmocka_unit_test(test_checkpoint_round_trip),
        cmocka_unit_test(test_eta_of_a_continued_run),
        cmocka_unit_test(test_damaged_checkpoints_rejected),
        cmocka_unit_test(test_in_wall_counts_current_positions),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
