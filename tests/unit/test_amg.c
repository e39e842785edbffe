/* Unit tests of the BoomerAMG-preconditioned conjugate gradients (src/linalg/amg.h) on the
 * Poisson matrices of a grid (5-point in 2D, 7-point in 3D, Dirichlet outside), with a
 * manufactured solution x* and b = A x*:
 * - the solution meets the relative residual asked (1e-10), recomputed here, and lies within
 *   1e-7 (relative, max norm) of x*, as the Jacobi-preconditioned CG's does;
 * - the iterations grow at most 1.3 times when the grid's spacing halves (2D: 64^2 -> 128^2,
 *   3D: 16^3 -> 32^3), where the Jacobi preconditioner's grow about twice (at least 1.7 times
 *   asserted, so that the test tells the two apart);
 * - three right-hand sides with one hierarchy, a zero right-hand side (x = 0);
 * - the system over slots (identity rows interleaved) gives the unknowns' solution of the
 *   system without them, within the tolerance; a hierarchy serves later solves while the slots'
 *   ids are the same and up to `reuse` solves, and is rebuilt when an id changes; with the
 *   unknowns in a third of the slots, the rows are the unknowns' and only their ids count;
 * - too few iterations: RY_ERR_UNSTABLE naming the residual. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "linalg/amg.h"

/* The Poisson matrix on a k^dim grid, row i = x + k (y + k z). */
static void poisson(ry_csr *a, int dim, size_t k) {
    ry_error err = {0};
    const size_t n = dim == 2 ? k * k : k * k * k;
    assert_int_equal(ry_csr_reserve(a, n, 0, &err), RY_OK);
    const size_t stride[3] = {1, k, k * k};
    for (size_t i = 0; i < n; ++i) {
        size_t len = 1;
        for (int d = 0; d < dim; ++d) {
            const size_t c = i / stride[d] % k;
            len += (c > 0) + (c + 1 < k);
        }
        a->row[i + 1] = len;
    }
    assert_int_equal(ry_csr_rows_from_lengths(a, &err), RY_OK);
    for (size_t i = 0; i < n; ++i) {
        ry_csr_row r = ry_csr_row_begin(a, i, 0.0);
        for (int d = 0; d < dim; ++d) {
            const size_t c = i / stride[d] % k;
            /* a missing neighbour is a known zero (Dirichlet): still on the diagonal */
            ry_csr_row_pair(&r, 1.0, c > 0 ? (int64_t)(i - stride[d]) : -1);
            ry_csr_row_pair(&r, 1.0, c + 1 < k ? (int64_t)(i + stride[d]) : -1);
        }
        ry_csr_row_end(&r);
    }
}

/* x* smooth with a rough part, b = A x*. */
static void manufactured(const ry_csr *a, double *xs, double *b) {
    for (size_t i = 0; i < a->n; ++i)
        xs[i] = sin(0.01 * (double)i) + 0.1 * cos(7.3 * (double)i) + 1.0;
    ry_csr_mul(a, xs, b);
}

static double rel_residual(const ry_csr *a, const double *x, const double *b) {
    double *ax = malloc(a->n * sizeof *ax), rr = 0, bb = 0;
    assert_non_null(ax);
    ry_csr_mul(a, x, ax);
    for (size_t i = 0; i < a->n; ++i) {
        rr += (b[i] - ax[i]) * (b[i] - ax[i]);
        bb += b[i] * b[i];
    }
    free(ax);
    return sqrt(rr / bb);
}

static double max_rel_error(size_t n, const double *x, const double *xs) {
    double e = 0, m = 0;
    for (size_t i = 0; i < n; ++i) {
        e = fmax(e, fabs(x[i] - xs[i]));
        m = fmax(m, fabs(xs[i]));
    }
    return e / m;
}

