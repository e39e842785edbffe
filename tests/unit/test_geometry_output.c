/* Geometry primitives (lattice counts) and the VTK writer (read back). */
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

#include "ryushi/atomic_file.h"
#include "ryushi/geometry.h"
#include "ryushi/output.h"

static const double RY_PI = 3.14159265358979323846;

static void test_box_and_tank_counts(void **state) {
    (void)state;
    ry_particles ps;
    ry_error err;
    ry_body_style fluid = {RY_KIND_FLUID, 0, {0, 0, 0}}, wall = {RY_KIND_WALL, 0, {0, 0, 0}};
    assert_int_equal(ry_particles_init(&ps, 2, &err), RY_OK);
    size_t added;
    double lo[2] = {0, 0}, hi[2] = {0.25, 0.5}, thi[2] = {1.0, 0.55};
    assert_int_equal(ry_fill_box(&ps, lo, hi, 0.00625, &fluid, &added, &err), RY_OK);
    assert_int_equal(added, 40 * 80); /* the seed's 40x80 column */
    double xmin = 1, xmax = 0;
    for (size_t i = 0; i < ps.n; ++i) {
        xmin = fmin(xmin, ps.f[RY_F_X][i]);
        xmax = fmax(xmax, ps.f[RY_F_X][i]);
    }
    assert_true(fabs(xmin - 0.003125) < 1e-12 && fabs(xmax - 0.246875) < 1e-12);
    /* Open tank, 3 layers: floor 166 x 3 plus two sides 3 x 91. */
    assert_int_equal(ry_fill_tank(&ps, lo, thi, 3, 1, NULL, 0.00625, &wall, &added, &err), RY_OK);
    assert_int_equal(added, 166 * 3 + 2 * 3 * 91);
    /* Closed tank: the whole frame. */
    assert_int_equal(ry_fill_tank(&ps, lo, thi, 2, 0, NULL, 0.00625, &wall, &added, &err), RY_OK);
    assert_int_equal(added, 164 * 92 - 160 * 88);
    /* No wall particle inside the cavity. */
    for (size_t i = 0; i < ps.n; ++i) {
        if (ps.kind[i] != RY_KIND_WALL) continue;
        int inside = ps.f[RY_F_X][i] > 0 && ps.f[RY_F_X][i] < 1.0 && ps.f[RY_F_Y][i] > 0 &&
                     ps.f[RY_F_Y][i] < 0.55;
        assert_false(inside);
    }
    double bad_hi[2] = {-1, 1};
    assert_int_equal(ry_fill_box(&ps, lo, bad_hi, 0.01, &fluid, &added, &err), RY_ERR_INPUT);
    ry_particles_free(&ps);
}

static void test_sphere_cylinder_volume(void **state) {
    (void)state;
    ry_particles ps;
    ry_error err;
    ry_body_style st = {RY_KIND_FLUID, 0, {0, 0, 0}};
    size_t added;
    double c[3] = {0.1, 0.2, 0.3};
    assert_int_equal(ry_particles_init(&ps, 2, &err), RY_OK);
    assert_int_equal(ry_fill_sphere(&ps, c, 1.0, 0.02, &st, &added, &err), RY_OK);
    assert_true(fabs(added * 0.02 * 0.02 / RY_PI - 1.0) < 0.01); /* circle area */
    double base[3] = {0, 0, 0}, axis[3] = {0, 0, 2};
    assert_int_equal(ry_fill_cylinder(&ps, base, axis, 1, 0.5, 0, 0.05, &st, &added, &err),
                     RY_ERR_INPUT); /* 3D only */
    ry_particles_free(&ps);
    assert_int_equal(ry_particles_init(&ps, 3, &err), RY_OK);
    assert_int_equal(ry_fill_sphere(&ps, c, 1.0, 0.04, &st, &added, &err), RY_OK);
    assert_true(fabs(added * pow(0.04, 3) / (4.0 / 3.0 * RY_PI) - 1.0) < 0.01);
    assert_int_equal(ry_fill_cylinder(&ps, base, axis, 2.0, 0.5, 0.3, 0.02, &st, &added, &err),
                     RY_OK);
    double tube = RY_PI * (0.25 - 0.09) * 2.0;
    assert_true(fabs(added * pow(0.02, 3) / tube - 1.0) < 0.03);
    ry_particles_free(&ps);
}

/* Reads array `name` of the raw appended section back. */
static double *read_points(const char *path, size_t *count) {
    FILE *fp = fopen(path, "rb");
    assert_non_null(fp);
    fseek(fp, 0, SEEK_END);
    long size = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    char *buf = malloc((size_t)size + 1);
    assert_int_equal(fread(buf, 1, (size_t)size, fp), (size_t)size);
    buf[size] = 0;
    fclose(fp);
    char *pts = strstr(buf, "Name=\"Points\"");
    assert_non_null(pts);
    char *o = strstr(pts, "offset=\"");
    unsigned long long off = strtoull(o + 8, NULL, 10);
    char *data = strstr(buf, "<AppendedData encoding=\"raw\">\n_");
    assert_non_null(data);
    data += strlen("<AppendedData encoding=\"raw\">\n_");
    uint64_t bytes;
    memcpy(&bytes, data + off, 8);
    *count = bytes / 24;
    double *xyz = malloc(bytes);
    memcpy(xyz, data + off + 8, bytes);
    free(buf);
    return xyz;
}

static void test_vtk_roundtrip(void **state) {
    (void)state;
    ry_particles ps;
    ry_error err;
    ry_body_style st = {RY_KIND_FLUID, 0, {0, 0, 0}};
    assert_int_equal(ry_particles_init(&ps, 2, &err), RY_OK);
    double lo[2] = {0, 0}, hi[2] = {0.1, 0.05};
    assert_int_equal(ry_fill_box(&ps, lo, hi, 0.01, &st, NULL, &err), RY_OK);
    char dir[] = "/tmp/ryushi_vtk_XXXXXX";
    assert_non_null(mkdtemp(dir));
    char path[256], pvd[256];
    snprintf(path, sizeof path, "%s/a.vtp", dir);
    snprintf(pvd, sizeof pvd, "%s/a.pvd", dir);
    assert_int_equal(ry_vtk_write_particles(path, &ps, 0.5, &err), RY_OK);
    size_t n;
    double *xyz = read_points(path, &n);
    assert_int_equal(n, ps.n);
    for (size_t i = 0; i < n; ++i) {
        assert_true(xyz[3 * i] == ps.f[RY_F_X][i]);
        assert_true(xyz[3 * i + 1] == ps.f[RY_F_Y][i]);
        assert_true(xyz[3 * i + 2] == 0.0);
    }
    free(xyz);
    char *files[1] = {"a.vtp"};
    double times[1] = {0.5};
    assert_int_equal(ry_pvd_write(pvd, 1, files, times, &err), RY_OK);
    /* No temporary files are left behind. */
    char tmp[300];
    snprintf(tmp, sizeof tmp, "%s/a.vtp.tmp.%ld", dir, (long)getpid());
    assert_int_equal(access(tmp, F_OK), -1);
    /* A folder that does not exist: an i/o error, nothing written. */
    assert_int_equal(ry_vtk_write_particles("/nonexistent/dir/a.vtp", &ps, 0, &err), RY_ERR_IO);
    assert_non_null(strstr(err.msg, "/nonexistent/dir/a.vtp"));
    remove(path);
    remove(pvd);
    rmdir(dir);
    ry_particles_free(&ps);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_box_and_tank_counts),
        cmocka_unit_test(test_sphere_cylinder_volume),
        cmocka_unit_test(test_vtk_roundtrip),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
