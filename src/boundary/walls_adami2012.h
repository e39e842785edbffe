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
 * ranges) and what a scheme does where a wall has no fluid neighbour are the scheme's. */
#ifndef RY_BOUNDARY_WALLS_ADAMI2012_H
#define RY_BOUNDARY_WALLS_ADAMI2012_H

#include "util/hd.h"

/* The sums of one wall particle: sum W, sum (p + head) W and sum v W. */
typedef struct ry_adami_sums {
    double sw, sp, sv[3];
} ry_adami_sums;

/* The hydrostatic head rho_f g . (x_w - x_f) of a pair, dxwf = x_w - x_f. */
RY_HD static inline double ry_adami_head(const double *g, const double *dxwf, int dim,
                                         double rho_f) {
    double gr = 0;
    for (int d = 0; d < dim; ++d) gr += g[d] * dxwf[d];
    return rho_f * gr;
}

/* Fluid neighbour f of weight w, pressure p_f and head (ry_adami_head) into the pressure
 * sums. */
RY_HD static inline void ry_adami_add_pressure(ry_adami_sums *s, double w, double p_f,
                                               double head) {
    s->sw += w;
    s->sp += (p_f + head) * w;
}

/* Fluid neighbour f of weight w and velocity v_f into the velocity sums (sw is counted by
 * ry_adami_add_pressure; ry_adami_add_weight where the pressure is not summed). */
RY_HD static inline void ry_adami_add_velocity(ry_adami_sums *s, double w, const double *v_f,
                                               int dim) {
    for (int d = 0; d < dim; ++d) s->sv[d] += v_f[d] * w;
}
RY_HD static inline void ry_adami_add_weight(ry_adami_sums *s, double w) {
    s->sw += w;
}

/* The wall pressure of eq. 27 (s->sw > 0). */
RY_HD static inline double ry_adami_pressure(const ry_adami_sums *s) {
    return s->sp / s->sw;
}

/* Component d of the ghost velocity of eq. 22-23, 2 v_w - v~_w, from the wall's own velocity
 * v_w (s->sw > 0). */
RY_HD static inline double ry_adami_ghost_velocity(const ry_adami_sums *s, int d, double v_w) {
    return 2.0 * v_w - s->sv[d] / s->sw;
}

#endif
