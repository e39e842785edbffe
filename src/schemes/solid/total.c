/* SPH for elastic solids, total-Lagrangian form (seed 000; docs/reference/solid.md): the neighbour
 * list, kernel gradients and corrections of the reference configuration, the stresses (with the
 * strain-gradient term of gradient integration) and the forces, and the residual of a static
 * solution. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/corrected.h"
#include "schemes/solid/solid_internal.h"
#include "schemes/solid/solid_pair.h"

size_t ry_solid_reverse_pair(const ry_nlist *nl, size_t i, size_t j) {
    size_t lo = nl->offset[j], hi = nl->offset[j + 1];
    while (lo < hi) { /* i in the sorted row of j */
        const size_t mid = lo + (hi - lo) / 2;
        if (nl->j[mid] < i)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

/* Neighbour list, kernel gradients and corrections in the reference configuration. */
ry_status ry_solid_tl_build(ry_sim *sim, solid *s, ry_error *err) {
    ry_particles *ps = &sim->ps;
    /* Distributed: the subdomains and their halo, once (the reference configuration stays). */
    if (sim->par) RY_TRY(sim->par->redistribute(sim, sim->kernel.radius, err));
    const size_t n = ps->n;
    const int dim = sim->dim;
    const ry_kernel *k = &sim->kernel;
    const double *X[3] = {ps->f[s->f_X[0]], ps->f[s->f_X[1]], dim > 2 ? ps->f[s->f_X[2]] : NULL};
    RY_TRY(ry_cells_build(&s->cells, &sim->box, k->radius, n, X, err));
    RY_TRY(ry_nlist_build_cells(&s->nl, &s->cells, &sim->box, k->radius, n, X, err));
    const size_t npair = s->nl.offset[n];
    s->G = malloc((npair ? npair : 1) * (size_t)dim * sizeof *s->G);
    if (s->integration == INTEGRATION_GRADIENT) {
        s->H = malloc((npair ? npair : 1) * (size_t)(dim * dim) * sizeof *s->H);
        s->Q = calloc(n * 27, sizeof *s->Q);
        RY_CHECK(err, s->H && s->Q, RY_ERR_NOMEM, "out of memory");
    }
    s->rev = malloc((npair ? npair : 1) * sizeof *s->rev);
    s->vol = malloc(n * sizeof *s->vol);
    s->A = malloc(n * 9 * sizeof *s->A);
    s->r2 = malloc(n * sizeof *s->r2);
    s->F = malloc(n * 9 * sizeof *s->F);
    s->mscale = malloc(n * sizeof *s->mscale);
    s->hgc = malloc((npair ? npair : 1) * sizeof *s->hgc);
    RY_CHECK(err, s->G && s->rev && s->vol && s->A && s->r2 && s->F && s->mscale && s->hgc,
             RY_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < n; ++i)
        s->vol[i] = ps->f[RY_F_MASS][i] / sim->mat[ps->material[i]].density;
    ry_status st = RY_OK;
#pragma omp parallel for schedule(static) if (n >= RY_SOLID_PARALLEL_MIN)
    for (size_t i = 0; i < n; ++i) {
        double xi[3] = {0, 0, 0};
        for (int d = 0; d < dim; ++d) xi[d] = X[d][i];
        const size_t o = s->nl.offset[i], nn = s->nl.offset[i + 1] - o;
        const int mi = ps->material[i];
        double ms = 1.0;
        for (size_t q = o; q < o + nn; ++q) {
            const uint32_t j = s->nl.j[q];
            const int mj = ps->material[j];
            double R2 = 0;
            for (int d = 0; d < dim; ++d) R2 += (X[d][j] - xi[d]) * (X[d][j] - xi[d]);
            const double R = sqrt(R2);
            s->hgc[q] = R > 0 && R < k->radius
                            ? 0.5 * (s->E[mi] + s->E[mj]) * s->vol[j] * ry_kernel_w(k, R) / R2
                            : 0.0;
            if (s->relax != RELAX_NONE) ms = fmax(ms, s->modulus[mj] / s->modulus[mi]);
        }
        s->mscale[i] = ms;
        for (size_t q = o; q < o + nn; ++q)
            s->rev[q] = ry_solid_reverse_pair(&s->nl, i, s->nl.j[q]);
        ry_error e1;
        ry_status si = RY_OK;
        if (s->correction == CORR_QUADRATIC) {
            si = ry_corr_quadratic_gradient(k, xi, nn, s->nl.j + o, X, s->vol,
                                            s->G + (size_t)dim * o,
                                            s->H ? s->H + (size_t)(dim * dim) * o : NULL, &e1);
        } else {
            ry_corr cr;
            si = ry_corr_build(
                &cr, s->correction == CORR_LINEAR ? RY_CORRECTION_LINEAR : RY_CORRECTION_NONE, k,
                xi, s->vol[i], nn, s->nl.j + o, X, s->vol, &e1);
            for (size_t q = o; q < o + nn && si == RY_OK; ++q) {
                const size_t j = s->nl.j[q];
                double xj[3] = {0, 0, 0}, g[3];
                for (int d = 0; d < dim; ++d) xj[d] = X[d][j];
                ry_corr_grad_w(&cr, k, xi, xj, g);
                for (int d = 0; d < dim; ++d) s->G[q * (size_t)dim + (size_t)d] = s->vol[j] * g[d];
            }
        }
        if (si != RY_OK) {
#pragma omp critical
            if (st == RY_OK) {
                st = si;
                if (err) *err = e1;
            }
        }
    }
    for (size_t q = 0; q < npair && st == RY_OK; ++q)
        RY_CHECK(err, s->rev[q] < npair, RY_ERR_INTERNAL, "solid: asymmetric neighbour list");
    if (st != RY_OK) ry_error_prefix(err, "solid: ");
    s->built = 1;
    return st;
}

