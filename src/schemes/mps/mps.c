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
 *              definite because lambda and n0 are constants of the lattice. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/small.h"
#include "linalg/sparse.h"
#include "neighbor/r2_simd.h"
#include "ryushi/mps.h"
#include "ryushi/surface_tension.h"
#include "physics/colour_field.h"
#include "pairs/pair_cache.h"
#include "ryushi/collisions.h"
#include "ryushi/rheology.h"

enum { SRC_MIXED, SRC_NUMBER_DENSITY };
enum { VISC_EXPLICIT, VISC_IMPLICIT, VISC_NONE, VISC_MIXED };
enum { GRAD_CORRECTED, GRAD_STANDARD };

/* Roles in the pressure Poisson equation. */
enum { ROLE_FLUID = 0, ROLE_SURFACE = 1, ROLE_WALL = 2, ROLE_DUMMY = 3 };

typedef struct mps {
    double re_g, re_l, re_max; /* radii: gradient/divergence/number density, Laplacian */
    double n0g, n0l, lambda;   /* lattice constants */
    double beta;               /* free-surface threshold */
    double wall_reach;         /* wall particles this close to a fluid one are in the PPE */
    int source, visc, grad;    /* options */
    double gamma;              /* weight of the number-density term of the source */
    double alpha;              /* compressibility [1/Pa] */
    double tol, vtol;          /* solver tolerances (pressure, viscosity) */
    long max_iter;
    int clamp;             /* negative pressures set to zero */
    int pmin_on;           /* gradient with the neighbourhood's least pressure (eq. 5) */
    int wall_extrapolate;  /* wall pressure for the gradient extrapolated from the fluid */
    int thin_neumann;      /* thin walls stay out of the pressure equation (Neumann) */
    int inlet_surface;     /* inflow buffers may be free surface (else a closed piston) */
    int cl_slip;           /* walls give no shear stress at a contact line of two liquids */
    double coll_r, coll_e; /* artificial repulsion: distance, restitution */
    int dilate;            /* number-density source also for n* < n0 (else compression only) */
    ry_surface_tension st;
    uint8_t *body_group; /* wetting: each body's wall group (bodies[k].contact_angle), or NULL */
    uint8_t *wgroup;     /* with it: each particle's wall group, set every step */
    uint8_t *body_thin;  /* each body's bodies[k].thin (walls never free surface), or NULL */
    int32_t *thin;       /* with it: each particle's thin body, or -1; set every step */
    double *tnrm;        /* with it: the unit normal of each thin wall particle (3 n) */
    double *tpw;         /*   its pressure for the gradient seen from either side (2 n) */
    uint32_t *tn_off;    /* thin wall particles near each particle: offsets (n + 1) */
    uint32_t *tn_j;      /*   and their indices */
    double *tn_d;        /*   and for each, x_i - x_k and its part along k's normal (4) */
    size_t tn_cap;
    uint8_t *cut;     /* pairs of the neighbour list that a thin wall separates (by place) */
    uint8_t *cut_row; /* with it: the rows that may hold a cut pair (n) */
    size_t cut_cap;
    int thin_cut_on; /* scheme.thin_wall_cut */
    long wb_key[3];  /* searches, list edits and particles when wall_bodies last ran */
    int wb_valid;
    size_t ncut;               /* pairs within re_max cut at the last step (both ends) */
    int surf_head;             /* surface particles hold the head of half a spacing */
    int f_nd, f_surf, f_vs[3]; /* fields */
    int rheo_gnf;              /* some material's viscosity follows the shear rate */
    int rheo_ob;               /* some material is visco-elastic */
    int f_nu, f_gd;            /* fields with rheology: viscosity [m^2/s], shear rate [1/s] */
    int f_tau[6];              /* polymer stress [Pa], components as ry_tau_index */
    double *vgrad;             /* velocity gradient, dim x dim per particle (visco-elastic) */
    int wall_mode;             /* walls in the viscous terms: own velocity, mirrored, slip */
    double *wd;                /* with it: distance of each particle to the wall surface */
    ry_csr A;
    long defl;          /* scheme.solver.deflation: aggregate side in spacings (0: none) */
    ry_csr_deflation D; /* with it: the pressure solve's aggregates */
    int32_t *dmap;      /*   and the aggregate of each cell of their grid */
    size_t dmap_cap;
    int32_t *unk; /* unknown index per particle, -1 if none */
    uint8_t *role;
    uint8_t *cline; /* with cl_slip: 1 for a fluid particle with another liquid near */
    double *b, *xs;
    double *pd;       /* Dirichlet pressure of the surface particles (8 n: work) */
    int csf_pressure; /* CSF as the Laplace jump on the surface particles */
    /* CSF between two liquids (surface_tension.interfacial_sigma with model csf): the colour
     * field of the SPH schemes (sph/multiphase.h) on the case's kernel */
    int colour_on;
    ry_colour colour;
    ry_pair_cache pc;
    double *cdelta, *cacc; /* its number density and acceleration (n and 3 n) */
    size_t ccap;
    uint8_t *own;       /* distributed run: unknown k is this rank's own (not a halo copy) */
    uint8_t *near_surf; /* the rows with a free-surface particle among their pairs (n) */
    double *divu;       /* the divergence of u* of each unknown (n) */
    double *ptmp;       /* distributed run: a vector of unknowns spread over the particles */
    /* The pairs within re_g and re_l at the current positions (pairs_build), in the rows of
     * the neighbour list: row i holds from sim->nl.offset[i] the pairs of the smaller radius,
     * then those of the larger one; gend[i] and lend[i] end the pairs within re_g and re_l. */
    uint32_t *pj;
    double *pr;          /* distance */
    size_t *gend, *lend; /* (per particle: allocated by scratch) */
    double *nu_pair;     /* the pair viscosity of two materials (nmat x nmat; pair_nu) */
    size_t pq_cap;
    ry_particle_unknowns pu; /* distributed run: the unknowns of the solve under way */
    size_t cap;
    int last_iters, last_viters;
    long total_iters, steps;
} mps;

static ry_status rheology_init(ry_sim *sim, mps *M, ry_error *err);
static void rheology_explicit(ry_sim *sim, mps *M, double dt);

static const char *const source_names[] = {"tanaka_masunaga", "number_density", NULL};
static const char *const visc_names[] = {"explicit", "implicit", "none", "mixed", NULL};
static const char *const grad_names[] = {"corrected", "standard", NULL};
static const char *const surface_pressure_names[] = {"zero", "hydrostatic", NULL};
static const char *const thin_pressure_names[] = {"unknown", "neumann", NULL};
static const char *const wall_velocity_names[] = {"own", "mirrored", "slip", NULL};
enum { WALLV_OWN, WALLV_MIRRORED, WALLV_SLIP };

void ry_mps_lattice(int dim, double l0, double re, double *n0, double *lambda) {
    const int K = (int)floor(re / l0 + 1e-9);
    double s = 0, s2 = 0;
    for (int a = -K; a <= K; ++a)
        for (int b = -K; b <= K; ++b)
            for (int c = (dim > 2 ? -K : 0); c <= (dim > 2 ? K : 0); ++c) {
                if (a == 0 && b == 0 && c == 0) continue;
                const double r2 = l0 * l0 * (double)(a * a + b * b + c * c);
                const double w = ry_mps_weight_tamai(sqrt(r2), re);
                s += w;
                s2 += r2 * w;
            }
    *n0 = s;
    *lambda = s2 / s;
}

/* The potential model's fluid-wall coefficient for a contact angle theta [degrees], relative to
 * C: (1 + cos theta)/2, the Dupre work of adhesion against the work of cohesion. */
static double wall_ratio_of(double theta) {
    return 0.5 * (1.0 + cos(theta * RY_PI / 180.0));
}

/* Checks that bodies[k], named in key, is a body of wall particles. */
static ry_status body_is_wall(ry_sim *sim, ry_case *c, size_t k, const char *key, ry_error *err) {
    char where[256];
    size_t walls = 0, others = 0;
    for (size_t i = 0; i < sim->ps.n; ++i)
        if (ry_sim_body_of(sim, sim->ps.id[i]) == (int)k)
            ++*(sim->ps.kind[i] == RY_KIND_WALL ? &walls : &others);
    RY_CHECK(err, walls > 0 && others == 0, RY_ERR_INPUT,
             "%s: key '%s': applies to a body of kind wall",
             ry_case_where(c, key, where, sizeof where), key);
    return RY_OK;
}

/* Thin walls (docs/mps.md, "Thin walls"): bodies[k].thin. A wall of one layer with air behind
 * it reads a number density below the free-surface threshold, and as free surface (p = 0) it
 * could not hold the pressure of the fluid on its other side. The particles of such a body
 * with a fluid particle within reach always take part in the pressure equation. */
static ry_status body_thin(ry_sim *sim, ry_case *c, mps *M, ry_error *err) {
    char key[160];
    for (size_t k = 0; k < sim->nbodies; ++k) {
        snprintf(key, sizeof key, "bodies[%zu].thin", k);
        if (!ry_case_has(c, key)) continue;
        const int no = 0;
        int on;
        RY_TRY(ry_case_bool(c, key, &no, &on, err));
        if (!on) continue;
        RY_TRY(body_is_wall(sim, c, k, key, err));
        if (!M->body_thin) {
            M->body_thin = calloc(sim->nbodies, 1);
            RY_CHECK(err, M->body_thin != NULL, RY_ERR_NOMEM, "out of memory");
        }
        M->body_thin[k] = 1;
    }
    return RY_OK;
}

/* Wetting of one wall body (docs/mps.md, "Wetting with two liquids"), potential model:
 * bodies[k].contact_angle, a number for every liquid or a mapping from material names to
 * angles (liquids not named keep their angle on the other walls). Bodies with the same angles
 * share a group of walls (M->body_group); each other set of angles has a group of its own. */
