/* A simulation's checkpoints and its last good state. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "sim/writer.h"
#include "ryushi/checkpoint.h"
#include "ryushi/output.h"
#include "ryushi/sim.h"
#include "ryushi/clock.h"
#include "ryushi/run.h"

enum { MAX_VARS = 64 };

/* Whether field f is checkpointed and kept in the last good state: allocated, and not scratch
 * (rewritten within every step before it is read). */
static int kept(const ry_particles *ps, int f) {
    return ps->f[f] && !(ps->info[f].flags & RY_FIELD_SCRATCH);
}

static int scheme_vars(const ry_sim *sim, ry_state_var *vars) {
    if (!sim->scheme || !sim->scheme->state_vars) return 0;
    return sim->scheme->state_vars(sim->scheme_state, vars, MAX_VARS);
}

static double var_get(const ry_state_var *v) {
    return v->f64 ? *v->f64 : v->i32 ? (double)*v->i32 : (double)*v->i64;
}

/* Sets a variable; 0 when an integer one cannot hold x. */
static int var_set(const ry_state_var *v, double x) {
    if (v->f64) {
        *v->f64 = x;
        return 1;
    }
    if (!(x == floor(x) && fabs(x) <= (v->i32 ? 2147483647.0 : 9.0e15))) return 0;
    if (v->i32)
        *v->i32 = (int)x;
    else
        *v->i64 = (long)x;
    return 1;
}

/* A restart may change time.output_interval or checkpoint.interval. The continued run then
 * keeps the stored run's phase, the last time it was due (its next time less its interval), and
 * steps from there by the new interval to the first time after t; with the stored schedule a
 * shorter interval would begin only at the old next time, and checkpoints asked for anew would
 * never come. Checkpoints written before the interval was stored keep their next time. */
static ry_status reschedule(const ry_ck_reader *r, const char *record, double now, double t,
                            double *next, ry_error *err) {
    if (!ry_ck_find(r, record)) return RY_OK;
    double before;
    RY_TRY(ry_ck_get_f64(r, record, &before, err));
    RY_CHECK(err, isfinite(before) && before >= 0, RY_ERR_INPUT,
             "checkpoint %s: record '%s': bad value", r->path, record);
    if (before == now) return RY_OK;
    if (!(now > 0)) {
        *next = INFINITY; /* checkpoint.interval: 0, none by time */
        return RY_OK;
    }
    const double last = before > 0 && isfinite(*next) ? *next - before : 0;
    const double eps = 1e-12 * fmax(fabs(t), now);
    double n = last + (floor((t + eps - last) / now) + 1) * now;
    while (n <= t + eps) n += now;
    *next = n;
    return RY_OK;
}

/* ---- writing ------------------------------------------------------------------------------ */