/* ---- forces ------------------------------------------------------------------------------- */

/* The strain-gradient term of the cell energy: with the strain varying linearly over the
 * particle's cell (a square or cube of side c, c^d = V_i), the cell's energy is
 * V_i (Psi(E_i) + (c^2/24) sum_k dE_k : C : dE_k), dE_k = d E / d X_k = sym(F^T D_k), D_k = d F /
 * d X_k from the second-derivative weights of the quadratic fit. Without it (nodal integration)
 * a beam of n particles across its thickness bends with I (1 - 1/n^2) instead of I. Adds
 * P' = (c^2/12) sum_k D_k T_k (T_k = C : dE_k) to the first Piola-Kirchhoff stress and stores
 * the stresses Q_k = (c^2/12) F T_k that act through the second-derivative weights. */
RY_SOLID_INLINE void strain_gradient(ry_sim *sim, solid *s, size_t i, const double *F, double *psi,
                                     const int dim) {
    const ry_particles *ps = &sim->ps;
    const double *x[3] = {ps->f[RY_F_X], ps->f[RY_F_Y], dim > 2 ? ps->f[RY_F_Z] : NULL};
    const double c12 = pow(s->vol[i], 2.0 / dim) / 12.0;
    const int m = ps->material[i];
    double D[3][9] = {{0}};
    for (size_t q = s->nl.offset[i]; q < s->nl.offset[i + 1]; ++q) {
        const size_t j = s->nl.j[q];
        const double *h = s->H + q * (size_t)(dim * dim);
        for (int a = 0; a < dim; ++a) {
            const double dxa = x[a][j] - x[a][i];
            for (int k = 0; k < dim; ++k)
                for (int b = 0; b < dim; ++b) D[k][3 * a + b] += dxa * h[dim * k + b];
        }
    }
    double *P = s->A + 9 * i, *Q = s->Q + 27 * i;
    for (int k = 0; k < dim; ++k) {
        double dE[9] = {0}, T[9] = {0}, tr = 0;
        for (int a = 0; a < dim; ++a)
            for (int b = 0; b < dim; ++b) {
                double t = 0;
                for (int c = 0; c < dim; ++c)
                    t += F[3 * c + a] * D[k][3 * c + b] + F[3 * c + b] * D[k][3 * c + a];
                dE[3 * a + b] = 0.5 * t;
            }
        for (int a = 0; a < dim; ++a) tr += dE[4 * a];
        for (int a = 0; a < dim; ++a)
            for (int b = 0; b < dim; ++b) {
                T[3 * a + b] = 2 * s->mu[m] * dE[3 * a + b] + (a == b ? s->lam[m] * tr : 0.0);
                *psi += 0.5 * c12 * T[3 * a + b] * dE[3 * a + b];
            }
        for (int a = 0; a < dim; ++a)
            for (int b = 0; b < dim; ++b) {
                double dt = 0, ft = 0;
                for (int c = 0; c < dim; ++c) {
                    dt += D[k][3 * a + c] * T[3 * c + b];
                    ft += F[3 * a + c] * T[3 * c + b];
                }
                P[3 * a + b] += c12 * dt;
                Q[9 * k + 3 * a + b] = c12 * ft;
            }
    }
}

