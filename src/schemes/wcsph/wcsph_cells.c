/* The cell-range pair loop of WCSPH (scheme.pair_loop: cells): the pair term of the
 * neighbour-list loop (wcsph_pair.h) in single precision, for the cases that wc_fast_eligible
 * admits, with its candidate ranges (wc_fast_ranges) and its single-precision records
 * (wc_fpack_fluid).
 *
 * The particles are sorted by cell at every neighbour search (sim->sort_always), so the
 * candidates of particle i are the particles of the 3 (2D) or 9 (3D) rows of cells around its
 * cell at the last search: consecutive index ranges, a superset of the Verlet list. The pair
 * terms run as one SIMD loop of eight lanes over each range (eight pairs per AVX instruction),
 * the pairs beyond the support masked: no neighbour list is read and no neighbour data is
 * gathered or copied. Separations are formed from the double-precision positions and then
 * rounded; densities enter as deviations from a reference density (so that rho_j - rho_i keeps
 * its digits); the lanes' sums are added in double precision. The state and the integrator stay
 * in double precision. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "kernel/kernel_float.h"
#include "schemes/wcsph/wcsph_internal.h"

typedef struct fast_ctx {
    const uint8_t *kind;
    const uint32_t *rng;
    const float *fk; /* field k of particle j: fk[k * fs + j] */
    size_t fs;
    const double *x[3], *rho;
    double *a[3], *drho, *de;
    const double *v[3], *rho0m;
    const uint8_t *material;
    double g[3], diff, rho_ref, inv_c02;
    double hdt, hdt_rho; /* the predictions of wc_lean (0 otherwise) */
    const uint8_t *halo; /* a distributed run's halo particles (NULL: none) */
    float rad2, inv_h, dnorm_h, c0, kappa;
    wc_pair_k_f K; /* the pair term's constants */
    int cont, fourtakas, energy;
} fast_ctx;

/* Candidate l of fluid particle i (at xi, yi, zi; record I) in the cell-range loop: the pair
 * term, its kernel factor zero beyond the support. (A function of its own, so that the SIMD loop
 * that calls it has no addressable locals to privatise per lane.) */
static inline __attribute__((always_inline)) wc_pair_out_f
fluid_lane(const fast_ctx *restrict c, const wc_pair_k_f *K, const wc_pair_i_f *I, float hi,
           double xi, double yi, double zi, size_t l, const int dim, const ry_kernel_type kt,
           const int repulse, const int general) {
    const size_t fs = c->fs;
    const float *restrict fk = c->fk;
    const float dx = (float)(xi - c->x[0][l]), dy = (float)(yi - c->x[1][l]);
    const float dz = dim > 2 ? (float)(zi - c->x[2][l]) : 0.0f;
    float r2 = dx * dx + dy * dy;
    if (dim > 2) r2 += dz * dz;
    /* i itself (r2 = 0) contributes nothing: every term has a factor x_ij or r2, and the
     * repulsion needs r2 > 0. */
    float fw;
    if (general) {
        /* At h_ij = (h_i + h_j) / 2: dW/dr / r = dnorm / h0 (h0 / h_ij)^(d+2) f'(q) / q with
         * q = r / h_ij, zero from q = kappa on (the search covers the largest h). */
        const float hij = 0.5f * (hi + c->fk[FK_H * fs + l]), inv_hij = 1.0f / hij;
        const float s = K->h * inv_hij, s2 = s * s, sd = dim > 2 ? s2 * s2 * s : s2 * s2;
        const float q = sqrtf(r2) * inv_hij;
        const float fq = c->dnorm_h * sd * ry_kdshape_over_qf(kt, q);
        fw = ((r2 < c->rad2) & (q < c->kappa)) ? fq : 0.0f;
    } else {
        const float fq = c->dnorm_h * ry_kdshape_over_qf(kt, sqrtf(r2) * c->inv_h);
        fw = r2 < c->rad2 ? fq : 0.0f;
    }
    wc_pair_j_f J;
    J.ux = fk[FK_U * fs + l];
    J.uy = fk[FK_V * fs + l];
    J.uz = dim > 2 ? fk[FK_W * fs + l] : 0.0f;
    J.ugx = fk[FK_UG * fs + l];
    J.ugy = fk[FK_VG * fs + l];
    J.ugz = dim > 2 ? fk[FK_WG * fs + l] : 0.0f;
    J.drho = fk[FK_DRHO * fs + l];
    J.prho2 = fk[FK_PRHO2 * fs + l];
    J.vol = fk[FK_VOL * fs + l];
    J.mu = fk[FK_MU * fs + l];
    J.cs = general ? fk[FK_CS * fs + l] : c->c0;
    J.mass = fk[FK_MASS * fs + l];
    /* (FK_MU: the viscous coupling of a particle that is not fluid; exact, and without a
     * comparison, which would keep this loop from vectorising with GCC) */
    J.fluid = fk[FK_FLUID * fs + l];
    J.visc = J.fluid + (1.0f - J.fluid) * J.mu;
    return wc_pair_f(K, I, &J, dx, dy, dz, r2, fw, dim, general, repulse);
}

