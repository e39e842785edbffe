/* Writing a simulation's results: VTK per output time, the .pvd collection, series.csv. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sim/writer.h"
#include "ryushi/atomic_file.h"
#include "ryushi/output.h"
#include "ryushi/probes.h"
#include "ryushi/run.h"

typedef struct writer {
    int n, cap;
    char **files;
    double *times;
    char *csv; /* series.csv contents so far */
    size_t csv_len, csv_cap;
} writer;

static ry_status csv_append(writer *w, ry_error *err, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

static ry_status csv_append(writer *w, ry_error *err, const char *fmt, ...) {
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        size_t room = w->csv_cap - w->csv_len;
        int k = vsnprintf(w->csv ? w->csv + w->csv_len : NULL, room, fmt, ap);
        va_end(ap);
        if (k < 0) return ry_error_set(err, RY_ERR_INTERNAL, "formatting series.csv failed");
        if ((size_t)k < room) {
            w->csv_len += (size_t)k;
            return RY_OK;
        }
        size_t cap = w->csv_cap ? 2 * w->csv_cap : 4096;
        while (cap < w->csv_len + (size_t)k + 1) cap *= 2;
        char *p = realloc(w->csv, cap);
        if (!p) return ry_error_set(err, RY_ERR_NOMEM, "out of memory (series.csv)");
        w->csv = p;
        w->csv_cap = cap;
    }
}

/* The header line of series.csv, its newline included. */
static ry_status csv_header(const ry_sim *sim, writer *w, ry_error *err) {
    RY_TRY(csv_append(w, err, "t,step,dt,particles"));
    for (int k = 0; k < sim->nprobes; ++k) RY_TRY(csv_append(w, err, ",%s", sim->probes[k]->name));
    return csv_append(w, err, "\n");
}

ry_status ry_sim_open_output(ry_sim *sim, ry_case *c, ry_error *err) {
    RY_TRY(ry_mkdir_p(sim->out_dir, err));
    writer *w = calloc(1, sizeof *w);
    RY_CHECK(err, w != NULL, RY_ERR_NOMEM, "out of memory");
    sim->writer = w;
    char path[4096];
    snprintf(path, sizeof path, "%s/case_resolved.yaml", sim->out_dir);
    RY_TRY(ry_case_write_resolved(c, path, err));
    return csv_header(sim, w, err);
}

/* Field k (0-based) of the comma-separated line [p, end): its start and length; 0 if absent. */
static int csv_field(const char *p, const char *end, int k, const char **at, size_t *len) {
    for (; k > 0; --k) {
        const char *c = memchr(p, ',', (size_t)(end - p));
        if (!c) return 0;
        p = c + 1;
    }
    const char *c = memchr(p, ',', (size_t)(end - p));
    *at = p;
    *len = (size_t)((c ? c : end) - p);
    return 1;
}

/* A restart whose measurement list differs from the checkpoint's: the rows of the series so far
 * (old, len bytes) rewritten under this run's header into w, column by name, empty where the
 * earlier run did not measure. */
static ry_status csv_remap(const ry_sim *sim, writer *w, const char *old, size_t len,
                           ry_error *err) {
    const char *end = old + len, *hend = memchr(old, '\n', len);
    if (!hend) hend = end;
    const int ncol = 4 + sim->nprobes;
    int *from = malloc((size_t)ncol * sizeof *from); /* old column of each new one, -1 none */
    RY_CHECK(err, from != NULL, RY_ERR_NOMEM, "out of memory");
    for (int k = 0; k < ncol; ++k) {
        static const char *const fixed[4] = {"t", "step", "dt", "particles"};
        const char *name = k < 4 ? fixed[k] : sim->probes[k - 4]->name;
        from[k] = -1;
        const char *at;
        size_t n;
        for (int o = 0; csv_field(old, hend, o, &at, &n); ++o)
            if (n == strlen(name) && memcmp(at, name, n) == 0) {
                from[k] = o;
                break;
            }
    }
    ry_status st = csv_header(sim, w, err);
    for (const char *p = hend + (hend < end); st == RY_OK && p < end;) {
        const char *e = memchr(p, '\n', (size_t)(end - p));
        if (!e) e = end;
        for (int k = 0; st == RY_OK && k < ncol; ++k) {
            const char *at = "";
            size_t n = 0;
            if (from[k] >= 0 && !csv_field(p, e, from[k], &at, &n)) n = 0;
            st = csv_append(w, err, "%s%.*s", k ? "," : "", (int)n, at);
        }
        if (st == RY_OK) st = csv_append(w, err, "\n");
        p = e + 1;
    }
    free(from);
    return st;
}

