/* The particle set: structure of arrays over a field table (see include/ryushi/particles.h). */
#include "ryushi/particles.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif

static const char *const kind_names[RY_KIND_COUNT] = {"fluid", "wall", "solid", "inlet", "outlet"};

const char *ry_kind_name(ry_kind kind) {
    return (unsigned)kind < RY_KIND_COUNT ? kind_names[kind] : "unknown";
}

int ry_kind_from_name(const char *name) {
    for (int k = 0; k < RY_KIND_COUNT; ++k)
        if (strcmp(name, kind_names[k]) == 0) return k;
    return -1;
}

static int field_allocated(const ry_particles *ps, int k) {
    return ps->info[k].component < ps->dim && !(ps->info[k].flags & RY_FIELD_ON_REQUEST);
}

static ry_status grow_fields(ry_particles *ps, ry_error *err) {
    if (ps->nfields < ps->cap_fields) return RY_OK;
    int cap = ps->cap_fields ? 2 * ps->cap_fields : 32;
    double **f = realloc(ps->f, (size_t)cap * sizeof *f);
    if (!f) return ry_error_set(err, RY_ERR_NOMEM, "out of memory (particle field table)");
    ps->f = f;
    ry_field_info *info = realloc(ps->info, (size_t)cap * sizeof *info);
    if (!info) return ry_error_set(err, RY_ERR_NOMEM, "out of memory (particle field table)");
    ps->info = info;
    ps->cap_fields = cap;
    return RY_OK;
}

ry_status ry_particles_add_field(ry_particles *ps, const char *name, const char *unit,
                                 int component, int flags, int *id, ry_error *err) {
    int existing = ry_particles_field(ps, name);
    if (existing >= 0) {
        if (id) *id = existing;
        return RY_OK;
    }
    RY_CHECK(err, component >= -1 && component <= 2, RY_ERR_INTERNAL,
             "field '%s': bad component %d", name, component);
    RY_TRY(grow_fields(ps, err));
    int k = ps->nfields;
    ry_field_info *fi = &ps->info[k];
    fi->name = ry_strdup(name);
    fi->unit = ry_strdup(unit);
    fi->component = component;
    fi->flags = flags;
    fi->odd = component >= 0 ? 1u << component : 0u;
    ps->f[k] = NULL;
    if (!fi->name || !fi->unit) {
        free(fi->name);
        free(fi->unit);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory (field '%s')", name);
    }
    if (field_allocated(ps, k) && ps->cap) {
        ps->f[k] = calloc(ps->cap, sizeof(double));
        if (!ps->f[k]) {
            free(fi->name);
            free(fi->unit);
            return ry_error_set(err, RY_ERR_NOMEM, "out of memory (field '%s')", name);
        }
    }
    ps->nfields++;
    if (id) *id = k;
    return RY_OK;
}

ry_status ry_particles_use_field(ry_particles *ps, int k, ry_error *err) {
    RY_CHECK(err, k >= 0 && k < ps->nfields, RY_ERR_INTERNAL, "no field %d", k);
    if (!(ps->info[k].flags & RY_FIELD_ON_REQUEST)) return RY_OK;
    ps->info[k].flags &= ~RY_FIELD_ON_REQUEST;
    if (field_allocated(ps, k) && ps->cap) {
        ps->f[k] = calloc(ps->cap, sizeof(double));
        RY_CHECK(err, ps->f[k] != NULL, RY_ERR_NOMEM, "out of memory (field '%s')",
                 ps->info[k].name);
    }
    return RY_OK;
}

void ry_particles_set_parity(ry_particles *ps, int k, unsigned odd) {
    if (k >= 0 && k < ps->nfields) ps->info[k].odd = odd;
}

int ry_particles_field(const ry_particles *ps, const char *name) {
    for (int k = 0; k < ps->nfields; ++k)
        if (strcmp(ps->info[k].name, name) == 0) return k;
    return -1;
}

