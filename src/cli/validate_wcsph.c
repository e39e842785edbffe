/* ryushi validate dam_break, cavity, channel: the WCSPH cases against Martin & Moyce, Ghia et
 * al. and the Poiseuille profile. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "ryushi/atomic_file.h"
#include "ryushi/manifest.h"
#include "ryushi/plot.h"
#include "ryushi/run.h"
#include "ryushi/validate.h"

typedef struct vctx {
    const char *root; /* project folder: cases/ and data/reference/ */
    const char *out;  /* output folder */
    int quick;
    int failures;
} vctx;

static void path_join(char *buf, size_t size, const char *a, const char *b) {
    snprintf(buf, size, "%s/%s", a, b);
}

static int report(vctx *v, const ry_error *err) {
    fprintf(stderr, "ryushi: validate: %s\n", err->msg);
    v->failures++;
    return 1;
}

/* A check of a figure at most tol. */
static void at_most(vctx *v, const char *what, double figure, double tol) {
    ry_cli_check_figure(what, figure, tol, figure <= tol, &v->failures);
}

/* Runs a case with overrides into out/sub, reads its series.csv. */
static ry_status run_series(vctx *v, const char *case_file, const char *sub, int nset,
                            const char *const *sets, ry_table *series, size_t *particles,
                            double *wall_s, ry_sim *keep, ry_error *err) {
    ry_sim sim;
    ry_run_stats stats;
    RY_TRY(
        ry_cli_run_series(v->root, v->out, case_file, sub, nset, sets, &sim, &stats, series, err));
    *particles = sim.ps.n;
    *wall_s = stats.wall_s;
    if (keep)
        *keep = sim;
    else
        ry_sim_free(&sim);
    return RY_OK;
}

/* The tolerances of validation/dam_break.yaml (tests/physics/test_wcsph.c reads the same). */
typedef struct dam_tol {
    double mass_drift, escaped, points_min, max_dev, rms_dev, rms_shifted, shift_min, shift_max;
    double arrival_min, arrival_max;
} dam_tol;

static ry_status dam_tolerances(ry_manifest *m, dam_tol *t, ry_error *err) {
    RY_TRY(ry_manifest_tol(m, "mass_drift", &t->mass_drift, err));
    RY_TRY(ry_manifest_tol(m, "escaped", &t->escaped, err));
    RY_TRY(ry_manifest_tol(m, "front_points_min", &t->points_min, err));
    RY_TRY(ry_manifest_tol(m, "front_max_dev", &t->max_dev, err));
    RY_TRY(ry_manifest_tol(m, "front_rms_dev", &t->rms_dev, err));
    RY_TRY(ry_manifest_tol(m, "front_rms_dev_shifted", &t->rms_shifted, err));
    RY_TRY(ry_manifest_tol(m, "front_shift_min", &t->shift_min, err));
    RY_TRY(ry_manifest_tol(m, "front_shift_max", &t->shift_max, err));
    RY_TRY(ry_manifest_tol(m, "wall_arrival_min", &t->arrival_min, err));
    return ry_manifest_tol(m, "wall_arrival_max", &t->arrival_max, err);
}

/* A dam break's mass drift and the fluid particles found outside the tank or in a wall. */
static void conserved(vctx *v, const char *run, const ry_table *s, const dam_tol *tol) {
    char what[128];
    snprintf(what, sizeof what, "%s: fluid mass drift", run);
    at_most(v, what, ry_mass_drift(s), tol->mass_drift);
    snprintf(what, sizeof what, "%s: fluid particles outside the tank or in a wall", run);
    at_most(v, what, fmax(ry_column_max(s, "outside"), ry_column_max(s, "in_wall")), tol->escaped);
}

