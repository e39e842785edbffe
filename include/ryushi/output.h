/* ryushi — output for ParaView and for analysis.
 *
 * VTK XML PolyData (.vtp) with binary (raw appended) arrays, one file per output time, and a
 * .pvd collection that ParaView opens as a time series. Every file is written atomically. */
#ifndef RYUSHI_OUTPUT_H
#define RYUSHI_OUTPUT_H

#include <stdint.h>

#include "ryushi/particles.h"
#include "ryushi/status.h"

/* Writes the particles as a .vtp file: points, and point data velocity, pressure, density,
 * mass, kind, material, id and every field flagged RY_FIELD_OUTPUT. */
ry_status ry_vtk_write_particles(const char *path, const ry_particles *ps, double time,
                                 ry_error *err);

/* The same for the particles whose skip[i] is zero: one piece of a parallel dataset. */
ry_status ry_vtk_write_piece(const char *path, const ry_particles *ps, const uint8_t *skip,
                             double time, ry_error *err);

/* Writes a parallel dataset (.pvtp) of npieces pieces DIR/piece_RRRR.vtp (DIR relative to the
 * .pvtp), with the arrays ry_vtk_write_particles writes for ps. */
ry_status ry_pvtp_write(const char *path, const ry_particles *ps, int npieces, const char *dir,
                        double time, ry_error *err);

/* Writes a .pvd collection of n datasets (file names relative to the .pvd) with times. */
ry_status ry_pvd_write(const char *path, int n, char *const *files, const double *times,
                       ry_error *err);

#endif
