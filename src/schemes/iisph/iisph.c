/* Implicit incompressible SPH (seed 004, SPEC section 4; docs/reference/iisph.md).
 *
 * Ihmsen, Cornelis, Solenthaler, Horvath & Teschner (2014), "Implicit incompressible SPH",
 * IEEE TVCG 20: 426, written in the number-density form of Hu & Adams (2006), J. Comput. Phys.
 * 213: 844, so that two fluids of very different density share one formulation:
 *
 *  number density  delta_i = sum_j W_ij (fluid and wall neighbours, self included); volume
 *                  V_i = 1 / delta_i; density rho_i = m_i delta_i (seed eq. 6 for equal masses)
 *  constraint      delta_i = delta_0, the number density of the initial lattice, the same for
 *                  every phase (masses are m_i = rho0_i / delta_0)
 *  pressure force  a^p_i = -(1/m_i) sum_j (p_i / delta_i^2 + p_j / delta_j^2) grad_i W_ij
 *                  (Hu & Adams 2006, eq. 8); wall particles take part with the pressure
 *                  extrapolated from the fluid (Adami, Hu & Adams 2012, eq. 27), updated
 *                  in every iteration of the solve, and the volume of the fluid particle
 *  viscosity       artificial Laplacian of seed eq. 5 with the harmonic mean of the dynamic
 *                  viscosities: a^v_i = (2 (d + 2) / rho_i) sum_j V_j mu_ij
 *                  (v_ij . x_ij) / (r_ij^2 + 0.01 h^2) grad_i W_ij, mu_ij = 2 mu_i mu_j / (mu_i
 *                  + mu_j) (V_j = V_i for walls, which carry the wall velocity: no slip)
 *  surface force   colour field (multiphase.h, seed eq. 7-8)
 *  solve           v* = v + dt (g + a^v + a^s); predicted delta*_i = delta_i + dt sum_j
 *                  (v*_i - v*_j) . grad_i W_ij; relaxed Jacobi on
 *                  sum_j (D_i - D_j) . grad_i W_ij = delta_0 - delta*_i, D_i = dt^2 a^p_i,
 *                  p_i <- max(0, (1 - omega) p_i + omega (delta_0 - delta*_i - rest_i) / a_ii)
 *                  (Ihmsen et al. 2014, eq. 12-17); warm start p^0 = w p(t - dt); stops
 *                  when the average density error is below the tolerance (after at least
 *                  min_iterations)
 *  light phase     a material lighter than 0.05 of the heaviest (air) solved with the heavy
 *                  particles as moving walls, and left out of the heavy phase's sums
 *                  (scheme.light_phase: boundary; docs/reference/iisph.md, "A light phase")
 *  time            symplectic Euler: v = v* + dt a^p, x += dt v;
 *                  dt = min(CFL h / |v|max, 0.25 sqrt(h / |a|max), 0.045 h^2 / nu_max,
 *                  surface-tension limit, dt_max).
 *
 * This file: the keys of the case, the state, the time step and the step as its sequence of
 * passes (iisph_step). The passes: iisph_viscosity.c (number density, the non-pressure forces,
 * implicit viscosity), iisph_surface.c (free-surface tension), iisph_walls.c (the walls'
 * pressure), iisph_pressure.c (the pressure solve and the pressure force); the light phase's
 * set-up in iisph_light.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/sparse.h"
#include "ryushi/sim.h"
#include "ryushi/surface_tension.h"
#include "schemes/iisph/iisph.h"
#include "schemes/iisph/iisph_internal.h"
#include "physics/colour_field.h"
#include "pairs/pair_cache.h"
#include "physics/polymer_stress.h"
#include "ryushi/collisions.h"
#include "ryushi/rheology.h"

static ry_status iisph_init(ry_sim *sim, ry_case *c, void **state, ry_error *err) {
    iisph *s = calloc(1, sizeof *s);
    RY_CHECK(err, s != NULL, RY_ERR_NOMEM, "out of memory");
    *state = s;
    /* Relaxation: 0.5 (Ihmsen et al. 2014) diverges in 3D with the Wendland C2 kernel at
     * h = 1.4 dx (about 130 neighbours; the 3D dam break blows up at the first steps), 0.35
     * converges; 0.3 is the 3D default. */
    double omega = sim->dim == 3 ? 0.3 : 0.5, tol = 1e-3, warm = 0.5;
    long maxit = 200, minit = 2;
    RY_TRY(ry_case_double(c, "scheme.relaxation", &omega, 0.05, 1.0, &s->omega, err));
    RY_TRY(ry_case_double(c, "scheme.tolerance", &tol, 1e-7, 0.1, &s->tol, err));
    RY_TRY(ry_case_double(c, "scheme.warm_start", &warm, 0.0, 1.0, &s->warm, err));
    RY_TRY(ry_case_int(c, "scheme.max_iterations", &maxit, 1, 100000, &s->max_iter, err));
    RY_TRY(ry_case_int(c, "scheme.min_iterations", &minit, 1, 1000, &s->min_iter, err));
    static const char *const walls[] = {"no_slip", "free_slip", NULL};
    RY_TRY(ry_case_choice(c, "scheme.wall", "no_slip", walls, &s->slip, err));
    static const char *const wall_velocities[] = {"own", "ghost", NULL};
    RY_TRY(ry_case_choice(c, "scheme.wall_velocity", "own", wall_velocities, &s->ghost, err));
    static const char *const corrections[] = {"none", "lattice", NULL};
    int corr;
    RY_TRY(ry_case_choice(c, "scheme.viscosity_correction", "none", corrections, &corr, err));
    static const char *const forms[] = {"projected", "morris", NULL};
    RY_TRY(ry_case_choice(c, "scheme.viscous_form", "projected", forms, &s->morris, err));
    static const char *const vschemes[] = {"explicit", "implicit", NULL};
    RY_TRY(ry_case_choice(c, "scheme.viscosity", "explicit", vschemes, &s->implicit, err));
    double vtol = 1e-8;
    RY_TRY(ry_case_double(c, "scheme.viscosity_tolerance", &vtol, 1e-14, 1e-2, &s->vtol, err));
    /* the pair cache's wall rows: their mobile neighbours alone (the Adami extrapolation, the
     * ghost velocity); no pass reads a wall's wall neighbours */
    static const int wall_rows[RY_KIND_COUNT] = {[RY_KIND_WALL] = 1};
    s->pc.partner_rows = wall_rows;
    s->pc.partners = MOBILE;
    RY_TRY(ry_case_choice(c, "scheme.viscosity_preconditioner", "jacobi", ry_precond_names,
                          &s->vprecond, err));
    char vwhere[256];
    RY_CHECK(err, !(s->vprecond == RY_PRECOND_BOOMERAMG && ry_box_mirrors(&sim->box) > 1),
             RY_ERR_INPUT,
             "%s: key 'scheme.viscosity_preconditioner': boomeramg runs without symmetry "
             "planes so far (domain.symmetry): jacobi",
             ry_case_where(c, "scheme.viscosity_preconditioner", vwhere, sizeof vwhere));
    long reuse = 1;
    RY_TRY(ry_case_int(c, "scheme.amg_reuse", &reuse, 1, 1000, &s->vamg.reuse, err));
    if (s->implicit) {
        char where[256];
        RY_CHECK(err, s->morris, RY_ERR_INPUT,
                 "%s: key 'scheme.viscosity': implicit needs scheme.viscous_form: morris",
                 ry_case_where(c, "scheme.viscosity", where, sizeof where));
    }
    /* The explicit limits keep 39 % of each form's stability limit on the lattice (iisph_dt). */
    s->cvisc = s->morris ? 0.125 : 0.045;
    double zero = 0, eps = 0.01;
    RY_TRY(ry_case_double(c, "scheme.surface_tension", &zero, 0.0, 1e3, &s->colour.sigma, err));
    s->colour_on = s->colour.sigma > 0;
    s->colour.material = sim->nmat > 1 ? 1 : 0;
    if (ry_case_has(c, "scheme.colour_material") || s->colour_on) {
        const char *def = sim->mat[s->colour.material].name, *name;
        RY_TRY(ry_case_string(c, "scheme.colour_material", def, &name, err));
        int found = -1;
        for (int m = 0; m < sim->nmat; ++m)
            if (strcmp(sim->mat[m].name, name) == 0) found = m;
        char where[256];
        RY_CHECK(err, found >= 0, RY_ERR_INPUT,
                 "%s: key 'scheme.colour_material': no material '%s'",
                 ry_case_where(c, "scheme.colour_material", where, sizeof where), name);
        s->colour.material = found;
        RY_TRY(ry_case_double(c, "scheme.normal_threshold", &eps, 0.0, 1.0, &s->colour.eps, err));
        long passes, one = 1;
        RY_TRY(ry_case_int(c, "scheme.curvature_smoothing", &one, 0, 20, &passes, err));
        s->colour.smoothing = (int)passes;
    }
    if (ry_case_has(c, "scheme.contact_line_force") && !ry_case_has(c, "scheme.contact_angle")) {
        char where[256];
        RY_CHECK(err, 0, RY_ERR_INPUT,
                 "%s: key 'scheme.contact_line_force': needs scheme.contact_angle",
                 ry_case_where(c, "scheme.contact_line_force", where, sizeof where));
    }
    if (ry_case_has(c, "scheme.contact_angle")) {
        /* the two liquids' angle at the walls, through the liquid without colour */
        double theta;
        char where[256];
        RY_CHECK(err, s->colour_on, RY_ERR_INPUT,
                 "%s: key 'scheme.contact_angle': needs two liquids with scheme.surface_tension",
                 ry_case_where(c, "scheme.contact_angle", where, sizeof where));
        RY_TRY(ry_case_double(c, "scheme.contact_angle", NULL, 0.0, 180.0, &theta, err));
        s->colour.wet = 1;
        s->colour.cos_theta = cos(theta * 3.14159265358979323846 / 180.0);
        s->colour.sin_theta = sin(theta * 3.14159265358979323846 / 180.0);
        int no = 0, lf;
        RY_TRY(ry_case_bool(c, "scheme.contact_line_force", &no, &lf, err));
        s->colour.line_force = lf;
    }
    if (s->colour_on) {
        const int a = s->colour.material, b = a == 0 && sim->nmat > 1 ? 1 : 0;
        s->colour.rho_bar = 0.5 * (sim->mat[a].density + sim->mat[b].density);
        RY_TRY(ry_colour_init(&s->colour, sim, err));
    }
    RY_TRY(ry_st_read_sph(&s->st, c, sim->dim, sim->dx, &s->st_beta, &s->coll_r, &s->coll_e, err));
    s->mu = calloc((size_t)sim->nmat, sizeof *s->mu);
    RY_CHECK(err, s->mu != NULL, RY_ERR_NOMEM, "out of memory");
    for (int m = 0; m < sim->nmat; ++m) s->mu[m] = sim->mat[m].density * sim->mat[m].viscosity;
    s->delta0 = ry_lattice_number_density(&sim->kernel, sim->dim, sim->dx);
    s->colour.wall_volume = 1.0 / s->delta0;
    /* The lattice's value of the viscous term for a unit shear Laplacian (Wendland C2,
     * h = 1.4 dx: projected 0.85 in 2D, 0.90 in 3D; Morris 0.98). */
    const double eta2 = ry_morris_eta2(sim->kernel.h);
    s->mu_corr = corr ? 1.0 / ry_lattice_viscous_factor(&sim->kernel, sim->dim, sim->dx,
                                                        1.0 / s->delta0, eta2, !s->morris)
                      : 1.0;
    RY_TRY(ry_sph_rheo_init(&s->rheo, sim, err));
    /* The projected form is not div(mu grad u) where the viscosity varies: a shear-thinning
     * channel ran 14-16 % slow with it. */
    for (int m = 0; m < sim->nmat && !s->morris; ++m) {
        char where[256];
        RY_CHECK(err, !ry_rheology_generalised(&sim->mat[m].rheo), RY_ERR_INPUT,
                 "%s: key 'scheme.viscous_form': material '%s' (%s) needs morris",
                 ry_case_where(c, "scheme.viscous_form", where, sizeof where), sim->mat[m].name,
                 ry_rheology_names[sim->mat[m].rheo.model]);
    }
    RY_TRY(iisph_light_phase_init(sim, s, c, err));
    ry_particles *ps = &sim->ps;
    int no = 0, hydro;
    RY_TRY(ry_case_bool(c, "scheme.hydrostatic_init", &no, &hydro, err));
    /* The first solve starts from the hydrostatic pressure (hydrostatic_init) or from zero. */
    ry_hydrostatic_pressure(sim, ps->f[RY_F_P]);
    for (size_t i = 0; i < ps->n; ++i) {
        ps->f[RY_F_MASS][i] = sim->mat[ps->material[i]].density / s->delta0;
        if (!hydro || ps->kind[i] != RY_KIND_FLUID) ps->f[RY_F_P][i] = 0;
        /* the warm start scales the previous pressure: undo it for the first step */
        else if (s->warm > 0)
            ps->f[RY_F_P][i] /= s->warm;
        ps->f[RY_F_RHO][i] = sim->mat[ps->material[i]].density;
    }
    return RY_OK;
}

