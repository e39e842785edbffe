/* SPH for elastic solids, total-Lagrangian form with corrected kernel gradients (seed 000,
 * SPEC section 2; docs/reference/solid.md). The scheme's set-up, loads, initial velocity, time
 * stepping and probes serve the updated-Lagrangian form (updated.c, scheme.formulation) as well.
 *
 * Every quantity refers to the reference (initial) configuration X, in which the neighbour list,
 * the kernel gradients grad W_ij = grad_X W(|X_i - X_j|) and the volumes V_j = m_j / rho0_j are
 * computed once:
 *
 *   correction      L_i = (sum_j V_j grad W_ij (x) (X_j - X_i))^-1     (seed eq. 10-12,
 *                   include/ryushi/corrected.h; L_i = I without kernel correction)
 *   deformation     F_i = sum_j V_j (x_j - x_i) (x) L_i grad W_ij
 *   material        St Venant-Kirchhoff: E_i = (F_i^T F_i - I)/2, S_i = lambda tr(E_i) I + 2 mu E_i
 *                   (plane stress in 2D: lambda* = 2 lambda mu / (lambda + 2 mu)), P_i = F_i S_i
 *   forces          f_i = sum_j V_i V_j (P_i L_i + P_j L_j) grad W_ij  (= -dU/dx_i for the
 *                   stored energy U = sum_i V_i S_i : E_i / 2: momentum and energy conserving)
 *   motion          m_i dv_i/dt = f_i + f_ext,i + m_i g, symplectic Euler (kick, then drift)
 *
 * Particles of kind wall are clamped: they keep their initial position and zero velocity. With
 * scheme.clamp: face (the default) they hold no energy and only supply u = 0 to the gradient fits
 * of their neighbours; they should form one column on the clamped face (x = 0 of a beam), so that
 * no fit straddles the kink between the rigid clamp and the bent beam. With clamp: block they are
 * a block of the elastic material held fixed, at least a kernel radius deep, stress included
 * (measured: the root then yields as if the beam were about one spacing longer). Loads are body
 * forces per particle (see load_forces). Static solutions by dynamic relaxation: kinetic damping
 * (all velocities set to zero whenever the kinetic energy passes a maximum) or viscous damping -c
 * v; the run ends when the relative residual |f + f_ext| / |f_ext| drops below scheme.residual.
 *
 * Time step: dt = CFL h / c, c = sqrt((lambda + 2 mu) / rho0), the fastest (P-) wave speed. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/corrected.h"
#include "schemes/solid/solid_internal.h"

static const double RY_SOLID_TL_DYNAMIC_DT = 0.25;
static const char *const load_names[] = {"none", "end", "uniform", "linear", "cosine", NULL};
static const char *const relax_names[] = {"none", "kinetic", "viscous", NULL};
static const char *const plane_names[] = {"stress", "strain", NULL};
static const char *const corr_names[] = {"none", "linear", "quadratic", NULL};
static const char *const clamp_names[] = {"face", "block", NULL};
static const char *const integration_names[] = {"nodal", "gradient", NULL};
static const char *const formulation_names[] = {"total_lagrangian", "updated_lagrangian", NULL};
static const char *const initial_names[] = {"none", "cantilever_mode", NULL};

/* ---- materials ---------------------------------------------------------------------------- */

