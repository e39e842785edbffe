/* ryushi — the library's public interface: set a case up, advance it, read its particles.
 *
 * Plain C (C89 declarations, C11 or C++ callers alike), standard headers only; the handle is
 * opaque. Every function returning int returns 0 on success, otherwise the program's exit-code
 * class: 2 bad input (a case error names the file, line and key), 3 input/output, 4 unstable
 * run, 130 interrupted, 1 internal error or out of memory; ry_last_error() then gives the
 * message. A handle is used by one thread at a time; the steps themselves run on OpenMP threads
 * (ry_sim_set_threads). docs/embedding.md has a complete example. Link with -lryushi
 * (pkg-config ryushi). */
#ifndef RYUSHI_RYUSHI_H
#define RYUSHI_RYUSHI_H

#include <stddef.h>
#include <stdint.h>

/* Marks the exported functions; empty for callers and for compilers without visibility. */
#if defined(RY_BUILDING_LIBRARY) && defined(__GNUC__)
#define RY_API __attribute__((visibility("default")))
#else
#define RY_API
#endif

#ifdef __cplusplus
extern "C" {
#endif

typedef struct ry_sim ry_sim;

/* A simulation from a case file, with overrides ("key=value" as `--set` takes them, e.g.
 * "time.end=0.3" or "bodies[0].hi=[0.25,0.5]"), its output in out_dir (NULL: the case's
 * output.folder). The output folder is created and case_resolved.yaml written into it. */
RY_API int ry_sim_load(ry_sim **sim, const char *case_path, int nset, const char *const *sets,
                       const char *out_dir);
/* The same from the text of a case; name stands for the file in messages and names the
 * output files. */
RY_API int ry_sim_create(ry_sim **sim, const char *yaml_text, const char *name, int nset,
                         const char *const *sets, const char *out_dir);
/* Continues from the newest sound checkpoint in dir (an output folder or its checkpoints/);
 * damaged newer ones are skipped. used and skipped (either may be NULL) receive the file
 * taken and the ones skipped. */
RY_API int ry_sim_restart(ry_sim *sim, const char *dir, char *used, size_t used_size, char *skipped,
                          size_t skipped_size);
RY_API void ry_sim_destroy(ry_sim *sim);

/* OpenMP threads for this handle's steps (0: the OpenMP default). Results do not depend on
 * it. */
RY_API int ry_sim_set_threads(ry_sim *sim, int threads);
/* One time step; *dt (may be NULL) receives its length (0 when the run had ended). Outputs and
 * checkpoints fall due as in ry_sim_run. */
RY_API int ry_sim_step(ry_sim *sim, double *dt);
/* Steps until the simulated time reaches t (the last step lands on it) or the case ends. */
RY_API int ry_sim_advance_to(ry_sim *sim, double t);
/* Runs to the case's end (time.end, time.max_steps, time.stop_when), with its outputs and
 * checkpoints; on instability the last good state is written (guard.last_good). */
RY_API int ry_sim_run(ry_sim *sim);
/* Asks a running ry_sim_run, ry_sim_step or ry_sim_advance_to to stop after the current step
 * (the state is checkpointed; the call returns 130). Safe to call from a signal handler. */
RY_API void ry_sim_request_stop(ry_sim *sim);
/* A function called during ry_sim_run every interval_s wall seconds with the time, the end
 * time, the step, the step's length, the speed (particle-steps per second) and the estimated
 * wall seconds left. NULL: none. */
typedef void (*ry_progress_fn)(void *ctx, double t, double t_end, long step, double dt,
                               double particle_steps_per_s, double eta_s);
RY_API int ry_sim_set_progress(ry_sim *sim, ry_progress_fn fn, void *ctx, double interval_s);

RY_API double ry_sim_time(const ry_sim *sim);
RY_API double ry_sim_end_time(const ry_sim *sim);
RY_API long ry_sim_step_count(const ry_sim *sim);
RY_API int ry_sim_dimension(const ry_sim *sim);
/* Particles of every kind (fluid, wall, solid, inflow and outflow buffers); with symmetry
 * planes, those simulated (not their mirror images), as for the fields below. */
RY_API size_t ry_sim_count(const ry_sim *sim);
RY_API const char *ry_sim_scheme(const ry_sim *sim);
RY_API const char *ry_sim_output_dir(const ry_sim *sim);

/* A field of doubles by name: "x", "y", "z", "vx", "vy", "vz", "ax", ..., "density",
 * "pressure", "mass", and the scheme's own (ry_sim_field_names); *n receives the particle
 * count. Read-only; valid until the next call that steps, restarts or destroys. */
RY_API int ry_sim_field(const ry_sim *sim, const char *name, const double **data, size_t *n);
/* "id", "kind" (0 fluid, 1 wall, 2 solid, 3 inflow buffer, 4 outflow buffer) and "material"
 * (the index of the case's material), as 64-bit integers (a copy kept by the handle). */
RY_API int ry_sim_int_field(const ry_sim *sim, const char *name, const int64_t **data, size_t *n);
/* The names of the fields of doubles, then "id", "kind", "material": the first max into names
 * (valid until the next call that steps); returns their number, or -1 on failure. */
RY_API int ry_sim_field_names(const ry_sim *sim, const char **names, int max);
/* The unit of a field ("m", "m/s", "kg/m^3", "1"; NULL for an unknown name). */
RY_API const char *ry_sim_field_unit(const ry_sim *sim, const char *name);
/* A measured quantity by name, as `ryushi probes` lists them (the first value of a probe with
 * several); with symmetry planes, the whole problem's, as in series.csv. */
RY_API int ry_sim_probe(ry_sim *sim, const char *name, double *value);
/* The probes by index from 0 (NULL past the last): the name ry_sim_probe takes and a line on
 * what it measures, as `ryushi probes` lists them. */
RY_API const char *ry_probe_name(int index);
RY_API const char *ry_probe_summary(int index);
/* A statistic of the run: "steps" (of the last ry_sim_run, ry_sim_step or ry_sim_advance_to
 * call), "wall_s" and "particle_steps_per_s" (of that call), "outputs", "searches",
 * "list_edits", "bytes_per_particle", or the scheme's (e.g. "iisph_iterations_mean"). */
RY_API int ry_sim_stat(const ry_sim *sim, const char *name, double *value);
/* The scheme's statistics as "name=value ..." (empty when it keeps none), and why the run
 * stopped before its end time (time.stop_when; empty otherwise). */
RY_API int ry_sim_report(const ry_sim *sim, char *buf, size_t size);
RY_API const char *ry_sim_stop_reason(const ry_sim *sim);

/* Writes the current state as an output (VTK file, .pvd entry, series.csv row) and a
 * checkpoint into OUT/checkpoints/. */
RY_API int ry_sim_write_output(ry_sim *sim);
RY_API int ry_sim_checkpoint(ry_sim *sim);

/* The message of this thread's last failed call ("" if none), and its kind in words
 * ("input error", "i/o error", "simulation unstable", "interrupted", "out of memory", ...). */
RY_API const char *ry_last_error(void);
RY_API const char *ry_last_error_kind(void);
RY_API const char *ry_version(void);

#ifdef __cplusplus
}
#endif

#endif
