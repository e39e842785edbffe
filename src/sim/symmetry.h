/* Symmetry planes (domain.symmetry, docs/guide.md "Symmetry planes"): half or a quarter of a
 * symmetric problem is simulated, and the particles within reach of each plane are mirrored
 * across it as copies that every scheme reads as neighbours.
 *
 * The copies are the halo of the distributed runs' hooks (ry_par_ops) in a serial run: made
 * afresh at each neighbour search (2 * reach deep, sim->halo_depth reaches), refreshed from
 * their originals between searches, flagged in sim->halo, never integrated. A copy's position
 * is its original's mirrored, and a field's value is its original's, negated where the mirror
 * reverses it (ry_field_info.odd: a vector's normal component, a tensor's shear component
 * across the plane). Copies always follow the set's own particles (indices from
 * ry_symmetry_owned on), so output, checkpoints, measurements and the library's accessors
 * see the own particles as the first ones. A particle that crosses a plane is reflected back.
 * Near two (three) planes a particle has a copy across each and one across both (all). */
#ifndef RY_SIM_SYMMETRY_H
#define RY_SIM_SYMMETRY_H

#include "ryushi/case.h"
#include "ryushi/sim.h"

/* Reads domain.symmetry (a list of x_lo, x_hi, y_lo, ...: planes at the faces of the domain
 * box, which must be set up) and removes the particles beyond the planes (the mirror gives
 * them back). Called by the set-up before the domain's particles are checked. */
ry_status ry_symmetry_read(ry_sim *sim, ry_case *c, ry_error *err);

/* Puts the copies' hooks in place when sim->box has symmetry planes (the end of the set-up). */
ry_status ry_symmetry_attach(ry_sim *sim, ry_error *err);
void ry_symmetry_detach(ry_sim *sim);

/* The particles of the set itself, copies excluded (sim->ps.n without symmetry planes). */
size_t ry_symmetry_owned(const ry_sim *sim);

/* Runs fn on the whole problem: the set's own particles and their mirror images across each
 * plane and each pair (triple) of planes, with cells and a list over them; then puts the
 * simulation back as it was. Measurements of a run with symmetry planes (series.csv, profiles,
 * time.stop_when, the library's probes) are the whole problem's. Without planes, fn on sim. */
typedef ry_status (*ry_measure_fn)(ry_sim *sim, void *ctx, ry_error *err);
ry_status ry_symmetry_measure(ry_sim *sim, ry_measure_fn fn, void *ctx, ry_error *err);

/* While hidden, sim->ps.n counts the set's own particles only and the run is a serial one to
 * whatever reads it (output, measurements, checkpoints). */
typedef struct ry_symmetry_hidden {
    size_t n;
    const uint8_t *halo;
    const ry_par_ops *par;
} ry_symmetry_hidden;
void ry_symmetry_hide(ry_sim *sim, ry_symmetry_hidden *h);
void ry_symmetry_show(ry_sim *sim, const ry_symmetry_hidden *h);

#endif
