/* Shared pieces of the neighbour search: the pair distance used by both the cell list and the
 * brute-force reference (the same floating-point operations in the same order, so both agree
 * exactly on pairs at the cut-off distance) and the growth of a neighbour list. */
#ifndef RYUSHI_NEIGHBOR_INTERNAL_H
#define RYUSHI_NEIGHBOR_INTERNAL_H

#include "ryushi/neighbor.h"

/* Box geometry in the form the inner loops use. */
typedef struct ry_nb_geom {
    int dim;
    int periodic[3];
    double len[3];  /* hi - lo in periodic directions */
    double half[3]; /* 0.5 * len */
} ry_nb_geom;

static inline void ry_nb_geom_init(ry_nb_geom *g, const ry_box *box) {
    g->dim = box->dim;
    for (int d = 0; d < 3; ++d) {
        g->periodic[d] = d < box->dim && box->periodic[d];
        g->len[d] = g->periodic[d] ? box->hi[d] - box->lo[d] : 0.0;
        g->half[d] = 0.5 * g->len[d];
    }
}

/* Squared minimum-image distance between particles i and j. The correction is written
 * without branches, dx - len * s with s in {-1, 0, 1}: the same value as ry_box_min_image (len
 * times +-1 or 0 is exact; len is 0 in open directions). Call with a literal dim so that the
 * loop unrolls. */
static inline double ry_nb_r2(const ry_nb_geom *g, int dim, const double *const x[3], size_t i,
                              size_t j) {
    double r2 = 0.0;
    for (int d = 0; d < dim; ++d) {
        double dx = x[d][i] - x[d][j];
        dx -= g->len[d] * (double)((dx > g->half[d]) - (dx < -g->half[d]));
        r2 += dx * dx;
    }
    return r2;
}

/* ry_nb_r2 where no direction is periodic: the same value without the correction (a no-op
 * there, but compares, a conversion and a multiplication per axis in the search's inner loop). */
static inline double ry_nb_r2_open(int dim, const double *const x[3], size_t i, size_t j) {
    double r2 = 0.0;
    for (int d = 0; d < dim; ++d) {
        const double dx = x[d][i] - x[d][j];
        r2 += dx * dx;
    }
    return r2;
}

/* Checks dim, n (indices must fit 32 bits) and radius (finite, > 0). */
ry_status ry_nb_check_args(const ry_box *box, double radius, size_t n, const double *const x[3],
                           ry_error *err);
/* Makes room for n + 1 offsets. */
ry_status ry_nb_reserve_offsets(ry_nlist *nl, size_t n, ry_error *err);
/* Makes room for m neighbour entries. */
ry_status ry_nb_reserve_j(ry_nlist *nl, size_t m, ry_error *err);
/* Turns counts stored in offset[1..n] into offsets (offset[0] = 0); returns the total. */
size_t ry_nb_prefix_sum(size_t *offset, size_t n, size_t *max_row);

/* Brute-force neighbour lists of the k particles queries[0..k-1] (of all n when queries is
 * NULL, then k = n): row q of nl holds the neighbours of particle queries[q]. */
ry_status ry_nb_brute_subset(ry_nlist *nl, const ry_box *box, double radius, size_t n,
                             const double *const x[3], const uint32_t *queries, size_t k,
                             ry_error *err);

#endif
