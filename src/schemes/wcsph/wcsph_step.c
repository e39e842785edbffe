/* The time integration of WCSPH: the evaluation of all rates at the predicted state (walls,
 * pair loop, non-Newtonian stress, surface tension), the time step dt = min(CFL h / (c0 +
 * |v|max), 0.25 sqrt(h / |a|max), 0.125 h^2 / nu), and the kick-drift-kick leapfrog (second
 * order, one force evaluation per step), in a general form and in contiguous passes for the
 * cell-range loop's cases. */
#include <math.h>
#include <stdlib.h>

#include "core/guard_check.h"
#include "ryushi/collisions.h"
#include "schemes/wcsph/wcsph_internal.h"

/* Kinds that move under the fluid equations. */
static const int MOBILE[RY_KIND_COUNT] = {[RY_KIND_FLUID] = 1, [RY_KIND_OUTLET] = 1};

/* Picks the specialised pair loop. */
static ry_status fluid_forces(ry_sim *sim, wcsph *w, force_out *res, ry_error *err) {
    if (w->tvf) {
        wc_tvf_forces(sim, w, res);
        return RY_OK;
    }
    if (w->fast) {
        wc_fast_forces(sim, w, res);
        return RY_OK;
    }
    return wc_list_forces(sim, w, res, err);
}

/* In a distributed run: the largest acceleration and speed of the fluid over all ranks, from
 * owned particles only (a halo particle's rates lack the neighbours beyond the halo). */
static void global_maxima(ry_sim *sim, force_out *res) {
    const ry_particles *ps = &sim->ps;
    double a2 = 0, v2 = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || ry_sim_is_halo(sim, i)) continue;
        double a = 0, v = 0;
        for (int d = 0; d < sim->dim; ++d) {
            a += ps->f[RY_F_AX + d][i] * ps->f[RY_F_AX + d][i];
            v += ps->f[RY_F_VX + d][i] * ps->f[RY_F_VX + d][i];
        }
        a2 = a > a2 ? a : a2;
        v2 = v > v2 ? v : v2;
    }
    res->amax2 = sim->par->max(sim, a2);
    res->vmax2 = sim->par->max(sim, v2);
}

/* Non-Newtonian materials: velocity gradient, viscosity and stress divergence at the current
 * state (sph_rheology.h); walls enter with the velocity the viscous terms give them. */
static ry_status rheology_rates(ry_sim *sim, wcsph *w, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    if (w->vol_cap < n) {
        double *v = realloc(w->vol, n * sizeof *v);
        RY_CHECK(err, v != NULL, RY_ERR_NOMEM, "out of memory (%zu particles)", n);
        w->vol = v;
        w->vol_cap = n;
    }
    for (size_t i = 0; i < n; ++i) w->vol[i] = ps->f[RY_F_MASS][i] / ps->f[RY_F_RHO][i];
    RY_TRY(ry_pair_cache_fill(&w->pc, sim, MOBILE, err));
    const double *vg[3];
    for (int d = 0; d < 3; ++d) vg[d] = ps->f[w->f_vg[d]];
    return ry_sph_rheo_rates(&w->rheo, sim, &w->pc, MOBILE, w->vol,
                             w->wall == WALL_NO_SLIP ? vg : NULL, err);
}

/* Adds the polymer stress divergence to the fluid's acceleration. */
static void polymer_forces(ry_sim *sim, const wcsph *w, force_out *res) {
    ry_particles *ps = &sim->ps;
    double amax2 = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (!MOBILE[ps->kind[i]]) continue;
        double a2 = 0;
        for (int d = 0; d < sim->dim; ++d) {
            ps->f[RY_F_AX + d][i] += w->rheo.acc[3 * i + d];
            a2 += ps->f[RY_F_AX + d][i] * ps->f[RY_F_AX + d][i];
        }
        amax2 = fmax(amax2, a2);
    }
    res->amax2 = amax2;
}

