/* ryushi — the beam a set of solid particles forms, by their reference positions.
 *
 * Beams lie along x: the solid particles (kind solid) form the beam, the particles of kind wall
 * are clamped (fixed at their initial position) and should fill a few layers behind the root so
 * that the kernel support of the root particles is complete. The beam's root is half a spacing
 * before its first particle column, its free end half a spacing after the last one; its length
 * L is the distance between the two and its cross-section A = (solid volume) / L.
 *
 * Reference positions are the particle fields x0, y0, z0 where a scheme keeps them (the scheme
 * `solid` does), else the current positions. */
#ifndef RYUSHI_BEAM_H
#define RYUSHI_BEAM_H

#include <math.h>

#include "ryushi/sim.h"

/* k1 L = 1.8751040687: the first root of cos(kL) cosh(kL) = -1, the first bending mode of a
 * clamped-free beam. */
#define RY_CANTILEVER_KL1 1.8751040687119611

/* Beam geometry of the solid particles: root x, length L, cross-section A, spacing of the
 * particle columns. RY_ERR_INPUT when there is no solid particle. */
typedef struct ry_beam {
    double x_root, length, area;
    double centre[3]; /* reference centroid of the cross-section (y, z) */
    int ncol;         /* particle columns along x */
} ry_beam;
ry_status ry_beam_geometry(const ry_sim *sim, ry_beam *beam, ry_error *err);

/* The fields of the reference positions (x0, y0, z0) into f[0..dim-1]; 0 when the particles
 * have none. */
int ry_beam_reference_fields(const ry_sim *sim, int f[3]);

/* Column (0 .. ncol-1) of a solid particle by its reference x. */
static inline int ry_beam_column(const ry_beam *b, double dx, double X) {
    int k = (int)lround((X - b->x_root) / dx - 0.5);
    return k < 0 ? 0 : k >= b->ncol ? b->ncol - 1 : k;
}

#endif
