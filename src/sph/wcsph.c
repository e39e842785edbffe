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
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/sim.h"
#include "sph/wcsph.h"

enum { DENS_CONTINUITY, DENS_SUMMATION };
enum { EOS_TAIT, EOS_LINEAR, EOS_IDEAL_GAS };
enum { DIFF_NONE, DIFF_MOLTENI, DIFF_FOURTAKAS };
enum { WALL_NO_SLIP, WALL_FREE_SLIP };

typedef struct wcsph {
    int density, eos, diffusion, wall, laminar, energy, variable_h;
    double c0, gamma, p_background, alpha, beta, delta;
    double vmax, amax, numax, hmax; /* from the last force evaluation */
    int have_forces;
    int f_vh[3], f_rhoh, f_eh, f_hh, f_vg[3];
    int f_prho2, f_vol, f_mu, f_cs, f_isfluid, f_visc; /* per-evaluation scratch */
    double *pack; /* PK_STRIDE doubles per particle, rebuilt each evaluation */
    size_t pack_cap;
    int repulse;           /* wall repulsion on */
    double rep_r0, rep_d;  /* its radius and strength */
    int tvf;               /* transport-velocity formulation */
    double p_tvf;          /* its background pressure p_b */
    int f_vt[3], f_abg[3]; /* transport velocity, background-pressure acceleration */
    double *Bm;            /* Tait coefficient per material */
    double *rho0m;         /* reference density per material */
} wcsph;

/* Density in hydrostatic equilibrium under gravity, free surface half a spacing above the
 * highest fluid particle: rho = rho0 (1 + rho0 g (H - z) / B)^(1/gamma) for Tait. */
static void hydrostatic_init(ry_sim *sim, const wcsph *w);

static const char *const density_names[] = {"continuity", "summation", NULL};
static const char *const eos_names[] = {"tait", "linear", "ideal_gas", NULL};
static const char *const diffusion_names[] = {"none", "molteni", "fourtakas", NULL};
static const char *const wall_names[] = {"no_slip", "free_slip", NULL};

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
    if (w->variable_h)
        RY_CHECK(err, w->density == DENS_CONTINUITY, RY_ERR_INPUT,
                 "%s: key 'scheme.variable_h': needs scheme.density: continuity",
                 ry_case_where(c, "scheme.variable_h", where, sizeof where));
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
    RY_TRY(ry_particles_add_field(ps, "p_over_rho2", "m^3/kg", -1, 0, &w->f_prho2, err));
    RY_TRY(ry_particles_add_field(ps, "volume", "m^3", -1, 0, &w->f_vol, err));
    RY_TRY(ry_particles_add_field(ps, "dynamic_viscosity", "Pa s", -1, 0, &w->f_mu, err));
    RY_TRY(ry_particles_add_field(ps, "sound_speed", "m/s", -1, 0, &w->f_cs, err));
    RY_TRY(ry_particles_add_field(ps, "is_fluid", "1", -1, 0, &w->f_isfluid, err));
    RY_TRY(ry_particles_add_field(ps, "viscous_coupling", "1", -1, 0, &w->f_visc, err));

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
    if (hydro) hydrostatic_init(sim, w);
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
    free(w);
}

