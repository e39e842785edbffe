/* SPH for elastic solids, updated-Lagrangian form (seed 000 eq. 14-18, SPEC section 2; Gray,
 * Monaghan & Swift 2001; docs/reference/solid.md).
 *
 * Every quantity refers to the current configuration; the neighbour list follows the particles
 * (ry_sim_neighbors). With V_j = m_j / rho_j and gradient weights G_ij built from the current
 * positions at every step (scheme.correction: none, V_j grad W_ij; linear, V_j L_i grad W_ij with
 * L_i = (sum_j V_j grad W_ij (x) (x_j - x_i))^-1, seed eq. 10-12; quadratic, the weights of the
 * quadratic least-squares fit of include/ryushi/corrected.h):
 *
 *   velocity gradient  (grad v)_i = sum_j (v_j - v_i) (x) G_ij
 *   continuity         d rho_i / dt = -rho_i tr (grad v)_i                               (eq. 17)
 *   deviatoric stress  dS/dt = 2 G (eps_dot - tr(eps_dot)/d I) + S Omega^T + Omega S    (eq. 16)
 *                      (Jaumann rate; eps_dot, Omega the symmetric and antisymmetric parts)
 *   pressure           P = c0^2 (rho - rho0), c0^2 = K / rho0                           (eq. 18)
 *   stress             sigma = -P I + S
 *   momentum           m_i dv_i/dt = sum_j [V_i sigma_i G_ij - V_j sigma_j G_ji]
 *                                   + sum_j m_i m_j (f_ij^n (R_i + R_j) - Pi_ij I) grad W_ij
 *                                   + f_ext,i + m_i g
 *
 * The stress term is the one whose power is exactly -sum_i V_i sigma_i : (grad v)_i, so the
 * spatial discretisation exchanges energy between motion and strain without loss or gain.
 *
 * In d = 2 dimensions the model is the in-plane part of plane strain (K = lambda + G, trace
 * taken over the plane: the same in-plane stresses as the 3D deviator with the 1/3 and the 3D
 * bulk modulus) or of plane stress (lambda -> lambda* = 2 lambda G / (lambda + 2 G)):
 * K = lambda + 2 G / d throughout.
 *
 * Artificial viscosity (Monaghan 1992): Pi_ij = (-alpha c mu_ij + beta mu_ij^2) / rho_ij for
 * approaching pairs, mu_ij = h v_ij . x_ij / (r_ij^2 + 0.01 h^2), c the P-wave speed.
 * Artificial stress against the tensile instability (Monaghan 2000; Gray, Monaghan & Swift
 * 2001): in the principal axes of sigma_i, R_i = -epsilon sigma_i^aa / rho_i^2 for each tensile
 * principal stress (0 for a compressive one), rotated back; f_ij = W(r_ij) / W(dx).
 *
 * Clamped particles (kind wall): with scheme.clamp: block (the default here) a block of the
 * material held fixed, whose density and stress evolve with the velocity gradient that the
 * moving neighbours give them; with clamp: face they hold no stress and only supply v = 0 to
 * the gradients of their neighbours. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/corrected.h"
#include "physics/artificial_viscosity_monaghan1992.h"
#include "schemes/solid/solid_internal.h"
#include "schemes/solid/solid_pair.h"

/* Components of the symmetric deviatoric stress: xx, yy, zz, xy, xz, yz. */
static const int comp_a[6] = {0, 1, 2, 0, 0, 1}, comp_b[6] = {0, 1, 2, 1, 2, 2};
static const char *const comp_name[6] = {"deviatoric_stress_xx", "deviatoric_stress_yy",
                                         "deviatoric_stress_zz", "deviatoric_stress_xy",
                                         "deviatoric_stress_xz", "deviatoric_stress_yz"};

