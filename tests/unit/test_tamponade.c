/* The tamponade's equilibrium (ry_tamponade_solve, src/validate/tamponade.c) against closed
 * forms:
 * - a flat interface at height z_c is a solution for any Bond number when the contact angle is
 *   the plane's own, cos(theta) = -z_c: then fill = x^2 (3 - 2x) and coverage = x, x = (1 - z_c)
 *   / 2 (to 1e-7, the shooting's tolerance on the fill being 1e-6 relative);
 * - without gravity the interface is a sphere of radius rho = 2 / k0: the oil is the lens
 *   where two balls overlap (volume in closed form), the contact line where the spheres meet,
 *   and the angle through the saline acos(n_wall . n_interface) (to 1e-7);
 * - as the Bond number grows the meniscus shrinks to the capillary length R / sqrt(B) and the
 *   coverage approaches the flat limit: sqrt(B) |coverage - x| about constant (within 10 % at
 *   B = 30, 100, 300; measured 0.37, 0.39, 0.39).
 * Units: the sphere's radius. */
#include <math.h>
#include <stdio.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "ryushi/validate.h"

static const double PI = 3.14159265358979323846;

static double flat_x(double fill) {
    double lo = 0, hi = 1;
    for (int i = 0; i < 80; ++i) {
        const double x = 0.5 * (lo + hi);
        if (x * x * (3 - 2 * x) < fill)
            lo = x;
        else
            hi = x;
    }
    return 0.5 * (lo + hi);
}

static void test_flat_interface(void **state) {
    (void)state;
    const double bonds[] = {0.0, 1.06, 10.0}, xs[] = {0.5, 0.7, 0.85};
    for (int b = 0; b < 3; ++b)
        for (int k = 0; k < 3; ++k) {
            const double x = xs[k], fill = x * x * (3 - 2 * x);
            ry_tamponade t;
            ry_error err = {0};
            assert_int_equal(ry_tamponade_solve(fill, acos(2 * x - 1), bonds[b], &t, &err), RY_OK);
            assert_true(fabs(t.coverage - x) < 1e-7);
            assert_true(fabs(t.z_apex - t.z_contact) < 1e-7);
            assert_true(fabs(t.k0) < 1e-6);
        }
}

static void test_zero_bond_lens(void **state) {
    (void)state;
    const double theta = 18 * PI / 180, fills[] = {0.6, 0.8, 0.9};
    for (int k = 0; k < 3; ++k) {
        ry_tamponade t;
        ry_error err = {0};
        assert_int_equal(ry_tamponade_solve(fills[k], theta, 0.0, &t, &err), RY_OK);
        const double rho = 2 / t.k0, c = t.z_apex + rho; /* the interface's sphere */
        const double zc = (1 - rho * rho + c * c) / (2 * c);
        const double d = fabs(c), lens = PI * (1 + rho - d) * (1 + rho - d) *
                                         (d * d + 2 * d * (1 + rho) - 3 * (1 - rho) * (1 - rho)) /
                                         (12 * d);
        assert_true(fabs(t.z_contact - zc) < 1e-7);
        assert_true(fabs(lens / (4 * PI / 3) - fills[k]) < 1e-7);
        assert_true(fabs(acos((1 - c * zc) / rho) - theta) < 1e-7);
        assert_true(t.coverage < flat_x(fills[k])); /* the oil beads up: less than the plane */
        /* its meridian (ry_tamponade_profile): on that sphere, from the apex to the wall */
        double r[200], z[200];
        const size_t n = ry_tamponade_profile(&t, 0.0, 200, r, z);
        assert_true(n >= 100 && n <= 200);
        for (size_t i = 0; i < n; ++i) assert_true(fabs(hypot(r[i], z[i] - c) - rho) < 1e-7);
        assert_true(fabs(r[0]) < 1e-5 && fabs(z[0] - t.z_apex) < 1e-9);
        assert_true(fabs(z[n - 1] - t.z_contact) < 1e-12 && fabs(r[n - 1] - t.r_contact) < 1e-12);
    }
    ry_tamponade t;
    ry_error err = {0};
    double r[2], z[2];
    assert_int_equal(ry_tamponade_solve(0.8, theta, 1.0, &t, &err), RY_OK);
    assert_int_equal(ry_tamponade_profile(&t, 1.0, 1, r, z), 0);
    assert_int_equal(ry_tamponade_profile(&t, 1.0, 2, r, z), 2);
}