/* Acceleration and density rate of fluid particle i: the pair term of wcsph_pair.h in single
 * precision over the candidate ranges, eight candidates at a time (one SIMD loop of eight
 * lanes, each lane with its own sums, so that the order of summation does not depend on the
 * processor's vector width), candidates beyond the support masked by fw = 0. dim, the kernel
 * type and `repulse` are literals at each call site. */
static inline __attribute__((always_inline)) void
fast_particle(const fast_ctx *restrict c, size_t i, const int dim, const ry_kernel_type kt,
              const int repulse, const int general, double *amax2, double *vmax2) {
    if (c->kind[i] != RY_KIND_FLUID) return;
    const int nrange = dim > 2 ? 9 : 3;
    const uint32_t *restrict rg = c->rng + (size_t)i * 2 * (size_t)nrange;
    const size_t fs = c->fs;
    const float *restrict fk = c->fk;
    const double xi = c->x[0][i], yi = c->x[1][i], zi = dim > 2 ? c->x[2][i] : 0.0;
    const wc_pair_k_f K = c->K; /* (a local copy: loop-invariant for the vectoriser) */
    wc_pair_i_f I;
    I.ux = fk[FK_U * fs + i];
    I.uy = fk[FK_V * fs + i];
    I.uz = dim > 2 ? fk[FK_W * fs + i] : 0.0f;
    I.drho = fk[FK_DRHO * fs + i];
    I.rho2 = 2.0f * (float)c->rho_ref + I.drho;
    I.prho2 = fk[FK_PRHO2 * fs + i];
    I.mu = fk[FK_MU * fs + i];
    /* The predicted density and velocity (wc_lean; hdt = 0 otherwise), from the old rates
     * before this particle's new ones replace them. */
    const double rho_i = c->rho[i] + c->hdt_rho * c->drho[i];
    double vs[3] = {0, 0, 0};
    for (int d = 0; d < dim; ++d) vs[d] = c->v[d][i] + c->hdt * c->a[d][i];
    I.inv_rho = (float)(1.0 / rho_i);
    /* The sound speed is c0 for the Tait and linear equations of state (constant), the
     * particles' own with the ideal gas (the general form). */
    I.cs = general ? fk[FK_CS * fs + i] : c->c0;
    const float hi = general ? fk[FK_H * fs + i] : K.h;
    const float fh = c->fourtakas ? (float)(c->rho0m[c->material[i]] * c->inv_c02) : 0.0f;
    I.fgx = fh * (float)c->g[0];
    I.fgy = fh * (float)c->g[1];
    I.fgz = fh * (float)c->g[2];
    float sx[8] = {0}, sy[8] = {0}, sz[8] = {0}, sr[8] = {0}, sd[8] = {0}, se[8] = {0};
    for (int r = 0; r < nrange; ++r) {
        for (size_t j = rg[2 * r]; j < rg[2 * r + 1]; j += 8) {
#pragma omp simd
            for (int k = 0; k < 8; ++k) {
                const wc_pair_out_f o =
                    fluid_lane(c, &K, &I, hi, xi, yi, zi, j + (size_t)k, dim, kt, repulse, general);
                sx[k] += o.ax;
                sy[k] += o.ay;
                if (dim > 2) sz[k] += o.az;
                sr[k] += o.div;
                sd[k] -= o.diff;
                if (general) se[k] += o.de;
            }
        }
    }
    const double ai[3] = {wc_lanes_sum(sx) + c->g[0], wc_lanes_sum(sy) + c->g[1],
                          wc_lanes_sum(sz) + c->g[2]};
    double a2 = 0, v2 = 0;
    for (int d = 0; d < dim; ++d) {
        c->a[d][i] = ai[d];
        a2 += ai[d] * ai[d];
        v2 += vs[d] * vs[d];
    }
    if (c->cont) c->drho[i] = rho_i * wc_lanes_sum(sr) + c->diff * wc_lanes_sum(sd);
    if (general && c->energy) c->de[i] = wc_lanes_sum(se);
    if (c->halo && c->halo[i]) return; /* the largest values: owned particles only */
    *amax2 = a2 > *amax2 ? a2 : *amax2;
    *vmax2 = v2 > *vmax2 ? v2 : *vmax2;
}

