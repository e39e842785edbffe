/* Conjugate gradients preconditioned by hypre's BoomerAMG (linalg/amg.h). The settings follow
 * hypre's advice for Poisson-like problems, with the choices measured on the MPS dam break
 * (docs/reference/mps.md, "Linear solver"): HMIS coarsening (De Sterck, Yang & Heys 2006) with
 * one level of aggressive coarsening and multipass interpolation there, extended+i
 * interpolation below (De Sterck et al. 2008) truncated to 4 entries a row, a strength threshold
 * of 0.5 (the particles' wide stencils), and one Gauss-Seidel sweep forward on the way down and
 * backward on the way up, so that the V-cycle is symmetric, as CG needs. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <HYPRE.h>
#include <HYPRE_parcsr_ls.h>
#include <mpi.h>

#include "linalg/amg.h"
#include "ryushi/clock.h"

const char *const ry_precond_names[] = {"jacobi", "boomeramg", NULL};

static int hypre_ready;

static void hypre_stop(void) {
    HYPRE_Finalize();
    int done = 0;
    MPI_Finalized(&done);
    if (!done) MPI_Finalize();
}

/* MPI (where the program has not initialised it) and hypre, once. */
static ry_status hypre_start(ry_error *err) {
    if (hypre_ready) return RY_OK;
    int on = 0;
    MPI_Initialized(&on);
    if (!on) {
        int provided = 0;
        RY_CHECK(err, MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided) == MPI_SUCCESS,
                 RY_ERR_INTERNAL, "BoomerAMG: MPI could not be initialised");
        atexit(hypre_stop);
    }
    HYPRE_Init();
    hypre_ready = 1;
    return RY_OK;
}

static void drop_solve(ry_amg *s) {
    if (s->solver) HYPRE_ParCSRPCGDestroy((HYPRE_Solver)s->solver);
    if (s->ij && s->ij != s->ij_setup) HYPRE_IJMatrixDestroy((HYPRE_IJMatrix)s->ij);
    if (s->bv) HYPRE_IJVectorDestroy((HYPRE_IJVector)s->bv);
    if (s->xv) HYPRE_IJVectorDestroy((HYPRE_IJVector)s->xv);
    s->solver = s->ij = s->bv = s->xv = NULL;
}

/* The hierarchy dropped: the next solve builds a new one. */
static void invalidate(ry_amg *s) {
    if (s->precond) HYPRE_BoomerAMGDestroy((HYPRE_Solver)s->precond);
    if (s->ij_setup && s->ij_setup != s->ij) HYPRE_IJMatrixDestroy((HYPRE_IJMatrix)s->ij_setup);
    s->precond = s->ij_setup = NULL;
    s->nids = 0;
}

void ry_amg_free(ry_amg *s) {
    if (!s) return;
    drop_solve(s);
    invalidate(s);
    free(s->ids);
    free(s->key);
    free(s->ncols);
    free(s->rows);
    free(s->cols);
    free(s->map);
    free(s->vals);
    free(s->vec);
    s->ids = s->key = NULL;
    s->ncols = s->rows = s->cols = s->map = NULL;
    s->vals = s->vec = NULL;
    s->cap_ids = s->cap_n = s->cap_nz = 0;
}

static int grow(void **p, size_t want, size_t size) {
    void *q = realloc(*p, want * size);
    if (!q) return 0;
    *p = q;
    return 1;
}

static ry_status reserve(ry_amg *s, size_t n, size_t nz, ry_error *err) {
    RY_CHECK(err, n < (size_t)INT32_MAX && nz < (size_t)INT32_MAX, RY_ERR_RANGE,
             "BoomerAMG: %zu rows and %zu entries exceed hypre's 32-bit indices", n, nz);
    if (n > s->cap_n) {
        const size_t c = n + n / 8 + 16;
        const int ok =
            grow((void **)&s->ncols, c, sizeof(int)) && grow((void **)&s->rows, c, sizeof(int)) &&
            grow((void **)&s->map, c, sizeof(int)) && grow((void **)&s->vec, c, sizeof(double)) &&
            grow((void **)&s->key, c, sizeof(int64_t));
        RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (BoomerAMG: %zu rows)", n);
        s->cap_n = c;
    }
    if (nz > s->cap_nz) {
        const size_t c = nz + nz / 8 + 16;
        const int ok =
            grow((void **)&s->cols, c, sizeof(int)) && grow((void **)&s->vals, c, sizeof(double));
        RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (BoomerAMG: %zu entries)", nz);
        s->cap_nz = c;
    }
    return RY_OK;
}