static inline double eos_pressure(const wcsph *w, int mat, double rho, double e) {
    double rho0 = w->rho0m[mat];
    switch (w->eos) {
    case EOS_TAIT:
        return w->Bm[mat] * (pow(rho / rho0, w->gamma) - 1.0) + w->p_background;
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

static void hydrostatic_init(ry_sim *sim, const wcsph *w) {
    ry_particles *ps = &sim->ps;
    double g2 = 0, up[3] = {0, 0, 0};
    for (int d = 0; d < sim->dim; ++d) g2 += sim->gravity[d] * sim->gravity[d];
    if (g2 <= 0) return;
    double g = sqrt(g2);
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
        int m = ps->material[i];
        double p = w->rho0m[m] * g * (top - z);
        ps->f[RY_F_RHO][i] = eos_density(w, m, p + w->p_background);
    }
}

/* The kernel at a smoothing length other than the reference one (variable h). */
static inline double dwdr_h(const ry_kernel *k, double r, double h) {
    double s = k->h / h, sd = s * s;
    if (k->dim == 3) sd *= s;
    return k->dnorm * sd * s * ry_kernel_dshape(k->type, r / h);
}
static inline double w_h(const ry_kernel *k, double r, double h) {
    double s = k->h / h, sd = s * s;
    if (k->dim == 3) sd *= s;
    return k->norm * sd * ry_kernel_shape(k->type, r / h);
}

/* Density by summation for fluid particles (walls keep their extrapolated density). */
static void density_summation(ry_sim *sim, const wcsph *w) {
    ry_particles *ps = &sim->ps;
    const ry_kernel *k = &sim->kernel;
    const int dim = sim->dim;
    const size_t n = ps->n;
    const double *restrict m = ps->f[RY_F_MASS];
    const double *restrict hh = ps->f[RY_F_H];
    double *restrict rho = ps->f[RY_F_RHO];
    const double *x[3];
    ry_particles_coords(ps, x);
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = sim->nl.j;
    const double rad2 = sim->nl_radius * sim->nl_radius;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        const int numden = w->tvf; /* rho_i = m_i sum_j W_ij (Adami et al. 2013) */
        double s = m[i] * (w->variable_h ? w_h(k, 0.0, hh[i]) : ry_kernel_w(k, 0.0));
        for (size_t q = off[i]; q < off[i + 1]; ++q) {
            uint32_t j = nb[q];
            double dx[3] = {0, 0, 0}, r2 = 0;
            for (int d = 0; d < dim; ++d) dx[d] = x[d][i] - x[d][j];
            ry_box_min_image(&sim->box, dx);
            for (int d = 0; d < dim; ++d) r2 += dx[d] * dx[d];
            if (r2 >= rad2) continue;
            double r = sqrt(r2);
            s += (numden ? m[i] : m[j]) *
                 (w->variable_h ? w_h(k, r, 0.5 * (hh[i] + hh[j])) : ry_kernel_w(k, r));
        }
        rho[i] = s;
    }
}

/* Wall particles: pressure, density and ghost velocity extrapolated from the fluid (Adami et
 * al. 2012, eq. 22-23 and 27-28). */
static void wall_pass(ry_sim *sim, const wcsph *w) {
    ry_particles *ps = &sim->ps;
    const ry_kernel *k = &sim->kernel;
    const int dim = sim->dim;
    const size_t n = ps->n;
    const double *x[3];
    ry_particles_coords(ps, x);
    double *restrict p = ps->f[RY_F_P];
    double *restrict rho = ps->f[RY_F_RHO];
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = sim->nl.j;
    const double *g = sim->gravity;
    const double rad2 = k->radius * k->radius;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_WALL) continue;
        double sw = 0, sp = 0, srx = 0, sv[3] = {0, 0, 0};
        for (size_t q = off[i]; q < off[i + 1]; ++q) {
            uint32_t j = nb[q];
            if (ps->kind[j] != RY_KIND_FLUID) continue;
            double dx[3] = {0, 0, 0}, r2 = 0;
            for (int d = 0; d < dim; ++d) dx[d] = x[d][i] - x[d][j];
            ry_box_min_image(&sim->box, dx);
            for (int d = 0; d < dim; ++d) r2 += dx[d] * dx[d];
            if (r2 >= rad2) continue;
            double wij = ry_kernel_w(k, sqrt(r2));
            double gr = 0;
            for (int d = 0; d < dim; ++d) gr += g[d] * dx[d];
            sw += wij;
            sp += p[j] * wij;
            srx += rho[j] * gr * wij;
            for (int d = 0; d < dim; ++d) sv[d] += ps->f[RY_F_VX + d][j] * wij;
        }
        int mat = ps->material[i];
        if (sw > 0) {
            double pw = (sp + srx) / sw;
            p[i] = pw;
            rho[i] = eos_density(w, mat, pw);
            for (int d = 0; d < dim; ++d)
                ps->f[w->f_vg[d]][i] = 2.0 * ps->f[RY_F_VX + d][i] - sv[d] / sw;
        } else {
            p[i] = w->p_background;
            rho[i] = w->rho0m[mat];
            for (int d = 0; d < dim; ++d) ps->f[w->f_vg[d]][i] = ps->f[RY_F_VX + d][i];
        }
    }
}

