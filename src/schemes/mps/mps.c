/* Moving Particle Semi-implicit method (Koshizuka & Oka 1996; seed 003, SPEC section 3).
 *
 *  weight      w(r) = (r/re - 1)^2 for r < re (Tamai et al. 2017; seed eq. 3)
 *  number density  n_i = sum_j w(r_ij) (eq. 4); n0 and lambda from the full lattice
 *  gradient    Iribe's corrected gradient with Koshizuka's minimum pressure (eq. 5):
 *              <grad p>_i = [sum_j w x^_ij (x) x^_ij]^-1 sum_j w (p_j - p^_i) x_ij / r_ij^2,
 *              x^ = x_ij / r_ij, p^_i the least pressure over i and its neighbours
 *  divergence  <div u>_i = d/n0 sum_j (u_j - u_i).x_ij / r_ij^2 w (eq. 6)
 *  Laplacian   <lap f>_i = 2d/(lambda n0) sum_j (f_j - f_i) w (eq. 7-8)
 *  step        u* = u^n + dt (g + f_st + nu lap u) (explicit viscosity) or
 *              (1 - dt nu lap) u* = u^n + dt (g + f_st) (implicit viscosity); x* = x^n + dt u*;
 *              pressure Poisson equation at x*, source of Tanaka & Masunaga (2010):
 *              lap p = (1 - gamma) rho/dt div u* - gamma rho/dt^2 (n* - n0)/n0,
 *              or the classic number-density source (gamma = 1); u' = -dt/rho grad p;
 *              u^{n+1} = u* + u', x^{n+1} = x* + dt u'.
 *  free surface  fluid with n* < beta n0 is Dirichlet: the head of half a spacing,
 *              rho l0/2 max(0, g.n) (n inward), or p = 0 (scheme.surface_pressure).
 *  walls       wall particles with a fluid particle within re (gradient) take part in the
 *              Poisson equation (wall particles); the others only add to the number density
 *              (dummy particles).
 *  solver      conjugate gradients with the Jacobi preconditioner on a CSR matrix assembled
 *              each step (src/linalg/sparse.c); the matrix of both systems is symmetric positive
 *              definite because lambda and n0 are constants of the lattice.
 *
 * This file: the scheme's keys and state, its registration and the time step, which runs the
 * steps of the files beside it: mps_operators.c (lattice sums, pairs, number density and
 * divergence), mps_walls.c (wall and dummy particles, thin walls, wall pressure), mps_viscosity.c
 * (explicit and implicit viscosity, rheology), mps_surface.c (surface tension, two liquids,
 * outlets), mps_pressure.c (pressure Poisson equation, gradient and correction);
 * mps_internal.h holds what they share. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/collisions.h"
#include "ryushi/mps.h"
#include "ryushi/rheology.h"
#include "schemes/mps/mps.h"
#include "schemes/mps/mps_internal.h"

static const char *const source_names[] = {"tanaka_masunaga", "number_density", NULL};
static const char *const visc_names[] = {"explicit", "implicit", "none", "mixed", NULL};
static const char *const grad_names[] = {"corrected", "standard", NULL};
static const char *const surface_pressure_names[] = {"zero", "hydrostatic", NULL};
static const char *const thin_pressure_names[] = {"unknown", "neumann", NULL};
static const char *const wall_pressure_names[] = {"unknown", "neumann", NULL};
static const char *const wall_velocity_names[] = {"own", "mirrored", "slip", NULL};

static ry_status mps_init(ry_sim *sim, ry_case *c, void **state, ry_error *err) {
    mps *M = calloc(1, sizeof *M);
    RY_CHECK(err, M != NULL, RY_ERR_NOMEM, "out of memory");
    *state = M;
    const double l0 = sim->dx;
    double reg = 2.1, rel = 3.1, beta = 0.97, gamma = 0.01, zero = 0, tol = 1e-8, vtol = 1e-10;
    long maxit = 5000;
    int yes = 1;
    RY_TRY(ry_case_double(c, "scheme.re_gradient", &reg, 1.0, 6.0, &M->re_g, err));
    RY_TRY(ry_case_double(c, "scheme.re_laplacian", &rel, 1.0, 6.0, &M->re_l, err));
    RY_TRY(ry_case_double(c, "scheme.surface_threshold", &beta, 0.5, 1.0, &M->beta, err));
    double reach = 1.5;
    RY_TRY(ry_case_double(c, "scheme.wall_reach", &reach, 1.0, 6.0, &M->wall_reach, err));
    M->wall_reach *= l0;
    RY_TRY(ry_case_choice(c, "scheme.source", "tanaka_masunaga", source_names, &M->source, err));
    RY_TRY(ry_case_double(c, "scheme.source_gamma", &gamma, 0.0, 1.0, &M->gamma, err));
    if (M->source == SRC_NUMBER_DENSITY) M->gamma = 1.0;
    RY_TRY(ry_case_double(c, "scheme.compressibility", &zero, 0.0, 1.0, &M->alpha, err));
    RY_TRY(ry_case_choice(c, "scheme.viscosity", "explicit", visc_names, &M->visc, err));
    RY_TRY(ry_case_choice(c, "scheme.gradient", "corrected", grad_names, &M->grad, err));
    RY_TRY(
        ry_case_choice(c, "scheme.wall_velocity", "own", wall_velocity_names, &M->wall_mode, err));
    RY_TRY(ry_case_bool(c, "scheme.clamp_negative_pressure", &yes, &M->clamp, err));
    int no = 0;
    RY_TRY(ry_case_bool(c, "scheme.source_dilatation", &no, &M->dilate, err));
    RY_TRY(ry_case_bool(c, "scheme.minimum_pressure", &yes, &M->pmin_on, err));
    RY_TRY(ry_case_choice(c, "scheme.surface_pressure", "hydrostatic", surface_pressure_names,
                          &M->surf_head, err));
    double cr = 0.85, ce = 0.2;
    RY_TRY(ry_case_double(c, "scheme.repulsion.distance", &cr, 0.0, 1.0, &M->coll_r, err));
    RY_TRY(ry_case_double(c, "scheme.repulsion.restitution", &ce, 0.0, 1.0, &M->coll_e, err));
    M->coll_r *= l0;
    RY_TRY(ry_case_bool(c, "scheme.wall_extrapolation", &yes, &M->wall_extrapolate, err));
    RY_TRY(ry_case_choice(c, "scheme.thin_wall_pressure", "neumann", thin_pressure_names,
                          &M->thin_neumann, err));
    RY_TRY(ry_case_choice(c, "scheme.wall_pressure", "unknown", wall_pressure_names,
                          &M->wall_neumann, err));
    char where[512];
    RY_CHECK(err, !(M->wall_neumann && !M->wall_extrapolate), RY_ERR_INPUT,
             "%s: key 'scheme.wall_extrapolation': false leaves the walls without a pressure "
             "with scheme.wall_pressure: neumann (their pressure is the extrapolated one)",
             ry_case_where(c, "scheme.wall_extrapolation", where, sizeof where));
    RY_TRY(ry_case_bool(c, "scheme.inlet_free_surface", &no, &M->inlet_surface, err));
    RY_TRY(ry_case_bool(c, "scheme.contact_line_slip", &no, &M->cl_slip, err));
    RY_TRY(ry_case_bool(c, "scheme.thin_wall_cut", &yes, &M->thin_cut_on, err));
    const long three = 3;
    long layers;
    RY_TRY(ry_case_int(c, "scheme.thin_wall_layers", &three, 1, 3, &layers, err));
    RY_TRY(ry_case_double(c, "scheme.solver.tolerance", &tol, 1e-14, 1e-2, &M->tol, err));
    RY_TRY(
        ry_case_double(c, "scheme.solver.viscosity_tolerance", &vtol, 1e-14, 1e-2, &M->vtol, err));
    RY_TRY(ry_case_int(c, "scheme.solver.max_iterations", &maxit, 10, 1000000, &M->max_iter, err));
    long defl = 0;
    RY_TRY(ry_case_int(c, "scheme.solver.deflation", &defl, 0, 1000, &M->defl, err));
    RY_TRY(ry_case_choice(c, "scheme.solver.preconditioner", "jacobi", ry_precond_names,
                          &M->precond, err));
    RY_TRY(ry_case_choice(c, "scheme.solver.viscosity_preconditioner", "jacobi", ry_precond_names,
                          &M->vprecond, err));
    RY_CHECK(err, !(M->vprecond == RY_PRECOND_BOOMERAMG && ry_box_mirrors(&sim->box) > 1),
             RY_ERR_INPUT,
             "%s: key 'scheme.solver.viscosity_preconditioner': boomeramg runs without "
             "symmetry planes so far (domain.symmetry): jacobi",
             ry_case_where(c, "scheme.solver.viscosity_preconditioner", where, sizeof where));
    RY_CHECK(err, !(M->defl > 0 && M->precond == RY_PRECOND_BOOMERAMG), RY_ERR_INPUT,
             "%s: key 'scheme.solver.deflation': goes with the jacobi preconditioner only "
             "(boomeramg already solves the smooth error that deflation removes)",
             ry_case_where(c, "scheme.solver.deflation", where, sizeof where));
    long reuse = 1;
    RY_TRY(ry_case_int(c, "scheme.solver.amg_reuse", &reuse, 1, 1000, &reuse, err));
    M->amg.reuse = M->vamg.reuse = reuse;
    M->re_g *= l0;
    M->re_l *= l0;
    RY_TRY(ry_st_read(&M->st, c, sim->dim, l0, 3.1, 6.0, err));
    M->st.thin_layers = (int)layers;
    M->csf_pressure = ry_st_pressure_form(&M->st);
    RY_TRY(mps_contact_angle(sim, c, M, err));
    RY_TRY(mps_body_thin(sim, c, M, err));
    M->re_max = fmax(fmax(M->re_g, M->re_l), M->st.model != RY_ST_NONE ? M->st.re : 0.0);
    RY_TRY(mps_interfacial(sim, c, M, err));
    double lam_g;
    ry_mps_lattice(sim->dim, l0, M->re_g, &M->n0g, &lam_g);
    ry_mps_lattice(sim->dim, l0, M->re_l, &M->n0l, &M->lambda);

    ry_particles *ps = &sim->ps;
    static const char *const vs[3] = {"vstar_x", "vstar_y", "vstar_z"};
    for (int d = 0; d < 3; ++d)
        RY_TRY(ry_particles_add_field(ps, vs[d], "m/s", d, 0, &M->f_vs[d], err));
    RY_TRY(ry_particles_add_field(ps, "number_density", "1", -1, RY_FIELD_OUTPUT, &M->f_nd, err));
    RY_TRY(ry_particles_add_field(ps, "free_surface", "1", -1, RY_FIELD_OUTPUT, &M->f_surf, err));
    RY_TRY(mps_rheology_init(sim, M, err));
    RY_TRY(mps_outlet_sinks(sim, c, err));
    for (size_t i = 0; i < ps->n; ++i) {
        ps->f[RY_F_RHO][i] = sim->mat[ps->material[i]].density;
        ps->f[RY_F_P][i] = 0;
    }
    return RY_OK;
}

static void mps_free(void *state) {
    mps *M = state;
    if (!M) return;
    ry_csr_free(&M->A);
    ry_csr_deflation_free(&M->D);
    ry_amg_free(&M->amg);
    ry_amg_free(&M->vamg);
    free(M->dmap);
    free(M->unk);
    free(M->uslot);
    free(M->ucol);
    free(M->role);
    free(M->cline);
    free(M->b);
    free(M->xs);
    free(M->pd);
    free(M->own);
    free(M->near_surf);
    free(M->divu);
    free(M->ptmp);
    free(M->vgrad);
    free(M->wd);
    free(M->cdelta);
    free(M->pj);
    free(M->pr);
    free(M->gend);
    free(M->lend);
    free(M->nu_pair);
    free(M->body_group);
    free(M->wgroup);
    free(M->body_thin);
    free(M->thin);
    free(M->tnrm);
    free(M->tpw);
    free(M->tn_off);
    free(M->tn_j);
    free(M->tn_d);
    free(M->cut_row);
    free(M->cut);
    ry_colour_free(&M->colour);
    ry_pair_cache_free(&M->pc);
    free(M);
}

static ry_status scratch(mps *M, size_t n, ry_error *err) {
    if (M->cap >= n) return RY_OK;
    size_t c = n + n / 4 + 16;
    int32_t *u = realloc(M->unk, c * sizeof *u);
    if (u) M->unk = u;
    int32_t *us = realloc(M->uslot, c * sizeof *us);
    if (us) M->uslot = us;
    int32_t *uc = realloc(M->ucol, c * sizeof *uc);
    if (uc) M->ucol = uc;
    uint8_t *r = realloc(M->role, c * sizeof *r);
    if (r) M->role = r;
    double *b = realloc(M->b, 3 * c * sizeof *b);
    if (b) M->b = b;
    double *x = realloc(M->xs, 3 * c * sizeof *x);
    if (x) M->xs = x;
    double *pd = realloc(M->pd, 8 * c * sizeof *pd);
    if (pd) M->pd = pd;
    uint8_t *o = realloc(M->own, c * sizeof *o);
    if (o) M->own = o;
    uint8_t *ns = realloc(M->near_surf, c * sizeof *ns);
    if (ns) M->near_surf = ns;
    double *dv = realloc(M->divu, c * sizeof *dv);
    if (dv) M->divu = dv;
    double *t = realloc(M->ptmp, c * sizeof *t);
    if (t) M->ptmp = t;
    size_t *ge = realloc(M->gend, c * sizeof *ge);
    if (ge) M->gend = ge;
    size_t *le = realloc(M->lend, c * sizeof *le);
    if (le) M->lend = le;
    double *vg = M->vgrad;
    if (M->rheo_ob) {
        vg = realloc(M->vgrad, 9 * c * sizeof *vg);
        if (vg) M->vgrad = vg;
    }
    double *wv = M->wd;
    if (M->wall_mode == WALLV_MIRRORED) {
        wv = realloc(M->wd, c * sizeof *wv);
        if (wv) M->wd = wv;
    }
    uint8_t *cl = M->cline;
    if (M->cl_slip) {
        cl = realloc(M->cline, c * sizeof *cl);
        if (cl) M->cline = cl;
    }
    uint8_t *wg = M->wgroup;
    if (M->body_group) {
        wg = realloc(M->wgroup, c * sizeof *wg);
        if (wg) M->wgroup = wg;
    }
    int32_t *th = M->thin;
    double *tv = M->tnrm;
    uint32_t *to = M->tn_off;
    uint8_t *cr = M->cut_row;
    double *tp = M->tpw;
    if (M->body_thin) {
        th = realloc(M->thin, c * sizeof *th);
        if (th) M->thin = th;
        tv = realloc(M->tnrm, 3 * c * sizeof *tv);
        if (tv) M->tnrm = tv;
        tp = realloc(M->tpw, 2 * c * sizeof *tp);
        if (tp) M->tpw = tp;
        to = realloc(M->tn_off, (c + 1) * sizeof *to);
        if (to) M->tn_off = to;
        cr = realloc(M->cut_row, c);
        if (cr) M->cut_row = cr;
    }
    RY_CHECK(err,
             u && us && uc && r && b && x && pd && o && ns && dv && t && ge && le &&
                 (vg || !M->rheo_ob) && (wv || M->wall_mode != WALLV_MIRRORED) &&
                 (cl || !M->cl_slip) && (wg || !M->body_group) &&
                 ((th && tv && tp && to && cr) || !M->body_thin),
             RY_ERR_NOMEM, "out of memory (MPS work arrays)");
    M->cap = c;
    return RY_OK;
}

/* Fluid particles that crossed a periodic side back into the box. */
static void wrap_periodic(ry_sim *sim) {
    ry_particles *ps = &sim->ps;
    for (int d = 0; d < sim->dim; ++d) {
        if (!sim->box.periodic[d]) continue;
        const double lo = sim->box.lo[d], L = sim->box.hi[d] - lo;
        double *x = ps->f[RY_F_X + d];
        for (size_t i = 0; i < ps->n; ++i) {
            if (ps->kind[i] != RY_KIND_FLUID) continue;
            if (x[i] < lo) x[i] += L;
            if (x[i] >= lo + L) x[i] -= L;
        }
    }
}

