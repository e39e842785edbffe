/* Non-Newtonian materials in the SPH schemes (sph_rheology.h, docs/reference/rheology.md). */
#include "physics/polymer_stress.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/small.h"
#include "ryushi/rheology.h"

ry_status ry_sph_rheo_init(ry_sph_rheo *r, ry_sim *sim, ry_error *err) {
    memset(r, 0, sizeof *r);
    r->f_nu = r->f_gd = -1;
    for (int k = 0; k < 6; ++k) r->f_tau[k] = -1;
    for (int m = 0; m < sim->nmat; ++m) {
        const int model = sim->mat[m].rheo.model;
        r->on |= model != RY_RHEO_NEWTONIAN;
        r->ob |= ry_rheology_viscoelastic(&sim->mat[m].rheo);
    }
    if (!r->on) return RY_OK;
    ry_particles *ps = &sim->ps;
    RY_TRY(ry_particles_add_field(ps, "viscosity", "m^2/s", -1, RY_FIELD_STATE | RY_FIELD_OUTPUT,
                                  &r->f_nu, err));
    RY_TRY(ry_particles_add_field(ps, "shear_rate", "1/s", -1, RY_FIELD_OUTPUT, &r->f_gd, err));
    for (int k = 0; r->ob && k < ry_tau_count(sim->dim); ++k) {
        RY_TRY(ry_particles_add_field(ps, ry_tau_name(sim->dim, k), "Pa", -1,
                                      RY_FIELD_STATE | RY_FIELD_OUTPUT, &r->f_tau[k], err));
        ry_particles_set_parity(ps, r->f_tau[k], ry_tau_odd(sim->dim, k));
    }
    /* Before the first rates: the viscosity at rest (the time step reads it). */
    for (size_t i = 0; i < ps->n; ++i) {
        const ry_material *mat = &sim->mat[ps->material[i]];
        ps->f[r->f_nu][i] = ry_rheology_nu(&mat->rheo, mat->viscosity, 0.0);
    }
    return RY_OK;
}

void ry_sph_rheo_free(ry_sph_rheo *r) {
    free(r->L);
    free(r->acc);
    r->L = r->acc = NULL;
    r->cap = 0;
}