static ry_status read_material(ry_sim *sim, ry_case *c, solid *s, int m, ry_error *err) {
    char k1[96], k2[96], where[256];
    double E, nu;
    snprintf(k1, sizeof k1, "materials[%d].youngs_modulus", m);
    if (ry_case_has(c, k1)) {
        snprintf(k2, sizeof k2, "materials[%d].poisson_ratio", m);
        RY_TRY(ry_case_positive(c, k1, NULL, &E, err));
        RY_TRY(ry_case_double(c, k2, NULL, -0.99, 0.49, &nu, err));
    } else {
        double G, K;
        snprintf(k1, sizeof k1, "materials[%d].shear_modulus", m);
        snprintf(k2, sizeof k2, "materials[%d].bulk_modulus", m);
        RY_CHECK(err, ry_case_has(c, k1), RY_ERR_INPUT,
                 "%s: key 'materials[%d]': a solid material needs youngs_modulus and "
                 "poisson_ratio, or shear_modulus and bulk_modulus",
                 ry_case_where(c, k1, where, sizeof where), m);
        RY_TRY(ry_case_positive(c, k1, NULL, &G, err));
        RY_TRY(ry_case_positive(c, k2, NULL, &K, err));
        E = 9 * K * G / (3 * K + G);
        nu = (3 * K - 2 * G) / (2 * (3 * K + G));
        RY_CHECK(err, nu <= 0.49, RY_ERR_INPUT,
                 "%s: key '%s': Poisson's ratio %g from these moduli is too close to 1/2",
                 ry_case_where(c, k2, where, sizeof where), k2, nu);
    }
    double mu = E / (2 * (1 + nu)), lam = E * nu / ((1 + nu) * (1 - 2 * nu));
    if (sim->dim == 2 && s->plane == PLANE_STRESS) lam = 2 * lam * mu / (lam + 2 * mu);
    s->lam[m] = lam;
    s->mu[m] = mu;
    s->E[m] = E;
    s->modulus[m] = lam + 2 * mu;
    return RY_OK;
}

/* ---- loads -------------------------------------------------------------------------------- */

/* External force per particle (N; per metre of depth in 2D) for the load types:
 *   end      P = load.intensity at the free end: statically equivalent to a point load at
 *            x = L (same resultant and moment), spread evenly over the last column (weight 3/2)
 *            and the one before it (weight -1/2), whose centres lie at L - dx/2 and L - 3dx/2;
 *   uniform  q(s) = q0, linear q(s) = q0 s / L, cosine q(s) = q0 cos(pi s / (2 L)) (N/m;
 *            per metre of depth in 2D), s the distance from the root: f_i = q(s_i) V_i / A.
 * The direction is load.direction (normalised). */
static ry_status load_forces(ry_sim *sim, solid *s, ry_error *err) {
    ry_particles *ps = &sim->ps;
    for (int d = 0; d < sim->dim; ++d) memset(ps->f[s->f_fext[d]], 0, ps->n * sizeof(double));
    if (s->load == LOAD_NONE) return RY_OK;
    ry_beam b;
    RY_TRY(ry_beam_geometry(sim, &b, err));
    double *count = calloc((size_t)b.ncol, sizeof *count);
    RY_CHECK(err, count != NULL, RY_ERR_NOMEM, "out of memory");
    /* symmetry planes: the load is the whole problem's (the beam with its mirror images) */
    const double whole = ry_box_mirrors(&sim->box);
    b.area *= whole;
    for (size_t i = 0; i < ps->n; ++i)
        if (ps->kind[i] == RY_KIND_SOLID)
            count[ry_beam_column(&b, sim->dx, ps->f[s->f_X[0]][i])] += whole;
    const double pi = 3.14159265358979323846;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_SOLID) continue;
        int k = ry_beam_column(&b, sim->dx, ps->f[s->f_X[0]][i]);
        double sx = ps->f[s->f_X[0]][i] - b.x_root, f = 0;
        double v = ps->f[RY_F_MASS][i] / sim->mat[ps->material[i]].density;
        switch (s->load) {
        case LOAD_END:
            if (b.ncol < 2)
                f = s->load_q / count[k];
            else if (k == b.ncol - 1)
                f = 1.5 * s->load_q / count[k];
            else if (k == b.ncol - 2)
                f = -0.5 * s->load_q / count[k];
            break;
        case LOAD_UNIFORM:
            f = s->load_q * v / b.area;
            break;
        case LOAD_LINEAR:
            f = s->load_q * sx / b.length * v / b.area;
            break;
        case LOAD_COSINE:
            f = s->load_q * cos(0.5 * pi * sx / b.length) * v / b.area;
            break;
        default:
            break;
        }
        for (int d = 0; d < sim->dim; ++d) ps->f[s->f_fext[d]][i] = f * s->load_dir[d];
    }
    free(count);
    return RY_OK;
}

/* Initial velocity (scheme.initial_velocity) and the direction the probe tip_deflection
 * measures along: the load's, else the initial velocity's, else -y (2D) or -z (3D).
 *   cantilever_mode  the first bending mode of a clamped-free beam (Gray, Monaghan & Swift
 *                    2001): v(s) = V f(s) / f(L) along the direction, s the distance from the
 *                    root, f(s) = (sin kL + sinh kL)(cos ks - cosh ks)
 *                             - (cos kL + cosh kL)(sin ks - sinh ks), kL = 1.875104. */