static void iisph_free(void *state) {
    iisph *s = state;
    if (!s) return;
    ry_colour_free(&s->colour);
    ry_pair_cache_free(&s->pc);
    ry_sph_rheo_free(&s->rheo);
    free(s->delta);
    free(s->mu);
    ry_csr_free(&s->A);
    ry_amg_free(&s->vamg);
    free(s->unk);
    free(s->vslot);
    free(s->vb);
    free(s->vx);
    free(s->vown);
    ry_st_work_free(&s->stw);
    iisph_wall_map_free(&s->wm);
    free(s->gl.off);
    free(s->gl.j);
    free(s->gl.g);
    free(s->light_mat);
    free(s->lt);
    free(s->pl);
    iisph_wall_map_free(&s->wml);
    free(s);
}

/* The per-particle scratch of a step for n particles. */
static ry_status ensure(iisph *s, size_t n, ry_error *err) {
    if (s->cap >= n) return RY_OK;
    size_t cap = n + n / 4 + 16;
    /* one block: delta, dstar, aii (1 each), dii, sum, acc (3 each), pnew (1), vg (3), perr (1),
     * pq (1), djp (3) */
    double *b = realloc(s->delta, cap * 21 * sizeof(double));
    RY_CHECK(err, b != NULL, RY_ERR_NOMEM, "out of memory (%zu particles)", n);
    s->delta = b;
    s->dstar = b + cap;
    s->aii = b + 2 * cap;
    s->pnew = b + 3 * cap;
    s->dii = b + 4 * cap;
    s->sum = b + 7 * cap;
    s->acc = b + 10 * cap;
    for (int d = 0; d < 3; ++d) s->vg[d] = b + (13 + d) * cap;
    s->perr = b + 16 * cap;
    s->pq = b + 17 * cap;
    s->djp = b + 18 * cap;
    uint8_t *lt = realloc(s->lt, cap);
    if (lt) s->lt = lt;
    double *pl = realloc(s->pl, cap * sizeof *pl);
    if (pl) s->pl = pl;
    RY_CHECK(err, lt && pl, RY_ERR_NOMEM, "out of memory (%zu particles)", n);
    s->cap = cap;
    return RY_OK;
}

