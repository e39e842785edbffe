/* Non-Newtonian materials in the SPH schemes (docs/reference/rheology.md, "In the SPH schemes"):
 * the velocity gradient by the corrected kernel gradient, the viscosity of a generalised Newtonian
 * material (power law, Carreau) from its shear rate, and the polymer stress of a visco-elastic
 * material (Oldroyd-B, Giesekus) with its divergence. The scheme's viscous term reads the
 * per-particle viscosity; the stress divergence is an acceleration the scheme adds to its own. */
#ifndef RYUSHI_SPH_RHEOLOGY_H
#define RYUSHI_SPH_RHEOLOGY_H

#include "ryushi/sim.h"
#include "pairs/pair_cache.h"

typedef struct ry_sph_rheo {
    int on;       /* some material is not Newtonian */
    int ob;       /* some material is visco-elastic (Oldroyd-B, Giesekus) */
    int f_nu;     /* kinematic viscosity per particle [m^2/s] (state: the time step reads it) */
    int f_gd;     /* shear rate sqrt(2 D:D) [1/s] */
    int f_tau[6]; /* polymer stress [Pa]: xx, yy, (zz,) xy, (xz, yz) */
    double *L;    /* 9 per particle: velocity gradient L_ab = du_a/dx_b of the last rates */
    double *acc;  /* 3 per particle: div(tau) / rho of the last rates */
    size_t cap;
} ry_sph_rheo;

/* Reads nothing (the materials carry their models); registers the fields when some material
 * is not Newtonian. */
ry_status ry_sph_rheo_init(ry_sph_rheo *r, ry_sim *sim, ry_error *err);
void ry_sph_rheo_free(ry_sph_rheo *r);

/* At the present state, for the particles with mobile[kind] set: L, the shear rate and the
 * viscosity; with a polymer stress also div(tau)/rho into r->acc (other particles: 0). vol holds
 * every particle's volume. The velocity gradient sees the fixed particles (walls, inlets) with
 * the velocities vwall (the ghost velocity of a no-slip wall); vwall NULL leaves them out
 * (free slip). The stress divergence is taken over the mobile neighbours. pc is the pair cache
 * of the present positions (rows of the mobile particles filled). */
ry_status ry_sph_rheo_rates(ry_sph_rheo *r, ry_sim *sim, const ry_pair_cache *pc,
                            const int mobile[RY_KIND_COUNT], const double *vol,
                            const double *const vwall[3], ry_error *err);

/* Advances the polymer stress by dt with the last rates' L:
 * tau' = (tau + dt (L tau + tau L^T + 2 rho nu_p D / lambda)) / (1 + dt / lambda). */
void ry_sph_rheo_advance(ry_sph_rheo *r, ry_sim *sim, const int mobile[RY_KIND_COUNT], double dt);

/* Time-step limit of the rheology: cvisc h^2 / (largest particle viscosity) for the explicit
 * viscous term (cvisc from the scheme's viscous form) and cfl h sqrt(lambda / nu_p) for the
 * polymer's shear waves; INFINITY when off. */
double ry_sph_rheo_dt(const ry_sph_rheo *r, const ry_sim *sim, const int mobile[RY_KIND_COUNT],
                      double h, double cfl, double cvisc);

#endif
