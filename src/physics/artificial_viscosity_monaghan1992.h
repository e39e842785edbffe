/* The artificial viscosity of Monaghan (1992), Annu. Rev. Astron. Astrophys. 30: 543 (seed 001
 * eq. 3.50-3.51), used by WCSPH (both pair loops) and the updated-Lagrangian SPH solid:
 *
 *   Pi_ij = (-alpha c_ij mu_ij + beta mu_ij^2) / rho_ij  for approaching pairs (v_ij . x_ij < 0),
 *   mu_ij = h v_ij . x_ij / (r_ij^2 + eta^2),  eta^2 = 0.01 h^2,
 *
 * 0 for receding pairs, with c_ij and rho_ij the pair's mean sound speed and density. It enters
 * the momentum equation as -m_j Pi_ij grad_i W_ij. The pair function is written once over
 * RY_REAL (artificial_viscosity_monaghan1992_body.h) and exists in double precision
 * (ry_monaghan_pi) and single precision (ry_monaghan_pif). */
#ifndef RY_PHYSICS_ARTIFICIAL_VISCOSITY_MONAGHAN1992_H
#define RY_PHYSICS_ARTIFICIAL_VISCOSITY_MONAGHAN1992_H

#include "util/hd.h"

#define RY_C(x) ((RY_REAL)(x))
#define RY_REAL double
#define RY_AV(name) name
#include "physics/artificial_viscosity_monaghan1992_body.h"
#undef RY_AV
#undef RY_REAL

#define RY_REAL float
#define RY_AV(name) name##f
#include "physics/artificial_viscosity_monaghan1992_body.h"
#undef RY_AV
#undef RY_REAL
#undef RY_C

#endif
