/* The body of artificial_viscosity_monaghan1992.h in the precision RY_REAL, its names passed
 * through RY_AV (no include guard: included once per precision). */

/* Pi_ij from v_ij . x_ij, 1 / (r^2 + eta^2), h, the mean sound speed c_ij and the sum of the
 * densities rho_i + rho_j (rho_ij = half of it). */
RY_HD static inline RY_REAL RY_AV(ry_monaghan_pi)(RY_REAL vdx, RY_REAL inv_r2eta2, RY_REAL h,
                                                  RY_REAL c_ij, RY_REAL rho_sum, RY_REAL alpha,
                                                  RY_REAL beta) {
    const RY_REAL mu = h * (vdx < RY_C(0.0) ? vdx : RY_C(0.0)) * inv_r2eta2;
    return (-alpha * c_ij + beta * mu) * mu * RY_C(2.0) / rho_sum;
}
