/* Neighbour search: the cell list must give exactly the brute-force neighbour sets. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>
#include <omp.h>

#include "ryushi/neighbor.h"

/* A particle set with its own coordinate storage. */
typedef struct pset {
    size_t n;
    double *c[3];
} pset;

static void pset_init(pset *s, size_t n) {
    s->n = n;
    for (int d = 0; d < 3; ++d) {
        s->c[d] = calloc(n ? n : 1, sizeof(double));
        assert_non_null(s->c[d]);
    }
}

static void pset_free(pset *s) {
    for (int d = 0; d < 3; ++d) free(s->c[d]);
}

static const double *const *coords(const pset *s) {
    return (const double *const *)s->c;
}

static uint64_t rng_state;

static double urand(void) {
    /* splitmix64 */
    uint64_t z = (rng_state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    z ^= z >> 31;
    return (double)(z >> 11) * 0x1.0p-53;
}

static double grand(void) {
    double u = urand(), v = urand();
    if (u < 1e-300) u = 1e-300;
    return sqrt(-2.0 * log(u)) * cos(6.283185307179586 * v);
}

static ry_box make_box(int dim, double lo, double hi, int px, int py, int pz) {
    ry_box b = {.dim = dim};
    for (int d = 0; d < 3; ++d) {
        b.lo[d] = lo;
        b.hi[d] = hi;
    }
    b.periodic[0] = px;
    b.periodic[1] = py;
    b.periodic[2] = pz;
    return b;
}

static void fill_uniform(pset *s, int dim, double lo, double hi) {
    for (size_t i = 0; i < s->n; ++i)
        for (int d = 0; d < dim; ++d) {
            double v = lo + (hi - lo) * urand();
            s->c[d][i] = v < hi ? v : lo;
        }
}

/* Builds both lists and requires them identical, sorted, without self pairs, symmetric;
 * also with 1 and 3 threads. Returns the total number of pairs. */
static size_t check_same(const ry_box *box, double radius, const pset *s) {
    ry_cell_list cl = {0};
    ry_nlist a = {0}, b = {0};
    ry_error err = {0};
    assert_int_equal(ry_nlist_build_brute(&b, box, radius, s->n, coords(s), &err), RY_OK);
    int threads[2] = {omp_get_max_threads(), 1};
    int saved = omp_get_max_threads();
    for (int t = 0; t < 2; ++t) {
        omp_set_num_threads(threads[t]);
        ry_status st = ry_cells_build(&cl, box, radius, s->n, coords(s), &err);
        if (st != RY_OK) fail_msg("%s", err.msg);
        st = ry_nlist_build_cells(&a, &cl, box, radius, s->n, coords(s), &err);
        if (st != RY_OK) fail_msg("%s", err.msg);
        assert_int_equal(a.n, s->n);
        assert_int_equal(b.n, s->n);
        assert_memory_equal(a.offset, b.offset, (s->n + 1) * sizeof(size_t));
        if (a.offset[s->n] > 0) assert_memory_equal(a.j, b.j, a.offset[s->n] * sizeof(uint32_t));
        /* The cell list itself: a permutation, sorted by cell, stable. */
        size_t sum = 0;
        for (size_t c = 0; c < cl.ncells; ++c) {
            assert_true(cl.start[c] <= cl.start[c + 1]);
            for (size_t p = cl.start[c]; p < cl.start[c + 1]; ++p) {
                assert_int_equal(cl.cell_of[cl.order[p]], c);
                if (p > cl.start[c]) assert_true(cl.order[p - 1] < cl.order[p]);
                ++sum;
            }
        }
        assert_int_equal(sum, s->n);
        assert_int_equal(cl.start[cl.ncells], s->n);
    }
    omp_set_num_threads(saved);
    for (size_t i = 0; i < s->n; ++i)
        for (size_t k = b.offset[i]; k < b.offset[i + 1]; ++k) {
            uint32_t j = b.j[k];
            assert_true(j != i);
            if (k > b.offset[i]) assert_true(b.j[k - 1] < j);
            /* symmetric: i is among j's neighbours (binary search in a sorted list) */
            size_t lo = b.offset[j], hi = b.offset[j + 1];
            while (lo < hi) {
                size_t mid = lo + (hi - lo) / 2;
                if (b.j[mid] < i)
                    lo = mid + 1;
                else
                    hi = mid;
            }
            assert_true(lo < b.offset[j + 1] && b.j[lo] == i);
        }
    size_t total = b.offset[s->n];
    ry_cells_free(&cl);
    ry_nlist_free(&a);
    ry_nlist_free(&b);
    return total;
}

static void test_uniform_2d(void **state) {
    (void)state;
    rng_state = 1;
    pset s;
    pset_init(&s, 2000);
    fill_uniform(&s, 2, 0.0, 1.0);
    ry_box box = make_box(2, 0.0, 1.0, 0, 0, 0);
    double r = sqrt(20.0 / (3.14159 * 2000.0));
    size_t pairs = check_same(&box, r, &s);
    assert_true(pairs > 2000 * 10 && pairs < 2000 * 30);
    pset_free(&s);
}

static void test_uniform_3d(void **state) {
    (void)state;
    rng_state = 2;
    pset s;
    pset_init(&s, 2000);
    fill_uniform(&s, 3, -1.0, 2.0);
    ry_box box = make_box(3, -1.0, 2.0, 0, 0, 0);
    double r = 3.0 * cbrt(50.0 * 3.0 / (4.0 * 3.14159 * 2000.0));
    size_t pairs = check_same(&box, r, &s);
    assert_true(pairs > 2000 * 20);
    pset_free(&s);
}

static void test_uniform_1d(void **state) {
    (void)state;
    rng_state = 3;
    pset s;
    pset_init(&s, 1000);
    fill_uniform(&s, 1, 0.0, 10.0);
    ry_box box = make_box(1, 0.0, 10.0, 0, 0, 0);
    check_same(&box, 0.1, &s);
    box.periodic[0] = 1;
    check_same(&box, 0.1, &s);
    pset_free(&s);
}

/* Gaussian blobs of very different widths: dense cores next to sparse regions. */
static void test_clustered(void **state) {
    (void)state;
    rng_state = 4;
    for (int dim = 2; dim <= 3; ++dim) {
        pset s;
        pset_init(&s, 700);
        double centre[3][3] = {{0.2, 0.3, 0.4}, {5.0, 5.0, 5.0}, {9.0, 1.0, 7.0}};
        double sigma[3] = {0.002, 0.05, 2.0};
        for (size_t i = 0; i < s.n; ++i) {
            int b = (int)(i % 3);
            for (int d = 0; d < dim; ++d) s.c[d][i] = centre[b][d] + sigma[b] * grand();
        }
        ry_box box = make_box(dim, 0.0, 1.0, 0, 0, 0);
        check_same(&box, 0.01, &s);
        check_same(&box, 0.3, &s);
        pset_free(&s);
    }
}

/* Lattice points spaced radius / 2 (exact binary fractions): particles on cell faces and pairs
 * at exactly the radius, which must be excluded. */
static void lattice(int dim) {
    const double spacing[3] = {0.125, 0.25, 0.5};
    for (int k = 0; k < 3; ++k) {
        {
            int m = dim == 2 ? 20 : 7;
            pset s;
            pset_init(&s, (size_t)(dim == 2 ? m * m : m * m * m));
            size_t i = 0;
            for (int a = 0; a < m; ++a)
                for (int b = 0; b < m; ++b)
                    for (int c = 0; c < (dim == 3 ? m : 1); ++c, ++i) {
                        s.c[0][i] = spacing[k] * a;
                        s.c[1][i] = spacing[k] * b;
                        s.c[2][i] = spacing[k] * c;
                    }
            ry_box box = make_box(dim, 0.0, spacing[k] * m, 0, 0, 0);
            double radius = 2.0 * spacing[k];
            size_t pairs = check_same(&box, radius, &s);
            /* Interior point in 2D: 12 lattice points strictly within 2 spacings. */
            if (dim == 2) assert_true(pairs < (size_t)m * m * 12 + 1);
            /* nearest neighbours at exactly the radius */
            assert_int_equal(check_same(&box, spacing[k], &s), 0);
            check_same(&box, 1.5 * spacing[k], &s);
            /* Periodic lattice: box of exactly m spacings. */
            box.periodic[0] = box.periodic[1] = box.periodic[2] = 1;
            size_t ppairs = check_same(&box, radius, &s);
            assert_int_equal(ppairs, s.n * (dim == 2 ? 8 : 26));
            pset_free(&s);
        }
    }
}

static void test_lattice_2d(void **state) {
    (void)state;
    lattice(2);
}

static void test_lattice_3d(void **state) {
    (void)state;
    lattice(3);
}

/* Every combination of periodic directions in a box of the given width (radius 0.1). */
static void periodic(int dim, double width, size_t n) {
    rng_state = 5;
    const double r = 0.1;
    for (int mask = 1; mask < (1 << dim); ++mask) {
        pset s;
        pset_init(&s, n);
        fill_uniform(&s, dim, 0.0, width);
        /* A few particles exactly on the box faces. */
        for (int d = 0; d < dim; ++d) {
            s.c[d][d] = 0.0;
            s.c[d][10 + d] = width;
        }
        ry_box box = make_box(dim, 0.0, width, mask & 1, (mask >> 1) & 1, (mask >> 2) & 1);
        check_same(&box, r, &s);
        pset_free(&s);
    }
}

static void test_periodic_2d(void **state) {
    (void)state;
    periodic(2, 1.0, 1000);
    periodic(2, 0.25, 300); /* 2 cells wide */
    periodic(2, 0.15, 200); /* 1 cell wide */
}

static void test_periodic_3d_wide(void **state) {
    (void)state;
    periodic(3, 1.0, 700);
}

static void test_periodic_3d_narrow(void **state) {
    (void)state;
    periodic(3, 0.25, 300);
    periodic(3, 0.15, 150);
}

/* The same list for 1, 2 and 3 threads. */
static void test_thread_count(void **state) {
    (void)state;
    rng_state = 10;
    pset s;
    pset_init(&s, 3000);
    fill_uniform(&s, 3, 0.0, 1.0);
    ry_box box = make_box(3, 0.0, 1.0, 1, 0, 1);
    ry_cell_list cl = {0};
    ry_nlist ref = {0}, nl = {0};
    ry_error err = {0};
    int saved = omp_get_max_threads();
    for (int t = 1; t <= 3; ++t) {
        omp_set_num_threads(t);
        assert_int_equal(ry_cells_build(&cl, &box, 0.12, s.n, coords(&s), &err), RY_OK);
        ry_nlist *out = t == 1 ? &ref : &nl;
        assert_int_equal(ry_nlist_build_cells(out, &cl, &box, 0.12, s.n, coords(&s), &err), RY_OK);
        assert_memory_equal(out->offset, ref.offset, (s.n + 1) * sizeof(size_t));
        assert_memory_equal(out->j, ref.j, ref.offset[s.n] * sizeof(uint32_t));
    }
    omp_set_num_threads(saved);
    ry_cells_free(&cl);
    ry_nlist_free(&ref);
    ry_nlist_free(&nl);
    pset_free(&s);
}

static void test_small_sets(void **state) {
    (void)state;
    ry_box box = make_box(3, 0.0, 1.0, 0, 0, 0);
    pset s;
    pset_init(&s, 0);
    assert_int_equal(check_same(&box, 0.1, &s), 0);
    box.periodic[0] = 1;
    assert_int_equal(check_same(&box, 0.1, &s), 0);
    pset_free(&s);
    /* n = 0 with no coordinate arrays at all */
    ry_cell_list cl = {0};
    ry_nlist nl = {0};
    ry_error err = {0};
    assert_int_equal(ry_cells_build(&cl, &box, 0.1, 0, NULL, &err), RY_OK);
    assert_int_equal(ry_nlist_build_cells(&nl, &cl, &box, 0.1, 0, NULL, &err), RY_OK);
    assert_int_equal(nl.offset[0], 0);
    ry_cells_free(&cl);
    ry_nlist_free(&nl);

    pset_init(&s, 1);
    s.c[0][0] = 0.5;
    assert_int_equal(check_same(&box, 0.1, &s), 0);
    pset_free(&s);
    /* All particles at one point: everybody is everybody's neighbour. */
    pset_init(&s, 40);
    for (size_t i = 0; i < s.n; ++i) s.c[0][i] = s.c[1][i] = s.c[2][i] = 0.3;
    box.periodic[0] = 0;
    assert_int_equal(check_same(&box, 0.1, &s), 40 * 39);
    pset_free(&s);
}

/* Non-periodic directions: the box does not bound the particles. */
static void test_outside_box(void **state) {
    (void)state;
    rng_state = 6;
    pset s;
    pset_init(&s, 1000);
    fill_uniform(&s, 2, -3.0, 4.0);
    ry_box box = make_box(2, 0.0, 1.0, 0, 0, 0);
    check_same(&box, 0.2, &s);
    /* periodic in x, open in y with particles far outside [0, 1) */
    for (size_t i = 0; i < s.n; ++i) s.c[0][i] = urand();
    box.periodic[0] = 1;
    check_same(&box, 0.2, &s);
    pset_free(&s);
}

/* A few far-away particles would need a huge grid: the cells are enlarged instead. */
static void test_sparse_grid_capped(void **state) {
    (void)state;
    rng_state = 7;
    pset s;
    pset_init(&s, 500);
    fill_uniform(&s, 3, 0.0, 0.1);
    s.c[0][0] = 1e9;
    s.c[1][1] = -1e9;
    s.c[2][2] = 5e8;
    ry_box box = make_box(3, 0.0, 1.0, 0, 0, 0);
    check_same(&box, 0.01, &s);
    ry_cell_list cl = {0};
    ry_error err = {0};
    assert_int_equal(ry_cells_build(&cl, &box, 0.01, s.n, coords(&s), &err), RY_OK);
    assert_true(cl.ncells <= 8 * s.n + 65536);
    assert_true(ry_cells_bytes_per_particle(&cl) < 2000.0);
    ry_cells_free(&cl);
    /* A periodic box of 1e12 radii */
    box = make_box(2, 0.0, 1e10, 1, 1, 0);
    for (size_t i = 0; i < s.n; ++i) s.c[0][i] = s.c[1][i] = 1e10 * urand();
    check_same(&box, 0.01, &s);
    pset_free(&s);
}

/* Memory is reused: a large set, a small one, a large one again. */
static void test_reuse(void **state) {
    (void)state;
    rng_state = 8;
    ry_box box = make_box(2, 0.0, 1.0, 1, 0, 0);
    ry_cell_list cl = {0};
    ry_nlist a = {0}, b = {0};
    ry_error err = {0};
    size_t sizes[4] = {1500, 20, 0, 1200};
    double radii[4] = {0.05, 0.5, 0.1, 0.02};
    for (int k = 0; k < 4; ++k) {
        pset s;
        pset_init(&s, sizes[k]);
        fill_uniform(&s, 2, 0.0, 1.0);
        assert_int_equal(ry_cells_build(&cl, &box, radii[k], s.n, coords(&s), &err), RY_OK);
        assert_int_equal(ry_nlist_build_cells(&a, &cl, &box, radii[k], s.n, coords(&s), &err),
                         RY_OK);
        assert_int_equal(ry_nlist_build_brute(&b, &box, radii[k], s.n, coords(&s), &err), RY_OK);
        assert_memory_equal(a.offset, b.offset, (s.n + 1) * sizeof(size_t));
        if (a.offset[s.n]) assert_memory_equal(a.j, b.j, a.offset[s.n] * sizeof(uint32_t));
        if (s.n) {
            assert_true(ry_cells_bytes_per_particle(&cl) > 0.0);
            assert_true(ry_nlist_bytes_per_particle(&a) >= sizeof(size_t));
        }
        pset_free(&s);
    }
    assert_true(cl.cap_n >= 1500);
    ry_cells_free(&cl);
    ry_nlist_free(&a);
    ry_nlist_free(&b);
    assert_null(cl.start);
    assert_null(a.j);
    ry_cells_free(NULL);
    ry_nlist_free(NULL);
}

/* After the points are reordered by the cell order (and sorted by x within cells), the cell
 * list derived without binning equals a new build from the reordered points. */
static void test_permuted(void **state) {
    (void)state;
    rng_state = 11;
    for (int dim = 2; dim <= 3; ++dim) {
        ry_box box = make_box(dim, 0.0, 1.0, 0, 0, 0);
        ry_cell_list cl = {0}, fresh = {0};
        ry_error err = {0};
        pset s, t;
        pset_init(&s, 3000);
        pset_init(&t, 3000);
        fill_uniform(&s, dim, 0.0, 1.0);
        assert_int_equal(ry_cells_build(&cl, &box, 0.07, s.n, coords(&s), &err), RY_OK);
        ry_cells_sort_x(&cl, s.c[0]);
        for (size_t i = 0; i < s.n; ++i)
            for (int d = 0; d < 3; ++d) t.c[d][i] = s.c[d][cl.order[i]];
        ry_cells_permuted(&cl);
        assert_int_equal(ry_cells_build(&fresh, &box, 0.07, t.n, coords(&t), &err), RY_OK);
        assert_int_equal(cl.ncells, fresh.ncells);
        assert_memory_equal(cl.start, fresh.start, (cl.ncells + 1) * sizeof(size_t));
        assert_memory_equal(cl.order, fresh.order, t.n * sizeof(uint32_t));
        assert_memory_equal(cl.cell_of, fresh.cell_of, t.n * sizeof(uint32_t));
        for (size_t i = 1; i < t.n; ++i) /* x ascending within each cell */
            if (cl.cell_of[i] == cl.cell_of[i - 1]) assert_true(t.c[0][i] >= t.c[0][i - 1]);
        pset_free(&s);
        pset_free(&t);
        ry_cells_free(&cl);
        ry_cells_free(&fresh);
    }
}

static void expect_error(ry_status got, ry_status want, const ry_error *err, const char *part) {
    assert_int_equal(got, want);
    if (part && !strstr(err->msg, part)) fail_msg("message \"%s\" lacks \"%s\"", err->msg, part);
}

static void test_errors(void **state) {
    (void)state;
    rng_state = 9;
    pset s;
    pset_init(&s, 100);
    fill_uniform(&s, 3, 0.0, 1.0);
    ry_box box = make_box(3, 0.0, 1.0, 0, 0, 0);
    ry_cell_list cl = {0};
    ry_nlist nl = {0};
    ry_error err = {0};
    const double bad_r[4] = {0.0, -1.0, NAN, INFINITY};
    for (int k = 0; k < 4; ++k) {
        expect_error(ry_cells_build(&cl, &box, bad_r[k], s.n, coords(&s), &err), RY_ERR_RANGE, &err,
                     "radius");
        expect_error(ry_nlist_build_brute(&nl, &box, bad_r[k], s.n, coords(&s), &err), RY_ERR_RANGE,
                     &err, "radius");
    }
    box.dim = 4;
    expect_error(ry_cells_build(&cl, &box, 0.1, s.n, coords(&s), &err), RY_ERR_INPUT, &err,
                 "dimension");
    box.dim = 0;
    expect_error(ry_nlist_build_brute(&nl, &box, 0.1, s.n, coords(&s), &err), RY_ERR_INPUT, &err,
                 "dimension");
    box.dim = 3;
    s.c[1][37] = NAN;
    expect_error(ry_cells_build(&cl, &box, 0.1, s.n, coords(&s), &err), RY_ERR_RANGE, &err,
                 "particle 37");
    expect_error(ry_nlist_build_brute(&nl, &box, 0.1, s.n, coords(&s), &err), RY_ERR_RANGE, &err,
                 "particle 37");
    s.c[1][37] = 0.5;
    s.c[2][12] = -INFINITY;
    s.c[0][80] = NAN;
    expect_error(ry_cells_build(&cl, &box, 0.1, s.n, coords(&s), &err), RY_ERR_RANGE, &err,
                 "particle 12");
    s.c[2][12] = 0.5;
    s.c[0][80] = 0.5;
    /* outside a periodic box */
    box.periodic[2] = 1;
    s.c[2][55] = 1.25;
    expect_error(ry_cells_build(&cl, &box, 0.1, s.n, coords(&s), &err), RY_ERR_RANGE, &err,
                 "particle 55");
    s.c[2][55] = 0.5;
    box.hi[2] = box.lo[2];
    expect_error(ry_cells_build(&cl, &box, 0.1, s.n, coords(&s), &err), RY_ERR_INPUT, &err,
                 "periodic");
    box.hi[2] = 1.0;
    /* absurd spans */
    s.c[0][3] = 1e308;
    s.c[0][4] = -1e308;
    expect_error(ry_cells_build(&cl, &box, 0.1, s.n, coords(&s), &err), RY_ERR_RANGE, &err,
                 "range");
    s.c[0][3] = s.c[0][4] = 0.5;
    /* list from a cell list built for another radius or another set */
    assert_int_equal(ry_cells_build(&cl, &box, 0.1, s.n, coords(&s), &err), RY_OK);
    expect_error(ry_nlist_build_cells(&nl, &cl, &box, 0.2, s.n, coords(&s), &err), RY_ERR_INPUT,
                 &err, "radius");
    expect_error(ry_nlist_build_cells(&nl, &cl, &box, 0.1, s.n - 1, coords(&s), &err), RY_ERR_INPUT,
                 &err, "particles");
    assert_int_equal(ry_nlist_build_cells(&nl, &cl, &box, 0.05, s.n, coords(&s), &err), RY_OK);
    expect_error(ry_nlist_build_cells(&nl, &cl, NULL, 0.1, s.n, coords(&s), &err), RY_ERR_INPUT,
                 &err, "box");
    expect_error(ry_cells_build(&cl, &box, 0.1, s.n, NULL, &err), RY_ERR_INPUT, &err,
                 "coordinates");
    /* err may be NULL */
    assert_int_equal(ry_cells_build(&cl, &box, -1.0, s.n, coords(&s), NULL), RY_ERR_RANGE);
    ry_cells_free(&cl);
    ry_nlist_free(&nl);
    pset_free(&s);
}

/* An optional argument selects tests by name pattern. */
int main(int argc, char **argv) {
    if (argc > 1) cmocka_set_test_filter(argv[1]);
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_uniform_2d),         cmocka_unit_test(test_uniform_3d),
        cmocka_unit_test(test_uniform_1d),         cmocka_unit_test(test_clustered),
        cmocka_unit_test(test_lattice_2d),         cmocka_unit_test(test_lattice_3d),
        cmocka_unit_test(test_periodic_2d),        cmocka_unit_test(test_periodic_3d_wide),
        cmocka_unit_test(test_periodic_3d_narrow), cmocka_unit_test(test_thread_count),
        cmocka_unit_test(test_small_sets),         cmocka_unit_test(test_outside_box),
        cmocka_unit_test(test_sparse_grid_capped), cmocka_unit_test(test_reuse),
        cmocka_unit_test(test_permuted),           cmocka_unit_test(test_errors),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