static ry_status put_sim(const ry_sim *sim, ry_ck_writer *w, ry_error *err) {
    const ry_particles *ps = &sim->ps;
    RY_TRY(
        ry_ck_put_text(w, "meta/program", "ryushi " RY_VERSION, strlen("ryushi " RY_VERSION), err));
    RY_TRY(ry_ck_put_text(w, "meta/scheme", sim->scheme->name, strlen(sim->scheme->name), err));
    RY_TRY(ry_ck_put_text(w, "meta/case", sim->case_name, strlen(sim->case_name), err));
    RY_TRY(ry_ck_put_i64(w, "meta/dimension", sim->dim, err));
    RY_TRY(ry_ck_put_f64(w, "meta/spacing", sim->dx, err));
    RY_TRY(ry_ck_put_f64(w, "meta/h_over_dx", sim->h_over_dx, err));
    for (int m = 0; m < sim->nmat; ++m) {
        char k[64];
        snprintf(k, sizeof k, "material/%d", m);
        RY_TRY(ry_ck_put_text(w, k, sim->mat[m].name, strlen(sim->mat[m].name), err));
    }
    RY_TRY(ry_ck_put_f64(w, "time/t", sim->t, err));
    RY_TRY(ry_ck_put_f64(w, "time/dt", sim->dt, err));
    RY_TRY(ry_ck_put_f64(w, "time/next_output", sim->next_output, err));
    RY_TRY(ry_ck_put_f64(w, "time/output_interval", sim->output_interval, err));
    RY_TRY(ry_ck_put_i64(w, "time/step", sim->step, err));
    RY_TRY(ry_ck_put_i64(w, "time/finished", sim->finished, err));
    RY_TRY(ry_ck_put_i64(w, "output/index", sim->output_index, err));
    RY_TRY(ry_ck_put_f64(w, "checkpoint/next_t", sim->ckpt.next_t, err));
    RY_TRY(ry_ck_put_f64(w, "checkpoint/interval", sim->ckpt.interval, err));
    RY_TRY(ry_ck_put_f64(w, "neighbors/radius", sim->nl_radius, err));
    RY_TRY(ry_ck_put_i64(w, "neighbors/searches", sim->searches, err));
    RY_TRY(ry_ck_put_i64(w, "neighbors/reuses", sim->nl_reuses, err));
    RY_TRY(ry_ck_put_i64(w, "neighbors/have_list", ry_sim_searched(sim), err));
    RY_TRY(ry_ck_put_i64(w, "particles/n", (int64_t)ps->n, err));
    RY_TRY(ry_ck_put_i64(w, "particles/next_id", ps->next_id, err));
    RY_TRY(ry_ck_put(w, "particles/id", RY_CK_I64, ps->id, ps->n, err));
    RY_TRY(ry_ck_put(w, "particles/kind", RY_CK_U8, ps->kind, ps->n, err));
    RY_TRY(ry_ck_put(w, "particles/material", RY_CK_U8, ps->material, ps->n, err));
    for (int f = 0; f < ps->nfields; ++f) {
        if (!kept(ps, f)) continue;
        char k[300];
        snprintf(k, sizeof k, "field/%s", ps->info[f].name);
        RY_TRY(ry_ck_put(w, k, RY_CK_F64, ps->f[f], ps->n, err));
    }
    ry_state_var vars[MAX_VARS];
    int nv = scheme_vars(sim, vars);
    for (int i = 0; i < nv; ++i) {
        char k[300];
        snprintf(k, sizeof k, "scheme/%s", vars[i].name);
        RY_TRY(ry_ck_put_f64(w, k, var_get(&vars[i]), err));
    }
    for (int k = 0; k < sim->nprofiles; ++k) {
        const ry_profile *pf = &sim->profiles[k];
        char key[300];
        snprintf(key, sizeof key, "profile/%s/samples", pf->name);
        RY_TRY(ry_ck_put_i64(w, key, pf->nsamples, err));
        snprintf(key, sizeof key, "profile/%s/sum", pf->name);
        RY_TRY(ry_ck_put(w, key, RY_CK_F64, pf->sum, (size_t)pf->npoints * (size_t)(sim->dim + 2),
                         err));
    }
    for (int q = 0; q < sim->nopen; ++q) {
        char key[64];
        snprintf(key, sizeof key, "open/%d/count", q);
        RY_TRY(ry_ck_put_i64(w, key, sim->open[q].count, err));
    }
    return ry_writer_save(sim, w, err);
}

ry_status ry_sim_checkpoint_write(const ry_sim *sim, const char *path, ry_error *err) {
    ry_ck_writer w;
    RY_TRY(ry_ck_begin(&w, path, err));
    ry_status st = put_sim(sim, &w, err);
    if (st != RY_OK) {
        ry_ck_abort(&w);
        return st;
    }
    return ry_ck_commit(&w, err);
}

/* ---- reading ------------------------------------------------------------------------------ */

static ry_status text_is(const ry_ck_reader *r, const char *key, const char *want, const char *what,
                         ry_error *err) {
    char *s;
    RY_TRY(ry_ck_get_text(r, key, &s, NULL, err));
    int same = strcmp(s, want) == 0;
    ry_status st = same ? RY_OK
                        : ry_error_set(err, RY_ERR_INPUT,
                                       "checkpoint %s: written for %s '%s', the case has '%s'",
                                       r->path, what, s, want);
    free(s);
    return st;
}

