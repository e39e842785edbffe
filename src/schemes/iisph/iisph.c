/* Implicit incompressible SPH (seed 004, SPEC section 4; docs/iisph.md).
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
 *                  (scheme.light_phase: boundary; docs/iisph.md, "A light phase")
 *  time            symplectic Euler: v = v* + dt a^p, x += dt v;
 *                  dt = min(CFL h / |v|max, 0.25 sqrt(h / |a|max), 0.045 h^2 / nu_max,
 *                  surface-tension limit, dt_max). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "util/cell_key.h"
#include "linalg/sparse.h"
#include "ryushi/sim.h"
#include "ryushi/surface_tension.h"
#include "schemes/iisph/iisph.h"
#include "physics/colour_field.h"
#include "pairs/pair_cache.h"
#include "physics/polymer_stress.h"
#include "ryushi/collisions.h"
#include "ryushi/rheology.h"

/* Grows the array ptr to count elements; on failure leaves it as it is and clears ok. */
#define RY_IISPH_GROW(ptr, count, ok)                                                              \
    do {                                                                                           \
        void *q_ = realloc((ptr), (count) * sizeof *(ptr));                                        \
        if (q_)                                                                                    \
            (ptr) = q_;                                                                            \
        else                                                                                       \
            (ok) = 0;                                                                              \
    } while (0)

/* The walls' pressure extrapolation (wall_extrapolate) as lists built once per step: each wall or
 * inlet particle with a mobile neighbour within the kernel (w, nw of them), those neighbours (j,
 * from off[k] to off[k + 1]), W_wf and rho_f g . x_wf. An iteration of the solve then reads 20
 * bytes per entry instead of the pair cache's 64, and skips the walls beyond the fluid's
 * reach. */
typedef struct wall_map {
    size_t nw, cap_n, cap_e;
    uint32_t *w, *j;
    size_t *off, *cnt; /* cnt: per particle, the mobile neighbours (cap_n) */
    double *wt, *h;
} wall_map;

/* The pairs of the pressure solve's iterations (grad_list_build): for each mobile particle i
 * (from off[i] to off[i + 1]) its neighbours j with a non-zero kernel gradient and grad_i W_ij
 * (3 per entry): an iteration reads 28 bytes per pair instead of the cache's 64. */
typedef struct grad_list {
    size_t cap_n, cap_e;
    size_t *off;
    uint32_t *j;
    double *g;
} grad_list;

typedef struct iisph {
    double omega, tol, warm;
    long max_iter, min_iter;
    int slip; /* free-slip walls: no viscous coupling to walls */
    double delta0;
    double vmax, amax;
    int have_state;
    /* iteration statistics */
    long iters_last, iters_total, solves;
    double error_last;
    int colour_on;
    ry_colour colour;
    ry_pair_cache pc;
    double *delta, *dstar, *aii, *dii, *sum, *pnew, *acc; /* per particle scratch */
    double *vg[3]; /* velocity seen by the viscous term, one array per component */
    size_t cap;
    double *mu;       /* dynamic viscosity per material */
    double mu_corr;   /* viscosity factor (scheme.viscosity_correction: lattice) */
    int morris;       /* scheme.viscous_form: morris */
    double cvisc;     /* its explicit time-step factor: dt <= cvisc h^2 / nu */
    int ghost;        /* scheme.wall_velocity: ghost (Adami et al. 2012) */
    ry_sph_rheo rheo; /* non-Newtonian materials */
    /* Free-surface tension (the surface_tension section; docs/iisph.md): */
    ry_surface_tension st;
    double st_beta;        /* CSF pressure form: surface particles have delta < st_beta delta0 */
    ry_st_work stw;        /* the Laplace jump P_i of the surface particles (0 elsewhere) and their
                              tag (1) */
    double coll_r, coll_e; /* artificial repulsion: distance [m], restitution */
    /* scheme.viscosity: implicit (Morris form, backward Euler; docs/iisph.md) */
    int implicit;
    double vtol;
    ry_csr A;
    int32_t *unk;    /* unknown number of a mobile particle, else -1 */
    double *vb, *vx; /* right-hand sides (3 per unknown); the components' and their solutions */
    double *vtmp;    /* per particle: halo entries on their way from the owners */
    uint8_t *vown;   /* per unknown: owned by this process (a distributed run) */
    ry_particle_unknowns vpu; /* the distribution of the solve under way */
    size_t vcap;
    long viters_last, viters_total;
    wall_map wm;
    grad_list gl;
    /* A light phase as a moving boundary (scheme.light_phase: boundary; docs/iisph.md, "A light
     * phase"): */
    int light_on;       /* some fluid material is light */
    uint8_t *light_mat; /* per material: light (density below RY_IISPH_LIGHT of the heaviest) */
    uint8_t *lt;        /* per particle: a mobile particle of a light material */
    double *pl;         /* per particle: the pressure a light row reads at a wall-like neighbour */
    wall_map wml;       /* the light rows' extrapolation: walls and heavy fluid from light fluid */
    double light_tol;   /* scheme.light_tolerance: the light phase's average density error */
} iisph;

/* A material lighter than this share of the heaviest is light (air against water: 1.2e-3). */
#define RY_IISPH_LIGHT 0.05

/* Kinds that move under the fluid equations (and take part as fluid): fluid and outlet
 * buffers; the pressure is solved for fluid only (outlet buffers keep the outlet pressure). */
static const int MOBILE[RY_KIND_COUNT] = {[RY_KIND_FLUID] = 1, [RY_KIND_OUTLET] = 1};

/* The pair (i, j) with a light phase as a moving boundary (docs/iisph.md, "A light phase").
 * A heavy row i leaves its light neighbours j out (pair_skip: not in its pair lists): its
 * interface is a free surface. A light row i counts its heavy neighbours j as walls that move:
 * in its number density and its viscosity (no slip, with v_j), in its continuity with v*_j
 * and the pressure displacement D_j of the heavy solve's current iterate, and in its force
 * with the light phase's pressure extrapolated onto j (pair_force_mobile is 0). */
static inline int pair_skip(const iisph *s, size_t i, uint32_t j) {
    return s->light_on && !s->lt[i] && s->lt[j];
}
static inline int pair_force_mobile(const iisph *s, const uint8_t *kind, size_t i, uint32_t j) {
    return MOBILE[kind[j]] && (!s->light_on || !s->lt[i] || s->lt[j]);
}

/* A pocket of the light phase that the heavy fluid encloses (a bubble) is not held: the heavy
 * phase does not feel the light one's pressure and fills it (docs/iisph.md, "A light phase").
 * The set-up refuses one. The light particles are joined into bodies (neighbours within
 * 1.5 dx); a body is a pocket when none of its particles lacks lattice neighbours within
 * 1.5 dx (a free surface: fewer than 3/4 of the full lattice's 8 in 2D, 18 in 3D) and none has a
 * wall neighbour. *size receives the size of the first pocket found (0: none), *where one of
 * its particles. */
