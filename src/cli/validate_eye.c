/* ryushi validate eye, eye_positions, eye_clinical: silicone oil filling the eye (IISPH with
 * in- and outflow), run in segments with slice pictures. */
#define _POSIX_C_SOURCE 200809L
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

/* A check of a figure against its bound, both recorded. */
static void verdict(int *failures, const char *what, double figure, double bound, int ok) {
    ry_cli_check_figure(what, figure, bound, ok, failures);
}

/* Slice y = 0 of the eye (|y| < dx): walls, saline and oil as markers, x and z in mm. */
static void eye_slice(ry_plot *p, int panel, int legend, const ry_sim *sim, const char *what,
                      double t) {
    ry_error err;
    char title[128];
    snprintf(title, sizeof title, "%s, t = %.2f s", what, t);
    ry_plot_panel(p, panel, title, "x [mm] (patient's left)", "z [mm] (anterior)", &err);
    const char *const label[3] = {"wall", "saline", "silicone oil"};
    ry_cli_slice_markers(p, panel, sim, sim->dx, label, legend);
    ry_plot_xrange(p, panel, -25, 25, &err);
    ry_plot_yrange(p, panel, -25, 20, &err);
    ry_plot_legend(p, panel, legend ? RY_PLOT_LEGEND_SW : RY_PLOT_LEGEND_NONE, &err);
}

/* The oil's share of the injected volume: filled fraction x fluid particles x dx^3 over the
 * inflow volume (NAN before any inflow). */
static double oil_kept(double filled, double fluid_particles, double dx, double inflow) {
    return inflow > 0 ? filled * fluid_particles * pow(dx, 3) / inflow : NAN;
}

/* When the oil first reaches the drainage, read from an eye run's series (columns t, filled
 * fraction, fluid particles, inflow volume): the first row after t_from where the oil kept is
 * below 0.99, INFINITY if none. *inflow takes that row's inflow volume (NAN if none), and
 * *kept_end the last row's oil kept. */
static double oil_reaches(const ry_table *s, int ct, int cf, int cn, int ci, double dx,
                          double t_from, double *inflow, double *kept_end) {
    double reached = INFINITY, kept = NAN;
    *inflow = NAN;
    for (size_t r = 0; r < s->nrows; ++r) {
        kept = oil_kept(ry_table_at(s, r, cf), ry_table_at(s, r, cn), dx, ry_table_at(s, r, ci));
        if (ry_table_at(s, r, ct) > t_from && kept < 0.99 && !isfinite(reached)) {
            reached = ry_table_at(s, r, ct);
            *inflow = ry_table_at(s, r, ci);
        }
    }
    *kept_end = kept;
    return reached;
}

/* The filling at one output: filled fraction, oil-wall contact and the oil's share of the
 * injected volume (filled fraction x fluid particles x dx^3 over inflow_volume). */
typedef struct eye_state {
    double filled, contact, retained;
} eye_state;

/* Runs an eye case with overrides in segments to times[0..nt-1], drawing the slice y = 0 into
 * row `row` of p (panel 0 of the row: the start) and recording the filling at each time into
 * at (when not NULL). */
static ry_status eye_segments(const char *root, const char *out, const char *case_file,
                              const char *sub, const char *what, int nset, const char *const *sets,
                              const double *times, int nt, ry_plot *p, int row, eye_state *at,
                              ry_error *err) {
    char cpath[4096], odir[4096];
    snprintf(cpath, sizeof cpath, "%s/%s", root, case_file);
    snprintf(odir, sizeof odir, "%s/%s", out, sub);
    ry_sim sim;
    ry_status st = ry_setup_case_file(cpath, nset, sets, odir, &sim, err);
    if (st != RY_OK) return st;
    printf("  %s (%s, %zu particles):\n", what, case_file, sim.ps.n);
    printf("  %8s %8s %10s %10s %10s %9s %9s\n", "t [s]", "steps", "filled", "oil-wall", "oil kept",
           "wall [s]", "iters");
    if (p) eye_slice(p, row * (nt + 1), 0, &sim, what, 0.0);
    double wall = 0;
    for (int k = 0; k < nt && st == RY_OK; ++k) {
        sim.t_end = times[k];
        ry_run_stats stats;
        st = ry_run(&sim, NULL, &stats, err);
        if (st != RY_OK) break;
        wall += stats.wall_s;
        double ff = 0, oc = 0, vin = 0, nf = 0, mean = 0;
        for (const ry_probe *const *q = ry_probes(); *q; ++q) {
            if (strcmp((*q)->name, "filled_fraction") == 0) (*q)->eval(&sim, &ff, err);
            if (strcmp((*q)->name, "oil_wall_contact") == 0) (*q)->eval(&sim, &oc, err);
            if (strcmp((*q)->name, "inflow_volume") == 0) (*q)->eval(&sim, &vin, err);
            if (strcmp((*q)->name, "fluid_particles") == 0) (*q)->eval(&sim, &nf, err);
            if (strcmp((*q)->name, "iisph_iterations_mean") == 0) (*q)->eval(&sim, &mean, err);
        }
        const double kept = oil_kept(ff, nf, sim.dx, vin);
        if (at) at[k] = (eye_state){ff, oc, kept};
        printf("  %8.3f %8ld %10.4f %10.4f %10.3f %9.1f %9.2f\n", sim.t, sim.step, ff, oc, kept,
               wall, mean);
        /* The legend on the last panel of the first row, where all three kinds show. */
        if (p) eye_slice(p, row * (nt + 1) + k + 1, row == 0 && k == nt - 1, &sim, what, sim.t);
    }
    ry_sim_free(&sim);
    return st;
}

