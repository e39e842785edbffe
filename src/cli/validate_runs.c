/* Validations given as data alone: the runs of validation/NAME.yaml (`runs`), each a case with
 * overrides judged by a statistic of one column of its series against an expected value and a
 * tolerance of the manifest, and their figures (`figures`: the column against time, one curve
 * per run). validation/README.md ("Runs as data") documents the keys. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "ryushi/case.h"
#include "ryushi/manifest.h"
#include "ryushi/run.h"

enum { MAX_SETS = 16, MAX_FIGURES = 8 };

/* A figure of the manifest: the runs naming it draw their column against time into it. */
typedef struct figure {
    const char *name, *file;
    ry_plot *plot;
    int used; /* a run drew into it (a figure of the full version's runs alone is not written
               * by the short one) */
} figure;

static const char *key_text(ry_manifest *m, const char *fmt, int k, const char *field,
                            const char *def) {
    char key[256];
    snprintf(key, sizeof key, fmt, k, field);
    return ry_manifest_text(m, key, def);
}

/* The figures of the manifest, drawn with their titles and axes (a figure that cannot be drawn
 * is left out: NULL plot). */
static int open_figures(ry_manifest *m, figure *f) {
    int n = 0;
    for (int k = 0; k < MAX_FIGURES && key_text(m, "figures[%d].%s", k, "name", NULL); ++k) {
        ry_error err = {0};
        f[n].name = key_text(m, "figures[%d].%s", k, "name", NULL);
        f[n].file = key_text(m, "figures[%d].%s", k, "file", "figure.png");
        f[n].plot = NULL;
        f[n].used = 0;
        if (ry_plot_new(&f[n].plot, 1, 1, 900, 600, &err) != RY_OK)
            f[n].plot = NULL;
        else
            ry_plot_panel(f[n].plot, 0, key_text(m, "figures[%d].%s", k, "title", ""),
                          key_text(m, "figures[%d].%s", k, "x", "t (ms)"),
                          key_text(m, "figures[%d].%s", k, "y", ""), &err);
        ++n;
    }
    return n;
}

static const char *field_text(ry_manifest *m, const char *prefix, const char *field,
                              const char *def) {
    char key[256];
    snprintf(key, sizeof key, "%s.%s", prefix, field);
    return ry_manifest_text(m, key, def);
}

/* One check of a run (prefix: "runs[k]", or "runs[k].checks[c]" for a run with several): the
 * mean of its column over t >= from against its expected value within its tolerance, and the
 * column's curve (in ms) into its figure. A check's keys default to the run's. */
static void judge(ry_manifest *m, const char *run, const char *prefix, const ry_table *s,
                  const char *label, const ry_run_stats *stats, figure *figs, int nfig,
                  int *failures) {
    ry_error err = {0};
    const char *column = field_text(m, prefix, "column", field_text(m, run, "column", NULL));
    const char *tol_key = field_text(m, prefix, "tolerance", field_text(m, run, "tolerance", NULL));
    const char *what = field_text(m, prefix, "what", field_text(m, run, "what", label));
    const char *fig = field_text(m, prefix, "figure", field_text(m, run, "figure", NULL));
    double from = 0, expect = 0, tol = NAN;
    char key[300];
    snprintf(key, sizeof key, "%s.from", run);
    ry_status st = ry_case_double(m->doc, key, &from, -INFINITY, INFINITY, &from, &err);
    snprintf(key, sizeof key, "%s.from", prefix);
    if (st == RY_OK) st = ry_case_double(m->doc, key, &from, -INFINITY, INFINITY, &from, &err);
    snprintf(key, sizeof key, "%s.expect", prefix);
    if (st == RY_OK && !ry_case_has(m->doc, key)) snprintf(key, sizeof key, "%s.expect", run);
    if (st == RY_OK) st = ry_case_double(m->doc, key, NULL, -INFINITY, INFINITY, &expect, &err);
    if (st == RY_OK && (!column || !tol_key))
        st = ry_error_set(&err, RY_ERR_INPUT, "%s: %s needs column and tolerance", m->path, prefix);
    if (st == RY_OK) st = ry_manifest_tol(m, tol_key, &tol, &err);
    if (st != RY_OK) {
        ry_cli_fail(failures, &err);
        return;
    }
    const int ct = ry_table_col(s, "t"), ca = ry_table_col(s, column);
    double sum = 0, lo = INFINITY, hi = -INFINITY;
    int cnt = 0;
    double *t = calloc(s->nrows + 1, sizeof *t), *a = calloc(s->nrows + 1, sizeof *a);
    size_t np = 0;
    for (size_t r = 0; r < s->nrows && ct >= 0 && ca >= 0; ++r) {
        const double tr = ry_table_at(s, r, ct), ar = ry_table_at(s, r, ca);
        if (t && a && isfinite(ar)) {
            t[np] = 1e3 * tr;
            a[np++] = ar;
        }
        if (tr < from) continue;
        sum += ar;
        lo = fmin(lo, ar);
        hi = fmax(hi, ar);
        ++cnt;
    }
    const double mean = cnt ? sum / cnt : NAN;
    printf("  %-36s %s settles at %.4g (%.4g-%.4g from %g ms), %ld steps, %.1f s\n", label, column,
           mean, lo, hi, 1e3 * from, stats->steps, stats->wall_s);
    for (int f = 0; fig && f < nfig; ++f)
        if (strcmp(figs[f].name, fig) == 0 && figs[f].plot && t && a) {
            ry_plot_series(figs[f].plot, 0, label, np, t, a, ry_plot_style_line(), &err);
            figs[f].used = 1;
        }
    ry_cli_check_figure(what, fabs(mean - expect), tol, fabs(mean - expect) <= tol, failures);
    free(t);
    free(a);
}

