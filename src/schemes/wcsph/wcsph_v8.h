/* Eight lanes of single precision for the cell-range loop of WCSPH (wcsph_cells.c) and its
 * wall pass (wcsph_walls.c): the lane helpers and the kernels' shape functions f(q) and
 * f'(q)/q (include/ryushi/kernel_shapes.h) for every kernel, in single precision. The caller
 * masks the lanes at or beyond the support; lanes there may hold infinities, which the mask
 * (a bitwise and) removes. */
#ifndef RY_SCHEMES_WCSPH_V8_H
#define RY_SCHEMES_WCSPH_V8_H

#include <math.h>
#include <string.h>

#include "ryushi/kernel.h"

/* Eight lanes of single precision (GCC/Clang vector extensions: one AVX register, two SSE
 * registers, or lane loops elsewhere). */
typedef float v8f __attribute__((vector_size(32)));
typedef int v8i __attribute__((vector_size(32)));
typedef double v8d __attribute__((vector_size(64)));

static inline v8f v8_load(const float *p) {
    v8f v;
    memcpy(&v, p, sizeof v);
    return v;
}
/* x_i - x_j for eight j, formed in double precision and rounded. */
static inline v8f v8_sep(double xi, const double *xj) {
    v8d v;
    memcpy(&v, xj, sizeof v);
    return __builtin_convertvector(xi - v, v8f);
}
/* m ? a : 0 for a lane mask m (all bits set or clear). */
static inline v8f v8_and(v8i m, v8f a) {
    return (v8f)(m & (v8i)a);
}
static inline v8f v8_sqrt(v8f a) {
#if defined(__AVX__)
    return __builtin_ia32_sqrtps256(a);
#else
    v8f r;
    for (int k = 0; k < 8; ++k) r[k] = sqrtf(a[k]);
    return r;
#endif
}
/* Whether any lane of a mask is set. */
static inline int v8_any(v8i m) {
#if defined(__AVX__)
    return !__builtin_ia32_ptestz256((__attribute__((vector_size(32))) long long)m,
                                     (__attribute__((vector_size(32))) long long)m);
#else
    int a = 0;
    for (int k = 0; k < 8; ++k) a |= m[k];
    return a != 0;
#endif
}
/* The sum of the lanes, in double precision: halves added, then pairs. */
static inline double v8_sum(v8f a) {
    typedef float v4f __attribute__((vector_size(16)));
    typedef double v4d __attribute__((vector_size(32)));
    const v4f lo = {a[0], a[1], a[2], a[3]}, hi = {a[4], a[5], a[6], a[7]};
    const v4d s = __builtin_convertvector(lo, v4d) + __builtin_convertvector(hi, v4d);
    return (s[0] + s[2]) + (s[1] + s[3]);
}

/* m ? a : b for a lane mask m. */
static inline v8f v8_select(v8i m, v8f a, v8f b) {
    return (v8f)((m & (v8i)a) | (~m & (v8i)b));
}
/* exp(a) lane by lane. */
static inline v8f v8_exp(v8f a) {
    v8f r;
    for (int k = 0; k < 8; ++k) r[k] = expf(a[k]);
    return r;
}

/* f(q), the unnormalised kernel of include/ryushi/kernel_shapes.h (lanes with q < kappa). */
static inline v8f v8_kernel_shape(const ry_kernel_type kt, v8f q) {
    const v8f zero = {0};
    switch (kt) {
    case RY_KERNEL_CUBIC: {
        const v8f t = 2.0f - q;
        return v8_select(q < 1.0f, 1.0f - 1.5f * q * q + 0.75f * q * q * q, 0.25f * t * t * t);
    }
    case RY_KERNEL_QUINTIC: {
        const v8f a = 3.0f - q, b = v8_and(q < 2.0f, 2.0f - q), c = v8_and(q < 1.0f, 1.0f - q);
        const v8f a2 = a * a, b2 = b * b, c2 = c * c;
        return a2 * a2 * a - 6.0f * b2 * b2 * b + 15.0f * c2 * c2 * c;
    }
    case RY_KERNEL_WENDLAND_C2: {
        const v8f s = 0.5f * q, t = 1.0f - s, t2 = t * t;
        return t2 * t2 * (1.0f + 4.0f * s);
    }
    case RY_KERNEL_WENDLAND_C4: {
        const v8f s = 0.5f * q, t = 1.0f - s, t2 = t * t;
        return t2 * t2 * t2 * (1.0f + s * (6.0f + s * (35.0f / 3.0f)));
    }
    case RY_KERNEL_LUCY: {
        const v8f s = 0.5f * q, t = 1.0f - s;
        return (1.0f + 3.0f * s) * t * t * t;
    }
    case RY_KERNEL_GAUSSIAN:
        return v8_exp(-q * q);
    default:
        return zero;
    }
}

/* f'(q) / q (lanes with q < kappa), finite at q = 0 where the double-precision form is: the
 * quintic's inner piece expanded (-120 + 120 q^2 - 50 q^3), whose three terms would cancel in
 * single precision near q = 0. */
static inline v8f v8_kernel_dshape_over_q(const ry_kernel_type kt, v8f q) {
    const v8f zero = {0};
    switch (kt) {
    case RY_KERNEL_CUBIC: {
        const v8f t = 2.0f - q;
        return v8_select(q < 1.0f, 2.25f * q - 3.0f, -0.75f * t * t / q);
    }
    case RY_KERNEL_QUINTIC: {
        const v8f a = 3.0f - q, b = v8_and(q < 2.0f, 2.0f - q);
        const v8f a2 = a * a, b2 = b * b;
        return v8_select(q < 1.0f, -120.0f + q * q * (120.0f - 50.0f * q),
                         (30.0f * b2 * b2 - 5.0f * a2 * a2) / q);
    }
    case RY_KERNEL_WENDLAND_C2: {
        const v8f u = 1.0f - 0.5f * q, u2 = u * u;
        return -5.0f * u2 * u;
    }
    case RY_KERNEL_WENDLAND_C4: {
        const v8f s = 0.5f * q, u = 1.0f - s, u2 = u * u;
        return (-14.0f / 3.0f) * u2 * u2 * u * (1.0f + 5.0f * s);
    }
    case RY_KERNEL_LUCY: {
        const v8f t = 1.0f - 0.5f * q;
        return -3.0f * t * t;
    }
    case RY_KERNEL_GAUSSIAN:
        return -2.0f * v8_exp(-q * q);
    default:
        return zero;
    }
}

#endif
