/* Validation helpers: measured series and states compared with references. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/atomic_file.h"
#include "linalg/small.h"
#include "ryushi/validate.h"
#include "ryushi/probes.h"

ry_status ry_compare_front(const ry_table *series, const ry_table *ref, double a, double g,
                           double T_max, ry_front_cmp *out, ry_error *err) {
    int ct = ry_table_col(series, "t"), cf = ry_table_col(series, "front_x");
    int cT = ry_table_col(ref, "T"), cZ = ry_table_col(ref, "Z");
    RY_CHECK(err, ct >= 0 && cf >= 0, RY_ERR_INPUT, "series has no columns t and front_x");
    RY_CHECK(err, cT >= 0 && cZ >= 0, RY_ERR_INPUT, "reference has no columns T and Z");
    size_t n = series->nrows;
    double *T = malloc((n ? n : 1) * sizeof *T), *Z = malloc((n ? n : 1) * sizeof *Z);
    if (!T || !Z) {
        free(T);
        free(Z);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
    }
    double s = sqrt(2.0 * g / a);
    for (size_t r = 0; r < n; ++r) {
        T[r] = ry_table_at(series, r, ct) * s;
        Z[r] = ry_table_at(series, r, cf) / a;
    }
    memset(out, 0, sizeof *out);
    out->rms_dev_shifted = INFINITY;
    for (int k = 0; k <= 80; ++k) {
        const double shift = 0.005 * k;
        double sum2 = 0, maxd = 0;
        int np = 0;
        for (size_t r = 0; r < ref->nrows; ++r) {
            double Tr = ry_table_at(ref, r, cT);
            if (Tr > T_max) continue;
            /* Before the shifted start the column has not moved: Z = 1. */
            double Zs = Tr - shift < T[0] ? 1.0 : ry_interp_linear(T, Z, n, Tr - shift);
            if (!isfinite(Zs)) continue;
            double d = Zs - ry_table_at(ref, r, cZ);
            maxd = fmax(maxd, fabs(d));
            sum2 += d * d;
            ++np;
        }
        double rms = np ? sqrt(sum2 / np) : NAN;
        if (k == 0) {
            out->npoints = np;
            out->max_dev = maxd;
            out->rms_dev = rms;
        }
        if (rms < out->rms_dev_shifted) {
            out->rms_dev_shifted = rms;
            out->max_dev_shifted = maxd;
            out->shift = shift;
        }
    }
    free(T);
    free(Z);
    RY_CHECK(err, out->npoints > 0, RY_ERR_INPUT, "no reference point within the simulated time");
    return RY_OK;
}

double ry_front_arrival(const ry_table *series, double x_wall) {
    int ct = ry_table_col(series, "t"), cf = ry_table_col(series, "front_x");
    if (ct < 0 || cf < 0) return NAN;
    for (size_t r = 1; r < series->nrows; ++r) {
        double f0 = ry_table_at(series, r - 1, cf), f1 = ry_table_at(series, r, cf);
        if (f1 >= x_wall && f0 < x_wall) {
            double t0 = ry_table_at(series, r - 1, ct), t1 = ry_table_at(series, r, ct);
            return t0 + (x_wall - f0) / (f1 - f0) * (t1 - t0);
        }
    }
    return NAN;
}

double ry_mass_drift(const ry_table *series) {
    int cm = ry_table_col(series, "mass");
    if (cm < 0 || series->nrows == 0) return NAN;
    double m0 = ry_table_at(series, 0, cm), d = 0;
    for (size_t r = 0; r < series->nrows; ++r)
        d = fmax(d, fabs(ry_table_at(series, r, cm) - m0) / m0);
    return d;
}

double ry_column_max(const ry_table *series, const char *name) {
    int c = ry_table_col(series, name);
    double m = 0;
    if (c < 0) return 0;
    for (size_t r = 0; r < series->nrows; ++r) m = fmax(m, ry_table_at(series, r, c));
    return m;
}

double ry_column_min(const ry_table *series, const char *name) {
    int c = ry_table_col(series, name);
    double m = INFINITY;
    if (c < 0) return NAN;
    for (size_t r = 0; r < series->nrows; ++r) {
        const double v = ry_table_at(series, r, c);
        if (v == v) m = fmin(m, v);
    }
    return m;
}

