/* The WCSPH pair term on two hand-placed particles against the equations by hand, through
 * both pair loops (the neighbour list in double precision, the cell ranges in single).
 *
 * Two fluid particles of a 2D lattice of spacing dx = 0.01 m (mass 0.1 kg each), i at
 * (0.005, 0.005) and j at (0.013, 0.011): x_ij = (-0.008, -0.006), r = 0.01 m; Wendland C2,
 * h = 1.4 dx, so q = 0.714 and dW/dr = sigma / h^3 f'(q) with sigma = 7 / (4 pi),
 * f'(q) = -10 s (1 - s)^3, s = q / 2. Densities 1010 and 995 kg/m^3, velocities (0.1, 0.05) and
 * (-0.2, 0) m/s, set after the set-up. Linear equation of state p = c0^2 (rho - rho0) with
 * c0 = 10 m/s; Monaghan's artificial viscosity alpha = 0.1 (the pair approaches);
 * kinematic viscosity nu = 1e-3 m^2/s (mu = rho nu); delta-SPH after Molteni & Colagrossi,
 * delta = 0.1; gravity (0, -9.81). By hand, with grad_i W = dW/dr x_ij / r, V_j = m_j / rho_j
 * and eta^2 = 0.01 h^2:
 *   a_i = -m_j (p_i / rho_i^2 + p_j / rho_j^2 + Pi_ij) grad_i W
 *         + 1/rho_i V_j (mu_i + mu_j) x_ij . grad_i W / (r^2 + eta^2) v_ij + g,
 *   Pi_ij = -alpha c0 mu_ij / rho_bar, mu_ij = h v_ij . x_ij / (r^2 + eta^2),
 *   drho_i/dt = rho_i V_j v_ij . grad_i W - 2 delta h c0 (rho_j - rho_i) V_j
 *               x_ij . grad_i W / (r^2 + eta^2),
 * and the same for j with i and j exchanged.
 * Tolerances: the list loop 1e-12 of each quantity's scale (a few roundings of double
 * precision); the cell loop 2e-6 (single precision, 2^-24 = 6e-8, over some 20 operations). */
#define _POSIX_C_SOURCE 200809L /* mkdtemp (tmpdir.h) */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#define RY_TMPDIR_PREFIX "ryushi_pair_"
#include "tmpdir.h"
#include "ryushi/run.h"

#define PI 3.14159265358979323846

static const double dx = 0.01, rho0 = 1000.0, c0 = 10.0, alpha = 0.1, nu = 1e-3, delta = 0.1;
static const double g[2] = {0.0, -9.81};

/* The two particles' rates by hand: a[k][d] and drho[k], k = 0 for i, 1 for j. */
static void by_hand(const double x[2][2], const double v[2][2], const double rho[2], double m,
                    double a[2][2], double drho[2]) {
    const double h = 1.4 * dx, eta2 = 0.01 * h * h, sigma = 7.0 / (4.0 * PI);
    for (int k = 0; k < 2; ++k) {
        const int o = 1 - k;
        const double xij[2] = {x[k][0] - x[o][0], x[k][1] - x[o][1]};
        const double vij[2] = {v[k][0] - v[o][0], v[k][1] - v[o][1]};
        const double r = sqrt(xij[0] * xij[0] + xij[1] * xij[1]), q = r / h, s = 0.5 * q;
        const double dwdr = sigma / (h * h * h) * (-10.0 * s * pow(1.0 - s, 3));
        const double gw[2] = {dwdr * xij[0] / r, dwdr * xij[1] / r};
        const double xg = xij[0] * gw[0] + xij[1] * gw[1], vx = vij[0] * xij[0] + vij[1] * xij[1];
        const double vg = vij[0] * gw[0] + vij[1] * gw[1];
        const double pk = c0 * c0 * (rho[k] - rho0), po = c0 * c0 * (rho[o] - rho0);
        const double muij = vx < 0 ? h * vx / (r * r + eta2) : 0.0;
        const double pi_ij = -alpha * c0 * muij / (0.5 * (rho[k] + rho[o]));
        const double vol = m / rho[o], musum = (rho[k] + rho[o]) * nu;
        for (int d = 0; d < 2; ++d)
            a[k][d] = -m * (pk / (rho[k] * rho[k]) + po / (rho[o] * rho[o]) + pi_ij) * gw[d] +
                      vol * musum * xg / (r * r + eta2) * vij[d] / rho[k] + g[d];
        drho[k] = rho[k] * vol * vg -
                  2.0 * delta * h * c0 * (rho[o] - rho[k]) * vol * xg / (r * r + eta2);
    }
}

