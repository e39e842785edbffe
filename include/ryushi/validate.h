/* ryushi — validation: measured series and states compared with reference data and analytic
 * solutions (the cases are run through ry_run_case_file, ryushi/run.h). Part of the layer
 * above the library's interface (src/validate/): the program and the tests use it, the shared
 * library does not hold it. */
#ifndef RYUSHI_VALIDATE_H
#define RYUSHI_VALIDATE_H

#include <stdio.h>

#include "ryushi/csv.h"
#include "ryushi/probes.h" /* ry_band_max_speed */
#include "ryushi/sim.h"

/* Surge front against Martin & Moyce: Z = front_x / a against T = t sqrt(2 g / a). */
typedef struct ry_front_cmp {
    int npoints;    /* reference points compared (T <= T_max) */
    double max_dev; /* largest |Z - Z_ref| */
    double rms_dev; /* RMS of Z - Z_ref */
    /* The experiment's time origin is uncertain (the gate takes time to lift): the shift dT of
     * the simulated curve, T -> T + dT in [0, 0.4], that minimises the RMS, and the deviations
     * after that shift. */
    double shift, max_dev_shifted, rms_dev_shifted;
} ry_front_cmp;
/* series: a table with columns t and front_x; ref: columns T and Z. */
ry_status ry_compare_front(const ry_table *series, const ry_table *ref, double a, double g,
                           double T_max, ry_front_cmp *out, ry_error *err);
/* First time front_x reaches x_wall (linear interpolation between rows); NAN if never. */
double ry_front_arrival(const ry_table *series, double x_wall);
/* Largest |m(t) - m(0)| / m(0) of the column `mass`. */
double ry_mass_drift(const ry_table *series);
/* Largest value of a column (e.g. outside, in_wall); 0 when absent. */
double ry_column_max(const ry_table *series, const char *name);

/* Smallest value of a column (rows holding NAN skipped); NAN when absent. */
double ry_column_min(const ry_table *series, const char *name);

/* An oscillation in series.csv: the period from the zero crossings of a column (mean spacing of
 * the first and last crossing, linear interpolation between rows; the first row is skipped),
 * and the total energy solid_kinetic_energy + strain_energy at the start and its means over the
 * first and the last period (NAN without these columns). period is NAN with fewer than two
 * crossings. */
typedef struct ry_oscillation {
    double period;
    int crossings;
    double energy0, energy_first, energy_last;
} ry_oscillation;
ry_oscillation ry_series_oscillation(const ry_table *series, const char *name);

/* Largest value of a column over the rows with t >= t0; NAN when absent. */
double ry_column_max_from(const ry_table *series, const char *name, double t0);
/* Mean of a column over the rows with t >= t0 (NAN when there is none); *rows receives their
 * number (may be NULL). */
double ry_column_mean_from(const ry_table *series, const char *name, double t0, int *rows);
/* The same over the rows with t0 <= t < t1. */
double ry_column_mean_between(const ry_table *series, const char *name, double t0, double t1,
                              int *rows);

/* Static drop: mean pressure of the fluid particles within r_in of centre minus that of the
 * fluid particles farther than r_out (2D: x, y; 3D: x, y, z). NAN when either set is empty. */
double ry_pressure_jump(const ry_sim *sim, const double *centre, double r_in, double r_out);

/* Largest and rms speed of the fluid particles of one material (0 and 0 without any). */
void ry_material_speeds(const ry_sim *sim, int material, double *vmax, double *vrms);

/* Cavity centrelines against Ghia et al.: the case's profiles `u_vertical_centreline` (u along
 * x = L/2, bottom to top) and `v_horizontal_centreline` (v along y = L/2, left to right), time
 * averaged when they have average_from, interpolated at the reference's y/L and x/L, for a
 * cavity [0, L]^2 with lid speed U. Writes centreline_u.csv and centreline_v.csv in out_dir and
 * returns the RMS of (u - u_ref)/U and (v - v_ref)/U. */
ry_status ry_cavity_centrelines(const ry_sim *sim, double L, double U, const ry_table *ghia_u,
                                const ry_table *ghia_v, const char *out_dir, double *rms_u,
                                double *rms_v, ry_error *err);

/* A hydrostatic column: the time-mean pressure of profile `name` at its point k (*p) against
 * rho g h, with h = top - x_k along the last axis (*h); returns the relative error, NAN when the
 * profile is missing or has no sample there. */
double ry_profile_hydrostatic_error(const ry_sim *sim, const char *name, int k, double top,
                                    double rho, double g, double *p, double *h);

/* Oscillating drop as the seed measures it (seed 003, section 3): from a column (the width),
 * smoothed by a moving average over 5 rows, the half period is the time of the first maximum
 * of the width (the first local maximum above the middle between the initial and the largest
 * width) and the period the time of the least width after it, searched up to 2.5 half periods (NAN
 * when that minimum lies at the end of the search, i.e. the record is too short). */
