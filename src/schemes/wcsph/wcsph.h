/* Weakly compressible SPH scheme (registered as "wcsph"). */
#ifndef RYUSHI_SPH_WCSPH_H
#define RYUSHI_SPH_WCSPH_H

#include "ryushi/sim.h"

extern const ry_scheme_type ry_scheme_wcsph;

#endif
