/* IISPH (scheme iisph) against references: short versions of the validation cases. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ryushi/validate.h"
#define RY_TMPDIR_PREFIX "ryushi_iisph_"
#include "run_case.h"
#include "manifest_tol.h"
#include "ryushi/run.h"

/* Tolerance `key` of validation/iisph.yaml. */
static double tol(const char *key) {
    return manifest_tol(root, "iisph", key);
}

/* Water at rest in a tank (cases/hydrostatic_iisph.yaml, H = 0.2 m, dx = 5 mm, started with
 * zero pressure): after 0.5 s the pressure of the lowest fluid layer, away from the side walls,
 * is rho g (H - y) within 3 % (measured 2.5 %); the water stays at rest: from t = 0.25 s the
 * kinetic energy is below 1e-3 of M g H (measured about 1.5e-4; what moves are single
 * free-surface particles at the corners, max speed reported); the solver reports its
 * iterations. The tolerances: validation/iisph.yaml. */
static void test_hydrostatic(void **state) {
    (void)state;
    const char *sets[] = {"time.end=0.5", "output.vtk=false", "time.output_interval=0.05"};
    ry_sim sim;
    ry_run_stats stats;
    ry_table s;
    run_case("cases/hydrostatic_iisph.yaml", "hydro", 3, sets, &s, &sim, &stats);
    const double H = 0.2, g = 9.81, M = 1000.0 * 0.4 * H;
    double psum = 0, ysum = 0;
    int count = 0;
    for (size_t i = 0; i < sim.ps.n; ++i) {
        if (sim.ps.kind[i] != RY_KIND_FLUID) continue;
        double x = sim.ps.f[RY_F_X][i], y = sim.ps.f[RY_F_Y][i];
        if (y < 0.005 && x > 0.1 && x < 0.3) {
            psum += sim.ps.f[RY_F_P][i];
            ysum += y;
            ++count;
        }
    }
    assert_true(count > 10);
    double p = psum / count, y = ysum / count, pexp = 1000.0 * g * (H - y);
    double ke = ry_column_max_from(&s, "kinetic_energy", 0.25) / (M * g * H);
    double vmax = ry_column_max_from(&s, "max_speed", 0.25);
    double iters = ry_column_max(&s, "iisph_iterations_mean");
    printf("IISPH hydrostatic: bottom pressure %.1f Pa, expected %.1f Pa (%.2f %%), kinetic "
           "energy / MgH %.2e, max speed %.4f m/s, mean iterations %.2f\n",
           p, pexp, 100 * (p / pexp - 1), ke, vmax, iters);
    assert_true(fabs(p / pexp - 1) < tol("hydrostatic_pressure"));
    assert_true(ke < tol("rest_kinetic_energy"));
    assert_true(iters >= 2);
    assert_true(ry_mass_drift(&s) <= 1e-12);
    ry_sim_free(&sim);
    ry_table_free(&s);
}

/* Martin & Moyce column at a/20 with IISPH: the surge front within 0.45 (max) and 0.35 (RMS)
 * of the experiment in Z = front/a for T <= 3 (measured 0.37 and 0.28: the incompressible
 * front leaves at once, while the experiment's gate takes time to lift); with the time origin
 * fitted (shift dT in [0.05, 0.3], measured 0.23) the RMS is within 0.06 (measured 0.033);
 * mass exact, no particle outside. */
/* Runs a Martin & Moyce case (a/20, to 0.18 s) into tmpdir/sub and compares its front with the
 * experiment (T <= 3); keeps the final state in *keep (or frees it). */
static void run_martin_moyce(const char *case_rel, const char *sub, ry_table *s, ry_sim *keep,
                             ry_run_stats *stats, ry_front_cmp *cmp) {
    const char *sets[] = {"time.end=0.18", "time.output_interval=0.001", "output.vtk=false"};
    run_case(case_rel, sub, 3, sets, s, keep, stats);
    char rp[4096];
    ry_error err;
    ry_table ref;
    snprintf(rp, sizeof rp, "%s/data/reference/martin_moyce1952_n2_2_surge_front_table2.csv", root);
    assert_int_equal(ry_table_read(&ref, rp, &err), RY_OK);
    assert_int_equal(ry_compare_front(s, &ref, 0.05715, 9.81, 3.0, cmp, &err), RY_OK);
    ry_table_free(&ref);
}