ry_status ry_sim_checkpoint_load(ry_sim *sim, const ry_ck_reader *r, ry_error *err) {
    ry_particles *ps = &sim->ps;
    int64_t dim, n, v;
    RY_TRY(text_is(r, "meta/scheme", sim->scheme->name, "scheme", err));
    RY_TRY(ry_ck_get_i64(r, "meta/dimension", &dim, err));
    RY_CHECK(err, dim == sim->dim, RY_ERR_INPUT,
             "checkpoint %s: written for a %dD case, the case is %dD", r->path, (int)dim, sim->dim);
    for (int m = 0; m < sim->nmat; ++m) {
        char k[64];
        snprintf(k, sizeof k, "material/%d", m);
        RY_TRY(text_is(r, k, sim->mat[m].name, "material", err));
    }
    /* the particles' spacing and smoothing length are the checkpoint's (older checkpoints do not
     * record them) */
    const char *const geom[2] = {"meta/spacing", "meta/h_over_dx"};
    const double want[2] = {sim->dx, sim->h_over_dx};
    for (int k = 0; k < 2; ++k) {
        double got;
        if (!ry_ck_find(r, geom[k])) continue;
        RY_TRY(ry_ck_get_f64(r, geom[k], &got, err));
        RY_CHECK(err, got == want[k], RY_ERR_INPUT,
                 "checkpoint %s: written with %s = %.9g, the case has %.9g (a restart keeps the "
                 "case's spacing and kernel; set them as the run that wrote it did)",
                 r->path, k ? "kernel.h_over_dx" : "spacing", got, want[k]);
    }
    RY_TRY(ry_ck_get_i64(r, "particles/n", &n, err));
    RY_CHECK(err, n >= 0 && n < ((int64_t)1 << 40), RY_ERR_INPUT,
             "checkpoint %s: record 'particles/n': bad count %lld", r->path, (long long)n);
    /* Every field of the set must be there with n values: check before changing anything. */
    for (int f = 0; f < ps->nfields; ++f) {
        if (!kept(ps, f)) continue;
        char k[300];
        snprintf(k, sizeof k, "field/%s", ps->info[f].name);
        const ry_ck_record *rec = ry_ck_find(r, k);
        RY_CHECK(err, rec && rec->type == RY_CK_F64 && rec->count == (size_t)n, RY_ERR_INPUT,
                 "checkpoint %s: field '%s' is missing or has the wrong size (%lld particles)",
                 r->path, ps->info[f].name, (long long)n);
    }
    if ((size_t)n > ps->n) {
        size_t first;
        RY_TRY(ry_particles_add(ps, (size_t)n - ps->n, &first, err));
    }
    ps->n = (size_t)n;
    RY_TRY(ry_ck_get(r, "particles/id", RY_CK_I64, ps->n, ps->id, err));
    RY_TRY(ry_ck_get(r, "particles/kind", RY_CK_U8, ps->n, ps->kind, err));
    RY_TRY(ry_ck_get(r, "particles/material", RY_CK_U8, ps->n, ps->material, err));
    for (size_t i = 0; i < ps->n; ++i)
        RY_CHECK(err, ps->kind[i] < RY_KIND_COUNT && ps->material[i] < sim->nmat, RY_ERR_INPUT,
                 "checkpoint %s: particle %zu has an unknown kind or material", r->path, i);
    RY_TRY(ry_ck_get_i64(r, "particles/next_id", &ps->next_id, err));
    for (int f = 0; f < ps->nfields; ++f) {
        if (!kept(ps, f)) continue;
        char k[300];
        snprintf(k, sizeof k, "field/%s", ps->info[f].name);
        RY_TRY(ry_ck_get(r, k, RY_CK_F64, ps->n, ps->f[f], err));
    }
    RY_TRY(ry_ck_get_f64(r, "time/t", &sim->t, err));
    RY_TRY(ry_ck_get_f64(r, "time/dt", &sim->dt, err));
    RY_TRY(ry_ck_get_f64(r, "time/next_output", &sim->next_output, err));
    RY_TRY(ry_ck_get_i64(r, "time/step", &v, err));
    RY_CHECK(err, v >= 0 && isfinite(sim->t) && isfinite(sim->dt) && sim->dt >= 0, RY_ERR_INPUT,
             "checkpoint %s: bad time, time step or step count", r->path);
    sim->step = (long)v;
    RY_TRY(ry_ck_get_i64(r, "time/finished", &v, err));
    /* a run that time.stop_when ended goes on, and stops again at the next output where the
     * condition (perhaps changed) holds */
    sim->finished = v != 0 && sim->stop_probe < 0;
    RY_TRY(ry_ck_get_i64(r, "output/index", &v, err));
    RY_CHECK(err, v >= 0 && v < 100000000, RY_ERR_INPUT,
             "checkpoint %s: record 'output/index': bad value", r->path);
    sim->output_index = (int)v;
    RY_TRY(ry_ck_get_f64(r, "checkpoint/next_t", &sim->ckpt.next_t, err));
    RY_TRY(reschedule(r, "time/output_interval", sim->output_interval, sim->t, &sim->next_output,
                      err));
    RY_TRY(
        reschedule(r, "checkpoint/interval", sim->ckpt.interval, sim->t, &sim->ckpt.next_t, err));
    RY_TRY(ry_ck_get_f64(r, "neighbors/radius", &sim->nl_radius, err));
    RY_TRY(ry_ck_get_i64(r, "neighbors/searches", &v, err));
    sim->searches = (long)v;
    RY_TRY(ry_ck_get_i64(r, "neighbors/reuses", &v, err));
    sim->nl_reuses = (long)v;
    RY_TRY(ry_ck_get_i64(r, "neighbors/have_list", &v, err));
    sim->nl_restore = v != 0;
    ry_nlist_free(&sim->nl);
    ry_state_var vars[MAX_VARS];
    int nv = scheme_vars(sim, vars);
    for (int i = 0; i < nv; ++i) {
        char k[300];
        double x;
        snprintf(k, sizeof k, "scheme/%s", vars[i].name);
        RY_TRY(ry_ck_get_f64(r, k, &x, err));
        RY_CHECK(err, var_set(&vars[i], x), RY_ERR_INPUT,
                 "checkpoint %s: record '%s': %g is not a valid value", r->path, k, x);
    }
    for (int k = 0; k < sim->nprofiles; ++k) {
        ry_profile *pf = &sim->profiles[k];
        char key[300];
        snprintf(key, sizeof key, "profile/%s/samples", pf->name);
        RY_TRY(ry_ck_get_i64(r, key, &v, err));
        RY_CHECK(err, v >= 0 && v <= 2147483647, RY_ERR_INPUT,
                 "checkpoint %s: record '%s': bad count", r->path, key);
        pf->nsamples = (int)v;
        snprintf(key, sizeof key, "profile/%s/sum", pf->name);
        RY_TRY(ry_ck_get(r, key, RY_CK_F64, (size_t)pf->npoints * (size_t)(sim->dim + 2), pf->sum,
                         err));
    }
    for (int q = 0; q < sim->nopen; ++q) {
        char key[64];
        snprintf(key, sizeof key, "open/%d/count", q);
        RY_TRY(ry_ck_get_i64(r, key, &v, err));
        sim->open[q].count = (long)v;
    }
    if (sim->writer) RY_TRY(ry_writer_load(sim, r, err));
    sim->halo = NULL; /* a checkpoint holds no halo copies (symmetry planes' are made again) */
    return RY_OK;
}

