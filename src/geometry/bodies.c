/* The case file's `bodies` section: primitives filled with particles. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ryushi/geometry.h"

static const char *const body_types[] = {"box", "sphere", "circle", "cylinder", "tank", NULL};
enum { BODY_BOX, BODY_SPHERE, BODY_CIRCLE, BODY_CYLINDER, BODY_TANK };
static const char *const kind_names[] = {"fluid", "wall", "solid", NULL};

static const char *key(char *buf, size_t size, size_t i, const char *name) {
    snprintf(buf, size, "bodies[%zu].%s", i, name);
    return buf;
}

static ry_status read_body(ry_particles *ps, ry_case *c, size_t i, double dx,
                           const char *const *material_names, int nmat, ry_error *err) {
    char k[96];
    int dim = ps->dim;
    int type;
    RY_TRY(ry_case_choice(c, key(k, sizeof k, i, "type"), NULL, body_types, &type, err));
    ry_body_style st = {0};
    RY_TRY(ry_case_choice(c, key(k, sizeof k, i, "kind"), type == BODY_TANK ? "wall" : "fluid",
                          kind_names, &st.kind, err));
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
        s = ry_fill_box(ps, lo, hi, dx, &st, &added, err);
        break;
    }
    case BODY_SPHERE:
    case BODY_CIRCLE: {
        double centre[3], r;
        RY_TRY(ry_case_vector(c, key(k, sizeof k, i, "centre"), NULL, dim, centre, err));
        RY_TRY(ry_case_positive(c, key(k, sizeof k, i, "radius"), NULL, &r, err));
        s = ry_fill_sphere(ps, centre, r, dx, &st, &added, err);
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
    default:
        return ry_error_set(err, RY_ERR_INTERNAL, "unhandled body type %d", type);
    }
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

ry_status ry_geometry_from_case(ry_particles *ps, ry_case *c, double dx,
                                const char *const *material_names, int nmat, ry_error *err) {
    size_t n;
    RY_TRY(ry_case_count(c, "bodies", &n, err));
    RY_CHECK(err, n > 0, RY_ERR_INPUT, "%s: key 'bodies': at least one body is required",
             ry_case_name(c));
    for (size_t i = 0; i < n; ++i) RY_TRY(read_body(ps, c, i, dx, material_names, nmat, err));
    return RY_OK;
}
