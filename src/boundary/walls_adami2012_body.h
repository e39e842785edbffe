/* The body of walls_adami2012.h in the precision RY_REAL, its names passed through RY_ADAMI
 * (no include guard: included once per precision; constants are written RY_C(...), of type
 * RY_REAL). */

/* The sums of one wall particle: sum W, sum (p + head) W and sum v W. */
typedef struct RY_ADAMI(ry_adami_sums) {
    RY_REAL sw, sp, sv[3];
} RY_ADAMI(ry_adami_sums);

/* The hydrostatic head rho_f g . (x_w - x_f) of a pair, dxwf = x_w - x_f. */
RY_HD static inline RY_REAL RY_ADAMI(ry_adami_head)(const RY_REAL *g, const RY_REAL *dxwf, int dim,
                                                    RY_REAL rho_f) {
    RY_REAL gr = RY_C(0.0);
    for (int d = 0; d < dim; ++d) gr += g[d] * dxwf[d];
    return rho_f * gr;
}

/* Fluid neighbour f of weight w, pressure p_f and head (ry_adami_head) into the pressure
 * sums. */
RY_HD static inline void RY_ADAMI(ry_adami_add_pressure)(RY_ADAMI(ry_adami_sums) * s, RY_REAL w,
                                                         RY_REAL p_f, RY_REAL head) {
    s->sw += w;
    s->sp += (p_f + head) * w;
}

/* Fluid neighbour f of weight w and velocity v_f into the velocity sums (sw is counted by
 * ry_adami_add_pressure; ry_adami_add_weight where the pressure is not summed). */
RY_HD static inline void RY_ADAMI(ry_adami_add_velocity)(RY_ADAMI(ry_adami_sums) * s, RY_REAL w,
                                                         const RY_REAL *v_f, int dim) {
    for (int d = 0; d < dim; ++d) s->sv[d] += v_f[d] * w;
}
RY_HD static inline void RY_ADAMI(ry_adami_add_weight)(RY_ADAMI(ry_adami_sums) * s, RY_REAL w) {
    s->sw += w;
}

/* The wall pressure of eq. 27 (s->sw > 0). */
RY_HD static inline RY_REAL RY_ADAMI(ry_adami_pressure)(const RY_ADAMI(ry_adami_sums) * s) {
    return s->sp / s->sw;
}

/* Component d of the ghost velocity of eq. 22-23, 2 v_w - v~_w, from the wall's own velocity
 * v_w (s->sw > 0). */
RY_HD static inline RY_REAL RY_ADAMI(ry_adami_ghost_velocity)(const RY_ADAMI(ry_adami_sums) * s,
                                                              int d, RY_REAL v_w) {
    return RY_C(2.0) * v_w - s->sv[d] / s->sw;
}