/* Free-surface tension (docs/reference/wcsph.md, "Surface tension"): the surface_tension section as
 * in MPS and IISPH, on the neighbour-list loop. The potential model and CSF in force form add their
 * accelerations. CSF in pressure form: the surface particles (kernel sum below st_beta times the
 * lattice's) take the Laplace jump P_i = sigma kappa_i as their pressure instead of the equation
 * of state's, and their pressure force counts pressures from P_i:
 *   a_i = -sum_j m_j ((p_i - P_i) / rho_i^2 + (p_j - P_i) / rho_j^2) grad_i W_ij,
 * the symmetric form plus P_i sum_j m_j (1/rho_i^2 + 1/rho_j^2) grad_i W_ij (st_forces). With
 * the pressure form the artificial repulsion of MPS is on by default (scheme.repulsion). */

/* CSF in pressure form: the surface particles and their Laplace jump, which replaces their
 * pressure. */
static ry_status st_laplace(ry_sim *sim, wcsph *w, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    RY_TRY(ry_st_work_ensure(&w->stw, n, err));
    const double w0 = sim->kernel.norm * ry_kernel_shape(sim->kernel.type, 0.0);
    const double rad = sim->kernel.radius;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        double sw = w0;
        if (ps->kind[i] == RY_KIND_FLUID)
            for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
                const uint32_t j = sim->nl.j[q];
                if (ps->kind[j] == RY_KIND_SOLID) continue;
                double dx[3] = {0, 0, 0}, r2 = 0;
                for (int d = 0; d < sim->dim; ++d)
                    dx[d] = ps->f[RY_F_X + d][j] - ps->f[RY_F_X + d][i];
                ry_box_min_image(&sim->box, dx);
                for (int d = 0; d < sim->dim; ++d) r2 += dx[d] * dx[d];
                if (r2 < rad * rad) sw += ry_kernel_w(&sim->kernel, sqrt(r2));
            }
        w->stw.tag[i] = ps->kind[i] == RY_KIND_FLUID && sw < w->st_beta * w->st_w0;
    }
    double *P = w->stw.p;
    ry_st_laplace_pressure(&w->st, sim, w->stw.tag, 1, 2.1 * sim->dx, P);
    for (size_t i = 0; i < n; ++i) {
        if (!w->stw.tag[i])
            P[i] = 0.0;
        else
            ps->f[RY_F_P][i] = P[i];
    }
    return RY_OK;
}

/* The surface-tension accelerations, added to the fluid's (RY_F_AX). */
static ry_status st_forces(ry_sim *sim, wcsph *w, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    if (!ry_st_pressure_form(&w->st)) {
        double *a[3];
        for (int d = 0; d < 3; ++d) a[d] = ps->f[RY_F_AX + (d < dim ? d : 0)];
        return ry_st_accelerate(&w->st, sim, a, err);
    }
    const double *P = w->stw.p, *m = ps->f[RY_F_MASS], *rho = ps->f[RY_F_RHO];
    const double rad = sim->kernel.radius;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (P[i] == 0.0) continue; /* not a surface particle */
        double a[3] = {0, 0, 0};
        const double ri2 = 1.0 / (rho[i] * rho[i]);
        for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
            const uint32_t j = sim->nl.j[q];
            if (ps->kind[j] == RY_KIND_SOLID) continue;
            double dx[3] = {0, 0, 0}, r2 = 0;
            for (int d = 0; d < dim; ++d) dx[d] = ps->f[RY_F_X + d][i] - ps->f[RY_F_X + d][j];
            ry_box_min_image(&sim->box, dx);
            for (int d = 0; d < dim; ++d) r2 += dx[d] * dx[d];
            if (r2 >= rad * rad || r2 <= 0) continue;
            const double r = sqrt(r2), g = ry_kernel_dwdr(&sim->kernel, r) / r;
            const double f = m[j] * (ri2 + 1.0 / (rho[j] * rho[j])) * g;
            for (int d = 0; d < dim; ++d) a[d] += f * dx[d];
        }
        for (int d = 0; d < dim; ++d) ps->f[RY_F_AX + d][i] += P[i] * a[d];
    }
    return RY_OK;
}