ry_status ry_sim_checkpoint_read(ry_sim *sim, const char *path, ry_error *err) {
    ry_ck_reader r;
    RY_TRY(ry_ck_open(&r, path, err));
    ry_status st = ry_sim_checkpoint_load(sim, &r, err);
    ry_ck_close(&r);
    return st;
}

/* ---- the checkpoints folder --------------------------------------------------------------- */

static const char CK_PREFIX[] = "checkpoint_";
static const char CK_SUFFIX[] = ".ryc";

/* Steps of the checkpoints in folder dir, newest first; *n of them (malloc'd array). */
static ry_status list_checkpoints(const char *dir, long **steps, int *n, ry_error *err) {
    *steps = NULL;
    *n = 0;
    DIR *d = opendir(dir);
    if (!d) return RY_OK;
    int cap = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        size_t len = strlen(e->d_name), pl = strlen(CK_PREFIX), sl = strlen(CK_SUFFIX);
        if (len <= pl + sl || strncmp(e->d_name, CK_PREFIX, pl) != 0 ||
            strcmp(e->d_name + len - sl, CK_SUFFIX) != 0)
            continue;
        char *end;
        long s = strtol(e->d_name + pl, &end, 10);
        if (end != e->d_name + len - sl || s < 0) continue;
        if (*n == cap) {
            cap = cap ? 2 * cap : 16;
            long *p = realloc(*steps, (size_t)cap * sizeof *p);
            if (!p) {
                closedir(d);
                free(*steps);
                *steps = NULL;
                return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
            }
            *steps = p;
        }
        (*steps)[(*n)++] = s;
    }
    closedir(d);
    for (int i = 1; i < *n; ++i) /* insertion sort, newest first */
        for (int j = i; j > 0 && (*steps)[j] > (*steps)[j - 1]; --j) {
            long t = (*steps)[j];
            (*steps)[j] = (*steps)[j - 1];
            (*steps)[j - 1] = t;
        }
    return RY_OK;
}

