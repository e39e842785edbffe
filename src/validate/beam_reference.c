/* Reference solutions for cantilevers: Euler-Bernoulli and Timoshenko deflections, elastica,
 * the vibrating plate and the buckled column. */
#include <math.h>

#include "ryushi/beam.h"
#include "ryushi/validate.h"

#define PI 3.14159265358979323846

/* Bending moment and shear force at s for intensity 1. */
static double moment(ry_beam_load load, double L, double s) {
    const double k = 0.5 * PI / L;
    switch (load) {
    case RY_BEAM_LOAD_END:
        return L - s;
    case RY_BEAM_LOAD_UNIFORM:
        return 0.5 * (L - s) * (L - s);
    case RY_BEAM_LOAD_LINEAR: /* (1/L) int_s^L xi (xi - s) dxi */
        return ((L * L * L - s * s * s) / 3 - 0.5 * s * (L * L - s * s)) / L;
    case RY_BEAM_LOAD_COSINE: /* int_s^L cos(k xi) (xi - s) dxi, sin kL = 1, cos kL = 0 */
        return (L - s) / k - cos(k * s) / (k * k);
    default:
        return 0.0;
    }
}

static double shear(ry_beam_load load, double L, double s) {
    const double k = 0.5 * PI / L;
    switch (load) {
    case RY_BEAM_LOAD_END:
        return 1.0;
    case RY_BEAM_LOAD_UNIFORM:
        return L - s;
    case RY_BEAM_LOAD_LINEAR:
        return 0.5 * (L * L - s * s) / L;
    case RY_BEAM_LOAD_COSINE:
        return (1 - sin(k * s)) / k;
    default:
        return 0.0;
    }
}

/* Composite Simpson over [0, x], 2000 intervals (the integrands are smooth: error below
 * 1e-12), of f(s) times the lever arm (x - s) when `lever` is set. */
static double simpson(double (*f)(ry_beam_load, double, double), ry_beam_load load, double L,
                      double x, int lever) {
    const int n = 2000;
    const double hs = x / n;
    double sum = 0;
    for (int i = 0; i <= n; ++i) {
        double s = i * hs, w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
        sum += w * (lever ? x - s : 1.0) * f(load, L, s);
    }
    return sum * hs / 3;
}

double ry_beam_deflection_eb(ry_beam_load load, double L, double EI, double x) {
    return simpson(moment, load, L, x, 1) / EI;
}

double ry_beam_deflection_shear(ry_beam_load load, double L, double kappa_GA, double x) {
    return simpson(shear, load, L, x, 0) / kappa_GA;
}

/* With theta the angle of the centreline from the x axis (0 at the root, theta0 at the tip),
 * EI theta'' = -P cos theta and theta'(L) = 0 give theta' = sqrt(2 P/EI (sin theta0 -
 * sin theta)), so that (lengths in units of L, a2 = P L^2 / EI)
 *   1 = int_0^theta0 dtheta / theta',  y = int sin theta dtheta / theta',
 *   x = sqrt(2 sin theta0 / a2).
 * The substitution theta = theta0 (1 - t^2) removes the end singularity. */
static void elastica_integrals(double a2, double th0, double *len, double *y) {
    const int n = 4000;
    double sl = 0, sy = 0;
    for (int i = 0; i <= n; ++i) {
        double t = (double)i / n, w = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
        double th = th0 * (1 - t * t), d = sin(th0) - sin(th);
        double f;
        if (t > 0)
            f = 2 * th0 * t / sqrt(2 * a2 * d);
        else /* limit t -> 0: d ~ cos(th0) th0 t^2 */
            f = 2 * th0 / sqrt(2 * a2 * th0 * cos(th0));
        sl += w * f;
        sy += w * f * sin(th);
    }
    *len = sl / (3.0 * n);
    *y = sy / (3.0 * n);
}

void ry_elastica_end_load(double alpha2, double *x_tip, double *y_tip, double *theta_tip) {
    double lo = 1e-9, hi = 0.5 * PI - 1e-9, y = 0, len;
    for (int it = 0; it < 200; ++it) { /* the length grows with theta0 */
        double mid = 0.5 * (lo + hi);
        elastica_integrals(alpha2, mid, &len, &y);
        if (len < 1)
            lo = mid;
        else
            hi = mid;
    }
    double th0 = 0.5 * (lo + hi);
    elastica_integrals(alpha2, th0, &len, &y);
    *x_tip = sqrt(2 * sin(th0) / alpha2);
    *y_tip = y;
    *theta_tip = th0;
}

double ry_plate_omega(double E, double nu, double rho, double H, double L) {
    const double k = RY_CANTILEVER_KL1 / L;
    return sqrt(E * H * H * k * k * k * k / (12 * rho * (1 - nu * nu)));
}

void ry_elliptic_ke(double p, double *K, double *E) {
    double a = 1, b = sqrt(1 - p * p), c = p, sum = 0.5 * p * p, pow2 = 0.5;
    for (int it = 0; it < 60 && fabs(c) > 1e-17; ++it) {
        const double an = 0.5 * (a + b);
        c = 0.5 * (a - b);
        b = sqrt(a * b);
        a = an;
        pow2 *= 2;
        sum += pow2 * c * c;
    }
    *K = PI / (2 * a);
    *E = *K * (1 - sum);
}

void ry_elastica_column(double load_ratio, double *x_tip, double *y_tip, double *theta_tip) {
    *x_tip = 1;
    *y_tip = *theta_tip = 0;
    if (!(load_ratio > 1)) return;
    const double kL = 0.5 * PI * sqrt(load_ratio);
    double lo = 0, hi = 1 - 1e-15, K = 0, E = 0;
    for (int it = 0; it < 200; ++it) { /* K(p) grows with p */
        const double mid = 0.5 * (lo + hi);
        ry_elliptic_ke(mid, &K, &E);
        if (K < kL)
            lo = mid;
        else
            hi = mid;
    }
    const double p = 0.5 * (lo + hi);
    ry_elliptic_ke(p, &K, &E);
    *x_tip = 2 * E / K - 1;
    *y_tip = 2 * p / K;
    *theta_tip = 2 * asin(p);
}