/* The scheme's buffers (ry_scheme_type.bytes). */
size_t wc_bytes(const void *state) {
    const wcsph *w = state;
    const size_t nr = w->rng_cap * (2 * (size_t)w->nrange * sizeof(uint32_t) + 1);
    return w->pack_cap * PK_STRIDE(3) * sizeof(double) +
           w->scratch_cap * (SC_COUNT + 1) * sizeof(double) +
           w->fpack_cap * (size_t)wc_fk_count(w) * sizeof(float) + nr;
}

/* Evaluates all rates at the current (predicted) state. */
static ry_status evaluate(ry_sim *sim, wcsph *w, ry_error *err) {
    ry_particles *ps = &sim->ps;
    double hmax = sim->kernel.h;
    if (w->variable_h) {
        for (size_t i = 0; i < ps->n; ++i) hmax = fmax(hmax, ps->f[RY_F_H][i]);
    }
    if (sim->par) hmax = sim->par->max(sim, hmax); /* one search radius on every rank */
    w->hmax = hmax;
    /* The surface-tension radius may reach beyond the kernel's (the pair loop keeps to the
     * support). */
    const double reach = fmax(sim->kernel.kappa * hmax, w->st.model ? w->st.re : 0.0);
    RY_TRY(ry_sim_neighbors(sim, reach, err));
    if (w->fast && w->rng_gen != sim->nl_generation) RY_TRY(wc_fast_ranges(sim, w, err));
    if (w->density == DENS_SUMMATION) wc_density_summation(sim, w);
    const size_t n = ps->n;
    double *p = ps->f[RY_F_P];
    const double *rho = ps->f[RY_F_RHO], *e = ps->f[RY_F_E];
    if (!w->fast) {
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; ++i)
            if (ps->kind[i] == RY_KIND_FLUID)
                p[i] = eos_pressure(w, ps->material[i], rho[i], e ? e[i] : 0.0);
    }
    if (ry_st_pressure_form(&w->st)) RY_TRY(st_laplace(sim, w, err));
    if (w->fast) {
        /* The wall pass reads the fluid's records and rewrites the walls'. */
        RY_TRY(wc_prepare_pairs(sim, w, err));
        wc_fast_wall_pass(sim, w);
    } else {
        wc_wall_pass(sim, w);
        if (w->rheo.on) RY_TRY(rheology_rates(sim, w, err));
        RY_TRY(wc_prepare_pairs(sim, w, err));
    }
    force_out res;
    RY_TRY(fluid_forces(sim, w, &res, err));
    if (w->st.model != RY_ST_NONE) RY_TRY(st_forces(sim, w, err));
    if (w->rheo.ob) polymer_forces(sim, w, &res);
    if (sim->par && w->lean) {
        /* (the loop's largest values are the owned particles'; v holds v_{n+1/2} here) */
        res.amax2 = sim->par->max(sim, res.amax2);
        res.vmax2 = sim->par->max(sim, res.vmax2);
    } else if (sim->par) {
        global_maxima(sim, &res);
    }
    w->amax = sqrt(res.amax2);
    w->vmax = sqrt(res.vmax2);
    w->have_forces = 1;
    return RY_OK;
}

ry_status wc_dt(ry_sim *sim, void *state, double *dt, ry_error *err) {
    wcsph *w = state;
    if (!w->have_forces) RY_TRY(evaluate(sim, w, err));
    double h = sim->kernel.h;
    double c = w->c0;
    if (w->eos == EOS_IDEAL_GAS) {
        c = 0;
        const ry_particles *ps = &sim->ps;
        for (size_t i = 0; i < ps->n; ++i)
            c = fmax(c, sound_speed(w, ps->f[RY_F_RHO][i], ps->f[RY_F_P][i]));
    }
    double t = sim->cfl * h / (c + w->vmax);
    if (w->amax > 0) t = fmin(t, 0.25 * sqrt(h / w->amax));
    double numax = 0;
    for (int m = 0; m < sim->nmat; ++m) numax = fmax(numax, sim->mat[m].viscosity);
    if (numax > 0 && w->laminar) t = fmin(t, 0.125 * h * h / (numax * w->mu_corr));
    if (w->laminar)
        t = fmin(t, ry_sph_rheo_dt(&w->rheo, sim, MOBILE, h, sim->cfl, 0.125 / w->mu_corr));
    t = fmin(t, ry_st_capillary_dt(&w->st, sim));
    *dt = t;
    return RY_OK;
}