static ry_status mps_step(ry_sim *sim, void *state, double dt, ry_error *err) {
    mps *M = state;
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    /* Explicit part at x^n: gravity, surface tension, viscosity. */
    RY_TRY(ry_sim_neighbors(sim, M->re_max, err));
    RY_TRY(scratch(M, ps->n, err));
    /* the terms at x^n read the rows of the fluid particles alone (and, for the mirrored wall
     * velocity, the walls' distances to the fluid) */
    const int fluid_rows = M->wall_mode != WALLV_MIRRORED;
    RY_TRY(mps_wall_bodies(sim, M, fluid_rows, err));
    RY_TRY(mps_pairs_build(sim, M, fluid_rows, err));
    size_t n = ps->n;
    double *a[3];
    for (int d = 0; d < 3; ++d) a[d] = ps->f[RY_F_AX + (d < dim ? d : 0)];
    for (size_t i = 0; i < n; ++i)
        for (int d = 0; d < dim; ++d) a[d][i] = ps->kind[i] == RY_KIND_FLUID ? sim->gravity[d] : 0;
    /* The potential model's pass and the viscosity's split read the same pairs: with nothing
     * between them that reads a neighbour's acceleration, one pass does both (the same sums) */
    const int fuse = M->st.model == RY_ST_POTENTIAL && M->st.sigma != 0.0 && !M->csf_pressure &&
                     !M->colour_on && M->wall_mode != WALLV_MIRRORED && !M->rheo_gnf &&
                     !M->rheo_ob && M->visc == VISC_MIXED && !sim->par;
    if (M->cl_slip) mps_contact_lines(sim, M);
    if (!M->csf_pressure && !fuse) RY_TRY(ry_st_accelerate(&M->st, sim, a, err));
    if (M->colour_on) RY_TRY(mps_colour_accelerate(sim, M, a, err));
    if (M->wall_mode == WALLV_MIRRORED) mps_wall_distances(sim, M);
    if (M->rheo_gnf || M->rheo_ob) mps_rheology_explicit(sim, M, dt);
    if (M->visc == VISC_EXPLICIT) mps_viscous_explicit(sim, M);
    /* Prediction: u* (which the implicit viscosity solves for), x* = x^n + dt u*. */
    if (M->visc == VISC_IMPLICIT || M->visc == VISC_MIXED) {
        RY_TRY(mps_viscous_implicit(sim, M, dt, fuse, err));
    } else {
        for (size_t i = 0; i < n; ++i)
            if (ps->kind[i] == RY_KIND_FLUID)
                for (int d = 0; d < dim; ++d)
                    ps->f[M->f_vs[d]][i] = ps->f[RY_F_VX + d][i] + dt * a[d][i];
    }
    for (size_t i = 0; i < n; ++i)
        if (ps->kind[i] == RY_KIND_FLUID)
            for (int d = 0; d < dim; ++d) ps->f[RY_F_X + d][i] += dt * ps->f[M->f_vs[d]][i];
    wrap_periodic(sim);
    /* Pressure at x* (the list may be rebuilt and the particles reordered). */
    RY_TRY(ry_sim_neighbors(sim, M->re_max, err));
    RY_TRY(scratch(M, ps->n, err));
    RY_TRY(mps_wall_bodies(sim, M, 0, err));
    RY_TRY(mps_pairs_build(sim, M, 0, err));
    mps_number_density(sim, M);
    RY_TRY(mps_pressure(sim, M, dt, err));
    mps_correct(sim, M, dt);
    M->st.pair_j = NULL;           /* the pairs are of x*, the particles now elsewhere */
    if (sim->par && M->coll_r > 0) /* the collisions read the corrected neighbours */
        for (int d = 0; d < dim; ++d) {
            sim->par->sync_field(sim, RY_F_X + d);
            sim->par->sync_field(sim, RY_F_VX + d);
        }
    /* the pairs within re_g (M->pj up to gend); xs: dim n doubles of scratch */
    ry_collisions(sim, M->coll_r, M->coll_e, dt, M->pj, M->gend, M->xs);
    /* Inflow buffer particles (open_boundaries) move with their prescribed velocity; in the
     * pressure and viscous terms they are walls with that velocity, and ry_open_update turns
     * those past the zone into fluid. */
    for (size_t i = 0; i < ps->n; ++i)
        if (ps->kind[i] == RY_KIND_INLET)
            for (int d = 0; d < dim; ++d) ps->f[RY_F_X + d][i] += dt * ps->f[RY_F_VX + d][i];
    wrap_periodic(sim);
    M->steps++;
    return RY_OK;
}

