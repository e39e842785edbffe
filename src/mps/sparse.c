/* CSR matrix and Jacobi-preconditioned conjugate gradients (Hestenes & Stiefel 1952; the
 * preconditioned form as in Saad, Iterative Methods for Sparse Linear Systems, alg. 9.1). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "mps/sparse.h"
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

void ry_csr_free(ry_csr *a) {
    free(a->row);
    free(a->col);
    free(a->val);
    free(a->diag);
    free(a->work);
    *a = (ry_csr){0};
}

void ry_csr_mul(const ry_csr *a, const double *x, double *y) {
    const size_t n = a->n;
#pragma omp parallel for schedule(static) if (n > 4096)
    for (size_t i = 0; i < n; ++i) {
        double s = 0;
        for (size_t q = a->row[i]; q < a->row[i + 1]; ++q) s += a->val[q] * x[a->col[q]];
        y[i] = s;
    }
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

ry_status ry_csr_pcg(ry_csr *a, const double *b, double *x, double tol, int max_iter, int *iters,
                     double *resid, const ry_csr_dist *dist, ry_error *err) {
    const size_t n = a->n;
    double *r = a->work, *z = r + n, *p = z + n, *q = p + n;
    *iters = 0;
    *resid = 0;
    /* (a distributed system goes on with no local unknowns: the others' sums need this one) */
    if (n == 0 && !dist) return RY_OK;
    const double bnorm = sqrt(ddot(dist, b, b, n));
    if (bnorm == 0) {
        for (size_t i = 0; i < n; ++i) x[i] = 0;
        return RY_OK;
    }
    if (dist) dist->sync(dist->ctx, x);
    ry_csr_mul(a, x, q);
#pragma omp parallel for schedule(static) if (n > 4096)
    for (size_t i = 0; i < n; ++i) {
        r[i] = b[i] - q[i];
        z[i] = r[i] / a->diag[i];
        p[i] = z[i];
    }
    double rz = ddot(dist, r, z, n), rn = sqrt(ddot(dist, r, r, n));
    int k = 0;
    while (rn > tol * bnorm && k < max_iter) {
        if (dist) dist->sync(dist->ctx, p);
        ry_csr_mul(a, p, q);
        const double pq = ddot(dist, p, q, n);
        RY_CHECK(err, pq > 0 && isfinite(pq), RY_ERR_UNSTABLE,
                 "conjugate gradients broke down after %d iterations (p.Ap = %g: the matrix is "
                 "not positive definite)",
                 k, pq);
        const double alpha = rz / pq;
#pragma omp parallel for schedule(static) if (n > 4096)
        for (size_t i = 0; i < n; ++i) {
            x[i] += alpha * p[i];
            r[i] -= alpha * q[i];
            z[i] = r[i] / a->diag[i];
        }
        const double rz1 = ddot(dist, r, z, n);
        const double beta = rz1 / rz;
        rz = rz1;
#pragma omp parallel for schedule(static) if (n > 4096)
        for (size_t i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
        rn = sqrt(ddot(dist, r, r, n));
        ++k;
    }
    *iters = k;
    *resid = rn / bnorm;
    RY_CHECK(err, rn <= tol * bnorm, RY_ERR_UNSTABLE,
             "conjugate gradients did not converge in %d iterations (relative residual %.3g, "
             "tolerance %.3g)",
             k, rn / bnorm, tol);
    return RY_OK;
}

static void particle_sync(void *ctx, double *v) {
    ry_particle_unknowns *pu = ctx;
    ry_sim *sim = (ry_sim *)pu->sim;
    const size_t n = sim->ps.n;
    for (size_t i = 0; i < n; ++i) pu->tmp[i] = pu->unk[i] >= 0 ? v[pu->unk[i]] : 0.0;
    sim->par->sync(sim, pu->tmp, 1);
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
