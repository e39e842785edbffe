/* ryushi validate rheology: non-Newtonian MPS, WCSPH and IISPH against analytic channel flows
 * (docs/reference/rheology.md): steady power-law, Carreau and Giesekus Poiseuille profiles, and the
 * start-up of Poiseuille flow of an Oldroyd-B fluid, at 20 and 40 particles across (--quick:
 * 20). Tables on stdout and in rheology.md, plots in rheology.png. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "ryushi/atomic_file.h"
#include "ryushi/plot.h"
#include "ryushi/validate.h"
#include "ryushi/run.h"

#define CH 1.0e-3 /* channel width of the cases [m] */
#define MAXROWS 128

/* A scheme the channels run with: its label, the prefix of its case files (cases/PREFIX_*.yaml)
 * and the end time of its steady runs (0: the case's). */
typedef struct scheme_def {
    const char *label, *prefix;
    double steady_end;
} scheme_def;

/* Runs the scheme's case NAME at n particles across into out/PREFIX_NAME_N, keeping the
 * simulation and its series; end > 0 overrides the end time. */
static ry_status run_at(const char *root, const char *out, const scheme_def *sd, const char *name,
                        double end, int across, ry_table *series, ry_sim *sim, ry_run_stats *stats,
                        ry_error *err) {
    char cpath[4096], odir[4096], spath[4200], sp[64], te[64];
    snprintf(cpath, sizeof cpath, "%s/cases/%s_%s.yaml", root, sd->prefix, name);
    snprintf(odir, sizeof odir, "%s/%s_%s_%d", out, sd->prefix, name, across);
    snprintf(sp, sizeof sp, "spacing=%.17g", CH / across);
    snprintf(te, sizeof te, "time.end=%.17g", end);
    const char *sets[] = {sp, "output.vtk=false", te};
    RY_TRY(ry_run_case_file(cpath, end > 0 ? 3 : 2, sets, odir, sim, stats, err));
    snprintf(spath, sizeof spath, "%s/series.csv", odir);
    ry_status st = ry_table_read(series, spath, err);
    if (st != RY_OK) ry_sim_free(sim);
    return st;
}

typedef struct steady_case {
    const char *name, *file; /* file: the case's name after the scheme's prefix */
    double g;
    double end; /* > 0: the end time for every scheme (a visco-elastic fluid settles in lambdas) */
} steady_case;

/* The steady profile of material m (nu: its solvent's viscosity). */
static double steady_ref(const steady_case *sc, const ry_material *m, double s) {
    const ry_rheology *r = &m->rheo;
    if (r->model == RY_RHEO_POWER_LAW && r->nu_min == 0)
        return ry_power_law_poiseuille(sc->g, r->consistency, r->index, 0.5 * CH, s);
    return ry_viscometric_poiseuille(r, m->viscosity, sc->g, 0.5 * CH, s);
}

/* A steady channel flow at one resolution: RMS and centreline errors, a row of md, and the
 * profile into the plot panel. */
