/* The pair terms of the SPH solids (docs/reference/solid.md), for particle i and neighbour j,
 * tensors as 3 x 3 arrays in row-major order: the velocity gradient and correction moment of the
 * updated Lagrangian's rates pass (below), and the momentum equations:
 *
 *   updated Lagrangian (Gray, Monaghan & Swift 2001; seed 000 eq. 14-18):
 *     m_i dv_i/dt gains  sigma_i w_i + sigma_j w_j + m_i m_j (f_ij^n (R_i + R_j) - Pi_ij I) grad_i
 * W_ij with the weights w_i = V_i V_j L_i grad_i W_ij, w_j = V_i V_j L_j grad_i W_ij (linear
 *     correction, L = I without) or w_i = V_i G_ij, w_j = -V_j G_ji (quadratic), the artificial
 *     stress R (Monaghan 2000) and the artificial viscosity Pi_ij
 *     (physics/artificial_viscosity_monaghan1992.h);
 *   total Lagrangian: f_i gains V_i A_i G_ij - V_j A_j G_ji (A the first Piola-Kirchhoff stress,
 *     G the corrected reference gradients), the strain-gradient stresses' pair through the
 *     second-derivative weights, and the hourglass penalty c_ij e_ij with
 *     e_ij = x_j - x_i - (F_i + F_j)/2 (X_j - X_i) (Ganzenmueller 2015).
 *
 * Each function adds the pair's share to its sum, component by component; the traversals (the
 * neighbour lists of the current or the reference configuration) are updated.c's and
 * total.c's. RY_HD: written in the common subset of C and C++. */
#ifndef RY_SCHEMES_SOLID_PAIR_H
#define RY_SCHEMES_SOLID_PAIR_H

#include "util/hd.h"

/* The rates pass of the updated Lagrangian (seed 000 eq. 10-12): with g = V_j grad_i W_ij
 * (or a quadratic fit's weight G_ij), the velocity gradient's pair (v_j - v_i) (x) g into Lv and
 * the linear correction's moment g (x) (x_j - x_i) into B (L_i = B^-1). */
RY_HD static inline void ry_solid_gradient_add(double *Lv, const double *dv, const double *g,
                                               int dim) {
    for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) Lv[3 * a + b] += dv[a] * g[b];
}
RY_HD static inline void ry_solid_moment_add(double *B, const double *g, const double *d, int dim) {
    for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) B[3 * a + b] += g[a] * d[b];
}

/* The linear-corrected weights w_i = V_i V_j L_i g and w_j = V_i V_j L_j g (g = grad_i W_ij),
 * added to wi and wj. */
RY_HD static inline void ry_solid_ul_weights(const double *Li, const double *Lj, double vi,
                                             double vj, const double *g, double *wi, double *wj,
                                             int dim) {
    for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) {
            wi[a] += vi * vj * Li[3 * a + b] * g[b];
            wj[a] += vi * vj * Lj[3 * a + b] * g[b];
        }
}

/* The updated-Lagrangian pair into f (m_i dv_i/dt): mm = m_i m_j, fn = f_ij^n, pi = Pi_ij. */
RY_HD static inline void ry_solid_ul_pair(double *f, const double *si, const double *wi,
                                          const double *sj, const double *wj, const double *Ri,
                                          const double *Rj, const double *g, double mm, double fn,
                                          double pi, int dim) {
    for (int a = 0; a < dim; ++a) {
        double t = 0, u = 0;
        for (int b = 0; b < dim; ++b) {
            t += si[3 * a + b] * wi[b] + sj[3 * a + b] * wj[b];
            u += (Ri[3 * a + b] + Rj[3 * a + b]) * g[b];
        }
        f[a] += t + mm * (fn * u - pi * g[a]);
    }
}

/* The total-Lagrangian pair V_i A_i G_ij - V_j A_j G_ji into f. */
RY_HD static inline void ry_solid_tl_pair(double *f, const double *Ai, double vi, const double *gij,
                                          const double *Aj, double vj, const double *gji, int dim) {
    for (int a = 0; a < dim; ++a) {
        double t = 0;
        for (int b = 0; b < dim; ++b)
            t += vi * Ai[3 * a + b] * gij[b] - vj * Aj[3 * a + b] * gji[b];
        f[a] += t;
    }
}

/* The strain-gradient stresses' pair (docs/reference/solid.md, strain-gradient cell integration):
 * sum_k V_i Q_i,k H_ij,k - V_j Q_j,k H_ji,k into f, with Q_k (3 x 3 each, k < dim) the
 * stresses that act through the quadratic fit's second-derivative weights H (dim x dim per
 * pair, row k). */
RY_HD static inline void ry_solid_tl_strain_gradient_pair(double *f, const double *Qi, double vi,
                                                          const double *hij, const double *Qj,
                                                          double vj, const double *hji, int dim) {
    for (int a = 0; a < dim; ++a) {
        double t = 0;
        for (int k = 0; k < dim; ++k)
            for (int b = 0; b < dim; ++b)
                t += vi * Qi[9 * k + 3 * a + b] * hij[dim * k + b] -
                     vj * Qj[9 * k + 3 * a + b] * hji[dim * k + b];
        f[a] += t;
    }
}

/* The hourglass penalty c_ij e_ij into fh, from x_j - x_i (xji), X_j - X_i (Xji) and the
 * deformation gradients F_i, F_j. */
RY_HD static inline void ry_solid_tl_hourglass(double *fh, const double *xji, const double *Xji,
                                               const double *Fi, const double *Fj, double cij,
                                               int dim) {
    for (int a = 0; a < dim; ++a) {
        double e = xji[a];
        for (int b = 0; b < dim; ++b) e -= 0.5 * (Fi[3 * a + b] + Fj[3 * a + b]) * Xji[b];
        fh[a] += cij * e;
    }
}

#endif