ry_oscillation ry_series_oscillation(const ry_table *series, const char *name) {
    ry_oscillation o = {NAN, 0, NAN, NAN, NAN};
    const int ct = ry_table_col(series, "t"), cy = ry_table_col(series, name);
    const int ck = ry_table_col(series, "solid_kinetic_energy");
    const int cs = ry_table_col(series, "strain_energy");
    if (ct < 0 || cy < 0) return o;
    double first = NAN, last = NAN;
    for (size_t r = 1; r < series->nrows; ++r) {
        const double y0 = ry_table_at(series, r - 1, cy), y1 = ry_table_at(series, r, cy);
        if (!((y0 < 0 && y1 >= 0) || (y0 >= 0 && y1 < 0)) || r == 1) continue;
        const double t0 = ry_table_at(series, r - 1, ct), t1 = ry_table_at(series, r, ct);
        const double tz = t0 + (t1 - t0) * y0 / (y0 - y1);
        if (o.crossings == 0) first = tz;
        last = tz;
        o.crossings++;
    }
    if (o.crossings >= 2) o.period = 2 * (last - first) / (o.crossings - 1);
    if (ck >= 0 && cs >= 0 && series->nrows > 0 && o.period > 0) {
        /* means over the first and the last period */
        const size_t n = series->nrows;
        const double t_end = ry_table_at(series, n - 1, ct);
        double s0 = 0, s1 = 0, n0 = 0, n1 = 0;
        o.energy0 = ry_table_at(series, 0, ck) + ry_table_at(series, 0, cs);
        for (size_t r = 0; r < n; ++r) {
            const double t = ry_table_at(series, r, ct);
            const double e = ry_table_at(series, r, ck) + ry_table_at(series, r, cs);
            if (t <= o.period) {
                s0 += e;
                n0 += 1;
            }
            if (t >= t_end - o.period) {
                s1 += e;
                n1 += 1;
            }
        }
        o.energy_first = s0 / n0;
        o.energy_last = s1 / n1;
    }
    return o;
}

/* One centreline against a reference: the profile's mean, interpolated linearly at the
 * reference's coordinates (coordinate `axis` of the points, in units of L); writes the CSV and
 * returns the RMS of (value/U - reference). */
static ry_status centreline(const ry_sim *sim, const char *profile, int axis, double L, double U,
                            const ry_table *ref, const char *coord, const char *value, int comp,
                            const char *path, double *rms, ry_error *err) {
    int cc = ry_table_col(ref, coord), cv = ry_table_col(ref, value);
    RY_CHECK(err, cc >= 0 && cv >= 0, RY_ERR_INPUT, "reference lacks columns %s, %s", coord, value);
    const ry_profile *pf = ry_profile_find(sim, profile);
    RY_CHECK(err, pf != NULL, RY_ERR_INPUT, "the case has no profile named '%s'", profile);
    RY_CHECK(err, pf->nsamples > 0, RY_ERR_INPUT, "profile '%s' has no samples", profile);
    const double a = pf->from[axis], b = pf->to[axis];
    RY_CHECK(err, b > a, RY_ERR_INPUT, "profile '%s' must run along increasing coordinate %d",
             profile, axis);
    ry_atomic_file f;
    RY_TRY(ry_atomic_open(&f, path, err));
    double sum2 = 0;
    fprintf(f.fp, "%s,%s,%s_ref\n", coord, value, value);
    for (size_t r = 0; r < ref->nrows; ++r) {
        const double s = (ry_table_at(ref, r, cc) * L - a) / (b - a) * (pf->npoints - 1);
        int k = (int)floor(s);
        if (k < 0) k = 0;
        if (k > pf->npoints - 2) k = pf->npoints - 2;
        const double fr = fmin(fmax(s - k, 0.0), 1.0);
        const double val = (1 - fr) * ry_profile_mean(sim, pf, k, comp) +
                           fr * ry_profile_mean(sim, pf, k + 1, comp);
        const double sim_v = val / U, ref_v = ry_table_at(ref, r, cv);
        fprintf(f.fp, "%.6f,%.6f,%.6f\n", ry_table_at(ref, r, cc), sim_v, ref_v);
        sum2 += (sim_v - ref_v) * (sim_v - ref_v);
    }
    *rms = ref->nrows ? sqrt(sum2 / (double)ref->nrows) : NAN;
    return ry_atomic_commit(&f, err);
}