static HYPRE_IJVector vector(int n) {
    HYPRE_IJVector v;
    HYPRE_IJVectorCreate(MPI_COMM_SELF, 0, n - 1, &v);
    HYPRE_IJVectorSetObjectType(v, HYPRE_PARCSR);
    HYPRE_IJVectorInitialize(v);
    HYPRE_IJVectorAssemble(v);
    return v;
}

/* The matrix of this solve in hypre's form, over the slots (identity rows where no unknown
 * lies) or, where the unknowns are fewer than half the slots, over the unknowns; the rows'
 * particle ids (*keyed: 0 without slots); and the vectors. */
static ry_status assemble(ry_amg *s, const ry_csr *a, const ry_amg_slots *given, int *nrows,
                          int *keyed, ry_error *err) {
    const size_t nu = a->n;
    const ry_amg_slots *slots = given && 2 * nu >= given->n ? given : NULL;
    const size_t ns = slots ? slots->n : nu, nz = a->row[nu];
    RY_TRY(reserve(s, ns, nz + ns, err));
    const int n = (int)ns;
    for (int r = 0; r < n; ++r) {
        s->rows[r] = r;
        s->map[r] = -1;
    }
    for (size_t k = 0; k < nu; ++k) s->map[slots ? slots->slot_of[k] : (int32_t)k] = (int)k;
    if (slots)
        memcpy(s->key, slots->id, ns * sizeof *s->key);
    else if (given)
        for (size_t k = 0; k < nu; ++k) s->key[k] = given->id[given->slot_of[k]];
    *keyed = given != NULL;
    /* rows in the slots' order, each unknown's entries with its neighbours' slots */
    size_t p = 0;
    for (int r = 0; r < n; ++r) {
        const int k = s->map[r];
        if (k < 0) {
            s->ncols[r] = 1;
            s->cols[p] = r;
            s->vals[p++] = 1.0;
            continue;
        }
        s->ncols[r] = (int)(a->row[k + 1] - a->row[k]);
        for (size_t q = a->row[k]; q < a->row[k + 1]; ++q) {
            s->cols[p] = slots ? slots->slot_of[a->col[q]] : (int)a->col[q];
            s->vals[p++] = a->val[q];
        }
    }
    HYPRE_IJMatrix ij;
    HYPRE_IJMatrixCreate(MPI_COMM_SELF, 0, n - 1, 0, n - 1, &ij);
    s->ij = ij;
    HYPRE_IJMatrixSetObjectType(ij, HYPRE_PARCSR);
    HYPRE_IJMatrixSetRowSizes(ij, s->ncols);
    HYPRE_IJMatrixInitialize(ij);
    HYPRE_IJMatrixSetValues(ij, n, s->ncols, s->rows, s->cols, s->vals);
    HYPRE_IJMatrixAssemble(ij);
    s->bv = vector(n);
    s->xv = vector(n);
    *nrows = n;
    return RY_OK;
}

/* A hierarchy already built: PCG's set-up leaves it as it is. */
static HYPRE_Int keep_hierarchy(HYPRE_Solver sv, HYPRE_ParCSRMatrix a, HYPRE_ParVector b,
                                HYPRE_ParVector x) {
    (void)sv;
    (void)a;
    (void)b;
    (void)x;
    return 0;
}

/* The rows hold the same particles as when the hierarchy was built. */
static int same_rows(const ry_amg *s, int keyed, int n) {
    return keyed && s->nids == (size_t)n && !memcmp(s->ids, s->key, (size_t)n * sizeof *s->key);
}