typedef struct ry_drop_periods {
    double half, period;                 /* [s] */
    double width0, width_max, width_min; /* smoothed widths at 0, half, period */
} ry_drop_periods;
ry_drop_periods ry_drop_periods_measure(const ry_table *series, const char *name);

/* Exponential growth of a mode (Rayleigh-Taylor): a(t) = A e^(n t) + B e^(-n t) fitted to a
 * column by least squares on the relative residual, (fit - a) / a, over the rows from t0 up to
 * the last one before abs(a) first exceeds amax; for each n the best A and B are linear, n is
 * searched by golden section in [n_lo, n_hi]. rows < 4: no fit (n = NAN). */
typedef struct ry_growth_fit {
    double n, A, B; /* [1/s], column units */
    double rms;     /* RMS relative residual */
    double t_last;  /* last fitted time [s] */
    int rows;
} ry_growth_fit;
ry_growth_fit ry_fit_growth(const ry_table *series, const char *name, double t0, double amax,
                            double n_lo, double n_hi);

/* A damped oscillation w(t) = a + e^(-k s) (b cos(2 pi s / T) + c sin(2 pi s / T)), s = t - t0,
 * fitted to a column by least squares over the rows with t0 <= t <= t1 (rows holding NAN
 * skipped). For each period T and decay rate k the best a, b, c are linear (the normal
 * equations); T is searched over [T_lo, T_hi] and k over [0, k_max] on a grid of 200 x 41, then
 * twice on grids ten times finer around the best. Fewer than 6 rows, or T_hi <= T_lo: no fit
 * (period NAN). The rms is that of the residual; mean = a, amplitude = sqrt(b^2 + c^2). */
typedef struct ry_oscillation_fit {
    double period, decay;   /* T [s], k [1/s] */
    double mean, amplitude; /* column units */
    double rms;
    int rows;
} ry_oscillation_fit;
ry_oscillation_fit ry_fit_oscillation(const ry_table *series, const char *name, double t0,
                                      double t1, double T_lo, double T_hi, double k_max);
/* An oscillating drop's period from the whole drop's shape moment (the column shape_m4,
 * ry_particles_shape_m4): the damped cosine above fitted from T/4 on, past the first rounding
 * of the cube or square, to the end, over periods 0.5-2 T and decay rates up to 2000 1/s;
 * T is Lamb's period. */
ry_oscillation_fit ry_drop_shape_fit(const ry_table *series, double T);

/* Linear Rayleigh-Taylor growth rate [1/s] of a heavy layer (rho1, depth h1) over a light one
 * (rho2, depth h2, on a rigid floor), wavenumber k, gravity g, interfacial tension sigma, from
 * linear potential flow: n^2 (rho1 R + rho2 coth(k h2)) = (rho1 - rho2) g k - sigma k^3, with
 * R = coth(k h1) under a rigid lid, R = (n^2 tanh(k h1) + g k) / (n^2 + g k tanh(k h1)) under a
 * free surface (free_top); deep layers: n^2 = A g k - sigma k^3 / (rho1 + rho2) (Chandrasekhar
 * 1961, Hydrodynamic and Hydromagnetic Stability, ch. X). Viscous correction for equal
 * kinematic viscosity nu, of the inviscid-flow approximation (Mikaelian 1993, Phys. Rev. E 47:
 * 375): n = sqrt(N^2 + nu^2 k^4) - nu k^2. 0 when the layer is stable (N^2 <= 0). */
double ry_rt_growth_rate(double rho1, double rho2, double h1, double h2, double g, double k,
                         double nu, double sigma, int free_top);

/* Channel flows of non-Newtonian fluids (docs/reference/rheology.md): walls at y = 0 and y = H, a
 * body force g along x; s the distance from the centreline, b = H/2, every viscosity kinematic.
 * Steady power law (nu = k gamma_dot^(n-1)): u(s) = n/(n+1) (g/k)^(1/n) (b^(1+1/n) - s^(1+1/n)).
 * Steady flow of any model with solvent viscosity nu (ry_viscometric_poiseuille; nu is not read
 * by the generalised Newtonian models): the shear rate gd(s) solves nu(gd) gd = g s with nu(gd)
 * the steady shear viscosity ry_rheology_shear_nu (bisection; nu(gd) gd increasing), and
 * u(s) = int_s^b gd ds' (Simpson, 2000 intervals). A steady channel flow is a simple shear at
 * every s; for a visco-elastic fluid the polymer's normal stresses do not enter the balance of
 * x momentum.
 * Oldroyd-B start-up from rest (Waters & King 1970): u = sum over odd k of u_k(t) sin(a_k y),
 * a_k = k pi / H, each mode with its polymer stress (tau_xy / rho = sum s_k a_k cos(a_k y))
 * the linear system du_k/dt = 4 g/(k pi) - a_k^2 (nu_s u_k + s_k),
 * lambda ds_k/dt = nu_p u_k - s_k, solved exactly from u_k = s_k = 0; `modes` odd modes. */
