/* Unit tests of the graph-Laplacian assembly of src/linalg/sparse.h (ry_csr_rows_from_lengths,
 * ry_csr_row_begin / _pair / _end), the matrix of the implicit viscosity (MPS, IISPH) and of the
 * MPS pressure equation.
 *
 * A chain of four particles, 0 - 1 - 2 - 3, with 0 and 3 walls (known values) and 1, 2 the
 * unknowns 0, 1; pair coefficients c_01 = 2, c_12 = 3, c_23 = 5, diagonal terms d = (1, 4):
 *   A = [[1 + 2 + 3, -3], [-3, 4 + 3 + 5]] = [[6, -3], [-3, 12]]
 * by hand. With the walls' values u_0 = 1, u_3 = -2 moved to the right-hand side and
 * b = d u* + known, u* = (0.5, 0.25): b = (0.5 + 2, 1 - 10) = (2.5, -9); the solution by
 * Cramer's rule x = (2.5 * 12 - 27) / 63, (6 * -9 + 7.5) / 63 = (1/21, -31/42).
 * Tolerances: the entries are exact (sums of small integers); the conjugate-gradient solution
 * to a relative residual of 1e-14, compared within 1e-12. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>
#include <cmocka.h>

#include "linalg/sparse.h"

static void test_chain(void **state) {
    (void)state;
    /* each particle's neighbours (both sides), coefficients and unknowns */
    const int unk[4] = {-1, 0, 1, -1};
    const int nbr[4][2] = {{1, -1}, {0, 2}, {1, 3}, {2, -1}};
    const double c[4][2] = {{2, 0}, {2, 3}, {3, 5}, {5, 0}};
    const double d[2] = {1, 4}, ustar[2] = {0.5, 0.25}, uknown[4] = {1, 0, 0, -2};
    ry_csr A = {0};
    ry_error err;
    assert_int_equal(ry_csr_reserve(&A, 2, 0, &err), RY_OK);
    for (int i = 0; i < 4; ++i) {
        if (unk[i] < 0) continue;
        size_t len = 1;
        for (int q = 0; q < 2; ++q) len += nbr[i][q] >= 0 && unk[nbr[i][q]] >= 0;
        A.row[unk[i] + 1] = len;
    }
    assert_int_equal(ry_csr_rows_from_lengths(&A, &err), RY_OK);
    assert_int_equal(A.row[0], 0);
    assert_int_equal(A.row[1], 2);
    assert_int_equal(A.row[2], 4);
    double b[2];
    for (int i = 0; i < 4; ++i) {
        if (unk[i] < 0) continue;
        const size_t k = (size_t)unk[i];
        ry_csr_row row = ry_csr_row_begin(&A, k, d[k]);
        double known = 0;
        for (int q = 0; q < 2; ++q) {
            const int j = nbr[i][q];
            if (j < 0) continue;
            ry_csr_row_pair(&row, c[i][q], unk[j]);
            if (unk[j] < 0) known += c[i][q] * uknown[j];
        }
        ry_csr_row_end(&row);
        b[k] = d[k] * ustar[k] + known;
    }
    /* the diagonal first in each row, then the unknown neighbours */
    const uint32_t col[4] = {0, 1, 1, 0};
    const double val[4] = {6, -3, 12, -3};
    for (int p = 0; p < 4; ++p) {
        assert_int_equal(A.col[p], col[p]);
        assert_true(A.val[p] == val[p]);
    }
    assert_true(A.diag[0] == 6 && A.diag[1] == 12);
    assert_true(b[0] == 2.5 && b[1] == -9);
    double x[2] = {ustar[0], ustar[1]}, res;
    int it;
    assert_int_equal(ry_csr_pcg(&A, b, x, 1e-14, 100, &it, &res, NULL, &err), RY_OK);
    assert_true(fabs(x[0] - 1.0 / 21.0) <= 1e-12);
    assert_true(fabs(x[1] + 31.0 / 42.0) <= 1e-12);
    ry_csr_free(&A);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(test_chain)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
