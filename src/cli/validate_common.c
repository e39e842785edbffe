/* What the validations share: series into plots, the PASS/FAIL lines, plots written, slices of
 * 3D runs. */
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <sys/stat.h>

#include "cli/cli.h"
#include "ryushi/manifest.h"

ry_status ry_cli_add_series(ry_plot *p, int panel, const char *label, const ry_table *t,
                            const char *cx, double sx, const char *cy, double sy,
                            ry_plot_style style, ry_error *err) {
    int ix = ry_table_col(t, cx), iy = ry_table_col(t, cy);
    RY_CHECK(err, ix >= 0 && iy >= 0, RY_ERR_INPUT, "missing column %s or %s", cx, cy);
    double *x = ry_table_column(t, ix), *y = ry_table_column(t, iy);
    ry_status st = RY_OK;
    if (!x || !y) st = ry_error_set(err, RY_ERR_NOMEM, "out of memory");
    for (size_t r = 0; r < t->nrows && st == RY_OK; ++r) {
        x[r] *= sx;
        y[r] *= sy;
    }
    if (st == RY_OK) st = ry_plot_series(p, panel, label, t->nrows, x, y, style, err);
    free(x);
    free(y);
    return st;
}

void ry_cli_slice_markers_in(ry_plot *p, int panel, const ry_sim *sim, const ry_cli_slice *sl,
                             const char *const label[3], int legend) {
    ry_error err;
    const ry_particles *ps = &sim->ps;
    const int sides = sl->mirror ? 2 : 1;
    double *x = malloc(sides * ps->n * sizeof *x), *z = malloc(sides * ps->n * sizeof *z);
    const int color[3] = {7, 0, 1};
    for (int set = 0; x && z && set < 3; ++set) {
        size_t m = 0;
        for (size_t i = 0; i < ps->n; ++i) {
            const double c = ps->f[RY_F_X + sl->normal][i], h = ps->f[RY_F_X + sl->ax][i];
            if (c < sl->lo || c > sl->hi || (sl->mirror && h < 0)) continue;
            const int k = ps->kind[i];
            const int which =
                k == RY_KIND_WALL ? 0 : (k == RY_KIND_FLUID ? 1 + (ps->material[i] == 1) : -1);
            if (which != set) continue;
            for (int side = 0; side < sides; ++side) {
                x[m] = (side ? -1e3 : 1e3) * h;
                z[m++] = 1e3 * ps->f[RY_F_X + sl->ay][i];
            }
        }
        if (m == 0) continue;
        ry_plot_style st = ry_plot_style_markers(RY_PLOT_MARKER_CIRCLE);
        st.color = color[set];
        st.marker_size = sl->marker_size;
        ry_plot_series(p, panel, legend ? label[set] : NULL, m, x, z, st, &err);
    }
    free(x);
    free(z);
}

void ry_cli_slice_markers(ry_plot *p, int panel, const ry_sim *sim, double half,
                          const char *const label[3], int legend) {
    const ry_cli_slice sl = {1, -half, half, 0, 2, 0, 6};
    ry_cli_slice_markers_in(p, panel, sim, &sl, label, legend);
}

double *ry_cli_scaled_column(const ry_table *s, const char *name, double k) {
    const int c = ry_table_col(s, name);
    double *v = c >= 0 ? ry_table_column(s, c) : NULL;
    for (size_t r = 0; v && r < s->nrows; ++r) v[r] *= k;
    return v;
}

/* Where the checks of the running validation are recorded (ry_cli_results). */
static FILE *results;

void ry_cli_results(FILE *fp) {
    results = fp;
}

/* A check's line and its row of the results: "what",figure,tolerance,verdict (the figure and
 * the tolerance empty when NAN). */
static void check_row(const char *what, double figure, double tolerance, int ok, int *failures) {
    if (isnan(figure))
        printf("  %-64s %s\n", what, ok ? "PASS" : "FAIL");
    else
        printf("  %-64s %s (%.4g)\n", what, ok ? "PASS" : "FAIL", figure);
    if (!ok) ++*failures;
    if (!results) return;
    fputc('"', results);
    for (const char *c = what; *c; ++c) {
        if (*c == '"') fputc('"', results);
        fputc(*c, results);
    }
    fputs("\",", results);
    if (!isnan(figure)) fprintf(results, "%.6g", figure);
    fputc(',', results);
    if (!isnan(tolerance)) fprintf(results, "%.6g", tolerance);
    fprintf(results, ",%s\n", ok ? "PASS" : "FAIL");
}