double ry_power_law_poiseuille(double g, double k, double n, double b, double s);
double ry_viscometric_poiseuille(const ry_rheology *r, double nu, double g, double b, double s);
double ry_oldroyd_b_startup(double g, double H, double nu_s, double nu_p, double lambda, double y,
                            double t, int modes);
/* Mean x velocity of the fluid particles by row (rows of a lattice of spacing l0 whose first
 * row is at y0 + l0/2): y[r], u[r] for r < max; returns the rows filled. */
size_t ry_row_velocity(const ry_sim *sim, double y0, double l0, double *y, double *u, size_t max);

/* Reference solutions for a cantilever of length L clamped at x = 0 (unit intensity: the
 * deflection is proportional to it). Load types as in the case key scheme.load.type. */
typedef enum ry_beam_load {
    RY_BEAM_LOAD_NONE,
    RY_BEAM_LOAD_END,     /* point load P at x = L */
    RY_BEAM_LOAD_UNIFORM, /* q = q0 */
    RY_BEAM_LOAD_LINEAR,  /* q = q0 x / L ("hydrostatic", largest at the free end) */
    RY_BEAM_LOAD_COSINE   /* q = q0 cos(pi x / (2 L)) */
} ry_beam_load;
/* Euler-Bernoulli deflection w(x) = (1/EI) int_0^x (x - s) M(s) ds for intensity 1. */
double ry_beam_deflection_eb(ry_beam_load load, double L, double EI, double x);
/* Timoshenko's shear deflection int_0^x V(s) ds / (kappa G A) for intensity 1 (add it to the
 * Euler-Bernoulli one); kappa = 5/6 for a rectangle. */
double ry_beam_deflection_shear(ry_beam_load load, double L, double kappa_GA, double x);
/* Elastica of a cantilever under a dead end load P normal to it, alpha2 = P L^2 / EI: the tip
 * position (x along the undeformed beam, y along the load) in units of L, and the tip angle. */
void ry_elastica_end_load(double alpha2, double *x_tip, double *y_tip, double *theta_tip);

/* Angular frequency of the first bending mode of a clamped-free plate of length L and
 * thickness H in cylindrical bending (thin-plate theory, plane strain):
 * omega^2 = E H^2 k^4 / (12 rho (1 - nu^2)), k = RY_CANTILEVER_KL1 / L. */
double ry_plate_omega(double E, double nu, double rho, double H, double L);

/* Complete elliptic integrals of the first and second kind, K(p) and E(p), modulus p < 1
 * (arithmetic-geometric mean). */
void ry_elliptic_ke(double p, double *K, double *E);

/* Euler's elastica of a clamped-free column under a dead axial end load P above the critical
 * load P_cr = pi^2 EI / (4 L^2), load_ratio = P / P_cr >= 1 (Timoshenko & Gere 1961, sec. 2.7):
 * kL = sqrt(P / EI) L = K(p), p = sin(theta_tip / 2); tip position in units of L along the
 * undeformed axis from the root, 2 E(p) / K(p) - 1, and across it, 2 p / K(p). At or below the
 * critical load the column stays straight: (1, 0, 0). */
void ry_elastica_column(double load_ratio, double *x_tip, double *y_tip, double *theta_tip);

/* The equilibrium of a tamponade: a lighter liquid (silicone oil) above a heavier one (saline)
 * filling a sphere of radius R, their interface an axisymmetric Young-Laplace surface under
 * gravity along the axis, meeting the wall at the contact angle theta measured through the
 * heavier liquid (Fawcett, Williams & Wong 1994: 18 degrees for oil on retina). fill: the
 * lighter liquid's share of the volume; bond = (rho_heavy - rho_light) g R^2 / sigma. Lengths in
 * units of R, the sphere centred at 0, z up. With bond = 0 the interface is a sphere's cap; as
 * bond grows it flattens towards the plane z = z_c, where fill = x^2 (3 - 2x) and coverage =
 * x. */
typedef struct ry_tamponade {
    double z_apex;          /* the interface on the axis */
    double z_contact;       /* the contact line's height */
    double r_contact;       /* and its radius */
    double coverage;        /* share of the wall's area the lighter liquid covers */
    double fill, theta, k0; /* as found: the fill, the angle (rad), the apex curvature (1/R) */
} ry_tamponade;
ry_status ry_tamponade_solve(double fill, double theta, double bond, ry_tamponade *out,
                             ry_error *err);
/* The meridian of t's interface (bond: its Bond number) from the apex to the wall: at most cap
 * points (r, z), in units of R, the last on the wall; returns their number (0 when cap < 2). */
size_t ry_tamponade_profile(const ry_tamponade *t, double bond, size_t cap, double *r, double *z);
/* The share of a region of the wall that the lighter liquid of t covers: the cone of half angle
 * half_angle [rad] about the unit direction d, in the frame where the unit vector up points
 * against gravity (the lighter liquid covers the wall above the contact line, p.up >=
 * z_contact, in units of R). */
double ry_tamponade_region_coverage(const ry_tamponade *t, const double up[3], const double d[3],
                                    double half_angle);

#endif