static int dam_break(vctx *v) {
    ry_error err = {0};
    ry_manifest man;
    if (ry_manifest_load(&man, v->root, "dam_break", &err) != RY_OK) return report(v, &err);
    dam_tol tol;
    char ref_path[4096];
    path_join(ref_path, sizeof ref_path, v->root,
              ry_manifest_text(&man, "reference", "(no reference in the manifest)"));
    ry_status mst = dam_tolerances(&man, &tol, &err);
    ry_manifest_free(&man);
    if (mst != RY_OK) return report(v, &err);
    ry_table ref;
    if (ry_table_read(&ref, ref_path, &err) != RY_OK) return report(v, &err);
    const double a = 0.05715, g = 9.81;
    const int nres = v->quick ? 1 : 3;
    const int per_a[3] = {20, 40, 80};
    ry_plot *p = NULL;
    if (ry_plot_new(&p, 1, 2, 1400, 560, &err) != RY_OK) return report(v, &err);
    ry_plot_panel(p, 0, "Martin & Moyce column (n^2 = 2)", "T = t sqrt(2g/a)", "Z = front / a",
                  &err);
    ry_plot_panel(p, 1, "seed 001 dam break", "t [s]", "front_x [m]", &err);
    printf("Martin & Moyce (1952), n^2 = 2, a = %.5f m: surge front Z(T), T <= 3\n", a);
    printf("  (dT: the shift of the time origin that fits best; deviations after it follow)\n");
    printf("  %-10s %10s %8s %8s %6s %8s %8s %11s %8s %8s %8s\n", "spacing", "particles", "max|dZ|",
           "rms dZ", "dT", "max|dZ|", "rms dZ", "mass drift", "outside", "in_wall", "wall_s");
    for (int r = 0; r < nres; ++r) {
        char sp[64], sub[64], label[64];
        snprintf(sp, sizeof sp, "spacing=%.10g", a / per_a[r]);
        snprintf(sub, sizeof sub, "dam_break_mm_a%d", per_a[r]);
        const char *sets[] = {sp, "time.end=0.18", "time.output_interval=0.001", "output.vtk=false",
                              "measure=[front_x, mass, kinetic_energy, outside, in_wall]"};
        ry_table s;
        size_t np;
        double ws;
        if (run_series(v, "cases/dam_break_mm.yaml", sub, 5, sets, &s, &np, &ws, NULL, &err) !=
            RY_OK) {
            report(v, &err);
            continue;
        }
        ry_front_cmp cmp;
        if (ry_compare_front(&s, &ref, a, g, 3.0, &cmp, &err) != RY_OK) report(v, &err);
        printf("  a/%-8d %10zu %8.3f %8.3f %6.3f %8.3f %8.3f %11.2e %8.0f %8.0f %8.1f\n", per_a[r],
               np, cmp.max_dev, cmp.rms_dev, cmp.shift, cmp.max_dev_shifted, cmp.rms_dev_shifted,
               ry_mass_drift(&s), ry_column_max(&s, "outside"), ry_column_max(&s, "in_wall"), ws);
        snprintf(label, sizeof label, "ryushi a/%d", per_a[r]);
        ry_cli_add_series(p, 0, label, &s, "t", sqrt(2 * g / a), "front_x", 1 / a,
                          ry_plot_style_line(), &err);
        char what[128];
        snprintf(what, sizeof what, "a/%d", per_a[r]);
        conserved(v, what, &s, &tol);
        if (per_a[r] == 20) {
            ry_cli_check_figure("a/20: Martin & Moyce points compared (at least)", cmp.npoints,
                                tol.points_min, cmp.npoints >= tol.points_min, &v->failures);
            at_most(v, "a/20: front, largest |dZ|", cmp.max_dev, tol.max_dev);
            at_most(v, "a/20: front, RMS of dZ", cmp.rms_dev, tol.rms_dev);
            at_most(v, "a/20: front with the time origin fitted, RMS of dZ", cmp.rms_dev_shifted,
                    tol.rms_shifted);
            snprintf(what, sizeof what, "a/20: the fitted shift dT within %g..%g", tol.shift_min,
                     tol.shift_max);
            ry_cli_check_figure(what, cmp.shift, NAN,
                                cmp.shift >= tol.shift_min && cmp.shift <= tol.shift_max,
                                &v->failures);
        }
        ry_table_free(&s);
    }
    ry_cli_add_series(p, 0, "Martin & Moyce (1952)", &ref, "T", 1, "Z", 1,
                      ry_plot_style_markers(RY_PLOT_MARKER_CIRCLE), &err);
    ry_plot_xrange(p, 0, 0, 3.5, &err);
    ry_plot_legend(p, 0, RY_PLOT_LEGEND_NW, &err);

    const double seed_dx[3] = {0.0125, 0.00625, 0.003125};
    const char *seed_name[3] = {"20x40", "40x80", "80x160"};
    printf("seed 001 dam break: time the front reaches the right wall (seed: about 0.32 s)\n");
    printf("  %-10s %10s %12s %12s %8s %8s %8s\n", "columns", "particles", "t_wall [s]",
           "mass drift", "outside", "in_wall", "wall_s");
    for (int r = 0; r < nres; ++r) {
        char sp[64], sub[64];
        snprintf(sp, sizeof sp, "spacing=%.10g", seed_dx[r]);
        snprintf(sub, sizeof sub, "dam_break_seed_%s", seed_name[r]);
        const char *sets[] = {sp, "time.end=0.6", "time.output_interval=0.0025", "output.vtk=false",
                              "measure=[front_x, mass, kinetic_energy, outside, in_wall]"};
        ry_table s;
        size_t np;
        double ws;
        if (run_series(v, "cases/dam_break_seed.yaml", sub, 5, sets, &s, &np, &ws, NULL, &err) !=
            RY_OK) {
            report(v, &err);
            continue;
        }
        double tw = ry_front_arrival(&s, 1.0 - 0.25 * seed_dx[r]);
        printf("  %-10s %10zu %12.4f %12.2e %8.0f %8.0f %8.1f\n", seed_name[r], np, tw,
               ry_mass_drift(&s), ry_column_max(&s, "outside"), ry_column_max(&s, "in_wall"), ws);
        char what[128];
        snprintf(what, sizeof what, "%s: front reaches the wall between %g s and %g s",
                 seed_name[r], tol.arrival_min, tol.arrival_max);
        ry_cli_check_figure(what, tw, NAN, tw >= tol.arrival_min && tw <= tol.arrival_max,
                            &v->failures);
        conserved(v, seed_name[r], &s, &tol);
        ry_cli_add_series(p, 1, seed_name[r], &s, "t", 1, "front_x", 1, ry_plot_style_line(), &err);
        ry_table_free(&s);
    }
    double sx[2] = {0.32, 0.32}, sy[2] = {0.2, 1.05};
    ry_plot_style dash = ry_plot_style_line();
    dash.dash = RY_PLOT_DASH_DASHED;
    ry_plot_series(p, 1, "seed: wall at 0.32 s", 2, sx, sy, dash, &err);
    ry_plot_legend(p, 1, RY_PLOT_LEGEND_SE, &err);
    char png[4096];
    path_join(png, sizeof png, v->out, "dam_break_front.png");
    if (ry_plot_write_png(p, png, &err) != RY_OK)
        report(v, &err);
    else
        printf("  plot: %s\n", png);
    ry_plot_free(p);
    ry_table_free(&ref);
    return 0;
}

