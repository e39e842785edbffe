/* The case file's `bodies` section: primitives filled with particles. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <stdio.h>
#include <string.h>

#include "util/cell_key.h"
#include "ryushi/geometry.h"
#include "ryushi/stl.h"

static const char *const body_types[] = {"box",  "sphere", "circle", "cylinder",
                                         "tank", "stl",    NULL};
enum { BODY_BOX, BODY_SPHERE, BODY_CIRCLE, BODY_CYLINDER, BODY_TANK, BODY_STL };
static const char *const kind_names[] = {"fluid", "wall", "solid", NULL};
static const char *const fill_names[] = {"volume", "surface", NULL};
enum { FILL_VOLUME, FILL_SURFACE };

static const char *key(char *buf, size_t size, size_t i, const char *name) {
    snprintf(buf, size, "bodies[%zu].%s", i, name);
    return buf;
}

/* The STL file of body i, relative to the case file's folder unless absolute. */
static ry_status stl_path(ry_case *c, const char *file, char **out, ry_error *err) {
    const char *name = ry_case_name(c);
    const char *slash = strrchr(name, '/');
    size_t dir = file[0] == '/' || !slash ? 0 : (size_t)(slash - name) + 1;
    size_t n = strlen(file);
    *out = malloc(dir + n + 1);
    RY_CHECK(err, *out != NULL, RY_ERR_NOMEM, "out of memory");
    memcpy(*out, name, dir);
    memcpy(*out + dir, file, n + 1);
    return RY_OK;
}

typedef struct stl_body {
    const char *file;
    double scale, shift[3];
    long layers; /* 0: fill the volume */
} stl_body;

static ry_status read_stl_keys(ry_case *c, size_t i, int fill, stl_body *b, ry_error *err) {
    char k[96];
    double one = 1, zero[3] = {0, 0, 0};
    long three = 3;
    b->layers = 0;
    RY_TRY(ry_case_string(c, key(k, sizeof k, i, "file"), NULL, &b->file, err));
    RY_TRY(ry_case_positive(c, key(k, sizeof k, i, "scale"), &one, &b->scale, err));
    RY_TRY(ry_case_vector(c, key(k, sizeof k, i, "translate"), zero, 3, b->shift, err));
    if (fill == FILL_SURFACE)
        return ry_case_int(c, key(k, sizeof k, i, "layers"), &three, 1, 20, &b->layers, err);
    if (ry_case_has(c, key(k, sizeof k, i, "layers"))) {
        char where[256];
        return ry_error_set(err, RY_ERR_INPUT, "%s: key '%s': layers needs fill: surface",
                            ry_case_where(c, k, where, sizeof where), k);
    }
    return RY_OK;
}

/* Reads, checks and fills the surface of an STL body. */
static ry_status fill_stl_body(ry_particles *ps, ry_case *c, const stl_body *b, double dx,
                               const ry_body_style *st, size_t *added, ry_error *err) {
    char *path;
    RY_TRY(stl_path(c, b->file, &path, err));
    ry_stl m;
    ry_status s = ry_stl_read(&m, path, err);
    free(path);
    RY_TRY(s);
    ry_stl_transform(&m, b->scale, b->shift);
    s = ry_stl_check(&m, ry_stl_default_tolerance(&m), err);
    if (s == RY_OK) s = ry_fill_stl(ps, &m, dx, (int)b->layers, st, added, err);
    ry_stl_free(&m);
    return s;
}

/* bodies[i].half_space {normal, offset}: of the body's particles just added (the last *added),
 * only those with normal . x >= offset stay (normal made unit): a liquid filled up to a level. */
static ry_status cut_half_space(ry_particles *ps, ry_case *c, size_t i, size_t *added,
                                ry_error *err) {
    char k[96], where[256];
    double nrm[3] = {0, 0, 0}, off, nn = 0;
    RY_TRY(ry_case_vector(c, key(k, sizeof k, i, "half_space.normal"), NULL, ps->dim, nrm, err));
    for (int d = 0; d < ps->dim; ++d) nn += nrm[d] * nrm[d];
    RY_CHECK(err, nn > 0, RY_ERR_INPUT, "%s: key '%s': the normal must not be zero",
             ry_case_where(c, k, where, sizeof where), k);
    RY_TRY(ry_case_double(c, key(k, sizeof k, i, "half_space.offset"), NULL, -1e300, 1e300, &off,
                          err));
    uint8_t *drop = calloc(ps->n ? ps->n : 1, 1);
    RY_CHECK(err, drop != NULL, RY_ERR_NOMEM, "out of memory");
    size_t ndrop = 0;
    for (size_t q = ps->n - *added; q < ps->n; ++q) {
        double h = 0;
        for (int d = 0; d < ps->dim; ++d) h += nrm[d] / sqrt(nn) * ps->f[RY_F_X + d][q];
        if (h < off) {
            drop[q] = 1;
            ++ndrop;
        }
    }
    if (ndrop) ry_particles_remove(ps, drop);
    free(drop);
    *added -= ndrop;
    return RY_OK;
}

