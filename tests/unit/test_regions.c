/* The retina regions (case section `retina_regions`) and their coverage columns: a cavity of
 * radius 6 mm inside a wall shell, its upper half (y > 0) oil, the lower saline; a cone about
 * +y is all oil, one about -y none, one about +x or -x half; the columns follow the case's
 * measurements in series.csv's order; ry_wall_share_above counts the same walls by their
 * direction; bad sections are refused with the key named. The probe
 * interface_height finds the level between the two liquids on the vertical through the origin,
 * whichever way gravity points, and leaves a stray particle of either liquid out. */
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

#define RY_TMPDIR_PREFIX "ryushi_regions_"
#include "tmpdir.h"
#include "ryushi/probes.h"
#include "ryushi/run.h"

static const char *const base =
    "dimension: 3\nspacing: 1.0e-3\n"
    "materials: [{name: saline, density: 1000}, {name: oil, density: 970}]\n"
    "bodies:\n"
    "  - {type: sphere, centre: [0, 0, 0], radius: 6.0e-3, material: saline}\n"
    "  - {type: sphere, kind: wall, centre: [0, 0, 0], radius: 9.0e-3, overlap: skip}\n"
    "domain: {lo: [-0.012, -0.012, -0.012], hi: [0.012, 0.012, 0.012]}\n"
    "scheme: {name: static}\n"
    "time: {end: 0.1}\n"
    "output: {vtk: false}\n"
    "measure: [oil_wall_contact]\n";

static ry_status setup(ry_sim *sim, ry_case **c, const char *regions, ry_error *err) {
    char text[4096];
    snprintf(text, sizeof text, "%s%s", base, regions);
    memset(sim, 0, sizeof *sim);
    RY_TRY(ry_case_load_string(c, "regions.yaml", text, err));
    return ry_sim_setup(sim, *c, tmpdir, err);
}

static double column(const ry_sim *sim, const char *name) {
    for (int k = 0; k < sim->nprobes; ++k)
        if (strcmp(sim->probes[k]->name, name) == 0) {
            ry_error err = {0};
            double v = -1;
            assert_int_equal(ry_probe_eval(sim->probes[k], sim, &v, &err), RY_OK);
            return v;
        }
    fail_msg("no column %s", name);
    return NAN;
}

static void test_coverage(void **state) {
    (void)state;
    ry_sim sim;
    ry_case *c = NULL;
    ry_error err = {0};
    assert_int_equal(setup(&sim, &c,
                           "retina_regions:\n"
                           "  - {name: superior, direction: [0, 2, 0], half_angle: 45}\n"
                           "  - {name: inferior, direction: [0, -1, 0], half_angle: 45}\n"
                           "  - {name: nasal, direction: [1, 0, 0], half_angle: 45}\n"
                           "  - {name: temporal, direction: [-1, 0, 0], half_angle: 45}\n",
                           &err),
                     RY_OK);
    /* the columns: the measurements listed, then one per region in the section's order */
    assert_int_equal(sim.nprobes, 5);
    assert_string_equal(sim.probes[0]->name, "oil_wall_contact");
    assert_string_equal(sim.probes[1]->name, "coverage_superior");
    assert_string_equal(sim.probes[4]->name, "coverage_temporal");
    for (size_t i = 0; i < sim.ps.n; ++i)
        if (sim.ps.kind[i] == RY_KIND_FLUID && sim.ps.f[RY_F_Y][i] > 0) sim.ps.material[i] = 1;
    assert_float_equal(column(&sim, "coverage_superior"), 1.0, 0.0);
    assert_float_equal(column(&sim, "coverage_inferior"), 0.0, 0.0);
    /* the lattice is symmetric about y = 0: half, give or take a tie between nearest particles */
    assert_float_equal(column(&sim, "coverage_nasal"), 0.5, 0.05);
    assert_float_equal(column(&sim, "coverage_temporal"), 0.5, 0.05);
    assert_float_equal(column(&sim, "oil_wall_contact"), 0.5, 0.05);
    /* the wall a contact line at a given height would leave to the oil, over the same walls */
    const double o[3] = {0, 0, 0}, up[3] = {0, 2, 0}, side[3] = {1, 0, 0};
    double share = -1;
    assert_int_equal(ry_wall_share_above(&sim, NULL, o, up, -1.0, &share, &err), RY_OK);
    assert_float_equal(share, 1.0, 0.0);
    assert_int_equal(ry_wall_share_above(&sim, NULL, o, up, 1.0 + 1e-9, &share, &err), RY_OK);
    assert_float_equal(share, 0.0, 0.0);
    assert_int_equal(ry_wall_share_above(&sim, NULL, o, up, 0.0, &share, &err), RY_OK);
    assert_float_equal(share, 0.5, 0.05);
    assert_int_equal(ry_wall_share_above(&sim, NULL, o, side, 0.0, &share, &err), RY_OK);
    assert_float_equal(share, 0.5, 0.05);
    /* a region: the superior cone of 45 degrees lies wholly above 50 degrees from up, the
     * inferior wholly below */
    const double c50 = cos(50.0 * 3.14159265358979323846 / 180.0);
    assert_int_equal(ry_wall_share_above(&sim, &sim.regions[0], o, up, c50, &share, &err), RY_OK);
    assert_float_equal(share, 1.0, 0.0);
    assert_int_equal(ry_wall_share_above(&sim, &sim.regions[1], o, up, c50, &share, &err), RY_OK);
    assert_float_equal(share, 0.0, 0.0);
    /* the oil in the cone of directions 0.3 or more from up: about the sphere's area above
     * 0.3 R (0.35); the wall whose nearest fluid particle is oil reads 0.307 here, where the
     * cavity is 6 spacings in radius and a wall particle's nearest fluid particle lies off its
     * direction (the same count done apart from the engine, brute force) */
    for (size_t i = 0; i < sim.ps.n; ++i) {
        const double x = sim.ps.f[RY_F_X][i], y = sim.ps.f[RY_F_Y][i], z = sim.ps.f[RY_F_Z][i];
        if (sim.ps.kind[i] == RY_KIND_FLUID)
            sim.ps.material[i] = y > 0.3 * sqrt(x * x + y * y + z * z);
    }
    assert_int_equal(ry_wall_share_above(&sim, NULL, o, up, 0.3, &share, &err), RY_OK);
    assert_float_equal(share, 0.35, 0.025);
    assert_float_equal(column(&sim, "oil_wall_contact"), 0.307, 0.001);
    const double none[3] = {0, 0, 0};
    assert_int_equal(ry_wall_share_above(&sim, NULL, o, none, 0.0, &share, &err), RY_ERR_INPUT);
    ry_sim_free(&sim);
    ry_case_free(c);
}