/* The first half kick and the drift of particle i (leapfrog). */
static inline __attribute__((always_inline)) void kick_drift(ry_sim *sim, const wcsph *w, size_t i,
                                                             double dt, int cont) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    /* Outlet buffers move as fluid, at the outlet's pressure and the reference density. */
    const int outlet = ps->kind[i] == RY_KIND_OUTLET;
    if (ps->kind[i] != RY_KIND_FLUID && !outlet) {
        if (ps->kind[i] == RY_KIND_INLET) /* inflow buffers drift at the inlet velocity */
            for (int d = 0; d < dim; ++d) ps->f[RY_F_X + d][i] += dt * ps->f[RY_F_VX + d][i];
        return;
    }
    for (int d = 0; d < dim; ++d) {
        double vh = ps->f[RY_F_VX + d][i] + 0.5 * dt * ps->f[RY_F_AX + d][i];
        ps->f[w->f_vh[d]][i] = vh;
        if (w->tvf) {
            /* Particles move with the transport velocity (Adami et al. 2013, eq. 13). */
            double vt = vh + 0.5 * dt * ps->f[w->f_abg[d]][i];
            ps->f[w->f_vt[d]][i] = vt;
            ps->f[RY_F_X + d][i] += dt * vt;
        } else {
            ps->f[RY_F_X + d][i] += dt * vh;
        }
        if (sim->box.periodic[d]) { /* back into the periodic box */
            const double lo = sim->box.lo[d], L = sim->box.hi[d] - lo;
            double *x = &ps->f[RY_F_X + d][i];
            if (*x < lo) *x += L;
            if (*x >= lo + L) *x -= L;
        }
        ps->f[RY_F_VX + d][i] = vh + 0.5 * dt * ps->f[RY_F_AX + d][i];
    }
    if (outlet) return;
    if (cont) {
        double rh = ps->f[RY_F_RHO][i] + 0.5 * dt * ps->f[RY_F_DRHO][i];
        ps->f[w->f_rhoh][i] = rh;
        ps->f[RY_F_RHO][i] = rh + 0.5 * dt * ps->f[RY_F_DRHO][i];
    }
    if (w->energy) {
        double eh = ps->f[RY_F_E][i] + 0.5 * dt * ps->f[RY_F_DE][i];
        ps->f[w->f_eh][i] = eh;
        ps->f[RY_F_E][i] = eh + 0.5 * dt * ps->f[RY_F_DE][i];
    }
    if (w->variable_h) {
        double dh = -ps->f[RY_F_H][i] / (dim * ps->f[RY_F_RHO][i]) * ps->f[RY_F_DRHO][i];
        double hh = ps->f[RY_F_H][i] + 0.5 * dt * dh;
        ps->f[w->f_hh][i] = hh;
        ps->f[RY_F_H][i] = hh + 0.5 * dt * dh;
    }
}

/* The second half kick of particle i, with the rates at the new positions. */
static inline __attribute__((always_inline)) void final_kick(ry_sim *sim, const wcsph *w, size_t i,
                                                             double dt, int cont) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    if (ps->kind[i] != RY_KIND_FLUID && ps->kind[i] != RY_KIND_OUTLET) return;
    for (int d = 0; d < dim; ++d)
        ps->f[RY_F_VX + d][i] = ps->f[w->f_vh[d]][i] + 0.5 * dt * ps->f[RY_F_AX + d][i];
    if (ps->kind[i] == RY_KIND_OUTLET) return;
    if (cont) ps->f[RY_F_RHO][i] = ps->f[w->f_rhoh][i] + 0.5 * dt * ps->f[RY_F_DRHO][i];
    if (w->energy) ps->f[RY_F_E][i] = ps->f[w->f_eh][i] + 0.5 * dt * ps->f[RY_F_DE][i];
    if (w->variable_h) {
        double dh = -ps->f[RY_F_H][i] / (dim * ps->f[RY_F_RHO][i]) * ps->f[RY_F_DRHO][i];
        ps->f[RY_F_H][i] = ps->f[w->f_hh][i] + 0.5 * dt * dh;
    }
}

