/* The pair terms of the IISPH pressure (Ihmsen, Cornelis, Solenthaler, Horvath & Teschner
 * (2014), IEEE TVCG 20: 426, eq. 12-17, in the number-density form of Hu & Adams (2006),
 * J. Comput. Phys. 213: 844), for fluid particle i and neighbour j with G = grad_i W_ij (the
 * pair cache's gradient), number densities delta and masses m:
 *
 *   predicted number density  delta*_i = delta_i + dt sum_j (v_i - v_j) . G
 *   d_ii = -dt^2 / (m_i delta_i^2) sum_j G
 *   a_ii = sum_j (d_ii - d_ji) . G,  d_ji = -dt^2 / (m_j delta_i^2) grad_j W_ji (mobile j)
 *   S_i  = sum_j d_ij p_j = -dt^2 / m_i sum_j p_j / delta_j^2 G
 *   Jacobi: a_ii p_i + sum_j (S_i - D_j) . G = delta_0 - delta*_i,
 *           D_j = d_jj p_j + S_j - d_ji p_i (mobile j; 0 for walls)
 *   pressure acceleration  a_i = -1/m_i sum_j (p_i / delta_i^2 + p_j / delta_j^2) G  (eq. 8)
 *
 * so that dt^2 a_i = d_ii p_i + S_i and a_ii p_i + sum_j (S_i - D_j) . G = dt^2 sum_j
 * (a_i - a_j) . G, the change of delta_i the pressures give. The functions below are the pair
 * terms, each adding one neighbour to its sum (component by component, in the order of the
 * sums' loops); the traversals (the pairs of the solve, iisph_grad_list_build) and the
 * per-particle factors are iisph_pressure.c's. RY_HD: written in the common subset of C and
 * C++. */
#ifndef RY_SCHEMES_IISPH_PAIR_H
#define RY_SCHEMES_IISPH_PAIR_H

#include "util/hd.h"

/* (v_i - v_j) . G into *dv and G into the sum dii (d_ii without its factor). */
RY_HD static inline void iisph_pair_predict(double *dv, double *dii, const double *vi,
                                            const double *vj, const double *G, int dim) {
    for (int d = 0; d < dim; ++d) {
        *dv += (vi[d] - vj[d]) * G[d];
        dii[d] += G[d];
    }
}

/* (d_ii - d_ji) . G into *a; c_ji = dt^2 / (m_j delta_i^2) for a mobile j (`mobile`). */
RY_HD static inline void iisph_pair_aii(double *a, const double *dii, const double *G, int mobile,
                                        double c_ji, int dim) {
    double g2 = 0, dg = 0;
    for (int d = 0; d < dim; ++d) {
        dg += dii[d] * G[d];
        g2 += G[d] * G[d];
    }
    *a += dg;
    if (mobile) *a -= c_ji * g2;
}

/* f G into s (S_i before its factor -dt^2 / m_i, with f = p_j / delta_j^2). */
RY_HD static inline void iisph_pair_sum(double *s, double f, const double *G, int dim) {
    for (int d = 0; d < dim; ++d) s[d] += f * G[d];
}

/* The Jacobi term (S_i - D_j) . G in two parts: S_i . G for every neighbour, and for a mobile
 * j the part -D_j . G from u_j = d_jj p_j + S_j and cp_ji = dt^2 p_i / (m_j delta_i^2) (0 where
 * j does not see i), subtracted from t. */
RY_HD static inline double iisph_pair_jacobi(const double *s_i, const double *G, int dim) {
    double t = 0;
    for (int d = 0; d < dim; ++d) t += s_i[d] * G[d];
    return t;
}
RY_HD static inline void iisph_pair_jacobi_mobile(double *t, const double *u_j, double cp_ji,
                                                  const double *G, int dim) {
    for (int d = 0; d < dim; ++d) *t -= (u_j[d] - cp_ji * G[d]) * G[d];
}

/* -(p_i / delta_i^2 + p_j / delta_j^2) G into a (m_i a_i). */
RY_HD static inline void iisph_pair_pressure(double *a, double pi_d2, double pj_d2, const double *G,
                                             int dim) {
    for (int d = 0; d < dim; ++d) a[d] -= (pi_d2 + pj_d2) * G[d];
}

#endif
