/* Internal to src/schemes/mps: the state of the scheme `mps` and what its files share: the
 * roles of the pressure equation, and the small helpers that the pair loops of more than one
 * file inline (the pair viscosity and the wall velocity of the viscous terms, thin walls in the
 * pressure equation and in its gradient). The scheme's equations are listed in mps.c. */
#ifndef RYUSHI_MPS_INTERNAL_H
#define RYUSHI_MPS_INTERNAL_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "ryushi/sim.h"
#include "ryushi/surface_tension.h"
#include "linalg/amg.h"
#include "linalg/sparse.h"
#include "physics/colour_field.h"
#include "pairs/pair_cache.h"

enum { SRC_MIXED, SRC_NUMBER_DENSITY };
enum { VISC_EXPLICIT, VISC_IMPLICIT, VISC_NONE, VISC_MIXED };
enum { GRAD_CORRECTED, GRAD_STANDARD };
enum { WALLV_OWN, WALLV_MIRRORED, WALLV_SLIP };

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
    int wall_neumann;      /* every wall stays out of it (Neumann with the hydrostatic head) */
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
    long wb_key[3];  /* searches, list edits and particles when mps_wall_bodies last ran */
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
    int precond, vprecond; /* scheme.solver.preconditioner, .viscosity_preconditioner */
    ry_amg amg, vamg;      /* with boomeramg: the pressure's and the viscosity's solver */
    int32_t *unk;          /* unknown index per particle, -1 if none */
    int32_t *uslot;        /* with boomeramg: the particle of each unknown */
    int32_t *ucol;         /* symmetry planes: a particle's column in the pressure's rows */
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
    /* The pairs within re_g and re_l at the current positions (mps_pairs_build), in the rows of
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
    /* this process's solves (not in checkpoints): iterations and solves of the pressure and
     * the viscosity, and the seconds in their solvers (assembly excluded) */
    long total_piters, psolves, total_viters, vsolves;
    double psolve_s, vsolve_s;
    /* and of the pressure equation: its unknowns and those of them that are walls (summed over
     * the solves), the seconds of its assembly (matrix and right-hand side) and of the walls'
     * extrapolated pressure */
    double total_unk, total_wunk, passemble_s, pwall_s;
} mps;

/* Kinematic viscosity of a pair (harmonic mean: symmetric, and 0 next to an inviscid fluid).
 * With a shear-rate dependent viscosity each particle has its own value (field f_nu, set by
 * mps_rheology_explicit). A wall takes the fluid particle's: a no-slip wall's shear stress is the
 * fluid's own. (The mean with the wall body's material, the first one unless the body names
 * another, would let the embolic liquid slide through a catheter as if it were water.) */
static inline double nu_mean(double a, double b) {
    return a + b > 0 ? 2.0 * a * b / (a + b) : 0.0;
}
static inline double pair_nu(const ry_sim *sim, const mps *M, size_t i, size_t j) {
    if (!M->rheo_gnf) { /* the materials' pairs, computed once (mps_rheology_init) */
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
    if (M->cl_slip && M->cline[i]) return 0.0; /* a contact line slides (mps_contact_lines) */
    if (M->wall_mode == WALLV_OWN) return 1.0;
    if (M->wall_mode == WALLV_SLIP) return 0.0; /* no shear stress from the walls */
    return 1.0 + fmin(M->wd[j] / fmax(M->wd[i], 1e-3 * sim->dx), 1.5);
}

/* Whether wall particle i stays out of the pressure equation: a thin wall's one layer has
 * fluid on both sides, and as an unknown it would carry the pressure from one to the other
 * (from a catheter's bore to the water around it). Left out, it is a Neumann boundary to the
 * fluid on either side, and its pressure for the gradient is extrapolated from each side. */
static inline int thin_out(const mps *M, size_t i) {
    return M->thin_neumann && M->thin && M->thin[i] >= 0;
}

/* Whether particle i stays out of the pressure equation as a wall: a thin one (thin_out), or with
 * `scheme.wall_pressure: neumann` any wall particle. */
static inline int wall_out(const ry_sim *sim, const mps *M, size_t i) {
    return thin_out(M, i) || (M->wall_neumann && sim->ps.kind[i] == RY_KIND_WALL);
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

/* mps_operators.c: the pairs within re_g and re_l, the number density and the roles */
ry_status mps_pairs_build(ry_sim *sim, mps *M, int fluid_rows, ry_error *err);
void mps_number_density(ry_sim *sim, mps *M);

/* mps_walls.c: thin walls and wetting groups of wall bodies, the walls' distances, contact lines
 * and extrapolated pressure */
ry_status mps_body_is_wall(ry_sim *sim, ry_case *c, size_t k, const char *key, ry_error *err);
ry_status mps_body_thin(ry_sim *sim, ry_case *c, mps *M, ry_error *err);
ry_status mps_wall_bodies(ry_sim *sim, mps *M, int fluid_rows, ry_error *err);
void mps_contact_lines(ry_sim *sim, mps *M);
void mps_wall_distances(ry_sim *sim, mps *M);
void mps_extrapolate_walls(ry_sim *sim, mps *M);

/* mps_viscosity.c: viscosity and rheology */
ry_status mps_rheology_init(ry_sim *sim, mps *M, ry_error *err);
void mps_rheology_explicit(ry_sim *sim, mps *M, double dt);
void mps_viscous_explicit(ry_sim *sim, const mps *M);
ry_status mps_viscous_implicit(ry_sim *sim, mps *M, double dt, int with_st, ry_error *err);

/* mps_surface.c: surface tension, two liquids, outlets */
ry_status mps_contact_angle(ry_sim *sim, ry_case *c, mps *M, ry_error *err);
ry_status mps_interfacial(ry_sim *sim, ry_case *c, mps *M, ry_error *err);
ry_status mps_outlet_sinks(ry_sim *sim, ry_case *c, ry_error *err);
ry_status mps_colour_accelerate(ry_sim *sim, mps *M, double *const a[3], ry_error *err);
void mps_csf_dirichlet(ry_sim *sim, mps *M);

/* mps_pressure.c: the linear systems, the pressure Poisson equation and the correction */
const ry_csr_dist *mps_dist_of(const ry_sim *sim, mps *M, int velocity, ry_csr_dist *d);
ry_amg_slots mps_slots(const ry_sim *sim, mps *M);
ry_status mps_assemble(ry_sim *sim, mps *M, size_t nunk, int viscous, double dt, double diag_extra,
                       const int32_t *col, ry_error *err);
ry_status mps_pressure(ry_sim *sim, mps *M, double dt, ry_error *err);
void mps_correct(ry_sim *sim, mps *M, double dt);

#endif
