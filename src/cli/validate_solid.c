/* ryushi validate cantilever: the seed-000 cantilever (EI = 1, L = 1, L/t = 20, plane stress)
 * for three kernels, three resolutions and three loads against Euler-Bernoulli / Timoshenko,
 * and the large-deflection end load against the elastica. Results in docs/validation.md. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "ryushi/plot.h"
#include "ryushi/solid.h"
#include "ryushi/validate.h"
#include "ryushi/run.h"

enum { NK = 3, NL = 3, NR = 3 };
static const char *const kname[NK] = {"lucy", "gaussian", "wendland_c2"};
static const double khdx[NK] = {1.4, 1.0, 1.4}; /* support radius about 3 spacings */
static const char *const lname[NL] = {"end", "linear", "cosine"};
static const ry_beam_load lload[NL] = {RY_BEAM_LOAD_END, RY_BEAM_LOAD_LINEAR, RY_BEAM_LOAD_COSINE};
static const int nthick[NR] = {4, 6, 8}; /* particles across the thickness */

/* The beam of cases/cantilever.yaml. */
static const double beam_t = 0.05, beam_E = 96000.0, beam_nu = 0.3;

/* Runs the cantilever with a kernel, particles across the thickness, load type and intensity;
 * returns the deflections (along the load) at x = L/2 and the tip, and the tip's axial
 * displacement, per unit intensity when per_unit. */
static ry_status run_beam(const char *root, const char *out, int ki, int n, const char *load,
                          double q, double *w_half, double *w_tip, double *u_tip, double *prof_x,
                          double *prof_w, int nprof, ry_error *err) {
    char cpath[4096], odir[4096], sp[64], kt[64], kh[64], lo[96], hi[96], lt[64], li[64];
    const double dx = beam_t / n;

    snprintf(cpath, sizeof cpath, "%s/cases/cantilever.yaml", root);
    snprintf(odir, sizeof odir, "%s/cantilever_%s_%s_t%d_q%g", out, kname[ki], load, n, q);
    snprintf(sp, sizeof sp, "spacing=%.17g", dx);
    snprintf(kt, sizeof kt, "kernel.type=%s", kname[ki]);
    snprintf(kh, sizeof kh, "kernel.h_over_dx=%g", khdx[ki]);
    snprintf(lo, sizeof lo, "bodies[1].lo=[%.17g, %.17g]", -0.5 * dx, -0.5 * beam_t);
    snprintf(hi, sizeof hi, "bodies[1].hi=[%.17g, %.17g]", 0.5 * dx, 0.5 * beam_t);
    snprintf(lt, sizeof lt, "scheme.load.type=%s", load);
    snprintf(li, sizeof li, "scheme.load.intensity=%.17g", q);
    const char *sets[] = {sp, kt, kh, lo, hi, lt, li, "output.vtk=false"};
    ry_sim sim;
    ry_run_stats stats;
    RY_TRY(ry_run_case_file(cpath, 8, sets, odir, &sim, &stats, err));
    ry_beam b;
    double d[3];
    ry_status st = ry_beam_geometry(&sim, &b, err);
    if (st == RY_OK) st = ry_beam_centreline(&sim, 0.5 * b.length, NULL, d, err);
    if (st == RY_OK) *w_half = -d[1] / q;
    if (st == RY_OK) st = ry_beam_centreline(&sim, b.length, NULL, d, err);
    if (st == RY_OK) {
        *w_tip = -d[1] / q;
        *u_tip = d[0];
    }
    for (int k = 0; k < nprof && st == RY_OK; ++k) {
        prof_x[k] = b.length * k / (nprof - 1);
        st = ry_beam_centreline(&sim, prof_x[k], NULL, d, err);
        prof_w[k] = -d[1] / q;
    }
    double res = ry_sim_stat_value(&sim, "residual");
    if (st == RY_OK && !(res < 1e-5))
        st = ry_error_set(err, RY_ERR_UNSTABLE, "%s: not converged (residual %g)", odir, res);
    ry_sim_free(&sim);
    return st;
}

