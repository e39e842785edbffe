/* Cell list by counting sort, and the neighbour list built from it.
 *
 * Cells: edge >= radius (slightly more, see cell_margin), so that two particles closer than
 * the radius always lie in the same or in adjacent cells. Periodic directions are split into
 * floor(L / edge) cells of length L / ncell; non-periodic directions cover the particles'
 * bounding box. Particles are binned by floor((x - lo) / edge), clamped into the edge cells
 * (non-periodic) or wrapped (periodic), then sorted by cell with a stable counting sort.
 *
 * Neighbour list: for each particle the distinct neighbouring cells (at most 3 per direction,
 * fewer where a periodic direction has under 3 cells) are scanned in increasing cell order;
 * the pairs closer than the radius (minimum image) are kept. One pass writes and sorts each
 * particle's list by index into a buffer of its thread, a prefix sum gives the offsets, and the
 * lists are copied into place. Each particle's list depends only on the input, so the result is
 * the same for any number of threads. */
#include <float.h>
#include <omp.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "neighbor/neighbor_internal.h"
#include "neighbor/r2_simd.h"

/* Upper bound on the number of cells: beyond it the cells are enlarged (still correct, only
 * slower). Keeps memory O(n) for sparse sets (far-apart clusters, a few stray particles). */
static double cell_limit(size_t n) {
    double lim = 8.0 * (double)n + 65536.0;
    return lim < 2147483647.0 ? lim : 2147483647.0;
}

/* Relative margin added to the radius to get the minimum cell edge: it absorbs the rounding
 * of the cell coordinate (x - lo) / edge, whose absolute error in cells grows with the
 * magnitude of the coordinates measured in radii. */
static double cell_margin(double radius, double maxabs) {
    return 1e-12 + 16.0 * DBL_EPSILON * (2.0 + maxabs / radius);
}

static const char axis_name[3] = {'x', 'y', 'z'};

/* Diagnoses particle i after the scan found a bad one. */
static ry_status bad_particle(const ry_box *box, size_t i, const double *const x[3],
                              ry_error *err) {
    for (int d = 0; d < box->dim; ++d)
        if (!isfinite(x[d][i]))
            return ry_error_set(err, RY_ERR_RANGE,
                                "cell list: particle %zu has a non-finite coordinate %c = %g", i,
                                axis_name[d], x[d][i]);
    for (int d = 0; d < box->dim; ++d)
        if (box->periodic[d] && !(x[d][i] >= box->lo[d] && x[d][i] <= box->hi[d]))
            return ry_error_set(err, RY_ERR_RANGE,
                                "cell list: particle %zu lies outside the periodic box in %c "
                                "(%c = %g, box [%g, %g])",
                                i, axis_name[d], axis_name[d], x[d][i], box->lo[d], box->hi[d]);
    return ry_error_set(err, RY_ERR_INTERNAL, "cell list: particle %zu flagged without reason", i);
}

