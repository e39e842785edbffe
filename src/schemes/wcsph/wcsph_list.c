/* The neighbour-list pair loop of WCSPH in double precision (scheme.pair_loop: list): the
 * per-particle records both pair loops read (wc_prepare_pairs), then for each fluid particle the
 * momentum equation with the artificial viscosity of Monaghan (1992) and the laminar viscosity
 * of Morris et al. (1997), the continuity equation with delta-SPH density diffusion (Molteni &
 * Colagrossi 2009; Fourtakas et al. 2019), the energy equation and variable h (seed eq. 3.26,
 * 3.43, 3.50-3.52; docs/reference/wcsph.md). */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "schemes/wcsph/wcsph_internal.h"

/* The kernel at a smoothing length other than the reference one (variable h). */
static inline double dwdr_h(const ry_kernel *k, double r, double h) {
    double s = k->h / h, sd = s * s;
    if (k->dim == 3) sd *= s;
    return k->dnorm * sd * s * ry_kernel_dshape(k->type, r / h);
}

/* Per-particle quantities the pair loop reads (computed once per evaluation, so that the pair
 * loop has no divisions by rho and no branches on the kind of j). */
ry_status wc_prepare_pairs(ry_sim *sim, wcsph *w, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const int noslip = w->wall == WALL_NO_SLIP;
    const int tvf = w->tvf;
    double *restrict vol = tvf ? ps->f[w->f_vol] : NULL, *restrict mu = tvf ? ps->f[w->f_mu] : NULL;
    double *restrict isfl = tvf ? ps->f[w->f_isfluid] : NULL;
    double *restrict vis = tvf ? ps->f[w->f_visc] : NULL;
    const double *restrict rho = ps->f[RY_F_RHO], *restrict p = ps->f[RY_F_P];
    const double *restrict m = ps->f[RY_F_MASS];
    const size_t stride = PK_STRIDE(dim);
    if (w->fast) {
        const size_t fs = (n + 8 + 15) & ~(size_t)15; /* room for a last vector */
        if (w->fpack_cap < fs) {
            /* The float fields, 64-byte aligned. */
            free(w->fpack);
            w->fpack = aligned_alloc(64, fs * (size_t)wc_fk_count(w) * sizeof(float));
            w->fpack_cap = w->fpack ? fs : 0;
            RY_CHECK(err, w->fpack != NULL, RY_ERR_NOMEM, "out of memory (%zu particles)", n);
        }
        w->fpack_stride = fs;
        /* Padding: far away and inert. The positions are read in place: the particle arrays
         * hold the padding after the last particle. */
        RY_TRY(ry_particles_reserve(ps, fs, err));
        float *fk = w->fpack;
        for (int d = 0; d < dim; ++d)
            for (size_t i = n; i < fs; ++i) ps->f[RY_F_X + d][i] = 1e10;
        for (int k = 0; k < wc_fk_count(w); ++k)
            for (size_t i = n; i < fs; ++i) fk[k * fs + i] = 0.0f;
        wc_fpack_fluid(sim, w);
        return RY_OK;
    } else if (w->pack_cap < n) {
        double *pk = realloc(w->pack, n * PK_STRIDE(3) * sizeof(double));
        RY_CHECK(err, pk != NULL, RY_ERR_NOMEM, "out of memory (%zu particles)", n);
        w->pack = pk;
        w->pack_cap = n;
    }
    const double *x[3], *v[3];
    double *vg[3];
    for (int d = 0; d < 3; ++d) {
        x[d] = ps->f[RY_F_X + d];
        v[d] = ps->f[RY_F_VX + d];
        vg[d] = ps->f[w->f_vg[d]];
    }
    const double *restrict hh = ps->f[RY_F_H];
    const uint8_t *restrict kind = ps->kind;
    double *restrict pack = w->pack;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        const int fluid = kind[i] == RY_KIND_FLUID, wall = kind[i] == RY_KIND_WALL;
        const double rhoi = rho[i], inv_rho = 1.0 / rhoi;
        const double mui = pack_mu(sim, w, i), visi = pack_visc(sim, w, i);
        if (tvf) {
            vol[i] = m[i] / rhoi;
            mu[i] = mui;
            isfl[i] = fluid ? 1.0 : 0.0;
            vis[i] = visi;
        }
        /* Velocity seen by viscous terms: the ghost velocity on no-slip walls. */
        if (!wall || !noslip)
            for (int d = 0; d < dim; ++d) vg[d][i] = v[d][i];
        double *restrict P = pack + i * stride;
        for (int d = 0; d < dim; ++d) {
            P[PK_X(dim) + d] = x[d][i];
            P[PK_U(dim) + d] = v[d][i];
            P[PK_UG(dim) + d] = vg[d][i];
        }
        double *restrict S = P + PK_S(dim, 0);
        S[PK_RHO] = rhoi;
        S[PK_PRHO2] = p[i] * inv_rho * inv_rho;
        S[PK_VOL] = m[i] * inv_rho;
        S[PK_MU] = mui;
        S[PK_CS] = sound_speed(w, rhoi, p[i]);
        S[PK_MASS] = m[i];
        S[PK_FLUID] = fluid || kind[i] == RY_KIND_OUTLET ? 1.0 : 0.0;
        S[PK_VISC] = visi;
        S[PK_H] = hh ? hh[i] : sim->kernel.h; /* (the field exists with variable h) */
    }
    return RY_OK;
}

