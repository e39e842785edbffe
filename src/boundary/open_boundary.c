/* Open boundaries: inflow and outflow buffer zones (after Federico et al. 2012, Eur. J. Mech.
 * B/Fluids 34: 35, and Tafuni et al. 2018, Comput. Methods Appl. Mech. Engrg. 342: 604: velocity
 * prescribed and pressure taken from the fluid at an inlet, pressure prescribed at an outlet). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/sim.h"
#include "ryushi/open_boundary.h"

static const char *const type_names[] = {"inlet", "outlet", NULL};

/* The flow axis of a vector with exactly one non-zero component; -1 otherwise. */
static int flow_axis(const double *v, int dim, int *sign) {
    int axis = -1;
    for (int d = 0; d < dim; ++d) {
        if (v[d] == 0) continue;
        if (axis >= 0) return -1;
        axis = d;
        *sign = v[d] > 0 ? 1 : -1;
    }
    return axis;
}

/* The share of an inlet's velocity at time t: 1, or with a ramp T the half cosine
 * (1 - cos(pi t / T)) / 2 up to T, which starts and ends the rise without a jump in the
 * acceleration. */
static const double pi = 3.14159265358979323846;
static double ramp_share(const ry_open_boundary *b, double t) {
    if (!(b->ramp > 0) || t >= b->ramp) return 1.0;
    return t <= 0 ? 0.0 : 0.5 * (1.0 - cos(pi * t / b->ramp));
}

/* The time integral of ramp_share from 0 to t: the volume through the zone over U A. */
static double ramp_time(const ry_open_boundary *b, double t) {
    if (!(b->ramp > 0)) return t;
    if (t >= b->ramp) return t - 0.5 * b->ramp;
    return t <= 0 ? 0.0 : 0.5 * t - 0.5 * b->ramp / pi * sin(pi * t / b->ramp);
}

/* Fills an inlet zone with buffer particles on the case lattice (cell centres, as boxes are). */
static ry_status fill_inlet(ry_sim *sim, const ry_open_boundary *b, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    long cnt[3] = {1, 1, 1};
    for (int d = 0; d < dim; ++d) cnt[d] = lround((b->hi[d] - b->lo[d]) / sim->dx);
    const double total_d = (double)cnt[0] * (double)cnt[1] * (double)cnt[2];
    RY_CHECK(err, total_d <= (double)ry_particles_limit(), RY_ERR_RANGE,
             "inlet zone would hold %.4g particles, more than the limit of %zu", total_d,
             ry_particles_limit());
    const size_t total = (size_t)total_d;
    size_t first;
    RY_TRY(ry_particles_add(ps, total, &first, err));
    size_t i = first;
    for (long a = 0; a < cnt[0]; ++a)
        for (long bb = 0; bb < cnt[1]; ++bb)
            for (long cc = 0; cc < cnt[2]; ++cc, ++i) {
                const long idx[3] = {a, bb, cc};
                for (int d = 0; d < dim; ++d) {
                    ps->f[RY_F_X + d][i] = b->lo[d] + ((double)idx[d] + 0.5) * sim->dx;
                    ps->f[RY_F_VX + d][i] = b->velocity[d] * ramp_share(b, sim->t);
                }
                ps->kind[i] = RY_KIND_INLET;
                ps->material[i] = (uint8_t)b->material;
            }
    return RY_OK;
}

/* An inlet zone must hold no fluid: its buffer particles would sit on the fluid's. */
static ry_status inlet_clear(const ry_sim *sim, ry_case *c, size_t q, const ry_open_boundary *b,
                             ry_error *err) {
    const ry_particles *ps = &sim->ps;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        int in = 1;
        for (int d = 0; d < sim->dim; ++d)
            in &= ps->f[RY_F_X + d][i] > b->lo[d] && ps->f[RY_F_X + d][i] < b->hi[d];
        if (!in) continue;
        char at[96] = "", k[64], where[256];
        for (int d = 0, len = 0; d < sim->dim; ++d)
            len += snprintf(at + len, sizeof at - (size_t)len, "%s%g", d ? ", " : "",
                            ps->f[RY_F_X + d][i]);
        snprintf(k, sizeof k, "open_boundaries[%zu].lo", q);
        return ry_error_set(
            err, RY_ERR_INPUT,
            "%s: key '%s': the inlet zone overlaps the fluid particle at (%s); its "
            "buffer particles would sit on the fluid's (end the fluid bodies at the "
            "zone)",
            ry_case_where(c, k, where, sizeof where), k, at);
    }
    return RY_OK;
}

