/* Neighbour-search benchmark: cell list against brute force (see include/ryushi/bench.h). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <omp.h>

#include "neighbor/neighbor_internal.h"
#include "ryushi/bench.h"

enum {
    BENCH_QUERIES = 2000,     /* brute-force sample size for large sets */
    BENCH_FULL_BRUTE = 10000, /* largest set searched in full by brute force */
    BENCH_REPS = 5,           /* cell-list repetitions (median) */
    BENCH_REPS_LARGE = 3      /* ... for sets of a million particles and more */
};

static uint64_t bench_next(uint64_t *s) {
    uint64_t z = (*s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

static int cmp_double(const void *a, const void *b) {
    double u = *(const double *)a, v = *(const double *)b;
    return (u > v) - (u < v);
}

static double median(double *v, int m) {
    qsort(v, (size_t)m, sizeof *v, cmp_double);
    return m % 2 ? v[m / 2] : 0.5 * (v[m / 2 - 1] + v[m / 2]);
}

/* Median time of reps cell-list builds (cells + neighbour list). */
static ry_status time_cells(ry_cell_list *cl, ry_nlist *nl, const ry_box *box, double radius,
                            size_t n, const double *const x[3], int reps, double *median_s,
                            ry_error *err) {
    double t[BENCH_REPS];
    /* warm-up: allocates the memory that later builds reuse, as a simulation does */
    RY_TRY(ry_cells_build(cl, box, radius, n, x, err));
    RY_TRY(ry_nlist_build_cells(nl, cl, box, radius, n, x, err));
    for (int r = 0; r < reps; ++r) {
        double t0 = omp_get_wtime();
        RY_TRY(ry_cells_build(cl, box, radius, n, x, err));
        RY_TRY(ry_nlist_build_cells(nl, cl, box, radius, n, x, err));
        t[r] = omp_get_wtime() - t0;
    }
    *median_s = median(t, reps);
    return RY_OK;
}

typedef struct bench_mem {
    double *x[3], *xs[3];
    uint32_t *queries;
    ry_cell_list cl;
    ry_nlist nl, bl;
} bench_mem;

static void bench_mem_free(bench_mem *m) {
    for (int d = 0; d < 3; ++d) {
        free(m->x[d]);
        free(m->xs[d]);
    }
    free(m->queries);
    ry_cells_free(&m->cl);
    ry_nlist_free(&m->nl);
    ry_nlist_free(&m->bl);
    memset(m, 0, sizeof *m);
}

static ry_status bench_one(FILE *out, int dim, size_t n, bench_mem *m, ry_error *err) {
    for (int d = 0; d < 3; ++d) {
        m->x[d] = malloc((n ? n : 1) * sizeof(double));
        m->xs[d] = malloc((n ? n : 1) * sizeof(double));
        RY_CHECK(err, m->x[d] && m->xs[d], RY_ERR_NOMEM, "bench: no memory for %zu particles", n);
    }
    uint64_t seed = 12345u + 7u * (uint64_t)n + (uint64_t)dim;
    for (size_t i = 0; i < n; ++i)
        for (int d = 0; d < 3; ++d)
            m->x[d][i] = d < dim ? (double)(bench_next(&seed) >> 11) * 0x1.0p-53 : 0.0;
    const double pi = 3.14159265358979323846;
    const double radius =
        dim == 2 ? sqrt(20.0 / (pi * (double)n)) : cbrt(50.0 * 3.0 / (4.0 * pi * (double)n));
    ry_box box = {.dim = dim, .lo = {0, 0, 0}, .hi = {1, 1, 1}, .periodic = {0, 0, 0}};
    const double *const *x = (const double *const *)m->x;
    const double *const *xs = (const double *const *)m->xs;
    const int reps = n >= 1000000 ? BENCH_REPS_LARGE : BENCH_REPS;

    /* Particles in random order. */
    double raw_s;
    RY_TRY(time_cells(&m->cl, &m->nl, &box, radius, n, x, reps, &raw_s, err));
    const double neigh = n ? (double)m->nl.offset[n] / (double)n : 0.0;

    /* Brute force on a sample of queries; the same rows of the cell list must match. */
    size_t k = n < BENCH_QUERIES ? n : BENCH_QUERIES;
    m->queries = malloc((k ? k : 1) * sizeof *m->queries);
    RY_CHECK(err, m->queries, RY_ERR_NOMEM, "bench: no memory");
    for (size_t q = 0; q < k; ++q) m->queries[q] = (uint32_t)(q * n / k);
    double t0 = omp_get_wtime();
    RY_TRY(ry_nb_brute_subset(&m->bl, &box, radius, n, x, m->queries, k, err));
    double sample_s = omp_get_wtime() - t0;
    for (size_t q = 0; q < k; ++q) {
        size_t i = m->queries[q];
        size_t cnt = m->nl.offset[i + 1] - m->nl.offset[i];
        RY_CHECK(err,
                 cnt == m->bl.offset[q + 1] - m->bl.offset[q] &&
                     memcmp(m->nl.j + m->nl.offset[i], m->bl.j + m->bl.offset[q],
                            cnt * sizeof(uint32_t)) == 0,
                 RY_ERR_INTERNAL, "bench: cell list and brute force disagree for particle %zu", i);
    }
    double brute_s;
    int brute_full = n <= BENCH_FULL_BRUTE;
    if (brute_full) {
        double t[3];
        for (int r = 0; r < 3; ++r) {
            t0 = omp_get_wtime();
            RY_TRY(ry_nlist_build_brute(&m->bl, &box, radius, n, x, err));
            t[r] = omp_get_wtime() - t0;
        }
        brute_s = median(t, 3);
    } else {
        brute_s = sample_s * (double)n / (double)k;
    }

    /* Particles sorted by cell, as the engine keeps them. */
    t0 = omp_get_wtime();
    RY_TRY(ry_cells_build(&m->cl, &box, radius, n, x, err));
    for (int d = 0; d < dim; ++d) {
        double *dst = m->xs[d];
        const double *src = m->x[d];
        const uint32_t *order = m->cl.order;
        const long long nn = (long long)n;
#pragma omp parallel for schedule(static)
        for (long long p = 0; p < nn; ++p) dst[p] = src[order[p]];
    }
    double reorder_s = omp_get_wtime() - t0;
    double sorted_s;
    RY_TRY(time_cells(&m->cl, &m->nl, &box, radius, n, xs, reps, &sorted_s, err));
    RY_CHECK(err, n == 0 || (double)m->nl.offset[n] / (double)n == neigh, RY_ERR_INTERNAL,
             "bench: the sorted set has another number of pairs");
    double bytes = ry_cells_bytes_per_particle(&m->cl) + ry_nlist_bytes_per_particle(&m->nl);

    double per = n ? 1e9 / (double)n : 0.0;
    char brute_how[64];
    if (brute_full)
        snprintf(brute_how, sizeof brute_how, "measured");
    else
        snprintf(brute_how, sizeof brute_how, "estimated from %zu queries", k);
    fprintf(out, "%9zu %3d %6.1f %10.4g %8.1f %10.4g %8.1f %10.4g %6.0f %10.4g %-28s %8.0f %8.0f\n",
            n, dim, neigh, raw_s, raw_s * per, sorted_s, sorted_s * per, reorder_s, bytes, brute_s,
            brute_how, raw_s > 0 ? brute_s / raw_s : 0.0, sorted_s > 0 ? brute_s / sorted_s : 0.0);
    fflush(out);
    return RY_OK;
}

ry_status ry_bench_neighbors(FILE *out, int dim, const size_t *ns, int count, ry_error *err) {
    RY_CHECK(err, out != NULL, RY_ERR_INPUT, "bench: no output stream");
    RY_CHECK(err, dim == 2 || dim == 3, RY_ERR_INPUT, "bench: dimension %d is not 2 or 3", dim);
    RY_CHECK(err, count >= 0 && (count == 0 || ns != NULL), RY_ERR_INPUT,
             "bench: no particle counts given");
    for (int c = 0; c < count; ++c)
        RY_CHECK(err, ns[c] >= 1 && ns[c] <= UINT32_MAX, RY_ERR_RANGE,
                 "bench: particle count %zu out of range", ns[c]);
    fprintf(out,
            "# neighbour search, %dD: N uniform random particles in the unit %s, radius for "
            "about %d neighbours\n"
            "# %d OpenMP threads; cell list = ry_cells_build + ry_nlist_build_cells, median of "
            "%d runs (%d from 1e6)\n"
            "# raw: particles in random order; sorted: coordinates reordered by cell first "
            "(reorder_s: its cost, once)\n",
            dim, dim == 2 ? "square" : "cube", dim == 2 ? 20 : 50, omp_get_max_threads(),
            (int)BENCH_REPS, (int)BENCH_REPS_LARGE);
    fprintf(out, "%9s %3s %6s %10s %8s %10s %8s %10s %6s %10s %-28s %8s %8s\n", "N", "dim", "neigh",
            "raw_s", "raw_ns/p", "sorted_s", "srt_ns/p", "reorder_s", "B/p", "brute_s", "brute",
            "x_raw", "x_sorted");
    for (int c = 0; c < count; ++c) {
        bench_mem m;
        memset(&m, 0, sizeof m);
        ry_status st = bench_one(out, dim, ns[c], &m, err);
        bench_mem_free(&m);
        if (st != RY_OK) {
            ry_error_prefix(err, "neighbour benchmark with %zu particles: ", ns[c]);
            return st;
        }
    }
    return RY_OK;
}