static ry_status light_pocket(const ry_sim *sim, const iisph *s, size_t *size_out, size_t *where,
                              ry_error *err) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const double dx = sim->dx, reach = 1.5 * dx, r2 = reach * reach * (1 + 1e-9);
    const int full = dim == 3 ? 18 : 8;
    ry_cell_key *k = malloc((n ? n : 1) * sizeof *k);
    uint8_t *seen = calloc(n ? n : 1, 1);
    uint32_t *stack = malloc((n ? n : 1) * sizeof *stack);
    if (!k || !seen || !stack) {
        free(k);
        free(seen);
        free(stack);
        RY_CHECK(err, 0, RY_ERR_NOMEM, "out of memory (light-phase pockets)");
    }
    for (size_t i = 0; i < n; ++i) {
        k[i].i = (uint32_t)i;
        for (int d = 0; d < 3; ++d)
            k[i].c[d] = d < dim ? (int64_t)floor(ps->f[RY_F_X + d][i] / reach) : 0;
    }
    qsort(k, n, sizeof *k, ry_cell_key_cmp);
    size_t found = 0;
    for (size_t seed = 0; seed < n && !found; ++seed) {
        if (!MOBILE[ps->kind[seed]] || !s->light_mat[ps->material[seed]] || seen[seed]) continue;
        size_t top = 0, size = 0;
        int open = 0;
        stack[top++] = (uint32_t)seed;
        seen[seed] = 1;
        while (top) {
            const size_t i = stack[--top];
            ++size;
            int count = 0;
            int64_t c[3] = {0, 0, 0};
            for (int d = 0; d < dim; ++d) c[d] = (int64_t)floor(ps->f[RY_F_X + d][i] / reach);
            for (int a = -1; a <= 1; ++a)
                for (int b = -1; b <= 1; ++b)
                    for (int e = dim == 3 ? -1 : 0; e <= (dim == 3 ? 1 : 0); ++e) {
                        const int64_t q[3] = {c[0] + a, c[1] + b, c[2] + e};
                        for (size_t m = ry_cell_key_find(k, n, q); m < n && ry_cell_same(k[m].c, q);
                             ++m) {
                            const size_t j = k[m].i;
                            if (j == i) continue;
                            double d2 = 0;
                            for (int d = 0; d < dim; ++d) {
                                const double u = ps->f[RY_F_X + d][i] - ps->f[RY_F_X + d][j];
                                d2 += u * u;
                            }
                            if (d2 > r2) continue;
                            ++count;
                            const int light = MOBILE[ps->kind[j]] && s->light_mat[ps->material[j]];
                            if (!MOBILE[ps->kind[j]]) open = 1; /* a wall: not enclosed by fluid */
                            if (light && !seen[j]) {
                                seen[j] = 1;
                                stack[top++] = (uint32_t)j;
                            }
                        }
                    }
            if (4 * count < 3 * full) open = 1;
        }
        if (!open) {
            found = size;
            *where = seed;
        }
    }
    free(k);
    free(seen);
    free(stack);
    *size_out = found;
    return RY_OK;
}

/* scheme.light_phase: with boundary (the default) a material lighter than RY_IISPH_LIGHT of the
 * heaviest is light, and the light and heavy phases are solved as two incompressible fluids,
 * each with the other as its boundary: the heavy phase does not see the light one (its
 * interface is a free surface, p >= 0), the light phase sees the heavy particles as moving
 * walls with their velocity and its own pressure extrapolated onto them (docs/iisph.md, "A
 * light phase"). The couplings this does not define are refused. */
static ry_status light_phase_init(ry_sim *sim, iisph *s, ry_case *c, ry_error *err) {
    static const char *const modes[] = {"coupled", "boundary", NULL};
    int boundary;
    RY_TRY(ry_case_choice(c, "scheme.light_phase", "boundary", modes, &boundary, err));
    s->light_mat = calloc((size_t)sim->nmat, 1);
    RY_CHECK(err, s->light_mat != NULL, RY_ERR_NOMEM, "out of memory");
    /* over the materials of the fluid, and of what inlets and outlets carry */
    const ry_particles *ps = &sim->ps;
    double rmax = 0;
    for (size_t i = 0; i < ps->n; ++i)
        if (MOBILE[ps->kind[i]] || ps->kind[i] == RY_KIND_INLET)
            rmax = fmax(rmax, sim->mat[ps->material[i]].density);
    for (int m = 0; m < sim->nmat; ++m)
        s->light_mat[m] = boundary && sim->mat[m].density < RY_IISPH_LIGHT * rmax;
    for (size_t i = 0; i < ps->n; ++i)
        if (MOBILE[ps->kind[i]] || ps->kind[i] == RY_KIND_INLET)
            s->light_on |= s->light_mat[ps->material[i]];
    /* The light phase's error does not reach the heavy phase: a looser tolerance (10 times the
     * heavy one by default) took the dam break under air from 15 to 5 iterations per step with
     * the same front and the same air speeds (docs/iisph.md). */
    double ltol = fmin(10.0 * s->tol, 0.1);
    RY_TRY(ry_case_double(c, "scheme.light_tolerance", &ltol, 1e-7, 0.1, &s->light_tol, err));
    if (!s->light_on) return RY_OK;
    int light = 0;
    while (!s->light_mat[light]) ++light;
    const char *key = s->st.model != RY_ST_NONE ? "surface_tension.model"
                      : s->implicit             ? "scheme.viscosity"
                                                : NULL;
    if (!key && s->rheo.on) key = "scheme.light_phase";
    if (!key) {
        size_t at = 0, pocket = 0;
        RY_TRY(light_pocket(sim, s, &pocket, &at, err));
        char where[256];
        RY_CHECK(err, pocket == 0, RY_ERR_INPUT,
                 "%s: key 'scheme.light_phase': %zu particles of the light material '%s' around "
                 "(%g, %g, %g) lie wholly inside the heavy fluid, a pocket the light phase does "
                 "not hold (the heavy phase fills it; docs/iisph.md, \"A light phase\")",
                 ry_case_where(c, "scheme.light_phase", where, sizeof where), pocket,
                 sim->mat[ps->material[at]].name, ps->f[RY_F_X][at], ps->f[RY_F_Y][at],
                 sim->dim == 3 ? ps->f[RY_F_Z][at] : 0.0);
    }
    char where[256];
    RY_CHECK(err, key == NULL, RY_ERR_INPUT,
             "%s: key '%s': not available with a light phase (material '%s' is lighter than %g "
             "of the heaviest, and scheme.light_phase is boundary%s); set scheme.light_phase: "
             "coupled",
             ry_case_where(c, key ? key : "scheme", where, sizeof where), key ? key : "",
             sim->mat[light].name, RY_IISPH_LIGHT,
             key && strcmp(key, "scheme.light_phase") == 0 ? ", with a non-Newtonian material"
                                                           : "");
    return RY_OK;
}

