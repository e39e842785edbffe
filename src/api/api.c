/* The library's public interface (include/ryushi/ryushi.h) over the simulation layer: a handle
 * is a ry_sim allocated here, with the case it was set up from and what the interface keeps
 * for its callers (integer copies of narrow fields, the list of field names, the hooks). */
#define RY_BUILDING_LIBRARY
#include "ryushi/ryushi.h"

#include <math.h>
#include <omp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/case.h"
#include "ryushi/probes.h"
#include "ryushi/run.h"
#include "ryushi/sim.h"
#include "sim/symmetry.h"

/* What the interface keeps per handle (ry_sim.api). */
typedef struct api_state {
    ry_case *c;
    int threads;
    volatile sig_atomic_t stop;
    ry_progress_fn progress;
    void *progress_ctx;
    double progress_interval;
    ry_run_stats stats; /* of the last call that stepped */
    int64_t *ints[3];   /* id, kind, material as int64 */
    size_t ints_cap[3];
    const char **names;
    int nnames;
} api_state;

static _Thread_local char last_error[sizeof(((ry_error *)0)->msg) + 64];
static _Thread_local const char *last_kind = "ok";

static int fail(const ry_error *err) {
    last_kind = ry_status_name(err->code);
    snprintf(last_error, sizeof last_error, "%s: %s", last_kind, err->msg);
    return ry_status_exit_code(err->code);
}

static int fail_input(const char *fmt, const char *what) {
    ry_error e = {0};
    ry_error_set(&e, RY_ERR_INPUT, fmt, what ? what : "(null)");
    return fail(&e);
}

const char *ry_last_error(void) {
    return last_error;
}

const char *ry_last_error_kind(void) {
    return last_kind;
}

const char *ry_version(void) {
    return RY_VERSION;
}

static api_state *state_of(const ry_sim *sim) {
    return (api_state *)sim->api;
}

static void destroy_state(api_state *a) {
    if (!a) return;
    ry_case_free(a->c);
    for (int k = 0; k < 3; ++k) free(a->ints[k]);
    free(a->names);
    free(a);
}

void ry_sim_destroy(ry_sim *sim) {
    if (!sim) return;
    api_state *a = state_of(sim);
    ry_sim_free(sim);
    destroy_state(a);
    free(sim);
}

/* Set-up of a loaded case (taken over, freed on failure): the simulation and its output. */
static int make(ry_sim **out, ry_case *c, int nset, const char *const *sets, const char *out_dir,
                ry_error *err) {
    *out = NULL;
    ry_status st = RY_OK;
    for (int i = 0; i < nset && st == RY_OK; ++i) st = ry_case_override(c, sets[i], err);
    ry_sim *sim = st == RY_OK ? calloc(1, sizeof *sim) : NULL;
    api_state *a = sim ? calloc(1, sizeof *a) : NULL;
    if (st == RY_OK && !a) st = ry_error_set(err, RY_ERR_NOMEM, "out of memory");
    if (st == RY_OK) {
        a->c = c;
        c = NULL;
        st = ry_sim_setup(sim, a->c, out_dir, err);
        sim->api = a;
        if (st == RY_OK) st = ry_sim_open_output(sim, a->c, err);
    }
    if (st != RY_OK) {
        if (sim) {
            ry_sim_free(sim);
            free(sim);
        }
        destroy_state(a);
        ry_case_free(c);
        return fail(err);
    }
    *out = sim;
    return 0;
}

int ry_sim_load(ry_sim **sim, const char *case_path, int nset, const char *const *sets,
                const char *out_dir) {
    if (!sim || !case_path || nset < 0 || (nset > 0 && !sets))
        return fail_input("ry_sim_load: %s", "a handle pointer and a case path are required");
    ry_error err = {0};
    ry_case *c;
    if (ry_case_load(&c, case_path, &err) != RY_OK) {
        *sim = NULL;
        return fail(&err);
    }
    return make(sim, c, nset, sets, out_dir, &err);
}

