/* ryushi — unnormalised kernel shape functions f(q) and their derivatives f'(q), q = r / h.
 *
 * Included by ryushi/kernel.h after the declaration of ry_kernel_type; needs nothing else.
 * W(r) = sigma_d / h^d * f(r / h), with the normalisation sigma_d set by ry_kernel_init
 * (src/kernel/kernel.c; constants and sources listed in docs/kernels.md). Every f here is
 * zero for q at or beyond the support (kappa = 2 or 3) and f'(q) <= 0 for q >= 0. */
#ifndef RYUSHI_KERNEL_SHAPES_H
#define RYUSHI_KERNEL_SHAPES_H

#include <math.h>

/* Cubic B-spline M4 (Monaghan & Lattanzio 1985), support q < 2. */
static inline double ry_kshape_cubic(double q) {
    if (q < 1.0) return 1.0 - 1.5 * q * q + 0.75 * q * q * q;
    if (q < 2.0) {
        double t = 2.0 - q;
        return 0.25 * t * t * t;
    }
    return 0.0;
}
static inline double ry_kdshape_cubic(double q) {
    if (q < 1.0) return q * (2.25 * q - 3.0);
    if (q < 2.0) {
        double t = 2.0 - q;
        return -0.75 * t * t;
    }
    return 0.0;
}

/* Quintic B-spline M6 (Schoenberg 1946; Morris et al. 1997), support q < 3:
 * f = (3-q)^5 - 6 (2-q)^5 + 15 (1-q)^5, each term present only while its base is positive. */
static inline double ry_kshape_quintic(double q) {
    if (q >= 3.0) return 0.0;
    double a = 3.0 - q, a2 = a * a;
    double f = a2 * a2 * a;
    if (q < 2.0) {
        double b = 2.0 - q, b2 = b * b;
        f -= 6.0 * b2 * b2 * b;
    }
    if (q < 1.0) {
        double c = 1.0 - q, c2 = c * c;
        f += 15.0 * c2 * c2 * c;
    }
    return f;
}
static inline double ry_kdshape_quintic(double q) {
    if (q >= 3.0) return 0.0;
    double a = 3.0 - q, a2 = a * a;
    double g = -5.0 * a2 * a2;
    if (q < 2.0) {
        double b = 2.0 - q, b2 = b * b;
        g += 30.0 * b2 * b2;
    }
    if (q < 1.0) {
        double c = 1.0 - q, c2 = c * c;
        g -= 75.0 * c2 * c2;
    }
    return g;
}

/* Wendland C2 (Wendland 1995; Dehnen & Aly 2012), support q < 2, in s = q / 2:
 * f = (1-s)^4 (1+4s), f'(q) = -10 s (1-s)^3. */
static inline double ry_kshape_wendland_c2(double q) {
    if (q >= 2.0) return 0.0;
    double s = 0.5 * q, t = 1.0 - s, t2 = t * t;
    return t2 * t2 * (1.0 + 4.0 * s);
}
static inline double ry_kdshape_wendland_c2(double q) {
    if (q >= 2.0) return 0.0;
    double s = 0.5 * q, t = 1.0 - s;
    return -10.0 * s * t * t * t;
}

/* Wendland C4 (Wendland 1995; Dehnen & Aly 2012), support q < 2, in s = q / 2:
 * f = (1-s)^6 (1 + 6s + 35/3 s^2), f'(q) = -28/3 s (1-s)^5 (1+5s). */
static inline double ry_kshape_wendland_c4(double q) {
    if (q >= 2.0) return 0.0;
    double s = 0.5 * q, t = 1.0 - s, t3 = t * t * t;
    return t3 * t3 * (1.0 + s * (6.0 + s * (35.0 / 3.0)));
}
static inline double ry_kdshape_wendland_c4(double q) {
    if (q >= 2.0) return 0.0;
    double s = 0.5 * q, t = 1.0 - s, t2 = t * t;
    return -(28.0 / 3.0) * s * t2 * t2 * t * (1.0 + 5.0 * s);
}

/* Lucy (1977) quartic, support radius 2h, in s = q / 2: f = (1+3s)(1-s)^3,
 * f'(q) = -6 s (1-s)^2. */
static inline double ry_kshape_lucy(double q) {
    if (q >= 2.0) return 0.0;
    double s = 0.5 * q, t = 1.0 - s;
    return (1.0 + 3.0 * s) * t * t * t;
}
static inline double ry_kdshape_lucy(double q) {
    if (q >= 2.0) return 0.0;
    double s = 0.5 * q, t = 1.0 - s;
    return -6.0 * s * t * t;
}

/* Gaussian (Gingold & Monaghan 1977) f = exp(-q^2), truncated at q = 3 (f(3-) = exp(-9),
 * about 1.2e-4 of the peak); ry_kernel_init renormalises the truncated kernel. */
static inline double ry_kshape_gaussian(double q) {
    return q < 3.0 ? exp(-q * q) : 0.0;
}
static inline double ry_kdshape_gaussian(double q) {
    return q < 3.0 ? -2.0 * q * exp(-q * q) : 0.0;
}

/* f(q) for a kernel type; 0 for an unknown type. q >= 0. */
static inline double ry_kernel_shape(ry_kernel_type t, double q) {
    switch (t) {
    case RY_KERNEL_CUBIC:
        return ry_kshape_cubic(q);
    case RY_KERNEL_QUINTIC:
        return ry_kshape_quintic(q);
    case RY_KERNEL_WENDLAND_C2:
        return ry_kshape_wendland_c2(q);
    case RY_KERNEL_WENDLAND_C4:
        return ry_kshape_wendland_c4(q);
    case RY_KERNEL_LUCY:
        return ry_kshape_lucy(q);
    case RY_KERNEL_GAUSSIAN:
        return ry_kshape_gaussian(q);
    default:
        return 0.0;
    }
}

/* f'(q) = df/dq for a kernel type; 0 for an unknown type. q >= 0. */
static inline double ry_kernel_dshape(ry_kernel_type t, double q) {
    switch (t) {
    case RY_KERNEL_CUBIC:
        return ry_kdshape_cubic(q);
    case RY_KERNEL_QUINTIC:
        return ry_kdshape_quintic(q);
    case RY_KERNEL_WENDLAND_C2:
        return ry_kdshape_wendland_c2(q);
    case RY_KERNEL_WENDLAND_C4:
        return ry_kdshape_wendland_c4(q);
    case RY_KERNEL_LUCY:
        return ry_kdshape_lucy(q);
    case RY_KERNEL_GAUSSIAN:
        return ry_kdshape_gaussian(q);
    default:
        return 0.0;
    }
}

/* f'(q) / q, finite at q = 0 for every kernel here: grad W = (sigma_d / h^(d+2)) f'(q)/q x_ij,
 * so pair loops need no division by r. Closed forms where they are cheaper. */
static inline double ry_kernel_dshape_over_q(ry_kernel_type t, double q) {
    switch (t) {
    case RY_KERNEL_WENDLAND_C2: {
        if (q >= 2.0) return 0.0;
        double u = 1.0 - 0.5 * q;
        return -5.0 * u * u * u;
    }
    case RY_KERNEL_WENDLAND_C4: {
        if (q >= 2.0) return 0.0;
        double s = 0.5 * q, u = 1.0 - s, u2 = u * u;
        return -14.0 / 3.0 * u2 * u2 * u * (1.0 + 5.0 * s);
    }
    default:
        return q > 0.0 ? ry_kernel_dshape(t, q) / q : 0.0;
    }
}

#endif
