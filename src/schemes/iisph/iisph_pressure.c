/* The pressure of IISPH: the pairs of the solve, the predicted number density, d_ii and a_ii,
 * the relaxed Jacobi iterations on the pressure Poisson equation (Ihmsen, Cornelis, Solenthaler,
 * Horvath & Teschner (2014), IEEE TVCG 20: 426, eq. 12-17, in the number-density form of Hu &
 * Adams (2006), J. Comput. Phys. 213: 844), the light phase's own tolerance, and the pressure
 * force a^p_i = -(1/m_i) sum_j (p_i / delta_i^2 + p_j / delta_j^2) grad_i W_ij (Hu & Adams 2006,
 * eq. 8) with the kick v = v* + dt a^p. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "schemes/iisph/iisph_internal.h"
#include "schemes/iisph/iisph_pair.h"

/* The pairs of the solve's iterations (grad_list), once per step: those pair_skip keeps with a
 * non-zero gradient, in a compact copy. (Read in place, from the cache's rows with the gaps of
 * the list's skin between them, the iterations ran slower: each stream fetches the gaps.) */
ry_status iisph_grad_list_build(ry_sim *sim, iisph *s, ry_error *err) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = s->pc.j; /* the pairs within the support */
    const size_t *end = s->pc.end;
    const uint8_t *kind = ps->kind;
    const double *cg = s->pc.g;
    grad_list *l = &s->gl;
    if (l->cap_n < n + 1) {
        const size_t c = n + n / 4 + 16;
        int ok = 1;
        RY_IISPH_GROW(l->off, c + 1, ok);
        RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (pressure pairs)");
        l->cap_n = c;
    }
#define RY_GRAD_NONZERO(G) ((G)[0] != 0 || (G)[1] != 0 || (G)[2] != 0)
#pragma omp parallel for schedule(dynamic, 256)
    for (size_t i = 0; i < n; ++i) {
        size_t c = 0;
        if (MOBILE[kind[i]])
            for (size_t q = off[i]; q < end[i]; ++q)
                c += RY_GRAD_NONZERO(cg + 3 * q) && !pair_skip(s, i, nb[q]);
        l->off[i + 1] = c;
    }
    l->off[0] = 0;
    for (size_t i = 0; i < n; ++i) l->off[i + 1] += l->off[i];
    const size_t ne = l->off[n];
    if (l->cap_e < ne) {
        const size_t c = ne + ne / 4 + 16;
        int ok = 1;
        RY_IISPH_GROW(l->j, c, ok);
        RY_IISPH_GROW(l->g, 3 * c, ok);
        RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (pressure pairs)");
        l->cap_e = c;
    }
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        size_t e = l->off[i];
        if (!MOBILE[kind[i]]) continue;
        for (size_t q = off[i]; q < end[i]; ++q) {
            const double *G = cg + 3 * q;
            if (!RY_GRAD_NONZERO(G) || pair_skip(s, i, nb[q])) continue;
            l->j[e] = nb[q];
            for (int d = 0; d < 3; ++d) l->g[3 * e + d] = G[d];
            e++;
        }
    }
#undef RY_GRAD_NONZERO
    return RY_OK;
}
/* p_j / delta_j^2 of the pair (i, j): a mobile j's own (pq, p / delta^2 of each mobile
 * particle), a wall's extrapolated pressure with the volume of i, di2 = delta_i^2 (a light row:
 * the walls and the heavy particles with the light phase's extrapolation pl);
 * neighbour_pressure_sum sums it times grad_i W_ij over the pairs of row i, inlined with a
 * literal dim so that the sums stay in registers. */
static inline double neighbour_pressure(const iisph *s, const uint8_t *kind, const double *p,
                                        const double *pq, double di2, size_t i, uint32_t j) {
    if (pair_force_mobile(s, kind, i, j)) return pq[j];
    const double *pw = s->light_on && s->lt[i] ? s->pl : p;
    return pw[j] / di2;
}

static inline void neighbour_pressure_sum(const iisph *s, const uint8_t *kind, const double *p,
                                          size_t i, double *a, int dim) {
    const grad_list *gl = &s->gl;
    const double di2 = s->delta[i] * s->delta[i];
    for (size_t e = gl->off[i]; e < gl->off[i + 1]; ++e) {
        iisph_pair_sum(a, neighbour_pressure(s, kind, p, s->pq, di2, i, gl->j[e]), gl->g + 3 * e,
                       dim);
    }
}

