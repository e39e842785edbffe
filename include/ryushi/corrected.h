/* ryushi — corrected SPH: kernel and kernel-gradient corrections (seed 000, eq. 10-13).
 *
 * At a point x_i with neighbours x_j of volume V_j (W_ij = W(|x_i - x_j|), grad W_ij the
 * gradient with respect to x_i, d_j = x_i - x_j):
 *
 *   Shepard (zeroth order)   W~_ij = alpha_i W_ij,  alpha_i = 1 / sum_j V_j W_ij          (eq. 13)
 *   linear (first order)     W~_ij = alpha_i (1 + beta_i . d_j) W_ij,
 *                            beta_i = -(sum_j V_j W_ij d_j (x) d_j)^-1 sum_j V_j W_ij d_j  (eq. 11)
 *                            alpha_i = 1 / sum_j V_j (1 + beta_i . d_j) W_ij               (eq. 12)
 *
 * so that sum_j V_j W~_ij f_j reproduces constants (Shepard) or linear fields (linear) exactly.
 * The kernel sums include the point itself (W(0)) when it is a particle of volume v_self.
 *
 * Gradients of a field f at x_i:
 *
 *   none      grad f_i = sum_j V_j f_j grad W_ij                  (plain SPH)
 *   Shepard   grad f_i = sum_j V_j (f_j - f_i) grad W_ij / sum_j V_j W_ij   (constants exact)
 *   linear    grad f_i = sum_j V_j (f_j - f_i) L_i grad W_ij,
 *             L_i = (sum_j V_j grad W_ij (x) (x_j - x_i))^-1       (linear fields exact)
 *
 * L_i grad W_ij is the corrected kernel gradient that the total-Lagrangian solid scheme uses
 * (src/schemes/solid/solid.c). Matrices are 3 x 3, row-major; only the leading dim x dim block is
 * used. */
#ifndef RYUSHI_CORRECTED_H
#define RYUSHI_CORRECTED_H

#include <stddef.h>
#include <stdint.h>

#include "ryushi/kernel.h"
#include "ryushi/status.h"

typedef enum ry_correction {
    RY_CORRECTION_NONE = 0,
    RY_CORRECTION_SHEPARD = 1,
    RY_CORRECTION_LINEAR = 2
} ry_correction;

/* Correction data of one point. */
typedef struct ry_corr {
    ry_correction type;
    int dim;
    double alpha;   /* kernel factor (1 for none) */
    double beta[3]; /* linear factor (0 unless linear) */
    double L[9];    /* gradient correction matrix (identity for none; (1/sum V W) I for Shepard) */
} ry_corr;

/* Inverse of the dim x dim block of a 3 x 3 row-major matrix. RY_ERR_RANGE when it is singular
 * (|det| below 1e-12 times the product of the row norms). */
ry_status ry_mat_inverse(int dim, const double *a, double *inv, ry_error *err);

/* Builds the correction at xi from nn neighbours nbr[] (indices into the coordinate arrays x and
 * volumes vol); v_self > 0 adds the point itself to the kernel sums. RY_ERR_RANGE (naming the
 * point) when a moment matrix is singular, e.g. too few neighbours for the linear correction. */
ry_status ry_corr_build(ry_corr *c, ry_correction type, const ry_kernel *k, const double *xi,
                        double v_self, size_t nn, const uint32_t *nbr, const double *const x[3],
                        const double *vol, ry_error *err);

/* The corrected kernel W~ between xi and xj. */
double ry_corr_w(const ry_corr *c, const ry_kernel *k, const double *xi, const double *xj);
/* The corrected kernel gradient at xi for neighbour xj (L grad W_ij for linear). */
void ry_corr_grad_w(const ry_corr *c, const ry_kernel *k, const double *xi, const double *xj,
                    double *g);

/* Gradient weights that reproduce quadratic fields (an extension beyond the seed, for beams in
 * bending, whose displacement is quadratic across the thickness): the kernel-weighted least-
 * squares fit of f_j - f_i = a . d + d^T H d / 2 (d = x_j - x_i) over the neighbours gives
 * grad f_i = a = sum_j G_j (f_j - f_i), exact for every quadratic f. G holds dim numbers per
 * neighbour: G_j = V_j W_ij [M^-1 p(d_j)]_{0..dim-1}, M = sum_j V_j W_ij p p^T, p the
 * monomials (d, d (x) d) scaled by 1/h. RY_ERR_RANGE when M is singular (too few or coplanar
 * neighbours: 5 are needed in 2D, 9 in 3D). H (may be NULL) receives dim x dim numbers per
 * neighbour, the weights of the second derivatives of the same fit: d_a d_b f_i =
 * sum_j H_j[a][b] (f_j - f_i), exact for quadratic f. */
ry_status ry_corr_quadratic_gradient(const ry_kernel *k, const double *xi, size_t nn,
                                     const uint32_t *nbr, const double *const x[3],
                                     const double *vol, double *G, double *H, ry_error *err);

/* Interpolates f (one value per particle) at particle i of a particle set: value
 * sum_j V_j W~_ij f_j (self included) and gradient as in the table above. nn neighbours nbr[]
 * (excluding i). Either output may be NULL. */
ry_status ry_corr_field(ry_correction type, const ry_kernel *k, size_t i, size_t nn,
                        const uint32_t *nbr, const double *const x[3], const double *vol,
                        const double *f, double *value, double *grad, ry_error *err);

#endif
