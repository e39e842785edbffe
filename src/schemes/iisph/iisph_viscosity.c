/* The non-pressure forces of IISPH: number density and density, the velocity the viscous term
 * sees (the ghost velocity of Adami, Hu & Adams (2012), eq. 22-23), the explicit viscous term
 * (seed eq. 5 with the harmonic mean of the viscosities, or the form of Morris, Fox & Zhu
 * (1997), J. Comput. Phys. 136: 214) with gravity and the polymer stress, the shear rates of the
 * non-Newtonian materials, and the implicit viscosity (backward Euler, conjugate gradients on the
 * CSR matrix of linalg/sparse.h). */
#include <stdlib.h>

#include "boundary/walls_adami2012.h"
#include "schemes/iisph/iisph_internal.h"

/* Dynamic viscosity of particle i: its material's, or with a non-Newtonian material the
 * reference density times the viscosity of its shear rate; times the lattice factor. */
static inline double dyn_viscosity(const ry_sim *sim, const iisph *s, size_t i) {
    const int m = sim->ps.material[i];
    return s->mu_corr * (s->rheo.on ? sim->mat[m].density * sim->ps.f[s->rheo.f_nu][i] : s->mu[m]);
}

/* The Morris coefficient mu_ij L_ij (physics/viscosity_morris1997.h, twice the harmonic mean of
 * the viscosities) of a pair with separation dx, r^2 r2 and kernel gradient G, with the volume
 * vj of j. */
static inline double morris_pair(const double *dx, double r2, const double *G, double vj,
                                 double mui, double muj, double eta2, int dim) {
    double xg = 0;
    for (int d = 0; d < dim; ++d) xg += dx[d] * G[d];
    return ry_morris_coefficient(ry_morris_mu_harmonic2(mui, muj),
                                 ry_morris_weight(vj, xg, 1.0 / (r2 + eta2)));
}

/* The velocity the viscous term sees at each particle (s->vg): its own, or at a wall
 * with wall_velocity: ghost the ghost velocity of Adami et al. (2012, eq. 22-23;
 * boundary/walls_adami2012.h), which puts the no-slip condition on the wall surface. */
static void viscous_velocities(ry_sim *sim, iisph *s) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = s->pc.j; /* the pairs within the support */
    const size_t *end = s->pc.end;
    const double *cw = s->pc.w;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        ry_adami_sums a = {0, 0, {0, 0, 0}};
        if (s->ghost && ps->kind[i] == RY_KIND_WALL)
            for (size_t q = off[i]; q < end[i]; ++q) {
                const uint32_t j = nb[q];
                if (!MOBILE[ps->kind[j]]) continue;
                const double w = cw[q];
                double vj[3] = {0, 0, 0};
                for (int d = 0; d < dim; ++d) vj[d] = ps->f[RY_F_VX + d][j];
                ry_adami_add_weight(&a, w);
                ry_adami_add_velocity(&a, w, vj, dim);
            }
        for (int d = 0; d < 3; ++d) {
            const double v = d < dim ? ps->f[RY_F_VX + d][i] : 0.0;
            s->vg[d][i] = a.sw > 0 ? ry_adami_ghost_velocity(&a, d, v) : v;
        }
    }
}

/* The viscous (explicit) and body-force acceleration of particle i into out[0..2] (zero where
 * it is not mobile); inlined with a literal dim, so that the sums stay in registers. */
static inline void force_row(const ry_sim *sim, const iisph *s, size_t i, const double *const vg[3],
                             double *out, int dim) {
    const ry_particles *ps = &sim->ps;
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = s->pc.j; /* the pairs within the support */
    const size_t *end = s->pc.end;
    const uint8_t *kind = ps->kind;
    const double *cw = s->pc.w, *cg = s->pc.g, *m = ps->f[RY_F_MASS], *delta = s->delta;
    const double eta2 = ry_morris_eta2(sim->kernel.h), cvis = 2.0 * (dim + 2);
    double a[3] = {0, 0, 0};
    if (MOBILE[kind[i]]) {
        const double mui = dyn_viscosity(sim, s, i);
        for (size_t q = off[i]; !s->implicit && q < end[i]; ++q) {
            const uint32_t j = nb[q];
            if (cw[q] == 0 || pair_skip(s, i, j)) continue;
            /* a light row's heavy neighbour is a wall to it, always without slip */
            const int wall = !pair_force_mobile(s, kind, i, j);
            if (!MOBILE[kind[j]] && s->slip) continue;
            const double muj = wall ? mui : dyn_viscosity(sim, s, j);
            if (mui + muj <= 0) continue;
            const double vj = wall ? 1.0 / delta[i] : 1.0 / delta[j], *G = cg + 3 * q;
            double dx[3];
            const double r2 = ry_pair_separation(sim, i, j, dx);
            if (s->morris) {
                const double f = morris_pair(dx, r2, G, vj, mui, muj, eta2, dim);
                for (int d = 0; d < dim; ++d) a[d] += f * (vg[d][i] - vg[d][j]);
                continue;
            }
            const double mu = 2 * mui * muj / (mui + muj);
            double vx = 0;
            for (int d = 0; d < dim; ++d) vx += (vg[d][i] - vg[d][j]) * dx[d];
            const double f = cvis * vj * mu * vx / (r2 + eta2);
            for (int d = 0; d < dim; ++d) a[d] += f * G[d];
        }
        const double inv_rho = 1.0 / (m[i] * delta[i]);
        for (int d = 0; d < dim; ++d) a[d] = a[d] * inv_rho + sim->gravity[d];
        if (s->rheo.ob)
            for (int d = 0; d < dim; ++d) a[d] += s->rheo.acc[3 * i + d];
    }
    for (int d = 0; d < 3; ++d) out[d] = a[d];
}

