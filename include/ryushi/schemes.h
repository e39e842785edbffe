/* ryushi — the scheme registry: every scheme a case can name in `scheme.name`. */
#ifndef RYUSHI_SCHEMES_H
#define RYUSHI_SCHEMES_H

#include "ryushi/sim.h"

/* The registered schemes, NULL-terminated. */
const ry_scheme_type *const *ry_schemes(void);
const ry_scheme_type *ry_scheme_find(const char *name);

#endif
