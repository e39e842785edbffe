/* ryushi — SPH smoothing kernels and MPS weight functions.
 *
 * Convention: h is the smoothing length; a kernel vanishes for r >= radius = kappa * h,
 * kappa depending on the kernel (documented per kernel in src/kernel/kernel.c and
 * docs/kernels.md). W(r, h) = sigma_d / h^d * f(q), q = r / h. Each kernel is normalised
 * so that its integral over R^d is 1 in d = 1, 2, 3. The gradient is
 * grad_i W_ij = dW/dr(r_ij) * x_ij / r_ij.
 *
 * The evaluation functions are static inline so that hot loops inline them; the switch on
 * the kernel type is the same for every pair (perfectly predicted). */
#ifndef RYUSHI_KERNEL_H
#define RYUSHI_KERNEL_H

#include "ryushi/status.h"

typedef enum ry_kernel_type {
    RY_KERNEL_CUBIC = 0,   /* cubic B-spline (M4), kappa = 2 */
    RY_KERNEL_QUINTIC,     /* quintic B-spline (M6), kappa = 3 */
    RY_KERNEL_WENDLAND_C2, /* Wendland C2, kappa = 2 */
    RY_KERNEL_WENDLAND_C4, /* Wendland C4, kappa = 2 */
    RY_KERNEL_LUCY,        /* Lucy (1977) quartic, kappa = 2 */
    RY_KERNEL_GAUSSIAN,    /* Gaussian truncated at q = 3 and renormalised, kappa = 3 */
    RY_KERNEL_COUNT
} ry_kernel_type;

typedef struct ry_kernel {
    ry_kernel_type type;
    int dim;       /* 1, 2 or 3 */
    double h;      /* smoothing length */
    double kappa;  /* support radius in units of h */
    double radius; /* kappa * h */
    double inv_h;  /* 1 / h */
    double norm;   /* sigma_d / h^d */
    double dnorm;  /* sigma_d / h^(d+1): factor of dW/dr */
} ry_kernel;

/* Sets up k for a type, dimension and smoothing length (h > 0, dim in 1..3). */
ry_status ry_kernel_init(ry_kernel *k, ry_kernel_type type, int dim, double h, ry_error *err);
/* Name used in case files ("cubic", "quintic", "wendland_c2", "wendland_c4", "lucy",
 * "gaussian") and back; ry_kernel_type_from_name returns -1 for an unknown name. */
const char *ry_kernel_name(ry_kernel_type type);
int ry_kernel_type_from_name(const char *name);
/* Support radius in units of h for a type. */
double ry_kernel_kappa(ry_kernel_type type);

/* Shape functions f(q) and f'(q) (unnormalised), defined in kernel_shapes.h. */
#include "ryushi/kernel_shapes.h"

/* W(r). */
static inline double ry_kernel_w(const ry_kernel *k, double r) {
    return k->norm * ry_kernel_shape(k->type, r * k->inv_h);
}
/* dW/dr(r) (<= 0 for r > 0 for every kernel here). */
static inline double ry_kernel_dwdr(const ry_kernel *k, double r) {
    return k->dnorm * ry_kernel_dshape(k->type, r * k->inv_h);
}

/* MPS weight functions (Koshizuka et al. 1996; Tamai et al. 2017 in seed 003, eq. 3). Both
 * vanish for r >= re. Koshizuka's is singular at r = 0 (callers never pass r = 0). */
static inline double ry_mps_weight_koshizuka(double r, double re) {
    return r < re ? re / r - 1.0 : 0.0;
}
static inline double ry_mps_weight_tamai(double r, double re) {
    double s = r / re - 1.0;
    return r < re ? s * s : 0.0;
}
/* d/dr of the two weights. */
static inline double ry_mps_dweight_koshizuka(double r, double re) {
    return r < re ? -re / (r * r) : 0.0;
}
static inline double ry_mps_dweight_tamai(double r, double re) {
    return r < re ? 2.0 * (r / re - 1.0) / re : 0.0;
}

#endif
