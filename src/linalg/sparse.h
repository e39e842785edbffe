/* A symmetric sparse matrix in CSR form, its assembly from particle pairs, and the
 * Jacobi-preconditioned conjugate-gradient solver (with deflation) of the implicit schemes: the
 * pressure Poisson equation of MPS, the implicit viscosity of MPS and IISPH. */
#ifndef RYUSHI_MPS_SPARSE_H
#define RYUSHI_MPS_SPARSE_H

#include <stddef.h>
#include <stdint.h>

#include "ryushi/status.h"

typedef struct ry_csr {
    size_t n;      /* rows */
    size_t *row;   /* n + 1 entries */
    uint32_t *col; /* row[n] entries */
    double *val;   /* row[n] entries */
    double *diag;  /* n entries (also stored in the rows) */
    size_t cap_n, cap_nz;
    double *work; /* 4 n: residual, preconditioned residual, direction, A p */
    size_t cap_work;
} ry_csr;

/* Makes room for n rows and nz entries (keeps the row offsets when n is unchanged). */
ry_status ry_csr_reserve(ry_csr *a, size_t n, size_t nz, ry_error *err);
void ry_csr_free(ry_csr *a);

/* Assembly of a matrix of the graph-Laplacian form of the implicit schemes, one row per
 * unknown k, from the pairs (k, j) of its particle with coefficients a_kj >= 0:
 *   A_kk = d_k + sum_j a_kj (every pair, the unknown neighbours and the known ones),
 *   A_kl = -a_kj where neighbour j is the unknown l,
 * symmetric where a_kj = a_jk. In three steps, the rows in parallel:
 *   1. ry_csr_reserve(A, n, 0), and the length of row k (1 + its unknown neighbours) into
 *      A->row[k + 1];
 *   2. ry_csr_rows_from_lengths(A): the offsets and room for the entries;
 *   3. per row: ry_csr_row_begin, ry_csr_row_pair for each pair in the order of step 1,
 *      ry_csr_row_end. The diagonal is stored first in the row and in A->diag. */
ry_status ry_csr_rows_from_lengths(ry_csr *a, ry_error *err);

typedef struct ry_csr_row {
    ry_csr *a;
    size_t k, pdiag, p;
    double diag;
} ry_csr_row;

static inline ry_csr_row ry_csr_row_begin(ry_csr *a, size_t k, double d_k) {
    const ry_csr_row r = {a, k, a->row[k], a->row[k] + 1, d_k};
    return r;
}

/* A pair of coefficient c; col the neighbour's unknown, or negative for a known neighbour. */
static inline void ry_csr_row_pair(ry_csr_row *r, double c, int64_t col) {
    r->diag += c;
    if (col >= 0) {
        r->a->col[r->p] = (uint32_t)col;
        r->a->val[r->p++] = -c;
    }
}

static inline void ry_csr_row_end(const ry_csr_row *r) {
    r->a->col[r->pdiag] = (uint32_t)r->k;
    r->a->val[r->pdiag] = r->diag;
    r->a->diag[r->k] = r->diag;
}

/* The most right-hand sides solved together (ry_csr_pcg_multi). */
#define RY_CSR_MAX_RHS 3

/* y = A x (OpenMP over rows). */
void ry_csr_mul(const ry_csr *a, const double *x, double *y);

/* A system shared by several processes (a distributed run): each holds rows for its own
 * unknowns (owned[k] non-zero) and copies of its neighbours' (halo) unknowns, whose rows it
 * does not use. sync fills a vector's halo entries from their owners; sum adds a number over
 * the processes. */
typedef struct ry_csr_dist {
    const uint8_t *owned;
    void (*sync)(void *ctx, double *v, int k); /* k: the system (ry_csr_pcg_multi's index) */
    double (*sum)(void *ctx, double v);
    void *ctx;
} ry_csr_dist;

/* Unknowns numbered over a particle set (unk[i] >= 0: the unknown of particle i), for a
 * system distributed with the particles: unknown k is owned where its particle is not a halo
 * copy, and a vector's halo entries come from their owners through a per-particle array. The
 * caller keeps own (room for every unknown) and tmp (room for every particle). */
