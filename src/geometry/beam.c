/* The beam a set of solid particles forms (include/ryushi/beam.h). */
#include <math.h>
#include <string.h>

#include "ryushi/beam.h"

int ry_beam_reference_fields(const ry_sim *sim, int f[3]) {
    static const char *const names[3] = {"x0", "y0", "z0"};
    for (int d = 0; d < sim->dim; ++d) {
        f[d] = ry_particles_field(&sim->ps, names[d]);
        if (f[d] < 0) return 0;
    }
    return 1;
}

ry_status ry_beam_geometry(const ry_sim *sim, ry_beam *b, ry_error *err) {
    const ry_particles *ps = &sim->ps;
    int fX[3];
    const int ref = ry_beam_reference_fields(sim, fX);
    const double *X = ref ? ps->f[fX[0]] : ps->f[RY_F_X];
    double xmin = INFINITY, xmax = -INFINITY, vol = 0, c[3] = {0, 0, 0};
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_SOLID) continue;
        xmin = fmin(xmin, X[i]);
        xmax = fmax(xmax, X[i]);
        double v = ps->f[RY_F_MASS][i] / sim->mat[ps->material[i]].density;
        vol += v;
        for (int d = 1; d < sim->dim; ++d)
            c[d] += v * (ref ? ps->f[fX[d]][i] : ps->f[RY_F_X + d][i]);
    }
    RY_CHECK(err, vol > 0, RY_ERR_INPUT, "beam: no solid particle");
    memset(b, 0, sizeof *b);
    b->x_root = xmin - 0.5 * sim->dx;
    b->length = xmax - xmin + sim->dx;
    b->area = vol / b->length;
    for (int d = 1; d < sim->dim; ++d) b->centre[d] = c[d] / vol;
    b->ncol = (int)lround((xmax - xmin) / sim->dx) + 1;
    return RY_OK;
}