/* Prints a check with PASS or FAIL and counts a failure. */
/* Writes a plot as out/name and frees it. */
static void finish_plot(ry_plot *p, const char *out, const char *name, int *failures) {
    ry_error err = {0};
    char png[4200];
    snprintf(png, sizeof png, "%s/%s", out, name);
    if (ry_plot_write_png(p, png, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        (*failures)++;
    } else {
        printf("  plot: %s\n", png);
    }
    ry_plot_free(p);
}

int ry_cli_validate_cantilever(const char *root, const char *out, int quick, int *failures) {
    ry_error err = {0};
    /* the tolerances of validation/cantilever.yaml (the short version's at 4 across) */
    enum { LINEAR, ELASTICA, BAR3D, NTOL };
    const char *const keys[NTOL] = {quick ? "linear_4" : "linear_8",
                                    quick ? "elastica_4" : "elastica_8", "bar3d"};
    double tol[NTOL];
    if (ry_cli_tolerances(root, "cantilever", NTOL, keys, tol, failures)) return 1;
    const double I = beam_t * beam_t * beam_t / 12, EI = beam_E * I;
    const double kGA = 5.0 / 6.0 * beam_E / (2 * (1 + beam_nu)) * beam_t;
    const int nres = quick ? 1 : NR;
    double errs[NK][NL][NR][2];
    enum { NP = 41 };
    double px[NP], pw[NP], best_x[NP], best_w[NP];
    int have_profile = 0;
    char csv[4200];
    snprintf(csv, sizeof csv, "%s/cantilever_table.csv", out);
    FILE *fc = fopen(csv, "w");
    if (fc) fprintf(fc, "kernel,t_over_dx,load,w_half,w_tip,err_half_pct,err_tip_pct\n");
    printf("cantilever, L = 1, EI = 1, L/t = 20, plane stress, nu = 0.3: small deflection (load "
           "0.01, scaled back to 1)\n");
    printf("  reference: Euler-Bernoulli + Timoshenko shear (kappa = 5/6); error in %% of it\n");
    printf("  %-12s %-7s %-7s %10s %10s %8s %10s %10s %8s\n", "kernel", "t/dx", "load", "w(0.5)",
           "ref", "err %", "w(1)", "ref", "err %");
    for (int l = 0; l < NL; ++l) {
        double rh = ry_beam_deflection_eb(lload[l], 1.0, EI, 0.5) +
                    ry_beam_deflection_shear(lload[l], 1.0, kGA, 0.5);
        double rt = ry_beam_deflection_eb(lload[l], 1.0, EI, 1.0) +
                    ry_beam_deflection_shear(lload[l], 1.0, kGA, 1.0);
        printf("  %-12s %-7s %-7s %10.5f %10s %8s %10.5f\n", "Euler-Bern.", "", lname[l],
               ry_beam_deflection_eb(lload[l], 1.0, EI, 0.5), "", "",
               ry_beam_deflection_eb(lload[l], 1.0, EI, 1.0));
        for (int k = 0; k < NK; ++k)
            for (int r = 0; r < nres; ++r) {
                double wh = NAN, wt = NAN, ut;
                int prof = k == NK - 1 && l == 0 && r == nres - 1;
                if (run_beam(root, out, k, nthick[r], lname[l], 0.01, &wh, &wt, &ut, px, pw,
                             prof ? NP : 0, &err) != RY_OK) {
                    fprintf(stderr, "ryushi: validate: %s\n", err.msg);
                    (*failures)++;
                }
                if (prof) {
                    memcpy(best_x, px, sizeof px);
                    memcpy(best_w, pw, sizeof pw);
                    have_profile = 1;
                }
                errs[k][l][r][0] = 100 * (wh - rh) / rh;
                errs[k][l][r][1] = 100 * (wt - rt) / rt;
                printf("  %-12s %-7d %-7s %10.5f %10.5f %+8.2f %10.5f %10.5f %+8.2f\n", kname[k],
                       nthick[r], lname[l], wh, rh, errs[k][l][r][0], wt, rt, errs[k][l][r][1]);
                fflush(stdout);
                if (fc)
                    fprintf(fc, "%s,%d,%s,%.8g,%.8g,%.4f,%.4f\n", kname[k], nthick[r], lname[l], wh,
                            wt, errs[k][l][r][0], errs[k][l][r][1]);
            }
    }
    if (fc) fclose(fc);
    /* verdicts at the finest resolution */
    double worst = 0;
    int decreasing = 1;
    for (int k = 0; k < NK; ++k)
        for (int l = 0; l < NL; ++l) {
            for (int e = 0; e < 2; ++e) worst = fmax(worst, fabs(errs[k][l][nres - 1][e]));
            if (nres > 1 && fabs(errs[k][l][nres - 1][1]) > fabs(errs[k][l][0][1])) decreasing = 0;
        }
    printf("  largest |error| at t/dx = %d: %.2f %%\n", nthick[nres - 1], worst);
    char what[128];
    snprintf(what, sizeof what, "every error <= %g %% at t/dx = %d", 100 * tol[LINEAR],
             nthick[nres - 1]);
    int ok = worst <= 100 * tol[LINEAR];
    ry_cli_check_figure(what, worst / 100, tol[LINEAR], ok, failures);
    if (nres > 1) {
        ry_cli_check("tip error decreases from t/dx = 4 to 8 (every kernel, load)", decreasing,
                     failures);
    }

    /* large deflection: P L^2 / EI = 1 against the elastica */
    double ex, ey, eth;
    ry_elastica_end_load(1.0, &ex, &ey, &eth);
    printf("large deflection, end load P L^2/EI = 1 (Wendland C2): elastica tip x = %.5f, y = "
           "%.5f\n",
           ex, ey);
    printf("  %-7s %10s %10s %10s\n", "t/dx", "x_tip", "y_tip", "|dx|/L %");
    double last = NAN;
    for (int r = 0; r < nres; ++r) {
        double wh, wt, ut;
        if (run_beam(root, out, NK - 1, nthick[r], "end", 1.0, &wh, &wt, &ut, NULL, NULL, 0,
                     &err) != RY_OK) {
            fprintf(stderr, "ryushi: validate: %s\n", err.msg);
            (*failures)++;
            continue;
        }
        double xt = 1 + ut, e = 100 * hypot(xt - ex, wt - ey);
        printf("  %-7d %10.5f %10.5f %10.2f\n", nthick[r], xt, wt, e);
        last = e;
    }
    snprintf(what, sizeof what, "tip within %g %% of L of the elastica at t/dx = %d",
             100 * tol[ELASTICA], nthick[nres - 1]);
    ok = last <= 100 * tol[ELASTICA];
    ry_cli_check_figure(what, last / 100, tol[ELASTICA], ok, failures);

    /* 3D bar (cases/cantilever_3d.yaml): square section t = 0.1, L/t = 10, EI = 1, end load */
    {
        const double t3 = 0.1, E3 = 120000.0, nu3 = 0.3;
        const double k3 = 10 * (1 + nu3) / (12 + 11 * nu3); /* Cowper, square */
        const double ref3 = ry_beam_deflection_eb(RY_BEAM_LOAD_END, 1.0, 1.0, 1.0) +
                            ry_beam_deflection_shear(RY_BEAM_LOAD_END, 1.0,
                                                     k3 * E3 / (2 * (1 + nu3)) * t3 * t3, 1.0);
        const int n3[2] = {4, 6}, nres3 = quick ? 1 : 2;
        double e3 = NAN;
        printf("3D bar, square section, L/t = 10, EI = 1, end load 0.01 (Wendland C2): "
               "Euler-Bernoulli + Timoshenko shear (kappa = %.4f): w(1) = %.5f\n",
               k3, ref3);
        printf("  %-7s %10s %10s %8s\n", "t/dx", "particles", "w(1)", "err %");
        for (int r = 0; r < nres3; ++r) {
            char cp3[4096], od3[4096], sp3[64], lo3[128], hi3[128];
            const double dx = t3 / n3[r];
            snprintf(cp3, sizeof cp3, "%s/cases/cantilever_3d.yaml", root);
            snprintf(od3, sizeof od3, "%s/cantilever_3d_t%d", out, n3[r]);
            snprintf(sp3, sizeof sp3, "spacing=%.17g", dx);
            snprintf(lo3, sizeof lo3, "bodies[1].lo=[%.17g, -0.05, -0.05]", -0.5 * dx);
            snprintf(hi3, sizeof hi3, "bodies[1].hi=[%.17g, 0.05, 0.05]", 0.5 * dx);
            const char *sets3[] = {sp3, lo3, hi3, "output.vtk=false"};
            ry_sim sim;
            ry_run_stats stats;
            double d[3];
            if (ry_run_case_file(cp3, 4, sets3, od3, &sim, &stats, &err) != RY_OK) {
                fprintf(stderr, "ryushi: validate: %s\n", err.msg);
                (*failures)++;
                continue;
            }
            if (ry_beam_centreline(&sim, 1.0, NULL, d, &err) == RY_OK) {
                const double w = -d[2] / 0.01;
                e3 = 100 * (w - ref3) / ref3;
                printf("  %-7d %10zu %10.5f %+8.2f\n", n3[r], sim.ps.n, w, e3);
            }
            ry_sim_free(&sim);
        }
        snprintf(what, sizeof what, "3D bar: tip within %g %% of Timoshenko", 100 * tol[BAR3D]);
        ry_cli_check_figure(what, fabs(e3) / 100, tol[BAR3D], fabs(e3) <= 100 * tol[BAR3D],
                            failures);
    }

    /* plot: deflection profile, and tip errors against resolution */
    ry_plot *p = NULL;
    if (ry_plot_new(&p, 1, 2, 1400, 600, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        return 1;
    }
    ry_plot_panel(p, 0, "cantilever, end load: deflection", "x / L", "w EI / (P L^3)", &err);
    ry_plot_panel(p, 1, "error of the tip deflection", "particles across the thickness",
                  "error (%)", &err);
    double ex_x[NP], ex_w[NP];
    for (int k = 0; k < NP; ++k) {
        ex_x[k] = (double)k / (NP - 1);
        ex_w[k] = ry_beam_deflection_eb(RY_BEAM_LOAD_END, 1.0, 1.0, ex_x[k]);
    }
    ry_plot_series(p, 0, "Euler-Bernoulli", NP, ex_x, ex_w, ry_plot_style_line(), &err);
    if (have_profile) {
        char lab[64];
        snprintf(lab, sizeof lab, "SPH, Wendland C2, t/dx = %d", nthick[nres - 1]);
        ry_plot_series(p, 0, lab, NP, best_x, best_w, ry_plot_style_markers(RY_PLOT_MARKER_CIRCLE),
                       &err);
    }
    ry_plot_legend(p, 0, RY_PLOT_LEGEND_NW, &err);
    for (int k = 0; k < NK; ++k)
        for (int l = 0; l < NL; ++l) {
            double xs[NR], ys[NR];
            char lab[64];
            for (int r = 0; r < nres; ++r) {
                xs[r] = nthick[r];
                ys[r] = errs[k][l][r][1];
            }
            snprintf(lab, sizeof lab, "%s, %s", kname[k], lname[l]);
            ry_plot_style st = ry_plot_style_line();
            st.marker = (ry_plot_marker)(1 + l);
            st.dash = (ry_plot_dash)k;
            ry_plot_series(p, 1, lab, (size_t)nres, xs, ys, st, &err);
        }
    char png[4200];
    snprintf(png, sizeof png, "%s/cantilever.png", out);
    if (ry_plot_write_png(p, png, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        (*failures)++;
    } else {
        printf("  plot: %s\n  table: %s\n", png, csv);
    }
    ry_plot_free(p);
    return 0;
}

/* ---- oscillating plate ---------------------------------------------------------------------- */

/* The plate of cases/oscillating_plate.yaml. */
static const double plate_L = 0.2, plate_H = 0.02, plate_E = 2.0e6, plate_nu = 0.3975,
                    plate_rho = 1000.0;

/* One plate run: formulation (updated- or total-Lagrangian) and particles across the
 * thickness; returns its oscillation and smallest pair distance, and adds its tip deflection to
 * the plot. */
static ry_status run_plate(const char *root, const char *out, int ul, int n, double t_end,
                           ry_oscillation *osc, double *min_sp, ry_plot *p, ry_error *err) {
    char cpath[4096], odir[4096], spath[4200], sp[64], lo[96], hi[96], te[64];
    const double dx = plate_H / n;
    snprintf(cpath, sizeof cpath, "%s/cases/oscillating_plate.yaml", root);
    snprintf(odir, sizeof odir, "%s/plate_%s_h%d", out, ul ? "ul" : "tl", n);
    snprintf(sp, sizeof sp, "spacing=%.17g", dx);
    snprintf(te, sizeof te, "time.end=%.17g", t_end);
    /* total-Lagrangian (cases/oscillating_plate_tl.yaml): the clamp is one column on the root
     * face */
    snprintf(lo, sizeof lo, "bodies[1].lo=[%.17g, %.17g]", -0.5 * dx, -0.5 * plate_H);
    snprintf(hi, sizeof hi, "bodies[1].hi=[%.17g, %.17g]", 0.5 * dx, 0.5 * plate_H);
    const char *sets[] = {sp, te, "output.vtk=false", lo, hi};
    if (!ul) snprintf(cpath, sizeof cpath, "%s/cases/oscillating_plate_tl.yaml", root);
    ry_sim sim;
    ry_run_stats stats;
    RY_TRY(ry_run_case_file(cpath, ul ? 3 : 5, sets, odir, &sim, &stats, err));
    ry_sim_free(&sim);
    ry_table t;
    snprintf(spath, sizeof spath, "%s/series.csv", odir);
    RY_TRY(ry_table_read(&t, spath, err));
    *osc = ry_series_oscillation(&t, "tip_deflection");
    *min_sp = ry_column_min(&t, "min_spacing");
    int ct = ry_table_col(&t, "t"), cy = ry_table_col(&t, "tip_deflection");
    double *x = ry_table_column(&t, ct), *y = ry_table_column(&t, cy);
    ry_status st = x && y ? RY_OK : ry_error_set(err, RY_ERR_NOMEM, "out of memory");
    char lab[64];
    snprintf(lab, sizeof lab, "%s, H/dx = %d", ul ? "updated-Lagrangian" : "total-Lagrangian", n);
    ry_plot_style style = ry_plot_style_line();
    style.dash = ul ? RY_PLOT_DASH_SOLID : RY_PLOT_DASH_DASHED;
    if (st == RY_OK) st = ry_plot_series(p, 0, lab, t.nrows, x, y, style, err);
    free(x);
    free(y);
    ry_table_free(&t);
    return st;
}

int ry_cli_validate_plate(const char *root, const char *out, int quick, int *failures) {
    ry_error err = {0};
    enum { TL_PERIOD, UL_PERIOD_4, UL_PERIOD_8, UL_MIN_SPACING, ENERGY_GROWTH, NTOL };
    static const char *const keys[NTOL] = {"tl_period", "ul_period_4", "ul_period_8",
                                           "ul_min_spacing", "energy_growth"};
    double tol[NTOL];
    if (ry_cli_tolerances(root, "plate", NTOL, keys, tol, failures)) return 1;
    const double omega = ry_plate_omega(plate_E, plate_nu, plate_rho, plate_H, plate_L);
    const double T = 2 * 3.14159265358979323846 / omega, t_end = 10 * T + 0.02;
    printf("oscillating plate (Gray, Monaghan & Swift 2001): L = %.2f m, H = %.2f m, plane strain, "
           "V = 0.01\n  thin-plate theory: omega = %.4f rad/s, period T = %.5f s; 10 periods\n",
           plate_L, plate_H, omega, T);
    printf("  %-20s %6s %10s %8s %10s %10s %9s\n", "formulation", "H/dx", "period", "err %",
           "E first", "E last", "min r/dx");
    ry_plot *p = NULL;
    if (ry_plot_new(&p, 1, 1, 1400, 600, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        return 1;
    }
    ry_plot_panel(p, 0, "oscillating plate: tip deflection", "t [s]", "tip deflection [m]", &err);
    const int nres = quick ? 1 : 2, nh[2] = {4, 8};
    double err_ul[2] = {NAN, NAN}, err_tl[2] = {NAN, NAN};
    for (int form = 0; form < 2; ++form)
        for (int r = 0; r < nres; ++r) {
            ry_oscillation o;
            double msp = NAN;
            if (run_plate(root, out, form == 0, nh[r], t_end, &o, &msp, p, &err) != RY_OK) {
                fprintf(stderr, "ryushi: validate: %s\n", err.msg);
                (*failures)++;
                continue;
            }
            const double e = 100 * (o.period - T) / T;
            (form == 0 ? err_ul : err_tl)[r] = e;
            printf("  %-20s %6d %10.5f %+8.2f %10.5f %10.5f %9.3f\n",
                   form == 0 ? "updated-Lagrangian" : "total-Lagrangian", nh[r], o.period, e,
                   o.energy_first, o.energy_last, msp);
            fflush(stdout);
            char what[128];
            snprintf(what, sizeof what, "%s, H/dx = %d: energy does not grow over 10 periods",
                     form == 0 ? "UL" : "TL", nh[r]);
            int ok = o.energy_last <= o.energy_first * (1 + tol[ENERGY_GROWTH]);
            ry_cli_check_figure(what, o.energy_last / o.energy_first - 1, tol[ENERGY_GROWTH], ok,
                                failures);
            if (form == 0) {
                snprintf(what, sizeof what, "UL, H/dx = %d: no clumping (min r/dx >= %g)", nh[r],
                         tol[UL_MIN_SPACING]);
                ok = msp >= tol[UL_MIN_SPACING];
                ry_cli_check_figure(what, msp, tol[UL_MIN_SPACING], ok, failures);
            }
        }
    /* verdicts (validation/plate.yaml): the total-Lagrangian form at every resolution; the
     * updated-Lagrangian form converges from above */
    char what[128];
    snprintf(what, sizeof what, "TL: period within %g %% of thin-plate theory",
             100 * tol[TL_PERIOD]);
    ry_cli_check_figure(what, fabs(err_tl[nres - 1]) / 100, tol[TL_PERIOD],
                        fabs(err_tl[nres - 1]) <= 100 * tol[TL_PERIOD], failures);
    snprintf(what, sizeof what, "UL: period within %g %% at H/dx = 4", 100 * tol[UL_PERIOD_4]);
    ry_cli_check_figure(what, fabs(err_ul[0]) / 100, tol[UL_PERIOD_4],
                        fabs(err_ul[0]) <= 100 * tol[UL_PERIOD_4], failures);
    if (nres > 1) {
        snprintf(what, sizeof what, "UL: error falls with resolution, within %g %% at H/dx = 8",
                 100 * tol[UL_PERIOD_8]);
        const int ok =
            fabs(err_ul[1]) < fabs(err_ul[0]) && fabs(err_ul[1]) <= 100 * tol[UL_PERIOD_8];
        ry_cli_check_figure(what, fabs(err_ul[1]) / 100, tol[UL_PERIOD_8], ok, failures);
    }
    ry_plot_legend(p, 0, RY_PLOT_LEGEND_NE, &err);
    finish_plot(p, out, "oscillating_plate.png", failures);
    return 0;
}

/* ---- filament buckling ---------------------------------------------------------------------- */

/* The filament of cases/filament_buckling.yaml: a microtubule, EI = 2.2e-23 N m^2, L = 5 um, a
 * strip of thickness t standing for a t x t bar (loads per metre of depth = force / t). */
static const double fil_EI = 2.2e-23, fil_L = 5e-6, fil_t = 0.25e-6;

static double filament_pcr(void) {
    return 3.14159265358979323846 * 3.14159265358979323846 * fil_EI / (4 * fil_L * fil_L);
}

/* Runs the filament at load ratio P / P_cr with `ecc` the tilt of the load; returns the tip
 * position (x, y) in units of L and, with np > 0, the centreline. */
static ry_status run_filament(const char *root, const char *out, double ratio, int vtk, double *xt,
                              double *yt, int np, double *cx, double *cy, ry_error *err) {
    char cpath[4096], odir[4096], li[96], ov[64];
    snprintf(cpath, sizeof cpath, "%s/cases/filament_buckling.yaml", root);
    snprintf(odir, sizeof odir, "%s/buckling_%.2f", out, ratio);
    snprintf(li, sizeof li, "scheme.load.intensity=%.17g", ratio * filament_pcr() / fil_t);
    snprintf(ov, sizeof ov, "output.vtk=%s", vtk ? "true" : "false");
    const char *sets[] = {li, ov};
    ry_sim sim;
    ry_run_stats stats;
    RY_TRY(ry_run_case_file(cpath, 2, sets, odir, &sim, &stats, err));
    ry_beam b;
    double pos[3];
    ry_status st = ry_beam_geometry(&sim, &b, err);
    if (st == RY_OK) st = ry_beam_centreline(&sim, b.length, pos, NULL, err);
    if (st == RY_OK) {
        *xt = pos[0] / fil_L;
        *yt = -pos[1] / fil_L;
    }
    for (int k = 0; k < np && st == RY_OK; ++k) {
        st = ry_beam_centreline(&sim, b.length * k / (np - 1), pos, NULL, err);
        cx[k] = pos[0] / fil_L;
        cy[k] = -pos[1] / fil_L;
    }
    if (st == RY_OK && !(ry_sim_stat_value(&sim, "residual") < 1e-5))
        st = ry_error_set(err, RY_ERR_UNSTABLE, "%s: not converged (residual %g)", odir,
                          ry_sim_stat_value(&sim, "residual"));
    ry_sim_free(&sim);
    return st;
}

int ry_cli_validate_buckling(const char *root, const char *out, int quick, int *failures) {
    ry_error err = {0};
    static const char *const keys[2] = {"critical_load", "tip_distance_own"};
    double tol[2];
    if (ry_cli_tolerances(root, "buckling", 2, keys, tol, failures)) return 1;
    const double pcr = filament_pcr();
    printf("filament buckling: microtubule EI = %.3g N m^2 (Gittes et al. 1993), L = %.3g m, "
           "clamped-free, L/t = %.0f\n  Euler: P_cr = pi^2 EI / (4 L^2) = %.4g N; load tilted by "
           "1e-3 rad (imperfection)\n",
           fil_EI, fil_L, fil_L / fil_t, pcr);
    ry_plot *p = NULL;
    if (ry_plot_new(&p, 1, 2, 1400, 600, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        return 1;
    }
    ry_plot_panel(p, 0, "Southwell plot (below P_cr)", "tip deflection w / L",
                  "(w / L) / (P / P_cr)", &err);
    ry_plot_panel(p, 1, "post-buckled centrelines", "x / L", "y / L", &err);
    /* below the critical load: Southwell's w / P against w is a line of slope 1 / P_cr */
    const double sub[3] = {0.5, 0.7, 0.85};
    const int nsub = quick ? 2 : 3;
    double sw[3], sq[3], xt, yt;
    int nok = 0;
    printf("  %-10s %12s %12s\n", "P / P_cr", "x_tip / L", "w_tip / L");
    for (int r = 0; r < nsub; ++r) {
        if (run_filament(root, out, sub[r], 0, &xt, &yt, 0, NULL, NULL, &err) != RY_OK) {
            fprintf(stderr, "ryushi: validate: %s\n", err.msg);
            (*failures)++;
            continue;
        }
        printf("  %-10.2f %12.6f %12.4e\n", sub[r], xt, yt);
        sw[nok] = yt;
        sq[nok++] = yt / sub[r];
    }
    double slope = NAN;
    if (nok >= 2) { /* least squares */
        double mx = 0, my = 0, sxx = 0, sxy = 0;
        for (int r = 0; r < nok; ++r) {
            mx += sw[r] / nok;
            my += sq[r] / nok;
        }
        for (int r = 0; r < nok; ++r) {
            sxx += (sw[r] - mx) * (sw[r] - mx);
            sxy += (sw[r] - mx) * (sq[r] - my);
        }
        slope = sxy / sxx;
        ry_plot_series(p, 0, "SPH", (size_t)nok, sw, sq,
                       ry_plot_style_markers(RY_PLOT_MARKER_CIRCLE), &err);
    }
    const double pcr_sw = 1 / slope; /* in units of the Euler load */
    printf("  Southwell: P_cr = %.4f x Euler (%.4g N), error %+.2f %%\n", pcr_sw, pcr_sw * pcr,
           100 * (pcr_sw - 1));
    char what[128];
    snprintf(what, sizeof what, "critical load within %g %% of pi^2 EI / (4 L^2)", 100 * tol[0]);
    int ok = fabs(pcr_sw - 1) <= tol[0];
    ry_cli_check_figure(what, fabs(pcr_sw - 1), tol[0], ok, failures);

    /* above: the post-buckled tip against Euler's elastica */
    const double sup[3] = {1.2, 1.1, 1.5};
    const int nsup = quick ? 1 : 3;
    enum { NP = 41 };
    double cx[NP], cy[NP], worst = 0;
    /* The post-buckled shape is compared with the elastica twice: at the same P / P_cr, and at
     * the same load relative to the column's own critical load (Southwell, above), which
     * separates the shape from the bifurcation load (checked above): near P_cr the elastica's
     * tip moves by 0.015 L per 1 % of load, so a 0.7 % lower P_cr alone moves it by 1-2 % of L. */
    const double own = isfinite(pcr_sw) && pcr_sw > 0 ? pcr_sw : 1.0;
    double worst_own = 0;
    printf("  %-10s %10s %10s %10s %10s %12s %14s\n", "P / P_cr", "x_tip / L", "elastica",
           "y_tip / L", "elastica", "distance / L", "at own P_cr");
    for (int r = 0; r < nsup; ++r) {
        double ex, ey, eth;
        if (run_filament(root, out, sup[r], r == 0, &xt, &yt, NP, cx, cy, &err) != RY_OK) {
            fprintf(stderr, "ryushi: validate: %s\n", err.msg);
            (*failures)++;
            continue;
        }
        ry_elastica_column(sup[r], &ex, &ey, &eth);
        const double d = hypot(xt - ex, fabs(yt) - ey);
        worst = fmax(worst, d);
        double ox, oy, oth;
        ry_elastica_column(sup[r] / own, &ox, &oy, &oth);
        const double d_own = hypot(xt - ox, fabs(yt) - oy);
        worst_own = fmax(worst_own, d_own);
        printf("  %-10.2f %10.5f %10.5f %10.5f %10.5f %12.4f %14.4f\n", sup[r], xt, ex, fabs(yt),
               ey, d, d_own);
        char lab[64];
        snprintf(lab, sizeof lab, "SPH, P = %.1f P_cr", sup[r]);
        ry_plot_series(p, 1, lab, NP, cx, cy, ry_plot_style_line(), &err);
        double mx[1] = {ex}, my[1] = {yt < 0 ? -ey : ey};
        snprintf(lab, sizeof lab, "elastica tip, %.1f P_cr", sup[r]);
        ry_plot_series(p, 1, lab, 1, mx, my, ry_plot_style_markers(RY_PLOT_MARKER_SQUARE), &err);
    }
    printf("  largest distance at the same P / P_cr: %.4f L\n", worst);
    ok = worst_own <= tol[1];
    snprintf(what, sizeof what, "post-buckled tip within %g %% of L of the elastica (own P_cr)",
             100 * tol[1]);
    ry_cli_check_figure(what, worst_own, tol[1], ok, failures);
    printf("  post-buckled shape (VTK): %s/buckling_1.20/\n", out);
    ry_plot_legend(p, 1, RY_PLOT_LEGEND_SW, &err);
    finish_plot(p, out, "filament_buckling.png", failures);
    return 0;
}
