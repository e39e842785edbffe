/* The equilibrium of a tamponade (include/ryushi/validate.h): a lighter liquid (silicone oil)
 * above a heavier one (saline) in a sphere, the interface an axisymmetric Young-Laplace surface
 * meeting the wall at the contact angle, found by shooting from the apex.
 *
 * Lengths in units of the sphere's radius R, the sphere centred at the origin, z up (against
 * gravity). The meridian of the interface from its apex (0, z0), by arc length s, at angle phi
 * to the horizontal: r' = cos phi, z' = sin phi, and Young-Laplace with the hydrostatic
 * pressures, p_oil - p_saline = sigma (phi' + sin(phi) / r), the curvature growing with height:
 * phi' = k0 + B (z - z0) - sin(phi) / r, B = (rho_saline - rho_oil) g R^2 / sigma (at the apex
 * phi' = k0 / 2). The profile's shape depends on k0 alone; z0 places it. The contact angle,
 * measured through the saline between the wall (going down) and the interface (going in), is
 * cos(theta) = r_c sin(phi_c) - z_c cos(phi_c) at the contact point (r_c, z_c). The oil holds
 * the cap of the sphere above z_c and the volume between the interface and the plane z_c. */
#include <math.h>

#include "ryushi/validate.h"

static const double PI = 3.14159265358979323846;

enum { MAX_STEPS = 200000 };
static const double DS = 1e-3; /* arc-length step, units of R */

typedef struct state {
    double r, z, phi, vol; /* vol: pi int r^2 dz from the apex */
} state;

static void deriv(const state *y, double k0, double bond, double z0, state *d) {
    const double r = y->r > 1e-12 ? y->r : 1e-12;
    d->r = cos(y->phi);
    d->z = sin(y->phi);
    d->phi = k0 + bond * (y->z - z0) - sin(y->phi) / r;
    d->vol = PI * y->r * y->r * sin(y->phi);
}

static state rk4(const state *y, double h, double k0, double bond, double z0) {
    state k1, k2, k3, k4, t;
#define STAGE(out, from, c)                                                                        \
    t.r = y->r + (c) * (from).r;                                                                   \
    t.z = y->z + (c) * (from).z;                                                                   \
    t.phi = y->phi + (c) * (from).phi;                                                             \
    t.vol = y->vol + (c) * (from).vol;                                                             \
    deriv(&t, k0, bond, z0, &(out))
    deriv(y, k0, bond, z0, &k1);
    STAGE(k2, k1, 0.5 * h);
    STAGE(k3, k2, 0.5 * h);
    STAGE(k4, k3, h);
#undef STAGE
    state o = {y->r + h / 6 * (k1.r + 2 * k2.r + 2 * k3.r + k4.r),
               y->z + h / 6 * (k1.z + 2 * k2.z + 2 * k3.z + k4.z),
               y->phi + h / 6 * (k1.phi + 2 * k2.phi + 2 * k3.phi + k4.phi),
               y->vol + h / 6 * (k1.vol + 2 * k2.vol + 2 * k3.vol + k4.vol)};
    return o;
}

/* The points of a profile kept while shooting (ry_tamponade_profile): every stride-th step's,
 * up to cap, and the wall's; steps counts the steps taken. */
typedef struct trace {
    double *r, *z;
    size_t cap, n, stride, steps;
} trace;

static void keep(trace *tr, const state *y, int last) {
    if (!tr) return;
    if ((last || tr->steps % tr->stride == 0) && tr->n < tr->cap) {
        tr->r[tr->n] = y->r;
        tr->z[tr->n++] = y->z;
    }
    tr->steps += !last;
}

/* The profile of apex curvature k0 from the apex at z0 to the wall: the contact point, angle and
 * the oil's volume fraction; 1 when it reaches the wall, otherwise +2 when it turned back
 * upwards before (bent too much) and -2 when it turned back downwards. tr (or NULL) keeps its
 * points. */
static int shoot(double k0, double z0, double bond, ry_tamponade *out, trace *tr) {
    /* start off the axis by the series r = s, z = z0 + k0 s^2 / 4, phi = k0 s / 2 */
    const double s0 = 1e-6;
    state y = {s0, z0 + 0.25 * k0 * s0 * s0, 0.5 * k0 * s0, 0.0};
    for (int it = 0; it < MAX_STEPS; ++it) {
        keep(tr, &y, 0);
        state n = rk4(&y, DS, k0, bond, z0);
        if (n.r * n.r + n.z * n.z >= 1.0) {
            /* the step crosses the wall: bisect it until the crossing is found to 1e-15 */
            double lo = 0, hi = DS;
            for (int b = 0; b < 40; ++b) {
                const double mid = 0.5 * (lo + hi);
                const state m = rk4(&y, mid, k0, bond, z0);
                if (m.r * m.r + m.z * m.z >= 1.0)
                    hi = mid;
                else
                    lo = mid;
            }
            n = rk4(&y, hi, k0, bond, z0);
            keep(tr, &n, 1);
            const double zc = n.z;
            const double cap = PI * (1 - zc) * (1 - zc) * (2 + zc) / 3;
            out->z_contact = zc;
            out->r_contact = n.r;
            out->theta = acos(fmax(-1.0, fmin(1.0, n.r * sin(n.phi) - zc * cos(n.phi))));
            out->fill = (cap + n.vol) / (4 * PI / 3);
            out->coverage = 0.5 * (1 - zc);
            out->z_apex = z0;
            out->k0 = k0;
            return 1;
        }
        /* back at the axis or turned over: classified by the way it was bending before (at
         * the axis the last step may throw phi anywhere) */
        if (n.r <= 0 || fabs(n.phi) >= PI) return y.phi > 0 ? 2 : -2;
        y = n;
    }
    return 2;
}