static void ck_path(char *buf, size_t size, const char *dir, long step) {
    snprintf(buf, size, "%s/%s%010ld%s", dir, CK_PREFIX, step, CK_SUFFIX);
}

ry_status ry_sim_checkpoint_now(ry_sim *sim, char *path, size_t path_size, ry_error *err) {
    if (sim->par) return sim->par->checkpoint(sim, path, path_size, err);
    char dir[4096], file[4200];
    snprintf(dir, sizeof dir, "%s/checkpoints", sim->out_dir);
    RY_TRY(ry_mkdir_p(dir, err));
    ck_path(file, sizeof file, dir, sim->step);
    RY_TRY(ry_sim_checkpoint_write(sim, file, err));
    sim->ckpt.last_wall = ry_wall_time();
    if (path) snprintf(path, path_size, "%s", file);
    /* The new one is complete: only now are the oldest removed. */
    long *steps;
    int n;
    RY_TRY(list_checkpoints(dir, &steps, &n, err));
    int keep = sim->ckpt.keep > 0 ? sim->ckpt.keep : 1;
    for (int i = keep; i < n; ++i) {
        ck_path(file, sizeof file, dir, steps[i]);
        unlink(file);
    }
    free(steps);
    return RY_OK;
}

ry_status ry_restart_newest(ry_sim *sim, const char *dir, char *used, size_t used_size,
                            char *skipped, size_t skipped_size, ry_error *err) {
    char ckdir[4096], file[4200];
    snprintf(ckdir, sizeof ckdir, "%s/checkpoints", dir);
    long *steps;
    int n;
    RY_TRY(list_checkpoints(ckdir, &steps, &n, err));
    if (n == 0) {
        snprintf(ckdir, sizeof ckdir, "%s", dir);
        RY_TRY(list_checkpoints(ckdir, &steps, &n, err));
    }
    if (skipped && skipped_size) skipped[0] = '\0';
    if (n == 0) {
        free(steps);
        return ry_error_set(err, RY_ERR_INPUT,
                            "--restart %s: no checkpoint (%s*%s) in %s/checkpoints or %s", dir,
                            CK_PREFIX, CK_SUFFIX, dir, dir);
    }
    ry_status st = RY_ERR_INPUT;
    ry_error first = {0};
    for (int i = 0; i < n; ++i) {
        ck_path(file, sizeof file, ckdir, steps[i]);
        ry_ck_reader r;
        ry_error e = {0};
        st = ry_ck_open(&r, file, &e);
        if (st == RY_OK) {
            st = ry_sim_checkpoint_load(sim, &r, &e);
            ry_ck_close(&r);
            if (st != RY_OK) { /* the file was sound: the case does not fit it */
                *err = e;
                break;
            }
            if (used) snprintf(used, used_size, "%s", file);
            break;
        }
        if (i == 0) first = e;
        if (skipped && skipped_size) {
            size_t l = strlen(skipped);
            snprintf(skipped + l, skipped_size - l, "%s%s", l ? "; " : "", e.msg);
        }
        if (i == n - 1) *err = first;
    }
    free(steps);
    return st;
}

/* ---- the last good state ------------------------------------------------------------------ */

typedef struct snapshot {
    size_t n, cap;
    int nfields;
    double **f;
    int64_t *id, next_id;
    uint8_t *kind, *material;
    double t, dt, next_output, nl_radius;
    long step, searches;
    int nv;
    double vars[MAX_VARS];
    int valid;
} snapshot;

void ry_sim_snapshot_free(ry_sim *sim) {
    snapshot *s = sim->snapshot;
    if (!s) return;
    for (int f = 0; f < s->nfields; ++f) free(s->f[f]);
    free(s->f);
    free(s->id);
    free(s->kind);
    free(s->material);
    free(s);
    sim->snapshot = NULL;
}

