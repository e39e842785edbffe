/* Weakly compressible SPH (seed 001, SPEC section 1).
 *
 *  momentum   dv_i/dt = -sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2 + Pi_ij) grad_i W_ij
 *                       + laminar viscosity (Morris et al. 1997) + g           (seed eq. 3.52)
 *  continuity d rho_i/dt = rho_i sum_j (m_j/rho_j) v_ij . grad_i W_ij          (seed eq. 3.26)
 *             (or density by summation rho_i = sum_j m_j W_ij)
 *  artificial viscosity Pi_ij (Monaghan 1992; seed eq. 3.50-3.51)
 *  density diffusion (delta-SPH): Molteni & Colagrossi (2009), optionally with the hydrostatic
 *             correction of Fourtakas et al. (2019)
 *  energy     de_i/dt = 1/2 sum_j m_j (p_i/rho_i^2 + p_j/rho_j^2 + Pi_ij) v_ij . grad_i W_ij
 *             (seed eq. 3.43), with the ideal-gas equation of state for compressible cases
 *  variable h dh_i/dt = -(h_i / (d rho_i)) d rho_i/dt (Benz 1990)
 *  walls      dummy particles with pressure extrapolated from the fluid, Adami, Hu & Adams
 *             (2012), J. Comput. Phys. 231: 7057, eq. 27-28; no-slip through the extrapolated
 *             ghost velocity 2 v_w - v~ (eq. 22-23), or free-slip.
 *  transport velocity (option, confined flows): Adami, Hu & Adams (2013), J. Comput. Phys.
 *             241: 292, eq. 8-13: particles move with v~ = v + dt (-p_b/m_i) sum_j (V_i^2 + V_j^2)
 *             grad W_ij, momentum with the inter-particle averaged pressure and viscosity and the
 *             extra stress A = rho v (v~ - v); density from the number density.
 *  wall repulsion (safety net): fluid particles that come closer than r0 = 0.75 dx to a wall
 *             particle (which only happens where the fluid is too sparse to build up wall
 *             pressure, e.g. a film sliding down a wall) are pushed back with the force of
 *             Monaghan (1994), D ((r0/r)^12 - (r0/r)^4) x_ij / r^2, D = 0.01 c0^2.
 *  time       kick-drift-kick leapfrog, second order, one force evaluation per step; forces
 *             are evaluated with the predicted velocity and density (v_n + dt a_n).
 *             dt = min(CFL h / (c0 + |v|max), 0.25 sqrt(h / |a|max), 0.125 h^2 / nu). */
#include <float.h>
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/guard_check.h"
#include "ryushi/sim.h"
#include "ryushi/surface_tension.h"
#include "pairs/pair_cache.h"
#include "physics/polymer_stress.h"
#include "schemes/wcsph/wcsph.h"
#include "ryushi/collisions.h"

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
    int fast;    /* the cell-range pair loop in single precision (scheme.pair_loop) */
    void *fpack; /* its per-particle data: positions (3 arrays of fpack_stride doubles), then
                    FK_COUNT arrays of fpack_stride floats; padded, 64-byte aligned */
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
    /* Free-surface tension (the surface_tension section; list loop only; docs/wcsph.md) */
    ry_surface_tension st;
    double st_beta; /* CSF pressure form: surface where sum_j W < st_beta times the lattice's */
    double st_w0;   /* the lattice's kernel sum */
    ry_st_work stw; /* the Laplace jump P_i of the surface particles (0 elsewhere), their tag */
    double coll_r, coll_e; /* artificial repulsion: distance [m], restitution */
} wcsph;

/* Kinds that move under the fluid equations. */
static const int MOBILE[RY_KIND_COUNT] = {[RY_KIND_FLUID] = 1, [RY_KIND_OUTLET] = 1};

/* Density in hydrostatic equilibrium under gravity, free surface half a spacing above the
 * highest fluid particle: rho = rho0 (1 + rho0 g (H - z) / B)^(1/gamma) for Tait. */
static ry_status hydrostatic_init(ry_sim *sim, const wcsph *w, ry_error *err);

static const char *const density_names[] = {"continuity", "summation", NULL};
static const char *const eos_names[] = {"tait", "linear", "ideal_gas", NULL};
static const char *const diffusion_names[] = {"none", "molteni", "fourtakas", NULL};
static const char *const wall_names[] = {"no_slip", "free_slip", NULL};
enum { LOOP_AUTO, LOOP_CELLS, LOOP_LIST };
static const char *const loop_names[] = {"auto", "cells", "list", NULL};
static const char *const viscosity_correction_names[] = {"none", "lattice", NULL};
static int fast_eligible(const ry_sim *sim, const wcsph *w, const char **why);

static ry_status wcsph_init(ry_sim *sim, ry_case *c, void **state, ry_error *err) {
    wcsph *w = calloc(1, sizeof *w);
    RY_CHECK(err, w != NULL, RY_ERR_NOMEM, "out of memory");
    *state = w;
    double seven = 7.0, zero = 0.0, alpha = 0.0, delta = 0.1;
    int no = 0, yes = 1;
    RY_TRY(ry_case_choice(c, "scheme.density", "continuity", density_names, &w->density, err));
    RY_TRY(ry_case_choice(c, "scheme.eos", "tait", eos_names, &w->eos, err));
    RY_TRY(ry_case_positive(c, "scheme.sound_speed", NULL, &w->c0, err));
    RY_TRY(ry_case_double(c, "scheme.gamma", &seven, 1.0, 10.0, &w->gamma, err));
    RY_TRY(ry_case_double(c, "scheme.background_pressure", &zero, 0.0, INFINITY, &w->p_background,
                          err));
    RY_TRY(
        ry_case_double(c, "scheme.artificial_viscosity.alpha", &alpha, 0.0, 10.0, &w->alpha, err));
    RY_TRY(ry_case_double(c, "scheme.artificial_viscosity.beta", &zero, 0.0, 10.0, &w->beta, err));
    RY_TRY(ry_case_bool(c, "scheme.laminar_viscosity", &yes, &w->laminar, err));
    RY_TRY(
        ry_case_choice(c, "scheme.density_diffusion", "none", diffusion_names, &w->diffusion, err));
    RY_TRY(ry_case_double(c, "scheme.delta", &delta, 0.0, 1.0, &w->delta, err));
    RY_TRY(ry_case_bool(c, "scheme.energy", &no, &w->energy, err));
    RY_TRY(ry_case_bool(c, "scheme.variable_h", &no, &w->variable_h, err));
    RY_TRY(ry_case_choice(c, "scheme.wall", "no_slip", wall_names, &w->wall, err));
    RY_TRY(ry_case_bool(c, "scheme.transport_velocity", &no, &w->tvf, err));
    int corr;
    RY_TRY(ry_case_choice(c, "scheme.viscosity_correction", "none", viscosity_correction_names,
                          &corr, err));
    /* The lattice's value of the Morris term for a unit Laplacian (Wendland C2, h = 1.4 dx, 2D:
     * 0.979); the transport-velocity form has no 0.01 h^2 (docs/wcsph.md). */
    const double dxd = sim->dim > 2 ? sim->dx * sim->dx * sim->dx : sim->dx * sim->dx;
    const double eta2 = w->tvf ? 0.0 : 0.01 * sim->kernel.h * sim->kernel.h;
    w->mu_corr =
        corr ? 1.0 / ry_lattice_viscous_factor(&sim->kernel, sim->dim, sim->dx, dxd, eta2, 0) : 1.0;
    RY_TRY(ry_case_bool(c, "scheme.wall_repulsion", &yes, &w->repulse, err));
    double r0 = 0.75;
    RY_TRY(ry_case_double(c, "scheme.wall_repulsion_radius", &r0, 0.1, 1.0, &w->rep_r0, err));
    w->rep_r0 *= sim->dx;
    w->rep_d = w->repulse ? 0.01 * w->c0 * w->c0 : 0.0;
    char where[256];
    if (w->tvf) {
        RY_CHECK(err, w->density == DENS_SUMMATION && !w->variable_h && !w->energy, RY_ERR_INPUT,
                 "%s: key 'scheme.transport_velocity': needs scheme.density: summation (and no "
                 "variable_h or energy)",
                 ry_case_where(c, "scheme.transport_velocity", where, sizeof where));
        double pb_def = 0;
        for (int m = 0; m < sim->nmat; ++m)
            pb_def = fmax(pb_def, sim->mat[m].density * w->c0 * w->c0);
        RY_TRY(ry_case_positive(c, "scheme.transport_pressure", &pb_def, &w->p_tvf, err));
    }
    if (w->tvf)
        RY_CHECK(err, sim->nopen == 0, RY_ERR_INPUT,
                 "%s: key 'scheme.transport_velocity': open boundaries need it off",
                 ry_case_where(c, "scheme.transport_velocity", where, sizeof where));
    for (int q = 0; q < sim->nopen; ++q) {
        char k[64];
        snprintf(k, sizeof k, "open_boundaries[%d].type", q);
        /* the buffer moves as a plug: in the no-slip channel (cases/channel_inflow.yaml) it
         * tore the weakly compressible fluid off the walls, unstable at 0.16 s */
        RY_CHECK(err, !sim->open[q].rate, RY_ERR_INPUT,
                 "%s: key '%s': scheme wcsph takes no rate outlets (flow_rate or velocity); use "
                 "an outlet at a pressure, or scheme iisph",
                 ry_case_where(c, k, where, sizeof where), k);
    }
    if (w->variable_h)
        RY_CHECK(err, w->density == DENS_CONTINUITY, RY_ERR_INPUT,
                 "%s: key 'scheme.variable_h': needs scheme.density: continuity",
                 ry_case_where(c, "scheme.variable_h", where, sizeof where));
    RY_TRY(ry_sph_rheo_init(&w->rheo, sim, err));
    if (w->rheo.on)
        RY_CHECK(err, w->laminar, RY_ERR_INPUT,
                 "%s: key 'scheme.laminar_viscosity': a non-Newtonian material needs it true",
                 ry_case_where(c, "scheme.laminar_viscosity", where, sizeof where));
    if (w->rheo.on)
        RY_CHECK(err, !w->variable_h, RY_ERR_INPUT,
                 "%s: key 'scheme.variable_h': not available with a non-Newtonian material",
                 ry_case_where(c, "scheme.variable_h", where, sizeof where));
    RY_TRY(ry_st_read_sph(&w->st, c, sim->dim, sim->dx, &w->st_beta, &w->coll_r, &w->coll_e, err));
    w->st_w0 = ry_lattice_number_density(&sim->kernel, sim->dim, sim->dx);
    int loop;
    RY_TRY(ry_case_choice(c, "scheme.pair_loop", "auto", loop_names, &loop, err));
    const char *why;
    w->fast = loop != LOOP_LIST && fast_eligible(sim, w, &why);
    if (loop == LOOP_CELLS)
        RY_CHECK(err, w->fast, RY_ERR_INPUT, "%s: key 'scheme.pair_loop': 'cells' needs %s",
                 ry_case_where(c, "scheme.pair_loop", where, sizeof where), why);
    sim->sort_always = w->fast;
    sim->cells_only = w->fast && w->density == DENS_CONTINUITY;
    /* Default Verlet skin of the cell-range loop: its candidates grow with the square (cube)
     * of support + skin, while a search (sort, reorder, candidate ranges) costs about two
     * steps' worth of element-wise passes. Over whole dam breaks on one thread, 10 % in 2D
     * was about 10 % faster than 5 % (the seed case at 40x80, 0.6 s: a search every second
     * step late in the run at 5 %), while in 3D 5 % was about 20 % faster than 10 %. */
    if (w->fast) sim->nl_skin = sim->dim > 2 ? 0.05 : 0.1;
    w->rng_gen = -1;
    if (w->eos == EOS_IDEAL_GAS)
        RY_CHECK(err, w->energy, RY_ERR_INPUT,
                 "%s: key 'scheme.eos': ideal_gas needs scheme.energy: true",
                 ry_case_where(c, "scheme.eos", where, sizeof where));

    ry_particles *ps = &sim->ps;
    static const char *const vh[3] = {"vhalf_x", "vhalf_y", "vhalf_z"};
    static const char *const vg[3] = {"vwall_x", "vwall_y", "vwall_z"};
    for (int d = 0; d < 3; ++d) {
        RY_TRY(ry_particles_add_field(ps, vh[d], "m/s", d, RY_FIELD_STATE, &w->f_vh[d], err));
        RY_TRY(ry_particles_add_field(ps, vg[d], "m/s", d, 0, &w->f_vg[d], err));
    }
    if (w->tvf) {
        static const char *const vt[3] = {"vtransport_x", "vtransport_y", "vtransport_z"};
        static const char *const ab[3] = {"abg_x", "abg_y", "abg_z"};
        for (int d = 0; d < 3; ++d) {
            RY_TRY(ry_particles_add_field(ps, vt[d], "m/s", d, RY_FIELD_STATE, &w->f_vt[d], err));
            RY_TRY(
                ry_particles_add_field(ps, ab[d], "m/s^2", d, RY_FIELD_STATE, &w->f_abg[d], err));
        }
    }
    RY_TRY(
        ry_particles_add_field(ps, "density_half", "kg/m^3", -1, RY_FIELD_STATE, &w->f_rhoh, err));
    RY_TRY(ry_particles_add_field(ps, "energy_half", "J/kg", -1, RY_FIELD_STATE, &w->f_eh, err));
    RY_TRY(ry_particles_add_field(ps, "h_half", "m", -1, RY_FIELD_STATE, &w->f_hh, err));
    if (w->tvf) { /* per-evaluation quantities the transport-velocity pair loop reads */
        RY_TRY(ry_particles_add_field(ps, "volume", "m^3", -1, 0, &w->f_vol, err));
        RY_TRY(ry_particles_add_field(ps, "dynamic_viscosity", "Pa s", -1, 0, &w->f_mu, err));
        RY_TRY(ry_particles_add_field(ps, "is_fluid", "1", -1, 0, &w->f_isfluid, err));
        RY_TRY(ry_particles_add_field(ps, "viscous_coupling", "1", -1, 0, &w->f_visc, err));
    }

    w->Bm = calloc((size_t)sim->nmat, sizeof *w->Bm);
    w->rho0m = calloc((size_t)sim->nmat, sizeof *w->rho0m);
    RY_CHECK(err, w->Bm && w->rho0m, RY_ERR_NOMEM, "out of memory");
    for (int m = 0; m < sim->nmat; ++m) {
        w->rho0m[m] = sim->mat[m].density;
        w->Bm[m] = w->c0 * w->c0 * w->rho0m[m] / w->gamma;
    }
    if (w->tvf)
        for (size_t i = 0; i < ps->n; ++i)
            for (int d = 0; d < sim->dim; ++d) ps->f[w->f_vt[d]][i] = ps->f[RY_F_VX + d][i];
    /* Initial pressure from the density (zero for a fluid at rest at rho0); energy for gases. */
    for (size_t i = 0; i < ps->n; ++i) {
        ps->f[RY_F_E][i] = 0;
        ps->f[RY_F_P][i] = 0;
    }
    int hydro;
    RY_TRY(ry_case_bool(c, "scheme.hydrostatic_init", &no, &hydro, err));
    if (hydro) RY_TRY(hydrostatic_init(sim, w, err));
    /* A sound run stays far below the sound speed and within a few per cent of the reference
     * density; beyond these it has failed (checked every step; case section `guard`). */
    if (w->eos != EOS_IDEAL_GAS) {
        sim->guard.max_speed = w->c0;
        sim->guard.rho_min = 0.5;
        sim->guard.rho_max = 2.0;
    }
    if (w->eos == EOS_IDEAL_GAS) {
        double e0;
        RY_TRY(ry_case_positive(c, "scheme.initial_energy", NULL, &e0, err));
        for (size_t i = 0; i < ps->n; ++i) ps->f[RY_F_E][i] = e0;
    }
    return RY_OK;
}