void ry_cli_check(const char *what, int ok, int *failures) {
    check_row(what, NAN, NAN, ok, failures);
}

void ry_cli_check_figure(const char *what, double figure, double tolerance, int ok, int *failures) {
    check_row(what, figure, tolerance, ok, failures);
}

void ry_cli_write_plot(ry_plot *p, const char *out, const char *name, int *failures) {
    ry_error err = {0};
    char png[4096];
    snprintf(png, sizeof png, "%s/%s", out, name);
    if (ry_plot_write_png(p, png, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        ++*failures;
    } else {
        printf("  plot: %s\n", png);
    }
}

ry_status ry_cli_run_series(const char *root, const char *out, const char *case_file,
                            const char *sub, int nset, const char *const *sets, ry_sim *sim,
                            ry_run_stats *stats, ry_table *series, ry_error *err) {
    char cpath[4096], odir[4096], spath[4200];
    snprintf(cpath, sizeof cpath, "%s/%s", root, case_file);
    snprintf(odir, sizeof odir, "%s/%s", out, sub);
    RY_TRY(ry_run_case_file(cpath, nset, sets, odir, sim, stats, err));
    snprintf(spath, sizeof spath, "%s/series.csv", odir);
    const ry_status st = ry_table_read(series, spath, err);
    if (st != RY_OK) ry_sim_free(sim);
    return st;
}

int ry_cli_tolerances(const char *root, const char *name, int n, const char *const *keys,
                      double *values, int *failures) {
    ry_manifest m;
    ry_error err = {0};
    ry_status st = ry_manifest_load(&m, root, name, &err);
    for (int k = 0; k < n && st == RY_OK; ++k) st = ry_manifest_tol(&m, keys[k], &values[k], &err);
    if (m.doc) ry_manifest_free(&m);
    return st == RY_OK ? 0 : ry_cli_fail(failures, &err);
}

int ry_cli_fail(int *failures, const ry_error *err) {
    fprintf(stderr, "ryushi: validate: %s\n", err->msg);
    ++*failures;
    return 1;
}

static volatile sig_atomic_t stop_requested;
static void on_signal(int sig) {
    (void)sig;
    stop_requested = 1;
}

static void on_progress(void *ctx, const ry_sim *sim, double rate, double eta) {
    (void)ctx;
    printf("  t = %.3f s, %.3g particle-steps/s, at most %.0f s to go\n", sim->t, rate, eta);
    fflush(stdout);
}

ry_status ry_cli_run_or_resume(const char *cpath, int nset, const char *const *sets,
                               const char *odir, ry_sim *sim, ry_run_stats *stats, ry_error *err) {
    char ck[4200];
    struct stat sb;
    snprintf(ck, sizeof ck, "%s/checkpoints", odir);
    const int resume = stat(ck, &sb) == 0 && S_ISDIR(sb.st_mode);
    RY_TRY(ry_setup_case_file(cpath, nset, sets, odir, sim, err));
    ry_status st = RY_OK;
    char used[4300] = "";
    if (resume) {
        st = ry_restart_newest(sim, odir, used, sizeof used, NULL, 0, err);
        if (st == RY_OK) printf("  resuming from %s (t = %.4g s)\n", used, sim->t);
    }
    if (st == RY_OK) {
        fflush(stdout);
        stop_requested = 0;
        void (*old_int)(int) = signal(SIGINT, on_signal);
        void (*old_term)(int) = signal(SIGTERM, on_signal);
        ry_run_hooks hooks = {on_progress, NULL, 300.0, &stop_requested};
        st = ry_run(sim, &hooks, stats, err);
        signal(SIGINT, old_int);
        signal(SIGTERM, old_term);
    }
    if (st != RY_OK && st != RY_ERR_INTERRUPTED) ry_sim_free(sim);
    return st;
}
