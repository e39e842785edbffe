/* Unit tests of the viscous term of Morris, Fox & Zhu (1997) (src/physics/viscosity_morris1997.h),
 * shared by WCSPH and IISPH.
 *
 *   - one pair by hand: Wendland C2 in 2D, h = 1, x_ij = (0.3, 0.4) (r = 0.5, q = 0.5), so
 *     dW/dr = -5 q (1 - q/2)^3 sigma / h^3 with sigma = 7 / (4 pi), x . grad W = r dW/dr,
 *     eta^2 = 0.01; V_j = 2e-3: L_ij = V_j r dW/dr / (r^2 + eta^2), compared within 1e-15
 *     relative (a few roundings);
 *   - the means: mu_i + mu_j for equal viscosities, 0 next to an inviscid fluid, symmetric;
 *   - the Laplacian of a quadratic field f = a x^2 + b y^2 on a 2D lattice (dx = 1/40):
 *     2 sum_j L_ij (f_i - f_j) / lap f tends, as h / dx grows, to the continuum value of the
 *     operator, int W' r^4 / (r^2 + eta^2) dr / int W' r^2 dr (1 without eta; 0.9837 for
 *     Wendland C2: eta^2 = 0.01 h^2 scales with h, so its bias stays). The continuum value
 *     lies in (1 - 4 eta^2 / h^2, 1); the lattice's distance to it falls from h = 3 dx to 4 dx
 *     to 6 dx and is at most 5e-4 at 4 dx (seen: 6.3e-4, 2.9e-4, 6.5e-5). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "physics/viscosity_morris1997.h"
#include "ryushi/kernel.h"

#define PI 3.14159265358979323846

static void test_pair_by_hand(void **state) {
    (void)state;
    const double q = 0.5, r = 0.5, sigma = 7.0 / (4.0 * PI), volj = 2e-3;
    const double dwdr = -5.0 * q * pow(1.0 - 0.5 * q, 3) * sigma;
    const double expect = volj * r * dwdr / (r * r + 0.01);
    ry_kernel k;
    ry_error err;
    assert_int_equal(ry_kernel_init(&k, RY_KERNEL_WENDLAND_C2, 2, 1.0, &err), RY_OK);
    const double xg =
        0.3 * (0.3 / r) * ry_kernel_dwdr(&k, r) + 0.4 * (0.4 / r) * ry_kernel_dwdr(&k, r);
    assert_true(ry_morris_eta2(1.0) == 0.01);
    const double w = ry_morris_weight(volj, xg, 1.0 / (r * r + ry_morris_eta2(1.0)));
    assert_true(w < 0);
    assert_true(fabs(w - expect) <= 1e-15 * fabs(expect));
    assert_true(fabs(ry_morris_coefficient(3e-3, w) - 3e-3 * expect) <=
                1e-15 * fabs(3e-3 * expect));
}

static void test_means(void **state) {
    (void)state;
    assert_true(ry_morris_mu_harmonic2(1e-3, 1e-3) == 2e-3);
    assert_true(ry_morris_mu_harmonic2(0.0, 1e-3) == 0.0);
    assert_true(ry_morris_mu_harmonic2(0.0, 0.0) == 0.0);
    assert_true(ry_morris_mu_harmonic2(1e-3, 5e-2) == ry_morris_mu_harmonic2(5e-2, 1e-3));
    /* twice the harmonic mean of 1 and 3: 2 * 2 * 3 / 4 = 3 */
    assert_true(fabs(ry_morris_mu_harmonic2(1.0, 3.0) - 3.0) <= 1e-15);
}

/* 2 sum_j L_ij (f_i - f_j) at the origin of a lattice, f = a x^2 + b y^2. */
static double lattice_laplacian(double h_over_dx, double a, double b) {
    const double dx = 1.0 / 40.0, h = h_over_dx * dx, vol = dx * dx;
    ry_kernel k;
    ry_error err;
    assert_int_equal(ry_kernel_init(&k, RY_KERNEL_WENDLAND_C2, 2, h, &err), RY_OK);
    const int m = (int)ceil(k.radius / dx) + 1;
    double s = 0;
    for (int i = -m; i <= m; ++i)
        for (int j = -m; j <= m; ++j) {
            const double x = i * dx, y = j * dx, r = sqrt(x * x + y * y);
            if (r == 0 || r >= k.radius) continue;
            const double xg = r * ry_kernel_dwdr(&k, r); /* x_ij . grad_i W, x_ij = -x_j */
            const double w = ry_morris_weight(vol, xg, 1.0 / (r * r + ry_morris_eta2(h)));
            s += 2.0 * w * (0.0 - (a * x * x + b * y * y));
        }
    return s;
}

/* The continuum limit of lattice_laplacian / lap f: int W' r^4 / (r^2 + eta^2) dr /
 * int W' r^2 dr (h = 1, composite Simpson, 4000 intervals), below 1 by the eta^2 term. */
static double continuum_ratio(void) {
    ry_kernel k;
    ry_error err;
    assert_int_equal(ry_kernel_init(&k, RY_KERNEL_WENDLAND_C2, 2, 1.0, &err), RY_OK);
    const int n = 4000;
    const double step = k.radius / n, eta2 = ry_morris_eta2(1.0);
    double num = 0, den = 0;
    for (int i = 0; i <= n; ++i) {
        const double r = i * step, wt = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2);
        const double d = i == n ? 0.0 : ry_kernel_dwdr(&k, r);
        num += wt * d * r * r * r * r / (r * r + eta2);
        den += wt * d * r * r;
    }
    return num / den;
}

static void test_lattice_laplacian(void **state) {
    (void)state;
    const double a = 1.5, b = -0.5, lap = 2.0 * (a + b), limit = continuum_ratio();
    const double e3 = lattice_laplacian(3, a, b) / lap - limit;
    const double e4 = lattice_laplacian(4, a, b) / lap - limit;
    const double e6 = lattice_laplacian(6, a, b) / lap - limit;
    print_message("continuum %.5f; lattice less continuum: h = 3 dx %.1e, 4 dx %.1e, 6 dx %.1e\n",
                  limit, e3, e4, e6);
    assert_true(limit < 1.0 && limit > 1.0 - 4.0 * ry_morris_eta2(1.0));
    assert_true(fabs(e4) <= 5e-4);
    assert_true(fabs(e6) < fabs(e4) && fabs(e4) < fabs(e3));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_pair_by_hand),
        cmocka_unit_test(test_means),
        cmocka_unit_test(test_lattice_laplacian),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