static ry_status initial_velocity(ry_sim *sim, ry_case *c, solid *s, ry_error *err) {
    const int dim = sim->dim;
    int mode;
    memset(s->probe_dir, 0, sizeof s->probe_dir);
    s->probe_dir[dim - 1] = -1;
    if (s->load != LOAD_NONE) memcpy(s->probe_dir, s->load_dir, sizeof s->probe_dir);
    RY_TRY(ry_case_choice(c, "scheme.initial_velocity.type", "none", initial_names, &mode, err));
    if (mode == 0) return RY_OK;
    double V, dir[3] = {0, 0, 0}, def[3] = {0, 0, 0}, n2 = 0;
    char where[256];
    def[dim - 1] = 1;
    RY_TRY(
        ry_case_double(c, "scheme.initial_velocity.tip_speed", NULL, -INFINITY, INFINITY, &V, err));
    RY_TRY(ry_case_vector(c, "scheme.initial_velocity.direction", def, dim, dir, err));
    for (int d = 0; d < dim; ++d) n2 += dir[d] * dir[d];
    RY_CHECK(err, n2 > 0, RY_ERR_INPUT, "%s: key 'scheme.initial_velocity.direction': zero vector",
             ry_case_where(c, "scheme.initial_velocity.direction", where, sizeof where));
    for (int d = 0; d < dim; ++d) dir[d] /= sqrt(n2);
    if (s->load == LOAD_NONE) memcpy(s->probe_dir, dir, sizeof dir);
    ry_beam b;
    RY_TRY(ry_beam_geometry(sim, &b, err));
    const double k = RY_CANTILEVER_KL1 / b.length, kL = RY_CANTILEVER_KL1;
    const double A = sin(kL) + sinh(kL), B = cos(kL) + cosh(kL);
    const double fL = A * (cos(kL) - cosh(kL)) - B * (sin(kL) - sinh(kL));
    ry_particles *ps = &sim->ps;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_SOLID) continue;
        const double ks = k * (ps->f[s->f_X[0]][i] - b.x_root);
        const double f = A * (cos(ks) - cosh(ks)) - B * (sin(ks) - sinh(ks));
        for (int d = 0; d < dim; ++d) ps->f[RY_F_VX + d][i] = V * f / fL * dir[d];
    }
    return RY_OK;
}

/* ---- set-up ------------------------------------------------------------------------------- */

