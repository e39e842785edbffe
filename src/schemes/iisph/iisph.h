/* Implicit incompressible SPH scheme (registered as "iisph"; docs/reference/iisph.md). */
#ifndef RYUSHI_SPH_IISPH_H
#define RYUSHI_SPH_IISPH_H

#include "ryushi/sim.h"

extern const ry_scheme_type ry_scheme_iisph;

#endif