static ry_status body_angles(ry_sim *sim, ry_case *c, mps *M, ry_error *err) {
    char where[256], key[160];
    int groups = 1;
    for (size_t k = 0; k < sim->nbodies; ++k) {
        snprintf(key, sizeof key, "bodies[%zu].contact_angle", k);
        if (!ry_case_has(c, key)) continue;
        RY_CHECK(err, M->st.model == RY_ST_POTENTIAL, RY_ERR_INPUT,
                 "%s: key '%s': a contact angle per wall body needs surface_tension.model "
                 "potential",
                 ry_case_where(c, key, where, sizeof where), key);
        RY_TRY(body_is_wall(sim, c, k, key, err));
        double row[sizeof M->st.wall_ratio[0] / sizeof M->st.wall_ratio[0][0]];
        int named = 0;
        for (int m = 0; m < sim->nmat; ++m) {
            char mk[224];
            snprintf(mk, sizeof mk, "%s.%s", key, sim->mat[m].name);
            row[m] = M->st.wall_ratio[0][m];
            if (ry_case_has(c, mk)) {
                double th;
                RY_TRY(ry_case_double(c, mk, NULL, 0.0, 180.0, &th, err));
                row[m] = wall_ratio_of(th);
                ++named;
            }
        }
        if (!named) {
            double th;
            RY_CHECK(err, ry_case_double(c, key, NULL, 0.0, 180.0, &th, err) == RY_OK, RY_ERR_INPUT,
                     "%s: key '%s': expected an angle in degrees (0..180), or a mapping from "
                     "material names to angles",
                     ry_case_where(c, key, where, sizeof where), key);
            for (int m = 0; m < sim->nmat; ++m) row[m] = wall_ratio_of(th);
        }
        int g = 1;
        while (g < groups && memcmp(M->st.wall_ratio[g], row, sim->nmat * sizeof *row) != 0) ++g;
        if (g == groups) {
            RY_CHECK(err, groups < RY_ST_WALL_GROUPS, RY_ERR_INPUT,
                     "%s: key '%s': at most %d different sets of contact angles on wall bodies",
                     ry_case_where(c, key, where, sizeof where), key, RY_ST_WALL_GROUPS - 1);
            for (int m = 0; m < sim->nmat; ++m) M->st.wall_ratio[g][m] = row[m];
            ++groups;
        }
        if (!M->body_group) {
            M->body_group = calloc(sim->nbodies, 1);
            RY_CHECK(err, M->body_group != NULL, RY_ERR_NOMEM, "out of memory");
        }
        M->body_group[k] = (uint8_t)g;
    }
    return RY_OK;
}

/* Wetting (docs/mps.md): surface_tension.contact_angle [degrees]. The potential model takes it
 * as its fluid-wall coefficient, CSF as the normal at the contact line. With the potential
 * model, materials[k].contact_angle sets the angle of liquid k alone (the others keep
 * surface_tension.contact_angle, or no attraction). */
static ry_status contact_angle(ry_sim *sim, ry_case *c, mps *M, ry_error *err) {
    char where[256], key[64] = "surface_tension.contact_angle";
    RY_CHECK(err, M->st.model != RY_ST_NONE || !ry_case_has(c, key), RY_ERR_INPUT,
             "%s: key '%s': needs a surface_tension.model",
             ry_case_where(c, key, where, sizeof where), key);
    double theta = NAN;
    if (ry_case_has(c, key)) {
        RY_TRY(ry_case_double(c, key, NULL, 0.0, 180.0, &theta, err));
        if (M->st.model == RY_ST_CSF) M->st.contact_angle = theta * RY_PI / 180.0;
    }
    for (int m = 0; m < sim->nmat; ++m) {
        double th = theta;
        snprintf(key, sizeof key, "materials[%d].contact_angle", m);
        if (ry_case_has(c, key)) {
            RY_CHECK(err, M->st.model == RY_ST_POTENTIAL, RY_ERR_INPUT,
                     "%s: key '%s': a contact angle per liquid needs surface_tension.model "
                     "potential (CSF takes one angle, surface_tension.contact_angle)",
                     ry_case_where(c, key, where, sizeof where), key);
            RY_TRY(ry_case_double(c, key, NULL, 0.0, 180.0, &th, err));
        }
        if (!isnan(th)) M->st.wall_ratio[0][m] = wall_ratio_of(th);
    }
    return body_angles(sim, c, M, err);
}

/* Two liquids: surface_tension.interfacial_sigma sigma_ab. Potential model: by the Dupre
 * relation the pairs of two different liquids do the work W_ab = 2 sigma - sigma_ab, the
 * coefficient C (1 - sigma_ab / (2 sigma)). CSF: the colour field of the first two materials
 * (colour 1 for the second), its curvature and the force sigma_ab kappa n / rho_bar, on the
 * case's SPH kernel (sph/multiphase.h; docs/mps.md, "Two liquids"). */
static ry_status interfacial(ry_sim *sim, ry_case *c, mps *M, ry_error *err) {
    char where[256];
    const char *key = "surface_tension.interfacial_sigma";
    if (!ry_case_has(c, key)) return RY_OK;
    RY_CHECK(err, M->st.model == RY_ST_POTENTIAL || M->st.model == RY_ST_CSF, RY_ERR_INPUT,
             "%s: key '%s': needs surface_tension.model potential or csf",
             ry_case_where(c, key, where, sizeof where), key);
    RY_CHECK(err, sim->nmat >= 2, RY_ERR_INPUT, "%s: key '%s': needs two fluid materials",
             ry_case_where(c, key, where, sizeof where), key);
    double sab;
    if (M->st.model == RY_ST_POTENTIAL) {
        RY_TRY(ry_case_double(c, key, NULL, 0.0, 2.0 * M->st.sigma, &sab, err));
        M->st.cross_ratio = 1.0 - sab / (2.0 * M->st.sigma);
        return RY_OK;
    }
    RY_TRY(ry_case_double(c, key, NULL, 0.0, 1e3, &sab, err));
    RY_CHECK(err, sim->kernel.radius <= M->re_max * (1 + 1e-12), RY_ERR_INPUT,
             "%s: key '%s': the kernel's support (%g m) must not exceed the MPS radius %g m "
             "(kernel.h_over_dx at most %g)",
             ry_case_where(c, key, where, sizeof where), key, sim->kernel.radius, M->re_max,
             0.5 * M->re_max / sim->dx);
    M->colour_on = sab > 0;
    M->colour.sigma = sab;
    M->colour.material = 1;
    M->colour.eps = 0.01;
    long passes, one = 1;
    RY_TRY(ry_case_int(c, "surface_tension.interfacial_smoothing", &one, 0, 20, &passes, err));
    M->colour.smoothing = (int)passes;
    M->colour.rho_bar = 0.5 * (sim->mat[0].density + sim->mat[1].density);
    return M->colour_on ? ry_colour_init(&M->colour, sim, err) : RY_OK;
}

/* The interfacial acceleration of CSF between two liquids, added to a. */
static ry_status colour_accelerate(ry_sim *sim, mps *M, double *const a[3], ry_error *err) {
    static const int mobile[RY_KIND_COUNT] = {[RY_KIND_FLUID] = 1};
    static const int need[RY_KIND_COUNT] = {[RY_KIND_FLUID] = 1};
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    if (M->ccap < n) {
        double *b = realloc(M->cdelta, 4 * n * sizeof *b);
        RY_CHECK(err, b != NULL, RY_ERR_NOMEM, "out of memory (colour field)");
        M->cdelta = b;
        M->cacc = b + n;
        M->ccap = n;
    }
    M->pc.cut = M->st.cut; /* no pairs across a thin wall */
    RY_TRY(ry_pair_cache_fill(&M->pc, sim, need, err));
    /* The SPH number density over every neighbour, the particle itself included. */
    const double w0 = sim->kernel.norm * ry_kernel_shape(sim->kernel.type, 0.0);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        double sw = w0;
        for (size_t q = sim->nl.offset[i]; q < M->pc.end[i]; ++q)
            sw += M->pc.v[q * RY_PAIR_STRIDE + RY_PW_W];
        M->cdelta[i] = sw;
        M->cacc[3 * i] = M->cacc[3 * i + 1] = M->cacc[3 * i + 2] = 0;
    }
    if (sim->par) sim->par->sync(sim, M->cdelta, 1);
    RY_TRY(ry_colour_force(&M->colour, sim, &M->pc, M->cdelta, mobile, M->cacc, err));
    for (size_t i = 0; i < n; ++i)
        if (ps->kind[i] == RY_KIND_FLUID)
            for (int d = 0; d < sim->dim; ++d) a[d][i] += M->cacc[3 * i + d];
    return RY_OK;
}

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
    M->re_g *= l0;
    M->re_l *= l0;
    RY_TRY(ry_st_read(&M->st, c, sim->dim, l0, 3.1, 6.0, err));
    M->st.thin_layers = (int)layers;
    M->csf_pressure = ry_st_pressure_form(&M->st);
    RY_TRY(contact_angle(sim, c, M, err));
    RY_TRY(body_thin(sim, c, M, err));
    M->re_max = fmax(fmax(M->re_g, M->re_l), M->st.model != RY_ST_NONE ? M->st.re : 0.0);
    RY_TRY(interfacial(sim, c, M, err));
    double lam_g;
    ry_mps_lattice(sim->dim, l0, M->re_g, &M->n0g, &lam_g);
    ry_mps_lattice(sim->dim, l0, M->re_l, &M->n0l, &M->lambda);

    ry_particles *ps = &sim->ps;
    static const char *const vs[3] = {"vstar_x", "vstar_y", "vstar_z"};
    for (int d = 0; d < 3; ++d)
        RY_TRY(ry_particles_add_field(ps, vs[d], "m/s", d, 0, &M->f_vs[d], err));
    RY_TRY(ry_particles_add_field(ps, "number_density", "1", -1, RY_FIELD_OUTPUT, &M->f_nd, err));
    RY_TRY(ry_particles_add_field(ps, "free_surface", "1", -1, RY_FIELD_OUTPUT, &M->f_surf, err));
    RY_TRY(rheology_init(sim, M, err));
    /* Outlets are sinks: the fluid that crosses the downstream face is removed, and the free
     * surface this leaves takes the free-surface condition (an open top, an overflow, a pipe's
     * exit). */
    sim->open_sink = 1;
    for (int q = 0; q < sim->nopen; ++q) {
        char k[64], where[256];
        snprintf(k, sizeof k, "open_boundaries[%d].pressure", q);
        RY_CHECK(err, sim->open[q].type == RY_OPEN_INLET || sim->open[q].pressure == 0.0,
                 RY_ERR_INPUT,
                 "%s: key '%s': scheme mps takes outlets at pressure 0 only (its outlets remove "
                 "the fluid at the downstream face, a free surface)",
                 ry_case_where(c, k, where, sizeof where), k);
        snprintf(k, sizeof k, "open_boundaries[%d].type", q);
        RY_CHECK(err, !sim->open[q].rate, RY_ERR_INPUT,
                 "%s: key '%s': scheme mps takes no rate outlets (flow_rate or velocity): its "
                 "outlets are sinks at pressure 0",
                 ry_case_where(c, k, where, sizeof where), k);
    }
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
    free(M->dmap);
    free(M->unk);
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
             u && r && b && x && pd && o && ns && dv && t && ge && le && (vg || !M->rheo_ob) &&
                 (wv || M->wall_mode != WALLV_MIRRORED) && (cl || !M->cl_slip) &&
                 (wg || !M->body_group) && ((th && tv && tp && to && cr) || !M->body_thin),
             RY_ERR_NOMEM, "out of memory (MPS work arrays)");
    M->cap = c;
    return RY_OK;
}

/* A distributed run (sim->par): the linear systems span the ranks. Vectors of unknowns reach
 * the halo copies through the particles. */
/* The distribution of the current unknowns (NULL in a serial run). */
static const ry_csr_dist *dist_of(const ry_sim *sim, mps *M, ry_csr_dist *d) {
    M->pu = (ry_particle_unknowns){sim, M->unk, M->own, M->ptmp};
    return ry_particle_dist(&M->pu, d);
}

