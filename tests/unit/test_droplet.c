/* The droplet measurements (case section `droplet`): length, width and aspect ratio of the body
 * of a material attached to a nozzle, and its detachment, on particle sets built by hand; and
 * the largest polymer stress (`max_polymer_stress`) of the visco-elastic embolic liquid; and the
 * 3D wide tank's variants, which build its particles with the same identifiers, so that a run of
 * it continues with them from its checkpoint. */
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

#define RY_TMPDIR_PREFIX "ryushi_droplet_"
#include "tmpdir.h"
#include "ryushi/probes.h"
#include "ryushi/run.h"

/* A column of embolic liquid in a nozzle (x 0..0.4 mm, y 1..2 mm) and a droplet hanging below
 * the tip (y = 1 mm): x -0.2..0.6 mm, y 0.4..1 mm, spacing 0.1 mm, in water. */
static ry_status setup(ry_sim *sim, ry_case **c, int with_section, ry_error *err) {
    char text[2048];
    snprintf(text, sizeof text,
             "dimension: 2\nspacing: 1.0e-4\n"
             "materials: [{name: water, density: 1000}, {name: embolic, density: 1182}]\n"
             "bodies:\n"
             "  - {type: box, lo: [0, 1.0e-3], hi: [4.0e-4, 2.0e-3], material: embolic}\n"
             "  - {type: box, lo: [-2.0e-4, 4.0e-4], hi: [6.0e-4, 1.0e-3], material: embolic}\n"
             "  - {type: box, lo: [-1.0e-3, -1.0e-3], hi: [1.5e-3, 4.0e-4], material: water}\n"
             "domain: {lo: [-3.0e-3, -3.0e-3], hi: [3.0e-3, 3.0e-3]}\n"
             "scheme: {name: static}\n"
             "time: {end: 0.1}\n"
             "output: {vtk: false}\n%s",
             with_section == 2 ? "droplet: {material: embolic, tip: 1.0e-3, axis: [2.0e-4]}\n"
             : with_section    ? "droplet: {material: embolic, tip: 1.0e-3}\n"
                               : "");
    memset(sim, 0, sizeof *sim);
    RY_TRY(ry_case_load_string(c, "droplet.yaml", text, err));
    return ry_sim_setup(sim, *c, tmpdir, err);
}

static const ry_probe *probe_named(const char *name) {
    for (const ry_probe *const *p = ry_probes(); *p; ++p)
        if (strcmp((*p)->name, name) == 0) return *p;
    fail_msg("no probe %s", name);
    return NULL;
}

static double eval(const ry_sim *sim, const char *name) {
    ry_error err = {0};
    double v = -1;
    assert_int_equal(probe_named(name)->eval(sim, &v, &err), RY_OK);
    return v;
}

