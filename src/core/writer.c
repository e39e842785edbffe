/* Writing a simulation's results: VTK per output time, the .pvd collection, series.csv. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/writer.h"
#include "ryushi/atomic_file.h"
#include "ryushi/output.h"

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

ry_status ry_sim_open_output(ry_sim *sim, ry_case *c, ry_error *err) {
    RY_TRY(ry_mkdir_p(sim->out_dir, err));
    writer *w = calloc(1, sizeof *w);
    RY_CHECK(err, w != NULL, RY_ERR_NOMEM, "out of memory");
    sim->writer = w;
    char path[4096];
    snprintf(path, sizeof path, "%s/case_resolved.yaml", sim->out_dir);
    RY_TRY(ry_case_write_resolved(c, path, err));
    RY_TRY(csv_append(w, err, "t,step,dt,particles"));
    for (int k = 0; k < sim->nprobes; ++k) RY_TRY(csv_append(w, err, ",%s", sim->probes[k]->name));
    RY_TRY(csv_append(w, err, "\n"));
    return RY_OK;
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

ry_status ry_sim_write_output(ry_sim *sim, ry_error *err) {
    writer *w = sim->writer;
    RY_CHECK(err, w != NULL, RY_ERR_INTERNAL, "output written before the writer was opened");
    char path[4096], name[512];
    if (sim->write_vtk) {
        snprintf(name, sizeof name, "%s_%05d.vtp", sim->case_name, sim->output_index);
        snprintf(path, sizeof path, "%s/%s", sim->out_dir, name);
        RY_TRY(ry_vtk_write_particles(path, &sim->ps, sim->t, err));
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
    RY_TRY(csv_append(w, err, "%.10g,%ld,%.6g,%zu", sim->t, sim->step, sim->dt, sim->ps.n));
    for (int k = 0; k < sim->nprobes; ++k) {
        double v;
        RY_TRY(sim->probes[k]->eval(sim, &v, err));
        RY_TRY(csv_append(w, err, ",%.12g", v));
    }
    RY_TRY(csv_append(w, err, "\n"));
    snprintf(path, sizeof path, "%s/series.csv", sim->out_dir);
    RY_TRY(ry_atomic_write(path, w->csv, w->csv_len, err));
    RY_TRY(ry_profiles_output(sim, err));
    sim->output_index++;
    return RY_OK;
}
