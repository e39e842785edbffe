/* A closed STL surface filled with particles on the lattice (i + 1/2) dx (see geometry.h).
 *
 * Inside test: a ray along +x through every lattice line (y_j, z_k). Each triangle is projected
 * onto the (y, z) plane; the lattice lines it covers get a crossing at the triangle's x there,
 * signed by the facing of the triangle (+1 where the ray enters an outward-facing surface). The
 * winding number of a lattice point is the sum of the crossings before it; the point is inside
 * when it is non-zero (so an inward-facing surface fills as well).
 *
 * Rays through edges and vertices: the point-in-triangle test evaluates every edge function with
 * the edge's end points in one canonical order, so that the two triangles sharing an edge compute
 * exactly opposite values, and a point exactly on an edge is given to one side only by a fixed
 * rule on the edge direction (the "top-left" rule of rasterisers). A ray through a shared edge or
 * vertex therefore crosses the surface exactly once where it passes through it, and zero or two
 * times (with opposite signs) where it grazes it. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/geometry.h"
#include "ryushi/stl.h"

typedef struct crossing {
    uint64_t line; /* k * ny + j */
    double x;
    int sign;
} crossing;

static int crossing_cmp(const void *p, const void *q) {
    const crossing *a = p, *b = q;
    if (a->line != b->line) return a->line < b->line ? -1 : 1;
    return a->x < b->x ? -1 : a->x > b->x;
}

/* Orientation of r against the segment p -> q in the (y, z) plane, evaluated with the end points
 * in lexicographic order so that the reversed edge gives exactly the negated value. */
static double edge_fn(const double *p, const double *q, const double *r) {
    int swap = p[0] > q[0] || (p[0] == q[0] && p[1] > q[1]);
    const double *s = swap ? q : p, *t = swap ? p : q;
    double w = (t[0] - s[0]) * (r[1] - s[1]) - (t[1] - s[1]) * (r[0] - s[0]);
    return swap ? -w : w;
}

/* Whether a point on the line of the directed edge p -> q (of a counter-clockwise triangle)
 * belongs to the triangle: exactly one of an edge and its reverse says yes. */
static int edge_owns(const double *p, const double *q) {
    double dy = q[0] - p[0], dz = q[1] - p[1];
    return dy > 0 || (dy == 0 && dz < 0);
}

/* Lattice index range [first, last] of the points (i + 1/2) dx in [lo, hi]. */
static int lattice_range(double lo, double hi, double dx, int64_t *first, int64_t *last) {
    double a = ceil(lo / dx - 0.5), b = floor(hi / dx - 0.5);
    if (!(fabs(a) < 1e15 && fabs(b) < 1e15)) return -1;
    *first = (int64_t)a;
    *last = (int64_t)b;
    return 0;
}

typedef struct grid {
    double dx;
    int64_t i0[3]; /* first lattice index per direction */
    int64_t n[3];  /* points per direction */
} grid;

/* Clamped index range of the grid covering [lo, hi] in direction d; 0 when empty. */
static int grid_span(const grid *g, int d, double lo, double hi, int64_t *a, int64_t *b) {
    int64_t f, l;
    if (lattice_range(lo, hi, g->dx, &f, &l)) return 0;
    *a = f - g->i0[d] < 0 ? 0 : f - g->i0[d];
    *b = l - g->i0[d] > g->n[d] - 1 ? g->n[d] - 1 : l - g->i0[d];
    return *a <= *b;
}

static double coord(const grid *g, int d, int64_t i) {
    return ((double)(g->i0[d] + i) + 0.5) * g->dx;
}

enum { MAX_CROSSINGS = 1 << 27 };