static void test_attached_and_detached(void **state) {
    (void)state;
    ry_sim sim;
    ry_case *c = NULL;
    ry_error err = {0};
    assert_int_equal(setup(&sim, &c, 1, &err), RY_OK);
    /* lowest particle at y = 0.45 mm: length 1 - 0.4 = 0.6 mm; x from -0.15 to 0.55 mm: width
     * 0.7 + 0.1 = 0.8 mm. The water below does not count. */
    assert_float_equal(eval(&sim, "droplet_length"), 6.0e-4, 1e-12);
    assert_float_equal(eval(&sim, "droplet_width"), 8.0e-4, 1e-12);
    assert_float_equal(eval(&sim, "droplet_aspect"), 0.75, 1e-9);
    assert_true(eval(&sim, "droplet_detached") == 0);
    /* 8 x 6 particles below the tip, 1e-8 m^2 each */
    assert_float_equal(eval(&sim, "droplet_volume"), 48 * 1e-8, 1e-18);
    /* their centroid at x = 0.2 mm, the axis at the origin (no droplet.axis) */
    assert_float_equal(eval(&sim, "droplet_offset"), 2.0e-4, 1e-12);
    /* the nozzle's axis at x = 0.2 mm: the droplet hangs on it; moved by 0.3 mm it slides off */
    sim.droplet_axis[0] = 2.0e-4;
    assert_float_equal(eval(&sim, "droplet_offset"), 0.0, 1e-12);
    for (size_t i = 0; i < sim.ps.n; ++i)
        if (sim.ps.material[i] == 1 && sim.ps.f[RY_F_Y][i] < 1.0e-3) sim.ps.f[RY_F_X][i] -= 3e-4;
    assert_float_equal(eval(&sim, "droplet_offset"), 3.0e-4, 1e-12);
    for (size_t i = 0; i < sim.ps.n; ++i)
        if (sim.ps.material[i] == 1 && sim.ps.f[RY_F_Y][i] < 1.0e-3) sim.ps.f[RY_F_X][i] += 3e-4;
    sim.droplet_axis[0] = 0;
    /* A void in the bore: the liquid above the tip moved up by three spacings. The droplet's
     * top (0.95 mm) still touches the tip, so it hangs from it, with the same size. */
    for (size_t i = 0; i < sim.ps.n; ++i)
        if (sim.ps.material[i] == 1 && sim.ps.f[RY_F_Y][i] >= 1.0e-3) sim.ps.f[RY_F_Y][i] += 3e-4;
    assert_true(eval(&sim, "droplet_detached") == 0);
    assert_float_equal(eval(&sim, "droplet_length"), 6.0e-4, 1e-12);
    assert_float_equal(eval(&sim, "droplet_width"), 8.0e-4, 1e-12);
    for (size_t i = 0; i < sim.ps.n; ++i)
        if (sim.ps.material[i] == 1 && sim.ps.f[RY_F_Y][i] >= 1.0e-3) sim.ps.f[RY_F_Y][i] -= 3e-4;
    /* The droplet rose beside the nozzle, a row of two particles still hanging under the tip
     * (x 0.05 and 0.15 mm, y 0.95 mm): the attached body holds, its volume below the tip falls
     * to those two. */
    for (size_t i = 0; i < sim.ps.n; ++i) {
        double *x = &sim.ps.f[RY_F_X][i], *y = &sim.ps.f[RY_F_Y][i];
        if (sim.ps.material[i] != 1 || *y >= 1.0e-3) continue;
        if (*y > 0.9e-3 && *x > 0 && *x < 0.2e-3) continue;
        *y += 1.0e-3;
        *x += *x < 0.2e-3 ? -0.6e-3 : 0.6e-3;
    }
    assert_true(eval(&sim, "droplet_detached") == 0);
    assert_float_equal(eval(&sim, "droplet_volume"), 2 * 1e-8, 1e-18);
    assert_float_equal(eval(&sim, "droplet_length"), 1.0e-4, 1e-12);
    ry_sim_free(&sim);
    ry_case_free(c);
    assert_int_equal(setup(&sim, &c, 1, &err), RY_OK);
    /* The droplet moved down by three spacings: it is cut off from the nozzle. */
    for (size_t i = 0; i < sim.ps.n; ++i)
        if (sim.ps.material[i] == 1 && sim.ps.f[RY_F_Y][i] < 1.0e-3) sim.ps.f[RY_F_Y][i] -= 3e-4;
    assert_true(eval(&sim, "droplet_detached") == 1);
    assert_float_equal(eval(&sim, "droplet_length"), 0.0, 0);
    assert_float_equal(eval(&sim, "droplet_width"), 0.0, 0);
    ry_sim_free(&sim);
    ry_case_free(c);
}

/* droplet.axis from the case: the droplet of setup hangs on x = 0.2 mm. */
static void test_axis_from_the_case(void **state) {
    (void)state;
    ry_sim sim;
    ry_case *c = NULL;
    ry_error err = {0};
    assert_int_equal(setup(&sim, &c, 2, &err), RY_OK);
    assert_float_equal(sim.droplet_axis[0], 2.0e-4, 0);
    assert_float_equal(eval(&sim, "droplet_offset"), 0.0, 1e-12);
    ry_sim_free(&sim);
    ry_case_free(c);
}

static void test_needs_the_section(void **state) {
    (void)state;
    ry_sim sim;
    ry_case *c = NULL;
    ry_error err = {0};
    assert_int_equal(setup(&sim, &c, 0, &err), RY_OK);
    for (const ry_probe *const *p = ry_probes(); *p; ++p)
        if (strcmp((*p)->name, "droplet_length") == 0) {
            double v;
            assert_int_equal((*p)->eval(&sim, &v, &err), RY_ERR_INPUT);
            assert_non_null(strstr(err.msg, "'droplet'"));
        }
    ry_sim_free(&sim);
    ry_case_free(c);
}

/* max_polymer_stress: sqrt(tau : tau), the off-diagonal component counted twice, largest over
 * the fluid; refused without the stress fields. */
static void test_polymer_stress(void **state) {
    (void)state;
    ry_sim sim;
    ry_case *c = NULL;
    ry_error err = {0};
    assert_int_equal(setup(&sim, &c, 0, &err), RY_OK);
    double v = -1;
    assert_int_equal(probe_named("max_polymer_stress")->eval(&sim, &v, &err), RY_ERR_INPUT);
    assert_non_null(strstr(err.msg, "visco-elastic"));
    int f[3];
    const char *names[3] = {"tau_xx", "tau_yy", "tau_xy"};
    for (int k = 0; k < 3; ++k)
        assert_int_equal(ry_particles_add_field(&sim.ps, names[k], "Pa", -1, 0, &f[k], &err),
                         RY_OK);
    assert_float_equal(eval(&sim, "max_polymer_stress"), 0.0, 0.0);
    /* (3, 4, 6): sqrt(9 + 16 + 2 x 36) = sqrt(97) */
    sim.ps.f[f[0]][5] = 3;
    sim.ps.f[f[1]][5] = 4;
    sim.ps.f[f[2]][5] = -6;
    sim.ps.f[f[0]][7] = 9;
    assert_float_equal(eval(&sim, "max_polymer_stress"), sqrt(97.0), 1e-12);
    ry_sim_free(&sim);
    ry_case_free(c);
}

