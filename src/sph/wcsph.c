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
    double *Bm;    /* Tait coefficient per material */
    double *rho0m; /* reference density per material */
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
    RY_TRY(ry_case_double(c, "scheme.background_pressure", &zero, 0.0, INFINITY,
                          &w->p_background, err));
    RY_TRY(ry_case_double(c, "scheme.artificial_viscosity.alpha", &alpha, 0.0, 10.0, &w->alpha,
                          err));
    RY_TRY(ry_case_double(c, "scheme.artificial_viscosity.beta", &zero, 0.0, 10.0, &w->beta, err));
    RY_TRY(ry_case_bool(c, "scheme.laminar_viscosity", &yes, &w->laminar, err));
    RY_TRY(ry_case_choice(c, "scheme.density_diffusion", "none", diffusion_names, &w->diffusion,
                          err));
    RY_TRY(ry_case_double(c, "scheme.delta", &delta, 0.0, 1.0, &w->delta, err));
    RY_TRY(ry_case_bool(c, "scheme.energy", &no, &w->energy, err));
    RY_TRY(ry_case_bool(c, "scheme.variable_h", &no, &w->variable_h, err));
    RY_TRY(ry_case_choice(c, "scheme.wall", "no_slip", wall_names, &w->wall, err));
    char where[256];
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
    RY_TRY(ry_particles_add_field(ps, "density_half", "kg/m^3", -1, RY_FIELD_STATE, &w->f_rhoh,
                                  err));
    RY_TRY(ry_particles_add_field(ps, "energy_half", "J/kg", -1, RY_FIELD_STATE, &w->f_eh, err));
    RY_TRY(ry_particles_add_field(ps, "h_half", "m", -1, RY_FIELD_STATE, &w->f_hh, err));

    w->Bm = calloc((size_t)sim->nmat, sizeof *w->Bm);
    w->rho0m = calloc((size_t)sim->nmat, sizeof *w->rho0m);
    RY_CHECK(err, w->Bm && w->rho0m, RY_ERR_NOMEM, "out of memory");
    for (int m = 0; m < sim->nmat; ++m) {
        w->rho0m[m] = sim->mat[m].density;
        w->Bm[m] = w->c0 * w->c0 * w->rho0m[m] / w->gamma;
    }
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
    free(w);
}

