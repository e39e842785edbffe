/* ryushi — surface-tension models for particle methods (MPS and SPH): the continuum surface
 * force (Brackbill et al. 1992; in particle form after Nomura et al. 2001) with the curvature
 * from the colour function, and the inter-particle potential model of Kondo et al. (2007)
 * (seed 003, eq. 9-12). docs/reference/mps.md gives the equations.
 *
 * Both act on fluid particles only and read a neighbour list that covers the model's radius
 * re (3.1 spacings by default); the acceleration of particle i is its force divided by the
 * particle's mass (field `mass`), so the same code serves MPS (m = rho l0^d) and SPH. */
#ifndef RYUSHI_SURFACE_TENSION_H
#define RYUSHI_SURFACE_TENSION_H

#include "ryushi/sim.h"

#define RY_PI 3.14159265358979323846

typedef enum ry_st_model { RY_ST_NONE = 0, RY_ST_CSF, RY_ST_POTENTIAL } ry_st_model;

/* CSF curvature: the divergence of the normals of the single colour gradients (the default), or
 * the surface divergence tr((I - n n) grad n) of the normals of the smoothed colour gradient. */
typedef enum ry_st_curvature_form {
    RY_ST_CURV_DIVERGENCE = 0,
    RY_ST_CURV_SURFACE
} ry_st_curvature_form;

/* Groups of walls with their own contact angles (bodies[k].contact_angle), besides the rest. */
#define RY_ST_WALL_GROUPS 8

typedef struct ry_surface_tension {
    int model;     /* ry_st_model */
    int curvature; /* ry_st_curvature_form (CSF; ry_st_setup sets the default) */
    int dim;
    double sigma; /* surface tension coefficient [N/m] */
    double l0;    /* lattice spacing [m] */
    double re;    /* radius of the model [m] */
    /* potential model: C of eq. 11 (negative: the sum of the potential over the pairs across
     * the split is negative) [N/m^2 in 3D] */
    double C;
    /* CSF: sum over a column across a flat surface of the inward weight sums (the discrete
     * delta function's normalisation) [m] */
    double delta_sum;
    double g_top; /* that sum for the top layer alone */
    /* Wetting, potential model: the pairs of a fluid particle of material m and a wall of
     * group g with C wall_ratio[g][m], wall_ratio = (1 + cos theta)/2 for that liquid's contact
     * angle theta on those walls (the Dupre work of adhesion sigma (1 + cos theta) against the
     * work of cohesion 2 sigma); 0: walls do not attract. Group 0 holds the walls without
     * angles of their own; wall_group (NULL: all in group 0) gives each particle's group,
     * indexed like the particles. */
    double wall_ratio[RY_ST_WALL_GROUPS][256];
    const uint8_t *wall_group;
    /* Pairs of the neighbour list (by their place in sim->nl.j) that a thin wall separates
     * and that take no part (NULL: none); MPS sets it each step (docs/reference/mps.md, "Thin
     * walls"). */
    const uint8_t *cut;
    /* Potential model, thin walls: each particle's unit normal of its thin wall's sheet (3 per
     * particle, zero where it is not a thin wall or has no sheet), or NULL; MPS sets it each
     * step. A thin wall particle then attracts as a wall of thin_layers layers would: images of
     * it 1, ..., thin_layers - 1 spacings behind the sheet, away from the fluid particle, add
     * their pair forces (ry_st_setup: 1, the wall as it stands; docs/reference/mps.md, "Thin
     * walls"). */
    const double *thin_normal;
    int thin_layers;
    /* The scheme's own pairs at the current positions, where it keeps them (NULL: the models
     * read the neighbour list): particle i's pairs are pair_j[q], at distance pair_r[q], for q
     * from sim->nl.offset[i] to pair_end[i]; they hold every pair within re but the cut ones.
     * MPS sets them after each pair build and takes them back when the particles move. */
    const uint32_t *pair_j;
    const double *pair_r;
    const size_t *pair_end;
    /* Two liquids, potential model: pairs of different fluid materials with C cross_ratio,
     * cross_ratio = 1 - sigma_ab / (2 sigma) (1: the liquids mix). */
    double cross_ratio;
    /* CSF with walls (wetting): the contact angle [rad], NAN for none. Walls then count in the
     * colour function, and the normal of a fluid particle beside a wall (within 1.5 spacings)
     * is set to sin(theta) t + cos(theta) n_w (Brackbill et al. 1992): n_w the wall's normal
     * into the fluid, t the particle's normal projected on the wall plane. */
    double contact_angle;
    /* CSF: the Laplace jump sigma kappa as the pressure of the surface particles (1) or a force
     * (0), and the passes of smoothing of that jump along the surface (ry_st_read). */
    int pressure_form;
    int smoothing;
} ry_surface_tension;

/* Work space of the pressure form in a scheme: the Laplace jump per particle (8 n doubles, as
 * ry_st_laplace_pressure needs) and the surface tag (n). */
typedef struct ry_st_work {
    double *p;
    uint8_t *tag;
    size_t cap;
} ry_st_work;
ry_status ry_st_work_ensure(ry_st_work *w, size_t n, ry_error *err);
void ry_st_work_free(ry_st_work *w);

/* Names used in case files: "none", "csf", "potential" (NULL-terminated, indexed by model). */
extern const char *const ry_st_model_names[];
/* "divergence", "surface" (NULL-terminated, indexed by ry_st_curvature_form). */
extern const char *const ry_st_curvature_names[];

