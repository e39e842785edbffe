/* The scheme "solid" (its registration). */
#ifndef RY_SCHEMES_SOLID_H
#define RY_SCHEMES_SOLID_H

#include "ryushi/sim.h"

extern const ry_scheme_type ry_scheme_solid;

#endif
