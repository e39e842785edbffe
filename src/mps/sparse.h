/* A symmetric sparse matrix in CSR form and the Jacobi-preconditioned conjugate-gradient
 * solver of the MPS scheme (pressure Poisson equation, implicit viscosity). */
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

/* Makes room for n rows and nz entries (keeps nothing). */
ry_status ry_csr_reserve(ry_csr *a, size_t n, size_t nz, ry_error *err);
void ry_csr_free(ry_csr *a);

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
    void (*sync)(void *ctx, double *v);
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

#endif
