/* ryushi — rheology of a material: Newtonian, generalised Newtonian (power law, Carreau) and
 * visco-elastic (Oldroyd-B, Giesekus). Read from `materials[i].rheology`
 * (docs/reference/rheology.md); every viscosity here is kinematic [m^2/s], as the material's
 * `viscosity`.
 *
 * Generalised Newtonian: nu = nu(gamma_dot), gamma_dot = sqrt(2 D:D), D the rate of strain.
 *   power law: nu = k gamma_dot^(n - 1), bounded to [viscosity_min, viscosity_max];
 *   Carreau:   nu = nu_inf + (nu_0 - nu_inf) (1 + (t gamma_dot)^2)^((n - 1)/2).
 * Oldroyd-B: the solvent has the material's `viscosity` nu_s; the polymer stress tau obeys
 *   tau + lambda tau^(upper-convected) = 2 rho nu_p D.
 * Giesekus: the same with the quadratic term of mobility alpha (0 <= alpha <= 1/2; 0 is
 *   Oldroyd-B), which bounds the stress in extension and thins the fluid in shear:
 *   tau + lambda tau^(upper-convected) + (alpha lambda / (rho nu_p)) tau . tau = 2 rho nu_p D. */
#ifndef RYUSHI_RHEOLOGY_H
#define RYUSHI_RHEOLOGY_H

#include "ryushi/case.h"
#include "ryushi/material.h"
#include "ryushi/status.h"

extern const char *const ry_rheology_names[]; /* NULL-terminated, in ry_rheo_model order */

/* Reads `<prefix>.rheology` (prefix e.g. "materials[0]"); absent: Newtonian. */
ry_status ry_rheology_read(ry_case *c, const char *prefix, ry_rheology *r, ry_error *err);
/* Whether the model makes the viscosity depend on the shear rate. */
int ry_rheology_generalised(const ry_rheology *r);
/* Whether the model carries a polymer stress (Oldroyd-B, Giesekus). */
int ry_rheology_viscoelastic(const ry_rheology *r);
/* Kinematic viscosity at shear rate gd; nu_newtonian for the Newtonian and visco-elastic models
 * (the solvent). */
double ry_rheology_nu(const ry_rheology *r, double nu_newtonian, double gd);
/* Largest viscosity the model can take (for time-step limits): nu_newtonian, viscosity_max, or
 * the larger of Carreau's two plateaus. */
double ry_rheology_nu_max(const ry_rheology *r, double nu_newtonian);
/* Steady simple shear at rate gd: the shear stress over density and rate [m^2/s], solvent and
 * polymer together. Generalised Newtonian: ry_rheology_nu; Oldroyd-B: nu_newtonian + nu_p;
 * Giesekus (Bird, Armstrong & Hassager 1987, Dynamics of Polymeric Liquids, vol. 1):
 * nu_newtonian + nu_p (1 - f)^2 / (1 + (1 - 2 alpha) f), f = (1 - chi) / (1 + (1 - 2 alpha) chi),
 * chi^2 = (sqrt(1 + 16 alpha (1 - alpha) Wi^2) - 1) / (8 alpha (1 - alpha) Wi^2), Wi = lambda gd.
 */
double ry_rheology_shear_nu(const ry_rheology *r, double nu_newtonian, double gd);

/* The symmetric polymer stress is stored by components, ry_tau_count(dim) of them: in 2D
 * xx, yy, xy; in 3D xx, yy, zz, xy, xz, yz. Component k is tau_ab with (a, b) from
 * ry_tau_index, and its field is named ry_tau_name (tau_xx, ...). */
int ry_tau_count(int dim);
void ry_tau_index(int dim, int k, int *a, int *b);
const char *ry_tau_name(int dim, int k);
/* The axes whose mirror negates component k (tau_ab: a's and b's unless they are the same). */
unsigned ry_tau_odd(int dim, int k);
/* |tau|^2 = tau : tau of the stored components (the off-diagonal ones counted twice). */
double ry_tau_norm2(int dim, const double *tau);
/* One step of a visco-elastic model's stress equation at a particle of density rho, tau
 * (ry_tau_count components) in place:
 * (1 + th dt/lambda - dt/2 K) tau' = (1 - (1 - th) dt/lambda + dt/2 K) tau
 *                                      + dt (2 eta_p D / lambda - (alpha / eta_p) tau . tau),
 * K tau = L tau + tau L^T, with L the velocity gradient (3 x 3 row-major, L_ab = du_a/dx_b), D
 * its symmetric part, eta_p = rho nu_p the polymer's dynamic viscosity and alpha 0 for
 * Oldroyd-B: the upper-convected term at the midpoint (a rotation turns the stress without
 * stretching it), the relaxation at the midpoint too where dt <= lambda and towards implicit
 * beyond (th = max(1/2, 1 - lambda/(2 dt)): stable, and not oscillating, for any dt against
 * lambda), the quadratic term explicit. A steady state of the model is one of the step. Where dt
 * |L| exceeds 1, or the quadratic term's rate alpha |tau| / eta_p exceeds 1/(4 dt), the step is
 * taken in as many equal parts as keep both below. */
void ry_polymer_step(int dim, const ry_rheology *r, const double L[9], double rho, double dt,
                     double *tau);

#endif
