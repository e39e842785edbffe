/* Internal to src/schemes/wcsph: the state of the scheme `wcsph` and what its files share: the
 * per-particle records of the two pair loops, the equation of state, the eight-lane vectors of
 * the cell-range loop and the small helpers that the passes inline. The scheme's equations are
 * listed in wcsph.c. */
#ifndef RYUSHI_WCSPH_INTERNAL_H
#define RYUSHI_WCSPH_INTERNAL_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#include "ryushi/sim.h"
#include "ryushi/surface_tension.h"
#include "pairs/pair_cache.h"
#include "physics/polymer_stress.h"
#include "physics/viscosity_morris1997.h"
#include "schemes/wcsph/wcsph_pair.h"

enum { DENS_CONTINUITY, DENS_SUMMATION };
enum { EOS_TAIT, EOS_LINEAR, EOS_IDEAL_GAS };
enum { DIFF_NONE, DIFF_MOLTENI, DIFF_FOURTAKAS };
enum { WALL_NO_SLIP, WALL_FREE_SLIP };

typedef struct wcsph {
    int density, eos, diffusion, wall, laminar, energy, variable_h;
    double mu_corr; /* laminar viscosity factor (scheme.viscosity_correction: lattice) */
    double c0, gamma, p_background, alpha, beta, delta;
    double vmax, amax, numax, hmax; /* from the last force evaluation */
    int have_forces;
    int f_vh[3], f_rhoh, f_eh, f_hh, f_vg[3];
    int f_vol, f_mu, f_isfluid, f_visc; /* per-evaluation scratch (transport velocity) */
    double *pack; /* PK_STRIDE doubles per particle, rebuilt each evaluation */
    size_t pack_cap;
    double *scratch; /* per thread: the in-range neighbours of one particle, field by field */
    size_t scratch_cap;
    int fast;     /* the cell-range pair loop in single precision (scheme.pair_loop) */
    int lean;     /* its plain form: no half-step fields (wc_lean) */
    double hdt;   /* lean: dt/2 of the step under way (0 outside a step), see wc_lean */
    float *fpack; /* its per-particle data: FK_COUNT arrays of fpack_stride floats, padded,
                     64-byte aligned (the positions are the particles' own, padded in place) */
    size_t fpack_stride, fpack_cap;
    uint32_t *rng; /* candidate ranges per particle: 3 (2D) or 9 (3D) pairs [a, b) */
    size_t rng_cap;
    int nrange;          /* ranges per particle */
    uint8_t *wet;        /* wall particles: fluid among the candidates */
    uint8_t *cell_fluid; /* per cell of the last search: whether it holds fluid */
    size_t cell_fluid_cap;
    long rng_gen;          /* sim->nl_generation they were made for */
    int repulse;           /* wall repulsion on */
    double rep_r0, rep_d;  /* its radius and strength */
    int tvf;               /* transport-velocity formulation */
    double p_tvf;          /* its background pressure p_b */
    int f_vt[3], f_abg[3]; /* transport velocity, background-pressure acceleration */
    double *Bm;            /* Tait coefficient per material */
    double *rho0m;         /* reference density per material */
    ry_sph_rheo rheo;      /* non-Newtonian materials (list loop only) */
    ry_pair_cache pc;      /* its kernel gradients */
    double *vol;           /* its particle volumes m / rho */
    size_t vol_cap;
    /* Free-surface tension (the surface_tension section; list loop only; docs/reference/wcsph.md)
     */
    ry_surface_tension st;
    double st_beta; /* CSF pressure form: surface where sum_j W < st_beta times the lattice's */
    double st_w0;   /* the lattice's kernel sum */
    ry_st_work stw; /* the Laplace jump P_i of the surface particles (0 elsewhere), their tag */
    double coll_r, coll_e; /* artificial repulsion: distance [m], restitution */
} wcsph;

/* The sum of eight single-precision lanes in double precision, halves added, then pairs: the
 * cell-range loop's sums (one per lane of eight candidates). */
static inline double wc_lanes_sum(const float *a) {
    const double s0 = (double)a[0] + (double)a[4], s1 = (double)a[1] + (double)a[5];
    const double s2 = (double)a[2] + (double)a[6], s3 = (double)a[3] + (double)a[7];
    return (s0 + s2) + (s1 + s3);
}

/* The constants of the pair term (wcsph_pair.h) for this run, in double precision. */
static inline wc_pair_k_d wc_pair_constants(const ry_sim *sim, const wcsph *w) {
    wc_pair_k_d K;
    K.h = sim->kernel.h;
    K.eta2 = ry_morris_eta2(sim->kernel.h);
    K.alpha = w->alpha;
    K.beta = w->beta;
    K.rep_d = w->rep_d;
    K.rep_r02 = w->rep_d > 0 ? w->rep_r0 * w->rep_r0 : 0.0;
    return K;
}

/* What a force evaluation returns: the largest squared acceleration and speed of the fluid. */
typedef struct force_out {
    double amax2, vmax2;
} force_out;