ry_status ry_cells_build(ry_cell_list *cl, const ry_box *box, double radius, size_t n,
                         const double *const x[3], ry_error *err) {
    RY_CHECK(err, cl != NULL, RY_ERR_INPUT, "cell list: no cell list given");
    RY_TRY(ry_nb_check_args(box, radius, n, x, err));
    const int dim = box->dim;
    for (int d = 0; d < dim; ++d)
        if (box->periodic[d])
            RY_CHECK(err, isfinite(box->lo[d]) && isfinite(box->hi[d]) && box->hi[d] > box->lo[d],
                     RY_ERR_INPUT, "cell list: periodic direction %c has an empty box [%g, %g]",
                     axis_name[d], box->lo[d], box->hi[d]);

    /* Bounding box, non-finite coordinates and particles outside periodic boxes. */
    double mn[3] = {0, 0, 0}, mx[3] = {0, 0, 0};
    {
        double mn0 = INFINITY, mn1 = INFINITY, mn2 = INFINITY;
        double mx0 = -INFINITY, mx1 = -INFINITY, mx2 = -INFINITY;
        size_t bad = SIZE_MAX;
        int per[3];
        double plo[3] = {0, 0, 0}, phi[3] = {0, 0, 0};
        for (int d = 0; d < 3; ++d) {
            per[d] = d < dim && box->periodic[d];
            if (per[d]) {
                plo[d] = box->lo[d];
                phi[d] = box->hi[d];
            }
        }
        const double *x0 = n > 0 ? x[0] : NULL;
        const double *x1 = n > 0 && dim > 1 ? x[1] : NULL;
        const double *x2 = n > 0 && dim > 2 ? x[2] : NULL;
        const long long nn = (long long)n;
#pragma omp parallel for schedule(static) reduction(min                                            \
                                                    : mn0, mn1, mn2, bad)                          \
    reduction(max                                                                                  \
              : mx0, mx1, mx2)
        for (long long ii = 0; ii < nn; ++ii) {
            size_t i = (size_t)ii;
            double a = x0[i], b = x1 ? x1[i] : 0.0, c = x2 ? x2[i] : 0.0;
            int ok = isfinite(a) && isfinite(b) && isfinite(c);
            if (per[0] && !(a >= plo[0] && a <= phi[0])) ok = 0;
            if (per[1] && !(b >= plo[1] && b <= phi[1])) ok = 0;
            if (per[2] && !(c >= plo[2] && c <= phi[2])) ok = 0;
            if (!ok) {
                if (i < bad) bad = i;
                continue;
            }
            mn0 = a < mn0 ? a : mn0;
            mx0 = a > mx0 ? a : mx0;
            mn1 = b < mn1 ? b : mn1;
            mx1 = b > mx1 ? b : mx1;
            mn2 = c < mn2 ? c : mn2;
            mx2 = c > mx2 ? c : mx2;
        }
        if (bad != SIZE_MAX) return bad_particle(box, bad, x, err);
        if (n > 0) {
            mn[0] = mn0, mn[1] = mn1, mn[2] = mn2;
            mx[0] = mx0, mx[1] = mx1, mx[2] = mx2;
        }
    }

    /* Grid geometry. */
    double lo[3], maxabs = 0.0;
    for (int d = 0; d < dim; ++d) {
        lo[d] = box->periodic[d] ? box->lo[d] : mn[d];
        double hi = box->periodic[d] ? box->hi[d] : mx[d];
        if (fabs(lo[d]) > maxabs) maxabs = fabs(lo[d]);
        if (fabs(hi) > maxabs) maxabs = fabs(hi);
        RY_CHECK(err, isfinite(hi - lo[d]), RY_ERR_RANGE,
                 "cell list: the particles span too large a range in %c ([%g, %g])", axis_name[d],
                 lo[d], hi);
    }
    double target = radius * (1.0 + cell_margin(radius, maxabs));
    RY_CHECK(err, isfinite(target), RY_ERR_RANGE, "cell list: radius %g is too large", radius);
    const double limit = cell_limit(n);
    double cell[3] = {1, 1, 1};
    int ncell[3] = {1, 1, 1};
    for (int iter = 0;; ++iter) {
        double total = 1.0, nc[3] = {1, 1, 1};
        for (int d = 0; d < dim; ++d) {
            if (box->periodic[d]) {
                double len = box->hi[d] - box->lo[d];
                nc[d] = floor(len / target);
                if (!(nc[d] >= 1.0)) nc[d] = 1.0;
                if (nc[d] > limit) nc[d] = limit + 1.0; /* product check below rejects it */
                cell[d] = len / nc[d];
            } else {
                nc[d] = floor((mx[d] - mn[d]) / target) + 1.0;
                if (!(nc[d] <= limit)) nc[d] = limit + 1.0;
                cell[d] = target;
            }
            total *= nc[d];
        }
        if (total <= limit) {
            for (int d = 0; d < dim; ++d) ncell[d] = (int)nc[d];
            break;
        }
        RY_CHECK(err, iter < 200, RY_ERR_INTERNAL, "cell list: cannot size the grid");
        double grow = pow(total / limit, 1.0 / dim);
        target *= grow > 1.001 ? grow : 1.001;
    }
    size_t ncells = (size_t)ncell[0] * (size_t)ncell[1] * (size_t)ncell[2];

    /* Memory: grow only. */
    if (cl->start == NULL || cl->cap_cells < ncells) {
        size_t cap =
            ncells > cl->cap_cells + cl->cap_cells / 2 ? ncells : cl->cap_cells + cl->cap_cells / 2;
        size_t *p = realloc(cl->start, (cap + 1) * sizeof *p);
        RY_CHECK(err, p != NULL, RY_ERR_NOMEM, "cell list: no memory for %zu cells", ncells);
        cl->start = p;
        cl->cap_cells = cap;
    }
    if (cl->order == NULL || cl->cap_n < n) {
        size_t cap = n > cl->cap_n + cl->cap_n / 4 ? n : cl->cap_n + cl->cap_n / 4;
        if (cap == 0) cap = 1;
        free(cl->order);
        free(cl->cell_of);
        cl->order = malloc(cap * sizeof *cl->order);
        cl->cell_of = malloc(cap * sizeof *cl->cell_of);
        if (!cl->order || !cl->cell_of) {
            free(cl->order);
            free(cl->cell_of);
            cl->order = cl->cell_of = NULL;
            cl->cap_n = 0;
            return ry_error_set(err, RY_ERR_NOMEM, "cell list: no memory for %zu particles", n);
        }
        cl->cap_n = cap;
    }

    cl->dim = dim;
    for (int d = 0; d < 3; ++d) {
        cl->lo[d] = d < dim ? lo[d] : 0.0;
        cl->cell[d] = d < dim ? cell[d] : 1.0;
        cl->ncell[d] = d < dim ? ncell[d] : 1;
    }
    cl->ncells = ncells;
    cl->n = n;

    /* Cell of each particle. */
    {
        double inv[3] = {0, 0, 0};
        int per[3] = {0, 0, 0};
        for (int d = 0; d < dim; ++d) {
            inv[d] = 1.0 / cell[d];
            per[d] = box->periodic[d];
        }
        uint32_t *cell_of = cl->cell_of;
        const long long nn = (long long)n;
#pragma omp parallel for schedule(static)
        for (long long ii = 0; ii < nn; ++ii) {
            size_t i = (size_t)ii;
            size_t id = 0, stride = 1;
            for (int d = 0; d < dim; ++d) {
                double t = floor((x[d][i] - lo[d]) * inv[d]);
                long k;
                if (per[d]) {
                    /* x in [lo, hi]: t in [0, ncell] up to rounding; ncell wraps to 0. */
                    k = t < 0.0 ? 0 : (t >= (double)ncell[d] ? (long)t % ncell[d] : (long)t);
                } else {
                    k = t < 0.0 ? 0 : (t >= (double)ncell[d] ? ncell[d] - 1 : (long)t);
                }
                id += (size_t)k * stride;
                stride *= (size_t)ncell[d];
            }
            cell_of[i] = (uint32_t)id;
        }
    }

    /* Stable counting sort. */
    size_t *start = cl->start;
    memset(start, 0, (ncells + 1) * sizeof *start);
    for (size_t i = 0; i < n; ++i) ++start[cl->cell_of[i]];
    size_t sum = 0;
    for (size_t c = 0; c < ncells; ++c) {
        size_t k = start[c];
        start[c] = sum;
        sum += k;
    }
    for (size_t i = 0; i < n; ++i) cl->order[start[cl->cell_of[i]]++] = (uint32_t)i;
    /* start[c] now holds the end of cell c: shift to get the beginnings back. */
    memmove(start + 1, start, ncells * sizeof *start);
    start[0] = 0;
    return RY_OK;
}

