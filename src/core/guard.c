/* The guard of a run (case section `guard`): every particle checked for non-finite or
 * runaway values and the fluid for leaving the domain; the verdict names the first bad particle. */
#include <float.h>
#include <math.h>
#include <stdio.h>

#include "core/guard_check.h"
#include "ryushi/sim.h"

/* What is wrong with particle i (NULL when nothing); why receives formatted reasons. */
static const char *particle_problem(const ry_sim *sim, size_t i, char *why, size_t size) {
    const ry_particles *ps = &sim->ps;
    const ry_guard *g = &sim->guard;
    double v2 = 0;
    for (int d = 0; d < sim->dim; ++d) {
        double x = ps->f[RY_F_X + d][i], v = ps->f[RY_F_VX + d][i];
        if (!isfinite(x)) return "position is not finite";
        if (!isfinite(v)) return "velocity is not finite";
        v2 += v * v;
    }
    const double rho = ps->f[RY_F_RHO][i];
    if (!isfinite(ps->f[RY_F_P][i])) return "pressure is not finite";
    if (!(rho > 0 && isfinite(rho))) return "density is not positive and finite";
    if (g->max_speed > 0 && v2 > g->max_speed * g->max_speed) {
        snprintf(why, size, "speed %.4g m/s exceeds guard.max_speed = %g m/s", sqrt(v2),
                 g->max_speed);
        return why;
    }
    if (ps->kind[i] == RY_KIND_FLUID) {
        const double r = rho / sim->mat[ps->material[i]].density;
        if ((g->rho_min > 0 && r < g->rho_min) || (g->rho_max > 0 && r > g->rho_max)) {
            snprintf(why, size,
                     "density %.6g kg/m^3 is %.4g times the reference, outside "
                     "guard.density_min..density_max = %g..%g",
                     rho, r, g->rho_min, g->rho_max);
            return why;
        }
    }
    return NULL;
}

int ry_check_init(const ry_sim *sim, ry_check_ctx *c, double *inv_rho0) {
    const ry_particles *ps = &sim->ps;
    const ry_guard *g = &sim->guard;
    const int dim = sim->dim;
    int uniform = 1;
    for (int m = 0; m < sim->nmat && m < 256; ++m) {
        inv_rho0[m] = 1.0 / sim->mat[m].density;
        uniform &= sim->mat[m].density == sim->mat[0].density;
    }
    c->v2max = g->max_speed > 0 ? g->max_speed * g->max_speed : INFINITY;
    c->rmin = g->rho_min;
    c->rmax = g->rho_max > 0 ? g->rho_max : INFINITY;
    for (int d = 0; d < 3; ++d) {
        c->x[d] = ps->f[RY_F_X + (d < dim ? d : 0)];
        c->v[d] = ps->f[RY_F_VX + (d < dim ? d : 0)];
        c->lo[d] = d < dim ? sim->box.lo[d] : -INFINITY;
        c->hi[d] = d < dim ? sim->box.hi[d] : INFINITY;
    }
    c->rho = ps->f[RY_F_RHO];
    c->p = ps->f[RY_F_P];
    c->kind = ps->kind;
    return uniform;
}

/* Sets under 4096 particles are checked on one thread: for a beam of a few hundred particles a
 * parallel region per step costs more than the check. */
/* clang-format off */
#define RY_CHECK_LOOP_(DIM, INV)                                                                   \
    _Pragma("omp parallel for simd schedule(static) reduction(+ : bad, fluid, outside) if (n >= 4096)") \
    for (size_t i = 0; i < n; ++i) ry_check_tally(&c, i, DIM, INV, &bad, &fluid, &outside);
/* clang-format on */

ry_status ry_sim_check(const ry_sim *sim, ry_error *err) {
    const size_t n = sim->ps.n;
    const uint8_t *material = sim->ps.material;
    size_t bad = 0, fluid = 0, outside = 0;
    ry_check_ctx c;
    double inv_rho0[256];
    const int uniform = ry_check_init(sim, &c, inv_rho0);
    const double inv0 = inv_rho0[0];
    /* One pass without branches; the diagnosis is made afterwards. */
    if (uniform && sim->dim == 2) {
        RY_CHECK_LOOP_(2, inv0)
    } else if (uniform) {
        RY_CHECK_LOOP_(3, inv0)
    } else if (sim->dim == 2) {
        RY_CHECK_LOOP_(2, inv_rho0[material[i]])
    } else {
        RY_CHECK_LOOP_(3, inv_rho0[material[i]])
    }
    return ry_check_verdict(sim, bad, fluid, outside, err);
}

ry_status ry_check_verdict(const ry_sim *sim, size_t nbad, size_t fluid, size_t outside,
                           ry_error *err) {
    if (sim->par) return sim->par->verdict(sim, nbad, fluid, outside, err);
    return ry_check_verdict_here(sim, nbad, fluid, outside, err);
}

ry_status ry_check_verdict_here(const ry_sim *sim, size_t nbad, size_t fluid, size_t outside,
                                ry_error *err) {
    const ry_particles *ps = &sim->ps;
    const ry_guard *g = &sim->guard;
    const int dim = sim->dim;
    const size_t n = ps->n;
    const double *x[3];
    for (int d = 0; d < 3; ++d) x[d] = ps->f[RY_F_X + (d < dim ? d : 0)];
    size_t bad = 0, first = 0;
    char why[160], what[160] = "";
    if (nbad > 0) {
        for (size_t i = 0; i < n; ++i) {
            if (ry_sim_is_halo(sim, i)) continue;
            const char *w = particle_problem(sim, i, why, sizeof why);
            if (!w) continue;
            if (!bad) {
                first = i;
                snprintf(what, sizeof what, "%s", w);
            }
            ++bad;
        }
    }
    if (bad) {
        return ry_error_set(err, RY_ERR_UNSTABLE,
                            "unstable at step %ld, t = %.6g s: %zu particle(s) bad; first: "
                            "particle id %lld (%s) at (%g, %g, %g): %s",
                            sim->step, sim->t, bad, (long long)ps->id[first],
                            ry_kind_name((ry_kind)ps->kind[first]), ps->f[RY_F_X][first],
                            ps->f[RY_F_Y][first], sim->dim > 2 ? ps->f[RY_F_Z][first] : 0.0, what);
    }
    if (g->max_outside_fraction > 0 && fluid > 0 &&
        (double)outside > g->max_outside_fraction * (double)fluid) {
        for (size_t i = 0; i < ps->n; ++i) {
            if (ps->kind[i] != RY_KIND_FLUID || ry_sim_is_halo(sim, i)) continue;
            int out = 0;
            for (int d = 0; d < dim; ++d)
                out |= !(x[d][i] >= sim->box.lo[d] && x[d][i] < sim->box.hi[d]);
            if (out) {
                first = i;
                break;
            }
        }
        return ry_error_set(err, RY_ERR_UNSTABLE,
                            "unstable at step %ld, t = %.6g s: %zu of %zu fluid particles (more "
                            "than guard.max_outside_fraction = %g) have left the domain; first: "
                            "particle id %lld at (%g, %g, %g)",
                            sim->step, sim->t, outside, fluid, g->max_outside_fraction,
                            (long long)ps->id[first], ps->f[RY_F_X][first], ps->f[RY_F_Y][first],
                            sim->dim > 2 ? ps->f[RY_F_Z][first] : 0.0);
    }
    return RY_OK;
}

void ry_sim_checked(ry_sim *sim, size_t bad, size_t fluid, size_t outside) {
    sim->check_bad = bad;
    sim->check_fluid = fluid;
    sim->check_outside = outside;
    sim->checked = 1;
}
