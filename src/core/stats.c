/* A scheme's statistics by name (ry_scheme_type.stat). */
#include <math.h>

#include "ryushi/sim.h"

int ry_sim_stat(const ry_sim *sim, const char *name, double *value) {
    if (!sim->scheme || !sim->scheme->stat || !sim->scheme_state) return 0;
    return sim->scheme->stat(sim, sim->scheme_state, name, value);
}

double ry_sim_stat_value(const ry_sim *sim, const char *name) {
    double v = NAN;
    ry_sim_stat(sim, name, &v);
    return v;
}