static ry_status iisph_init(ry_sim *sim, ry_case *c, void **state, ry_error *err) {
    iisph *s = calloc(1, sizeof *s);
    RY_CHECK(err, s != NULL, RY_ERR_NOMEM, "out of memory");
    *state = s;
    /* Distributed: every pass that reads its neighbours' results of the pass before gets them
     * synchronised, so a halo one search radius deep serves. */
    sim->halo_depth = 1;
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
    /* The lattice's value of the viscous term for a unit shear Laplacian (Wendland C2,
     * h = 1.4 dx: projected 0.85 in 2D, 0.90 in 3D; Morris 0.98). */
    const double eta2 = 0.01 * sim->kernel.h * sim->kernel.h;
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
    RY_TRY(light_phase_init(sim, s, c, err));
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
    /* Incompressible: densities stay within the tolerance inside the fluid (summation density
     * is lower at a free surface, so there is no lower bound). */
    sim->guard.rho_min = 0.0;
    sim->guard.rho_max = 1.5;
    return RY_OK;
}

static void wall_map_free(wall_map *m) {
    free(m->w);
    free(m->j);
    free(m->off);
    free(m->cnt);
    free(m->wt);
    free(m->h);
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
    free(s->unk);
    free(s->vb);
    free(s->vx);
    free(s->vown);
    ry_st_work_free(&s->stw);
    wall_map_free(&s->wm);
    free(s->gl.off);
    free(s->gl.j);
    free(s->gl.g);
    free(s->light_mat);
    free(s->lt);
    free(s->pl);
    wall_map_free(&s->wml);
    free(s);
}

static ry_status ensure(iisph *s, size_t n, ry_error *err) {
    if (s->cap >= n) return RY_OK;
    size_t cap = n + n / 4 + 16;
    /* one block: delta, dstar, aii (1 each), dii, sum, acc (3 each), pnew (1), vg (3) */
    double *b = realloc(s->delta, cap * 16 * sizeof(double));
    RY_CHECK(err, b != NULL, RY_ERR_NOMEM, "out of memory (%zu particles)", n);
    s->delta = b;
    s->dstar = b + cap;
    s->aii = b + 2 * cap;
    s->pnew = b + 3 * cap;
    s->dii = b + 4 * cap;
    s->sum = b + 7 * cap;
    s->acc = b + 10 * cap;
    for (int d = 0; d < 3; ++d) s->vg[d] = b + (13 + d) * cap;
    uint8_t *lt = realloc(s->lt, cap);
    if (lt) s->lt = lt;
    double *pl = realloc(s->pl, cap * sizeof *pl);
    if (pl) s->pl = pl;
    RY_CHECK(err, lt && pl, RY_ERR_NOMEM, "out of memory (%zu particles)", n);
    s->cap = cap;
    return RY_OK;
}

/* Dynamic viscosity of particle i: its material's, or with a non-Newtonian material the
 * reference density times the viscosity of its shear rate; times the lattice factor. */
static inline double dyn_viscosity(const ry_sim *sim, const iisph *s, size_t i) {
    const int m = sim->ps.material[i];
    return s->mu_corr * (s->rheo.on ? sim->mat[m].density * sim->ps.f[s->rheo.f_nu][i] : s->mu[m]);
}

/* The velocity the viscous term sees at each particle (s->vg): its own, or at a wall
 * with wall_velocity: ghost the ghost velocity of Adami et al. (2012, eq. 22-23),
 * 2 v_w - sum_f v_f W_wf / sum_f W_wf, which puts the no-slip condition on the wall surface. */
static void viscous_velocities(ry_sim *sim, iisph *s) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = s->pc.j; /* the pairs within the support */
    const size_t *end = s->pc.end;
    const double *cv = s->pc.v;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        double sw = 0, sv[3] = {0, 0, 0};
        if (s->ghost && ps->kind[i] == RY_KIND_WALL)
            for (size_t q = off[i]; q < end[i]; ++q) {
                const uint32_t j = nb[q];
                if (!MOBILE[ps->kind[j]]) continue;
                const double w = cv[q * RY_PAIR_STRIDE + RY_PW_W];
                sw += w;
                for (int d = 0; d < dim; ++d) sv[d] += w * ps->f[RY_F_VX + d][j];
            }
        for (int d = 0; d < 3; ++d) {
            const double v = d < dim ? ps->f[RY_F_VX + d][i] : 0.0;
            s->vg[d][i] = sw > 0 ? 2.0 * v - sv[d] / sw : v;
        }
    }
}

/* Number density, density, and the non-pressure accelerations (gravity, viscosity, polymer
 * stress) into acc. */
/* The viscous (explicit) and body-force acceleration of particle i into out[0..2] (zero where
 * it is not mobile); inlined with a literal dim, so that the sums stay in registers. */
static inline void force_row(const ry_sim *sim, const iisph *s, size_t i, const double *const vg[3],
                             double *out, int dim) {
    const ry_particles *ps = &sim->ps;
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = s->pc.j; /* the pairs within the support */
    const size_t *end = s->pc.end;
    const uint8_t *kind = ps->kind;
    const double *cv = s->pc.v, *m = ps->f[RY_F_MASS], *delta = s->delta;
    const double eta2 = 0.01 * sim->kernel.h * sim->kernel.h, cvis = 2.0 * (dim + 2);
    double a[3] = {0, 0, 0};
    if (MOBILE[kind[i]]) {
        const double mui = dyn_viscosity(sim, s, i);
        for (size_t q = off[i]; !s->implicit && q < end[i]; ++q) {
            const uint32_t j = nb[q];
            const double *P = cv + q * RY_PAIR_STRIDE;
            if (P[RY_PW_W] == 0 || pair_skip(s, i, j)) continue;
            /* a light row's heavy neighbour is a wall to it, always without slip */
            const int wall = !pair_force_mobile(s, kind, i, j);
            if (!MOBILE[kind[j]] && s->slip) continue;
            const double muj = wall ? mui : dyn_viscosity(sim, s, j);
            if (mui + muj <= 0) continue;
            const double mu = 2 * mui * muj / (mui + muj);
            const double vj = wall ? 1.0 / delta[i] : 1.0 / delta[j];
            if (s->morris) { /* 2 V mu x_ij . grad W / (r^2 + eta^2) v_ij (Morris 1997) */
                double xg = 0;
                for (int d = 0; d < dim; ++d) xg += P[RY_PW_DX + d] * P[RY_PW_GX + d];
                const double f = 2.0 * vj * mu * xg / (P[RY_PW_R2] + eta2);
                for (int d = 0; d < dim; ++d) a[d] += f * (vg[d][i] - vg[d][j]);
                continue;
            }
            double vx = 0;
            for (int d = 0; d < dim; ++d) vx += (vg[d][i] - vg[d][j]) * P[RY_PW_DX + d];
            const double f = cvis * vj * mu * vx / (P[RY_PW_R2] + eta2);
            for (int d = 0; d < dim; ++d) a[d] += f * P[RY_PW_GX + d];
        }
        const double inv_rho = 1.0 / (m[i] * delta[i]);
        for (int d = 0; d < dim; ++d) a[d] = a[d] * inv_rho + sim->gravity[d];
        if (s->rheo.ob)
            for (int d = 0; d < dim; ++d) a[d] += s->rheo.acc[3 * i + d];
    }
    for (int d = 0; d < 3; ++d) out[d] = a[d];
}