void ry_cells_sort_x(ry_cell_list *cl, const double *x) {
    uint32_t *order = cl->order;
    const size_t *start = cl->start;
    const long long nc = (long long)cl->ncells;
#pragma omp parallel for schedule(dynamic, 256)
    for (long long c = 0; c < nc; ++c) {
        /* Insertion sort: a few particles per cell, usually in order already. */
        for (size_t q = start[c] + 1; q < start[c + 1]; ++q) {
            const uint32_t v = order[q];
            size_t k = q;
            while (k > start[c] &&
                   (x[order[k - 1]] > x[v] || (x[order[k - 1]] == x[v] && order[k - 1] > v))) {
                order[k] = order[k - 1];
                --k;
            }
            order[k] = v;
        }
    }
}

void ry_cells_permuted(ry_cell_list *cl) {
    uint32_t *order = cl->order, *cell_of = cl->cell_of;
    const size_t *start = cl->start;
    const long long nc = (long long)cl->ncells;
#pragma omp parallel for schedule(static)
    for (long long c = 0; c < nc; ++c)
        for (size_t q = start[c]; q < start[c + 1]; ++q) {
            order[q] = (uint32_t)q;
            cell_of[q] = (uint32_t)c;
        }
}

void ry_cells_free(ry_cell_list *cl) {
    if (!cl) return;
    free(cl->start);
    free(cl->order);
    free(cl->cell_of);
    *cl = (ry_cell_list){0};
}

