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
    double res = ry_solid_residual(&sim);
    if (st == RY_OK && !(res < 1e-5))
        st = ry_error_set(err, RY_ERR_UNSTABLE, "%s: not converged (residual %g)", odir, res);
    ry_sim_free(&sim);
    return st;
}

int ry_cli_validate_cantilever(const char *root, const char *out, int quick, int *failures) {
    ry_error err = {0};
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
    /* the target of the issue: 2 % at the finest resolution; --quick checks t/dx = 4 against
     * 3 % (measured: at most 1.8 %) */
    int ok = worst <= (quick ? 3.0 : 2.0);
    printf("  %-60s %s\n",
           quick ? "every error <= 3 % at t/dx = 4" : "every error <= 2 % at t/dx = 8",
           ok ? "PASS" : "FAIL");
    if (!ok) (*failures)++;
    if (nres > 1) {
        printf("  %-60s %s\n", "tip error decreases from t/dx = 4 to 8 (every kernel, load)",
               decreasing ? "PASS" : "FAIL");
        if (!decreasing) (*failures)++;
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
    ok = last <= (quick ? 5.0 : 2.0);
    printf("  %-60s %s\n",
           quick ? "tip within 5 % of L of the elastica at t/dx = 4"
                 : "tip within 2 % of L of the elastica at t/dx = 8",
           ok ? "PASS" : "FAIL");
    if (!ok) (*failures)++;

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
