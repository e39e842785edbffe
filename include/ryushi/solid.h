/* ryushi — what measures the beams of the scheme `solid` (SPH for elastic solids, seed 000,
 * SPEC section 2): the centreline. The beam's geometry is in ryushi/beam.h; the reference
 * solutions (beams, vibrating plate, buckled column) are in ryushi/validate.h. */
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

#endif