typedef void (*fast_driver)(const fast_ctx *c, size_t n, force_out *res);
#define RY_FAST_DRIVER_(DIM, KT, REP, GEN)                                                         \
    static void fast_##DIM##_##KT##_##REP##GEN(const fast_ctx *c, size_t n, force_out *res) {      \
        double amax2 = 0, vmax2 = 0;                                                               \
        _Pragma("omp parallel for schedule(dynamic, 64) reduction(max : amax2, vmax2)") for (      \
            size_t i = 0; i < n; ++i) fast_particle(c, i, DIM, KT, REP, GEN, &amax2, &vmax2);      \
        res->amax2 = amax2;                                                                        \
        res->vmax2 = vmax2;                                                                        \
    }
#define RY_FAST_DRIVERS_DIM_(DIM, KT)                                                              \
    RY_FAST_DRIVER_(DIM, KT, 0, 0)                                                                 \
    RY_FAST_DRIVER_(DIM, KT, 0, 1) RY_FAST_DRIVER_(DIM, KT, 1, 0) RY_FAST_DRIVER_(DIM, KT, 1, 1)
#define RY_FAST_DRIVERS_(KT) RY_FAST_DRIVERS_DIM_(2, KT) RY_FAST_DRIVERS_DIM_(3, KT)
RY_FOR_EACH_KERNEL_(RY_FAST_DRIVERS_)
/* fast_drivers[kernel][dim - 2][repulsion][general form] */
#define RY_FAST_ROW_DIM_(DIM, KT)                                                                  \
    {                                                                                              \
        {fast_##DIM##_##KT##_00, fast_##DIM##_##KT##_01}, {                                        \
            fast_##DIM##_##KT##_10, fast_##DIM##_##KT##_11                                         \
        }                                                                                          \
    }
#define RY_FAST_ROW_(KT) [KT] = {RY_FAST_ROW_DIM_(2, KT), RY_FAST_ROW_DIM_(3, KT)},
static const fast_driver fast_drivers[RY_KERNEL_COUNT][2][2][2] = {
    RY_FOR_EACH_KERNEL_(RY_FAST_ROW_)};
#undef RY_FAST_ROW_
#undef RY_FAST_ROW_DIM_
#undef RY_FAST_DRIVERS_
#undef RY_FAST_DRIVERS_DIM_
#undef RY_FAST_DRIVER_

/* Whether the cell-range loop serves this case (every kernel, the energy equation, variable h):
 * no periodic directions, symmetry planes, transport velocity or open boundaries (whose buffers
 * change the particle set between searches), rheology or surface tension. */
int wc_fast_eligible(const ry_sim *sim, const wcsph *w, const char **why) {
    const ry_box *b = &sim->box;
    *why = is_periodic(sim)                                     ? "no periodic directions"
           : b->symmetry[0] || b->symmetry[1] || b->symmetry[2] ? "no symmetry planes"
           : w->tvf                                             ? "no transport_velocity"
           : sim->nopen > 0                                     ? "no open boundaries"
           : w->rheo.on                                         ? "Newtonian materials"
           : w->st.model != RY_ST_NONE                          ? "no surface_tension"
                                                                : NULL;
    return *why == NULL;
}

