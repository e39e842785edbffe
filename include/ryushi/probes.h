/* ryushi — measurements: the probes (columns of series.csv) and line profiles. */
#ifndef RYUSHI_PROBES_H
#define RYUSHI_PROBES_H

#include "ryushi/sim.h"

/* Contact angle [degrees] of a sessile drop shaped as a circular cap (2D: a circular segment
 * of area A; 3D: a spherical cap of volume V) of height h on a flat wall: 2D, theta solves
 * (1 - cos theta)^2 / (theta - sin theta cos theta) = h^2 / A (bisection); 3D,
 * cos theta = (1 - 2 q) / (1 + q), q = pi h^3 / (3 V). NAN when h or A is not positive. */
double ry_cap_contact_angle(int dim, double h, double size);

/* The registered probes, NULL-terminated. */
const ry_probe *const *ry_probes(void);
/* A probe's value (eval, or eval_item with its item). */
ry_status ry_probe_eval(const ry_probe *p, const ry_sim *sim, double *value, ry_error *err);

/* The share of the wetted wall (as the probe oil_wall_contact counts it: the wall particles
 * with a fluid particle within the kernel support, the ports' channels and collars left out;
 * with reg, only those in its cone) whose direction from centre makes an angle with up of
 * cosine cos_min or more: the wall a lighter liquid covers above a horizontal contact line at
 * height cos_min R in a sphere of radius R (ry_tamponade's z_contact). */
ry_status ry_wall_share_above(const ry_sim *sim, const ry_region *reg, const double centre[3],
                              const double up[3], double cos_min, double *share, ry_error *err);

/* The case section `retina_regions` (ry_sim_setup calls it; each region's probe is appended
 * to the measurements), and its release. */
ry_status ry_regions_setup(ry_sim *sim, ry_case *c, ry_error *err);
void ry_regions_free(ry_sim *sim);

/* Profiles: read from the case (ry_sim_setup calls it), sampled and written as
 * profile_NAME.csv at each output time (ry_output_write calls it), freed. */
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

/* Largest speed of the fluid particles whose coordinate `axis` lies in [lo, hi]. */
double ry_band_max_speed(const ry_sim *sim, int axis, double lo, double hi);

#endif
