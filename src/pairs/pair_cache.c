/* Pair cache of the implicit SPH schemes (sph_pairs.h). */
#include "pairs/pair_cache.h"

#include <math.h>
#include <stdlib.h>

/* Row i of the cache from the neighbour list's row (entries off[i]..off[i + 1]); in holds room
 * for the row. */
static void cache_row(ry_pair_cache *pc, const ry_sim *sim, size_t i, uint32_t *in) {
    const ry_kernel *k = &sim->kernel;
    const double rad2 = k->radius * k->radius;
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = sim->nl.j;
    _Static_assert(RY_KIND_COUNT == 5, "every kind a partner");
    static const int every[RY_KIND_COUNT] = {1, 1, 1, 1, 1};
    const uint8_t *kind = sim->ps.kind;
    const int *partner = pc->partner_rows && pc->partner_rows[kind[i]] ? pc->partners : every;
    size_t c = 0;
    for (size_t q = off[i]; q < off[i + 1]; ++q) {
        if (!partner[kind[nb[q]]]) continue;
        double dx[3]; /* x_i - x_j */
        const double r2 = ry_pair_separation(sim, i, nb[q], dx);
        in[c] = (uint32_t)(q - off[i]);
        c += (r2 < rad2) & (r2 > 0) & !(pc->cut && pc->cut[q]);
    }
    for (size_t e = 0; e < c; ++e) {
        const size_t q = off[i] + in[e];
        const uint32_t j = nb[q];
        double dx[3];
        const double r2 = ry_pair_separation(sim, i, j, dx);
        const double r = sqrt(r2), f = ry_kernel_dwdr(k, r) / r;
        double *G = pc->g + 3 * (off[i] + e);
        pc->w[off[i] + e] = ry_kernel_w(k, r);
        for (int d = 0; d < 3; ++d) G[d] = f * dx[d];
        pc->j[off[i] + e] = j;
    }
    pc->end[i] = off[i] + c;
}

ry_status ry_pair_cache_fill(ry_pair_cache *pc, const ry_sim *sim, const int need[RY_KIND_COUNT],
                             ry_error *err) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n, m = sim->nl.offset[n];
    if (pc->cap < m) {
        size_t cap = m + m / 4 + 64;
        double *w = realloc(pc->w, cap * sizeof *w);
        if (w) pc->w = w;
        double *g = realloc(pc->g, 3 * cap * sizeof *g);
        if (g) pc->g = g;
        uint32_t *j = realloc(pc->j, cap * sizeof *j);
        if (j) pc->j = j;
        RY_CHECK(err, w && g && j, RY_ERR_NOMEM, "out of memory (pair cache of %zu entries)", m);
        pc->cap = cap;
    }
    if (pc->cap_n < n) {
        size_t cap = n + n / 4 + 64;
        size_t *e = realloc(pc->end, cap * sizeof *e);
        RY_CHECK(err, e != NULL, RY_ERR_NOMEM, "out of memory (pair cache of %zu rows)", n);
        pc->end = e;
        pc->cap_n = cap;
    }
    const size_t *off = sim->nl.offset;
    size_t rowmax = 0;
    for (size_t i = 0; i < n; ++i)
        if (off[i + 1] - off[i] > rowmax) rowmax = off[i + 1] - off[i];
    int ok = 1;
#pragma omp parallel reduction(&& : ok)
    {
        /* the row's entries within the support: chosen without branches (a third of the list
         * lies beyond it, in no predictable order), then filled */
        uint32_t *in = malloc((rowmax + 1) * sizeof *in);
        ok = in != NULL;
#pragma omp for schedule(dynamic, 64)
        for (size_t i = 0; i < n; ++i) {
            if (ok && need[ps->kind[i]])
                cache_row(pc, sim, i, in);
            else
                pc->end[i] = off[i];
        }
        free(in);
    }
    RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (pair cache rows)");
    return RY_OK;
}

void ry_pair_cache_free(ry_pair_cache *pc) {
    free(pc->w);
    free(pc->g);
    free(pc->j);
    free(pc->end);
    *pc = (ry_pair_cache){0};
}

double ry_lattice_number_density(const ry_kernel *k, int dim, double dx) {
    const int m = (int)ceil(k->radius / dx) + 1;
    double s = 0;
    for (int a = -m; a <= m; ++a)
        for (int b = -m; b <= m; ++b)
            for (int c = (dim > 2 ? -m : 0); c <= (dim > 2 ? m : 0); ++c) {
                double r = dx * sqrt((double)(a * a + b * b + c * c));
                if (r < k->radius) s += ry_kernel_w(k, r);
            }
    return s;
}

double ry_lattice_viscous_factor(const ry_kernel *k, int dim, double dx, double vol, double eta2,
                                 int projected) {
    const int m = (int)ceil(k->radius / dx) + 1;
    double s = 0;
    for (int a = -m; a <= m; ++a)
        for (int b = -m; b <= m; ++b)
            for (int c = (dim > 2 ? -m : 0); c <= (dim > 2 ? m : 0); ++c) {
                const double x = a * dx, y = b * dx, r2 = dx * dx * (a * a + b * b + c * c);
                const double r = sqrt(r2);
                if (r <= 0 || r >= k->radius) continue;
                const double f = ry_kernel_dwdr(k, r) / r;
                s -= vol * (projected ? (dim + 2) * x * x * y * y : r2 * y * y) * f / (r2 + eta2);
            }
    return s;
}

void ry_hydrostatic_pressure(const ry_sim *sim, double *p) {
    const ry_particles *ps = &sim->ps;
    double g2 = 0, up[3] = {0, 0, 0};
    for (size_t i = 0; i < ps->n; ++i) p[i] = 0;
    for (int d = 0; d < sim->dim; ++d) g2 += sim->gravity[d] * sim->gravity[d];
    if (g2 <= 0) return;
    const double g = sqrt(g2);
    for (int d = 0; d < sim->dim; ++d) up[d] = -sim->gravity[d] / g;
    double top = -INFINITY;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        double z = 0;
        for (int d = 0; d < sim->dim; ++d) z += up[d] * ps->f[RY_F_X + d][i];
        top = fmax(top, z);
    }
    top += 0.5 * sim->dx;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        double z = 0;
        for (int d = 0; d < sim->dim; ++d) z += up[d] * ps->f[RY_F_X + d][i];
        p[i] = sim->mat[ps->material[i]].density * g * (top - z);
    }
}
