/* CSR matrix and Jacobi-preconditioned conjugate gradients (Hestenes & Stiefel 1952; the
 * preconditioned form as in Saad, Iterative Methods for Sparse Linear Systems, alg. 9.1),
 * optionally deflated on aggregates of unknowns (Nicolaides 1987; Tang et al. 2009). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <omp.h>

#include "linalg/sparse.h"
#include "ryushi/sim.h"

static int grow(void **p, size_t *cap, size_t want, size_t size) {
    if (*cap >= want) return 1;
    size_t c = want + want / 4 + 16;
    void *q = realloc(*p, c * size);
    if (!q) return 0;
    *p = q;
    *cap = c;
    return 1;
}

ry_status ry_csr_reserve(ry_csr *a, size_t n, size_t nz, ry_error *err) {
    size_t cn = a->cap_n, cn2 = a->cap_n, cz = a->cap_nz, cz2 = a->cap_nz, cw = a->cap_work;
    int ok = grow((void **)&a->row, &cn, n + 1, sizeof *a->row) &&
             grow((void **)&a->diag, &cn2, n + 1, sizeof *a->diag) &&
             grow((void **)&a->col, &cz, nz, sizeof *a->col) &&
             grow((void **)&a->val, &cz2, nz, sizeof *a->val) &&
             grow((void **)&a->work, &cw, 4 * n + 4, sizeof *a->work);
    RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (sparse matrix of %zu rows, %zu entries)", n,
             nz);
    a->cap_n = cn < cn2 ? cn : cn2;
    a->cap_nz = cz < cz2 ? cz : cz2;
    a->cap_work = cw;
    a->n = n;
    return RY_OK;
}

ry_status ry_csr_rows_from_lengths(ry_csr *a, ry_error *err) {
    a->row[0] = 0;
    for (size_t k = 0; k < a->n; ++k) a->row[k + 1] += a->row[k];
    return ry_csr_reserve(a, a->n, a->row[a->n], err);
}

void ry_csr_free(ry_csr *a) {
    free(a->row);
    free(a->col);
    free(a->val);
    free(a->diag);
    free(a->work);
    *a = (ry_csr){0};
}

/* y_k[i] = (A x_k)_i for k < m: each sum in the order of the row (the same bits as one product
 * at a time). Inlined with a literal m, so that the sums stay in registers. */
static inline void csr_row_m(const ry_csr *a, size_t i, int m, const double *const *x,
                             double *const *y) {
    double s[RY_CSR_MAX_RHS] = {0};
    for (size_t q = a->row[i]; q < a->row[i + 1]; ++q) {
        const double v = a->val[q];
        const uint32_t c = a->col[q];
        for (int k = 0; k < m; ++k) s[k] += v * x[k][c];
    }
    for (int k = 0; k < m; ++k) y[k][i] = s[k];
}

/* (threads pay from some 30,000 entries on: a few thousand rows of a 3D Laplacian) */
#define CSR_THREADED(a) ((a)->row[(a)->n] > 30000)

/* y = A x with the rows taken two at a time, their sums side by side: each sum is one chain
 * of additions in the order of its row, so two chains overlap where one would wait on the
 * latency of each addition. The same bits as row by row. */
static void csr_mul1(const ry_csr *a, const double *x, double *y) {
    const size_t n = a->n, *row = a->row;
    const uint32_t *col = a->col;
    const double *val = a->val;
#pragma omp parallel for schedule(static) if (CSR_THREADED(a))
    for (size_t h = 0; h < n / 2; ++h) {
        const size_t i = 2 * h, q0 = row[i], q1 = row[i + 1], e1 = row[i + 2];
        const size_t l0 = q1 - q0, l1 = e1 - q1, l = l0 < l1 ? l0 : l1;
        double s0 = 0, s1 = 0;
        for (size_t k = 0; k < l; ++k) {
            s0 += val[q0 + k] * x[col[q0 + k]];
            s1 += val[q1 + k] * x[col[q1 + k]];
        }
        for (size_t k = l; k < l0; ++k) s0 += val[q0 + k] * x[col[q0 + k]];
        for (size_t k = l; k < l1; ++k) s1 += val[q1 + k] * x[col[q1 + k]];
        y[i] = s0;
        y[i + 1] = s1;
    }
    if (n % 2) csr_row_m(a, n - 1, 1, &x, &y);
}

