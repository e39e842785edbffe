/* Conjugate gradients preconditioned by algebraic multigrid: hypre's BoomerAMG (Henson & Yang
 * 2002, Appl. Numer. Math. 41: 155) as the preconditioner of hypre's PCG, for the symmetric
 * positive definite systems of the implicit schemes (ry_csr, linalg/sparse.h). Its iterations
 * barely grow with the number of unknowns, where those of the Jacobi preconditioner grow with the
 * number of particles across the domain. One process: hypre runs on MPI_COMM_SELF (MPI is
 * initialised on first use where the program has not done so, and finalised at exit). hypre
 * runs on one thread, so the results do not depend on the thread count.
 *
 * The multigrid hierarchy (coarse levels and interpolation) may serve several solves while the
 * particles keep their places in memory: the system is then posed over slots (one per particle,
 * the rows of the particles without an unknown being identity rows), so that a particle whose
 * role changes between solves keeps its row. Where the unknowns are fewer than half the slots
 * (an implicit viscosity for one liquid of several), the system keeps the unknowns' rows alone,
 * and a hierarchy serves while the same particles are the unknowns in the same order. The
 * finest level always smooths with the current matrix, and CG iterates on it, so the stop
 * criterion is unchanged; only the preconditioner ages. */
#ifndef RYUSHI_LINALG_AMG_H
#define RYUSHI_LINALG_AMG_H

#include "linalg/sparse.h"

/* The preconditioners of the implicit schemes' conjugate gradients (case key
 * scheme.solver.preconditioner). */
typedef enum ry_precond { RY_PRECOND_JACOBI = 0, RY_PRECOND_BOOMERAMG = 1 } ry_precond;
extern const char *const ry_precond_names[]; /* "jacobi", "boomeramg", NULL */

/* Where the unknowns of a system lie among n slots (particles): slot_of[k] for unknown k, and
 * id[s] the identity of slot s (a particle's stable id): a hierarchy is reused only while the
 * ids are the same, slot by slot. */
typedef struct ry_amg_slots {
    size_t n;
    const int32_t *slot_of;
    const int64_t *id;
} ry_amg_slots;

/* The solver's state between solves (its buffers and hypre's objects); zero-initialised, then
 * reuse set, before first use; released by ry_amg_free. */
typedef struct ry_amg {
    long reuse;                  /* solves one hierarchy may serve (1: built for every solve) */
    void *ij, *bv, *xv, *solver; /* hypre's objects of the current solve */
    void *precond, *ij_setup;    /* the hierarchy and the matrix it was built from */
    long age;                    /* solves served by the hierarchy */
    int first_iters;             /* iterations of its first solve */
    int stale;                   /* the last solve took too many iterations: rebuild */
    int64_t *ids;                /* the rows' particle ids when it was built */
    size_t nids, cap_ids;
    int64_t *key;                   /* the rows' particle ids now */
    int *ncols, *rows, *cols, *map; /* the matrix in hypre's integer types; slot of each row */
    double *vals, *vec;
    size_t cap_n, cap_nz;
    long setups;    /* hierarchies built */
    double setup_s; /* seconds in building hierarchies, all solves */
    double solve_s; /* seconds in assembling and iterating, all solves */
} ry_amg;

/* Solves A x_k = b_k (1 <= m <= RY_CSR_MAX_RHS) by CG preconditioned with one V-cycle of
 * BoomerAMG per iteration, each from its initial x_k until |b_k - A x_k| <= tol |b_k| (2-norms)
 * or max_iter iterations; iters and resid as ry_csr_pcg. With slots (NULL: the unknowns alone,
 * a hierarchy for every solve), the system is posed over them (above) and a hierarchy serves
 * up to s->reuse solves: it is rebuilt when the rows' particles change, or after a solve that
 * took more than twice the iterations of its first solve plus 2. RY_ERR_UNSTABLE where a system
 * does not converge. */
ry_status ry_amg_pcg(ry_amg *s, const ry_csr *a, const ry_amg_slots *slots, int m,
                     const double *const b[], double *const x[], double tol, int max_iter,
                     int iters[], double resid[], ry_error *err);
void ry_amg_free(ry_amg *s);

#endif