/* The eye cases (docs/reference/iisph.md, "Eye case"): the ports facing each other
 * (cases/eye_sphere.yaml) and the drainage at the posterior pole (cases/eye_posterior_drain.yaml),
 * run in segments with slice pictures; the posterior-drain case again at a third of its time step
 * (implicit viscosity: about 6e-4 s, set by the speeds; again at 2e-4 s). Checks: with the drainage
 * where the oil arrives last, the cavity keeps the injected oil (within 3 %), and the filling and
 * the contact agree at the two time steps. */
ry_status ry_cli_eye_bond(ry_case *c, double *R, double *rho_s, double *rho_o, double *sigma,
                          double *bond, ry_error *err) {
    RY_TRY(ry_case_double(c, "bodies[0].radius", NULL, 0, INFINITY, R, err));
    RY_TRY(ry_case_double(c, "materials[0].density", NULL, 0, INFINITY, rho_s, err));
    RY_TRY(ry_case_double(c, "materials[1].density", NULL, 0, INFINITY, rho_o, err));
    RY_TRY(ry_case_double(c, "scheme.surface_tension", NULL, 0, INFINITY, sigma, err));
    *bond = (*rho_s - *rho_o) * 9.81 * *R * *R / *sigma; /* head_position's gravity */
    return RY_OK;
}

/* The equilibrium the filling tends to (src/validate/tamponade.c): the oil's axisymmetric
 * Young-Laplace cap in the cavity of cases/eye_sphere.yaml (its radius, the two densities and
 * the oil-saline tension of the case), the contact angle through the saline 18 degrees (Fawcett,
 * Williams & Wong 1994); the retina's covered share at fills 0.5 to 0.95, and that of each of
 * the case's retina regions in each head position at fills 0.8 and 0.9. A table on stdout and
 * in eye_equilibrium.md; no check (the reference of the simulations at rest). *R:
 * the cavity's radius [m]. */