/* The bounds of test_martin_moyce (above), mass exact and no particle outside; those the
 * validation checks from validation/name.yaml (iisph or air). */
static void check_martin_moyce(const ry_table *s, const ry_front_cmp *cmp, const char *name) {
    assert_true(cmp->npoints >= 13);
    assert_true(cmp->max_dev <= 0.45);
    assert_true(cmp->rms_dev <= 0.35);
    assert_true(cmp->rms_dev_shifted <= manifest_tol(root, name, "front_rms_dev_shifted"));
    assert_true(cmp->shift >= 0.05 && cmp->shift <= 0.3);
    assert_true(ry_mass_drift(s) <= manifest_tol(root, name, "mass_drift"));
    assert_true(ry_column_max(s, "outside") <= manifest_tol(root, name, "escaped"));
}

static void test_martin_moyce(void **state) {
    (void)state;
    ry_table s;
    ry_run_stats stats;
    ry_front_cmp cmp;
    run_martin_moyce("cases/dam_break_mm_iisph.yaml", "mm", &s, NULL, &stats, &cmp);
    printf("IISPH Martin & Moyce a/20: %d points, max |dZ| %.3f, rms %.3f; shift %.3f: max %.3f, "
           "rms %.3f; %ld steps, mean iterations %.2f\n",
           cmp.npoints, cmp.max_dev, cmp.rms_dev, cmp.shift, cmp.max_dev_shifted,
           cmp.rms_dev_shifted, stats.steps, ry_column_max(&s, "iisph_iterations_mean"));
    check_martin_moyce(&s, &cmp, "iisph");
    ry_table_free(&s);
}

/* Water under silicone oil at rest (cases/stacked_fluids.yaml at dx = 10 mm, 1 s; density
 * ratio 0.97, viscosity ratio 1000, interfacial tension 0.04 N/m): from t = 0.5 s the kinetic
 * energy stays below 1e-3 of M g H and the largest speed in the band +-2 cm about the
 * interface below 0.05 m/s (measured 0.010 m/s). With air above the water (density ratio
 * 1.2e-3, a light phase: docs/reference/iisph.md, "A light phase") the kinetic energy stays below
 * 1e-3 M g H, the water below the interface (y in [0.06, 0.1] m) slower than 0.2 m/s, and the air
 * slower than 0.3 m/s at 1 s (measured 0.103 m/s, rms 0.040; coupled, scheme.light_phase:
 * coupled, 0.36 m/s, rms 0.16, and 0.60 m/s at 0.5 s). */
static void test_stacked(void **state) {
    (void)state;
    for (int k = 0; k < 2; ++k) {
        const char *sets[] = {"spacing=0.01", "time.end=1.0", "output.vtk=false",
                              "materials[1].density=1.2", "materials[1].viscosity=1.5e-5"};
        ry_sim sim;
        ry_run_stats stats;
        ry_table s;
        run_case("cases/stacked_fluids.yaml", k ? "stacked_air" : "stacked_oil", k ? 5 : 3, sets,
                 &s, &sim, &stats);
        const double M = ry_column_max(&s, "mass"), g = 9.81, H = 0.2;
        const double ke = ry_column_max_from(&s, "kinetic_energy", 0.5) / (M * g * H);
        const double band = ry_band_max_speed(&sim, 1, 0.08, 0.12);
        const double below = ry_band_max_speed(&sim, 1, 0.06, 0.1);
        double vair, rair;
        ry_material_speeds(&sim, 1, &vair, &rair);
        printf("stacked fluids (%s above water): KE/(MgH) %.2e, max speed near the interface "
               "%.4f m/s, just below it %.4f m/s, overall %.4f m/s, the upper fluid at 1 s %.4f "
               "m/s (rms %.4f), mean iterations %.2f\n",
               k ? "air" : "silicone oil", ke, band, below,
               ry_column_max_from(&s, "max_speed", 0.5), vair, rair,
               ry_column_max(&s, "iisph_iterations_mean"));
        assert_true(ke < tol("rest_kinetic_energy"));
        if (k == 0) assert_true(band < 0.05);
        if (k == 1) assert_true(below < 0.2 && vair < 0.3);
        assert_true(ry_mass_drift(&s) <= 1e-12);
        ry_sim_free(&sim);
        ry_table_free(&s);
    }
}