static void wcsph_free(void *state) {
    wcsph *w = state;
    if (!w) return;
    free(w->Bm);
    free(w->rho0m);
    free(w->pack);
    free(w->scratch);
    free(w->fpack);
    free(w->rng);
    free(w->wet);
    free(w->cell_fluid);
    ry_sph_rheo_free(&w->rheo);
    ry_pair_cache_free(&w->pc);
    ry_st_work_free(&w->stw);
    free(w->vol);
    free(w);
}

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

static ry_status hydrostatic_init(ry_sim *sim, const wcsph *w, ry_error *err) {
    ry_particles *ps = &sim->ps;
    double *p = malloc((ps->n ? ps->n : 1) * sizeof *p);
    RY_CHECK(err, p != NULL, RY_ERR_NOMEM, "out of memory");
    ry_hydrostatic_pressure(sim, p);
    for (size_t i = 0; i < ps->n; ++i)
        if (ps->kind[i] == RY_KIND_FLUID)
            ps->f[RY_F_RHO][i] = eos_density(w, ps->material[i], p[i] + w->p_background);
    free(p);
    return RY_OK;
}

static int is_periodic(const ry_sim *sim) {
    return sim->box.periodic[0] || sim->box.periodic[1] || sim->box.periodic[2];
}

/* The kernel at a smoothing length other than the reference one (variable h). */
static inline double dwdr_h(const ry_kernel *k, double r, double h) {
    double s = k->h / h, sd = s * s;
    if (k->dim == 3) sd *= s;
    return k->dnorm * sd * s * ry_kernel_dshape(k->type, r / h);
}

/* Density by summation for fluid particles (walls keep their extrapolated density):
 * rho_i = sum_j m_j W_ij, or with the transport velocity rho_i = m_i sum_j W_ij (Adami et al.
 * 2013). (Variable h needs the continuity equation, so h is the reference one here.) dim, the
 * kernel and `periodic` are literals at each call site, as for the force loops. */
static inline __attribute__((always_inline)) void
density_particle(const ry_sim *sim, const wcsph *w, size_t i, const int dim,
                 const ry_kernel_type kt, const int periodic) {
    const ry_particles *ps = &sim->ps;
    if (ps->kind[i] != RY_KIND_FLUID) return;
    const ry_kernel *k = &sim->kernel;
    const double *restrict m = ps->f[RY_F_MASS];
    const double *restrict x0 = ps->f[RY_F_X], *restrict x1 = ps->f[RY_F_Y];
    const double *restrict x2 = dim > 2 ? ps->f[RY_F_Z] : x0;
    const size_t q1 = sim->nl.offset[i + 1];
    const uint32_t *restrict nb = sim->nl.j;
    const double rad2 = sim->nl_radius * sim->nl_radius, inv_h = k->inv_h;
    const double xi = x0[i], yi = x1[i], zi = dim > 2 ? x2[i] : 0.0;
    const int numden = w->tvf;
    double s = 0.0;
    for (size_t q = sim->nl.offset[i]; q < q1; ++q) {
        const uint32_t j = nb[q];
        double dx[3] = {xi - x0[j], yi - x1[j], dim > 2 ? zi - x2[j] : 0.0};
        if (periodic) ry_box_min_image(&sim->box, dx);
        const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
        const double wq = r2 < rad2 ? ry_kernel_shape(kt, sqrt(r2) * inv_h) : 0.0;
        s += (numden ? 1.0 : m[j]) * wq;
    }
    ps->f[RY_F_RHO][i] =
        m[i] * k->norm * ry_kernel_shape(kt, 0.0) + (numden ? m[i] : 1.0) * k->norm * s;
}

typedef void (*density_driver)(ry_sim *sim, const wcsph *w);
#define RY_DENSITY_DRIVER_(DIM, KT, PER)                                                           \
    static void density_##DIM##_##KT##_##PER(ry_sim *sim, const wcsph *w) {                        \
        const size_t n = sim->ps.n;                                                                \
        _Pragma("omp parallel for schedule(static)") for (size_t i = 0; i < n; ++i)                \
            density_particle(sim, w, i, DIM, KT, PER);                                             \
    }

/* Wall particles: pressure, density and ghost velocity extrapolated from the fluid (Adami et
 * al. 2012, eq. 22-23 and 27-28). The sums of wall particle i over its fluid neighbours j, from
 * the list (rows) or from the candidate ranges of the cell-range loop. */
typedef struct wall_sums {
    double sw, sp, srx, sv[3];
} wall_sums;

static inline __attribute__((always_inline)) void wall_sums_list(const ry_sim *sim, size_t i,
                                                                 wall_sums *s) {
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
        double wij = ry_kernel_w(k, sqrt(r2));
        double gr = 0;
        for (int d = 0; d < dim; ++d) gr += g[d] * dx[d];
        s->sw += wij;
        s->sp += p[j] * wij;
        s->srx += rho[j] * gr * wij;
        for (int d = 0; d < dim; ++d) s->sv[d] += ps->f[RY_F_VX + d][j] * wij;
    }
}

/* Pressure, density and ghost velocity of wall (and inlet) particle i from its sums. */
static inline void wall_set(ry_sim *sim, const wcsph *w, size_t i, const wall_sums *s) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim, inlet = ps->kind[i] == RY_KIND_INLET;
    const int mat = ps->material[i];
    if (s->sw > 0) {
        const double pw = (s->sp + s->srx) / s->sw;
        ps->f[RY_F_P][i] = pw;
        ps->f[RY_F_RHO][i] = eos_density(w, mat, pw);
        for (int d = 0; d < dim; ++d)
            ps->f[w->f_vg[d]][i] =
                inlet ? ps->f[RY_F_VX + d][i] : 2.0 * ps->f[RY_F_VX + d][i] - s->sv[d] / s->sw;
    } else {
        ps->f[RY_F_P][i] = w->p_background;
        ps->f[RY_F_RHO][i] = w->rho0m[mat];
        for (int d = 0; d < dim; ++d) ps->f[w->f_vg[d]][i] = ps->f[RY_F_VX + d][i];
    }
}

/* Inlet buffers take their pressure from the fluid too (their velocity is prescribed); outlet
 * buffers keep the pressure set at the outlet. */
static inline int wall_like(const ry_particles *ps, size_t i) {
    return ps->kind[i] == RY_KIND_WALL || ps->kind[i] == RY_KIND_INLET;
}

static void wall_pass(ry_sim *sim, const wcsph *w) {
    const size_t n = sim->ps.n;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        if (!wall_like(&sim->ps, i)) continue;
        wall_sums s = {0, 0, 0, {0, 0, 0}};
        wall_sums_list(sim, i, &s);
        wall_set(sim, w, i, &s);
    }
}

typedef struct force_out {
    double amax2, vmax2;
} force_out;

