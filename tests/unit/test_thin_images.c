/* The potential model's images of thin walls (ry_surface_tension.thin_normal, thin_layers;
 * docs/reference/mps.md, "Thin walls"): a block of fluid on a wall of one layer whose images stand
 * one and two spacings behind it takes from the wall the same forces as on a wall of three layers,
 * to rounding (1e-12 of the largest). Without the images the wall holds the layer next to it less:
 * at 90 degrees the fluid above pulls the middle of that layer off the wall at 2,097 m/s^2,
 * against 1,363 with the images (the test asks for a difference of more than 10 %). */
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
#include "ryushi/surface_tension.h"

#define RY_TMPDIR_PREFIX "ryushi_thin_images_"
#include "tmpdir.h"
#include "ryushi/run.h"

#define L0 2.0e-4

/* A block of 6 x 6 x 3 fluid particles on a wall of the given layers (one layer: its top at
 * z = 0), set up and searched within the model's radius. */
static void setup(ry_sim *sim, ry_case **c, int layers) {
    char text[2048];
    snprintf(text, sizeof text,
             "dimension: 3\nspacing: %g\n"
             "materials: [{name: water, density: 1000}]\n"
             "bodies:\n"
             "  - {type: box, lo: [-6.0e-4, -6.0e-4, 0], hi: [6.0e-4, 6.0e-4, 6.0e-4]}\n"
             "  - {type: box, kind: wall, lo: [-1.4e-3, -1.4e-3, %g], hi: [1.4e-3, 1.4e-3, 0]}\n"
             "domain: {lo: [-2.0e-3, -2.0e-3, -1.0e-3], hi: [2.0e-3, 2.0e-3, 1.0e-3]}\n"
             "scheme: {name: static}\n"
             "time: {end: 0.1}\n"
             "output: {vtk: false}\n",
             L0, -layers * L0);
    ry_error err = {0};
    memset(sim, 0, sizeof *sim);
    assert_int_equal(ry_case_load_string(c, "thin_images.yaml", text, &err), RY_OK);
    char od[512];
    snprintf(od, sizeof od, "%s/layers%d", tmpdir, layers);
    assert_int_equal(ry_sim_setup(sim, *c, od, &err), RY_OK);
    assert_int_equal(ry_sim_neighbors(sim, 3.1 * L0, &err), RY_OK);
}

/* The potential model's acceleration of every particle (3 n, zero for walls); images of the
 * walls with thin_layers > 1, their sheet's normal +z. */
static double *accelerate(ry_sim *sim, int thin_layers) {
    const size_t n = sim->ps.n;
    ry_surface_tension st;
    ry_error err = {0};
    assert_int_equal(ry_st_setup(&st, RY_ST_POTENTIAL, 3, L0, 3.1 * L0, 0.0728, &err), RY_OK);
    st.wall_ratio[0][0] = 0.5; /* 90 degrees */
    double *nrm = calloc(3 * n, sizeof *nrm), *acc = calloc(3 * n, sizeof *acc);
    assert_non_null(nrm);
    assert_non_null(acc);
    for (size_t i = 0; i < n; ++i)
        if (sim->ps.kind[i] == RY_KIND_WALL) nrm[3 * i + 2] = 1.0;
    st.thin_normal = nrm;
    st.thin_layers = thin_layers;
    double *a[3] = {acc, acc + n, acc + 2 * n};
    assert_int_equal(ry_st_accelerate(&st, sim, a, &err), RY_OK);
    free(nrm);
    return acc;
}

/* The index in sim of the particle of the given kind at x (the searches may reorder). */
static size_t find(const ry_sim *sim, const double *x, int kind) {
    for (size_t j = 0; j < sim->ps.n; ++j) {
        if (sim->ps.kind[j] != kind) continue;
        double d2 = 0;
        for (int d = 0; d < 3; ++d) {
            const double e = sim->ps.f[RY_F_X + d][j] - x[d];
            d2 += e * e;
        }
        if (d2 < 1e-6 * L0 * L0) return j;
    }
    fail_msg("no particle at (%g, %g, %g)", x[0], x[1], x[2]);
    return 0;
}

static void test_images_as_thick_wall(void **state) {
    (void)state;
    ry_sim thin, thick;
    ry_case *c1 = NULL, *c3 = NULL;
    setup(&thin, &c1, 1);
    setup(&thick, &c3, 3);
    double *a1 = accelerate(&thin, 3), *a3 = accelerate(&thick, 1), *a0 = accelerate(&thin, 1);
    const size_t n1 = thin.ps.n, n3 = thick.ps.n;
    double amax = 0, dmax = 0, bottom_images = 0, bottom_none = 0;
    int fluid = 0;
    for (size_t i = 0; i < n1; ++i) {
        if (thin.ps.kind[i] != RY_KIND_FLUID) continue;
        const double x[3] = {thin.ps.f[RY_F_X][i], thin.ps.f[RY_F_Y][i], thin.ps.f[RY_F_Z][i]};
        const size_t j = find(&thick, x, RY_KIND_FLUID);
        for (int d = 0; d < 3; ++d) {
            amax = fmax(amax, fabs(a3[d * n3 + j]));
            dmax = fmax(dmax, fabs(a1[d * n1 + i] - a3[d * n3 + j]));
        }
        if (x[2] < L0 && fabs(x[0]) < L0 && fabs(x[1]) < L0) { /* the middle of the bottom */
            bottom_images = a1[2 * n1 + i];
            bottom_none = a0[2 * n1 + i];
        }
        ++fluid;
    }
    printf("thin wall with images against three layers: %d fluid particles, largest difference "
           "%.3g of %.3g m/s^2; the bottom layer's z acceleration %.4g with images, %.4g without\n",
           fluid, dmax, amax, bottom_images, bottom_none);
    assert_int_equal(fluid, 108);
    assert_true(amax > 0 && dmax <= 1e-12 * amax);
    /* without the images the wall holds the layer next to it less */
    assert_true(bottom_images != 0 &&
                fabs(bottom_none - bottom_images) > 0.1 * fabs(bottom_images));
    free(a0);
    free(a1);
    free(a3);
    ry_sim_free(&thin);
    ry_sim_free(&thick);
    ry_case_free(c1);
    ry_case_free(c3);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_images_as_thick_wall),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