/* Water and air in motion (density ratio 1.2e-3, the air a light phase; docs/reference/iisph.md, "A
 * light phase"). The Martin & Moyce column under air up to the tank's rim
 * (cases/dam_break_mm_iisph_air.yaml, a/20, to 0.18 s): the water's front against the
 * experiment as test_martin_moyce asks (measured: shift 0.225, RMS after it 0.033, the water
 * alone 0.230 and 0.033), mass exact, no particle outside, the air slower than 3 m/s at the end
 * (measured 1.8 m/s, the water 1.7 m/s). A standing wave under air (cases/standing_wave_air.yaml,
 * one wavelength 0.1 m, water 0.05 m deep, a0 = 2 mm, 1 s): its period from the zero crossings of
 * the surface mode within 3 % of the two-layer linear theory (measured 0.2514 s against
 * 0.2539 s, -1.0 %), largest speed below 0.3 m/s (measured 0.11 m/s). */
static void test_air_water(void **state) {
    (void)state;
    ry_table s;
    ry_sim sim;
    ry_run_stats stats;
    ry_front_cmp cmp;
    run_martin_moyce("cases/dam_break_mm_iisph_air.yaml", "mm_air", &s, &sim, &stats, &cmp);
    double vw, rw, va, ra;
    ry_material_speeds(&sim, 0, &vw, &rw);
    ry_material_speeds(&sim, 1, &va, &ra);
    printf("IISPH Martin & Moyce under air: max |dZ| %.3f, rms %.3f; shift %.3f: rms %.3f; at the "
           "end water %.2f m/s, air %.2f m/s (rms %.2f); %ld steps, mean iterations %.2f\n",
           cmp.max_dev, cmp.rms_dev, cmp.shift, cmp.rms_dev_shifted, vw, va, ra, stats.steps,
           ry_column_max(&s, "iisph_iterations_mean"));
    check_martin_moyce(&s, &cmp, "air");
    assert_true(va < manifest_tol(root, "air", "air_speed"));
    ry_sim_free(&sim);
    ry_table_free(&s);

    const char *wsets[] = {"output.vtk=false"};
    run_case("cases/standing_wave_air.yaml", "wave_air", 1, wsets, &s, NULL, NULL);
    const double pi = 3.14159265358979323846, g = 9.81, k = 2 * pi / 0.1;
    const double w2 = g * k * (1000.0 - 1.2) / (1000.0 / tanh(k * 0.05) + 1.2 / tanh(k * 0.03));
    const double T = 2 * pi / sqrt(w2);
    const ry_oscillation osc = ry_series_oscillation(&s, "wave_amplitude");
    const double vmax = ry_column_max(&s, "max_speed");
    printf("standing wave under air: period %.4f s (%d crossings), theory %.4f s (%+.2f %%), "
           "largest speed %.3f m/s\n",
           osc.period, osc.crossings, T, 100 * (osc.period / T - 1), vmax);
    assert_true(osc.crossings >= 6);
    assert_true(fabs(osc.period / T - 1) <= manifest_tol(root, "air", "wave_period"));
    assert_true(vmax < manifest_tol(root, "air", "wave_speed"));
    ry_table_free(&s);
}