/* y_k = A x_k for k < m (2 or 3): one pass over the matrix for all of them. */
static void csr_mul2(const ry_csr *a, const double *const *x, double *const *y) {
#pragma omp parallel for schedule(static) if (CSR_THREADED(a))
    for (size_t i = 0; i < a->n; ++i) csr_row_m(a, i, 2, x, y);
}

static void csr_mul3(const ry_csr *a, const double *const *x, double *const *y) {
#pragma omp parallel for schedule(static) if (CSR_THREADED(a))
    for (size_t i = 0; i < a->n; ++i) csr_row_m(a, i, 3, x, y);
}

/* (one function per m: an OpenMP region is outlined before m could be propagated into it) */
static void csr_mul_any(const ry_csr *a, int m, const double *const *x, double *const *y) {
    if (m == 1)
        csr_mul1(a, x[0], y[0]);
    else if (m == 2)
        csr_mul2(a, x, y);
    else
        csr_mul3(a, x, y);
}

void ry_csr_mul(const ry_csr *a, const double *x, double *y) {
    csr_mul_any(a, 1, &x, &y);
}

/* Dot product in fixed blocks summed in order: the same bits for any thread count. */
enum { DOT_BLOCK = 2048 };
static double dot(const double *x, const double *y, size_t n) {
    const size_t nb = (n + DOT_BLOCK - 1) / DOT_BLOCK;
    double part[256], s = 0;
    for (size_t b0 = 0; b0 < nb; b0 += 256) {
        const size_t b1 = nb - b0 < 256 ? nb : b0 + 256;
#pragma omp parallel for schedule(static) if (b1 - b0 > 1)
        for (size_t b = b0; b < b1; ++b) {
            const size_t i1 = (b + 1) * DOT_BLOCK < n ? (b + 1) * DOT_BLOCK : n;
            double t = 0;
            for (size_t i = b * DOT_BLOCK; i < i1; ++i) t += x[i] * y[i];
            part[b - b0] = t;
        }
        for (size_t b = b0; b < b1; ++b) s += part[b - b0];
    }
    return s;
}

/* The dot product of a distributed system: over the owned unknowns, summed over processes. */
static double ddot(const ry_csr_dist *d, const double *x, const double *y, size_t n) {
    if (!d) return dot(x, y, n);
    double s = 0;
    for (size_t i = 0; i < n; ++i) s += d->owned[i] ? x[i] * y[i] : 0.0;
    return d->sum(d->ctx, s);
}

/* The state of one of the systems solved together. */
typedef struct pcg_one {
    const double *b;
    double *x, *r, *z, *p, *q;
    double *u, *w; /* deflated: b - A x~ and P A p */
    double bnorm, rz, rn;
    int iters, done;
} pcg_one;

/* Defined with the deflation below. */
static ry_status deflation_room(const ry_csr *a, ry_csr_deflation *d, ry_error *err);
static int deflation_setup(const ry_csr *a, ry_csr_deflation *d);
static void coarse_solve(const ry_csr_deflation *d, const double *v);
static void deflate(const ry_csr *a, const ry_csr_deflation *d, const double *v, double *out);

/* Conjugate gradients for m systems with one matrix, deflated by d where d is not NULL
 * (DEF1 of Tang et al.: the iterate x~ solves P A x~ = P b, and x = x~ + Z E^-1 Z^T (b - A x~)
 * at the end, whose residual is the deflated residual r, so the stop is the same). */
