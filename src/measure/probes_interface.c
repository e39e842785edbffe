/* Probes of the interface between two liquids at rest (listed by `ryushi probes`). */
#include <math.h>
#include <stdlib.h>

#include "measure/probes_internal.h"
#include "ryushi/probes.h"

typedef struct {
    double h; /* height along -g */
    int up;   /* of the lighter liquid */
} axis_particle;

static int by_height(const void *a, const void *b) {
    const double x = ((const axis_particle *)a)->h, y = ((const axis_particle *)b)->h;
    return (x > y) - (x < y);
}

/* interface_height: the height along -g, from the origin, where the interface between the first
 * two materials crosses the vertical line through the origin. Among the fluid particles of
 * those materials within one spacing of the line, sorted by height, the split that leaves the
 * fewest on the wrong side (the lighter liquid below it, the heavier above; the second is taken
 * as the lighter at equal densities); the interface lies halfway between the two particles of
 * the split (the mean over splits that tie). NaN without gravity or with one liquid alone on the
 * line. */
static ry_status probe_interface_height(const ry_sim *sim, double *v, ry_error *err) {
    RY_CHECK(err, sim->nmat >= 2, RY_ERR_INPUT,
             "measurement 'interface_height' needs two materials");
    const ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const int light = sim->mat[1].density <= sim->mat[0].density ? 1 : 0;
    double up[3] = {0, 0, 0}, g = 0;
    for (int d = 0; d < dim; ++d) g += sim->gravity[d] * sim->gravity[d];
    *v = NAN;
    if (!(g > 0)) return RY_OK;
    g = sqrt(g);
    for (int d = 0; d < dim; ++d) up[d] = -sim->gravity[d] / g;
    axis_particle *a = malloc((ps->n ? ps->n : 1) * sizeof *a);
    RY_CHECK(err, a != NULL, RY_ERR_NOMEM, "out of memory (interface_height)");
    size_t m = 0, nup = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || ps->material[i] > 1) continue;
        double h = 0, r2 = 0;
        for (int d = 0; d < dim; ++d) h += ps->f[RY_F_X + d][i] * up[d];
        for (int d = 0; d < dim; ++d) {
            const double e = ps->f[RY_F_X + d][i] - h * up[d];
            r2 += e * e;
        }
        if (r2 >= sim->dx * sim->dx) continue;
        a[m].h = h;
        a[m].up = ps->material[i] == light;
        nup += (size_t)a[m].up;
        ++m;
    }
    if (nup > 0 && nup < m) {
        qsort(a, m, sizeof *a, by_height);
        /* split k: a[0..k) below, a[k..m) above; wrong = lighter below + heavier above */
        size_t wrong = m - nup, best = (size_t)-1, nbest = 0;
        double sum = 0;
        for (size_t k = 1; k < m; ++k) {
            if (a[k - 1].up) /* a[k-1] moves below the split */
                ++wrong;
            else
                --wrong;
            if (wrong < best) {
                best = wrong;
                sum = 0;
                nbest = 0;
            }
            if (wrong == best) {
                sum += 0.5 * (a[k - 1].h + a[k].h);
                ++nbest;
            }
        }
        *v = sum / (double)nbest;
    }
    free(a);
    return RY_OK;
}

const ry_probe ry_probe_interface_height = {
    "interface_height",
    "two liquids at rest: height along -g from the origin of their interface on the vertical "
    "line through the origin [m] (the fluid within one spacing of the line, split where the "
    "fewest lie on the wrong side)",
    probe_interface_height, NULL, 0};
