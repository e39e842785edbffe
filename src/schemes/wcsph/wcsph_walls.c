/* The wall pass of WCSPH: dummy wall particles take a pressure extrapolated from the fluid,
 * a density from the equation of state and, for no-slip walls, the ghost velocity 2 v_w - v~
 * (Adami, Hu & Adams (2012), J. Comput. Phys. 231: 7057, eq. 22-23 and 27-28). Sums over the
 * neighbour list (double precision) or over the candidate ranges of the cell-range loop (single
 * precision, which then also writes the walls' records). */
#include <math.h>

#include "boundary/walls_adami2012.h"
#include "kernel/kernel_float.h"
#include "schemes/wcsph/wcsph_internal.h"

/* Wall particles: pressure, density and ghost velocity extrapolated from the fluid
 * (boundary/walls_adami2012.h). The sums of wall particle i over its fluid neighbours j, from
 * the list (rows) or from the candidate ranges of the cell-range loop. */
static inline __attribute__((always_inline)) void wall_sums_list(const ry_sim *sim, size_t i,
                                                                 ry_adami_sums *s) {
    const ry_particles *ps = &sim->ps;
    const ry_kernel *k = &sim->kernel;
    const int dim = sim->dim;
    const double *p = ps->f[RY_F_P], *rho = ps->f[RY_F_RHO], *g = sim->gravity;
    const double rad2 = k->radius * k->radius;
    const int periodic = is_periodic(sim);
    for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
        uint32_t j = sim->nl.j[q];
        if (ps->kind[j] != RY_KIND_FLUID && ps->kind[j] != RY_KIND_OUTLET) continue;
        double dx[3] = {0, 0, 0}, r2 = 0;
        for (int d = 0; d < dim; ++d) dx[d] = ps->f[RY_F_X + d][i] - ps->f[RY_F_X + d][j];
        if (periodic) ry_box_min_image(&sim->box, dx);
        for (int d = 0; d < dim; ++d) r2 += dx[d] * dx[d];
        if (r2 >= rad2) continue;
        const double wij = ry_kernel_w(k, sqrt(r2));
        double vj[3] = {0, 0, 0};
        for (int d = 0; d < dim; ++d) vj[d] = ps->f[RY_F_VX + d][j];
        ry_adami_add_pressure(s, wij, p[j], ry_adami_head(g, dx, dim, rho[j]));
        ry_adami_add_velocity(s, wij, vj, dim);
    }
}

/* Pressure and density of wall (and inlet) particle i from its sums, and its ghost velocity
 * into vg. */
static inline void wall_set(ry_sim *sim, const wcsph *w, size_t i, const ry_adami_sums *s,
                            double vg[3]) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim, inlet = ps->kind[i] == RY_KIND_INLET;
    const int mat = ps->material[i];
    if (s->sw > 0) {
        const double pw = ry_adami_pressure(s);
        ps->f[RY_F_P][i] = pw;
        ps->f[RY_F_RHO][i] = eos_density(w, mat, pw);
        for (int d = 0; d < dim; ++d) {
            const double vw = ps->f[RY_F_VX + d][i];
            vg[d] = inlet ? vw : ry_adami_ghost_velocity(s, d, vw);
        }
    } else {
        ps->f[RY_F_P][i] = w->p_background;
        ps->f[RY_F_RHO][i] = w->rho0m[mat];
        for (int d = 0; d < dim; ++d) vg[d] = ps->f[RY_F_VX + d][i];
    }
}

void wc_wall_pass(ry_sim *sim, const wcsph *w) {
    const size_t n = sim->ps.n;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        if (!wall_like(&sim->ps, i)) continue;
        ry_adami_sums s = {0, 0, {0, 0, 0}};
        wall_sums_list(sim, i, &s);
        double vg[3];
        wall_set(sim, w, i, &s, vg);
        for (int d = 0; d < sim->dim; ++d) sim->ps.f[w->f_vg[d]][i] = vg[d];
    }
}

/* The walls' records after the wall pass (fpack_one for each wall), for uniform materials:
 * one pass per array, the other particles' entries kept (the ghost velocities are written by
 * the wall pass itself). */
