/* A scheme's statistics by name (ry_scheme_type.stat), its needs' defaults and the end of a
 * run it reports. */
#include <math.h>

#include "ryushi/sim.h"

int ry_scheme_stat(const ry_sim *sim, const char *name, double *value) {
    if (!sim->scheme || !sim->scheme->stat || !sim->scheme_state) return 0;
    return sim->scheme->stat(sim, sim->scheme_state, name, value);
}

double ry_sim_stat_value(const ry_sim *sim, const char *name) {
    double v = NAN;
    ry_scheme_stat(sim, name, &v);
    return v;
}

ry_scheme_needs ry_scheme_needs_default(const ry_sim *sim) {
    ry_scheme_needs nd = {0};
    nd.halo_depth = 2;
    for (int d = 0; d < 3; ++d) nd.dd_x[d] = RY_F_X + (d < sim->dim ? d : 0);
    return nd;
}

void ry_sim_finish(ry_sim *sim) {
    sim->finished = 1;
}