/* Whether a cell of the block of 3 x 3 (x 3) around cell (kx, ky, kz) holds fluid. */
static int fluid_near(const ry_cell_list *cl, const uint8_t *cell_fluid, int kx, int ky, int kz) {
    const int nx = cl->ncell[0], ny = cl->ncell[1], nz = cl->ncell[2];
    int f = 0;
    for (int z = kz - 1; z <= kz + 1; ++z) {
        if (z < 0 || z >= nz) continue;
        for (int y = ky - 1; y <= ky + 1; ++y) {
            if (y < 0 || y >= ny) continue;
            const size_t row = ((size_t)z * (size_t)ny + (size_t)y) * (size_t)nx;
            for (int x = kx - 1; x <= kx + 1; ++x)
                if (x >= 0 && x < nx) f |= cell_fluid[row + (size_t)x];
        }
    }
    return f;
}

/* The candidates of each particle, from the positions and cells of the last search (the
 * particles sorted by cell and, within each row of cells, by x): in each of the 3 (2D) or 9
 * (3D) rows of cells around its cell, the particles within the circle (sphere) of radius
 * reach = support + skin: in a row at distance e from the particle, those within
 * x +- sqrt(reach^2 - e^2). A pair within the support now was within reach then (no particle
 * has moved more than half the skin since), so the ranges hold every neighbour, like the
 * Verlet list. Each range's length is rounded up to a multiple of 8 (whole vectors) and ranges
 * that then overlap are merged, so that no pair is counted twice; the particles this adds lie
 * beyond reach, and the padding after the last particle lies 1e10 m away: the pair loop's
 * range mask removes both. */
