/* ryushi — the state of a simulation: particles, domain, kernel, materials, neighbour search,
 * the scheme's interface, and the queries every layer above the core may make of them.
 *
 * Data flows one way: case file -> ry_sim_setup (ryushi/run.h: validated parameters, bodies
 * filled with particles) -> ry_run [neighbour search -> scheme step -> measurements ->
 * output]. A scheme (WCSPH, IISPH, MPS, solid SPH) is a table of functions (ry_scheme_type)
 * registered by name in src/schemes/registry.c and chosen by the case's `scheme.name`. */
#ifndef RYUSHI_SIM_H
#define RYUSHI_SIM_H

#include <stdio.h>

#include "ryushi/case.h"
#include "ryushi/kernel.h"
#include "ryushi/neighbor.h"
#include "ryushi/particles.h"
#include "ryushi/material.h"
#include "ryushi/status.h"

typedef struct ry_sim ry_sim;

/* A named scalar of a scheme's own state (beside its particle fields), saved in checkpoints
 * and in the last-good snapshot; exactly one of the pointers is set. */
typedef struct ry_state_var {
    const char *name;
    double *f64;
    int *i32;
    long *i64;
} ry_state_var;

typedef struct ry_material {
    char *name;
    double density;   /* reference density rho0 [kg/m^3] */
    double viscosity; /* kinematic viscosity nu [m^2/s] (Oldroyd-B: the solvent's) */
    ry_rheology rheo; /* Newtonian unless materials[i].rheology says otherwise */
} ry_material;

/* What a scheme can do (ry_scheme_type.caps). */
enum {
    RY_SCHEME_RHEOLOGY = 1 << 0, /* carries non-Newtonian materials (materials[i].rheology) */
};

/* A scheme: how particles advance in time. */
/* What a scheme needs of the core for the case at hand (ry_scheme_type.needs); the core starts
 * from ry_scheme_needs_default and keeps the result in its own fields. */
typedef struct ry_scheme_needs {
    double skin;     /* default Verlet skin, a fraction of the search radius (the case's
                        neighbors.skin overrides it); 0: the core's default, 0.15 */
    int sort_always; /* reorder at every search (by cell, and by x within each cell), so that
                        the particles of each cell are consecutive */
    int cells_only;  /* the cells of the search only, no neighbour list */
    int keep_order;  /* never reorder the particles (per-particle arrays indexed like them) */
    int open_sink;   /* outlets are sinks: fluid that crosses an outlet's downstream face inside
                        its cross-section is removed, and no outlet buffer particles are made */
    int halo_depth;  /* distributed runs: search radii of halo (2: a value a halo particle
                        computes from its own neighbours is right where an owned particle reads
                        it; 1 for a scheme that synchronises every such value) */
    int dd_x[3];     /* distributed runs: the fields of the coordinates the decomposition
                        follows (the positions, or a scheme's reference positions) */
    double max_speed, rho_min, rho_max; /* the guard's defaults (case section `guard`
                                           overrides them; 0: no limit) */
} ry_scheme_needs;

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
    /* Optional: lists up to max state variables (returns how many). Everything else a scheme
     * keeps must be either a particle field or derivable from the fields. */
    int (*state_vars)(void *state, ry_state_var *vars, int max);
    /* Optional: a line of `key=value` statistics for the run summary (e.g. solver iterations). */
    void (*report)(void *state, char *buf, size_t size);
    /* Optional: the statistic `name` of the scheme's current state into *value (e.g.
     * "pressure_iterations"); returns 0 when the scheme keeps no statistic of that name.
     * docs/ARCHITECTURE.md lists the names in use. */
    int (*stat)(const ry_sim *sim, const void *state, const char *name, double *value);
    /* Optional: what the scheme needs of the core for this case (called once, after init; the
     * defaults of ry_scheme_needs_default where absent). */
    void (*needs)(const ry_sim *sim, const void *state, ry_scheme_needs *needs);
    /* Optional: bytes of the buffers the scheme holds besides particle fields (for the memory
     * figures of `ryushi bench`). */
    size_t (*bytes)(const void *state);
    unsigned caps; /* RY_SCHEME_* flags */
} ry_scheme_type;

/* Memory per particle of a set-up simulation: particle fields, cells, neighbour list and the
 * scheme's own buffers. */
double ry_sim_bytes_per_particle(const ry_sim *sim);