/* Squared distances from particle i to the nb particles nj[0..nb-1] into r2 (no periodic
 * sides; call with a literal dim, so that the loop unrolls and vectorises). */
static inline void row_r2(int dim, const double *const x[3], size_t i, const uint32_t *nj,
                          size_t nb, double *r2) {
    for (size_t k = 0; k < nb; ++k) {
        double s = 0;
        for (int d = 0; d < dim; ++d) {
            const double e = x[d][nj[k]] - x[d][i];
            s += e * e;
        }
        r2[k] = s;
    }
}

/* Thin walls, part 2 (docs/mps.md, "Thin walls"): pairs on the two sides of a thin wall take
 * no part in any term. Each thin wall particle k has the unit normal of its body's sheet (the
 * null direction of the second moment of the same body's particles within 1.5 l0; none where
 * the body turns a corner, so that it cuts nothing there). The pair
 * (i, j) is cut where it crosses the plane of some thin wall particle k near either end (both
 * ends at least l0/4 off the plane) within 0.75 l0 of k: a line through a sheet of particles
 * l0 apart passes within l0/sqrt(2) of one of them, and a line that passes the sheet's edge
 * (the catheter's tip) farther off is not cut. The test takes the pair in one order, so the
 * cut is symmetric, as the pressure matrix must be. */
static void thin_normals(ry_sim *sim, mps *M) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const double r2max = 2.25 * sim->dx * sim->dx;
    const int dim = sim->dim;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        double *nv = M->tnrm + 3 * i;
        nv[0] = nv[1] = nv[2] = 0;
        if (M->thin[i] < 0) continue;
        double c[3][3] = {{0}};
        for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
            const uint32_t j = sim->nl.j[q];
            double dx[3];
            if (M->thin[j] != M->thin[i] || ry_sim_separation(sim, i, j, dx) > r2max) continue;
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b) c[a][b] += dx[a] * dx[b];
        }
        if (dim == 2) { /* the sheet is a line: the normal is across its largest row */
            const int r =
                c[0][0] * c[0][0] + c[0][1] * c[0][1] >= c[1][0] * c[1][0] + c[1][1] * c[1][1] ? 0
                                                                                               : 1;
            nv[0] = -c[r][1];
            nv[1] = c[r][0];
        } else { /* rank 2: the largest cross product of two rows */
            double best = -1;
            for (int a = 0; a < 3; ++a) {
                const int b = (a + 1) % 3;
                const double x[3] = {c[a][1] * c[b][2] - c[a][2] * c[b][1],
                                     c[a][2] * c[b][0] - c[a][0] * c[b][2],
                                     c[a][0] * c[b][1] - c[a][1] * c[b][0]};
                const double m = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
                if (m > best) {
                    best = m;
                    memcpy(nv, x, sizeof x);
                }
            }
        }
        const double m = sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
        for (int d = 0; d < 3; ++d) nv[d] = m > 0 ? nv[d] / m : 0;
        /* not a sheet here (a corner where the body turns): no normal, no cut */
        double q = 0;
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) q += nv[a] * c[a][b] * nv[b];
        if (q > 0.01 * (c[0][0] + c[1][1] + c[2][2])) nv[0] = nv[1] = nv[2] = 0;
    }
}

/* Does a thin wall particle k near one end of the pair separate particles a and b? The list
 * ks[0..nk-1] holds the thin particles near the end `own` (a, or b where own_b), with
 * own_d[4 m] = x_own - x_k and its part along k's normal; the other end's are computed. */
static int thin_between(ry_sim *sim, const mps *M, size_t a, size_t b, int own_b,
                        const uint32_t *ks, const double *own_d, size_t nk) {
    const double l0 = sim->dx, off = 0.25 * l0, reach2 = 0.5625 * l0 * l0;
    const size_t far = own_b ? a : b;
    for (size_t m = 0; m < nk; ++m) {
        const uint32_t k = ks[m];
        if (k == a || k == b) continue;
        const double *od = own_d + 4 * m;
        if (fabs(od[3]) < off) continue;
        const double *nv = M->tnrm + 3 * k;
        double fd[3];
        ry_sim_separation(sim, k, far, fd);
        const double fs = nv[0] * fd[0] + nv[1] * fd[1] + nv[2] * fd[2];
        if (fabs(fs) < off) continue;
        const double *da = own_b ? fd : od, *db = own_b ? od : fd;
        const double sa = own_b ? fs : od[3], sb = own_b ? od[3] : fs;
        if (!(sa * sb < 0)) continue;
        const double t = sa / (sa - sb);
        double c2 = 0;
        for (int d = 0; d < 3; ++d) {
            const double c = da[d] + t * (db[d] - da[d]);
            c2 += c * c;
        }
        if (c2 < reach2) return 1;
    }
    return 0;
}

static ry_status thin_cut(ry_sim *sim, mps *M, int fluid_rows, ry_error *err) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n, nq = sim->nl.offset[n];
    thin_normals(sim, M);
    M->st.cut = NULL;
    M->ncut = 0;
    if (!M->thin_cut_on) return RY_OK;
    /* the thin wall particles within 2.3 l0 of each particle: the crossing lies within half
     * the pair's length (at most re, 3.1 l0) of one end, and k within 0.75 l0 of it. The list
     * is symmetric, so they come from the rows of the thin particles, which are few: rows far
     * from every thin wall are not read. */
    const double r2k = 2.3 * 2.3 * sim->dx * sim->dx;
    uint32_t *cnt = M->tn_off + 1;
    memset(M->tn_off, 0, (n + 1) * sizeof *M->tn_off);
    for (size_t k = 0; k < n; ++k) {
        if (M->thin[k] < 0) continue;
        for (size_t q = sim->nl.offset[k]; q < sim->nl.offset[k + 1]; ++q) {
            double dx[3];
            const uint32_t j = sim->nl.j[q];
            cnt[j] += ry_sim_separation(sim, j, k, dx) < r2k;
        }
    }
    for (size_t i = 0; i < n; ++i) M->tn_off[i + 1] += M->tn_off[i];
    if (M->tn_cap < M->tn_off[n] || !M->tn_j || !M->tn_d) {
        const size_t c = M->tn_off[n] + M->tn_off[n] / 4 + 16;
        uint32_t *t = realloc(M->tn_j, c * sizeof *t);
        if (t) M->tn_j = t;
        double *td = realloc(M->tn_d, 4 * c * sizeof *td);
        if (td) M->tn_d = td;
        RY_CHECK(err, t && td, RY_ERR_NOMEM, "out of memory (thin walls)");
        M->tn_cap = c;
    }
    if (M->cut_cap < nq || !M->cut) {
        const size_t c = nq + nq / 4 + 16;
        uint8_t *t = realloc(M->cut, c);
        RY_CHECK(err, t != NULL, RY_ERR_NOMEM, "out of memory (thin walls)");
        M->cut = t;
        M->cut_cap = c;
    }
    /* fill each particle's list from its end down: tn_off[i + 1] ends at i's start, and one
     * shift makes it the start again */
    const uint32_t total = M->tn_off[n];
    for (size_t k = 0; k < n; ++k) {
        if (M->thin[k] < 0) continue;
        for (size_t q = sim->nl.offset[k]; q < sim->nl.offset[k + 1]; ++q) {
            double dx[3];
            const uint32_t j = sim->nl.j[q];
            if (ry_sim_separation(sim, j, k, dx) < r2k) M->tn_j[--cnt[j]] = (uint32_t)k;
        }
    }
    memmove(M->tn_off, M->tn_off + 1, n * sizeof *M->tn_off);
    M->tn_off[n] = total;
    /* each particle's separation from its thin neighbours, and the part along their normals */
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i)
        for (uint32_t m = M->tn_off[i]; m < M->tn_off[i + 1]; ++m) {
            const uint32_t k = M->tn_j[m];
            const double *nv = M->tnrm + 3 * k;
            double *td = M->tn_d + 4 * (size_t)m;
            ry_sim_separation(sim, k, i, td);
            td[3] = nv[0] * td[0] + nv[1] * td[1] + nv[2] * td[2];
        }
    /* the rows with a pair that may be cut: a particle with a thin one near, and its
     * neighbours */
    uint8_t *act = M->cut_row;
    memset(act, 0, n);
    for (size_t i = 0; i < n; ++i) {
        if (M->tn_off[i + 1] == M->tn_off[i]) continue;
        act[i] = 1;
        for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) act[sim->nl.j[q]] = 1;
    }
    /* the cut pairs within the interaction radius are counted for the statistic cut_pairs */
    const double rm2 = M->re_max * M->re_max;
    size_t nc = 0;
#pragma omp parallel for reduction(+ : nc) schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        const size_t q0 = sim->nl.offset[i], q1 = sim->nl.offset[i + 1];
        if (fluid_rows && ps->kind[i] != RY_KIND_FLUID) continue; /* rows not read (x^n) */
        if (!act[i]) {
            memset(M->cut + q0, 0, q1 - q0);
            continue;
        }
        for (size_t q = q0; q < q1; ++q) {
            const uint32_t j = sim->nl.j[q];
            const size_t a = i < j ? i : j, b = i < j ? j : i;
            uint8_t cut = 0;
            double dx[3];
            /* (the pairs of the list's skin take part in nothing) */
            const int near = M->tn_off[a + 1] > M->tn_off[a] || M->tn_off[b + 1] > M->tn_off[b];
            if (near && (ps->kind[a] != RY_KIND_WALL || ps->kind[b] != RY_KIND_WALL) &&
                ry_sim_separation(sim, i, j, dx) < rm2)
                cut = (uint8_t)(thin_between(sim, M, a, b, 0, M->tn_j + M->tn_off[a],
                                             M->tn_d + 4 * (size_t)M->tn_off[a],
                                             M->tn_off[a + 1] - M->tn_off[a]) ||
                                thin_between(sim, M, a, b, 1, M->tn_j + M->tn_off[b],
                                             M->tn_d + 4 * (size_t)M->tn_off[b],
                                             M->tn_off[b + 1] - M->tn_off[b]));
            M->cut[q] = cut;
            nc += cut;
        }
    }
    M->st.cut = M->cut;
    M->ncut = nc;
    return RY_OK;
}

/* Each wall particle's body, every step (ids survive reordering): its wetting group
 * (bodies[k].contact_angle) and whether it is thin, with the pairs thin walls cut. */
static ry_status wall_bodies(ry_sim *sim, mps *M, int fluid_rows, ry_error *err) {
    if (!M->body_group && !M->body_thin) return RY_OK;
    const ry_particles *ps = &sim->ps;
    /* the particles keep their places between searches and edits of the set (a serial run) */
    const long key[3] = {sim->searches, sim->nl_edits, (long)ps->n};
    const int same = !sim->par && M->wb_valid && memcmp(key, M->wb_key, sizeof key) == 0;
    memcpy(M->wb_key, key, sizeof key);
    M->wb_valid = 1;
    for (size_t i = 0; i < ps->n && !same; ++i) {
        const int b = ps->kind[i] == RY_KIND_WALL ? ry_sim_body_of(sim, ps->id[i]) : -1;
        if (M->body_group) M->wgroup[i] = b >= 0 ? M->body_group[b] : 0;
        if (M->body_thin) M->thin[i] = b >= 0 && M->body_thin[b] ? b : -1;
    }
    if (M->body_group) M->st.wall_group = M->wgroup;
    if (!M->body_thin) return RY_OK;
    RY_TRY(thin_cut(sim, M, fluid_rows, err));
    M->st.thin_normal = M->tnrm; /* the potential model's images of thin walls */
    return RY_OK;
}