ry_status wc_fast_ranges(ry_sim *sim, wcsph *w, ry_error *err) {
    const ry_cell_list *cl = &sim->cells;
    const int dim = sim->dim, nrange = dim > 2 ? 9 : 3;
    const size_t n = sim->ps.n;
    if (w->rng_cap < n) {
        uint32_t *r = realloc(w->rng, n * 2 * (size_t)nrange * sizeof *r);
        RY_CHECK(err, r != NULL, RY_ERR_NOMEM, "out of memory (%zu particles)", n);
        w->rng = r;
        uint8_t *wet = realloc(w->wet, n);
        RY_CHECK(err, wet != NULL, RY_ERR_NOMEM, "out of memory (%zu particles)", n);
        w->wet = wet;
        w->rng_cap = n;
        w->nrange = nrange;
    }
    const double *xr = sim->ps.f[sim->f_xref];
    const double reach = sim->nl_radius * (1.0 + sim->nl_skin), reach2 = reach * reach;
    const double *yr = sim->ps.f[sim->f_xref + 1];
    const double *zr = sim->ps.f[sim->f_xref + (dim > 2 ? 2 : 1)];
    const size_t *start = cl->start;
    const int nx = cl->ncell[0], ny = cl->ncell[1], nz = cl->ncell[2];
    uint32_t *rng = w->rng;
    if (w->cell_fluid_cap < cl->ncells) {
        uint8_t *cf = realloc(w->cell_fluid, cl->ncells);
        RY_CHECK(err, cf != NULL, RY_ERR_NOMEM, "out of memory (%zu cells)", cl->ncells);
        w->cell_fluid = cf;
        w->cell_fluid_cap = cl->ncells;
    }
    uint8_t *cell_fluid = w->cell_fluid;
    const uint8_t *kind = sim->ps.kind;
    const long long ncells = (long long)cl->ncells;
#pragma omp parallel for schedule(static)
    for (long long c = 0; c < ncells; ++c) {
        uint8_t f = 0;
        for (size_t j = start[c]; j < start[c + 1]; ++j) f |= kind[j] == RY_KIND_FLUID;
        cell_fluid[c] = f;
    }
#pragma omp parallel
    {
        /* The bounds of the previous particle of the same cell, per row slot: the particles
         * of a cell are close in x, so a particle finds its bounds by stepping from there (a
         * binary search for the first particle of a cell). */
        size_t prev_cell = SIZE_MAX, lb[9], ub[9];
        int known[9] = {0};
#pragma omp for schedule(static)
        for (size_t i = 0; i < n; ++i) {
            const size_t cell = cl->cell_of[i];
            const int kx = (int)(cell % (size_t)nx), ky = (int)(cell / (size_t)nx % (size_t)ny);
            const int kz = dim > 2 ? (int)(cell / ((size_t)nx * (size_t)ny)) : 0;
            const int xa = kx > 0 ? kx - 1 : 0, xb = kx + 1 < nx ? kx + 1 : nx - 1;
            if (cell != prev_cell)
                for (int k = 0; k < 9; ++k) known[k] = 0;
            prev_cell = cell;
            /* Distances from the particle to the rows of cells above and below (and in front
             * and behind): a row at distance e holds candidates within x +- sqrt(reach^2 - e^2)
             * only. The margin covers the rounding of the binning. */
            const double yi = yr[i], zi = dim > 2 ? zr[i] : 0.0, margin = 1e-9 * reach;
            const double ylo = cl->lo[1] + ky * cl->cell[1], zlo = cl->lo[2] + kz * cl->cell[2];
            const double eb = yi - ylo - margin, ea = ylo + cl->cell[1] - yi - margin;
            const double fb = dim > 2 ? zi - zlo - margin : 0.0;
            const double fa = dim > 2 ? zlo + cl->cell[2] - zi - margin : 0.0;
            const double ey[3] = {eb > 0 ? eb : 0.0, 0.0, ea > 0 ? ea : 0.0};
            const double ez[3] = {fb > 0 ? fb : 0.0, 0.0, fa > 0 ? fa : 0.0};
            /* Half-widths per row slot, all at once (negative: the row lies beyond reach). */
            double half[9];
            for (int k = dim > 2 ? 0 : 3; k < (dim > 2 ? 9 : 6); ++k) {
                const double e2 = ey[k % 3] * ey[k % 3] + ez[k / 3] * ez[k / 3];
                half[k] = e2 < reach2 ? sqrt(reach2 - e2) : -1.0;
            }
            uint32_t *rg = rng + i * 2 * (size_t)nrange;
            if (wall_like(&sim->ps, i) && !fluid_near(cl, cell_fluid, kx, ky, kz)) {
                /* No fluid in the cells around: no candidates the wall pass would use. */
                for (int r = 0; r < nrange; ++r) rg[2 * r] = rg[2 * r + 1] = 0;
                w->wet[i] = 0;
                continue;
            }
            int nr = 0;
            for (int z = kz - 1; z <= kz + 1; ++z) {
                if (dim < 3 && z != kz) continue;
                if (z < 0 || z >= nz) continue;
                for (int y = ky - 1; y <= ky + 1; ++y) {
                    if (y < 0 || y >= ny) continue;
                    const int slot = (z - kz + 1) * 3 + (y - ky + 1);
                    if (half[slot] < 0) continue;
                    const double lo = xr[i] - half[slot], hi = xr[i] + half[slot];
                    const size_t row = ((size_t)z * (size_t)ny + (size_t)y) * (size_t)nx;
                    const size_t ra = start[row + (size_t)xa], b0 = start[row + (size_t)xb + 1];
                    size_t a, b;
                    if (known[slot]) {
                        /* first with x >= lo, first with x > hi */
                        a = lb[slot];
                        while (a > ra && xr[a - 1] >= lo) --a;
                        while (a < b0 && xr[a] < lo) ++a;
                        b = ub[slot] > a ? ub[slot] : a;
                        while (b > a && xr[b - 1] > hi) --b;
                        while (b < b0 && xr[b] <= hi) ++b;
                    } else {
                        size_t l = ra, u = b0;
                        while (l < u) {
                            const size_t m = l + (u - l) / 2;
                            if (xr[m] < lo)
                                l = m + 1;
                            else
                                u = m;
                        }
                        a = l;
                        u = b0;
                        while (l < u) {
                            const size_t m = l + (u - l) / 2;
                            if (xr[m] <= hi)
                                l = m + 1;
                            else
                                u = m;
                        }
                        b = l;
                    }
                    known[slot] = 1;
                    lb[slot] = a;
                    ub[slot] = b;
                    if (b <= a) continue;
                    if (nr > 0 && a < rg[2 * nr - 1]) {
                        const size_t a0 = rg[2 * nr - 2];
                        rg[2 * nr - 1] = (uint32_t)(a0 + ((b - a0 + 7) & ~(size_t)7));
                    } else {
                        rg[2 * nr] = (uint32_t)a;
                        rg[2 * nr + 1] = (uint32_t)(a + ((b - a + 7) & ~(size_t)7));
                        ++nr;
                    }
                }
            }
            for (; nr < nrange; ++nr) rg[2 * nr] = rg[2 * nr + 1] = 0;
            /* Whether a wall particle has fluid among its candidates (its pass is skipped if not:
             * its sums would be exactly zero). The kinds do not change between searches. */
            uint8_t wet = 0;
            if (wall_like(&sim->ps, i))
                for (int r = 0; r < nrange && !wet; ++r)
                    for (size_t j = rg[2 * r]; j < rg[2 * r + 1] && j < n && !wet; ++j)
                        wet = sim->ps.kind[j] == RY_KIND_FLUID;
            w->wet[i] = wet;
        }
    }
    w->rng_gen = sim->nl_generation;
    return RY_OK;
}

