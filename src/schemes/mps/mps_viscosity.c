/* The viscous terms of MPS (Koshizuka & Oka 1996; seed 003): nu lap u with the Laplacian of
 * eq. 7-8, explicit (u* = u^n + dt (a + nu lap u^n)), implicit ((1 - dt nu lap) u* = u^n + dt a,
 * by conjugate gradients on the matrix of mps_assemble) or both (`viscosity: mixed`); and the
 * rheology (docs/reference/rheology.md): the shear-rate dependent viscosity from the corrected
 * velocity gradient, and the polymer stress of visco-elastic materials, its divergence and its
 * update (ry_polymer_step). */
#include <math.h>
#include <stdlib.h>

#include "linalg/small.h"
#include "ryushi/clock.h"
#include "ryushi/rheology.h"
#include "physics/gradient_mps_koshizuka1996.h"
#include "physics/laplacian_mps_koshizuka1996.h"
#include "schemes/mps/mps_internal.h"

/* Rheology (docs/reference/rheology.md); the polymer stress by components as ry_tau_index says. */

ry_status mps_rheology_init(ry_sim *sim, mps *M, ry_error *err) {
    M->f_nu = M->f_gd = -1;
    for (int k = 0; k < 6; ++k) M->f_tau[k] = -1;
    const size_t nm = (size_t)sim->nmat;
    M->nu_pair = malloc((nm ? nm * nm : 1) * sizeof *M->nu_pair);
    RY_CHECK(err, M->nu_pair != NULL, RY_ERR_NOMEM, "out of memory");
    for (size_t a = 0; a < nm; ++a)
        for (size_t b = 0; b < nm; ++b)
            M->nu_pair[a * nm + b] = nu_mean(sim->mat[a].viscosity, sim->mat[b].viscosity);
    for (int m = 0; m < sim->nmat; ++m) {
        M->rheo_gnf |= ry_rheology_generalised(&sim->mat[m].rheo);
        M->rheo_ob |= ry_rheology_viscoelastic(&sim->mat[m].rheo);
    }
    if (!M->rheo_gnf && !M->rheo_ob) return RY_OK;
    ry_particles *ps = &sim->ps;
    RY_TRY(ry_particles_add_field(ps, "viscosity", "m^2/s", -1, RY_FIELD_OUTPUT, &M->f_nu, err));
    RY_TRY(ry_particles_add_field(ps, "shear_rate", "1/s", -1, RY_FIELD_OUTPUT, &M->f_gd, err));
    for (int k = 0; M->rheo_ob && k < ry_tau_count(sim->dim); ++k) {
        RY_TRY(ry_particles_add_field(ps, ry_tau_name(sim->dim, k), "Pa", -1,
                                      RY_FIELD_STATE | RY_FIELD_OUTPUT, &M->f_tau[k], err));
        ry_particles_set_parity(ps, M->f_tau[k], ry_tau_odd(sim->dim, k));
    }
    return RY_OK;
}

/* Corrected (least-squares) gradient at particle i of the fields val(i, j, c), c < nc (the
 * value of j as seen from i), over the neighbours within re_g (fluid ones only with
 * fluid_only): grad[c][b] =
 * d val_c / d x_b, exact for linear fields however one-sided the neighbourhood. Returns 0 when
 * the moment matrix is singular (too few neighbours); grad is then zero. */
typedef double (*grad_value_fn)(const ry_sim *sim, const mps *M, size_t i, size_t j, int c);
static int corrected_gradient(const ry_sim *sim, const mps *M, size_t i, int fluid_only,
                              grad_value_fn val, int nc, double grad[6][3]) {
    const int dim = sim->dim;
    double m[3][3] = {{0}}, g[6][3] = {{0}};
    for (size_t q = sim->nl.offset[i]; q < M->gend[i]; ++q) {
        const uint32_t j = M->pj[q];
        if (fluid_only && sim->ps.kind[j] != RY_KIND_FLUID) continue;
        double dx[3];
        const double r2 = ry_sim_separation(sim, i, j, dx);
        if (r2 <= 0) continue;
        const double wr = ry_mps_weight_tamai(M->pr[q], M->re_g) / r2;
        ry_grad_moment_add(m, wr, dx, dim);
        for (int c = 0; c < nc; ++c)
            ry_grad_value_add(g[c], wr, val(sim, M, i, j, c) - val(sim, M, i, i, c), dx, dim);
    }
    return ry_solve_rows(dim, m, nc, g, grad);
}

