/* Simulation set-up from a case file: materials, domain, measurements, scheme, guard and
 * checkpoints. */
#define _POSIX_C_SOURCE 200809L
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "sim/symmetry.h"
#include "sim/writer.h"
#include "ryushi/geometry.h"
#include "ryushi/sim.h"
#include "core/guard_check.h"
#include "neighbor/neighbor_internal.h"
#include "ryushi/clock.h"
#include "ryushi/open_boundary.h"
#include "ryushi/probes.h"
#include "ryushi/run.h"
#include "ryushi/schemes.h"
#include "ryushi/rheology.h"

static ry_status read_materials(ry_sim *sim, ry_case *c, ry_error *err) {
    size_t n;
    char k[96], where[256];
    RY_TRY(ry_case_count(c, "materials", &n, err));
    RY_CHECK(err, n > 0, RY_ERR_INPUT, "%s: key 'materials': at least one material is required",
             ry_case_name(c));
    RY_CHECK(err, n <= 255, RY_ERR_INPUT, "%s: key 'materials': at most 255 materials",
             ry_case_name(c));
    sim->mat = calloc(n, sizeof *sim->mat);
    RY_CHECK(err, sim->mat != NULL, RY_ERR_NOMEM, "out of memory");
    sim->nmat = (int)n;
    double zero = 0;
    for (size_t i = 0; i < n; ++i) {
        ry_material *m = &sim->mat[i];
        const char *name;
        snprintf(k, sizeof k, "materials[%zu].name", i);
        RY_TRY(ry_case_string(c, k, NULL, &name, err));
        for (size_t j = 0; j < i; ++j)
            RY_CHECK(err, strcmp(sim->mat[j].name, name) != 0, RY_ERR_INPUT,
                     "%s: key '%s': material '%s' is defined twice",
                     ry_case_where(c, k, where, sizeof where), k, name);
        RY_CHECK(err, name[0] != '\0', RY_ERR_INPUT, "%s: key '%s': empty material name",
                 ry_case_where(c, k, where, sizeof where), k);
        m->name = ry_strdup(name);
        RY_CHECK(err, m->name != NULL, RY_ERR_NOMEM, "out of memory");
        snprintf(k, sizeof k, "materials[%zu].density", i);
        RY_TRY(ry_case_positive(c, k, NULL, &m->density, err));
        snprintf(k, sizeof k, "materials[%zu].viscosity", i);
        RY_TRY(ry_case_double(c, k, &zero, 0.0, INFINITY, &m->viscosity, err));
        char prefix[48];
        snprintf(prefix, sizeof prefix, "materials[%zu]", i);
        RY_TRY(ry_rheology_read(c, prefix, &m->rheo, err));
        RY_CHECK(err, !ry_rheology_generalised(&m->rheo) || !ry_case_has(c, k), RY_ERR_INPUT,
                 "%s: key '%s': not used with rheology.model %s (the viscosity follows from the "
                 "shear rate)",
                 ry_case_where(c, k, where, sizeof where), k, ry_rheology_names[m->rheo.model]);
    }
    return RY_OK;
}

static const char *const kernel_names[] = {"cubic", "quintic",  "wendland_c2", "wendland_c4",
                                           "lucy",  "gaussian", NULL};