static ry_status densities_and_forces(ry_sim *sim, iisph *s, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const size_t *off = sim->nl.offset;
    const size_t *end = s->pc.end; /* the pairs within the support */
    const uint8_t *kind = ps->kind;
    const double *cv = s->pc.v, *m = ps->f[RY_F_MASS];
    const double w0 = sim->kernel.norm * ry_kernel_shape(sim->kernel.type, 0.0);
    double *delta = s->delta, *acc = s->acc;
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        double sw = w0;
        if (MOBILE[kind[i]])
            for (size_t q = off[i]; q < end[i]; ++q)
                if (!pair_skip(s, i, s->pc.j[q])) sw += cv[q * RY_PAIR_STRIDE + RY_PW_W];
        delta[i] = sw;
    }
    if (sim->par) sim->par->sync(sim, delta, 1); /* halo copies: their owners' values */
    for (size_t i = 0; i < n; ++i)
        if (MOBILE[kind[i]]) ps->f[RY_F_RHO][i] = m[i] * delta[i];
    viscous_velocities(sim, s);
    const double *vg[3] = {s->vg[0], s->vg[1], s->vg[2]};
    if (s->rheo.on) { /* the velocity gradient and the viscosity it gives; pnew is free here */
        double *vol = s->pnew;
        for (size_t i = 0; i < n; ++i) vol[i] = 1.0 / (MOBILE[kind[i]] ? delta[i] : s->delta0);
        RY_TRY(ry_sph_rheo_rates(&s->rheo, sim, &s->pc, MOBILE, vol, s->slip ? NULL : vg, err));
    }
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        double *a = acc + 3 * i;
        if (dim == 3)
            force_row(sim, s, i, vg, a, 3);
        else
            force_row(sim, s, i, vg, a, 2);
    }
    return RY_OK;
}

/* Iterations allowed to one component's viscous solve (the same on every process). */
#define RY_IISPH_VISCOUS_MAX_ITER 5000

/* Implicit viscosity (scheme.viscosity: implicit): the Morris term of densities_and_forces by
 * backward Euler, for each velocity component
 *   m_i v_i + sum_j c_ij (v_i - v_j) = m_i v*_i,  c_ij = -2 dt V_i V_j mu_ij x_ij . grad_i W_ij
 *                                                           / (r_ij^2 + 0.01 h^2) >= 0,
 * (the explicit term times m_i, whose pair coefficients are symmetric), walls and inlets with
 * their velocity (or the ghost velocity) as known values. The matrix is symmetric positive
 * definite: conjugate gradients with the Jacobi preconditioner (mps/sparse.h), from v*.
 * The viscous acceleration (v - v*)/dt is added to acc. */
static ry_status viscous_implicit(ry_sim *sim, iisph *s, double dt, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    if (s->vcap < n) {
        const size_t cap = n + n / 4 + 16;
        int32_t *u = realloc(s->unk, cap * sizeof *u);
        if (u) s->unk = u;
        double *b = realloc(s->vb, 3 * cap * sizeof *b);
        if (b) s->vb = b;
        double *x = realloc(s->vx, 7 * cap * sizeof *x);
        if (x) s->vx = x;
        uint8_t *o = realloc(s->vown, cap * sizeof *o);
        if (o) s->vown = o;
        RY_CHECK(err, u && b && x && o, RY_ERR_NOMEM, "out of memory (implicit viscosity)");
        s->vtmp = s->vx + 6 * cap;
        s->vcap = cap;
    }
    size_t nunk = 0;
    for (size_t i = 0; i < n; ++i) s->unk[i] = MOBILE[ps->kind[i]] ? (int32_t)nunk++ : -1;
    /* distributed: each process holds rows for its own and its halo's particles and the solver
     * uses its own only (NULL in a serial run) */
    ry_csr_dist dist;
    s->vpu = (ry_particle_unknowns){sim, s->unk, s->vown, s->vtmp};
    const ry_csr_dist *dd = ry_particle_dist(&s->vpu, &dist);
    s->viters_last = 0;
    if (nunk == 0 && !dd) return RY_OK; /* (distributed: the others' sums need this process) */
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = s->pc.j; /* the pairs within the support */
    const size_t *end = s->pc.end;
    const double *cv = s->pc.v, *m = ps->f[RY_F_MASS], *delta = s->delta;
    const double eta2 = 0.01 * sim->kernel.h * sim->kernel.h;
    ry_csr *A = &s->A;
    RY_TRY(ry_csr_reserve(A, nunk, 0, err));
    A->row[0] = 0;
#pragma omp parallel for schedule(dynamic, 256)
    for (size_t i = 0; i < n; ++i) {
        if (s->unk[i] < 0) continue;
        size_t len = 1;
        for (size_t q = off[i]; q < end[i]; ++q)
            len += s->unk[nb[q]] >= 0 && cv[q * RY_PAIR_STRIDE + RY_PW_W] != 0;
        A->row[(size_t)s->unk[i] + 1] = len;
    }
    for (size_t k = 0; k < nunk; ++k) A->row[k + 1] += A->row[k];
    RY_TRY(ry_csr_reserve(A, nunk, A->row[nunk], err));
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (s->unk[i] < 0) continue;
        const size_t k = (size_t)s->unk[i];
        size_t p = A->row[k];
        const size_t pdiag = p++;
        const double mui = dyn_viscosity(sim, s, i), vi = 1.0 / delta[i];
        double diag = m[i], known[3] = {0, 0, 0};
        for (size_t q = off[i]; q < end[i]; ++q) {
            const uint32_t j = nb[q];
            const double *P = cv + q * RY_PAIR_STRIDE;
            if (P[RY_PW_W] == 0) continue;
            const int wall = !MOBILE[ps->kind[j]];
            double c = 0;
            if (!(wall && s->slip)) {
                const double muj = wall ? mui : dyn_viscosity(sim, s, j);
                if (mui + muj > 0) {
                    double xg = 0;
                    for (int d = 0; d < dim; ++d) xg += P[RY_PW_DX + d] * P[RY_PW_GX + d];
                    const double vj = wall ? vi : 1.0 / delta[j];
                    c = -2.0 * dt * vi * vj * (2 * mui * muj / (mui + muj)) * xg /
                        (P[RY_PW_R2] + eta2);
                }
            }
            diag += c;
            if (!wall) {
                A->col[p] = (uint32_t)s->unk[j];
                A->val[p++] = -c;
            } else {
                for (int d = 0; d < dim; ++d) known[d] += c * s->vg[d][j];
            }
        }
        A->col[pdiag] = (uint32_t)k;
        A->val[pdiag] = diag;
        A->diag[k] = diag;
        for (int d = 0; d < 3; ++d)
            s->vb[3 * k + d] = d < dim ? m[i] * ps->f[RY_F_VX + d][i] + known[d] : 0.0;
    }
    /* component d: right-hand side from d nunk, solution from (3 + d) nunk; the components
     * are solved together, one pass over the matrix serving all three */
    const double *bd[3];
    double *xd[3];
    for (int d = 0; d < dim; ++d) {
        const double *v = ps->f[RY_F_VX + d];
        double *b = s->vx + (size_t)d * nunk, *x = s->vx + (size_t)(3 + d) * nunk;
        bd[d] = b;
        xd[d] = x;
        for (size_t i = 0; i < n; ++i)
            if (s->unk[i] >= 0) {
                b[s->unk[i]] = s->vb[3 * (size_t)s->unk[i] + d];
                x[s->unk[i]] = v[i];
            }
    }
    int it[3] = {0, 0, 0};
    double res[3] = {0, 0, 0};
    RY_TRY(ry_csr_pcg_multi(A, dim, bd, xd, s->vtol, RY_IISPH_VISCOUS_MAX_ITER, it, res, dd, err));
    for (int d = 0; d < dim; ++d) {
        double *v = ps->f[RY_F_VX + d];
        for (size_t i = 0; i < n; ++i)
            if (s->unk[i] >= 0) {
                const double vn = xd[d][s->unk[i]];
                s->acc[3 * i + d] += (vn - v[i]) / dt;
                v[i] = vn;
            }
        s->viters_last += it[d];
    }
    s->viters_total += s->viters_last;
    return RY_OK;
}