static ry_status pcg_core(ry_csr *a, int m, const double *const b[], double *const x[],
                          ry_csr_deflation *d, double tol, int max_iter, int iters[],
                          double resid[], const ry_csr_dist *dist, ry_error *err) {
    RY_CHECK(err, m >= 1 && m <= RY_CSR_MAX_RHS, RY_ERR_INTERNAL,
             "conjugate gradients: %d right-hand sides (1 to %d)", m, RY_CSR_MAX_RHS);
    const size_t n = a->n;
    size_t cw = a->cap_work;
    RY_CHECK(err, grow((void **)&a->work, &cw, 4 * (size_t)m * n + 4, sizeof *a->work),
             RY_ERR_NOMEM, "out of memory (conjugate gradients: %d vectors of %zu)", 4 * m, n);
    a->cap_work = cw;
    pcg_one s[RY_CSR_MAX_RHS];
    for (int k = 0; k < m; ++k) {
        double *w = a->work + 4 * (size_t)k * n;
        s[k] = (pcg_one){b[k], x[k], w, w + n, w + 2 * n, w + 3 * n, NULL, NULL, 0, 0, 0, 0, 0};
        iters[k] = 0;
        resid[k] = 0;
    }
    /* (a distributed system goes on with no local unknowns: the others' sums need this one) */
    if (n == 0 && !dist) return RY_OK;
    if (d && (d->m == 0 || dist)) d = NULL;
    if (d) {
        RY_TRY(deflation_room(a, d, err));
        if (!deflation_setup(a, d)) d = NULL; /* E not positive definite in floating point */
        for (int k = 0; d && k < m; ++k) {
            s[k].u = d->u + 2 * (size_t)k * n;
            s[k].w = s[k].u + n;
        }
    }
    const double *in[RY_CSR_MAX_RHS];
    double *out[RY_CSR_MAX_RHS];
    int na = 0;
    for (int k = 0; k < m; ++k) {
        pcg_one *o = &s[k];
        o->bnorm = sqrt(ddot(dist, o->b, o->b, n));
        if (o->bnorm == 0) {
            for (size_t i = 0; i < n; ++i) o->x[i] = 0;
            o->done = 1;
            continue;
        }
        if (dist) dist->sync(dist->ctx, o->x, k);
        in[na] = o->x;
        out[na++] = o->q;
    }
    if (na > 0) csr_mul_any(a, na, in, out);
    for (int k = 0; k < m; ++k) {
        pcg_one *o = &s[k];
        if (o->done) continue;
        double *r = o->r, *z = o->z, *p = o->p;
        const double *q = o->q, *bb = o->b;
        if (d) {
            double *u = o->u;
#pragma omp parallel for schedule(static) if (n > 4096)
            for (size_t i = 0; i < n; ++i) u[i] = bb[i] - q[i];
            coarse_solve(d, u);
            deflate(a, d, u, r);
        } else {
#pragma omp parallel for schedule(static) if (n > 4096)
            for (size_t i = 0; i < n; ++i) r[i] = bb[i] - q[i];
        }
#pragma omp parallel for schedule(static) if (n > 4096)
        for (size_t i = 0; i < n; ++i) {
            z[i] = r[i] / a->diag[i];
            p[i] = z[i];
        }
        o->rz = ddot(dist, r, z, n);
        o->rn = sqrt(ddot(dist, r, r, n));
    }
    for (;;) {
        pcg_one *act[RY_CSR_MAX_RHS];
        na = 0;
        for (int k = 0; k < m; ++k) {
            pcg_one *o = &s[k];
            if (o->done || !(o->rn > tol * o->bnorm && o->iters < max_iter)) continue;
            if (dist) dist->sync(dist->ctx, o->p, k);
            act[na] = o;
            in[na] = o->p;
            out[na++] = o->q;
        }
        if (na == 0) break;
        csr_mul_any(a, na, in, out);
        for (int k = 0; k < na; ++k) {
            pcg_one *o = act[k];
            double *xx = o->x, *r = o->r, *z = o->z, *p = o->p, *u = o->u;
            const double *q = o->q, *w = o->q;
            if (d) {
                coarse_solve(d, q);
                deflate(a, d, q, o->w);
                w = o->w;
            }
            const double pq = ddot(dist, p, w, n);
            RY_CHECK(err, pq > 0 && isfinite(pq), RY_ERR_UNSTABLE,
                     "conjugate gradients broke down after %d iterations (p.Ap = %g: the matrix "
                     "is not positive definite)",
                     o->iters, pq);
            const double alpha = o->rz / pq;
            if (d) {
#pragma omp parallel for schedule(static) if (n > 4096)
                for (size_t i = 0; i < n; ++i) u[i] -= alpha * q[i];
            }
#pragma omp parallel for schedule(static) if (n > 4096)
            for (size_t i = 0; i < n; ++i) {
                xx[i] += alpha * p[i];
                r[i] -= alpha * w[i];
                z[i] = r[i] / a->diag[i];
            }
            const double rz1 = ddot(dist, r, z, n);
            const double beta = rz1 / o->rz;
            o->rz = rz1;
#pragma omp parallel for schedule(static) if (n > 4096)
            for (size_t i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
            o->rn = sqrt(ddot(dist, r, r, n));
            ++o->iters;
        }
    }
    for (int k = 0; k < m; ++k) {
        const pcg_one *o = &s[k];
        if (o->done) continue;
        if (d) { /* x = x~ + Z E^-1 Z^T (b - A x~) */
            coarse_solve(d, o->u);
            double *xx = o->x;
#pragma omp parallel for schedule(static) if (n > 4096)
            for (size_t i = 0; i < n; ++i) xx[i] += d->c[d->agg[i]];
        }
        iters[k] = o->iters;
        resid[k] = o->rn / o->bnorm;
        RY_CHECK(err, o->rn <= tol * o->bnorm, RY_ERR_UNSTABLE,
                 "conjugate gradients did not converge in %d iterations (relative residual "
                 "%.3g, tolerance %.3g)",
                 o->iters, o->rn / o->bnorm, tol);
    }
    return RY_OK;
}

ry_status ry_csr_pcg_multi(ry_csr *a, int m, const double *const b[], double *const x[], double tol,
                           int max_iter, int iters[], double resid[], const ry_csr_dist *dist,
                           ry_error *err) {
    return pcg_core(a, m, b, x, NULL, tol, max_iter, iters, resid, dist, err);
}

ry_status ry_csr_pcg_deflated(ry_csr *a, int m, const double *const b[], double *const x[],
                              ry_csr_deflation *d, double tol, int max_iter, int iters[],
                              double resid[], ry_error *err) {
    return pcg_core(a, m, b, x, d, tol, max_iter, iters, resid, NULL, err);
}

ry_status ry_csr_pcg(ry_csr *a, const double *b, double *x, double tol, int max_iter, int *iters,
                     double *resid, const ry_csr_dist *dist, ry_error *err) {
    return ry_csr_pcg_multi(a, 1, &b, &x, tol, max_iter, iters, resid, dist, err);
}

static void particle_sync(void *ctx, double *v, int k) {
    ry_particle_unknowns *pu = ctx;
    ry_sim *sim = (ry_sim *)pu->sim;
    const size_t n = sim->ps.n;
    for (size_t i = 0; i < n; ++i) pu->tmp[i] = pu->unk[i] >= 0 ? v[pu->unk[i]] : 0.0;
    sim->par->sync(sim, pu->tmp, 1, pu->odd[k]);
    for (size_t i = 0; i < n; ++i)
        if (pu->unk[i] >= 0 && ry_sim_is_halo(sim, i)) v[pu->unk[i]] = pu->tmp[i];
}

static double particle_sum(void *ctx, double v) {
    ry_particle_unknowns *pu = ctx;
    ry_sim *sim = (ry_sim *)pu->sim;
    return sim->par->sum(sim, v);
}

const ry_csr_dist *ry_particle_dist(ry_particle_unknowns *pu, ry_csr_dist *d) {
    const ry_sim *sim = pu->sim;
    if (!sim->par) return NULL;
    for (size_t i = 0; i < sim->ps.n; ++i)
        if (pu->unk[i] >= 0) pu->own[pu->unk[i]] = !ry_sim_is_halo(sim, i);
    *d = (ry_csr_dist){pu->own, particle_sync, particle_sum, pu};
    return d;
}

ry_status ry_csr_deflation_reserve(ry_csr_deflation *d, size_t n, size_t m, ry_error *err) {
    /* every array of a kind grows together: one capacity each for n, m and u */
    size_t cn[4] = {d->cap_n, d->cap_n, d->cap_n, d->cap_n}, cm[3] = {d->cap_m, d->cap_m, d->cap_m};
    size_t cu = d->cap_u;
    int ok = grow((void **)&d->agg, &cn[0], n + 1, sizeof *d->agg) &&
             grow((void **)&d->rows, &cn[1], n + 1, sizeof *d->rows) &&
             grow((void **)&d->azn, &cn[2], n + 1, sizeof *d->azn) &&
             grow((void **)&d->azo, &cn[3], n + 1, sizeof *d->azo) &&
             grow((void **)&d->u, &cu, 2 * RY_CSR_MAX_RHS * (n + 1), sizeof *d->u) &&
             grow((void **)&d->start, &cm[0], m + 1, sizeof *d->start) &&
             grow((void **)&d->lo, &cm[1], m + 1, sizeof *d->lo) &&
             grow((void **)&d->c, &cm[2], m + 1, sizeof *d->c);
    RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (deflation: %zu unknowns, %zu aggregates)", n,
             m);
    d->cap_n = cn[0];
    d->cap_m = cm[0];
    d->cap_u = cu;
    for (int k = 1; k < 4; ++k)
        if (cn[k] < d->cap_n) d->cap_n = cn[k];
    for (int k = 1; k < 3; ++k)
        if (cm[k] < d->cap_m) d->cap_m = cm[k];
    return RY_OK;
}