/* Velocity of j seen from fluid particle i: a wall's mirrored as in the viscous terms. */
static double velocity_value(const ry_sim *sim, const mps *M, size_t i, size_t j, int c) {
    const double vj = sim->ps.f[RY_F_VX + c][j];
    if (j == i) return vj;
    return vj + (wall_beta(sim, M, i, j) - 1.0) * (vj - sim->ps.f[RY_F_VX + c][i]);
}

static double tau_value(const ry_sim *sim, const mps *M, size_t i, size_t j, int c) {
    (void)i;
    return sim->ps.f[M->f_tau[c]][j];
}

/* At x^n: the velocity gradient L (L[a][b] = du_a/dx_b, over fluid and wall neighbours, walls
 * with the velocity the viscous terms give them, wall_beta), the shear rate sqrt(2 D:D) and the
 * viscosity it gives; with a visco-elastic model the acceleration div(tau)/rho (tau's gradient
 * over the fluid neighbours) and the stress at t + dt by ry_polymer_step (the upper-convected and
 * Giesekus terms explicit, the relaxation implicit). */
void mps_rheology_explicit(ry_sim *sim, mps *M, double dt) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim, nt = ry_tau_count(dim);
    const size_t n = ps->n;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        const ry_material *mat = &sim->mat[ps->material[i]];
        if (ps->kind[i] != RY_KIND_FLUID) {
            ps->f[M->f_nu][i] = mat->viscosity;
            ps->f[M->f_gd][i] = 0;
            continue;
        }
        double L[6][3];
        corrected_gradient(sim, M, i, 0, velocity_value, dim, L);
        double dd = 0;
        for (int a = 0; a < dim; ++a)
            for (int b = 0; b < dim; ++b) {
                const double d = 0.5 * (L[a][b] + L[b][a]);
                dd += d * d;
            }
        const double gd = sqrt(2.0 * dd);
        ps->f[M->f_gd][i] = gd;
        ps->f[M->f_nu][i] = ry_rheology_nu(&mat->rheo, mat->viscosity, gd);
        if (M->rheo_ob)
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b)
                    M->vgrad[9 * i + 3 * a + b] = a < dim && b < dim ? L[a][b] : 0.0;
    }
    if (sim->par) sim->par->sync_field(sim, M->f_nu);
    if (!M->rheo_ob) return;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        double G[6][3];
        corrected_gradient(sim, M, i, 1, tau_value, nt, G);
        double div[3] = {0, 0, 0};
        for (int k = 0; k < nt; ++k) {
            int a, b;
            ry_tau_index(dim, k, &a, &b);
            div[a] += G[k][b];
            if (a != b) div[b] += G[k][a];
        }
        const double rho = sim->mat[ps->material[i]].density;
        for (int d = 0; d < dim; ++d) ps->f[RY_F_AX + d][i] += div[d] / rho;
    }
    /* The stress update reads only particle i's own values: no race. */
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        const ry_material *mat = &sim->mat[ps->material[i]];
        if (ps->kind[i] != RY_KIND_FLUID || !ry_rheology_viscoelastic(&mat->rheo)) continue;
        double t[6];
        for (int k = 0; k < nt; ++k) t[k] = ps->f[M->f_tau[k]][i];
        ry_polymer_step(dim, &mat->rheo, &M->vgrad[9 * i], mat->density, dt, t);
        for (int k = 0; k < nt; ++k) ps->f[M->f_tau[k]][i] = t[k];
    }
    for (int k = 0; sim->par && k < nt; ++k) sim->par->sync_field(sim, M->f_tau[k]);
}