ry_status ry_solid_ul_init(ry_sim *sim, ry_case *c, solid *s, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    double one = 1.0, zero = 0.0, eps = 0.3, expo = 4.0;
    RY_TRY(
        ry_case_double(c, "scheme.artificial_viscosity.alpha", &one, 0.0, 10.0, &s->av_alpha, err));
    RY_TRY(
        ry_case_double(c, "scheme.artificial_viscosity.beta", &zero, 0.0, 10.0, &s->av_beta, err));
    RY_TRY(ry_case_double(c, "scheme.artificial_stress.epsilon", &eps, 0.0, 1.0, &s->as_eps, err));
    RY_TRY(ry_case_double(c, "scheme.artificial_stress.exponent", &expo, 1.0, 12.0, &s->as_n, err));
    s->K = calloc((size_t)sim->nmat, sizeof *s->K);
    RY_CHECK(err, s->K != NULL, RY_ERR_NOMEM, "out of memory");
    for (int m = 0; m < sim->nmat; ++m) s->K[m] = s->lam[m] + 2 * s->mu[m] / dim;
    for (int k = 0; k < 6; ++k) {
        s->f_S[k] = -1;
        if (comp_a[k] >= dim || comp_b[k] >= dim) continue;
        RY_TRY(ry_particles_add_field(ps, comp_name[k], "Pa", -1, RY_FIELD_STATE | RY_FIELD_OUTPUT,
                                      &s->f_S[k], err));
        memset(ps->f[s->f_S[k]], 0, ps->n * sizeof(double));
    }
    const size_t n = ps->n ? ps->n : 1;
    s->Lc = malloc(9 * n * sizeof *s->Lc);
    s->sig = malloc(9 * n * sizeof *s->sig);
    s->Ras = malloc(9 * n * sizeof *s->Ras);
    s->mscale = malloc(n * sizeof *s->mscale);
    s->r2 = malloc(n * sizeof *s->r2);
    RY_CHECK(err, s->Lc && s->sig && s->Ras && s->mscale && s->r2, RY_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < ps->n; ++i) s->mscale[i] = 1.0;
    return RY_OK;
}

void ry_solid_ul_free(solid *s) {
    free(s->K);
    free(s->Lc);
    free(s->sig);
    free(s->Ras);
}

/* Eigenvalues lam and eigenvectors (the columns of Q) of the symmetric dim x dim block of A
 * (3 x 3, row-major) by cyclic Jacobi rotations. */
static void sym_eigen(int dim, const double *A, double *lam, double *Q) {
    double a[9];
    memcpy(a, A, sizeof a);
    for (int r = 0; r < 9; ++r) Q[r] = r % 4 == 0;
    for (int sweep = 0; sweep < 30; ++sweep) {
        double off = 0, diag = 0;
        for (int p = 0; p < dim; ++p) {
            diag += a[4 * p] * a[4 * p];
            for (int q = p + 1; q < dim; ++q) off += a[3 * p + q] * a[3 * p + q];
        }
        if (!(off > 1e-30 * diag)) break;
        for (int p = 0; p < dim; ++p)
            for (int q = p + 1; q < dim; ++q) {
                const double apq = a[3 * p + q];
                if (apq == 0) continue;
                const double th = (a[4 * q] - a[4 * p]) / (2 * apq);
                const double t = (th >= 0 ? 1.0 : -1.0) / (fabs(th) + sqrt(th * th + 1));
                const double cs = 1 / sqrt(t * t + 1), sn = t * cs;
                for (int k = 0; k < 3; ++k) { /* A P */
                    const double akp = a[3 * k + p], akq = a[3 * k + q];
                    a[3 * k + p] = cs * akp - sn * akq;
                    a[3 * k + q] = sn * akp + cs * akq;
                }
                for (int k = 0; k < 3; ++k) { /* P^T (A P) */
                    const double apk = a[3 * p + k], aqk = a[3 * q + k];
                    a[3 * p + k] = cs * apk - sn * aqk;
                    a[3 * q + k] = sn * apk + cs * aqk;
                }
                for (int k = 0; k < 3; ++k) { /* Q P */
                    const double qkp = Q[3 * k + p], qkq = Q[3 * k + q];
                    Q[3 * k + p] = cs * qkp - sn * qkq;
                    Q[3 * k + q] = sn * qkp + cs * qkq;
                }
            }
    }
    for (int p = 0; p < 3; ++p) lam[p] = p < dim ? a[4 * p] : 0.0;
}

/* Artificial stress of a particle: R = sum over tensile principal stresses sigma_a > 0 of
 * -epsilon sigma_a / rho^2 q_a (x) q_a. */
static void artificial_stress(int dim, double eps, double rho, const double *sig, double *R) {
    double lam[3], Q[9];
    memset(R, 0, 9 * sizeof *R);
    if (eps == 0) return;
    sym_eigen(dim, sig, lam, Q);
    for (int p = 0; p < dim; ++p) {
        if (!(lam[p] > 0)) continue;
        const double r = -eps * lam[p] / (rho * rho);
        for (int a = 0; a < dim; ++a)
            for (int b = 0; b < dim; ++b) R[3 * a + b] += r * Q[3 * a + p] * Q[3 * b + p];
    }
}

