/* The laminar viscous term of Morris, Fox & Zhu (1997), J. Comput. Phys. 136: 214, the SPH
 * Laplacian built from the kernel's first derivative, used by WCSPH (explicit) and IISPH
 * (scheme.viscous_form: morris, explicit or by backward Euler):
 *
 *   (1/rho div(mu grad v))_i = 1/rho_i sum_j mu_ij L_ij (v_i - v_j),
 *   L_ij = V_j x_ij . grad_i W_ij / (r_ij^2 + eta^2),  eta^2 = 0.01 h^2,
 *
 * with mu_ij = mu_i + mu_j in the paper (WCSPH) or twice the harmonic mean 4 mu_i mu_j /
 * (mu_i + mu_j), which vanishes next to an inviscid fluid (IISPH). x_ij . grad_i W_ij = r dW/dr
 * is negative; in the backward-Euler form (IISPH) the pair enters the matrix of m_i v_i with
 * the coefficient -dt V_i mu_ij L_ij >= 0, symmetric. The same weight L_ij carries the density
 * diffusion of Molteni & Colagrossi (2009), -2 delta h c0 sum_j (rho_j - rho_i) L_ij (WCSPH).
 * The pieces below are the pair weight and coefficient; the traversal and the mean are the
 * scheme's. */
#ifndef RY_PHYSICS_VISCOSITY_MORRIS1997_H
#define RY_PHYSICS_VISCOSITY_MORRIS1997_H

#include "util/hd.h"

/* eta^2 = RY_MORRIS_ETA2 h^2 keeps the pair weight finite as r -> 0. */
#define RY_MORRIS_ETA2 0.01

RY_HD static inline double ry_morris_eta2(double h) {
    return RY_MORRIS_ETA2 * h * h;
}

/* The pair weight L_ij from the volume V_j, x_ij . grad_i W_ij and 1 / (r_ij^2 + eta^2) (the
 * schemes share that inverse with Monaghan's artificial viscosity). */
RY_HD static inline double ry_morris_weight(double vol_j, double xgradw, double inv_r2eta2) {
    return xgradw * inv_r2eta2 * vol_j;
}

/* The pair's viscous coefficient mu_ij L_ij: particle i's acceleration gains
 * coefficient (v_i - v_j) / rho_i. */
RY_HD static inline double ry_morris_coefficient(double mu_ij, double weight) {
    return mu_ij * weight;
}

/* Twice the harmonic mean of two viscosities (0 where either is 0). */
RY_HD static inline double ry_morris_mu_harmonic2(double mu_i, double mu_j) {
    return mu_i + mu_j > 0 ? 4.0 * mu_i * mu_j / (mu_i + mu_j) : 0.0;
}

#endif
