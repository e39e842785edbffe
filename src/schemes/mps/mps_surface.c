/* Surface tension and two liquids in MPS (docs/reference/mps.md; the forces in
 * src/physics/surface_tension.c): the keys of wetting (the contact angles of the potential
 * model, per liquid and per wall body, by the Dupre relation; CSF's angle at the contact line)
 * and of the interface of two liquids (surface_tension.interfacial_sigma); the CSF interfacial
 * force of the colour field (sph/multiphase.h); CSF in pressure form, the Laplace jump as the
 * free surface's Dirichlet value; and the outlets, which are sinks at pressure 0. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "schemes/mps/mps_internal.h"

/* The potential model's fluid-wall coefficient for a contact angle theta [degrees], relative to
 * C: (1 + cos theta)/2, the Dupre work of adhesion against the work of cohesion. */
static double wall_ratio_of(double theta) {
    return 0.5 * (1.0 + cos(theta * RY_PI / 180.0));
}

/* Wetting of one wall body (docs/reference/surface_tension.md, "Wetting with two liquids"),
 * potential model: bodies[k].contact_angle, a number for every liquid or a mapping from material
 * names to angles (liquids not named keep their angle on the other walls). Bodies with the same
 * angles share a group of walls (M->body_group); each other set of angles has a group of its own.
 */
static ry_status body_angles(ry_sim *sim, ry_case *c, mps *M, ry_error *err) {
    char where[256], key[160];
    int groups = 1;
    for (size_t k = 0; k < sim->nbodies; ++k) {
        snprintf(key, sizeof key, "bodies[%zu].contact_angle", k);
        if (!ry_case_has(c, key)) continue;
        RY_CHECK(err, M->st.model == RY_ST_POTENTIAL, RY_ERR_INPUT,
                 "%s: key '%s': a contact angle per wall body needs surface_tension.model "
                 "potential",
                 ry_case_where(c, key, where, sizeof where), key);
        RY_TRY(mps_body_is_wall(sim, c, k, key, err));
        double row[sizeof M->st.wall_ratio[0] / sizeof M->st.wall_ratio[0][0]];
        int named = 0;
        for (int m = 0; m < sim->nmat; ++m) {
            char mk[224];
            snprintf(mk, sizeof mk, "%s.%s", key, sim->mat[m].name);
            row[m] = M->st.wall_ratio[0][m];
            if (ry_case_has(c, mk)) {
                double th;
                RY_TRY(ry_case_double(c, mk, NULL, 0.0, 180.0, &th, err));
                row[m] = wall_ratio_of(th);
                ++named;
            }
        }
        if (!named) {
            double th;
            RY_CHECK(err, ry_case_double(c, key, NULL, 0.0, 180.0, &th, err) == RY_OK, RY_ERR_INPUT,
                     "%s: key '%s': expected an angle in degrees (0..180), or a mapping from "
                     "material names to angles",
                     ry_case_where(c, key, where, sizeof where), key);
            for (int m = 0; m < sim->nmat; ++m) row[m] = wall_ratio_of(th);
        }
        int g = 1;
        while (g < groups && memcmp(M->st.wall_ratio[g], row, sim->nmat * sizeof *row) != 0) ++g;
        if (g == groups) {
            RY_CHECK(err, groups < RY_ST_WALL_GROUPS, RY_ERR_INPUT,
                     "%s: key '%s': at most %d different sets of contact angles on wall bodies",
                     ry_case_where(c, key, where, sizeof where), key, RY_ST_WALL_GROUPS - 1);
            for (int m = 0; m < sim->nmat; ++m) M->st.wall_ratio[g][m] = row[m];
            ++groups;
        }
        if (!M->body_group) {
            M->body_group = calloc(sim->nbodies, 1);
            RY_CHECK(err, M->body_group != NULL, RY_ERR_NOMEM, "out of memory");
        }
        M->body_group[k] = (uint8_t)g;
    }
    return RY_OK;
}