static void check_loop(const char *loop, double tol) {
    char text[1024];
    snprintf(text, sizeof text,
             "dimension: 2\nspacing: %g\n"
             "kernel: {type: wendland_c2, h_over_dx: 1.4}\n"
             "materials: [{name: water, density: %g, viscosity: %g}]\n"
             "gravity: [%g, %g]\n"
             "bodies:\n"
             "  - {type: box, lo: [0, 0], hi: [0.01, 0.01]}\n"
             "  - {type: box, lo: [0.008, 0.006], hi: [0.018, 0.016]}\n"
             "domain: {lo: [-0.05, -0.05], hi: [0.07, 0.07]}\n"
             "scheme: {name: wcsph, eos: linear, sound_speed: %g, artificial_viscosity: "
             "{alpha: %g}, density_diffusion: molteni, delta: %g, pair_loop: %s}\n"
             "time: {end: 0.01}\n"
             "output: {vtk: false}\n",
             dx, rho0, nu, g[0], g[1], c0, alpha, delta, loop);
    ry_case *c = NULL;
    ry_sim sim;
    ry_error err = {0};
    memset(&sim, 0, sizeof sim);
    assert_int_equal(ry_case_load_string(&c, "pair.yaml", text, &err), RY_OK);
    if (ry_sim_setup(&sim, c, tmpdir, &err) != RY_OK) fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(sim.ps.n, 2);
    ry_particles *ps = &sim.ps;
    /* particle i: the one at the lower left */
    const size_t i = ps->f[RY_F_X][0] < ps->f[RY_F_X][1] ? 0 : 1, j = 1 - i;
    const double rho[2] = {1010.0, 995.0}, v[2][2] = {{0.1, 0.05}, {-0.2, 0.0}};
    double x[2][2];
    const size_t idx[2] = {i, j};
    for (int k = 0; k < 2; ++k) {
        ps->f[RY_F_RHO][idx[k]] = rho[k];
        for (int d = 0; d < 2; ++d) {
            ps->f[RY_F_VX + d][idx[k]] = v[k][d];
            x[k][d] = ps->f[RY_F_X + d][idx[k]];
        }
    }
    assert_true(fabs(x[0][0] - 0.005) < 1e-12 && fabs(x[1][1] - 0.011) < 1e-12);
    const double m = ps->f[RY_F_MASS][i];
    assert_true(fabs(m - rho0 * dx * dx) < 1e-15);
    double dt;
    assert_int_equal(sim.scheme->stable_dt(&sim, sim.scheme_state, &dt, &err), RY_OK);
    double a[2][2], drho[2];
    by_hand(x, v, rho, m, a, drho);
    for (int k = 0; k < 2; ++k) {
        const double ascale = fabs(a[k][0]) + fabs(a[k][1]), dscale = fabs(drho[k]);
        print_message("%s loop, particle %c: a = (%.9g, %.9g) by hand (%.9g, %.9g); drho/dt = "
                      "%.9g by hand %.9g\n",
                      loop, k ? 'j' : 'i', ps->f[RY_F_AX][idx[k]], ps->f[RY_F_AY][idx[k]], a[k][0],
                      a[k][1], ps->f[RY_F_DRHO][idx[k]], drho[k]);
        for (int d = 0; d < 2; ++d)
            assert_true(fabs(ps->f[RY_F_AX + d][idx[k]] - a[k][d]) <= tol * ascale);
        assert_true(fabs(ps->f[RY_F_DRHO][idx[k]] - drho[k]) <= tol * dscale);
    }
    ry_sim_free(&sim);
    ry_case_free(c);
}

static void test_list_loop(void **state) {
    (void)state;
    check_loop("list", 1e-12);
}

static void test_cell_loop(void **state) {
    (void)state;
    check_loop("cells", 2e-6);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_list_loop),
        cmocka_unit_test(test_cell_loop),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
