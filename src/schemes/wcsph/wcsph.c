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
 *             dt = min(CFL h / (c0 + |v|max), 0.25 sqrt(h / |a|max), 0.125 h^2 / nu).
 *
 * This file: the scheme's keys and state, its registration. The passes: wcsph_walls.c (wall
 * pressure), wcsph_list.c (neighbour-list pair loop, double precision), wcsph_cells.c
 * (cell-range pair loop, single precision), wcsph_tvf.c (transport velocity, density
 * summation), wcsph_step.c (evaluation, time step, leapfrog, rheology and surface tension);
 * wcsph_internal.h holds what they share. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "schemes/wcsph/wcsph.h"
#include "schemes/wcsph/wcsph_internal.h"

/* Density in hydrostatic equilibrium under gravity, free surface half a spacing above the
 * highest fluid particle: rho = rho0 (1 + rho0 g (H - z) / B)^(1/gamma) for Tait. */
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

static const char *const density_names[] = {"continuity", "summation", NULL};
static const char *const eos_names[] = {"tait", "linear", "ideal_gas", NULL};
static const char *const diffusion_names[] = {"none", "molteni", "fourtakas", NULL};
static const char *const wall_names[] = {"no_slip", "free_slip", NULL};
enum { LOOP_AUTO, LOOP_CELLS, LOOP_LIST };
static const char *const loop_names[] = {"auto", "cells", "list", NULL};
static const char *const viscosity_correction_names[] = {"none", "lattice", NULL};

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
     * 0.979); the transport-velocity form has no 0.01 h^2 (docs/reference/wcsph.md). */
    const double dxd = sim->dim > 2 ? sim->dx * sim->dx * sim->dx : sim->dx * sim->dx;
    const double eta2 = w->tvf ? 0.0 : ry_morris_eta2(sim->kernel.h);
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
    w->fast = loop != LOOP_LIST && wc_fast_eligible(sim, w, &why);
    if (loop == LOOP_CELLS)
        RY_CHECK(err, w->fast, RY_ERR_INPUT, "%s: key 'scheme.pair_loop': 'cells' needs %s",
                 ry_case_where(c, "scheme.pair_loop", where, sizeof where), why);
    w->rng_gen = -1;
    if (w->eos == EOS_IDEAL_GAS)
        RY_CHECK(err, w->energy, RY_ERR_INPUT,
                 "%s: key 'scheme.eos': ideal_gas needs scheme.energy: true",
                 ry_case_where(c, "scheme.eos", where, sizeof where));

    ry_particles *ps = &sim->ps;
    static const char *const vh[3] = {"vhalf_x", "vhalf_y", "vhalf_z"};
    static const char *const vg[3] = {"vwall_x", "vwall_y", "vwall_z"};
    w->lean = wc_lean(w);
    for (int d = 0; d < 3; ++d) {
        w->f_vh[d] = -1; /* (the plain cell-range loop keeps no half-step fields: wc_lean) */
        if (!w->lean)
            RY_TRY(ry_particles_add_field(ps, vh[d], "m/s", d, RY_FIELD_SCRATCH, &w->f_vh[d], err));
        /* (the cell-range loop keeps the walls' ghost velocities in its records) */
        w->f_vg[d] = -1;
        if (!w->fast) RY_TRY(ry_particles_add_field(ps, vg[d], "m/s", d, 0, &w->f_vg[d], err));
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
    w->f_rhoh = -1;
    if (!w->lean)
        RY_TRY(ry_particles_add_field(ps, "density_half", "kg/m^3", -1, RY_FIELD_SCRATCH,
                                      &w->f_rhoh, err));
    w->f_eh = w->f_hh = -1; /* (only where they are integrated) */
    if (w->energy)
        RY_TRY(
            ry_particles_add_field(ps, "energy_half", "J/kg", -1, RY_FIELD_SCRATCH, &w->f_eh, err));
    if (w->variable_h)
        RY_TRY(ry_particles_add_field(ps, "h_half", "m", -1, RY_FIELD_SCRATCH, &w->f_hh, err));
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
    /* Initial pressure from the density (zero for a fluid at rest at rho0); energy for gases;
     * the smoothing length where it varies. */
    for (size_t i = 0; i < ps->n; ++i) ps->f[RY_F_P][i] = 0;
    if (w->energy) {
        RY_TRY(ry_particles_use_field(ps, RY_F_E, err));
        RY_TRY(ry_particles_use_field(ps, RY_F_DE, err));
    }
    if (w->variable_h) {
        RY_TRY(ry_particles_use_field(ps, RY_F_H, err));
        for (size_t i = 0; i < ps->n; ++i) ps->f[RY_F_H][i] = sim->kernel.h;
    }
    int hydro;
    RY_TRY(ry_case_bool(c, "scheme.hydrostatic_init", &no, &hydro, err));
    if (hydro) RY_TRY(hydrostatic_init(sim, w, err));
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

/* The cell-range loop sorts by cell at every search and, with the continuity equation, needs
 * no list. Its default Verlet skin: its candidates grow with the square (cube) of support +
 * skin, while a search (sort, reorder, candidate ranges) costs about two steps' worth of
 * element-wise passes. Over whole dam breaks on one thread, 10 % in 2D was about 10 % faster
 * than 5 % (the seed case at 40x80, 0.6 s: a search every second step late in the run at 5 %),
 * while in 3D 5 % was about 20 % faster than 10 %. */
static void wcsph_needs(const ry_sim *sim, const void *state, ry_scheme_needs *nd) {
    const wcsph *w = state;
    nd->sort_always = w->fast;
    nd->cells_only = w->fast && w->density == DENS_CONTINUITY;
    if (w->fast) nd->skin = sim->dim > 2 ? 0.05 : 0.1;
    /* A sound run stays far below the sound speed and within a few per cent of the reference
     * density; beyond these it has failed (checked every step; case section `guard`). */
    if (w->eos != EOS_IDEAL_GAS) {
        nd->max_speed = w->c0;
        nd->rho_min = 0.5;
        nd->rho_max = 2.0;
    }
}

const ry_scheme_type ry_scheme_wcsph = {
    .name = "wcsph",
    .summary = "weakly compressible SPH (Tait/linear/ideal-gas EOS, Adami walls, leapfrog, "
               "free-surface tension)",
    .init = wcsph_init,
    .stable_dt = wc_dt,
    .step = wc_step,
    .free = wcsph_free,
    .state_vars = wcsph_vars,
    .needs = wcsph_needs,
    .bytes = wc_bytes,
    .caps = RY_SCHEME_RHEOLOGY};