/* Per-particle record read by the pair loop: everything about j in two (2D, 16 doubles) or
 * three (3D, 24 doubles) cache lines instead of one array per quantity. Vectors come first, one
 * component per dimension (position, velocity, velocity seen by viscous terms), then scalars. */
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
    FK_MU,
    FK_MASS,
    FK_FLUID,
    FK_VISC,
    FK_P, /* pressure, for the wall pass */
    FK_COUNT
};
enum { PK_RHO, PK_PRHO2, PK_VOL, PK_MU, PK_CS, PK_MASS, PK_FLUID, PK_VISC, PK_H, PK_NSCALAR };
#define PK_X(dim) 0
#define PK_U(dim) (dim)
#define PK_UG(dim) (2 * (dim))
#define PK_S(dim, s) (3 * (dim) + (s))
#define PK_STRIDE(dim) ((dim) == 2 ? 16 : 24)
_Static_assert(6 + PK_NSCALAR <= 16 && 9 + PK_NSCALAR <= 24, "pack record too small");

/* Monaghan (1994) wall repulsion per unit mass, divided by r^2 (multiplies x_ij), for a pair
 * with `on` set (a wall particle within r0); written without branches for vector loops. */
static inline double wall_repulsion(double r2, int on, double r02, double D) {
    const double q2 = on ? r02 / r2 : 1.0, rr = on ? r2 : 1.0;
    const double q4 = q2 * q2, q12 = q4 * q4 * q4;
    return D * (q12 - q4) / rr;
}

/* The single-precision record of particle i for the cell-range loop (mu_i and the viscous
 * coupling as computed by prepare_pairs). */
static inline void fpack_one(const ry_sim *sim, const wcsph *w, size_t i, double mui, double visi) {
    const ry_particles *ps = &sim->ps;
    const size_t fs = w->fpack_stride;
    double *restrict XP = (double *)w->fpack + i;
    float *restrict F = (float *)((double *)w->fpack + 3 * fs) + i;
    const double rhoi = ps->f[RY_F_RHO][i], inv_rho = 1.0 / rhoi, pi = ps->f[RY_F_P][i];
    const double mi = ps->f[RY_F_MASS][i];
    for (int d = 0; d < sim->dim; ++d) {
        XP[d * fs] = ps->f[RY_F_X + d][i];
        F[(FK_U + d) * fs] = (float)ps->f[RY_F_VX + d][i];
        F[(FK_UG + d) * fs] = (float)ps->f[w->f_vg[d]][i];
    }
    F[FK_DRHO * fs] = (float)(rhoi - w->rho0m[0]);
    F[FK_PRHO2 * fs] = (float)(pi * inv_rho * inv_rho);
    F[FK_VOL * fs] = (float)(mi * inv_rho);
    F[FK_MU * fs] = (float)mui;
    F[FK_MASS * fs] = (float)mi;
    F[FK_FLUID * fs] = ps->kind[i] == RY_KIND_FLUID || ps->kind[i] == RY_KIND_OUTLET ? 1.0f : 0.0f;
    F[FK_VISC * fs] = (float)visi;
    F[FK_P * fs] = (float)pi;
}

/* The pressure of the fluid (equation of state) and the records of the particles other than
 * walls (the wall pass writes the walls'), in one loop over contiguous arrays. */
static void fpack_fluid_one_rho0(ry_sim *sim, const wcsph *w);
static int uniform_materials(const ry_sim *sim, const wcsph *w);

/* Whether every material has the density and viscosity of the first, and the equation of
 * state is Tait or linear (the cell-range loop's single-material passes). */
static int uniform_materials(const ry_sim *sim, const wcsph *w) {
    int same = w->eos != EOS_IDEAL_GAS;
    for (int m = 1; m < sim->nmat; ++m)
        same &= sim->mat[m].density == sim->mat[0].density &&
                sim->mat[m].viscosity == sim->mat[0].viscosity;
    return same;
}

static void fpack_fluid(ry_sim *sim, const wcsph *w) {
    if (uniform_materials(sim, w)) {
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
    double *restrict xp = w->fpack;
    float *restrict fk = (float *)(xp + 3 * fs);
    const double *x[3], *v[3];
    ry_particles_coords(ps, x);
    for (int d = 0; d < 3; ++d) v[d] = ps->f[RY_F_VX + (d < dim ? d : 0)];
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        for (int d = 0; d < dim; ++d) {
            xp[(size_t)d * fs + i] = x[d][i];
            /* walls: rewritten by the wall pass */
            fk[(FK_U + d) * fs + i] = fk[(FK_UG + d) * fs + i] = (float)v[d][i];
        }
        if (kind[i] == RY_KIND_WALL || kind[i] == RY_KIND_INLET) {
            /* Until the wall pass: inert, as the wall pass reads every candidate (masked). */
            for (int k = FK_DRHO; k < FK_COUNT; ++k) fk[(size_t)k * fs + i] = 0.0f;
            continue;
        }
        if (kind[i] == RY_KIND_FLUID) p[i] = eos_pressure(w, matl[i], rho[i], e[i]);
        const double inv_rho = 1.0 / rho[i];
        fk[FK_DRHO * fs + i] = (float)(rho[i] - rho_ref);
        fk[FK_PRHO2 * fs + i] = (float)(p[i] * inv_rho * inv_rho);
        fk[FK_VOL * fs + i] = (float)(m[i] * inv_rho);
        fk[FK_MU * fs + i] = laminar ? (float)(rho[i] * mat[matl[i]].viscosity) : 0.0f;
        fk[FK_MASS * fs + i] = (float)m[i];
        fk[FK_FLUID * fs + i] = kind[i] == RY_KIND_FLUID || kind[i] == RY_KIND_OUTLET;
        fk[FK_VISC * fs + i] = 1.0f; /* not a wall */
        fk[FK_P * fs + i] = (float)p[i];
    }
}

/* fpack_fluid for one reference density and the Tait or linear equation of state: one pass
 * per array, so that each vectorises; walls get inert records until the wall pass. */
static void fpack_fluid_one_rho0(ry_sim *sim, const wcsph *w) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n, fs = w->fpack_stride;
    const int dim = sim->dim;
    const uint8_t *restrict kind = ps->kind;
    const double *restrict rho = ps->f[RY_F_RHO], *restrict m = ps->f[RY_F_MASS];
    double *restrict p = ps->f[RY_F_P];
    double *restrict xp = w->fpack;
    float *restrict fk = (float *)(xp + 3 * fs);
    const double rho0 = w->rho0m[0], B = w->Bm[0], pb = w->p_background;
    const double c02 = w->c0 * w->c0;
    const int tait7 = w->eos == EOS_TAIT && w->gamma == 7.0, linear = w->eos == EOS_LINEAR;
    const double nu = w->laminar ? sim->mat[0].viscosity : 0.0;
#pragma omp parallel
    {
        for (int d = 0; d < dim; ++d) {
            const double *restrict x = ps->f[RY_F_X + d], *restrict v = ps->f[RY_F_VX + d];
            double *restrict xd = xp + (size_t)d * fs;
            float *restrict u = fk + (FK_U + d) * fs, *restrict ug = fk + (FK_UG + d) * fs;
#pragma omp for schedule(static) nowait
            for (size_t i = 0; i < n; ++i) {
                xd[i] = x[i];
                u[i] = ug[i] = (float)v[i]; /* walls: rewritten by the wall pass */
            }
        }
        if (tait7 || linear) {
#pragma omp for schedule(static) nowait
            for (size_t i = 0; i < n; ++i) {
                const double q = rho[i] / rho0, q2 = q * q;
                const double pt =
                    tait7 ? B * (q2 * q2 * q2 * q - 1.0) + pb : c02 * (rho[i] - rho0) + pb;
                p[i] = kind[i] == RY_KIND_FLUID ? pt : p[i];
            }
        } else {
#pragma omp for schedule(static) nowait
            for (size_t i = 0; i < n; ++i)
                if (kind[i] == RY_KIND_FLUID) p[i] = eos_pressure(w, 0, rho[i], 0.0);
        }
        float *restrict fdr = fk + FK_DRHO * fs, *restrict fpr = fk + FK_PRHO2 * fs;
        float *restrict fvol = fk + FK_VOL * fs, *restrict fmu = fk + FK_MU * fs;
        float *restrict fm = fk + FK_MASS * fs, *restrict ffl = fk + FK_FLUID * fs;
        float *restrict fvi = fk + FK_VISC * fs, *restrict fp = fk + FK_P * fs;
#pragma omp for schedule(static) nowait
        for (size_t i = 0; i < n; ++i) {
            /* Walls stay inert until the wall pass (it reads every candidate, masked). */
            const float on = kind[i] == RY_KIND_WALL ? 0.0f : 1.0f;
            const double inv_rho = 1.0 / rho[i];
            fdr[i] = on * (float)(rho[i] - rho0);
            fpr[i] = on * (float)(p[i] * inv_rho * inv_rho);
            fvol[i] = on * (float)(m[i] * inv_rho);
            fmu[i] = on * (float)(rho[i] * nu);
            fm[i] = on * (float)m[i];
            ffl[i] = kind[i] == RY_KIND_FLUID ? 1.0f : 0.0f;
            fvi[i] = on;
            fp[i] = on * (float)p[i];
        }
    }
}

/* The walls' records after the wall pass (fpack_one for each wall), for uniform materials:
 * one pass per array, the other particles' entries kept. */
static void fpack_walls_one_rho0(ry_sim *sim, const wcsph *w) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n, fs = w->fpack_stride;
    const int dim = sim->dim;
    const uint8_t *restrict kind = ps->kind;
    const double *restrict rho = ps->f[RY_F_RHO], *restrict m = ps->f[RY_F_MASS];
    const double *restrict p = ps->f[RY_F_P];
    float *restrict fk = (float *)((double *)w->fpack + 3 * fs);
    const double rho0 = w->rho0m[0], nu = w->laminar ? sim->mat[0].viscosity : 0.0;
    const float visc = w->wall == WALL_NO_SLIP ? 1.0f : 0.0f;
#pragma omp parallel
    {
        for (int d = 0; d < dim; ++d) {
            const double *restrict vg = ps->f[w->f_vg[d]];
            float *restrict ug = fk + (FK_UG + d) * fs;
#pragma omp for schedule(static) nowait
            for (size_t i = 0; i < n; ++i) ug[i] = kind[i] == RY_KIND_WALL ? (float)vg[i] : ug[i];
        }
        float *restrict fdr = fk + FK_DRHO * fs, *restrict fpr = fk + FK_PRHO2 * fs;
        float *restrict fvol = fk + FK_VOL * fs, *restrict fmu = fk + FK_MU * fs;
        float *restrict fm = fk + FK_MASS * fs, *restrict fvi = fk + FK_VISC * fs;
        float *restrict fp = fk + FK_P * fs;
#pragma omp for schedule(static) nowait
        for (size_t i = 0; i < n; ++i) {
            const int wall = kind[i] == RY_KIND_WALL;
            const double inv_rho = 1.0 / rho[i];
            fdr[i] = wall ? (float)(rho[i] - rho0) : fdr[i];
            fpr[i] = wall ? (float)(p[i] * inv_rho * inv_rho) : fpr[i];
            fvol[i] = wall ? (float)(m[i] * inv_rho) : fvol[i];
            fmu[i] = wall ? (float)(rho[i] * nu) : fmu[i];
            fm[i] = wall ? (float)m[i] : fm[i];
            fvi[i] = wall ? visc : fvi[i];
            fp[i] = wall ? (float)p[i] : fp[i];
        }
    }
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

/* Per-particle quantities the pair loop reads (computed once per evaluation, so that the pair
 * loop has no divisions by rho and no branches on the kind of j). */