static ry_status read_body(ry_particles *ps, ry_case *c, size_t i, double dx,
                           const char *const *material_names, int nmat, ry_error *err) {
    char k[96];
    int dim = ps->dim;
    int type;
    RY_TRY(ry_case_choice(c, key(k, sizeof k, i, "type"), NULL, body_types, &type, err));
    ry_body_style st = {0};
    int fill = FILL_VOLUME;
    if (type == BODY_STL)
        RY_TRY(ry_case_choice(c, key(k, sizeof k, i, "fill"), "volume", fill_names, &fill, err));
    RY_TRY(ry_case_choice(c, key(k, sizeof k, i, "kind"),
                          type == BODY_TANK || fill == FILL_SURFACE ? "wall" : "fluid", kind_names,
                          &st.kind, err));
    if (nmat > 0) {
        RY_TRY(ry_case_choice(c, key(k, sizeof k, i, "material"), material_names[0], material_names,
                              &st.material, err));
    }
    double zero[3] = {0, 0, 0};
    RY_TRY(ry_case_vector(c, key(k, sizeof k, i, "velocity"), zero, dim, st.velocity, err));
    const char *label;
    RY_TRY(ry_case_string(c, key(k, sizeof k, i, "name"), "", &label, err));

    size_t added = 0;
    ry_status s = RY_OK;
    char where[256];
    switch (type) {
    case BODY_BOX: {
        double lo[3], hi[3];
        RY_TRY(ry_case_vector(c, key(k, sizeof k, i, "lo"), NULL, dim, lo, err));
        RY_TRY(ry_case_vector(c, key(k, sizeof k, i, "hi"), NULL, dim, hi, err));
        const int wave = ry_case_has(c, key(k, sizeof k, i, "top_amplitude"));
        if (wave || ry_case_has(c, key(k, sizeof k, i, "top_wavelength"))) {
            double amp, len, width = hi[0] - lo[0], zero1 = 0;
            RY_TRY(ry_case_double(c, key(k, sizeof k, i, "top_amplitude"), &zero1, -1e300, 1e300,
                                  &amp, err));
            RY_TRY(ry_case_positive(c, key(k, sizeof k, i, "top_wavelength"),
                                    width > 0 ? &width : NULL, &len, err));
            s = ry_fill_box_wave(ps, lo, hi, amp, len, dx, &st, &added, err);
        } else
            s = ry_fill_box(ps, lo, hi, dx, &st, &added, err);
        break;
    }
    case BODY_SPHERE:
    case BODY_CIRCLE: {
        double centre[3], r;
        RY_TRY(ry_case_vector(c, key(k, sizeof k, i, "centre"), NULL, dim, centre, err));
        RY_TRY(ry_case_positive(c, key(k, sizeof k, i, "radius"), NULL, &r, err));
        long mode, zero_mode = 0;
        double amp, zero_amp = 0;
        RY_TRY(ry_case_int(c, key(k, sizeof k, i, "mode"), &zero_mode, 0, 16, &mode, err));
        RY_TRY(
            ry_case_double(c, key(k, sizeof k, i, "amplitude"), &zero_amp, -0.5, 0.5, &amp, err));
        RY_CHECK(err, mode != 1, RY_ERR_INPUT,
                 "%s: key '%s': mode 1 is a translation, not a shape (0, or 2 to 16)",
                 ry_case_where(c, key(k, sizeof k, i, "mode"), where, sizeof where), k);
        if (ry_case_has(c, key(k, sizeof k, i, "amplitude")) && mode == 0) {
            return ry_error_set(
                err, RY_ERR_INPUT, "%s: key '%s': amplitude needs a mode (2 to 16)",
                ry_case_where(c, key(k, sizeof k, i, "amplitude"), where, sizeof where), k);
        }
        s = ry_fill_sphere_mode(ps, centre, r, (int)mode, amp, dx, &st, &added, err);
        break;
    }
    case BODY_CYLINDER: {
        double base[3], axis[3], len, r, ri;
        double zero1 = 0;
        RY_CHECK(err, dim == 3, RY_ERR_INPUT, "%s: key '%s': a cylinder needs dimension 3",
                 ry_case_where(c, key(k, sizeof k, i, "type"), where, sizeof where), k);
        RY_TRY(ry_case_vector(c, key(k, sizeof k, i, "base"), NULL, dim, base, err));
        RY_TRY(ry_case_vector(c, key(k, sizeof k, i, "axis"), NULL, dim, axis, err));
        RY_TRY(ry_case_positive(c, key(k, sizeof k, i, "length"), NULL, &len, err));
        RY_TRY(ry_case_positive(c, key(k, sizeof k, i, "radius"), NULL, &r, err));
        RY_TRY(ry_case_double(c, key(k, sizeof k, i, "inner_radius"), &zero1, 0.0, r, &ri, err));
        s = ry_fill_cylinder(ps, base, axis, len, r, ri, dx, &st, &added, err);
        break;
    }
    case BODY_TANK: {
        double lo[3], hi[3];
        long layers, three = 3;
        int open_top, no = 0;
        RY_TRY(ry_case_vector(c, key(k, sizeof k, i, "lo"), NULL, dim, lo, err));
        RY_TRY(ry_case_vector(c, key(k, sizeof k, i, "hi"), NULL, dim, hi, err));
        RY_TRY(ry_case_int(c, key(k, sizeof k, i, "layers"), &three, 1, 20, &layers, err));
        RY_TRY(ry_case_bool(c, key(k, sizeof k, i, "open_top"), &no, &open_top, err));
        double lid[3] = {0, 0, 0};
        int has_lid = ry_case_has(c, key(k, sizeof k, i, "lid_velocity"));
        if (has_lid) {
            RY_TRY(ry_case_vector(c, k, NULL, dim, lid, err));
            char where2[256];
            RY_CHECK(err, !open_top, RY_ERR_INPUT,
                     "%s: key '%s': a sliding lid needs a closed tank (open_top: false)",
                     ry_case_where(c, k, where2, sizeof where2), k);
        }
        s = ry_fill_tank(ps, lo, hi, (int)layers, open_top, has_lid ? lid : NULL, dx, &st, &added,
                         err);
        break;
    }
    case BODY_STL: {
        RY_CHECK(err, dim == 3, RY_ERR_INPUT, "%s: key '%s': an STL body needs dimension 3",
                 ry_case_where(c, key(k, sizeof k, i, "type"), where, sizeof where), k);
        stl_body b;
        RY_TRY(read_stl_keys(c, i, fill, &b, err));
        s = fill_stl_body(ps, c, &b, dx, &st, &added, err);
        break;
    }
    default:
        return ry_error_set(err, RY_ERR_INTERNAL, "unhandled body type %d", type);
    }
    if (s == RY_OK && ry_case_has(c, key(k, sizeof k, i, "half_space")))
        s = cut_half_space(ps, c, i, &added, err);
    snprintf(k, sizeof k, "bodies[%zu]", i);
    if (s != RY_OK) {
        ry_error_prefix(err, "%s: body '%s': ", ry_case_where(c, k, where, sizeof where), k);
        return s;
    }
    RY_CHECK(err, added > 0, RY_ERR_INPUT,
             "%s: body '%s': holds no particle at spacing %g (too small or inverted)",
             ry_case_where(c, k, where, sizeof where), k, dx);
    return RY_OK;
}

