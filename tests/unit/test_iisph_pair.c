/* Unit tests of the pair terms of the IISPH pressure (src/schemes/iisph/iisph_pair.h) on three
 * hand-placed fluid particles that are all neighbours of one another, with gradients
 * G_ij = grad_i W_ij = -G_ji given by hand (any values serve: the terms are linear in them),
 * masses, number densities, pressures and velocities:
 *
 *   - each sum against its formula written out here: the predicted number density, d_ii,
 *     a_ii, S_i and the pressure acceleration, within 1e-13 relative;
 *   - the identity the Jacobi iteration rests on: a_ii p_i + sum_j (S_i - D_j) . G_ij equals
 *     dt^2 sum_j (a_i - a_j) . G_ij with the pressure accelerations a of the pair term, for each
 *     particle, within 1e-12 relative (d_ii, a_ii, S, the Jacobi term and the force must agree
 *     for it to hold);
 *   - a wall neighbour (not mobile) enters a_ii without d_ji, and the Jacobi term with S_i . G
 *     only (the traversal adds -D_j . G for mobile neighbours alone). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "schemes/iisph/iisph_pair.h"

enum { N = 3 };
static const double dt = 1e-3, m[N] = {1.0e-3, 1.2e-3, 0.9e-3};
static const double delta[N] = {1.02e4, 0.99e4, 1.05e4}, p[N] = {350.0, 120.0, 610.0};
static const double v[N][3] = {{0.1, -0.2, 0.05}, {-0.3, 0.1, 0.0}, {0.2, 0.25, -0.1}};

/* G[i][j] = grad_i W_ij, antisymmetric. */
static void gradients(double G[N][N][3]) {
    const double g01[3] = {-2.0e3, 1.5e3, 0.5e3}, g02[3] = {1.0e3, 2.5e3, -3.0e3};
    const double g12[3] = {4.0e3, -0.5e3, 1.0e3};
    for (int d = 0; d < 3; ++d) {
        G[0][0][d] = G[1][1][d] = G[2][2][d] = 0;
        G[0][1][d] = g01[d], G[1][0][d] = -g01[d];
        G[0][2][d] = g02[d], G[2][0][d] = -g02[d];
        G[1][2][d] = g12[d], G[2][1][d] = -g12[d];
    }
}

static double dot(const double *a, const double *b) {
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void near(double got, double want, double tol) {
    assert_true(fabs(got - want) <= tol * fabs(want));
}

static void test_sums_and_identity(void **state) {
    (void)state;
    double G[N][N][3];
    gradients(G);
    const double dt2 = dt * dt;
    double dii[N][3], S[N][3], acc[N][3], aii[N];
    /* The pair functions. */
    for (int i = 0; i < N; ++i) {
        double dv = 0, sd[3] = {0, 0, 0}, s[3] = {0, 0, 0}, a[3] = {0, 0, 0};
        for (int j = 0; j < N; ++j)
            if (j != i) {
                iisph_pair_predict(&dv, sd, v[i], v[j], G[i][j], 3);
                iisph_pair_sum(s, p[j] / (delta[j] * delta[j]), G[i][j], 3);
                iisph_pair_pressure(a, p[i] / (delta[i] * delta[i]), p[j] / (delta[j] * delta[j]),
                                    G[i][j], 3);
            }
        /* by hand */
        double dv_h = 0, sd_h[3] = {0, 0, 0}, s_h[3] = {0, 0, 0}, a_h[3] = {0, 0, 0};
        for (int j = 0; j < N; ++j)
            for (int d = 0; d < 3; ++d) {
                dv_h += (v[i][d] - v[j][d]) * G[i][j][d];
                sd_h[d] += G[i][j][d];
                s_h[d] += p[j] / (delta[j] * delta[j]) * G[i][j][d];
                a_h[d] -=
                    (p[i] / (delta[i] * delta[i]) + p[j] / (delta[j] * delta[j])) * G[i][j][d];
            }
        near(dv, dv_h, 1e-13);
        for (int d = 0; d < 3; ++d) {
            near(sd[d], sd_h[d], 1e-13);
            near(s[d], s_h[d], 1e-13);
            near(a[d], a_h[d], 1e-13);
            dii[i][d] = -dt2 / (m[i] * delta[i] * delta[i]) * sd[d];
            S[i][d] = -dt2 / m[i] * s[d];
            acc[i][d] = a[d] / m[i];
        }
    }
    for (int i = 0; i < N; ++i) {
        const double di2 = delta[i] * delta[i];
        double a = 0, a_h = 0, rest = 0, change = 0;
        for (int j = 0; j < N; ++j) {
            if (j == i) continue;
            iisph_pair_aii(&a, dii[i], G[i][j], 1, dt2 / (m[j] * di2), 3);
            /* d_ji = -dt^2 / (m_j delta_i^2) grad_j W_ji = dt^2 / (m_j delta_i^2) G_ij */
            double dji[3];
            for (int d = 0; d < 3; ++d) dji[d] = dt2 / (m[j] * di2) * G[i][j][d];
            a_h += dot(dii[i], G[i][j]) - dot(dji, G[i][j]);
            double t = iisph_pair_jacobi(S[i], G[i][j], 3);
            double u[3]; /* d_jj p_j + S_j */
            for (int d = 0; d < 3; ++d) u[d] = dii[j][d] * p[j] + S[j][d];
            iisph_pair_jacobi_mobile(&t, u, dt2 / (m[j] * di2) * p[i], G[i][j], 3);
            rest += t;
            double da[3];
            for (int d = 0; d < 3; ++d) da[d] = acc[i][d] - acc[j][d];
            change += dt2 * dot(da, G[i][j]);
        }
        near(a, a_h, 1e-13);
        aii[i] = a;
        const double lhs = aii[i] * p[i] + rest;
        print_message("particle %d: a_ii p_i + rest = %.15g, dt^2 sum (a_i - a_j).G = %.15g\n", i,
                      lhs, change);
        near(lhs, change, 1e-12);
    }
}

/* A wall neighbour: no d_ji in a_ii, no D_j in the Jacobi term. */
static void test_wall_neighbour(void **state) {
    (void)state;
    const double dii[3] = {1e-4, -2e-4, 3e-4}, G[3] = {1e3, 2e3, -1e3}, si[3] = {0.1, 0.2, 0.3};
    double a = 0;
    iisph_pair_aii(&a, dii, G, 0, 123.0, 3);
    near(a, dot(dii, G), 1e-15);
    near(iisph_pair_jacobi(si, G, 3), dot(si, G), 1e-15);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_sums_and_identity),
        cmocka_unit_test(test_wall_neighbour),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
