/* The per-particle guard check (case section `guard`), for ry_sim_check and for schemes that
 * fuse it into their last loop over the particles of a step (sim->checked). */
#ifndef RY_GUARD_CHECK_H
#define RY_GUARD_CHECK_H

#include <math.h>
#include <stdint.h>

#include "ryushi/sim.h"

typedef struct ry_check_ctx {
    const double *x[3], *v[3], *rho, *p;
    const uint8_t *kind, *material;
    double inv_rho0[256];
    const double *lo, *hi;
    double v2max, rmin, rmax;
} ry_check_ctx;

/* The limits and field pointers of the check (the fields as they are now: call after any
 * reordering of the particles). */
void ry_check_init(const ry_sim *sim, ry_check_ctx *c);

/* Whether particle i passes every guard (out: whether it lies outside the domain); dim is a
 * literal at each call, so that loops compile for 2D and 3D separately. */
static inline __attribute__((always_inline)) int ry_check_one(const ry_check_ctx *c, size_t i,
                                                              const int dim, int *out) {
    int ok = 1, o = 0;
    double v2 = 0;
    for (int d = 0; d < dim; ++d) {
        const double xi = c->x[d][i], vi = c->v[d][i];
        ok &= isfinite(xi) & isfinite(vi);
        v2 += vi * vi;
        o |= !(xi >= c->lo[d]) | !(xi < c->hi[d]);
    }
    const double r = c->rho[i];
    ok &= isfinite(c->p[i]) & (r > 0) & isfinite(r) & (v2 <= c->v2max);
    const double q = r * c->inv_rho0[c->material[i]];
    ok &= (c->kind[i] != RY_KIND_FLUID) | ((q >= c->rmin) & (q <= c->rmax));
    *out = o;
    return ok;
}

/* Adds particle i to the tallies of a check: the first failing index, the fluid particles and
 * those of them outside the domain. */
static inline __attribute__((always_inline)) void ry_check_tally(const ry_check_ctx *c, size_t i,
                                                                 const int dim, size_t *first,
                                                                 size_t *fluid, size_t *outside) {
    int out;
    const int ok = ry_check_one(c, i, dim, &out);
    const int isf = c->kind[i] == RY_KIND_FLUID;
    *fluid += (size_t)isf;
    *outside += (size_t)(isf & out);
    *first = ok ? *first : (i < *first ? i : *first);
}

/* The verdict from the tallies over all particles (a diagnosis naming the first bad particle,
 * or RY_OK). */
ry_status ry_check_verdict(const ry_sim *sim, size_t first, size_t fluid, size_t outside,
                           ry_error *err);

#endif