/* An inlet's or a rate outlet's velocity: `velocity` as given, or `flow_rate` Q [m^3/s, m^2/s
 * in 2D] along the unit vector `direction`, through the zone's cross-section A across that
 * axis: Q / A. */
static ry_status zone_velocity(ry_case *c, size_t q, int dim, ry_open_boundary *b, ry_error *err) {
    char k[128], kv[128], where[256];
    snprintf(k, sizeof k, "open_boundaries[%zu].flow_rate", q);
    snprintf(kv, sizeof kv, "open_boundaries[%zu].velocity", q);
    if (!ry_case_has(c, k)) return ry_case_vector(c, kv, NULL, dim, b->velocity, err);
    if (ry_case_has(c, kv))
        return ry_error_set(err, RY_ERR_INPUT,
                            "%s: key '%s': an open boundary takes 'velocity' or 'flow_rate' "
                            "with 'direction', not both",
                            ry_case_where(c, k, where, sizeof where), k);
    double rate, dir[3] = {0, 0, 0};
    RY_TRY(ry_case_positive(c, k, NULL, &rate, err));
    snprintf(k, sizeof k, "open_boundaries[%zu].direction", q);
    RY_TRY(ry_case_vector(c, k, NULL, dim, dir, err));
    int sign = 0;
    const int axis = flow_axis(dir, dim, &sign);
    if (axis < 0 || fabs(dir[axis]) != 1)
        return ry_error_set(err, RY_ERR_INPUT,
                            "%s: key '%s': the flow must be along one axis (a unit vector such "
                            "as [0, 0, -1])",
                            ry_case_where(c, k, where, sizeof where), k);
    double area = 1;
    for (int d = 0; d < dim; ++d)
        if (d != axis) area *= b->hi[d] - b->lo[d];
    b->velocity[axis] = sign * rate / area;
    return RY_OK;
}

/* The optional ramp of an inlet or a rate outlet [s]. */
static ry_status read_ramp(ry_case *c, size_t q, ry_open_boundary *b, ry_error *err) {
    char k[128];
    double none = 0;
    snprintf(k, sizeof k, "open_boundaries[%zu].ramp", q);
    return ry_case_double(c, k, &none, 0.0, 1e300, &b->ramp, err);
}

/* An outlet with `flow_rate` or `velocity`: a rate outlet. */
static int rate_outlet(ry_case *c, size_t q) {
    char k[128], kv[128];
    snprintf(k, sizeof k, "open_boundaries[%zu].flow_rate", q);
    snprintf(kv, sizeof kv, "open_boundaries[%zu].velocity", q);
    return ry_case_has(c, k) || ry_case_has(c, kv);
}

