/* The pressure of MPS at x* (Koshizuka & Oka 1996; seed 003): the matrix of the Laplacian
 * (eq. 7-8) for the pressure Poisson equation and the implicit viscosity; the source of Tanaka &
 * Masunaga (2010), lap p = (1 - gamma) rho/dt div u* - gamma rho/dt^2 (n* - n0)/n0, with the
 * compressibility of Ikeda et al. (2001); the Dirichlet values of the free surface (the head of
 * half a spacing); conjugate gradients (src/linalg/sparse.h), deflated by aggregates or across
 * the ranks of a distributed run; and the correction u' = -dt/rho grad p with Iribe's corrected
 * gradient and Koshizuka's minimum pressure (eq. 5). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/clock.h"
#include "physics/gradient_mps_koshizuka1996.h"
#include "physics/laplacian_mps_koshizuka1996.h"
#include "schemes/mps/mps_internal.h"

/* A distributed run (sim->par): the linear systems span the ranks. Vectors of unknowns reach
 * the halo copies through the particles. */
/* The distribution of the current unknowns (NULL in a serial run): a pressure's, or with
 * velocity the velocity's components (system d: component d, which a mirror across axis d
 * negates). */
const ry_csr_dist *mps_dist_of(const ry_sim *sim, mps *M, int velocity, ry_csr_dist *d) {
    M->pu = (ry_particle_unknowns){sim, M->unk, M->own, M->ptmp, {0}};
    for (int k = 0; velocity && k < RY_CSR_MAX_RHS; ++k) M->pu.odd[k] = 1u << k;
    return ry_particle_dist(&M->pu, d);
}

/* The particles as the slots of a BoomerAMG solve over the current unknowns (mps_pressure,
 * mps_viscosity). */
ry_amg_slots mps_slots(const ry_sim *sim, mps *M) {
    const ry_particles *ps = &sim->ps;
    for (size_t i = 0; i < ps->n; ++i)
        if (M->unk[i] >= 0) M->uslot[M->unk[i]] = (int32_t)i;
    return (ry_amg_slots){ps->n, M->uslot, ps->id};
}

/* Pressure: pairs between unknowns and free-surface particles (Dirichlet); dummies and the
 * walls out of the equation (wall_out: thin ones, or all with the Neumann walls) are left out. */
static int couple_pressure(const ry_sim *sim, const mps *M, size_t i, size_t j, double *coef,
                           double dt) {
    (void)i;
    (void)dt;
    *coef = 1.0;
    return M->role[j] != ROLE_DUMMY && !wall_out(sim, M, j);
}

/* With `scheme.wall_pressure: neumann` a wall particle j within re_l of unknown i stands in the
 * Laplacian for the pressure p_j = p_i + rho_i g.(x_j - x_i), the hydrostatic extension of i's
 * own (the Neumann condition dp/dn = rho g.n at the wall): the pair's term c w (p_i - p_j) is
 * known, -c w rho_i g.(x_j - x_i), and goes to the right-hand side. Every wall particle in reach
 * counts (dummies too), so that the Laplacian of a hydrostatic field is that of a full support.
 * Thin walls keep their pairs out (zero gradient, scheme.thin_wall_pressure). */
static double wall_head_source(const ry_sim *sim, const mps *M, size_t i, double cl) {
    const ry_particles *ps = &sim->ps;
    const double rho = sim->mat[ps->material[i]].density;
    double b = 0;
    for (size_t q = sim->nl.offset[i]; q < M->lend[i]; ++q) {
        const uint32_t j = M->pj[q];
        if (ps->kind[j] != RY_KIND_WALL || thin_out(M, j)) continue;
        double dx[3];
        ry_sim_separation(sim, i, j, dx); /* x_j - x_i */
        double gd = 0;
        for (int a = 0; a < sim->dim; ++a) gd += sim->gravity[a] * dx[a];
        b += cl * ry_mps_weight_tamai(M->pr[q], M->re_l) * rho * gd;
    }
    return b;
}

/* Viscosity: every pair; walls are known velocities. */
static int couple_viscous(const ry_sim *sim, const mps *M, size_t i, size_t j, double *coef,
                          double dt) {
    *coef = dt * pair_nu(sim, M, i, j) * wall_beta(sim, M, i, j);
    return 1;
}

