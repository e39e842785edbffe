/* Lattice filling of geometric primitives (see include/ryushi/geometry.h). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/geometry.h"

/* Number of lattice points lo + (i + 1/2) dx inside [a, b] (with a tolerance of 1e-9 spacings,
 * so that a box exactly n spacings wide gets n points). */
static long lattice_count(double a, double b, double dx) {
    double q = floor((b - a) / dx + 1e-9);
    if (!(q > 0)) return 0;
    return q < 1e9 ? (long)q : 1000000000L; /* far beyond any particle limit */
}

/* ceil(q) lattice spacings (0 for q <= 0 or NaN), held below 1e9 as lattice_count is: a
 * body far too large for its spacing reaches fill_lattice's check instead of overflowing. */
static long lattice_span(double q) {
    if (!(q > 0)) return 0;
    return q < 1e9 ? (long)ceil(q) : 1000000000L;
}

typedef int (*inside_fn)(const double *p, const void *ctx);

/* Appends the lattice points of [lo, lo + n dx] for which inside() holds. */
static ry_status fill_lattice(ry_particles *ps, const double *lo, const long *n, double dx,
                              inside_fn inside, const void *ctx, const ry_body_style *st,
                              size_t *added, ry_error *err) {
    int dim = ps->dim;
    long nz = dim > 2 ? n[2] : 1;
    const double total_d = (double)n[0] * (double)n[1] * (double)nz;
    size_t count = 0;
    size_t limit = ry_particles_limit();
    limit = limit < UINT32_MAX / 8 ? 8 * limit : UINT32_MAX;
    RY_CHECK(err, total_d < (double)limit, RY_ERR_RANGE,
             "body would hold %.4g lattice points: spacing too small for its size", total_d);
    const size_t total = (size_t)total_d;
    size_t room = ry_particles_limit() > ps->n ? ry_particles_limit() - ps->n : 0;
    RY_TRY(ry_particles_reserve(ps, ps->n + (total < room ? total : room), err));
    for (long k = 0; k < nz; ++k)
        for (long j = 0; j < n[1]; ++j)
            for (long i = 0; i < n[0]; ++i) {
                double p[3] = {lo[0] + (i + 0.5) * dx, lo[1] + (j + 0.5) * dx,
                               dim > 2 ? lo[2] + (k + 0.5) * dx : 0.0};
                if (inside && !inside(p, ctx)) continue;
                size_t q;
                RY_TRY(ry_particles_add(ps, 1, &q, err));
                for (int d = 0; d < dim; ++d) {
                    ps->f[RY_F_X + d][q] = p[d];
                    ps->f[RY_F_VX + d][q] = st->velocity[d];
                }
                ps->kind[q] = (uint8_t)st->kind;
                ps->material[q] = (uint8_t)st->material;
                ++count;
            }
    if (added) *added = count;
    return RY_OK;
}

ry_status ry_fill_box(ry_particles *ps, const double *lo, const double *hi, double dx,
                      const ry_body_style *st, size_t *added, ry_error *err) {
    long n[3] = {1, 1, 1};
    for (int d = 0; d < ps->dim; ++d) {
        RY_CHECK(err, hi[d] > lo[d], RY_ERR_INPUT, "box: hi must exceed lo in every direction");
        n[d] = lattice_count(lo[d], hi[d], dx);
    }
    return fill_lattice(ps, lo, n, dx, NULL, NULL, st, added, err);
}

typedef struct wave_ctx {
    int up;
    double x0, top, amp, k;
} wave_ctx;

static int below_wave(const double *p, const void *ctx) {
    const wave_ctx *w = ctx;
    return p[w->up] <= w->top + w->amp * cos(w->k * (p[0] - w->x0));
}