static ry_status prepare_pairs(ry_sim *sim, wcsph *w, ry_error *err) {
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
            /* Positions (3 x fs doubles) then the FK_COUNT float fields, 64-byte aligned. */
            free(w->fpack);
            w->fpack = aligned_alloc(64, fs * (3 * sizeof(double) + FK_COUNT * sizeof(float)));
            w->fpack_cap = w->fpack ? fs : 0;
            RY_CHECK(err, w->fpack != NULL, RY_ERR_NOMEM, "out of memory (%zu particles)", n);
        }
        w->fpack_stride = fs;
        /* Padding: far away and inert. */
        double *xp = w->fpack;
        float *fk = (float *)(xp + 3 * fs);
        for (int d = 0; d < 3; ++d)
            for (size_t i = n; i < fs; ++i) xp[d * fs + i] = 1e10;
        for (int k = 0; k < FK_COUNT; ++k)
            for (size_t i = n; i < fs; ++i) fk[k * fs + i] = 0.0f;
        fpack_fluid(sim, w);
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
        if (w->fast) {
            fpack_one(sim, w, i, mui, visi);
            continue;
        }
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
        S[PK_H] = hh[i];
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
    double h0, eta2, inv_h0, dnorm_h, rad2, g[3], diff, alpha, beta, inv_c02, rep_d, rep_r02;
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
    c->eta2 = 0.01 * k->h * k->h;
    c->inv_h0 = 1.0 / k->h;
    c->dnorm_h = k->dnorm / k->h; /* (dW/dr) / r = dnorm_h f'(q)/q */
    c->rad2 = sim->nl_radius * sim->nl_radius;
    c->cont = w->density == DENS_CONTINUITY;
    c->varh = w->variable_h;
    c->energy = w->energy;
    c->diff = w->diffusion != DIFF_NONE ? 2.0 * w->delta * k->h * w->c0 : 0.0;
    c->fourtakas = w->diffusion == DIFF_FOURTAKAS;
    c->alpha = w->alpha;
    c->beta = w->beta;
    c->periodic = sim->box.periodic[0] || sim->box.periodic[1] || sim->box.periodic[2];
    c->inv_c02 = 1.0 / (w->c0 * w->c0);
    c->rep_d = w->rep_d;
    c->rep_r02 = w->rep_d > 0 ? w->rep_r0 * w->rep_r0 : 0.0;
    c->len = (sim->nl.max_row + 8) & ~(size_t)7; /* rounded up, at least 8 */
}

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

    /* Phase 2: the pair terms. */
    const double h0 = c->h0, eta2 = c->eta2, inv_h0 = c->inv_h0, dnorm_h = c->dnorm_h;
    const double alpha = c->alpha, beta = c->beta;
    const double rep_d = c->rep_d, rep_r02 = c->rep_r02;
    const int fourtakas = c->fourtakas;
    const double rhoi = Si[PK_RHO], pri = Si[PK_PRHO2], mui = Si[PK_MU], ci = Si[PK_CS];
    const double hi = Si[PK_H];
    const double inv_rhoi = 1.0 / rhoi;
    const double fh = fourtakas ? c->rho0m[c->material[i]] * c->inv_c02 : 0.0;
    const double ui = Pi[U], vi = Pi[U + 1], wi = dim > 2 ? Pi[U + 2] : 0.0;
    const double gx = c->g[0], gy = c->g[1], gz = dim > 2 ? c->g[2] : 0.0;
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
        const double uj = su[p], vj = sv[p], wj = dim > 2 ? sw[p] : 0.0;
        const double vx = ui - sug[p], vy = vi - svg[p], vz = dim > 2 ? wi - swg[p] : 0.0;
        const double vdx = vx * dx + vy * dy + vz * dz;
        const double vdw = (ui - uj) * dx + (vi - vj) * dy + (wi - wj) * dz;
        const double ieta = 1.0 / (r2 + eta2);
        /* Monaghan's artificial viscosity, active for approaching pairs only. */
        const double mu_ij = h0 * (vdx < 0.0 ? vdx : 0.0) * ieta;
        const double rhoj = srho[p], volj = svol[p], isj = sfl[p];
        const double prj = sprho2[p];
        const double pi_ij =
            (-alpha * 0.5 * (ci + scs[p]) * mu_ij + beta * mu_ij * mu_ij) * 2.0 / (rhoi + rhoj);
        const double mj = smass[p];
        const double fp = -mj * (pri + prj + pi_ij) * fw;
        /* Morris et al. (1997) laminar viscosity (a wall takes the fluid's viscosity). */
        const double muj = isj * smu[p] + (1.0 - isj) * mui; /* isj is 0 or 1 */
        const double fv = svis[p] * volj * (mui + muj) * inv_rhoi * fw * r2 * ieta;
        /* Wall repulsion, the rare case of a fluid particle very close to a wall. */
        const double fr =
            wall_repulsion(r2, isj == 0.0 && r2 < rep_r02 && r2 > 0.0, rep_r02, rep_d);
        ax += fp * dx + fv * vx + fr * dx;
        ay += fp * dy + fv * vy + fr * dy;
        if (dim > 2) az += fp * dz + fv * vz + fr * dz;
        dr += volj * vdw * fw;
        double drj = rhoj - rhoi;
        if (fourtakas) drj += fh * (gx * dx + gy * dy + gz * dz);
        dd -= isj * drj * fw * r2 * ieta * volj;
        if (energy) dei += 0.5 * mj * (pri + prj + pi_ij) * vdx * fw;
    }
    const double ai[3] = {ax + gx, ay + gy, az + gz}, vi3[3] = {ui, vi, wi};
    double a2 = 0, v2 = 0;
    for (int d = 0; d < dim; ++d) {
        c->a[d][i] = ai[d];
        a2 += ai[d] * ai[d];
        v2 += vi3[d] * vi3[d];
    }
    if (c->cont) c->drho[i] = rhoi * dr + c->diff * dd;
    if (energy) c->de[i] = dei;
    *amax2 = a2 > *amax2 ? a2 : *amax2;
    *vmax2 = v2 > *vmax2 ? v2 : *vmax2;
}

/* The kernels the pair loops are compiled for, and a row of a driver table: [kernel][dim - 2]
 * [variant] -> PREFIX_DIM_KERNEL_VARIANT. */
#define RY_FOR_EACH_KERNEL_(X)                                                                     \
    X(RY_KERNEL_CUBIC)                                                                             \
    X(RY_KERNEL_QUINTIC)                                                                           \
    X(RY_KERNEL_WENDLAND_C2) X(RY_KERNEL_WENDLAND_C4) X(RY_KERNEL_LUCY) X(RY_KERNEL_GAUSSIAN)