/* A distributed run (the ryushi-mpi program, src/parallel/): each process (rank) holds the
 * particles of its subdomain and copies of its neighbours' particles near its boundary (halo
 * particles, flagged in sim->halo). The core calls these hooks where a serial run would act
 * alone; a serial run has sim->par NULL. Every hook is collective: all ranks call it together. */
typedef struct ry_par_ops {
    /* Logical AND of flag over the ranks. */
    int (*all)(ry_sim *sim, int flag);
    /* Largest of v over the ranks, and the sum. */
    double (*max)(ry_sim *sim, double v);
    double (*sum)(ry_sim *sim, double v);
    /* A scheme's own per-particle array (ncomp values per particle, interleaved) from the
     * owners to their halo copies: for solvers whose passes read their neighbours' results
     * of the pass before (e.g. an iterative pressure solve). Three values per particle are a
     * vector; one is a scalar, or, with odd, a quantity a mirror negates (bit d: a mirror
     * across axis d; a vector's component d has 1 << d, see ry_field_info.odd). */
    void (*sync)(ry_sim *sim, double *a, int ncomp, unsigned odd);
    /* The same for a particle field k (its own parity; positions mirrored). */
    void (*sync_field)(ry_sim *sim, int k);
    /* At a neighbour search: drops the halo, moves particles to the ranks that own their
     * positions (re-balancing the subdomains when needed) and receives the new halo, which
     * reaches 2 * reach beyond the subdomain (so that a quantity of a halo particle computed
     * from its own neighbours, e.g. a wall's pressure, is right where an owned particle uses
     * it). */
    ry_status (*redistribute)(ry_sim *sim, double reach, ry_error *err);
    /* After a restart, before the list of the last search is built again from the positions
     * it was built at (sim->f_xref): the halo of that search, from those positions. NULL
     * where a restart searches afresh (a distributed run). */
    ry_status (*redistribute_at_ref)(ry_sim *sim, double reach, ry_error *err);
    /* Between searches: the halo particles' fields from their owners. */
    ry_status (*halo_update)(ry_sim *sim, ry_error *err);
    /* Before a search reorders the particles by cell: may rearrange order (a permutation);
     * returns non-zero when it did, and the cells are then binned afresh. NULL: none. */
    int (*partition)(ry_sim *sim, uint32_t *order);
    /* After the particles were reordered (ry_particles_permute with order). */
    void (*permuted)(ry_sim *sim, const uint32_t *order);
    /* The guard's verdict from this rank's tallies (see ry_check_verdict). */
    ry_status (*verdict)(const ry_sim *sim, size_t bad, size_t fluid, size_t outside,
                         ry_error *err);
    /* The open boundaries' conversions after a step (ry_open_update) on each rank's own
     * particles, with the ids of the particles created made unique over the ranks. */
    ry_status (*open_update)(ry_sim *sim, ry_error *err);
    /* Output (VTK, .pvd entry, series.csv row) and checkpoints of the whole set. */
    ry_status (*output)(ry_sim *sim, ry_error *err);
    ry_status (*checkpoint)(ry_sim *sim, char *path, size_t path_size, ry_error *err);
    /* A serial run's halo (symmetry planes' mirror copies; NULL in a distributed run): for a
     * copy i, its original's index and the axes of the mirror between them (non-zero
     * returned); 0 for a particle of the set. A linear system may then fold a copy's
     * coefficient onto its original's unknown and be solved by one process. */
    int (*copy_of)(const ry_sim *sim, size_t i, size_t *orig, unsigned *axes);
} ry_par_ops;

/* A measured quantity written as a column of series.csv. A probe of an item of a case section
 * (a retina region) has eval NULL and eval_item, called with its item's index; ry_probe_eval
 * calls either. */
typedef struct ry_probe {
    const char *name;
    const char *summary;
    ry_status (*eval)(const ry_sim *sim, double *value, ry_error *err);
    ry_status (*eval_item)(const ry_sim *sim, int item, double *value, ry_error *err);
    int item;
} ry_probe;

/* Case section `retina_regions` (3D, two materials): named regions of the wall, each the wall
 * particles whose direction from `centre` lies within half_angle of `direction`; each adds the
 * column coverage_NAME to series.csv (docs/reference/probes.md). */
typedef struct ry_region {
    char *name;
    double centre[3], dir[3]; /* dir: unit */
    double cos_half;          /* cos(half_angle) */
    ry_probe probe;           /* coverage_NAME */
} ry_region;

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