static void test_large_bond_flattens(void **state) {
    (void)state;
    const double bonds[] = {30, 100, 300}, fill = 0.8, x = flat_x(fill);
    double scaled[3], dev[3];
    for (int b = 0; b < 3; ++b) {
        ry_tamponade t;
        ry_error err = {0};
        assert_int_equal(ry_tamponade_solve(fill, 18 * PI / 180, bonds[b], &t, &err), RY_OK);
        dev[b] = x - t.coverage;
        scaled[b] = sqrt(bonds[b]) * dev[b];
    }
    assert_true(dev[0] > dev[1] && dev[1] > dev[2] && dev[2] > 0 && dev[2] < 0.025);
    for (int b = 1; b < 3; ++b) assert_true(fabs(scaled[b] / scaled[0] - 1) < 0.1);
}

/* The 24 mm eye (R = 12 mm, oil-saline 0.04 N/m, 30 kg/m^3: B = 1.06) at 18 degrees: printed
 * for docs and notes; the oil beads up, so it covers less than the flat interface would. */
static void test_eye_values(void **state) {
    (void)state;
    const double fills[] = {0.6, 0.8, 0.9}, bond = 30 * 9.81 * 0.012 * 0.012 / 0.04;
    for (int k = 0; k < 3; ++k) {
        ry_tamponade t;
        ry_error err = {0};
        assert_int_equal(ry_tamponade_solve(fills[k], 18 * PI / 180, bond, &t, &err), RY_OK);
        printf("tamponade B = %.3f, 18 degrees, fill %.1f: coverage %.4f (flat %.4f), apex at "
               "%.4f R\n",
               bond, fills[k], t.coverage, flat_x(fills[k]), t.z_apex);
        assert_true(t.coverage < flat_x(fills[k]));
    }
}

/* Region coverage (ry_tamponade_region_coverage) against what the sphere's symmetry gives: the
 * whole sphere and any hemisphere about a horizontal direction carry the covered share
 * (1 - z_c)/2 (the contact line a circle of latitude about `up`); a cone about `up` narrower
 * than the dry cap's complement is covered wholly, one about `down` within the dry cap not at
 * all; cones about opposite horizontal directions agree (to 1e-6, Simpson's rule's error). */
static void test_region_coverage(void **state) {
    (void)state;
    ry_tamponade t;
    ry_error err = {0};
    assert_int_equal(ry_tamponade_solve(0.8, 18 * PI / 180, 1.06, &t, &err), RY_OK);
    const double up[3] = {0, 1, 0}, down[3] = {0, -1, 0}, x[3] = {1, 0, 0}, mx[3] = {-1, 0, 0},
                 z[3] = {0, 0, 1}, tilt[3] = {0.6, 0, 0.8};
    const double half = (1 - t.z_contact) / 2;
    assert_true(fabs(t.coverage - half) < 1e-9);
    assert_true(fabs(ry_tamponade_region_coverage(&t, up, up, PI) - half) < 1e-6);
    assert_true(fabs(ry_tamponade_region_coverage(&t, up, x, PI / 2) - half) < 1e-6);
    assert_true(fabs(ry_tamponade_region_coverage(&t, up, tilt, PI / 2) - half) < 1e-6);
    const double a = acos(t.z_contact); /* the oil's cap about up */
    assert_true(ry_tamponade_region_coverage(&t, up, up, 0.99 * a) == 1.0);
    assert_true(ry_tamponade_region_coverage(&t, up, down, 0.99 * (PI - a)) == 0.0);
    assert_true(fabs(ry_tamponade_region_coverage(&t, up, x, PI / 4) -
                     ry_tamponade_region_coverage(&t, up, mx, PI / 4)) < 1e-12);
    assert_true(fabs(ry_tamponade_region_coverage(&t, up, z, PI / 4) -
                     ry_tamponade_region_coverage(&t, up, x, PI / 4)) < 1e-12);
}

static void test_bad_input(void **state) {
    (void)state;
    ry_tamponade t;
    ry_error err = {0};
    assert_int_equal(ry_tamponade_solve(1.2, 0.3, 1.0, &t, &err), RY_ERR_INPUT);
    assert_non_null(strstr(err.msg, "fill 1.2"));
    assert_int_equal(ry_tamponade_solve(0.8, 0.3, 5000, &t, &err), RY_ERR_INPUT);
    assert_non_null(strstr(err.msg, "Bond number 5000"));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_flat_interface),      cmocka_unit_test(test_zero_bond_lens),
        cmocka_unit_test(test_large_bond_flattens), cmocka_unit_test(test_eye_values),
        cmocka_unit_test(test_region_coverage),     cmocka_unit_test(test_bad_input),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