#define RY_DRIVER_ROW_(P, KT)                                                                      \
    [KT] = {{P##_2_##KT##_0, P##_2_##KT##_1}, {P##_3_##KT##_0, P##_3_##KT##_1}}

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

/* The cell-range pair loop (scheme.pair_loop: cells). The particles are sorted by cell at every
 * neighbour search (sim->sort_always), so the candidates of particle i are the particles of the
 * 3 (2D) or 9 (3D) rows of cells around its cell at the last search: consecutive index ranges,
 * a superset of the Verlet list. The pair terms run as one SIMD loop over each range, in
 * single precision (eight pairs per AVX2 instruction), with the pairs beyond the support masked:
 * no neighbour list is read and no neighbour data is gathered or copied. Separations are formed
 * from the double-precision positions and then rounded; densities enter as deviations from a
 * reference density (so that rho_j - rho_i keeps its digits); the pair terms are summed in
 * double precision. The state and the integrator stay in double precision. */

typedef struct fast_ctx {
    const uint8_t *kind;
    const uint32_t *rng;
    const float *fk; /* field k of particle j: fk[k * fs + j] */
    size_t fs;
    const double *x[3], *rho;
    double *a[3], *drho;
    const double *v[3], *rho0m;
    const uint8_t *material;
    double g[3], diff, rho_ref, inv_c02;
    float rad2, inv_h, dnorm_h, h0, eta2, alpha, beta, rep_d, rep_r02, c0;
    int cont, fourtakas;
} fast_ctx;

/* Eight lanes of single precision (GCC/Clang vector extensions: one AVX register, two SSE
 * registers, or lane loops elsewhere). */
typedef float v8f __attribute__((vector_size(32)));
typedef int v8i __attribute__((vector_size(32)));
typedef double v8d __attribute__((vector_size(64)));

static inline v8f v8_load(const float *p) {
    v8f v;
    memcpy(&v, p, sizeof v);
    return v;
}
/* x_i - x_j for eight j, formed in double precision and rounded. */
static inline v8f v8_sep(double xi, const double *xj) {
    v8d v;
    memcpy(&v, xj, sizeof v);
    return __builtin_convertvector(xi - v, v8f);
}
/* m ? a : 0 for a lane mask m (all bits set or clear). */
static inline v8f v8_and(v8i m, v8f a) {
    return (v8f)(m & (v8i)a);
}
static inline v8f v8_sqrt(v8f a) {
#if defined(__AVX__)
    return __builtin_ia32_sqrtps256(a);
#else
    v8f r;
    for (int k = 0; k < 8; ++k) r[k] = sqrtf(a[k]);
    return r;
#endif
}
/* Whether any lane of a mask is set. */
static inline int v8_any(v8i m) {
#if defined(__AVX__)
    return !__builtin_ia32_ptestz256((__attribute__((vector_size(32))) long long)m,
                                     (__attribute__((vector_size(32))) long long)m);
#else
    int a = 0;
    for (int k = 0; k < 8; ++k) a |= m[k];
    return a != 0;
#endif
}
/* The sum of the lanes, in double precision: halves added, then pairs. */
static inline double v8_sum(v8f a) {
    typedef float v4f __attribute__((vector_size(16)));
    typedef double v4d __attribute__((vector_size(32)));
    const v4f lo = {a[0], a[1], a[2], a[3]}, hi = {a[4], a[5], a[6], a[7]};
    const v4d s = __builtin_convertvector(lo, v4d) + __builtin_convertvector(hi, v4d);
    return (s[0] + s[2]) + (s[1] + s[3]);
}

/* (dW/dq)/q of the Wendland kernels (q < 2 is masked by the caller). */
static inline v8f dshape_over_q_v8(const ry_kernel_type kt, v8f q) {
    const v8f s = 0.5f * q, u = 1.0f - s, u2 = u * u;
    return kt == RY_KERNEL_WENDLAND_C2 ? -5.0f * u2 * u
                                       : (-14.0f / 3.0f) * u2 * u2 * u * (1.0f + 5.0f * s);
}

static inline __attribute__((always_inline)) void fast_particle(const fast_ctx *restrict c,
                                                                size_t i, const int dim,
                                                                const ry_kernel_type kt,
                                                                double *amax2, double *vmax2) {
    if (c->kind[i] != RY_KIND_FLUID) return;
    const int nrange = dim > 2 ? 9 : 3;
    const uint32_t *restrict rg = c->rng + (size_t)i * 2 * (size_t)nrange;
    const size_t fs = c->fs;
    const float *restrict fk = c->fk;
    const double *restrict x0 = c->x[0], *restrict x1 = c->x[1], *restrict x2 = c->x[2];
    const double xi = x0[i], yi = x1[i], zi = dim > 2 ? x2[i] : 0.0;
    const float ui = fk[FK_U * fs + i], vi = fk[FK_V * fs + i];
    const float wi = dim > 2 ? fk[FK_W * fs + i] : 0.0f;
    const float dri = fk[FK_DRHO * fs + i], pri = fk[FK_PRHO2 * fs + i];
    const float mui = fk[FK_MU * fs + i];
    const float rhoi2 = 2.0f * (float)c->rho_ref + dri; /* rho_i + rho_j - dr_j */
    const float inv_rhoi = (float)(1.0 / c->rho[i]);
    const float rad2 = c->rad2, inv_h = c->inv_h, dnorm_h = c->dnorm_h, h0 = c->h0;
    /* -alpha c_ij with c_ij = c0: the cell-range loop serves the Tait and linear equations of
     * state, whose sound speed is constant. */
    const float eta2 = c->eta2, hac0 = -c->alpha * c->c0, beta = c->beta;
    const float rep_d = c->rep_d, rep_r02 = c->rep_r02;
    const int fourtakas = c->fourtakas;
    const float fh = fourtakas ? (float)(c->rho0m[c->material[i]] * c->inv_c02) : 0.0f;
    const float fgx = fh * (float)c->g[0], fgy = fh * (float)c->g[1], fgz = fh * (float)c->g[2];
    const v8f zero = {0};
    v8f sx = zero, sy = zero, sz = zero, sr = zero, sd = zero;
    for (int r = 0; r < nrange; ++r) {
        for (size_t j = rg[2 * r]; j < rg[2 * r + 1]; j += 8) {
            const v8f dx = v8_sep(xi, x0 + j), dy = v8_sep(yi, x1 + j);
            const v8f dz = dim > 2 ? v8_sep(zi, x2 + j) : zero;
            v8f r2 = dx * dx + dy * dy;
            if (dim > 2) r2 += dz * dz;
            /* i itself (r2 = 0) contributes nothing: every term has a factor x_ij or r2, and
             * the repulsion needs r2 > 0. */
            const v8f fw = v8_and(r2 < rad2, dnorm_h * dshape_over_q_v8(kt, v8_sqrt(r2) * inv_h));
            const v8f vx = ui - v8_load(fk + FK_UG * fs + j),
                      vy = vi - v8_load(fk + FK_VG * fs + j);
            const v8f vz = dim > 2 ? wi - v8_load(fk + FK_WG * fs + j) : zero;
            v8f vdx = vx * dx + vy * dy;
            if (dim > 2) vdx += vz * dz;
            v8f vdw =
                (ui - v8_load(fk + FK_U * fs + j)) * dx + (vi - v8_load(fk + FK_V * fs + j)) * dy;
            if (dim > 2) vdw += (wi - v8_load(fk + FK_W * fs + j)) * dz;
            const v8f ieta = 1.0f / (r2 + eta2);
            /* Monaghan's artificial viscosity, active for approaching pairs only. */
            const v8f mu_ij = h0 * v8_and(vdx < 0.0f, vdx) * ieta;
            const v8f drj = v8_load(fk + FK_DRHO * fs + j);
            const v8f pi_ij = (hac0 + beta * mu_ij) * mu_ij * 2.0f / (rhoi2 + drj);
            const v8f volj = v8_load(fk + FK_VOL * fs + j), isj = v8_load(fk + FK_FLUID * fs + j);
            v8f fp =
                -v8_load(fk + FK_MASS * fs + j) * (pri + v8_load(fk + FK_PRHO2 * fs + j) + pi_ij);
            const v8f fwe = fw * r2 * ieta * volj;
            const v8f muj = isj * v8_load(fk + FK_MU * fs + j) + (1.0f - isj) * mui;
            const v8f fv = v8_load(fk + FK_VISC * fs + j) * (mui + muj) * inv_rhoi * fwe;
            fp *= fw;
            /* Wall repulsion (r2 < r0^2 lies within the support), rarely active: computed
             * only for the vectors that need it. (r0/r)^2 is capped at 1e3 so that single
             * precision cannot overflow. */
            const v8i on = (isj == 0.0f) & (r2 < rep_r02) & (r2 > 0.0f);
            if (v8_any(on)) {
                const v8f inv_r2 = 1.0f / (r2 + v8_and(~on, zero + 1.0f));
                v8f q2 = rep_r02 * inv_r2;
                const v8i big = q2 >= 1e3f;
                q2 = v8_and(~big, q2) + v8_and(big, zero + 1e3f);
                const v8f q4 = q2 * q2;
                fp += v8_and(on, rep_d * (q4 * q4 * q4 - q4) * inv_r2);
            }
            sx += fp * dx + fv * vx;
            sy += fp * dy + fv * vy;
            if (dim > 2) sz += fp * dz + fv * vz;
            sr += volj * vdw * fw;
            v8f dd = drj - dri;
            if (fourtakas) dd += dim > 2 ? fgx * dx + fgy * dy + fgz * dz : fgx * dx + fgy * dy;
            sd -= isj * dd * fwe;
        }
    }
    const double ai[3] = {v8_sum(sx) + c->g[0], v8_sum(sy) + c->g[1], v8_sum(sz) + c->g[2]};
    double a2 = 0, v2 = 0;
    for (int d = 0; d < dim; ++d) {
        c->a[d][i] = ai[d];
        a2 += ai[d] * ai[d];
        v2 += c->v[d][i] * c->v[d][i];
    }
    if (c->cont) c->drho[i] = c->rho[i] * v8_sum(sr) + c->diff * v8_sum(sd);
    *amax2 = a2 > *amax2 ? a2 : *amax2;
    *vmax2 = v2 > *vmax2 ? v2 : *vmax2;
}

typedef void (*fast_driver)(const fast_ctx *c, size_t n, force_out *res);
#define RY_FAST_DRIVER_(DIM, KT)                                                                   \
    static void fast_##DIM##_##KT(const fast_ctx *c, size_t n, force_out *res) {                   \
        double amax2 = 0, vmax2 = 0;                                                               \
        _Pragma("omp parallel for schedule(dynamic, 64) reduction(max : amax2, vmax2)") for (      \
            size_t i = 0; i < n; ++i) fast_particle(c, i, DIM, KT, &amax2, &vmax2);                \
        res->amax2 = amax2;                                                                        \
        res->vmax2 = vmax2;                                                                        \
    }
RY_FAST_DRIVER_(2, RY_KERNEL_WENDLAND_C2)
RY_FAST_DRIVER_(3, RY_KERNEL_WENDLAND_C2)
RY_FAST_DRIVER_(2, RY_KERNEL_WENDLAND_C4)
RY_FAST_DRIVER_(3, RY_KERNEL_WENDLAND_C4)
#undef RY_FAST_DRIVER_

/* Whether the cell-range loop serves this case: Wendland kernels, no periodic directions, no
 * variable h, energy equation, transport velocity or open boundaries (whose buffers change the
 * particle set between searches). */
static int fast_eligible(const ry_sim *sim, const wcsph *w, const char **why) {
    const ry_kernel_type kt = sim->kernel.type;
    *why = kt != RY_KERNEL_WENDLAND_C2 && kt != RY_KERNEL_WENDLAND_C4 ? "a Wendland kernel"
           : is_periodic(sim)                                         ? "no periodic directions"
           : w->variable_h || w->energy                               ? "no variable_h or energy"
           : w->tvf                                                   ? "no transport_velocity"
           : sim->nopen > 0                                           ? "no open boundaries"
           : w->rheo.on                                               ? "Newtonian materials"
           : w->st.model != RY_ST_NONE                                ? "no surface_tension"
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
static ry_status fast_ranges(ry_sim *sim, wcsph *w, ry_error *err) {
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

/* W(q) / norm of the Wendland kernels (q < 2 is masked by the caller). */
static inline v8f shape_v8(const ry_kernel_type kt, v8f q) {
    const v8f s = 0.5f * q, t = 1.0f - s, t2 = t * t;
    return kt == RY_KERNEL_WENDLAND_C2 ? t2 * t2 * (1.0f + 4.0f * s)
                                       : t2 * t2 * t2 * (1.0f + s * (6.0f + s * (35.0f / 3.0f)));
}

/* The wall pass of the cell-range loop: the sums of wall particle i over the fluid among its
 * candidates, in single precision from the records of prepare_pairs (whose wall entries are
 * then rewritten). */
static inline __attribute__((always_inline)) void
wall_sums_ranges(const ry_sim *sim, const wcsph *w, size_t i, const int dim,
                 const ry_kernel_type kt, wall_sums *s) {
    const ry_kernel *k = &sim->kernel;
    const int nrange = dim > 2 ? 9 : 3;
    const uint32_t *restrict rg = w->rng + i * 2 * (size_t)nrange;
    const size_t fs = w->fpack_stride;
    const double *restrict x0 = w->fpack, *restrict x1 = x0 + fs, *restrict x2 = x0 + 2 * fs;
    const float *restrict fk = (const float *)(x0 + 3 * fs);
    const double xi = x0[i], yi = x1[i], zi = dim > 2 ? x2[i] : 0.0;
    const float rad2 = (float)(k->radius * k->radius), inv_h = (float)k->inv_h;
    const float gx = (float)sim->gravity[0], gy = (float)sim->gravity[1];
    const float gz = dim > 2 ? (float)sim->gravity[2] : 0.0f;
    const float rho_ref = (float)w->rho0m[0];
    const v8f zero = {0};
    v8f sw = zero, sp = zero, srx = zero, su = zero, sv = zero, sz = zero;
    for (int r = 0; r < nrange; ++r) {
        for (size_t j = rg[2 * r]; j < rg[2 * r + 1]; j += 8) {
            const v8f dx = v8_sep(xi, x0 + j), dy = v8_sep(yi, x1 + j);
            const v8f dz = dim > 2 ? v8_sep(zi, x2 + j) : zero;
            v8f r2 = dx * dx + dy * dy, gr = gx * dx + gy * dy;
            if (dim > 2) {
                r2 += dz * dz;
                gr += gz * dz;
            }
            const v8i on = (r2 < rad2) & (v8_load(fk + FK_FLUID * fs + j) != 0.0f);
            const v8f wij = v8_and(on, shape_v8(kt, v8_sqrt(r2) * inv_h));
            sw += wij;
            sp += v8_load(fk + FK_P * fs + j) * wij;
            srx += (rho_ref + v8_load(fk + FK_DRHO * fs + j)) * gr * wij;
            su += v8_load(fk + FK_U * fs + j) * wij;
            sv += v8_load(fk + FK_V * fs + j) * wij;
            if (dim > 2) sz += v8_load(fk + FK_W * fs + j) * wij;
        }
    }
    /* The kernel's normalisation cancels in every ratio but is kept for sw > 0 semantics. */
    const double norm = k->norm;
    s->sw = norm * v8_sum(sw);
    s->sp = norm * v8_sum(sp);
    s->srx = norm * v8_sum(srx);
    s->sv[0] = norm * v8_sum(su);
    s->sv[1] = norm * v8_sum(sv);
    s->sv[2] = norm * v8_sum(sz);
}

#define RY_WALL_RANGES_(DIM, KT)                                                                   \
    static void wall_ranges_##DIM##_##KT(ry_sim *sim, const wcsph *w) {                            \
        const size_t n = sim->ps.n;                                                                \
        _Pragma("omp parallel for schedule(static)") for (size_t i = 0; i < n; ++i) {              \
            if (!wall_like(&sim->ps, i)) continue;                                                 \
            wall_sums s = {0, 0, 0, {0, 0, 0}};                                                    \
            if (w->wet[i]) wall_sums_ranges(sim, w, i, DIM, KT, &s);                               \
            wall_set(sim, w, i, &s);                                                               \
        }                                                                                          \
        /* The walls' records, once no thread reads them any more. */                              \
        if (uniform_materials(sim, w)) {                                                           \
            fpack_walls_one_rho0(sim, w);                                                          \
            return;                                                                                \
        }                                                                                          \
        _Pragma("omp parallel for schedule(static)") for (size_t i = 0; i < n; ++i) {              \
            if (wall_like(&sim->ps, i))                                                            \
                fpack_one(sim, w, i, pack_mu(sim, w, i), pack_visc(sim, w, i));                    \
        }                                                                                          \
    }
RY_WALL_RANGES_(2, RY_KERNEL_WENDLAND_C2)
RY_WALL_RANGES_(3, RY_KERNEL_WENDLAND_C2)
RY_WALL_RANGES_(2, RY_KERNEL_WENDLAND_C4)
RY_WALL_RANGES_(3, RY_KERNEL_WENDLAND_C4)
#undef RY_WALL_RANGES_

static void fast_wall_pass(ry_sim *sim, const wcsph *w) {
    static void (*const drivers[2][2])(ry_sim *, const wcsph *) = {
        {wall_ranges_2_RY_KERNEL_WENDLAND_C2, wall_ranges_3_RY_KERNEL_WENDLAND_C2},
        {wall_ranges_2_RY_KERNEL_WENDLAND_C4, wall_ranges_3_RY_KERNEL_WENDLAND_C4}};
    drivers[sim->kernel.type == RY_KERNEL_WENDLAND_C4][sim->dim - 2](sim, w);
}

static void fast_forces(ry_sim *sim, const wcsph *w, force_out *res) {
    const ry_particles *ps = &sim->ps;
    const ry_kernel *k = &sim->kernel;
    fast_ctx c;
    memset(&c, 0, sizeof c);
    c.kind = ps->kind;
    c.rng = w->rng;
    c.fs = w->fpack_stride;
    c.fk = (const float *)((const double *)w->fpack + 3 * c.fs);
    for (int d = 0; d < 3; ++d) {
        c.x[d] = (const double *)w->fpack + (size_t)d * c.fs;
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
    c.h0 = (float)k->h;
    c.eta2 = (float)(0.01 * k->h * k->h);
    c.alpha = (float)w->alpha;
    c.c0 = (float)w->c0;
    c.beta = (float)w->beta;
    c.rep_d = (float)w->rep_d;
    c.rep_r02 = (float)(w->rep_d > 0 ? w->rep_r0 * w->rep_r0 : 0.0);
    static const fast_driver drivers[2][2] = {
        {fast_2_RY_KERNEL_WENDLAND_C2, fast_3_RY_KERNEL_WENDLAND_C2},
        {fast_2_RY_KERNEL_WENDLAND_C4, fast_3_RY_KERNEL_WENDLAND_C4}};
    drivers[k->type == RY_KERNEL_WENDLAND_C4][sim->dim - 2](&c, ps->n, res);
}

/* Transport-velocity formulation (Adami, Hu & Adams 2013, eq. 8 and 13): pressure with the
 * density-weighted inter-particle average, the extra stress A = rho v (v~ - v), the viscous
 * term with the inter-particle averaged viscosity, and the background-pressure acceleration
 * that moves particles with v~. V_i = m_i / rho_i. */
static inline __attribute__((always_inline)) void
tvf_particle(const ry_sim *sim, const wcsph *w, size_t i, const int dim, const ry_kernel_type kt,
             const int periodic, double *amax2, double *vmax2) {
    const ry_particles *ps = &sim->ps;
    if (ps->kind[i] != RY_KIND_FLUID) return;
    const ry_kernel *k = &sim->kernel;
    const double *x[3], *v[3], *vg[3], *vt[3];
    for (int d = 0; d < 3; ++d) {
        x[d] = ps->f[RY_F_X + (d < dim ? d : 0)];
        v[d] = ps->f[RY_F_VX + (d < dim ? d : 0)];
        vg[d] = ps->f[w->f_vg[d < dim ? d : 0]];
        vt[d] = ps->f[w->f_vt[d < dim ? d : 0]];
    }
    const double *restrict m = ps->f[RY_F_MASS];
    const double *restrict rho = ps->f[RY_F_RHO];
    const double *restrict p = ps->f[RY_F_P];
    const double *restrict vol = ps->f[w->f_vol];
    const double *restrict mu = ps->f[w->f_mu];
    const double *restrict isfl = ps->f[w->f_isfluid];
    const double *restrict vis = ps->f[w->f_visc];
    const uint32_t *restrict nb = sim->nl.j;
    const double rad2 = sim->nl_radius * sim->nl_radius;
    const double dnorm_h = k->dnorm * k->inv_h, inv_h = k->inv_h; /* (dW/dr)/r */
    const double rep_r02 = w->rep_r0 * w->rep_r0, rep_d = w->rep_d;
    const double rhoi = rho[i], pi = p[i], mui = mu[i], vi2 = vol[i] * vol[i];
    double ai[3] = {0, 0, 0}, bi[3] = {0, 0, 0}, Ai[3] = {0, 0, 0}, vi[3] = {0, 0, 0}, xi[3];
    double v2 = 0;
    /* A_i = rho_i v_i (v~_i - v_i), a tensor; A_i . grad W = rho_i v_i ((v~_i - v_i).gradW) */
    for (int d = 0; d < dim; ++d) {
        vi[d] = v[d][i];
        xi[d] = x[d][i];
        Ai[d] = vt[d][i] - vi[d];
        v2 += vi[d] * vi[d];
    }
    const size_t q1 = sim->nl.offset[i + 1];
    for (size_t q = sim->nl.offset[i]; q < q1; ++q) {
        const uint32_t j = nb[q];
        double dx[3] = {0, 0, 0}, r2 = 0;
        for (int d = 0; d < dim; ++d) dx[d] = xi[d] - x[d][j];
        if (periodic) ry_box_min_image(&sim->box, dx);
        for (int d = 0; d < dim; ++d) r2 += dx[d] * dx[d];
        if (r2 >= rad2 || r2 <= 0) continue;
        const double fw = dnorm_h * ry_kernel_dshape_over_q(kt, sqrt(r2) * inv_h); /* gradW/x */
        const double rhoj = rho[j], vv = vi2 + vol[j] * vol[j];
        const double pij = (rhoj * pi + rhoi * p[j]) / (rhoi + rhoj);
        const double fj = isfl[j]; /* 0 or 1 */
        const double muj = fj * mu[j] + (1.0 - fj) * mui;
        const double etaij = (mui + muj) > 0 ? 2.0 * mui * muj / (mui + muj) : 0.0;
        /* (A_i + A_j)/2 . grad W; walls carry no extra stress. */
        double adi = 0, adj = 0;
        for (int d = 0; d < dim; ++d) {
            adi += Ai[d] * dx[d];
            adj += (vt[d][j] - v[d][j]) * dx[d];
        }
        adi *= fw;
        adj *= fw * fj;
        const double fr = wall_repulsion(r2, fj == 0.0 && r2 < rep_r02, rep_r02, rep_d) * m[i] / vv;
        const double visj = vis[j];
        for (int d = 0; d < dim; ++d) {
            const double vij = vi[d] - vg[d][j];
            double f = -pij * fw * dx[d] + fr * dx[d];
            f += 0.5 * (rhoi * vi[d] * adi + rhoj * v[d][j] * adj);
            f += visj * etaij * vij * fw; /* eta_ij v_ij (1/r) dW/dr */
            ai[d] += vv * f;
            bi[d] += vv * fw * dx[d];
        }
    }
    double a2 = 0;
    for (int d = 0; d < dim; ++d) {
        ai[d] = ai[d] / m[i] + sim->gravity[d];
        ps->f[RY_F_AX + d][i] = ai[d];
        ps->f[w->f_abg[d]][i] = -w->p_tvf / m[i] * bi[d];
        a2 += ai[d] * ai[d];
    }
    *amax2 = a2 > *amax2 ? a2 : *amax2;
    *vmax2 = v2 > *vmax2 ? v2 : *vmax2;
}

typedef void (*tvf_driver)(ry_sim *sim, const wcsph *w, force_out *res);
#define RY_TVF_DRIVER_(DIM, KT, PER)                                                               \
    static void tvf_##DIM##_##KT##_##PER(ry_sim *sim, const wcsph *w, force_out *res) {            \
        double amax2 = 0, vmax2 = 0;                                                               \
        const size_t n = sim->ps.n;                                                                \
        _Pragma("omp parallel for schedule(dynamic, 64) reduction(max : amax2, vmax2)") for (      \
            size_t i = 0; i < n; ++i) tvf_particle(sim, w, i, DIM, KT, PER, &amax2, &vmax2);       \
        res->amax2 = amax2;                                                                        \
        res->vmax2 = vmax2;                                                                        \
    }
#define RY_TVF_DRIVERS_(KT)                                                                        \
    RY_TVF_DRIVER_(2, KT, 0)                                                                       \
    RY_TVF_DRIVER_(2, KT, 1)                                                                       \
    RY_TVF_DRIVER_(3, KT, 0)                                                                       \
    RY_TVF_DRIVER_(3, KT, 1)                                                                       \
    RY_DENSITY_DRIVER_(2, KT, 0)                                                                   \
    RY_DENSITY_DRIVER_(2, KT, 1) RY_DENSITY_DRIVER_(3, KT, 0) RY_DENSITY_DRIVER_(3, KT, 1)
RY_FOR_EACH_KERNEL_(RY_TVF_DRIVERS_)
#define RY_TVF_ROW_(KT) RY_DRIVER_ROW_(tvf, KT),
static const tvf_driver tvf_drivers[RY_KERNEL_COUNT][2][2] = {RY_FOR_EACH_KERNEL_(RY_TVF_ROW_)};
#define RY_DENSITY_ROW_(KT) RY_DRIVER_ROW_(density, KT),
static const density_driver density_drivers[RY_KERNEL_COUNT][2][2] = {
    RY_FOR_EACH_KERNEL_(RY_DENSITY_ROW_)};
#undef RY_TVF_ROW_
#undef RY_DENSITY_ROW_
#undef RY_TVF_DRIVERS_
#undef RY_TVF_DRIVER_
#undef RY_DENSITY_DRIVER_
#undef RY_DRIVER_ROW_
#undef RY_FOR_EACH_KERNEL_

static void density_summation(ry_sim *sim, const wcsph *w) {
    density_drivers[sim->kernel.type][sim->dim - 2][is_periodic(sim)](sim, w);
}

/* Picks the specialised pair loop. */
static ry_status fluid_forces(ry_sim *sim, wcsph *w, force_out *res, ry_error *err) {
    if (w->tvf) {
        tvf_drivers[sim->kernel.type][sim->dim - 2][is_periodic(sim)](sim, w, res);
        return RY_OK;
    }
    if (w->fast) {
        fast_forces(sim, w, res);
        return RY_OK;
    }
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

/* The scheme's buffers, for sim->scheme_bytes. */
static size_t wcsph_bytes(const wcsph *w) {
    const size_t nr = w->rng_cap * (2 * (size_t)w->nrange * sizeof(uint32_t) + 1);
    return w->pack_cap * PK_STRIDE(3) * sizeof(double) +
           w->scratch_cap * (SC_COUNT + 1) * sizeof(double) +
           w->fpack_cap * (3 * sizeof(double) + FK_COUNT * sizeof(float)) + nr;
}

/* In a distributed run: the largest acceleration and speed of the fluid over all ranks, from
 * owned particles only (a halo particle's rates lack the neighbours beyond the halo). */
static void global_maxima(ry_sim *sim, force_out *res) {
    const ry_particles *ps = &sim->ps;
    double a2 = 0, v2 = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || ry_sim_is_halo(sim, i)) continue;
        double a = 0, v = 0;
        for (int d = 0; d < sim->dim; ++d) {
            a += ps->f[RY_F_AX + d][i] * ps->f[RY_F_AX + d][i];
            v += ps->f[RY_F_VX + d][i] * ps->f[RY_F_VX + d][i];
        }
        a2 = a > a2 ? a : a2;
        v2 = v > v2 ? v : v2;
    }
    res->amax2 = sim->par->max(sim, a2);
    res->vmax2 = sim->par->max(sim, v2);
}

/* Non-Newtonian materials: velocity gradient, viscosity and stress divergence at the current
 * state (sph_rheology.h); walls enter with the velocity the viscous terms give them. */
static ry_status rheology_rates(ry_sim *sim, wcsph *w, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    if (w->vol_cap < n) {
        double *v = realloc(w->vol, n * sizeof *v);
        RY_CHECK(err, v != NULL, RY_ERR_NOMEM, "out of memory (%zu particles)", n);
        w->vol = v;
        w->vol_cap = n;
    }
    for (size_t i = 0; i < n; ++i) w->vol[i] = ps->f[RY_F_MASS][i] / ps->f[RY_F_RHO][i];
    RY_TRY(ry_pair_cache_fill(&w->pc, sim, MOBILE, err));
    const double *vg[3];
    for (int d = 0; d < 3; ++d) vg[d] = ps->f[w->f_vg[d]];
    return ry_sph_rheo_rates(&w->rheo, sim, &w->pc, MOBILE, w->vol,
                             w->wall == WALL_NO_SLIP ? vg : NULL, err);
}

/* Adds the polymer stress divergence to the fluid's acceleration. */
static void polymer_forces(ry_sim *sim, const wcsph *w, force_out *res) {
    ry_particles *ps = &sim->ps;
    double amax2 = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (!MOBILE[ps->kind[i]]) continue;
        double a2 = 0;
        for (int d = 0; d < sim->dim; ++d) {
            ps->f[RY_F_AX + d][i] += w->rheo.acc[3 * i + d];
            a2 += ps->f[RY_F_AX + d][i] * ps->f[RY_F_AX + d][i];
        }
        amax2 = fmax(amax2, a2);
    }
    res->amax2 = amax2;
}

