/* The pair cache's partner rows (src/pairs/pair_cache.h): water in a tank of 4 wall layers
 * (2D and 3D), the cache filled with full rows and again with the walls' rows kept to their
 * mobile neighbours (as IISPH fills it). The fluid's rows are the same entries, values and
 * order, to the bit; each wall's row is exactly the subsequence of its full row whose
 * neighbours are fluid, in the same order, with the same bits: so a pass that reads a wall's
 * fluid neighbours alone sums the same terms in the same order. And the walls' rows shrink:
 * most of a thick wall's pairs are with walls. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdio.h>
#include <string.h>

#include "ryushi/sim.h"

#define RY_TMPDIR_PREFIX "ryushi_pair_cache_"
#include "tmpdir.h"
#include "pairs/pair_cache.h"
#include "ryushi/run.h"

static void check(int dim) {
    char text[1024];
    snprintf(text, sizeof text,
             "dimension: %d\nspacing: 0.01\nkernel: {type: wendland_c2, h_over_dx: 1.4}\n"
             "materials: [{name: water, density: 1000}]\n"
             "bodies:\n"
             "  - {type: box, lo: [0, 0%s], hi: [0.1, 0.05%s]}\n"
             "  - {type: tank, lo: [0, 0%s], hi: [0.2, 0.1%s], layers: 4, open_top: true}\n"
             "scheme: {name: static}\ntime: {end: 0.1}\noutput: {vtk: false}\n",
             dim, dim == 3 ? ", 0" : "", dim == 3 ? ", 0.04" : "", dim == 3 ? ", 0" : "",
             dim == 3 ? ", 0.04" : "");
    ry_sim sim;
    memset(&sim, 0, sizeof sim);
    ry_case *c = NULL;
    ry_error err = {0};
    assert_int_equal(ry_case_load_string(&c, "pairs.yaml", text, &err), RY_OK);
    assert_int_equal(ry_sim_setup(&sim, c, tmpdir, &err), RY_OK);
    assert_int_equal(ry_sim_neighbors(&sim, sim.kernel.radius, &err), RY_OK);
    static const int need[RY_KIND_COUNT] = {[RY_KIND_FLUID] = 1, [RY_KIND_WALL] = 1};
    static const int walls[RY_KIND_COUNT] = {[RY_KIND_WALL] = 1};
    static const int mobile[RY_KIND_COUNT] = {[RY_KIND_FLUID] = 1};
    ry_pair_cache full = {0}, part = {0};
    assert_int_equal(ry_pair_cache_fill(&full, &sim, need, &err), RY_OK);
    part.partner_rows = walls;
    part.partners = mobile;
    assert_int_equal(ry_pair_cache_fill(&part, &sim, need, &err), RY_OK);
    const ry_particles *ps = &sim.ps;
    const size_t *off = sim.nl.offset;
    size_t wall_full = 0, wall_part = 0, nwall = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] == RY_KIND_FLUID) {
            assert_int_equal(full.end[i], part.end[i]);
            const size_t k = full.end[i] - off[i];
            assert_memory_equal(full.j + off[i], part.j + off[i], k * sizeof *full.j);
            assert_memory_equal(full.w + off[i], part.w + off[i], k * sizeof(double));
            assert_memory_equal(full.g + 3 * off[i], part.g + 3 * off[i], 3 * k * sizeof(double));
            continue;
        }
        ++nwall;
        size_t e = off[i];
        for (size_t q = off[i]; q < full.end[i]; ++q) {
            if (ps->kind[full.j[q]] != RY_KIND_FLUID) continue;
            assert_true(e < part.end[i]);
            assert_int_equal(part.j[e], full.j[q]);
            assert_memory_equal(part.w + e, full.w + q, sizeof(double));
            assert_memory_equal(part.g + 3 * e, full.g + 3 * q, 3 * sizeof(double));
            ++e;
        }
        assert_int_equal(e, part.end[i]);
        wall_full += full.end[i] - off[i];
        wall_part += part.end[i] - off[i];
    }
    print_message("%dD: %zu walls, %zu pairs in their full rows, %zu with fluid\n", dim, nwall,
                  wall_full, wall_part);
    assert_true(nwall > 0 && 4 * wall_part < wall_full);
    ry_pair_cache_free(&full);
    ry_pair_cache_free(&part);
    ry_sim_free(&sim);
    ry_case_free(c);
}

static void test_partner_rows_2d(void **state) {
    (void)state;
    check(2);
}

static void test_partner_rows_3d(void **state) {
    (void)state;
    check(3);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_partner_rows_2d),
                                       cmocka_unit_test(test_partner_rows_3d)};
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