static ry_status add_crossings(const ry_stl *m, const grid *g, crossing **out, size_t *count,
                               ry_error *err) {
    size_t n = 0, cap = 1024;
    crossing *cr = malloc(cap * sizeof *cr);
    RY_CHECK(err, cr != NULL, RY_ERR_NOMEM, "out of memory");
    for (size_t t = 0; t < m->ntri; ++t) {
        const double *v = m->v + 9 * t;
        double a[2] = {v[1], v[2]}, b[2] = {v[4], v[5]}, c[2] = {v[7], v[8]};
        double area = edge_fn(a, b, c);
        if (area == 0) continue; /* parallel to the rays */
        int sign = area < 0 ? 1 : -1;
        const double *p[3] = {a, b, c};
        const double *px = v; /* x of vertex k is px[3 k] */
        int order[3] = {0, 1, 2};
        if (area < 0) order[1] = 2, order[2] = 1; /* counter-clockwise in (y, z) */
        int64_t j0, j1, k0, k1;
        if (!grid_span(g, 1, fmin(a[0], fmin(b[0], c[0])), fmax(a[0], fmax(b[0], c[0])), &j0,
                       &j1) ||
            !grid_span(g, 2, fmin(a[1], fmin(b[1], c[1])), fmax(a[1], fmax(b[1], c[1])), &k0, &k1))
            continue;
        for (int64_t k = k0; k <= k1; ++k)
            for (int64_t j = j0; j <= j1; ++j) {
                double r[2] = {coord(g, 1, j), coord(g, 2, k)};
                double w[3], sum = 0;
                int in = 1;
                for (int e = 0; e < 3 && in; ++e) {
                    const double *s = p[order[e]], *q = p[order[(e + 1) % 3]];
                    double f = edge_fn(s, q, r);
                    in = f > 0 || (f == 0 && edge_owns(s, q));
                    w[order[(e + 2) % 3]] = f; /* weight of the opposite vertex */
                    sum += f;
                }
                if (!in || !(sum > 0)) continue;
                if (n == cap) {
                    if (cap >= MAX_CROSSINGS) {
                        free(cr);
                        return ry_error_set(err, RY_ERR_RANGE,
                                            "%s: more than %d ray crossings: spacing too small "
                                            "for the surface",
                                            m->name, (int)MAX_CROSSINGS);
                    }
                    crossing *q = realloc(cr, 2 * cap * sizeof *cr);
                    if (!q) {
                        free(cr);
                        return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
                    }
                    cr = q;
                    cap *= 2;
                }
                double x = (w[0] * px[0] + w[1] * px[3] + w[2] * px[6]) / sum;
                cr[n++] = (crossing){(uint64_t)k * (uint64_t)g->n[1] + (uint64_t)j, x, sign};
            }
    }
    qsort(cr, n, sizeof *cr, crossing_cmp);
    *out = cr;
    *count = n;
    return RY_OK;
}

static double dist2_segment(const double *p, const double *a, const double *b) {
    double ab[3], ap[3], l2 = 0, s = 0;
    for (int d = 0; d < 3; ++d) {
        ab[d] = b[d] - a[d];
        ap[d] = p[d] - a[d];
        l2 += ab[d] * ab[d];
        s += ab[d] * ap[d];
    }
    s = l2 > 0 ? fmin(1.0, fmax(0.0, s / l2)) : 0.0;
    double r = 0;
    for (int d = 0; d < 3; ++d) r += (ap[d] - s * ab[d]) * (ap[d] - s * ab[d]);
    return r;
}

static void cross3(const double *u, const double *w, double *c) {
    c[0] = u[1] * w[2] - u[2] * w[1];
    c[1] = u[2] * w[0] - u[0] * w[2];
    c[2] = u[0] * w[1] - u[1] * w[0];
}

/* Squared distance from p to the triangle v (9 doubles). */
static double dist2_triangle(const double *p, const double *v) {
    double u[3], w[3], nrm[3], n2 = 0, h = 0;
    for (int d = 0; d < 3; ++d) {
        u[d] = v[3 + d] - v[d];
        w[d] = v[6 + d] - v[d];
    }
    cross3(u, w, nrm);
    for (int d = 0; d < 3; ++d) {
        n2 += nrm[d] * nrm[d];
        h += (p[d] - v[d]) * nrm[d];
    }
    if (n2 > 0) {
        double q[3];
        for (int d = 0; d < 3; ++d) q[d] = p[d] - h / n2 * nrm[d];
        int inside = 1;
        for (int k = 0; k < 3 && inside; ++k) {
            const double *a = v + 3 * k, *b = v + 3 * ((k + 1) % 3);
            double e[3], aq[3], c[3];
            for (int d = 0; d < 3; ++d) {
                e[d] = b[d] - a[d];
                aq[d] = q[d] - a[d];
            }
            cross3(e, aq, c);
            inside = c[0] * nrm[0] + c[1] * nrm[1] + c[2] * nrm[2] >= 0;
        }
        if (inside) return h * h / n2;
    }
    double r = INFINITY;
    for (int k = 0; k < 3; ++k) r = fmin(r, dist2_segment(p, v + 3 * k, v + 3 * ((k + 1) % 3)));
    return r;
}