/* The viscous pair sums of fluid particle i: s = sum_j nu_ij w_ij (v_j - v_i) (times beta
 * with mirrored walls) and the return value sum_j nu_ij w_ij; nu lap v = cl s. */
static inline double viscous_sums_d(const ry_sim *sim, const mps *M, size_t i, double s[3],
                                    int dim) {
    const ry_particles *ps = &sim->ps;
    const double re = M->re_l;
    const double *v[3];
    double c = 0, t[3] = {0, 0, 0}, vi[3] = {0, 0, 0};
    for (int d = 0; d < dim; ++d) {
        v[d] = ps->f[RY_F_VX + d];
        vi[d] = v[d][i];
    }
    for (size_t q = sim->nl.offset[i]; q < M->lend[i]; ++q) {
        const uint32_t j = M->pj[q];
        const double w =
            pair_nu(sim, M, i, j) * ry_mps_weight_tamai(M->pr[q], re) * wall_beta(sim, M, i, j);
        c += w;
        for (int d = 0; d < dim; ++d) t[d] += w * (v[d][j] - vi[d]);
    }
    s[0] = t[0];
    s[1] = t[1];
    s[2] = t[2];
    return c;
}

/* (with a literal dimension: the sums stay in registers) */
static inline double viscous_sums(const ry_sim *sim, const mps *M, size_t i, double s[3]) {
    if (sim->dim == 3) return viscous_sums_d(sim, M, i, s, 3);
    if (sim->dim == 2) return viscous_sums_d(sim, M, i, s, 2);
    return viscous_sums_d(sim, M, i, s, sim->dim);
}

/* a += nu lap v (explicit viscosity, eq. 7) for fluid particles; walls enter with their
 * velocity (no slip). */
void mps_viscous_explicit(ry_sim *sim, const mps *M) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const size_t n = ps->n;
    const double cl = ry_mps_laplacian_coefficient(dim, M->lambda, M->n0l);
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        double s[3];
        viscous_sums(sim, M, i, s);
        for (int d = 0; d < dim; ++d) ps->f[RY_F_AX + d][i] += cl * s[d];
    }
}

/* `viscosity: mixed`: a fluid particle whose viscous diagonal dt sum_j c nu_ij w_ij (the
 * matrix's diagonal less 1) is at most this takes the explicit step. Explicit diffusion keeps
 * a maximum principle up to 1 (the new velocity a convex combination of the old ones). */
#define MIXED_EXPLICIT_MAX 0.25

/* `viscosity: mixed`: marks the fluid particles of the implicit solve (unk >= 0, numbered) and
 * gives the others their explicit u* = v + dt (a + nu lap v) in f_vs; returns the unknowns. */
static size_t viscous_split(ry_sim *sim, mps *M, double dt, int with_st) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const double cl = ry_mps_laplacian_coefficient(dim, M->lambda, M->n0l);
    double *a[3];
    for (int d = 0; d < 3; ++d) a[d] = ps->f[RY_F_AX + (d < dim ? d : 0)];
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        M->unk[i] = -1;
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        if (with_st) ry_st_potential_particle(&M->st, sim, i, a); /* (mps_step) */
        double s[3];
        if (dt * cl * viscous_sums(sim, M, i, s) > MIXED_EXPLICIT_MAX) {
            M->unk[i] = 0; /* numbered below */
            continue;
        }
        /* as mps_viscous_explicit, then u* = v + dt a */
        for (int d = 0; d < dim; ++d)
            ps->f[M->f_vs[d]][i] = ps->f[RY_F_VX + d][i] + dt * (ps->f[RY_F_AX + d][i] + cl * s[d]);
    }
    size_t nunk = 0;
    for (size_t i = 0; i < n; ++i)
        if (M->unk[i] == 0) M->unk[i] = (int32_t)nunk++;
    return nunk;
}

/* Symmetry planes: each copy takes its original's side of the split (a threshold its own sums
 * may cross the other way by rounding) and explicit velocity; the unknowns numbered again. */
