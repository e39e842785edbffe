/* Output state of a simulation: the .pvd entries and the series.csv rows written so far. */
#ifndef RYUSHI_CORE_WRITER_H
#define RYUSHI_CORE_WRITER_H

#include "ryushi/sim.h"

void ry_writer_free(ry_sim *sim);

#endif