static ry_status read_domain(ry_sim *sim, ry_case *c, ry_error *err) {
    ry_box *b = &sim->box;
    memset(b, 0, sizeof *b);
    b->dim = sim->dim;
    const ry_particles *ps = &sim->ps;
    double lo[3] = {0}, hi[3] = {0};
    for (int d = 0; d < sim->dim; ++d) {
        lo[d] = INFINITY;
        hi[d] = -INFINITY;
        for (size_t i = 0; i < ps->n; ++i) {
            lo[d] = fmin(lo[d], ps->f[RY_F_X + d][i]);
            hi[d] = fmax(hi[d], ps->f[RY_F_X + d][i]);
        }
    }
    /* Default: the particles' bounding box, widened by a quarter of its size on every side
     * (and by at least a few spacings). */
    double dlo[3], dhi[3];
    for (int d = 0; d < sim->dim; ++d) {
        double w = fmax(0.25 * (hi[d] - lo[d]), 4 * sim->dx);
        dlo[d] = lo[d] - w;
        dhi[d] = hi[d] + w;
    }
    RY_TRY(ry_case_vector(c, "domain.lo", dlo, sim->dim, b->lo, err));
    RY_TRY(ry_case_vector(c, "domain.hi", dhi, sim->dim, b->hi, err));
    static const char *const pk[3] = {"domain.periodic_x", "domain.periodic_y",
                                      "domain.periodic_z"};
    int no = 0;
    char where[256];
    for (int d = 0; d < sim->dim; ++d) {
        RY_CHECK(err, b->hi[d] > b->lo[d], RY_ERR_INPUT,
                 "%s: key 'domain.hi': must exceed domain.lo in every direction",
                 ry_case_where(c, "domain.hi", where, sizeof where));
        RY_TRY(ry_case_bool(c, pk[d], &no, &b->periodic[d], err));
        if (b->periodic[d])
            RY_CHECK(err, b->hi[d] - b->lo[d] >= 2 * sim->kernel.radius, RY_ERR_INPUT,
                     "%s: key '%s': periodic length must be at least two support radii",
                     ry_case_where(c, pk[d], where, sizeof where), pk[d]);
    }
    RY_TRY(ry_symmetry_read(sim, c, err));
    for (size_t i = 0; i < ps->n; ++i)
        for (int d = 0; d < sim->dim; ++d) {
            double x = ps->f[RY_F_X + d][i];
            RY_CHECK(
                err,
                x >= b->lo[d] &&
                        x<b->hi[d], RY_ERR_INPUT,
                          "%s: key 'domain': particle %lld of body at (%g, %g%s) lies outside the "
                          "domain",
                          ry_case_where(c, "domain", where, sizeof where), (long long)ps->id[i],
                          ps->f[RY_F_X][i], ps->f[RY_F_Y][i], sim->dim> 2
                    ? ", ..."
                    : "");
        }
    return RY_OK;
}

/* The `droplet` section: material (name), tip (height along the last axis) and axis (the
 * nozzle's horizontal position, dim - 1 numbers, default 0). */
static ry_status read_droplet(ry_sim *sim, ry_case *c, ry_error *err) {
    sim->droplet_material = -1;
    if (!ry_case_has(c, "droplet")) return RY_OK;
    const char *name;
    char where[256];
    RY_TRY(ry_case_string(c, "droplet.material", NULL, &name, err));
    for (int m = 0; m < sim->nmat; ++m)
        if (strcmp(sim->mat[m].name, name) == 0) sim->droplet_material = m;
    RY_CHECK(err, sim->droplet_material >= 0, RY_ERR_INPUT,
             "%s: key 'droplet.material': no material named '%s'",
             ry_case_where(c, "droplet.material", where, sizeof where), name);
    const double origin[2] = {0, 0};
    RY_TRY(ry_case_vector(c, "droplet.axis", origin, sim->dim - 1, sim->droplet_axis, err));
    return ry_case_double(c, "droplet.tip", NULL, -INFINITY, INFINITY, &sim->droplet_tip, err);
}

/* time.stop_when: {quantity: NAME, above: V} or {quantity: NAME, below: V}, NAME one of the
 * quantities in `measure`. */
static ry_status read_stop_when(ry_sim *sim, ry_case *c, ry_error *err) {
    sim->stop_probe = -1;
    sim->stop_reason[0] = 0;
    if (!ry_case_has(c, "time.stop_when")) return RY_OK;
    char where[512];
    const int above = ry_case_has(c, "time.stop_when.above"),
              below = ry_case_has(c, "time.stop_when.below");
    RY_CHECK(err, above + below == 1, RY_ERR_INPUT,
             "%s: key 'time.stop_when' needs one of 'above' and 'below'",
             ry_case_where(c, "time.stop_when", where, sizeof where));
    const char **names = calloc((size_t)sim->nprobes + 1, sizeof *names);
    RY_CHECK(err, names != NULL, RY_ERR_NOMEM, "out of memory");
    for (int k = 0; k < sim->nprobes; ++k) names[k] = sim->probes[k]->name;
    const char *q = NULL;
    ry_status st = ry_case_string(c, "time.stop_when.quantity", NULL, &q, err);
    int which = -1;
    for (int k = 0; st == RY_OK && k < sim->nprobes; ++k)
        if (strcmp(q, names[k]) == 0) which = k;
    free(names);
    RY_TRY(st);
    RY_CHECK(err, which >= 0, RY_ERR_INPUT,
             "%s: key 'time.stop_when.quantity': '%s' is not measured (add it to 'measure')",
             ry_case_where(c, "time.stop_when.quantity", where, sizeof where), q);
    sim->stop_probe = which;
    sim->stop_above = above;
    return ry_case_double(c, above ? "time.stop_when.above" : "time.stop_when.below", NULL,
                          -INFINITY, INFINITY, &sim->stop_value, err);
}

