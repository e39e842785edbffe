/* Smoothing kernels: names, supports and normalisation (see include/ryushi/kernel.h).
 *
 * W(r, h) = sigma_d / h^d * f(q), q = r / h, with f in ryushi/kernel_shapes.h. sigma_d is
 * 1 / integral of f(|x|) over R^d, i.e. 1 / (S_d * integral_0^kappa f(q) q^(d-1) dq) with
 * S_1 = 2, S_2 = 2 pi, S_3 = 4 pi. Every constant below was obtained by integrating the
 * piecewise polynomials exactly (they are also checked numerically by tests/unit/test_kernel.c)
 * and agrees with the published values:
 *
 *   cubic M4      2/3, 10/(7 pi), 1/pi             Monaghan & Lattanzio (1985); Monaghan (1992)
 *   quintic M6    1/120, 7/(478 pi), 1/(120 pi)    Morris, Fox & Zhu (1997); Liu & Liu (2003)
 *   Wendland C2   3/4, 7/(4 pi), 21/(16 pi)        Wendland (1995); Dehnen & Aly (2012), H = 2h
 *   Wendland C4   27/32, 9/(4 pi), 495/(256 pi)    Wendland (1995); Dehnen & Aly (2012), H = 2h
 *   Lucy quartic  5/8, 5/(4 pi), 105/(128 pi)      Lucy (1977), radius R = 2h
 *   Gaussian      1/(sqrt(pi) erf 3), 1/(pi (1 - e^-9)), 1/(pi^(3/2) erf 3 - 6 pi e^-9)
 *
 * Wendland C2 and C4 use the same functions in every dimension (the functions Wendland built
 * for d <= 3); they are positive definite in R^3 and so also in R^2 and R^1, and in 1D and 2D
 * they are simply normalised in that dimension (Wendland's lower-dimensional functions, such
 * as (1-s)^3 (1+3s) in 1D, are not used; that one is Lucy's kernel anyway).
 *
 * The Gaussian exp(-q^2) is cut at q = 3 and renormalised so that the truncated kernel
 * integrates to exactly 1 (the untruncated constants are pi^(-d/2)):
 *   1D: integral_{-3}^{3} e^{-q^2} dq = sqrt(pi) erf(3)
 *   2D: 2 pi integral_0^3 q e^{-q^2} dq = pi (1 - e^{-9})
 *   3D: 4 pi integral_0^3 q^2 e^{-q^2} dq = pi^(3/2) erf(3) - 6 pi e^{-9}. */
#include "ryushi/kernel.h"

#include <math.h>
#include <stddef.h>
#include <string.h>

#define RY_PI 3.14159265358979323846

static const char *const kernel_names[RY_KERNEL_COUNT] = {
    "cubic", "quintic", "wendland_c2", "wendland_c4", "lucy", "gaussian",
};

static const double kernel_kappa[RY_KERNEL_COUNT] = {2.0, 3.0, 2.0, 2.0, 2.0, 3.0};

static int type_valid(ry_kernel_type type) {
    return (int)type >= 0 && (int)type < (int)RY_KERNEL_COUNT;
}

const char *ry_kernel_name(ry_kernel_type type) {
    return type_valid(type) ? kernel_names[type] : "unknown";
}

int ry_kernel_type_from_name(const char *name) {
    if (!name) return -1;
    for (int i = 0; i < (int)RY_KERNEL_COUNT; i++)
        if (strcmp(name, kernel_names[i]) == 0) return i;
    return -1;
}

double ry_kernel_kappa(ry_kernel_type type) {
    return type_valid(type) ? kernel_kappa[type] : 0.0;
}

/* Normalisation of the truncated Gaussian exp(-q^2), q < 3, in dim dimensions. */
static double gaussian_sigma(int dim) {
    const double e9 = exp(-9.0), erf3 = erf(3.0);
    switch (dim) {
    case 1:
        return 1.0 / (sqrt(RY_PI) * erf3);
    case 2:
        return 1.0 / (RY_PI * (1.0 - e9));
    default:
        return 1.0 / (RY_PI * sqrt(RY_PI) * erf3 - 6.0 * RY_PI * e9);
    }
}

/* sigma_d for a valid type and dim in 1..3. */
static double kernel_sigma(ry_kernel_type type, int dim) {
    static const double poly[RY_KERNEL_COUNT][3] = {
        [RY_KERNEL_CUBIC] = {2.0 / 3.0, 10.0 / (7.0 * RY_PI), 1.0 / RY_PI},
        [RY_KERNEL_QUINTIC] = {1.0 / 120.0, 7.0 / (478.0 * RY_PI), 1.0 / (120.0 * RY_PI)},
        [RY_KERNEL_WENDLAND_C2] = {3.0 / 4.0, 7.0 / (4.0 * RY_PI), 21.0 / (16.0 * RY_PI)},
        [RY_KERNEL_WENDLAND_C4] = {27.0 / 32.0, 9.0 / (4.0 * RY_PI), 495.0 / (256.0 * RY_PI)},
        [RY_KERNEL_LUCY] = {5.0 / 8.0, 5.0 / (4.0 * RY_PI), 105.0 / (128.0 * RY_PI)},
    };
    if (type == RY_KERNEL_GAUSSIAN) return gaussian_sigma(dim);
    return poly[type][dim - 1];
}

ry_status ry_kernel_init(ry_kernel *k, ry_kernel_type type, int dim, double h, ry_error *err) {
    RY_CHECK(err, k != NULL, RY_ERR_INTERNAL, "ry_kernel_init: no kernel to initialise");
    RY_CHECK(err, type_valid(type), RY_ERR_INPUT,
             "unknown kernel type %d (expected cubic, quintic, wendland_c2, wendland_c4, lucy "
             "or gaussian)",
             (int)type);
    RY_CHECK(err, dim >= 1 && dim <= 3, RY_ERR_RANGE,
             "kernel '%s': dimension must be 1, 2 or 3, got %d", kernel_names[type], dim);
    RY_CHECK(err, isfinite(h) && h > 0.0, RY_ERR_RANGE,
             "kernel '%s': smoothing length h must be positive and finite, got %g",
             kernel_names[type], h);
    double sigma = kernel_sigma(type, dim);
    double hd = dim == 1 ? h : dim == 2 ? h * h : h * h * h;
    k->type = type;
    k->dim = dim;
    k->h = h;
    k->kappa = kernel_kappa[type];
    k->radius = k->kappa * h;
    k->inv_h = 1.0 / h;
    k->norm = sigma / hd;
    k->dnorm = k->norm / h;
    RY_CHECK(err, isfinite(k->norm) && isfinite(k->dnorm) && k->norm > 0.0, RY_ERR_RANGE,
             "kernel '%s': smoothing length h = %g gives a normalisation outside the range of "
             "double",
             kernel_names[type], h);
    return RY_OK;
}
