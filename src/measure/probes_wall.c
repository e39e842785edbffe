/* Measurements on the wall: the share of the wetted wall the injected fluid covers (the probe
 * oil_wall_contact and the retina regions' coverage_NAME, case section `retina_regions`), and
 * the share a given contact line's height would cover (ry_wall_share_above). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "measure/probes_internal.h"
#include "ryushi/open_boundary.h"
#include "ryushi/probes.h"
#include "ryushi/sim.h"

/* Whether wall particle i belongs to a port: within half the diagonal of an open boundary's
 * cross-section plus the kernel support radius of the line through the zone's centre along its
 * flow axis (the channel leading to the port and the collar around it). */
static int near_port_axis(const ry_sim *sim, size_t i) {
    for (int b = 0; b < sim->nopen; ++b) {
        const ry_open_boundary *o = &sim->open[b];
        double half2 = 0, r2 = 0;
        for (int d = 0; d < sim->dim; ++d) {
            if (d == o->axis) continue;
            const double w = 0.5 * (o->hi[d] - o->lo[d]);
            const double x = sim->ps.f[RY_F_X + d][i] - 0.5 * (o->lo[d] + o->hi[d]);
            half2 += w * w;
            r2 += x * x;
        }
        const double rmax = sqrt(half2) + sim->kernel.radius;
        if (r2 <= rmax * rmax) return 1;
    }
    return 0;
}

/* Whether the point (x[0][i], x[1][i], x[2][i]) lies in the cone: its direction from the cone's
 * centre at an angle to its unit direction of cosine cos_half or more. */
static int in_cone(const ry_region *cone, const double *const x[3], size_t i) {
    double c = 0, r2 = 0;
    for (int d = 0; d < 3; ++d) {
        const double e = x[d][i] - cone->centre[d];
        c += e * cone->dir[d];
        r2 += e * e;
    }
    return r2 > 0 && c >= cone->cos_half * sqrt(r2);
}

/* Among the wall particles with a fluid particle within the kernel support (the wetted wall,
 * e.g. the retina), the fraction whose nearest fluid particle is of the second material (the
 * injected fluid, e.g. silicone oil), or with the cone `above` the fraction in that cone (in_cone).
 * Wall particles of the ports (near_port_axis) do not count, nor, with a region, those outside
 * it.
 * Searches cells of its own (ry_probe_current_cells). */
static ry_status wall_contact(const ry_sim *sim, const ry_region *reg, const ry_region *above,
                              double *v, ry_error *err) {
    const ry_particles *ps = &sim->ps;
    const double rad2 = sim->kernel.radius * sim->kernel.radius;
    ry_cell_list cl;
    const double *x[3];
    int per[3];
    RY_TRY(ry_probe_current_cells(sim, sim->kernel.radius, &cl, x, per, err));
    size_t wet = 0, oil = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_WALL || near_port_axis(sim, i)) continue;
        if (reg && !in_cone(reg, x, i)) continue;
        double best = rad2;
        int mat = -1;
        size_t cells[27];
        const int nc = ry_cells_neighbours(&cl, per, cl.cell_of[i], cells);
        for (int c = 0; c < nc; ++c)
            for (size_t q = cl.start[cells[c]]; q < cl.start[cells[c] + 1]; ++q) {
                const uint32_t j = cl.order[q];
                if (ps->kind[j] != RY_KIND_FLUID) continue;
                double dx[3] = {0, 0, 0}, r2 = 0;
                for (int d = 0; d < sim->dim; ++d) dx[d] = x[d][i] - x[d][j];
                ry_box_min_image(&sim->box, dx);
                for (int d = 0; d < sim->dim; ++d) r2 += dx[d] * dx[d];
                if (r2 < best) {
                    best = r2;
                    mat = ps->material[j];
                }
            }
        if (mat < 0) continue;
        ++wet;
        oil += above ? in_cone(above, x, i) : mat == 1;
    }
    ry_cells_free(&cl);
    *v = wet ? (double)oil / (double)wet : 0.0;
    return RY_OK;
}

static ry_status probe_oil_wall_contact(const ry_sim *sim, double *v, ry_error *err) {
    RY_CHECK(err, sim->nmat >= 2, RY_ERR_INPUT,
             "measurement 'oil_wall_contact' needs two materials (the second is the injected one)");
    return wall_contact(sim, NULL, NULL, v, err);
}

const ry_probe ry_probe_oil_wall_contact = {
    "oil_wall_contact",
    "fraction of the wetted wall (without the ports' channels and collars) whose nearest fluid "
    "particle is of the second material",
    probe_oil_wall_contact, NULL, 0};