/* S_i = sum_j d_ij p_j = -(dt^2 / m_i) sum_j p_j / delta_j^2 grad_i W_ij (row i of a mobile
 * particle), and the part of D_i that is i's own, d_ii p_i + S_i, which the Jacobi sums of i's
 * neighbours read. */
static inline void pressure_sum_row(const iisph *s, const uint8_t *kind, const double *m,
                                    const double *p, double dt2, size_t i, double *out, double *djp,
                                    int dim) {
    double a[3] = {0, 0, 0};
    neighbour_pressure_sum(s, kind, p, i, a, dim);
    for (int d = 0; d < dim; ++d) a[d] *= -dt2 / m[i];
    for (int d = 0; d < 3; ++d) {
        out[d] = a[d];
        djp[d] = s->dii[3 * i + d] * p[i] + a[d];
    }
}

/* pq = p / delta^2 of every mobile particle (0 for the others). */
static void pressure_over_delta2(const ry_particles *ps, iisph *s, const double *p) {
    const double *delta = s->delta;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < ps->n; ++i)
        s->pq[i] = MOBILE[ps->kind[i]] ? p[i] / (delta[i] * delta[i]) : 0.0;
}

static void pressure_sums(ry_sim *sim, iisph *s, const double *p, double dt2) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const uint8_t *kind = ps->kind;
    const double *m = ps->f[RY_F_MASS];
    pressure_over_delta2(ps, s, p);
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (!MOBILE[kind[i]]) continue; /* (zeros, iisph_pressure_solve) */
        double *out = s->sum + 3 * i, *djp = s->djp + 3 * i;
        if (dim == 3)
            pressure_sum_row(s, kind, m, p, dt2, i, out, djp, 3);
        else
            pressure_sum_row(s, kind, m, p, dt2, i, out, djp, 2);
    }
}

/* The Jacobi update's sum over the pairs of fluid particle i: sum_j (S_i - D_j) . grad_i W_ij,
 * with D_j the part of j's sum without p_i (inlined with a literal dim). */
static inline double jacobi_rest(const iisph *s, const grad_list *gl, const uint8_t *kind,
                                 const double *m, const double *p, double dt2, size_t i, int dim) {
    const double *si = s->sum + 3 * i;
    const double di2 = s->delta[i] * s->delta[i];
    double rest = 0;
    double mlast = NAN, clast = 0; /* d_ji p_i for the last mass seen (one per material) */
    for (size_t e = gl->off[i]; e < gl->off[i + 1]; ++e) {
        const uint32_t j = gl->j[e];
        const double *G = gl->g + 3 * e;
        double t = iisph_pair_jacobi(si, G, dim);
        if (MOBILE[kind[j]]) {
            /* D_j without the part from p_i: d_jj p_j + S_j - d_ji p_i (a heavy j of a light
             * row: none, j does not see i) */
            double cji = 0.0;
            if (pair_force_mobile(s, kind, i, j)) {
                if (m[j] != mlast) {
                    mlast = m[j];
                    clast = dt2 / (mlast * di2) * p[i];
                }
                cji = clast;
            }
            iisph_pair_jacobi_mobile(&t, s->djp + 3 * j, cji, G, dim);
        }
        rest += t;
    }
    return rest;
}

/* Row i's sums of the predicted number density and of d_ii (inlined with a literal dim, so
 * that the velocities stay in registers). */
static inline __attribute__((always_inline)) void predict_row(const grad_list *gl,
                                                              const double *const v[3], size_t i,
                                                              double *dv, double *dii,
                                                              const int dim) {
    double vi[3] = {0, 0, 0};
    for (int d = 0; d < dim; ++d) vi[d] = v[d][i];
    for (size_t e = gl->off[i]; e < gl->off[i + 1]; ++e) {
        const uint32_t j = gl->j[e];
        double vj[3] = {0, 0, 0};
        for (int d = 0; d < dim; ++d) vj[d] = v[d][j];
        iisph_pair_predict(dv, dii, vi, vj, gl->g + 3 * e, dim);
    }
}