ry_status ry_fill_box_wave(ry_particles *ps, const double *lo, const double *hi, double amplitude,
                           double wavelength, double dx, const ry_body_style *st, size_t *added,
                           ry_error *err) {
    RY_CHECK(err, wavelength > 0, RY_ERR_INPUT, "box: top_wavelength must be > 0");
    const int up = ps->dim - 1;
    long n[3] = {1, 1, 1};
    for (int d = 0; d < ps->dim; ++d) {
        RY_CHECK(err, hi[d] > lo[d], RY_ERR_INPUT, "box: hi must exceed lo in every direction");
        n[d] = lattice_count(lo[d], d == up ? hi[d] + fabs(amplitude) : hi[d], dx);
    }
    RY_CHECK(err, fabs(amplitude) < hi[up] - lo[up], RY_ERR_INPUT,
             "box: top_amplitude must be smaller than the box height");
    const double pi = 3.14159265358979323846;
    wave_ctx w = {.up = up, .x0 = lo[0], .top = hi[up], .amp = amplitude, .k = 2 * pi / wavelength};
    return fill_lattice(ps, lo, n, dx, below_wave, &w, st, added, err);
}

typedef struct sphere_ctx {
    int dim, mode;
    double c[3], r2, r, eps;
} sphere_ctx;

/* P_n(x) (3D) or T_n(x) = cos(n acos x) (2D) by their three-term recurrences. */
static double shape_poly(int dim, int n, double x) {
    double a = 1, b = x;
    if (n == 0) return a;
    for (int k = 1; k < n; ++k) {
        const double c = dim > 2 ? ((2 * k + 1) * x * b - k * a) / (k + 1) : 2 * x * b - a;
        a = b;
        b = c;
    }
    return b;
}

static int inside_sphere(const double *p, const void *ctx) {
    const sphere_ctx *s = ctx;
    double r2 = 0;
    for (int d = 0; d < s->dim; ++d) r2 += (p[d] - s->c[d]) * (p[d] - s->c[d]);
    if (s->mode == 0) return r2 <= s->r2;
    const int up = s->dim - 1;
    const double r = sqrt(r2), x = r > 0 ? (p[up] - s->c[up]) / r : 1.0;
    return r <= s->r * (1 + s->eps * shape_poly(s->dim, s->mode, x));
}

ry_status ry_fill_sphere(ry_particles *ps, const double *centre, double radius, double dx,
                         const ry_body_style *st, size_t *added, ry_error *err) {
    return ry_fill_sphere_mode(ps, centre, radius, 0, 0.0, dx, st, added, err);
}

ry_status ry_fill_sphere_mode(ry_particles *ps, const double *centre, double radius, int mode,
                              double amplitude, double dx, const ry_body_style *st, size_t *added,
                              ry_error *err) {
    RY_CHECK(err, radius > 0, RY_ERR_INPUT, "sphere: radius must be > 0");
    RY_CHECK(err, mode == 0 || (mode >= 2 && mode <= 16), RY_ERR_INPUT,
             "sphere: mode must be 0 or 2 to 16");
    RY_CHECK(err, fabs(amplitude) <= 0.5, RY_ERR_INPUT,
             "sphere: amplitude must lie within [-0.5, 0.5]");
    /* The radius of the perturbed surface, R0 (1 + eps Y), scaled so that the body holds the
     * volume of the sphere of the given radius to second order in eps: the mean of Y^2 over the
     * surface is 1/(2n + 1) (3D, Legendre) or 1/2 (2D, cosine). */
    const double eps = mode ? amplitude : 0.0;
    const double scale = ps->dim > 2 ? cbrt(1.0 / (1.0 + 3.0 * eps * eps / (2 * mode + 1)))
                                     : 1.0 / sqrt(1.0 + 0.5 * eps * eps);
    sphere_ctx s = {
        .dim = ps->dim, .mode = mode, .r2 = radius * radius, .r = radius * scale, .eps = eps};
    double lo[3] = {0, 0, 0};
    long n[3] = {1, 1, 1};
    /* A lattice centred on the sphere's centre (points symmetric about it). */
    long m = lattice_span(radius * (1 + fabs(eps)) / dx) + 1;
    for (int d = 0; d < ps->dim; ++d) {
        s.c[d] = centre[d];
        lo[d] = centre[d] - m * dx;
        n[d] = 2 * m;
    }
    return fill_lattice(ps, lo, n, dx, inside_sphere, &s, st, added, err);
}

typedef struct cyl_ctx {
    double base[3], axis[3], length, r2, ri2;
} cyl_ctx;

