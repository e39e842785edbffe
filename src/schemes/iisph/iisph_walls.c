/* The wall pressure of IISPH: wall and inlet particles (and, for the light phase, the heavy
 * fluid) take the pressure extrapolated from the fluid with the hydrostatic term (Adami, Hu &
 * Adams (2012), J. Comput. Phys. 231: 7057, eq. 27), from lists built once per step and summed
 * in every iteration of the pressure solve. */
#include <math.h>
#include <stdlib.h>

#include "boundary/walls_adami2012.h"
#include "schemes/iisph/iisph_internal.h"

/* The lists of map m. */
void iisph_wall_map_free(wall_map *m) {
    free(m->w);
    free(m->j);
    free(m->off);
    free(m->cnt);
    free(m->wt);
    free(m->h);
}

/* Wall and inlet particles: pressure extrapolated from the fluid with the hydrostatic term
 * (boundary/walls_adami2012.h, eq. 27), from the current iterate (not negative).
 * iisph_wall_map_build sets the walls without a mobile neighbour to 0 and lists the others' terms;
 * iisph_wall_extrapolate sums them in the same order. Two maps: RY_MAP_WALL, the walls from the
 * (heavy) fluid into the pressure field; with a light phase also RY_MAP_LIGHT, the walls and the
 * heavy fluid from the light fluid into s->pl. A target of the map, and a source. */
static inline int wall_target(const iisph *s, const uint8_t *kind, size_t i, int map) {
    return kind[i] == RY_KIND_WALL || kind[i] == RY_KIND_INLET ||
           (map == RY_MAP_LIGHT && MOBILE[kind[i]] && !s->lt[i]);
}
static inline int wall_source(const iisph *s, const uint8_t *kind, size_t j, int map) {
    return MOBILE[kind[j]] && (map == RY_MAP_LIGHT ? s->lt[j] : !s->light_on || !s->lt[j]);
}

/* Builds map m of kind `map` (above), setting the targets without a source neighbour to 0 in
 * p. */
ry_status iisph_wall_map_build(ry_sim *sim, iisph *s, wall_map *m, double *p, int map,
                               ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = s->pc.j; /* the pairs within the support */
    const size_t *end = s->pc.end;
    const uint8_t *kind = ps->kind;
    const double *cw = s->pc.w, *rho = ps->f[RY_F_RHO];
    if (m->cap_n < n + 1) {
        const size_t c = n + n / 4 + 16;
        int ok = 1;
        RY_IISPH_GROW(m->w, c, ok);
        RY_IISPH_GROW(m->off, c + 1, ok);
        RY_IISPH_GROW(m->cnt, c, ok);
        RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (wall pressure lists)");
        m->cap_n = c;
    }
#pragma omp parallel for schedule(dynamic, 256)
    for (size_t i = 0; i < n; ++i) {
        size_t c = 0;
        if (wall_target(s, kind, i, map))
            for (size_t q = off[i]; q < end[i]; ++q)
                c += wall_source(s, kind, nb[q], map) && cw[q] != 0;
        m->cnt[i] = c;
    }
    m->nw = 0;
    m->off[0] = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!wall_target(s, kind, i, map)) continue;
        if (m->cnt[i] == 0) {
            p[i] = 0.0;
            continue;
        }
        m->w[m->nw] = (uint32_t)i;
        m->off[m->nw + 1] = m->off[m->nw] + m->cnt[i];
        m->nw++;
    }
    const size_t ne = m->off[m->nw];
    if (m->cap_e < ne) {
        const size_t c = ne + ne / 4 + 16;
        int ok = 1;
        RY_IISPH_GROW(m->j, c, ok);
        RY_IISPH_GROW(m->wt, c, ok);
        RY_IISPH_GROW(m->h, c, ok);
        RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (wall pressure lists)");
        m->cap_e = c;
    }
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t k = 0; k < m->nw; ++k) {
        const size_t i = m->w[k];
        size_t e = m->off[k];
        for (size_t q = off[i]; q < end[i]; ++q) {
            const uint32_t j = nb[q];
            if (!wall_source(s, kind, j, map) || cw[q] == 0) continue;
            double dx[3];
            ry_pair_separation(sim, i, j, dx);
            m->j[e] = j;
            m->wt[e] = cw[q];
            m->h[e] = ry_adami_head(sim->gravity, dx, dim, rho[j]);
            e++;
        }
    }
    return RY_OK;
}
/* The targets of map m into out from the sources' pressures p (out may be p). */
void iisph_wall_extrapolate(const wall_map *m, const double *p, double *out) {
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t k = 0; k < m->nw; ++k) {
        ry_adami_sums a = {0, 0, {0, 0, 0}};
        for (size_t e = m->off[k]; e < m->off[k + 1]; ++e)
            ry_adami_add_pressure(&a, m->wt[e], p[m->j[e]], m->h[e]);
        out[m->w[k]] = fmax(ry_adami_pressure(&a), 0.0); /* sw > 0: every entry has W > 0 */
    }
}
