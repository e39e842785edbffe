/* ryushi — geometry: bodies of particles on a lattice of spacing dx.
 *
 * Lattice points sit at cell centres, lo + (i + 1/2) dx, so that a fluid box and the walls
 * around it line up: a tank's wall layers lie at lo - (k + 1/2) dx. Every primitive appends
 * particles of one kind and material with a uniform initial velocity; mass is set later from
 * the material density (rho0 dx^d). */
#ifndef RYUSHI_GEOMETRY_H
#define RYUSHI_GEOMETRY_H

#include "ryushi/case.h"
#include "ryushi/particles.h"
#include "ryushi/status.h"

typedef struct ry_body_style {
    int kind;
    int material;
    double velocity[3];
} ry_body_style;

/* Filled rectangle (2D) or box (3D) [lo, hi]. */
ry_status ry_fill_box(ry_particles *ps, const double *lo, const double *hi, double dx,
                      const ry_body_style *st, size_t *added, ry_error *err);
/* The same box with a wavy top face: the largest coordinate (y in 2D, z in 3D) ends at
 * hi + amplitude cos(2 pi (x - lo_x) / wavelength) instead of hi (a perturbed interface). */
ry_status ry_fill_box_wave(ry_particles *ps, const double *lo, const double *hi, double amplitude,
                           double wavelength, double dx, const ry_body_style *st, size_t *added,
                           ry_error *err);
/* Filled circle (2D) or sphere (3D). */
ry_status ry_fill_sphere(ry_particles *ps, const double *centre, double radius, double dx,
                         const ry_body_style *st, size_t *added, ry_error *err);
/* A circle or sphere whose surface is perturbed by one mode (a drop set to oscillate): the
 * surface at R (1 + amplitude Y_n), Y_n = P_n(cos theta) in 3D (Legendre, theta from the z axis:
 * axisymmetric about it), cos(n phi) in 2D (phi from the y axis: symmetric about it), R scaled so
 * that the body holds the volume of the unperturbed one to second order in the amplitude. mode 0
 * is the plain sphere; otherwise 2 <= mode <= 16 and |amplitude| <= 0.5. */
ry_status ry_fill_sphere_mode(ry_particles *ps, const double *centre, double radius, int mode,
                              double amplitude, double dx, const ry_body_style *st, size_t *added,
                              ry_error *err);
/* Filled (3D) cylinder from base centre along an axis (unit vector computed from axis) of a
 * length, with an outer radius and an inner radius (0 for solid; > 0 gives a tube). */
ry_status ry_fill_cylinder(ry_particles *ps, const double *base, const double *axis, double length,
                           double radius, double inner_radius, double dx, const ry_body_style *st,
                           size_t *added, ry_error *err);
/* Walls of `layers` particle layers around the box [lo, hi] (the inside stays empty); with
 * open_top the wall at the top (largest coordinate of the last dimension) is left out. With
 * lid_velocity (may be NULL) the top wall above the cavity moves with that velocity (a sliding
 * lid); the corners stay with the side walls. */
ry_status ry_fill_tank(ry_particles *ps, const double *lo, const double *hi, int layers,
                       int open_top, const double *lid_velocity, double dx, const ry_body_style *st,
                       size_t *added, ry_error *err);

struct ry_stl;
/* A closed STL surface (3D; checked with ry_stl_check first) on the lattice (i + 1/2) dx anchored
 * at the origin. layers = 0: every lattice point inside the surface (winding number of a ray
 * along +x); layers > 0: only the inside points closer than layers * dx to the surface (a wall
 * shell). */
ry_status ry_fill_stl(ry_particles *ps, const struct ry_stl *m, double dx, int layers,
                      const ry_body_style *st, size_t *added, ry_error *err);

/* Reads the case's `bodies` sequence and fills them. material_names has nmat entries. When
 * first_id is not NULL it receives a malloc'd array of *nbodies + 1 ids: the particles of
 * bodies[k] have ids in [first_id[k], first_id[k + 1]) (ids are given in order and kept when a
 * particle is removed). */
ry_status ry_geometry_from_case(ry_particles *ps, ry_case *c, double dx,
                                const char *const *material_names, int nmat, int64_t **first_id,
                                size_t *nbodies, ry_error *err);

/* Removes the wall particles more than `layers` layers (of one spacing dx) from the space the
 * fluid can reach: the space no wall occupies that is connected to a non-wall particle, entering
 * the nzones boxes `zones` (open boundaries; lo[3] then hi[3] each) but not leaving them. The
 * others keep their order and ids; *removed receives the count. */
ry_status ry_walls_trim(ry_particles *ps, double dx, int layers, const double *zones, int nzones,
                        size_t *removed, ry_error *err);

#endif