/* Fields of the cell-range loop (single precision, one array each; see fast_particle). */
enum {
    FK_U,
    FK_V,
    FK_W,
    FK_UG,
    FK_VG,
    FK_WG,
    FK_DRHO, /* rho - rho_ref */
    FK_PRHO2,
    FK_VOL,
    FK_MU, /* a fluid particle's dynamic viscosity; any other's viscous coupling (1 or 0: the
              pair term reads no other viscosity, a wall takes the fluid's) */
    FK_MASS,
    FK_FLUID, /* 1 fluid, 0 otherwise */
    FK_P,     /* pressure, for the wall pass */
    FK_COUNT,
    /* only with the energy equation, the ideal gas or variable h (wc_fk_count): */
    FK_CS = FK_COUNT, /* sound speed */
    FK_H,             /* smoothing length */
    FK_COUNT_ALL
};
/* Whether the cell-range loop's pair term takes the general form: per-particle sound speeds
 * and smoothing lengths, and the energy rate. */
static inline int wc_fast_general(const wcsph *w) {
    return w->energy || w->variable_h || w->eos == EOS_IDEAL_GAS;
}
/* The plain cell-range loop (no energy equation or variable h) keeps no half-step fields: its
 * first half kick leaves the half-step velocity and density v_{n+1/2}, rho_{n+1/2} in v and
 * rho, and the evaluation forms the predicted values v* = v_{n+1/2} + dt/2 a_n and rho* =
 * rho_{n+1/2} + dt/2 (drho/dt)_n where it reads them (the records, the pressure, the pair loop's
 * rho_i and largest speed) before the new rates overwrite a_n; the second half kick adds
 * dt/2 a_{n+1}. The same arithmetic as with the fields, 32 bytes per particle less. */
static inline int wc_lean(const wcsph *w) {
    return w->fast && !wc_fast_general(w);
}

/* The number of single-precision fields of the cell-range loop's records. */
static inline int wc_fk_count(const wcsph *w) {
    return wc_fast_general(w) ? FK_COUNT_ALL : FK_COUNT;
}
/* Per-particle record read by the neighbour-list pair loop: everything about j in two (2D, 16
 * doubles) or three (3D, 24 doubles) cache lines instead of one array per quantity. Vectors come
 * first, one component per dimension (position, velocity, velocity seen by viscous terms), then
 * scalars. */
enum { PK_RHO, PK_PRHO2, PK_VOL, PK_MU, PK_CS, PK_MASS, PK_FLUID, PK_VISC, PK_H, PK_NSCALAR };
#define PK_X(dim) 0
#define PK_U(dim) (dim)
#define PK_UG(dim) (2 * (dim))
#define PK_S(dim, s) (3 * (dim) + (s))
#define PK_STRIDE(dim) ((dim) == 2 ? 16 : 24)
_Static_assert(6 + PK_NSCALAR <= 16 && 9 + PK_NSCALAR <= 24, "pack record too small");

/* Fields of the scratch block: the in-range neighbours of one particle, one array per field,
 * so that the arithmetic runs as a SIMD loop over contiguous memory. */
enum {
    SC_DX,
    SC_DY,
    SC_DZ,
    SC_R2,
    SC_U,
    SC_V,
    SC_W,
    SC_UG,
    SC_VG,
    SC_WG,
    SC_RHO,
    SC_PRHO2,
    SC_VOL,
    SC_MU,
    SC_CS,
    SC_MASS,
    SC_FLUID,
    SC_VISC,
    SC_H,
    SC_COUNT
};

/* The equation of state: pressure from density (and, for the ideal gas, internal energy), its
 * inverse for the walls and the hydrostatic start, and the sound speed. */
static inline double eos_pressure(const wcsph *w, int mat, double rho, double e) {
    double rho0 = w->rho0m[mat];
    switch (w->eos) {
    case EOS_TAIT: {
        const double x = rho / rho0;
        double xg;
        if (w->gamma == 7.0) { /* x^7 without pow */
            const double x2 = x * x;
            xg = x2 * x2 * x2 * x;
        } else {
            xg = pow(x, w->gamma);
        }
        return w->Bm[mat] * (xg - 1.0) + w->p_background;
    }
    case EOS_LINEAR:
        return w->c0 * w->c0 * (rho - rho0) + w->p_background;
    default:
        return (w->gamma - 1.0) * rho * e;
    }
}

static inline double eos_density(const wcsph *w, int mat, double p) {
    double rho0 = w->rho0m[mat];
    double q = p - w->p_background;
    switch (w->eos) {
    case EOS_TAIT: {
        double s = 1.0 + q / w->Bm[mat];
        return rho0 * pow(s > 1e-3 ? s : 1e-3, 1.0 / w->gamma);
    }
    case EOS_LINEAR:
        return fmax(rho0 + q / (w->c0 * w->c0), 1e-3 * rho0);
    default:
        return rho0;
    }
}

static inline double sound_speed(const wcsph *w, double rho, double p) {
    if (w->eos == EOS_IDEAL_GAS) return sqrt(fmax(w->gamma * p / rho, 0.0));
    return w->c0;
}

static inline int is_periodic(const ry_sim *sim) {
    return sim->box.periodic[0] || sim->box.periodic[1] || sim->box.periodic[2];
}