/* The records of the general form (wc_fast_general) once the wall pass has set the walls'
 * densities and pressures: every particle's sound speed and smoothing length. */
static void fpack_general(ry_sim *sim, const wcsph *w) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n, fs = w->fpack_stride;
    const double *restrict rho = ps->f[RY_F_RHO], *restrict p = ps->f[RY_F_P];
    const double *restrict h = ps->f[RY_F_H];
    const double h0 = sim->kernel.h;
    float *restrict cs = w->fpack + FK_CS * fs, *restrict fh = w->fpack + FK_H * fs;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        cs[i] = (float)sound_speed(w, rho[i], p[i]);
        fh[i] = (float)(h ? h[i] : h0);
    }
}

void wc_fast_forces(ry_sim *sim, const wcsph *w, force_out *res) {
    const ry_particles *ps = &sim->ps;
    const ry_kernel *k = &sim->kernel;
    fast_ctx c;
    memset(&c, 0, sizeof c);
    c.kind = ps->kind;
    c.rng = w->rng;
    c.fs = w->fpack_stride;
    c.fk = w->fpack;
    for (int d = 0; d < 3; ++d) {
        c.x[d] = ps->f[RY_F_X + (d < sim->dim ? d : 0)];
        c.v[d] = ps->f[RY_F_VX + (d < sim->dim ? d : 0)];
        c.a[d] = ps->f[RY_F_AX + d];
        c.g[d] = d < sim->dim ? sim->gravity[d] : 0.0;
    }
    c.rho = ps->f[RY_F_RHO];
    c.drho = ps->f[RY_F_DRHO];
    c.rho_ref = w->rho0m[0];
    c.cont = w->density == DENS_CONTINUITY;
    c.diff = w->diffusion != DIFF_NONE ? 2.0 * w->delta * k->h * w->c0 : 0.0;
    c.fourtakas = w->diffusion == DIFF_FOURTAKAS;
    c.rho0m = w->rho0m;
    c.material = ps->material;
    c.inv_c02 = 1.0 / (w->c0 * w->c0);
    c.rad2 = (float)(sim->nl_radius * sim->nl_radius);
    c.inv_h = (float)k->inv_h;
    c.dnorm_h = (float)(k->dnorm / k->h);
    c.c0 = (float)w->c0;
    c.hdt = w->hdt;
    c.halo = sim->halo;
    c.hdt_rho = c.cont ? w->hdt : 0.0;
    c.kappa = (float)k->kappa;
    c.de = ps->f[RY_F_DE];
    c.energy = w->energy;
    const wc_pair_k_d K = wc_pair_constants(sim, w);
    c.K.h = (float)K.h;
    c.K.eta2 = (float)K.eta2;
    c.K.alpha = (float)K.alpha;
    c.K.beta = (float)K.beta;
    c.K.rep_d = (float)K.rep_d;
    c.K.rep_r02 = (float)K.rep_r02;
    const int general = wc_fast_general(w);
    if (general) fpack_general(sim, w);
    fast_drivers[k->type][sim->dim - 2][c.K.rep_r02 > 0.0f][general](&c, ps->n, res);
}