ry_status ry_cavity_centrelines(const ry_sim *sim, double L, double U, const ry_table *ghia_u,
                                const ry_table *ghia_v, const char *out_dir, double *rms_u,
                                double *rms_v, ry_error *err) {
    char path[4096];
    snprintf(path, sizeof path, "%s/centreline_u.csv", out_dir);
    RY_TRY(centreline(sim, "u_vertical_centreline", 1, L, U, ghia_u, "y_over_L", "u_over_U", 0,
                      path, rms_u, err));
    snprintf(path, sizeof path, "%s/centreline_v.csv", out_dir);
    return centreline(sim, "v_horizontal_centreline", 0, L, U, ghia_v, "x_over_L", "v_over_U", 1,
                      path, rms_v, err);
}

double ry_profile_hydrostatic_error(const ry_sim *sim, const char *name, int k, double top,
                                    double rho, double g, double *p, double *h) {
    *p = *h = NAN;
    const ry_profile *pf = ry_profile_find(sim, name);
    if (!pf || k < 0 || k >= pf->npoints) return NAN;
    double x[3];
    ry_profile_point(sim, pf, k, x);
    *h = top - x[sim->dim - 1];
    *p = ry_profile_mean(sim, pf, k, sim->dim);
    return *p / (rho * g * *h) - 1.0;
}

ry_drop_periods ry_drop_periods_measure(const ry_table *series, const char *name) {
    ry_drop_periods out = {NAN, NAN, NAN, NAN, NAN};
    const int ct = ry_table_col(series, "t"), cw = ry_table_col(series, name);
    const size_t n = series->nrows;
    if (ct < 0 || cw < 0 || n < 5) return out;
    double *w = malloc(n * sizeof *w);
    if (!w) return out;
    /* Moving average over 5 rows (3 at the ends, the first row as it is). */
    for (size_t r = 0; r < n; ++r) {
        double s = 0;
        int k = 0;
        for (long q = (long)r - 2; q <= (long)r + 2; ++q)
            if (q >= 0 && q < (long)n && isfinite(ry_table_at(series, (size_t)q, cw))) {
                s += ry_table_at(series, (size_t)q, cw);
                ++k;
            }
        w[r] = r == 0 || k == 0 ? ry_table_at(series, r, cw) : s / k;
    }
    /* The first maximum: the first row above the middle between the start and the largest
     * width, then on while the width grows. */
    size_t imax = 1;
    for (size_t r = 1; r < n; ++r)
        if (w[r] > w[imax]) imax = r;
    const double mid = 0.5 * (w[0] + w[imax]);
    size_t r0 = 1;
    while (r0 < imax && w[r0] <= mid) ++r0;
    while (r0 + 1 < n && w[r0 + 1] >= w[r0]) ++r0;
    imax = r0;
    const double th = ry_table_at(series, imax, ct);
    size_t imin = imax;
    for (size_t r = imax + 1; r < n && ry_table_at(series, r, ct) <= 2.5 * th; ++r)
        if (w[r] < w[imin]) imin = r;
    out.width0 = w[0];
    out.width_max = w[imax];
    out.half = th;
    if (imin > imax && imin + 1 < n && ry_table_at(series, imin, ct) < 2.5 * th) {
        out.period = ry_table_at(series, imin, ct);
        out.width_min = w[imin];
    }
    free(w);
    return out;
}

double ry_column_max_from(const ry_table *series, const char *name, double t0) {
    const int c = ry_table_col(series, name), ct = ry_table_col(series, "t");
    if (c < 0 || ct < 0) return NAN;
    double m = -INFINITY;
    for (size_t r = 0; r < series->nrows; ++r)
        if (series->data[r * series->ncols + ct] >= t0)
            m = fmax(m, series->data[r * series->ncols + c]);
    return m;
}

double ry_column_mean_between(const ry_table *series, const char *name, double t0, double t1,
                              int *rows) {
    const int c = ry_table_col(series, name), ct = ry_table_col(series, "t");
    double s = 0;
    int k = 0;
    for (size_t r = 0; c >= 0 && ct >= 0 && r < series->nrows; ++r) {
        const double t = series->data[r * series->ncols + ct];
        if (t >= t0 && t < t1) {
            s += series->data[r * series->ncols + c];
            ++k;
        }
    }
    if (rows) *rows = k;
    return k ? s / k : NAN;
}

double ry_column_mean_from(const ry_table *series, const char *name, double t0, int *rows) {
    return ry_column_mean_between(series, name, t0, INFINITY, rows);
}