double ry_cells_bytes_per_particle(const ry_cell_list *cl) {
    if (!cl || cl->n == 0) return 0.0;
    double bytes = (cl->start ? (double)(cl->cap_cells + 1) * sizeof(size_t) : 0.0) +
                   (double)cl->cap_n * (sizeof(uint32_t) + sizeof(uint32_t));
    return bytes / (double)cl->n;
}

/* The distinct cells neighbouring cell c (c included), in increasing order; returns how many. */
int ry_cells_neighbours(const ry_cell_list *cl, const int per[3], size_t c, size_t out[27]) {
    long idx[3][3];
    int m[3];
    size_t rest = c;
    for (int d = 0; d < 3; ++d) {
        long nc = cl->ncell[d];
        long k = (long)(rest % (size_t)nc);
        rest /= (size_t)nc;
        int cnt = 0;
        if (nc == 1) {
            idx[d][cnt++] = 0;
        } else if (per[d]) {
            if (nc == 2) {
                idx[d][cnt++] = 0;
                idx[d][cnt++] = 1;
            } else {
                idx[d][cnt++] = (k + nc - 1) % nc;
                idx[d][cnt++] = k;
                idx[d][cnt++] = (k + 1) % nc;
            }
        } else {
            if (k > 0) idx[d][cnt++] = k - 1;
            idx[d][cnt++] = k;
            if (k + 1 < nc) idx[d][cnt++] = k + 1;
        }
        m[d] = cnt;
    }
    const size_t nx = (size_t)cl->ncell[0], nxy = nx * (size_t)cl->ncell[1];
    int cnt = 0;
    for (int a = 0; a < m[2]; ++a)
        for (int b = 0; b < m[1]; ++b)
            for (int e = 0; e < m[0]; ++e)
                out[cnt++] = (size_t)idx[2][a] * nxy + (size_t)idx[1][b] * nx + (size_t)idx[0][e];
    /* Wrapped indices may be out of order: insertion sort (at most 27 entries). */
    for (int p = 1; p < cnt; ++p) {
        size_t v = out[p];
        int q = p - 1;
        while (q >= 0 && out[q] > v) {
            out[q + 1] = out[q];
            --q;
        }
        out[q + 1] = v;
    }
    return cnt;
}

/* Sorts a[0..m-1], whose values lie below 2^(8 passes), by a least-significant-digit radix
 * sort on bytes into tmp and back (m entries each). */