typedef struct force_out {
    double amax2, vmax2;
} force_out;

/* Per-particle record read by the pair loop: everything about j in two (2D) or three (3D)
 * cache lines instead of one array per quantity. */
enum {
    PK_X,
    PK_Y,
    PK_Z, /* position */
    PK_U,
    PK_V,
    PK_W, /* velocity (continuity uses the wall's own velocity) */
    PK_UG,
    PK_VG,
    PK_WG, /* velocity seen by viscous terms (ghost velocity on no-slip walls) */
    PK_RHO,
    PK_PRHO2,
    PK_VOL,
    PK_MU,
    PK_CS,
    PK_MASS,
    PK_FLUID,
    PK_VISC,
    PK_H,
    PK_STRIDE = 24
};

/* Monaghan (1994) wall repulsion per unit mass, divided by r^2 (multiplies x_ij), for a pair
 * with `on` set (a wall particle within r0); written without branches for vector loops. */
static inline double wall_repulsion(double r2, int on, double r02, double D) {
    const double q2 = on ? r02 / r2 : 1.0, rr = on ? r2 : 1.0;
    const double q4 = q2 * q2, q12 = q4 * q4 * q4;
    return D * (q12 - q4) / rr;
}

/* Per-particle quantities the pair loop reads (computed once per evaluation, so that the pair
 * loop has no divisions by rho and no branches on the kind of j). */
static ry_status prepare_pairs(ry_sim *sim, wcsph *w, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const int noslip = w->wall == WALL_NO_SLIP;
    double *restrict prho2 = ps->f[w->f_prho2], *restrict vol = ps->f[w->f_vol];
    double *restrict mu = ps->f[w->f_mu], *restrict cs = ps->f[w->f_cs];
    double *restrict isfl = ps->f[w->f_isfluid], *restrict vis = ps->f[w->f_visc];
    const double *restrict rho = ps->f[RY_F_RHO], *restrict p = ps->f[RY_F_P];
    const double *restrict m = ps->f[RY_F_MASS];
    if (w->pack_cap < n) {
        double *pk = realloc(w->pack, n * PK_STRIDE * sizeof(double));
        RY_CHECK(err, pk != NULL, RY_ERR_NOMEM, "out of memory (%zu particles)", n);
        w->pack = pk;
        w->pack_cap = n;
    }
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        const int fluid = ps->kind[i] == RY_KIND_FLUID;
        prho2[i] = p[i] / (rho[i] * rho[i]);
        vol[i] = m[i] / rho[i];
        mu[i] = w->laminar ? rho[i] * sim->mat[ps->material[i]].viscosity : 0.0;
        cs[i] = sound_speed(w, rho[i], p[i]);
        isfl[i] = fluid ? 1.0 : 0.0;
        /* Viscous coupling: fluid, and no-slip walls (through their ghost velocity). */
        vis[i] = (fluid || noslip) ? 1.0 : 0.0;
        /* Velocity seen by viscous terms: the ghost velocity on no-slip walls. */
        if (fluid || !noslip)
            for (int d = 0; d < dim; ++d) ps->f[w->f_vg[d]][i] = ps->f[RY_F_VX + d][i];
        double *restrict P = w->pack + i * PK_STRIDE;
        for (int d = 0; d < 3; ++d) {
            P[PK_X + d] = d < dim ? ps->f[RY_F_X + d][i] : 0.0;
            P[PK_U + d] = d < dim ? ps->f[RY_F_VX + d][i] : 0.0;
            P[PK_UG + d] = d < dim ? ps->f[w->f_vg[d]][i] : 0.0;
        }
        P[PK_RHO] = rho[i];
        P[PK_PRHO2] = prho2[i];
        P[PK_VOL] = vol[i];
        P[PK_MU] = mu[i];
        P[PK_CS] = cs[i];
        P[PK_MASS] = m[i];
        P[PK_FLUID] = isfl[i];
        P[PK_VISC] = vis[i];
        P[PK_H] = ps->f[RY_F_H][i];
    }
    return RY_OK;
}