/* An open boundary (case section `open_boundaries`). An inlet is a zone of buffer particles
 * moving with the prescribed velocity; one that crosses the zone's downstream face becomes
 * fluid and a new buffer particle enters one zone length upstream (so the lattice is kept). At
 * an outlet, fluid that crosses the zone's upstream face becomes an outlet buffer particle:
 * it moves on as fluid at the outlet's pressure (and the reference density) and is removed
 * when it leaves the zone (with sim->open_sink, fluid is removed at the downstream face
 * instead). A rate outlet (`flow_rate` or `velocity` given instead of `pressure`) takes the
 * flow out at a prescribed rate: fluid that crosses its upstream face becomes a buffer particle
 * of kind RY_KIND_INLET that moves on at the prescribed velocity, a wall to the fluid as an
 * inlet's buffer is, and is removed at the downstream face. The flow direction is along one
 * axis. */
enum { RY_OPEN_INLET, RY_OPEN_OUTLET };
typedef struct ry_open_boundary {
    int type;
    double lo[3], hi[3]; /* zone */
    int axis, sign;      /* flow along +axis (sign 1) or -axis (sign -1) */
    double velocity[3];  /* inlet (and rate outlet) velocity [m/s] */
    double ramp;         /* inlet: seconds over which the velocity rises from 0 (0: at once) */
    int ramped;          /* inlet: its buffer has been set to the full velocity after the ramp */
    double pressure;     /* outlet pressure [Pa] */
    int rate;            /* outlet: its buffer moves at `velocity` (a rate outlet) */
    int material;
    long count; /* inlet: particles turned fluid, less the fluid pushed back into the zone and
                   removed; outlet: particles removed */
} ry_open_boundary;

/* Limits that stop a run as unstable (case section `guard`); 0 disables a limit. */
typedef struct ry_guard {
    double max_speed;            /* [m/s] any particle faster */
    double rho_min, rho_max;     /* fluid density / reference density outside [min, max] */
    double max_outside_fraction; /* of the fluid particles outside the domain box */
    double min_dt_ratio;         /* the stable step below this times the run's largest */
    int last_good;               /* RY_LAST_GOOD_*: how the state before a failure is kept */
    int snapshot_every;          /* RY_LAST_GOOD_MEMORY: steps between in-memory copies */
} ry_guard;

/* What the time loop keeps from one call to the next (src/sim/run.c). */
typedef struct ry_loop_state {
    int begun, ended; /* the run's first output, check and checkpoint; its final ones */
    long first_step;  /* the step the run began at */
    double dt_peak;   /* the largest stable step so far (guard.min_dt_ratio) */
    long good_step;   /* the last step that passed the check */
    long ck_step;     /* the step of the newest checkpoint the run wrote (-1: none) */
    char ckpt[4300];  /* its file */
} ry_loop_state;

/* How a run keeps its last good state (case key guard.last_good). */
enum {
    RY_LAST_GOOD_REPLAY, /* replayed from the newest checkpoint up to the last checked step */
    RY_LAST_GOOD_MEMORY, /* an in-memory copy every guard.snapshot_every steps */
    RY_LAST_GOOD_NONE
};

