/* ryushi — what measures the beams of the scheme `solid` (SPH for elastic solids, seed 000,
 * SPEC section 2): the centreline and the reference solutions (beams, vibrating plate, buckled
 * column). The beam's geometry is in ryushi/beam.h. */
#ifndef RYUSHI_SOLID_H
#define RYUSHI_SOLID_H

#include "ryushi/beam.h"
#include "ryushi/sim.h"

/* Position of the beam's centreline at arc length s from the root (0 <= s <= L): the mean
 * position of each particle column (by reference x), interpolated linearly between column
 * centres and extrapolated along the first and last segment to the root and the free end.
 * disp (may be NULL) receives the displacement from the reference centreline. Needs the
 * reference positions (x0, y0, z0) that the scheme `solid` keeps. */
ry_status ry_beam_centreline(const ry_sim *sim, double s, double *pos, double *disp, ry_error *err);

/* Reference solutions for a cantilever of length L clamped at x = 0 (unit intensity: the
 * deflection is proportional to it). Load types as in the case key scheme.load.type. */
typedef enum ry_beam_load {
    RY_BEAM_LOAD_NONE,
    RY_BEAM_LOAD_END,     /* point load P at x = L */
    RY_BEAM_LOAD_UNIFORM, /* q = q0 */
    RY_BEAM_LOAD_LINEAR,  /* q = q0 x / L ("hydrostatic", largest at the free end) */
    RY_BEAM_LOAD_COSINE   /* q = q0 cos(pi x / (2 L)) */
} ry_beam_load;
/* Euler-Bernoulli deflection w(x) = (1/EI) int_0^x (x - s) M(s) ds for intensity 1. */
double ry_beam_deflection_eb(ry_beam_load load, double L, double EI, double x);
/* Timoshenko's shear deflection int_0^x V(s) ds / (kappa G A) for intensity 1 (add it to the
 * Euler-Bernoulli one); kappa = 5/6 for a rectangle. */
double ry_beam_deflection_shear(ry_beam_load load, double L, double kappa_GA, double x);
/* Elastica of a cantilever under a dead end load P normal to it, alpha2 = P L^2 / EI: the tip
 * position (x along the undeformed beam, y along the load) in units of L, and the tip angle. */
void ry_elastica_end_load(double alpha2, double *x_tip, double *y_tip, double *theta_tip);

/* Angular frequency of the first bending mode of a clamped-free plate of length L and
 * thickness H in cylindrical bending (thin-plate theory, plane strain):
 * omega^2 = E H^2 k^4 / (12 rho (1 - nu^2)), k = RY_CANTILEVER_KL1 / L. */
double ry_plate_omega(double E, double nu, double rho, double H, double L);

/* Complete elliptic integrals of the first and second kind, K(p) and E(p), modulus p < 1
 * (arithmetic-geometric mean). */
void ry_elliptic_ke(double p, double *K, double *E);

/* Euler's elastica of a clamped-free column under a dead axial end load P above the critical
 * load P_cr = pi^2 EI / (4 L^2), load_ratio = P / P_cr >= 1 (Timoshenko & Gere 1961, sec. 2.7):
 * kL = sqrt(P / EI) L = K(p), p = sin(theta_tip / 2); tip position in units of L along the
 * undeformed axis from the root, 2 E(p) / K(p) - 1, and across it, 2 p / K(p). At or below the
 * critical load the column stays straight: (1, 0, 0). */
void ry_elastica_column(double load_ratio, double *x_tip, double *y_tip, double *theta_tip);

#endif
