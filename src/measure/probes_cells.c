/* Cells over the current positions, for the probes (probes_internal.h). */
#include <string.h>

#include "measure/probes_internal.h"
#include "ryushi/neighbor.h"
#include "ryushi/particles.h"

/* Cells of edge >= radius over the current positions, for probes that must not read the run's
 * neighbour structures (they may be older than the particle set: open boundaries add and remove
 * particles after a step); x and per receive the coordinates and the periodic directions. */
ry_status ry_probe_current_cells(const ry_sim *sim, double radius, ry_cell_list *cl,
                                 const double *x[3], int per[3], ry_error *err) {
    memset(cl, 0, sizeof *cl);
    ry_particles_coords(&sim->ps, x);
    for (int d = 0; d < 3; ++d) per[d] = d < sim->dim && sim->box.periodic[d];
    return ry_cells_build(cl, &sim->box, radius, sim->ps.n, x, err);
}