/* Inlet buffers take their pressure from the fluid too (their velocity is prescribed); outlet
 * buffers keep the pressure set at the outlet. */
static inline int wall_like(const ry_particles *ps, size_t i) {
    return ps->kind[i] == RY_KIND_WALL || ps->kind[i] == RY_KIND_INLET;
}

/* mu_i = rho_i nu (laminar viscosity) and the viscous coupling of particle i: fluid, open-
 * boundary buffers, and no-slip walls (through their ghost velocity). */
static inline double pack_mu(const ry_sim *sim, const wcsph *w, size_t i) {
    if (!w->laminar) return 0.0;
    const double nu = w->rheo.on ? sim->ps.f[w->rheo.f_nu][i] /* from the shear rate */
                                 : sim->mat[sim->ps.material[i]].viscosity;
    return sim->ps.f[RY_F_RHO][i] * nu * w->mu_corr;
}
static inline double pack_visc(const ry_sim *sim, const wcsph *w, size_t i) {
    return sim->ps.kind[i] != RY_KIND_WALL || w->wall == WALL_NO_SLIP ? 1.0 : 0.0;
}

/* The single-precision record of particle i for the cell-range loop (mu_i and the viscous
 * coupling as computed by wc_prepare_pairs; the ghost velocity is the wall pass's). */
static inline void fpack_one(const ry_sim *sim, const wcsph *w, size_t i, double mui) {
    const ry_particles *ps = &sim->ps;
    const size_t fs = w->fpack_stride;
    float *restrict F = w->fpack + i;
    const double rhoi = ps->f[RY_F_RHO][i], inv_rho = 1.0 / rhoi, pi = ps->f[RY_F_P][i];
    const double mi = ps->f[RY_F_MASS][i];
    for (int d = 0; d < sim->dim; ++d) {
        F[(FK_U + d) * fs] = (float)ps->f[RY_F_VX + d][i];
    }
    F[FK_DRHO * fs] = (float)(rhoi - w->rho0m[0]);
    F[FK_PRHO2 * fs] = (float)(pi * inv_rho * inv_rho);
    F[FK_VOL * fs] = (float)(mi * inv_rho);
    const int fluid = ps->kind[i] == RY_KIND_FLUID || ps->kind[i] == RY_KIND_OUTLET;
    F[FK_MU * fs] = (float)(fluid ? mui : pack_visc(sim, w, i));
    F[FK_MASS * fs] = (float)mi;
    F[FK_FLUID * fs] = fluid ? 1.0f : 0.0f;
    F[FK_P * fs] = (float)pi;
}

/* The kernels the pair loops are compiled for, and a row of a driver table: [kernel][dim - 2]
 * [variant] -> PREFIX_DIM_KERNEL_VARIANT. */
#define RY_FOR_EACH_KERNEL_(X)                                                                     \
    X(RY_KERNEL_CUBIC)                                                                             \
    X(RY_KERNEL_QUINTIC)                                                                           \
    X(RY_KERNEL_WENDLAND_C2) X(RY_KERNEL_WENDLAND_C4) X(RY_KERNEL_LUCY) X(RY_KERNEL_GAUSSIAN)
#define RY_DRIVER_ROW_(P, KT)                                                                      \
    [KT] = {{P##_2_##KT##_0, P##_2_##KT##_1}, {P##_3_##KT##_0, P##_3_##KT##_1}}

/* wcsph_step.c: the scheme's buffers (ry_scheme_type.bytes) */
size_t wc_bytes(const void *state);

/* wcsph_walls.c: pressure, density and ghost velocity of the walls (Adami et al. 2012), from the
 * neighbour list or, for the cell-range loop, from the candidate ranges (then also the walls'
 * single-precision records). */
void wc_wall_pass(ry_sim *sim, const wcsph *w);
void wc_fast_wall_pass(ry_sim *sim, const wcsph *w);

/* wcsph_list.c: the per-particle records of the pair loops, and the neighbour-list pair loop. */
ry_status wc_prepare_pairs(ry_sim *sim, wcsph *w, ry_error *err);
ry_status wc_list_forces(ry_sim *sim, wcsph *w, force_out *res, ry_error *err);

/* wcsph_cells.c: the cell-range pair loop in single precision. */
int wc_fast_eligible(const ry_sim *sim, const wcsph *w, const char **why);
int wc_uniform_materials(const ry_sim *sim, const wcsph *w);
void wc_fpack_fluid(ry_sim *sim, const wcsph *w);
ry_status wc_fast_ranges(ry_sim *sim, wcsph *w, ry_error *err);
void wc_fast_forces(ry_sim *sim, const wcsph *w, force_out *res);

/* wcsph_tvf.c: the transport-velocity pair loop and density summation. */
void wc_tvf_forces(ry_sim *sim, const wcsph *w, force_out *res);
void wc_density_summation(ry_sim *sim, const wcsph *w);

/* wcsph_step.c: the time step and the leapfrog step. */
ry_status wc_dt(ry_sim *sim, void *state, double *dt, ry_error *err);
ry_status wc_step(ry_sim *sim, void *state, double dt, ry_error *err);

#endif