/* The coefficient of the pair (i, j) of the Laplacian (zero where the pair does not couple). */
static inline double pair_coef(const ry_sim *sim, const mps *M, size_t i, size_t q, int viscous,
                               double dt, double cl) {
    const uint32_t j = M->pj[q];
    double coef = 0;
    if (viscous ? couple_viscous(sim, M, i, j, &coef, dt)
                : couple_pressure(sim, M, i, j, &coef, dt))
        return cl * coef * ry_mps_weight_tamai(M->pr[q], M->re_l);
    return 0;
}

/* Row i's columns folded from symmetry planes' copies (col[j] their originals'): those of the
 * set's own neighbours, then the copies' not among them and not i's own (which folds onto the
 * diagonal); into cols (room for the row), their number returned. */
static size_t folded_columns(const ry_sim *sim, const mps *M, size_t i, const int32_t *col,
                             uint32_t *cols) {
    size_t c = 0;
    for (size_t q = sim->nl.offset[i]; q < M->lend[i]; ++q)
        if (col[M->pj[q]] >= 0 && !ry_sim_is_halo(sim, M->pj[q]))
            cols[c++] = (uint32_t)col[M->pj[q]];
    for (size_t q = sim->nl.offset[i]; q < M->lend[i]; ++q) {
        const int32_t k = col[M->pj[q]];
        if (k < 0 || !ry_sim_is_halo(sim, M->pj[q]) || k == M->unk[i]) continue;
        size_t e = 0;
        while (e < c && cols[e] != (uint32_t)k) ++e;
        if (e == c) cols[c++] = (uint32_t)k;
    }
    return c;
}

/* Assembles the rows of the unknowns (unk[i] >= 0) from the Laplacian pairs: for each pair
 * (i, j) within re_l that couple_pressure or, where `viscous`, couple_viscous accepts,
 * coefficient c w_ij on the diagonal and -c w_ij off it when j is an unknown too (pairs beyond
 * re_l make no entry); diag_extra is added to every diagonal. coef(i, j) scales c w_ij (1 for
 * the pressure, dt nu_ij for the viscosity). (A flag rather than a function pointer: the
 * coefficient inlines into the loop.) With fold (symmetry planes, a quantity their mirrors
 * keep), j's unknown is col[j]: a copy's coefficient goes to its original's unknown, i's own
 * image's to the diagonal (A->diag keeps the unfolded diagonal, the Jacobi preconditioner's:
 * the solve is then the whole problem's, restricted to its symmetric part). */
ry_status mps_assemble(ry_sim *sim, mps *M, size_t nunk, int viscous, double dt, double diag_extra,
                       const int32_t *col, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int fold = col != NULL;
    if (!fold) col = M->unk;
    const double cl = ry_mps_laplacian_coefficient(sim->dim, M->lambda, M->n0l);
    size_t rowmax = 1;
    for (size_t i = 0; fold && i < n; ++i)
        if (M->lend[i] - sim->nl.offset[i] + 1 > rowmax)
            rowmax = M->lend[i] - sim->nl.offset[i] + 1;
    /* Row lengths (diagonal included) in parallel, their offsets, then the rows. */
    ry_csr *A = &M->A;
    RY_TRY(ry_csr_reserve(A, nunk, 0, err));
    int ok = 1;
#pragma omp parallel reduction(&& : ok)
    {
        uint32_t *cols = fold ? malloc(rowmax * sizeof *cols) : NULL;
        ok = !fold || cols;
#pragma omp for schedule(dynamic, 256)
        for (size_t i = 0; i < n; ++i) {
            if (M->unk[i] < 0 || !ok) continue;
            size_t len = 1;
            if (fold)
                len += folded_columns(sim, M, i, col, cols);
            else
                for (size_t q = sim->nl.offset[i]; q < M->lend[i]; ++q) len += col[M->pj[q]] >= 0;
            A->row[(size_t)M->unk[i] + 1] = len;
        }
        free(cols);
    }
    RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (pressure rows)");
    RY_TRY(ry_csr_rows_from_lengths(A, err));
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (M->unk[i] < 0) continue;
        ry_csr_row row = ry_csr_row_begin(A, (size_t)M->unk[i], diag_extra);
        for (size_t q = sim->nl.offset[i]; q < M->lend[i]; ++q)
            if (!fold || !ry_sim_is_halo(sim, M->pj[q]))
                ry_csr_row_pair(&row, pair_coef(sim, M, i, q, viscous, dt, cl), col[M->pj[q]]);
        double self = 0; /* i's own image's coefficient */
        for (size_t q = sim->nl.offset[i]; fold && q < M->lend[i]; ++q) {
            const int32_t k = col[M->pj[q]];
            if (!ry_sim_is_halo(sim, M->pj[q])) continue;
            const double a = pair_coef(sim, M, i, q, viscous, dt, cl);
            if (k < 0 || k != M->unk[i]) {
                size_t e = row.pdiag + 1;
                while (k >= 0 && e < row.p && A->col[e] != (uint32_t)k) ++e;
                if (k >= 0 && e < row.p) { /* the column of an own neighbour, or of a copy */
                    A->val[e] -= a;
                    row.diag += a;
                } else {
                    ry_csr_row_pair(&row, a, k);
                }
            } else {
                row.diag += a;
                self += a;
            }
        }
        ry_csr_row_end(&row);
        A->val[row.pdiag] -= self;
    }
    return RY_OK;
}