/* Square drop relaxing to a circle (cases/square_drop.yaml, 16 particles across, sigma = 1 N/m,
 * solver tolerance 1e-6), to 0.8 s: the pressure inside (r < R/2) minus outside (r > 1.5 R) is
 * sigma / R within 5 % (measured +1.6 % at 0.8 s, -0.1 % at 0.4 s), R = 0.4/sqrt(pi); and the
 * drop comes to rest: from 0.6 s its largest speed stays below 0.03 m/s (measured 0.010). With
 * the curvature as read, before its average over the interface (docs/reference/iisph.md), the
 * parasitic currents kept it at 0.092 m/s and the jump read +4.5 %. */
static void test_square_drop(void **state) {
    (void)state;
    const char *sets[] = {"time.end=0.8", "output.vtk=false"};
    ry_sim sim;
    ry_run_stats stats;
    ry_table s;
    run_case("cases/square_drop.yaml", "drop", 2, sets, &s, &sim, &stats);
    const double R = 0.4 / sqrt(3.14159265358979323846), c[2] = {0.5, 0.5};
    const double dp = ry_pressure_jump(&sim, c, 0.5 * R, 1.5 * R);
    const double vlate = ry_column_max_from(&s, "max_speed", 0.6);
    printf("square drop: pressure jump %.3f Pa, sigma/R %.3f Pa (%+.2f %%), max speed from 0.6 s "
           "%.4f m/s, mean iterations %.1f\n",
           dp, 1.0 / R, 100 * (dp * R - 1), vlate, ry_column_max(&s, "iisph_iterations_mean"));
    assert_true(fabs(dp * R - 1) <= tol("laplace_jump"));
    assert_true(vlate < 0.03);
    ry_sim_free(&sim);
    ry_table_free(&s);
}

/* Free-surface tension (CSF in pressure form): the circular drop of cases/iisph_drop_rest_2d.yaml
 * (R = 2 mm, 20 spacings, sigma = 0.0728 N/m, 10 ms) keeps a pressure inside within 6 % of the
 * Laplace jump sigma / R over its second half (measured +3.2 %; +16.1 % before the liquid
 * beneath the surface counted its pressures from the drop's mean jump: docs/reference/iisph.md) and
 * its spurious speeds below 0.05 m/s (measured 0.016). */
static void test_free_drop_rest(void **state) {
    (void)state;
    const char *sets[] = {"time.end=0.01"};
    free_drop_at_rest("cases/iisph_drop_rest_2d.yaml", "free_drop", 1, sets, 0.005,
                      tol("iisph_free_jump"), tol("iisph_free_speed"));
}

/* The oscillating square of cases/iisph_droplet_square.yaml (40 x 40, CSF in pressure form, 15
 * ms): period within 10 % of Lamb's mode 4, T = 2 pi / sqrt(60 sigma / (rho R^3)),
 * R = a / sqrt(pi) (measured +4.0 %, half period +9.9 %: docs/reference/iisph.md). */
static void test_free_square(void **state) {
    (void)state;
    free_square_period("cases/iisph_droplet_square.yaml", "free_square", tol("square_period"));
}

/* Two liquids on a wall with a contact angle (cases/iisph_two_liquid_sessile.yaml at twice its
 * spacing, 1,616 particles, free-slip walls): the drop's angle through it, the mean of
 * contact_angle_second over 40-60 ms, within validation/wetting.yaml's tolerance of the angle
 * prescribed at 60 and 120 degrees (measured 62.3 and 115.6; the drop starts as a block, about
 * 90 degrees, so each has moved most of the way). With the contact line's force
 * (scheme.contact_line_force), 30 degrees in a tank twice as wide (the drop's base, 4.7 mm, would
 * fill the case's 5 mm floor; without the force the drop stays near 53 degrees) and 120 degrees
 * (measured 32.5 and 120.1). */