static ry_status solid_init(ry_sim *sim, ry_case *c, void **state, ry_error *err) {
    solid *s = calloc(1, sizeof *s);
    RY_CHECK(err, s != NULL, RY_ERR_NOMEM, "out of memory");
    *state = s;
    double zero = 0.0;
    char where[256];
    RY_TRY(ry_case_choice(c, "scheme.formulation", "total_lagrangian", formulation_names, &s->ul,
                          err));
    RY_TRY(ry_case_choice(c, "scheme.correction", "quadratic", corr_names, &s->correction, err));
    RY_TRY(
        ry_case_choice(c, "scheme.clamp", s->ul ? "block" : "face", clamp_names, &s->clamp, err));
    if (s->ul) {
    } else {
        RY_TRY(ry_case_choice(c, "scheme.integration",
                              s->correction == CORR_QUADRATIC ? "gradient" : "nodal",
                              integration_names, &s->integration, err));
        RY_CHECK(err, s->integration == INTEGRATION_NODAL || s->correction == CORR_QUADRATIC,
                 RY_ERR_INPUT,
                 "%s: key 'scheme.integration': gradient needs scheme.correction: quadratic",
                 ry_case_where(c, "scheme.integration", where, sizeof where));
        double hg = 0.1;
        RY_TRY(ry_case_double(c, "scheme.hourglass", &hg, 0.0, 100.0, &s->hourglass, err));
    }
    if (sim->dim == 2)
        RY_TRY(ry_case_choice(c, "scheme.plane", "stress", plane_names, &s->plane, err));
    RY_TRY(ry_case_choice(c, "scheme.load.type", "none", load_names, &s->load, err));
    if (s->load != LOAD_NONE) {
        double def[3] = {0, 0, 0};
        def[sim->dim - 1] = -1;
        RY_TRY(
            ry_case_double(c, "scheme.load.intensity", NULL, -INFINITY, INFINITY, &s->load_q, err));
        RY_TRY(ry_case_vector(c, "scheme.load.direction", def, sim->dim, s->load_dir, err));
        double n2 = 0;
        for (int d = 0; d < sim->dim; ++d) n2 += s->load_dir[d] * s->load_dir[d];
        RY_CHECK(err, n2 > 0, RY_ERR_INPUT, "%s: key 'scheme.load.direction': zero vector",
                 ry_case_where(c, "scheme.load.direction", where, sizeof where));
        for (int d = 0; d < sim->dim; ++d) s->load_dir[d] /= sqrt(n2);
    }
    RY_TRY(ry_case_choice(c, "scheme.relaxation", "none", relax_names, &s->relax, err));
    if (s->relax == RELAX_VISCOUS)
        RY_TRY(ry_case_positive(c, "scheme.damping", NULL, &s->damping, err));
    RY_TRY(ry_case_double(c, "scheme.residual", &zero, 0.0, 1.0, &s->residual_tol, err));
    s->residual = NAN;

    ry_particles *ps = &sim->ps;
    s->lam = calloc((size_t)sim->nmat, sizeof *s->lam);
    s->mu = calloc((size_t)sim->nmat, sizeof *s->mu);
    s->E = calloc((size_t)sim->nmat, sizeof *s->E);
    s->modulus = calloc((size_t)sim->nmat, sizeof *s->modulus);
    RY_CHECK(err, s->lam && s->mu && s->E && s->modulus, RY_ERR_NOMEM, "out of memory");
    int *used = calloc((size_t)sim->nmat, sizeof *used);
    RY_CHECK(err, used != NULL, RY_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < ps->n; ++i) used[ps->material[i]] = 1;
    ry_status st = RY_OK;
    for (int m = 0; m < sim->nmat && st == RY_OK; ++m)
        if (used[m]) st = read_material(sim, c, s, m, err);
    if (st != RY_OK) {
        free(used);
        return st;
    }
    /* Time step from the fastest wave. With dynamic relaxation only the free (solid) particles
     * count: the ones next to a stiffer clamp get a larger fictitious mass instead. */
    for (size_t i = 0; i < ps->n; ++i) {
        const int m = ps->material[i];
        if (s->relax == RELAX_NONE || ps->kind[i] == RY_KIND_SOLID)
            s->c_max = fmax(s->c_max, sqrt(s->modulus[m] / sim->mat[m].density));
    }
    free(used);
    for (size_t i = 0; i < ps->n; ++i)
        RY_CHECK(err, ps->kind[i] != RY_KIND_FLUID, RY_ERR_INPUT,
                 "%s: the scheme 'solid' takes bodies of kind solid or wall (clamped), not fluid",
                 ry_case_where(c, "bodies", where, sizeof where));

    static const char *const Xn[3] = {"x0", "y0", "z0"};
    static const char *const fn[3] = {"load_x", "load_y", "load_z"};
    static const char *const un[3] = {"displacement_x", "displacement_y", "displacement_z"};
    for (int d = 0; d < 3; ++d) {
        RY_TRY(ry_particles_add_field(ps, Xn[d], "m", d, RY_FIELD_STATE | RY_FIELD_POSITION,
                                      &s->f_X[d], err));
        RY_TRY(ry_particles_add_field(ps, fn[d], "N", d, RY_FIELD_STATE, &s->f_fext[d], err));
        RY_TRY(ry_particles_add_field(ps, un[d], "m", d, RY_FIELD_OUTPUT, &s->f_u[d], err));
    }
    RY_TRY(ry_particles_add_field(ps, "strain_energy_density", "J/m^3", -1, RY_FIELD_OUTPUT,
                                  &s->f_psi, err));
    for (int d = 0; d < sim->dim; ++d)
        memcpy(ps->f[s->f_X[d]], ps->f[RY_F_X + d], ps->n * sizeof(double));
    for (size_t i = 0; i < ps->n; ++i)
        if (ps->kind[i] == RY_KIND_WALL)
            for (int d = 0; d < sim->dim; ++d) ps->f[RY_F_VX + d][i] = 0;
    RY_TRY(load_forces(sim, s, err));
    RY_TRY(initial_velocity(sim, c, s, err));
    if (s->ul) RY_TRY(ry_solid_ul_init(sim, c, s, err));
    return RY_OK;
}

