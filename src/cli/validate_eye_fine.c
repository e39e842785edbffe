/* ryushi validate eye_fine: the silicone-oil filling at clinical resolution
 * (cases/eye_posterior_drain_fine.yaml: the posterior drain at 2 ml/s, the oil at 18 degrees on
 * the retina, the half y > 0 of the cavity) at 1.5, 0.75 and 0.375 mm (--quick: 1.5 mm), its
 * coverage over time, and its end state against the Young-Laplace equilibrium of its own fill
 * (src/validate/tamponade.c) over the same walls. The finest run is long (about two hours on 2
 * threads; docs/reference/eye.md): each spacing's run goes on from the newest checkpoint in its
 * folder, so an interrupted validation resumes. */
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "ryushi/atomic_file.h"
#include "ryushi/csv.h"
#include "ryushi/plot.h"
#include "ryushi/probes.h"
#include "ryushi/run.h"
#include "ryushi/ryushi.h" /* ry_sim_probe: the whole problem of a symmetric part */
#include "ryushi/validate.h"
#include "sim/symmetry.h"

#define PI 3.14159265358979323846

/* The equilibrium's share of the wetted wall, over the whole problem's walls (the ports' left
 * out as the probe oil_wall_contact leaves them): the wall above the contact line. */
typedef struct share_call {
    const ry_region *reg;
    double up[3], cos_min, share;
} share_call;

static ry_status share_eval(ry_sim *sim, void *ctx, ry_error *err) {
    share_call *c = ctx;
    const double o[3] = {0, 0, 0};
    return ry_wall_share_above(sim, c->reg, o, c->up, c->cos_min, &c->share, err);
}