static int cavity(vctx *v) {
    ry_error err = {0};
    char pu[4096], pv[4096];
    ry_manifest man;
    if (ry_manifest_load(&man, v->root, "cavity", &err) != RY_OK) return report(v, &err);
    path_join(pu, sizeof pu, v->root, ry_manifest_text(&man, "reference", "-"));
    path_join(pv, sizeof pv, v->root, ry_manifest_text(&man, "reference_v", "-"));
    /* the tolerances of validation/cavity.yaml */
    double tu, tv, escaped, de_max, speed_max;
    ry_status mst =
        ry_manifest_tol(&man, v->quick ? "ghia_rms_u_short" : "ghia_rms_full", &tu, &err);
    if (mst == RY_OK)
        mst = ry_manifest_tol(&man, v->quick ? "ghia_rms_v_short" : "ghia_rms_full", &tv, &err);
    if (mst == RY_OK) mst = ry_manifest_tol(&man, "escaped", &escaped, &err);
    if (mst == RY_OK) mst = ry_manifest_tol(&man, "re1_energy_change", &de_max, &err);
    if (mst == RY_OK) mst = ry_manifest_tol(&man, "re1_max_speed", &speed_max, &err);
    ry_manifest_free(&man);
    if (mst != RY_OK) return report(v, &err);
    ry_table gu, gv;
    if (ry_table_read(&gu, pu, &err) != RY_OK) return report(v, &err);
    if (ry_table_read(&gv, pv, &err) != RY_OK) {
        ry_table_free(&gu);
        return report(v, &err);
    }
    ry_plot *p = NULL;
    if (ry_plot_new(&p, 1, 2, 1400, 600, &err) != RY_OK) return report(v, &err);
    ry_plot_panel(p, 0, "u on the vertical centreline", "u / U", "y / L", &err);
    ry_plot_panel(p, 1, "v on the horizontal centreline", "x / L", "v / U", &err);
    printf("lid-driven cavity, Re = 100, against Ghia, Ghia & Shin (1982)\n");
    printf("  %-10s %10s %10s %10s %8s\n", "grid", "particles", "rms u/U", "rms v/U", "wall_s");
    const int nres = v->quick ? 1 : 2;
    const int N[2] = {50, 100};
    for (int r = 0; r < nres; ++r) {
        char sp[64], sub[64], end[64];
        snprintf(sp, sizeof sp, "spacing=%.10g", 1.0 / N[r]);
        snprintf(sub, sizeof sub, "cavity_re100_%dx%d", N[r], N[r]);
        /* Centrelines averaged over the last 2 L/U (quick) or 3 L/U, sampled every 0.1 L/U. */
        const double t_end = v->quick ? 10.0 : 15.0, t_avg = v->quick ? 8.0 : 12.0;
        char avg0[64], avg1[64];
        snprintf(end, sizeof end, "time.end=%g", t_end);
        snprintf(avg0, sizeof avg0, "profiles[0].average_from=%g", t_avg);
        snprintf(avg1, sizeof avg1, "profiles[1].average_from=%g", t_avg);
        const char *sets[] = {sp, end, "output.vtk=false", "time.output_interval=0.1", avg0, avg1};
        ry_table s;
        size_t np;
        double ws, ru = NAN, rv = NAN;
        ry_sim sim;
        if (run_series(v, "cases/cavity_re100.yaml", sub, 6, sets, &s, &np, &ws, &sim, &err) !=
            RY_OK) {
            report(v, &err);
            continue;
        }
        char odir[4096];
        path_join(odir, sizeof odir, v->out, sub);
        if (ry_cavity_centrelines(&sim, 1.0, 1.0, &gu, &gv, odir, &ru, &rv, &err) != RY_OK)
            report(v, &err);
        ry_sim_free(&sim);
        printf("  %3dx%-6d %10zu %10.4f %10.4f %8.1f\n", N[r], N[r], np, ru, rv, ws);
        char what[128];
        snprintf(what, sizeof what, "%dx%d: RMS of (u - u_Ghia)/U", N[r], N[r]);
        at_most(v, what, ru, tu);
        snprintf(what, sizeof what, "%dx%d: RMS of (v - v_Ghia)/U", N[r], N[r]);
        at_most(v, what, rv, tv);
        snprintf(what, sizeof what, "%dx%d: fluid particles outside or in a wall", N[r], N[r]);
        at_most(v, what, fmax(ry_column_max(&s, "outside"), ry_column_max(&s, "in_wall")), escaped);
        ry_table_free(&s);
        char label[64], path[4200];
        snprintf(label, sizeof label, "ryushi %dx%d", N[r], N[r]);
        ry_table cu, cv;
        /* The whole profiles (101 points; L = 1 m, U = 1 m/s, so metres and m/s are L and U). */
        snprintf(path, sizeof path, "%s/profile_u_vertical_centreline.csv", odir);
        if (ry_table_read(&cu, path, &err) == RY_OK) {
            ry_cli_add_series(p, 0, label, &cu, "u", 1, "y", 1, ry_plot_style_line(), &err);
            ry_table_free(&cu);
        }
        snprintf(path, sizeof path, "%s/profile_v_horizontal_centreline.csv", odir);
        if (ry_table_read(&cv, path, &err) == RY_OK) {
            ry_cli_add_series(p, 1, label, &cv, "x", 1, "v", 1, ry_plot_style_line(), &err);
            ry_table_free(&cv);
        }
    }
    ry_cli_add_series(p, 0, "Ghia et al. (1982)", &gu, "u_over_U", 1, "y_over_L", 1,
                      ry_plot_style_markers(RY_PLOT_MARKER_CIRCLE), &err);
    ry_cli_add_series(p, 1, "Ghia et al. (1982)", &gv, "x_over_L", 1, "v_over_U", 1,
                      ry_plot_style_markers(RY_PLOT_MARKER_CIRCLE), &err);
    ry_plot_legend(p, 0, RY_PLOT_LEGEND_SE, &err);
    ry_plot_legend(p, 1, RY_PLOT_LEGEND_SW, &err);
    char png[4096];
    path_join(png, sizeof png, v->out, "cavity_re100_centrelines.png");
    if (ry_plot_write_png(p, png, &err) != RY_OK)
        report(v, &err);
    else
        printf("  plot: %s\n", png);
    ry_plot_free(p);

    /* The seed's Re = 1 cavity: steady state (mean kinetic energy over the last two fifths
     * of one viscous time, first half against second half). */
    ry_table s;
    size_t np;
    double ws;
    const char *sets[] = {"output.vtk=false", "time.output_interval=0.01"};
    if (run_series(v, "cases/cavity_seed.yaml", "cavity_seed", 2, sets, &s, &np, &ws, NULL, &err) ==
        RY_OK) {
        int ck = ry_table_col(&s, "kinetic_energy");
        size_t n = s.nrows, w = (size_t)(0.2 * (double)n);
        double e0 = 0, e1 = 0;
        for (size_t r = n - 2 * w; r < n - w; ++r) e0 += ry_table_at(&s, r, ck) / (double)w;
        for (size_t r = n - w; r < n; ++r) e1 += ry_table_at(&s, r, ck) / (double)w;
        double change = fabs(e1 - e0) / e1;
        printf("seed cavity, Re = 1, 40x40 (%zu particles, %.1f s): mean kinetic energy %.4g J "
               "then %.4g J, change %.2f%%\n",
               np, ws, e0, e1, 100 * change);
        ry_cli_check_figure("Re = 1 cavity settles: relative change of the mean kinetic energy",
                            change, de_max, change < de_max, &v->failures);
        at_most(v, "Re = 1 cavity: largest fluid speed [m/s]", ry_column_max(&s, "max_speed"),
                speed_max);
        at_most(v, "Re = 1 cavity: fluid particles outside or in a wall",
                fmax(ry_column_max(&s, "outside"), ry_column_max(&s, "in_wall")), escaped);
        ry_table_free(&s);
    } else {
        report(v, &err);
    }
    ry_table_free(&gu);
    ry_table_free(&gv);
    return 0;
}

