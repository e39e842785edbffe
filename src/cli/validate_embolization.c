/* ryushi validate embolization: the 2D embolization tank (cases/mps_embolization_2d_coarse.yaml,
 * seed 003 Table 5 in 2D, l0 = 0.2 mm) run for 8 s (--quick: 4 s) with the interfacial tension
 * by the potential model (the case as it is) and by CSF: the droplet's length, width and aspect
 * ratio over time as the seed's figure 9 plots them, the injected and displaced volumes, and
 * the detachment time against the 2D form of Tate's law (docs/reference/embolization.md, "Inflow
 * and outflow"). Table on stdout and in embolization.md, plots in embolization.png. */
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

/* The case's values (cases/mps_embolization_2d_coarse.yaml). */
#define U_IN 8.5e-3         /* inflow [m/s] */
#define BORE 4.0e-4         /* catheter bore [m] */
#define TANK 4.0e-3         /* tank width [m] */
#define NCOL_MAX 64         /* columns of the tank, one spacing wide */
#define SIGMA_AB 10.8e-3    /* interfacial tension [N/m] */
#define DRHO (1182.0 - 1e3) /* density difference [kg/m^3] */
#define G 9.8

typedef struct model_run {
    const char *label, *sub;
    int nset;
    const char *sets[4];
    ry_table s;
    int ok;
} model_run;