static void solid_free(void *state) {
    solid *s = state;
    if (!s) return;
    ry_cells_free(&s->cells);
    ry_nlist_free(&s->nl);
    free(s->G);
    free(s->H);
    free(s->Q);
    free(s->rev);
    free(s->vol);
    free(s->A);
    free(s->r2);
    free(s->lam);
    free(s->mu);
    free(s->E);
    free(s->F);
    free(s->modulus);
    free(s->mscale);
    free(s->hgc);
    ry_solid_ul_free(s);
    free(s);
}

/* Kinetic energy of the solid (with the relaxation's mass scaling), over all ranks. */
static double owned_kinetic_energy(ry_sim *sim, const double *mscale) {
    const double e =
        ry_particles_kinetic_energy_of(&sim->ps, sim->dim, RY_KIND_SOLID, mscale, sim->halo);
    return sim->par ? sim->par->sum(sim, e) : e;
}

/* Forces for the current positions and velocities; the updated-Lagrangian form also advances
 * its density and stress by dt (0 before the first step). */
static ry_status evaluate(ry_sim *sim, solid *s, double dt, ry_error *err) {
    if (s->ul) {
        RY_TRY(ry_solid_ul_evaluate(sim, s, dt, err));
    } else {
        if (!s->built) RY_TRY(ry_solid_tl_build(sim, s, err));
        if (sim->par) RY_TRY(sim->par->halo_update(sim, err)); /* the halo's positions */
        ry_solid_tl_forces(sim, s);
    }
    s->have_forces = 1;
    return RY_OK;
}

static ry_status solid_dt(ry_sim *sim, void *state, double *dt, ry_error *err) {
    solid *s = state;
    (void)err;
    *dt = sim->cfl * sim->kernel.h / s->c_max;
    /* Total-Lagrangian dynamics (no relaxation): the corrected gradient weights of the particles
     * on free surfaces and next to the clamp reach higher frequencies than the P wave between
     * interior particles. Measured on the oscillating plate (H/dx = 4, nu = 0.3975, plane strain,
     * face clamp): the energy runs away within one period at CFL 0.25 and 0.2, after 0.65 s
     * (2.5 periods) at 0.125, and is conserved to 1e-4 over 10 periods at 0.0625; the limit is
     * therefore a quarter of the CFL step. Dynamic relaxation keeps the full step (kinetic
     * damping removes the energy). */
    if (!s->ul && s->relax == RELAX_NONE) *dt *= RY_SOLID_TL_DYNAMIC_DT;
    return RY_OK;
}

static ry_status solid_step(ry_sim *sim, void *state, double dt, ry_error *err) {
    solid *s = state;
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    if (!s->ul && !s->built) RY_TRY(ry_solid_tl_build(sim, s, err)); /* e.g. after a restart */
    if (!s->have_forces) RY_TRY(evaluate(sim, s, 0.0, err));
    const double keep = s->relax == RELAX_VISCOUS ? (1 - 0.5 * s->damping * dt) : 1.0;
    const double gain = s->relax == RELAX_VISCOUS ? 1.0 / (1 + 0.5 * s->damping * dt) : 1.0;
#pragma omp parallel for schedule(static) if (n >= RY_SOLID_PARALLEL_MIN)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_SOLID) continue;
        for (int d = 0; d < dim; ++d) {
            double *v = ps->f[RY_F_VX + d];
            v[i] = (keep * v[i] + dt * ps->f[RY_F_AX + d][i]) * gain;
        }
    }
    if (s->relax == RELAX_KINETIC) {
        double ke = owned_kinetic_energy(sim, s->mscale);
        if (ke < s->ke_prev) { /* past a maximum of the kinetic energy: stop everything */
            for (size_t i = 0; i < n; ++i)
                for (int d = 0; d < dim; ++d) ps->f[RY_F_VX + d][i] = 0;
            s->peaks++;
            ke = 0;
        }
        s->ke_prev = ke;
    }