/* Everything the pair loop reads, gathered once per evaluation. */
typedef struct pass_ctx {
    size_t n;
    const uint8_t *kind, *material;
    const size_t *off;
    const uint32_t *nb;
    const double *pack, *rho0m;
    const double *x[3]; /* positions, for the range test (denser in memory than the records) */
    double *a[3], *drho, *de;
    double *scratch; /* (SC_COUNT + 1) x len doubles per thread */
    size_t len;      /* longest neighbour list */
    const ry_kernel *k;
    const ry_box *box;
    double h0, inv_h0, dnorm_h, rad2, g[3], diff, inv_c02;
    wc_pair_k_d K; /* the pair term's constants */
    int cont, varh, energy, fourtakas, periodic;
} pass_ctx;

static void pass_ctx_init(pass_ctx *c, ry_sim *sim, const wcsph *w) {
    ry_particles *ps = &sim->ps;
    const ry_kernel *k = &sim->kernel;
    memset(c, 0, sizeof *c);
    c->n = ps->n;
    c->kind = ps->kind;
    c->material = ps->material;
    c->off = sim->nl.offset;
    c->nb = sim->nl.j;
    c->pack = w->pack;
    c->rho0m = w->rho0m;
    for (int d = 0; d < 3; ++d) {
        c->x[d] = ps->f[RY_F_X + (d < sim->dim ? d : 0)];
        c->a[d] = ps->f[RY_F_AX + d];
        c->g[d] = d < sim->dim ? sim->gravity[d] : 0.0;
    }
    c->drho = ps->f[RY_F_DRHO];
    c->de = ps->f[RY_F_DE];
    c->k = k;
    c->box = &sim->box;
    c->h0 = k->h;
    c->inv_h0 = 1.0 / k->h;
    c->dnorm_h = k->dnorm / k->h; /* (dW/dr) / r = dnorm_h f'(q)/q */
    c->rad2 = sim->nl_radius * sim->nl_radius;
    c->cont = w->density == DENS_CONTINUITY;
    c->varh = w->variable_h;
    c->energy = w->energy;
    c->diff = w->diffusion != DIFF_NONE ? 2.0 * w->delta * k->h * w->c0 : 0.0;
    c->fourtakas = w->diffusion == DIFF_FOURTAKAS;
    c->periodic = sim->box.periodic[0] || sim->box.periodic[1] || sim->box.periodic[2];
    c->inv_c02 = 1.0 / (w->c0 * w->c0);
    c->K = wc_pair_constants(sim, w);
    c->len = (sim->nl.max_row + 8) & ~(size_t)7; /* rounded up, at least 8 */
}

/* Acceleration and rates of fluid particle i, in two phases: the neighbours within the support
 * are copied into the scratch block without branches (a pair beyond the support, held by the
 * Verlet skin, is written and then overwritten), then a SIMD loop sums the pair terms. dim,
 * the kernel type and `general` are literals at each call site: the body is compiled once per
 * (dimension, kernel), and the fast variant (general = 0) drops the variable-h, energy and
 * periodic terms. */
