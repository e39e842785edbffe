/* Particle set: fields, growth, removal, reordering and stable ids. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <stdlib.h>

#include "ryushi/particles.h"

static void fill(ry_particles *ps, size_t n) {
    size_t first;
    ry_error err;
    assert_int_equal(ry_particles_add(ps, n, &first, &err), RY_OK);
    for (size_t i = first; i < first + n; ++i) {
        ps->f[RY_F_X][i] = (double)ps->id[i];
        ps->f[RY_F_RHO][i] = 1000.0 + (double)ps->id[i];
        ps->kind[i] = (uint8_t)(ps->id[i] % 2);
    }
}

static void test_dimension_fields(void **state) {
    (void)state;
    ry_particles ps;
    ry_error err;
    assert_int_equal(ry_particles_init(&ps, 2, &err), RY_OK);
    fill(&ps, 10);
    assert_non_null(ps.f[RY_F_X]);
    assert_non_null(ps.f[RY_F_VY]);
    assert_null(ps.f[RY_F_Z]); /* no z in 2D */
    assert_null(ps.f[RY_F_AZ]);
    /* 16 core fields, 3 of them z components: 13 doubles + id 8 + kind 1 + material 1 */
    assert_int_equal(ry_particles_bytes_per_particle(&ps), 13 * 8 + 10);
    ry_particles_free(&ps);
    assert_int_equal(ry_particles_init(&ps, 3, &err), RY_OK);
    assert_int_equal(ry_particles_bytes_per_particle(&ps), 16 * 8 + 10);
    ry_particles_free(&ps);
    assert_int_equal(ry_particles_init(&ps, 4, &err), RY_ERR_INPUT);
}

static void test_growth_keeps_data(void **state) {
    (void)state;
    ry_particles ps;
    ry_error err;
    assert_int_equal(ry_particles_init(&ps, 3, &err), RY_OK);
    for (int k = 0; k < 50; ++k) fill(&ps, 777);
    assert_int_equal(ps.n, 50 * 777);
    for (size_t i = 0; i < ps.n; ++i) {
        assert_int_equal(ps.id[i], (int64_t)i);
        assert_true(ps.f[RY_F_X][i] == (double)i);
        assert_true(ps.f[RY_F_VZ][i] == 0.0);
    }
    ry_particles_free(&ps);
}

static void test_extra_field_follows(void **state) {
    (void)state;
    ry_particles ps;
    ry_error err;
    int fid, again;
    assert_int_equal(ry_particles_init(&ps, 2, &err), RY_OK);
    fill(&ps, 100);
    assert_int_equal(ry_particles_add_field(&ps, "stress_xx", "Pa", -1, RY_FIELD_STATE, &fid, &err),
                     RY_OK);
    assert_int_equal(ry_particles_add_field(&ps, "stress_xx", "Pa", -1, 0, &again, &err), RY_OK);
    assert_int_equal(fid, again);
    assert_int_equal(ry_particles_field(&ps, "stress_xx"), fid);
    assert_int_equal(ry_particles_field(&ps, "nope"), -1);
    for (size_t i = 0; i < ps.n; ++i) {
        assert_true(ps.f[fid][i] == 0.0);
        ps.f[fid][i] = 2.0 * (double)ps.id[i];
    }
    fill(&ps, 5000); /* growth after the field was added */
    uint32_t *order = malloc(ps.n * sizeof *order);
    for (size_t i = 0; i < ps.n; ++i) order[i] = (uint32_t)(ps.n - 1 - i); /* reverse */
    assert_int_equal(ry_particles_permute(&ps, order, &err), RY_OK);
    for (size_t i = 0; i < ps.n; ++i) {
        int64_t id = ps.id[i];
        assert_int_equal(id, (int64_t)(ps.n - 1 - i));
        assert_true(ps.f[RY_F_X][i] == (double)id);
        assert_true(ps.f[RY_F_RHO][i] == 1000.0 + (double)id);
        assert_int_equal(ps.kind[i], id % 2);
        if (id < 100) assert_true(ps.f[fid][i] == 2.0 * (double)id);
    }
    /* Permute twice more and grow: the swapped buffers keep full capacity. */
    assert_int_equal(ry_particles_permute(&ps, order, &err), RY_OK);
    fill(&ps, 3);
    assert_int_equal(ps.id[ps.n - 1], 5102);
    free(order);
    ry_particles_free(&ps);
}

static void test_remove_keeps_order(void **state) {
    (void)state;
    ry_particles ps;
    ry_error err;
    assert_int_equal(ry_particles_init(&ps, 2, &err), RY_OK);
    fill(&ps, 1000);
    uint8_t *rm = calloc(ps.n, 1);
    for (size_t i = 0; i < ps.n; ++i) rm[i] = (i % 3) == 0;
    ry_particles_remove(&ps, rm);
    assert_int_equal(ps.n, 666);
    int64_t prev = -1;
    for (size_t i = 0; i < ps.n; ++i) {
        assert_true(ps.id[i] % 3 != 0);
        assert_true(ps.id[i] > prev);
        assert_true(ps.f[RY_F_X][i] == (double)ps.id[i]);
        prev = ps.id[i];
    }
    /* New particles get fresh ids, never reused. */
    fill(&ps, 1);
    assert_int_equal(ps.id[ps.n - 1], 1000);
    free(rm);
    ry_particles_free(&ps);
}

static void test_kind_names(void **state) {
    (void)state;
    for (int k = 0; k < RY_KIND_COUNT; ++k)
        assert_int_equal(ry_kind_from_name(ry_kind_name((ry_kind)k)), k);
    assert_int_equal(ry_kind_from_name("gas"), -1);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_dimension_fields),    cmocka_unit_test(test_growth_keeps_data),
        cmocka_unit_test(test_extra_field_follows), cmocka_unit_test(test_remove_keeps_order),
        cmocka_unit_test(test_kind_names),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