/* A free-surface particle stands half a spacing inside the surface it represents, so under a
 * body force g its pressure is the head of that half spacing, rho g.n l0 / 2, with n the
 * inward direction (towards the neighbours, sum_j w (x_j - x_i) normalised): zero on a surface
 * that faces down or sideways. With p = 0 on the particles instead, the pressure under the
 * surface of a column at rest falls short of rho g h by rho g l0 / 2 at every depth
 * (docs/validation.md). Added to the Dirichlet values in pd. */
static void surface_head(ry_sim *sim, mps *M) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const double l0 = sim->dx;
    if (sim->gravity[0] == 0 && sim->gravity[1] == 0 && sim->gravity[2] == 0) return;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < ps->n; ++i) {
        if (M->role[i] != ROLE_SURFACE || ps->kind[i] != RY_KIND_FLUID) continue;
        double in[3] = {0, 0, 0}, nin = 0, gin = 0;
        for (size_t q = sim->nl.offset[i]; q < M->gend[i]; ++q) {
            double dx[3];
            if (ry_sim_separation(sim, i, M->pj[q], dx) <= 0) continue;
            const double w = ry_mps_weight_tamai(M->pr[q], M->re_g);
            for (int a = 0; a < dim; ++a) in[a] += w * dx[a];
        }
        for (int a = 0; a < dim; ++a) {
            nin += in[a] * in[a];
            gin += sim->gravity[a] * in[a];
        }
        if (nin > 0 && gin > 0)
            M->pd[i] += 0.5 * l0 * sim->mat[ps->material[i]].density * gin / sqrt(nin);
    }
    if (sim->par) sim->par->sync(sim, M->pd, 1, 0);
}

/* The aggregates of the deflated pressure solve: the unknowns grouped by the cubes of side
 * defl spacings they lie in (a grid over their bounding box; empty cubes take no aggregate),
 * numbered in the grid's order, so that the coarse matrix is banded (neighbouring cubes differ
 * by at most a layer of the grid). Where that gives more than MAX_AGG aggregates the side
 * doubles. */
