/* ryushi — the particle set: a structure of arrays in double precision.
 *
 * Every per-particle quantity is one contiguous array ("field"). The core fields (position,
 * velocity, acceleration, density and its rate, pressure, mass, smoothing length, energy and
 * its rate) come from one table, RY_CORE_FIELDS; schemes register further fields by name
 * (e.g. a stress tensor) with ry_particles_add_field. Allocation, growth, removal, reordering,
 * output and checkpoints all walk the same field table, so a new field is handled everywhere
 * at once. Vector components beyond the dimension are not allocated (z is NULL in 2D).
 *
 * Integer data: a stable id (kept through reordering and removal, unique over the run), a kind
 * (fluid, wall, solid, ...) and a material index. */
#ifndef RYUSHI_PARTICLES_H
#define RYUSHI_PARTICLES_H

#include <stddef.h>
#include <stdint.h>

#include "ryushi/status.h"

/* X(ID, name, unit, component, flags): component is the vector component (0, 1, 2) or -1 for a
 * scalar; flags are RY_FIELD_* bits. */
#define RY_CORE_FIELDS(X)                                                                          \
    X(RY_F_X, "x", "m", 0, RY_FIELD_STATE | RY_FIELD_POSITION)                                     \
    X(RY_F_Y, "y", "m", 1, RY_FIELD_STATE | RY_FIELD_POSITION)                                     \
    X(RY_F_Z, "z", "m", 2, RY_FIELD_STATE | RY_FIELD_POSITION)                                     \
    X(RY_F_VX, "vx", "m/s", 0, RY_FIELD_STATE)                                                     \
    X(RY_F_VY, "vy", "m/s", 1, RY_FIELD_STATE)                                                     \
    X(RY_F_VZ, "vz", "m/s", 2, RY_FIELD_STATE)                                                     \
    X(RY_F_AX, "ax", "m/s^2", 0, 0)                                                                \
    X(RY_F_AY, "ay", "m/s^2", 1, 0)                                                                \
    X(RY_F_AZ, "az", "m/s^2", 2, 0)                                                                \
    X(RY_F_RHO, "density", "kg/m^3", -1, RY_FIELD_STATE)                                           \
    X(RY_F_DRHO, "density_rate", "kg/m^3/s", -1, 0)                                                \
    X(RY_F_P, "pressure", "Pa", -1, RY_FIELD_STATE)                                                \
    X(RY_F_MASS, "mass", "kg", -1, RY_FIELD_STATE)                                                 \
    X(RY_F_H, "smoothing_length", "m", -1, RY_FIELD_STATE | RY_FIELD_ON_REQUEST)                   \
    X(RY_F_E, "energy", "J/kg", -1, RY_FIELD_STATE | RY_FIELD_ON_REQUEST)                          \
    X(RY_F_DE, "energy_rate", "W/kg", -1, RY_FIELD_ON_REQUEST)

enum {
    /* part of the physical state (a label: checkpoints and the last good state hold every
     * field but the RY_FIELD_SCRATCH ones, since a step may read a derived field such as the
     * acceleration before it recomputes it) */
    RY_FIELD_STATE = 1,
    RY_FIELD_OUTPUT = 2, /* written to VTK output by default */
    /* no array (f[k] NULL) until a scheme asks for it (ry_particles_use_field): a variable
     * smoothing length, the energy equation */
    RY_FIELD_ON_REQUEST = 4,
    /* rewritten within every step before it is read (a half-step value): neither checkpointed
     * nor kept in the guard's last good state */
    RY_FIELD_SCRATCH = 8,
    /* a coordinate (component 0..2) of a point: a mirror maps it to the plane's far side
     * rather than negating it */
    RY_FIELD_POSITION = 16
};

typedef enum ry_field_id {
#define RY_FIELD_ENUM_(id, name, unit, comp, flags) id,
    RY_CORE_FIELDS(RY_FIELD_ENUM_)
#undef RY_FIELD_ENUM_
        RY_F_CORE_COUNT
} ry_field_id;

typedef enum ry_kind {
    RY_KIND_FLUID = 0,
    RY_KIND_WALL = 1,   /* fixed or moving boundary (dummy) particle */
    RY_KIND_SOLID = 2,  /* elastic solid */
    RY_KIND_INLET = 3,  /* inflow buffer: moves with the prescribed velocity, becomes fluid */
    RY_KIND_OUTLET = 4, /* outflow buffer: former fluid, moves on and is removed */
    RY_KIND_COUNT
} ry_kind;

typedef struct ry_field_info {
    char *name;
    char *unit;
    int component; /* 0..2 for vector components, -1 for scalars */
    int flags;
    /* The axes (bit d for axis d) whose mirror negates the value (a symmetry plane's copies):
     * 1 << component for a vector's component, none for a scalar (the default); a tensor's
     * component ab sets it to (1 << a) ^ (1 << b) (ry_particles_set_parity). */
    unsigned odd;
} ry_field_info;

