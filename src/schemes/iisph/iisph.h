/* Implicit incompressible SPH scheme (registered as "iisph"; docs/iisph.md). */
#ifndef RYUSHI_SPH_IISPH_H
#define RYUSHI_SPH_IISPH_H

#include "ryushi/sim.h"

extern const ry_scheme_type ry_scheme_iisph;

/* Pressure-solve iterations of the last step and their mean over the run so far; 0 (and
 * nothing set) when the simulation does not run IISPH. */
int ry_iisph_iterations(const ry_sim *sim, double *last, double *mean);

#endif