enum { MAX_AGG = 4000 };
static ry_status aggregates(const ry_sim *sim, mps *M, size_t nunk, ry_error *err) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    int first = 1;
    for (size_t i = 0; i < n; ++i) {
        if (M->unk[i] < 0) continue;
        for (int d = 0; d < dim; ++d) {
            const double v = ps->f[RY_F_X + d][i];
            if (first || v < lo[d]) lo[d] = v;
            if (first || v > hi[d]) hi[d] = v;
        }
        first = 0;
    }
    M->D.m = 0; /* (positions not finite: no deflation; the solve reports the failure) */
    for (int d = 0; d < dim; ++d)
        if (!isfinite(lo[d]) || !isfinite(hi[d])) return RY_OK;
    RY_TRY(ry_csr_deflation_reserve(&M->D, nunk, MAX_AGG, err));
    for (double side = (double)M->defl * sim->dx;; side *= 2) {
        double span[3] = {1, 1, 1};
        for (int d = 0; d < dim; ++d) span[d] = floor((hi[d] - lo[d]) / side) + 1;
        if (span[0] * span[1] * span[2] > 64.0 * (double)nunk + 4096)
            continue; /* a grid far finer than the unknowns */
        const size_t nc[3] = {(size_t)span[0], (size_t)span[1], (size_t)span[2]},
                     cells = nc[0] * nc[1] * nc[2];
        if (cells > M->dmap_cap) {
            int32_t *p = realloc(M->dmap, cells * sizeof *p);
            RY_CHECK(err, p, RY_ERR_NOMEM, "out of memory (deflation grid: %zu cells)", cells);
            M->dmap = p;
            M->dmap_cap = cells;
        }
        for (size_t k = 0; k < cells; ++k) M->dmap[k] = -1;
        for (size_t i = 0; i < n; ++i) { /* the cell of each unknown (in agg for now) */
            if (M->unk[i] < 0) continue;
            size_t cell = 0;
            for (int d = dim - 1; d >= 0; --d) {
                const double f = floor((ps->f[RY_F_X + d][i] - lo[d]) / side);
                cell = cell * nc[d] + (f <= 0 ? 0 : f >= (double)nc[d] ? nc[d] - 1 : (size_t)f);
            }
            M->dmap[cell] = 0;
            M->D.agg[M->unk[i]] = (uint32_t)cell;
        }
        size_t m = 0;
        for (size_t k = 0; k < cells; ++k)
            if (M->dmap[k] == 0) M->dmap[k] = (int32_t)++m;
        if (m > MAX_AGG) continue;
        for (size_t u = 0; u < nunk; ++u) M->D.agg[u] = (uint32_t)(M->dmap[M->D.agg[u]] - 1);
        M->D.m = m;
        return RY_OK;
    }
}

/* Pressure Poisson equation at x*: unknowns are the inner fluid and the wall particles (not the
 * walls out of it, wall_out). */