/* Solves the grid's system by both preconditioners; the iterations of each. */
static void solve_grid(int dim, size_t k, int *it_amg, int *it_jac) {
    ry_csr a = {0};
    poisson(&a, dim, k);
    const size_t n = a.n;
    double *xs = malloc(n * sizeof *xs), *b = malloc(n * sizeof *b), *x = calloc(n, sizeof *x);
    assert_true(xs && b && x);
    manufactured(&a, xs, b);
    ry_amg s = {.reuse = 1};
    ry_error err = {0};
    double res;
    const double *bb[1] = {b};
    double *xx[1] = {x};
    assert_int_equal(ry_amg_pcg(&s, &a, NULL, 1, bb, xx, 1e-10, 1000, it_amg, &res, &err), RY_OK);
    assert_true(rel_residual(&a, x, b) <= 1e-10 * 1.01);
    assert_true(max_rel_error(n, x, xs) <= 1e-7);
    memset(x, 0, n * sizeof *x);
    assert_int_equal(ry_csr_pcg(&a, b, x, 1e-10, 100000, it_jac, &res, NULL, &err), RY_OK);
    assert_true(max_rel_error(n, x, xs) <= 1e-7);
    ry_amg_free(&s);
    ry_csr_free(&a);
    free(xs);
    free(b);
    free(x);
}

static void test_iterations_with_resolution(void **state) {
    (void)state;
    int a2[2], j2[2], a3[2], j3[2];
    solve_grid(2, 64, &a2[0], &j2[0]);
    solve_grid(2, 128, &a2[1], &j2[1]);
    solve_grid(3, 16, &a3[0], &j3[0]);
    solve_grid(3, 32, &a3[1], &j3[1]);
    print_message("2D 64^2, 128^2: BoomerAMG %d, %d; Jacobi %d, %d iterations\n", a2[0], a2[1],
                  j2[0], j2[1]);
    print_message("3D 16^3, 32^3: BoomerAMG %d, %d; Jacobi %d, %d iterations\n", a3[0], a3[1],
                  j3[0], j3[1]);
    assert_true(a2[1] <= 1.3 * a2[0] && a3[1] <= 1.3 * a3[0]);
    assert_true(j2[1] >= 1.7 * j2[0] && j3[1] >= 1.7 * j3[0]);
    assert_true(a2[1] * 5 < j2[1] && a3[1] * 3 < j3[1]);
}

static void test_several_and_zero(void **state) {
    (void)state;
    ry_csr a = {0};
    poisson(&a, 2, 40);
    const size_t n = a.n;
    double *xs = malloc(n * sizeof *xs), *b0 = malloc(n * sizeof *b0);
    double *b2 = malloc(n * sizeof *b2), *zero = calloc(n, sizeof *zero);
    double *x[3] = {calloc(n, sizeof(double)), malloc(n * sizeof(double)),
                    calloc(n, sizeof(double))};
    assert_true(xs && b0 && b2 && zero && x[0] && x[1] && x[2]);
    manufactured(&a, xs, b0);
    for (size_t i = 0; i < n; ++i) {
        b2[i] = -2.0 * b0[i];
        x[1][i] = 5.0; /* a zero right-hand side from a non-zero start: x = 0 */
    }
    const double *bb[3] = {b0, zero, b2};
    ry_amg s = {.reuse = 1};
    ry_error err = {0};
    int it[3];
    double res[3];
    assert_int_equal(ry_amg_pcg(&s, &a, NULL, 3, bb, x, 1e-10, 1000, it, res, &err), RY_OK);
    assert_int_equal(s.setups, 1);
    for (size_t i = 0; i < n; ++i) xs[i] *= -2.0;
    assert_true(max_rel_error(n, x[2], xs) <= 1e-7);
    assert_true(it[1] == 0 && res[1] == 0);
    for (size_t i = 0; i < n; ++i) assert_true(x[1][i] == 0);
    /* too few iterations */
    memset(x[0], 0, n * sizeof *x[0]);
    assert_int_equal(ry_amg_pcg(&s, &a, NULL, 1, bb, x, 1e-10, 1, it, res, &err), RY_ERR_UNSTABLE);
    assert_non_null(strstr(err.msg, "did not converge"));
    assert_int_equal(ry_amg_pcg(&s, &a, NULL, RY_CSR_MAX_RHS + 1, bb, x, 1e-10, 10, it, res, &err),
                     RY_ERR_INTERNAL);
    ry_amg_free(&s);
    ry_csr_free(&a);
    free(xs);
    free(b0);
    free(b2);
    free(zero);
    for (int k = 0; k < 3; ++k) free(x[k]);
}

