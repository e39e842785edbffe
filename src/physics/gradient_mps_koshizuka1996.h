/* The gradient of MPS (Koshizuka & Oka 1996, Nucl. Sci. Eng. 123: 421; seed 003 eq. 5) and its
 * corrected, least-squares form (Iribe & Nakaza), for the MPS pressure correction (scheme mps),
 * the velocity and stress gradients of MPS rheology and the curvature of the surface-tension
 * models (the gradient of the normals); and the divergence of the same family (eq. 6, the
 * source of the pressure equation):
 *
 *   standard:  <grad f>_i = d/n0 sum_j (f_j - f^_i) x_ji / r^2 w_ij
 *   corrected: <grad f>_i = C_i^-1 sum_j (f_j - f^_i) x_ji / r^2 w_ij,
 *              C_i = sum_j w_ij x_ji (x) x_ji / r^2
 *
 * with x_ji = x_j - x_i, w the MPS weight, n0 the lattice's number density and f^_i the value
 * the differences are taken from (f_i; for the pressure Koshizuka's least pressure around i,
 * the scheme's choice). The corrected form is exact for a linear field on any arrangement whose
 * C_i is regular. The pieces are the pair functions (one neighbour into the moment matrix and
 * into a field's sum) and, for the pressure, the finish that falls back to the standard form
 * where C_i is nearly singular (neighbours on a line or a plane only); ry_solve_small and
 * ry_solve_rows (linalg/small.h) finish the others. The traversals are the callers'. */
#ifndef RY_PHYSICS_GRADIENT_MPS_KOSHIZUKA1996_H
#define RY_PHYSICS_GRADIENT_MPS_KOSHIZUKA1996_H

#include "linalg/small.h"
#include "util/hd.h"

/* Neighbour j with w_ij / r^2 and x_ji into the moment matrix C_i. */
RY_HD static inline void ry_grad_moment_add(double m[3][3], double w_over_r2, const double *dx,
                                            int dim) {
    for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) m[a][b] += w_over_r2 * dx[a] * dx[b];
}

/* Neighbour j with w_ij / r^2, the difference df = f_j - f^_i and x_ji into a field's sum. */
RY_HD static inline void ry_grad_value_add(double *g, double w_over_r2, double df, const double *dx,
                                           int dim) {
    for (int b = 0; b < dim; ++b) g[b] += w_over_r2 * df * dx[b];
}

/* The divergence of MPS (eq. 6), <div u>_i = d/n0 sum_j (u_j - u_i) . x_ji / r^2 w_ij: the
 * pair's term from du = (u_j - u_i) . x_ji, r^2 and w_ij, and the finish from the sum. */
RY_HD static inline double ry_mps_divergence_term(double du, double r2, double w) {
    return du / r2 * w;
}
RY_HD static inline double ry_mps_divergence(double sum, int dim, double n0) {
    return dim * sum / n0;
}

/* The pressure gradient from the sums into out[0..dim-1]: corrected where `corrected` and C_i is
 * regular, else the standard form with n0. */
RY_HD static inline void ry_mps_pressure_gradient(double m[3][3], const double *g, int dim,
                                                  double n0, int corrected, double *out) {
    if (!corrected || !ry_solve_small(dim, m, g, out))
        for (int a = 0; a < dim; ++a) out[a] = dim * g[a] / n0;
}

#endif