struct ry_sim;
typedef struct ry_particle_unknowns {
    const struct ry_sim *sim;
    const int32_t *unk;
    uint8_t *own;
    double *tmp;
    /* Per system: the axes whose mirror negates the unknowns (symmetry planes; 0 for a
     * pressure, 1 << d for a velocity's component d). */
    unsigned odd[RY_CSR_MAX_RHS];
} ry_particle_unknowns;

/* Fills own and *d for pu (which must live as long as *d is used) and returns d; NULL in a
 * serial run (sim->par NULL). */
const ry_csr_dist *ry_particle_dist(ry_particle_unknowns *pu, ry_csr_dist *d);

/* Solves A x = b for a symmetric positive definite A by conjugate gradients with the Jacobi
 * (diagonal) preconditioner, from the initial x, until |b - A x| <= tol |b| (2-norms) or
 * max_iter iterations. *iters receives the iterations, *resid the final relative residual.
 * RY_ERR_UNSTABLE when it does not converge or breaks down. With dist (NULL: one process),
 * the system is distributed: norms and dot products over all processes' owned unknowns, and
 * the direction's halo entries synchronised before each product with A. */
ry_status ry_csr_pcg(ry_csr *a, const double *b, double *x, double tol, int max_iter, int *iters,
                     double *resid, const ry_csr_dist *dist, ry_error *err);

/* The same for m systems with the one matrix (1 <= m <= RY_CSR_MAX_RHS), A x_k = b_k, each
 * with its own iterations, residual and stop: each product with A serves the directions of
 * all the systems not yet converged, so the matrix is read once per iteration instead of m
 * times. Each solution has the same bits as from ry_csr_pcg. */
ry_status ry_csr_pcg_multi(ry_csr *a, int m, const double *const b[], double *const x[], double tol,
                           int max_iter, int iters[], double resid[], const ry_csr_dist *dist,
                           ry_error *err);

/* Deflation of the conjugate gradients (Nicolaides 1987; the "DEF1" form of Tang, Nabben,
 * Vuik & Erlangga 2009, J. Sci. Comput. 39: 340): the unknowns are grouped into m aggregates,
 * Z holds their indicator vectors, and the coarse matrix E = Z^T A Z is factored once per
 * solve. Each iteration removes from A p its part in the span of A Z (P = I - A Z E^-1 Z^T),
 * so the m smoothest error components, which slow Jacobi-preconditioned CG on a large
 * Poisson problem, are solved for exactly. The caller sets m and fills agg (aggregate of each
 * unknown, 0 .. m - 1, every aggregate used) after ry_csr_deflation_reserve; the rest is
 * internal. */
typedef struct ry_csr_deflation {
    size_t m;       /* aggregates (0: no deflation) */
    uint32_t *agg;  /* aggregate of each unknown */
    size_t *start;  /* each aggregate's unknowns in rows (m + 1) */
    size_t *lo;     /* the first column of each row of E within its envelope (m + 1) */
    uint32_t *rows; /* unknowns grouped by aggregate (n) */
    uint32_t *azn;  /* entries of row i of A Z (n) */
    size_t *azo;    /* where row i of A Z starts, rows packed one after the other (n + 1) */
    uint32_t *azc;  /* their aggregates (room for A's entries) */
    double *azv;    /* their values */
    double *e;      /* E, then its Cholesky factor (lower, m x m) */
    double *c;      /* a coarse vector (m) */
    double *u;      /* per system: b - A x~ and the deflated product (2 n each) */
    int32_t *slot;  /* per thread, each aggregate's place in the row of A Z being formed (m) */
    size_t cap_n, cap_m, cap_u, cap_nz, cap_e, cap_slot;
} ry_csr_deflation;

/* Makes room for n unknowns (agg) and m aggregates. */
ry_status ry_csr_deflation_reserve(ry_csr_deflation *d, size_t n, size_t m, ry_error *err);
void ry_csr_deflation_free(ry_csr_deflation *d);

/* ry_csr_pcg_multi with deflation by d (one process; d->m == 0: none): the same stop,
 * |b_k - A x_k| <= tol |b_k|, reached in fewer iterations. Where the coarse matrix is not
 * positive definite in floating point it solves without deflation. */
ry_status ry_csr_pcg_deflated(ry_csr *a, int m, const double *const b[], double *const x[],
                              ry_csr_deflation *d, double tol, int max_iter, int iters[],
                              double resid[], ry_error *err);

#endif