static inline __attribute__((always_inline)) void
fluid_particle(const pass_ctx *restrict c, size_t i, double *restrict sc, const int dim,
               const ry_kernel_type kt, const int general, double *amax2, double *vmax2) {
    if (c->kind[i] != RY_KIND_FLUID && c->kind[i] != RY_KIND_OUTLET) return;
    const size_t stride = PK_STRIDE(dim);
    const int X = PK_X(dim), U = PK_U(dim), UG = PK_UG(dim), S = PK_S(dim, 0);
    const double *restrict pack = c->pack;
    const uint32_t *restrict nb = c->nb;
    const size_t len = c->len;
    const double rad2 = c->rad2;
    const int varh = general && c->varh, energy = general && c->energy;
    const int periodic = general && c->periodic;
    const double *restrict Pi = pack + i * stride;
    const double *restrict Si = Pi + S;
    const double xi = Pi[X], yi = Pi[X + 1], zi = dim > 2 ? Pi[X + 2] : 0.0;

    /* Phase 1: the neighbours within the support (indices and separations, stored without
     * branches: a pair beyond the support is written and then overwritten), then their
     * fields copied field by field. */
    double *restrict sdx = sc + SC_DX * len, *restrict sdy = sc + SC_DY * len;
    double *restrict sdz = sc + SC_DZ * len, *restrict sr2 = sc + SC_R2 * len;
    size_t *restrict sj = (size_t *)(sc + SC_COUNT * len);
    size_t cnt = 0;
    const size_t q0 = c->off[i], q1 = c->off[i + 1];
    const double *restrict x0 = c->x[0], *restrict x1 = c->x[1], *restrict x2 = c->x[2];
    for (size_t q = q0; q < q1; ++q) {
        const uint32_t j = nb[q];
        double dxv[3] = {xi - x0[j], yi - x1[j], dim > 2 ? zi - x2[j] : 0.0};
        if (periodic) ry_box_min_image(c->box, dxv);
        const double r2 = dxv[0] * dxv[0] + dxv[1] * dxv[1] + dxv[2] * dxv[2];
        sdx[cnt] = dxv[0];
        sdy[cnt] = dxv[1];
        if (dim > 2) sdz[cnt] = dxv[2];
        sr2[cnt] = r2;
        sj[cnt] = (size_t)j * stride;
        cnt += r2 < rad2; /* the list never holds i itself */
    }
    for (size_t p = 0; p < cnt; ++p) {
        const double *restrict Pj = pack + sj[p];
        const double *restrict Sj = Pj + S;
        for (int d = 0; d < dim; ++d) {
            sc[(SC_U + d) * len + p] = Pj[U + d];
            sc[(SC_UG + d) * len + p] = Pj[UG + d];
        }
        sc[SC_RHO * len + p] = Sj[PK_RHO];
        sc[SC_PRHO2 * len + p] = Sj[PK_PRHO2];
        sc[SC_VOL * len + p] = Sj[PK_VOL];
        sc[SC_MU * len + p] = Sj[PK_MU];
        sc[SC_CS * len + p] = Sj[PK_CS];
        sc[SC_MASS * len + p] = Sj[PK_MASS];
        sc[SC_FLUID * len + p] = Sj[PK_FLUID];
        sc[SC_VISC * len + p] = Sj[PK_VISC];
        if (varh) sc[SC_H * len + p] = Sj[PK_H];
    }

    /* Phase 2: the pair terms (wcsph_pair.h, in double precision; densities taken from the
     * reference 0). */
    const double inv_h0 = c->inv_h0, dnorm_h = c->dnorm_h, hi = Si[PK_H];
    const double ui = Pi[U], vi = Pi[U + 1], wi = dim > 2 ? Pi[U + 2] : 0.0;
    const double gx = c->g[0], gy = c->g[1], gz = dim > 2 ? c->g[2] : 0.0;
    const wc_pair_k_d K = c->K; /* (a local copy: loop-invariant for the vectoriser) */
    wc_pair_i_d I;
    I.ux = ui;
    I.uy = vi;
    I.uz = wi;
    I.drho = I.rho2 = Si[PK_RHO];
    I.prho2 = Si[PK_PRHO2];
    I.mu = Si[PK_MU];
    I.inv_rho = 1.0 / Si[PK_RHO];
    I.cs = Si[PK_CS];
    const double fh = c->fourtakas ? c->rho0m[c->material[i]] * c->inv_c02 : 0.0;
    I.fgx = fh * gx;
    I.fgy = fh * gy;
    I.fgz = fh * gz;
    const double *restrict su = sc + SC_U * len, *restrict sv = sc + SC_V * len;
    const double *restrict sw = sc + SC_W * len, *restrict sug = sc + SC_UG * len;
    const double *restrict svg = sc + SC_VG * len, *restrict swg = sc + SC_WG * len;
    const double *restrict srho = sc + SC_RHO * len, *restrict sprho2 = sc + SC_PRHO2 * len;
    const double *restrict svol = sc + SC_VOL * len, *restrict smu = sc + SC_MU * len;
    const double *restrict scs = sc + SC_CS * len, *restrict smass = sc + SC_MASS * len;
    const double *restrict sfl = sc + SC_FLUID * len, *restrict svis = sc + SC_VISC * len;
    const double *restrict sh = sc + SC_H * len;
    double ax = 0, ay = 0, az = 0, dr = 0, dd = 0, dei = 0;
#pragma omp simd reduction(+ : ax, ay, az, dr, dd, dei)
    for (size_t p = 0; p < cnt; ++p) {
        const double dx = sdx[p], dy = sdy[p], dz = dim > 2 ? sdz[p] : 0.0, r2 = sr2[p];
        double fw;
        if (varh) {
            const double r = sqrt(r2);
            fw = r > 0.0 ? dwdr_h(c->k, r, 0.5 * (hi + sh[p])) / r : 0.0;
        } else {
            fw = dnorm_h * ry_kernel_dshape_over_q(kt, sqrt(r2) * inv_h0);
        }
        wc_pair_j_d J;
        J.ux = su[p];
        J.uy = sv[p];
        J.uz = dim > 2 ? sw[p] : 0.0;
        J.ugx = sug[p];
        J.ugy = svg[p];
        J.ugz = dim > 2 ? swg[p] : 0.0;
        J.drho = srho[p];
        J.prho2 = sprho2[p];
        J.vol = svol[p];
        J.mu = smu[p];
        J.cs = scs[p];
        J.mass = smass[p];
        J.fluid = sfl[p];
        J.visc = svis[p];
        const wc_pair_out_d o = wc_pair_d(&K, &I, &J, dx, dy, dz, r2, fw, dim, energy, 1);
        ax += o.ax;
        ay += o.ay;
        if (dim > 2) az += o.az;
        dr += o.div;
        dd -= o.diff;
        if (energy) dei += o.de;
    }
    const double ai[3] = {ax + gx, ay + gy, az + gz}, vi3[3] = {ui, vi, wi};
    double a2 = 0, v2 = 0;
    for (int d = 0; d < dim; ++d) {
        c->a[d][i] = ai[d];
        a2 += ai[d] * ai[d];
        v2 += vi3[d] * vi3[d];
    }
    if (c->cont) c->drho[i] = I.drho * dr + c->diff * dd;
    if (energy) c->de[i] = dei;
    *amax2 = a2 > *amax2 ? a2 : *amax2;
    *vmax2 = v2 > *vmax2 ? v2 : *vmax2;
}

