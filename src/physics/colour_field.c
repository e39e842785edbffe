/* Colour-field interface of two fluids (multiphase.h). */
#include "physics/colour_field.h"

#include <math.h>
#include <stdlib.h>

#include "linalg/small.h"

ry_status ry_colour_init(ry_colour *cf, ry_sim *sim, ry_error *err) {
    RY_TRY(
        ry_particles_add_field(&sim->ps, "colour", "1", -1, RY_FIELD_OUTPUT, &cf->f_colour, err));
    RY_TRY(ry_particles_add_field(&sim->ps, "curvature", "1/m", -1, RY_FIELD_OUTPUT,
                                  &cf->f_curvature, err));
    return RY_OK;
}

void ry_colour_free(ry_colour *cf) {
    free(cf->nrm);
    cf->nrm = NULL;
    cf->cap = 0;
}

double ry_colour_dt(const ry_colour *cf, const ry_sim *sim) {
    if (cf->sigma <= 0) return INFINITY;
    double rho = INFINITY;
    for (int m = 0; m < sim->nmat; ++m) rho = fmin(rho, sim->mat[m].density);
    const double h = sim->kernel.h;
    return 0.25 * sqrt(rho * h * h * h / (2.0 * 3.14159265358979323846 * cf->sigma));
}

/* The contact line's force on particle i (line_force; colour_field.h): its interface normal by the
 * corrected gradient of c' over the fluid neighbours, the angle it makes with the wall's normal w
 * (unit, into the fluid; gw = |sum_walls grad_i W_ij|), and Young's unbalanced force along the
 * wall, spread over the band where the interface and the wall's edge overlap. */
static void line_force(const ry_colour *cf, const ry_sim *sim, const ry_pair_cache *pc,
                       const double *cs, const double *delta, const int mobile[RY_KIND_COUNT],
                       size_t i, const double w[3], double gw, double *acc) {
    const ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    double m[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}, s[3] = {0, 0, 0}, a[3] = {0, 0, 0};
    for (size_t q = sim->nl.offset[i]; q < pc->end[i]; ++q) {
        const uint32_t j = pc->j[q];
        if (!mobile[ps->kind[j]]) continue;
        double dx[3];
        ry_pair_separation(sim, i, j, dx); /* x_i - x_j */
        const double *G = pc->g + 3 * q, vj = 1.0 / delta[j];
        for (int b = 0; b < dim; ++b) {
            s[b] += (cs[j] - cs[i]) * vj * G[b];
            for (int e = 0; e < dim; ++e) m[b][e] -= vj * G[b] * dx[e];
        }
    }
    if (!ry_solve_small(dim, m, s, a)) return;
    double la = 0, cd = 0;
    for (int d = 0; d < dim; ++d) la += a[d] * a[d];
    if (!(la > 0)) return;
    la = sqrt(la);
    for (int d = 0; d < dim; ++d) cd += a[d] / la * w[d];
    const double f =
        2.0 * cf->sigma * (cf->cos_theta - cd) * la * gw * cf->wall_volume / cf->rho_bar;
    for (int d = 0; d < dim; ++d) acc[d] += f * (a[d] / la - cd * w[d]);
}

/* The contact angle (wet): the unit normals of the interface particles beside a wall turned to
 * meet it at theta (colour_field.h), their sizes kept, and the contact line's force
 * (line_force). Each particle reads its own normal and the walls' pairs only. */
static void contact_angle(ry_colour *cf, ry_sim *sim, const ry_pair_cache *pc, const double *cs,
                          const double *delta, const int mobile[RY_KIND_COUNT], double thr,
                          double *acc) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    double *nrm = cf->nrm, *ln = nrm + 3 * n;
    const double r2max = 2.25 * sim->dx * sim->dx;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (!mobile[ps->kind[i]] || ln[i] <= thr) continue;
        double w[3] = {0, 0, 0}, nw = 0, dot = 0, nt = 0, t[3] = {0, 0, 0};
        int near = 0;
        for (size_t q = sim->nl.offset[i]; q < pc->end[i]; ++q) {
            if (ps->kind[pc->j[q]] != RY_KIND_WALL) continue;
            double dx[3];
            near |= ry_pair_separation(sim, i, pc->j[q], dx) < r2max;
            for (int d = 0; d < dim; ++d) w[d] -= pc->g[3 * q + d];
        }
        if (!near && !cf->line_force) continue;
        for (int d = 0; d < dim; ++d) nw += w[d] * w[d];
        if (!(nw > 0)) continue;
        nw = sqrt(nw);
        for (int d = 0; d < dim; ++d) w[d] /= nw;
        if (cf->line_force) line_force(cf, sim, pc, cs, delta, mobile, i, w, nw, acc + 3 * i);
        if (!near) continue;
        for (int d = 0; d < dim; ++d) dot += nrm[3 * i + d] / ln[i] * w[d];
        for (int d = 0; d < dim; ++d) {
            t[d] = nrm[3 * i + d] / ln[i] - dot * w[d];
            nt += t[d] * t[d];
        }
        if (!(nt > 1e-12)) continue; /* the normal along the wall's: no direction along it */
        nt = sqrt(nt);
        for (int d = 0; d < dim; ++d)
            nrm[3 * i + d] = ln[i] * (cf->cos_theta * w[d] + cf->sin_theta * t[d] / nt);
    }
    if (sim->par) sim->par->sync(sim, nrm, 3, 0);
}