typedef struct ry_particles {
    int dim;
    size_t n;   /* particles in use */
    size_t cap; /* allocated */
    int nfields;
    int cap_fields;
    double **f;          /* f[field][particle]; NULL for components >= dim */
    ry_field_info *info; /* per field */
    int64_t *id;         /* stable id */
    uint8_t *kind;       /* ry_kind */
    uint8_t *material;   /* index into the simulation's materials */
    int64_t next_id;     /* id given to the next particle added */
    void *scratch;       /* the reordering's bits (a bit per particle and thread) */
    size_t scratch_bytes;
} ry_particles;

const char *ry_kind_name(ry_kind kind);
int ry_kind_from_name(const char *name); /* -1 when unknown */

/* Upper bound on the particles of any set in this process (default UINT32_MAX). Adding beyond it
 * is an RY_ERR_RANGE error naming the limit; bodies also refuse to examine more than 8 times as
 * many lattice points. Meant for limiting memory (fuzzing, shared machines). */
void ry_particles_set_limit(size_t max);
size_t ry_particles_limit(void);

/* Sets up an empty set with the core fields. */
ry_status ry_particles_init(ry_particles *ps, int dim, ry_error *err);
void ry_particles_free(ry_particles *ps);
/* Gives field k (flagged RY_FIELD_ON_REQUEST) its array, zero for every particle. */
ry_status ry_particles_use_field(ry_particles *ps, int k, ry_error *err);
/* Ensures room for cap particles. */
ry_status ry_particles_reserve(ry_particles *ps, size_t cap, ry_error *err);
/* Appends count particles with zeroed fields, new ids, kind fluid and material 0; *first is
 * the index of the first one. */
ry_status ry_particles_add(ry_particles *ps, size_t count, size_t *first, ry_error *err);
/* Removes the particles whose remove[i] is non-zero, keeping the order of the others. */
void ry_particles_remove(ry_particles *ps, const uint8_t *remove);
/* Reorders: particle k after the call is particle order[k] before it (order a permutation). */
ry_status ry_particles_permute(ry_particles *ps, const uint32_t *order, ry_error *err);
/* Registers a field (or finds an existing one of that name); *id is its index. */
ry_status ry_particles_add_field(ry_particles *ps, const char *name, const char *unit,
                                 int component, int flags, int *id, ry_error *err);
/* Sets field k's odd axes (see ry_field_info.odd). */
void ry_particles_set_parity(ry_particles *ps, int k, unsigned odd);
/* Field index by name, -1 when absent. */
int ry_particles_field(const ry_particles *ps, const char *name);
/* Bytes per particle held by the set's arrays. */
size_t ry_particles_bytes_per_particle(const ry_particles *ps);
/* Kinetic energy sum 1/2 m v^2 of the particles of one kind (dim velocity components); with
 * mass_scale (one factor per particle, may be NULL), of the scaled masses. */
double ry_particles_kinetic_energy(const ry_particles *ps, int dim, ry_kind kind,
                                   const double *mass_scale);
/* The same without the particles whose skip[i] is non-zero (skip may be NULL). */
double ry_particles_kinetic_energy_of(const ry_particles *ps, int dim, ry_kind kind,
                                      const double *mass_scale, const uint8_t *skip);
/* Fourth-order shape moment of a drop: the particles of one kind about their centroid, the
 * amplitude of the cubic (3D) or square (2D) deformation: <x^4 + y^4 + z^4> / <r^4> - 3/5 in 3D,
 * <x^4 + y^4> / <r^4> - 3/4 in 2D (1D: 0). Zero for any isotropic set (a sphere, a circle); a
 * uniform cube reads -12/95 = -0.1263, a square -3/28 = -0.1071, the same shapes turned by 45
 * degrees positive values. Each particle counts once, so it averages over the whole drop. The
 * drop is the particles within twice the equivalent radius R (N dx^dim the volume) of the
 * median of each coordinate, so that particles thrown off, whose r^4 would outweigh thousands,
 * do not count; the moments are taken about the centroid of that drop (and of the particles
 * within 2 R of it). NAN without particles of the kind. */
double ry_particles_shape_m4(const ry_particles *ps, int dim, ry_kind kind, double dx);
/* The drop's mode-2 shape moment about its centroid (same particles as ry_particles_shape_m4):
 * <z^2 - (x^2 + y^2)/2>/<r^2> in 3D, <y^2 - x^2>/(2 <r^2>) in 2D. For a drop whose surface lies
 * at R (1 + eps P_2(cos theta)) (3D) or R (1 + eps cos 2 phi) (2D, phi from the y axis) it is eps
 * to first order; 0 for a sphere or circle. */
double ry_particles_shape_p2(const ry_particles *ps, int dim, ry_kind kind, double dx);
/* Coordinates as the neighbour search takes them (x[d] for d < dim, NULL beyond). */
static inline void ry_particles_coords(const ry_particles *ps, const double *x[3]) {
    x[0] = ps->f[RY_F_X];
    x[1] = ps->f[RY_F_Y];
    x[2] = ps->dim > 2 ? ps->f[RY_F_Z] : 0;
}

#endif