void ry_csr_deflation_free(ry_csr_deflation *d) {
    free(d->agg);
    free(d->start);
    free(d->lo);
    free(d->rows);
    free(d->azn);
    free(d->azo);
    free(d->azc);
    free(d->azv);
    free(d->e);
    free(d->c);
    free(d->u);
    free(d->slot);
    *d = (ry_csr_deflation){0};
}

/* Room for A Z (at most A's entries) and E (m x m); the rest comes from
 * ry_csr_deflation_reserve. */
static ry_status deflation_room(const ry_csr *a, ry_csr_deflation *d, ry_error *err) {
    const size_t n = a->n, nz = a->row[n];
    RY_CHECK(err, d->cap_n > n && d->cap_m > d->m && d->cap_u >= 2 * RY_CSR_MAX_RHS * (n + 1),
             RY_ERR_INTERNAL,
             "deflation: room for %zu unknowns and %zu aggregates, not %zu and %zu", d->cap_n,
             d->cap_m, n, d->m);
    size_t cz = d->cap_nz, cz2 = d->cap_nz;
    const size_t ns = (size_t)omp_get_max_threads() * d->m, cs = d->cap_slot;
    int ok = grow((void **)&d->azc, &cz, nz, sizeof *d->azc) &&
             grow((void **)&d->azv, &cz2, nz, sizeof *d->azv) &&
             grow((void **)&d->e, &d->cap_e, d->m * d->m, sizeof *d->e) &&
             grow((void **)&d->slot, &d->cap_slot, ns, sizeof *d->slot);
    /* (the new entries: no aggregate has a place in a row yet; the old ones hold -1) */
    for (size_t k = cs; ok && k < d->cap_slot; ++k) d->slot[k] = -1;
    RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (deflation: %zu entries, %zu aggregates)", nz,
             d->m);
    d->cap_nz = cz < cz2 ? cz : cz2;
    return RY_OK;
}

