/* ryushi — running a simulation: set-up from a case, the time loop, output, checkpoints and
 * the last good state. */
#ifndef RYUSHI_RUN_H
#define RYUSHI_RUN_H

#include <signal.h>

#include "ryushi/sim.h"

/* Writes the state at an output time: ry_output_write, or in a distributed run the
 * whole set through the parallel layer. */
ry_status ry_sim_output(ry_sim *sim, ry_error *err);

/* Builds the simulation from a case; checks every key (unknown keys are errors). out_dir may
 * be NULL to take the case's output.folder. */
ry_status ry_sim_setup(ry_sim *sim, ry_case *c, const char *out_dir, ry_error *err);
void ry_sim_free(ry_sim *sim);

/* Progress reports and the stop flag for ry_run. */
typedef struct ry_run_hooks {
    void (*progress)(void *ctx, const ry_sim *sim, double particle_steps_per_s, double eta_s);
    void *ctx;
    double progress_interval_s;  /* wall seconds between progress calls */
    volatile sig_atomic_t *stop; /* set (by a signal handler) to end the run cleanly */
} ry_run_hooks;

/* Summary of a run. */
typedef struct ry_run_stats {
    long steps;
    size_t particles;
    double wall_s;
    double particle_steps_per_s;
    int outputs;
} ry_run_stats;

/* Runs to t_end (or max_steps), writing output at the output interval and at the end. On
 * instability the last good state is kept on disk and RY_ERR_UNSTABLE returned with a
 * diagnosis; on a stop request the current state is written and RY_ERR_INTERRUPTED returned. */
ry_status ry_run(ry_sim *sim, const ry_run_hooks *hooks, ry_run_stats *stats, ry_error *err);
/* The same, for at most max_steps steps (< 0: no limit) and up to time until_t (the last step
 * lands on it; INFINITY: none): a run taken in pieces, as a library caller steps it. The piece
 * that reaches the end writes the final checkpoint and output. */
ry_status ry_run_some(ry_sim *sim, const ry_run_hooks *hooks, long max_steps, double until_t,
                      ry_run_stats *stats, ry_error *err);

/* Creates the output folder, writes the resolved case into it (case_resolved.yaml) and
 * starts series.csv. Call before ry_run. */
ry_status ry_sim_open_output(ry_sim *sim, ry_case *c, ry_error *err);

/* Writes the current state (VTK file, .pvd entry, series.csv row). */
ry_status ry_output_write(ry_sim *sim, ry_error *err);

/* Checkpoints (include/ryushi/checkpoint.h for the format). Writes the whole state to path. */
ry_status ry_sim_checkpoint_write(const ry_sim *sim, const char *path, ry_error *err);
/* Replaces the state of a simulation set up from the same case (scheme, dimension, materials
 * and fields must match) by a checkpoint's. */
ry_status ry_sim_checkpoint_read(ry_sim *sim, const char *path, ry_error *err);
/* Writes a checkpoint into OUT/checkpoints/ (named by step) and removes all but the newest
 * `checkpoint.keep`; path (if not NULL) receives the file name. */
ry_status ry_sim_checkpoint_now(ry_sim *sim, char *path, size_t path_size, ry_error *err);
/* Restarts from the newest readable checkpoint in dir (a run's output folder or its
 * checkpoints/ folder); damaged newer ones are skipped and named in *skipped (may be NULL). */
ry_status ry_restart_newest(ry_sim *sim, const char *dir, char *used, size_t used_size,
                            char *skipped, size_t skipped_size, ry_error *err);
/* Writes the state as the last good one: CASE_last_good.vtp and a checkpoint (its file in path). */
ry_status ry_sim_last_good_write(ry_sim *sim, char *path, size_t path_size, ry_error *err);
/* guard.last_good: memory. The state copied every guard.snapshot_every steps; on instability
 * restored and written by ry_sim_last_good_write. */
ry_status ry_sim_snapshot_take(ry_sim *sim, ry_error *err);
ry_status ry_sim_snapshot_write(ry_sim *sim, char *path, size_t path_size, ry_error *err);
void ry_sim_snapshot_free(ry_sim *sim);

/* Loads a case file, applies overrides ("key=value") and sets it up with its output open in
 * out_dir, ready to run. On failure sim is freed. */
ry_status ry_setup_case_file(const char *path, int nset, const char *const *sets,
                             const char *out_dir, ry_sim *sim, ry_error *err);

/* Loads a case file, applies overrides ("key=value"), sets it up with output in out_dir and
 * runs it. On success sim holds the final state (the caller frees it with ry_sim_free). */
ry_status ry_run_case_file(const char *path, int nset, const char *const *sets, const char *out_dir,
                           ry_sim *sim, ry_run_stats *stats, ry_error *err);

#endif