/* The liquids split at y = level (oil above, against gravity -y), a few particles out of place. */
static void test_interface_height(void **state) {
    (void)state;
    ry_sim sim;
    ry_case *c = NULL;
    ry_error err = {0};
    assert_int_equal(setup(&sim, &c, "gravity: [0, -9.81, 0]\n", &err), RY_OK);
    const ry_probe *p = NULL;
    for (const ry_probe *const *q = ry_probes(); *q; ++q)
        if (strcmp((*q)->name, "interface_height") == 0) p = *q;
    assert_non_null(p);
    double v = 0;
    assert_int_equal(ry_probe_eval(p, &sim, &v, &err), RY_OK);
    assert_true(isnan(v)); /* one liquid alone */
    /* the lattice's layers lie at y = (k + 1/2) mm: the level -2 mm lies between two */
    size_t stray_oil = 0, stray_saline = 0;
    for (size_t i = 0; i < sim.ps.n; ++i) {
        if (sim.ps.kind[i] != RY_KIND_FLUID) continue;
        const double x = sim.ps.f[RY_F_X][i], y = sim.ps.f[RY_F_Y][i], z = sim.ps.f[RY_F_Z][i];
        const int axis = x * x + z * z < 1e-6;
        sim.ps.material[i] = y > -2.0e-3;
        if (axis && y < -4.0e-3 && !stray_oil++) sim.ps.material[i] = 1;
        if (axis && y > 2.0e-3 && !stray_saline++) sim.ps.material[i] = 0;
    }
    assert_int_equal(stray_oil, 8); /* the four columns about the axis, y = -4.5 and -5.5 mm */
    assert_int_equal(ry_probe_eval(p, &sim, &v, &err), RY_OK);
    assert_float_equal(v, -2.0e-3, 1e-12);
    /* gravity along +x: heights along -x, the level at x = 1 mm */
    sim.gravity[0] = 9.81;
    sim.gravity[1] = 0;
    for (size_t i = 0; i < sim.ps.n; ++i)
        if (sim.ps.kind[i] == RY_KIND_FLUID) sim.ps.material[i] = sim.ps.f[RY_F_X][i] < 1.0e-3;
    assert_int_equal(ry_probe_eval(p, &sim, &v, &err), RY_OK);
    assert_float_equal(v, -1.0e-3, 1e-12);
    ry_sim_free(&sim);
    ry_case_free(c);
}

static void refused(const char *regions, const char *needle) {
    ry_sim sim;
    ry_case *c = NULL;
    ry_error err = {0};
    assert_int_equal(setup(&sim, &c, regions, &err), RY_ERR_INPUT);
    if (!strstr(err.msg, needle)) fail_msg("'%s' not in: %s", needle, err.msg);
    ry_sim_free(&sim);
    ry_case_free(c);
}

static void test_bad_sections(void **state) {
    (void)state;
    refused("retina_regions:\n  - {name: a, direction: [0, 0, 0], half_angle: 30}\n",
            "retina_regions[0].direction");
    refused("retina_regions:\n  - {name: a b, direction: [0, 0, 1], half_angle: 30}\n",
            "retina_regions[0].name");
    refused("retina_regions:\n  - {name: a, direction: [0, 0, 1], half_angle: 30}\n"
            "  - {name: a, direction: [0, 1, 0], half_angle: 30}\n",
            "named twice");
    refused("retina_regions:\n  - {name: a, direction: [0, 0, 1], half_angle: 0}\n",
            "retina_regions[0].half_angle");
    refused("retina_regions:\n  - {name: a, direction: [0, 0, 1]}\n",
            "retina_regions[0].half_angle");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_coverage),
        cmocka_unit_test(test_bad_sections),
        cmocka_unit_test(test_interface_height),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