static ry_status read_probes(ry_sim *sim, ry_case *c, ry_error *err) {
    size_t n;
    char k[64];
    RY_TRY(read_droplet(sim, c, err));
    RY_TRY(ry_regions_setup(sim, c, err));
    RY_TRY(ry_case_count(c, "measure", &n, err));
    const ry_probe *const *all = ry_probes();
    int count = 0;
    while (all[count]) ++count;
    const char **names = calloc((size_t)count + 1, sizeof *names);
    sim->probes = calloc(n + (size_t)sim->nregions + 1, sizeof *sim->probes);
    if (!names || !sim->probes) {
        free(names);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
    }
    for (int i = 0; i < count; ++i) names[i] = all[i]->name;
    ry_status st = RY_OK;
    for (size_t i = 0; i < n && st == RY_OK; ++i) {
        int which;
        snprintf(k, sizeof k, "measure[%zu]", i);
        st = ry_case_choice(c, k, NULL, names, &which, err);
        if (st == RY_OK) sim->probes[sim->nprobes++] = all[which];
    }
    free(names);
    RY_TRY(st);
    /* each retina region's coverage, after the measurements listed */
    for (int r = 0; r < sim->nregions; ++r) sim->probes[sim->nprobes++] = &sim->regions[r].probe;
    return read_stop_when(sim, c, err);
}

/* Each measurement once on the state set up, so that one the case cannot give (a polymer stress
 * without a visco-elastic material, a scheme's iterations under another scheme) stops the
 * set-up with the key that names it, before anything is written. */
static ry_status check_probes(ry_sim *sim, ry_case *c, ry_error *err) {
    for (int k = 0; k < sim->nprobes; ++k) {
        double v;
        const ry_status st = ry_probe_eval(sim->probes[k], sim, &v, err);
        if (st != RY_ERR_INPUT) {
            RY_TRY(st);
            continue;
        }
        char key[64], where[256], msg[RY_ERROR_MSG_MAX];
        snprintf(key, sizeof key, "measure[%d]", k);
        snprintf(msg, sizeof msg, "%s", err ? err->msg : "");
        return ry_error_set(err, RY_ERR_INPUT, "%s: key '%s': %s",
                            ry_case_where(c, key, where, sizeof where), key, msg);
    }
    return RY_OK;
}

static ry_status read_scheme(ry_sim *sim, ry_case *c, ry_error *err) {
    const ry_scheme_type *const *all = ry_schemes();
    int count = 0;
    while (all[count]) ++count;
    const char **names = calloc((size_t)count + 1, sizeof *names);
    RY_CHECK(err, names != NULL, RY_ERR_NOMEM, "out of memory");
    for (int i = 0; i < count; ++i) names[i] = all[i]->name;
    int which;
    ry_status st = ry_case_choice(c, "scheme.name", NULL, names, &which, err);
    free(names);
    RY_TRY(st);
    sim->scheme = all[which];
    /* Non-Newtonian materials need a scheme that carries them (docs/reference/rheology.md). */
    const int rheology = (sim->scheme->caps & RY_SCHEME_RHEOLOGY) != 0;
    for (int m = 0; m < sim->nmat && !rheology; ++m) {
        if (sim->mat[m].rheo.model == RY_RHEO_NEWTONIAN) continue;
        char k[96], where[256], able[128] = "";
        for (int i = 0; i < count; ++i)
            if (all[i]->caps & RY_SCHEME_RHEOLOGY)
                snprintf(able + strlen(able), sizeof able - strlen(able), "%s%s",
                         able[0] ? ", " : "", all[i]->name);
        snprintf(k, sizeof k, "materials[%d].rheology.model", m);
        return ry_error_set(err, RY_ERR_INPUT,
                            "%s: key '%s': %s is available with schemes %s (this case uses %s)",
                            ry_case_where(c, k, where, sizeof where), k,
                            ry_rheology_names[sim->mat[m].rheo.model], able, sim->scheme->name);
    }
    return sim->scheme->init(sim, c, &sim->scheme_state, err);
}