/* Pass 1: F_i, stress, A_i = P_i L_i for every particle (clamped ones included); particle i,
 * inlined with a literal dim into the loop of stresses() (RY_SOLID_ROWS). */
RY_SOLID_INLINE void stresses_dim(ry_sim *sim, solid *s, size_t i, const int dim) {
    ry_particles *ps = &sim->ps;
    const double *x[3] = {ps->f[RY_F_X], ps->f[RY_F_Y], dim > 2 ? ps->f[RY_F_Z] : NULL};
    double F[9] = {0}, E[9] = {0}, S[9] = {0}, P[9] = {0};
    for (size_t q = s->nl.offset[i]; q < s->nl.offset[i + 1]; ++q) {
        const size_t j = s->nl.j[q];
        const double *g = s->G + q * (size_t)dim;
        for (int a = 0; a < dim; ++a) {
            const double dxa = x[a][j] - x[a][i];
            for (int b = 0; b < dim; ++b) F[3 * a + b] += dxa * g[b];
        }
    }
    for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) {
            double t = 0;
            for (int c = 0; c < dim; ++c) t += F[3 * c + a] * F[3 * c + b];
            E[3 * a + b] = 0.5 * (t - (a == b));
        }
    const int m = ps->material[i];
    double tr = 0, psi = 0;
    for (int a = 0; a < dim; ++a) tr += E[4 * a];
    for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) {
            S[3 * a + b] = 2 * s->mu[m] * E[3 * a + b] + (a == b ? s->lam[m] * tr : 0.0);
            psi += 0.5 * S[3 * a + b] * E[3 * a + b];
        }
    for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) {
            double t = 0;
            for (int c = 0; c < dim; ++c) t += F[3 * a + c] * S[3 * c + b];
            P[3 * a + b] = t;
        }
    const int no_energy = s->clamp == CLAMP_FACE && ps->kind[i] != RY_KIND_SOLID;
    if (no_energy) {
        memset(P, 0, sizeof P);
        psi = 0;
    }
    memcpy(s->F + 9 * i, F, sizeof F);
    memcpy(s->A + 9 * i, P, sizeof P);
    if (s->H && !no_energy) strain_gradient(sim, s, i, F, &psi, dim);
    /* Cauchy stress sigma = P F^T / J for output: pressure -tr(sigma)/dim, density rho0/J */
    double J = dim == 2 ? F[0] * F[4] - F[1] * F[3]
                        : F[0] * (F[4] * F[8] - F[5] * F[7]) - F[1] * (F[3] * F[8] - F[5] * F[6]) +
                              F[2] * (F[3] * F[7] - F[4] * F[6]);
    double trs = 0;
    for (int a = 0; a < dim; ++a)
        for (int c = 0; c < dim; ++c) trs += P[3 * a + c] * F[3 * a + c];
    ps->f[RY_F_P][i] = J > 0 ? -trs / (J * dim) : 0.0;
    ps->f[RY_F_RHO][i] = sim->mat[m].density / (J > 0 ? J : 1.0);
    ps->f[s->f_psi][i] = psi;
}

/* Pass 2: the acceleration of particle i (zero where it is not free; inlined as
 * stresses_dim). */