/* The leapfrog loops of the cell-range loop's cases without the energy equation or variable h
 * (fluid and fixed walls; no transport velocity or open boundaries), one contiguous pass per array
 * so that they vectorise. Each thread keeps the particles of its static share through the passes of
 * a region, so the passes need no barrier between them. Walls keep their values. */
static double fast_kick_drift(ry_sim *sim, double dt, int cont) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const double hdt = 0.5 * dt;
    const uint8_t *restrict kind = ps->kind;
    double m = 0;
#pragma omp parallel
    {
        /* v and rho keep the half-step values (wc_lean). */
        for (int d = 0; d < dim; ++d) {
            double *restrict x = ps->f[RY_F_X + d], *restrict v = ps->f[RY_F_VX + d];
            const double *restrict a = ps->f[RY_F_AX + d];
#pragma omp for schedule(static) nowait
            for (size_t i = 0; i < n; ++i) {
                const int f = kind[i] == RY_KIND_FLUID;
                const double h = v[i] + hdt * a[i];
                x[i] = f ? x[i] + dt * h : x[i];
                v[i] = f ? h : v[i];
            }
        }
        if (cont) {
            double *restrict rho = ps->f[RY_F_RHO];
            const double *restrict dr = ps->f[RY_F_DRHO];
#pragma omp for schedule(static) nowait
            for (size_t i = 0; i < n; ++i) {
                const int f = kind[i] == RY_KIND_FLUID;
                rho[i] = f ? rho[i] + hdt * dr[i] : rho[i];
            }
        }
        const double *restrict x0 = ps->f[RY_F_X], *restrict x1 = ps->f[RY_F_Y];
        const double *restrict x2 = ps->f[dim > 2 ? RY_F_Z : RY_F_Y];
        const double *restrict r0 = ps->f[sim->f_xref], *restrict r1 = ps->f[sim->f_xref + 1];
        const double *restrict r2 = ps->f[sim->f_xref + (dim > 2 ? 2 : 1)];
        const double z = dim > 2 ? 1.0 : 0.0;
#pragma omp for simd schedule(static) nowait reduction(max : m)
        for (size_t i = 0; i < n; ++i) {
            const double e0 = x0[i] - r0[i], e1 = x1[i] - r1[i], e2 = z * (x2[i] - r2[i]);
            const double q = e0 * e0 + e1 * e1 + e2 * e2;
            m = q > m ? q : m;
        }
    }
    return m;
}

/* The second half kick and the guard check (src/core/guard_check.h) in one region. */
static void fast_final_kick(ry_sim *sim, double dt, int cont) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const double hdt = 0.5 * dt;
    const uint8_t *restrict kind = ps->kind;
    ry_check_ctx chk;
    double inv_rho0[256];
    const int uniform = ry_check_init(sim, &chk, inv_rho0);
    const uint8_t *material = ps->material;
    size_t bad = 0, fluid = 0, outside = 0;