typedef struct point3 {
    double p[3];
} point3;
static point3 xi_of(const double *const x[3], size_t i, int dim) {
    point3 r = {{0, 0, 0}};
    for (int a = 0; a < dim; ++a) r.p[a] = x[a][i];
    return r;
}

/* Pass 1, particle i: velocity gradient, correction matrix, density rate, deviatoric stress
 * advanced by dt. */
RY_SOLID_INLINE void rates_dim(ry_sim *sim, solid *s, size_t i, double dt, const int dim) {
    ry_particles *ps = &sim->ps;
    const ry_kernel *k = &sim->kernel;
    const double r2max = k->radius * k->radius;
    const double *x[3] = {ps->f[RY_F_X], ps->f[RY_F_Y], dim > 2 ? ps->f[RY_F_Z] : NULL};
    const double *v[3] = {ps->f[RY_F_VX], ps->f[RY_F_VY], dim > 2 ? ps->f[RY_F_VZ] : NULL};
    const double *rho = ps->f[RY_F_RHO], *mass = ps->f[RY_F_MASS];
    double *drho = ps->f[RY_F_DRHO];
    const int corr = s->correction != CORR_NONE, quad = s->correction == CORR_QUADRATIC;
    double B[9] = {0}, Lv[9] = {0}, L[9] = {0}, gv[9] = {0};
    const size_t o = sim->nl.offset[i], nn = sim->nl.offset[i + 1] - o;
    if (quad) {
        /* weights of the quadratic fit: grad v = sum_j (v_j - v_i) (x) G_ij */
        ry_error e1;
        double *Gi = s->G + (size_t)dim * o;
        if (ry_corr_quadratic_gradient(k, xi_of(x, i, dim).p, nn, sim->nl.j + o, x, s->vol, Gi,
                                       NULL, &e1) != RY_OK)
            memset(Gi, 0, nn * (size_t)dim * sizeof *Gi);
        for (size_t q = o; q < o + nn; ++q) {
            const size_t j = sim->nl.j[q];
            double dv[3] = {0, 0, 0};
            for (int a = 0; a < dim; ++a) dv[a] = v[a][j] - v[a][i];
            ry_solid_gradient_add(Lv, dv, Gi + (q - o) * (size_t)dim, dim);
        }
    }
    for (size_t q = o; q < o + nn && !quad; ++q) {
        const size_t j = sim->nl.j[q];
        double d[3], r2 = 0;
        for (int a = 0; a < dim; ++a) {
            d[a] = x[a][j] - x[a][i];
            r2 += d[a] * d[a];
        }
        if (r2 >= r2max || r2 == 0) continue;
        const double r = sqrt(r2), f = -ry_kernel_dwdr(k, r) / r, vj = mass[j] / rho[j];
        double g[3]; /* V_j grad_i W_ij */
        for (int a = 0; a < dim; ++a) g[a] = vj * f * d[a];
        double dv[3] = {0, 0, 0};
        for (int a = 0; a < dim; ++a) dv[a] = v[a][j] - v[a][i];
        ry_solid_moment_add(B, g, d, dim);
        ry_solid_gradient_add(Lv, dv, g, dim);
    }
    ry_error e1;
    if (!corr || quad || ry_mat_inverse(dim, B, L, &e1) != RY_OK) {
        memset(L, 0, sizeof L);
        for (int a = 0; a < dim; ++a) L[4 * a] = 1;
    }
    memcpy(s->Lc + 9 * i, L, sizeof L);
    for (int a = 0; a < dim; ++a) /* grad v = Lv L^T */
        for (int b = 0; b < dim; ++b)
            for (int c = 0; c < dim; ++c) gv[3 * a + b] += Lv[3 * a + c] * L[3 * b + c];
    double tr = 0;
    for (int a = 0; a < dim; ++a) tr += gv[4 * a];
    drho[i] = -rho[i] * tr;
    if (dt == 0) return;
    double S[9] = {0}, Sd[9] = {0}; /* (Sd: read only where written) */
    for (int c = 0; c < 6; ++c)
        if (s->f_S[c] >= 0)
            S[3 * comp_a[c] + comp_b[c]] = S[3 * comp_b[c] + comp_a[c]] = ps->f[s->f_S[c]][i];
    const double G = s->mu[ps->material[i]];
    for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) {
            const double e = 0.5 * (gv[3 * a + b] + gv[3 * b + a]) - (a == b ? tr / dim : 0.0);
            double rot = 0; /* S Omega^T + Omega S */
            for (int c = 0; c < dim; ++c) {
                const double om_bc = 0.5 * (gv[3 * b + c] - gv[3 * c + b]);
                const double om_ac = 0.5 * (gv[3 * a + c] - gv[3 * c + a]);
                rot += S[3 * a + c] * om_bc + om_ac * S[3 * c + b];
            }
            Sd[3 * a + b] = 2 * G * e + rot;
        }
    for (int c = 0; c < 6; ++c)
        if (s->f_S[c] >= 0) ps->f[s->f_S[c]][i] += dt * Sd[3 * comp_a[c] + comp_b[c]];
}