static double eye_equilibrium(const char *root, const char *out, double *R, int *failures) {
    ry_error err = {0};
    char path[4096];
    snprintf(path, sizeof path, "%s/cases/eye_sphere.yaml", root);
    ry_case *c = NULL;
    ry_sim s; /* only its regions, read by ry_regions_setup */
    memset(&s, 0, sizeof s);
    s.dim = 3;
    s.nmat = 2;
    double rho_s, rho_o, sigma, bond;
    const double theta = 18.0 * 3.14159265358979323846 / 180.0;
    if (ry_case_load(&c, path, &err) != RY_OK ||
        ry_cli_eye_bond(c, R, &rho_s, &rho_o, &sigma, &bond, &err) != RY_OK ||
        ry_regions_setup(&s, c, &err) != RY_OK) {
        ry_case_free(c);
        ry_regions_free(&s);
        ry_cli_fail(failures, &err);
        return NAN;
    }
    ry_case_free(c);
    char mdp[4096];
    snprintf(mdp, sizeof mdp, "%s/eye_equilibrium.md", out);
    FILE *md = fopen(mdp, "w");
    printf("Eye at equilibrium (Young-Laplace, cases/eye_sphere.yaml): R = %g mm, densities %g "
           "and %g kg/m^3, tension %g N/m, Bond number %.3f, contact angle 18 degrees\n",
           1e3 * *R, rho_s, rho_o, sigma, bond);
    printf("  %-6s %10s %12s %12s %12s\n", "fill", "coverage", "flat limit", "apex [mm]",
           "contact [mm]");
    if (md)
        fprintf(md, "| fill | retina covered | flat interface | interface on the axis [mm] | "
                    "contact line [mm] |\n|---|---|---|---|---|\n");
    const double fills[] = {0.5, 0.6, 0.7, 0.8, 0.9, 0.95};
    for (size_t k = 0; k < sizeof fills / sizeof fills[0]; ++k) {
        ry_tamponade t;
        if (ry_tamponade_solve(fills[k], theta, bond, &t, &err) != RY_OK) {
            ry_cli_fail(failures, &err);
            continue;
        }
        /* the flat interface of the same fill: x^2 (3 - 2x) = fill, coverage x */
        double lo = 0, hi = 1;
        for (int i = 0; i < 60; ++i) {
            const double x = 0.5 * (lo + hi);
            if (x * x * (3 - 2 * x) < fills[k])
                lo = x;
            else
                hi = x;
        }
        printf("  %-6.2f %9.1f%% %11.1f%% %12.2f %12.2f\n", fills[k], 100 * t.coverage, 100 * lo,
               1e3 * *R * t.z_apex, 1e3 * *R * t.z_contact);
        if (md)
            fprintf(md, "| %.2f | %.1f %% | %.1f %% | %+.2f | %+.2f |\n", fills[k],
                    100 * t.coverage, 100 * lo, 1e3 * *R * t.z_apex, 1e3 * *R * t.z_contact);
    }
    if (md) {
        fprintf(md, "\n| fill | position |");
        for (int r = 0; r < s.nregions; ++r) fprintf(md, " %s |", s.regions[r].name);
        fprintf(md, "\n|---|---|");
        for (int r = 0; r < s.nregions; ++r) fprintf(md, "---|");
        fprintf(md, "\n");
    }
    printf("  retina regions covered (%%), by head position:\n  %-6s %-11s", "fill", "position");
    for (int r = 0; r < s.nregions; ++r) printf(" %14s", s.regions[r].name);
    printf("\n");
    const double table_fills[2] = {0.8, 0.9};
    for (int f = 0; f < 2; ++f) {
        ry_tamponade t;
        if (ry_tamponade_solve(table_fills[f], theta, bond, &t, &err) != RY_OK) {
            ry_cli_fail(failures, &err);
            continue;
        }
        double down[3];
        for (int p = 0; ry_head_position(p, down); ++p) {
            const double up[3] = {-down[0], -down[1], -down[2]};
            printf("  %-6.2f %-11s", table_fills[f], ry_head_position(p, down));
            if (md) fprintf(md, "| %.2f | %s |", table_fills[f], ry_head_position(p, down));
            for (int r = 0; r < s.nregions; ++r) {
                const ry_region *reg = &s.regions[r];
                const double cov =
                    ry_tamponade_region_coverage(&t, up, reg->dir, acos(reg->cos_half));
                printf(" %13.0f%%", 100 * cov);
                if (md) fprintf(md, " %.0f %% |", 100 * cov);
            }
            printf("\n");
            if (md) fprintf(md, "\n");
        }
    }
    if (md) fclose(md);
    ry_regions_free(&s);
    return bond;
}

/* Panel `panel` of the oil at rest: the particles of the layer next to the plane z = 0 on its
 * side z > 0 with x >= 0 (a quarter's own, mirrored to x < 0) as markers, and the equilibrium's
 * interface t (R the cavity's radius) as a line, in mm. */
static void rest_panel(ry_plot *p, int panel, const ry_sim *sim, const ry_tamponade *t, double bond,
                       double R, const char *title) {
    ry_error err;
    ry_plot_panel(p, panel, title, "x [mm]", "y [mm] (up)", &err);
    const char *const label[3] = {"wall", "saline", "silicone oil"};
    const ry_cli_slice sl = {2, 0.0, sim->dx, 0, 1, 1, 4};
    ry_cli_slice_markers_in(p, panel, sim, &sl, label, 1);
    enum { NP = 400 };
    double r[NP], z[NP], xs[2 * NP], ys[2 * NP];
    const size_t n = ry_tamponade_profile(t, bond, NP, r, z);
    for (size_t i = 0; i < n; ++i) { /* from one contact point through the apex to the other */
        xs[i] = -1e3 * R * r[n - 1 - i];
        ys[i] = 1e3 * R * z[n - 1 - i];
        xs[n + i] = 1e3 * R * r[i];
        ys[n + i] = 1e3 * R * z[i];
    }
    ry_plot_style line = ry_plot_style_line();
    line.color = 3;
    if (n) ry_plot_series(p, panel, "Young-Laplace, 18 degrees", 2 * n, xs, ys, line, &err);
    ry_plot_xrange(p, panel, -15, 15, &err);
    ry_plot_yrange(p, panel, -15, 15, &err);
    ry_plot_legend(p, panel, panel == 0 ? RY_PLOT_LEGEND_SW : RY_PLOT_LEGEND_NONE, &err);
}