/* Sets up a model on the square (2D) or simple cubic (3D) lattice of spacing l0. */
ry_status ry_st_setup(ry_surface_tension *st, int model, int dim, double l0, double re,
                      double sigma, ry_error *err);

/* Reads the case's surface_tension section (model, sigma, radius in spacings with default
 * re_default and at most re_max, and for CSF csf_form, curvature and smoothing) and sets the
 * model up on the lattice of spacing l0. The curvature defaults to the form's own: the surface
 * divergence for the pressure form, the full divergence for the force form. */
ry_status ry_st_read(ry_surface_tension *st, ry_case *c, int dim, double l0, double re_default,
                     double re_max, ry_error *err);

/* The SPH schemes (IISPH, WCSPH): ry_st_read (radius 3.1 spacings by default), then, for CSF in
 * pressure form, surface_tension.surface_threshold (*beta, default 0.995, an error with another
 * form), and the artificial repulsion scheme.repulsion.distance (*rc [m]; 0.85 spacings by
 * default with the pressure form, else 0: off) and .restitution (*e, 0.2); see ry_collisions. */
ry_status ry_st_read_sph(ry_surface_tension *st, ry_case *c, int dim, double dx, double *beta,
                         double *rc, double *e, ry_error *err);

/* CSF with the Laplace jump as the surface particles' pressure. */
static inline int ry_st_pressure_form(const ry_surface_tension *st) {
    return st->model == RY_ST_CSF && st->pressure_form;
}

/* Capillary-wave limit of the time step (Brackbill et al. 1992), sqrt(rho l0^3 / (2 pi sigma))
 * with the least density of the materials; INFINITY without surface tension. */
double ry_st_capillary_dt(const ry_surface_tension *st, const ry_sim *sim);

/* Potential model (seed eq. 10 and 12): the inter-particle force f(r) = (r - l0)(r - re) and
 * its potential phi(r) = 1/3 (3/2 l0 - 1/2 re - r)(r - re)^2, f = -dphi/dr; both 0 for r > re. */
double ry_st_potential_f(double r, double l0, double re);
double ry_st_potential_phi(double r, double l0, double re);
/* Sum of phi over the pairs (i in A, j in B) of a lattice split into two half-spaces, per
 * lattice site of the split plane (i runs over one column of A normal to the plane, j over all
 * of B): the right-hand sum of eq. 11. */
double ry_st_potential_pair_sum(int dim, double l0, double re);
/* C from 2 sigma l0^(d-1) = C sum (eq. 11; in 2D per unit depth). */
double ry_st_potential_coefficient(int dim, double l0, double re, double sigma);

/* Linear stability of the potential model's lattice (docs/reference/mps.md, "The potential model's
 * lattice"): a plane wave u = U e^(i k.x) of the square (2D) or cubic (3D) lattice of spacing l0,
 * each site of mass rho l0^d, under the pair forces C f(r) within re, oscillates as
 * omega^2 = U.D(k).U / (m |U|^2), D(k) = sum_j K_j (1 - cos k.x_j), the pair stiffness
 * K_j = C (f'(r) e e + f(r)/r (I - e e)), e = x_j / r. ry_st_potential_lattice_omega2 gives
 * omega^2 [1/s^2] for the wave vector k [1/m] and the polarisation pol (not normalised);
 * negative: the wave grows as e^(sqrt(-omega^2) t). */
double ry_st_potential_lattice_omega2(int dim, double l0, double re, double sigma, double rho,
                                      const double k[3], const double pol[3]);
/* The fastest growth [1/s] of the transverse waves (pol normal to k: the divergence-free
 * ones, which the pressure equation leaves alone) over the wave vectors of a grid of
 * steps pi / (16 l0) up to pi / l0 along each axis; 0 if none grows. k_out (or NULL) receives
 * the wave vector of the fastest, in units of pi / l0. */
double ry_st_potential_lattice_growth(int dim, double l0, double re, double sigma, double rho,
                                      double k_out[3]);

/* The potential model's acceleration of fluid particle i alone, added to a[d][i] (what
 * ry_st_accelerate does for each, for a scheme that fuses it into a pass of its own). */
void ry_st_potential_particle(const ry_surface_tension *st, const ry_sim *sim, size_t i,
                              double *const a[3]);

/* Adds the surface-tension acceleration to a[d][i] of every fluid particle. The neighbour list
 * of sim must hold all pairs within st->re. */
ry_status ry_st_accelerate(const ry_surface_tension *st, const ry_sim *sim, double *const a[3],
                           ry_error *err);

/* CSF curvature (1/R in 2D, 2/R in 3D for a sphere) of the fluid particles near the surface
 * (0 elsewhere): the corrected divergence of the colour function's outward normal. kappa holds
 * 8 n doubles (the rest is work space). */
void ry_st_curvature(const ry_surface_tension *st, const ry_sim *sim, double *kappa);

/* CSF in pressure form: pd[i] = sigma kappa_s, the Laplace jump of the fluid particles with
 * tag[i] == surface (the surface particles, which carry it as their pressure). The curvature
 * (ry_st_curvature) is averaged over the surface particles within radius (st->smoothing passes,
 * Tamai weights, the particle itself 1), and corrected for the half spacing between the surface
 * layer and the free surface where it is convex. pd holds 8 n doubles (the rest is work
 * space). */
void ry_st_laplace_pressure(const ry_surface_tension *st, const ry_sim *sim, const uint8_t *tag,
                            uint8_t surface, double radius, double *pd);

#endif
