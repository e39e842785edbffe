/* Reference solutions for channel flows of non-Newtonian fluids (include/ryushi/validate.h). */
#include <math.h>
#include <stdlib.h>

#include "ryushi/rheology.h"
#include "ryushi/sim.h"
#include "ryushi/surface_tension.h" /* RY_PI */
#include "ryushi/validate.h"

double ry_power_law_poiseuille(double g, double k, double n, double b, double s) {
    const double e = 1.0 + 1.0 / n;
    return n / (n + 1.0) * pow(g / k, 1.0 / n) * (pow(b, e) - pow(fabs(s), e));
}

/* The shear rate at which the steady shear stress (per unit density) equals tau. */
static double shear_rate(const ry_rheology *r, double nu, double tau) {
    if (tau <= 0) return 0;
    double lo = 0, hi = 1;
    while (ry_rheology_shear_nu(r, nu, hi) * hi < tau && hi < 1e30) hi *= 2;
    for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        if (ry_rheology_shear_nu(r, nu, mid) * mid < tau)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

double ry_viscometric_poiseuille(const ry_rheology *r, double nu, double g, double b, double s) {
    s = fabs(s);
    if (s >= b) return 0;
    const int m = 2000; /* even */
    const double h = (b - s) / m;
    double sum = 0;
    for (int q = 0; q <= m; ++q) {
        const double wq = q == 0 || q == m ? 1 : q % 2 ? 4 : 2;
        sum += wq * shear_rate(r, nu, g * (s + q * h));
    }
    return sum * h / 3.0;
}

double ry_oldroyd_b_startup(double g, double H, double nu_s, double nu_p, double lambda, double y,
                            double t, int modes) {
    double u = 0;
    for (int q = 0; q < modes; ++q) {
        const int k = 2 * q + 1;
        const double a = k * RY_PI / H, gk = 4.0 * g / (k * RY_PI);
        /* x' = A x + (gk, 0), x(0) = 0: x(t) = (e^{At} - I) A^-1 (gk, 0). */
        const double A00 = -a * a * nu_s, A01 = -a * a, A10 = nu_p / lambda, A11 = -1.0 / lambda;
        const double T = A00 + A11, D = A00 * A11 - A01 * A10, disc = 0.25 * T * T - D;
        double c, sq; /* e^{At} = c I + sq (A - T/2 I) */
        if (disc > 0) {
            const double qq = sqrt(disc), e1 = exp((0.5 * T + qq) * t),
                         e2 = exp((0.5 * T - qq) * t);
            c = 0.5 * (e1 + e2);
            sq = 0.5 * (e1 - e2) / qq;
        } else if (disc < 0) {
            const double qq = sqrt(-disc), e = exp(0.5 * T * t);
            c = e * cos(qq * t);
            sq = e * sin(qq * t) / qq;
        } else {
            c = exp(0.5 * T * t);
            sq = t * c;
        }
        const double E00 = c + sq * (A00 - 0.5 * T), E01 = sq * A01;
        const double i0 = A11 * gk / D, i1 = -A10 * gk / D; /* A^-1 (gk, 0) */
        u += ((E00 - 1.0) * i0 + E01 * i1) * sin(a * y);
    }
    return u;
}

size_t ry_row_velocity(const ry_sim *sim, double y0, double l0, double *y, double *u, size_t max) {
    const ry_particles *ps = &sim->ps;
    size_t *count = calloc(max, sizeof *count);
    if (!count) return 0;
    for (size_t r = 0; r < max; ++r) u[r] = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        const double row = floor((ps->f[RY_F_Y][i] - y0) / l0);
        if (row < 0 || row >= (double)max) continue;
        count[(size_t)row]++;
        u[(size_t)row] += ps->f[RY_F_VX][i];
    }
    size_t rows = 0;
    for (size_t r = 0; r < max; ++r)
        if (count[r]) {
            y[rows] = y0 + (r + 0.5) * l0;
            u[rows] = u[r] / (double)count[r];
            ++rows;
        }
    free(count);
    return rows;
}
