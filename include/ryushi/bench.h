/* ryushi — built-in benchmarks, shared by the bench programs and `ryushi bench`. */
#ifndef RYUSHI_BENCH_H
#define RYUSHI_BENCH_H

#include <stddef.h>
#include <stdio.h>

#include "ryushi/status.h"

/* Neighbour search on count sets of ns[k] random uniform particles in the unit square or cube
 * (dim 2 or 3), the radius giving about 20 (2D) or 50 (3D) neighbours per particle. Times the
 * cell list plus neighbour list on the particles in random order and after sorting them by
 * cell (median of several runs), and the brute-force search (in full for small sets, else
 * estimated from a sample of query particles). Writes a table to out. */
ry_status ry_bench_neighbors(FILE *out, int dim, const size_t *ns, int count, ry_error *err);

#endif
