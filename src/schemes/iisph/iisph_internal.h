/* Internal to src/schemes/iisph: the state of the scheme `iisph` and what its files share: the
 * wall pressure lists and the pressure solve's pair lists, the light phase's pair rules and the
 * functions of each step of the scheme. The scheme's equations are listed in iisph.c. */
#ifndef RYUSHI_IISPH_INTERNAL_H
#define RYUSHI_IISPH_INTERNAL_H

#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include "linalg/amg.h"
#include "linalg/sparse.h"
#include "ryushi/sim.h"
#include "ryushi/surface_tension.h"
#include "physics/colour_field.h"
#include "pairs/pair_cache.h"
#include "physics/polymer_stress.h"
#include "physics/viscosity_morris1997.h"

/* Grows the array ptr to count elements; on failure leaves it as it is and clears ok. */
#define RY_IISPH_GROW(ptr, count, ok)                                                              \
    do {                                                                                           \
        void *q_ = realloc((ptr), (count) * sizeof *(ptr));                                        \
        if (q_)                                                                                    \
            (ptr) = q_;                                                                            \
        else                                                                                       \
            (ok) = 0;                                                                              \
    } while (0)

/* The walls' pressure extrapolation (iisph_wall_extrapolate) as lists built once per step: each
 * wall or inlet particle with a mobile neighbour within the kernel (w, nw of them), those
 * neighbours (j, from off[k] to off[k + 1]), W_wf and rho_f g . x_wf. An iteration of the solve
 * then reads 20 bytes per entry instead of the pair cache's 64, and skips the walls beyond the
 * fluid's reach. */
typedef struct wall_map {
    size_t nw, cap_n, cap_e;
    uint32_t *w, *j;
    size_t *off, *cnt; /* cnt: per particle, the mobile neighbours (cap_n) */
    double *wt, *h;
} wall_map;

/* The pairs of the pressure solve's iterations (iisph_grad_list_build): for each mobile
 * particle i (from off[i] to off[i + 1]) its neighbours j with a non-zero kernel gradient and
 * grad_i W_ij (3 per entry), 28 bytes per pair, contiguous. */
typedef struct grad_list {
    size_t cap_n, cap_e;
    size_t *off;
    uint32_t *j;
    double *g;
} grad_list;

/* The state of the scheme: its keys, the per-particle scratch of a step and the statistics. */
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
    double *perr;  /* per particle: its density error in the last Jacobi sweep (0: not counted) */
    double *pq;    /* per particle, in each Jacobi sweep: p / delta^2 (a mobile particle) */
    double *djp;   /* and d_ii p + S (3): the part of D_j that is j's own */
    double *vg[3]; /* velocity seen by the viscous term, one array per component */
    size_t cap;
    double *mu;       /* dynamic viscosity per material */
    double mu_corr;   /* viscosity factor (scheme.viscosity_correction: lattice) */
    int morris;       /* scheme.viscous_form: morris */
    double cvisc;     /* its explicit time-step factor: dt <= cvisc h^2 / nu */
    int ghost;        /* scheme.wall_velocity: ghost (Adami et al. 2012) */
    ry_sph_rheo rheo; /* non-Newtonian materials */
    /* Free-surface tension (the surface_tension section; docs/reference/iisph.md): */
    ry_surface_tension st;
    double st_beta;        /* CSF pressure form: surface particles have delta < st_beta delta0 */
    ry_st_work stw;        /* the Laplace jump P_i of the surface particles (0 elsewhere) and their
                              tag (1) */
    double coll_r, coll_e; /* artificial repulsion: distance [m], restitution */
    /* scheme.viscosity: implicit (Morris form, backward Euler; docs/reference/iisph.md) */
    int implicit;
    double vtol;
    ry_csr A;
    int vprecond;    /* scheme.viscosity_preconditioner (linalg/amg.h) */
    ry_amg vamg;     /* with boomeramg: its solver */
    int32_t *unk;    /* unknown number of a mobile particle, else -1 */
    int32_t *vslot;  /* with boomeramg: the particle of each unknown */
    double *vb, *vx; /* right-hand sides (3 per unknown); the components' and their solutions */
    double *vtmp;    /* per particle: halo entries on their way from the owners */
    uint8_t *vown;   /* per unknown: owned by this process (a distributed run) */
    ry_particle_unknowns vpu; /* the distribution of the solve under way */
    size_t vcap;
    long viters_last, viters_total;
    wall_map wm;
    grad_list gl;
    /* A light phase as a moving boundary (scheme.light_phase: boundary; docs/reference/iisph.md, "A
     * light phase"): */
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

/* The pair (i, j) with a light phase as a moving boundary (docs/reference/iisph.md, "A light
 * phase"). A heavy row i leaves its light neighbours j out (pair_skip: not in its pair lists): its
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

/* The two wall maps (iisph_walls.c): RY_MAP_WALL, the walls from the (heavy) fluid into the
 * pressure field; with a light phase also RY_MAP_LIGHT, the walls and the heavy fluid from the
 * light fluid into s->pl. */
enum { RY_MAP_WALL, RY_MAP_LIGHT };

/* The light phase (iisph_light.c): scheme.light_phase, scheme.light_tolerance, the light
 * materials and the checks of the set-up. */
ry_status iisph_light_phase_init(ry_sim *sim, iisph *s, ry_case *c, ry_error *err);

/* Number density, density and the non-pressure accelerations (iisph_viscosity.c). */
ry_status iisph_densities_and_forces(ry_sim *sim, iisph *s, ry_error *err);
/* Implicit viscosity on the predicted velocities (iisph_viscosity.c). */
ry_status iisph_viscous_implicit(ry_sim *sim, iisph *s, double dt, ry_error *err);

/* Free-surface tension (iisph_surface.c). */
ry_status iisph_surface_tension(ry_sim *sim, iisph *s, ry_error *err);

/* The wall pressure lists (iisph_walls.c). */
ry_status iisph_wall_map_build(ry_sim *sim, iisph *s, wall_map *m, double *p, int map,
                               ry_error *err);
void iisph_wall_extrapolate(const wall_map *m, const double *p, double *out);
void iisph_wall_map_free(wall_map *m);

/* The pressure solve and the pressure force (iisph_pressure.c). */
ry_status iisph_grad_list_build(ry_sim *sim, iisph *s, ry_error *err);
long iisph_pressure_solve(ry_sim *sim, iisph *s, double dt);
void iisph_pressure_force(ry_sim *sim, iisph *s, double dt, double *vmax2, double *amax2);

#endif