double ry_pressure_jump(const ry_sim *sim, const double *centre, double r_in, double r_out) {
    const ry_particles *ps = &sim->ps;
    double sin = 0, sout = 0;
    long nin = 0, nout = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        double r2 = 0;
        for (int d = 0; d < sim->dim; ++d) {
            const double dx = ps->f[RY_F_X + d][i] - centre[d];
            r2 += dx * dx;
        }
        if (r2 < r_in * r_in) {
            sin += ps->f[RY_F_P][i];
            ++nin;
        } else if (r2 > r_out * r_out) {
            sout += ps->f[RY_F_P][i];
            ++nout;
        }
    }
    return nin && nout ? sin / nin - sout / nout : NAN;
}

void ry_material_speeds(const ry_sim *sim, int material, double *vmax, double *vrms) {
    const ry_particles *ps = &sim->ps;
    double v2max = 0, v2sum = 0;
    size_t count = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || ps->material[i] != material) continue;
        double v2 = 0;
        for (int d = 0; d < sim->dim; ++d) v2 += ps->f[RY_F_VX + d][i] * ps->f[RY_F_VX + d][i];
        v2max = fmax(v2max, v2);
        v2sum += v2;
        ++count;
    }
    *vmax = sqrt(v2max);
    *vrms = count ? sqrt(v2sum / (double)count) : 0.0;
}

/* Residual of the best A e^(n t) + B e^(-n t) for a fixed n (relative weights 1 / a). */
static double growth_residual(const double *t, const double *a, int m, double n, double *A,
                              double *B) {
    double s11 = 0, s12 = 0, s22 = 0, r1 = 0, r2 = 0;
    for (int i = 0; i < m; ++i) {
        const double w = 1.0 / (a[i] * a[i]), e1 = exp(n * t[i]), e2 = exp(-n * t[i]);
        s11 += w * e1 * e1;
        s12 += w * e1 * e2;
        s22 += w * e2 * e2;
        r1 += w * e1 * a[i];
        r2 += w * e2 * a[i];
    }
    const double det = s11 * s22 - s12 * s12;
    *A = det != 0 ? (r1 * s22 - r2 * s12) / det : 0;
    *B = det != 0 ? (s11 * r2 - s12 * r1) / det : 0;
    double res = 0;
    for (int i = 0; i < m; ++i) {
        const double f = *A * exp(n * t[i]) + *B * exp(-n * t[i]);
        res += (f - a[i]) * (f - a[i]) / (a[i] * a[i]);
    }
    return res;
}

ry_growth_fit ry_fit_growth(const ry_table *series, const char *name, double t0, double amax,
                            double n_lo, double n_hi) {
    ry_growth_fit g = {NAN, NAN, NAN, NAN, NAN, 0};
    const int c = ry_table_col(series, name), ct = ry_table_col(series, "t");
    if (c < 0 || ct < 0 || series->nrows < 4 || !(n_hi > n_lo)) return g;
    double *t = malloc(series->nrows * sizeof *t), *a = malloc(series->nrows * sizeof *a);
    int m = 0;
    for (size_t r = 0; t && a && r < series->nrows; ++r) {
        const double tr = series->data[r * series->ncols + ct];
        const double ar = fabs(series->data[r * series->ncols + c]);
        if (ar > amax) break;
        if (tr < t0 || !(ar > 0)) continue;
        t[m] = tr;
        a[m++] = ar;
    }
    if (m >= 4) {
        const double phi = 0.5 * (sqrt(5.0) - 1.0);
        double lo = n_lo, hi = n_hi, A, B;
        double x1 = hi - phi * (hi - lo), x2 = lo + phi * (hi - lo);
        double f1 = growth_residual(t, a, m, x1, &A, &B), f2 = growth_residual(t, a, m, x2, &A, &B);
        for (int it = 0; it < 100 && hi - lo > 1e-9 * n_hi; ++it) {
            if (f1 < f2) {
                hi = x2;
                x2 = x1;
                f2 = f1;
                x1 = hi - phi * (hi - lo);
                f1 = growth_residual(t, a, m, x1, &A, &B);
            } else {
                lo = x1;
                x1 = x2;
                f1 = f2;
                x2 = lo + phi * (hi - lo);
                f2 = growth_residual(t, a, m, x2, &A, &B);
            }
        }
        g.n = 0.5 * (lo + hi);
        g.rms = sqrt(growth_residual(t, a, m, g.n, &g.A, &g.B) / m);
        g.t_last = t[m - 1];
        g.rows = m;
    }
    free(t);
    free(a);
    return g;
}

/* Sum of squares of the best fit a + e^(-k s)(b cos w s + c sin w s) to (s, y), w = 2 pi / T;
 * the coefficients in abc (INFINITY where the normal equations are singular). */