/* The contact angle of the profile k0 from z0, extended past the profiles that do not reach the
 * wall (0 for those that bend up too much, pi for those that bend down), so that it falls with
 * k0. */
static double angle_of(double k0, double z0, double bond, ry_tamponade *t) {
    const int r = shoot(k0, z0, bond, t, NULL);
    return r == 1 ? t->theta : r > 0 ? 0.0 : PI;
}

/* For the apex at z0, the apex curvature that meets the wall at theta (bisection on k0); 0 when
 * the profile found does not reach the wall. */
static int at_apex(double z0, double theta, double bond, ry_tamponade *out) {
    double lo = -1e3, hi = 1e3;
    ry_tamponade t;
    for (int b = 0; b < 200 && hi - lo > 1e-12 * (1 + fabs(lo)); ++b) {
        const double mid = 0.5 * (lo + hi);
        if (angle_of(mid, z0, bond, &t) >= theta)
            lo = mid;
        else
            hi = mid;
    }
    return shoot(lo, z0, bond, out, NULL) == 1;
}

ry_status ry_tamponade_solve(double fill, double theta, double bond, ry_tamponade *out,
                             ry_error *err) {
    RY_CHECK(err, fill > 0 && fill < 1, RY_ERR_INPUT, "tamponade: fill %g outside (0, 1)", fill);
    RY_CHECK(err, theta > 0 && theta < PI, RY_ERR_INPUT,
             "tamponade: contact angle %g rad outside (0, pi)", theta);
    RY_CHECK(err, bond >= 0 && bond <= 1e4, RY_ERR_INPUT,
             "tamponade: Bond number %g outside 0..1e4", bond);
    /* the oil's volume falls as the apex rises: bisection on z0 */
    double lo = -1 + 1e-9, hi = 1 - 1e-9;
    ry_tamponade t;
    int found = 0;
    for (int b = 0; b < 100 && hi - lo > 1e-13; ++b) {
        const double mid = 0.5 * (lo + hi);
        if (!at_apex(mid, theta, bond, &t)) {
            hi = mid; /* no profile meets the wall at theta from this high */
            continue;
        }
        found = 1;
        if (t.fill > fill)
            lo = mid;
        else
            hi = mid;
    }
    RY_CHECK(err, found && at_apex(lo, theta, bond, &t), RY_ERR_INPUT,
             "tamponade: no equilibrium for fill %g, contact angle %g deg, Bond number %g", fill,
             theta * 180 / PI, bond);
    RY_CHECK(err, fabs(t.fill - fill) < 1e-6, RY_ERR_INPUT,
             "tamponade: no equilibrium for fill %g, contact angle %g deg, Bond number %g "
             "(nearest fill %g)",
             fill, theta * 180 / PI, bond, t.fill);
    RY_CHECK(err, fabs(t.theta - theta) < 1e-6, RY_ERR_INPUT,
             "tamponade: the shooting does not resolve the meniscus for Bond number %g (contact "
             "angle %g deg found against %g; it holds to about Bond 300)",
             bond, t.theta * 180 / PI, theta * 180 / PI);
    *out = t;
    return RY_OK;
}

size_t ry_tamponade_profile(const ry_tamponade *t, double bond, size_t cap, double *r, double *z) {
    ry_tamponade u;
    trace tr = {r, z, 0, 0, 1, 0};
    if (cap < 2 || shoot(t->k0, t->z_apex, bond, &u, &tr) != 1) return 0;
    tr.stride = tr.steps / (cap - 1) + 1;
    tr.cap = cap;
    tr.steps = 0;
    shoot(t->k0, t->z_apex, bond, &u, &tr);
    return tr.n;
}

/* A cone of the wall about the unit direction d (half angle h) in the frame where `up` (unit)
 * points against gravity: the oil covers the wall where p.up >= z_contact. Over the cone, at
 * angle a from d and azimuth b, p.up = A cos a + B sin a cos(b - b0) (A = d.up, B the size of
 * up's part normal to d), so the covered share of each ring is acos(c) / pi with
 * c = (z_contact - A cos a) / (B sin a) clamped to [-1, 1]; the rings are summed with their area
 * sin a da by Simpson's rule. */
double ry_tamponade_region_coverage(const ry_tamponade *t, const double up[3], const double d[3],
                                    double half_angle) {
    double A = 0;
    for (int k = 0; k < 3; ++k) A += d[k] * up[k];
    const double B = sqrt(fmax(0.0, 1.0 - A * A));
    if (B < 1e-12) { /* a cone about the vertical: the rings are wholly wet or dry */
        const double cz = A > 0 ? t->z_contact : -t->z_contact, c = cos(half_angle);
        const double lim = half_angle <= 0 ? 0 : 1 - c;
        if (!(lim > 0)) return A * 1.0 >= t->z_contact ? 1.0 : 0.0;
        /* A = 1: wet where cos a >= z_c; A = -1: where cos a <= -z_c */
        const double edge = fmin(fmax(cz, c), 1.0);
        return A > 0 ? (1 - edge) / lim : (edge - c) / lim;
    }
    enum { N = 2000 };
    double cov = 0, area = 0;
    for (int i = 0; i <= N; ++i) {
        const double a = half_angle * i / N, w = (i == 0 || i == N) ? 1 : (i % 2 ? 4 : 2);
        const double s = sin(a), h = t->z_contact - A * cos(a);
        double share;
        if (B * s <= 0)
            share = h <= 0 ? 1.0 : 0.0;
        else {
            const double c = h / (B * s);
            share = c <= -1 ? 1.0 : c >= 1 ? 0.0 : acos(c) / PI;
        }
        cov += w * s * share;
        area += w * s;
    }
    return area > 0 ? cov / area : (A >= t->z_contact ? 1.0 : 0.0);
}