static inline double eos_pressure(const wcsph *w, int mat, double rho, double e) {
    double rho0 = w->rho0m[mat];
    switch (w->eos) {
    case EOS_TAIT: return w->Bm[mat] * (pow(rho / rho0, w->gamma) - 1.0) + w->p_background;
    case EOS_LINEAR: return w->c0 * w->c0 * (rho - rho0) + w->p_background;
    default: return (w->gamma - 1.0) * rho * e;
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
    case EOS_LINEAR: return fmax(rho0 + q / (w->c0 * w->c0), 1e-3 * rho0);
    default: return rho0;
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
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        double s = m[i] * (w->variable_h ? w_h(k, 0.0, hh[i]) : ry_kernel_w(k, 0.0));
        for (size_t q = off[i]; q < off[i + 1]; ++q) {
            uint32_t j = nb[q];
            double dx[3] = {0, 0, 0}, r2 = 0;
            for (int d = 0; d < dim; ++d) dx[d] = x[d][i] - x[d][j];
            ry_box_min_image(&sim->box, dx);
            for (int d = 0; d < dim; ++d) r2 += dx[d] * dx[d];
            double r = sqrt(r2);
            s += m[j] * (w->variable_h ? w_h(k, r, 0.5 * (hh[i] + hh[j])) : ry_kernel_w(k, r));
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

/* Accelerations and rates for fluid particles; dim is a literal at each call site so that the
 * loops are specialised. */
static inline __attribute__((always_inline)) void fluid_pass(ry_sim *sim, const wcsph *w,
                                                             const int dim, force_out *res) {
    ry_particles *ps = &sim->ps;
    const ry_kernel *k = &sim->kernel;
    const size_t n = ps->n;
    const double *x[3], *v[3], *vg[3];
    double *a[3];
    ry_particles_coords(ps, x);
    for (int d = 0; d < 3; ++d) {
        v[d] = ps->f[RY_F_VX + d];
        vg[d] = ps->f[w->f_vg[d]];
        a[d] = ps->f[RY_F_AX + d];
    }
    const double *restrict m = ps->f[RY_F_MASS];
    const double *restrict rho = ps->f[RY_F_RHO];
    const double *restrict p = ps->f[RY_F_P];
    const double *restrict hh = ps->f[RY_F_H];
    double *restrict drho = ps->f[RY_F_DRHO];
    double *restrict de = ps->f[RY_F_DE];
    const uint8_t *restrict kind = ps->kind;
    const uint8_t *restrict mat = ps->material;
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = sim->nl.j;
    const double h0 = k->h, eta2 = 0.01 * h0 * h0;
    const double *g = sim->gravity;
    const int cont = w->density == DENS_CONTINUITY;
    const int noslip = w->wall == WALL_NO_SLIP;
    const double diff = w->diffusion != DIFF_NONE ? 2.0 * w->delta * h0 * w->c0 : 0.0;
    const int fourtakas = w->diffusion == DIFF_FOURTAKAS;
    const double alpha = w->alpha, beta = w->beta;
    const int periodic = sim->box.periodic[0] || sim->box.periodic[1] || sim->box.periodic[2];
    double amax2 = 0, vmax2 = 0;
#pragma omp parallel for schedule(static) reduction(max : amax2, vmax2)
    for (size_t i = 0; i < n; ++i) {
        if (kind[i] != RY_KIND_FLUID) continue;
        const double rhoi = rho[i], pi = p[i], hi = hh[i];
        const double pri = pi / (rhoi * rhoi);
        const double mui = rhoi * sim->mat[mat[i]].viscosity;
        const double ci = sound_speed(w, rhoi, pi);
        const double rho0i = w->rho0m[mat[i]];
        double ai[3] = {0, 0, 0}, dr = 0, dd = 0, dei = 0;
        for (size_t q = off[i]; q < off[i + 1]; ++q) {
            const uint32_t j = nb[q];
            double dx[3] = {0, 0, 0}, r2 = 0;
            for (int d = 0; d < dim; ++d) dx[d] = x[d][i] - x[d][j];
            if (periodic) ry_box_min_image(&sim->box, dx);
            for (int d = 0; d < dim; ++d) r2 += dx[d] * dx[d];
            if (r2 <= 0) continue;
            const double r = sqrt(r2);
            const double fw = w->variable_h ? dwdr_h(k, r, 0.5 * (hi + hh[j])) / r
                                            : ry_kernel_dwdr(k, r) / r;
            const int wallj = kind[j] != RY_KIND_FLUID;
            const double rhoj = rho[j], pj = p[j], mj = m[j];
            /* Velocity of j: the ghost velocity of a no-slip wall for viscous terms. */
            double vij[3] = {0, 0, 0}, vdx = 0;
            const int visc_ghost = wallj && noslip;
            for (int d = 0; d < dim; ++d) {
                vij[d] = v[d][i] - (visc_ghost ? vg[d][j] : v[d][j]);
                vdx += vij[d] * dx[d];
            }
            double pi_ij = 0;
            if (vdx < 0 && (alpha > 0 || beta > 0)) {
                const double hij = w->variable_h ? 0.5 * (hi + hh[j]) : h0;
                const double mu = hij * vdx / (r2 + 0.01 * hij * hij);
                const double cij = 0.5 * (ci + sound_speed(w, rhoj, pj));
                pi_ij = (-alpha * cij * mu + beta * mu * mu) / (0.5 * (rhoi + rhoj));
            }
            const double fp = -mj * (pri + pj / (rhoj * rhoj) + pi_ij) * fw;
            for (int d = 0; d < dim; ++d) ai[d] += fp * dx[d];
            if (mui > 0 && (!wallj || noslip)) {
                const double muj = wallj ? mui : rhoj * sim->mat[mat[j]].viscosity;
                const double fv = mj * (mui + muj) / (rhoi * rhoj) * fw * r2 / (r2 + eta2);
                for (int d = 0; d < dim; ++d) ai[d] += fv * vij[d];
            }
            if (cont) {
                /* Continuity with the wall's own (prescribed) velocity. */
                double vdw = 0;
                for (int d = 0; d < dim; ++d) vdw += (v[d][i] - v[d][j]) * dx[d];
                dr += mj / rhoj * vdw * fw;
                if (diff > 0 && !wallj) {
                    double drj = rhoj - rhoi;
                    if (fourtakas) {
                        double gdx = 0;
                        for (int d = 0; d < dim; ++d) gdx += g[d] * dx[d];
                        drj += rho0i * gdx / (w->c0 * w->c0);
                    }
                    dd += -drj * fw * r2 / (r2 + eta2) * mj / rhoj;
                }
            }
            if (w->energy) dei += 0.5 * mj * (pri + pj / (rhoj * rhoj) + pi_ij) * vdx * fw;
        }
        double a2 = 0, v2 = 0;
        for (int d = 0; d < dim; ++d) {
            ai[d] += g[d];
            a[d][i] = ai[d];
            a2 += ai[d] * ai[d];
            v2 += v[d][i] * v[d][i];
        }
        if (cont) drho[i] = rhoi * dr + diff * dd;
        if (w->energy) de[i] = dei;
        amax2 = fmax(amax2, a2);
        vmax2 = fmax(vmax2, v2);
    }
    res->amax2 = amax2;
    res->vmax2 = vmax2;
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
    force_out res;
    if (sim->dim == 2)
        fluid_pass(sim, w, 2, &res);
    else
        fluid_pass(sim, w, 3, &res);
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
            ps->f[RY_F_X + d][i] += dt * vh;
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
    "wcsph", "weakly compressible SPH (Tait/linear/ideal-gas EOS, Adami walls, leapfrog)",
    wcsph_init, wcsph_dt, wcsph_step, wcsph_free};