static ry_status iisph_dt(ry_sim *sim, void *state, double *dt, ry_error *err) {
    (void)err;
    iisph *s = state;
    const double h = sim->kernel.h;
    double t = INFINITY;
    if (!s->have_state) { /* first step: speeds and gravity of the initial state */
        const ry_particles *ps = &sim->ps;
        double v2 = 0, g2 = 0;
        for (size_t i = 0; i < ps->n; ++i) {
            if (!MOBILE[ps->kind[i]]) continue;
            double u = 0;
            for (int d = 0; d < sim->dim; ++d) u += ps->f[RY_F_VX + d][i] * ps->f[RY_F_VX + d][i];
            v2 = fmax(v2, u);
        }
        for (int d = 0; d < sim->dim; ++d) g2 += sim->gravity[d] * sim->gravity[d];
        s->vmax = sqrt(v2);
        s->amax = sqrt(g2);
    }
    if (s->vmax > 0) t = sim->cfl * h / s->vmax;
    if (s->amax > 0) t = fmin(t, 0.25 * sqrt(h / s->amax));
    double numax = 0;
    for (int m = 0; m < sim->nmat; ++m) numax = fmax(numax, sim->mat[m].viscosity);
    /* The viscous term is explicit. On the lattice the projected form (2 (d + 2) times the
     * projection on x_ij) is stable up to dt = 0.115 h^2/nu in 2D and 0.113 in 3D (Wendland C2,
     * h = 1.4 dx), the Morris form up to 0.32 and 0.30. The usual 0.125 h^2/nu keeps 39 % of
     * the Morris limit; cvisc = 0.045 keeps the same share of the projected one. At 0.125 a
     * viscous film (nu = 1e-4 m^2/s, 10 particles deep) threw its surface particles at several
     * times its speed. */
    if (numax > 0 && !s->implicit) t = fmin(t, s->cvisc * h * h / (numax * s->mu_corr));
    t = fmin(t, ry_sph_rheo_dt(&s->rheo, sim, MOBILE, h, sim->cfl,
                               s->implicit ? INFINITY : s->cvisc / s->mu_corr));
    if (s->colour_on) t = fmin(t, ry_colour_dt(&s->colour, sim));
    t = fmin(t, ry_st_capillary_dt(&s->st, sim));
    if (!isfinite(t)) t = sim->dt_max > 0 ? sim->dt_max : 1e-3 * sim->t_end;
    *dt = t;
    return RY_OK;
}

