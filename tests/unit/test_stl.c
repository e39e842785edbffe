/* STL surfaces: binary and ASCII round trips, format detection, malformed files, closedness,
 * and filling closed surfaces with particles (volume of a cube and a sphere, wall shells). */
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

#include "ryushi/geometry.h"
#include "ryushi/stl.h"

/* The unit cube [0, 1]^3, outward-facing, two triangles per face. */
static const double cube_quads[6][4][3] = {
    {{0, 0, 0}, {0, 0, 1}, {0, 1, 1}, {0, 1, 0}}, {{1, 0, 0}, {1, 1, 0}, {1, 1, 1}, {1, 0, 1}},
    {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}}, {{0, 1, 0}, {0, 1, 1}, {1, 1, 1}, {1, 1, 0}},
    {{0, 0, 0}, {0, 1, 0}, {1, 1, 0}, {1, 0, 0}}, {{0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}},
};

static void cube_triangles(double *v) {
    static const int split[2][3] = {{0, 1, 2}, {0, 2, 3}};
    for (int f = 0; f < 6; ++f)
        for (int h = 0; h < 2; ++h)
            for (int k = 0; k < 3; ++k)
                memcpy(v + 9 * (2 * f + h) + 3 * k, cube_quads[f][split[h][k]], 3 * sizeof *v);
}

static const char *source_dir(void) {
    const char *s = getenv("RY_SOURCE_DIR");
    return s && *s ? s : RY_SOURCE_DIR;
}

typedef struct tmp {
    char dir[64];
    char path[128];
} tmp;

static const char *tmp_file(tmp *t, const char *name) {
    if (!t->dir[0]) {
        snprintf(t->dir, sizeof t->dir, "/tmp/ryushi_stl_XXXXXX");
        assert_non_null(mkdtemp(t->dir));
    }
    snprintf(t->path, sizeof t->path, "%s/%s", t->dir, name);
    return t->path;
}

static void tmp_done(tmp *t, const char *const *names) {
    char p[160];
    for (int i = 0; names[i]; ++i) {
        snprintf(p, sizeof p, "%s/%s", t->dir, names[i]);
        unlink(p);
    }
    rmdir(t->dir);
}

static void test_round_trip(void **state) {
    (void)state;
    ry_error err;
    ry_stl m, a, b;
    double v[12 * 9];
    cube_triangles(v);
    for (int i = 0; i < 12 * 9; ++i) v[i] = 0.1 * v[i] + 0.0123456789; /* not exact in float */
    assert_int_equal(ry_stl_from_triangles(&m, "cube", v, 12, &err), RY_OK);
    tmp t = {{0}, {0}};
    assert_int_equal(ry_stl_write(&m, tmp_file(&t, "b.stl"), 1, &err), RY_OK);
    assert_int_equal(ry_stl_read(&b, t.path, &err), RY_OK);
    assert_int_equal(ry_stl_write(&m, tmp_file(&t, "a.stl"), 0, &err), RY_OK);
    assert_int_equal(ry_stl_read(&a, t.path, &err), RY_OK);
    assert_int_equal(b.binary, 1);
    assert_int_equal(a.binary, 0);
    assert_int_equal(a.ntri, 12);
    assert_int_equal(b.ntri, 12);
    for (int i = 0; i < 12 * 9; ++i) {
        assert_true(a.v[i] == v[i]);                /* ASCII keeps every digit */
        assert_true(b.v[i] == (double)(float)v[i]); /* binary holds floats */
    }
    assert_int_equal(a.line[0], 2); /* 'facet' lines */
    assert_int_equal(a.line[1], 9);
    assert_true(fabs(ry_stl_volume(&a) - 1e-3) < 1e-15);
    assert_int_equal(ry_stl_check(&a, 0, &err), RY_OK);
    assert_int_equal(ry_stl_check(&b, ry_stl_default_tolerance(&b), &err), RY_OK);
    ry_stl_free(&m);
    ry_stl_free(&a);
    ry_stl_free(&b);
    static const char *const names[] = {"a.stl", "b.stl", NULL};
    tmp_done(&t, names);
}