void ry_writer_free(ry_sim *sim) {
    writer *w = sim->writer;
    if (!w) return;
    for (int i = 0; i < w->n; ++i) free(w->files[i]);
    free(w->files);
    free(w->times);
    free(w->csv);
    free(w);
    sim->writer = NULL;
}

ry_status ry_output_write(ry_sim *sim, ry_error *err) {
    RY_TRY(ry_output_write_vtk(sim, err));
    return ry_output_write_series(sim, err);
}

ry_status ry_output_write_vtk(ry_sim *sim, ry_error *err) {
    writer *w = sim->writer;
    RY_CHECK(err, w != NULL, RY_ERR_INTERNAL, "output written before the writer was opened");
    char path[4096], name[512];
    if (sim->write_vtk) {
        snprintf(name, sizeof name, "%s_%05d.%s", sim->case_name, sim->output_index,
                 sim->vtk_pieces ? "pvtp" : "vtp");
        snprintf(path, sizeof path, "%s/%s", sim->out_dir, name);
        if (sim->vtk_pieces) { /* the ranks wrote their pieces into CASE_NNNNN/ */
            char dir[600];
            snprintf(dir, sizeof dir, "%s_%05d", sim->case_name, sim->output_index);
            RY_TRY(ry_pvtp_write(path, &sim->ps, sim->vtk_pieces, dir, sim->t, err));
        } else {
            RY_TRY(ry_vtk_write_particles(path, &sim->ps, sim->t, err));
        }
        if (w->n == w->cap) {
            int cap = w->cap ? 2 * w->cap : 64;
            char **f = realloc(w->files, (size_t)cap * sizeof *f);
            if (f) w->files = f;
            double *t = realloc(w->times, (size_t)cap * sizeof *t);
            if (t) w->times = t;
            RY_CHECK(err, f && t, RY_ERR_NOMEM, "out of memory");
            w->cap = cap;
        }
        w->files[w->n] = malloc(strlen(name) + 1);
        RY_CHECK(err, w->files[w->n] != NULL, RY_ERR_NOMEM, "out of memory");
        strcpy(w->files[w->n], name);
        w->times[w->n] = sim->t;
        w->n++;
        snprintf(path, sizeof path, "%s/%s.pvd", sim->out_dir, sim->case_name);
        RY_TRY(ry_pvd_write(path, w->n, w->files, w->times, err));
    }
    return RY_OK;
}

ry_status ry_output_write_series(ry_sim *sim, ry_error *err) {
    writer *w = sim->writer;
    RY_CHECK(err, w != NULL, RY_ERR_INTERNAL, "output written before the writer was opened");
    char path[4096];
    RY_TRY(csv_append(w, err, "%.10g,%ld,%.6g,%zu", sim->t, sim->step, sim->dt, sim->ps.n));
    for (int k = 0; k < sim->nprobes; ++k) {
        double v;
        RY_TRY(ry_probe_eval(sim->probes[k], sim, &v, err));
        RY_TRY(csv_append(w, err, ",%.12g", v));
        if (k == sim->stop_probe && (sim->stop_above ? v > sim->stop_value : v < sim->stop_value)) {
            sim->finished = 1;
            snprintf(sim->stop_reason, sizeof sim->stop_reason,
                     "stopped at t = %.6g s: %s = %.6g, %s %.6g (time.stop_when)", sim->t,
                     sim->probes[k]->name, v, sim->stop_above ? "above" : "below", sim->stop_value);
        }
    }
    RY_TRY(csv_append(w, err, "\n"));
    snprintf(path, sizeof path, "%s/series.csv", sim->out_dir);
    RY_TRY(ry_atomic_write(path, w->csv, w->csv_len, err));
    RY_TRY(ry_profiles_output(sim, err));
    sim->output_index++;
    return RY_OK;
}