static double oscillation_residual(const double *s, const double *y, int m, double T, double k,
                                   double abc[3]) {
    const double w = 2.0 * 3.14159265358979323846 / T;
    double A[3][3] = {{0}}, r[3] = {0};
    for (int i = 0; i < m; ++i) {
        const double e = exp(-k * s[i]), f[3] = {1.0, e * cos(w * s[i]), e * sin(w * s[i])};
        for (int a = 0; a < 3; ++a) {
            r[a] += f[a] * y[i];
            for (int b = 0; b < 3; ++b) A[a][b] += f[a] * f[b];
        }
    }
    if (!ry_solve_small(3, A, r, abc)) return INFINITY; /* A is symmetric */
    double ss = 0;
    for (int i = 0; i < m; ++i) {
        const double e = exp(-k * s[i]);
        const double d = abc[0] + e * (abc[1] * cos(w * s[i]) + abc[2] * sin(w * s[i])) - y[i];
        ss += d * d;
    }
    return ss;
}

ry_oscillation_fit ry_fit_oscillation(const ry_table *series, const char *name, double t0,
                                      double t1, double T_lo, double T_hi, double k_max) {
    ry_oscillation_fit o = {NAN, NAN, NAN, NAN, NAN, 0};
    const int c = ry_table_col(series, name), ct = ry_table_col(series, "t");
    if (c < 0 || ct < 0 || !(T_hi > T_lo && T_lo > 0) || !(k_max >= 0)) return o;
    double *s = malloc((series->nrows + 1) * sizeof *s),
           *y = malloc((series->nrows + 1) * sizeof *y);
    int m = 0;
    for (size_t r = 0; s && y && r < series->nrows; ++r) {
        const double tr = series->data[r * series->ncols + ct];
        const double yr = series->data[r * series->ncols + c];
        if (tr < t0 || tr > t1 || !isfinite(yr)) continue;
        s[m] = tr - t0;
        y[m++] = yr;
    }
    if (m >= 6) {
        double bestT = NAN, bestk = 0, best = INFINITY, abc[3];
        double Tlo = T_lo, Thi = T_hi, klo = 0, khi = k_max;
        for (int level = 0; level < 3; ++level) {
            const int nT = level ? 41 : 200, nk = 41;
            for (int i = 0; i < nT; ++i)
                for (int j = 0; j < nk; ++j) {
                    const double T = Tlo + (Thi - Tlo) * i / (nT - 1),
                                 k = klo + (khi - klo) * j / (nk - 1);
                    if (!(T > 0) || k < 0) continue;
                    const double f = oscillation_residual(s, y, m, T, k, abc);
                    if (f < best) {
                        best = f;
                        bestT = T;
                        bestk = k;
                    }
                }
            /* the next grid: two steps of this one either side of the best */
            const double dT = 2.0 * (Thi - Tlo) / (nT - 1), dk = 2.0 * (khi - klo) / (nk - 1);
            Tlo = bestT - dT;
            Thi = bestT + dT;
            klo = fmax(bestk - dk, 0.0);
            khi = bestk + dk;
        }
        if (isfinite(best)) {
            oscillation_residual(s, y, m, bestT, bestk, abc);
            o.period = bestT;
            o.decay = bestk;
            o.mean = abc[0];
            o.amplitude = hypot(abc[1], abc[2]);
            o.rms = sqrt(best / m);
            o.rows = m;
        }
    }
    free(s);
    free(y);
    return o;
}

ry_oscillation_fit ry_drop_shape_fit(const ry_table *series, double T) {
    return ry_fit_oscillation(series, "shape_m4", 0.25 * T, INFINITY, 0.5 * T, 2.0 * T, 2000.0);
}

double ry_rt_growth_rate(double rho1, double rho2, double h1, double h2, double g, double k,
                         double nu, double sigma, int free_top) {
    const double drive = (rho1 - rho2) * g * k - sigma * k * k * k, t1 = tanh(k * h1);
    const double lower = rho2 / tanh(k * h2);
    double n2 = drive / (rho1 / t1 + lower); /* rigid lid */
    /* Free surface: R decreases from coth(k h1) as n^2 grows; the fixed point converges. */
    for (int it = 0; free_top && n2 > 0 && it < 200; ++it)
        n2 = drive / (rho1 * (n2 * t1 + g * k) / (n2 + g * k * t1) + lower);
    if (!(n2 > 0)) return 0.0;
    return sqrt(n2 + nu * nu * k * k * k * k) - nu * k * k;
}