/* Sets up cases/NAME.yaml into sim (and its case into *c). */
static void setup_case(const char *name, ry_sim *sim, ry_case **c) {
    const char *src = getenv("RY_SOURCE_DIR");
    char path[4096];
    snprintf(path, sizeof path, "%s/cases/%s.yaml", src && *src ? src : RY_SOURCE_DIR, name);
    ry_error err = {0};
    memset(sim, 0, sizeof *sim);
    ry_status st = ry_case_load(c, path, &err);
    if (st == RY_OK) st = ry_sim_setup(sim, *c, tmpdir, &err);
    if (st != RY_OK) fail_msg("%s: %s", path, err.msg);
}

/* Whether the particle with this id belongs to a body whose name ends in "_tip". */
static int is_tip_body(const ry_sim *sim, ry_case *c, int64_t id) {
    const int b = ry_sim_body_of(sim, id);
    char key[64];
    snprintf(key, sizeof key, "bodies[%d].name", b);
    const char *name = NULL;
    ry_error err = {0};
    if (b < 0 || ry_case_string(c, key, "", &name, &err) != RY_OK) return 0;
    const size_t l = strlen(name);
    return l >= 4 && strcmp(name + l - 4, "_tip") == 0;
}

/* The tip-face variants of the wide tank split the catheter's bodies (their last layer a body of
 * its own, listed first) and change coefficients only: every particle keeps its identifier,
 * kind, material and position, so a checkpoint of one continues as the other. */
static void test_wide_tank_variants_keep_identifiers(void **state) {
    (void)state;
    const char *variants[] = {"mps_embolization_3d_wide_deep_coarse_dry_tip",
                              "mps_embolization_3d_wide_deep_coarse_dry_tip_adhesion"};
    ry_sim base, var;
    ry_case *cb = NULL, *cv = NULL;
    setup_case("mps_embolization_3d_wide_deep_coarse", &base, &cb);
    assert_true(base.ps.n > 30000);
    for (int v = 0; v < 2; ++v) {
        setup_case(variants[v], &var, &cv);
        assert_int_equal(var.ps.n, base.ps.n);
        /* positions to rounding: a box filled from another corner (6.6 mm for the tip's
         * 6.4 mm) rounds a few of them in their last bit; a restart takes them from the
         * checkpoint anyway */
        size_t differ = 0, face = 0, face_ok = 0;
        for (size_t i = 0; i < base.ps.n; ++i) {
            differ += var.ps.id[i] != base.ps.id[i] || var.ps.kind[i] != base.ps.kind[i] ||
                      var.ps.material[i] != base.ps.material[i] ||
                      fabs(var.ps.f[RY_F_X][i] - base.ps.f[RY_F_X][i]) > 1e-12 ||
                      fabs(var.ps.f[RY_F_Y][i] - base.ps.f[RY_F_Y][i]) > 1e-12 ||
                      fabs(var.ps.f[RY_F_Z][i] - base.ps.f[RY_F_Z][i]) > 1e-12;
            /* the tip's bodies hold the catheter's last layer (z 6.4-6.6 mm, |x|, |y| < 0.4 mm)
             * and nothing else */
            if (var.ps.kind[i] != RY_KIND_WALL) continue;
            const double x = var.ps.f[RY_F_X][i], y = var.ps.f[RY_F_Y][i], z = var.ps.f[RY_F_Z][i];
            const int in_face = fabs(x) < 4e-4 && fabs(y) < 4e-4 && z > 6.4e-3 && z < 6.6e-3;
            face += in_face;
            face_ok += in_face == is_tip_body(&var, cv, var.ps.id[i]);
        }
        if (differ) fail_msg("%s: %zu particles differ from the wide tank's", variants[v], differ);
        /* one layer of the square tube: a ring of 4 x 4 particles around the 2 x 2 bore */
        assert_int_equal(face, 12);
        size_t walls = 0;
        for (size_t i = 0; i < var.ps.n; ++i) walls += var.ps.kind[i] == RY_KIND_WALL;
        assert_int_equal(face_ok, walls);
        ry_sim_free(&var);
        ry_case_free(cv);
    }
    ry_sim_free(&base);
    ry_case_free(cb);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_attached_and_detached),
        cmocka_unit_test(test_axis_from_the_case),
        cmocka_unit_test(test_needs_the_section),
        cmocka_unit_test(test_polymer_stress),
        cmocka_unit_test(test_wide_tank_variants_keep_identifiers),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
