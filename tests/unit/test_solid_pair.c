/* Unit tests of the solids' pair terms (src/schemes/solid/solid_pair.h) and of the artificial
 * viscosity of Monaghan (1992) (src/physics/artificial_viscosity_monaghan1992.h), on hand-placed
 * pairs in 3D with stresses, correction matrices and gradients given by hand:
 *
 *   - the updated-Lagrangian pair against sigma_i w_i + sigma_j w_j + m_i m_j (f^n (R_i + R_j)
 *     - Pi I) g written out here (1e-14 relative), and its antisymmetry: the force on j from i
 *     is minus the force on i from j (g_ji = -g_ij, the roles swapped), within 1e-15 of the
 *     force's size;
 *   - the total-Lagrangian pair against V_i A_i G_ij - V_j A_j G_ji and its antisymmetry with
 *     unrelated G_ij and G_ji (exact: the same products); the same for the strain-gradient
 *     pair sum_k V Q_k H_k;
 *   - the hourglass penalty vanishes for an affine motion x = F X (to rounding, 1e-15 of
 *     |x_ji|) and equals c_ij (x_ji - F X_ji) by hand for a perturbed one (1e-11: a difference
 *     a thousand times smaller than x_ji);
 *   - Pi_ij by hand for an approaching pair, 0 for a receding one, the single-precision form
 *     within 1e-6;
 *   - the rates pass: for a linear velocity field v = A x over hand-placed neighbours with any
 *     weights g_j, the sums give Lv = A B^T (so that the corrected gradient Lv B^-T is A):
 *     within 1e-13 of |Lv|. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "physics/artificial_viscosity_monaghan1992.h"
#include "schemes/solid/solid_pair.h"

static const double si[9] = {-2e5, 3e4, -1e4, 3e4, 1e5, 2e4, -1e4, 2e4, -5e4};
static const double sj[9] = {1e5, -2e4, 0, -2e4, -3e5, 1e4, 0, 1e4, 2e5};
static const double Ri[9] = {-0.1, 0.02, 0, 0.02, 0.05, 0, 0, 0, -0.03};
static const double Rj[9] = {0.04, 0, 0.01, 0, -0.02, 0, 0.01, 0, 0.06};
static const double Li[9] = {1.1, 0.05, 0, 0.02, 0.95, -0.03, 0, 0.01, 1.02};
static const double Lj[9] = {0.9, -0.04, 0.02, 0, 1.05, 0, 0.03, 0, 0.98};

static void matvec_add(double *y, const double *A, const double *x, double s) {
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) y[a] += s * A[3 * a + b] * x[b];
}

static double norm3(const double *v) {
    return sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
}

static void test_updated_lagrangian(void **state) {
    (void)state;
    const double g[3] = {-3e4, 1.2e4, 5e3}, vi = 2e-6, vj = 1.8e-6, mm = 4e-6, fn = 0.3, pi = 7.5;
    double wi[3] = {0, 0, 0}, wj[3] = {0, 0, 0}, f[3] = {0, 0, 0};
    ry_solid_ul_weights(Li, Lj, vi, vj, g, wi, wj, 3);
    ry_solid_ul_pair(f, si, wi, sj, wj, Ri, Rj, g, mm, fn, pi, 3);
    /* by hand */
    double hwi[3] = {0, 0, 0}, hwj[3] = {0, 0, 0}, hf[3] = {0, 0, 0}, R[9];
    matvec_add(hwi, Li, g, vi * vj);
    matvec_add(hwj, Lj, g, vi * vj);
    matvec_add(hf, si, hwi, 1.0);
    matvec_add(hf, sj, hwj, 1.0);
    for (int k = 0; k < 9; ++k) R[k] = Ri[k] + Rj[k];
    matvec_add(hf, R, g, mm * fn);
    for (int a = 0; a < 3; ++a) hf[a] -= mm * pi * g[a];
    for (int a = 0; a < 3; ++a) assert_true(fabs(f[a] - hf[a]) <= 1e-14 * norm3(hf));
    /* j's row: g_ji = -g, its own matrix first */
    const double gji[3] = {-g[0], -g[1], -g[2]};
    double wj2[3] = {0, 0, 0}, wi2[3] = {0, 0, 0}, f2[3] = {0, 0, 0};
    ry_solid_ul_weights(Lj, Li, vj, vi, gji, wj2, wi2, 3);
    ry_solid_ul_pair(f2, sj, wj2, si, wi2, Rj, Ri, gji, mm, fn, pi, 3);
    print_message("UL: f_ij = (%.9g, %.9g, %.9g), f_ji = (%.9g, %.9g, %.9g)\n", f[0], f[1], f[2],
                  f2[0], f2[1], f2[2]);
    for (int a = 0; a < 3; ++a) assert_true(fabs(f[a] + f2[a]) <= 1e-15 * norm3(f));
}