static ry_status iisph_step(ry_sim *sim, void *state, double dt, ry_error *err) {
    iisph *s = state;
    ry_particles *ps = &sim->ps;
    /* The surface-tension radius may reach beyond the kernel's (pairs there have W = 0). */
    const double reach = fmax(sim->kernel.radius, s->st.model != RY_ST_NONE ? s->st.re : 0.0);
    /* 1. Neighbours and the pair cache. */
    RY_TRY(ry_sim_neighbors(sim, reach, err)); /* may reorder particles */
    const size_t n = ps->n;
    const int dim = sim->dim;
    RY_TRY(ensure(s, n, err));
    /* Particles created by open boundaries get their mass here. */
    for (size_t i = 0; i < n; ++i) {
        ps->f[RY_F_MASS][i] = sim->mat[ps->material[i]].density / s->delta0;
        s->lt[i] = s->light_on && MOBILE[ps->kind[i]] && s->light_mat[ps->material[i]];
    }
    static const int need[RY_KIND_COUNT] = {
        [RY_KIND_FLUID] = 1, [RY_KIND_OUTLET] = 1, [RY_KIND_WALL] = 1, [RY_KIND_INLET] = 1};
    RY_TRY(ry_pair_cache_fill(&s->pc, sim, need, err));
    /* 2. Number density and the non-pressure forces: viscosity, gravity, polymer stress,
     * interfacial and surface tension. */
    RY_TRY(iisph_densities_and_forces(sim, s, err));
    if (s->colour_on)
        RY_TRY(ry_colour_force(&s->colour, sim, &s->pc, s->delta, MOBILE, s->acc, err));
    if (s->st.model != RY_ST_NONE) RY_TRY(iisph_surface_tension(sim, s, err));
    /* 3. Advection: the predicted velocity v* = v + dt a_nonpressure (implicit viscosity:
     * then solved for). */
    for (size_t i = 0; i < n; ++i) {
        if (!MOBILE[ps->kind[i]]) continue;
        for (int d = 0; d < dim; ++d) ps->f[RY_F_VX + d][i] += dt * s->acc[3 * i + d];
    }
    if (s->implicit) RY_TRY(iisph_viscous_implicit(sim, s, dt, err));
    if (sim->par)
        for (int d = 0; d < dim; ++d) sim->par->sync_field(sim, RY_F_VX + d);
    /* 4. The pressure solve: the walls' extrapolation lists, the pairs, relaxed Jacobi. */
    RY_TRY(iisph_wall_map_build(sim, s, &s->wm, ps->f[RY_F_P], RY_MAP_WALL, err));
    if (s->light_on) {
        RY_TRY(iisph_wall_map_build(sim, s, &s->wml, s->pl, RY_MAP_LIGHT, err));
    }
    RY_TRY(iisph_grad_list_build(sim, s, err));
    const long it = iisph_pressure_solve(sim, s, dt);
    s->iters_last = it;
    s->iters_total += it;
    s->solves += 1;
    /* 5. The pressure force with the final pressures and the kick v = v* + dt a^p; the drift
     * x += dt v. */
    double vmax2, amax2;
    iisph_pressure_force(sim, s, dt, &vmax2, &amax2);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        const int k = ps->kind[i];
        if (!MOBILE[k] && k != RY_KIND_INLET) continue;
        for (int d = 0; d < dim; ++d) {
            double x = ps->f[RY_F_X + d][i] + dt * ps->f[RY_F_VX + d][i];
            if (sim->box.periodic[d]) { /* back into the periodic box */
                const double lo = sim->box.lo[d], L = sim->box.hi[d] - lo;
                if (x < lo) x += L;
                if (x >= lo + L) x -= L;
            }
            ps->f[RY_F_X + d][i] = x;
        }
    }
    /* 6. Polymer stress and the artificial repulsion. */
    ry_sph_rheo_advance(&s->rheo, sim, MOBILE, dt); /* polymer stress, with L at t */
    /* Artificial repulsion (scheme.repulsion), from the positions and velocities at t + dt;
     * the neighbour list of this step still reaches 0.85 dx. */
    if (sim->par && s->coll_r > 0)
        for (int d = 0; d < dim; ++d) {
            sim->par->sync_field(sim, RY_F_X + d);
            sim->par->sync_field(sim, RY_F_VX + d);
        }
    ry_collisions(sim, s->coll_r, s->coll_e, dt, NULL, NULL, s->acc);
    s->vmax = sqrt(vmax2);
    s->amax = sqrt(amax2);
    s->have_state = 1;
    return RY_OK;
}