/* Whether every material has the density and viscosity of the first, and the equation of
 * state is Tait or linear (the cell-range loop's single-material passes). */
int wc_uniform_materials(const ry_sim *sim, const wcsph *w) {
    int same = w->eos != EOS_IDEAL_GAS;
    for (int m = 1; m < sim->nmat; ++m)
        same &= sim->mat[m].density == sim->mat[0].density &&
                sim->mat[m].viscosity == sim->mat[0].viscosity;
    return same;
}

/* The pressure of the fluid (equation of state) and the records of the particles other than
 * walls (the wall pass writes the walls'), in one loop over contiguous arrays. */
static void fpack_fluid_one_rho0(ry_sim *sim, const wcsph *w);

void wc_fpack_fluid(ry_sim *sim, const wcsph *w) {
    if (wc_uniform_materials(sim, w)) {
        fpack_fluid_one_rho0(sim, w);
        return;
    }
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n, fs = w->fpack_stride;
    const int dim = sim->dim, laminar = w->laminar;
    const double rho_ref = w->rho0m[0];
    const uint8_t *restrict kind = ps->kind, *restrict matl = ps->material;
    const double *restrict rho = ps->f[RY_F_RHO], *restrict e = ps->f[RY_F_E];
    double *restrict p = ps->f[RY_F_P];
    const double *restrict m = ps->f[RY_F_MASS];
    const ry_material *mat = sim->mat;
    float *restrict fk = w->fpack;
    /* the predicted velocity and density of the fluid (wc_lean) */
    const int pred = w->lean, pred_rho = w->lean && w->density == DENS_CONTINUITY;
    const double hdt = w->hdt, *restrict dr = ps->f[RY_F_DRHO];
    const double *v[3], *a[3];
    for (int d = 0; d < 3; ++d) {
        v[d] = ps->f[RY_F_VX + (d < dim ? d : 0)];
        a[d] = ps->f[RY_F_AX + (d < dim ? d : 0)];
    }
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        const int f = kind[i] == RY_KIND_FLUID;
        for (int d = 0; d < dim; ++d) {
            /* walls: rewritten by the wall pass */
            const double vs = pred && f ? v[d][i] + hdt * a[d][i] : v[d][i];
            fk[(FK_U + d) * fs + i] = fk[(FK_UG + d) * fs + i] = (float)vs;
        }
        if (kind[i] == RY_KIND_WALL || kind[i] == RY_KIND_INLET) {
            /* Until the wall pass: inert, as the wall pass reads every candidate (masked). */
            for (int k = FK_DRHO; k < FK_COUNT; ++k) fk[(size_t)k * fs + i] = 0.0f;
            continue;
        }
        const double r = pred_rho && f ? rho[i] + hdt * dr[i] : rho[i];
        if (f) p[i] = eos_pressure(w, matl[i], r, e ? e[i] : 0.0);
        const double inv_rho = 1.0 / r;
        fk[FK_DRHO * fs + i] = (float)(r - rho_ref);
        fk[FK_PRHO2 * fs + i] = (float)(p[i] * inv_rho * inv_rho);
        fk[FK_VOL * fs + i] = (float)(m[i] * inv_rho);
        fk[FK_MU * fs + i] = laminar ? (float)(r * mat[matl[i]].viscosity) : 0.0f;
        fk[FK_MASS * fs + i] = (float)m[i];
        fk[FK_FLUID * fs + i] = kind[i] == RY_KIND_FLUID || kind[i] == RY_KIND_OUTLET;
        if (!fk[FK_FLUID * fs + i]) fk[FK_MU * fs + i] = 1.0f; /* viscous (not a wall) */
        fk[FK_P * fs + i] = (float)p[i];
    }
}