static void test_total_lagrangian(void **state) {
    (void)state;
    const double gij[3] = {-2e4, 1e4, 3e3}, gji[3] = {2.2e4, -0.9e4, -2.5e3};
    const double vi = 2e-6, vj = 1.7e-6;
    double f[3] = {0, 0, 0}, f2[3] = {0, 0, 0}, hf[3] = {0, 0, 0};
    ry_solid_tl_pair(f, si, vi, gij, sj, vj, gji, 3);
    ry_solid_tl_pair(f2, sj, vj, gji, si, vi, gij, 3);
    matvec_add(hf, si, gij, vi);
    matvec_add(hf, sj, gji, -vj);
    for (int a = 0; a < 3; ++a) {
        assert_true(fabs(f[a] - hf[a]) <= 1e-14 * norm3(hf));
        assert_true(f[a] == -f2[a]);
    }
    /* strain-gradient pair: Q_k = (k + 1) si (3 x 3 each), H rows k = G scaled */
    double Qi[27], Qj[27], hij[9], hji[9];
    for (int k = 0; k < 3; ++k)
        for (int c = 0; c < 9; ++c) {
            Qi[9 * k + c] = (k + 1) * si[c];
            Qj[9 * k + c] = (k + 2) * sj[c];
        }
    for (int k = 0; k < 3; ++k)
        for (int b = 0; b < 3; ++b) {
            hij[3 * k + b] = (k + 1) * gij[b];
            hji[3 * k + b] = (2 - k) * gji[b] + 1e3;
        }
    double q[3] = {0, 0, 0}, q2[3] = {0, 0, 0}, hq[3] = {0, 0, 0};
    ry_solid_tl_strain_gradient_pair(q, Qi, vi, hij, Qj, vj, hji, 3);
    ry_solid_tl_strain_gradient_pair(q2, Qj, vj, hji, Qi, vi, hij, 3);
    for (int k = 0; k < 3; ++k) {
        matvec_add(hq, Qi + 9 * k, hij + 3 * k, vi);
        matvec_add(hq, Qj + 9 * k, hji + 3 * k, -vj);
    }
    for (int a = 0; a < 3; ++a) {
        assert_true(fabs(q[a] - hq[a]) <= 1e-14 * norm3(hq));
        assert_true(q[a] == -q2[a]);
    }
}

static void test_hourglass(void **state) {
    (void)state;
    const double F[9] = {1.01, 0.02, 0, -0.01, 0.99, 0.03, 0, 0.005, 1.02};
    const double Xji[3] = {1e-3, -0.5e-3, 0.2e-3}, cij = 3e9;
    double xji[3] = {0, 0, 0}, fh[3] = {0, 0, 0};
    matvec_add(xji, F, Xji, 1.0);
    ry_solid_tl_hourglass(fh, xji, Xji, F, F, cij, 3);
    for (int a = 0; a < 3; ++a) assert_true(fabs(fh[a]) <= 1e-15 * cij * norm3(xji));
    const double d[3] = {2e-6, -1e-6, 0.5e-6};
    double xp[3], want[3];
    for (int a = 0; a < 3; ++a) xp[a] = xji[a] + d[a];
    double fp[3] = {0, 0, 0};
    ry_solid_tl_hourglass(fp, xp, Xji, F, F, cij, 3);
    for (int a = 0; a < 3; ++a) {
        want[a] = cij * d[a];
        assert_true(fabs(fp[a] - want[a]) <= 1e-11 * fabs(want[a]));
    }
}

static void test_artificial_viscosity(void **state) {
    (void)state;
    const double h = 1.3e-3, r2 = 1e-6, vdx = -2e-4, c = 50.0, rho_sum = 2010.0;
    const double alpha = 0.5, beta = 1.0, ieta = 1.0 / (r2 + 0.01 * h * h);
    const double mu = h * vdx / (r2 + 0.01 * h * h);
    const double want = (-alpha * c * mu + beta * mu * mu) / (0.5 * rho_sum);
    const double got = ry_monaghan_pi(vdx, ieta, h, c, rho_sum, alpha, beta);
    print_message("Pi_ij = %.12g, by hand %.12g\n", got, want);
    assert_true(fabs(got - want) <= 1e-14 * fabs(want));
    assert_true(ry_monaghan_pi(-vdx, ieta, h, c, rho_sum, alpha, beta) == 0.0);
    const float gf = ry_monaghan_pif((float)vdx, (float)ieta, (float)h, (float)c, (float)rho_sum,
                                     (float)alpha, (float)beta);
    assert_true(fabs(gf - want) <= 1e-6 * fabs(want));
}

static void test_rates_linear_field(void **state) {
    (void)state;
    const double A[9] = {0.3, -1.2, 0.5, 2.0, 0.1, -0.7, -0.4, 0.9, 1.5};
    const double d[4][3] = {
        {1e-3, 0, 0}, {0.2e-3, 1.1e-3, 0}, {-0.7e-3, 0.3e-3, 0.9e-3}, {0.4e-3, -0.8e-3, 0.6e-3}};
    const double g[4][3] = {
        {-2e3, 1e2, 0}, {-3e2, -1.5e3, 2e2}, {9e2, -4e2, -1.2e3}, {-5e2, 1.1e3, -8e2}};
    double B[9] = {0}, Lv[9] = {0};
    for (int k = 0; k < 4; ++k) {
        double dv[3] = {0, 0, 0};
        matvec_add(dv, A, d[k], 1.0); /* v_j - v_i = A (x_j - x_i) */
        ry_solid_moment_add(B, g[k], d[k], 3);
        ry_solid_gradient_add(Lv, dv, g[k], 3);
    }
    double want[9] = {0}, scale = 0;
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            for (int c = 0; c < 3; ++c) want[3 * a + b] += A[3 * a + c] * B[3 * b + c];
            scale = fmax(scale, fabs(Lv[3 * a + b]));
        }
    for (int k = 0; k < 9; ++k) assert_true(fabs(Lv[k] - want[k]) <= 1e-13 * scale);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_updated_lagrangian), cmocka_unit_test(test_total_lagrangian),
        cmocka_unit_test(test_hourglass),          cmocka_unit_test(test_artificial_viscosity),
        cmocka_unit_test(test_rates_linear_field),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
