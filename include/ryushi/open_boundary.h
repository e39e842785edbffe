/* ryushi — open boundaries: inlets and outlets (case section `open_boundaries`). */
#ifndef RYUSHI_OPEN_BOUNDARY_H
#define RYUSHI_OPEN_BOUNDARY_H

#include "ryushi/sim.h"

/* Open boundaries: read from the case with their inlet zones filled (ry_sim_setup calls it),
 * and the conversions after each step (ry_run calls it): inlet particles past their zone
 * become fluid and are replaced upstream, fluid entering an outlet zone becomes an outlet
 * particle, outlet particles past their zone are removed. Schemes move inlet and outlet
 * particles with their own velocity in their drift. */
ry_status ry_open_setup(ry_sim *sim, ry_case *c, ry_error *err);
ry_status ry_open_update(ry_sim *sim, ry_error *err);
/* Volume [m^3] that entered through inlets / left through outlets so far. */
double ry_open_volume(const ry_sim *sim, int type);

#endif