static void test_contact_angle(void **state) {
    (void)state;
    const double want[4] = {60, 120, 30, 120}, t = manifest_tol(root, "wetting", "contact_angle");
    for (int k = 0; k < 4; ++k) {
        char ang[64], sub[32];
        snprintf(ang, sizeof ang, "scheme.contact_angle=%g", want[k]);
        snprintf(sub, sizeof sub, "sessile_%d", k);
        const char *sets[] = {"spacing=1.0e-4",
                              ang,
                              "scheme.contact_line_force=true",
                              "bodies[1].lo=[-5.0e-3,0.0]",
                              "bodies[1].hi=[5.0e-3,2.5e-3]",
                              "bodies[2].lo=[-5.0e-3,0.0]",
                              "bodies[2].hi=[5.0e-3,3.0e-3]",
                              "domain.lo=[-6.0e-3,-1.0e-3]",
                              "domain.hi=[6.0e-3,4.0e-3]"};
        const int nset = k < 2 ? 2 : k == 2 ? 9 : 3;
        ry_table s;
        run_case("cases/iisph_two_liquid_sessile.yaml", sub, nset, sets, &s, NULL, NULL);
        int rows = 0;
        const double mean = ry_column_mean_from(&s, "contact_angle_second", 0.04, &rows);
        printf("  IISPH two-liquid sessile drop, %g degrees%s: %.2f over %d rows\n", want[k],
               k < 2 ? "" : ", contact line force", mean, rows);
        assert_true(rows >= 10);
        assert_true(fabs(mean - want[k]) <= t);
        ry_table_free(&s);
    }
}

/* Rayleigh-Taylor instability (cases/rayleigh_taylor.yaml at 50 particles per wavelength,
 * top_amplitude one spacing; Atwood 0.286, light layer 0.05 m, heavy layer 0.016 m under a
 * free surface, interfacial tension 0.124 N/m, nu = 1e-6 m^2/s). At t = 0 the measurement
 * interface_amplitude is the first mode of the lattice interface (light particles one row
 * above y = 0.05 m where cos(kx) >= 1/2, heavy one row below where cos(kx) < -1/2), summed
 * here over the columns, within 1e-9. Theory (ry_rt_growth_rate): sqrt(A g k) for deep layers
 * without tension, and 12.16 1/s for the case (the free-surface dispersion relation solved
 * independently). The growth rate of the mode, a(t) = A e^(nt) + B e^(-nt) fitted up to
 * a = 0.1 lambda, within 15 % of theory (measured -12.5 %; -9.1 % at 100 per wavelength:
 * docs/reference/iisph.md); the fit follows the record within 5 % RMS, over at least 0.15 s. */
static void test_rayleigh_taylor(void **state) {
    (void)state;
    const char *sets[] = {"spacing=0.002", "bodies[0].top_amplitude=0.002", "output.vtk=false"};
    ry_table s;
    ry_run_stats stats;
    run_case("cases/rayleigh_taylor.yaml", "rt", 3, sets, &s, NULL, &stats);
    const double pi = 3.14159265358979323846, lambda = 0.1, k = 2 * pi / lambda;
    const double n_th = ry_rt_growth_rate(1800.0, 1000.0, 0.016, 0.05, 9.81, k, 1e-6, 0.124, 1);
    const double deep = ry_rt_growth_rate(1800.0, 1000.0, 10.0, 10.0, 9.81, k, 0.0, 0.0, 1);
    const int ca = ry_table_col(&s, "interface_amplitude");
    assert_true(ca >= 0);
    const ry_growth_fit f =
        ry_fit_growth(&s, "interface_amplitude", 0.0, 0.1 * lambda, 0.1 * n_th, 3 * n_th);
    printf("Rayleigh-Taylor (50 per wavelength): a0 %.5f m, growth rate %.3f 1/s, theory %.3f 1/s "
           "(%+.1f %%), fit to t = %.3f s (%d rows, rms %.3f), %ld steps, mean iterations %.1f\n",
           s.data[ca], f.n, n_th, 100 * (f.n / n_th - 1), f.t_last, f.rows, f.rms, stats.steps,
           ry_column_max(&s, "iisph_iterations_mean"));
    const int nx = 50;
    const double dx = lambda / nx;
    double lattice = 0;
    for (int i = 0; i < nx; ++i) {
        const double c = cos(k * (i + 0.5) * dx);
        lattice += c >= 0.5 ? c : (c < -0.5 ? -c : 0.0);
    }
    lattice *= 2 * dx * dx / lambda;
    assert_true(fabs(s.data[ca] / lattice - 1) < 1e-9);
    assert_true(fabs(deep / sqrt(800.0 / 2800.0 * 9.81 * k) - 1) < 1e-12);
    assert_true(fabs(n_th - 12.16) < 0.01);
    assert_true(fabs(f.n / n_th - 1) <= manifest_tol(root, "rt", "growth_rate_50"));
    assert_true(f.rms <= 0.05);
    assert_true(f.t_last >= 0.15);
    assert_true(ry_mass_drift(&s) <= 1e-12);
    ry_table_free(&s);
}