/* One parallel loop per (dimension, kernel, variant). The OpenMP region must sit in a function
 * of its own for each: the outlined body is made before inlining, so a region inside a shared
 * inline function would see dim and the kernel as run-time values. */
typedef void (*fluid_driver)(const pass_ctx *c, force_out *res);
#define RY_FLUID_DRIVER_(DIM, KT, GEN)                                                             \
    static void fluid_##DIM##_##KT##_##GEN(const pass_ctx *c, force_out *res) {                    \
        double amax2 = 0, vmax2 = 0;                                                               \
        const size_t n = c->n;                                                                     \
        _Pragma("omp parallel reduction(max : amax2, vmax2)") {                                    \
            double *sc = c->scratch + (size_t)omp_get_thread_num() * (SC_COUNT + 1) * c->len;      \
            _Pragma("omp for schedule(dynamic, 64)") for (size_t i = 0; i < n; ++i)                \
                fluid_particle(c, i, sc, DIM, KT, GEN, &amax2, &vmax2);                            \
        }                                                                                          \
        res->amax2 = amax2;                                                                        \
        res->vmax2 = vmax2;                                                                        \
    }
#define RY_FLUID_DRIVERS_(KT)                                                                      \
    RY_FLUID_DRIVER_(2, KT, 0)                                                                     \
    RY_FLUID_DRIVER_(2, KT, 1) RY_FLUID_DRIVER_(3, KT, 0) RY_FLUID_DRIVER_(3, KT, 1)
RY_FOR_EACH_KERNEL_(RY_FLUID_DRIVERS_)
#define RY_FLUID_ROW_(KT) RY_DRIVER_ROW_(fluid, KT),
static const fluid_driver fluid_drivers[RY_KERNEL_COUNT][2][2] = {
    RY_FOR_EACH_KERNEL_(RY_FLUID_ROW_)};
#undef RY_FLUID_ROW_
#undef RY_FLUID_DRIVERS_
#undef RY_FLUID_DRIVER_

/* Forces and rates by the neighbour-list loop, on the records of wc_prepare_pairs. */
ry_status wc_list_forces(ry_sim *sim, wcsph *w, force_out *res, ry_error *err) {
    pass_ctx c;
    pass_ctx_init(&c, sim, w);
    const size_t cap = c.len * (size_t)omp_get_max_threads();
    if (w->scratch_cap < cap) {
        double *sc = realloc(w->scratch, cap * (SC_COUNT + 1) * sizeof(double));
        RY_CHECK(err, sc != NULL, RY_ERR_NOMEM, "out of memory (neighbour scratch)");
        w->scratch = sc;
        w->scratch_cap = cap;
    }
    c.scratch = w->scratch;
    const int general = c.varh || c.energy || c.periodic;
    fluid_drivers[sim->kernel.type][sim->dim - 2][general](&c, res);
    return RY_OK;
}