/* Accelerations and rates of fluid particles. dim and the kernel type are literals at each call
 * site, so the loop is compiled once per (dimension, kernel) with the kernel inlined. */
static inline __attribute__((always_inline)) void
fluid_pass(ry_sim *sim, const wcsph *w, const int dim, const ry_kernel_type kt, force_out *res) {
    ry_particles *ps = &sim->ps;
    const ry_kernel *k = &sim->kernel;
    const size_t n = ps->n;
    double *a[3];
    for (int d = 0; d < 3; ++d) a[d] = ps->f[RY_F_AX + d];
    const double *restrict pack = w->pack;
    double *restrict drho = ps->f[RY_F_DRHO];
    double *restrict de = ps->f[RY_F_DE];
    const uint8_t *restrict kind = ps->kind;
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = sim->nl.j;
    const double h0 = k->h, eta2 = 0.01 * h0 * h0, inv_h0 = 1.0 / h0;
    const double dnorm_h = k->dnorm * inv_h0; /* (dW/dr) / r = dnorm_h f'(q)/q */
    const double rad2 = sim->nl_radius * sim->nl_radius;
    const double *g = sim->gravity;
    const int cont = w->density == DENS_CONTINUITY;
    const int varh = w->variable_h, energy = w->energy;
    const double diff = w->diffusion != DIFF_NONE ? 2.0 * w->delta * h0 * w->c0 : 0.0;
    const int fourtakas = w->diffusion == DIFF_FOURTAKAS;
    const double alpha = w->alpha, beta = w->beta;
    const int periodic = sim->box.periodic[0] || sim->box.periodic[1] || sim->box.periodic[2];
    const double inv_c02 = 1.0 / (w->c0 * w->c0);
    const double rep_d = w->rep_d, rep_r02 = rep_d > 0 ? w->rep_r0 * w->rep_r0 : 0.0;
    const double *rho0m = w->rho0m;
    double amax2 = 0, vmax2 = 0;
#pragma omp parallel for schedule(dynamic, 64) reduction(max : amax2, vmax2)
    for (size_t i = 0; i < n; ++i) {
        if (kind[i] != RY_KIND_FLUID) continue;
        const double *restrict Pi = pack + i * PK_STRIDE;
        const double rhoi = Pi[PK_RHO], pri = Pi[PK_PRHO2], mui = Pi[PK_MU], ci = Pi[PK_CS];
        const double hi = Pi[PK_H];
        const double inv_rhoi = 1.0 / rhoi;
        const double fh = fourtakas ? rho0m[ps->material[i]] * inv_c02 : 0.0;
        /* Scalars, not arrays, so that accumulators stay in registers; z terms vanish at
         * compile time in 2D. */
        const double xi = Pi[PK_X], yi = Pi[PK_Y], zi = dim > 2 ? Pi[PK_Z] : 0.0;
        const double ui = Pi[PK_U], vi = Pi[PK_V], wi = dim > 2 ? Pi[PK_W] : 0.0;
        const double gx = g[0], gy = g[1], gz = dim > 2 ? g[2] : 0.0;
        double ax = 0, ay = 0, az = 0, dr = 0, dd = 0, dei = 0;
        for (size_t q = off[i]; q < off[i + 1]; ++q) {
            const double *restrict Pj = pack + (size_t)nb[q] * PK_STRIDE;
            double dxv[3] = {xi - Pj[PK_X], yi - Pj[PK_Y], dim > 2 ? zi - Pj[PK_Z] : 0.0};
            if (periodic) ry_box_min_image(&sim->box, dxv);
            const double dx = dxv[0], dy = dxv[1], dz = dxv[2];
            const double r2 = dx * dx + dy * dy + dz * dz;
            if (r2 >= rad2 || r2 <= 0) continue; /* outside the support (Verlet skin) */
            double fw;
            if (varh) {
                const double r = sqrt(r2);
                fw = dwdr_h(k, r, 0.5 * (hi + Pj[PK_H])) / r;
            } else {
                fw = dnorm_h * ry_kernel_dshape_over_q(kt, sqrt(r2) * inv_h0);
            }
            const double uj = Pj[PK_U], vj = Pj[PK_V], wj = dim > 2 ? Pj[PK_W] : 0.0;
            const double ugj = Pj[PK_UG], vgj = Pj[PK_VG], wgj = dim > 2 ? Pj[PK_WG] : 0.0;
            const double vx = ui - ugj, vy = vi - vgj, vz = wi - wgj;
            const double vdx = vx * dx + vy * dy + vz * dz;
            const double vdw = (ui - uj) * dx + (vi - vj) * dy + (wi - wj) * dz;
            const double ieta = 1.0 / (r2 + eta2);
            /* Monaghan's artificial viscosity, active for approaching pairs only. */
            const double mu_ij = h0 * (vdx < 0.0 ? vdx : 0.0) * ieta;
            const double rhoj = Pj[PK_RHO], volj = Pj[PK_VOL], isj = Pj[PK_FLUID];
            const double prj = Pj[PK_PRHO2];
            const double pi_ij = (-alpha * 0.5 * (ci + Pj[PK_CS]) * mu_ij + beta * mu_ij * mu_ij) *
                                 2.0 / (rhoi + rhoj);
            const double mj = Pj[PK_MASS];
            const double fp = -mj * (pri + prj + pi_ij) * fw;
            /* Morris et al. (1997) laminar viscosity (a wall takes the fluid's viscosity). */
            const double muj = isj > 0.0 ? Pj[PK_MU] : mui;
            const double fv = Pj[PK_VISC] * volj * (mui + muj) * inv_rhoi * fw * r2 * ieta;
            /* Wall repulsion, the rare case of a fluid particle very close to a wall. */
            const double fr = wall_repulsion(r2, isj == 0.0 && r2 < rep_r02, rep_r02, rep_d);
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
            a[d][i] = ai[d];
            a2 += ai[d] * ai[d];
            v2 += vi3[d] * vi3[d];
        }
        if (cont) drho[i] = rhoi * dr + diff * dd;
        if (energy) de[i] = dei;
        amax2 = fmax(amax2, a2);
        vmax2 = fmax(vmax2, v2);
    }
    res->amax2 = amax2;
    res->vmax2 = vmax2;
}

