/* Unit tests of ry_walls_trim (domain.wall_layers): wall particles beyond the given layers from
 * the space the fluid can reach are removed, counted exactly on lattice-aligned tanks.
 * - A closed 2D tank of 6 layers around a 10 x 8 box, water in its lower half: trimmed to 3,
 *   (10 + 6)(8 + 6) - 10 x 8 = 144 wall particles stay, every one within 3 spacings of the
 *   inside; the water is untouched, ids and order kept.
 * - The same in 3D (6 x 5 x 4 inside): (6 + 6)(5 + 6)(4 + 6) - 120 = 1200.
 * - An open-top 2D tank of 6 layers: the fluid reaches the outside over the rim, so every
 *   layer lies within 3 of the reachable space (3 from the inside, 3 from the outside) and
 *   none goes; trimmed to 2, the middle two go.
 * - A closed 2D tank with a port: a channel through its wall ending in an open-boundary zone;
 *   the flood enters the zone but does not leave it, so the outside is not reached and the outer
 *   layers go; without the zone the outside is reached through the port and they stay. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <cmocka.h>

#include "ryushi/geometry.h"

static const double dx = 0.1;

static size_t count_kind(const ry_particles *ps, int kind) {
    size_t k = 0;
    for (size_t i = 0; i < ps->n; ++i) k += ps->kind[i] == kind;
    return k;
}

/* Largest distance of a wall particle outside the box [lo, hi] (0 inside). */
static double farthest_wall(const ry_particles *ps, const double *lo, const double *hi) {
    double far = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_WALL) continue;
        double d2 = 0;
        for (int d = 0; d < ps->dim; ++d) {
            const double x = ps->f[RY_F_X + d][i];
            const double o = x < lo[d] ? lo[d] - x : x > hi[d] ? x - hi[d] : 0.0;
            d2 = fmax(d2, o); /* the largest per-axis distance: layers of a box */
        }
        far = fmax(far, d2);
    }
    return far;
}

static void closed_tank(int dim, const double *hi, size_t expect) {
    ry_particles ps;
    ry_error err = {0};
    assert_int_equal(ry_particles_init(&ps, dim, &err), RY_OK);
    const double lo[3] = {0, 0, 0};
    double whi[3] = {hi[0], hi[1], hi[2]};
    whi[dim - 1] *= 0.5; /* water in the lower half: the flood fills the rest */
    const ry_body_style water = {RY_KIND_FLUID, 0, {0, 0, 0}}, wall = {RY_KIND_WALL, 0, {0, 0, 0}};
    size_t added;
    assert_int_equal(ry_fill_box(&ps, lo, whi, dx, &water, &added, &err), RY_OK);
    const size_t nwater = ps.n;
    const int64_t last_water_id = ps.id[nwater - 1];
    assert_int_equal(ry_fill_tank(&ps, lo, hi, 6, 0, NULL, dx, &wall, &added, &err), RY_OK);
    size_t gone = 0;
    assert_int_equal(ry_walls_trim(&ps, dx, 3, NULL, 0, &gone, &err), RY_OK);
    assert_int_equal(count_kind(&ps, RY_KIND_WALL), expect);
    assert_int_equal(gone, added - expect);
    assert_int_equal(count_kind(&ps, RY_KIND_FLUID), nwater);
    assert_true(ps.id[nwater - 1] == last_water_id);
    assert_true(farthest_wall(&ps, lo, hi) <= 3 * dx * (1 + 1e-9));
    ry_particles_free(&ps);
}

static void test_closed_2d(void **state) {
    (void)state;
    const double hi[3] = {1.0, 0.8, 0};
    closed_tank(2, hi, 16 * 14 - 80);
}

static void test_closed_3d(void **state) {
    (void)state;
    const double hi[3] = {0.6, 0.5, 0.4};
    closed_tank(3, hi, 12 * 11 * 10 - 120);
}