/* Density advanced by dt; pressure, stress, artificial stress and stored energy density. */
static void stress_state(ry_sim *sim, solid *s, double dt) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
#pragma omp parallel for schedule(static) if (n >= RY_SOLID_PARALLEL_MIN)
    for (size_t i = 0; i < n; ++i) {
        const int m = ps->material[i];
        const double rho0 = sim->mat[m].density;
        double *rho = ps->f[RY_F_RHO] + i;
        *rho += dt * ps->f[RY_F_DRHO][i];
        double P = s->K[m] * (*rho / rho0 - 1);
        double *sig = s->sig + 9 * i, ss = 0;
        memset(sig, 0, 9 * sizeof *sig);
        for (int c = 0; c < 6; ++c)
            if (s->f_S[c] >= 0) {
                const double v = ps->f[s->f_S[c]][i];
                sig[3 * comp_a[c] + comp_b[c]] = sig[3 * comp_b[c] + comp_a[c]] = v;
                ss += (comp_a[c] == comp_b[c] ? 1.0 : 2.0) * v * v;
            }
        for (int a = 0; a < dim; ++a) sig[4 * a] -= P;
        if (s->clamp == CLAMP_FACE && ps->kind[i] != RY_KIND_SOLID) { /* no energy */
            memset(sig, 0, 9 * sizeof *sig);
            ss = 0;
            P = 0;
        }
        artificial_stress(dim, s->as_eps, *rho, sig, s->Ras + 9 * i);
        ps->f[RY_F_P][i] = P;
        /* P^2 / (2 K) + S : S / (4 G) per unit current volume, stored per unit reference
         * volume (the probe strain_energy multiplies by m / rho0) */
        ps->f[s->f_psi][i] = (P * P / (2 * s->K[m]) + ss / (4 * s->mu[m])) * rho0 / *rho;
    }
}

