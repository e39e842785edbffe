/* ryushi — rheology of a material: Newtonian, generalised Newtonian (power law, Carreau) and
 * visco-elastic (Oldroyd-B). Read from `materials[i].rheology` (docs/rheology.md); every
 * viscosity here is kinematic [m^2/s], as the material's `viscosity`.
 *
 * Generalised Newtonian: nu = nu(gamma_dot), gamma_dot = sqrt(2 D:D), D the rate of strain.
 *   power law: nu = k gamma_dot^(n - 1), bounded to [viscosity_min, viscosity_max];
 *   Carreau:   nu = nu_inf + (nu_0 - nu_inf) (1 + (t gamma_dot)^2)^((n - 1)/2).
 * Oldroyd-B: the solvent has the material's `viscosity` nu_s; the polymer stress tau obeys
 *   tau + lambda tau^(upper-convected) = 2 rho nu_p D. */
#ifndef RYUSHI_RHEOLOGY_H
#define RYUSHI_RHEOLOGY_H

#include "ryushi/case.h"
#include "ryushi/status.h"

typedef enum {
    RY_RHEO_NEWTONIAN = 0,
    RY_RHEO_POWER_LAW,
    RY_RHEO_CARREAU,
    RY_RHEO_OLDROYD_B
} ry_rheo_model;

extern const char *const ry_rheology_names[]; /* NULL-terminated, in ry_rheo_model order */

typedef struct ry_rheology {
    int model;
    double consistency, index; /* power law k [m^2 s^(n-2)], n; Carreau n */
    double nu_min, nu_max;     /* power law bounds [m^2/s] */
    double nu_zero, nu_inf;    /* Carreau [m^2/s] */
    double time;               /* Carreau time constant [s] */
    double nu_polymer;         /* Oldroyd-B [m^2/s] */
    double relaxation;         /* Oldroyd-B lambda [s] */
} ry_rheology;

/* Reads `<prefix>.rheology` (prefix e.g. "materials[0]"); absent: Newtonian. */
ry_status ry_rheology_read(ry_case *c, const char *prefix, ry_rheology *r, ry_error *err);
/* Whether the model makes the viscosity depend on the shear rate. */
int ry_rheology_generalised(const ry_rheology *r);
/* Kinematic viscosity at shear rate gd; nu_newtonian for the Newtonian and Oldroyd-B models
 * (the solvent). */
double ry_rheology_nu(const ry_rheology *r, double nu_newtonian, double gd);
/* Largest viscosity the model can take (for time-step limits): nu_newtonian, viscosity_max, or
 * the larger of Carreau's two plateaus. */
double ry_rheology_nu_max(const ry_rheology *r, double nu_newtonian);

/* The symmetric polymer stress is stored by components, ry_tau_count(dim) of them: in 2D
 * xx, yy, xy; in 3D xx, yy, zz, xy, xz, yz. Component k is tau_ab with (a, b) from
 * ry_tau_index, and its field is named ry_tau_name (tau_xx, ...). */
int ry_tau_count(int dim);
void ry_tau_index(int dim, int k, int *a, int *b);
const char *ry_tau_name(int dim, int k);
/* One step of the Oldroyd-B equation at a particle, tau (ry_tau_count components) in place:
 * tau' = (tau + dt (L tau + tau L^T + 2 eta_p D / lambda)) / (1 + dt / lambda), with L the
 * velocity gradient (3 x 3 row-major, L_ab = du_a/dx_b), D its symmetric part and eta_p the
 * polymer's dynamic viscosity: the upper-convected terms explicit and the relaxation implicit,
 * so that the update is stable for any dt against lambda. */
void ry_oldroyd_b_step(int dim, const double L[9], double eta_p, double lambda, double dt,
                       double *tau);

#endif