static void fpack_walls_one_rho0(ry_sim *sim, const wcsph *w) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n, fs = w->fpack_stride;
    const uint8_t *restrict kind = ps->kind;
    const double *restrict rho = ps->f[RY_F_RHO], *restrict m = ps->f[RY_F_MASS];
    const double *restrict p = ps->f[RY_F_P];
    float *restrict fk = w->fpack;
    const double rho0 = w->rho0m[0];
#pragma omp parallel
    {
        float *restrict fdr = fk + FK_DRHO * fs, *restrict fpr = fk + FK_PRHO2 * fs;
        float *restrict fvol = fk + FK_VOL * fs, *restrict fmu = fk + FK_MU * fs;
        float *restrict fm = fk + FK_MASS * fs, *restrict fp = fk + FK_P * fs;
        const float visc = w->wall == WALL_NO_SLIP ? 1.0f : 0.0f;
#pragma omp for schedule(static) nowait
        for (size_t i = 0; i < n; ++i) {
            const int wall = kind[i] == RY_KIND_WALL;
            const double inv_rho = 1.0 / rho[i];
            fdr[i] = wall ? (float)(rho[i] - rho0) : fdr[i];
            fpr[i] = wall ? (float)(p[i] * inv_rho * inv_rho) : fpr[i];
            fvol[i] = wall ? (float)(m[i] * inv_rho) : fvol[i];
            fmu[i] = wall ? visc : fmu[i]; /* (FK_MU) */
            fm[i] = wall ? (float)m[i] : fm[i];
            fp[i] = wall ? (float)p[i] : fp[i];
        }
    }
}

/* The wall pass of the cell-range loop: the sums of wall particle i over the fluid among its
 * candidates, by the pair function of boundary/walls_adami2012.h in single precision from the
 * records of wc_prepare_pairs (whose wall entries are then rewritten), eight candidates at a
 * time as in the fluid pass (wcsph_cells.c). */
/* Candidate l of wall particle (xi, yi, zi) in the cell-range wall pass: its terms of the
 * sums, zero unless it is fluid within the support. (A function of its own so that its small
 * arrays are not privatised per lane by the SIMD loop that calls it.) */
static inline __attribute__((always_inline)) ry_adami_sumsf
wall_lane(const double *restrict x0, const double *restrict x1, const double *restrict x2,
          double xi, double yi, double zi, const float *restrict fk, size_t fs, size_t l,
          const float *g, float rho_ref, float rad2, float inv_h, const int dim,
          const ry_kernel_type kt) {
    const float dx[3] = {(float)(xi - x0[l]), (float)(yi - x1[l]),
                         dim > 2 ? (float)(zi - x2[l]) : 0.0f};
    float r2 = dx[0] * dx[0] + dx[1] * dx[1];
    if (dim > 2) r2 += dx[2] * dx[2];
    const float wq = ry_kshapef(kt, sqrtf(r2) * inv_h);
    const int on = (r2 < rad2) & (fk[FK_FLUID * fs + l] != 0.0f);
    const float wij = on ? wq : 0.0f;
    const float vf[3] = {fk[FK_U * fs + l], fk[FK_V * fs + l], dim > 2 ? fk[FK_W * fs + l] : 0.0f};
    ry_adami_sumsf t = {0.0f, 0.0f, {0.0f, 0.0f, 0.0f}};
    const float head = ry_adami_headf(g, dx, dim, rho_ref + fk[FK_DRHO * fs + l]);
    ry_adami_add_pressuref(&t, wij, fk[FK_P * fs + l], head);
    ry_adami_add_velocityf(&t, wij, vf, dim);
    return t;
}