int ry_sim_create(ry_sim **sim, const char *yaml_text, const char *name, int nset,
                  const char *const *sets, const char *out_dir) {
    if (!sim || !yaml_text || nset < 0 || (nset > 0 && !sets))
        return fail_input("ry_sim_create: %s", "a handle pointer and the case text are required");
    ry_error err = {0};
    ry_case *c;
    if (ry_case_load_string(&c, name ? name : "case", yaml_text, &err) != RY_OK) {
        *sim = NULL;
        return fail(&err);
    }
    return make(sim, c, nset, sets, out_dir, &err);
}

int ry_sim_restart(ry_sim *sim, const char *dir, char *used, size_t used_size, char *skipped,
                   size_t skipped_size) {
    if (!sim || !dir) return fail_input("ry_sim_restart: %s", "a handle and a folder are required");
    char u[4300] = "", s[2048] = "";
    ry_error err = {0};
    ry_status st = ry_restart_newest(sim, dir, u, sizeof u, s, sizeof s, &err);
    if (used && used_size) snprintf(used, used_size, "%s", u);
    if (skipped && skipped_size) snprintf(skipped, skipped_size, "%s", s);
    return st == RY_OK ? 0 : fail(&err);
}

int ry_sim_set_threads(ry_sim *sim, int threads) {
    if (!sim || threads < 0 || threads > 4096)
        return fail_input("ry_sim_set_threads: %s", "threads must be 0 (the default) to 4096");
    state_of(sim)->threads = threads;
    return 0;
}

void ry_sim_request_stop(ry_sim *sim) {
    if (sim && sim->api) state_of(sim)->stop = 1;
}

int ry_sim_set_progress(ry_sim *sim, ry_progress_fn fn, void *ctx, double interval_s) {
    if (!sim || !(interval_s >= 0))
        return fail_input("ry_sim_set_progress: %s", "the interval must be >= 0 s");
    api_state *a = state_of(sim);
    a->progress = fn;
    a->progress_ctx = ctx;
    a->progress_interval = interval_s;
    return 0;
}

static void on_progress(void *ctx, const ry_sim *sim, double rate, double eta) {
    const api_state *a = ctx;
    a->progress(a->progress_ctx, sim->t, sim->t_end, sim->step, sim->dt, rate, eta);
}

/* Steps by ry_run_some on the handle's threads, with its hooks. */
static int advance(ry_sim *sim, long max_steps, double until_t) {
    api_state *a = state_of(sim);
    const int before = omp_get_max_threads();
    if (a->threads > 0) omp_set_num_threads(a->threads);
    ry_run_hooks hooks = {a->progress ? on_progress : NULL, a, a->progress_interval, &a->stop};
    ry_error err = {0};
    memset(&a->stats, 0, sizeof a->stats);
    ry_status st = ry_run_some(sim, &hooks, max_steps, until_t, &a->stats, &err);
    a->stop = 0;
    if (a->threads > 0) omp_set_num_threads(before);
    return st == RY_OK ? 0 : fail(&err);
}

int ry_sim_step(ry_sim *sim, double *dt) {
    if (!sim) return fail_input("ry_sim_step: %s", "no handle");
    const long step = sim->step;
    const int rc = advance(sim, 1, INFINITY);
    if (dt) *dt = sim->step > step ? sim->dt : 0.0;
    return rc;
}

int ry_sim_advance_to(ry_sim *sim, double t) {
    if (!sim || isnan(t)) return fail_input("ry_sim_advance_to: %s", "a handle and a time");
    return advance(sim, -1, t);
}

int ry_sim_run(ry_sim *sim) {
    if (!sim) return fail_input("ry_sim_run: %s", "no handle");
    return advance(sim, -1, INFINITY);
}

double ry_sim_time(const ry_sim *sim) {
    return sim ? sim->t : NAN;
}