/* The oil and saline at rest (cases/eye_rest.yaml: upright, the quarter of the cavity at the
 * case's spacing, 1 s; the full version the fills of 0.6, 0.8 and 0.9, the short one 0.8): the
 * retina covered at the end against the Young-Laplace equilibrium of the run's own fill (its
 * lattice's filled fraction) at the contact angle of 18 degrees, each region's, and the
 * interface's height on the axis (bond and R: the equilibrium's Bond number and radius,
 * eye_equilibrium's).
 * Checks: the coverage within tol[0] (absolute), the height within tol[1] spacings. */
static void eye_rest(const char *root, const char *out, int quick, double bond, double R,
                     const double *tol, int *failures) {
    ry_error err = {0};
    const double offsets[3] = {-0.005109, -0.00161, -0.007301}, nominal[3] = {0.8, 0.6, 0.9};
    const double theta = 18.0 * 3.14159265358979323846 / 180.0, up[3] = {0, 1, 0};
    printf("Eye at rest (cases/eye_rest.yaml, upright, from a flat interface) against the "
           "equilibrium at 18 degrees:\n");
    const int nfill = quick ? 1 : 3;
    ry_plot *p = NULL;
    if (ry_plot_new(&p, 1, nfill, 640 * nfill, 600, &err) != RY_OK) {
        ry_cli_fail(failures, &err);
        return;
    }
    ry_plot_title(p, "The oil at rest against Young-Laplace", &err);
    for (int k = 0; k < nfill; ++k) {
        char cpath[4096], odir[4096], off[64], sub[64];
        snprintf(cpath, sizeof cpath, "%s/cases/eye_rest.yaml", root);
        snprintf(sub, sizeof sub, "eye_rest_%.1f", nominal[k]);
        snprintf(odir, sizeof odir, "%s/%s", out, sub);
        snprintf(off, sizeof off, "bodies[0].half_space.offset=%.10g", offsets[k]);
        const char *sets[] = {off, "output.vtk=false"};
        ry_sim sim;
        ry_run_stats stats;
        if (ry_run_case_file(cpath, 2, sets, odir, &sim, &stats, &err) != RY_OK) {
            ry_cli_fail(failures, &err);
            continue;
        }
        /* the whole cavity's measurements (a symmetric part's copies are not the whole) */
        double fill = NAN, covered = NAN, height = NAN;
        ry_sim_probe(&sim, "filled_fraction", &fill);
        ry_sim_probe(&sim, "oil_wall_contact", &covered);
        ry_sim_probe(&sim, "interface_height", &height);
        ry_tamponade t;
        if (ry_tamponade_solve(fill, theta, bond, &t, &err) != RY_OK) {
            ry_sim_free(&sim);
            ry_cli_fail(failures, &err);
            continue;
        }
        printf("  fill %.3f (nominal %.1f), %.2f mm, %zu particles with the copies, %ld steps, "
               "%.0f s: retina covered %.3f, reference %.3f; interface on the axis %+.2f mm, "
               "reference %+.2f mm\n",
               fill, nominal[k], 1e3 * sim.dx, sim.ps.n, stats.steps, stats.wall_s, covered,
               t.coverage, 1e3 * height, 1e3 * R * t.z_apex);
        for (int r = 0; r < sim.nregions; ++r) {
            double v = NAN;
            ry_sim_probe(&sim, sim.regions[r].probe.name, &v);
            printf("    %-16s %.3f, reference %.3f\n", sim.regions[r].name, v,
                   ry_tamponade_region_coverage(&t, up, sim.regions[r].dir,
                                                acos(sim.regions[r].cos_half)));
        }
        char what[160];
        snprintf(what, sizeof what, "fill %.3f, %.2f mm, t = %.1f s", fill, 1e3 * sim.dx, sim.t);
        rest_panel(p, k, &sim, &t, bond, R, what);
        snprintf(what, sizeof what,
                 "eye at rest, fill %.1f, %.2f mm: retina covered within %g of the equilibrium",
                 nominal[k], 1e3 * sim.dx, tol[0]);
        ry_cli_check_figure(what, fabs(covered - t.coverage), tol[0],
                            fabs(covered - t.coverage) <= tol[0], failures);
        const double dh = fabs(height - R * t.z_apex) / sim.dx;
        snprintf(what, sizeof what,
                 "eye at rest, fill %.1f, %.2f mm: interface on the axis within %g spacing(s)",
                 nominal[k], 1e3 * sim.dx, tol[1]);
        ry_cli_check_figure(what, dh, tol[1], dh <= tol[1], failures);
        ry_sim_free(&sim);
    }
    char png[4096];
    snprintf(png, sizeof png, "%s/eye_rest.png", out);
    if (ry_plot_write_png(p, png, &err) != RY_OK) ry_cli_fail(failures, &err);
    ry_plot_free(p);
}