ry_status ry_particles_init(ry_particles *ps, int dim, ry_error *err) {
    memset(ps, 0, sizeof *ps);
    RY_CHECK(err, dim >= 1 && dim <= 3, RY_ERR_INPUT, "dimension must be 1, 2 or 3, not %d", dim);
    ps->dim = dim;
    ry_status st = RY_OK;
#define RY_FIELD_ADD_(fid, name, unit, comp, flags)                                                \
    if (st == RY_OK) st = ry_particles_add_field(ps, name, unit, comp, flags, NULL, err);
    RY_CORE_FIELDS(RY_FIELD_ADD_)
#undef RY_FIELD_ADD_
    if (st != RY_OK) ry_particles_free(ps);
    return st;
}

void ry_particles_free(ry_particles *ps) {
    for (int k = 0; k < ps->nfields; ++k) {
        free(ps->f[k]);
        free(ps->info[k].name);
        free(ps->info[k].unit);
    }
    free(ps->f);
    free(ps->info);
    free(ps->id);
    free(ps->kind);
    free(ps->material);
    free(ps->scratch);
    memset(ps, 0, sizeof *ps);
}

static ry_status realloc_array(void **p, size_t count, size_t size, ry_error *err) {
    void *q = realloc(*p, count * size);
    if (!q && count) return ry_error_set(err, RY_ERR_NOMEM, "out of memory (%zu particles)", count);
    *p = q;
    return RY_OK;
}

ry_status ry_particles_reserve(ry_particles *ps, size_t cap, ry_error *err) {
    if (cap <= ps->cap) return RY_OK;
    for (int k = 0; k < ps->nfields; ++k) {
        if (!field_allocated(ps, k)) continue;
        /* (not cleared: ry_particles_add clears what it adds, and untouched room costs no
         * memory) */
        RY_TRY(realloc_array((void **)&ps->f[k], cap, sizeof(double), err));
    }
    RY_TRY(realloc_array((void **)&ps->id, cap, sizeof *ps->id, err));
    RY_TRY(realloc_array((void **)&ps->kind, cap, sizeof *ps->kind, err));
    RY_TRY(realloc_array((void **)&ps->material, cap, sizeof *ps->material, err));
    ps->cap = cap;
    return RY_OK;
}

static size_t particle_limit = UINT32_MAX;

void ry_particles_set_limit(size_t max) {
    particle_limit = max < UINT32_MAX ? max : UINT32_MAX;
}

size_t ry_particles_limit(void) {
    return particle_limit;
}

ry_status ry_particles_add(ry_particles *ps, size_t count, size_t *first, ry_error *err) {
    size_t need = ps->n + count;
    if (need > particle_limit || need < count)
        return ry_error_set(err, RY_ERR_RANGE, "more than %zu particles (the particle limit)",
                            particle_limit);
    if (need > ps->cap) {
        size_t cap = ps->cap ? ps->cap : 1024;
        while (cap < need) cap += cap / 2;
        RY_TRY(ry_particles_reserve(ps, cap, err));
    }
    size_t i0 = ps->n;
    for (int k = 0; k < ps->nfields; ++k)
        if (ps->f[k]) memset(ps->f[k] + i0, 0, count * sizeof(double));
    for (size_t i = i0; i < need; ++i) {
        ps->id[i] = ps->next_id++;
        ps->kind[i] = RY_KIND_FLUID;
        ps->material[i] = 0;
    }
    ps->n = need;
    if (first) *first = i0;
    return RY_OK;
}

void ry_particles_remove(ry_particles *ps, const uint8_t *remove) {
    size_t w = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (remove[i]) continue;
        if (w != i) {
            for (int k = 0; k < ps->nfields; ++k)
                if (ps->f[k]) ps->f[k][w] = ps->f[k][i];
            ps->id[w] = ps->id[i];
            ps->kind[w] = ps->kind[i];
            ps->material[w] = ps->material[i];
        }
        ++w;
    }
    ps->n = w;
}