/* Wall and inlet particles: pressure extrapolated from the fluid with the hydrostatic term,
 * Adami, Hu & Adams (2012), eq. 27, p_w = sum_f (p_f + rho_f g . x_wf) W_wf / sum_f W_wf,
 * from the current iterate (not negative). wall_map_build sets the walls without a mobile
 * neighbour to 0 and lists the others' terms; wall_extrapolate sums them in the same order.
 * Two maps: RY_MAP_WALL, the walls from the (heavy) fluid into the pressure field; with a light
 * phase also RY_MAP_LIGHT, the walls and the heavy fluid from the light fluid into s->pl. */
enum { RY_MAP_WALL, RY_MAP_LIGHT };
static inline int wall_target(const iisph *s, const uint8_t *kind, size_t i, int map) {
    return kind[i] == RY_KIND_WALL || kind[i] == RY_KIND_INLET ||
           (map == RY_MAP_LIGHT && MOBILE[kind[i]] && !s->lt[i]);
}
static inline int wall_source(const iisph *s, const uint8_t *kind, size_t j, int map) {
    return MOBILE[kind[j]] && (map == RY_MAP_LIGHT ? s->lt[j] : !s->light_on || !s->lt[j]);
}

/* Builds map m of kind `map` (above), setting the targets without a source neighbour to 0 in
 * p. */
static ry_status wall_map_build(ry_sim *sim, iisph *s, wall_map *m, double *p, int map,
                                ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = s->pc.j; /* the pairs within the support */
    const size_t *end = s->pc.end;
    const uint8_t *kind = ps->kind;
    const double *cv = s->pc.v, *rho = ps->f[RY_F_RHO];
    if (m->cap_n < n + 1) {
        const size_t c = n + n / 4 + 16;
        int ok = 1;
        RY_IISPH_GROW(m->w, c, ok);
        RY_IISPH_GROW(m->off, c + 1, ok);
        RY_IISPH_GROW(m->cnt, c, ok);
        RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (wall pressure lists)");
        m->cap_n = c;
    }
#pragma omp parallel for schedule(dynamic, 256)
    for (size_t i = 0; i < n; ++i) {
        size_t c = 0;
        if (wall_target(s, kind, i, map))
            for (size_t q = off[i]; q < end[i]; ++q)
                c += wall_source(s, kind, nb[q], map) && cv[q * RY_PAIR_STRIDE + RY_PW_W] != 0;
        m->cnt[i] = c;
    }
    m->nw = 0;
    m->off[0] = 0;
    for (size_t i = 0; i < n; ++i) {
        if (!wall_target(s, kind, i, map)) continue;
        if (m->cnt[i] == 0) {
            p[i] = 0.0;
            continue;
        }
        m->w[m->nw] = (uint32_t)i;
        m->off[m->nw + 1] = m->off[m->nw] + m->cnt[i];
        m->nw++;
    }
    const size_t ne = m->off[m->nw];
    if (m->cap_e < ne) {
        const size_t c = ne + ne / 4 + 16;
        int ok = 1;
        RY_IISPH_GROW(m->j, c, ok);
        RY_IISPH_GROW(m->wt, c, ok);
        RY_IISPH_GROW(m->h, c, ok);
        RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (wall pressure lists)");
        m->cap_e = c;
    }
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t k = 0; k < m->nw; ++k) {
        const size_t i = m->w[k];
        size_t e = m->off[k];
        for (size_t q = off[i]; q < end[i]; ++q) {
            const uint32_t j = nb[q];
            const double *P = cv + q * RY_PAIR_STRIDE;
            if (!wall_source(s, kind, j, map) || P[RY_PW_W] == 0) continue;
            double gr = 0;
            for (int d = 0; d < dim; ++d) gr += sim->gravity[d] * P[RY_PW_DX + d];
            m->j[e] = j;
            m->wt[e] = P[RY_PW_W];
            m->h[e] = rho[j] * gr;
            e++;
        }
    }
    return RY_OK;
}

static ry_status grad_list_build(ry_sim *sim, iisph *s, ry_error *err) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = s->pc.j; /* the pairs within the support */
    const size_t *end = s->pc.end;
    const uint8_t *kind = ps->kind;
    const double *cv = s->pc.v;
    grad_list *l = &s->gl;
    if (l->cap_n < n + 1) {
        const size_t c = n + n / 4 + 16;
        int ok = 1;
        RY_IISPH_GROW(l->off, c + 1, ok);
        RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (pressure pairs)");
        l->cap_n = c;
    }