static void plot_figure(model_run *runs, int nruns, const char *png, int *failures) {
    ry_error err = {0};
    ry_plot *p = NULL;
    if (ry_plot_new(&p, 1, 3, 1800, 560, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        ++*failures;
        return;
    }
    ry_plot_panel(p, 0, "Droplet below the tip (2D, l0 = 0.2 mm)", "t (s)", "mm", &err);
    ry_plot_panel(p, 1, "Aspect ratio (length / width)", "t (s)", "", &err);
    ry_plot_panel(p, 2, "Volumes per unit depth", "t (s)", "mm^2", &err);
    int ok = 1;
    for (int k = 0; k < nruns; ++k) {
        if (!runs[k].ok) continue;
        const ry_table *s = &runs[k].s;
        const size_t n = s->nrows;
        double *t = ry_cli_scaled_column(s, "t", 1.0),
               *len = ry_cli_scaled_column(s, "droplet_length", 1e3),
               *wid = ry_cli_scaled_column(s, "droplet_width", 1e3),
               *asp = ry_cli_scaled_column(s, "droplet_aspect", 1.0),
               *vin = ry_cli_scaled_column(s, "inflow_volume", 1e6),
               *vout = ry_cli_scaled_column(s, "outflow_volume", 1e6),
               *ref = malloc(n * sizeof *ref);
        char lab[128];
        if (t && len && wid && asp && vin && vout && ref) {
            for (size_t r = 0; r < n; ++r) ref[r] = 1e6 * U_IN * BORE * t[r];
            snprintf(lab, sizeof lab, "length, %s", runs[k].label);
            ry_plot_series(p, 0, lab, n, t, len, ry_plot_style_line(), &err);
            snprintf(lab, sizeof lab, "width, %s", runs[k].label);
            ry_plot_series(p, 0, lab, n, t, wid, ry_plot_style_line(), &err);
            ry_plot_series(p, 1, runs[k].label, n - 1, t + 1, asp + 1, ry_plot_style_line(), &err);
            if (k == 0) {
                ry_plot_series(p, 2, "injected", n, t, vin, ry_plot_style_line(), &err);
                ry_plot_series(p, 2, "U w t", n, t, ref, ry_plot_style_line(), &err);
            }
            snprintf(lab, sizeof lab, "out, %s", runs[k].label);
            ry_plot_series(p, 2, lab, n, t, vout, ry_plot_style_line(), &err);
        } else {
            ok = 0;
        }
        free(t);
        free(len);
        free(wid);
        free(asp);
        free(vin);
        free(vout);
        free(ref);
    }
    ry_plot_legend(p, 0, RY_PLOT_LEGEND_NW, &err);
    ry_plot_legend(p, 1, RY_PLOT_LEGEND_NW, &err);
    ry_plot_legend(p, 2, RY_PLOT_LEGEND_NW, &err);
    if (!ok || ry_plot_write_png(p, png, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", ok ? err.msg : "series lack a column");
        ++*failures;
    } else {
        printf("  plot: %s\n", png);
    }
    ry_plot_free(p);
}

/* The height of the highest fluid particle in each column of the tank, one spacing wide (the
 * free surface's profile, half a spacing below it); returns the number of columns. */
static int column_tops(const ry_sim *sim, double *top) {
    const int ncol = (int)lround(TANK / sim->dx);
    if (ncol < 1 || ncol > NCOL_MAX) return 0;
    for (int c = 0; c < ncol; ++c) top[c] = NAN;
    for (size_t i = 0; i < sim->ps.n; ++i) {
        if (sim->ps.kind[i] != RY_KIND_FLUID) continue;
        const int c = (int)floor((sim->ps.f[RY_F_X][i] + 0.5 * TANK) / sim->dx);
        const double y = sim->ps.f[RY_F_Y][i];
        if (c >= 0 && c < ncol && !(y <= top[c])) top[c] = y;
    }
    return ncol;
}

/* The rise of the free surface between the case's start and sim (per unit depth [m^2]): the
 * column tops' rise times the column width, summed over the tank. The level is measured, not
 * assumed at the outlets' face: interfacial tension can hold the two sides of the catheter at
 * different levels. */
static ry_status level_rise(const char *cpath, const ry_sim *sim, double *rise, ry_error *err) {
    ry_case *c = NULL;
    ry_sim s0;
    memset(&s0, 0, sizeof s0);
    ry_status st = ry_case_load(&c, cpath, err);
    if (st == RY_OK) st = ry_sim_setup(&s0, c, NULL, err);
    ry_case_free(c);
    double t0[NCOL_MAX], t1[NCOL_MAX];
    const int n0 = st == RY_OK ? column_tops(&s0, t0) : 0, n1 = column_tops(sim, t1);
    ry_sim_free(&s0);
    RY_TRY(st);
    RY_CHECK(err, n0 > 0 && n0 == n1, RY_ERR_INPUT, "the tank's columns differ from the case's");
    *rise = 0;
    for (int k = 0; k < n1; ++k)
        if (isfinite(t0[k]) && isfinite(t1[k])) *rise += (t1[k] - t0[k]) * sim->dx;
    return RY_OK;
}

/* One model: the run, its rows of the table, and its checks. */
static void model_check(const char *root, const char *out, double t_end, model_run *m, FILE *md,
                        int *failures) {
    ry_error err = {0};
    char cpath[4096], odir[4096], spath[4200], end[64];
    snprintf(cpath, sizeof cpath, "%s/cases/mps_embolization_2d_coarse.yaml", root);
    snprintf(odir, sizeof odir, "%s/embolization_2d_%s", out, m->sub);
    snprintf(spath, sizeof spath, "%s/series.csv", odir);
    snprintf(end, sizeof end, "time.end=%g", t_end);
    const char *sets[6] = {end, "output.vtk=false"};
    for (int k = 0; k < m->nset; ++k) sets[2 + k] = m->sets[k];
    printf(" %s\n", m->label);
    ry_sim sim;
    ry_run_stats stats;
    if (ry_run_case_file(cpath, 2 + m->nset, sets, odir, &sim, &stats, &err) != RY_OK ||
        ry_table_read(&m->s, spath, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        ++*failures;
        return;
    }
    m->ok = 1;
    double rise = NAN;
    if (level_rise(cpath, &sim, &rise, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        ++*failures;
    }
    ry_sim_free(&sim);
    const ry_table *s = &m->s;
    const int ct = ry_table_col(s, "t"), ci = ry_table_col(s, "inflow_volume"),
              co = ry_table_col(s, "outflow_volume"), cl = ry_table_col(s, "droplet_length"),
              cw = ry_table_col(s, "droplet_width"), ca = ry_table_col(s, "droplet_aspect"),
              cd = ry_table_col(s, "droplet_detached"), cs = ry_table_col(s, "max_speed");
    const size_t last = s->nrows - 1;
    const double t = ry_table_at(s, last, ct), vin = ry_table_at(s, last, ci),
                 vout = ry_table_at(s, last, co);
    const double a_tate = 2 * SIGMA_AB / (DRHO * G), t_tate = a_tate / (U_IN * BORE);
    double t_det = -1, vmax = 0;
    for (size_t r = 0; r < s->nrows; ++r) {
        if (t_det < 0 && ry_table_at(s, r, cd) > 0.5) t_det = ry_table_at(s, r, ct);
        vmax = fmax(vmax, ry_table_at(s, r, cs));
    }
    if (md)
        fprintf(md,
                "\n%s:\n\n| t [s] | length [mm] | width [mm] | aspect | injected [mm^2] | "
                "out [mm^2] |\n|---|---|---|---|---|---|\n",
                m->label);
    printf("  %6s %12s %11s %7s %16s %11s\n", "t [s]", "length [mm]", "width [mm]", "aspect",
           "injected [mm^2]", "out [mm^2]");
    for (size_t r = 1; r < s->nrows; ++r) {
        const double tr = ry_table_at(s, r, ct);
        if (fabs(tr - round(tr)) > 1e-6) continue;
        const double row[5] = {1e3 * ry_table_at(s, r, cl), 1e3 * ry_table_at(s, r, cw),
                               ry_table_at(s, r, ca), 1e6 * ry_table_at(s, r, ci),
                               1e6 * ry_table_at(s, r, co)};
        printf("  %6.0f %12.2f %11.2f %7.2f %16.2f %11.2f\n", tr, row[0], row[1], row[2], row[3],
               row[4]);
        if (md)
            fprintf(md, "| %.0f | %.2f | %.2f | %.2f | %.2f | %.2f |\n", tr, row[0], row[1], row[2],
                    row[3], row[4]);
    }
    /* What did not leave raised the level. */
    const double balance = (vout + rise) / vin - 1;
    printf("  injected %.4g m^2 against U w t = %.4g (%+.2f %%); out %.4g + level rise %.4g = in "
           "%+.2f %%\n",
           vin, U_IN * BORE * t, 100 * (vin / (U_IN * BORE * t) - 1), vout, rise, 100 * balance);
    printf("  Tate's law (2D): the droplet's weight reaches 2 sigma at %.2f mm^2, after %.2f s; "
           "detached: ",
           1e6 * a_tate, t_tate);
    if (t_det >= 0)
        printf("at %.2f s (%+.1f %%)", t_det, 100 * (t_det / t_tate - 1));
    else
        printf("no");
    printf("; largest speed %.3f m/s\n", vmax);
    if (md) {
        fprintf(md,
                "\nInjected %.4g m^2 (U w t = %.4g, %+.2f %%); outflow plus the level's rise "
                "%+.2f %% of it. Tate's law (2D): %.2f s. Detached: ",
                vin, U_IN * BORE * t, 100 * (vin / (U_IN * BORE * t) - 1), 100 * balance, t_tate);
        if (t_det >= 0)
            fprintf(md, "at %.2f s (%+.1f %%).", t_det, 100 * (t_det / t_tate - 1));
        else
            fprintf(md, "no.");
        fprintf(md, " Largest speed %.3f m/s; %ld steps, %.0f s.\n", vmax, stats.steps,
                stats.wall_s);
    }
    /* the tolerances of validation/embolization.yaml (tests/physics/test_mps.c reads the
     * first and the third) */
    enum { INJECTED, BALANCE, SPEED, TATE, NTOL };
    static const char *const keys[NTOL] = {"injected_volume", "balance", "max_speed",
                                           "detachment_tate"};
    double tol[NTOL];
    if (ry_cli_tolerances(root, "embolization", NTOL, keys, tol, failures)) return;
    char what[128];
    const double e_in = fabs(vin / (U_IN * BORE * t) - 1);
    snprintf(what, sizeof what, "%s: injected volume within %g %% of U w t", m->sub,
             100 * tol[INJECTED]);
    ry_cli_check_figure(what, e_in, tol[INJECTED], e_in < tol[INJECTED], failures);
    snprintf(what, sizeof what, "%s: outflow plus the level's rise within %g %% of the inflow",
             m->sub, 100 * tol[BALANCE]);
    ry_cli_check_figure(what, fabs(balance), tol[BALANCE], fabs(balance) < tol[BALANCE], failures);
    snprintf(what, sizeof what, "%s: largest speed below %g m/s (a stable run)", m->sub,
             tol[SPEED]);
    ry_cli_check_figure(what, vmax, tol[SPEED], vmax < tol[SPEED], failures);
    if (strcmp(m->sub, "csf") == 0 && t_end > 1.2 * t_tate) {
        const double e_det = fabs(t_det / t_tate - 1);
        snprintf(what, sizeof what, "%s: detaches within %g %% of Tate's law (2D)", m->sub,
                 100 * tol[TATE]);
        ry_cli_check_figure(what, t_det > 0 ? e_det : NAN, tol[TATE],
                            t_det > 0 && e_det < tol[TATE], failures);
    }
}

int ry_cli_validate_embolization(const char *root, const char *out, int quick, int *failures) {
    ry_error err = {0};
    const double t_end = quick ? 4.0 : 8.0;
    char mdp[4096], png[4096];
    snprintf(mdp, sizeof mdp, "%s/embolization.md", out);
    snprintf(png, sizeof png, "%s/embolization.png", out);
    printf(
        "Liquid embolization, 2D, l0 = 0.2 mm, to %g s (cases/mps_embolization_2d_coarse.yaml)\n",
        t_end);
    model_run runs[2] = {{"potential model", "potential", 0, {NULL}, {0}, 0},
                         {"CSF (free surface without tension)",
                          "csf",
                          2,
                          {"surface_tension.model=csf", "surface_tension.sigma=0"},
                          {0},
                          0}};
    ry_atomic_file af = {0};
    FILE *md = ry_atomic_open(&af, mdp, &err) == RY_OK ? af.fp : NULL;
    for (int k = 0; k < 2; ++k) model_check(root, out, t_end, &runs[k], md, failures);
    if (md) {
        if (ry_atomic_commit(&af, &err) != RY_OK) {
            fprintf(stderr, "ryushi: validate: %s\n", err.msg);
            ++*failures;
        } else {
            printf("  table: %s\n", mdp);
        }
    }
    plot_figure(runs, 2, png, failures);
    for (int k = 0; k < 2; ++k)
        if (runs[k].ok) ry_table_free(&runs[k].s);
    return *failures;
}
