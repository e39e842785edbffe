/* ryushi — the Moving Particle Semi-implicit method (seed 003, SPEC section 3): the scheme
 * `mps` and what measures its droplets. docs/mps.md describes the equations and options. */
#ifndef RYUSHI_MPS_H
#define RYUSHI_MPS_H

#include "ryushi/sim.h"

extern const ry_scheme_type ry_scheme_mps;

/* Probes of series.csv for MPS and droplets (listed by `ryushi probes`). */
extern const ry_probe ry_probe_width_x, ry_probe_drop_pressure, ry_probe_ppe_iterations,
    ry_probe_contact_angle, ry_probe_contact_angle_second, ry_probe_width_x_second,
    ry_probe_pressure_jump_second;

/* Contact angle [degrees] of a sessile drop shaped as a circular cap (2D: a circular segment
 * of area A; 3D: a spherical cap of volume V) of height h on a flat wall: 2D, theta solves
 * (1 - cos theta)^2 / (theta - sin theta cos theta) = h^2 / A (bisection); 3D,
 * cos theta = (1 - 2 q) / (1 + q), q = pi h^3 / (3 V). NAN when h or A is not positive. */
double ry_cap_contact_angle(int dim, double h, double size);

/* Number density n0 = sum_j w(|k| l0) and lambda = sum_j |k|^2 l0^2 w / n0 (seed eq. 4 and 8)
 * of the full square (2D) or simple cubic (3D) lattice of spacing l0 with Tamai's weight of
 * radius re (self excluded). */
void ry_mps_lattice(int dim, double l0, double re, double *n0, double *lambda);

/* Linear-solver iterations of the pressure Poisson equation: in the last step and in total
 * (0 for other schemes). */
int ry_mps_last_iterations(const ry_sim *sim);
long ry_mps_total_iterations(const ry_sim *sim);
/* Pairs of the neighbour list within the interaction radius that thin walls cut at the last
 * step, counted from both ends (docs/mps.md, "Thin walls"). */
size_t ry_mps_cut_pairs(const ry_sim *sim);

#endif
