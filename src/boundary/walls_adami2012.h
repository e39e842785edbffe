/* The generalized wall boundary condition of Adami, Hu & Adams (2012), J. Comput. Phys. 231:
 * 7057, used by every fluid scheme with dummy wall particles (WCSPH, IISPH, MPS). A wall
 * particle w takes from the fluid particles f within its support, with weights W_wf (the
 * scheme's kernel, or the MPS weight function):
 *
 *   p_w  = sum_f (p_f + rho_f g . (x_w - x_f)) W_wf / sum_f W_wf               (eq. 27)
 *   v~_w = sum_f v_f W_wf / sum_f W_wf;  ghost velocity for no slip 2 v_w - v~_w (eq. 22-23)
 *
 * and the density from the equation of state at p_w (eq. 28; the scheme's). The pieces below
 * are the pair function (one fluid neighbour f added to the sums of wall w) and the finish (the
 * wall's values from its sums); the traversal (a neighbour-list row, a cached pair list, cell
 * ranges) and what a scheme does where a wall has no fluid neighbour are the scheme's. The
 * pieces (walls_adami2012_body.h) exist in double precision and, for the pair loops in floats,
 * in single precision under the same names with the suffix f (ry_adami_sumsf, ry_adami_headf,
 * ...). */
#ifndef RY_BOUNDARY_WALLS_ADAMI2012_H
#define RY_BOUNDARY_WALLS_ADAMI2012_H

#include "util/hd.h"

#define RY_C(x) ((RY_REAL)(x))
#define RY_REAL double
#define RY_ADAMI(name) name
#include "boundary/walls_adami2012_body.h"
#undef RY_ADAMI
#undef RY_REAL

#define RY_REAL float
#define RY_ADAMI(name) name##f
#include "boundary/walls_adami2012_body.h"
#undef RY_ADAMI
#undef RY_REAL
#undef RY_C

#endif