/* Checkpoint policy (case section `checkpoint`). */
typedef struct ry_ckpt_policy {
    double interval;      /* simulated seconds between checkpoints (0: none) */
    long every_steps;     /* steps between checkpoints (0: none) */
    double wall_interval; /* wall seconds between checkpoints (0: none) */
    int keep;             /* checkpoints kept on disk */
    int at_end;           /* one at the end of the run */
    double next_t;        /* next simulated time due */
    double last_wall;     /* wall time of the last one */
    int scheduled;        /* the one being written is on the simulated schedule (interval,
                             every_steps, the end), not by the wall clock or a signal */
} ry_ckpt_policy;

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
    /* The case's bodies: the particles of bodies[k] have ids in
     * [body_first_id[k], body_first_id[k + 1]) (ry_sim_body_of). */
    size_t nbodies;
    int64_t *body_first_id;

    /* time */
    double t, t_end, dt;
    double cfl;    /* Courant number for the scheme's time-step limits */
    double dt_max; /* upper bound on dt (0: none) */
    long step, max_steps;
    int finished; /* the run has reached its goal (ry_sim_finish, or time.stop_when): the time
                     loop ends after this step */

    /* neighbour search */
    ry_cell_list cells;
    ry_nlist nl;
    double nl_radius;   /* support radius the list serves */
    double nl_skin;     /* Verlet skin (neighbors.skin; a scheme's init may preset its
                           default), a fraction of the radius: the list holds the pairs within
                           radius (1 + skin) and is rebuilt when a particle has moved more
                           than half the skin since the last build */
    int reorder_every;  /* reorder particles along cells every so many builds (0: never) */
    int sort_always;    /* the scheme's need (ry_scheme_needs.sort_always) */
    int cells_only;     /* the scheme's need: the cells only, not the list `nl` */
    long searches;      /* list builds so far */
    long nl_edits;      /* lists brought up to date after in- and outflow (ry_sim_list_edit) */
    long nl_generation; /* list and cell builds in this process (restarts included), for
                           schemes that derive data from them; not checkpointed */
    long nl_reuses;     /* steps that reused the list */
    int f_xref;         /* field: positions at the last build (x, y, z consecutive ids) */
    int nl_restore;     /* after a restart: rebuild the list from the positions at the last
                           build (xref), without reordering, so that it is the same list */
    int drift_known;    /* drift2 was measured by the scheme (ry_sim_drift_measured); the next
                           ry_sim_neighbors uses it instead of measuring, and clears this */
    double drift2;

    /* scheme */
    const ry_scheme_type *scheme;
    void *scheme_state;

    /* measurements */
    int nprobes;
    const ry_probe **probes;
    int nprofiles;
    ry_profile *profiles;
    /* Case section `droplet` (the droplet_* probes): the material whose droplet hangs from a
     * nozzle or catheter (-1: none), the height of the tip along the vertical (last) axis and
     * the horizontal position of the nozzle's axis (droplet.axis, default the origin). */
    int droplet_material;
    double droplet_tip;
    double droplet_axis[2];
    int nregions;
    ry_region *regions;
    /* Case key time.stop_when: the run ends at the first output whose measured quantity (one
     * of probes, index stop_probe; -1: none) lies above (stop_above) or below stop_value.
     * stop_reason then says so. */
    int stop_probe, stop_above;
    double stop_value;
    char stop_reason[192];

    /* output */
    char *out_dir;
    char *case_name; /* base name of the case file, without extension */
    double output_interval;
    int write_vtk;
    int write_pieces; /* distributed runs: each rank writes its piece of the VTK output */
    int vtk_pieces;   /* set by the parallel layer: this output's pieces are written; the VTK
                         file is a .pvtp of that many pieces */
    int output_index;
    double next_output;
    void *writer; /* output state (pvd entries, series buffer) */

    /* open boundaries */
    int nopen;
    ry_open_boundary *open;
    int open_sink; /* the scheme's need (ry_scheme_needs.open_sink; MPS): the free surface
                      an outlet sink leaves holds the pressure at 0 */

    /* reliability */
    ry_guard guard;
    ry_loop_state loop;
    void *api; /* what the library's interface keeps for its caller (src/api/api.c) */
    ry_ckpt_policy ckpt;
    int checked; /* the scheme's last loop of this step also made the guard check
                    (src/core/guard_check.h, ry_sim_checked), with the tallies below; the run
                    loop then gives the verdict without another pass, and clears this */
    size_t check_bad, check_fluid, check_outside;
    void *snapshot; /* the last good state (ry_sim_snapshot_*) */

    /* distributed runs (NULL in a serial run) */
    const ry_par_ops *par;
    void *par_state;
    const uint8_t *halo; /* halo[i]: particle i is a halo copy (see ry_par_ops) */
    int dd_x[3];         /* the scheme's needs (ry_scheme_needs.dd_x, .halo_depth) */
    int halo_depth;
};

/* Whether the run is spread over processes (ryushi-mpi), rather than serial (with or
 * without symmetry planes' hooks). */
static inline int ry_sim_distributed(const ry_sim *sim) {
    return sim->par && !sim->par->copy_of;
}

/* Whether particle i is a halo copy: of another rank's particle, or a symmetry plane's mirror copy.
 */
static inline int ry_sim_is_halo(const ry_sim *sim, size_t i) {
    return sim->halo && sim->halo[i];
}

/* Separation x_j - x_i of two particles (minimum image; zero beyond the dimension) and its
 * squared length. Written out where no side is periodic, so that an inlined caller's dx stays
 * in registers; the same values either way. */