ry_status ry_colour_force(ry_colour *cf, ry_sim *sim, const ry_pair_cache *pc, const double *delta,
                          const int mobile[RY_KIND_COUNT], double *acc, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    if (cf->cap < n) {
        double *v = realloc(cf->nrm, 5 * n * sizeof(double));
        RY_CHECK(err, v != NULL, RY_ERR_NOMEM, "out of memory (colour field)");
        cf->nrm = v;
        cf->cap = n;
    }
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = pc->j; /* the pairs within the support */
    const size_t *end = pc->end;
    const uint8_t *kind = ps->kind, *mat = ps->material;
    const double *cw = pc->w, *cg = pc->g;
    double *cs = ps->f[cf->f_colour], *kap = ps->f[cf->f_curvature], *nrm = cf->nrm;
    const double w0 = sim->kernel.norm * ry_kernel_shape(sim->kernel.type, 0.0);
    const int cm = cf->material;
    const double thr = cf->eps / sim->kernel.h;
    /* Smoothed colour (seed eq. 8), over fluid neighbours. */
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (!mobile[kind[i]]) {
            cs[i] = 0;
            continue;
        }
        double sn = w0 * (mat[i] == cm) / delta[i], sd = w0 / delta[i];
        for (size_t q = off[i]; q < end[i]; ++q) {
            const uint32_t j = nb[q];
            if (!mobile[kind[j]]) continue;
            const double wv = cw[q] / delta[j];
            sn += (mat[j] == cm) * wv;
            sd += wv;
        }
        cs[i] = sn / sd;
    }
    if (sim->par) sim->par->sync(sim, cs, 1, 0); /* halo copies: their owners' values */
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) { /* normal n = grad c' */
        double g[3] = {0, 0, 0};
        if (mobile[kind[i]])
            for (size_t q = off[i]; q < end[i]; ++q) {
                const uint32_t j = nb[q];
                if (!mobile[kind[j]]) continue;
                const double f = (cs[j] - cs[i]) / delta[j];
                for (int d = 0; d < dim; ++d) g[d] += f * cg[3 * q + d];
            }
        for (int d = 0; d < 3; ++d) nrm[3 * i + d] = g[d];
    }
    if (sim->par) sim->par->sync(sim, nrm, 3, 0);
    double *ln = nrm + 3 * n, *ks = nrm + 4 * n; /* |n| per particle; the average's output */
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        const double *ni = nrm + 3 * i;
        ln[i] = sqrt(ni[0] * ni[0] + ni[1] * ni[1] + ni[2] * ni[2]);
    }
    if (cf->wet) contact_angle(cf, sim, pc, cs, delta, mobile, thr, acc);
    /* Curvature and force. */
    const double sigma = cf->sigma;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        kap[i] = 0;
        if (!mobile[kind[i]]) continue;
        const double *ni = nrm + 3 * i;
        const double li = ln[i];
        if (li <= thr) continue;
        double num = 0, den = 0;
        for (size_t q = off[i]; q < end[i]; ++q) {
            const uint32_t j = nb[q];
            if (!mobile[kind[j]]) continue;
            const double *nj = nrm + 3 * j;
            const double lj = ln[j];
            if (lj <= thr) continue;
            const double *G = cg + 3 * q;
            double dot = 0, g2 = 0, dx[3];
            for (int d = 0; d < dim; ++d) {
                dot += (ni[d] / li - nj[d] / lj) * G[d];
                g2 += G[d] * G[d];
            }
            num += dot / delta[j];
            den += sqrt(ry_pair_separation(sim, i, j, dx) * g2) / delta[j];
        }
        if (den <= 0) continue;
        kap[i] = dim * num / den;
    }
    /* The curvature averaged over the interface particles, weighted by |n| W: smoothing
     * passes. */
    for (int pass = 0; pass < cf->smoothing; ++pass) {
        if (sim->par) sim->par->sync(sim, kap, 1, 0);
#pragma omp parallel for schedule(dynamic, 64)
        for (size_t i = 0; i < n; ++i) {
            ks[i] = kap[i];
            if (!mobile[kind[i]]) continue;
            const double li = ln[i];
            if (li <= thr) continue;
            double num = w0 * li * kap[i] / delta[i], den = w0 * li / delta[i];
            for (size_t q = off[i]; q < end[i]; ++q) {
                const uint32_t j = nb[q];
                if (!mobile[kind[j]]) continue;
                const double lj = ln[j];
                if (lj <= thr) continue;
                const double wv = lj * cw[q] / delta[j];
                num += wv * kap[j];
                den += wv;
            }
            ks[i] = num / den;
        }
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; ++i) kap[i] = ks[i];
    }
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        if (!mobile[kind[i]]) continue;
        const double f = sigma * kap[i] / cf->rho_bar;
        for (int d = 0; d < dim; ++d) acc[3 * i + d] += f * nrm[3 * i + d];
    }
    return RY_OK;
}
