/* ryushi — the Moving Particle Semi-implicit method (seed 003, SPEC section 3): the lattice
 * sums of its weight. docs/reference/mps.md describes the equations and options. */
#ifndef RYUSHI_MPS_H
#define RYUSHI_MPS_H

#include "ryushi/sim.h"

/* Number density n0 = sum_j w(|k| l0) and lambda = sum_j |k|^2 l0^2 w / n0 (seed eq. 4 and 8)
 * of the full square (2D) or simple cubic (3D) lattice of spacing l0 with Tamai's weight of
 * radius re (self excluded). */
void ry_mps_lattice(int dim, double l0, double re, double *n0, double *lambda);

#endif