/* In place, cycle by cycle: element k of each array becomes element order[k], for a set of
 * arrays of 8-byte (p8) and 1-byte (p1) elements walked together, so that each cycle is found
 * once for all of them. seen: a bit per particle, cleared here; first8, first1: room for one
 * element per array. The particles move little between two searches, so most stay and the
 * cycles are short: the walk stays within a few cache lines, and no copy of an array is needed. */
static void permute_arrays(unsigned char *const *p8, int n8, uint8_t *const *p1, int n1,
                           const uint32_t *order, size_t n, uint64_t *seen, uint64_t *first8,
                           uint8_t *first1) {
    memset(seen, 0, (n + 63) / 64 * sizeof *seen);
    for (size_t s = 0; s < n; ++s) {
        /* (a particle that stays is a cycle of its own: no other cycle visits it) */
        if (order[s] == s || (seen[s / 64] >> (s % 64) & 1u)) continue;
        seen[s / 64] |= (uint64_t)1 << (s % 64);
        for (int a = 0; a < n8; ++a) memcpy(&first8[a], p8[a] + 8 * s, 8);
        for (int a = 0; a < n1; ++a) first1[a] = p1[a][s];
        size_t j = s, k;
        while ((k = order[j]) != s) {
            for (int a = 0; a < n8; ++a) memcpy(p8[a] + 8 * j, p8[a] + 8 * k, 8);
            for (int a = 0; a < n1; ++a) p1[a][j] = p1[a][k];
            seen[k / 64] |= (uint64_t)1 << (k % 64);
            j = k;
        }
        for (int a = 0; a < n8; ++a) memcpy(p8[a] + 8 * j, &first8[a], 8);
        for (int a = 0; a < n1; ++a) p1[a][j] = first1[a];
    }
}

ry_status ry_particles_permute(ry_particles *ps, const uint32_t *order, ry_error *err) {
    const size_t n = ps->n, words = (n + 63) / 64;
    const int nt = omp_get_max_threads();
    /* a bit per particle per thread, and a thread's share of the arrays */
    int n8 = 1; /* the ids */
    for (int k = 0; k < ps->nfields; ++k) n8 += ps->f[k] != NULL;
    const size_t need = (size_t)nt * words * sizeof(uint64_t);
    if (ps->scratch_bytes < need) {
        void *s = realloc(ps->scratch, need);
        if (!s && need) return ry_error_set(err, RY_ERR_NOMEM, "out of memory (reordering)");
        ps->scratch = s;
        ps->scratch_bytes = need;
    }
    unsigned char **p8 = malloc((size_t)n8 * sizeof *p8);
    uint64_t *first8 = malloc((size_t)n8 * sizeof *first8);
    if (!p8 || !first8) {
        free(p8);
        free(first8);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory (reordering)");
    }
    int m = 0;
    for (int k = 0; k < ps->nfields; ++k)
        if (ps->f[k]) p8[m++] = (unsigned char *)ps->f[k];
    p8[m++] = (unsigned char *)ps->id;
    uint8_t *const p1[2] = {ps->kind, ps->material};
    uint64_t *seen = ps->scratch;
#pragma omp parallel
    {
        /* each thread walks a share of the 8-byte arrays, the last one also the bytes */
        const int t = omp_get_thread_num(), team = omp_get_num_threads();
        const int a0 = n8 * t / team, a1 = n8 * (t + 1) / team;
        permute_arrays(p8 + a0, a1 - a0, p1, t == team - 1 ? 2 : 0, order, n,
                       seen + (size_t)t * words, first8 + a0, (uint8_t[2]){0, 0});
    }
    free(p8);
    free(first8);
    return RY_OK;
}

size_t ry_particles_bytes_per_particle(const ry_particles *ps) {
    size_t b = sizeof *ps->id + sizeof *ps->kind + sizeof *ps->material;
    for (int k = 0; k < ps->nfields; ++k)
        if (field_allocated(ps, k)) b += sizeof(double);
    return b;
}

double ry_particles_kinetic_energy(const ry_particles *ps, int dim, ry_kind kind,
                                   const double *mass_scale) {
    return ry_particles_kinetic_energy_of(ps, dim, kind, mass_scale, NULL);
}