#ifdef RY_R2_SIMD
/* pairs_build's row i (3D, no periodic sides) eight entries at a time: the squared distances
 * of the list's entries nj[0..nb-1] (to rb) and the lanes within the inner and the outer
 * radius that are not cut (to mk), then the pairs, the inner ones first, with their
 * distances; *a and *no are the counts. The same pairs in the same order, and the same bits
 * (the square root is exact to the rounding on either path), as the scalar loop. */
static inline void simd_pairs_row(const double *const x[3], size_t i, const uint32_t *nj,
                                  const uint8_t *cut, size_t nb, double ri2, double ro2, double *rb,
                                  uint8_t *mk, uint32_t *pj, double *pr, size_t *a, size_t *no) {
    const __m512d xi[3] = {_mm512_set1_pd(x[0][i]), _mm512_set1_pd(x[1][i]),
                           _mm512_set1_pd(x[2][i])};
    const __m512d vi = _mm512_set1_pd(ri2), vo = _mm512_set1_pd(ro2);
    const __m128i z8 = _mm_setzero_si128();
    size_t ni = 0;
    for (size_t k = 0, c = 0; k < nb; k += 8, c += 2) {
        const __mmask8 m = ry_simd_lanes(nb - k);
        const __m512d v = ry_simd_r2(x, xi, _mm256_maskz_loadu_epi32(m, nj + k), m);
        __mmask8 keep = m;
        if (cut)
            keep &= (__mmask8)_mm_cmpeq_epi8_mask(_mm_maskz_loadu_epi8((__mmask16)m, cut + k), z8);
        mk[c] = keep & _mm512_cmp_pd_mask(v, vi, _CMP_LT_OQ);
        mk[c + 1] =
            keep & _mm512_cmp_pd_mask(v, vi, _CMP_GE_OQ) & _mm512_cmp_pd_mask(v, vo, _CMP_LT_OQ);
        _mm512_mask_storeu_pd(rb + k, m, v);
        ni += (size_t)__builtin_popcount(mk[c]);
    }
    size_t qi = 0, qo = ni;
    for (size_t k = 0, c = 0; k < nb; k += 8, c += 2) {
        const __mmask8 in = mk[c], out = mk[c + 1], m = in | out;
        if (!m) continue;
        const __m256i idx = _mm256_maskz_loadu_epi32(m, nj + k);
        const __m512d r = _mm512_sqrt_pd(_mm512_maskz_loadu_pd(m, rb + k));
        qi += ry_simd_append(in, idx, r, pj + qi, pr + qi);
        qo += ry_simd_append(out, idx, r, pj + qo, pr + qo);
    }
    *a = ni;
    *no = qo - ni;
}
#endif

/* The pairs within re_g and re_l (the fields pj, pr, gend, lend of mps) from the neighbour
 * list, whose reach is the largest radius and a skin: the loops over them need neither the
 * distances nor the pairs beyond their radius again. Within each radius the pairs keep the
 * order of the list. Each row's squared distances go to a buffer of the thread, and the
 * split into the inner and the outer pairs stores every entry and advances by a comparison
 * (the branches it replaces fail unpredictably). */
static ry_status pairs_build(ry_sim *sim, mps *M, int fluid_rows, ry_error *err) {
    const size_t n = sim->ps.n, nq = sim->nl.offset[n];
    if (M->pq_cap < nq) {
        const size_t c = nq + nq / 4 + 16;
        uint32_t *j = realloc(M->pj, c * sizeof *j);
        if (j) M->pj = j;
        double *r = realloc(M->pr, c * sizeof *r);
        if (r) M->pr = r;
        RY_CHECK(err, j && r, RY_ERR_NOMEM, "out of memory (MPS pairs: %zu)", nq);
        M->pq_cap = c;
    }
    const double ri = fmin(M->re_g, M->re_l), ro = fmax(M->re_g, M->re_l);
    const double ri2 = ri * ri, ro2 = ro * ro;
    const int g_inner = M->re_g <= M->re_l, dim = sim->dim;
    const uint8_t *cut = M->st.cut; /* thin walls' cut pairs, or NULL */
    int periodic = 0;
    for (int d = 0; d < dim; ++d) periodic |= sim->box.periodic[d];
    size_t rowmax = 0;
    for (size_t i = 0; i < n; ++i)
        if (sim->nl.offset[i + 1] - sim->nl.offset[i] > rowmax)
            rowmax = sim->nl.offset[i + 1] - sim->nl.offset[i];
    const double *x[3];
    for (int d = 0; d < 3; ++d) x[d] = sim->ps.f[RY_F_X + (d < dim ? d : 0)];
    int ok = 1;
#pragma omp parallel reduction(&& : ok)
    {
        /* the row's squared distances; the outer pairs, until they follow the inner ones */
        double *rb = malloc((rowmax + 1) * sizeof *rb);
        uint32_t *oj = malloc((rowmax + 1) * sizeof *oj);
        double *orr = malloc((rowmax + 1) * sizeof *orr);
        uint8_t *mk = malloc(2 * (rowmax / 8 + 2)); /* (the SIMD path's masks) */
        ok = rb && oj && orr && mk;
#pragma omp for schedule(dynamic, 64)
        for (size_t i = 0; i < n; ++i) {
            if (!ok) continue;
            const size_t lo = sim->nl.offset[i], nb = sim->nl.offset[i + 1] - lo;
            if (fluid_rows && sim->ps.kind[i] != RY_KIND_FLUID) {
                M->gend[i] = M->lend[i] = lo;
                continue;
            }
            const uint32_t *nj = sim->nl.j + lo;
            uint32_t *pj = M->pj + lo;
            double *pr = M->pr + lo;
            size_t a = 0, no = 0;
#ifdef RY_R2_SIMD
            if (dim == 3 && !periodic) { /* eight entries at a time: the same pairs, in order */
                simd_pairs_row(x, i, nj, cut ? cut + lo : NULL, nb, ri2, ro2, rb, mk, pj, pr, &a,
                               &no);
            } else
#endif
            {
                if (periodic) {
                    double dx[3];
                    for (size_t k = 0; k < nb; ++k) rb[k] = ry_sim_separation(sim, i, nj[k], dx);
                } else if (dim == 3) {
                    row_r2(3, x, i, nj, nb, rb);
                } else if (dim == 2) {
                    row_r2(2, x, i, nj, nb, rb);
                } else {
                    row_r2(1, x, i, nj, nb, rb);
                }
                for (size_t k = 0; k < nb; ++k) {
                    const double v = rb[k];
                    const uint32_t j = nj[k];
                    const int keep = !cut || !cut[lo + k];
                    pj[a] = j;
                    pr[a] = v;
                    oj[no] = j;
                    orr[no] = v;
                    a += keep & (v < ri2);
                    no += keep & (v >= ri2) & (v < ro2);
                }
                memcpy(pj + a, oj, no * sizeof *oj);
                memcpy(pr + a, orr, no * sizeof *orr);
                for (size_t k = 0; k < a + no; ++k) pr[k] = sqrt(pr[k]);
            }
            M->gend[i] = lo + (g_inner ? a : a + no);
            M->lend[i] = lo + (g_inner ? a + no : a);
        }
        free(rb);
        free(oj);
        free(orr);
        free(mk);
    }
    RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (MPS pairs)");
    /* the surface tension reads them where they reach its radius (until the particles move) */
    const int st_own = M->st.re <= ro && !sim->par;
    M->st.pair_j = st_own ? M->pj : NULL;
    M->st.pair_r = st_own ? M->pr : NULL;
    M->st.pair_end = st_own ? (g_inner ? M->lend : M->gend) : NULL;
    return RY_OK;
}

/* Number density (ratio n/n0) of every particle at the current positions, and the roles: free
 * surface (p = 0) for fluid and wall particles with n < beta n0 (walls above the water line);
 * the other wall particles with a fluid neighbour within re take part in the pressure
 * equation (those of thin bodies whatever their number density), the rest are dummies. */
static double divergence(const ry_sim *sim, const mps *M, size_t i);

/* divergence() of particle i as a vector loop and a sum (3D, no periodic side): u[d] the
 * velocity each particle brings (u* of the fluid, the velocity of the rest), bt and br2 room
 * for the row's terms and squared distances. The same terms, summed in the same order. */
static double divergence_lanes(const ry_sim *sim, const mps *M, size_t i, const double *const u[3],
                               double *bt, double *br2) {
    const double *x0 = sim->ps.f[RY_F_X], *x1 = sim->ps.f[RY_F_X + 1], *x2 = sim->ps.f[RY_F_X + 2],
                 re = M->re_g;
    const size_t q0 = sim->nl.offset[i], nb = M->gend[i] - q0;
    const uint32_t *jj = M->pj + q0;
    const double *rr = M->pr + q0, xi0 = x0[i], xi1 = x1[i], xi2 = x2[i];
    const double ui0 = u[0][i], ui1 = u[1][i], ui2 = u[2][i];
#pragma omp simd
    for (size_t k = 0; k < nb; ++k) {
        const uint32_t j = jj[k];
        const double e0 = x0[j] - xi0, e1 = x1[j] - xi1, e2 = x2[j] - xi2;
        double du = 0.0;
        du += (u[0][j] - ui0) * e0;
        du += (u[1][j] - ui1) * e1;
        du += (u[2][j] - ui2) * e2;
        const double r2 = e0 * e0 + e1 * e1 + e2 * e2, sr = rr[k] / re - 1.0;
        br2[k] = r2;
        bt[k] = du / r2 * (rr[k] < re ? sr * sr : 0.0);
    }
    double s = 0;
    for (size_t k = 0; k < nb; ++k)
        if (br2[k] > 0) s += bt[k];
    return 3 * s / M->n0g;
}

static void number_density(ry_sim *sim, mps *M) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const double re = M->re_g, reach = M->wall_reach;
    double *nd = ps->f[M->f_nd], *surf = ps->f[M->f_surf];
    const int div = M->gamma < 1.0, lanes = div && ry_box_plain(&sim->box) == 3;
    /* (lanes) the velocity each particle brings to the divergence, in M->b, which the
     * pressure equation fills only later */
    double *u[3] = {M->b, M->b + n, M->b + 2 * n};
    size_t rowmax = 0;
    for (size_t i = 0; lanes && i < n; ++i) {
        const int fl = ps->kind[i] == RY_KIND_FLUID;
        for (int d = 0; d < 3; ++d) u[d][i] = (fl ? ps->f[M->f_vs[d]] : ps->f[RY_F_VX + d])[i];
        if (M->gend[i] - sim->nl.offset[i] > rowmax) rowmax = M->gend[i] - sim->nl.offset[i];
    }
