/* The pair term of the transport-velocity formulation of Adami, Hu & Adams (2013), J. Comput.
 * Phys. 241: 292, eq. 8 and 13 (scheme.transport_velocity; docs/reference/wcsph.md): a momentum
 * equation of its own, not the seed's (wcsph_pair.h), so a pair function of its own. For fluid
 * particle i and neighbour j (fluid or wall), with V = m / rho and grad_i W_ij = fw x_ij,
 *
 *   m_i dv_i/dt = sum_j (V_i^2 + V_j^2) [ -p~_ij grad_i W_ij
 *                   + 1/2 (A_i + A_j) . grad_i W_ij + eta_ij (v_i - v~_j) fw ]       (eq. 8)
 *   m_i dv~_i/dt - m_i dv_i/dt = -p_b sum_j (V_i^2 + V_j^2) grad_i W_ij             (eq. 13)
 *
 * with p~_ij = (rho_j p_i + rho_i p_j) / (rho_i + rho_j), eta_ij = 2 mu_i mu_j / (mu_i + mu_j)
 * (a wall takes the fluid's viscosity), the extra stress A = rho v (v~ - v) (zero on walls),
 * v~_j the velocity viscous terms see (the ghost velocity of a no-slip wall), and the wall
 * repulsion of Monaghan (1994) of wcsph_pair.h. The traversal supplies x_ij, r^2 and fw
 * and sums the pair's shares of the two sums; double precision (the neighbour-list loop). */
#ifndef RY_SCHEMES_WCSPH_TVF_PAIR_H
#define RY_SCHEMES_WCSPH_TVF_PAIR_H

#include "schemes/wcsph/wcsph_pair.h"
#include "util/hd.h"

/* Particle i (or j: the same record). */
typedef struct wc_tvf_rec {
    double v[3];  /* velocity */
    double vg[3]; /* velocity viscous terms see (j) */
    double dv[3]; /* v~ - v (0 on walls) */
    double rho, p, mu, vol2, mass;
    double fluid; /* 1 fluid, 0 wall */
    double visc;  /* viscous coupling: 1, or the wall's factor */
} wc_tvf_rec;

/* The pair's shares: a (of m_i dv_i/dt before gravity) and b (of sum_j (V_i^2 + V_j^2)
 * grad_i W_ij, the background-pressure term). */
typedef struct wc_tvf_out {
    double a[3], b[3];
} wc_tvf_out;

/* The pair term; rep_r02 and rep_d: the repulsion's radius squared and strength. */
RY_HD static inline wc_tvf_out wc_tvf_pair(const wc_tvf_rec *I, const wc_tvf_rec *J,
                                           const double *dx, double r2, double fw, int dim,
                                           double rep_r02, double rep_d) {
    const double vv = I->vol2 + J->vol2;
    const double pij = (J->rho * I->p + I->rho * J->p) / (I->rho + J->rho);
    const double muj = J->fluid * J->mu + (1.0 - J->fluid) * I->mu;
    const double etaij = (I->mu + muj) > 0 ? 2.0 * I->mu * muj / (I->mu + muj) : 0.0;
    /* (A_i + A_j)/2 . grad W; walls carry no extra stress. */
    double adi = 0, adj = 0;
    for (int d = 0; d < dim; ++d) {
        adi += I->dv[d] * dx[d];
        adj += J->dv[d] * dx[d];
    }
    adi *= fw;
    adj *= fw * J->fluid;
    const double fr =
        wc_repulsion_d(J->fluid == 0.0 && r2 < rep_r02, r2, rep_r02, rep_d) * I->mass / vv;
    wc_tvf_out o = {{0, 0, 0}, {0, 0, 0}};
    for (int d = 0; d < dim; ++d) {
        const double vij = I->v[d] - J->vg[d];
        double f = -pij * fw * dx[d] + fr * dx[d];
        f += 0.5 * (I->rho * I->v[d] * adi + J->rho * J->v[d] * adj);
        f += J->visc * etaij * vij * fw; /* eta_ij v_ij (1/r) dW/dr */
        o.a[d] = vv * f;
        o.b[d] = vv * fw * dx[d];
    }
    return o;
}

#endif
