/* Brute-force neighbour list: every pair is tested. O(n^2); the reference the cell list is
 * tested against, and the baseline of the benchmark. */
#include <stdint.h>
#include <stdlib.h>

#include "neighbor/neighbor_internal.h"

ry_status ry_nb_check_args(const ry_box *box, double radius, size_t n, const double *const x[3],
                           ry_error *err) {
    RY_CHECK(err, box != NULL, RY_ERR_INPUT, "neighbour search: no box given");
    RY_CHECK(err, box->dim >= 1 && box->dim <= 3, RY_ERR_INPUT,
             "neighbour search: dimension %d is not 1, 2 or 3", box->dim);
    RY_CHECK(err, isfinite(radius) && radius > 0.0, RY_ERR_RANGE,
             "neighbour search: radius %g is not a finite positive number", radius);
    RY_CHECK(err, n <= UINT32_MAX, RY_ERR_RANGE,
             "neighbour search: %zu particles exceed the limit of %lu", n,
             (unsigned long)UINT32_MAX);
    if (n > 0) {
        RY_CHECK(err, x != NULL, RY_ERR_INPUT, "neighbour search: no coordinates given");
        for (int d = 0; d < box->dim; ++d)
            RY_CHECK(err, x[d] != NULL, RY_ERR_INPUT,
                     "neighbour search: no coordinates given in direction %d", d);
    }
    return RY_OK;
}

ry_status ry_nb_reserve_offsets(ry_nlist *nl, size_t n, ry_error *err) {
    if (nl->offset == NULL || nl->cap_n < n) {
        size_t cap = n > nl->cap_n + nl->cap_n / 2 ? n : nl->cap_n + nl->cap_n / 2;
        RY_CHECK(err, cap < SIZE_MAX / sizeof(size_t) - 1, RY_ERR_NOMEM,
                 "neighbour list: %zu particles are too many", n);
        size_t *p = realloc(nl->offset, (cap + 1) * sizeof *p);
        RY_CHECK(err, p != NULL, RY_ERR_NOMEM, "neighbour list: no memory for %zu particles", n);
        nl->offset = p;
        nl->cap_n = cap;
    }
    return RY_OK;
}

ry_status ry_nb_reserve_j(ry_nlist *nl, size_t m, ry_error *err) {
    if (nl->j == NULL || nl->cap_j < m) {
        size_t cap = m > nl->cap_j + nl->cap_j / 4 ? m : nl->cap_j + nl->cap_j / 4;
        if (cap == 0) cap = 1;
        RY_CHECK(err, cap < SIZE_MAX / sizeof(uint32_t), RY_ERR_NOMEM,
                 "neighbour list: %zu pairs are too many", m);
        /* The old contents are not needed: free first so that peak memory stays low. */
        free(nl->j);
        nl->j = malloc(cap * sizeof *nl->j);
        if (nl->j == NULL) {
            nl->cap_j = 0;
            return ry_error_set(err, RY_ERR_NOMEM, "neighbour list: no memory for %zu pairs", m);
        }
        nl->cap_j = cap;
    }
    return RY_OK;
}

size_t ry_nb_prefix_sum(size_t *offset, size_t n, size_t *max_row) {
    size_t sum = 0, m = 0;
    offset[0] = 0;
    for (size_t i = 0; i < n; ++i) {
        if (offset[i + 1] > m) m = offset[i + 1];
        sum += offset[i + 1];
        offset[i + 1] = sum;
    }
    *max_row = m;
    return sum;
}

/* Neighbours of i among all particles; writes them to out when out is not NULL. The counting
 * loop has no branches, so that the compiler can vectorise it. */
static inline size_t brute_row(const ry_nb_geom *g, int dim, const double *const x[3], size_t n,
                               double r2max, size_t i, uint32_t *out) {
    size_t c = 0;
    if (!out) {
        for (size_t j = 0; j < n; ++j) c += (ry_nb_r2(g, dim, x, i, j) < r2max) & (j != i);
        return c;
    }
    for (size_t j = 0; j < n; ++j) {
        if (j != i && ry_nb_r2(g, dim, x, i, j) < r2max) out[c++] = (uint32_t)j;
    }
    return c;
}

static size_t brute_row_dim(const ry_nb_geom *g, const double *const x[3], size_t n, double r2max,
                            size_t i, uint32_t *out) {
    switch (g->dim) {
    case 1:
        return brute_row(g, 1, x, n, r2max, i, out);
    case 2:
        return brute_row(g, 2, x, n, r2max, i, out);
    default:
        return brute_row(g, 3, x, n, r2max, i, out);
    }
}

ry_status ry_nb_brute_subset(ry_nlist *nl, const ry_box *box, double radius, size_t n,
                             const double *const x[3], const uint32_t *queries, size_t k,
                             ry_error *err) {
    RY_CHECK(err, nl != NULL, RY_ERR_INPUT, "neighbour list: no list given");
    RY_TRY(ry_nb_check_args(box, radius, n, x, err));
    for (size_t i = 0; i < n; ++i)
        for (int d = 0; d < box->dim; ++d)
            RY_CHECK(err, isfinite(x[d][i]), RY_ERR_RANGE,
                     "neighbour search: particle %zu has a non-finite coordinate %g "
                     "(direction %d)",
                     i, x[d][i], d);
    if (queries)
        for (size_t q = 0; q < k; ++q)
            RY_CHECK(err, queries[q] < n, RY_ERR_INPUT,
                     "neighbour search: query %zu names particle %lu of %zu", q,
                     (unsigned long)queries[q], n);
    RY_TRY(ry_nb_reserve_offsets(nl, k, err));
    ry_nb_geom g;
    ry_nb_geom_init(&g, box);
    const double r2max = radius * radius;
    size_t *off = nl->offset;
    const long long kk = (long long)k;

#pragma omp parallel for schedule(dynamic, 64)
    for (long long q = 0; q < kk; ++q) {
        size_t i = queries ? queries[q] : (size_t)q;
        off[q + 1] = brute_row_dim(&g, x, n, r2max, i, NULL);
    }

    size_t total = ry_nb_prefix_sum(off, k, &nl->max_row);
    RY_TRY(ry_nb_reserve_j(nl, total, err));
    uint32_t *jj = nl->j;

#pragma omp parallel for schedule(dynamic, 64)
    for (long long q = 0; q < kk; ++q) {
        size_t i = queries ? queries[q] : (size_t)q;
        brute_row_dim(&g, x, n, r2max, i, jj + off[q]);
    }

    nl->n = k;
    return RY_OK;
}

ry_status ry_nlist_build_brute(ry_nlist *nl, const ry_box *box, double radius, size_t n,
                               const double *const x[3], ry_error *err) {
    return ry_nb_brute_subset(nl, box, radius, n, x, NULL, n, err);
}

void ry_nlist_free(ry_nlist *nl) {
    if (!nl) return;
    free(nl->offset);
    free(nl->j);
    *nl = (ry_nlist){0};
}

double ry_nlist_bytes_per_particle(const ry_nlist *nl) {
    if (!nl || nl->n == 0) return 0.0;
    double bytes = (nl->offset ? (double)(nl->cap_n + 1) * sizeof(size_t) : 0.0) +
                   (double)nl->cap_j * sizeof(uint32_t);
    return bytes / (double)nl->n;
}