/* A new hierarchy from the current matrix. */
static ry_status build(ry_amg *s, int keyed, int n, ry_error *err) {
    invalidate(s);
    HYPRE_Solver amg;
    HYPRE_BoomerAMGCreate(&amg);
    s->precond = amg;
    HYPRE_BoomerAMGSetPrintLevel(amg, 0);
    HYPRE_BoomerAMGSetCoarsenType(amg, 10);
    HYPRE_BoomerAMGSetAggNumLevels(amg, 1);
    HYPRE_BoomerAMGSetInterpType(amg, 6);
    HYPRE_BoomerAMGSetPMaxElmts(amg, 4);
    HYPRE_BoomerAMGSetStrongThreshold(amg, 0.5);
    HYPRE_BoomerAMGSetCycleRelaxType(amg, 3, 1); /* forward hybrid Gauss-Seidel down */
    HYPRE_BoomerAMGSetCycleRelaxType(amg, 4, 2); /* backward up */
    HYPRE_BoomerAMGSetCycleRelaxType(amg, 9, 3); /* Gaussian elimination on the coarsest */
    HYPRE_BoomerAMGSetNumSweeps(amg, 1);
    HYPRE_BoomerAMGSetMaxIter(amg, 1);
    HYPRE_BoomerAMGSetTol(amg, 0.0);
    HYPRE_ParCSRMatrix pa;
    HYPRE_ParVector pb, px;
    HYPRE_IJMatrixGetObject((HYPRE_IJMatrix)s->ij, (void **)&pa);
    HYPRE_IJVectorGetObject((HYPRE_IJVector)s->bv, (void **)&pb);
    HYPRE_IJVectorGetObject((HYPRE_IJVector)s->xv, (void **)&px);
    HYPRE_ClearAllErrors();
    HYPRE_BoomerAMGSetup(amg, pa, pb, px);
    RY_CHECK(err, HYPRE_GetError() == 0, RY_ERR_UNSTABLE,
             "BoomerAMG: the set-up failed (hypre error %d)", HYPRE_GetError());
    s->ij_setup = s->ij;
    if (keyed) {
        if ((size_t)n > s->cap_ids) {
            RY_CHECK(err, grow((void **)&s->ids, (size_t)n, sizeof *s->ids), RY_ERR_NOMEM,
                     "out of memory (BoomerAMG: %d rows)", n);
            s->cap_ids = (size_t)n;
        }
        memcpy(s->ids, s->key, (size_t)n * sizeof *s->ids);
        s->nids = (size_t)n;
    }
    s->age = 0;
    s->stale = 0;
    s->setups++;
    return RY_OK;
}

/* One system: b and x into hypre's vectors (over the slots), the iterations, x back. */
static ry_status solve_one(ry_amg *s, int n, const double *b, double *x, double tol, int *iters,
                           double *resid, ry_error *err) {
    HYPRE_ParCSRMatrix pa;
    HYPRE_ParVector pb, px;
    HYPRE_IJMatrixGetObject((HYPRE_IJMatrix)s->ij, (void **)&pa);
    HYPRE_IJVectorGetObject((HYPRE_IJVector)s->bv, (void **)&pb);
    HYPRE_IJVectorGetObject((HYPRE_IJVector)s->xv, (void **)&px);
    double bb = 0;
    for (int r = 0; r < n; ++r) {
        const int k = s->map[r];
        s->vec[r] = k >= 0 ? b[k] : 0.0;
        bb += s->vec[r] * s->vec[r];
    }
    if (bb == 0) { /* (the Jacobi solver's answer to a zero right-hand side) */
        for (int r = 0; r < n; ++r)
            if (s->map[r] >= 0) x[s->map[r]] = 0;
        return RY_OK;
    }
    HYPRE_IJVectorSetValues((HYPRE_IJVector)s->bv, n, s->rows, s->vec);
    for (int r = 0; r < n; ++r) s->vec[r] = s->map[r] >= 0 ? x[s->map[r]] : 0.0;
    HYPRE_IJVectorSetValues((HYPRE_IJVector)s->xv, n, s->rows, s->vec);
    HYPRE_ClearAllErrors();
    HYPRE_ParCSRPCGSolve((HYPRE_Solver)s->solver, pa, pb, px);
    HYPRE_Int it = 0;
    HYPRE_Real r = 0;
    HYPRE_PCGGetNumIterations((HYPRE_Solver)s->solver, &it);
    HYPRE_PCGGetFinalRelativeResidualNorm((HYPRE_Solver)s->solver, &r);
    HYPRE_IJVectorGetValues((HYPRE_IJVector)s->xv, n, s->rows, s->vec);
    for (int q = 0; q < n; ++q)
        if (s->map[q] >= 0) x[s->map[q]] = s->vec[q];
    *iters = (int)it;
    *resid = (double)r;
    RY_CHECK(err, r <= tol, RY_ERR_UNSTABLE,
             "BoomerAMG-preconditioned CG did not converge: relative residual %.3g after %d "
             "iterations (tolerance %.3g, %d rows)",
             (double)r, (int)it, tol, n);
    return RY_OK;
}