#define RY_GRAD_NONZERO(P) ((P)[RY_PW_GX] != 0 || (P)[RY_PW_GY] != 0 || (P)[RY_PW_GZ] != 0)
#pragma omp parallel for schedule(dynamic, 256)
    for (size_t i = 0; i < n; ++i) {
        size_t c = 0;
        if (MOBILE[kind[i]])
            for (size_t q = off[i]; q < end[i]; ++q)
                c += RY_GRAD_NONZERO(cv + q * RY_PAIR_STRIDE) && !pair_skip(s, i, nb[q]);
        l->off[i + 1] = c;
    }
    l->off[0] = 0;
    for (size_t i = 0; i < n; ++i) l->off[i + 1] += l->off[i];
    const size_t ne = l->off[n];
    if (l->cap_e < ne) {
        const size_t c = ne + ne / 4 + 16;
        int ok = 1;
        RY_IISPH_GROW(l->j, c, ok);
        RY_IISPH_GROW(l->g, 3 * c, ok);
        RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (pressure pairs)");
        l->cap_e = c;
    }
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        size_t e = l->off[i];
        if (!MOBILE[kind[i]]) continue;
        for (size_t q = off[i]; q < end[i]; ++q) {
            const double *P = cv + q * RY_PAIR_STRIDE;
            if (!RY_GRAD_NONZERO(P) || pair_skip(s, i, nb[q])) continue;
            l->j[e] = nb[q];
            for (int d = 0; d < 3; ++d) l->g[3 * e + d] = P[RY_PW_GX + d];
            e++;
        }
    }
#undef RY_GRAD_NONZERO
    return RY_OK;
}

/* The targets of map m into out from the sources' pressures p (out may be p). */
static void wall_extrapolate(const wall_map *m, const double *p, double *out) {
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t k = 0; k < m->nw; ++k) {
        double sw = 0, sp = 0;
        for (size_t e = m->off[k]; e < m->off[k + 1]; ++e) {
            sw += m->wt[e];
            sp += (p[m->j[e]] + m->h[e]) * m->wt[e];
        }
        out[m->w[k]] = fmax(sp / sw, 0.0); /* sw > 0: every entry has W > 0 */
    }
}

/* p_j / delta_j^2 of the pair (i, j): a mobile j's own, a wall's extrapolated pressure with the
 * volume of i (a light row: the walls and the heavy particles with the light phase's
 * extrapolation pl); neighbour_pressure_sum sums it times grad_i W_ij over the pairs of row i,
 * inlined with a literal dim so that the sums stay in registers. */
static inline double neighbour_pressure(const iisph *s, const uint8_t *kind, const double *p,
                                        size_t i, uint32_t j) {
    const double *delta = s->delta;
    if (pair_force_mobile(s, kind, i, j)) return p[j] / (delta[j] * delta[j]);
    const double *pw = s->light_on && s->lt[i] ? s->pl : p;
    return pw[j] / (delta[i] * delta[i]);
}

static inline void neighbour_pressure_sum(const iisph *s, const uint8_t *kind, const double *p,
                                          size_t i, double *a, int dim) {
    const grad_list *gl = &s->gl;
    for (size_t e = gl->off[i]; e < gl->off[i + 1]; ++e) {
        const double f = neighbour_pressure(s, kind, p, i, gl->j[e]), *G = gl->g + 3 * e;
        for (int d = 0; d < dim; ++d) a[d] += f * G[d];
    }
}

/* S_i = sum_j d_ij p_j = -(dt^2 / m_i) sum_j p_j / delta_j^2 grad_i W_ij (row i). */
static inline void pressure_sum_row(const iisph *s, const uint8_t *kind, const double *m,
                                    const double *p, double dt2, size_t i, double *out, int dim) {
    double a[3] = {0, 0, 0};
    if (MOBILE[kind[i]]) {
        neighbour_pressure_sum(s, kind, p, i, a, dim);
        for (int d = 0; d < dim; ++d) a[d] *= -dt2 / m[i];
    }
    for (int d = 0; d < 3; ++d) out[d] = a[d];
}

static void pressure_sums(ry_sim *sim, iisph *s, const double *p, double dt2) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const uint8_t *kind = ps->kind;
    const double *m = ps->f[RY_F_MASS];
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        double *out = s->sum + 3 * i;
        if (dim == 3)
            pressure_sum_row(s, kind, m, p, dt2, i, out, 3);
        else
            pressure_sum_row(s, kind, m, p, dt2, i, out, 2);
    }
}

/* The Jacobi update's sum over the pairs of fluid particle i: sum_j (S_i - D_j) . grad_i W_ij,
 * with D_j the part of j's sum without p_i (inlined with a literal dim). */
static inline double jacobi_rest(const iisph *s, const grad_list *gl, const uint8_t *kind,
                                 const double *m, const double *p, double dt2, size_t i, int dim) {
    const double *si = s->sum + 3 * i;
    const double di2 = s->delta[i] * s->delta[i];
    double rest = 0;
    for (size_t e = gl->off[i]; e < gl->off[i + 1]; ++e) {
        const uint32_t j = gl->j[e];
        const double *G = gl->g + 3 * e;
        double t = 0;
        for (int d = 0; d < dim; ++d) t += si[d] * G[d];
        if (MOBILE[kind[j]]) {
            /* D_j without the part from p_i: d_jj p_j + S_j - d_ji p_i (a heavy j of a light
             * row: none, j does not see i) */
            const double *sj = s->sum + 3 * j, *djj = s->dii + 3 * j;
            const double cji = pair_force_mobile(s, kind, i, j) ? dt2 / (m[j] * di2) * p[i] : 0.0;
            for (int d = 0; d < dim; ++d) t -= (djj[d] * p[j] + sj[d] - cji * G[d]) * G[d];
        }
        rest += t;
    }
    return rest;
}