static size_t split_as_originals(ry_sim *sim, mps *M) {
    const size_t n = sim->ps.n;
    for (int d = 0; d < sim->dim; ++d) sim->par->sync_field(sim, M->f_vs[d]);
    size_t nunk = 0;
    for (size_t i = 0; i < n; ++i) {
        size_t o;
        unsigned axes;
        const int32_t side = sim->par->copy_of(sim, i, &o, &axes) ? M->unk[o] : M->unk[i];
        M->unk[i] = side >= 0 ? (int32_t)nunk++ : -1; /* (an original precedes its copies) */
    }
    return nunk;
}

/* Implicit viscosity: (1 - dt nu lap) u* = v + dt a, per component, walls as known values.
 * With `viscosity: mixed` only the stiff particles are unknowns (viscous_split); the others'
 * explicit u* enter their rows as known values, as the walls' velocities do. */
ry_status mps_viscous_implicit(ry_sim *sim, mps *M, double dt, int with_st, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    /* (a distributed run solves them all: a halo copy lacks the neighbours for the split) */
    const int mixed = M->visc == VISC_MIXED && !ry_sim_distributed(sim);
    size_t nunk = 0;
    if (mixed) {
        nunk = viscous_split(sim, M, dt, with_st);
        if (sim->par) nunk = split_as_originals(sim, M);
    } else
        for (size_t i = 0; i < n; ++i)
            M->unk[i] = ps->kind[i] == RY_KIND_FLUID ? (int32_t)nunk++ : -1;
    RY_TRY(mps_assemble(sim, M, nunk, 1, dt, 1.0, NULL, err));
    const double re = M->re_l, cl = ry_mps_laplacian_coefficient(dim, M->lambda, M->n0l);
    /* the components' right-hand sides and solutions: b and xs from d nunk */
    const double *bs[3];
    double *xv[3];
    for (int d = 0; d < dim; ++d) {
        const double *v = ps->f[RY_F_VX + d], *a = ps->f[RY_F_AX + d], *us = ps->f[M->f_vs[d]];
        double *bd = M->b + (size_t)d * nunk, *xd = M->xs + (size_t)d * nunk;
        bs[d] = bd;
        xv[d] = xd;
#pragma omp parallel for schedule(dynamic, 64)
        for (size_t i = 0; i < n; ++i) {
            if (M->unk[i] < 0) continue;
            double rhs = v[i] + dt * a[i];
            for (size_t q = sim->nl.offset[i]; q < M->lend[i]; ++q) {
                const uint32_t j = M->pj[q];
                if (M->unk[j] >= 0) continue;
                const double vj = mixed && ps->kind[j] == RY_KIND_FLUID ? us[j] : v[j];
                rhs += cl * dt * pair_nu(sim, M, i, j) * ry_mps_weight_tamai(M->pr[q], re) *
                       wall_beta(sim, M, i, j) * vj;
            }
            bd[M->unk[i]] = rhs;
            xd[M->unk[i]] = v[i];
        }
    }
    /* the components together: one pass over the matrix serves all three */
    int it[3];
    double res[3];
    ry_csr_dist dd;
    const double t0 = ry_wall_time();
    if (M->vprecond == RY_PRECOND_BOOMERAMG && !sim->par) {
        const ry_amg_slots sl = mps_slots(sim, M);
        RY_TRY(
            ry_amg_pcg(&M->vamg, &M->A, &sl, dim, bs, xv, M->vtol, (int)M->max_iter, it, res, err));
    } else
        RY_TRY(ry_csr_pcg_multi(&M->A, dim, bs, xv, M->vtol, (int)M->max_iter, it, res,
                                mps_dist_of(sim, M, 1, &dd), err));
    M->vsolve_s += ry_wall_time() - t0;
    M->vsolves++;
    M->last_viters = 0;
    for (int d = 0; d < dim; ++d) {
        double *vs = ps->f[M->f_vs[d]];
        M->last_viters += it[d];
        M->total_viters += it[d];
        for (size_t i = 0; i < n; ++i)
            if (M->unk[i] >= 0) vs[i] = xv[d][M->unk[i]];
    }
    return RY_OK;
}
