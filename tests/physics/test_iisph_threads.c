/* IISPH gives the same bits on any thread count: the Jacobi iteration stops on the mean density
 * error, summed in the particles' order rather than by the threads' shares, so the number of
 * iterations, and with it every field, is the same on 1 and 2 threads. Checked on Martin &
 * Moyce's column under air (both phases' errors, the light phase's own tolerance) to 0.03 s. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>
#include <omp.h>
#include <stdlib.h>

#define RY_TMPDIR_PREFIX "ryushi_iisph_threads_"
#include "run_case.h"

static void run_on(int threads, const char *sub, ry_sim *sim) {
    const char *sets[] = {"time.end=0.03", "output.vtk=false"};
    ry_table s;
    const int t0 = omp_get_max_threads();
    omp_set_num_threads(threads);
    run_case("cases/dam_break_mm_iisph_air.yaml", sub, 2, sets, &s, sim, NULL);
    omp_set_num_threads(t0);
    ry_table_free(&s);
}

static void test_thread_count_independent(void **state) {
    (void)state;
    ry_sim a, b;
    run_on(1, "one", &a);
    run_on(2, "two", &b);
    assert_int_equal(a.ps.n, b.ps.n);
    assert_int_equal(a.step, b.step);
    assert_true(a.step > 10);
    const int fs[] = {RY_F_X, RY_F_Y, RY_F_VX, RY_F_VY, RY_F_P, RY_F_RHO};
    for (int k = 0; k < 6; ++k)
        assert_memory_equal(a.ps.f[fs[k]], b.ps.f[fs[k]], a.ps.n * sizeof(double));
    assert_memory_equal(a.ps.id, b.ps.id, a.ps.n * sizeof *a.ps.id);
    ry_sim_free(&a);
    ry_sim_free(&b);
}

int main(void) {
    const char *src = getenv("RY_SOURCE_DIR");
    snprintf(root, sizeof root, "%s", src ? src : ".");
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_thread_count_independent)};
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