/* Channel with an inlet and an outlet (Re = 10) against Poiseuille's profile, at 20 and 40
 * particles across. */
static int channel(vctx *v) {
    ry_error err = {0};
    const double U = 0.1, H = 0.1;
    /* the tolerances of validation/channel.yaml */
    static const char *const keys[4] = {"poiseuille_rms", "poiseuille_max", "centreline",
                                        "balance"};
    double tol[4];
    if (ry_cli_tolerances(v->root, "channel", 4, keys, tol, &v->failures)) return 1;
    const double t_rms = tol[0], t_max = tol[1], t_uc = tol[2], t_bal = tol[3];
    ry_plot *p = NULL;
    if (ry_plot_new(&p, 1, 2, 1400, 600, &err) != RY_OK) return report(v, &err);
    ry_plot_panel(p, 0, "u across the channel at x = 0.3 m (mean over t = 3..4 s)", "u / U",
                  "y / H", &err);
    ry_plot_panel(p, 1, "volume through the open boundaries", "t (s)", "volume / (U H t_end)",
                  &err);
    printf("open-boundary channel, Re = 10, inlet U = 0.1 m/s, outlet p = 0, against Poiseuille\n");
    printf("  %-8s %10s %12s %10s %10s %12s %8s\n", "across", "particles", "u_c/(1.5U)-1", "rms",
           "max", "in-out rate", "wall_s");
    const int nres = v->quick ? 1 : 2;
    const int N[2] = {20, 40};
    for (int r = 0; r < nres; ++r) {
        const double dx = H / N[r];
        char sp[64], sub[64], in_lo[96], out_hi[96], b1[96], b2[96];
        snprintf(sp, sizeof sp, "spacing=%.10g", dx);
        snprintf(sub, sizeof sub, "channel_%d", N[r]);
        /* Buffer zones four spacings deep, walls three layers, at every resolution. */
        snprintf(in_lo, sizeof in_lo, "open_boundaries[0].lo=[%.10g,0]", -4 * dx);
        snprintf(out_hi, sizeof out_hi, "open_boundaries[1].hi=[%.10g,0.1]", 0.4 + 4 * dx);
        snprintf(b1, sizeof b1, "bodies[1].lo=[%.10g,%.10g]", -8 * dx, -3 * dx);
        snprintf(b2, sizeof b2, "bodies[2].hi=[%.10g,%.10g]", 0.4 + 8 * dx, 0.1 + 3 * dx);
        char b1h[96], b2l[96];
        snprintf(b1h, sizeof b1h, "bodies[1].hi=[%.10g,0]", 0.4 + 8 * dx);
        snprintf(b2l, sizeof b2l, "bodies[2].lo=[%.10g,0.1]", -8 * dx);
        const char *sets[] = {sp, in_lo, out_hi, b1, b1h, b2, b2l, "output.vtk=false"};
        ry_table s, prof;
        size_t np;
        double ws;
        if (run_series(v, "cases/channel_inflow.yaml", sub, 8, sets, &s, &np, &ws, NULL, &err) !=
            RY_OK) {
            report(v, &err);
            continue;
        }
        char path[4200], odir[4096];
        path_join(odir, sizeof odir, v->out, sub);
        snprintf(path, sizeof path, "%s/profile_u_across.csv", odir);
        if (ry_table_read(&prof, path, &err) != RY_OK) {
            ry_table_free(&s);
            report(v, &err);
            continue;
        }
        int cy = ry_table_col(&prof, "y"), cu = ry_table_col(&prof, "u");
        double se = 0, emax = 0, uc = NAN;
        int n = 0;
        for (size_t q = 0; q < prof.nrows; ++q) {
            double y = ry_table_at(&prof, q, cy), u = ry_table_at(&prof, q, cu);
            if (y <= 0.5 * dx || y >= H - 0.5 * dx) continue;
            double e = (u - 6 * U * y * (H - y) / (H * H)) / (1.5 * U);
            se += e * e;
            emax = fmax(emax, fabs(e));
            if (fabs(y - 0.5 * H) < 1e-9) uc = u;
            ++n;
        }
        const double rms = sqrt(se / n);
        const size_t last = s.nrows - 1;
        size_t r1 = 0;
        const int ct = ry_table_col(&s, "t"), ci = ry_table_col(&s, "inflow_volume"),
                  co = ry_table_col(&s, "outflow_volume");
        while (r1 < last && ry_table_at(&s, r1, ct) < ry_table_at(&s, last, ct) - 1.0) ++r1;
        const double qin = ry_table_at(&s, last, ci) - ry_table_at(&s, r1, ci);
        const double qout = ry_table_at(&s, last, co) - ry_table_at(&s, r1, co);
        const double imb = (qout - qin) / qin;
        printf("  %-8d %10zu %12.4f %10.4f %10.4f %12.4f %8.1f\n", N[r], np, uc / (1.5 * U) - 1,
               rms, emax, imb, ws);
        char what[160];
        snprintf(what, sizeof what, "%d across: profile against Poiseuille, RMS over 1.5 U", N[r]);
        at_most(v, what, rms, t_rms);
        snprintf(what, sizeof what, "%d across: profile, largest deviation over 1.5 U", N[r]);
        at_most(v, what, emax, t_max);
        snprintf(what, sizeof what, "%d across: centreline speed against 1.5 U (relative)", N[r]);
        at_most(v, what, fabs(uc / (1.5 * U) - 1), t_uc);
        snprintf(what, sizeof what, "%d across: outflow against inflow rate (relative)", N[r]);
        at_most(v, what, fabs(imb), t_bal);
        char label[64];
        snprintf(label, sizeof label, "ryushi, %d across", N[r]);
        ry_cli_add_series(p, 0, label, &prof, "u", 1 / U, "y", 1 / H, ry_plot_style_line(), &err);
        snprintf(label, sizeof label, "inflow, %d across", N[r]);
        ry_cli_add_series(p, 1, label, &s, "t", 1, "inflow_volume", 1 / (U * H * 4.0),
                          ry_plot_style_line(), &err);
        snprintf(label, sizeof label, "outflow, %d across", N[r]);
        ry_cli_add_series(p, 1, label, &s, "t", 1, "outflow_volume", 1 / (U * H * 4.0),
                          ry_plot_style_line(), &err);
        ry_table_free(&s);
        ry_table_free(&prof);
    }
    enum { NP = 101 };
    double yy[NP], uu[NP], tt[2] = {0, 4}, vv[2] = {0, 1};
    for (int k = 0; k < NP; ++k) {
        yy[k] = (double)k / (NP - 1);
        uu[k] = 6 * yy[k] * (1 - yy[k]);
    }
    ry_plot_series(p, 0, "Poiseuille", NP, uu, yy, ry_plot_style_markers(RY_PLOT_MARKER_CIRCLE),
                   &err);
    ry_plot_style dashed = ry_plot_style_line();
    dashed.dash = RY_PLOT_DASH_DASHED;
    ry_plot_series(p, 1, "U H t", 2, tt, vv, dashed, &err);
    ry_plot_legend(p, 0, RY_PLOT_LEGEND_SE, &err);
    ry_plot_legend(p, 1, RY_PLOT_LEGEND_NW, &err);
    char png[4096];
    path_join(png, sizeof png, v->out, "channel_open_boundaries.png");
    if (ry_plot_write_png(p, png, &err) != RY_OK)
        report(v, &err);
    else
        printf("  plot: %s\n", png);
    ry_plot_free(p);
    return 0;
}

int ry_cli_validate_dam_break(const char *root, const char *out, int quick, int *failures) {
    vctx v = {root, out, quick, 0};
    const int rc = dam_break(&v);
    *failures += v.failures;
    return rc;
}

int ry_cli_validate_cavity(const char *root, const char *out, int quick, int *failures) {
    vctx v = {root, out, quick, 0};
    const int rc = cavity(&v);
    *failures += v.failures;
    return rc;
}

int ry_cli_validate_channel(const char *root, const char *out, int quick, int *failures) {
    vctx v = {root, out, quick, 0};
    const int rc = channel(&v);
    *failures += v.failures;
    return rc;
}