int ry_cli_validate_eye(const char *root, const char *out, int quick, int *failures) {
    /* the tolerances of validation/eye.yaml */
    enum { KEPT, FILLED, CONTACT, REST, HEIGHT, NTOL };
    static const char *const keys[NTOL] = {"oil_kept", "filled_fraction_dt", "contact_dt",
                                           "coverage_at_rest", "interface_height_spacings"};
    double tol[NTOL];
    if (ry_cli_tolerances(root, "eye", NTOL, keys, tol, failures)) return 1;
    double R = NAN;
    const double bond = eye_equilibrium(root, out, &R, failures);
    if (isfinite(bond)) eye_rest(root, out, quick, bond, R, tol + REST, failures);
    ry_error err = {0};
    const double tq[2] = {0.05, 0.1}, tf[3] = {0.3, 0.6, 1.0};
    const double *times = quick ? tq : tf;
    enum { NT_MAX = 3 };
    const int nt = quick ? 2 : 3;
    ry_plot *p = NULL;
    if (ry_plot_new(&p, 2, nt + 1, 400 * (nt + 1), 2 * 380, &err) != RY_OK)
        return ry_cli_fail(failures, &err);
    ry_plot_title(p, "Silicone-oil filling, 24 mm cavity, supine: slice y = 0", &err);
    printf("Eye: silicone-oil filling, 1.5 mm, %d thread(s)\n", omp_get_max_threads());
    const char *vtk[] = {"output.vtk=false"};
    const char *small[] = {"output.vtk=false", "time.dt_max=2.0e-4"};
    eye_state post[NT_MAX], fine[NT_MAX];
    if (eye_segments(root, out, "cases/eye_sphere.yaml", "eye_sphere", "ports facing", 1, vtk,
                     times, nt, p, 0, NULL, &err) != RY_OK ||
        eye_segments(root, out, "cases/eye_posterior_drain.yaml", "eye_posterior_drain",
                     "posterior drain", 1, vtk, times, nt, p, 1, post, &err) != RY_OK) {
        ry_plot_free(p);
        return ry_cli_fail(failures, &err);
    }
    ry_cli_write_plot(p, out, "eye_slices.png", failures);
    ry_plot_free(p);
    if (eye_segments(root, out, "cases/eye_posterior_drain.yaml", "eye_posterior_drain_dt2e-4",
                     "posterior drain, dt <= 2e-4 s", 2, small, times, nt, NULL, 0, fine,
                     &err) != RY_OK)
        return ry_cli_fail(failures, &err);
    double dff = 0, doc = 0, dkept = 0;
    for (int k = 0; k < nt; ++k) {
        dff = fmax(dff, fabs(post[k].filled - fine[k].filled));
        doc = fmax(doc, fabs(post[k].contact - fine[k].contact));
        const double dk = fmax(fabs(post[k].retained - 1), fabs(fine[k].retained - 1));
        dkept =
            isfinite(post[k].retained) && isfinite(fine[k].retained) ? fmax(dkept, dk) : INFINITY;
    }
    printf("  posterior drain: largest |oil kept - 1| %.3f; its own step against 2e-4 s: filled "
           "fraction within %.4f, contact within %.4f\n",
           dkept, dff, doc);
    char what[128];
    snprintf(what, sizeof what,
             "eye, posterior drain: the cavity keeps the injected oil within %g %%",
             100 * tol[KEPT]);
    verdict(failures, what, dkept, tol[KEPT], dkept <= tol[KEPT]);
    snprintf(what, sizeof what,
             "eye, posterior drain: filled fraction, own step vs 2e-4 s, within %g", tol[FILLED]);
    verdict(failures, what, dff, tol[FILLED], dff <= tol[FILLED]);
    snprintf(what, sizeof what,
             "eye, posterior drain: oil-wall contact, own step vs 2e-4 s, within %g", tol[CONTACT]);
    verdict(failures, what, doc, tol[CONTACT], doc <= tol[CONTACT]);
    return 0;
}

/* One head position for the posterior drain: its name, the outlet's pressure (the saline's
 * hydrostatic head from the top of the cavity to the middle of the outflow zone, z = -19.5 mm;
 * none where the outflow zone lies above the cavity) and where the drainage lies. */
typedef struct eye_position {
    const char *name;
    double outlet_pa;
    const char *drainage;
} eye_position;

