/* The fluid pair term of WCSPH, written once and compiled in double precision (the
 * neighbour-list loop, wcsph_list.c) and in single precision (the cell-range loop,
 * wcsph_cells.c): wcsph_pair_body.h, included twice. For fluid particle i and a neighbour j
 * (fluid, outlet or wall) it gives the pair's share of
 *
 *   dv_i/dt   = -sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2 + Pi_ij) grad_i W_ij      (seed eq. 3.26)
 *               + 1/rho_i sum_j mu_ij L_ij (v_i - v~_j)            (Morris et al. 1997)
 *               + Monaghan (1994) wall repulsion
 *   drho_i/dt = rho_i sum_j V_j (v_i - v_j) . grad_i W_ij
 *               - 2 delta h c0 sum_j psi_ij L_ij  (Molteni & Colagrossi 2009; psi_ij =
 *               rho_j - rho_i, plus rho0 g . x_ij / c0^2 after Fourtakas et al. 2019)
 *   de_i/dt   = 1/2 sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2 + Pi_ij) (v_i - v~_j) . grad_i W_ij
 *
 * with the artificial viscosity of Monaghan (1992),
 *   Pi_ij = (-alpha c_ij mu_ij + beta mu_ij^2) / rho_ij,  mu_ij = h v_ij . x_ij / (r^2 +
 *   eta^2) for approaching pairs (0 otherwise), c_ij and rho_ij the pair's means,
 * and the Morris weight L_ij = V_j x_ij . grad_i W_ij / (r^2 + eta^2)
 * (physics/viscosity_morris1997.h). v~_j is the velocity viscous terms see: the ghost velocity
 * of a no-slip wall (boundary/walls_adami2012.h), v_j elsewhere. Equations:
 * docs/reference/wcsph.md.
 *
 * The view of a pair is three records: wc_pair_k (the run's constants), wc_pair_i (particle i)
 * and wc_pair_j (neighbour j), filled by the traversal from the field table (double) or from the
 * single-precision copy; densities enter as deviations from a reference density, so that
 * rho_j - rho_i keeps its digits in floats (the double-precision loop takes the reference 0).
 * The traversal supplies the separation x_ij, r^2 and the kernel factor fw = (dW/dr)/r
 * (grad_i W_ij = fw x_ij; 0 beyond the support), and sums what the pair function returns. */
#ifndef RY_SCHEMES_WCSPH_PAIR_H
#define RY_SCHEMES_WCSPH_PAIR_H

#include "physics/artificial_viscosity_monaghan1992.h"
#include "util/hd.h"

#define RY_C(x) ((RY_REAL)(x))

#define RY_REAL double
#define RY_PAIR(name) name##_d
#define RY_PAIR_AV ry_monaghan_pi
#include "schemes/wcsph/wcsph_pair_body.h"
#undef RY_PAIR_AV
#undef RY_PAIR
#undef RY_REAL

#define RY_REAL float
#define RY_PAIR(name) name##_f
#define RY_PAIR_AV ry_monaghan_pif
#include "schemes/wcsph/wcsph_pair_body.h"
#undef RY_PAIR_AV
#undef RY_PAIR
#undef RY_REAL
#undef RY_C

#endif
