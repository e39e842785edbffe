/* ryushi — output for ParaView and for analysis.
 *
 * VTK XML PolyData (.vtp) with binary (raw appended) arrays, one file per output time, and a
 * .pvd collection that ParaView opens as a time series. Every file is written atomically. */
#ifndef RYUSHI_OUTPUT_H
#define RYUSHI_OUTPUT_H

#include "ryushi/particles.h"
#include "ryushi/status.h"

/* Writes the particles as a .vtp file: points, and point data velocity, pressure, density,
 * mass, kind, material, id and every field flagged RY_FIELD_OUTPUT. */
ry_status ry_vtk_write_particles(const char *path, const ry_particles *ps, double time,
                                 ry_error *err);

/* Writes a .pvd collection of n datasets (file names relative to the .pvd) with times. */
ry_status ry_pvd_write(const char *path, int n, char *const *files, const double *times,
                       ry_error *err);

#endif