int ry_cli_validate_eye_fine(const char *root, const char *out, int quick, int *failures) {
    enum { COUNT, NTOL };
    static const char *const keys[NTOL] = {"fluid_count"};
    double tol[NTOL];
    if (ry_cli_tolerances(root, "eye_fine", NTOL, keys, tol, failures)) return 1;
    const double spacings[3] = {0.0015, 0.00075, 0.000375};
    const int ns = quick ? 1 : 3;
    enum { NT = 6 };
    const double times[NT] = {0.5, 1.0, 1.5, 2.0, 2.5, 3.0};
    char cpath[4096], mdp[4096];
    snprintf(cpath, sizeof cpath, "%s/cases/eye_posterior_drain_fine.yaml", root);
    ry_error err = {0};
    /* the equilibrium's Bond number and contact angle, from the case */
    ry_case *c = NULL;
    double R, rho_s, rho_o, sigma, bond, deg;
    const int ok = ry_case_load(&c, cpath, &err) == RY_OK &&
                   ry_cli_eye_bond(c, &R, &rho_s, &rho_o, &sigma, &bond, &err) == RY_OK &&
                   ry_case_double(c, "scheme.contact_angle", NULL, 0, 180, &deg, &err) == RY_OK;
    ry_case_free(c);
    if (!ok) return ry_cli_fail(failures, &err);
    const double theta = deg * PI / 180.0;
    ry_plot *p = NULL;
    if (ry_plot_new(&p, 1, 2, 1280, 520, &err) != RY_OK) return ry_cli_fail(failures, &err);
    ry_plot_title(p,
                  "Oil filling the eye (supine, 2 ml/s, 18 degrees): markers, the equilibrium "
                  "at the end's fill",
                  &err);
    ry_plot_panel(p, 0, "retina covered (oil_wall_contact)", "t [s]", "share of the retina", &err);
    ry_plot_panel(p, 1, "oil in the cavity (filled_fraction)", "t [s]", "share of the fluid", &err);
    printf("Eye: silicone-oil filling at clinical resolution (cases/eye_posterior_drain_fine.yaml, "
           "the half y > 0), %d thread(s)\n",
           omp_get_max_threads());
    snprintf(mdp, sizeof mdp, "%s/eye_fine.md", out);
    ry_atomic_file af = {0};
    FILE *md = ry_atomic_open(&af, mdp, &err) == RY_OK ? af.fp : NULL;
    if (!md) ry_cli_fail(failures, &err);
    if (md) {
        fprintf(md, "| spacing (fluid particles, whole cavity) | steps, wall time |");
        for (int k = 0; k < NT; ++k) fprintf(md, " %.1f s |", times[k]);
        fprintf(md,
                " end: fill, retina covered | equilibrium at that fill | oil kept |\n|---|---|");
        for (int k = 0; k < NT + 3; ++k) fprintf(md, "---|");
        fprintf(md, "\n");
    }
    int interrupted = 0;
    for (int s = 0; s < ns && !interrupted; ++s) {
        char odir[4096], sp[64];
        snprintf(odir, sizeof odir, "%s/eye_fine_%.3fmm", out, 1e3 * spacings[s]);
        snprintf(sp, sizeof sp, "spacing=%.10g", spacings[s]);
        const char *sets[] = {sp, "output.vtk=false"};
        ry_sim sim;
        ry_run_stats stats;
        const ry_status rs = ry_cli_run_or_resume(cpath, 2, sets, odir, &sim, &stats, &err);
        /* interrupted: reported as far as it went, a failure, and the finer runs not started */
        interrupted = rs == RY_ERR_INTERRUPTED;
        if (interrupted) {
            fprintf(stderr, "ryushi: validate: %s; the same command goes on from there\n", err.msg);
            ++*failures;
        } else if (rs != RY_OK) {
            ry_cli_fail(failures, &err);
            continue;
        }
        /* the end state: the whole cavity's measurements */
        double fill = NAN, covered = NAN, nfluid = NAN, kept = NAN, g = 0, up[3] = {0, 0, 0};
        ry_sim_probe(&sim, "filled_fraction", &fill);
        ry_sim_probe(&sim, "oil_wall_contact", &covered);
        ry_sim_probe(&sim, "fluid_particles", &nfluid);
        ry_sim_probe(&sim, "injected_kept", &kept);
        for (int d = 0; d < 3; ++d) g += sim.gravity[d] * sim.gravity[d];
        g = sqrt(g);
        for (int d = 0; d < 3; ++d) up[d] = g > 0 ? -sim.gravity[d] / g : 0;
        ry_tamponade t;
        if (ry_tamponade_solve(fill, theta, bond, &t, &err) != RY_OK) {
            ry_sim_free(&sim);
            ry_cli_fail(failures, &err);
            continue;
        }
        share_call sc = {NULL, {up[0], up[1], up[2]}, t.z_contact, NAN};
        if (ry_symmetry_measure(&sim, share_eval, &sc, &err) != RY_OK) ry_cli_fail(failures, &err);
        printf("  %.3f mm: %.0f fluid particles in the whole cavity, %ld steps this run, %.0f s; "
               "at t = %.2f s: fill %.3f, retina covered %.3f; the equilibrium of that fill "
               "(Bond %.3f, %.0f degrees) covers %.3f of the same walls (%.3f of the sphere); "
               "oil kept %.3f\n",
               1e3 * sim.dx, nfluid, stats.steps, stats.wall_s, sim.t, fill, covered, bond,
               theta * 180 / PI, sc.share, t.coverage, kept);
        for (int r = 0; r < sim.nregions; ++r) {
            double v = NAN;
            share_call rc = {&sim.regions[r], {up[0], up[1], up[2]}, t.z_contact, NAN};
            ry_sim_probe(&sim, sim.regions[r].probe.name, &v);
            if (ry_symmetry_measure(&sim, share_eval, &rc, &err) != RY_OK)
                ry_cli_fail(failures, &err);
            printf("    %-16s %.3f, equilibrium %.3f\n", sim.regions[r].name, v, rc.share);
        }
        /* the series: coverage and fill over time */
        char spath[4200];
        snprintf(spath, sizeof spath, "%s/series.csv", odir);
        ry_table tab = {0};
        if (ry_table_read(&tab, spath, &err) != RY_OK) {
            ry_sim_free(&sim);
            ry_cli_fail(failures, &err);
            continue;
        }
        const int cn = ry_table_col(&tab, "fluid_particles");
        double drift = cn >= 0 && tab.nrows > 0 ? 0 : NAN;
        for (size_t r = 0; cn >= 0 && r < tab.nrows; ++r)
            drift = fmax(drift, fabs(ry_table_at(&tab, r, cn) / ry_table_at(&tab, 0, cn) - 1));
        double *tc = ry_table_column(&tab, ry_table_col(&tab, "t"));
        double *cc = ry_table_column(&tab, ry_table_col(&tab, "oil_wall_contact"));
        double *fc = ry_table_column(&tab, ry_table_col(&tab, "filled_fraction"));
        char label[64];
        snprintf(label, sizeof label, "%.3f mm", 1e3 * sim.dx);
        if (tc && cc && fc) {
            ry_plot_style line = ry_plot_style_line(),
                          mark = ry_plot_style_markers(RY_PLOT_MARKER_CIRCLE);
            line.color = mark.color = s;
            ry_plot_series(p, 0, label, tab.nrows, tc, cc, line, &err);
            ry_plot_series(p, 1, label, tab.nrows, tc, fc, line, &err);
            const double te = sim.t;
            ry_plot_series(p, 0, NULL, 1, &te, &sc.share, mark, &err);
            printf("    %8s %10s %10s\n", "t [s]", "filled", "covered");
            for (int k = 0; k < NT && times[k] <= sim.t; ++k)
                printf("    %8.2f %10.3f %10.3f\n", times[k],
                       ry_interp_linear(tc, fc, tab.nrows, times[k]),
                       ry_interp_linear(tc, cc, tab.nrows, times[k]));
        }
        if (md) {
            fprintf(md, "| %.3f mm (%.0f) | %ld, %.0f s |", 1e3 * sim.dx, nfluid, stats.steps,
                    stats.wall_s);
            for (int k = 0; k < NT; ++k)
                if (tc && cc && fc && times[k] <= sim.t)
                    fprintf(md, " %.3f, %.3f |", ry_interp_linear(tc, fc, tab.nrows, times[k]),
                            ry_interp_linear(tc, cc, tab.nrows, times[k]));
                else
                    fprintf(md, " |");
            fprintf(md, " %.3f, %.3f | %.3f | %.3f |\n", fill, covered, sc.share, kept);
        }
        free(tc);
        free(cc);
        free(fc);
        ry_table_free(&tab);
        char what[160];
        snprintf(what, sizeof what,
                 "eye filling, %.3f mm: the cavity stays full (fluid particles within %g %%)",
                 1e3 * sim.dx, 100 * tol[COUNT]);
        ry_cli_check_figure(what, drift, tol[COUNT], drift <= tol[COUNT], failures);
        ry_sim_free(&sim);
    }
    ry_plot_legend(p, 0, RY_PLOT_LEGEND_SE, &err);
    ry_cli_write_plot(p, out, "eye_fine.png", failures);
    ry_plot_free(p);
    if (md) {
        fprintf(md, "\nEach time: filled fraction, retina covered (blank: the run had ended, "
                    "the oil at the drainage). The equilibrium: the Young-Laplace interface of "
                    "the run's fill at its end, its share of the same wall particles.\n");
        if (ry_atomic_commit(&af, &err) != RY_OK)
            ry_cli_fail(failures, &err);
        else
            printf("  table: %s\n", mdp);
    }
    return 0;
}