/* Number density, density, and the non-pressure accelerations (gravity, viscosity, polymer
 * stress) into acc. */
ry_status iisph_densities_and_forces(ry_sim *sim, iisph *s, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const size_t *off = sim->nl.offset;
    const size_t *end = s->pc.end; /* the pairs within the support */
    const uint8_t *kind = ps->kind;
    const double *cw = s->pc.w, *m = ps->f[RY_F_MASS];
    const double w0 = sim->kernel.norm * ry_kernel_shape(sim->kernel.type, 0.0);
    double *delta = s->delta, *acc = s->acc;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        double sw = w0;
        if (MOBILE[kind[i]])
            for (size_t q = off[i]; q < end[i]; ++q)
                if (!pair_skip(s, i, s->pc.j[q])) sw += cw[q];
        delta[i] = sw;
    }
    if (sim->par) sim->par->sync(sim, delta, 1, 0); /* halo copies: their owners' values */
    for (size_t i = 0; i < n; ++i)
        if (MOBILE[kind[i]]) ps->f[RY_F_RHO][i] = m[i] * delta[i];
    viscous_velocities(sim, s);
    const double *vg[3] = {s->vg[0], s->vg[1], s->vg[2]};
    if (s->rheo.on) { /* the velocity gradient and the viscosity it gives; pnew is free here */
        double *vol = s->pnew;
        for (size_t i = 0; i < n; ++i) vol[i] = 1.0 / (MOBILE[kind[i]] ? delta[i] : s->delta0);
        RY_TRY(ry_sph_rheo_rates(&s->rheo, sim, &s->pc, MOBILE, vol, s->slip ? NULL : vg, err));
    }
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        double *a = acc + 3 * i;
        if (dim == 3)
            force_row(sim, s, i, vg, a, 3);
        else
            force_row(sim, s, i, vg, a, 2);
    }
    return RY_OK;
}

/* Iterations allowed to one component's viscous solve (the same on every process). */
#define RY_IISPH_VISCOUS_MAX_ITER 5000

/* Implicit viscosity (scheme.viscosity: implicit): the Morris term of
 * iisph_densities_and_forces by backward Euler, for each velocity component
 *   m_i v_i + sum_j c_ij (v_i - v_j) = m_i v*_i,  c_ij = -2 dt V_i V_j mu_ij x_ij . grad_i W_ij
 *                                                           / (r_ij^2 + 0.01 h^2) >= 0,
 * (the explicit term times m_i, whose pair coefficients are symmetric), walls and inlets with
 * their velocity (or the ghost velocity) as known values. The matrix is symmetric positive
 * definite: conjugate gradients with the Jacobi preconditioner (linalg/sparse.h) or BoomerAMG
 * (linalg/amg.h, scheme.viscosity_preconditioner), from v*.
 * The viscous acceleration (v - v*)/dt is added to acc. */