static int cmp_coord(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The drop's shape moment of the given order about its centroid: order 4,
 * <x^4+y^4+z^4>/<r^4> - 3/5 (2D <x^4+y^4>/<r^4> - 3/4); order 2, <z^2 - (x^2+y^2)/2>/<r^2> in 3D
 * and <y^2 - x^2>/(2 <r^2>) in 2D. */
static double shape_moment(const ry_particles *ps, int dim, ry_kind kind, double dx, int order) {
    size_t n = 0;
    for (size_t i = 0; i < ps->n; ++i) n += ps->kind[i] == kind;
    if (n == 0) return NAN;
    if (dim < 2) return 0.0;
    /* the drop's middle, which particles thrown off do not move: the median of each coordinate */
    double *v = malloc(n * sizeof *v), m[3] = {0, 0, 0}, c[3] = {0, 0, 0};
    if (!v) return NAN;
    for (int d = 0; d < dim; ++d) {
        size_t k = 0;
        for (size_t i = 0; i < ps->n; ++i)
            if (ps->kind[i] == kind) v[k++] = ps->f[RY_F_X + d][i];
        qsort(v, n, sizeof *v, cmp_coord);
        m[d] = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
    }
    free(v);
    /* the drop: within twice the equivalent radius (pi R^2 = N dx^2, 4/3 pi R^3 = N dx^3) */
    const double pi = 3.14159265358979323846;
    const double R = dim > 2 ? dx * cbrt(3.0 * (double)n / (4.0 * pi)) : dx * sqrt((double)n / pi);
    const double rmax2 = 4.0 * R * R;
    const int up = dim - 1;
    for (int pass = 0; pass < 2; ++pass) { /* its centroid, then the moments about it */
        double num = 0, den = 0, sum[3] = {0, 0, 0};
        size_t k = 0;
        for (size_t i = 0; i < ps->n; ++i) {
            if (ps->kind[i] != kind) continue;
            double q4 = 0, r2 = 0, x[3] = {0, 0, 0};
            for (int d = 0; d < dim; ++d) {
                x[d] = ps->f[RY_F_X + d][i] - (pass ? c[d] : m[d]);
                const double x2 = x[d] * x[d];
                q4 += x2 * x2;
                r2 += x2;
            }
            if (r2 > rmax2) continue;
            for (int d = 0; d < dim; ++d) sum[d] += ps->f[RY_F_X + d][i];
            if (order == 4) {
                num += q4;
                den += r2 * r2;
            } else {
                const double z2 = x[up] * x[up];
                num += dim > 2 ? z2 - 0.5 * (r2 - z2) : 0.5 * (z2 - (r2 - z2));
                den += r2;
            }
            ++k;
        }
        if (k == 0) return NAN;
        if (pass) {
            if (!(den > 0)) return 0.0;
            return order == 4 ? num / den - (dim > 2 ? 0.6 : 0.75) : num / den;
        }
        for (int d = 0; d < dim; ++d) c[d] = sum[d] / (double)k;
    }
    return NAN;
}

double ry_particles_shape_m4(const ry_particles *ps, int dim, ry_kind kind, double dx) {
    return shape_moment(ps, dim, kind, dx, 4);
}

double ry_particles_shape_p2(const ry_particles *ps, int dim, ry_kind kind, double dx) {
    return shape_moment(ps, dim, kind, dx, 2);
}

double ry_particles_kinetic_energy_of(const ry_particles *ps, int dim, ry_kind kind,
                                      const double *mass_scale, const uint8_t *skip) {
    double e = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != kind || (skip && skip[i])) continue;
        double v2 = 0;
        for (int d = 0; d < dim; ++d) v2 += ps->f[RY_F_VX + d][i] * ps->f[RY_F_VX + d][i];
        e += 0.5 * ps->f[RY_F_MASS][i] * (mass_scale ? mass_scale[i] : 1.0) * v2;
    }
    return e;
}