/* Eye case (cases/eye_sphere.yaml), one step: oil_wall_contact counts the retinal wall only,
 * not the wall of the ports (within half the port's cross-section diagonal plus the kernel
 * support of a port axis). With oil only in the infusion channel no retinal wall touches oil:
 * 0 (it was 0.049 when the channel walls and collars counted); with oil filling the cavity and
 * saline in both channels every counted wall particle touches oil: 1 (it was 0.90). */
static void test_eye_port_walls(void **state) {
    (void)state;
    for (int k = 0; k < 2; ++k) {
        const char *sets[] = {"time.max_steps=1", "output.vtk=false",
                              k ? "bodies[0].material=silicone_oil"
                                : "bodies[1].material=silicone_oil"};
        ry_table s;
        run_case("cases/eye_sphere.yaml", k ? "eye_cavity_oil" : "eye_channel_oil", 3, sets, &s,
                 NULL, NULL);
        const int c = ry_table_col(&s, "oil_wall_contact");
        assert_true(c >= 0 && s.nrows >= 2);
        const double v = ry_table_at(&s, s.nrows - 1, c);
        printf("eye, oil in the %s: oil_wall_contact %.6f (expected %d)\n",
               k ? "cavity" : "infusion channel", v, k);
        assert_true(fabs(v - k) < 1e-12);
        ry_table_free(&s);
    }
}

/* Eye case with the drainage at the posterior pole (cases/eye_posterior_drain.yaml), the first
 * 0.2 s of the filling (0.41 ml of oil at 2 ml/s): the cavity is rigid and the liquids are
 * incompressible, so the fluid particles inside stay within 1.5 % of their number at the start
 * (measured -1.0 %: 16 particles leave in the first 0.06 s, then the number holds), and the
 * saline drained matches the oil injected to within 2 % of the cavity's fluid volume (measured
 * 0.06 ml of 7.4 ml); every injected drop of oil is still inside (the oil reaches the drain at
 * about 3 s); the solver keeps its average density error with at most 20 iterations per step
 * on average (measured 7.9). The full checks (time-step convergence of the filled fraction and
 * the contact) are in `ryushi validate eye`. */
static void test_eye_posterior_drain(void **state) {
    (void)state;
    const char *sets[] = {"time.end=0.2", "time.output_interval=0.02", "output.vtk=false"};
    ry_table s;
    run_case("cases/eye_posterior_drain.yaml", "eye_drain", 3, sets, &s, NULL, NULL);
    const int cn = ry_table_col(&s, "fluid_particles"), cf = ry_table_col(&s, "filled_fraction"),
              ci = ry_table_col(&s, "inflow_volume"), co = ry_table_col(&s, "outflow_volume");
    assert_true(cn >= 0 && cf >= 0 && ci >= 0 && co >= 0 && s.nrows >= 10);
    const double n0 = ry_table_at(&s, 0, cn), dx3 = 0.0015 * 0.0015 * 0.0015;
    double drift = 0;
    for (size_t r = 0; r < s.nrows; ++r) drift = fmax(drift, fabs(ry_table_at(&s, r, cn) / n0 - 1));
    const size_t e = s.nrows - 1;
    const double vin = ry_table_at(&s, e, ci), vout = ry_table_at(&s, e, co);
    const double oil = ry_table_at(&s, e, cf) * ry_table_at(&s, e, cn) * dx3;
    const int cm = ry_table_col(&s, "iisph_iterations_mean");
    assert_true(cm >= 0);
    const double iters = ry_table_at(&s, e, cm); /* the mean over the run */
    printf("eye, posterior drain at 0.2 s: fluid particles within %.2f %% of the start, injected "
           "%.4f ml, drained %.4f ml (%.2f %% of the fluid), oil inside %.4f ml, %.2f iterations "
           "per step\n",
           100 * drift, vin * 1e6, vout * 1e6, 100 * (vout - vin) / (n0 * dx3), oil * 1e6, iters);
    assert_true(fabs(vin - 2e-6 * 0.2) <= 0.05 * 2e-6 * 0.2);
    assert_true(drift <= 0.015);
    assert_true(fabs(vout - vin) <= 0.02 * n0 * dx3);
    assert_true(fabs(oil / vin - 1) <= 1e-6);
    assert_true(iters <= 20);
    ry_table_free(&s);
}