#pragma omp parallel
    {
        double *buf = lanes ? malloc(2 * (rowmax + 1) * sizeof *buf) : NULL;
#pragma omp for schedule(dynamic, 64)
        for (size_t i = 0; i < n; ++i) {
            double s = 0;
            int fluid_near = 0;
            for (size_t q = sim->nl.offset[i]; q < M->gend[i]; ++q) {
                const double r = M->pr[q];
                s += ry_mps_weight_tamai(r, re);
                if (ps->kind[M->pj[q]] == RY_KIND_FLUID && r < reach) fluid_near = 1;
            }
            nd[i] = s / M->n0g;
            if (ps->kind[i] == RY_KIND_FLUID) {
                M->role[i] = nd[i] < M->beta ? ROLE_SURFACE : ROLE_FLUID;
            } else {
                const int thin = M->thin && M->thin[i] >= 0;
                const int closed = thin || (!M->inlet_surface && ps->kind[i] == RY_KIND_INLET);
                M->role[i] = !fluid_near                  ? ROLE_DUMMY
                             : nd[i] < M->beta && !closed ? ROLE_SURFACE
                                                          : ROLE_WALL;
            }
            surf[i] = M->role[i] == ROLE_SURFACE && ps->kind[i] == RY_KIND_FLUID;
            /* the source's divergence of u* for the unknowns, while the row's pairs are at
             * hand */
            if (div && (M->role[i] == ROLE_FLUID || M->role[i] == ROLE_WALL))
                M->divu[i] = buf ? divergence_lanes(sim, M, i, (const double *const *)u, buf,
                                                    buf + rowmax + 1)
                                 : divergence(sim, M, i);
        }
        free(buf);
    }
}

/* Kinematic viscosity of a pair (harmonic mean: symmetric, and 0 next to an inviscid fluid).
 * With a shear-rate dependent viscosity each particle has its own value (field f_nu, set by
 * rheology_explicit). A wall takes the fluid particle's: a no-slip wall's shear stress is the
 * fluid's own. (The mean with the wall body's material, the first one unless the body names
 * another, would let the embolic liquid slide through a catheter as if it were water.) */
static inline double nu_mean(double a, double b) {
    return a + b > 0 ? 2.0 * a * b / (a + b) : 0.0;
}
static inline double pair_nu(const ry_sim *sim, const mps *M, size_t i, size_t j) {
    if (!M->rheo_gnf) { /* the materials' pairs, computed once (rheology_init) */
        const size_t a = sim->ps.material[i];
        const size_t b = sim->ps.kind[j] == RY_KIND_FLUID ? sim->ps.material[j] : a;
        return M->nu_pair[a * (size_t)sim->nmat + b];
    }
    const double a = sim->ps.f[M->f_nu][i];
    return nu_mean(a, sim->ps.kind[j] == RY_KIND_FLUID ? sim->ps.f[M->f_nu][j] : a);
}

/* With `wall_velocity: mirrored` a wall particle j enters the viscous terms of fluid particle i
 * with the velocity of the flow extended linearly through the wall surface (Morris et al.
 * 1997): u_j = v_j - (d_j/d_i)(u_i - v_j), d the distances to the surface, so that
 * u_j - u_i = beta (v_j - u_i), beta = 1 + d_j/d_i (at most 1.5 + 1, as a fluid particle
 * close to the surface would otherwise see a huge velocity difference). With the wall's own
 * velocity the no-slip plane lies about 0.7 l0 beyond the wall surface. The distances: that
 * to the nearest particle of the other kind (fluid for a wall, wall for a fluid particle) less
 * half a spacing, which is exact on a lattice beside a flat wall. */
static inline double wall_beta(const ry_sim *sim, const mps *M, size_t i, size_t j) {
    if (sim->ps.kind[j] == RY_KIND_FLUID) return 1.0;
    if (M->cl_slip && M->cline[i]) return 0.0; /* a contact line slides (contact_lines) */
    if (M->wall_mode == WALLV_OWN) return 1.0;
    if (M->wall_mode == WALLV_SLIP) return 0.0; /* no shear stress from the walls */
    return 1.0 + fmin(M->wd[j] / fmax(M->wd[i], 1e-3 * sim->dx), 1.5);
}

/* `scheme.contact_line_slip`: marks the fluid particles that have a fluid particle of another
 * material within the Laplacian's radius, the liquids' interface. Where such a particle meets a
 * wall, the wall gives it no shear stress (wall_beta 0), so that the line where the interface
 * meets the wall can slide while the wall holds each liquid elsewhere: the slip of the
 * generalised Navier boundary condition, which is confined to the contact line (Qian, Wang &
 * Sheng 2003), at the resolution of the particles. */
static void contact_lines(ry_sim *sim, mps *M) {
    const ry_particles *ps = &sim->ps;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < ps->n; ++i) {
        uint8_t c = 0;
        if (ps->kind[i] == RY_KIND_FLUID)
            for (size_t q = sim->nl.offset[i]; q < M->lend[i] && !c; ++q) {
                const uint32_t j = M->pj[q];
                c = ps->kind[j] == RY_KIND_FLUID && ps->material[j] != ps->material[i];
            }
        M->cline[i] = c;
    }
}

static void wall_distances(ry_sim *sim, mps *M) {
    const ry_particles *ps = &sim->ps;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < ps->n; ++i) {
        const int fi = ps->kind[i] == RY_KIND_FLUID;
        double rmin = INFINITY;
        for (size_t q = sim->nl.offset[i]; q < M->lend[i]; ++q)
            if ((ps->kind[M->pj[q]] == RY_KIND_FLUID) != fi) rmin = fmin(rmin, M->pr[q]);
        M->wd[i] = isfinite(rmin) ? fmax(rmin - 0.5 * sim->dx, 0.0) : INFINITY;
    }
}

/* Rheology (docs/rheology.md); the polymer stress by components as ry_tau_index says. */

static ry_status rheology_init(ry_sim *sim, mps *M, ry_error *err) {
    M->f_nu = M->f_gd = -1;
    for (int k = 0; k < 6; ++k) M->f_tau[k] = -1;
    const size_t nm = (size_t)sim->nmat;
    M->nu_pair = malloc((nm ? nm * nm : 1) * sizeof *M->nu_pair);
    RY_CHECK(err, M->nu_pair != NULL, RY_ERR_NOMEM, "out of memory");
    for (size_t a = 0; a < nm; ++a)
        for (size_t b = 0; b < nm; ++b)
            M->nu_pair[a * nm + b] = nu_mean(sim->mat[a].viscosity, sim->mat[b].viscosity);
    for (int m = 0; m < sim->nmat; ++m) {
        M->rheo_gnf |= ry_rheology_generalised(&sim->mat[m].rheo);
        M->rheo_ob |= ry_rheology_viscoelastic(&sim->mat[m].rheo);
    }
    if (!M->rheo_gnf && !M->rheo_ob) return RY_OK;
    ry_particles *ps = &sim->ps;
    RY_TRY(ry_particles_add_field(ps, "viscosity", "m^2/s", -1, RY_FIELD_OUTPUT, &M->f_nu, err));
    RY_TRY(ry_particles_add_field(ps, "shear_rate", "1/s", -1, RY_FIELD_OUTPUT, &M->f_gd, err));
    for (int k = 0; M->rheo_ob && k < ry_tau_count(sim->dim); ++k)
        RY_TRY(ry_particles_add_field(ps, ry_tau_name(sim->dim, k), "Pa", -1,
                                      RY_FIELD_STATE | RY_FIELD_OUTPUT, &M->f_tau[k], err));
    return RY_OK;
}

/* Corrected (least-squares) gradient at particle i of the fields val(i, j, c), c < nc (the
 * value of j as seen from i), over the neighbours within re_g (fluid ones only with
 * fluid_only): grad[c][b] =
 * d val_c / d x_b, exact for linear fields however one-sided the neighbourhood. Returns 0 when
 * the moment matrix is singular (too few neighbours); grad is then zero. */
typedef double (*grad_value_fn)(const ry_sim *sim, const mps *M, size_t i, size_t j, int c);
static int corrected_gradient(const ry_sim *sim, const mps *M, size_t i, int fluid_only,
                              grad_value_fn val, int nc, double grad[6][3]) {
    const int dim = sim->dim;
    double m[3][3] = {{0}}, g[6][3] = {{0}};
    for (size_t q = sim->nl.offset[i]; q < M->gend[i]; ++q) {
        const uint32_t j = M->pj[q];
        if (fluid_only && sim->ps.kind[j] != RY_KIND_FLUID) continue;
        double dx[3];
        const double r2 = ry_sim_separation(sim, i, j, dx);
        if (r2 <= 0) continue;
        const double wr = ry_mps_weight_tamai(M->pr[q], M->re_g) / r2;
        for (int a = 0; a < dim; ++a)
            for (int b = 0; b < dim; ++b) m[a][b] += wr * dx[a] * dx[b];
        for (int c = 0; c < nc; ++c) {
            const double dv = val(sim, M, i, j, c) - val(sim, M, i, i, c);
            for (int b = 0; b < dim; ++b) g[c][b] += wr * dv * dx[b];
        }
    }
    return ry_solve_rows(dim, m, nc, g, grad);
}

/* Velocity of j seen from fluid particle i: a wall's mirrored as in the viscous terms. */
static double velocity_value(const ry_sim *sim, const mps *M, size_t i, size_t j, int c) {
    const double vj = sim->ps.f[RY_F_VX + c][j];
    if (j == i) return vj;
    return vj + (wall_beta(sim, M, i, j) - 1.0) * (vj - sim->ps.f[RY_F_VX + c][i]);
}

static double tau_value(const ry_sim *sim, const mps *M, size_t i, size_t j, int c) {
    (void)i;
    return sim->ps.f[M->f_tau[c]][j];
}

/* At x^n: the velocity gradient L (L[a][b] = du_a/dx_b, over fluid and wall neighbours, walls
 * with the velocity the viscous terms give them, wall_beta), the shear rate sqrt(2 D:D) and the
 * viscosity it gives; with a visco-elastic model the acceleration div(tau)/rho (tau's gradient
 * over the fluid neighbours) and the stress at t + dt by ry_polymer_step (the upper-convected and
 * Giesekus terms explicit, the relaxation implicit). */