/* Limits of a sound run; the scheme's init may have set defaults (0: no limit). */
static ry_status read_guard(ry_sim *sim, ry_case *c, ry_error *err) {
    ry_guard *g = &sim->guard;
    double vmax = g->max_speed, rmin = g->rho_min, rmax = g->rho_max, out = 0.01, dtr = 1e-4;
    long every = 10; /* a copy every step would cost ~7 % of a WCSPH step */
    char where[256];
    RY_TRY(ry_case_double(c, "guard.max_speed", &vmax, 0.0, 1e300, &g->max_speed, err));
    RY_TRY(ry_case_double(c, "guard.density_min", &rmin, 0.0, 1.0, &g->rho_min, err));
    RY_TRY(ry_case_double(c, "guard.density_max", &rmax, 0.0, 1e300, &g->rho_max, err));
    RY_CHECK(err, g->rho_max == 0 || g->rho_max > 1, RY_ERR_INPUT,
             "%s: key 'guard.density_max': must exceed 1 (a ratio to the reference density) or "
             "be 0 (no limit)",
             ry_case_where(c, "guard.density_max", where, sizeof where));
    RY_TRY(ry_case_double(c, "guard.max_outside_fraction", &out, 0.0, 1.0, &g->max_outside_fraction,
                          err));
    RY_TRY(ry_case_double(c, "guard.min_dt_ratio", &dtr, 0.0, 0.999999, &g->min_dt_ratio, err));
    static const char *const modes[] = {"replay", "memory", "none", NULL};
    RY_TRY(ry_case_choice(c, "guard.last_good", "replay", modes, &g->last_good, err));
    RY_TRY(ry_case_int(c, "guard.snapshot_every", &every, 0, 1000000000L, &every, err));
    g->snapshot_every = g->last_good == RY_LAST_GOOD_MEMORY ? (int)every : 0;
    return RY_OK;
}

static ry_status read_checkpoint(ry_sim *sim, ry_case *c, ry_error *err) {
    ry_ckpt_policy *k = &sim->ckpt;
    double zero = 0, ten_min = 600; /* (bounds the replay of a last good state) */
    long none = 0, keep = 2;
    int yes = 1;
    RY_TRY(ry_case_double(c, "checkpoint.interval", &zero, 0.0, 1e300, &k->interval, err));
    RY_TRY(
        ry_case_int(c, "checkpoint.every_steps", &none, 0, 1000000000000L, &k->every_steps, err));
    RY_TRY(ry_case_double(c, "checkpoint.wall_interval", &ten_min, 0.0, 1e300, &k->wall_interval,
                          err));
    RY_TRY(ry_case_int(c, "checkpoint.keep", &keep, 1, 1000, &keep, err));
    k->keep = (int)keep;
    RY_TRY(ry_case_bool(c, "checkpoint.at_end", &yes, &k->at_end, err));
    k->next_t = k->interval > 0 ? k->interval : INFINITY;
    k->last_wall = ry_wall_time();
    return RY_OK;
}

static const char *base_name(const char *path, char *buf, size_t size) {
    const char *s = strrchr(path, '/');
    s = s ? s + 1 : path;
    snprintf(buf, size, "%s", s);
    char *dot = strrchr(buf, '.');
    if (dot && dot != buf) *dot = '\0';
    return buf;
}

/* The head positions of the eye cases and the direction of gravity in the eye's frame (x towards
 * the patient's left, y superior, z anterior). */
static const char *const pos_names[] = {"upright",   "supine",     "prone",
                                        "left_side", "right_side", NULL};
static const double head_dir[5][3] = {{0, -1, 0}, {0, 0, -1}, {0, 0, 1}, {1, 0, 0}, {-1, 0, 0}};

const char *ry_head_position(int k, double down[3]) {
    if (k < 0 || k >= 5) return NULL;
    for (int d = 0; d < 3; ++d) down[d] = head_dir[k][d];
    return pos_names[k];
}

/* Wall particles beyond the reach of the fluid's neighbours (domain.wall_layers: the layers
 * kept), removed where the case asks; the open boundaries' zones bound the fluid's space. */