/* Free-surface tension (docs/wcsph.md, "Surface tension"): the surface_tension section as in
 * MPS and IISPH, on the neighbour-list loop. The potential model and CSF in force form add their
 * accelerations. CSF in pressure form: the surface particles (kernel sum below st_beta times the
 * lattice's) take the Laplace jump P_i = sigma kappa_i as their pressure instead of the equation
 * of state's, and their pressure force counts pressures from P_i:
 *   a_i = -sum_j m_j ((p_i - P_i) / rho_i^2 + (p_j - P_i) / rho_j^2) grad_i W_ij,
 * the symmetric form plus P_i sum_j m_j (1/rho_i^2 + 1/rho_j^2) grad_i W_ij (st_forces). With
 * the pressure form the artificial repulsion of MPS is on by default (scheme.repulsion). */

/* CSF in pressure form: the surface particles and their Laplace jump, which replaces their
 * pressure. */
static ry_status st_laplace(ry_sim *sim, wcsph *w, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    RY_TRY(ry_st_work_ensure(&w->stw, n, err));
    const double w0 = sim->kernel.norm * ry_kernel_shape(sim->kernel.type, 0.0);
    const double rad = sim->kernel.radius;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        double sw = w0;
        if (ps->kind[i] == RY_KIND_FLUID)
            for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
                const uint32_t j = sim->nl.j[q];
                if (ps->kind[j] == RY_KIND_SOLID) continue;
                double dx[3] = {0, 0, 0}, r2 = 0;
                for (int d = 0; d < sim->dim; ++d)
                    dx[d] = ps->f[RY_F_X + d][j] - ps->f[RY_F_X + d][i];
                ry_box_min_image(&sim->box, dx);
                for (int d = 0; d < sim->dim; ++d) r2 += dx[d] * dx[d];
                if (r2 < rad * rad) sw += ry_kernel_w(&sim->kernel, sqrt(r2));
            }
        w->stw.tag[i] = ps->kind[i] == RY_KIND_FLUID && sw < w->st_beta * w->st_w0;
    }
    double *P = w->stw.p;
    ry_st_laplace_pressure(&w->st, sim, w->stw.tag, 1, 2.1 * sim->dx, P);
    for (size_t i = 0; i < n; ++i) {
        if (!w->stw.tag[i])
            P[i] = 0.0;
        else
            ps->f[RY_F_P][i] = P[i];
    }
    return RY_OK;
}