static int iisph_vars(void *state, ry_state_var *v, int max) {
    iisph *s = state;
    const ry_state_var all[] = {{"vmax", &s->vmax, NULL, NULL},
                                {"amax", &s->amax, NULL, NULL},
                                {"error_last", &s->error_last, NULL, NULL},
                                {"have_state", NULL, &s->have_state, NULL},
                                {"iters_last", NULL, NULL, &s->iters_last},
                                {"iters_total", NULL, NULL, &s->iters_total},
                                {"solves", NULL, NULL, &s->solves}};
    int n = (int)(sizeof all / sizeof all[0]);
    if (n > max) n = max;
    memcpy(v, all, (size_t)n * sizeof *v);
    return n;
}

static void iisph_report(void *state, char *buf, size_t size) {
    const iisph *s = state;
    const double solves = s->solves ? (double)s->solves : 1.0;
    const int k = snprintf(
        buf, size, "iisph_iterations_mean=%.3g iisph_iterations_last=%ld iisph_error_last=%.3g",
        (double)s->iters_total / solves, s->iters_last, s->error_last);
    /* implicit viscosity: conjugate-gradient iterations per step, all components together */
    if (s->implicit && k > 0 && (size_t)k < size)
        snprintf(buf + k, size - (size_t)k, " viscous_iterations_mean=%.3g",
                 (double)s->viters_total / solves);
}