/* Overlapping bodies: a particle within half a spacing, in every direction, of a particle of an
 * earlier body (inside its lattice cell; on its faces too for a body that skips them). Particles
 * are binned in cells one spacing wide; a match lies in the same or a neighbouring cell. body[i] is
 * the body of particle i; the particles of a body with skip[body] set that overlap an earlier body
 * are removed instead (so that a fluid can fill the inside of a wall shell made from the same
 * surface). */
static ry_status check_overlaps(ry_particles *ps, ry_case *c, const uint32_t *body,
                                const uint8_t *skip, double dx, ry_error *err) {
    size_t n = ps->n;
    char where[256], k[64];
    ry_cell_key *r = malloc((n ? n : 1) * sizeof *r);
    RY_CHECK(err, r != NULL, RY_ERR_NOMEM, "out of memory");
    for (size_t i = 0; i < n; ++i) {
        r[i] = (ry_cell_key){{0, 0, 0}, (uint32_t)i};
        for (int d = 0; d < ps->dim; ++d) {
            double q = floor(ps->f[RY_F_X + d][i] / dx);
            if (!(fabs(q) < 1e15)) {
                free(r);
                snprintf(k, sizeof k, "bodies[%u]", (unsigned)body[i]);
                return ry_error_set(
                    err, RY_ERR_INPUT, "%s: body '%s': coordinate %g too large for the spacing %g",
                    ry_case_where(c, k, where, sizeof where), k, ps->f[RY_F_X + d][i], dx);
            }
            r[i].c[d] = (int64_t)q;
        }
    }
    qsort(r, n, sizeof *r, ry_cell_key_cmp);
    uint8_t *drop = calloc(n ? n : 1, 1);
    if (!drop) {
        free(r);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
    }
    size_t ndrop = 0;
    /* A body that skips its overlaps leaves out the particles on the faces of an earlier
     * body's cells too: a box whose faces lie half a spacing off the other's lattice would
     * otherwise put two particles half a spacing apart, twice the density. For the error,
     * particles on a face are allowed (a clamp's column on a beam's root face). */
    const double half = 0.5 * dx * (1 - 1e-9), half_skip = 0.5 * dx * (1 + 1e-9);
    const int dz = ps->dim > 2 ? 1 : 0;
    size_t hit = SIZE_MAX, other = 0;
    for (size_t a = 0; a < n; ++a) {
        size_t i = r[a].i;
        const double lim = skip[body[i]] ? half_skip : half;
        for (int ox = -1; ox <= 1; ++ox)
            for (int oy = -1; oy <= 1; ++oy)
                for (int oz = -dz; oz <= dz; ++oz) {
                    int64_t cell[3] = {r[a].c[0] + ox, r[a].c[1] + oy, r[a].c[2] + oz};
                    for (size_t b = ry_cell_key_find(r, n, cell);
                         b < n && ry_cell_same(r[b].c, cell); ++b) {
                        size_t j = r[b].i;
                        if (body[j] >= body[i] || i >= hit) continue;
                        int near = 1;
                        for (int d = 0; d < ps->dim; ++d)
                            near &= fabs(ps->f[RY_F_X + d][i] - ps->f[RY_F_X + d][j]) < lim;
                        if (near && skip[body[i]]) {
                            ndrop += !drop[i];
                            drop[i] = 1;
                        } else if (near) {
                            hit = i;
                            other = j;
                        }
                    }
                }
    }
    free(r);
    if (hit == SIZE_MAX) {
        if (ndrop) ry_particles_remove(ps, drop);
        free(drop);
        return RY_OK;
    }
    free(drop);
    snprintf(k, sizeof k, "bodies[%u]", (unsigned)body[hit]);
    return ry_error_set(err, RY_ERR_INPUT,
                        "%s: body '%s' overlaps body 'bodies[%u]': its particle at (%g, %g%s) "
                        "lies within half a spacing of one of that body's particles",
                        ry_case_where(c, k, where, sizeof where), k, (unsigned)body[other],
                        ps->f[RY_F_X][hit], ps->f[RY_F_Y][hit], ps->dim > 2 ? ", ..." : "");
}