static void rheology_explicit(ry_sim *sim, mps *M, double dt) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim, nt = ry_tau_count(dim);
    const size_t n = ps->n;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        const ry_material *mat = &sim->mat[ps->material[i]];
        if (ps->kind[i] != RY_KIND_FLUID) {
            ps->f[M->f_nu][i] = mat->viscosity;
            ps->f[M->f_gd][i] = 0;
            continue;
        }
        double L[6][3];
        corrected_gradient(sim, M, i, 0, velocity_value, dim, L);
        double dd = 0;
        for (int a = 0; a < dim; ++a)
            for (int b = 0; b < dim; ++b) {
                const double d = 0.5 * (L[a][b] + L[b][a]);
                dd += d * d;
            }
        const double gd = sqrt(2.0 * dd);
        ps->f[M->f_gd][i] = gd;
        ps->f[M->f_nu][i] = ry_rheology_nu(&mat->rheo, mat->viscosity, gd);
        if (M->rheo_ob)
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b)
                    M->vgrad[9 * i + 3 * a + b] = a < dim && b < dim ? L[a][b] : 0.0;
    }
    if (sim->par) sim->par->sync(sim, ps->f[M->f_nu], 1);
    if (!M->rheo_ob) return;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        double G[6][3];
        corrected_gradient(sim, M, i, 1, tau_value, nt, G);
        double div[3] = {0, 0, 0};
        for (int k = 0; k < nt; ++k) {
            int a, b;
            ry_tau_index(dim, k, &a, &b);
            div[a] += G[k][b];
            if (a != b) div[b] += G[k][a];
        }
        const double rho = sim->mat[ps->material[i]].density;
        for (int d = 0; d < dim; ++d) ps->f[RY_F_AX + d][i] += div[d] / rho;
    }
    /* The stress update reads only particle i's own values: no race. */
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        const ry_material *mat = &sim->mat[ps->material[i]];
        if (ps->kind[i] != RY_KIND_FLUID || !ry_rheology_viscoelastic(&mat->rheo)) continue;
        double t[6];
        for (int k = 0; k < nt; ++k) t[k] = ps->f[M->f_tau[k]][i];
        ry_polymer_step(dim, &mat->rheo, &M->vgrad[9 * i], mat->density, dt, t);
        for (int k = 0; k < nt; ++k) ps->f[M->f_tau[k]][i] = t[k];
    }
    for (int k = 0; sim->par && k < nt; ++k) sim->par->sync(sim, ps->f[M->f_tau[k]], 1);
}

/* The viscous pair sums of fluid particle i: s = sum_j nu_ij w_ij (v_j - v_i) (times beta
 * with mirrored walls) and the return value sum_j nu_ij w_ij; nu lap v = cl s. */
static inline double viscous_sums_d(const ry_sim *sim, const mps *M, size_t i, double s[3],
                                    int dim) {
    const ry_particles *ps = &sim->ps;
    const double re = M->re_l;
    const double *v[3];
    double c = 0, t[3] = {0, 0, 0}, vi[3] = {0, 0, 0};
    for (int d = 0; d < dim; ++d) {
        v[d] = ps->f[RY_F_VX + d];
        vi[d] = v[d][i];
    }
    for (size_t q = sim->nl.offset[i]; q < M->lend[i]; ++q) {
        const uint32_t j = M->pj[q];
        const double w =
            pair_nu(sim, M, i, j) * ry_mps_weight_tamai(M->pr[q], re) * wall_beta(sim, M, i, j);
        c += w;
        for (int d = 0; d < dim; ++d) t[d] += w * (v[d][j] - vi[d]);
    }
    s[0] = t[0];
    s[1] = t[1];
    s[2] = t[2];
    return c;
}

/* (with a literal dimension: the sums stay in registers) */
static inline double viscous_sums(const ry_sim *sim, const mps *M, size_t i, double s[3]) {
    if (sim->dim == 3) return viscous_sums_d(sim, M, i, s, 3);
    if (sim->dim == 2) return viscous_sums_d(sim, M, i, s, 2);
    return viscous_sums_d(sim, M, i, s, sim->dim);
}

/* a += nu lap v (explicit viscosity, eq. 7) for fluid particles; walls enter with their
 * velocity (no slip). */
static void viscous_explicit(ry_sim *sim, const mps *M) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const size_t n = ps->n;
    const double cl = 2.0 * dim / (M->lambda * M->n0l);
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        double s[3];
        viscous_sums(sim, M, i, s);
        for (int d = 0; d < dim; ++d) ps->f[RY_F_AX + d][i] += cl * s[d];
    }
}

/* Whether wall particle i stays out of the pressure equation: a thin wall's one layer has
 * fluid on both sides, and as an unknown it would carry the pressure from one to the other
 * (from a catheter's bore to the water around it). Left out, it is a Neumann boundary to the
 * fluid on either side, and its pressure for the gradient is extrapolated from each side. */
static inline int thin_out(const mps *M, size_t i) {
    return M->thin_neumann && M->thin && M->thin[i] >= 0;
}

/* Pressure: pairs between unknowns and free-surface particles (Dirichlet); dummies and thin
 * walls (thin_out) are left out. */
static int couple_pressure(const ry_sim *sim, const mps *M, size_t i, size_t j, double *coef,
                           double dt) {
    (void)sim;
    (void)i;
    (void)dt;
    *coef = 1.0;
    return M->role[j] != ROLE_DUMMY && !thin_out(M, j);
}

/* Viscosity: every pair; walls are known velocities. */
static int couple_viscous(const ry_sim *sim, const mps *M, size_t i, size_t j, double *coef,
                          double dt) {
    *coef = dt * pair_nu(sim, M, i, j) * wall_beta(sim, M, i, j);
    return 1;
}

/* Assembles the rows of the unknowns (unk[i] >= 0) from the Laplacian pairs: for each pair
 * (i, j) within re_l that couple_pressure or, where `viscous`, couple_viscous accepts,
 * coefficient c w_ij on the diagonal and -c w_ij off it when j is an unknown too (pairs beyond
 * re_l make no entry); diag_extra is added to every diagonal. coef(i, j) scales c w_ij (1 for
 * the pressure, dt nu_ij for the viscosity). (A flag rather than a function pointer: the
 * coefficient inlines into the loop.) */
static ry_status assemble(ry_sim *sim, mps *M, size_t nunk, int viscous, double dt,
                          double diag_extra, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const double re = M->re_l, cl = 2.0 * sim->dim / (M->lambda * M->n0l);
    /* Row lengths (diagonal included) in parallel, their prefix sums, then the rows. */
    RY_TRY(ry_csr_reserve(&M->A, nunk, 0, err));
    ry_csr *A = &M->A;
    A->row[0] = 0;
#pragma omp parallel for schedule(dynamic, 256)
    for (size_t i = 0; i < n; ++i) {
        if (M->unk[i] < 0) continue;
        size_t len = 1;
        for (size_t q = sim->nl.offset[i]; q < M->lend[i]; ++q) len += M->unk[M->pj[q]] >= 0;
        A->row[(size_t)M->unk[i] + 1] = len;
    }
    for (size_t k = 0; k < nunk; ++k) A->row[k + 1] += A->row[k];
    RY_TRY(ry_csr_reserve(&M->A, nunk, A->row[nunk], err));
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (M->unk[i] < 0) continue;
        const size_t k = (size_t)M->unk[i];
        size_t p = A->row[k];
        const size_t pdiag = p++;
        double diag = diag_extra;
        for (size_t q = sim->nl.offset[i]; q < M->lend[i]; ++q) {
            const uint32_t j = M->pj[q];
            double coef = 0, a = 0;
            if (viscous ? couple_viscous(sim, M, i, j, &coef, dt)
                        : couple_pressure(sim, M, i, j, &coef, dt))
                a = cl * coef * ry_mps_weight_tamai(M->pr[q], re);
            diag += a;
            if (M->unk[j] >= 0) {
                A->col[p] = (uint32_t)M->unk[j];
                A->val[p++] = -a;
            }
        }
        A->col[pdiag] = (uint32_t)k;
        A->val[pdiag] = diag;
        A->diag[k] = diag;
    }
    return RY_OK;
}

/* `viscosity: mixed`: a fluid particle whose viscous diagonal dt sum_j c nu_ij w_ij (the
 * matrix's diagonal less 1) is at most this takes the explicit step. Explicit diffusion keeps
 * a maximum principle up to 1 (the new velocity a convex combination of the old ones). */
#define MIXED_EXPLICIT_MAX 0.25

/* `viscosity: mixed`: marks the fluid particles of the implicit solve (unk >= 0, numbered) and
 * gives the others their explicit u* = v + dt (a + nu lap v) in f_vs; returns the unknowns. */
static size_t viscous_split(ry_sim *sim, mps *M, double dt, int with_st) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const double cl = 2.0 * dim / (M->lambda * M->n0l);
    double *a[3];
    for (int d = 0; d < 3; ++d) a[d] = ps->f[RY_F_AX + (d < dim ? d : 0)];
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        M->unk[i] = -1;
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        if (with_st) ry_st_potential_particle(&M->st, sim, i, a); /* (mps_step) */
        double s[3];
        if (dt * cl * viscous_sums(sim, M, i, s) > MIXED_EXPLICIT_MAX) {
            M->unk[i] = 0; /* numbered below */
            continue;
        }
        /* as viscous_explicit, then u* = v + dt a */
        for (int d = 0; d < dim; ++d)
            ps->f[M->f_vs[d]][i] = ps->f[RY_F_VX + d][i] + dt * (ps->f[RY_F_AX + d][i] + cl * s[d]);
    }
    size_t nunk = 0;
    for (size_t i = 0; i < n; ++i)
        if (M->unk[i] == 0) M->unk[i] = (int32_t)nunk++;
    return nunk;
}

/* Implicit viscosity: (1 - dt nu lap) u* = v + dt a, per component, walls as known values.
 * With `viscosity: mixed` only the stiff particles are unknowns (viscous_split); the others'
 * explicit u* enter their rows as known values, as the walls' velocities do. */
static ry_status viscous_implicit(ry_sim *sim, mps *M, double dt, int with_st, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    /* (a distributed run solves them all: a halo copy lacks the neighbours for the split) */
    const int mixed = M->visc == VISC_MIXED && !sim->par;
    size_t nunk = 0;
    if (mixed)
        nunk = viscous_split(sim, M, dt, with_st);
    else
        for (size_t i = 0; i < n; ++i)
            M->unk[i] = ps->kind[i] == RY_KIND_FLUID ? (int32_t)nunk++ : -1;
    RY_TRY(assemble(sim, M, nunk, 1, dt, 1.0, err));
    const double re = M->re_l, cl = 2.0 * dim / (M->lambda * M->n0l);
    /* the components' right-hand sides and solutions: b and xs from d nunk */
    const double *bs[3];
    double *xv[3];
    for (int d = 0; d < dim; ++d) {
        const double *v = ps->f[RY_F_VX + d], *a = ps->f[RY_F_AX + d], *us = ps->f[M->f_vs[d]];
        double *bd = M->b + (size_t)d * nunk, *xd = M->xs + (size_t)d * nunk;
        bs[d] = bd;
        xv[d] = xd;
#pragma omp parallel for schedule(dynamic, 64)
        for (size_t i = 0; i < n; ++i) {
            if (M->unk[i] < 0) continue;
            double rhs = v[i] + dt * a[i];
            for (size_t q = sim->nl.offset[i]; q < M->lend[i]; ++q) {
                const uint32_t j = M->pj[q];
                if (M->unk[j] >= 0) continue;
                const double vj = mixed && ps->kind[j] == RY_KIND_FLUID ? us[j] : v[j];
                rhs += cl * dt * pair_nu(sim, M, i, j) * ry_mps_weight_tamai(M->pr[q], re) *
                       wall_beta(sim, M, i, j) * vj;
            }
            bd[M->unk[i]] = rhs;
            xd[M->unk[i]] = v[i];
        }
    }
    /* the components together: one pass over the matrix serves all three */
    int it[3];
    double res[3];
    ry_csr_dist dd;
    RY_TRY(ry_csr_pcg_multi(&M->A, dim, bs, xv, M->vtol, (int)M->max_iter, it, res,
                            dist_of(sim, M, &dd), err));
    M->last_viters = 0;
    for (int d = 0; d < dim; ++d) {
        double *vs = ps->f[M->f_vs[d]];
        M->last_viters += it[d];
        for (size_t i = 0; i < n; ++i)
            if (M->unk[i] >= 0) vs[i] = xv[d][M->unk[i]];
    }
    return RY_OK;
}