/* Transport-velocity formulation (Adami, Hu & Adams 2013, eq. 8 and 13): pressure with the
 * density-weighted inter-particle average, the extra stress A = rho v (v~ - v), the viscous
 * term with the inter-particle averaged viscosity, and the background-pressure acceleration
 * that moves particles with v~. V_i = m_i / rho_i. */
static inline __attribute__((always_inline)) void fluid_pass_tvf(ry_sim *sim, const wcsph *w,
                                                                 const int dim, force_out *res) {
    ry_particles *ps = &sim->ps;
    const ry_kernel *k = &sim->kernel;
    const size_t n = ps->n;
    const double *x[3], *v[3], *vg[3], *vt[3];
    double *a[3], *ab[3];
    ry_particles_coords(ps, x);
    for (int d = 0; d < 3; ++d) {
        v[d] = ps->f[RY_F_VX + d];
        vg[d] = ps->f[w->f_vg[d]];
        vt[d] = ps->f[w->f_vt[d]];
        a[d] = ps->f[RY_F_AX + d];
        ab[d] = ps->f[w->f_abg[d]];
    }
    const double *restrict m = ps->f[RY_F_MASS];
    const double *restrict rho = ps->f[RY_F_RHO];
    const double *restrict p = ps->f[RY_F_P];
    const double *restrict vol = ps->f[w->f_vol];
    const double *restrict mu = ps->f[w->f_mu];
    const double *restrict isfl = ps->f[w->f_isfluid];
    const double *restrict vis = ps->f[w->f_visc];
    const uint8_t *restrict kind = ps->kind;
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = sim->nl.j;
    const double rad2 = sim->nl_radius * sim->nl_radius;
    const double pb = w->p_tvf;
    const double *g = sim->gravity;
    const int periodic = sim->box.periodic[0] || sim->box.periodic[1] || sim->box.periodic[2];
    double amax2 = 0, vmax2 = 0;
#pragma omp parallel for schedule(dynamic, 64) reduction(max : amax2, vmax2)
    for (size_t i = 0; i < n; ++i) {
        if (kind[i] != RY_KIND_FLUID) continue;
        const double rhoi = rho[i], pi = p[i], mui = mu[i], vi2 = vol[i] * vol[i];
        double ai[3] = {0, 0, 0}, bi[3] = {0, 0, 0}, Ai[3], v2 = 0;
        /* A_i = rho_i v_i (v~_i - v_i), a tensor; A_i . grad W = rho_i v_i ((v~_i - v_i).gradW) */
        for (int d = 0; d < dim; ++d) {
            Ai[d] = vt[d][i] - v[d][i];
            v2 += v[d][i] * v[d][i];
        }
        for (size_t q = off[i]; q < off[i + 1]; ++q) {
            const uint32_t j = nb[q];
            double dx[3] = {0, 0, 0}, r2 = 0;
            for (int d = 0; d < dim; ++d) dx[d] = x[d][i] - x[d][j];
            if (periodic) ry_box_min_image(&sim->box, dx);
            for (int d = 0; d < dim; ++d) r2 += dx[d] * dx[d];
            if (r2 >= rad2 || r2 <= 0) continue;
            const double r = sqrt(r2);
            const double fw = ry_kernel_dwdr(k, r) / r; /* grad W = fw dx */
            const double rhoj = rho[j], vv = vi2 + vol[j] * vol[j];
            const double pij = (rhoj * pi + rhoi * p[j]) / (rhoi + rhoj);
            const int fj = isfl[j] > 0.0;
            const double muj = fj ? mu[j] : mui;
            const double etaij = (mui + muj) > 0 ? 2.0 * mui * muj / (mui + muj) : 0.0;
            /* (A_i + A_j)/2 . grad W; walls carry no extra stress. */
            double adi = 0, adj = 0;
            for (int d = 0; d < dim; ++d) {
                adi += Ai[d] * dx[d];
                if (fj) adj += (vt[d][j] - v[d][j]) * dx[d];
            }
            adi *= fw;
            adj *= fw;
            const double fr = wall_repulsion(r2, !fj && r2 < w->rep_r0 * w->rep_r0,
                                             w->rep_r0 * w->rep_r0, w->rep_d) *
                              m[i] / vv;
            for (int d = 0; d < dim; ++d) {
                const double vij = v[d][i] - vg[d][j];
                double f = -pij * fw * dx[d] + fr * dx[d];
                f += 0.5 * (rhoi * v[d][i] * adi + (fj ? rhoj * v[d][j] * adj : 0.0));
                f += vis[j] * etaij * vij * fw; /* eta_ij v_ij (1/r) dW/dr */
                ai[d] += vv * f;
                bi[d] += vv * fw * dx[d];
            }
        }
        double a2 = 0;
        for (int d = 0; d < dim; ++d) {
            ai[d] = ai[d] / m[i] + g[d];
            a[d][i] = ai[d];
            ab[d][i] = -pb / m[i] * bi[d];
            a2 += ai[d] * ai[d];
        }
        amax2 = fmax(amax2, a2);
        vmax2 = fmax(vmax2, v2);
    }
    res->amax2 = amax2;
    res->vmax2 = vmax2;
}

