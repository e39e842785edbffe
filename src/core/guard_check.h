/* The per-particle guard check (case section `guard`), for ry_sim_check and for schemes that
 * fuse it into their last loop over the particles of a step (sim->checked). */
#ifndef RY_GUARD_CHECK_H
#define RY_GUARD_CHECK_H

#include <float.h>
#include <math.h>
#include <stdint.h>

#include "ryushi/sim.h"

typedef struct ry_check_ctx {
    const double *x[3], *v[3], *rho, *p; /* unused directions point at x and v */
    const uint8_t *kind;
    double lo[3], hi[3]; /* domain box; -inf..inf in unused directions */
    double v2max, rmin, rmax;
} ry_check_ctx;

/* The limits and field pointers of the check (the fields as they are now: call after any
 * reordering of the particles), and 1 / reference density per material (256 entries).
 * Returns whether every material has the density of the first (inv_rho0[0] then serves
 * all). Loops should check from a copy of the context local to the loop, so that the compiler
 * keeps its pointers in registers and vectorises. */
int ry_check_init(const ry_sim *sim, ry_check_ctx *c, double *inv_rho0);

/* Adds particle i to the tallies of a check: bad particles (non-finite or runaway values),
 * fluid particles, and fluid particles outside the domain. inv_rho0 is 1 / the reference
 * density of its material. Without branches and with a literal dim, so that loops over i
 * vectorise; the verdict finds the bad particles again for its diagnosis. */
static inline __attribute__((always_inline)) void ry_check_tally(const ry_check_ctx *c, size_t i,
                                                                 const int dim, double inv_rho0,
                                                                 size_t *bad, size_t *fluid,
                                                                 size_t *outside) {
    int fin = 1, in = 1;
    double v2 = 0;
    for (int d = 0; d < dim; ++d) {
        const double xi = c->x[d][i], vi = c->v[d][i];
        fin &= (fabs(xi) <= DBL_MAX) & (fabs(vi) <= DBL_MAX);
        v2 += vi * vi;
        in &= (xi >= c->lo[d]) & (xi < c->hi[d]);
    }
    const double r = c->rho[i], q = r * inv_rho0;
    const int isf = c->kind[i] == RY_KIND_FLUID;
    fin &= (fabs(c->p[i]) <= DBL_MAX) & (r > 0) & (r <= DBL_MAX);
    const int ok = fin & (v2 <= c->v2max) & ((isf == 0) | ((q >= c->rmin) & (q <= c->rmax)));
    *bad += (size_t)(ok == 0);
    *fluid += (size_t)isf;
    *outside += (size_t)(isf & (in == 0));
}

/* The verdict from the tallies over all particles (a diagnosis naming the first bad particle,
 * or RY_OK); in a distributed run, over all ranks. */
ry_status ry_check_verdict(const ry_sim *sim, size_t bad, size_t fluid, size_t outside,
                           ry_error *err);
/* The same from this process's particles alone (halo copies skipped): what the parallel
 * layer's verdict uses on the rank that names a bad particle. */
ry_status ry_check_verdict_here(const ry_sim *sim, size_t bad, size_t fluid, size_t outside,
                                ry_error *err);

#endif