ry_status ry_open_setup(ry_sim *sim, ry_case *c, ry_error *err) {
    size_t n;
    RY_TRY(ry_case_count(c, "open_boundaries", &n, err));
    if (n == 0) return RY_OK;
    sim->open = calloc(n, sizeof *sim->open);
    RY_CHECK(err, sim->open != NULL, RY_ERR_NOMEM, "out of memory");
    sim->nopen = (int)n;
    const char **mnames = calloc((size_t)sim->nmat + 1, sizeof *mnames);
    RY_CHECK(err, mnames != NULL, RY_ERR_NOMEM, "out of memory");
    for (int m = 0; m < sim->nmat; ++m) mnames[m] = sim->mat[m].name;
    ry_status st = RY_OK;
    char k[128], where[256];
    const int dim = sim->dim;
    for (size_t q = 0; q < n && st == RY_OK; ++q) {
        ry_open_boundary *b = &sim->open[q];
        snprintf(k, sizeof k, "open_boundaries[%zu].type", q);
        if ((st = ry_case_choice(c, k, NULL, type_names, &b->type, err)) != RY_OK) break;
        snprintf(k, sizeof k, "open_boundaries[%zu].lo", q);
        if ((st = ry_case_vector(c, k, NULL, dim, b->lo, err)) != RY_OK) break;
        snprintf(k, sizeof k, "open_boundaries[%zu].hi", q);
        if ((st = ry_case_vector(c, k, NULL, dim, b->hi, err)) != RY_OK) break;
        for (int d = 0; d < dim && st == RY_OK; ++d) {
            double len = (b->hi[d] - b->lo[d]) / sim->dx;
            if (!(len >= 0.999 && len < 1e6) || fabs(len - round(len)) > 1e-6)
                st = ry_error_set(err, RY_ERR_INPUT,
                                  "%s: key '%s': the zone must span a whole number (1 to 1e6) "
                                  "of particle spacings in every direction (%g spacings)",
                                  ry_case_where(c, k, where, sizeof where), k, len);
        }
        if (st != RY_OK) break;
        double dir[3] = {0, 0, 0};
        if (b->type == RY_OPEN_INLET) {
            /* a velocity from flow_rate lies along its checked direction: only a given
             * velocity can fail the one-axis test below */
            if ((st = zone_velocity(c, q, dim, b, err)) != RY_OK) break;
            snprintf(k, sizeof k, "open_boundaries[%zu].velocity", q);
            memcpy(dir, b->velocity, sizeof dir);
            int mat = 0;
            snprintf(k, sizeof k, "open_boundaries[%zu].material", q);
            if ((st = ry_case_choice(c, k, mnames[0], mnames, &mat, err)) != RY_OK) break;
            b->material = mat;
            if ((st = read_ramp(c, q, b, err)) != RY_OK) break;
        } else if ((b->rate = rate_outlet(c, q))) {
            snprintf(k, sizeof k, "open_boundaries[%zu].pressure", q);
            if (ry_case_has(c, k)) {
                st = ry_error_set(err, RY_ERR_INPUT,
                                  "%s: key '%s': an outlet takes 'pressure', or 'flow_rate' or "
                                  "'velocity' (a rate outlet), not both",
                                  ry_case_where(c, k, where, sizeof where), k);
                break;
            }
            if ((st = zone_velocity(c, q, dim, b, err)) != RY_OK) break;
            if ((st = read_ramp(c, q, b, err)) != RY_OK) break;
            snprintf(k, sizeof k, "open_boundaries[%zu].velocity", q);
            memcpy(dir, b->velocity, sizeof dir);
        } else {
            double zero = 0;
            snprintf(k, sizeof k, "open_boundaries[%zu].direction", q);
            if ((st = ry_case_vector(c, k, NULL, dim, dir, err)) != RY_OK) break;
            snprintf(k, sizeof k, "open_boundaries[%zu].pressure", q);
            if ((st = ry_case_double(c, k, &zero, -1e300, 1e300, &b->pressure, err)) != RY_OK)
                break;
        }
        b->axis = flow_axis(dir, dim, &b->sign);
        if (b->axis < 0) {
            st = ry_error_set(err, RY_ERR_INPUT,
                              "%s: key '%s': the flow must be along one axis (exactly one "
                              "non-zero component)",
                              ry_case_where(c, k, where, sizeof where), k);
            break;
        }
        if (b->type == RY_OPEN_INLET && (st = inlet_clear(sim, c, q, b, err)) == RY_OK)
            st = fill_inlet(sim, b, err);
    }
    free(mnames);
    return st;
}

/* Signed distance past a face along a boundary's flow direction. */
static inline double past(const ry_open_boundary *b, const double *x, double face) {
    return (double)b->sign * (x[b->axis] - face);
}

static int inside_across(const ry_open_boundary *b, const double *x, int dim) {
    for (int d = 0; d < dim; ++d)
        if (d != b->axis && !(x[d] >= b->lo[d] && x[d] < b->hi[d])) return 0;
    return 1;
}

/* An outlet (or fluid) particle that has left the zone sideways (downstream of the entrance,
 * outside the cross-section but within one zone length of it): removed as if it had left
 * downstream. */
static int left_sideways(const ry_open_boundary *b, const double *x, int dim) {
    if (inside_across(b, x, dim) || past(b, x, b->sign > 0 ? b->lo[b->axis] : b->hi[b->axis]) < 0)
        return 0;
    const double len = b->hi[b->axis] - b->lo[b->axis];
    for (int d = 0; d < dim; ++d)
        if (d != b->axis && (x[d] < b->lo[d] - len || x[d] > b->hi[d] + len)) return 0;
    return 1;
}