/* Groups the unknowns by aggregate, forms A Z and E = Z^T A Z and factors E (Cholesky).
 * Returns 0 where E is not positive definite in floating point. */
static int deflation_setup(const ry_csr *a, ry_csr_deflation *d) {
    const size_t n = a->n, m = d->m;
    size_t *start = d->start, *lo = d->lo;
    for (size_t k = 0; k <= m; ++k) start[k] = 0;
    for (size_t i = 0; i < n; ++i) ++start[d->agg[i] + 1];
    for (size_t k = 0; k < m; ++k) start[k + 1] += start[k];
    for (size_t k = 0; k < m; ++k) lo[k] = start[k]; /* (a cursor while grouping) */
    for (size_t i = 0; i < n; ++i) d->rows[lo[d->agg[i]]++] = (uint32_t)i;
    const uint32_t *agg = d->agg;
    uint32_t *azn = d->azn, *azc = d->azc;
    double *azv = d->azv, *e = d->e;
    /* row i of A Z: A's entries of the row summed by the aggregate of their column, in the
     * order the aggregates first appear; the thread's slot table gives an aggregate's place
     * in the row (-1: none yet) and is cleared after it */
#pragma omp parallel if (n > 4096)
    {
        int32_t *slot = d->slot + (size_t)omp_get_thread_num() * m;
#pragma omp for schedule(static)
        for (size_t i = 0; i < n; ++i) {
            const size_t base = a->row[i];
            uint32_t cnt = 0;
            for (size_t q = a->row[i]; q < a->row[i + 1]; ++q) {
                const uint32_t l = agg[a->col[q]];
                if (slot[l] < 0) {
                    slot[l] = (int32_t)cnt;
                    azc[base + cnt] = l;
                    azv[base + cnt++] = 0;
                }
                azv[base + (uint32_t)slot[l]] += a->val[q];
            }
            for (uint32_t t = 0; t < cnt; ++t) slot[azc[base + t]] = -1;
            azn[i] = cnt;
        }
    }
    /* the rows packed one after the other, for the products of every iteration (each row
     * moves to an earlier place or stays) */
    size_t *azo = d->azo;
    azo[0] = 0;
    for (size_t i = 0; i < n; ++i) {
        azo[i + 1] = azo[i] + azn[i];
        if (azo[i] == a->row[i]) continue;
        memmove(azc + azo[i], azc + a->row[i], azn[i] * sizeof *azc);
        memmove(azv + azo[i], azv + a->row[i], azn[i] * sizeof *azv);
    }
    /* row k of E: the rows of A Z of aggregate k's unknowns, in order; its first entry */
#pragma omp parallel for schedule(dynamic, 4) if (m > 64)
    for (size_t k = 0; k < m; ++k) {
        double *ek = e + k * m;
        for (size_t l = 0; l <= k; ++l) ek[l] = 0;
        size_t f = k;
        for (size_t s = start[k]; s < start[k + 1]; ++s) {
            const uint32_t i = d->rows[s];
            for (size_t t = azo[i]; t < azo[i + 1]; ++t) {
                const uint32_t l = azc[t];
                if (l > k) continue;
                ek[l] += azv[t];
                if (l < f) f = l;
            }
        }
        lo[k] = f;
    }
    /* E = L L^T, L in the lower triangle within E's envelope (row i from lo[i]; the
     * factor fills no entry outside it), row by row from the rows before */
    for (size_t i = 0; i < m; ++i) {
        double *li = e + i * m;
        for (size_t j = lo[i]; j < i; ++j) {
            const double *lj = e + j * m;
            double s = li[j];
            for (size_t p = lo[i] > lo[j] ? lo[i] : lo[j]; p < j; ++p) s -= li[p] * lj[p];
            li[j] = s / lj[j];
        }
        double s = li[i];
        for (size_t p = lo[i]; p < i; ++p) s -= li[p] * li[p];
        if (!(s > 0) || !isfinite(s)) return 0;
        li[i] = sqrt(s);
    }
    return 1;
}