ry_status iisph_viscous_implicit(ry_sim *sim, iisph *s, double dt, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    if (s->vcap < n) {
        const size_t cap = n + n / 4 + 16;
        int32_t *u = realloc(s->unk, cap * sizeof *u);
        if (u) s->unk = u;
        int32_t *us = realloc(s->vslot, cap * sizeof *us);
        if (us) s->vslot = us;
        double *b = realloc(s->vb, 3 * cap * sizeof *b);
        if (b) s->vb = b;
        double *x = realloc(s->vx, 7 * cap * sizeof *x);
        if (x) s->vx = x;
        uint8_t *o = realloc(s->vown, cap * sizeof *o);
        if (o) s->vown = o;
        RY_CHECK(err, u && us && b && x && o, RY_ERR_NOMEM, "out of memory (implicit viscosity)");
        s->vtmp = s->vx + 6 * cap;
        s->vcap = cap;
    }
    size_t nunk = 0;
    for (size_t i = 0; i < n; ++i) s->unk[i] = MOBILE[ps->kind[i]] ? (int32_t)nunk++ : -1;
    /* distributed: each process holds rows for its own and its halo's particles and the solver
     * uses its own only (NULL in a serial run) */
    ry_csr_dist dist;
    s->vpu = (ry_particle_unknowns){sim, s->unk, s->vown, s->vtmp, {1u, 2u, 4u}};
    const ry_csr_dist *dd = ry_particle_dist(&s->vpu, &dist);
    s->viters_last = 0;
    if (nunk == 0 && !dd) return RY_OK; /* (distributed: the others' sums need this process) */
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = s->pc.j; /* the pairs within the support */
    const size_t *end = s->pc.end;
    const double *cw = s->pc.w, *cg = s->pc.g, *m = ps->f[RY_F_MASS], *delta = s->delta;
    const double eta2 = ry_morris_eta2(sim->kernel.h);
    ry_csr *A = &s->A;
    RY_TRY(ry_csr_reserve(A, nunk, 0, err));
#pragma omp parallel for schedule(dynamic, 256)
    for (size_t i = 0; i < n; ++i) {
        if (s->unk[i] < 0) continue;
        size_t len = 1;
        for (size_t q = off[i]; q < end[i]; ++q) len += s->unk[nb[q]] >= 0 && cw[q] != 0;
        A->row[(size_t)s->unk[i] + 1] = len;
    }
    RY_TRY(ry_csr_rows_from_lengths(A, err));
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (s->unk[i] < 0) continue;
        const size_t k = (size_t)s->unk[i];
        ry_csr_row row = ry_csr_row_begin(A, k, m[i]);
        const double mui = dyn_viscosity(sim, s, i), vi = 1.0 / delta[i];
        double known[3] = {0, 0, 0};
        for (size_t q = off[i]; q < end[i]; ++q) {
            const uint32_t j = nb[q];
            if (cw[q] == 0) continue;
            const int wall = !MOBILE[ps->kind[j]];
            double c = 0;
            if (!(wall && s->slip)) {
                const double muj = wall ? mui : dyn_viscosity(sim, s, j);
                const double vj = wall ? vi : 1.0 / delta[j];
                double dx[3];
                const double r2 = ry_pair_separation(sim, i, j, dx);
                c = -dt * vi * morris_pair(dx, r2, cg + 3 * q, vj, mui, muj, eta2, dim);
            }
            ry_csr_row_pair(&row, c, s->unk[j]); /* (a wall: a known velocity) */
            if (wall)
                for (int d = 0; d < dim; ++d) known[d] += c * s->vg[d][j];
        }
        ry_csr_row_end(&row);
        for (int d = 0; d < 3; ++d)
            s->vb[3 * k + d] = d < dim ? m[i] * ps->f[RY_F_VX + d][i] + known[d] : 0.0;
    }
    /* component d: right-hand side from d nunk, solution from (3 + d) nunk; the components
     * are solved together, one pass over the matrix serving all three */
    const double *bd[3];
    double *xd[3];
    for (int d = 0; d < dim; ++d) {
        const double *v = ps->f[RY_F_VX + d];
        double *b = s->vx + (size_t)d * nunk, *x = s->vx + (size_t)(3 + d) * nunk;
        bd[d] = b;
        xd[d] = x;
        for (size_t i = 0; i < n; ++i)
            if (s->unk[i] >= 0) {
                b[s->unk[i]] = s->vb[3 * (size_t)s->unk[i] + d];
                x[s->unk[i]] = v[i];
            }
    }
    int it[3] = {0, 0, 0};
    double res[3] = {0, 0, 0};
    if (s->vprecond == RY_PRECOND_BOOMERAMG && !sim->par) {
        /* over the particles as slots, so that a hierarchy may serve several steps */
        for (size_t i = 0; i < n; ++i)
            if (s->unk[i] >= 0) s->vslot[s->unk[i]] = (int32_t)i;
        const ry_amg_slots sl = {n, s->vslot, ps->id};
        RY_TRY(ry_amg_pcg(&s->vamg, A, &sl, dim, bd, xd, s->vtol, RY_IISPH_VISCOUS_MAX_ITER, it,
                          res, err));
    } else {
        RY_TRY(
            ry_csr_pcg_multi(A, dim, bd, xd, s->vtol, RY_IISPH_VISCOUS_MAX_ITER, it, res, dd, err));
    }
    for (int d = 0; d < dim; ++d) {
        double *v = ps->f[RY_F_VX + d];
        for (size_t i = 0; i < n; ++i)
            if (s->unk[i] >= 0) {
                const double vn = xd[d][s->unk[i]];
                s->acc[3 * i + d] += (vn - v[i]) / dt;
                v[i] = vn;
            }
        s->viters_last += it[d];
    }
    s->viters_total += s->viters_last;
    return RY_OK;
}