static void radix_u32(uint32_t *a, size_t m, uint32_t *tmp, int passes) {
    uint32_t *src = a, *dst = tmp;
    for (int p = 0; p < passes; ++p) {
        const int sh = 8 * p;
        size_t cnt[256] = {0};
        for (size_t k = 0; k < m; ++k) cnt[(src[k] >> sh) & 255u]++;
        size_t sum = 0;
        for (int d = 0; d < 256; ++d) {
            const size_t c = cnt[d];
            cnt[d] = sum;
            sum += c;
        }
        for (size_t k = 0; k < m; ++k) dst[cnt[(src[k] >> sh) & 255u]++] = src[k];
        uint32_t *t = src;
        src = dst;
        dst = t;
    }
    if (src != a) memcpy(a, src, m * sizeof *a);
}

/* The cells around particle i's own (no periodic sides) that come within r2max of it, in
 * ascending order: a corner cell of the 27 lies beyond the radius for about half the
 * particles, an edge cell for a fifth. The distance to a cell is taken to its nominal box,
 * which holds its particles up to the rounding of the binning (and the outer cells' clamped
 * ones farther out); the margin of 1e-9 r2max covers the rounding. */
static inline int near_cells(const ry_cell_list *cl, int dim, const double *const x[3],
                             double r2max, size_t i, size_t out[27]) {
    const size_t c0 = cl->cell_of[i], nx = (size_t)cl->ncell[0], ny = (size_t)cl->ncell[1];
    const size_t k[3] = {c0 % nx, (c0 / nx) % ny, c0 / (nx * ny)};
    double e2[3][3] = {{0}}; /* squared distance to the cell at offset -1, 0, +1 per axis */
    int from[3], to[3];
    for (int d = 0; d < 3; ++d) {
        from[d] = k[d] > 0 ? -1 : 0;
        to[d] = k[d] + 1 < (size_t)cl->ncell[d] ? 1 : 0;
        if (d >= dim) continue;
        const double b0 = cl->lo[d] + (double)k[d] * cl->cell[d];
        const double el = x[d][i] - b0, eh = b0 + cl->cell[d] - x[d][i];
        e2[d][0] = el > 0 ? el * el : 0.0;
        e2[d][2] = eh > 0 ? eh * eh : 0.0;
    }
    const double thr = r2max * (1.0 + 1e-9);
    int n = 0;
    for (int c = from[2]; c <= to[2]; ++c)
        for (int b = from[1]; b <= to[1]; ++b)
            for (int a = from[0]; a <= to[0]; ++a) {
                if (e2[0][a + 1] + e2[1][b + 1] + e2[2][c + 1] > thr) continue;
                const size_t z = (size_t)((long)k[2] + c), y = (size_t)((long)k[1] + b),
                             w = (size_t)((long)k[0] + a);
                out[n++] = (z * ny + y) * nx + w;
            }
    return n;
}

/* The particles js[0..m-1] of one cell within the radius of particle i (3D, no periodic
 * sides), appended to out from cnt; returns the new count. With AVX-512 eight at a time (the
 * same entries in the same order as the scalar loop). */
#ifdef RY_R2_SIMD
#define RY_SIMD_3D 1
static inline size_t cell_run_simd(const double *const x[3], size_t i, double r2max,
                                   const uint32_t *js, size_t m, uint32_t *out, size_t cnt) {
    const __m512d xi[3] = {_mm512_set1_pd(x[0][i]), _mm512_set1_pd(x[1][i]),
                           _mm512_set1_pd(x[2][i])};
    const __m512d vr = _mm512_set1_pd(r2max);
    const __m256i self = _mm256_set1_epi32((int)i);
    for (size_t k = 0; k < m; k += 8) {
        const __mmask8 lanes = ry_simd_lanes(m - k);
        const __m256i idx = _mm256_maskz_loadu_epi32(lanes, js + k);
        const __mmask8 keep =
            _mm512_mask_cmp_pd_mask(lanes, ry_simd_r2(x, xi, idx, lanes), vr, _CMP_LT_OQ) &
            _mm256_cmpneq_epi32_mask(idx, self);
        cnt += ry_simd_append(keep, idx, _mm512_setzero_pd(), out + cnt, NULL);
    }
    return cnt;
}
#else
#define RY_SIMD_3D 0
static inline size_t cell_run_simd(const double *const x[3], size_t i, double r2max,
                                   const uint32_t *js, size_t m, uint32_t *out, size_t cnt) {
    (void)x, (void)i, (void)r2max, (void)js, (void)m, (void)out;
    return cnt;
}
#endif

