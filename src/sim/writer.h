/* Output state of a simulation: the .pvd entries and the series.csv rows written so far. */
#ifndef RYUSHI_CORE_WRITER_H
#define RYUSHI_CORE_WRITER_H

#include "ryushi/checkpoint.h"
#include "ryushi/sim.h"

void ry_writer_free(ry_sim *sim);
/* ry_output_write's two parts: the VTK file with its .pvd entry, then the measurements
 * (the series.csv row, the profiles, time.stop_when). */
ry_status ry_output_write_vtk(ry_sim *sim, ry_error *err);
ry_status ry_output_write_series(ry_sim *sim, ry_error *err);
/* The output state in a checkpoint: .pvd entries and series.csv so far. */
ry_status ry_writer_save(const ry_sim *sim, ry_ck_writer *ck, ry_error *err);
/* Replaces the output state by a checkpoint's and rewrites the .pvd and series.csv from it. */
ry_status ry_writer_load(ry_sim *sim, const ry_ck_reader *ck, ry_error *err);

#endif