/* The posterior drain at a clinical rate (cases/eye_posterior_drain_clinical.yaml: 0.1 ml/s of
 * oil in, a rate outlet taking 0.1 ml/s out), the first 1.0 s. The cavity stays full: the fluid
 * particles inside stay within 1.2 % of their number at the start at every output (measured
 * 0.82 %: the outflow zone starts empty, and 16 particles' worth of saline falls into it in the
 * first 0.5 s; the full run holds 2186-2190 of the 2204 from 4 to 72 s. The same case with the
 * drainage a pressure outlet at the hydrostatic head lost 15 % of its saline by 1.5 s, as the
 * top of the cavity emptied). The inflow is 0.1 ml/s within a layer of the inlet's 2 x 2
 * lattice (0.0135 ml: a layer enters every 0.135 s), all the injected oil is inside, and
 * nothing moves faster than 0.1 m/s (measured 0.048 m/s; the pressure outlet's saline fell
 * through the drainage at 0.3-1 m/s). The probe injected_kept reads that share. */
static void test_eye_clinical_rate(void **state) {
    (void)state;
    const char *sets[] = {"time.end=1.0", "time.output_interval=0.1", "output.vtk=false"};
    ry_table s;
    run_case("cases/eye_posterior_drain_clinical.yaml", "eye_clinical", 3, sets, &s, NULL, NULL);
    const int cn = ry_table_col(&s, "fluid_particles"), cf = ry_table_col(&s, "filled_fraction"),
              ci = ry_table_col(&s, "inflow_volume"), cv = ry_table_col(&s, "max_speed"),
              ck = ry_table_col(&s, "injected_kept");
    assert_true(cn >= 0 && cf >= 0 && ci >= 0 && cv >= 0 && ck >= 0 && s.nrows >= 10);
    const double n0 = ry_table_at(&s, 0, cn), dx3 = 0.0015 * 0.0015 * 0.0015;
    double drift = 0, vmax = 0;
    for (size_t r = 0; r < s.nrows; ++r) {
        drift = fmax(drift, fabs(ry_table_at(&s, r, cn) / n0 - 1));
        vmax = fmax(vmax, ry_table_at(&s, r, cv));
    }
    const size_t e = s.nrows - 1;
    const double vin = ry_table_at(&s, e, ci);
    const double oil = ry_table_at(&s, e, cf) * ry_table_at(&s, e, cn) * dx3;
    printf("eye, clinical rate at 1.0 s: fluid particles within %.2f %% of the start, injected "
           "%.4f ml, oil inside %.4f ml, largest speed %.3f m/s\n",
           100 * drift, vin * 1e6, oil * 1e6, vmax);
    assert_true(fabs(vin - 1e-7 * 1.0) <= 4 * dx3 * (1 + 1e-9));
    assert_true(drift <= manifest_tol(root, "eye_clinical", "fluid_count_quick"));
    assert_true(fabs(oil / vin - 1) <= 1e-6);
    /* the probe injected_kept is that share (the oil has not reached the drainage) */
    assert_true(fabs(ry_table_at(&s, e, ck) - oil / vin) <= 1e-9);
    assert_true(vmax <= 0.1);
    ry_table_free(&s);
}