/* Neighbours of particle i, written to out, which must have room for one entry more than
 * their number (the stores are unconditional, to avoid mispredicted branches), and sorted;
 * tmp has room for as many (a long row out of order is radix-sorted through it, in passes
 * bytes). */
static inline size_t cells_row(const ry_cell_list *cl, const ry_nb_geom *g, int dim, int per,
                               const double *const x[3], double r2max, size_t i, uint32_t *out,
                               uint32_t *tmp, int passes) {
    size_t cells[27];
    int nc = per ? ry_cells_neighbours(cl, g->periodic, cl->cell_of[i], cells)
                 : near_cells(cl, dim, x, r2max, i, cells);
    size_t cnt = 0;
    const size_t *start = cl->start;
    const uint32_t *order = cl->order;
    for (int q = 0; q < nc; ++q) {
        const size_t c = cells[q], end = start[c + 1];
        if (per)
            for (size_t p = start[c]; p < end; ++p) {
                const uint32_t j = order[p];
                out[cnt] = j;
                cnt += (ry_nb_r2(g, dim, x, i, j) < r2max) & (j != i);
            }
        else if (RY_SIMD_3D && dim == 3)
            cnt = cell_run_simd(x, i, r2max, order + start[c], end - start[c], out, cnt);
        else
            for (size_t p = start[c]; p < end; ++p) {
                const uint32_t j = order[p];
                out[cnt] = j;
                cnt += (ry_nb_r2_open(dim, x, i, j) < r2max) & (j != i);
            }
    }
    if (cnt > 64) {
        /* Runs from each cell are sorted; with particles ordered by cell, the whole list
         * already is, and this is a linear check. Between reorderings the few particles that
         * changed cells leave it nearly sorted, and insertion sorts it in a few moves; past a
         * budget of moves the radix sort takes over. */
        size_t p = 1, moves = 0;
        while (p < cnt && out[p - 1] < out[p]) ++p;
        for (; p < cnt && moves <= 4 * cnt; ++p) {
            const uint32_t v = out[p];
            size_t q = p;
            while (q > 0 && out[q - 1] > v) {
                out[q] = out[q - 1];
                --q;
            }
            out[q] = v;
            moves += p - q;
        }
        if (p < cnt) radix_u32(out, cnt, tmp, passes);
    } else {
        for (size_t p = 1; p < cnt; ++p) {
            uint32_t v = out[p];
            size_t q = p;
            while (q > 0 && out[q - 1] > v) {
                out[q] = out[q - 1];
                --q;
            }
            out[q] = v;
        }
    }
    return cnt;
}

static size_t cells_row_dim(const ry_cell_list *cl, const ry_nb_geom *g, const double *const x[3],
                            double r2max, size_t i, uint32_t *out, uint32_t *tmp, int passes) {
    const int per = g->periodic[0] | g->periodic[1] | g->periodic[2];
    switch (g->dim * 2 + per) {
    case 2:
        return cells_row(cl, g, 1, 0, x, r2max, i, out, tmp, passes);
    case 3:
        return cells_row(cl, g, 1, 1, x, r2max, i, out, tmp, passes);
    case 4:
        return cells_row(cl, g, 2, 0, x, r2max, i, out, tmp, passes);
    case 5:
        return cells_row(cl, g, 2, 1, x, r2max, i, out, tmp, passes);
    case 6:
        return cells_row(cl, g, 3, 0, x, r2max, i, out, tmp, passes);
    default:
        return cells_row(cl, g, 3, 1, x, r2max, i, out, tmp, passes);
    }
}