/* Run k of the manifest: its case with its overrides into out/NAME, then its check, or each of
 * its `checks`. */
static void one_run(const char *root, const char *out, ry_manifest *m, int k, figure *figs,
                    int nfig, int *failures) {
    ry_error err = {0};
    char run[64], prefix[96];
    snprintf(run, sizeof run, "runs[%d]", k);
    const char *sub = field_text(m, run, "name", "run");
    const char *case_rel = field_text(m, run, "case", NULL);
    const char *label = field_text(m, run, "label", sub);
    const char *sets[MAX_SETS];
    int nset = 0;
    for (int i = 0; i < MAX_SETS; ++i) {
        char key[256];
        snprintf(key, sizeof key, "%s.set", run);
        const char *v = ry_manifest_item(m, key, i);
        if (!v) break;
        sets[nset++] = v;
    }
    if (!case_rel) {
        ry_error_set(&err, RY_ERR_INPUT, "%s: %s needs a case", m->path, run);
        ry_cli_fail(failures, &err);
        return;
    }
    char cpath[4096], odir[4096], spath[4200];
    snprintf(cpath, sizeof cpath, "%s/%s", root, case_rel);
    snprintf(odir, sizeof odir, "%s/%s", out, sub);
    ry_sim sim;
    ry_run_stats stats;
    ry_table s;
    if (ry_run_case_file(cpath, nset, sets, odir, &sim, &stats, &err) != RY_OK) {
        ry_cli_fail(failures, &err);
        return;
    }
    ry_sim_free(&sim);
    snprintf(spath, sizeof spath, "%s/series.csv", odir);
    if (ry_table_read(&s, spath, &err) != RY_OK) {
        ry_cli_fail(failures, &err);
        return;
    }
    snprintf(prefix, sizeof prefix, "%s.checks[0].column", run);
    if (!ry_manifest_text(m, prefix, NULL))
        judge(m, run, run, &s, label, &stats, figs, nfig, failures);
    for (int c = 0;; ++c) {
        snprintf(prefix, sizeof prefix, "%s.checks[%d].column", run, c);
        if (!ry_manifest_text(m, prefix, NULL)) break;
        snprintf(prefix, sizeof prefix, "%s.checks[%d]", run, c);
        judge(m, run, prefix, &s, label, &stats, figs, nfig, failures);
    }
    ry_table_free(&s);
}

int ry_cli_validate_runs(const char *root, const char *out, int quick, const char *name,
                         int *failures) {
    ry_manifest m;
    ry_error err = {0};
    if (ry_manifest_load(&m, root, name, &err) != RY_OK) return ry_cli_fail(failures, &err);
    figure figs[MAX_FIGURES];
    const int nfig = open_figures(&m, figs);
    const char *heading = NULL;
    for (int k = 0; key_text(&m, "runs[%d].%s", k, "case", NULL); ++k) {
        int in_quick = 1;
        char key[64];
        snprintf(key, sizeof key, "runs[%d].quick", k);
        const int yes = 1;
        if (ry_case_bool(m.doc, key, &yes, &in_quick, &err) != RY_OK) {
            ry_cli_fail(failures, &err);
            continue;
        }
        if (quick && !in_quick) continue;
        const char *h = key_text(&m, "runs[%d].%s", k, "heading", NULL);
        if (h && (!heading || strcmp(h, heading) != 0)) printf("%s\n", h);
        if (h) heading = h;
        one_run(root, out, &m, k, figs, nfig, failures);
    }
    for (int f = 0; f < nfig; ++f) {
        if (!figs[f].plot) continue;
        ry_plot_legend(figs[f].plot, 0, RY_PLOT_LEGEND_SE, &err);
        if (figs[f].used) ry_cli_write_plot(figs[f].plot, out, figs[f].file, failures);
        ry_plot_free(figs[f].plot);
    }
    ry_manifest_free(&m);
    return 0;
}

int ry_cli_manifest_has_runs(ry_manifest *m) {
    return ry_manifest_text(m, "runs[0].case", NULL) != NULL;
}