/* Marks particle i of n for removal (the flags allocated at the first). */
static ry_status mark_removed(uint8_t **remove, size_t n, size_t i, ry_error *err) {
    if (!*remove) *remove = calloc(n, 1);
    RY_CHECK(err, *remove != NULL, RY_ERR_NOMEM, "out of memory");
    (*remove)[i] = 1;
    return RY_OK;
}

/* Records particle i of n as held in rate outlet q's buffer (the list allocated at the first). */
static ry_status hold(size_t **held, size_t *nheld, size_t n, size_t i, int q, ry_error *err) {
    if (!*held) *held = malloc(2 * n * sizeof **held);
    RY_CHECK(err, *held != NULL, RY_ERR_NOMEM, "out of memory");
    (*held)[2 * *nheld] = i;
    (*held)[2 * (*nheld)++ + 1] = (size_t)q;
    return RY_OK;
}

/* The rate outlet whose buffer a particle at x belongs to (within its cross-section, past its
 * upstream face), or -1. */
static int rate_zone(const ry_sim *sim, const double *x) {
    for (int q = 0; q < sim->nopen; ++q) {
        const ry_open_boundary *b = &sim->open[q];
        if (b->type != RY_OPEN_OUTLET || !b->rate || !inside_across(b, x, sim->dim)) continue;
        if (past(b, x, b->sign > 0 ? b->lo[b->axis] : b->hi[b->axis]) >= 0) return q;
    }
    return -1;
}

/* A rate outlet's buffer particles move together along the flow (a plug), at the speed that
 * keeps the volume removed at Q t (with a ramp, Q times the ramp's time integral): U = Q / A while
 * it is on time, faster when it lags, by up to twice U when a layer of the zone (A dx) behind, and
 * slower when it runs ahead, at rest a layer ahead. Fluid that crowds into the zone closer than the
 * lattice's spacing therefore does not leave faster than Q, nor does a zone that starts empty lag
 * it for long. held: nheld pairs (particle, rate outlet), the buffer particles that stay. */
static ry_status rate_speeds(ry_sim *sim, const size_t *held, size_t nheld, ry_error *err) {
    const double cell = pow(sim->dx, sim->dim);
    double *v = calloc((size_t)sim->nopen, sizeof *v);
    RY_CHECK(err, v != NULL, RY_ERR_NOMEM, "out of memory");
    for (int q = 0; q < sim->nopen; ++q) {
        const ry_open_boundary *b = &sim->open[q];
        if (b->type != RY_OPEN_OUTLET || !b->rate) continue;
        /* the cross-section within the domain (a zone cut by a symmetry plane: its half) */
        double area = 1;
        for (int d = 0; d < sim->dim; ++d)
            if (d != b->axis)
                area *= fmin(b->hi[d], sim->box.hi[d]) - fmax(b->lo[d], sim->box.lo[d]);
        const double u = fabs(b->velocity[b->axis]);
        /* under MPI each rank counts its own removals (every rank calls this, in order) */
        const double removed = sim->par ? sim->par->sum(sim, (double)b->count) : (double)b->count;
        const double behind = u * area * ramp_time(b, sim->t) - removed * cell;
        v[q] = (double)b->sign * u *
               fmin(2.0, fmax(0.0, ramp_share(b, sim->t) + behind / (area * sim->dx)));
    }
    for (size_t k = 0; k < nheld; ++k) {
        const ry_open_boundary *b = &sim->open[held[2 * k + 1]];
        sim->ps.f[RY_F_VX + b->axis][held[2 * k]] = v[held[2 * k + 1]];
    }
    free(v);
    return RY_OK;
}

/* The buffer particles of the inlets still ramping up at their share of the velocity at the
 * time reached (once more at the full velocity when the ramp has ended). */
