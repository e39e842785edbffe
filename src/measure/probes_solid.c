/* Probes of beams and solids (listed by `ryushi probes`), and the beam's centreline. */
#include <math.h>

#include "measure/probes_internal.h"
#include "ryushi/beam.h"
#include "ryushi/solid.h"

ry_status ry_beam_centreline(const ry_sim *sim, double sx, double *pos, double *disp,
                             ry_error *err) {
    int fX[3];
    RY_CHECK(err, ry_beam_reference_fields(sim, fX), RY_ERR_INPUT,
             "beam centreline: needs the reference positions (x0, y0, z0) of the scheme 'solid'");
    ry_beam b;
    RY_TRY(ry_beam_geometry(sim, &b, err));
    RY_CHECK(err, b.ncol >= 2, RY_ERR_INPUT, "beam centreline: the beam has a single column");
    const ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    /* the two columns around s (or the nearest two at the ends) */
    double t = sx / sim->dx - 0.5;
    int k0 = (int)floor(t);
    if (k0 < 0) k0 = 0;
    if (k0 > b.ncol - 2) k0 = b.ncol - 2;
    double w1 = t - k0, p[2][3] = {{0}}, cnt[2] = {0, 0};
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_SOLID) continue;
        int k = ry_beam_column(&b, sim->dx, ps->f[fX[0]][i]) - k0;
        if (k < 0 || k > 1) continue;
        cnt[k] += 1;
        for (int d = 0; d < dim; ++d) p[k][d] += ps->f[RY_F_X + d][i];
    }
    RY_CHECK(err, cnt[0] > 0 && cnt[1] > 0, RY_ERR_INTERNAL, "beam centreline: empty column");
    for (int d = 0; d < 3; ++d) {
        double q = d < dim ? (1 - w1) * p[0][d] / cnt[0] + w1 * p[1][d] / cnt[1] : 0.0;
        double ref = d == 0 ? b.x_root + sx : b.centre[d];
        if (pos) pos[d] = q;
        if (disp) disp[d] = d < dim ? q - ref : 0.0;
    }
    return RY_OK;
}

static ry_status probe_tip(const ry_sim *sim, double *v, int axial, ry_error *err) {
    static const char *const dir_names[3] = {"load_direction_x", "load_direction_y",
                                             "load_direction_z"};
    double dir[3];
    *v = NAN;
    for (int d = 0; d < 3; ++d)
        if (!ry_scheme_stat(sim, dir_names[d], &dir[d])) return RY_OK;
    ry_beam b;
    double u[3];
    RY_TRY(ry_beam_geometry(sim, &b, err));
    RY_TRY(ry_beam_centreline(sim, b.length, NULL, u, err));
    if (axial) {
        *v = u[0];
    } else {
        *v = u[0] * dir[0] + u[1] * dir[1] + u[2] * dir[2];
    }
    return RY_OK;
}
static ry_status probe_tip_deflection(const ry_sim *sim, double *v, ry_error *err) {
    return probe_tip(sim, v, 0, err);
}
static ry_status probe_tip_axial(const ry_sim *sim, double *v, ry_error *err) {
    return probe_tip(sim, v, 1, err);
}
static ry_status probe_residual(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    if (!ry_scheme_stat(sim, "residual", v)) *v = NAN;
    return RY_OK;
}
static ry_status probe_solid_ke(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    *v = ry_particles_kinetic_energy(&sim->ps, sim->dim, RY_KIND_SOLID, NULL);
    return RY_OK;
}
static ry_status probe_strain_energy(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    const ry_particles *ps = &sim->ps;
    const int f_psi = ry_particles_field(ps, "strain_energy_density");
    double e = 0;
    if (f_psi >= 0)
        for (size_t i = 0; i < ps->n; ++i)
            e += ps->f[f_psi][i] * ps->f[RY_F_MASS][i] / sim->mat[ps->material[i]].density;
    *v = f_psi >= 0 ? e : NAN;
    return RY_OK;
}

const ry_probe ry_probe_tip_deflection = {
    "tip_deflection", "beam: displacement of the free end of the centreline along the load [m]",
    probe_tip_deflection, NULL, 0};
const ry_probe ry_probe_tip_axial = {
    "tip_axial", "beam: displacement of the free end of the centreline along x [m]",
    probe_tip_axial, NULL, 0};
const ry_probe ry_probe_residual = {
    "residual", "solid: relative residual |f + f_ext| / |f_ext| of the last force evaluation",
    probe_residual, NULL, 0};
const ry_probe ry_probe_solid_kinetic_energy = {
    "solid_kinetic_energy", "kinetic energy of the solid particles [J]", probe_solid_ke, NULL, 0};
const ry_probe ry_probe_strain_energy = {
    "strain_energy", "elastic energy stored in the solid and clamped particles [J]",
    probe_strain_energy, NULL, 0};

static ry_status probe_min_spacing(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    if (!ry_scheme_stat(sim, "min_spacing", v)) *v = NAN;
    return RY_OK;
}
const ry_probe ry_probe_min_spacing = {
    "min_spacing", "solid: smallest distance between neighbouring particles, in initial spacings",
    probe_min_spacing, NULL, 0};