/* Marks inside points (mask 1) within layers * dx of the surface as 2. */
static void mark_shell(const ry_stl *m, const grid *g, double depth, uint8_t *mask) {
    for (size_t t = 0; t < m->ntri; ++t) {
        const double *v = m->v + 9 * t;
        int64_t a[3], b[3];
        int ok = 1;
        for (int d = 0; d < 3 && ok; ++d) {
            double lo = fmin(v[d], fmin(v[3 + d], v[6 + d])) - depth;
            double hi = fmax(v[d], fmax(v[3 + d], v[6 + d])) + depth;
            ok = grid_span(g, d, lo, hi, &a[d], &b[d]);
        }
        if (!ok) continue;
        for (int64_t k = a[2]; k <= b[2]; ++k)
            for (int64_t j = a[1]; j <= b[1]; ++j)
                for (int64_t i = a[0]; i <= b[0]; ++i) {
                    size_t q =
                        ((size_t)k * (size_t)g->n[1] + (size_t)j) * (size_t)g->n[0] + (size_t)i;
                    if (mask[q] != 1) continue;
                    double p[3] = {coord(g, 0, i), coord(g, 1, j), coord(g, 2, k)};
                    if (dist2_triangle(p, v) < depth * depth) mask[q] = 2;
                }
    }
}

ry_status ry_fill_stl(ry_particles *ps, const ry_stl *m, double dx, int layers,
                      const ry_body_style *st, size_t *added, ry_error *err) {
    RY_CHECK(err, ps->dim == 3, RY_ERR_INPUT, "STL surface: only in 3D");
    RY_CHECK(err, dx > 0 && layers >= 0, RY_ERR_INPUT, "STL surface: bad spacing or layers");
    grid g = {.dx = dx};
    double total = 1;
    for (int d = 0; d < 3; ++d) {
        int64_t last;
        RY_CHECK(err, lattice_range(m->lo[d], m->hi[d], dx, &g.i0[d], &last) == 0, RY_ERR_RANGE,
                 "%s: the surface spans too many spacings", m->name);
        g.n[d] = last < g.i0[d] ? 0 : last - g.i0[d] + 1;
        total *= (double)g.n[d];
    }
    double limit = fmin(4294967295.0, 8.0 * (double)ry_particles_limit());
    RY_CHECK(err, total < limit, RY_ERR_RANGE,
             "%s: the surface's bounding box holds %.0f lattice points at spacing %g, more than "
             "%.0f (spacing too small for its size)",
             m->name, total, dx, limit);
    if (total == 0) {
        if (added) *added = 0;
        return RY_OK;
    }
    crossing *cr = NULL;
    size_t ncr = 0;
    RY_TRY(add_crossings(m, &g, &cr, &ncr, err));
    uint8_t *mask = calloc((size_t)total, 1);
    if (!mask) {
        free(cr);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
    }
    size_t c = 0, q = 0, count = 0;
    for (int64_t line = 0; line < g.n[1] * g.n[2]; ++line) {
        int w = 0;
        for (int64_t i = 0; i < g.n[0]; ++i, ++q) {
            double x = coord(&g, 0, i);
            while (c < ncr && cr[c].line == (uint64_t)line && cr[c].x < x) w += cr[c++].sign;
            mask[q] = w != 0;
        }
        while (c < ncr && cr[c].line == (uint64_t)line) ++c;
    }
    free(cr);
    uint8_t keep = 1;
    if (layers > 0) {
        mark_shell(m, &g, layers * dx, mask);
        keep = 2;
    }
    for (size_t i = 0; i < (size_t)total; ++i) count += mask[i] == keep;
    size_t first = 0;
    ry_status s = count ? ry_particles_add(ps, count, &first, err) : RY_OK;
    if (s == RY_OK) {
        size_t p = first;
        q = 0;
        for (int64_t k = 0; k < g.n[2]; ++k)
            for (int64_t j = 0; j < g.n[1]; ++j)
                for (int64_t i = 0; i < g.n[0]; ++i, ++q) {
                    if (mask[q] != keep) continue;
                    double x[3] = {coord(&g, 0, i), coord(&g, 1, j), coord(&g, 2, k)};
                    for (int d = 0; d < 3; ++d) {
                        ps->f[RY_F_X + d][p] = x[d];
                        ps->f[RY_F_VX + d][p] = st->velocity[d];
                    }
                    ps->kind[p] = (uint8_t)st->kind;
                    ps->material[p] = (uint8_t)st->material;
                    ++p;
                }
    }
    free(mask);
    if (added) *added = s == RY_OK ? count : 0;
    return s;
}
