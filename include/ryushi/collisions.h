/* ryushi — the collision model of Lee et al. (2011) between fluid particles. */
#ifndef RYUSHI_COLLISIONS_H
#define RYUSHI_COLLISIONS_H

#include "ryushi/sim.h"

/* Artificial repulsion between fluid particles closer than rc (Lee et al. 2011 collision model
 * in the gather form; MPS, seed 003, and IISPH with free-surface tension): for each approaching
 * pair, particle i takes the share of a partially inelastic collision,
 * dv_i = (1 + e)/2 (v_ij . n) n, n = x_ij / r, v_ij = v_j - v_i (walls count with their own
 * velocity, twice, and do not move). Positions follow by dt dv_i. Reads the rows of the
 * neighbour list of sim (which must reach rc), or with nj the neighbours nj[q] for q from
 * sim->nl.offset[i] to row_end[i] (a shorter list in the same rows); dv is work space of dim n
 * doubles. rc <= 0: nothing. */
void ry_collisions(ry_sim *sim, double rc, double restitution, double dt, const uint32_t *nj,
                   const size_t *row_end, double *dv);

#endif