/* Divergence of u* (eq. 6) at particle i over fluid and wall neighbours within re_g. */
static double divergence(const ry_sim *sim, const mps *M, size_t i) {
    const ry_particles *ps = &sim->ps;
    const double re = M->re_g;
    const int dim = sim->dim;
    /* u* of the fluid, the velocity of the rest */
    const double *us[3], *uv[3];
    double ui[3] = {0, 0, 0};
    for (int d = 0; d < dim; ++d) {
        us[d] = ps->f[M->f_vs[d]];
        uv[d] = ps->f[RY_F_VX + d];
        ui[d] = ps->kind[i] == RY_KIND_FLUID ? us[d][i] : uv[d][i];
    }
    double s = 0;
    for (size_t q = sim->nl.offset[i]; q < M->gend[i]; ++q) {
        const uint32_t j = M->pj[q];
        double dx[3];
        const double r2 = ry_sim_separation(sim, i, j, dx);
        if (r2 <= 0) continue;
        const double *const *u = ps->kind[j] == RY_KIND_FLUID ? us : uv;
        double du = 0;
        for (int d = 0; d < dim; ++d) du += (u[d][j] - ui[d]) * dx[d];
        s += du / r2 * ry_mps_weight_tamai(M->pr[q], re);
    }
    return sim->dim * s / M->n0g;
}

/* The unit normal of thin wall particle i, or NULL (not thin, or no sheet there). */
static inline const double *thin_normal(const mps *M, size_t i) {
    if (!M->body_thin || M->thin[i] < 0) return NULL;
    const double *nv = M->tnrm + 3 * i;
    return nv[0] != 0 || nv[1] != 0 || nv[2] != 0 ? nv : NULL;
}

/* The pressure of neighbour j in the gradient of fluid particle i (dx = x_j - x_i): a thin
 * wall's extrapolated pressure is taken from the fluid on i's side of it. */
static inline double grad_pressure(const mps *M, const double *p, size_t j, const double *dx) {
    const double *tn = M->wall_extrapolate || M->thin_neumann ? thin_normal(M, j) : NULL;
    if (!tn) return p[j];
    const int side = tn[0] * dx[0] + tn[1] * dx[1] + tn[2] * dx[2] > 0;
    return M->tpw[2 * j + side];
}

/* Wall pressure for the gradient extrapolated from the fluid (as Adami et al. 2012 do for
 * SPH): p_w = sum_f w (p_f + rho_f g.(x_w - x_f)) / sum_f w over the fluid within re_g. Kept
 * in the xs work array (the PPE values stay in the pressure field). */
static void extrapolate_walls(ry_sim *sim, mps *M) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const double re = M->re_g;
    double *pw = M->xs + n;
    const double *p = ps->f[RY_F_P];
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        pw[i] = p[i];
        if (M->role[i] != ROLE_WALL || !(M->wall_extrapolate || thin_out(M, i))) continue;
        double s = 0, sw = 0, ss[2] = {0, 0}, sws[2] = {0, 0};
        const double *tn = thin_normal(M, i);
        for (size_t q = sim->nl.offset[i]; q < M->gend[i]; ++q) {
            const uint32_t j = M->pj[q];
            if (ps->kind[j] != RY_KIND_FLUID) continue;
            double dx[3];
            ry_sim_separation(sim, i, j, dx);
            const double w = ry_mps_weight_tamai(M->pr[q], re);
            double gd = 0; /* g . (x_i - x_j) = -g . dx */
            for (int d = 0; d < sim->dim; ++d) gd -= sim->gravity[d] * dx[d];
            const double v = p[j] + sim->mat[ps->material[j]].density * gd;
            s += w * v;
            sw += w;
            if (tn) { /* a thin wall: the fluid on either side of its sheet apart */
                const int side = tn[0] * dx[0] + tn[1] * dx[1] + tn[2] * dx[2] < 0;
                ss[side] += w * v;
                sws[side] += w;
            }
        }
        if (sw > 0) pw[i] = fmax(s / sw, 0.0);
        if (tn)
            for (int side = 0; side < 2; ++side)
                M->tpw[2 * i + side] = sws[side] > 0 ? fmax(ss[side] / sws[side], 0.0) : pw[i];
    }
    for (size_t i = 0; i < n; ++i)
        if (M->role[i] == ROLE_WALL) ps->f[RY_F_P][i] = pw[i];
}

/* CSF in pressure form: the Dirichlet value of each surface particle is the Laplace jump
 * sigma kappa, averaged along the surface within the gradient radius. */
static void csf_dirichlet(ry_sim *sim, mps *M) {
    ry_st_laplace_pressure(&M->st, sim, M->role, ROLE_SURFACE, M->re_g, M->pd);
}

/* A free-surface particle stands half a spacing inside the surface it represents, so under a
 * body force g its pressure is the head of that half spacing, rho g.n l0 / 2, with n the
 * inward direction (towards the neighbours, sum_j w (x_j - x_i) normalised): zero on a surface
 * that faces down or sideways. With p = 0 on the particles instead, the pressure under the
 * surface of a column at rest falls short of rho g h by rho g l0 / 2 at every depth
 * (docs/validation.md). Added to the Dirichlet values in pd. */
static void surface_head(ry_sim *sim, mps *M) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const double l0 = sim->dx;
    if (sim->gravity[0] == 0 && sim->gravity[1] == 0 && sim->gravity[2] == 0) return;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < ps->n; ++i) {
        if (M->role[i] != ROLE_SURFACE || ps->kind[i] != RY_KIND_FLUID) continue;
        double in[3] = {0, 0, 0}, nin = 0, gin = 0;
        for (size_t q = sim->nl.offset[i]; q < M->gend[i]; ++q) {
            double dx[3];
            if (ry_sim_separation(sim, i, M->pj[q], dx) <= 0) continue;
            const double w = ry_mps_weight_tamai(M->pr[q], M->re_g);
            for (int a = 0; a < dim; ++a) in[a] += w * dx[a];
        }
        for (int a = 0; a < dim; ++a) {
            nin += in[a] * in[a];
            gin += sim->gravity[a] * in[a];
        }
        if (nin > 0 && gin > 0)
            M->pd[i] += 0.5 * l0 * sim->mat[ps->material[i]].density * gin / sqrt(nin);
    }
    if (sim->par) sim->par->sync(sim, M->pd, 1);
}

/* The aggregates of the deflated pressure solve: the unknowns grouped by the cubes of side
 * defl spacings they lie in (a grid over their bounding box; empty cubes take no aggregate),
 * numbered in the grid's order, so that the coarse matrix is banded (neighbouring cubes differ
 * by at most a layer of the grid). Where that gives more than MAX_AGG aggregates the side
 * doubles. */
enum { MAX_AGG = 4000 };
static ry_status aggregates(const ry_sim *sim, mps *M, size_t nunk, ry_error *err) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const int dim = sim->dim;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    int first = 1;
    for (size_t i = 0; i < n; ++i) {
        if (M->unk[i] < 0) continue;
        for (int d = 0; d < dim; ++d) {
            const double v = ps->f[RY_F_X + d][i];
            if (first || v < lo[d]) lo[d] = v;
            if (first || v > hi[d]) hi[d] = v;
        }
        first = 0;
    }
    M->D.m = 0; /* (positions not finite: no deflation; the solve reports the failure) */
    for (int d = 0; d < dim; ++d)
        if (!isfinite(lo[d]) || !isfinite(hi[d])) return RY_OK;
    RY_TRY(ry_csr_deflation_reserve(&M->D, nunk, MAX_AGG, err));
    for (double side = (double)M->defl * sim->dx;; side *= 2) {
        double span[3] = {1, 1, 1};
        for (int d = 0; d < dim; ++d) span[d] = floor((hi[d] - lo[d]) / side) + 1;
        if (span[0] * span[1] * span[2] > 64.0 * (double)nunk + 4096)
            continue; /* a grid far finer than the unknowns */
        const size_t nc[3] = {(size_t)span[0], (size_t)span[1], (size_t)span[2]},
                     cells = nc[0] * nc[1] * nc[2];
        if (cells > M->dmap_cap) {
            int32_t *p = realloc(M->dmap, cells * sizeof *p);
            RY_CHECK(err, p, RY_ERR_NOMEM, "out of memory (deflation grid: %zu cells)", cells);
            M->dmap = p;
            M->dmap_cap = cells;
        }
        for (size_t k = 0; k < cells; ++k) M->dmap[k] = -1;
        for (size_t i = 0; i < n; ++i) { /* the cell of each unknown (in agg for now) */
            if (M->unk[i] < 0) continue;
            size_t cell = 0;
            for (int d = dim - 1; d >= 0; --d) {
                const double f = floor((ps->f[RY_F_X + d][i] - lo[d]) / side);
                cell = cell * nc[d] + (f <= 0 ? 0 : f >= (double)nc[d] ? nc[d] - 1 : (size_t)f);
            }
            M->dmap[cell] = 0;
            M->D.agg[M->unk[i]] = (uint32_t)cell;
        }
        size_t m = 0;
        for (size_t k = 0; k < cells; ++k)
            if (M->dmap[k] == 0) M->dmap[k] = (int32_t)++m;
        if (m > MAX_AGG) continue;
        for (size_t u = 0; u < nunk; ++u) M->D.agg[u] = (uint32_t)(M->dmap[M->D.agg[u]] - 1);
        M->D.m = m;
        return RY_OK;
    }
}