ry_status ry_wall_share_above(const ry_sim *sim, const ry_region *reg, const double centre[3],
                              const double up[3], double cos_min, double *share, ry_error *err) {
    ry_region above = {.cos_half = cos_min};
    double nu = 0;
    for (int d = 0; d < 3; ++d) nu += up[d] * up[d];
    RY_CHECK(err, nu > 0, RY_ERR_INPUT, "ry_wall_share_above: the direction up must not be zero");
    for (int d = 0; d < 3; ++d) {
        above.centre[d] = centre[d];
        above.dir[d] = up[d] / sqrt(nu);
    }
    return wall_contact(sim, reg, &above, share, err);
}

/* coverage_NAME: oil_wall_contact over the wall particles of retina region `item`. */
static ry_status probe_region_coverage(const ry_sim *sim, int item, double *v, ry_error *err) {
    RY_CHECK(err, item >= 0 && item < sim->nregions, RY_ERR_INTERNAL, "no retina region %d", item);
    return wall_contact(sim, &sim->regions[item], NULL, v, err);
}

/* The case section `retina_regions`: each item's name, direction, half angle [degrees] and
 * centre (default the origin); its probe coverage_NAME. */
ry_status ry_regions_setup(ry_sim *sim, ry_case *c, ry_error *err) {
    size_t n = 0;
    if (!ry_case_has(c, "retina_regions")) return RY_OK;
    RY_TRY(ry_case_count(c, "retina_regions", &n, err));
    char k[96], where[256];
    RY_CHECK(err, sim->dim == 3 && sim->nmat >= 2 && n <= 64, RY_ERR_INPUT,
             "%s: key 'retina_regions': needs dimension 3 and two materials (the second the "
             "injected one), and at most 64 regions",
             ry_case_where(c, "retina_regions", where, sizeof where));
    sim->regions = calloc(n ? n : 1, sizeof *sim->regions);
    RY_CHECK(err, sim->regions != NULL, RY_ERR_NOMEM, "out of memory");
    for (size_t r = 0; r < n; ++r) {
        ry_region *g = &sim->regions[r];
        const char *name;
        double zero[3] = {0, 0, 0}, half, nd = 0;
        snprintf(k, sizeof k, "retina_regions[%zu].name", r);
        RY_TRY(ry_case_string(c, k, NULL, &name, err));
        RY_CHECK(err,
                 name[0] && strlen(name) < 48 &&
                     strspn(name, "abcdefghijklmnopqrstuvwxyz"
                                  "ABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                  "0123456789_") == strlen(name),
                 RY_ERR_INPUT,
                 "%s: key '%s': a region's name is 1 to 47 letters, digits or '_' (it names "
                 "the column coverage_NAME)",
                 ry_case_where(c, k, where, sizeof where), k);
        for (size_t q = 0; q < r; ++q)
            RY_CHECK(err, strcmp(sim->regions[q].name, name) != 0, RY_ERR_INPUT,
                     "%s: key '%s': region '%s' is named twice",
                     ry_case_where(c, k, where, sizeof where), k, name);
        snprintf(k, sizeof k, "retina_regions[%zu].direction", r);
        RY_TRY(ry_case_vector(c, k, NULL, 3, g->dir, err));
        for (int d = 0; d < 3; ++d) nd += g->dir[d] * g->dir[d];
        RY_CHECK(err, nd > 0, RY_ERR_INPUT, "%s: key '%s': the direction must not be zero",
                 ry_case_where(c, k, where, sizeof where), k);
        for (int d = 0; d < 3; ++d) g->dir[d] /= sqrt(nd);
        snprintf(k, sizeof k, "retina_regions[%zu].half_angle", r);
        RY_TRY(ry_case_double(c, k, NULL, 0.0, 180.0, &half, err));
        RY_CHECK(err, half > 0, RY_ERR_INPUT, "%s: key '%s': must be > 0 degrees",
                 ry_case_where(c, k, where, sizeof where), k);
        g->cos_half = cos(half * 3.14159265358979323846 / 180.0);
        snprintf(k, sizeof k, "retina_regions[%zu].centre", r);
        RY_TRY(ry_case_vector(c, k, zero, 3, g->centre, err));
        const size_t len = strlen(name);
        g->name = malloc(2 * len + 16);
        RY_CHECK(err, g->name != NULL, RY_ERR_NOMEM, "out of memory");
        memcpy(g->name, name, len + 1);
        char *column = g->name + len + 1; /* coverage_NAME, in the same block */
        snprintf(column, len + 15, "coverage_%s", name);
        g->probe = (ry_probe){column, "share of the region's wetted wall the injected fluid covers",
                              NULL, probe_region_coverage, (int)r};
        sim->nregions = (int)r + 1;
    }
    return RY_OK;
}

void ry_regions_free(ry_sim *sim) {
    for (int r = 0; r < sim->nregions; ++r) free(sim->regions[r].name);
    free(sim->regions);
    sim->regions = NULL;
    sim->nregions = 0;
}