static inline double ry_sim_separation(const ry_sim *sim, size_t i, size_t j, double dx[3]) {
    double *const *x = sim->ps.f + RY_F_X;
    const int plain = ry_box_plain(&sim->box);
    if (plain) {
        dx[0] = x[0][j] - x[0][i];
        dx[1] = x[1][j] - x[1][i];
        dx[2] = plain == 3 ? x[2][j] - x[2][i] : 0.0;
    } else {
        dx[0] = dx[1] = dx[2] = 0;
        for (int d = 0; d < sim->dim; ++d) dx[d] = x[d][j] - x[d][i];
        ry_box_min_image(&sim->box, dx);
    }
    return dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
}

/* A scheme's reports to the core during a step. ry_sim_drift_measured: its drift loop measured
 * drift2, the largest squared displacement since the last search, which the next
 * ry_sim_neighbors then uses instead of measuring. ry_sim_checked: its last loop over the
 * particles made the guard check (src/core/guard_check.h) with these tallies, so that the time
 * loop gives the verdict without another pass. ry_sim_finish: the run has reached its goal
 * (e.g. a static solution converged to its residual); the time loop ends after this step. */
void ry_sim_drift_measured(ry_sim *sim, double drift2);
void ry_sim_checked(ry_sim *sim, size_t bad, size_t fluid, size_t outside);
void ry_sim_finish(ry_sim *sim);
/* The needs of a scheme without a needs function. */
ry_scheme_needs ry_scheme_needs_default(const ry_sim *sim);

/* Brings the neighbour list up to date for a support radius: rebuilt (and the particles
 * reordered along cells every reorder_every builds, or every build with sort_always) when the
 * radius or the particle count changed or a particle moved more than half the skin since the last
 * build; otherwise the list is reused. Pair loops must skip pairs beyond the radius. Schemes call
 * this at the start of each force evaluation. */
ry_status ry_sim_neighbors(ry_sim *sim, double radius, ry_error *err);
/* After ry_open_update added nspawn particles at the end of the n_old there were (the list's
 * count) and removed those flagged in remove (indices below n_old, or NULL), with the survivors
 * compacted in order: the list becomes that of a search from the reference positions, with the
 * new particles' positions as theirs, so that the next call of ry_sim_neighbors can reuse it
 * (a search over every row otherwise follows each change of the count). Leaves the list to
 * the next search in a distributed run, with the cells alone, or without a skin. */
ry_status ry_sim_list_edit(ry_sim *sim, size_t n_old, size_t nspawn, const uint8_t *remove,
                           ry_error *err);
/* The cells of the last search when their 3 x 3 (x 3) blocks still hold every pair of particles
 * now closer than dist (the particle set unchanged since, in a run on one process, and no
 * particle moved so far since that such a pair could have left them), with *drift the largest
 * distance a particle moved since it was binned; NULL otherwise. For measurements that would
 * otherwise bin the particles again. */
const ry_cell_list *ry_sim_cells_within(const ry_sim *sim, double dist, double *drift);
/* The index of the body (bodies[k] of the case) a particle with this id came from, or -1 (a
 * particle made later, e.g. by an inlet). */
int ry_sim_body_of(const ry_sim *sim, int64_t id);
/* Whether a neighbour search has been made (a list, or the cells alone), so that a restored
 * state must rebuild it from the positions of that search. */
static inline int ry_sim_searched(const ry_sim *sim) {
    return sim->nl_restore || (sim->cells_only ? sim->cells.start != NULL : sim->nl.offset != NULL);
}

/* The running scheme's statistic `name` (ry_scheme_type.stat) into *value; returns 0, and leaves
 * *value alone, when the scheme keeps none of that name. */
int ry_scheme_stat(const ry_sim *sim, const char *name, double *value);
/* The same as a value: NAN when the scheme keeps no statistic of that name. */
double ry_sim_stat_value(const ry_sim *sim, const char *name);

/* Checks every particle for non-finite or runaway values and the domain; RY_ERR_UNSTABLE with
 * the first bad particles named. */
ry_status ry_sim_check(const ry_sim *sim, ry_error *err);

/* Counts fluid particles outside the domain box, and total mass of a kind. */
size_t ry_sim_count_outside(const ry_sim *sim);
/* Particles other than i within `radius` of it, found through the cells of the last neighbour
 * search (radius at most the cell edge minus the distance moved since). */
size_t ry_sim_count_within(const ry_sim *sim, size_t i, double radius);

/* Head position k of the eye cases (case key `head_position`): its name (NULL past the last)
 * and, in down, the direction of gravity in the eye's frame (x towards the patient's left, y
 * superior, z anterior). */
const char *ry_head_position(int k, double down[3]);

#endif
