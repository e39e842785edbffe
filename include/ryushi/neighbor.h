/* ryushi — neighbour search: a cell list built by counting sort (the seed's bucket sort) and a
 * brute-force O(N^2) reference used as a test oracle.
 *
 * Both produce the same CSR neighbour list: for particle i, its neighbours are
 * nl->j[nl->offset[i] .. nl->offset[i+1]-1], every j != i with |x_i - x_j| < radius (distance
 * by minimum image in periodic directions), sorted by increasing j. */
#ifndef RYUSHI_NEIGHBOR_H
#define RYUSHI_NEIGHBOR_H

#include <math.h>
#include <stddef.h>
#include <stdint.h>

#include "ryushi/status.h"

/* The domain: particles are expected inside [lo, hi) in periodic directions; in the others
 * they may lie outside (they are clamped into the edge cells). */
typedef struct ry_box {
    int dim;
    double lo[3], hi[3];
    int periodic[3];
    /* Symmetry planes (domain.symmetry): bit 1, the face at lo[d]; bit 2, the one at hi[d]. */
    int symmetry[3];
} ry_box;

/* The parts of the whole problem a box with symmetry planes holds one of: 2^planes. */
static inline int ry_box_mirrors(const ry_box *b) {
    int m = 1;
    for (int d = 0; d < 3; ++d)
        if (b->symmetry[d]) m *= 2;
    return m;
}

/* Minimum-image correction of a separation vector dx (x_i - x_j) in periodic directions. */
static inline void ry_box_min_image(const ry_box *b, double *dx) {
    for (int d = 0; d < b->dim; ++d) {
        if (b->periodic[d]) {
            double L = b->hi[d] - b->lo[d];
            if (dx[d] > 0.5 * L)
                dx[d] -= L;
            else if (dx[d] < -0.5 * L)
                dx[d] += L;
        }
    }
}

/* The dimension (2 or 3) of a box with no periodic side, else 0: there separations need no
 * minimum image, and their parts can be written out (kept in registers) instead of looped
 * over a dimension read at run time. */
static inline int ry_box_plain(const ry_box *b) {
    if (b->periodic[0] || b->periodic[1] || b->periodic[2]) return 0;
    return b->dim == 2 || b->dim == 3 ? b->dim : 0;
}

typedef struct ry_cell_list {
    int dim;
    double lo[3];      /* origin of cell (0,0,0) */
    double cell[3];    /* cell edge per direction (>= radius) */
    int ncell[3];      /* cells per direction (1 in unused directions) */
    size_t ncells;     /* product of ncell */
    size_t n;          /* particles binned */
    size_t *start;     /* ncells + 1 entries: particles of cell c are order[start[c]..start[c+1]) */
    uint32_t *order;   /* particle indices sorted by cell (stable: by index within a cell) */
    uint32_t *cell_of; /* cell index of each particle */
    size_t cap_cells, cap_n;
} ry_cell_list;

typedef struct ry_nlist {
    size_t n;       /* particles */
    size_t *offset; /* n + 1 entries */
    uint32_t *j;    /* offset[n] entries */
    size_t max_row; /* longest row */
    size_t cap_n, cap_j;
} ry_nlist;

/* Bins n particles (coordinates x[0..dim-1], each an array of n) into cells of edge >= radius
 * covering the box (the bounding box of the particles in non-periodic directions). Reuses the
 * memory of cl between calls; zero-initialise cl before the first call. O(n) counting sort. */
ry_status ry_cells_build(ry_cell_list *cl, const ry_box *box, double radius, size_t n,
                         const double *const x[3], ry_error *err);
/* After the particles were reordered by cl->order (ry_particles_permute): the cell list of
 * the reordered particles, the same as a new ry_cells_build from their positions (particles
 * of each cell consecutive, in order), without binning them again. */
void ry_cells_permuted(ry_cell_list *cl);
void ry_cells_free(ry_cell_list *cl);
/* Orders the particles of each cell by their x coordinate (ties by index) in cl->order, so
 * that after a reordering along cl->order every row of cells (consecutive cells along x) holds
 * its particles sorted by x. */
void ry_cells_sort_x(ry_cell_list *cl, const double *x);
/* The distinct cells neighbouring cell c (c included; per[d]: direction d wraps), in
 * increasing order; returns how many (at most 27). */
int ry_cells_neighbours(const ry_cell_list *cl, const int per[3], size_t c, size_t out[27]);

/* Neighbour list from a built cell list (OpenMP-parallel, deterministic). */
ry_status ry_nlist_build_cells(ry_nlist *nl, const ry_cell_list *cl, const ry_box *box,
                               double radius, size_t n, const double *const x[3], ry_error *err);
/* The same list by testing every pair: O(n^2), for tests and benchmarks only. */
ry_status ry_nlist_build_brute(ry_nlist *nl, const ry_box *box, double radius, size_t n,
                               const double *const x[3], ry_error *err);
void ry_nlist_free(ry_nlist *nl);

/* Memory in bytes held per particle by the cell list and the neighbour list (for reports). */
double ry_cells_bytes_per_particle(const ry_cell_list *cl);
double ry_nlist_bytes_per_particle(const ry_nlist *nl);

#endif