ry_status ry_sph_rheo_rates(ry_sph_rheo *r, ry_sim *sim, const ry_pair_cache *pc,
                            const int mobile[RY_KIND_COUNT], const double *vol,
                            const double *const vwall[3], ry_error *err) {
    if (!r->on) return RY_OK;
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim, nt = ry_tau_count(dim);
    if (r->cap < n) {
        const size_t cap = n + n / 4 + 64;
        double *L = realloc(r->L, 9 * cap * sizeof *L);
        if (L) r->L = L;
        double *a = L ? realloc(r->acc, 3 * cap * sizeof *a) : NULL;
        if (a) r->acc = a;
        RY_CHECK(err, L && a, RY_ERR_NOMEM, "out of memory (rheology of %zu particles)", n);
        r->cap = cap;
    }
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = pc->j; /* the pairs within the support */
    const size_t *end = pc->end;
    const double *cw = pc->w, *cg = pc->g;
    const double *v[3], *rho = ps->f[RY_F_RHO];
    for (int d = 0; d < 3; ++d) v[d] = ps->f[RY_F_VX + (d < dim ? d : 0)];
    const double *tau[6] = {NULL};
    for (int k = 0; r->ob && k < nt; ++k) tau[k] = ps->f[r->f_tau[k]];
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        const ry_material *mat = &sim->mat[ps->material[i]];
        double *L = r->L + 9 * i, *acc = r->acc + 3 * i;
        memset(L, 0, 9 * sizeof *L);
        acc[0] = acc[1] = acc[2] = 0;
        if (!mobile[ps->kind[i]]) {
            ps->f[r->f_nu][i] = mat->viscosity;
            ps->f[r->f_gd][i] = 0;
            continue;
        }
        /* Corrected gradients: sum_j V_j (f_j - f_i) grad W_ij = grad f . M, with the moment
         * matrix M = sum_j V_j (x_j - x_i) (x) grad W_ij (symmetric, as grad W_ij is along
         * x_ij): exact for linear fields however one-sided the neighbourhood. The velocity
         * over the mobile and (with vwall) fixed neighbours; the stress over the mobile. */
        double mv[3][3] = {{0}}, mt[3][3] = {{0}}, gv[6][3] = {{0}}, gt[6][3] = {{0}};
        for (size_t q = off[i]; q < end[i]; ++q) {
            if (cw[q] == 0) continue;
            const uint32_t j = nb[q];
            const int mj = mobile[ps->kind[j]];
            if (!mj && !vwall) continue;
            const double vj = vol[j], *G = cg + 3 * q;
            double dx[3];
            ry_pair_separation(sim, i, j, dx);
            for (int a = 0; a < dim; ++a)
                for (int b = 0; b < dim; ++b) {
                    const double e = -vj * dx[a] * G[b];
                    mv[a][b] += e;
                    if (mj) mt[a][b] += e;
                }
            for (int a = 0; a < dim; ++a) {
                const double du = (mj ? v[a][j] : vwall[a][j]) - v[a][i];
                for (int b = 0; b < dim; ++b) gv[a][b] += vj * du * G[b];
            }
            for (int k = 0; r->ob && mj && k < nt; ++k) {
                const double dt = tau[k][j] - tau[k][i];
                for (int b = 0; b < dim; ++b) gt[k][b] += vj * dt * G[b];
            }
        }
        ry_solve_rows(dim, mv, dim, gv, gv); /* a particle with too few neighbours: L = 0 */
        double dd = 0;
        for (int a = 0; a < dim; ++a)
            for (int b = 0; b < dim; ++b) {
                L[3 * a + b] = gv[a][b];
                const double d = 0.5 * (gv[a][b] + gv[b][a]);
                dd += d * d;
            }
        const double gd = sqrt(2.0 * dd);
        ps->f[r->f_gd][i] = gd;
        ps->f[r->f_nu][i] = ry_rheology_nu(&mat->rheo, mat->viscosity, gd);
        if (!r->ob || !ry_solve_rows(dim, mt, nt, gt, gt)) continue;
        for (int k = 0; k < nt; ++k) {
            int a, b;
            ry_tau_index(dim, k, &a, &b);
            acc[a] += gt[k][b] / rho[i];
            if (a != b) acc[b] += gt[k][a] / rho[i];
        }
    }
    if (sim->par) sim->par->sync_field(sim, r->f_nu);
    return RY_OK;
}

void ry_sph_rheo_advance(ry_sph_rheo *r, ry_sim *sim, const int mobile[RY_KIND_COUNT], double dt) {
    if (!r->ob) return;
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim, nt = ry_tau_count(dim);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        const ry_material *mat = &sim->mat[ps->material[i]];
        if (!mobile[ps->kind[i]] || !ry_rheology_viscoelastic(&mat->rheo)) continue;
        double t[6];
        for (int k = 0; k < nt; ++k) t[k] = ps->f[r->f_tau[k]][i];
        ry_polymer_step(dim, &mat->rheo, r->L + 9 * i, mat->density, dt, t);
        for (int k = 0; k < nt; ++k) ps->f[r->f_tau[k]][i] = t[k];
    }
    for (int k = 0; sim->par && k < nt; ++k) sim->par->sync_field(sim, r->f_tau[k]);
}

double ry_sph_rheo_dt(const ry_sph_rheo *r, const ry_sim *sim, const int mobile[RY_KIND_COUNT],
                      double h, double cfl, double cvisc) {
    if (!r->on) return INFINITY;
    const ry_particles *ps = &sim->ps;
    double numax = 0;
    for (size_t i = 0; i < ps->n; ++i)
        if (mobile[ps->kind[i]]) numax = fmax(numax, ps->f[r->f_nu][i]);
    if (sim->par) numax = sim->par->max((ry_sim *)sim, numax);
    double t = numax > 0 ? cvisc * h * h / numax : INFINITY;
    for (int m = 0; m < sim->nmat; ++m) {
        const ry_rheology *rh = &sim->mat[m].rheo;
        if (ry_rheology_viscoelastic(rh) && rh->nu_polymer > 0)
            t = fmin(t, cfl * h * sqrt(rh->relaxation / rh->nu_polymer));
    }
    return t;
}
