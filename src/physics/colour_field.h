/* Two-phase interface by a colour field (seed 004, eq. 7-8; Brackbill et al. 1992 continuum
 * surface force in the number-density form of Hu & Adams 2006).
 *
 *  colour       c_i = 1 for particles of the colour material, 0 for the other fluid
 *  smoothing    c'_i = sum_j (c_j / delta_j) W_ij / sum_j (1 / delta_j) W_ij    (seed eq. 8)
 *               delta_i = sum_j W_ij, the number density (fluid neighbours, self included)
 *  normal       n_i = grad c'_i = sum_j V_j (c'_j - c'_i) grad_i W_ij,  V_j = 1 / delta_j
 *  curvature    kappa_i = -div(n / |n|) = d sum_j V_j (nh_i - nh_j) . grad_i W_ij
 *                                         / sum_j V_j |x_ij| |grad_i W_ij|
 *               over the neighbours with a reliable normal, |n| > eps / h (Morris 2000)
 *  average      kappa_i <- sum_j |n_j| kappa_j W_ij / delta_j / sum_j |n_j| W_ij / delta_j over
 *               the particle and its neighbours with a reliable normal, `smoothing` passes: one
 *               curvature for the particles of the interface's band, which cuts the parasitic
 *               currents of a curvature that scatters from particle to particle
 *  force        F_i = (1 / delta_i) sigma kappa_i n_i                          (seed eq. 7)
 *               with Brackbill's density scaling: the force per volume sigma kappa n is
 *               weighted by 2 rho_i / (rho_a + rho_b) (rho_a, rho_b the two reference
 *               densities), so that both phases get the same acceleration
 *               sigma kappa n / rhobar, rhobar = (rho_a + rho_b) / 2: a light phase (air) is not
 *               kicked by the force the heavy side needs.
 *  contact angle (wet) the unit normal of an interface particle with a wall particle within 1.5
 *               spacings is turned to meet the wall at theta, measured through the phase without
 *               colour (Brackbill et al. 1992, section 2.3): nh = cos(theta) n_w + sin(theta) t,
 *               n_w the wall's normal into the fluid (-sum_walls grad_i W_ij, normalised), t the
 *               normal's part along the wall (normalised); |n| is kept. The curvature, and so
 *               the force, then bends the interface towards the angle.
 *  contact line (line_force) Young's unbalanced force at the contact line (the contact-line force
 *               of Huber et al. 2016, J. Comput. Phys. 310:459), per volume
 *               f_i = sigma (cos theta - cos theta_i) t_i delta_CL,
 *               cos theta_i = nc_i . n_w the angle the interface makes with the wall at i, nc_i
 *               = grad c' by the corrected gradient (the moment matrix sum_j V_j grad_i W_ij
 *               (x_j - x_i) inverted: exact for a linear c' where the wall cuts the kernel), t_i
 *               = nc_i/|nc_i| - cos theta_i n_w (sin theta_i long: the direction along the wall
 *               out of the phase without colour), delta_CL = |nc_i| 2 |sum_walls V_w grad_i
 *               W_ij| sin theta_i: the interface's delta |grad c'| times the wall edge's,
 *               2 |grad phi_w| (phi_w = sum_walls V_w W_ij falls from 1/2 at the wall's face
 *               to 0), times sin theta_i, since two bands crossing at theta_i overlap over an
 *               area 1 / sin theta_i times their widths' product: the force integrates to
 *               sigma (cos theta - cos theta_i) per length of contact line.
 *               V_w = 1 / delta_0. Applied with Brackbill's density scaling, as the force. */
#ifndef RYUSHI_SPH_MULTIPHASE_H
#define RYUSHI_SPH_MULTIPHASE_H

#include "ryushi/sim.h"
#include "pairs/pair_cache.h"

typedef struct ry_colour {
    int material;   /* the colour material (c = 1) */
    double sigma;   /* interfacial tension [N/m] */
    double eps;     /* normal threshold |n| h > eps */
    double rho_bar; /* mean reference density of the two phases */
    int smoothing;  /* passes of the |n|-weighted curvature average (0: none) */
    int wet;        /* a contact angle at the walls (cos_theta, sin_theta) */
    double cos_theta, sin_theta;
    int line_force;     /* the contact line's force (with wet) */
    double wall_volume; /* a wall particle's volume V_w (1 / the lattice's number density) */
    int f_colour;       /* particle field: smoothed colour c' */
    int f_curvature;    /* particle field: curvature [1/m] */
    double *nrm;        /* 5 x n: normals (3 x n), then |n| and the curvature average's work */
    size_t cap;
} ry_colour;

/* Registers the output fields. */
ry_status ry_colour_init(ry_colour *cf, ry_sim *sim, ry_error *err);
void ry_colour_free(ry_colour *cf);

/* Adds the interfacial acceleration to acc[3 i + d] of the fluid particles (mobile[kind] set),
 * given their number density delta and the pair cache of the current step. */
ry_status ry_colour_force(ry_colour *cf, ry_sim *sim, const ry_pair_cache *pc, const double *delta,
                          const int mobile[RY_KIND_COUNT], double *acc, ry_error *err);

/* Largest stable time step for surface tension (Brackbill et al. 1992):
 * dt <= 0.25 sqrt(rho_min h^3 / (2 pi sigma)). */
double ry_colour_dt(const ry_colour *cf, const ry_sim *sim);

#endif