static void test_open_top(void **state) {
    (void)state;
    ry_particles ps;
    ry_error err = {0};
    assert_int_equal(ry_particles_init(&ps, 2, &err), RY_OK);
    const double lo[3] = {0, 0, 0}, hi[3] = {1.0, 0.8, 0}, whi[3] = {1.0, 0.4, 0};
    const ry_body_style water = {RY_KIND_FLUID, 0, {0, 0, 0}}, wall = {RY_KIND_WALL, 0, {0, 0, 0}};
    size_t added, gone = 0;
    assert_int_equal(ry_fill_box(&ps, lo, whi, dx, &water, &added, &err), RY_OK);
    assert_int_equal(ry_fill_tank(&ps, lo, hi, 6, 1, NULL, dx, &wall, &added, &err), RY_OK);
    assert_int_equal(ry_walls_trim(&ps, dx, 3, NULL, 0, &gone, &err), RY_OK);
    assert_int_equal(gone, 0);
    /* two layers from each side: the middle two of the six go */
    assert_int_equal(ry_walls_trim(&ps, dx, 2, NULL, 0, &gone, &err), RY_OK);
    assert_true(gone > 0 && count_kind(&ps, RY_KIND_WALL) == added - gone);
    ry_particles_free(&ps);
}

/* A closed tank of 6 layers with a channel 2 spacings wide through its right wall at mid
 * height, lined by walls outside the tank; the channel's outer part an open-boundary zone. */
static size_t port_tank(int with_zone, size_t *walls_before) {
    ry_particles ps;
    ry_error err = {0};
    assert_int_equal(ry_particles_init(&ps, 2, &err), RY_OK);
    const double lo[3] = {0, 0, 0}, hi[3] = {1.0, 0.8, 0}, whi[3] = {1.0, 0.4, 0};
    const ry_body_style water = {RY_KIND_FLUID, 0, {0, 0, 0}}, wall = {RY_KIND_WALL, 0, {0, 0, 0}};
    size_t added;
    assert_int_equal(ry_fill_box(&ps, lo, whi, dx, &water, &added, &err), RY_OK);
    const size_t nwater = ps.n;
    assert_int_equal(ry_fill_tank(&ps, lo, hi, 6, 0, NULL, dx, &wall, &added, &err), RY_OK);
    /* the channel: wall particles at y in (0.3, 0.5) from x = 1.0 to 1.6 removed, and the
     * channel lined by walls of 3 layers above and below out to x = 2.2 */
    uint8_t *cut = calloc(ps.n, 1);
    assert_non_null(cut);
    for (size_t i = nwater; i < ps.n; ++i) {
        const double x = ps.f[RY_F_X][i], y = ps.f[RY_F_Y][i];
        cut[i] = x > 1.0 && y > 0.3 && y < 0.5;
    }
    ry_particles_remove(&ps, cut);
    free(cut);
    const double l1[3] = {1.6, 0.5, 0}, h1[3] = {2.2, 0.8, 0}, l2[3] = {1.6, 0.0, 0},
                 h2[3] = {2.2, 0.3, 0};
    assert_int_equal(ry_fill_box(&ps, l1, h1, dx, &wall, &added, &err), RY_OK);
    assert_int_equal(ry_fill_box(&ps, l2, h2, dx, &wall, &added, &err), RY_OK);
    *walls_before = count_kind(&ps, RY_KIND_WALL);
    const double zone[6] = {1.6, 0.3, 0, 2.2, 0.5, 0};
    size_t gone = 0;
    assert_int_equal(ry_walls_trim(&ps, dx, 3, zone, with_zone, &gone, &err), RY_OK);
    const size_t left = count_kind(&ps, RY_KIND_WALL);
    if (with_zone) { /* nothing left beyond three layers of the tank's inside or the channel */
        for (size_t i = 0; i < ps.n; ++i) {
            if (ps.kind[i] != RY_KIND_WALL) continue;
            const double x = ps.f[RY_F_X][i], y = ps.f[RY_F_Y][i];
            const int near_tank = x < 1.3 && x > -0.3 && y < 1.1 && y > -0.3;
            const int near_channel = x > 1.0 && y > 0.0 && y < 0.8;
            assert_true(near_tank || near_channel);
        }
    }
    ry_particles_free(&ps);
    return left;
}

static void test_port_zone(void **state) {
    (void)state;
    size_t before_z, before_o;
    const size_t with = port_tank(1, &before_z), without = port_tank(0, &before_o);
    print_message("port: %zu walls, %zu kept with the zone, %zu without\n", before_z, with,
                  without);
    assert_int_equal(before_z, before_o);
    assert_true(with < without && without == before_o); /* all six layers: 3 in, 3 out */
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_closed_2d), cmocka_unit_test(test_closed_3d),
        cmocka_unit_test(test_open_top), cmocka_unit_test(test_port_zone)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