ry_status mps_pressure(ry_sim *sim, mps *M, double dt, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    /* Symmetry planes: the unknowns are the set's own, a copy's column its original's (the
     * pressure is even across a mirror), and the system is solved in one piece. */
    const int fold = sim->par && !ry_sim_distributed(sim);
    const double ta = ry_wall_time();
    size_t nunk = 0, nwall = 0;
    for (size_t i = 0; i < n; ++i) {
        const int u = (M->role[i] == ROLE_FLUID || M->role[i] == ROLE_WALL) &&
                      !wall_out(sim, M, i) && !(fold && ry_sim_is_halo(sim, i));
        M->unk[i] = u ? (int32_t)nunk++ : -1;
        nwall += u && ps->kind[i] != RY_KIND_FLUID;
    }
    M->total_unk += (double)nunk;
    M->total_wunk += (double)nwall;
    for (size_t i = 0; fold && i < n; ++i) {
        size_t o;
        unsigned axes;
        M->ucol[i] = sim->par->copy_of(sim, i, &o, &axes) ? M->unk[o] : M->unk[i];
    }
    /* Compressibility (Ikeda et al. 2001): rho alpha / dt^2 p on the diagonal, with the
     * largest density (a bound; exact for one material). */
    double rho_max = 0;
    for (int m = 0; m < sim->nmat; ++m) rho_max = fmax(rho_max, sim->mat[m].density);
    if (M->alpha == 0) { /* a closed domain leaves the pressure without a reference value */
        size_t nsurf = 0;
        for (size_t i = 0; i < n; ++i) nsurf += M->role[i] == ROLE_SURFACE;
        if (sim->par) nsurf = (size_t)sim->par->sum(sim, (double)nsurf);
        RY_CHECK(err, nsurf > 0 || nunk == 0, RY_ERR_INPUT,
                 "MPS: no free-surface particle, so the pressure equation has no reference value "
                 "(a closed or periodic domain): set scheme.compressibility (e.g. 1e-9 1/Pa)");
    }
    RY_TRY(mps_assemble(sim, M, nunk, 0, dt, M->alpha * rho_max / (dt * dt), fold ? M->ucol : NULL,
                        err));
    const double *nd = ps->f[M->f_nd];
    const double g = M->gamma;
    /* Dirichlet values: 0, or the Laplace jump sigma kappa with CSF in pressure form; plus,
     * on the fluid's surface particles, the pressure half a spacing under the surface. */
    if (M->csf_pressure)
        mps_csf_dirichlet(sim, M);
    else
        for (size_t i = 0; i < n; ++i) M->pd[i] = 0;
    if (M->surf_head) surface_head(sim, M);
    const int dirichlet = M->csf_pressure || M->surf_head;
    /* the rows with a surface particle among their pairs, which are symmetric at x* (every
     * row built): the others have no Dirichlet term to add */
    uint8_t *near = M->near_surf;
    if (dirichlet) {
        memset(near, sim->par != NULL, n); /* (a halo copy's row may lack pairs) */
        for (size_t i = 0; i < n; ++i)
            if (M->role[i] == ROLE_SURFACE)
                for (size_t q = sim->nl.offset[i]; q < M->lend[i]; ++q) near[M->pj[q]] = 1;
    }
    const double rel = M->re_l, cl = ry_mps_laplacian_coefficient(sim->dim, M->lambda, M->n0l);
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (M->unk[i] < 0) continue;
        const double rho = sim->mat[ps->material[i]].density;
        double b = g * rho / (dt * dt) * (M->dilate ? nd[i] - 1.0 : fmax(nd[i] - 1.0, 0.0));
        if (g < 1.0) b -= (1.0 - g) * rho / dt * M->divu[i]; /* (mps_number_density) */
        for (size_t q = sim->nl.offset[i]; dirichlet && near[i] && q < M->lend[i]; ++q)
            if (M->role[M->pj[q]] == ROLE_SURFACE)
                b += cl * ry_mps_weight_tamai(M->pr[q], rel) * M->pd[M->pj[q]];
        if (M->wall_neumann) b += wall_head_source(sim, M, i, cl);
        M->b[M->unk[i]] = b;
        M->xs[M->unk[i]] = ps->f[RY_F_P][i];
    }
    int it;
    double res;
    ry_csr_dist dd;
    const double t0 = ry_wall_time();
    M->passemble_s += t0 - ta;
    if (M->precond == RY_PRECOND_BOOMERAMG && !ry_sim_distributed(sim)) {
        const double *bb = M->b;
        const ry_amg_slots sl = mps_slots(sim, M);
        RY_TRY(ry_amg_pcg(&M->amg, &M->A, &sl, 1, &bb, &M->xs, M->tol, (int)M->max_iter, &it, &res,
                          err));
    } else if (M->defl > 0 && !ry_sim_distributed(sim)) {
        const double *bb = M->b;
        RY_TRY(aggregates(sim, M, nunk, err));
        RY_TRY(ry_csr_pcg_deflated(&M->A, 1, &bb, &M->xs, &M->D, M->tol, (int)M->max_iter, &it,
                                   &res, err));
    } else {
        RY_TRY(ry_csr_pcg(&M->A, M->b, M->xs, M->tol, (int)M->max_iter, &it, &res,
                          fold ? NULL : mps_dist_of(sim, M, 0, &dd), err));
    }
    M->psolve_s += ry_wall_time() - t0;
    M->psolves++;
    M->total_piters += it;
    M->last_iters = it;
    M->total_iters += it;
    double *p = ps->f[RY_F_P];
    for (size_t i = 0; i < n; ++i) {
        double v = M->unk[i] >= 0 ? M->xs[M->unk[i]] : M->role[i] == ROLE_SURFACE ? M->pd[i] : 0.0;
        if (M->clamp && v < 0) v = 0;
        p[i] = v;
    }
    if (sim->par) sim->par->sync(sim, p, 1, 0);
    if (M->wall_extrapolate || M->thin_neumann) {
        const double tw = ry_wall_time();
        mps_extrapolate_walls(sim, M);
        if (sim->par) sim->par->sync(sim, p, 1, 0);
        M->pwall_s += ry_wall_time() - tw;
    }
    return RY_OK;
}

/* Pressure gradient (eq. 5) and the correction u' = -dt/rho grad p at x*: v = u* + u',
 * x = x* + dt u'. Neighbours: fluid and wall particles (dummies carry no pressure). */
void mps_correct(ry_sim *sim, mps *M, double dt) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const size_t n = ps->n;
    const double re = M->re_g;
    const double *p = ps->f[RY_F_P];
    double *gx = M->xs; /* dim per particle */
    /* the pair terms' first half as a vector loop (3D, no periodic side) */
    const int lanes = ry_box_plain(&sim->box) == 3;
    size_t rowmax = 0;
    for (size_t i = 0; lanes && i < n; ++i)
        if (M->gend[i] - sim->nl.offset[i] > rowmax) rowmax = M->gend[i] - sim->nl.offset[i];
    const double *x0 = ps->f[RY_F_X], *x1 = ps->f[RY_F_X + (dim > 1)],
                 *x2 = ps->f[RY_F_X + (dim > 2 ? 2 : 0)];