/* The posterior drain (cases/eye_posterior_drain.yaml) in the five head positions, one cavity
 * volume each (--quick: 1.0 s). For each: when the oil first reaches the drainage (the oil inside
 * falls below 99 % of the oil injected), the filled fraction, the contact and the oil kept.
 * Table on stdout and in eye_positions.md. Checks: the lighter oil reaches the drainage last
 * where it is the lowest point (supine: keeps 99 % until the cavity is three quarters full)
 * and first where it is the highest (face-down: by 1.0 s, the cavity a quarter full). */
int ry_cli_validate_eye_positions(const char *root, const char *out, int quick, int *failures) {
    static const eye_position pos[] = {
        {"supine", 309.0, "lowest point"},
        {"upright", 118.0, "horizontal meridian"},
        {"left_side", 118.0, "horizontal meridian, infusion port below"},
        {"right_side", 118.0, "horizontal meridian, infusion port on top"},
        {"prone", 0.0, "highest point"},
    };
    const int npos = (int)(sizeof pos / sizeof pos[0]);
    /* the bounds of validation/eye_positions.yaml [s] */
    static const char *const keys[2] = {"supine_kept_until", "prone_reached_by"};
    double tol[2];
    if (ry_cli_tolerances(root, "eye_positions", 2, keys, tol, failures)) return 1;
    const double t_end = quick ? 1.0 : 3.6, times[3] = {1.0, 2.0, 3.6};
    ry_error err = {0};
    char cpath[4096], mdp[4096];
    snprintf(cpath, sizeof cpath, "%s/cases/eye_posterior_drain.yaml", root);
    snprintf(mdp, sizeof mdp, "%s/eye_positions.md", out);
    ry_atomic_file af = {0};
    FILE *md = ry_atomic_open(&af, mdp, &err) == RY_OK ? af.fp : NULL;
    if (!md) ry_cli_fail(failures, &err);
    printf("Eye: the posterior drain in five head positions, 1.5 mm, to %.1f s, %d thread(s)\n",
           t_end, omp_get_max_threads());
    printf("  %-11s %-42s %9s %23s %23s %6s %7s %7s\n", "position", "drainage", "reached",
           "filled 1 / 2 / 3.6 s", "contact 1 / 2 / 3.6 s", "kept", "steps", "wall");
    if (md)
        fprintf(md, "| head position | drainage | oil first leaves [s] | filled_fraction at 1.0 / "
                    "2.0 / 3.6 s | oil_wall_contact at 1.0 / 2.0 / 3.6 s | oil kept at the end | "
                    "steps | wall [s] |\n|---|---|---|---|---|---|---|---|\n");
    double reached[sizeof pos / sizeof pos[0]];
    for (int k = 0; k < npos; ++k) {
        char end[64], head[64], pa[64], odir[4096], spath[4200];
        snprintf(end, sizeof end, "time.end=%g", t_end);
        snprintf(head, sizeof head, "head_position=%s", pos[k].name);
        snprintf(pa, sizeof pa, "open_boundaries[1].pressure=%g", pos[k].outlet_pa);
        snprintf(odir, sizeof odir, "%s/eye_position_%s%s", out, pos[k].name,
                 quick ? "_quick" : "");
        snprintf(spath, sizeof spath, "%s/series.csv", odir);
        const char *sets[4] = {"output.vtk=false", end, head, pa};
        ry_sim sim;
        ry_run_stats stats = {0};
        ry_table s = {0};
        reached[k] = NAN;
        if (ry_run_case_file(cpath, 4, sets, odir, &sim, &stats, &err) != RY_OK) {
            ry_cli_fail(failures, &err);
            continue;
        }
        const double dx = sim.dx;
        ry_sim_free(&sim);
        if (ry_table_read(&s, spath, &err) != RY_OK) {
            ry_cli_fail(failures, &err);
            continue;
        }
        const int ct = ry_table_col(&s, "t"), cf = ry_table_col(&s, "filled_fraction"),
                  cc = ry_table_col(&s, "oil_wall_contact"), ci = ry_table_col(&s, "inflow_volume"),
                  cn = ry_table_col(&s, "fluid_particles");
        if (ct < 0 || cf < 0 || cc < 0 || ci < 0 || cn < 0) {
            fprintf(stderr, "ryushi: validate: %s lacks a column\n", spath);
            ++*failures;
            ry_table_free(&s);
            continue;
        }
        double kept, vin;
        reached[k] = oil_reaches(&s, ct, cf, cn, ci, dx, 0.2, &vin, &kept);
        char when[32], ff[64], oc[64];
        if (isfinite(reached[k]))
            snprintf(when, sizeof when, "%.2f", reached[k]);
        else
            snprintf(when, sizeof when, "not by %.1f", t_end);
        double f[3], c[3];
        double *tcol = ry_table_column(&s, ct), *fcol = ry_table_column(&s, cf),
               *ocol = ry_table_column(&s, cc);
        for (int j = 0; j < 3; ++j) {
            f[j] = tcol && fcol ? ry_interp_linear(tcol, fcol, s.nrows, times[j]) : NAN;
            c[j] = tcol && ocol ? ry_interp_linear(tcol, ocol, s.nrows, times[j]) : NAN;
        }
        free(tcol);
        free(fcol);
        free(ocol);
        snprintf(ff, sizeof ff, "%.3f / %.3f / %.3f", f[0], f[1], f[2]);
        snprintf(oc, sizeof oc, "%.3f / %.3f / %.3f", c[0], c[1], c[2]);
        printf("  %-11s %-42s %9s %23s %23s %6.3f %7ld %7.0f\n", pos[k].name, pos[k].drainage, when,
               ff, oc, kept, stats.steps, stats.wall_s);
        if (md)
            fprintf(md, "| %s | %s | %s | %s | %s | %.3f | %ld | %.0f |\n", pos[k].name,
                    pos[k].drainage, when, ff, oc, kept, stats.steps, stats.wall_s);
        ry_table_free(&s);
    }
    if (md) {
        if (ry_atomic_commit(&af, &err) != RY_OK)
            ry_cli_fail(failures, &err);
        else
            printf("  table: %s\n", mdp);
    }
    char what[128];
    /* the oil reaches 0.75 of the cavity in 2.7 s at this rate (1 cavity volume in 3.6 s) */
    if (!quick) {
        snprintf(what, sizeof what,
                 "eye positions: supine, the oil kept until %g s (drainage lowest)", tol[0]);
        verdict(failures, what, reached[0], tol[0], !(reached[0] <= tol[0]));
    }
    snprintf(what, sizeof what,
             "eye positions: face-down, the oil at the drainage by %.1f s (highest)", tol[1]);
    verdict(failures, what, reached[4], tol[1], reached[4] <= tol[1]);
    return 0;
}