RY_SOLID_INLINE void forces_dim(ry_sim *sim, solid *s, size_t i, const int dim) {
    ry_particles *ps = &sim->ps;
    const double *x[3] = {ps->f[RY_F_X], ps->f[RY_F_Y], dim > 2 ? ps->f[RY_F_Z] : NULL};
    const double *X[3] = {ps->f[s->f_X[0]], ps->f[s->f_X[1]], dim > 2 ? ps->f[s->f_X[2]] : NULL};
    const double hg = s->hourglass;
    if (ps->kind[i] != RY_KIND_SOLID) {
        ry_solid_accelerate(sim, s, i, NULL, dim);
        return;
    }
    double f[3] = {0, 0, 0}, fh[3] = {0, 0, 0};
    const double *Ai = s->A + 9 * i, *Fi = s->F + 9 * i;
    const double vi = s->vol[i];
    for (size_t q = s->nl.offset[i]; q < s->nl.offset[i + 1]; ++q) {
        const size_t j = s->nl.j[q];
        const double *gij = s->G + q * (size_t)dim, *gji = s->G + s->rev[q] * (size_t)dim;
        const double *Aj = s->A + 9 * j;
        const double vj = s->vol[j];
        ry_solid_tl_pair(f, Ai, vi, gij, Aj, vj, gji, dim);
        if (s->H) { /* strain-gradient stresses through the second-derivative weights */
            const double *hij = s->H + q * (size_t)(dim * dim);
            const double *hji = s->H + s->rev[q] * (size_t)(dim * dim);
            ry_solid_tl_strain_gradient_pair(f, s->Q + 27 * i, vi, hij, s->Q + 27 * j, vj, hji,
                                             dim);
        }
        if (hg > 0) {
            /* e_ij = x_j - x_i - (F_i + F_j)/2 (X_j - X_i) */
            const double *Fj = s->F + 9 * j, cij = s->hgc[q];
            double Xji[3] = {0, 0, 0}, xji[3] = {0, 0, 0};
            for (int a = 0; a < dim; ++a) {
                Xji[a] = X[a][j] - X[a][i];
                xji[a] = x[a][j] - x[a][i];
            }
            ry_solid_tl_hourglass(fh, xji, Xji, Fi, Fj, cij, dim);
        }
    }
    for (int a = 0; a < dim; ++a) f[a] += vi * hg * fh[a];
    ry_solid_accelerate(sim, s, i, f, dim);
}

void ry_solid_accelerate(ry_sim *sim, solid *s, size_t i, const double *f, int dim) {
    ry_particles *ps = &sim->ps;
    if (!f) {
        for (int a = 0; a < dim; ++a) ps->f[RY_F_AX + a][i] = 0;
        s->r2[i] = 0;
        return;
    }
    const double m = ps->f[RY_F_MASS][i];
    double r2 = 0;
    for (int a = 0; a < dim; ++a) {
        double ft = f[a] + ps->f[s->f_fext[a]][i] + m * sim->gravity[a];
        ps->f[RY_F_AX + a][i] = ft / (m * s->mscale[i]);
        r2 += ft * ft;
    }
    s->r2[i] = r2;
}

void ry_solid_residual_update(ry_sim *sim, solid *s) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    /* summed in particle order (the same for any thread count); distributed, over the ranks */
    double net = 0, ext = 0;
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_SOLID || ry_sim_is_halo(sim, i)) continue;
        net += s->r2[i];
        for (int a = 0; a < dim; ++a) {
            double fe = ps->f[s->f_fext[a]][i] + ps->f[RY_F_MASS][i] * sim->gravity[a];
            ext += fe * fe;
        }
    }
    if (sim->par) {
        net = sim->par->sum(sim, net);
        ext = sim->par->sum(sim, ext);
    }
    s->residual = ext > 0 ? sqrt(net / ext) : sqrt(net);
}

/* The pair loops with the dimension a compile-time constant. */
static void stresses(ry_sim *sim, solid *s) {
    RY_SOLID_ROWS(sim, i, stresses_dim(sim, s, i, 2), stresses_dim(sim, s, i, 3));
}
/* Accelerations of the free particles and the residual. */
static void forces(ry_sim *sim, solid *s) {
    RY_SOLID_ROWS(sim, i, forces_dim(sim, s, i, 2), forces_dim(sim, s, i, 3));
    ry_solid_residual_update(sim, s);
}

void ry_solid_tl_forces(ry_sim *sim, solid *s) {
    stresses(sim, s);
    forces(sim, s);
}