ry_status ry_geometry_from_case(ry_particles *ps, ry_case *c, double dx,
                                const char *const *material_names, int nmat, int64_t **first_id,
                                size_t *nbodies, ry_error *err) {
    size_t n;
    RY_TRY(ry_case_count(c, "bodies", &n, err));
    RY_CHECK(err, n > 0, RY_ERR_INPUT, "%s: key 'bodies': at least one body is required",
             ry_case_name(c));
    size_t *start = malloc((n + 1) * sizeof *start);
    int64_t *ids = malloc((n + 1) * sizeof *ids);
    if (!start || !ids) {
        free(start);
        free(ids);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
    }
    ry_status st = RY_OK;
    for (size_t i = 0; i < n && st == RY_OK; ++i) {
        start[i] = ps->n;
        ids[i] = ps->next_id;
        st = read_body(ps, c, i, dx, material_names, nmat, err);
    }
    start[n] = ps->n;
    ids[n] = ps->next_id;
    uint32_t *body = st == RY_OK ? malloc((ps->n ? ps->n : 1) * sizeof *body) : NULL;
    uint8_t *skip = st == RY_OK ? calloc(n, 1) : NULL;
    if (st == RY_OK && (!body || !skip)) st = ry_error_set(err, RY_ERR_NOMEM, "out of memory");
    static const char *const overlap_names[] = {"error", "skip", NULL};
    for (size_t b = 0; b < n && st == RY_OK; ++b) {
        char k[64];
        int v;
        st = ry_case_choice(c, key(k, sizeof k, b, "overlap"), "error", overlap_names, &v, err);
        skip[b] = (uint8_t)v;
    }
    if (st == RY_OK) {
        for (size_t b = 0; b < n; ++b)
            for (size_t i = start[b]; i < start[b + 1]; ++i) body[i] = (uint32_t)b;
        st = check_overlaps(ps, c, body, skip, dx, err);
    }
    free(skip);
    free(body);
    free(start);
    if (st == RY_OK && first_id) {
        *first_id = ids;
        *nbodies = n;
    } else {
        free(ids);
    }
    return st;
}
