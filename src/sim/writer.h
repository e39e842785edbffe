/* Output state of a simulation: the .pvd entries and the series.csv rows written so far. */
#ifndef RYUSHI_CORE_WRITER_H
#define RYUSHI_CORE_WRITER_H

#include "ryushi/checkpoint.h"
#include "ryushi/sim.h"

void ry_writer_free(ry_sim *sim);
/* The output state in a checkpoint: .pvd entries and series.csv so far. */
ry_status ry_writer_save(const ry_sim *sim, ry_ck_writer *ck, ry_error *err);
/* Replaces the output state by a checkpoint's and rewrites the .pvd and series.csv from it. */
ry_status ry_writer_load(ry_sim *sim, const ry_ck_reader *ck, ry_error *err);

#endif