/* Wetting (docs/reference/mps.md): surface_tension.contact_angle [degrees]. The potential model
 * takes it as its fluid-wall coefficient, CSF as the normal at the contact line. With the potential
 * model, materials[k].contact_angle sets the angle of liquid k alone (the others keep
 * surface_tension.contact_angle, or no attraction). */
ry_status mps_contact_angle(ry_sim *sim, ry_case *c, mps *M, ry_error *err) {
    char where[256], key[64] = "surface_tension.contact_angle";
    RY_CHECK(err, M->st.model != RY_ST_NONE || !ry_case_has(c, key), RY_ERR_INPUT,
             "%s: key '%s': needs a surface_tension.model",
             ry_case_where(c, key, where, sizeof where), key);
    double theta = NAN;
    if (ry_case_has(c, key)) {
        RY_TRY(ry_case_double(c, key, NULL, 0.0, 180.0, &theta, err));
        if (M->st.model == RY_ST_CSF) M->st.contact_angle = theta * RY_PI / 180.0;
    }
    for (int m = 0; m < sim->nmat; ++m) {
        double th = theta;
        snprintf(key, sizeof key, "materials[%d].contact_angle", m);
        if (ry_case_has(c, key)) {
            RY_CHECK(err, M->st.model == RY_ST_POTENTIAL, RY_ERR_INPUT,
                     "%s: key '%s': a contact angle per liquid needs surface_tension.model "
                     "potential (CSF takes one angle, surface_tension.contact_angle)",
                     ry_case_where(c, key, where, sizeof where), key);
            RY_TRY(ry_case_double(c, key, NULL, 0.0, 180.0, &th, err));
        }
        if (!isnan(th)) M->st.wall_ratio[0][m] = wall_ratio_of(th);
    }
    return body_angles(sim, c, M, err);
}

/* Two liquids: surface_tension.interfacial_sigma sigma_ab. Potential model: by the Dupre
 * relation the pairs of two different liquids do the work W_ab = 2 sigma - sigma_ab, the
 * coefficient C (1 - sigma_ab / (2 sigma)). CSF: the colour field of the first two materials
 * (colour 1 for the second), its curvature and the force sigma_ab kappa n / rho_bar, on the
 * case's SPH kernel (sph/multiphase.h; docs/reference/surface_tension.md, "Two liquids"). */
ry_status mps_interfacial(ry_sim *sim, ry_case *c, mps *M, ry_error *err) {
    char where[256];
    const char *key = "surface_tension.interfacial_sigma";
    if (!ry_case_has(c, key)) return RY_OK;
    RY_CHECK(err, M->st.model == RY_ST_POTENTIAL || M->st.model == RY_ST_CSF, RY_ERR_INPUT,
             "%s: key '%s': needs surface_tension.model potential or csf",
             ry_case_where(c, key, where, sizeof where), key);
    RY_CHECK(err, sim->nmat >= 2, RY_ERR_INPUT, "%s: key '%s': needs two fluid materials",
             ry_case_where(c, key, where, sizeof where), key);
    double sab;
    if (M->st.model == RY_ST_POTENTIAL) {
        RY_TRY(ry_case_double(c, key, NULL, 0.0, 2.0 * M->st.sigma, &sab, err));
        M->st.cross_ratio = 1.0 - sab / (2.0 * M->st.sigma);
        return RY_OK;
    }
    RY_TRY(ry_case_double(c, key, NULL, 0.0, 1e3, &sab, err));
    RY_CHECK(err, sim->kernel.radius <= M->re_max * (1 + 1e-12), RY_ERR_INPUT,
             "%s: key '%s': the kernel's support (%g m) must not exceed the MPS radius %g m "
             "(kernel.h_over_dx at most %g)",
             ry_case_where(c, key, where, sizeof where), key, sim->kernel.radius, M->re_max,
             0.5 * M->re_max / sim->dx);
    M->colour_on = sab > 0;
    M->colour.sigma = sab;
    M->colour.material = 1;
    M->colour.eps = 0.01;
    long passes, one = 1;
    RY_TRY(ry_case_int(c, "surface_tension.interfacial_smoothing", &one, 0, 20, &passes, err));
    M->colour.smoothing = (int)passes;
    M->colour.rho_bar = 0.5 * (sim->mat[0].density + sim->mat[1].density);
    return M->colour_on ? ry_colour_init(&M->colour, sim, err) : RY_OK;
}