#pragma omp parallel
    {
        /* each pair's separation, squared distance and w / r^2 (lanes) */
        double *buf = lanes ? malloc(5 * (rowmax + 1) * sizeof *buf) : NULL;
        double *bx = buf, *by = buf + rowmax + 1, *bz = by + rowmax + 1, *br2 = bz + rowmax + 1,
               *bwr = br2 + rowmax + 1;
#pragma omp for schedule(dynamic, 64)
        for (size_t i = 0; i < n; ++i) {
            if (ps->kind[i] != RY_KIND_FLUID) continue;
            double pmin = p[i];
            /* CSF in pressure form: a surface particle measures the gradient from its own pressure,
             * the Laplace jump at its place. With the neighbourhood's least pressure (eq. 5) a
             * protruding particle, whose larger curvature gives it the larger jump, would lose the
             * difference that pushes it back, and the surface roughens until the drop breaks up. */
            const int own = M->csf_pressure && M->role[i] == ROLE_SURFACE;
            for (size_t q = sim->nl.offset[i]; M->pmin_on && !own && q < M->gend[i]; ++q)
                if (M->role[M->pj[q]] != ROLE_DUMMY) {
                    const uint32_t j = M->pj[q];
                    double pj = p[j];
                    if (thin_normal(M, j)) { /* the side of a thin wall needs the separation */
                        double dx[3];
                        ry_sim_separation(sim, i, j, dx);
                        pj = grad_pressure(M, p, j, dx);
                    }
                    pmin = fmin(pmin, pj);
                }
            double m[3][3] = {{0}}, g[3] = {0, 0, 0}, x[3] = {0, 0, 0};
            if (buf) { /* the same values as sep() and the weight below, eight pairs at a time */
                const size_t q0 = sim->nl.offset[i], nb = M->gend[i] - q0;
                const uint32_t *jj = M->pj + q0;
                const double *rr = M->pr + q0, xi0 = x0[i], xi1 = x1[i], xi2 = x2[i];
#pragma omp simd
                for (size_t k = 0; k < nb; ++k) {
                    const uint32_t j = jj[k];
                    const double e0 = x0[j] - xi0, e1 = x1[j] - xi1, e2 = x2[j] - xi2;
                    const double r2 = e0 * e0 + e1 * e1 + e2 * e2, s = rr[k] / re - 1.0;
                    bx[k] = e0;
                    by[k] = e1;
                    bz[k] = e2;
                    br2[k] = r2;
                    bwr[k] = (rr[k] < re ? s * s : 0.0) / r2;
                }
                for (size_t k = 0; k < nb; ++k) {
                    const uint32_t j = jj[k];
                    if (M->role[j] == ROLE_DUMMY || br2[k] <= 0) continue;
                    const double dx[3] = {bx[k], by[k], bz[k]}, wr = bwr[k];
                    ry_grad_value_add(g, wr, grad_pressure(M, p, j, dx) - pmin, dx, 3);
                    ry_grad_moment_add(m, wr, dx, 3);
                }
            } else
                for (size_t q = sim->nl.offset[i]; q < M->gend[i]; ++q) {
                    const uint32_t j = M->pj[q];
                    double dx[3];
                    const double r2 = ry_sim_separation(sim, i, j, dx);
                    if (M->role[j] == ROLE_DUMMY || r2 <= 0) continue;
                    const double w = ry_mps_weight_tamai(M->pr[q], re), wr = w / r2;
                    ry_grad_value_add(g, wr, grad_pressure(M, p, j, dx) - pmin, dx, dim);
                    ry_grad_moment_add(m, wr, dx, dim);
                }
            ry_mps_pressure_gradient(m, g, dim, M->n0g, M->grad != GRAD_STANDARD, x);
            for (int a = 0; a < dim; ++a) gx[dim * i + a] = x[a];
        }
        free(buf);
    }
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        const double rho = sim->mat[ps->material[i]].density;
        for (int d = 0; d < dim; ++d) {
            const double du = -dt / rho * gx[dim * i + d];
            ps->f[RY_F_VX + d][i] = ps->f[M->f_vs[d]][i] + du;
            ps->f[RY_F_X + d][i] += dt * du;
        }
    }
}
