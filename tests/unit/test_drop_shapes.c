/* Drops set to oscillate (bodies[k].mode, .amplitude) and the mode-2 shape moment (shape_p2):
 * the moment reads the amplitude of the surface R (1 + eps Y_2) to first order (within 10 % at 20
 * spacings per radius, the lattice's steps), 0 for the round drop (to 1e-3) and -eps when the
 * sign is turned; the body holds the round drop's volume (within 2 %, the lattice's); mode 4
 * leaves the mode-2 moment below 0.01; a body's half_space keeps the side of its plane; the keys'
 * errors name them. */
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

#include "ryushi/sim.h"

#define RY_TMPDIR_PREFIX "ryushi_drop_shapes_"
#include "tmpdir.h"
#include "ryushi/particles.h"
#include "ryushi/run.h"

static const double PI = 3.14159265358979323846;

static ry_status setup(ry_sim *sim, ry_case **c, int dim, const char *shape, ry_error *err) {
    char text[2048];
    snprintf(text, sizeof text,
             "dimension: %d\nspacing: 1.0e-4\n"
             "materials: [{name: water, density: 1000}]\n"
             "bodies:\n"
             "  - {type: %s, centre: [0, 0%s], radius: %s%s}\n"
             "domain: {lo: [-5.0e-3, -5.0e-3%s], hi: [5.0e-3, 5.0e-3%s]}\n"
             "scheme: {name: static}\n"
             "time: {end: 0.1}\n"
             "output: {vtk: false}\n",
             dim, dim == 2 ? "circle" : "sphere", dim == 2 ? "" : ", 0",
             dim == 2 ? "2.0e-3" : "1.0e-3", shape, dim == 2 ? "" : ", -5.0e-3",
             dim == 2 ? "" : ", 5.0e-3");
    memset(sim, 0, sizeof *sim);
    RY_TRY(ry_case_load_string(c, "drop.yaml", text, err));
    return ry_sim_setup(sim, *c, tmpdir, err);
}

static void shape(int dim, const char *keys, double *p2, size_t *n) {
    ry_sim sim;
    ry_case *c = NULL;
    ry_error err = {0};
    assert_int_equal(setup(&sim, &c, dim, keys, &err), RY_OK);
    *p2 = ry_particles_shape_p2(&sim.ps, dim, RY_KIND_FLUID, sim.dx);
    *n = sim.ps.n;
    ry_sim_free(&sim);
    ry_case_free(c);
}

static void test_mode2(void **state) {
    (void)state;
    for (int dim = 2; dim <= 3; ++dim) {
        double round, up, down;
        size_t n0, n1, n2;
        shape(dim, "", &round, &n0);
        shape(dim, ", mode: 2, amplitude: 0.05", &up, &n1);
        shape(dim, ", mode: 2, amplitude: -0.05", &down, &n2);
        assert_true(fabs(round) < 1e-3);
        assert_true(fabs(up / 0.05 - 1) < 0.1);
        assert_true(fabs(down / -0.05 - 1) < 0.1);
        /* the volume of the round drop of radius R: 20 spacings (2D), 10 (3D) */
        const double R = dim == 2 ? 20.0 : 10.0,
                     v = dim == 2 ? PI * R * R : 4.0 / 3.0 * PI * R * R * R;
        assert_true(fabs((double)n1 / v - 1) < 0.02);
        assert_true(fabs((double)n2 / v - 1) < 0.02);
        /* mode 4 keeps the mode-2 moment near zero */
        double m4;
        size_t n4;
        shape(dim, ", mode: 4, amplitude: 0.05", &m4, &n4);
        assert_true(fabs(m4) < 0.01);
    }
}

/* bodies[k].half_space keeps the body's particles on one side of a plane: the circle cut at
 * y = 0.5 mm keeps those above it, as many as the lattice has there. */
static void test_half_space(void **state) {
    (void)state;
    ry_sim sim;
    ry_case *c = NULL;
    ry_error err = {0};
    size_t n0;
    double p2;
    shape(2, "", &p2, &n0);
    assert_int_equal(setup(&sim, &c, 2, ", half_space: {normal: [0, 2], offset: 5.0e-4}", &err),
                     RY_OK);
    size_t above = 0;
    for (size_t i = 0; i < sim.ps.n; ++i) assert_true(sim.ps.f[RY_F_Y][i] >= 5.0e-4);
    ry_sim_free(&sim);
    ry_case_free(c);
    assert_int_equal(setup(&sim, &c, 2, "", &err), RY_OK);
    for (size_t i = 0; i < sim.ps.n; ++i) above += sim.ps.f[RY_F_Y][i] >= 5.0e-4;
    ry_sim_free(&sim);
    ry_case_free(c);
    assert_int_equal(setup(&sim, &c, 2, ", half_space: {normal: [0, 2], offset: 5.0e-4}", &err),
                     RY_OK);
    assert_int_equal(sim.ps.n, above);
    assert_true(above > 0 && above < n0);
    ry_sim_free(&sim);
    ry_case_free(c);
}

static void refused(const char *keys, const char *needle) {
    ry_sim sim;
    ry_case *c = NULL;
    ry_error err = {0};
    assert_int_not_equal(setup(&sim, &c, 2, keys, &err), RY_OK);
    if (!strstr(err.msg, needle)) fail_msg("'%s' not in: %s", needle, err.msg);
    ry_sim_free(&sim);
    ry_case_free(c);
}

static void test_bad_keys(void **state) {
    (void)state;
    refused(", mode: 1", "bodies[0].mode");
    refused(", mode: 17", "bodies[0].mode");
    refused(", amplitude: 0.1", "bodies[0].amplitude");
    refused(", mode: 2, amplitude: 0.6", "bodies[0].amplitude");
    refused(", half_space: {normal: [0, 0], offset: 0}", "bodies[0].half_space.normal");
    refused(", half_space: {normal: [0, 1]}", "bodies[0].half_space.offset");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_mode2),
        cmocka_unit_test(test_half_space),
        cmocka_unit_test(test_bad_keys),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