double ry_sim_end_time(const ry_sim *sim) {
    return sim ? sim->t_end : NAN;
}

long ry_sim_step_count(const ry_sim *sim) {
    return sim ? sim->step : 0;
}

int ry_sim_dimension(const ry_sim *sim) {
    return sim ? sim->dim : 0;
}

/* (symmetry planes' copies follow the set's own particles: the accessors stop before them) */
size_t ry_sim_count(const ry_sim *sim) {
    return sim ? ry_symmetry_owned(sim) : 0;
}

const char *ry_sim_scheme(const ry_sim *sim) {
    return sim && sim->scheme ? sim->scheme->name : "";
}

const char *ry_sim_output_dir(const ry_sim *sim) {
    return sim && sim->out_dir ? sim->out_dir : "";
}

const char *ry_sim_stop_reason(const ry_sim *sim) {
    return sim ? sim->stop_reason : "";
}

static const char *const int_names[3] = {"id", "kind", "material"};

int ry_sim_field(const ry_sim *sim, const char *name, const double **data, size_t *n) {
    if (!sim || !name || !data || !n) return fail_input("ry_sim_field: %s", "missing argument");
    const int k = ry_particles_field(&sim->ps, name);
    if (k < 0 || !sim->ps.f[k])
        return fail_input("no field of doubles '%s' (ry_sim_field_names lists them)", name);
    *data = sim->ps.f[k];
    *n = ry_symmetry_owned(sim);
    return 0;
}

int ry_sim_int_field(const ry_sim *sim, const char *name, const int64_t **data, size_t *n) {
    if (!sim || !name || !data || !n) return fail_input("ry_sim_int_field: %s", "missing argument");
    const ry_particles *ps = &sim->ps;
    const size_t own = ry_symmetry_owned(sim);
    if (strcmp(name, "id") == 0) {
        *data = ps->id;
        *n = own;
        return 0;
    }
    const int k = strcmp(name, "kind") == 0 ? 1 : strcmp(name, "material") == 0 ? 2 : -1;
    if (k < 0) return fail_input("no integer field '%s' (id, kind, material)", name);
    api_state *a = state_of(sim);
    if (a->ints_cap[k] < own || !a->ints[k]) {
        int64_t *p = realloc(a->ints[k], (own ? own : 1) * sizeof *p);
        if (!p) {
            ry_error e = {0};
            ry_error_set(&e, RY_ERR_NOMEM, "out of memory (field %s)", name);
            return fail(&e);
        }
        a->ints[k] = p;
        a->ints_cap[k] = own;
    }
    const uint8_t *src = k == 1 ? ps->kind : ps->material;
    for (size_t i = 0; i < own; ++i) a->ints[k][i] = src[i];
    *data = a->ints[k];
    *n = own;
    return 0;
}

int ry_sim_field_names(const ry_sim *sim, const char **names, int max) {
    if (!sim || (max > 0 && !names)) {
        fail_input("ry_sim_field_names: %s", "no handle, or no room for the names");
        return -1;
    }
    api_state *a = state_of(sim);
    const ry_particles *ps = &sim->ps;
    int count = 3;
    for (int k = 0; k < ps->nfields; ++k) count += ps->f[k] != NULL;
    if (a->nnames != count) {
        const char **p = realloc(a->names, (size_t)count * sizeof *p);
        if (!p) {
            ry_error e = {0};
            ry_error_set(&e, RY_ERR_NOMEM, "out of memory (field names)");
            fail(&e);
            return -1;
        }
        a->names = p;
        a->nnames = count;
    }
    int m = 0;
    for (int k = 0; k < ps->nfields; ++k)
        if (ps->f[k]) a->names[m++] = ps->info[k].name;
    for (int k = 0; k < 3; ++k) a->names[m++] = int_names[k];
    for (int k = 0; k < count && k < max; ++k) names[k] = a->names[k];
    return count;
}

