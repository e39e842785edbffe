/* The Laplacian of MPS (Koshizuka & Oka 1996, Nucl. Sci. Eng. 123: 421; seed 003 eq. 7-8),
 * used by the MPS pressure Poisson equation, its explicit and implicit viscosity:
 *
 *   <lap f>_i = 2d / (lambda n0) sum_j (f_j - f_i) w_ij,
 *
 * with w the MPS weight (ry_mps_weight_tamai), n0 and lambda the full lattice's number density
 * and mean squared distance (ry_mps_lattice) at the Laplacian's radius. The pair weight is the
 * scheme's (w_ij, times nu_ij and the wall factor for the viscosity); this is its coefficient. */
#ifndef RY_PHYSICS_LAPLACIAN_MPS_KOSHIZUKA1996_H
#define RY_PHYSICS_LAPLACIAN_MPS_KOSHIZUKA1996_H

#include "util/hd.h"

/* 2d / (lambda n0). */
RY_HD static inline double ry_mps_laplacian_coefficient(int dim, double lambda, double n0) {
    return 2.0 * dim / (lambda * n0);
}

#endif