ry_status ry_writer_save(const ry_sim *sim, ry_ck_writer *ck, ry_error *err) {
    const writer *w = sim->writer;
    RY_CHECK(err, w != NULL, RY_ERR_INTERNAL, "checkpoint written before the writer was opened");
    size_t len = 0;
    for (int i = 0; i < w->n; ++i) len += strlen(w->files[i]) + 1;
    char *names = malloc(len + 1);
    RY_CHECK(err, names != NULL, RY_ERR_NOMEM, "out of memory");
    size_t at = 0;
    for (int i = 0; i < w->n; ++i) at += (size_t)sprintf(names + at, "%s\n", w->files[i]);
    ry_status st = ry_ck_put_text(ck, "output/pvd_files", names, len, err);
    free(names);
    RY_TRY(st);
    RY_TRY(ry_ck_put(ck, "output/pvd_times", RY_CK_F64, w->times, (size_t)w->n, err));
    return ry_ck_put_text(ck, "output/series", w->csv, w->csv_len, err);
}

ry_status ry_writer_load(ry_sim *sim, const ry_ck_reader *ck, ry_error *err) {
    writer *w = sim->writer;
    RY_CHECK(err, w != NULL, RY_ERR_INTERNAL, "checkpoint read before the writer was opened");
    char *names = NULL, *csv = NULL;
    size_t len, csv_len;
    RY_TRY(ry_ck_get_text(ck, "output/pvd_files", &names, &len, err));
    ry_status st = ry_ck_get_text(ck, "output/series", &csv, &csv_len, err);
    int n = 0;
    for (size_t i = 0; i < len; ++i) n += names[i] == '\n';
    char **files = calloc((size_t)n + 1, sizeof *files);
    double *times = malloc(((size_t)n + 1) * sizeof *times);
    if (st == RY_OK && (!files || !times)) st = ry_error_set(err, RY_ERR_NOMEM, "out of memory");
    if (st == RY_OK) st = ry_ck_get(ck, "output/pvd_times", RY_CK_F64, (size_t)n, times, err);
    char *p = names;
    for (int i = 0; st == RY_OK && i < n; ++i) {
        char *nl = strchr(p, '\n');
        *nl = '\0';
        if (!*p || strchr(p, '/') || strchr(p, '"') || strchr(p, '<') || strchr(p, '&')) {
            st = ry_error_set(err, RY_ERR_INPUT,
                              "checkpoint %s: record 'output/pvd_files': bad file name", ck->path);
            break;
        }
        files[i] = ry_strdup(p);
        if (!files[i]) st = ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        p = nl + 1;
    }
    free(names);
    if (st != RY_OK) {
        for (int i = 0; i < n; ++i) free(files[i]);
        free(files);
        free(times);
        free(csv);
        return st;
    }
    for (int i = 0; i < w->n; ++i) free(w->files[i]);
    free(w->files);
    free(w->times);
    free(w->csv);
    w->files = files;
    w->times = times;
    w->n = w->cap = n;
    w->csv = NULL;
    w->csv_len = w->csv_cap = 0;
    RY_TRY(csv_header(sim, w, err));
    if (csv_len >= w->csv_len && memcmp(csv, w->csv, w->csv_len) == 0) {
        free(w->csv); /* the same measurements: the series as it was */
        w->csv = csv;
        w->csv_len = csv_len;
        w->csv_cap = csv_len + 1;
    } else {
        w->csv_len = 0;
        st = csv_remap(sim, w, csv, csv_len, err);
        free(csv);
        RY_TRY(st);
    }
    char path[4096];
    if (n > 0) {
        snprintf(path, sizeof path, "%s/%s.pvd", sim->out_dir, sim->case_name);
        RY_TRY(ry_pvd_write(path, w->n, w->files, w->times, err));
    }
    snprintf(path, sizeof path, "%s/series.csv", sim->out_dir);
    return ry_atomic_write(path, w->csv, w->csv_len, err);
}