/* The example cube is binary although its header starts with "solid". */
static void read_example(const char *name, ry_stl *m) {
    char path[512];
    ry_error err;
    snprintf(path, sizeof path, "%s/cases/geometry/%s", source_dir(), name);
    assert_int_equal(ry_stl_read(m, path, &err), RY_OK);
}

static void test_detect_binary_solid_header(void **state) {
    (void)state;
    ry_error err;
    ry_stl m;
    read_example("cube.stl", &m);
    assert_int_equal(m.binary, 1);
    assert_int_equal(m.ntri, 12);
    assert_true(fabs(ry_stl_volume(&m) - 1.0) < 1e-12);
    assert_int_equal(ry_stl_check(&m, 0, &err), RY_OK);
    ry_stl_free(&m);
}

static void parse_fails(const void *data, size_t n, const char *msg) {
    ry_error err;
    ry_stl m;
    ry_error_clear(&err);
    assert_int_equal(ry_stl_parse(&m, "m.stl", data, n, &err), RY_ERR_INPUT);
    assert_string_equal(err.msg, msg);
    assert_null(m.v);
}

#define FACET_HEAD "solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\n"

static void test_malformed_ascii(void **state) {
    (void)state;
    static const struct {
        const char *text, *msg;
    } cases[] = {
        {FACET_HEAD "endloop\n", "m.stl:6: expected 'vertex', got 'endloop'"},
        {FACET_HEAD "vertex 0 1 nan\nendloop\nendfacet\nendsolid\n",
         "m.stl:6: a number (vertex z) 'nan' is not a finite number"},
        {FACET_HEAD "vertex 0 1 1e999\nendloop\nendfacet\nendsolid\n",
         "m.stl:6: a number (vertex z) '1e999' is not a finite number"},
        {FACET_HEAD "vertex 1.0x 1 0\nendloop\nendfacet\nendsolid\n",
         "m.stl:6: expected a number (vertex x), got '1.0x'"},
        {FACET_HEAD "vertex 0 1 0\nvertex 1 1 0\nendloop\n",
         "m.stl:7: expected 'endloop' (a facet has exactly 3 vertices), got 'vertex'"},
        {FACET_HEAD "vertex 0 1 0\nendloop\nendfacet\n",
         "m.stl:9: expected 'facet' or 'endsolid', got the end of the file"},
        {"solid x\nfacet norml 0 0 1\n", "m.stl:2: expected 'normal', got 'norml'"},
        {"solid x\nendsolid x\n", "m.stl: ASCII STL with no facet"},
        {"solid x\nendsolid x\nrubbish\n", "m.stl:3: expected 'solid' or the end of the file, "
                                           "got 'rubbish'"},
        {"solid", "m.stl:1: expected 'facet' or 'endsolid', got the end of the file"},
        {"hello", "m.stl: not an STL file: 5 bytes, too short for binary (84 bytes at least) and "
                  "no ASCII 'solid' at the start"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; ++i)
        parse_fails(cases[i].text, strlen(cases[i].text), cases[i].msg);
}

static void put32(unsigned char *p, uint32_t u) {
    for (int k = 0; k < 4; ++k) p[k] = (unsigned char)(u >> (8 * k));
}

static void test_malformed_binary(void **state) {
    (void)state;
    unsigned char buf[84 + 2 * 50];
    memset(buf, 0, sizeof buf);
    put32(buf + 80, 0);
    parse_fails(buf, 84, "m.stl: binary STL with no triangle (count 0 at byte 80)");
    put32(buf + 80, 3); /* three announced, two present */
    parse_fails(buf, sizeof buf,
                "m.stl: binary STL: the header (byte 80) gives 3 triangles, which need 84 + 50 x "
                "3 = 234 bytes, but the file has 184 bytes (truncated, or not an STL file)");
    put32(buf + 80, 2);
    float inf = INFINITY;
    memcpy(buf + 84 + 50 + 12 + 4 * 4, &inf, 4); /* triangle 1, vertex 2, y */
    parse_fails(buf, sizeof buf,
                "m.stl: triangle 1 (byte 162): vertex 2 coordinate y is not a finite number");
}

static ry_stl cube_mesh(const char *name, double *v) {
    ry_error err;
    ry_stl m;
    assert_int_equal(ry_stl_from_triangles(&m, name, v, 12, &err), RY_OK);
    return m;
}

static void check_fails(ry_stl *m, const char *msg) {
    ry_error err;
    ry_error_clear(&err);
    assert_int_equal(ry_stl_check(m, ry_stl_default_tolerance(m), &err), RY_ERR_INPUT);
    assert_string_equal(err.msg, msg);
    ry_stl_free(m);
}

static void test_not_closed(void **state) {
    (void)state;
    double v[12 * 9];
    cube_triangles(v);
    ry_error err;
    ry_stl m;
    /* Without the last triangle: the first open edge in file order is in triangle 0. */
    assert_int_equal(ry_stl_from_triangles(&m, "open.stl", v, 11, &err), RY_OK);
    check_fails(&m, "open.stl: triangle 0: the surface is not closed: the edge from (0, 0, 1) to "
                    "(0, 1, 1) belongs to no other triangle");
    /* The same from an ASCII file names the line. */
    assert_int_equal(ry_stl_from_triangles(&m, "open.stl", v, 11, &err), RY_OK);
    tmp t = {{0}, {0}};
    assert_int_equal(ry_stl_write(&m, tmp_file(&t, "open.stl"), 0, &err), RY_OK);
    ry_stl_free(&m);
    assert_int_equal(ry_stl_read(&m, t.path, &err), RY_OK);
    char msg[512];
    snprintf(msg, sizeof msg,
             "%s:2: the surface is not closed: the edge from (0, 0, 1) to (0, 1, 1) belongs to "
             "no other triangle",
             t.path);
    check_fails(&m, msg);
    static const char *const names[] = {"open.stl", NULL};
    tmp_done(&t, names);
    /* A triangle turned over. */
    double w[12 * 9];
    memcpy(w, v, sizeof w);
    for (int d = 0; d < 3; ++d) {
        double s = w[9 * 5 + 3 + d];
        w[9 * 5 + 3 + d] = w[9 * 5 + 6 + d];
        w[9 * 5 + 6 + d] = s;
    }
    m = cube_mesh("flip.stl", w);
    check_fails(&m, "flip.stl: triangle 0: inconsistent orientation: this triangle and the one at "
                    "flip.stl: triangle 5 run along their shared edge from (0, 0, 0) to (0, 0, 1) "
                    "in the same direction");
    /* A triangle with two equal vertices. */
    memcpy(w, v, sizeof w);
    memcpy(w + 9 * 7 + 3, w + 9 * 7, 3 * sizeof *w);
    m = cube_mesh("flat.stl", w);
    check_fails(&m, "flat.stl: triangle 7: degenerate triangle (zero area) with vertices (0, 1, "
                    "0), (0, 1, 0), (1, 1, 0)");
    /* Vertices that differ by less than the tolerance are merged. */
    memcpy(w, v, sizeof w);
    w[0] += 1e-9;
    m = cube_mesh("near.stl", w);
    assert_int_equal(ry_stl_check(&m, ry_stl_default_tolerance(&m), &err), RY_OK);
    assert_int_equal(ry_stl_check(&m, 0, &err), RY_ERR_INPUT);
    ry_stl_free(&m);
}

static size_t fill_count(ry_stl *m, double dx, int layers, ry_particles *ps) {
    ry_error err;
    ry_body_style st = {RY_KIND_FLUID, 0, {0, 0, 0}};
    assert_int_equal(ry_particles_init(ps, 3, &err), RY_OK);
    size_t added = 0;
    assert_int_equal(ry_stl_check(m, ry_stl_default_tolerance(m), &err), RY_OK);
    assert_int_equal(ry_fill_stl(ps, m, dx, layers, &st, &added, &err), RY_OK);
    assert_int_equal(added, ps->n);
    return added;
}

static void test_fill_cube(void **state) {
    (void)state;
    double v[12 * 9];
    cube_triangles(v);
    ry_particles ps;
    ry_stl m = cube_mesh("cube", v);
    /* Lattice lines run exactly through the face diagonals: 10^3 points, none twice. */
    assert_int_equal(fill_count(&m, 0.1, 0, &ps), 1000);
    ry_particles_free(&ps);
    assert_int_equal(fill_count(&m, 0.1, 2, &ps), 1000 - 6 * 6 * 6);
    ry_particles_free(&ps);
    double shift[3] = {0.013, 0.027, 0.041};
    ry_stl_transform(&m, 1.0, shift);
    assert_int_equal(fill_count(&m, 0.1, 0, &ps), 1000);
    ry_particles_free(&ps);
    ry_stl_free(&m);
}

/* The icosphere (radius 1, 320 triangles): the filled volume matches the enclosed volume within
 * 1.5 % at 40 spacings across, for either orientation, and no particle lies outside. */
static void test_fill_sphere(void **state) {
    (void)state;
    ry_error err;
    ry_stl m;
    read_example("icosphere.stl", &m);
    assert_int_equal(m.ntri, 320);
    double shift[3] = {0.31, -0.2, 0.05};
    ry_stl_transform(&m, 1.0, shift);
    double vol = ry_stl_volume(&m), dx = 0.05;
    assert_true(fabs(vol - 4.047) < 1e-3);
    ry_particles ps;
    size_t n = fill_count(&m, dx, 0, &ps);
    assert_true(fabs(n * dx * dx * dx - vol) < 0.015 * vol);
    for (size_t i = 0; i < ps.n; ++i) {
        double r2 = 0;
        for (int d = 0; d < 3; ++d) r2 += pow(ps.f[RY_F_X + d][i] - shift[d], 2);
        assert_true(r2 < 1.0);
    }
    ry_particles_free(&ps);
    /* Shell of 3 layers: about the volume between the sphere of the same volume and one 3
     * spacings smaller (within 3 %). */
    size_t shell = fill_count(&m, dx, 3, &ps);
    ry_particles_free(&ps);
    double r = cbrt(vol / (4.0 / 3.0 * 3.14159265358979323846));
    double expect = vol * (1 - pow(1 - 3 * dx / r, 3));
    printf("sphere: %zu particles, %.4f of the volume; shell %zu, %.4f of the expected\n", n,
           n * dx * dx * dx / vol, shell, shell * dx * dx * dx / expect);
    assert_true(fabs(shell * dx * dx * dx - expect) < 0.03 * expect);
    /* Turned inside out: the same points. */
    for (size_t t = 0; t < m.ntri; ++t)
        for (int d = 0; d < 3; ++d) {
            double s = m.v[9 * t + 3 + d];
            m.v[9 * t + 3 + d] = m.v[9 * t + 6 + d];
            m.v[9 * t + 6 + d] = s;
        }
    assert_true(ry_stl_volume(&m) < 0);
    assert_int_equal(fill_count(&m, dx, 0, &ps), n);
    ry_particles_free(&ps);
    /* 2D refused. */
    ry_body_style st = {RY_KIND_FLUID, 0, {0, 0, 0}};
    assert_int_equal(ry_particles_init(&ps, 2, &err), RY_OK);
    assert_int_equal(ry_fill_stl(&ps, &m, dx, 0, &st, NULL, &err), RY_ERR_INPUT);
    assert_string_equal(err.msg, "STL surface: only in 3D");
    ry_particles_free(&ps);
    ry_stl_free(&m);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_round_trip),      cmocka_unit_test(test_detect_binary_solid_header),
        cmocka_unit_test(test_malformed_ascii), cmocka_unit_test(test_malformed_binary),
        cmocka_unit_test(test_not_closed),      cmocka_unit_test(test_fill_cube),
        cmocka_unit_test(test_fill_sphere),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
