/* Pair cache shared by the implicit SPH schemes: the pairs of the CSR neighbour list within
 * the kernel's support (0 < r^2 < radius^2; the Verlet skin's pairs beyond it are left out),
 * with the kernel value and its gradient grad_i W_ij, computed once per step and read by every
 * later pass. Row i holds them from the list's offset[i] to end[i], in the list's order, with
 * the neighbour j[q]: the passes skip only the pairs whose terms were exact zeros. */
#ifndef RYUSHI_SPH_PAIRS_H
#define RYUSHI_SPH_PAIRS_H

#include "ryushi/sim.h"

/* The cache keeps what the separation alone cannot give back cheaply: per list entry the
 * kernel value W (w) and its gradient grad_i W_ij (g, 3 per entry, zeros beyond the dimension),
 * 36 bytes with the neighbour instead of 68 with r^2 and x_ij. Those two a pass takes from the
 * positions, which do not change while the cache serves (ry_pair_separation: the same bits as the
 * fill's). */
typedef struct ry_pair_cache {
    double *w;   /* W_ij per list entry */
    double *g;   /* grad_i W_ij, 3 per list entry */
    uint32_t *j; /* the neighbour of each entry */
    size_t *end; /* per particle: the end of its row */
    size_t cap, cap_n;
    const uint8_t *cut; /* set by the caller, or NULL: entries of the neighbour list to leave
                           out (MPS: the pairs across a thin wall) */
    /* set by the caller, or NULL: the rows of the kinds k with partner_rows[k] keep only the
     * pairs with a neighbour of a kind in partners (IISPH: a wall's row, its mobile
     * neighbours; the wall-wall pairs, most of a thick wall's, are read by no pass) */
    const int *partner_rows, *partners;
} ry_pair_cache;

/* x_ij = x_i - x_j into dx (zeros beyond the dimension) and r^2 of the pair (i, j): the values
 * the fill computed the entry from, bit for bit, while the positions are those of the fill. */
static inline double ry_pair_separation(const ry_sim *sim, size_t i, uint32_t j, double dx[3]) {
    return ry_sim_separation(sim, j, i, dx);
}

/* Fills the cache for the rows of the particles with need[kind] set (other rows are empty). */
ry_status ry_pair_cache_fill(ry_pair_cache *pc, const ry_sim *sim, const int need[RY_KIND_COUNT],
                             ry_error *err);
void ry_pair_cache_free(ry_pair_cache *pc);

/* Number density of a full lattice of spacing dx: sum over lattice points of W(|x|), the
 * value sum_j W_ij of a particle inside a uniform fluid at the initial spacing. */
double ry_lattice_number_density(const ry_kernel *k, int dim, double dx);

/* A viscous term applied to the shear field v = (y^2/2, 0(, 0)), whose Laplacian is
 * (1, 0(, 0)), at a particle of the full lattice of spacing dx (the x component; particle
 * volume vol, F = (dW/dr)/r): the form of Morris et al. (1997),
 * 2 sum_j V F_j r_j^2 / (r_j^2 + eta2) (v_i - v_j), gives -sum_j V F_j r_j^2 y_j^2 / (r_j^2 +
 * eta2); the projected form of seed 004 eq. 5, 2 (d + 2) sum_j V F_j ((v_i - v_j) . x_ij) x_ij /
 * (r_j^2 + eta2), gives -(d + 2) sum_j V F_j x_j^2 y_j^2 / (r_j^2 + eta2). The continuum value
 * is 1; the lattice's is what scheme.viscosity_correction: lattice divides the viscosity by. */
double ry_lattice_viscous_factor(const ry_kernel *k, int dim, double dx, double vol, double eta2,
                                 int projected);

/* Hydrostatic pressure of every fluid particle, p = rho0 |g| (top - z) along the upward
 * direction -g/|g|, the free surface half a spacing above the highest fluid particle; p is 0
 * for other kinds and everywhere without gravity. p has ps.n entries. */
void ry_hydrostatic_pressure(const ry_sim *sim, double *p);

#endif