#pragma omp parallel
    {
        /* from the half-step values in v and rho (wc_lean) */
        for (int d = 0; d < dim; ++d) {
            double *restrict v = ps->f[RY_F_VX + d];
            const double *restrict a = ps->f[RY_F_AX + d];
#pragma omp for schedule(static) nowait
            for (size_t i = 0; i < n; ++i)
                v[i] = kind[i] == RY_KIND_FLUID ? v[i] + hdt * a[i] : v[i];
        }
        if (cont) {
            double *restrict rho = ps->f[RY_F_RHO];
            const double *restrict dr = ps->f[RY_F_DRHO];
#pragma omp for schedule(static) nowait
            for (size_t i = 0; i < n; ++i)
                rho[i] = kind[i] == RY_KIND_FLUID ? rho[i] + hdt * dr[i] : rho[i];
        }
        const ry_check_ctx c = chk;
        const double inv0 = inv_rho0[0];
        if (uniform && dim == 2) {
#pragma omp for simd schedule(static) nowait reduction(+ : bad, fluid, outside)
            for (size_t i = 0; i < n; ++i) ry_check_tally(&c, i, 2, inv0, &bad, &fluid, &outside);
        } else if (uniform) {
#pragma omp for simd schedule(static) nowait reduction(+ : bad, fluid, outside)
            for (size_t i = 0; i < n; ++i) ry_check_tally(&c, i, 3, inv0, &bad, &fluid, &outside);
        } else {
#pragma omp for schedule(static) nowait reduction(+ : bad, fluid, outside)
            for (size_t i = 0; i < n; ++i)
                ry_check_tally(&c, i, dim, inv_rho0[material[i]], &bad, &fluid, &outside);
        }
    }
    ry_sim_checked(sim, bad, fluid, outside);
}

ry_status wc_step(ry_sim *sim, void *state, double dt, ry_error *err) {
    wcsph *w = state;
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const int cont = w->density == DENS_CONTINUITY;
    size_t n = ps->n;
    /* Kick (half step) and drift; then predict v and rho at the new time for the forces. The
     * same loop measures the largest displacement since the last neighbour search. */
    if (w->lean) {
        ry_sim_drift_measured(sim, fast_kick_drift(sim, dt, cont));
        w->hdt = 0.5 * dt; /* the evaluation predicts v and rho (wc_lean) */
        const ry_status st = evaluate(sim, w, err); /* may reorder particles */
        w->hdt = 0.0;
        RY_TRY(st);
        fast_final_kick(sim, dt, cont);
        return RY_OK;
    }
    const double *xref[3];
    for (int d = 0; d < 3; ++d) xref[d] = ps->f[sim->f_xref + (d < dim ? d : 0)];
    double drift2 = 0;
    const int periodic = is_periodic(sim);
#pragma omp parallel for schedule(static) reduction(max : drift2)
    for (size_t i = 0; i < n; ++i) {
        kick_drift(sim, w, i, dt, cont);
        double e[3] = {0, 0, 0}, r2 = 0;
        for (int d = 0; d < dim; ++d) e[d] = ps->f[RY_F_X + d][i] - xref[d][i];
        if (periodic) ry_box_min_image(&sim->box, e); /* a wrapped particle moved little */
        for (int d = 0; d < dim; ++d) r2 += e[d] * e[d];
        drift2 = r2 > drift2 ? r2 : drift2;
    }
    ry_sim_drift_measured(sim, drift2);
    RY_TRY(evaluate(sim, w, err)); /* may reorder particles: fields move together */
    n = ps->n;
    /* The second half kick, and the guard check of the new state in the same pass. */
    ry_check_ctx chk;
    double inv_rho0[256];
    ry_check_init(sim, &chk, inv_rho0);
    size_t bad = 0, fluid = 0, outside = 0;
#pragma omp parallel for schedule(static) reduction(+ : bad, fluid, outside)
    for (size_t i = 0; i < n; ++i) {
        final_kick(sim, w, i, dt, cont);
        ry_check_tally(&chk, i, dim, inv_rho0[ps->material[i]], &bad, &fluid, &outside);
    }
    ry_sph_rheo_advance(&w->rheo, sim, MOBILE, dt); /* polymer stress, with L at t + dt */
    /* Artificial repulsion (scheme.repulsion), from the new positions and velocities. */
    if (w->coll_r > 0) {
        RY_TRY(ry_st_work_ensure(&w->stw, sim->ps.n, err));
        if (sim->par)
            for (int d = 0; d < dim; ++d) {
                sim->par->sync_field(sim, RY_F_X + d);
                sim->par->sync_field(sim, RY_F_VX + d);
            }
        ry_collisions(sim, w->coll_r, w->coll_e, dt, NULL, NULL, w->stw.p);
    }
    ry_sim_checked(sim, bad, fluid, outside);
    return RY_OK;
}