/* Picks the specialised pair loop. */
static void fluid_forces(ry_sim *sim, const wcsph *w, force_out *res) {
    if (w->tvf) {
        if (sim->dim == 2)
            fluid_pass_tvf(sim, w, 2, res);
        else
            fluid_pass_tvf(sim, w, 3, res);
        return;
    }
#define RY_WCSPH_CASE_(kt)                                                                         \
    case kt:                                                                                       \
        if (sim->dim == 2)                                                                         \
            fluid_pass(sim, w, 2, kt, res);                                                        \
        else                                                                                       \
            fluid_pass(sim, w, 3, kt, res);                                                        \
        break;
    switch (sim->kernel.type) {
        RY_WCSPH_CASE_(RY_KERNEL_CUBIC)
        RY_WCSPH_CASE_(RY_KERNEL_QUINTIC)
        RY_WCSPH_CASE_(RY_KERNEL_WENDLAND_C2)
        RY_WCSPH_CASE_(RY_KERNEL_WENDLAND_C4)
        RY_WCSPH_CASE_(RY_KERNEL_LUCY)
        RY_WCSPH_CASE_(RY_KERNEL_GAUSSIAN)
    default:
        break;
    }
#undef RY_WCSPH_CASE_
}

/* Evaluates all rates at the current (predicted) state. */
static ry_status evaluate(ry_sim *sim, wcsph *w, ry_error *err) {
    ry_particles *ps = &sim->ps;
    double hmax = sim->kernel.h;
    if (w->variable_h) {
        for (size_t i = 0; i < ps->n; ++i) hmax = fmax(hmax, ps->f[RY_F_H][i]);
    }
    w->hmax = hmax;
    RY_TRY(ry_sim_neighbors(sim, sim->kernel.kappa * hmax, err));
    if (w->density == DENS_SUMMATION) density_summation(sim, w);
    const size_t n = ps->n;
    double *p = ps->f[RY_F_P];
    const double *rho = ps->f[RY_F_RHO], *e = ps->f[RY_F_E];
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i)
        if (ps->kind[i] == RY_KIND_FLUID) p[i] = eos_pressure(w, ps->material[i], rho[i], e[i]);
    wall_pass(sim, w);
    RY_TRY(prepare_pairs(sim, w, err));
    force_out res;
    fluid_forces(sim, w, &res);
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
    if (numax > 0 && w->laminar) t = fmin(t, 0.125 * h * h / numax);
    *dt = t;
    return RY_OK;
}

