/* ryushi validate embolization3d: the coarse 3D embolization tank
 * (cases/mps_embolization_3d_coarse.yaml, seed 003 Table 5, l0 = 0.2 mm) run until its droplet
 * detaches (the case's time.stop_when; --quick: 0.5 s). The droplet's length, width and aspect
 * ratio over time as the seed's figure 9 plots them, and the detachment time against the
 * experiment (11.72 s), the seed's simulation (14.0 s) and Tate's law. The run takes hours on
 * two cores: an interrupted one (Ctrl-C writes a checkpoint) goes on from its newest checkpoint
 * when the command is given again. Table on stdout and in embolization3d.md, plots in
 * embolization3d.png.
 *
 * ryushi validate embolization3d_all: the same, then the tank with a visco-elastic embolic
 * liquid (_oldroyd_b.yaml), one of the two pieces the seed names as missing (the other, the
 * tip's wetting, is docs/validation.md's), and the tank 6 x 6 mm wide with the tip 1.6 mm under
 * the water's surface (mps_embolization_3d_wide_deep_coarse.yaml), where neither a wall nor the
 * surface is within the surface-tension model's reach of the droplet. Each run has its table and
 * figure, and the detachment times are compared in embolization3d_all.md and
 * embolization3d_all.png. The fourth tank is the wide one with a tip face that the embolic
 * liquid meets at 180 degrees, against 120 on the rest of the catheter (..._dry_tip.yaml).
 *
 * ryushi validate embolization3d_wide: the two wide tanks alone (the tip's face at 120 and at 180
 * degrees), compared in embolization3d_wide.md and .png. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "ryushi/atomic_file.h"
#include "ryushi/plot.h"
#include "ryushi/surface_tension.h"
#include "ryushi/validate.h"
#include "ryushi/run.h"

/* The case's values (cases/mps_embolization_3d_coarse.yaml) and the seed's; the inflow
 * velocity is read from the case's inlet. */
#define BORE 4.0e-4         /* the square bore's side [m] */
#define SEED_U 8.5e-3       /* the seed's mean inflow velocity [m/s] */
#define OUTER 8.0e-4        /* the square tip's outer side [m] */
#define SEED_BORE 4.0e-4    /* the seed's round catheter: inner diameter [m] */
#define SEED_OUTER 6.0e-4   /*   outer diameter [m] */
#define SIGMA_AB 10.8e-3    /* interfacial tension [N/m] */
#define DRHO (1182.0 - 1e3) /* density difference [kg/m^3] */
#define G 9.8
#define T_EXPERIMENT 11.72 /* the seed's experiment [s] */
#define T_SEED_SIM 14.0    /* the seed's simulation [s] */

/* Slice y = 0 of the tank (|y| < dx/2): walls, water and the embolic liquid as markers, x and z
 * in mm, over the walls' extent (the tanks differ in width). */
static void tip_slice(ry_plot *p, int panel, const ry_sim *sim) {
    ry_error err;
    char title[128];
    snprintf(title, sizeof title, "Slice y = 0, t = %.2f s", sim->t);
    ry_plot_panel(p, panel, title, "x [mm]", "z [mm]", &err);
    const char *const label[3] = {"wall", "water", "embolic liquid"};
    ry_cli_slice_markers(p, panel, sim, 0.5 * sim->dx, label, 1);
    double xmax = 0, zlo = 0, zhi = 0;
    for (size_t i = 0; i < sim->ps.n; ++i)
        if (sim->ps.kind[i] == RY_KIND_WALL) {
            xmax = fmax(xmax, fabs(sim->ps.f[RY_F_X][i]));
            zlo = fmin(zlo, sim->ps.f[RY_F_Z][i]);
            zhi = fmax(zhi, sim->ps.f[RY_F_Z][i]);
        }
    const double pad = 1e3 * sim->dx;
    ry_plot_xrange(p, panel, -1e3 * xmax - pad, 1e3 * xmax + pad, &err);
    ry_plot_yrange(p, panel, 1e3 * zlo - pad, 1e3 * zhi + pad, &err);
    ry_plot_legend(p, panel, RY_PLOT_LEGEND_SW, &err);
}

/* The detachment times as vertical marks in panel 0, from 0 to ymax: ryushi's t_det (if it
 * detached), the experiment's and the seed's simulation's, each where it lies within 1.3 times
 * the last time tmax. */
