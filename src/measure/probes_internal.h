/* The probes defined outside src/measure/probes.c, for its list. */
#ifndef RY_MEASURE_PROBES_INTERNAL_H
#define RY_MEASURE_PROBES_INTERNAL_H

#include "ryushi/neighbor.h"
#include "ryushi/sim.h"

/* Cells of edge >= radius over the current positions (src/measure/probes_cells.c). */
ry_status ry_probe_current_cells(const ry_sim *sim, double radius, ry_cell_list *cl,
                                 const double *x[3], int per[3], ry_error *err);

/* src/measure/probes_drop.c */
extern const ry_probe ry_probe_width_x, ry_probe_drop_pressure, ry_probe_ppe_iterations,
    ry_probe_contact_angle, ry_probe_contact_angle_second, ry_probe_width_x_second,
    ry_probe_pressure_jump_second;
/* src/measure/probes_interface.c */
extern const ry_probe ry_probe_interface_height;
/* src/measure/probes_wall.c */
extern const ry_probe ry_probe_oil_wall_contact;
/* src/measure/probes_solid.c */
extern const ry_probe ry_probe_tip_deflection, ry_probe_tip_axial, ry_probe_residual,
    ry_probe_solid_kinetic_energy, ry_probe_strain_energy, ry_probe_min_spacing;

#endif