static void test_slots_and_reuse(void **state) {
    (void)state;
    ry_csr a = {0};
    poisson(&a, 2, 48);
    const size_t n = a.n, ns = n + n / 3; /* every fourth slot holds no unknown */
    double *xs = malloc(n * sizeof *xs), *b = malloc(n * sizeof *b), *x = calloc(n, sizeof *x);
    int32_t *slot_of = malloc(n * sizeof *slot_of);
    int64_t *id = malloc(ns * sizeof *id);
    assert_true(xs && b && x && slot_of && id);
    manufactured(&a, xs, b);
    for (size_t s = 0, k = 0; s < ns; ++s) {
        id[s] = (int64_t)(1000 + s);
        if (s % 4 != 3 && k < n) slot_of[k++] = (int32_t)s;
    }
    const ry_amg_slots sl = {ns, slot_of, id};
    ry_amg s = {.reuse = 3};
    ry_error err = {0};
    int it, it1;
    double res;
    const double *bb[1] = {b};
    double *xx[1] = {x};
    assert_int_equal(ry_amg_pcg(&s, &a, &sl, 1, bb, xx, 1e-10, 1000, &it1, &res, &err), RY_OK);
    assert_true(rel_residual(&a, x, b) <= 1e-10 * 1.01);
    assert_true(max_rel_error(n, x, xs) <= 1e-7);
    /* the same slots: the hierarchy serves (and the solution holds from any start) */
    for (int rep = 0; rep < 2; ++rep) {
        memset(x, 0, n * sizeof *x);
        assert_int_equal(ry_amg_pcg(&s, &a, &sl, 1, bb, xx, 1e-10, 1000, &it, &res, &err), RY_OK);
        assert_int_equal(s.setups, 1);
        assert_int_equal(it, it1);
        assert_true(max_rel_error(n, x, xs) <= 1e-7);
    }
    /* its reuse spent: a new one */
    assert_int_equal(ry_amg_pcg(&s, &a, &sl, 1, bb, xx, 1e-10, 1000, &it, &res, &err), RY_OK);
    assert_int_equal(s.setups, 2);
    /* a particle replaced in a slot: a new one */
    id[5] = 99;
    memset(x, 0, n * sizeof *x);
    assert_int_equal(ry_amg_pcg(&s, &a, &sl, 1, bb, xx, 1e-10, 1000, &it, &res, &err), RY_OK);
    assert_int_equal(s.setups, 3);
    assert_true(max_rel_error(n, x, xs) <= 1e-7);
    ry_amg_free(&s);
    /* unknowns in a third of the slots: their rows alone, keyed by their particles' ids */
    int64_t *id3 = malloc(3 * n * sizeof *id3);
    assert_non_null(id3);
    for (size_t k = 0; k < n; ++k) slot_of[k] = (int32_t)(3 * k + 1);
    for (size_t q = 0; q < 3 * n; ++q) id3[q] = (int64_t)q;
    const ry_amg_slots sl3 = {3 * n, slot_of, id3};
    ry_amg s3 = {.reuse = 5};
    for (int rep = 0; rep < 2; ++rep) {
        memset(x, 0, n * sizeof *x);
        assert_int_equal(ry_amg_pcg(&s3, &a, &sl3, 1, bb, xx, 1e-10, 1000, &it, &res, &err), RY_OK);
        assert_true(max_rel_error(n, x, xs) <= 1e-7);
    }
    assert_int_equal(s3.setups, 1);
    id3[3] = -5; /* a slot without an unknown: the rows are the same particles */
    assert_int_equal(ry_amg_pcg(&s3, &a, &sl3, 1, bb, xx, 1e-10, 1000, &it, &res, &err), RY_OK);
    assert_int_equal(s3.setups, 1);
    id3[4] = -6; /* the particle of unknown 1 replaced */
    assert_int_equal(ry_amg_pcg(&s3, &a, &sl3, 1, bb, xx, 1e-10, 1000, &it, &res, &err), RY_OK);
    assert_int_equal(s3.setups, 2);
    ry_amg_free(&s3);
    ry_csr_free(&a);
    free(xs);
    free(b);
    free(x);
    free(slot_of);
    free(id);
    free(id3);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_iterations_with_resolution),
                                       cmocka_unit_test(test_several_and_zero),
                                       cmocka_unit_test(test_slots_and_reuse)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
