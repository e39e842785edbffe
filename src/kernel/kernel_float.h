/* The kernels' shape functions f(q) and f'(q)/q (include/ryushi/kernel_shapes.h) in single
 * precision, for the pair loops that run in floats (WCSPH's cell-range loop and its wall pass).
 * Written without branches on q, so that a loop over candidates compiles to SIMD code: the
 * caller masks candidates at or beyond the support (kappa = 2 or 3), where these forms may give
 * any finite value. f'(q)/q is finite at q = 0 where the double-precision form is: the
 * quintic's inner piece is expanded (-120 + 120 q^2 - 50 q^3), as its three terms would cancel
 * in single precision near q = 0. RY_HD: written in the common subset of C and C++. */
#ifndef RY_KERNEL_KERNEL_FLOAT_H
#define RY_KERNEL_KERNEL_FLOAT_H

#include <math.h>

#include "ryushi/kernel.h"
#include "util/hd.h"

/* f(q) for q below the support. */
RY_HD static inline float ry_kshapef(const ry_kernel_type kt, float q) {
    switch (kt) {
    case RY_KERNEL_CUBIC: {
        const float t = 2.0f - q;
        return q < 1.0f ? 1.0f - 1.5f * q * q + 0.75f * q * q * q : 0.25f * t * t * t;
    }
    case RY_KERNEL_QUINTIC: {
        const float a = 3.0f - q, b = q < 2.0f ? 2.0f - q : 0.0f, c = q < 1.0f ? 1.0f - q : 0.0f;
        const float a2 = a * a, b2 = b * b, c2 = c * c;
        return a2 * a2 * a - 6.0f * b2 * b2 * b + 15.0f * c2 * c2 * c;
    }
    case RY_KERNEL_WENDLAND_C2: {
        const float s = 0.5f * q, t = 1.0f - s, t2 = t * t;
        return t2 * t2 * (1.0f + 4.0f * s);
    }
    case RY_KERNEL_WENDLAND_C4: {
        const float s = 0.5f * q, t = 1.0f - s, t2 = t * t;
        return t2 * t2 * t2 * (1.0f + s * (6.0f + s * (35.0f / 3.0f)));
    }
    case RY_KERNEL_LUCY: {
        const float s = 0.5f * q, t = 1.0f - s;
        return (1.0f + 3.0f * s) * t * t * t;
    }
    case RY_KERNEL_GAUSSIAN:
        return expf(-q * q);
    default:
        return 0.0f;
    }
}

/* f'(q) / q for q below the support. */
RY_HD static inline float ry_kdshape_over_qf(const ry_kernel_type kt, float q) {
    switch (kt) {
    case RY_KERNEL_CUBIC: {
        const float t = 2.0f - q;
        return q < 1.0f ? 2.25f * q - 3.0f : -0.75f * t * t / q;
    }
    case RY_KERNEL_QUINTIC: {
        const float a = 3.0f - q, b = q < 2.0f ? 2.0f - q : 0.0f;
        const float a2 = a * a, b2 = b * b;
        return q < 1.0f ? -120.0f + q * q * (120.0f - 50.0f * q)
                        : (30.0f * b2 * b2 - 5.0f * a2 * a2) / q;
    }
    case RY_KERNEL_WENDLAND_C2: {
        const float u = 1.0f - 0.5f * q, u2 = u * u;
        return -5.0f * u2 * u;
    }
    case RY_KERNEL_WENDLAND_C4: {
        const float s = 0.5f * q, u = 1.0f - s, u2 = u * u;
        return (-14.0f / 3.0f) * u2 * u2 * u * (1.0f + 5.0f * s);
    }
    case RY_KERNEL_LUCY: {
        const float t = 1.0f - 0.5f * q;
        return -3.0f * t * t;
    }
    case RY_KERNEL_GAUSSIAN:
        return -2.0f * expf(-q * q);
    default:
        return 0.0f;
    }
}

#endif