static void ramp_speeds(ry_sim *sim) {
    ry_particles *ps = &sim->ps;
    for (int q = 0; q < sim->nopen; ++q) {
        ry_open_boundary *b = &sim->open[q];
        if (b->type != RY_OPEN_INLET || !(b->ramp > 0) || b->ramped) continue;
        const double share = ramp_share(b, sim->t);
        b->ramped = share == 1.0;
        const double downstream = b->sign > 0 ? b->hi[b->axis] : b->lo[b->axis];
        const double upstream = b->sign > 0 ? b->lo[b->axis] : b->hi[b->axis];
        for (size_t i = 0; i < ps->n; ++i) {
            if (ps->kind[i] != RY_KIND_INLET) continue;
            double x[3] = {0, 0, 0};
            for (int d = 0; d < sim->dim; ++d) x[d] = ps->f[RY_F_X + d][i];
            if (!inside_across(b, x, sim->dim) || past(b, x, upstream) < -sim->dx ||
                past(b, x, downstream) >= 0)
                continue;
            for (int d = 0; d < sim->dim; ++d) ps->f[RY_F_VX + d][i] = b->velocity[d] * share;
        }
    }
}

ry_status ry_open_update(ry_sim *sim, ry_error *err) {
    if (sim->nopen == 0) return RY_OK;
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    size_t n = ps->n, nspawn = 0, nremove = 0;
    uint8_t *remove = NULL;
    size_t *spawn = NULL;           /* pairs (particle, inlet): copies enter upstream */
    size_t *held = NULL, nheld = 0; /* pairs (particle, rate outlet): its buffer that stays */
    ry_status st = RY_OK;
    for (size_t i = 0; i < n; ++i) {
        double x[3] = {0, 0, 0};
        for (int d = 0; d < dim; ++d) x[d] = ps->f[RY_F_X + d][i];
        int in_outlet = 0;                  /* inside the zone of some outlet */
        if (ps->kind[i] == RY_KIND_INLET) { /* a rate outlet's buffer: removed past its zone */
            const int q = rate_zone(sim, x);
            if (q >= 0) {
                ry_open_boundary *b = &sim->open[q];
                if (past(b, x, b->sign > 0 ? b->hi[b->axis] : b->lo[b->axis]) >= 0) {
                    if ((st = mark_removed(&remove, n, i, err)) != RY_OK) goto done;
                    nremove++;
                    b->count++;
                } else if ((st = hold(&held, &nheld, n, i, q, err)) != RY_OK) {
                    goto done;
                }
                continue;
            }
        }
        for (int q = 0; q < sim->nopen; ++q) {
            ry_open_boundary *b = &sim->open[q];
            const double downstream = b->sign > 0 ? b->hi[b->axis] : b->lo[b->axis];
            const double upstream = b->sign > 0 ? b->lo[b->axis] : b->hi[b->axis];
            if (b->type == RY_OPEN_INLET && ps->kind[i] == RY_KIND_INLET &&
                inside_across(b, x, dim) && past(b, x, downstream) >= 0 &&
                past(b, x, upstream) < 2 * (b->hi[b->axis] - b->lo[b->axis])) {
                if (!spawn) spawn = malloc(2 * n * sizeof *spawn);
                if (!spawn) {
                    st = ry_error_set(err, RY_ERR_NOMEM, "out of memory");
                    goto done;
                }
                spawn[2 * nspawn] = i;
                spawn[2 * nspawn++ + 1] = (size_t)q;
                ps->kind[i] = RY_KIND_FLUID;
                for (int d = 0; d < dim; ++d) ps->f[RY_F_AX + d][i] = 0;
                ps->f[RY_F_DRHO][i] = 0;
                b->count++;
                break;
            }
            /* Fluid pushed back into an inlet's zone, deeper than half a spacing (a pressure
             * against the prescribed inflow): returned to the supply, and taken off the inflow.
             * Left there it would sit among the buffer's particles, or pass through them out of
             * the zone's far side. */
            if (b->type == RY_OPEN_INLET && ps->kind[i] == RY_KIND_FLUID &&
                inside_across(b, x, dim) && past(b, x, downstream) < -0.5 * sim->dx &&
                past(b, x, upstream) >= -0.5 * sim->dx) {
                if ((st = mark_removed(&remove, n, i, err)) != RY_OK) goto done;
                nremove++;
                b->count--;
                break;
            }
            if (b->type != RY_OPEN_OUTLET) continue;
            const int across = inside_across(b, x, dim);
            if (b->rate && ps->kind[i] == RY_KIND_FLUID && across &&
                past(b, x, upstream) >= 0) { /* into the buffer, at the outlet's velocity */
                ps->kind[i] = RY_KIND_INLET; /* moves with the buffer (rate_speeds) */
                for (int d = 0; d < dim; ++d) {
                    ps->f[RY_F_VX + d][i] = 0;
                    ps->f[RY_F_AX + d][i] = 0;
                }
                ps->f[RY_F_RHO][i] = sim->mat[ps->material[i]].density;
                ps->f[RY_F_DRHO][i] = 0;
                if ((st = hold(&held, &nheld, n, i, q, err)) != RY_OK) goto done;
                in_outlet = 1;
                break;
            }
            /* a sink (MPS): fluid past the downstream face is removed, nothing else */
            if (sim->open_sink && !b->rate) {
                if (!(across && ps->kind[i] == RY_KIND_FLUID && past(b, x, downstream) >= 0))
                    continue;
                if ((st = mark_removed(&remove, n, i, err)) != RY_OK) goto done;
                nremove++;
                b->count++;
                break;
            }
            const int in_zone = across && past(b, x, upstream) >= 0 && past(b, x, downstream) < 0;
            in_outlet |= in_zone;
            if (in_zone && ps->kind[i] == RY_KIND_FLUID) {
                ps->kind[i] = RY_KIND_OUTLET;
                ps->f[RY_F_P][i] = b->pressure;
                ps->f[RY_F_RHO][i] = sim->mat[ps->material[i]].density;
                break;
            }
            /* Removed: an outlet particle past the downstream face, or an outlet or fluid
             * particle that left the zone sideways. */
            const int gone =
                (across && ps->kind[i] == RY_KIND_OUTLET && past(b, x, downstream) >= 0) ||
                ((ps->kind[i] == RY_KIND_OUTLET || ps->kind[i] == RY_KIND_FLUID) &&
                 left_sideways(b, x, dim));
            if (gone) {
                if ((st = mark_removed(&remove, n, i, err)) != RY_OK) goto done;
                nremove++;
                b->count++;
                in_outlet = 1;
                break;
            }
        }
        /* An outlet particle that went back upstream of its zone (gravity pulling the fluid back
         * from an outlet above it, a reversed flow) is fluid again: left as an outlet particle,
         * with its pressure fixed, it would fall through the fluid and the walls and out of the
         * domain, and its speed would set the time step. */
        if (ps->kind[i] == RY_KIND_OUTLET && !in_outlet) ps->kind[i] = RY_KIND_FLUID;
    }
    if ((st = rate_speeds(sim, held, nheld, err)) != RY_OK) goto done;
    if (nspawn) {
        size_t first;
        st = ry_particles_add(ps, nspawn, &first, err);
        if (st != RY_OK) goto done;
        for (size_t s = 0; s < nspawn; ++s) {
            const size_t i = spawn[2 * s], j = first + s;
            const ry_open_boundary *b = &sim->open[spawn[2 * s + 1]];
            for (int f = 0; f < ps->nfields; ++f)
                if (ps->f[f]) ps->f[f][j] = ps->f[f][i];
            ps->f[RY_F_X + b->axis][j] -= (double)b->sign * (b->hi[b->axis] - b->lo[b->axis]);
            /* (during a ramp, ramp_speeds below sets its share) */
            for (int d = 0; d < dim; ++d) ps->f[RY_F_VX + d][j] = b->velocity[d];
            ps->kind[j] = RY_KIND_INLET;
            ps->material[j] = (uint8_t)b->material;
        }
    }
    ramp_speeds(sim);
    if (nremove) {
        if (ps->n > n) { /* the new inlet particles stay */
            uint8_t *r = realloc(remove, ps->n);
            if (!r) {
                st = ry_error_set(err, RY_ERR_NOMEM, "out of memory");
                goto done;
            }
            remove = r;
            memset(remove + n, 0, ps->n - n);
        }
        ry_particles_remove(ps, remove);
    }
    if (nspawn || nremove) st = ry_sim_list_edit(sim, n, nspawn, remove, err);
done:
    free(remove);
    free(spawn);
    free(held);
    return st;
}

double ry_open_volume(const ry_sim *sim, int type) {
    double v = 0, cell = pow(sim->dx, sim->dim);
    for (int q = 0; q < sim->nopen; ++q)
        if (sim->open[q].type == type) v += (double)sim->open[q].count * cell;
    return v;
}