ry_status ry_amg_pcg(ry_amg *s, const ry_csr *a, const ry_amg_slots *slots, int m,
                     const double *const b[], double *const x[], double tol, int max_iter,
                     int iters[], double resid[], ry_error *err) {
    RY_CHECK(err, m >= 1 && m <= RY_CSR_MAX_RHS, RY_ERR_INTERNAL,
             "BoomerAMG: %d right-hand sides (1 to %d)", m, RY_CSR_MAX_RHS);
    for (int k = 0; k < m; ++k) {
        iters[k] = 0;
        resid[k] = 0;
    }
    if (a->n == 0) return RY_OK;
    RY_TRY(hypre_start(err));
    const double t0 = ry_wall_time();
    drop_solve(s);
    int n = 0, keyed = 0;
    RY_TRY(assemble(s, a, slots, &n, &keyed, err));
    double t1 = ry_wall_time();
    s->solve_s += t1 - t0;
    const int rebuild = !s->precond || !same_rows(s, keyed, n) ||
                        s->age >= (s->reuse > 0 ? s->reuse : 1) || s->stale;
    if (rebuild) {
        const ry_status st = build(s, keyed, n, err);
        const double t2 = ry_wall_time();
        s->setup_s += t2 - t1;
        t1 = t2;
        if (st != RY_OK) return st;
    }
    HYPRE_Solver pcg;
    HYPRE_ParCSRPCGCreate(MPI_COMM_SELF, &pcg);
    s->solver = pcg;
    HYPRE_PCGSetTol(pcg, tol);
    HYPRE_PCGSetAbsoluteTol(pcg, 0.0);
    HYPRE_PCGSetMaxIter(pcg, max_iter);
    HYPRE_PCGSetTwoNorm(pcg, 1);
    HYPRE_PCGSetPrintLevel(pcg, 0);
    HYPRE_PCGSetLogging(pcg, 1);
    HYPRE_PCGSetPrecond(pcg, (HYPRE_PtrToSolverFcn)HYPRE_BoomerAMGSolve,
                        (HYPRE_PtrToSolverFcn)keep_hierarchy, (HYPRE_Solver)s->precond);
    HYPRE_ParCSRMatrix pa;
    HYPRE_ParVector pb, px;
    HYPRE_IJMatrixGetObject((HYPRE_IJMatrix)s->ij, (void **)&pa);
    HYPRE_IJVectorGetObject((HYPRE_IJVector)s->bv, (void **)&pb);
    HYPRE_IJVectorGetObject((HYPRE_IJVector)s->xv, (void **)&px);
    HYPRE_ParCSRPCGSetup(pcg, pa, pb, px);
    ry_status st = RY_OK;
    int most = 0;
    for (int k = 0; k < m && st == RY_OK; ++k) {
        st = solve_one(s, n, b[k], x[k], tol, &iters[k], &resid[k], err);
        if (iters[k] > most) most = iters[k];
    }
    if (s->age == 0) s->first_iters = most;
    s->age++;
    if (most > 2 * s->first_iters + 2) s->stale = 1;
    s->solve_s += ry_wall_time() - t1;
    return st;
}