/* Wall layers beyond the reach of the sums removed (domain.wall_layers; cases/README.md): the eye
 * at rest at 0.75 mm (the whole cavity), whose wall shell is 6 layers thick, 10 steps with every
 * wall particle and with 3 layers kept. The support is 2.8 spacings, so the removed particles take
 * part in no sum of a fluid particle: the fluid's positions and velocities agree to round-off (the
 * sums' order changes with the particles' indices; within 1e-9 of the spacing and of the largest
 * speed: measured 7e-18 m and 1.7e-14 m/s of 0.0097 m/s over 17,256 fluid particles), with more
 * than a sixth of the particles gone (the shell's outer 3 layers: 9,176 of 44,720). */
static void test_wall_layers(void **state) {
    (void)state;
    const char *sets[] = {"spacing=0.00075",    "time.max_steps=10",
                          "output.vtk=false",   "domain.lo=[-0.02,-0.02,-0.02]",
                          "domain.symmetry=[]", "domain.wall_layers=0"};
    ry_sim a, b;
    ry_table s;
    run_case("cases/eye_rest.yaml", "layers_all", 6, sets, &s, &a, NULL);
    ry_table_free(&s);
    sets[5] = "domain.wall_layers=3";
    run_case("cases/eye_rest.yaml", "layers_3", 6, sets, &s, &b, NULL);
    ry_table_free(&s);
    printf("wall layers: %zu particles, %zu with 3 layers kept\n", a.ps.n, b.ps.n);
    assert_true(6 * (a.ps.n - b.ps.n) > a.ps.n);
    size_t nf = 0, *at = malloc((size_t)b.ps.next_id * sizeof *at); /* index of each id in b */
    assert_non_null(at);
    for (size_t j = 0; j < (size_t)b.ps.next_id; ++j) at[j] = SIZE_MAX;
    for (size_t j = 0; j < b.ps.n; ++j) at[b.ps.id[j]] = j;
    double dx = 0, dv = 0, vmax = 0;
    for (size_t i = 0; i < a.ps.n; ++i) {
        if (a.ps.kind[i] != RY_KIND_FLUID) continue;
        assert_true(a.ps.id[i] < b.ps.next_id);
        const size_t j = at[a.ps.id[i]];
        assert_true(j < b.ps.n && b.ps.kind[j] == RY_KIND_FLUID);
        for (int d = 0; d < 3; ++d) {
            dx = fmax(dx, fabs(a.ps.f[RY_F_X + d][i] - b.ps.f[RY_F_X + d][j]));
            dv = fmax(dv, fabs(a.ps.f[RY_F_VX + d][i] - b.ps.f[RY_F_VX + d][j]));
            vmax = fmax(vmax, fabs(a.ps.f[RY_F_VX + d][i]));
        }
        ++nf;
    }
    printf("wall layers: %zu fluid particles, largest differences %.3g m and %.3g m/s (largest "
           "speed %.3g m/s)\n",
           nf, dx, dv, vmax);
    assert_true(nf > 15000 && vmax > 0);
    assert_true(dx <= 1e-9 * 0.00075 && dv <= 1e-9 * vmax);
    free(at);
    ry_sim_free(&a);
    ry_sim_free(&b);
}

int main(void) {
    const char *src = getenv("RY_SOURCE_DIR");
    snprintf(root, sizeof root, "%s", src ? src : ".");
    const char *only = getenv("RY_TEST_FILTER"); /* e.g. "test_eye*" */
    if (only) cmocka_set_test_filter(only);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_hydrostatic),       cmocka_unit_test(test_martin_moyce),
        cmocka_unit_test(test_stacked),           cmocka_unit_test(test_air_water),
        cmocka_unit_test(test_square_drop),       cmocka_unit_test(test_free_drop_rest),
        cmocka_unit_test(test_free_square),       cmocka_unit_test(test_rayleigh_taylor),
        cmocka_unit_test(test_eye_port_walls),    cmocka_unit_test(test_eye_posterior_drain),
        cmocka_unit_test(test_eye_clinical_rate), cmocka_unit_test(test_contact_angle),
        cmocka_unit_test(test_wall_layers),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