static ry_status wcsph_step(ry_sim *sim, void *state, double dt, ry_error *err) {
    wcsph *w = state;
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const int cont = w->density == DENS_CONTINUITY;
    size_t n = ps->n;
    /* Kick (half step) and drift; then predict v and rho at the new time for the forces. */
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
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
            ps->f[RY_F_VX + d][i] = vh + 0.5 * dt * ps->f[RY_F_AX + d][i];
        }
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
    RY_TRY(evaluate(sim, w, err)); /* may reorder particles: fields move together */
    n = ps->n;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        for (int d = 0; d < dim; ++d)
            ps->f[RY_F_VX + d][i] = ps->f[w->f_vh[d]][i] + 0.5 * dt * ps->f[RY_F_AX + d][i];
        if (cont) ps->f[RY_F_RHO][i] = ps->f[w->f_rhoh][i] + 0.5 * dt * ps->f[RY_F_DRHO][i];
        if (w->energy) ps->f[RY_F_E][i] = ps->f[w->f_eh][i] + 0.5 * dt * ps->f[RY_F_DE][i];
        if (w->variable_h) {
            double dh = -ps->f[RY_F_H][i] / (dim * ps->f[RY_F_RHO][i]) * ps->f[RY_F_DRHO][i];
            ps->f[RY_F_H][i] = ps->f[w->f_hh][i] + 0.5 * dt * dh;
        }
    }
    return RY_OK;
}

const ry_scheme_type ry_scheme_wcsph = {
    "wcsph",    "weakly compressible SPH (Tait/linear/ideal-gas EOS, Adami walls, leapfrog)",
    wcsph_init, wcsph_dt,
    wcsph_step, wcsph_free};