static int inside_cylinder(const double *p, const void *ctx) {
    const cyl_ctx *c = ctx;
    double v[3] = {p[0] - c->base[0], p[1] - c->base[1], p[2] - c->base[2]};
    double s = v[0] * c->axis[0] + v[1] * c->axis[1] + v[2] * c->axis[2];
    if (s < 0 || s > c->length) return 0;
    double r2 = 0;
    for (int d = 0; d < 3; ++d) {
        double w = v[d] - s * c->axis[d];
        r2 += w * w;
    }
    return r2 <= c->r2 && r2 >= c->ri2;
}

ry_status ry_fill_cylinder(ry_particles *ps, const double *base, const double *axis, double length,
                           double radius, double inner_radius, double dx, const ry_body_style *st,
                           size_t *added, ry_error *err) {
    RY_CHECK(err, ps->dim == 3, RY_ERR_INPUT, "cylinder: only in 3D (use a box in 2D)");
    RY_CHECK(err, radius > 0 && length > 0, RY_ERR_INPUT,
             "cylinder: radius and length must be > 0");
    RY_CHECK(err, inner_radius >= 0 && inner_radius < radius, RY_ERR_INPUT,
             "cylinder: inner_radius must be in [0, radius)");
    double a = sqrt(axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]);
    RY_CHECK(err, a > 0 && isfinite(a), RY_ERR_INPUT, "cylinder: axis must be non-zero");
    cyl_ctx c = {.length = length, .r2 = radius * radius, .ri2 = inner_radius * inner_radius};
    double lo[3], hi[3];
    for (int d = 0; d < 3; ++d) {
        c.base[d] = base[d];
        c.axis[d] = axis[d] / a;
        double e0 = base[d], e1 = base[d] + length * c.axis[d];
        lo[d] = fmin(e0, e1) - radius;
        hi[d] = fmax(e0, e1) + radius;
    }
    long n[3];
    for (int d = 0; d < 3; ++d) n[d] = lattice_span((hi[d] - lo[d]) / dx);
    return fill_lattice(ps, lo, n, dx, inside_cylinder, &c, st, added, err);
}

typedef struct tank_ctx {
    int dim, open_top;
    double lo[3], hi[3];
} tank_ctx;

static int inside_tank_wall(const double *p, const void *ctx) {
    const tank_ctx *t = ctx;
    int inside = 1;
    for (int d = 0; d < t->dim; ++d)
        if (p[d] < t->lo[d] || p[d] > t->hi[d]) inside = 0;
    if (inside) return 0; /* the cavity itself */
    if (t->open_top && p[t->dim - 1] > t->lo[t->dim - 1]) {
        /* Above the floor: keep only points beside the cavity (side walls), not above it. */
        for (int d = 0; d < t->dim - 1; ++d)
            if (p[d] < t->lo[d] || p[d] > t->hi[d]) return 1;
        return 0;
    }
    return 1;
}

ry_status ry_fill_tank(ry_particles *ps, const double *lo, const double *hi, int layers,
                       int open_top, const double *lid_velocity, double dx, const ry_body_style *st,
                       size_t *added, ry_error *err) {
    RY_CHECK(err, layers >= 1, RY_ERR_INPUT, "tank: layers must be >= 1");
    tank_ctx t = {.dim = ps->dim, .open_top = open_top};
    double olo[3] = {0, 0, 0};
    long n[3] = {1, 1, 1};
    for (int d = 0; d < ps->dim; ++d) {
        RY_CHECK(err, hi[d] > lo[d], RY_ERR_INPUT, "tank: hi must exceed lo in every direction");
        long m = lattice_count(lo[d], hi[d], dx);
        t.lo[d] = lo[d];
        t.hi[d] = lo[d] + m * dx;
        olo[d] = lo[d] - layers * dx;
        n[d] = m + 2 * layers;
    }
    size_t first = ps->n;
    RY_TRY(fill_lattice(ps, olo, n, dx, inside_tank_wall, &t, st, added, err));
    if (lid_velocity && !open_top) {
        const int up = ps->dim - 1;
        for (size_t i = first; i < ps->n; ++i) {
            int lid = ps->f[RY_F_X + up][i] > t.hi[up];
            for (int d = 0; d < up; ++d)
                if (ps->f[RY_F_X + d][i] < t.lo[d] || ps->f[RY_F_X + d][i] > t.hi[d]) lid = 0;
            if (lid)
                for (int d = 0; d < ps->dim; ++d) ps->f[RY_F_VX + d][i] = lid_velocity[d];
        }
    }
    return RY_OK;
}