static void steady_run(const char *root, const char *out, const scheme_def *sd,
                       const steady_case *sc, int across, FILE *md, ry_plot *plot, int panel,
                       int marker, int analytic, int *failures) {
    ry_error err = {0};
    ry_table s;
    ry_sim sim;
    ry_run_stats stats;
    const double end = sc->end > 0 ? sc->end : sd->steady_end;
    if (run_at(root, out, sd, sc->file, end, across, &s, &sim, &stats, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        ++*failures;
        return;
    }
    const ry_material *mat = &sim.mat[0];
    double y[MAXROWS], u[MAXROWS], ua[MAXROWS];
    const double l0 = CH / across;
    const size_t rows = ry_row_velocity(&sim, 0.0, l0, y, u, MAXROWS);
    const double uc = steady_ref(sc, mat, 0.0);
    double s2 = 0, umax = 0, worst = 0;
    for (size_t k = 0; k < rows; ++k) {
        ua[k] = steady_ref(sc, mat, y[k] - 0.5 * CH);
        const double e = (u[k] - ua[k]) / uc;
        s2 += e * e;
        worst = fmax(worst, fabs(e));
        umax = fmax(umax, u[k]);
    }
    const double rms = rows ? sqrt(s2 / rows) : NAN;
    const double centre = umax / steady_ref(sc, mat, 0.5 * l0) - 1;
    const double pss = stats.wall_s > 0 ? (double)sim.ps.n * stats.steps / stats.wall_s : 0;
    printf("  %-5s %-10s %3d across: u_c %.3f mm/s, centreline %+.2f %%, RMS %.2f %%, largest "
           "%.2f %% (%ld steps, %.2e particle-steps/s)\n",
           sd->label, sc->name, across, 1e3 * uc, 100 * centre, 100 * rms, 100 * worst, stats.steps,
           pss);
    if (md)
        fprintf(md, "| %s | %s | %d | %zu | %.3f | %+.2f %% | %.2f %% | %.2f %% | %ld |\n",
                sd->label, sc->name, across, sim.ps.n, 1e3 * uc, 100 * centre, 100 * rms,
                100 * worst, stats.steps);
    char label[64];
    double ymm[MAXROWS], umm[MAXROWS], uamm[MAXROWS];
    for (size_t k = 0; k < rows; ++k) {
        ymm[k] = 1e3 * y[k];
        umm[k] = 1e3 * u[k];
        uamm[k] = 1e3 * ua[k];
    }
    if (plot) {
        snprintf(label, sizeof label, "%s, %d across", sd->label, across);
        ry_plot_series(plot, panel, label, rows, ymm, umm, ry_plot_style_markers(marker), &err);
        if (analytic)
            ry_plot_series(plot, panel, "analytic", rows, ymm, uamm, ry_plot_style_line(), &err);
    }
    char what[160];
    static const char *const keys[2] = {"profile_rms", "centreline"};
    double tol[2];
    if (ry_cli_tolerances(root, "rheology", 2, keys, tol, failures) == 0) {
        snprintf(what, sizeof what, "%s %s, %d across: profile RMS within %g %% of u_c", sd->label,
                 sc->name, across, 100 * tol[0]);
        ry_cli_check_figure(what, rms, tol[0], rms < tol[0], failures);
        snprintf(what, sizeof what, "%s %s, %d across: centreline within %g %%", sd->label,
                 sc->name, across, 100 * tol[1]);
        ry_cli_check_figure(what, fabs(centre), tol[1], fabs(centre) < tol[1], failures);
    }
    ry_sim_free(&sim);
    ry_table_free(&s);
}

/* Oldroyd-B start-up at one resolution: the largest speed against the analytic velocity of the
 * rows next to the centreline at every output. */
static void startup_run(const char *root, const char *out, const scheme_def *sd, int across,
                        FILE *md, ry_plot *plot, int panel, int marker, int analytic,
                        int *failures) {
    ry_error err = {0};
    ry_table s;
    ry_sim sim;
    ry_run_stats stats;
    if (run_at(root, out, sd, "oldroyd_b_startup", 0, across, &s, &sim, &stats, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        ++*failures;
        return;
    }
    const ry_material *m = &sim.mat[0];
    const double g = sim.gravity[0], l0 = CH / across, nus = m->viscosity;
    const double nup = m->rheo.nu_polymer, lam = m->rheo.relaxation;
    const int ct = ry_table_col(&s, "t"), cv = ry_table_col(&s, "max_speed");
    const size_t nr = s.nrows;
    double *t = calloc(nr, sizeof *t), *v = calloc(nr, sizeof *v), *va = calloc(nr, sizeof *va);
    double worst = 0, s2 = 0, peak = 0, peak_ref = 0, tpeak = 0, tpeak_ref = 0;
    for (size_t k = 0; t && v && va && ct >= 0 && cv >= 0 && k < nr; ++k) {
        t[k] = 1e3 * ry_table_at(&s, k, ct);
        v[k] = 1e3 * ry_table_at(&s, k, cv);
        va[k] = 1e3 * ry_oldroyd_b_startup(g, CH, nus, nup, lam, 0.5 * (CH - l0), 1e-3 * t[k], 400);
        worst = fmax(worst, fabs(v[k] - va[k]));
        s2 += (v[k] - va[k]) * (v[k] - va[k]);
        if (v[k] > peak) peak = v[k], tpeak = t[k];
        if (va[k] > peak_ref) peak_ref = va[k], tpeak_ref = t[k];
    }
    const double rms = nr ? sqrt(s2 / nr) : NAN;
    const double pss = stats.wall_s > 0 ? (double)sim.ps.n * stats.steps / stats.wall_s : 0;
    printf("  %-5s Oldroyd-B %3d across: peak %.2f mm/s at %.2f ms (analytic %.2f at %.2f), RMS "
           "%.2f %%, largest %.2f %% of the peak (%ld steps, %.2e particle-steps/s)\n",
           sd->label, across, peak, tpeak, peak_ref, tpeak_ref, 100 * rms / peak_ref,
           100 * worst / peak_ref, stats.steps, pss);
    if (md)
        fprintf(md,
                "| %s | %d | %zu | %.2f at %.2f ms | %.2f at %.2f ms | %.2f %% | %.2f %% | %ld |\n",
                sd->label, across, sim.ps.n, peak, tpeak, peak_ref, tpeak_ref, 100 * rms / peak_ref,
                100 * worst / peak_ref, stats.steps);
    if (plot && t && v && va) {
        char label[64];
        snprintf(label, sizeof label, "%s, %d across", sd->label, across);
        ry_plot_series(plot, panel, label, nr, t, v, ry_plot_style_markers(marker), &err);
        if (analytic)
            ry_plot_series(plot, panel, "analytic", nr, t, va, ry_plot_style_line(), &err);
    }
    char what[160];
    static const char *const keys[2] = {"startup_worst", "startup_peak"};
    double tol[2];
    if (ry_cli_tolerances(root, "rheology", 2, keys, tol, failures) == 0) {
        snprintf(what, sizeof what,
                 "%s Oldroyd-B, %d across: within %g %% of the peak at every output", sd->label,
                 across, 100 * tol[0]);
        ry_cli_check_figure(what, worst / peak_ref, tol[0], worst < tol[0] * peak_ref, failures);
        snprintf(what, sizeof what, "%s Oldroyd-B, %d across: first peak within %g %%", sd->label,
                 across, 100 * tol[1]);
        ry_cli_check_figure(what, fabs(peak / peak_ref - 1), tol[1],
                            fabs(peak / peak_ref - 1) < tol[1], failures);
    }
    free(t);
    free(v);
    free(va);
    ry_sim_free(&sim);
    ry_table_free(&s);
}

int ry_cli_validate_rheology(const char *root, const char *out, int quick, int *failures) {
    ry_error err = {0};
    const int res[2] = {20, 40};
    const int nres = quick ? 1 : 2;
    char mdp[4096], png[4096];
    snprintf(mdp, sizeof mdp, "%s/rheology.md", out);
    snprintf(png, sizeof png, "%s/rheology.png", out);
    ry_atomic_file af = {0};
    FILE *md = ry_atomic_open(&af, mdp, &err) == RY_OK ? af.fp : NULL;
    ry_plot *plot = NULL;
    if (ry_plot_new(&plot, 2, 2, 1400, 1000, &err) != RY_OK) plot = NULL;
    if (plot) {
        ry_plot_panel(plot, 0, "Power law, n = 0.5", "y (mm)", "u (mm/s)", &err);
        ry_plot_panel(plot, 1, "Carreau, n = 0.4", "y (mm)", "u (mm/s)", &err);
        ry_plot_panel(plot, 2, "Giesekus, alpha = 0.3, Wi = 1.9 at the wall", "y (mm)", "u (mm/s)",
                      &err);
        ry_plot_panel(plot, 3, "Oldroyd-B start-up, E = 1, beta = 0.1", "t (ms)",
                      "centreline u (mm/s)", &err);
    }
    enum { NSTEADY = 3 };
    const steady_case sc[NSTEADY] = {{"power law", "power_law_poiseuille", 6.9, 0},
                                     {"Carreau", "carreau_poiseuille", 40.0, 0},
                                     {"Giesekus", "giesekus_poiseuille", 400.0, 0.04}};
    /* The viscosity of WCSPH and IISPH is explicit (dt <= 0.125 and 0.045 h^2 / nu); their
     * steady runs stop at 20 and 15 ms, where the centreline velocity has settled to 0.2 %. */
    const scheme_def sd[3] = {{"MPS", "mps", 0}, {"WCSPH", "sph", 0.02}, {"IISPH", "iisph", 0.015}};
    enum { NSCHEME = 3 };
    printf("Non-Newtonian channel flows, MPS, WCSPH and IISPH (cases/mps_*.yaml, cases/sph_*.yaml, "
           "cases/iisph_*.yaml)\n");
    if (md)
        fprintf(md, "| scheme | model | across | particles | u_c [mm/s] | centreline | RMS | "
                    "largest | steps |\n|---|---|---|---|---|---|---|---|---|\n");
    /* markers: one per scheme and resolution; the analytic curve once per panel */
    const int mk[NSCHEME][2] = {{RY_PLOT_MARKER_CIRCLE, RY_PLOT_MARKER_SQUARE},
                                {RY_PLOT_MARKER_TRIANGLE, RY_PLOT_MARKER_DIAMOND},
                                {RY_PLOT_MARKER_CROSS, RY_PLOT_MARKER_PLUS}};
    for (int c = 0; c < NSTEADY; ++c)
        for (int m = 0; m < NSCHEME; ++m)
            for (int k = 0; k < nres; ++k)
                steady_run(root, out, &sd[m], &sc[c], res[k], md, plot, c, mk[m][k],
                           m == NSCHEME - 1 && k == nres - 1, failures);
    if (md)
        fprintf(md, "\n| scheme | across | particles | peak [mm/s] | analytic [mm/s] | RMS / peak "
                    "| largest / peak | steps |\n|---|---|---|---|---|---|---|---|\n");
    for (int m = 0; m < NSCHEME; ++m)
        for (int k = 0; k < nres; ++k)
            startup_run(root, out, &sd[m], res[k], md, plot, 3, mk[m][k],
                        m == NSCHEME - 1 && k == nres - 1, failures);
    if (md && ry_atomic_commit(&af, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        ++*failures;
    } else if (md) {
        printf("  table: %s\n", mdp);
    }
    if (plot) {
        ry_plot_legend(plot, 0, RY_PLOT_LEGEND_SE, &err);
        ry_plot_legend(plot, 1, RY_PLOT_LEGEND_SE, &err);
        ry_plot_legend(plot, 2, RY_PLOT_LEGEND_SE, &err);
        if (ry_plot_write_png(plot, png, &err) != RY_OK) {
            fprintf(stderr, "ryushi: validate: %s\n", err.msg);
            ++*failures;
        } else {
            printf("  plot: %s\n", png);
        }
        ry_plot_free(plot);
    }
    return *failures;
}