/* The surface-tension accelerations, added to the fluid's (RY_F_AX). */
static ry_status st_forces(ry_sim *sim, wcsph *w, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    if (!ry_st_pressure_form(&w->st)) {
        double *a[3];
        for (int d = 0; d < 3; ++d) a[d] = ps->f[RY_F_AX + (d < dim ? d : 0)];
        return ry_st_accelerate(&w->st, sim, a, err);
    }
    const double *P = w->stw.p, *m = ps->f[RY_F_MASS], *rho = ps->f[RY_F_RHO];
    const double rad = sim->kernel.radius;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (P[i] == 0.0) continue; /* not a surface particle */
        double a[3] = {0, 0, 0};
        const double ri2 = 1.0 / (rho[i] * rho[i]);
        for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
            const uint32_t j = sim->nl.j[q];
            if (ps->kind[j] == RY_KIND_SOLID) continue;
            double dx[3] = {0, 0, 0}, r2 = 0;
            for (int d = 0; d < dim; ++d) dx[d] = ps->f[RY_F_X + d][i] - ps->f[RY_F_X + d][j];
            ry_box_min_image(&sim->box, dx);
            for (int d = 0; d < dim; ++d) r2 += dx[d] * dx[d];
            if (r2 >= rad * rad || r2 <= 0) continue;
            const double r = sqrt(r2), g = ry_kernel_dwdr(&sim->kernel, r) / r;
            const double f = m[j] * (ri2 + 1.0 / (rho[j] * rho[j])) * g;
            for (int d = 0; d < dim; ++d) a[d] += f * dx[d];
        }
        for (int d = 0; d < dim; ++d) ps->f[RY_F_AX + d][i] += P[i] * a[d];
    }
    return RY_OK;
}

/* Evaluates all rates at the current (predicted) state. */
static ry_status evaluate(ry_sim *sim, wcsph *w, ry_error *err) {
    ry_particles *ps = &sim->ps;
    double hmax = sim->kernel.h;
    if (w->variable_h) {
        for (size_t i = 0; i < ps->n; ++i) hmax = fmax(hmax, ps->f[RY_F_H][i]);
    }
    if (sim->par) hmax = sim->par->max(sim, hmax); /* one search radius on every rank */
    w->hmax = hmax;
    /* The surface-tension radius may reach beyond the kernel's (the pair loop keeps to the
     * support). */
    const double reach = fmax(sim->kernel.kappa * hmax, w->st.model ? w->st.re : 0.0);
    RY_TRY(ry_sim_neighbors(sim, reach, err));
    if (w->fast && w->rng_gen != sim->nl_generation) RY_TRY(fast_ranges(sim, w, err));
    if (w->density == DENS_SUMMATION) density_summation(sim, w);
    const size_t n = ps->n;
    double *p = ps->f[RY_F_P];
    const double *rho = ps->f[RY_F_RHO], *e = ps->f[RY_F_E];
    if (!w->fast) {
#pragma omp parallel for schedule(static)
        for (size_t i = 0; i < n; ++i)
            if (ps->kind[i] == RY_KIND_FLUID) p[i] = eos_pressure(w, ps->material[i], rho[i], e[i]);
    }
    if (ry_st_pressure_form(&w->st)) RY_TRY(st_laplace(sim, w, err));
    if (w->fast) {
        /* The wall pass reads the fluid's records and rewrites the walls'. */
        RY_TRY(prepare_pairs(sim, w, err));
        fast_wall_pass(sim, w);
    } else {
        wall_pass(sim, w);
        if (w->rheo.on) RY_TRY(rheology_rates(sim, w, err));
        RY_TRY(prepare_pairs(sim, w, err));
    }
    force_out res;
    RY_TRY(fluid_forces(sim, w, &res, err));
    if (w->st.model != RY_ST_NONE) RY_TRY(st_forces(sim, w, err));
    if (w->rheo.ob) polymer_forces(sim, w, &res);
    if (sim->par) global_maxima(sim, &res);
    sim->scheme_bytes = wcsph_bytes(w);
    w->amax = sqrt(res.amax2);
    w->vmax = sqrt(res.vmax2);
    w->have_forces = 1;
    return RY_OK;
}

static ry_status wcsph_dt(ry_sim *sim, void *state, double *dt, ry_error *err) {
    wcsph *w = state;
    if (!w->have_forces) RY_TRY(evaluate(sim, w, err));
    double h = sim->kernel.h;
    double c = w->c0;
    if (w->eos == EOS_IDEAL_GAS) {
        c = 0;
        const ry_particles *ps = &sim->ps;
        for (size_t i = 0; i < ps->n; ++i)
            c = fmax(c, sound_speed(w, ps->f[RY_F_RHO][i], ps->f[RY_F_P][i]));
    }
    double t = sim->cfl * h / (c + w->vmax);
    if (w->amax > 0) t = fmin(t, 0.25 * sqrt(h / w->amax));
    double numax = 0;
    for (int m = 0; m < sim->nmat; ++m) numax = fmax(numax, sim->mat[m].viscosity);
    if (numax > 0 && w->laminar) t = fmin(t, 0.125 * h * h / (numax * w->mu_corr));
    if (w->laminar)
        t = fmin(t, ry_sph_rheo_dt(&w->rheo, sim, MOBILE, h, sim->cfl, 0.125 / w->mu_corr));
    t = fmin(t, ry_st_capillary_dt(&w->st, sim));
    *dt = t;
    return RY_OK;
}

/* The first half kick and the drift of particle i (leapfrog). */
static inline __attribute__((always_inline)) void kick_drift(ry_sim *sim, const wcsph *w, size_t i,
                                                             double dt, int cont) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    /* Outlet buffers move as fluid, at the outlet's pressure and the reference density. */
    const int outlet = ps->kind[i] == RY_KIND_OUTLET;
    if (ps->kind[i] != RY_KIND_FLUID && !outlet) {
        if (ps->kind[i] == RY_KIND_INLET) /* inflow buffers drift at the inlet velocity */
            for (int d = 0; d < dim; ++d) ps->f[RY_F_X + d][i] += dt * ps->f[RY_F_VX + d][i];
        return;
    }
    for (int d = 0; d < dim; ++d) {
        double vh = ps->f[RY_F_VX + d][i] + 0.5 * dt * ps->f[RY_F_AX + d][i];
        ps->f[w->f_vh[d]][i] = vh;
        if (w->tvf) {
            /* Particles move with the transport velocity (Adami et al. 2013, eq. 13). */
            double vt = vh + 0.5 * dt * ps->f[w->f_abg[d]][i];
            ps->f[w->f_vt[d]][i] = vt;
            ps->f[RY_F_X + d][i] += dt * vt;
        } else {
            ps->f[RY_F_X + d][i] += dt * vh;
        }
        if (sim->box.periodic[d]) { /* back into the periodic box */
            const double lo = sim->box.lo[d], L = sim->box.hi[d] - lo;
            double *x = &ps->f[RY_F_X + d][i];
            if (*x < lo) *x += L;
            if (*x >= lo + L) *x -= L;
        }
        ps->f[RY_F_VX + d][i] = vh + 0.5 * dt * ps->f[RY_F_AX + d][i];
    }
    if (outlet) return;
    if (cont) {
        double rh = ps->f[RY_F_RHO][i] + 0.5 * dt * ps->f[RY_F_DRHO][i];
        ps->f[w->f_rhoh][i] = rh;
        ps->f[RY_F_RHO][i] = rh + 0.5 * dt * ps->f[RY_F_DRHO][i];
    }
    if (w->energy) {
        double eh = ps->f[RY_F_E][i] + 0.5 * dt * ps->f[RY_F_DE][i];
        ps->f[w->f_eh][i] = eh;
        ps->f[RY_F_E][i] = eh + 0.5 * dt * ps->f[RY_F_DE][i];
    }
    if (w->variable_h) {
        double dh = -ps->f[RY_F_H][i] / (dim * ps->f[RY_F_RHO][i]) * ps->f[RY_F_DRHO][i];
        double hh = ps->f[RY_F_H][i] + 0.5 * dt * dh;
        ps->f[w->f_hh][i] = hh;
        ps->f[RY_F_H][i] = hh + 0.5 * dt * dh;
    }
}