static void detachment_marks(ry_plot *p, double t_det, double tmax, double ymax) {
    ry_error err = {0};
    const double marks[3] = {t_det, T_EXPERIMENT, T_SEED_SIM};
    const char *names[3] = {"detached (ryushi)", "experiment 11.72 s", "seed's simulation 14.0 s"};
    for (int k = 0; k < 3; ++k) {
        if (!(marks[k] > 0) || marks[k] > 1.3 * tmax) continue;
        const double xs[2] = {marks[k], marks[k]}, ys[2] = {0, ymax};
        ry_plot_style st = ry_plot_style_line();
        st.dash = (ry_plot_dash)(k + 1);
        ry_plot_series(p, 0, names[k], 2, xs, ys, st, &err);
    }
}

static void plot_figure(const ry_table *s, const ry_sim *sim, double t_det, const char *title,
                        const char *png, int *failures) {
    ry_error err = {0};
    ry_plot *p = NULL;
    if (ry_plot_new(&p, 1, 3, 1800, 600, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        ++*failures;
        return;
    }
    ry_plot_panel(p, 0, title, "t (s)", "mm", &err);
    ry_plot_panel(p, 1, "Aspect ratio (length / width)", "t (s)", "", &err);
    const size_t n = s->nrows;
    double *t = ry_cli_scaled_column(s, "t", 1.0),
           *len = ry_cli_scaled_column(s, "droplet_length", 1e3),
           *wid = ry_cli_scaled_column(s, "droplet_width", 1e3),
           *asp = ry_cli_scaled_column(s, "droplet_aspect", 1.0);
    int ok = t && len && wid && asp && n > 1;
    if (ok) {
        ry_plot_series(p, 0, "length", n, t, len, ry_plot_style_line(), &err);
        ry_plot_series(p, 0, "width", n, t, wid, ry_plot_style_line(), &err);
        ry_plot_series(p, 1, "ryushi", n - 1, t + 1, asp + 1, ry_plot_style_line(), &err);
        double ymax = 0;
        for (size_t r = 0; r < n; ++r) ymax = fmax(ymax, fmax(len[r], wid[r]));
        detachment_marks(p, t_det, t[n - 1], ymax);
        ry_plot_legend(p, 0, RY_PLOT_LEGEND_NW, &err);
        ry_plot_legend(p, 1, RY_PLOT_LEGEND_NE, &err);
        tip_slice(p, 2, sim);
    }
    if (!ok || ry_plot_write_png(p, png, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", ok ? err.msg : "series lack a column");
        ++*failures;
    } else {
        printf("  plot: %s\n", png);
    }
    free(t);
    free(len);
    free(wid);
    free(asp);
    ry_plot_free(p);
}

/* One tank of the comparison: its case file (cases/mps_<file>.yaml; the run goes to <file> under
 * the output folder), the suffix of its table and figure, and what it changes. All have the same
 * catheter. */
typedef struct variant {
    const char *file, *stem, *name, *label; /* name: in titles and legends */
} variant;

static const variant variants[] = {
    {"embolization_3d_coarse", "", "seed's tank", "the seed's tank (4 x 4 mm, tip 0.5 mm deep)"},
    {"embolization_3d_coarse_oldroyd_b", "_oldroyd_b", "Oldroyd-B",
     "the seed's tank, the embolic liquid Oldroyd-B (lambda 0.1 s, 10 % solvent)"},
    {"embolization_3d_wide_deep_coarse", "_wide_deep", "wide, deep tip",
     "the tank 6 x 6 mm, the tip 1.6 mm deep"},
    {"embolization_3d_wide_deep_coarse_dry_tip", "_wide_deep_dry_tip",
     "wide, deep, tip face 180 deg",
     "the tank 6 x 6 mm, the tip 1.6 mm deep, its face at 180 degrees to the embolic liquid"},
};
#define FIRST_WIDE 2 /* the wide tanks are the last ones */
#define NVARIANTS (sizeof variants / sizeof variants[0])

/* What a run gives the comparison: its series (owned) and the figures read from it. */
typedef struct result {
    ry_table s;
    double t_det, v_det, t_end, vmax, len_max;
    int ok;
} result;

/* The time of the first row of a series (if there is one) where the droplet has left, or -1. */
static double detached_at(const char *spath) {
    ry_table s = {0};
    ry_error err = {0};
    double t = -1;
    if (ry_table_read(&s, spath, &err) != RY_OK) return -1; /* no series yet: a fresh run */
    const int ct = ry_table_col(&s, "t"), cd = ry_table_col(&s, "droplet_detached");
    for (size_t r = 0; ct >= 0 && cd >= 0 && r < s.nrows && t < 0; ++r)
        if (ry_table_at(&s, r, cd) > 0.5) t = ry_table_at(&s, r, ct);
    ry_table_free(&s);
    return t;
}

/* Runs one tank (resuming), prints its table, writes embolization3d{stem}.md and .png, and, with
 * checks, asserts the injected volume, a stable run and the detachment against the experiment
 * (the case as it is); the other tanks assert the injected volume and a stable run only. */
static void run_variant(const char *root, const char *out, int quick, const variant *v, int checks,
                        int *failures, result *res) {
    ry_error err = {0};
    char cpath[4096], odir[4096], spath[4200], mdp[4096], png[4096], title[256];
    snprintf(cpath, sizeof cpath, "%s/cases/mps_%s.yaml", root, v->file);
    snprintf(odir, sizeof odir, "%s/%s%s", out, v->file, quick ? "_quick" : "");
    snprintf(spath, sizeof spath, "%s/series.csv", odir);
    snprintf(mdp, sizeof mdp, "%s/embolization3d%s.md", out, v->stem);
    snprintf(png, sizeof png, "%s/embolization3d%s.png", out, v->stem);
    snprintf(title, sizeof title, "Droplet below the tip (3D, l0 = 0.2 mm)%s%s",
             *v->stem ? ", " : "", *v->stem ? v->name : "");
    printf("Liquid embolization, 3D, l0 = 0.2 mm (cases/mps_%s.yaml: %s), %s\n", v->file, v->label,
           quick ? "to 0.5 s" : "until the droplet detaches");
    memset(res, 0, sizeof *res);
    res->t_det = -1;
    /* A run that has let go already ends where it did: time.stop_when stopped it at the output
     * where the droplet had left, but a restart would measure the drop then forming at the tip
     * afresh and go on to the case's end. */
    char end_set[64] = "time.end=0.5";
    const double t_left = quick ? -1 : detached_at(spath);
    if (t_left > 0) snprintf(end_set, sizeof end_set, "time.end=%.10g", t_left);
    const char *sets[2] = {"output.vtk=false", end_set};
    ry_sim sim;
    ry_run_stats stats = {0};
    ry_table *s = &res->s;
    /* an interrupted run (Ctrl-C) is reported as far as it went, and counts as a failure */
    const ry_status rs =
        ry_cli_run_or_resume(cpath, quick || t_left > 0 ? 2 : 1, sets, odir, &sim, &stats, &err);
    if (rs == RY_ERR_INTERRUPTED) {
        fprintf(stderr, "ryushi: validate: %s; the same command goes on from there\n", err.msg);
        ++*failures;
    }
    if ((rs != RY_OK && rs != RY_ERR_INTERRUPTED) || ry_table_read(s, spath, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        if (rs == RY_OK || rs == RY_ERR_INTERRUPTED) ry_sim_free(&sim);
        ++*failures;
        return;
    }
    const double wall = stats.wall_s;
    const long steps = stats.steps;
    const size_t np = sim.ps.n;
    const int ct = ry_table_col(s, "t"), ci = ry_table_col(s, "inflow_volume"),
              cl = ry_table_col(s, "droplet_length"), cw = ry_table_col(s, "droplet_width"),
              ca = ry_table_col(s, "droplet_aspect"), cd = ry_table_col(s, "droplet_detached"),
              cs = ry_table_col(s, "max_speed");
    if (ct < 0 || ci < 0 || cl < 0 || cw < 0 || ca < 0 || cd < 0 || cs < 0 || s->nrows < 2) {
        fprintf(stderr, "ryushi: validate: %s lacks a column or rows\n", spath);
        ry_sim_free(&sim);
        ++*failures;
        return;
    }
    const size_t last = s->nrows - 1;
    const double t_end = ry_table_at(s, last, ct), vin = ry_table_at(s, last, ci);
    double u_in = 0;
    for (int b = 0; b < sim.nopen; ++b)
        if (sim.open[b].type == RY_OPEN_INLET) u_in = fabs(sim.open[b].velocity[2]);
    /* the case's flow rate through its square bore, and the seed's through its round one */
    const double q = u_in * BORE * BORE, q_seed = SEED_U * RY_PI * 0.25 * SEED_BORE * SEED_BORE;
    /* droplet_offset, where the case measures it: the droplet's centroid off the axis in the
     * last row before it left */
    const int co = ry_table_col(s, "droplet_offset");
    double t_det = -1, v_det = NAN, vmax = 0, len_max = 0, off = NAN;
    for (size_t r = 0; r < s->nrows; ++r) {
        if (t_det < 0 && ry_table_at(s, r, cd) > 0.5) {
            t_det = ry_table_at(s, r, ct);
            v_det = ry_table_at(s, r, ci);
        }
        if (t_det < 0) {
            len_max = fmax(len_max, ry_table_at(s, r, cl));
            if (co >= 0) off = ry_table_at(s, r, co);
        }
        vmax = fmax(vmax, ry_table_at(s, r, cs));
    }
    /* Tate's law: the droplet's weight in water reaches sigma times the tip's perimeter */
    const double v_tate = SIGMA_AB * 4 * OUTER / (DRHO * G),
                 v_tate_bore = SIGMA_AB * 4 * BORE / (DRHO * G),
                 v_tate_seed = SIGMA_AB * RY_PI * SEED_OUTER / (DRHO * G);
    ry_atomic_file af = {0};
    FILE *md = ry_atomic_open(&af, mdp, &err) == RY_OK ? af.fp : NULL;
    printf("  %6s %12s %11s %7s %16s\n", "t [s]", "length [mm]", "width [mm]", "aspect",
           "injected [mm^3]");
    if (md)
        fprintf(md, "| t [s] | length [mm] | width [mm] | aspect | injected [mm^3] |\n"
                    "|---|---|---|---|---|\n");
    double t_prev = 0;
    for (size_t r = 1; r < s->nrows; ++r) {
        const double tr = ry_table_at(s, r, ct);
        if ((fabs(tr - round(tr)) > 1e-6 && r != last) || tr == t_prev) continue;
        t_prev = tr;
        const double row[4] = {1e3 * ry_table_at(s, r, cl), 1e3 * ry_table_at(s, r, cw),
                               ry_table_at(s, r, ca), 1e9 * ry_table_at(s, r, ci)};
        printf("  %6.2f %12.2f %11.2f %7.2f %16.2f\n", tr, row[0], row[1], row[2], row[3]);
        if (md)
            fprintf(md, "| %.2f | %.2f | %.2f | %.2f | %.2f |\n", tr, row[0], row[1], row[2],
                    row[3]);
    }
    char line[1024];
    snprintf(line, sizeof line,
             "injected %.4g m^3 against U A t = %.4g (%+.2f %%); largest speed %.3f m/s; "
             "longest droplet before detaching %.2f mm",
             vin, q * t_end, 100 * (vin / (q * t_end) - 1), vmax, 1e3 * len_max);
    printf("  %s\n", line);
    if (md) fprintf(md, "\n%s.\n", line);
    if (co >= 0 && isfinite(off)) {
        snprintf(line, sizeof line,
                 "the droplet's centroid %.2f mm off the catheter's axis %s (the tip's outer "
                 "half-width: %.1f mm)",
                 1e3 * off, t_det > 0 ? "just before it left" : "at the end", 0.5e3 * OUTER);
        printf("  %s\n", line);
        if (md) fprintf(md, "\n%s.\n", line);
    }
    if (t_det > 0)
        snprintf(line, sizeof line,
                 "detached at %.2f s: %+.1f %% against the experiment's %.2f s, %+.1f %% against "
                 "the seed's simulation (%.1f s). Injected then: %.4g mm^3 at %.4g mm^3/s, which "
                 "the seed's flow (%.1f mm/s through its round bore of %.1f mm, %.4g mm^3/s) "
                 "delivers in %.2f s. Tate's law: %.4g mm^3 at this square tip's outer edge "
                 "(%.1f mm), reached at %.2f s; %.4g mm^3 at its bore's rim (%.1f mm), at %.2f "
                 "s; %.4g mm^3 at the seed's outer edge (%.1f mm), at %.2f s of the seed's flow",
                 t_det, 100 * (t_det / T_EXPERIMENT - 1), T_EXPERIMENT,
                 100 * (t_det / T_SEED_SIM - 1), T_SEED_SIM, 1e9 * v_det, 1e9 * q, 1e3 * SEED_U,
                 1e3 * SEED_BORE, 1e9 * q_seed, v_det / q_seed, 1e9 * v_tate, 1e3 * OUTER,
                 v_tate / q, 1e9 * v_tate_bore, 1e3 * BORE, v_tate_bore / q, 1e9 * v_tate_seed,
                 1e3 * SEED_OUTER, v_tate_seed / q_seed);
    else
        snprintf(line, sizeof line, "not detached by %.2f s", t_end);
    printf("  %s\n", line);
    if (md) {
        fprintf(md, "\n%s. %ld steps, %zu particles, %.0f s of this run.\n", line, steps, np, wall);
        if (ry_atomic_commit(&af, &err) != RY_OK) {
            fprintf(stderr, "ryushi: validate: %s\n", err.msg);
            ++*failures;
        } else {
            printf("  table: %s\n", mdp);
        }
    }
    /* the tolerances of validation/embolization3d.yaml (every tank's) */
    enum { INJECTED, SPEED, EXPERIMENT, NTOL };
    static const char *const keys[NTOL] = {"injected_volume", "max_speed", "detachment"};
    double tol[NTOL];
    if (ry_cli_tolerances(root, "embolization3d", NTOL, keys, tol, failures) == 0) {
        /* the inlet lets in a layer of the bore's particles at a time: the bound is the larger,
         * recorded relative to U A t */
        const double layer = BORE * BORE * 2e-4, bound = fmax(tol[INJECTED] * q * t_end, layer);
        char what[128];
        snprintf(what, sizeof what,
                 "injected volume within %g %% of U A t (or a layer of the bore)",
                 100 * tol[INJECTED]);
        ry_cli_check_figure(what, fabs(vin - q * t_end) / (q * t_end), bound / (q * t_end),
                            fabs(vin - q * t_end) < bound, failures);
        snprintf(what, sizeof what, "largest speed below %g m/s (a stable run)", tol[SPEED]);
        ry_cli_check_figure(what, vmax, tol[SPEED], vmax < tol[SPEED], failures);
        if (checks && !quick) {
            ry_cli_check_figure("the droplet detaches", t_det > 0 ? t_det : NAN, NAN, t_det > 0,
                                failures);
            const double e_det = fabs(t_det / T_EXPERIMENT - 1);
            snprintf(what, sizeof what, "detaches within %g %% of the experiment (11.72 s)",
                     100 * tol[EXPERIMENT]);
            ry_cli_check_figure(what, t_det > 0 ? e_det : NAN, tol[EXPERIMENT],
                                t_det > 0 && e_det < tol[EXPERIMENT], failures);
        }
    }
    plot_figure(s, &sim, t_det, title, png, failures);
    ry_sim_free(&sim);
    res->t_det = t_det;
    res->v_det = v_det;
    res->t_end = t_end;
    res->vmax = vmax;
    res->len_max = len_max;
    res->ok = 1;
}

int ry_cli_validate_embolization3d(const char *root, const char *out, int quick, int *failures) {
    result r;
    run_variant(root, out, quick, &variants[0], 1, failures, &r);
    ry_table_free(&r.s);
    return *failures;
}

/* The droplets' lengths and widths of the runs in one figure, with the detachment times of the
 * experiment and the seed's simulation. */
static void plot_compare(const result *res, size_t first, size_t n, const char *png,
                         int *failures) {
    ry_error err = {0};
    ry_plot *p = NULL;
    if (ry_plot_new(&p, 1, 2, 1400, 600, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        ++*failures;
        return;
    }
    ry_plot_panel(p, 0, "Droplet length below the tip (3D, l0 = 0.2 mm)", "t (s)", "mm", &err);
    ry_plot_panel(p, 1, "Droplet width", "t (s)", "mm", &err);
    double tmax = 0, ymax = 0;
    int ok = 1;
    for (size_t k = first; k < first + n; ++k) {
        if (!res[k].ok) continue;
        const ry_table *s = &res[k].s;
        double *t = ry_cli_scaled_column(s, "t", 1.0),
               *len = ry_cli_scaled_column(s, "droplet_length", 1e3),
               *wid = ry_cli_scaled_column(s, "droplet_width", 1e3);
        if (t && len && wid && s->nrows > 1) {
            ry_plot_series(p, 0, variants[k].name, s->nrows, t, len, ry_plot_style_line(), &err);
            ry_plot_series(p, 1, variants[k].name, s->nrows, t, wid, ry_plot_style_line(), &err);
            tmax = fmax(tmax, t[s->nrows - 1]);
            for (size_t r = 0; r < s->nrows; ++r) ymax = fmax(ymax, fmax(len[r], wid[r]));
        } else {
            ok = 0;
        }
        free(t);
        free(len);
        free(wid);
    }
    if (ok) detachment_marks(p, -1, tmax, ymax);
    ry_plot_legend(p, 0, RY_PLOT_LEGEND_NW, &err);
    ry_plot_legend(p, 1, RY_PLOT_LEGEND_NW, &err);
    if (!ok || ry_plot_write_png(p, png, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", ok ? err.msg : "series lack a column");
        ++*failures;
    } else {
        printf("  plot: %s\n", png);
    }
    ry_plot_free(p);
}

/* Runs the tanks first .. first + n - 1 and compares their detachment in
 * embolization3d{stem}.md and .png. */
static int compare_variants(const char *root, const char *out, int quick, size_t first, size_t n,
                            const char *stem, const char *heading, int *failures) {
    result res[NVARIANTS];
    memset(res, 0, sizeof res);
    for (size_t k = first; k < first + n; ++k)
        run_variant(root, out, quick, &variants[k], k == 0, failures, &res[k]);
    char mdp[4096], png[4096];
    snprintf(mdp, sizeof mdp, "%s/embolization3d%s.md", out, stem);
    snprintf(png, sizeof png, "%s/embolization3d%s.png", out, stem);
    ry_error err = {0};
    ry_atomic_file af = {0};
    FILE *md = ry_atomic_open(&af, mdp, &err) == RY_OK ? af.fp : NULL;
    printf("Liquid embolization, 3D, l0 = 0.2 mm: %s\n", heading);
    if (md)
        fprintf(md, "| case | detached at [s] | against the experiment (11.72 s) | against the "
                    "seed's simulation (14.0 s) | injected then [mm^3] | longest before [mm] | "
                    "largest speed [m/s] |\n|---|---|---|---|---|---|---|\n");
    for (size_t k = first; k < first + n; ++k) {
        const result *r = &res[k];
        char when[64] = "", a[32] = "", b[32] = "", v[32] = "";
        if (!r->ok) {
            snprintf(when, sizeof when, "no result");
        } else if (r->t_det > 0) {
            snprintf(when, sizeof when, "%.2f", r->t_det);
            snprintf(a, sizeof a, "%+.1f %%", 100 * (r->t_det / T_EXPERIMENT - 1));
            snprintf(b, sizeof b, "%+.1f %%", 100 * (r->t_det / T_SEED_SIM - 1));
            snprintf(v, sizeof v, "%.2f", 1e9 * r->v_det);
        } else {
            snprintf(when, sizeof when, "not by %.2f", r->t_end);
        }
        printf("  %-64s %-14s %9s %9s %8s %6.2f mm %6.3f m/s\n", variants[k].label, when, a, b, v,
               1e3 * r->len_max, r->vmax);
        if (md)
            fprintf(md, "| %s | %s | %s | %s | %s | %.2f | %.3f |\n", variants[k].label, when, a, b,
                    v, 1e3 * r->len_max, r->vmax);
    }
    if (md) {
        if (ry_atomic_commit(&af, &err) != RY_OK) {
            fprintf(stderr, "ryushi: validate: %s\n", err.msg);
            ++*failures;
        } else {
            printf("  table: %s\n", mdp);
        }
    }
    plot_compare(res, first, n, png, failures);
    for (size_t k = first; k < first + n; ++k) ry_table_free(&res[k].s);
    return *failures;
}

int ry_cli_validate_embolization3d_all(const char *root, const char *out, int quick,
                                       int *failures) {
    return compare_variants(root, out, quick, 0, NVARIANTS, "_all",
                            "the detachment in the seed's tank with and without the "
                            "visco-elasticity, and in the wide tank with the deep tip, its face at "
                            "120 and at 180 degrees to the embolic liquid",
                            failures);
}

int ry_cli_validate_embolization3d_wide(const char *root, const char *out, int quick,
                                        int *failures) {
    return compare_variants(
        root, out, quick, FIRST_WIDE, NVARIANTS - FIRST_WIDE, "_wide",
        "the wide tank with the deep tip, its face at 120 and at 180 degrees to the embolic liquid",
        failures);
}
