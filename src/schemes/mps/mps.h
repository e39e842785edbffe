/* The scheme "mps" (its registration). */
#ifndef RY_SCHEMES_MPS_H
#define RY_SCHEMES_MPS_H

#include "ryushi/sim.h"

extern const ry_scheme_type ry_scheme_mps;

#endif