/* The interfacial acceleration of CSF between two liquids, added to a. */
ry_status mps_colour_accelerate(ry_sim *sim, mps *M, double *const a[3], ry_error *err) {
    static const int mobile[RY_KIND_COUNT] = {[RY_KIND_FLUID] = 1};
    static const int need[RY_KIND_COUNT] = {[RY_KIND_FLUID] = 1};
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    if (M->ccap < n) {
        double *b = realloc(M->cdelta, 4 * n * sizeof *b);
        RY_CHECK(err, b != NULL, RY_ERR_NOMEM, "out of memory (colour field)");
        M->cdelta = b;
        M->cacc = b + n;
        M->ccap = n;
    }
    M->pc.cut = M->st.cut; /* no pairs across a thin wall */
    RY_TRY(ry_pair_cache_fill(&M->pc, sim, need, err));
    /* The SPH number density over every neighbour, the particle itself included. */
    const double w0 = sim->kernel.norm * ry_kernel_shape(sim->kernel.type, 0.0);
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        double sw = w0;
        for (size_t q = sim->nl.offset[i]; q < M->pc.end[i]; ++q) sw += M->pc.w[q];
        M->cdelta[i] = sw;
        M->cacc[3 * i] = M->cacc[3 * i + 1] = M->cacc[3 * i + 2] = 0;
    }
    if (sim->par) sim->par->sync(sim, M->cdelta, 1, 0);
    RY_TRY(ry_colour_force(&M->colour, sim, &M->pc, M->cdelta, mobile, M->cacc, err));
    for (size_t i = 0; i < n; ++i)
        if (ps->kind[i] == RY_KIND_FLUID)
            for (int d = 0; d < sim->dim; ++d) a[d][i] += M->cacc[3 * i + d];
    return RY_OK;
}

/* CSF in pressure form: the Dirichlet value of each surface particle is the Laplace jump
 * sigma kappa, averaged along the surface within the gradient radius. */
void mps_csf_dirichlet(ry_sim *sim, mps *M) {
    ry_st_laplace_pressure(&M->st, sim, M->role, ROLE_SURFACE, M->re_g, M->pd);
}

/* Outlets are sinks (mps_needs): the fluid that crosses the downstream face is removed, and the
 * free surface this leaves takes the free-surface condition (an open top, an overflow, a pipe's
 * exit). */
ry_status mps_outlet_sinks(ry_sim *sim, ry_case *c, ry_error *err) {
    for (int q = 0; q < sim->nopen; ++q) {
        char k[64], where[256];
        snprintf(k, sizeof k, "open_boundaries[%d].pressure", q);
        RY_CHECK(err, sim->open[q].type == RY_OPEN_INLET || sim->open[q].pressure == 0.0,
                 RY_ERR_INPUT,
                 "%s: key '%s': scheme mps takes outlets at pressure 0 only (its outlets remove "
                 "the fluid at the downstream face, a free surface)",
                 ry_case_where(c, k, where, sizeof where), k);
        snprintf(k, sizeof k, "open_boundaries[%d].type", q);
        RY_CHECK(err, !sim->open[q].rate, RY_ERR_INPUT,
                 "%s: key '%s': scheme mps takes no rate outlets (flow_rate or velocity): its "
                 "outlets are sinks at pressure 0",
                 ry_case_where(c, k, where, sizeof where), k);
    }
    return RY_OK;
}