/* Statistics: pressure-solve iterations of the last step and their mean over the run so far. */
static int iisph_stat(const ry_sim *sim, const void *state, const char *name, double *value) {
    (void)sim;
    const iisph *s = state;
    if (!strcmp(name, "pressure_iterations")) {
        *value = (double)s->iters_last;
    } else if (!strcmp(name, "pressure_iterations_mean")) {
        *value = s->solves ? (double)s->iters_total / (double)s->solves : 0.0;
    } else {
        return 0;
    }
    return 1;
}

/* Distributed: every pass that reads its neighbours' results of the pass before gets them
 * synchronised, so a halo one search radius deep serves. Incompressible: densities stay within
 * the tolerance inside the fluid (summation density is lower at a free surface, so there is no
 * lower bound). */
static void iisph_needs(const ry_sim *sim, const void *state, ry_scheme_needs *nd) {
    (void)sim;
    (void)state;
    nd->halo_depth = 1;
    nd->rho_min = 0.0;
    nd->rho_max = 1.5;
}

const ry_scheme_type ry_scheme_iisph = {
    .name = "iisph",
    .summary = "implicit incompressible SPH (Ihmsen et al. 2014; number-density two-phase form, "
               "colour-field interfacial and free-surface tension)",
    .init = iisph_init,
    .stable_dt = iisph_dt,
    .step = iisph_step,
    .free = iisph_free,
    .state_vars = iisph_vars,
    .report = iisph_report,
    .stat = iisph_stat,
    .needs = iisph_needs,
    .caps = RY_SCHEME_RHEOLOGY};