/* The pressure Poisson equation by relaxed Jacobi; returns the iterations. */
long iisph_pressure_solve(ry_sim *sim, iisph *s, double dt) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const uint8_t *kind = ps->kind;
    const double *m = ps->f[RY_F_MASS], *delta = s->delta;
    const double dt2 = dt * dt, d0 = s->delta0;
    const grad_list *gl = &s->gl;
    double *p = ps->f[RY_F_P], *pnew = s->pnew;
    /* The Laplace jump of the surface particles (CSF, pressure form): their pressure. */
    const double *plow = ry_st_pressure_form(&s->st) ? s->stw.p : NULL;
    const double *v[3];
    for (int d = 0; d < 3; ++d) v[d] = ps->f[RY_F_VX + (d < dim ? d : 0)];
        /* Predicted number density from the predicted velocities (in the velocity field), the
         * diagonal d_ii and a_ii. */
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (!MOBILE[kind[i]]) continue;
        double dv = 0, dii[3] = {0, 0, 0};
        const double di2 = delta[i] * delta[i];
        if (dim == 3)
            predict_row(gl, v, i, &dv, dii, 3);
        else
            predict_row(gl, v, i, &dv, dii, 2);
        /* Only compression is corrected: an expanded particle (free surface, splash) asks for
         * no tension, which the non-negative pressure could not give. */
        s->dstar[i] = delta[i] + dt * dv;
        /* With the Laplace jump on the surface particles the others ask for no expansion: the
         * deficit of the layers under the surface would pull their pressure under the jump. */
        if (plow && !s->stw.tag[i]) s->dstar[i] = fmax(s->dstar[i], d0);
        for (int d = 0; d < 3; ++d) s->dii[3 * i + d] = -dt2 / (m[i] * di2) * dii[d];
    }
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (!MOBILE[kind[i]]) continue;
        const double *dii = s->dii + 3 * i;
        const double di2 = delta[i] * delta[i];
        double a = 0;
        for (size_t e = gl->off[i]; e < gl->off[i + 1]; ++e) {
            const uint32_t j = gl->j[e];
            /* - d_ji . grad_i W_ij, d_ji = -(dt^2 / m_j) grad_j W_ji / delta_i^2 */
            const int mobile = pair_force_mobile(s, kind, i, j);
            iisph_pair_aii(&a, dii, gl->g + 3 * e, mobile, mobile ? dt2 / (m[j] * di2) : 0.0, dim);
        }
        s->aii[i] = a;
    }
    /* Warm start. */
    for (size_t i = 0; i < n; ++i)
        if (kind[i] == RY_KIND_FLUID) p[i] *= s->warm;
    /* The error is averaged over each phase (heavy and light) apart when the light phase is a
     * boundary: their two solves are independent, and the light phase's many particles would
     * otherwise outvote the heavy one's. */
    double nfluid = 0, nlight = 0;
    for (size_t i = 0; i < n; ++i)
        if (kind[i] == RY_KIND_FLUID && !ry_sim_is_halo(sim, i)) {
            nfluid += !s->lt[i];
            nlight += s->lt[i];
        }
    /* A distributed run: a pass that reads its neighbours' results of the pass before gets
     * the halo copies' values from their owners first; the error is summed over all ranks. */
    if (sim->par) {
        sim->par->sync(sim, s->dii, 3, 0);
        sim->par->sync(sim, s->aii, 1, 0);
        sim->par->sync(sim, s->dstar, 1, 0);
        nfluid = sim->par->sum(sim, nfluid);
        nlight = sim->par->sum(sim, nlight);
    }
    /* What the sweeps leave alone: the sums of the particles that are not mobile and the
     * errors of those that are not fluid. */
    double *perr = s->perr;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        if (kind[i] != RY_KIND_FLUID) perr[i] = 0.0;
        if (MOBILE[kind[i]]) continue;
        for (int d = 0; d < 3; ++d) s->sum[3 * i + d] = s->djp[3 * i + d] = 0.0;
    }
    const double omega = s->omega;
    long it = 0;
    double avg = 0;
    while (it < s->max_iter) {
        iisph_wall_extrapolate(&s->wm, p, p);
        if (sim->par) sim->par->sync(sim, p, 1, 0);
        if (s->light_on) {
            iisph_wall_extrapolate(&s->wml, p, s->pl);
            if (sim->par) sim->par->sync(sim, s->pl, 1, 0);
        }
        pressure_sums(sim, s, p, dt2);
        if (sim->par) {
            sim->par->sync(sim, s->sum, 3, 0);
            sim->par->sync(sim, s->djp, 3, 0);
        }
#pragma omp parallel for schedule(dynamic, 64)
        for (size_t i = 0; i < n; ++i) {
            if (kind[i] != RY_KIND_FLUID) continue; /* (its pressure stays, its error is 0) */
            const double rest = dim == 3   ? jacobi_rest(s, gl, kind, m, p, dt2, i, 3)
                                : dim == 2 ? jacobi_rest(s, gl, kind, m, p, dt2, i, 2)
                                           : jacobi_rest(s, gl, kind, m, p, dt2, i, dim);
            const double aii = s->aii[i];
            const double err = aii * p[i] + rest + s->dstar[i] - d0; /* delta - delta_0 now */
            double pn = 0;
            if (fabs(aii) > 1e-300)
                pn = (1 - omega) * p[i] + omega * (d0 - s->dstar[i] - rest) / aii;
            /* CSF in pressure form: a surface particle's pressure is its Laplace jump. */
            const int dirichlet = plow && s->stw.tag[i];
            const double pmin = dirichlet ? plow[i] : 0.0;
            pnew[i] = dirichlet ? pmin : pn > 0 ? pn : 0;
            /* Ihmsen's average density error: clamped (free-surface) particles count only when
             * compressed. */
            perr[i] = (p[i] > pmin || err > 0) && !ry_sim_is_halo(sim, i) ? err : 0.0;
        }
        /* summed in the particles' order, not by the threads' shares: the same bits, and so
         * the same iterations, on any thread count */
        double esum = 0, lsum = 0;
        for (size_t i = 0; i < n; ++i) {
            if (s->lt[i])
                lsum += perr[i];
            else
                esum += perr[i];
        }
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; ++i)
            if (kind[i] == RY_KIND_FLUID) p[i] = pnew[i];
        if (sim->par) {
            sim->par->sync(sim, p, 1, 0);
            esum = sim->par->sum(sim, esum);
            if (s->light_on) lsum = sim->par->sum(sim, lsum);
        }
        ++it;
        avg = nfluid > 0 ? esum / (nfluid * d0) : 0.0;
        const double lavg = nlight > 0 ? lsum / (nlight * d0) : 0.0;
        /* the light phase is held to its own tolerance; the error reported is the larger of
         * the heavy phase's and the light phase's scaled to the heavy tolerance */
        if (fabs(lavg) * s->tol > fabs(avg) * s->light_tol) avg = lavg * s->tol / s->light_tol;
        if (it >= s->min_iter && fabs(avg) <= s->tol) break;
    }
    s->error_last = avg;
    return it;
}