/* The pressure Poisson equation by relaxed Jacobi; returns the iterations. */
static long pressure_solve(ry_sim *sim, iisph *s, double dt) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const uint8_t *kind = ps->kind;
    const double *m = ps->f[RY_F_MASS], *delta = s->delta;
    const double dt2 = dt * dt, d0 = s->delta0;
    const grad_list *gl = &s->gl;
    double *p = ps->f[RY_F_P], *pnew = s->pnew;
    /* The Laplace jump of the surface particles (CSF, pressure form): their pressure. */
    const double *plow = ry_st_pressure_form(&s->st) ? s->stw.p : NULL;
    const double *v[3];
    for (int d = 0; d < 3; ++d) v[d] = ps->f[RY_F_VX + (d < dim ? d : 0)];
        /* Predicted number density from the predicted velocities (in the velocity field), the
         * diagonal d_ii and a_ii. */
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (!MOBILE[kind[i]]) continue;
        double dv = 0, dii[3] = {0, 0, 0};
        const double di2 = delta[i] * delta[i];
        for (size_t e = gl->off[i]; e < gl->off[i + 1]; ++e) {
            const uint32_t j = gl->j[e];
            const double *G = gl->g + 3 * e;
            for (int d = 0; d < dim; ++d) {
                dv += (v[d][i] - v[d][j]) * G[d];
                dii[d] += G[d];
            }
        }
        /* Only compression is corrected: an expanded particle (free surface, splash) asks for
         * no tension, which the non-negative pressure could not give. */
        s->dstar[i] = delta[i] + dt * dv;
        /* With the Laplace jump on the surface particles the others ask for no expansion: the
         * deficit of the layers under the surface would pull their pressure under the jump. */
        if (plow && !s->stw.tag[i]) s->dstar[i] = fmax(s->dstar[i], d0);
        for (int d = 0; d < 3; ++d) s->dii[3 * i + d] = -dt2 / (m[i] * di2) * dii[d];
    }
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (!MOBILE[kind[i]]) continue;
        const double *dii = s->dii + 3 * i;
        const double di2 = delta[i] * delta[i];
        double a = 0;
        for (size_t e = gl->off[i]; e < gl->off[i + 1]; ++e) {
            const uint32_t j = gl->j[e];
            const double *G = gl->g + 3 * e;
            double g2 = 0, dg = 0;
            for (int d = 0; d < dim; ++d) {
                dg += dii[d] * G[d];
                g2 += G[d] * G[d];
            }
            a += dg;
            /* - d_ji . grad_i W_ij, d_ji = -(dt^2 / m_j) grad_j W_ji / delta_i^2 */
            if (pair_force_mobile(s, kind, i, j)) a -= dt2 / (m[j] * di2) * g2;
        }
        s->aii[i] = a;
    }
    /* Warm start. */
    for (size_t i = 0; i < n; ++i)
        if (kind[i] == RY_KIND_FLUID) p[i] *= s->warm;
    /* The error is averaged over each phase (heavy and light) apart when the light phase is a
     * boundary: their two solves are independent, and the light phase's many particles would
     * otherwise outvote the heavy one's. */
    double nfluid = 0, nlight = 0;
    for (size_t i = 0; i < n; ++i)
        if (kind[i] == RY_KIND_FLUID && !ry_sim_is_halo(sim, i)) {
            nfluid += !s->lt[i];
            nlight += s->lt[i];
        }
    /* A distributed run: a pass that reads its neighbours' results of the pass before gets
     * the halo copies' values from their owners first; the error is summed over all ranks. */
    if (sim->par) {
        sim->par->sync(sim, s->dii, 3);
        sim->par->sync(sim, s->aii, 1);
        sim->par->sync(sim, s->dstar, 1);
        nfluid = sim->par->sum(sim, nfluid);
        nlight = sim->par->sum(sim, nlight);
    }
    const double omega = s->omega;
    long it = 0;
    double avg = 0;
    while (it < s->max_iter) {
        wall_extrapolate(&s->wm, p, p);
        if (sim->par) sim->par->sync(sim, p, 1);
        if (s->light_on) {
            wall_extrapolate(&s->wml, p, s->pl);
            if (sim->par) sim->par->sync(sim, s->pl, 1);
        }
        pressure_sums(sim, s, p, dt2);
        if (sim->par) sim->par->sync(sim, s->sum, 3);
        double esum = 0, lsum = 0;
#pragma omp parallel for schedule(dynamic, 64) reduction(+ : esum, lsum)
        for (size_t i = 0; i < n; ++i) {
            if (kind[i] != RY_KIND_FLUID) {
                pnew[i] = p[i];
                continue;
            }
            const double rest = dim == 3   ? jacobi_rest(s, gl, kind, m, p, dt2, i, 3)
                                : dim == 2 ? jacobi_rest(s, gl, kind, m, p, dt2, i, 2)
                                           : jacobi_rest(s, gl, kind, m, p, dt2, i, dim);
            const double aii = s->aii[i];
            const double err = aii * p[i] + rest + s->dstar[i] - d0; /* delta - delta_0 now */
            double pn = 0;
            if (fabs(aii) > 1e-300)
                pn = (1 - omega) * p[i] + omega * (d0 - s->dstar[i] - rest) / aii;
            /* CSF in pressure form: a surface particle's pressure is its Laplace jump. */
            const int dirichlet = plow && s->stw.tag[i];
            const double pmin = dirichlet ? plow[i] : 0.0;
            pnew[i] = dirichlet ? pmin : pn > 0 ? pn : 0;
            /* Ihmsen's average density error: clamped (free-surface) particles count only when
             * compressed. */
            const double e = (p[i] > pmin || err > 0) && !ry_sim_is_halo(sim, i) ? err : 0.0;
            if (s->lt[i])
                lsum += e;
            else
                esum += e;
        }
        memcpy(p, pnew, n * sizeof *p);
        if (sim->par) {
            sim->par->sync(sim, p, 1);
            esum = sim->par->sum(sim, esum);
            if (s->light_on) lsum = sim->par->sum(sim, lsum);
        }
        ++it;
        avg = nfluid > 0 ? esum / (nfluid * d0) : 0.0;
        const double lavg = nlight > 0 ? lsum / (nlight * d0) : 0.0;
        /* the light phase is held to its own tolerance; the error reported is the larger of
         * the heavy phase's and the light phase's scaled to the heavy tolerance */
        if (fabs(lavg) * s->tol > fabs(avg) * s->light_tol) avg = lavg * s->tol / s->light_tol;
        if (it >= s->min_iter && fabs(avg) <= s->tol) break;
    }
    s->error_last = avg;
    return it;
}

/* Free-surface tension (the surface_tension section). The potential model and CSF in force form
 * add their accelerations. CSF in pressure form (docs/iisph.md): each surface particle (number
 * density below st_beta delta0) takes the Laplace jump P_i = sigma kappa_i as its pressure (a
 * Dirichlet value, as in MPS), and its pressure force counts pressures from P_i,
 *   a^p_i = -(1/m_i) sum_j ((p_i - P_i) / delta_i^2 + (p_j - P_i) / delta_j^2) grad_i W_ij,
 * so a surface particle at P_i feels only the pressure differences inside the liquid (the
 * symmetric form would push it out with P_i against the empty side). The part with P_i is
 * known before the solve and goes into the predicted velocity. The other particles ask for no
 * expansion (their predicted number density is taken as at least delta0). */