/* Pass 2, particle i: its acceleration where it is free, and its net force. */
RY_SOLID_INLINE void forces_dim(ry_sim *sim, solid *s, size_t i, const int dim) {
    ry_particles *ps = &sim->ps;
    const ry_kernel *k = &sim->kernel;
    const double r2max = k->radius * k->radius, h = k->h, c = s->c_max;
    const double *x[3] = {ps->f[RY_F_X], ps->f[RY_F_Y], dim > 2 ? ps->f[RY_F_Z] : NULL};
    const double *v[3] = {ps->f[RY_F_VX], ps->f[RY_F_VY], dim > 2 ? ps->f[RY_F_VZ] : NULL};
    const double *rho = ps->f[RY_F_RHO], *mass = ps->f[RY_F_MASS];
    const double iwdx = 1.0 / ry_kernel_w(k, sim->dx), eps = s->as_eps, expo = s->as_n;
    const int quad = s->correction == CORR_QUADRATIC, face = s->clamp == CLAMP_FACE;
    if (ps->kind[i] != RY_KIND_SOLID) {
        ry_solid_accelerate(sim, s, i, NULL, dim);
        return;
    }
    const double *si = s->sig + 9 * i, *Li = s->Lc + 9 * i, *Ri = s->Ras + 9 * i;
    const double vi = mass[i] / rho[i];
    double f[3] = {0, 0, 0};
    for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
        const size_t j = sim->nl.j[q];
        double d[3], r2 = 0, vd = 0;
        for (int a = 0; a < dim; ++a) {
            d[a] = x[a][j] - x[a][i];
            r2 += d[a] * d[a];
            vd += (v[a][j] - v[a][i]) * d[a]; /* v_ij . x_ij */
        }
        if (r2 >= r2max || r2 == 0) continue;
        const double r = sqrt(r2), fw = -ry_kernel_dwdr(k, r) / r;
        double g[3]; /* grad_i W_ij */
        for (int a = 0; a < dim; ++a) g[a] = fw * d[a];
        const double *sj = s->sig + 9 * j, *Lj = s->Lc + 9 * j, *Rj = s->Ras + 9 * j;
        const double vj = mass[j] / rho[j], mm = mass[i] * mass[j];
        double wi[3] = {0, 0, 0}, wj[3] = {0, 0, 0}; /* force: sigma_i wi + sigma_j wj */
        if (quad) {                                  /* V_i G_ij - V_j G_ji */
            const double *gij = s->G + q * (size_t)dim, *gji = s->G + s->rev[q] * (size_t)dim;
            for (int a = 0; a < dim; ++a) {
                wi[a] = vi * gij[a];
                wj[a] = -vj * gji[a];
            }
        } else { /* V_i V_j L grad W_ij */
            ry_solid_ul_weights(Li, Lj, vi, vj, g, wi, wj, dim);
        }
        double fn = 0, pi = 0;
        if (face && ps->kind[j] != RY_KIND_SOLID) { /* the clamp face holds no stress */
            for (int a = 0; a < dim; ++a)
                for (int b = 0; b < dim; ++b) f[a] += si[3 * a + b] * wi[b];
            continue;
        }
        if (eps > 0) {
            const double w = ry_kernel_w(k, r) * iwdx;
            fn = expo == 4.0 ? (w * w) * (w * w) : pow(w, expo);
        }
        if (vd < 0) /* (c the P-wave speed; eta^2 = 0.01 h^2) */
            pi = ry_monaghan_pi(vd, 1.0 / (r2 + 0.01 * h * h), h, c, rho[i] + rho[j], s->av_alpha,
                                s->av_beta);
        ry_solid_ul_pair(f, si, wi, sj, wj, Ri, Rj, g, mm, fn, pi, dim);
    }
    ry_solid_accelerate(sim, s, i, f, dim);
}

/* Per-pair arrays of the quadratic correction: the weights G (filled by the rates pass) and the
 * index of the reverse pair; current volumes. */
static ry_status quadratic_pairs(ry_sim *sim, solid *s, ry_error *err) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n, npair = sim->nl.offset[n];
    if (npair > s->cap_pair || !s->G) {
        free(s->G);
        free(s->rev);
        s->cap_pair = npair + npair / 4 + 1;
        s->G = malloc(s->cap_pair * (size_t)sim->dim * sizeof *s->G);
        s->rev = malloc(s->cap_pair * sizeof *s->rev);
        RY_CHECK(err, s->G && s->rev, RY_ERR_NOMEM, "out of memory");
    }
    if (!s->vol) {
        s->vol = malloc((n ? n : 1) * sizeof *s->vol);
        RY_CHECK(err, s->vol != NULL, RY_ERR_NOMEM, "out of memory");
    }
    for (size_t i = 0; i < n; ++i) s->vol[i] = ps->f[RY_F_MASS][i] / ps->f[RY_F_RHO][i];
    if (s->rev_search == sim->nl_generation) return RY_OK;
    s->rev_search = sim->nl_generation;
#pragma omp parallel for schedule(static) if (n >= RY_SOLID_PARALLEL_MIN)
    for (size_t i = 0; i < n; ++i)
        for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q)
            s->rev[q] = ry_solid_reverse_pair(&sim->nl, i, sim->nl.j[q]);
    return RY_OK;
}

ry_status ry_solid_ul_evaluate(ry_sim *sim, solid *s, double dt, ry_error *err) {
    RY_TRY(ry_sim_neighbors(sim, sim->kernel.radius, err));
    if (s->correction == CORR_QUADRATIC) RY_TRY(quadratic_pairs(sim, s, err));
    RY_SOLID_ROWS(sim, i, rates_dim(sim, s, i, dt, 2), rates_dim(sim, s, i, dt, 3));
    stress_state(sim, s, dt);
    RY_SOLID_ROWS(sim, i, forces_dim(sim, s, i, 2), forces_dim(sim, s, i, 3));
    ry_solid_residual_update(sim, s);
    return RY_OK;
}