static ry_status mps_dt(ry_sim *sim, void *state, double *dt, ry_error *err) {
    (void)err;
    const mps *M = state;
    const ry_particles *ps = &sim->ps;
    const double l0 = sim->dx;
    double v2 = 0, rho_min = INFINITY, nu_max = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if ((ps->kind[i] != RY_KIND_FLUID && ps->kind[i] != RY_KIND_INLET) ||
            ry_sim_is_halo(sim, i))
            continue;
        double s = 0;
        for (int d = 0; d < sim->dim; ++d) s += ps->f[RY_F_VX + d][i] * ps->f[RY_F_VX + d][i];
        v2 = fmax(v2, s);
    }
    double elastic = INFINITY; /* visco-elastic: shear waves at sqrt(nu_p / lambda) */
    for (int m = 0; m < sim->nmat; ++m) {
        const ry_rheology *r = &sim->mat[m].rheo;
        rho_min = fmin(rho_min, sim->mat[m].density);
        nu_max = fmax(nu_max, ry_rheology_nu_max(r, sim->mat[m].viscosity));
        if (ry_rheology_viscoelastic(r) && r->nu_polymer > 0)
            elastic = fmin(elastic, sim->cfl * l0 * sqrt(r->relaxation / r->nu_polymer));
    }
    double g = 0;
    for (int d = 0; d < sim->dim; ++d) g += sim->gravity[d] * sim->gravity[d];
    g = sqrt(g);
    double t = INFINITY;
    if (v2 > 0) t = sim->cfl * l0 / sqrt(v2);
    if (g > 0) t = fmin(t, sim->cfl * sqrt(l0 / g));
    t = fmin(t, ry_st_capillary_dt(&M->st, sim));
    if (M->visc == VISC_EXPLICIT && nu_max > 0) t = fmin(t, 0.2 * l0 * l0 / nu_max);
    t = fmin(t, elastic);
    if (M->colour_on) t = fmin(t, ry_colour_dt(&M->colour, sim));
    if (!isfinite(t)) t = sim->dt_max > 0 ? sim->dt_max : sim->output_interval;
    *dt = t;
    return RY_OK;
}