static ry_status trim_walls(ry_sim *sim, ry_case *c, ry_error *err) {
    long layers = 0;
    RY_TRY(ry_case_int(c, "domain.wall_layers", &layers, 0, 100, &layers, err));
    if (layers == 0) return RY_OK;
    double *zones = malloc((size_t)(sim->nopen + 1) * 6 * sizeof *zones);
    RY_CHECK(err, zones != NULL, RY_ERR_NOMEM, "out of memory");
    for (int k = 0; k < sim->nopen; ++k)
        for (int d = 0; d < 3; ++d) {
            zones[6 * k + d] = sim->open[k].lo[d];
            zones[6 * k + 3 + d] = sim->open[k].hi[d];
        }
    size_t gone = 0;
    const ry_status st =
        ry_walls_trim(&sim->ps, sim->dx, (int)layers, zones, sim->nopen, &gone, err);
    free(zones);
    if (st == RY_OK) return RY_OK;
    char where[512], msg[sizeof err->msg]; /* the message with the key's place in the case */
    snprintf(msg, sizeof msg, "%s", err->msg);
    return ry_error_set(err, st, "%s: %s",
                        ry_case_where(c, "domain.wall_layers", where, sizeof where), msg);
}

ry_status ry_sim_setup(ry_sim *sim, ry_case *c, const char *out_dir, ry_error *err) {
    memset(sim, 0, sizeof *sim);
    long dim;
    RY_TRY(ry_case_int(c, "dimension", NULL, 2, 3, &dim, err));
    sim->dim = (int)dim;
    RY_TRY(ry_particles_init(&sim->ps, sim->dim, err));
    RY_TRY(ry_case_positive(c, "spacing", NULL, &sim->dx, err));

    int kt;
    double hdx = 1.4;
    RY_TRY(ry_case_choice(c, "kernel.type", "wendland_c2", kernel_names, &kt, err));
    RY_TRY(ry_case_double(c, "kernel.h_over_dx", &hdx, 0.5, 4.0, &sim->h_over_dx, err));
    RY_TRY(
        ry_kernel_init(&sim->kernel, (ry_kernel_type)kt, sim->dim, sim->h_over_dx * sim->dx, err));

    double zero[3] = {0, 0, 0};
    if (ry_case_has(c, "head_position")) {
        /* Patient head position (eye cases, 3D): gravity 9.81 m/s^2 in the eye's frame, x
         * towards the patient's left, y superior, z anterior (out of the pupil). */
        int pos;
        char where[256];
        RY_CHECK(err, sim->dim == 3 && !ry_case_has(c, "gravity"), RY_ERR_INPUT,
                 "%s: key 'head_position': needs dimension 3 and no 'gravity' key",
                 ry_case_where(c, "head_position", where, sizeof where));
        RY_TRY(ry_case_choice(c, "head_position", NULL, pos_names, &pos, err));
        for (int d = 0; d < 3; ++d) sim->gravity[d] = 9.81 * head_dir[pos][d];
    } else {
        RY_TRY(ry_case_vector(c, "gravity", zero, sim->dim, sim->gravity, err));
    }
    RY_TRY(read_materials(sim, c, err));

    const char **mnames = calloc((size_t)sim->nmat + 1, sizeof *mnames);
    RY_CHECK(err, mnames != NULL, RY_ERR_NOMEM, "out of memory");
    for (int i = 0; i < sim->nmat; ++i) mnames[i] = sim->mat[i].name;
    ry_status st = ry_geometry_from_case(&sim->ps, c, sim->dx, mnames, sim->nmat,
                                         &sim->body_first_id, &sim->nbodies, err);
    free(mnames);
    RY_TRY(st);
    RY_TRY(ry_open_setup(sim, c, err));
    RY_TRY(trim_walls(sim, c, err));

    /* Mass from the material density on the lattice; density at rest. */
    double vol = pow(sim->dx, sim->dim);
    for (size_t i = 0; i < sim->ps.n; ++i) {
        const ry_material *m = &sim->mat[sim->ps.material[i]];
        sim->ps.f[RY_F_MASS][i] = m->density * vol;
        sim->ps.f[RY_F_RHO][i] = m->density;
    }
    RY_TRY(read_domain(sim, c, err));

    double one = 1.0, cfl = 0.25, dtmax = 0.0;
    long maxsteps = 1000000000L, reorder = 20;
    RY_TRY(ry_case_positive(c, "time.end", NULL, &sim->t_end, err));
    double oi = sim->t_end / 50;
    RY_TRY(ry_case_positive(c, "time.output_interval", &oi, &sim->output_interval, err));
    RY_TRY(ry_case_double(c, "time.cfl", &cfl, 1e-3, one, &sim->cfl, err));
    RY_TRY(ry_case_double(c, "time.dt_max", &dtmax, 0.0, INFINITY, &sim->dt_max, err));
    RY_TRY(ry_case_int(c, "time.max_steps", &maxsteps, 1, 1000000000000L, &sim->max_steps, err));
    RY_TRY(ry_case_int(c, "neighbors.reorder_every", &reorder, 0, 1000000, &reorder, err));
    sim->reorder_every = (int)reorder;
    static const char *const xr[3] = {"xref_x", "xref_y", "xref_z"};
    for (int d = 0; d < 3; ++d) {
        int id;
        RY_TRY(ry_particles_add_field(&sim->ps, xr[d], "m", d, RY_FIELD_POSITION, &id, err));
        if (d == 0) sim->f_xref = id;
    }

    char nb[256], def_out[300];
    base_name(ry_case_name(c), nb, sizeof nb);
    sim->case_name = ry_strdup(nb);
    snprintf(def_out, sizeof def_out, "out/%s", nb);
    const char *folder;
    int yes = 1;
    RY_TRY(ry_case_string(c, "output.folder", def_out, &folder, err));
    RY_TRY(ry_case_bool(c, "output.vtk", &yes, &sim->write_vtk, err));
    int no = 0;
    RY_TRY(ry_case_bool(c, "output.pieces", &no, &sim->write_pieces, err));
    sim->out_dir = ry_strdup(out_dir ? out_dir : folder);
    RY_CHECK(err, sim->out_dir && sim->case_name, RY_ERR_NOMEM, "out of memory");

    RY_TRY(read_probes(sim, c, err));
    RY_TRY(ry_profiles_setup(sim, c, err));
    RY_TRY(read_scheme(sim, c, err));
    /* What the scheme needs of the search and the decomposition; the Verlet skin its default
     * or the core's. */
    ry_scheme_needs nd = ry_scheme_needs_default(sim);
    if (sim->scheme->needs) sim->scheme->needs(sim, sim->scheme_state, &nd);
    sim->sort_always = nd.sort_always;
    sim->cells_only = nd.cells_only;
    if (nd.keep_order) sim->reorder_every = 0;
    sim->open_sink = nd.open_sink;
    sim->halo_depth = nd.halo_depth;
    for (int d = 0; d < 3; ++d) sim->dd_x[d] = nd.dd_x[d];
    sim->guard.max_speed = nd.max_speed;
    sim->guard.rho_min = nd.rho_min;
    sim->guard.rho_max = nd.rho_max;
    double skin = nd.skin > 0 ? nd.skin : 0.15;
    RY_TRY(ry_case_double(c, "neighbors.skin", &skin, 0.0, 1.0, &sim->nl_skin, err));
    RY_TRY(read_guard(sim, c, err));
    RY_TRY(read_checkpoint(sim, c, err));
    RY_TRY(check_probes(sim, c, err));
    ry_case_touch(c, "description");
    RY_TRY(ry_case_check_unused(c, err));
    return ry_symmetry_attach(sim, err);
}

void ry_sim_free(ry_sim *sim) {
    ry_symmetry_detach(sim);
    if (sim->scheme && sim->scheme->free) sim->scheme->free(sim->scheme_state);
    ry_writer_free(sim);
    ry_particles_free(&sim->ps);
    ry_cells_free(&sim->cells);
    ry_nlist_free(&sim->nl);
    for (int i = 0; i < sim->nmat; ++i) free(sim->mat[i].name);
    free(sim->mat);
    free(sim->body_first_id);
    free(sim->probes);
    ry_regions_free(sim);
    ry_profiles_free(sim);
    ry_sim_snapshot_free(sim);
    free(sim->open);
    free(sim->out_dir);
    free(sim->case_name);
    memset(sim, 0, sizeof *sim);
}