#pragma omp parallel for schedule(static) if (n >= RY_SOLID_PARALLEL_MIN)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_SOLID) continue;
        for (int d = 0; d < dim; ++d) {
            ps->f[RY_F_X + d][i] += dt * ps->f[RY_F_VX + d][i];
            ps->f[s->f_u[d]][i] = ps->f[RY_F_X + d][i] - ps->f[s->f_X[d]][i];
        }
    }
    RY_TRY(evaluate(sim, s, dt, err));
    if (s->relax != RELAX_NONE && s->residual_tol > 0 && s->residual < s->residual_tol)
        ry_sim_finish(sim);
    return RY_OK;
}

static int solid_vars(void *state, ry_state_var *v, int max) {
    solid *s = state;
    const ry_state_var all[] = {{"residual", &s->residual, NULL, NULL},
                                {"ke_prev", &s->ke_prev, NULL, NULL},
                                {"peaks", NULL, NULL, &s->peaks},
                                {"have_forces", NULL, &s->have_forces, NULL}};
    int n = (int)(sizeof all / sizeof all[0]);
    if (n > max) n = max;
    memcpy(v, all, (size_t)n * sizeof *v);
    return n;
}

/* ---- statistics ---------------------------------------------------------------------------- */

/* Smallest distance between neighbouring particles of the solid (clamp included), in initial
 * spacings: pairs of the current neighbour list (updated-Lagrangian) or of the reference one
 * (total-Lagrangian). Tensile clumping shows as pairs drawing much closer than a spacing. NAN
 * before a list is built. */
static double min_spacing(const ry_sim *sim, const solid *s) {
    /* (the current list where the reference one is not built: a distributed run's output) */
    const ry_nlist *nl = s->ul || !s->nl.offset ? &sim->nl : &s->nl;
    const ry_particles *ps = &sim->ps;
    if (!nl->offset || nl->n != ps->n) return NAN;
    double m2 = INFINITY;
    for (size_t i = 0; i < ps->n; ++i)
        for (size_t q = nl->offset[i]; q < nl->offset[i + 1]; ++q) {
            const size_t j = nl->j[q];
            double r2 = 0;
            for (int d = 0; d < sim->dim; ++d) {
                const double dd = ps->f[RY_F_X + d][j] - ps->f[RY_F_X + d][i];
                r2 += dd * dd;
            }
            m2 = fmin(m2, r2);
        }
    return sqrt(m2) / sim->dx;
}

/* Statistics: the relative residual of the last force evaluation, the smallest spacing of
 * neighbours (min_spacing) and the direction the tip deflection is measured along (the load's,
 * else the initial velocity's, else -y or -z). */
static int solid_stat(const ry_sim *sim, const void *state, const char *name, double *value) {
    static const char *const dir_names[3] = {"load_direction_x", "load_direction_y",
                                             "load_direction_z"};
    const solid *s = state;
    if (!strcmp(name, "residual")) {
        *value = s->residual;
        return 1;
    }
    if (!strcmp(name, "min_spacing")) {
        *value = min_spacing(sim, s);
        return 1;
    }
    for (int d = 0; d < 3; ++d)
        if (!strcmp(name, dir_names[d])) {
            *value = s->probe_dir[d];
            return 1;
        }
    return 0;
}

/* The updated-Lagrangian form's per-particle arrays are indexed like the particles: their order
 * is kept. Distributed: the total-Lagrangian form's neighbours are those of the reference
 * configuration, and so are its subdomains and halo. */
static void solid_needs(const ry_sim *sim, const void *state, ry_scheme_needs *nd) {
    const solid *s = state;
    nd->keep_order = s->ul;
    if (!s->ul)
        for (int d = 0; d < sim->dim; ++d) nd->dd_x[d] = s->f_X[d];
}

const ry_scheme_type ry_scheme_solid = {
    .name = "solid",
    .summary = "elastic solid: total-Lagrangian SPH with corrected kernel gradients, or "
               "updated-Lagrangian with Jaumann-rate stress and artificial stress (seed 000)",
    .init = solid_init,
    .stable_dt = solid_dt,
    .step = solid_step,
    .free = solid_free,
    .state_vars = solid_vars,
    .stat = solid_stat,
    .needs = solid_needs,
    .caps = 0};