static int mps_vars(void *state, ry_state_var *v, int max) {
    mps *M = state;
    const ry_state_var all[] = {{"ppe_iterations", NULL, &M->last_iters, NULL},
                                {"ppe_iterations_total", NULL, NULL, &M->total_iters},
                                {"mps_steps", NULL, NULL, &M->steps}};
    int k = (int)(sizeof all / sizeof all[0]);
    if (k > max) k = max;
    memcpy(v, all, (size_t)k * sizeof *v);
    return k;
}

/* The summary: the linear solves of this process, iterations per solve and seconds in them per
 * step (the implicit viscosity's iterations summed over the components); the pressure
 * equation's unknowns (mean per solve), how many of them are walls, and the seconds per solve of
 * its assembly and of the walls' extrapolated pressure. */
static void mps_report(void *state, char *buf, size_t size) {
    const mps *M = state;
    const double ps = M->psolves ? (double)M->psolves : 1.0;
    const int k =
        snprintf(buf, size,
                 "pressure_preconditioner=%s ppe_iterations_mean=%.3g ppe_solve_s=%.3g "
                 "ppe_unknowns_mean=%.0f ppe_wall_unknowns_mean=%.0f ppe_assembly_s=%.3g "
                 "wall_extrapolation_s=%.3g",
                 ry_precond_names[M->precond], (double)M->total_piters / ps, M->psolve_s / ps,
                 M->total_unk / ps, M->total_wunk / ps, M->passemble_s / ps, M->pwall_s / ps);
    int k2 = k;
    if (M->precond == RY_PRECOND_BOOMERAMG && k > 0 && (size_t)k < size)
        k2 += snprintf(buf + k, size - (size_t)k, " ppe_amg_setup_s=%.3g", M->amg.setup_s / ps);
    if (M->vsolves && k2 > 0 && (size_t)k2 < size)
        snprintf(buf + k2, size - (size_t)k2,
                 " viscous_preconditioner=%s viscous_iterations_mean=%.3g viscous_solve_s=%.3g",
                 ry_precond_names[M->vprecond], (double)M->total_viters / (double)M->vsolves,
                 M->vsolve_s / (double)M->vsolves);
}