/* The posterior drain at a clinical rate (cases/eye_posterior_drain_clinical.yaml: 0.1 ml/s in,
 * a rate outlet taking 0.1 ml/s out) beside the same cavity at 2 ml/s with its pressure outlet
 * (cases/eye_posterior_drain.yaml), compared at the same injected volumes: 1.2, 2.4, ... 7.2 ml
 * (--quick: 0.3 and 0.6 ml). Slices of both in eye_clinical.png; the table on stdout and in
 * eye_clinical.md, with when the oil first reaches the drainage at the clinical rate (the oil
 * inside below 99 % of the oil injected, from series.csv). Checks, at the clinical rate: the
 * cavity stays full (the fluid particles within 1.5 % of their number at the start, at every
 * output), and the oil reaches the drainage no sooner than at 2 ml/s (3.05 s there: 6.1 ml). */
int ry_cli_validate_eye_clinical(const char *root, const char *out, int quick, int *failures) {
    /* the bounds of validation/eye_clinical.yaml */
    static const char *const keys[2] = {"fluid_count", "reached_fast_ml"};
    double tol[2];
    if (ry_cli_tolerances(root, "eye_clinical", 2, keys, tol, failures)) return 1;
    enum { NT_MAX = 6 };
    const int nt = quick ? 2 : NT_MAX;
    double tc[NT_MAX], tf[NT_MAX];
    for (int k = 0; k < nt; ++k) {
        tc[k] = (quick ? 3.0 : 12.0) * (k + 1); /* 0.1 ml/s */
        tf[k] = tc[k] / 20;                     /* 2 ml/s */
    }
    ry_error err = {0};
    ry_plot *p = NULL;
    if (ry_plot_new(&p, 2, nt + 1, 330 * (nt + 1), 2 * 330, &err) != RY_OK)
        return ry_cli_fail(failures, &err);
    ry_plot_title(p,
                  "Silicone-oil filling, supine, posterior drain: 0.1 ml/s (top) and 2 ml/s "
                  "(bottom) at the same injected volumes, slice y = 0",
                  &err);
    printf("Eye: silicone-oil filling at 0.1 ml/s beside 2 ml/s, 1.5 mm, %d thread(s)\n",
           omp_get_max_threads());
    const char *vtk[] = {"output.vtk=false"};
    eye_state clin[NT_MAX], fast[NT_MAX];
    if (eye_segments(root, out, "cases/eye_posterior_drain_clinical.yaml", "eye_clinical",
                     "0.1 ml/s", 1, vtk, tc, nt, p, 0, clin, &err) != RY_OK ||
        eye_segments(root, out, "cases/eye_posterior_drain.yaml", "eye_clinical_fast", "2 ml/s", 1,
                     vtk, tf, nt, p, 1, fast, &err) != RY_OK) {
        ry_plot_free(p);
        return ry_cli_fail(failures, &err);
    }
    ry_cli_write_plot(p, out, "eye_clinical.png", failures);
    char spath[4096], mdp[4096];
    ry_plot_free(p);
    /* the clinical run's series: the cavity's fluid and when the oil first leaves */
    snprintf(spath, sizeof spath, "%s/eye_clinical/series.csv", out);
    ry_table s = {0};
    if (ry_table_read(&s, spath, &err) != RY_OK) return ry_cli_fail(failures, &err);
    const int ct = ry_table_col(&s, "t"), cf = ry_table_col(&s, "filled_fraction"),
              ci = ry_table_col(&s, "inflow_volume"), cn = ry_table_col(&s, "fluid_particles");
    if (ct < 0 || cf < 0 || ci < 0 || cn < 0 || s.nrows < 2) {
        fprintf(stderr, "ryushi: validate: %s lacks a column or rows\n", spath);
        ++*failures;
        ry_table_free(&s);
        return 0;
    }
    const double n0 = ry_table_at(&s, 0, cn), dx = 0.0015; /* the case's spacing */
    double drift = 0, at_ml, kept_end;
    for (size_t r = 0; r < s.nrows; ++r) drift = fmax(drift, fabs(ry_table_at(&s, r, cn) / n0 - 1));
    const double reached = oil_reaches(&s, ct, cf, cn, ci, dx, 4.0, &at_ml, &kept_end);
    at_ml *= 1e6;
    ry_table_free(&s);
    snprintf(mdp, sizeof mdp, "%s/eye_clinical.md", out);
    ry_atomic_file af = {0};
    FILE *md = ry_atomic_open(&af, mdp, &err) == RY_OK ? af.fp : NULL;
    if (!md) ry_cli_fail(failures, &err);
    printf("  %10s %21s %21s %21s\n", "oil [ml]", "filled 0.1 / 2 ml/s", "contact 0.1 / 2 ml/s",
           "kept 0.1 / 2 ml/s");
    if (md)
        fprintf(md, "| oil injected [ml] | t at 0.1 ml/s [s] | filled_fraction, 0.1 / 2 ml/s | "
                    "oil_wall_contact, 0.1 / 2 ml/s | oil kept, 0.1 / 2 ml/s |\n"
                    "|---|---|---|---|---|\n");
    for (int k = 0; k < nt; ++k) {
        printf("  %10.2f %10.3f %10.3f %10.3f %10.3f %10.3f %10.3f\n", 0.1 * tc[k], clin[k].filled,
               fast[k].filled, clin[k].contact, fast[k].contact, clin[k].retained,
               fast[k].retained);
        if (md)
            fprintf(md, "| %.2f | %.0f | %.3f / %.3f | %.3f / %.3f | %.3f / %.3f |\n", 0.1 * tc[k],
                    tc[k], clin[k].filled, fast[k].filled, clin[k].contact, fast[k].contact,
                    clin[k].retained, fast[k].retained);
    }
    char when[128];
    if (isfinite(reached))
        snprintf(when, sizeof when, "at %.0f s (%.2f ml injected)", reached, at_ml);
    else
        snprintf(when, sizeof when, "not by %.0f s", tc[nt - 1]);
    printf("  at 0.1 ml/s: fluid particles within %.2f %% of the start; the oil first reaches the "
           "drainage %s\n",
           100 * drift, when);
    if (md) {
        fprintf(md,
                "\nAt 0.1 ml/s the fluid particles stay within %.2f %% of their number at the "
                "start; the oil first reaches the drainage %s.\n",
                100 * drift, when);
        if (ry_atomic_commit(&af, &err) != RY_OK)
            ry_cli_fail(failures, &err);
        else
            printf("  table: %s\n", mdp);
    }
    /* the outflow zone starts empty: 16 particles (0.7 %) of saline fall into it at first */
    char what[128];
    snprintf(what, sizeof what,
             "eye, 0.1 ml/s: the cavity stays full (fluid particles within %g %%)", 100 * tol[0]);
    verdict(failures, what, drift, tol[0], drift <= tol[0]);
    if (!quick) /* 2 ml/s: the oil reaches the drainage at 3.05 s, 6.1 ml */
        verdict(failures, "eye, 0.1 ml/s: the oil reaches the drainage no sooner than at 2 ml/s",
                at_ml, tol[1], !(at_ml < tol[1]));
    return 0;
}
