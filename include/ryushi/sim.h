/* ryushi — the simulation: particles, domain, kernel, materials, scheme and time loop.
 *
 * Data flows one way: case file -> ry_sim_setup (validated parameters, bodies filled with
 * particles) -> ry_sim_run [neighbour search -> scheme step -> measurements -> output]. A
 * scheme (WCSPH, IISPH, MPS, solid SPH) is a small table of functions registered by name in
 * src/core/schemes.c and chosen by the case's `scheme.name`. */
#ifndef RYUSHI_SIM_H
#define RYUSHI_SIM_H

#include <signal.h>
#include <stdio.h>

#include "ryushi/case.h"
#include "ryushi/kernel.h"
#include "ryushi/neighbor.h"
#include "ryushi/particles.h"
#include "ryushi/status.h"

typedef struct ry_sim ry_sim;

typedef struct ry_material {
    char *name;
    double density;   /* reference density rho0 [kg/m^3] */
    double viscosity; /* kinematic viscosity nu [m^2/s] */
} ry_material;

/* A scheme: how particles advance in time. */
typedef struct ry_scheme_type {
    const char *name;
    const char *summary;
    /* Reads the scheme's keys from the case (section "scheme"), registers its particle fields
     * and prepares its state. */
    ry_status (*init)(ry_sim *sim, ry_case *c, void **state, ry_error *err);
    /* Largest stable time step for the current state. */
    ry_status (*stable_dt)(ry_sim *sim, void *state, double *dt, ry_error *err);
    /* Advances the state by dt (sim->t is advanced by the caller). */
    ry_status (*step)(ry_sim *sim, void *state, double dt, ry_error *err);
    void (*free)(void *state);
} ry_scheme_type;

/* The registered schemes, NULL-terminated. */
const ry_scheme_type *const *ry_schemes(void);
const ry_scheme_type *ry_scheme_find(const char *name);

/* A measured quantity written as a column of series.csv. */
typedef struct ry_probe {
    const char *name;
    const char *summary;
    ry_status (*eval)(const ry_sim *sim, double *value, ry_error *err);
} ry_probe;
const ry_probe *const *ry_probes(void);

/* A line profile (case file `profiles`): values sampled at evenly spaced points from `from` to
 * `to` at every output time, the state at that time or, with `average_from`, the mean over all
 * output times from then on. */
typedef struct ry_profile {
    char *name;
    double from[3], to[3];
    int npoints;
    int averaged;        /* average over output times t >= average_from */
    double average_from; /* [s] */
    int nsamples;        /* samples in sum */
    double *sum;         /* npoints x (dim velocity components, p, rho) */
} ry_profile;

struct ry_sim {
    int dim;
    ry_particles ps;
    ry_box box;        /* domain: neighbour search, and particles leaving it */
    double dx;         /* initial particle spacing [m] */
    double h_over_dx;  /* smoothing length / spacing */
    ry_kernel kernel;  /* at h = h_over_dx * dx */
    double gravity[3]; /* [m/s^2] */
    int nmat;
    ry_material *mat;

    /* time */
    double t, t_end, dt;
    double cfl;    /* Courant number for the scheme's time-step limits */
    double dt_max; /* upper bound on dt (0: none) */
    long step, max_steps;
    int finished; /* set by a scheme when the run has reached its goal (e.g. a static solution
                     converged to its residual): the time loop ends after that step */

    /* neighbour search */
    ry_cell_list cells;
    ry_nlist nl;
    double nl_radius;  /* support radius the list serves */
    double nl_skin;    /* Verlet skin, a fraction of the radius: the list holds the pairs
                          within radius (1 + skin) and is rebuilt when a particle has moved
                          more than half the skin since the last build */
    int reorder_every; /* reorder particles along cells every so many builds (0: never) */
    long searches;     /* list builds so far */
    long nl_reuses;    /* steps that reused the list */
    int f_xref;        /* field: positions at the last build (x, y, z consecutive ids) */

    /* scheme */
    const ry_scheme_type *scheme;
    void *scheme_state;

    /* measurements */
    int nprobes;
    const ry_probe **probes;
    int nprofiles;
    ry_profile *profiles;

    /* output */
    char *out_dir;
    char *case_name; /* base name of the case file, without extension */
    double output_interval;
    int write_vtk;
    int output_index;
    double next_output;
    void *writer; /* output state (pvd entries, series buffer) */
};

/* Builds the simulation from a case; checks every key (unknown keys are errors). out_dir may
 * be NULL to take the case's output.folder. */
ry_status ry_sim_setup(ry_sim *sim, ry_case *c, const char *out_dir, ry_error *err);
void ry_sim_free(ry_sim *sim);

/* Brings the neighbour list up to date for a support radius: rebuilt (and the particles
 * reordered along cells every reorder_every builds) when the radius or the particle count
 * changed or a particle moved more than half the skin since the last build; otherwise the
 * list is reused. Pair loops must skip pairs beyond the radius. Schemes call this at the
 * start of each force evaluation. */
ry_status ry_sim_neighbors(ry_sim *sim, double radius, ry_error *err);

/* Progress reports and the stop flag for ry_sim_run. */
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
ry_status ry_sim_run(ry_sim *sim, const ry_run_hooks *hooks, ry_run_stats *stats, ry_error *err);

/* Creates the output folder, writes the resolved case into it (case_resolved.yaml) and
 * starts series.csv. Call before ry_sim_run. */
ry_status ry_sim_open_output(ry_sim *sim, ry_case *c, ry_error *err);

/* Writes the current state (VTK file, .pvd entry, series.csv row). */
ry_status ry_sim_write_output(ry_sim *sim, ry_error *err);

/* Checks every particle for non-finite or runaway values and the domain; RY_ERR_UNSTABLE with
 * the first bad particles named. */
ry_status ry_sim_check(const ry_sim *sim, ry_error *err);

/* Counts fluid particles outside the domain box, and total mass of a kind. */
size_t ry_sim_count_outside(const ry_sim *sim);

/* Profiles: read from the case (ry_sim_setup calls it), sampled and written as
 * profile_NAME.csv at each output time (ry_sim_write_output calls it), freed. */
ry_status ry_profiles_setup(ry_sim *sim, ry_case *c, ry_error *err);
ry_status ry_profiles_output(ry_sim *sim, ry_error *err);
void ry_profiles_free(ry_sim *sim);
const ry_profile *ry_profile_find(const ry_sim *sim, const char *name);
/* Point k of a profile (x has 3 entries, unused ones 0). */
void ry_profile_point(const ry_sim *sim, const ry_profile *pf, int k, double *x);
/* Mean so far of value `value` (0..dim-1 velocity, dim pressure, dim + 1 density) at point k;
 * NAN before the first sample. */
double ry_profile_mean(const ry_sim *sim, const ry_profile *pf, int k, int value);
/* Shepard interpolation at x of velocity, pressure and density (dim + 2 values) over fluid and
 * wall particles; 0 (and NANs) when no particle is within the kernel support. */
int ry_sample_point(const ry_sim *sim, const double *x, double *out);

/* Monotonic wall clock in seconds. */
double ry_wall_time(void);

#endif