/* Pressure Poisson equation at x*: unknowns are the inner fluid and the wall particles. */
static ry_status pressure(ry_sim *sim, mps *M, double dt, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    size_t nunk = 0;
    for (size_t i = 0; i < n; ++i)
        M->unk[i] = (M->role[i] == ROLE_FLUID || M->role[i] == ROLE_WALL) && !thin_out(M, i)
                        ? (int32_t)nunk++
                        : -1;
    /* Compressibility (Ikeda et al. 2001): rho alpha / dt^2 p on the diagonal, with the
     * largest density (a bound; exact for one material). */
    double rho_max = 0;
    for (int m = 0; m < sim->nmat; ++m) rho_max = fmax(rho_max, sim->mat[m].density);
    if (M->alpha == 0) { /* a closed domain leaves the pressure without a reference value */
        size_t nsurf = 0;
        for (size_t i = 0; i < n; ++i) nsurf += M->role[i] == ROLE_SURFACE;
        if (sim->par) nsurf = (size_t)sim->par->sum(sim, (double)nsurf);
        RY_CHECK(err, nsurf > 0 || nunk == 0, RY_ERR_INPUT,
                 "MPS: no free-surface particle, so the pressure equation has no reference value "
                 "(a closed or periodic domain): set scheme.compressibility (e.g. 1e-9 1/Pa)");
    }
    RY_TRY(assemble(sim, M, nunk, 0, dt, M->alpha * rho_max / (dt * dt), err));
    const double *nd = ps->f[M->f_nd];
    const double g = M->gamma;
    /* Dirichlet values: 0, or the Laplace jump sigma kappa with CSF in pressure form; plus,
     * on the fluid's surface particles, the pressure half a spacing under the surface. */
    if (M->csf_pressure)
        csf_dirichlet(sim, M);
    else
        for (size_t i = 0; i < n; ++i) M->pd[i] = 0;
    if (M->surf_head) surface_head(sim, M);
    const int dirichlet = M->csf_pressure || M->surf_head;
    /* the rows with a surface particle among their pairs, which are symmetric at x* (every
     * row built): the others have no Dirichlet term to add */
    uint8_t *near = M->near_surf;
    if (dirichlet) {
        memset(near, sim->par != NULL, n); /* (a halo copy's row may lack pairs) */
        for (size_t i = 0; i < n; ++i)
            if (M->role[i] == ROLE_SURFACE)
                for (size_t q = sim->nl.offset[i]; q < M->lend[i]; ++q) near[M->pj[q]] = 1;
    }
    const double rel = M->re_l, cl = 2.0 * sim->dim / (M->lambda * M->n0l);
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (M->unk[i] < 0) continue;
        const double rho = sim->mat[ps->material[i]].density;
        double b = g * rho / (dt * dt) * (M->dilate ? nd[i] - 1.0 : fmax(nd[i] - 1.0, 0.0));
        if (g < 1.0) b -= (1.0 - g) * rho / dt * M->divu[i]; /* (number_density) */
        for (size_t q = sim->nl.offset[i]; dirichlet && near[i] && q < M->lend[i]; ++q)
            if (M->role[M->pj[q]] == ROLE_SURFACE)
                b += cl * ry_mps_weight_tamai(M->pr[q], rel) * M->pd[M->pj[q]];
        M->b[M->unk[i]] = b;
        M->xs[M->unk[i]] = ps->f[RY_F_P][i];
    }
    int it;
    double res;
    ry_csr_dist dd;
    if (M->defl > 0 && !sim->par) {
        const double *bb = M->b;
        RY_TRY(aggregates(sim, M, nunk, err));
        RY_TRY(ry_csr_pcg_deflated(&M->A, 1, &bb, &M->xs, &M->D, M->tol, (int)M->max_iter, &it,
                                   &res, err));
    } else {
        RY_TRY(ry_csr_pcg(&M->A, M->b, M->xs, M->tol, (int)M->max_iter, &it, &res,
                          dist_of(sim, M, &dd), err));
    }
    M->last_iters = it;
    M->total_iters += it;
    double *p = ps->f[RY_F_P];
    for (size_t i = 0; i < n; ++i) {
        double v = M->unk[i] >= 0 ? M->xs[M->unk[i]] : M->role[i] == ROLE_SURFACE ? M->pd[i] : 0.0;
        if (M->clamp && v < 0) v = 0;
        p[i] = v;
    }
    if (sim->par) sim->par->sync(sim, p, 1);
    if (M->wall_extrapolate || M->thin_neumann) {
        extrapolate_walls(sim, M);
        if (sim->par) sim->par->sync(sim, p, 1);
    }
    return RY_OK;
}

/* Pressure gradient (eq. 5) and the correction u' = -dt/rho grad p at x*: v = u* + u',
 * x = x* + dt u'. Neighbours: fluid and wall particles (dummies carry no pressure). */
static void correct(ry_sim *sim, mps *M, double dt) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const size_t n = ps->n;
    const double re = M->re_g;
    const double *p = ps->f[RY_F_P];
    double *gx = M->xs; /* dim per particle */
    /* the pair terms' first half as a vector loop (3D, no periodic side) */
    const int lanes = ry_box_plain(&sim->box) == 3;
    size_t rowmax = 0;
    for (size_t i = 0; lanes && i < n; ++i)
        if (M->gend[i] - sim->nl.offset[i] > rowmax) rowmax = M->gend[i] - sim->nl.offset[i];
    const double *x0 = ps->f[RY_F_X], *x1 = ps->f[RY_F_X + (dim > 1)],
                 *x2 = ps->f[RY_F_X + (dim > 2 ? 2 : 0)];
#pragma omp parallel
    {
        /* each pair's separation, squared distance and w / r^2 (lanes) */
        double *buf = lanes ? malloc(5 * (rowmax + 1) * sizeof *buf) : NULL;
        double *bx = buf, *by = buf + rowmax + 1, *bz = by + rowmax + 1, *br2 = bz + rowmax + 1,
               *bwr = br2 + rowmax + 1;
#pragma omp for schedule(dynamic, 64)
        for (size_t i = 0; i < n; ++i) {
            if (ps->kind[i] != RY_KIND_FLUID) continue;
            double pmin = p[i];
            /* CSF in pressure form: a surface particle measures the gradient from its own pressure,
             * the Laplace jump at its place. With the neighbourhood's least pressure (eq. 5) a
             * protruding particle, whose larger curvature gives it the larger jump, would lose the
             * difference that pushes it back, and the surface roughens until the drop breaks up. */
            const int own = M->csf_pressure && M->role[i] == ROLE_SURFACE;
            for (size_t q = sim->nl.offset[i]; M->pmin_on && !own && q < M->gend[i]; ++q)
                if (M->role[M->pj[q]] != ROLE_DUMMY) {
                    const uint32_t j = M->pj[q];
                    double pj = p[j];
                    if (thin_normal(M, j)) { /* the side of a thin wall needs the separation */
                        double dx[3];
                        ry_sim_separation(sim, i, j, dx);
                        pj = grad_pressure(M, p, j, dx);
                    }
                    pmin = fmin(pmin, pj);
                }
            double m[3][3] = {{0}}, g[3] = {0, 0, 0}, x[3] = {0, 0, 0};
            if (buf) { /* the same values as sep() and the weight below, eight pairs at a time */
                const size_t q0 = sim->nl.offset[i], nb = M->gend[i] - q0;
                const uint32_t *jj = M->pj + q0;
                const double *rr = M->pr + q0, xi0 = x0[i], xi1 = x1[i], xi2 = x2[i];
#pragma omp simd
                for (size_t k = 0; k < nb; ++k) {
                    const uint32_t j = jj[k];
                    const double e0 = x0[j] - xi0, e1 = x1[j] - xi1, e2 = x2[j] - xi2;
                    const double r2 = e0 * e0 + e1 * e1 + e2 * e2, s = rr[k] / re - 1.0;
                    bx[k] = e0;
                    by[k] = e1;
                    bz[k] = e2;
                    br2[k] = r2;
                    bwr[k] = (rr[k] < re ? s * s : 0.0) / r2;
                }
                for (size_t k = 0; k < nb; ++k) {
                    const uint32_t j = jj[k];
                    if (M->role[j] == ROLE_DUMMY || br2[k] <= 0) continue;
                    const double dx[3] = {bx[k], by[k], bz[k]}, wr = bwr[k];
                    const double pj = grad_pressure(M, p, j, dx);
                    for (int a = 0; a < 3; ++a) {
                        g[a] += wr * (pj - pmin) * dx[a];
                        for (int b = 0; b < 3; ++b) m[a][b] += wr * dx[a] * dx[b];
                    }
                }
            } else
                for (size_t q = sim->nl.offset[i]; q < M->gend[i]; ++q) {
                    const uint32_t j = M->pj[q];
                    double dx[3];
                    const double r2 = ry_sim_separation(sim, i, j, dx);
                    if (M->role[j] == ROLE_DUMMY || r2 <= 0) continue;
                    const double w = ry_mps_weight_tamai(M->pr[q], re), wr = w / r2;
                    const double pj = grad_pressure(M, p, j, dx);
                    for (int a = 0; a < dim; ++a) {
                        g[a] += wr * (pj - pmin) * dx[a];
                        for (int b = 0; b < dim; ++b) m[a][b] += wr * dx[a] * dx[b];
                    }
                }
            if (M->grad == GRAD_STANDARD || !ry_solve_small(dim, m, g, x))
                for (int a = 0; a < dim; ++a) x[a] = dim * g[a] / M->n0g;
            for (int a = 0; a < dim; ++a) gx[dim * i + a] = x[a];
        }
        free(buf);
    }
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        const double rho = sim->mat[ps->material[i]].density;
        for (int d = 0; d < dim; ++d) {
            const double du = -dt / rho * gx[dim * i + d];
            ps->f[RY_F_VX + d][i] = ps->f[M->f_vs[d]][i] + du;
            ps->f[RY_F_X + d][i] += dt * du;
        }
    }
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
    RY_TRY(wall_bodies(sim, M, fluid_rows, err));
    RY_TRY(pairs_build(sim, M, fluid_rows, err));
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
    if (M->cl_slip) contact_lines(sim, M);
    if (!M->csf_pressure && !fuse) RY_TRY(ry_st_accelerate(&M->st, sim, a, err));
    if (M->colour_on) RY_TRY(colour_accelerate(sim, M, a, err));
    if (M->wall_mode == WALLV_MIRRORED) wall_distances(sim, M);
    if (M->rheo_gnf || M->rheo_ob) rheology_explicit(sim, M, dt);
    if (M->visc == VISC_EXPLICIT) viscous_explicit(sim, M);
    if (M->visc == VISC_IMPLICIT || M->visc == VISC_MIXED) {
        RY_TRY(viscous_implicit(sim, M, dt, fuse, err));
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
    RY_TRY(wall_bodies(sim, M, 0, err));
    RY_TRY(pairs_build(sim, M, 0, err));
    number_density(sim, M);
    RY_TRY(pressure(sim, M, dt, err));
    correct(sim, M, dt);
    M->st.pair_j = NULL;           /* the pairs are of x*, the particles now elsewhere */
    if (sim->par && M->coll_r > 0) /* the collisions read the corrected neighbours */
        for (int d = 0; d < dim; ++d) {
            sim->par->sync(sim, ps->f[RY_F_X + d], 1);
            sim->par->sync(sim, ps->f[RY_F_VX + d], 1);
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

const ry_scheme_type ry_scheme_mps = {
    "mps",    "moving particle semi-implicit (Tamai weight, Iribe gradient, PCG pressure)",
    mps_init, mps_dt,
    mps_step, mps_free,
    mps_vars, NULL,
    mps_stat};