const char *ry_sim_field_unit(const ry_sim *sim, const char *name) {
    if (!sim || !name) return NULL;
    const int k = ry_particles_field(&sim->ps, name);
    if (k >= 0) return sim->ps.info[k].unit;
    for (int i = 0; i < 3; ++i)
        if (strcmp(name, int_names[i]) == 0) return "1";
    return NULL;
}

typedef struct probe_call {
    const ry_probe *p;
    double *value;
} probe_call;

static ry_status probe_eval(ry_sim *sim, void *ctx, ry_error *err) {
    probe_call *c = ctx;
    return ry_probe_eval(c->p, sim, c->value, err);
}

/* A probe's value: the whole problem's where symmetry planes halve it. */
static int probe_value(ry_sim *sim, const ry_probe *p, double *value) {
    ry_error err = {0};
    probe_call c = {p, value};
    return ry_symmetry_measure(sim, probe_eval, &c, &err) == RY_OK ? 0 : fail(&err);
}

int ry_sim_probe(ry_sim *sim, const char *name, double *value) {
    if (!sim || !name || !value) return fail_input("ry_sim_probe: %s", "missing argument");
    for (int k = 0; k < sim->nregions; ++k) /* the case's own: a retina region's coverage */
        if (strcmp(sim->regions[k].probe.name, name) == 0)
            return probe_value(sim, &sim->regions[k].probe, value);
    for (const ry_probe *const *p = ry_probes(); *p; ++p)
        if (strcmp((*p)->name, name) == 0) return probe_value(sim, *p, value);
    return fail_input("no probe '%s' (`ryushi probes` lists them)", name);
}

/* The index-th probe, NULL past the last. */
static const ry_probe *probe_at(int index) {
    const ry_probe *const *p = ry_probes();
    for (int i = 0; index >= 0 && p[i]; ++i)
        if (i == index) return p[i];
    return NULL;
}

const char *ry_probe_name(int index) {
    const ry_probe *p = probe_at(index);
    return p ? p->name : NULL;
}

const char *ry_probe_summary(int index) {
    const ry_probe *p = probe_at(index);
    return p ? p->summary : NULL;
}

int ry_sim_stat(const ry_sim *sim, const char *name, double *value) {
    if (!sim || !name || !value) return fail_input("ry_sim_stat: %s", "missing argument");
    const api_state *a = state_of(sim);
    const struct {
        const char *name;
        double v;
    } own[] = {
        {"steps", (double)a->stats.steps},
        {"wall_s", a->stats.wall_s},
        {"particle_steps_per_s", a->stats.particle_steps_per_s},
        {"outputs", (double)sim->output_index},
        {"searches", (double)sim->searches},
        {"list_edits", (double)sim->nl_edits},
        {"bytes_per_particle", ry_sim_bytes_per_particle(sim)},
    };
    for (size_t k = 0; k < sizeof own / sizeof own[0]; ++k)
        if (strcmp(own[k].name, name) == 0) {
            *value = own[k].v;
            return 0;
        }
    if (ry_scheme_stat(sim, name, value)) return 0;
    return fail_input("no statistic '%s'", name);
}

int ry_sim_report(const ry_sim *sim, char *buf, size_t size) {
    if (!sim || !buf || size == 0) return fail_input("ry_sim_report: %s", "missing argument");
    buf[0] = '\0';
    if (sim->scheme && sim->scheme->report) sim->scheme->report(sim->scheme_state, buf, size);
    return 0;
}

int ry_sim_write_output(ry_sim *sim) {
    if (!sim) return fail_input("ry_sim_write_output: %s", "no handle");
    ry_error err = {0};
    return ry_sim_output(sim, &err) == RY_OK ? 0 : fail(&err);
}

int ry_sim_checkpoint(ry_sim *sim) {
    if (!sim) return fail_input("ry_sim_checkpoint: %s", "no handle");
    ry_error err = {0};
    return ry_sim_checkpoint_now(sim, NULL, 0, &err) == RY_OK ? 0 : fail(&err);
}