static ry_status surface_tension(ry_sim *sim, iisph *s, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    RY_TRY(ry_st_work_ensure(&s->stw, n, err));
    double *P = s->stw.p;
    if (!ry_st_pressure_form(&s->st)) {
        double *a[3] = {P, P + n, P + 2 * n};
        memset(P, 0, 3 * n * sizeof *P);
        RY_TRY(ry_st_accelerate(&s->st, sim, a, err));
        for (size_t i = 0; i < n; ++i)
            for (int d = 0; d < dim; ++d) s->acc[3 * i + d] += a[d][i];
        return RY_OK;
    }
    for (size_t i = 0; i < n; ++i)
        s->stw.tag[i] = ps->kind[i] == RY_KIND_FLUID && s->delta[i] < s->st_beta * s->delta0;
    ry_st_laplace_pressure(&s->st, sim, s->stw.tag, 1, 2.1 * sim->dx, P);
    for (size_t i = 0; i < n; ++i)
        if (!s->stw.tag[i]) P[i] = 0.0;
    const size_t *off = sim->nl.offset;
    const uint32_t *nb = s->pc.j; /* the pairs within the support */
    const size_t *end = s->pc.end;
    const double *cv = s->pc.v, *m = ps->f[RY_F_MASS], *delta = s->delta;
    /* The reference R_i the force counts pressures from: P_i at the surface, and beneath it the
     * mean Laplace jump of all the surface particles (for one drop: its jump). With 0 there,
     * a particle within a kernel's reach of the surface, short of neighbours on the empty side,
     * was pushed out by the liquid's pressure and the solve raised the pressure beneath the
     * surface to hold it: the drop at rest read 16 % above sigma / R. A reference that varies
     * along the surface (the kernel-weighted mean of the surface neighbours' P_j) made the
     * oscillating square unstable. A constant R adds no net force to a particle with a full
     * neighbourhood on a lattice, and between two particles beneath the surface its pair terms
     * are equal and opposite. */
    double *R = P + n; /* free after ry_st_laplace_pressure */
    double psum = 0, pcount = 0;
    for (size_t i = 0; i < n; ++i)
        if (s->stw.tag[i] && !ry_sim_is_halo(sim, i)) {
            psum += P[i];
            pcount += 1;
        }
    if (sim->par) {
        psum = sim->par->sum(sim, psum);
        pcount = sim->par->sum(sim, pcount);
    }
    const double pavg = pcount > 0 ? psum / pcount : 0.0;
    for (size_t i = 0; i < n; ++i)
        R[i] = s->stw.tag[i] ? P[i] : ps->kind[i] == RY_KIND_FLUID ? pavg : 0.0;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (R[i] == 0.0) continue;
        double a[3] = {0, 0, 0};
        const double di2 = 1.0 / (delta[i] * delta[i]);
        for (size_t q = off[i]; q < end[i]; ++q) {
            const uint32_t j = nb[q];
            const double *Q = cv + q * RY_PAIR_STRIDE;
            const double f = di2 + (MOBILE[ps->kind[j]] ? 1.0 / (delta[j] * delta[j]) : di2);
            for (int d = 0; d < dim; ++d) a[d] += f * Q[RY_PW_GX + d];
        }
        for (int d = 0; d < dim; ++d) s->acc[3 * i + d] += R[i] * a[d] / m[i];
    }
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
    RY_TRY(densities_and_forces(sim, s, err));
    if (s->colour_on)
        RY_TRY(ry_colour_force(&s->colour, sim, &s->pc, s->delta, MOBILE, s->acc, err));
    if (s->st.model != RY_ST_NONE) RY_TRY(surface_tension(sim, s, err));
    /* Predicted velocity v* = v + dt a_nonpressure. */
    for (size_t i = 0; i < n; ++i) {
        if (!MOBILE[ps->kind[i]]) continue;
        for (int d = 0; d < dim; ++d) ps->f[RY_F_VX + d][i] += dt * s->acc[3 * i + d];
    }
    if (s->implicit) RY_TRY(viscous_implicit(sim, s, dt, err));
    if (sim->par)
        for (int d = 0; d < dim; ++d) sim->par->sync(sim, ps->f[RY_F_VX + d], 1);
    RY_TRY(wall_map_build(sim, s, &s->wm, ps->f[RY_F_P], RY_MAP_WALL, err));
    if (s->light_on) {
        RY_TRY(wall_map_build(sim, s, &s->wml, s->pl, RY_MAP_LIGHT, err));
    }
    RY_TRY(grad_list_build(sim, s, err));
    const long it = pressure_solve(sim, s, dt);
    s->iters_last = it;
    s->iters_total += it;
    s->solves += 1;
    /* Pressure acceleration with the final pressures; v = v* + dt a^p; x += dt v. */
    const grad_list *gl = &s->gl;
    const double *m = ps->f[RY_F_MASS], *delta = s->delta, *p = ps->f[RY_F_P];
    double vmax2 = 0, amax2 = 0;
#pragma omp parallel for schedule(dynamic, 64) reduction(max : vmax2, amax2)
    for (size_t i = 0; i < n; ++i) {
        if (!MOBILE[ps->kind[i]]) continue;
        const double pi = p[i] / (delta[i] * delta[i]);
        double a[3] = {0, 0, 0};
        for (size_t e = gl->off[i]; e < gl->off[i + 1]; ++e) {
            const double pj = neighbour_pressure(s, ps->kind, p, i, gl->j[e]), *G = gl->g + 3 * e;
            for (int d = 0; d < dim; ++d) a[d] -= (pi + pj) * G[d];
        }
        double a2 = 0, v2 = 0;
        for (int d = 0; d < dim; ++d) {
            a[d] /= m[i];
            ps->f[RY_F_VX + d][i] += dt * a[d];
            const double at = a[d] + s->acc[3 * i + d];
            ps->f[RY_F_AX + d][i] = at;
            a2 += at * at;
            v2 += ps->f[RY_F_VX + d][i] * ps->f[RY_F_VX + d][i];
        }
        if (ry_sim_is_halo(sim, i)) continue; /* its neighbours beyond the halo are missing */
        amax2 = fmax(amax2, a2);
        vmax2 = fmax(vmax2, v2);
    }
    if (sim->par) {
        amax2 = sim->par->max(sim, amax2);
        vmax2 = sim->par->max(sim, vmax2);
    }
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
    ry_sph_rheo_advance(&s->rheo, sim, MOBILE, dt); /* polymer stress, with L at t */
    /* Artificial repulsion (scheme.repulsion), from the positions and velocities at t + dt;
     * the neighbour list of this step still reaches 0.85 dx. */
    if (sim->par && s->coll_r > 0)
        for (int d = 0; d < dim; ++d) {
            sim->par->sync(sim, ps->f[RY_F_X + d], 1);
            sim->par->sync(sim, ps->f[RY_F_VX + d], 1);
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

const ry_scheme_type ry_scheme_iisph = {
    "iisph",
    "implicit incompressible SPH (Ihmsen et al. 2014; number-density two-phase form, colour-field "
    "interfacial and free-surface tension)",
    iisph_init,
    iisph_dt,
    iisph_step,
    iisph_free,
    iisph_vars,
    iisph_report,
    iisph_stat};