/* wc_fpack_fluid for one reference density and the Tait or linear equation of state: one pass
 * per array, so that each vectorises; walls get inert records until the wall pass. */
static void fpack_fluid_one_rho0(ry_sim *sim, const wcsph *w) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n, fs = w->fpack_stride;
    const int dim = sim->dim;
    const uint8_t *restrict kind = ps->kind;
    const double *restrict rho = ps->f[RY_F_RHO], *restrict m = ps->f[RY_F_MASS];
    double *restrict p = ps->f[RY_F_P];
    float *restrict fk = w->fpack;
    const double rho0 = w->rho0m[0], B = w->Bm[0], pb = w->p_background;
    const double c02 = w->c0 * w->c0;
    const int tait7 = w->eos == EOS_TAIT && w->gamma == 7.0, linear = w->eos == EOS_LINEAR;
    const double nu = w->laminar ? sim->mat[0].viscosity : 0.0;
    /* the predicted velocity and density of the fluid (wc_lean) */
    const int pred = w->lean, pred_rho = w->lean && w->density == DENS_CONTINUITY;
    const double hdt = w->hdt, *restrict dr = ps->f[RY_F_DRHO];
#pragma omp parallel
    {
        for (int d = 0; d < dim; ++d) {
            const double *restrict v = ps->f[RY_F_VX + d], *restrict a = ps->f[RY_F_AX + d];
            float *restrict u = fk + (FK_U + d) * fs, *restrict ug = fk + (FK_UG + d) * fs;
            if (pred) {
#pragma omp for schedule(static) nowait
                for (size_t i = 0; i < n; ++i) {
                    const double vs = kind[i] == RY_KIND_FLUID ? v[i] + hdt * a[i] : v[i];
                    u[i] = ug[i] = (float)vs; /* walls: rewritten by the wall pass */
                }
            } else {
#pragma omp for schedule(static) nowait
                for (size_t i = 0; i < n; ++i) u[i] = ug[i] = (float)v[i];
            }
        }
        if (tait7 || linear) {
#pragma omp for schedule(static) nowait
            for (size_t i = 0; i < n; ++i) {
                const double r =
                    pred_rho && kind[i] == RY_KIND_FLUID ? rho[i] + hdt * dr[i] : rho[i];
                const double q = r / rho0, q2 = q * q;
                const double pt = tait7 ? B * (q2 * q2 * q2 * q - 1.0) + pb : c02 * (r - rho0) + pb;
                p[i] = kind[i] == RY_KIND_FLUID ? pt : p[i];
            }
        } else {
#pragma omp for schedule(static) nowait
            for (size_t i = 0; i < n; ++i)
                if (kind[i] == RY_KIND_FLUID)
                    p[i] = eos_pressure(w, 0, pred_rho ? rho[i] + hdt * dr[i] : rho[i], 0.0);
        }
        float *restrict fdr = fk + FK_DRHO * fs, *restrict fpr = fk + FK_PRHO2 * fs;
        float *restrict fvol = fk + FK_VOL * fs, *restrict fmu = fk + FK_MU * fs;
        float *restrict fm = fk + FK_MASS * fs, *restrict fp = fk + FK_P * fs;
        float *restrict ffl = fk + FK_FLUID * fs;
#pragma omp for schedule(static) nowait
        for (size_t i = 0; i < n; ++i) {
            /* Walls stay inert until the wall pass (it reads every candidate, masked). */
            const float on = kind[i] == RY_KIND_WALL ? 0.0f : 1.0f;
            const double r = pred_rho && kind[i] == RY_KIND_FLUID ? rho[i] + hdt * dr[i] : rho[i];
            const double inv_rho = 1.0 / r;
            fdr[i] = on * (float)(r - rho0);
            fpr[i] = on * (float)(p[i] * inv_rho * inv_rho);
            fvol[i] = on * (float)(m[i] * inv_rho);
            fmu[i] = kind[i] == RY_KIND_FLUID ? (float)(r * nu) : on; /* (FK_MU) */
            fm[i] = on * (float)m[i];
            ffl[i] = kind[i] == RY_KIND_FLUID ? 1.0f : 0.0f;
            fp[i] = on * (float)p[i];
        }
    }
}