/* c = E^-1 Z^T v (the coarse solve). */
static void coarse_solve(const ry_csr_deflation *d, const double *v) {
    const size_t m = d->m;
    double *c = d->c;
    const double *e = d->e;
#pragma omp parallel for schedule(static) if (m > 64)
    for (size_t k = 0; k < m; ++k) {
        double s = 0;
        for (size_t q = d->start[k]; q < d->start[k + 1]; ++q) s += v[d->rows[q]];
        c[k] = s;
    }
    const size_t *lo = d->lo;
    for (size_t i = 0; i < m; ++i) { /* L y = c */
        double s = c[i];
        for (size_t p = lo[i]; p < i; ++p) s -= e[i * m + p] * c[p];
        c[i] = s / e[i * m + i];
    }
    for (size_t i = m; i-- > 0;) { /* L^T c = y, by columns of L^T (rows of L) */
        c[i] /= e[i * m + i];
        for (size_t p = lo[i]; p < i; ++p) c[p] -= e[i * m + p] * c[i];
    }
}

/* out = v - A Z c, the deflated v (P v) after coarse_solve(d, v). */
static void deflate(const ry_csr *a, const ry_csr_deflation *d, const double *v, double *out) {
    const size_t n = a->n;
#pragma omp parallel for schedule(static) if (n > 4096)
    for (size_t i = 0; i < n; ++i) {
        double s = v[i];
        for (size_t t = d->azo[i]; t < d->azo[i + 1]; ++t) s -= d->azv[t] * d->c[d->azc[t]];
        out[i] = s;
    }
}