static inline __attribute__((always_inline)) void
wall_sums_ranges(const ry_sim *sim, const wcsph *w, size_t i, const int dim,
                 const ry_kernel_type kt, ry_adami_sums *s) {
    const ry_kernel *k = &sim->kernel;
    const int nrange = dim > 2 ? 9 : 3;
    const uint32_t *restrict rg = w->rng + i * 2 * (size_t)nrange;
    const size_t fs = w->fpack_stride;
    const double *restrict x0 = sim->ps.f[RY_F_X], *restrict x1 = sim->ps.f[RY_F_Y];
    const double *restrict x2 = dim > 2 ? sim->ps.f[RY_F_Z] : x0;
    const float *restrict fk = w->fpack;
    const double xi = x0[i], yi = x1[i], zi = dim > 2 ? x2[i] : 0.0;
    const float rad2 = (float)(k->radius * k->radius), inv_h = (float)k->inv_h;
    const float g[3] = {(float)sim->gravity[0], (float)sim->gravity[1],
                        dim > 2 ? (float)sim->gravity[2] : 0.0f};
    const float rho_ref = (float)w->rho0m[0];
    float sw[8] = {0}, sp[8] = {0}, su[8] = {0}, sv[8] = {0}, sz[8] = {0};
    for (int r = 0; r < nrange; ++r) {
        for (size_t j = rg[2 * r]; j < rg[2 * r + 1]; j += 8) {
#pragma omp simd
            for (int q = 0; q < 8; ++q) {
                const ry_adami_sumsf t = wall_lane(x0, x1, x2, xi, yi, zi, fk, fs, j + (size_t)q, g,
                                                   rho_ref, rad2, inv_h, dim, kt);
                sw[q] += t.sw;
                sp[q] += t.sp;
                su[q] += t.sv[0];
                sv[q] += t.sv[1];
                if (dim > 2) sz[q] += t.sv[2];
            }
        }
    }
    /* The kernel's normalisation cancels in every ratio but is kept for sw > 0 semantics. */
    const double norm = k->norm;
    s->sw = norm * wc_lanes_sum(sw);
    s->sp = norm * wc_lanes_sum(sp);
    s->sv[0] = norm * wc_lanes_sum(su);
    s->sv[1] = norm * wc_lanes_sum(sv);
    s->sv[2] = norm * wc_lanes_sum(sz);
}

#define RY_WALL_RANGES_(DIM, KT)                                                                   \
    static void wall_ranges_##DIM##_##KT(ry_sim *sim, const wcsph *w) {                            \
        const size_t n = sim->ps.n;                                                                \
        _Pragma("omp parallel for schedule(static)") for (size_t i = 0; i < n; ++i) {              \
            if (!wall_like(&sim->ps, i)) continue;                                                 \
            ry_adami_sums s = {0, 0, {0, 0, 0}};                                                   \
            if (w->wet[i]) wall_sums_ranges(sim, w, i, DIM, KT, &s);                               \
            double vg[3];                                                                          \
            wall_set(sim, w, i, &s, vg);                                                           \
            for (int d = 0; d < DIM; ++d)                                                          \
                w->fpack[(FK_UG + d) * w->fpack_stride + i] = (float)vg[d];                        \
        }                                                                                          \
        /* The walls' records, once no thread reads them any more. */                              \
        if (wc_uniform_materials(sim, w)) {                                                        \
            fpack_walls_one_rho0(sim, w);                                                          \
            return;                                                                                \
        }                                                                                          \
        _Pragma("omp parallel for schedule(static)") for (size_t i = 0; i < n; ++i) {              \
            if (wall_like(&sim->ps, i)) fpack_one(sim, w, i, pack_mu(sim, w, i));                  \
        }                                                                                          \
    }
#define RY_WALL_RANGES_ALL_(KT) RY_WALL_RANGES_(2, KT) RY_WALL_RANGES_(3, KT)
RY_FOR_EACH_KERNEL_(RY_WALL_RANGES_ALL_)
#undef RY_WALL_RANGES_ALL_
#undef RY_WALL_RANGES_

void wc_fast_wall_pass(ry_sim *sim, const wcsph *w) {
#define RY_WALL_ROW_(KT) [KT] = {wall_ranges_2_##KT, wall_ranges_3_##KT},
    static void (*const drivers[RY_KERNEL_COUNT][2])(ry_sim *, const wcsph *) = {
        RY_FOR_EACH_KERNEL_(RY_WALL_ROW_)};
#undef RY_WALL_ROW_
    drivers[sim->kernel.type][sim->dim - 2](sim, w);
}