/* The second half kick of particle i, with the rates at the new positions. */
static inline __attribute__((always_inline)) void final_kick(ry_sim *sim, const wcsph *w, size_t i,
                                                             double dt, int cont) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    if (ps->kind[i] != RY_KIND_FLUID && ps->kind[i] != RY_KIND_OUTLET) return;
    for (int d = 0; d < dim; ++d)
        ps->f[RY_F_VX + d][i] = ps->f[w->f_vh[d]][i] + 0.5 * dt * ps->f[RY_F_AX + d][i];
    if (ps->kind[i] == RY_KIND_OUTLET) return;
    if (cont) ps->f[RY_F_RHO][i] = ps->f[w->f_rhoh][i] + 0.5 * dt * ps->f[RY_F_DRHO][i];
    if (w->energy) ps->f[RY_F_E][i] = ps->f[w->f_eh][i] + 0.5 * dt * ps->f[RY_F_DE][i];
    if (w->variable_h) {
        double dh = -ps->f[RY_F_H][i] / (dim * ps->f[RY_F_RHO][i]) * ps->f[RY_F_DRHO][i];
        ps->f[RY_F_H][i] = ps->f[w->f_hh][i] + 0.5 * dt * dh;
    }
}

/* The leapfrog loops of the cell-range loop's cases (fluid and fixed walls; no energy,
 * variable h, transport velocity or open boundaries), one contiguous pass per array so that
 * they vectorise. Each thread keeps the particles of its static share through the passes of a
 * region, so the passes need no barrier between them. Walls keep their values. */
static double fast_kick_drift(ry_sim *sim, const wcsph *w, double dt, int cont) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const double hdt = 0.5 * dt;
    const uint8_t *restrict kind = ps->kind;
    double m = 0;
#pragma omp parallel
    {
        for (int d = 0; d < dim; ++d) {
            double *restrict x = ps->f[RY_F_X + d], *restrict v = ps->f[RY_F_VX + d];
            double *restrict vh = ps->f[w->f_vh[d]];
            const double *restrict a = ps->f[RY_F_AX + d];
#pragma omp for schedule(static) nowait
            for (size_t i = 0; i < n; ++i) {
                const int f = kind[i] == RY_KIND_FLUID;
                const double h = v[i] + hdt * a[i];
                vh[i] = f ? h : vh[i];
                x[i] = f ? x[i] + dt * h : x[i];
                v[i] = f ? h + hdt * a[i] : v[i];
            }
        }
        if (cont) {
            double *restrict rho = ps->f[RY_F_RHO], *restrict rh = ps->f[w->f_rhoh];
            const double *restrict dr = ps->f[RY_F_DRHO];
#pragma omp for schedule(static) nowait
            for (size_t i = 0; i < n; ++i) {
                const int f = kind[i] == RY_KIND_FLUID;
                const double h = rho[i] + hdt * dr[i];
                rh[i] = f ? h : rh[i];
                rho[i] = f ? h + hdt * dr[i] : rho[i];
            }
        }
        const double *restrict x0 = ps->f[RY_F_X], *restrict x1 = ps->f[RY_F_Y];
        const double *restrict x2 = ps->f[dim > 2 ? RY_F_Z : RY_F_Y];
        const double *restrict r0 = ps->f[sim->f_xref], *restrict r1 = ps->f[sim->f_xref + 1];
        const double *restrict r2 = ps->f[sim->f_xref + (dim > 2 ? 2 : 1)];
        const double z = dim > 2 ? 1.0 : 0.0;
#pragma omp for simd schedule(static) nowait reduction(max : m)
        for (size_t i = 0; i < n; ++i) {
            const double e0 = x0[i] - r0[i], e1 = x1[i] - r1[i], e2 = z * (x2[i] - r2[i]);
            const double q = e0 * e0 + e1 * e1 + e2 * e2;
            m = q > m ? q : m;
        }
    }
    return m;
}

/* The second half kick and the guard check (src/core/guard_check.h) in one region. */
static void fast_final_kick(ry_sim *sim, const wcsph *w, double dt, int cont) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const double hdt = 0.5 * dt;
    const uint8_t *restrict kind = ps->kind;
    ry_check_ctx chk;
    double inv_rho0[256];
    const int uniform = ry_check_init(sim, &chk, inv_rho0);
    const uint8_t *material = ps->material;
    size_t bad = 0, fluid = 0, outside = 0;
#pragma omp parallel
    {
        for (int d = 0; d < dim; ++d) {
            double *restrict v = ps->f[RY_F_VX + d];
            const double *restrict vh = ps->f[w->f_vh[d]], *restrict a = ps->f[RY_F_AX + d];
#pragma omp for schedule(static) nowait
            for (size_t i = 0; i < n; ++i)
                v[i] = kind[i] == RY_KIND_FLUID ? vh[i] + hdt * a[i] : v[i];
        }
        if (cont) {
            double *restrict rho = ps->f[RY_F_RHO];
            const double *restrict rh = ps->f[w->f_rhoh], *restrict dr = ps->f[RY_F_DRHO];
#pragma omp for schedule(static) nowait
            for (size_t i = 0; i < n; ++i)
                rho[i] = kind[i] == RY_KIND_FLUID ? rh[i] + hdt * dr[i] : rho[i];
        }
        const ry_check_ctx c = chk;
        const double inv0 = inv_rho0[0];
        if (uniform && dim == 2) {
#pragma omp for simd schedule(static) nowait reduction(+ : bad, fluid, outside)
            for (size_t i = 0; i < n; ++i) ry_check_tally(&c, i, 2, inv0, &bad, &fluid, &outside);
        } else if (uniform) {
#pragma omp for simd schedule(static) nowait reduction(+ : bad, fluid, outside)
            for (size_t i = 0; i < n; ++i) ry_check_tally(&c, i, 3, inv0, &bad, &fluid, &outside);
        } else {
#pragma omp for schedule(static) nowait reduction(+ : bad, fluid, outside)
            for (size_t i = 0; i < n; ++i)
                ry_check_tally(&c, i, dim, inv_rho0[material[i]], &bad, &fluid, &outside);
        }
    }
    sim->check_bad = bad;
    sim->check_fluid = fluid;
    sim->check_outside = outside;
    sim->checked = 1;
}

static ry_status wcsph_step(ry_sim *sim, void *state, double dt, ry_error *err) {
    wcsph *w = state;
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const int cont = w->density == DENS_CONTINUITY;
    size_t n = ps->n;
    /* Kick (half step) and drift; then predict v and rho at the new time for the forces. The
     * same loop measures the largest displacement since the last neighbour search. */
    if (w->fast) {
        sim->drift2 = fast_kick_drift(sim, w, dt, cont);
        sim->drift_known = 1;
        RY_TRY(evaluate(sim, w, err)); /* may reorder particles: fields move together */
        fast_final_kick(sim, w, dt, cont);
        return RY_OK;
    }
    const double *xref[3];
    for (int d = 0; d < 3; ++d) xref[d] = ps->f[sim->f_xref + (d < dim ? d : 0)];
    double drift2 = 0;
    const int periodic = is_periodic(sim);
#pragma omp parallel for schedule(static) reduction(max : drift2)
    for (size_t i = 0; i < n; ++i) {
        kick_drift(sim, w, i, dt, cont);
        double e[3] = {0, 0, 0}, r2 = 0;
        for (int d = 0; d < dim; ++d) e[d] = ps->f[RY_F_X + d][i] - xref[d][i];
        if (periodic) ry_box_min_image(&sim->box, e); /* a wrapped particle moved little */
        for (int d = 0; d < dim; ++d) r2 += e[d] * e[d];
        drift2 = r2 > drift2 ? r2 : drift2;
    }
    sim->drift2 = drift2;
    sim->drift_known = 1;
    RY_TRY(evaluate(sim, w, err)); /* may reorder particles: fields move together */
    n = ps->n;
    /* The second half kick, and the guard check of the new state in the same pass. */
    ry_check_ctx chk;
    double inv_rho0[256];
    ry_check_init(sim, &chk, inv_rho0);
    size_t bad = 0, fluid = 0, outside = 0;
#pragma omp parallel for schedule(static) reduction(+ : bad, fluid, outside)
    for (size_t i = 0; i < n; ++i) {
        final_kick(sim, w, i, dt, cont);
        ry_check_tally(&chk, i, dim, inv_rho0[ps->material[i]], &bad, &fluid, &outside);
    }
    ry_sph_rheo_advance(&w->rheo, sim, MOBILE, dt); /* polymer stress, with L at t + dt */
    /* Artificial repulsion (scheme.repulsion), from the new positions and velocities. */
    if (w->coll_r > 0) {
        RY_TRY(ry_st_work_ensure(&w->stw, sim->ps.n, err));
        if (sim->par)
            for (int d = 0; d < dim; ++d) {
                sim->par->sync(sim, ps->f[RY_F_X + d], 1);
                sim->par->sync(sim, ps->f[RY_F_VX + d], 1);
            }
        ry_collisions(sim, w->coll_r, w->coll_e, dt, NULL, NULL, w->stw.p);
    }
    sim->check_bad = bad;
    sim->check_fluid = fluid;
    sim->check_outside = outside;
    sim->checked = 1;
    return RY_OK;
}

static int wcsph_vars(void *state, ry_state_var *v, int max) {
    wcsph *w = state;
    const ry_state_var all[] = {{"vmax", &w->vmax, NULL, NULL},
                                {"amax", &w->amax, NULL, NULL},
                                {"numax", &w->numax, NULL, NULL},
                                {"hmax", &w->hmax, NULL, NULL},
                                {"have_forces", NULL, &w->have_forces, NULL}};
    int n = (int)(sizeof all / sizeof all[0]);
    if (n > max) n = max;
    memcpy(v, all, (size_t)n * sizeof *v);
    return n;
}

const ry_scheme_type ry_scheme_wcsph = {
    "wcsph",
    "weakly compressible SPH (Tait/linear/ideal-gas EOS, Adami walls, leapfrog, "
    "free-surface tension)",
    wcsph_init,
    wcsph_dt,
    wcsph_step,
    wcsph_free,
    wcsph_vars,
    NULL,
    NULL};