ry_status ry_sim_snapshot_take(ry_sim *sim, ry_error *err) {
    const ry_particles *ps = &sim->ps;
    snapshot *s = sim->snapshot;
    if (!s || s->nfields != ps->nfields) {
        ry_sim_snapshot_free(sim);
        s = calloc(1, sizeof *s);
        RY_CHECK(err, s != NULL, RY_ERR_NOMEM, "out of memory (snapshot)");
        sim->snapshot = s;
        s->f = calloc((size_t)ps->nfields, sizeof *s->f);
        RY_CHECK(err, s->f != NULL, RY_ERR_NOMEM, "out of memory (snapshot)");
        s->nfields = ps->nfields;
    }
    if (s->cap < ps->n) {
        size_t cap = ps->n + ps->n / 8 + 16;
        for (int f = 0; f < ps->nfields; ++f) {
            if (!kept(ps, f)) continue;
            double *p = realloc(s->f[f], cap * sizeof *p);
            RY_CHECK(err, p != NULL, RY_ERR_NOMEM, "out of memory (snapshot)");
            s->f[f] = p;
        }
        int64_t *id = realloc(s->id, cap * sizeof *id);
        if (id) s->id = id;
        uint8_t *k = realloc(s->kind, cap), *m = k ? realloc(s->material, cap) : NULL;
        if (k) s->kind = k;
        if (m) s->material = m;
        RY_CHECK(err, id && k && m, RY_ERR_NOMEM, "out of memory (snapshot)");
        s->cap = cap;
    }
    s->n = ps->n;
    for (int f = 0; f < ps->nfields; ++f)
        if (kept(ps, f)) memcpy(s->f[f], ps->f[f], ps->n * sizeof(double));
    memcpy(s->id, ps->id, ps->n * sizeof *ps->id);
    memcpy(s->kind, ps->kind, ps->n);
    memcpy(s->material, ps->material, ps->n);
    s->next_id = ps->next_id;
    s->t = sim->t;
    s->dt = sim->dt;
    s->next_output = sim->next_output;
    s->nl_radius = sim->nl_radius;
    s->step = sim->step;
    s->searches = sim->searches;
    ry_state_var vars[MAX_VARS];
    s->nv = scheme_vars(sim, vars);
    for (int i = 0; i < s->nv; ++i) s->vars[i] = var_get(&vars[i]);
    s->valid = 1;
    return RY_OK;
}

ry_status ry_sim_snapshot_write(ry_sim *sim, char *path, size_t path_size, ry_error *err) {
    snapshot *s = sim->snapshot;
    RY_CHECK(err, s && s->valid, RY_ERR_INTERNAL, "no good state was kept");
    ry_particles *ps = &sim->ps;
    if (s->n > ps->n) {
        size_t first;
        RY_TRY(ry_particles_add(ps, s->n - ps->n, &first, err));
    }
    ps->n = s->n;
    for (int f = 0; f < ps->nfields; ++f)
        if (kept(ps, f)) memcpy(ps->f[f], s->f[f], ps->n * sizeof(double));
    memcpy(ps->id, s->id, ps->n * sizeof *ps->id);
    memcpy(ps->kind, s->kind, ps->n);
    memcpy(ps->material, s->material, ps->n);
    ps->next_id = s->next_id;
    sim->t = s->t;
    sim->dt = s->dt;
    sim->next_output = s->next_output;
    sim->nl_radius = s->nl_radius;
    sim->step = s->step;
    sim->searches = s->searches;
    sim->nl_restore = ry_sim_searched(sim);
    ry_nlist_free(&sim->nl);
    ry_state_var vars[MAX_VARS];
    int nv = scheme_vars(sim, vars);
    for (int i = 0; i < nv && i < s->nv; ++i) (void)var_set(&vars[i], s->vars[i]);
    return ry_sim_last_good_write(sim, path, path_size, err);
}

ry_status ry_sim_last_good_write(ry_sim *sim, char *path, size_t path_size, ry_error *err) {
    char vtp[4200];
    snprintf(vtp, sizeof vtp, "%s/%s_last_good.vtp", sim->out_dir, sim->case_name);
    RY_TRY(ry_vtk_write_particles(vtp, &sim->ps, sim->t, err));
    return ry_sim_checkpoint_now(sim, path, path_size, err);
}
