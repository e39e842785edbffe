/* Free-surface tension in IISPH (the surface_tension section; docs/reference/iisph.md): the
 * potential model and CSF in force form as accelerations, CSF in pressure form as the Laplace jump
 * P_i = sigma kappa_i on the surface particles (a Dirichlet value of the pressure solve) with
 * the known part of their pressure force counted from a reference pressure. */
#include <string.h>

#include "schemes/iisph/iisph_internal.h"

/* Free-surface tension (the surface_tension section). The potential model and CSF in force form
 * add their accelerations. CSF in pressure form (docs/reference/iisph.md): each surface particle
 * (number density below st_beta delta0) takes the Laplace jump P_i = sigma kappa_i as its pressure
 * (a Dirichlet value, as in MPS), and its pressure force counts pressures from P_i, a^p_i =
 * -(1/m_i) sum_j ((p_i - P_i) / delta_i^2 + (p_j - P_i) / delta_j^2) grad_i W_ij, so a surface
 * particle at P_i feels only the pressure differences inside the liquid (the symmetric form would
 * push it out with P_i against the empty side). The part with P_i is known before the solve and
 * goes into the predicted velocity. The other particles ask for no expansion (their predicted
 * number density is taken as at least delta0). */
ry_status iisph_surface_tension(ry_sim *sim, iisph *s, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    RY_TRY(ry_st_work_ensure(&s->stw, n, err));
    double *P = s->stw.p;
    if (!ry_st_pressure_form(&s->st)) {
        double *a[3] = {P, P + n, P + 2 * n};
        memset(P, 0, 3 * n * sizeof *P);
        RY_TRY(ry_st_accelerate(&s->st, sim, a, err));
        for (size_t i = 0; i < n; ++i)
            for (int d = 0; d < dim; ++d) s->acc[3 * i + d] += a[d][i];
        return RY_OK;
    }
    for (size_t i = 0; i < n; ++i)
        s->stw.tag[i] = ps->kind[i] == RY_KIND_FLUID && s->delta[i] < s->st_beta * s->delta0;
    ry_st_laplace_pressure(&s->st, sim, s->stw.tag, 1, 2.1 * sim->dx, P);
    for (size_t i = 0; i < n; ++i)
        if (!s->stw.tag[i]) P[i] = 0.0;
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = s->pc.j; /* the pairs within the support */
    const size_t *end = s->pc.end;
    const double *cg = s->pc.g, *m = ps->f[RY_F_MASS], *delta = s->delta;
    /* The reference R_i the force counts pressures from: P_i at the surface, and beneath it the
     * mean Laplace jump of all the surface particles (for one drop: its jump). With 0 there,
     * a particle within a kernel's reach of the surface, short of neighbours on the empty side,
     * was pushed out by the liquid's pressure and the solve raised the pressure beneath the
     * surface to hold it: the drop at rest read 16 % above sigma / R. A reference that varies
     * along the surface (the kernel-weighted mean of the surface neighbours' P_j) made the
     * oscillating square unstable. A constant R adds no net force to a particle with a full
     * neighbourhood on a lattice, and between two particles beneath the surface its pair terms
     * are equal and opposite. */
    double *R = P + n; /* free after ry_st_laplace_pressure */
    double psum = 0, pcount = 0;
    for (size_t i = 0; i < n; ++i)
        if (s->stw.tag[i] && !ry_sim_is_halo(sim, i)) {
            psum += P[i];
            pcount += 1;
        }
    if (sim->par) {
        psum = sim->par->sum(sim, psum);
        pcount = sim->par->sum(sim, pcount);
    }
    const double pavg = pcount > 0 ? psum / pcount : 0.0;
    for (size_t i = 0; i < n; ++i)
        R[i] = s->stw.tag[i] ? P[i] : ps->kind[i] == RY_KIND_FLUID ? pavg : 0.0;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (R[i] == 0.0) continue;
        double a[3] = {0, 0, 0};
        const double di2 = 1.0 / (delta[i] * delta[i]);
        for (size_t q = off[i]; q < end[i]; ++q) {
            const uint32_t j = nb[q];
            const double f = di2 + (MOBILE[ps->kind[j]] ? 1.0 / (delta[j] * delta[j]) : di2);
            for (int d = 0; d < dim; ++d) a[d] += f * cg[3 * q + d];
        }
        for (int d = 0; d < dim; ++d) s->acc[3 * i + d] += R[i] * a[d] / m[i];
    }
    return RY_OK;
}