ry_status ry_nlist_build_cells(ry_nlist *nl, const ry_cell_list *cl, const ry_box *box,
                               double radius, size_t n, const double *const x[3], ry_error *err) {
    RY_CHECK(err, nl != NULL && cl != NULL, RY_ERR_INPUT, "neighbour list: no list given");
    RY_TRY(ry_nb_check_args(box, radius, n, x, err));
    RY_CHECK(err, cl->start != NULL && cl->n == n && cl->dim == box->dim, RY_ERR_INPUT,
             "neighbour list: the cell list was built for %zu particles in %d dimensions, "
             "not %zu in %d",
             cl->n, cl->dim, n, box->dim);
    for (int d = 0; d < box->dim; ++d)
        RY_CHECK(err, cl->ncell[d] < 3 || radius <= cl->cell[d], RY_ERR_INPUT,
                 "neighbour list: radius %g exceeds the cell edge %g in %c: rebuild the cells "
                 "with this radius",
                 radius, cl->cell[d], axis_name[d]);
    RY_TRY(ry_nb_reserve_offsets(nl, n, err));
    ry_nb_geom g;
    ry_nb_geom_init(&g, box);
    const double r2max = radius * radius;
    size_t *off = nl->offset;
    const uint32_t *order = cl->order;
    const long long nn = (long long)n;
    int passes = 1; /* bytes of the largest index */
    while (passes < 4 && (uint64_t)(n - 1) >> (8 * passes)) ++passes;

    /* One pass. Each thread takes a contiguous run of particles in cell order (consecutive
     * ones share their candidate cells, which stay in cache) and writes their rows, one after
     * the other, into a buffer of its own; after the prefix sum of the counts it copies them
     * into place. The distances are computed once (a count pass and a fill pass computed them
     * twice), and the rows are the same. */
    size_t total = 0;
    int failed = 0; /* shared: set by any thread, read after the barriers */
#pragma omp parallel
    {
        const long long nt = omp_get_num_threads(), t = omp_get_thread_num();
        const long long lo = nn * t / nt, hi = nn * (t + 1) / nt;
        uint32_t *buf = NULL, *tmp = NULL;
        size_t len = 0, cap = 0, tcap = 0;
        int mine = 0;
        for (long long p = lo; p < hi && !mine; ++p) {
            const size_t i = order[p];
            size_t cells[27], cand = 1;
            const int nc = ry_cells_neighbours(cl, g.periodic, cl->cell_of[i], cells);
            for (int q = 0; q < nc; ++q) cand += cl->start[cells[q] + 1] - cl->start[cells[q]];
            if (len + cand > cap) {
                const size_t c = 2 * (len + cand) + 1024;
                uint32_t *b = realloc(buf, c * sizeof *b);
                if (!b) {
                    mine = 1;
                    break;
                }
                buf = b;
                cap = c;
            }
            if (cand > tcap) {
                uint32_t *b = realloc(tmp, 2 * cand * sizeof *b);
                if (!b) {
                    mine = 1;
                    break;
                }
                tmp = b;
                tcap = 2 * cand;
            }
            const size_t cnt = cells_row_dim(cl, &g, x, r2max, i, buf + len, tmp, passes);
            off[i + 1] = cnt;
            len += cnt;
        }
        if (mine) {
#pragma omp atomic write
            failed = 1;
        }
#pragma omp barrier
#pragma omp single
        {
            if (!failed) {
                total = ry_nb_prefix_sum(off, n, &nl->max_row);
                ry_error e2;
                if (ry_nb_reserve_j(nl, total, &e2) != RY_OK) failed = 1;
            }
        }
        if (!failed && buf) {
            size_t pos = 0;
            for (long long p = lo; p < hi; ++p) {
                const size_t i = order[p], cnt = off[i + 1] - off[i];
                memcpy(nl->j + off[i], buf + pos, cnt * sizeof *buf);
                pos += cnt;
            }
        }
        free(buf);
        free(tmp);
    }
    RY_CHECK(err, !failed, RY_ERR_NOMEM,
             "neighbour list: no memory for the rows of %zu particles (%zu entries)", n, total);
    nl->n = n;
    return RY_OK;
}