/* Statistics: the pressure solver's iterations (last step, total) and the pairs within the
 * interaction radius that thin walls cut at the last step, counted from both ends. */
static int mps_stat(const ry_sim *sim, const void *state, const char *name, double *value) {
    (void)sim;
    const mps *M = state;
    if (!strcmp(name, "pressure_iterations")) {
        *value = (double)M->last_iters;
    } else if (!strcmp(name, "pressure_iterations_total")) {
        *value = (double)M->total_iters;
    } else if (!strcmp(name, "cut_pairs")) {
        *value = (double)M->ncut;
    } else {
        return 0;
    }
    return 1;
}

/* Outlets are sinks (mps_outlet_sinks). */
static void mps_needs(const ry_sim *sim, const void *state, ry_scheme_needs *nd) {
    (void)sim;
    (void)state;
    nd->open_sink = 1;
}

const ry_scheme_type ry_scheme_mps = {
    .name = "mps",
    .summary = "moving particle semi-implicit (Tamai weight, Iribe gradient, PCG pressure)",
    .init = mps_init,
    .stable_dt = mps_dt,
    .step = mps_step,
    .free = mps_free,
    .state_vars = mps_vars,
    .report = mps_report,
    .stat = mps_stat,
    .needs = mps_needs,
    .caps = RY_SCHEME_RHEOLOGY};
