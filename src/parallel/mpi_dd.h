/* ryushi on MPI: domain decomposition for the ryushi-mpi program (docs/parallel.md).
 *
 * Every rank sets the whole case up (or restores the whole checkpoint), then keeps the
 * particles of its subdomain: an orthogonal recursive bisection of the particles, balanced by
 * count. At each neighbour search the ranks exchange the particles that left their subdomains
 * and a halo of copies 2 * (support + skin) deep; between searches only the halo's fields
 * travel, from each owner to the ranks that hold its copies. The subdomains are bisected
 * afresh when the largest rank holds more than `imbalance` times the mean. Output and
 * checkpoints gather the whole set on rank 0 (in id order), so that they are the serial
 * program's files whatever the rank count; at every checkpoint the ranks also re-partition
 * canonically (fresh bisection, particles in id order), which is what a restart from it
 * does, so that a run stopped at a checkpoint and continued ends bitwise identical to an
 * uninterrupted run on the same rank count. */
#ifndef RY_PARALLEL_MPI_DD_H
#define RY_PARALLEL_MPI_DD_H

#include <mpi.h>

#include "ryushi/sim.h"

/* Statistics of a rank's part of a run. */
typedef struct ry_mpi_stats {
    double comm_s;    /* seconds in exchanges and reductions, in all: */
    double redist_s;  /* redistributions at searches (with the bisections) */
    double halo_s;    /* halo updates between searches */
    double reduce_s;  /* reductions (time step, guard, stop, search decision; they also
                         wait for the slowest rank) */
    long rebalances;  /* fresh bisections */
    size_t halo;      /* halo copies at the last search */
    size_t owned_max; /* largest owned count over the ranks at the last search */
    int fields;       /* values per particle in a halo update */
} ry_mpi_stats;

/* Distributes a simulation set up (and possibly restored) identically on every rank of comm;
 * on rank 0, view is a second copy of the same set-up with its output opened, through which
 * output and checkpoints are written (NULL on other ranks). Refuses periodic domains on more
 * than one rank. */
ry_status ry_mpi_attach(ry_sim *sim, ry_sim *view, MPI_Comm comm, double imbalance, ry_error *err);
void ry_mpi_detach(ry_sim *sim);
void ry_mpi_get_stats(const ry_sim *sim, ry_mpi_stats *s);

#endif