/* The pressure acceleration with the final pressures (Hu & Adams 2006, eq. 8) and the kick
 * v = v* + dt a^p; the total acceleration (with the non-pressure part in s->acc) into the
 * acceleration field. *vmax2_out and *amax2_out receive the largest |v|^2 and |a|^2 of the mobile
 * particles (owned ones, over all processes). */
void iisph_pressure_force(ry_sim *sim, iisph *s, double dt, double *vmax2_out, double *amax2_out) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const grad_list *gl = &s->gl;
    const double *m = ps->f[RY_F_MASS], *delta = s->delta, *p = ps->f[RY_F_P];
    double vmax2 = 0, amax2 = 0;
    pressure_over_delta2(ps, s, p); /* of the final pressures */
    const double *pq = s->pq;
#pragma omp parallel for schedule(dynamic, 64) reduction(max : vmax2, amax2)
    for (size_t i = 0; i < n; ++i) {
        if (!MOBILE[ps->kind[i]]) continue;
        const double di2 = delta[i] * delta[i], pi = pq[i];
        double a[3] = {0, 0, 0};
        for (size_t e = gl->off[i]; e < gl->off[i + 1]; ++e)
            iisph_pair_pressure(a, pi, neighbour_pressure(s, ps->kind, p, pq, di2, i, gl->j[e]),
                                gl->g + 3 * e, dim);
        double a2 = 0, v2 = 0;
        for (int d = 0; d < dim; ++d) {
            a[d] /= m[i];
            ps->f[RY_F_VX + d][i] += dt * a[d];
            const double at = a[d] + s->acc[3 * i + d];
            ps->f[RY_F_AX + d][i] = at;
            a2 += at * at;
            v2 += ps->f[RY_F_VX + d][i] * ps->f[RY_F_VX + d][i];
        }
        if (ry_sim_is_halo(sim, i)) continue; /* its neighbours beyond the halo are missing */
        amax2 = fmax(amax2, a2);
        vmax2 = fmax(vmax2, v2);
    }
    if (sim->par) {
        amax2 = sim->par->max(sim, amax2);
        vmax2 = sim->par->max(sim, vmax2);
    }
    *vmax2_out = vmax2;
    *amax2_out = amax2;
}
