/* Unit tests of corrected SPH (include/ryushi/corrected.h, seed 000 eq. 10-13).
 *
 * Particle set: a lattice of spacing dx filling the unit square (cube), every particle moved by
 * a pseudo-random offset of up to 0.25 dx in each direction, volumes dx^d times a factor in
 * [0.8, 1.2]; kernel Wendland C2 (and Lucy, Gaussian) with h = 1.3 dx. Every particle is
 * checked, the boundary ones included (where plain SPH is worst).
 *
 *   linear correction: f = 1.5 + 2 x - 3 y (+ 0.7 z) and its gradient reproduced to round-off,
 *     |f~ - f| <= 1e-12 and |grad f~ - grad f| <= 1e-10 (largest seen: 5e-15 and 7e-15);
 *   without correction: errors above 0.05 (value) and 0.5 (gradient) somewhere;
 *   Shepard: a constant reproduced to 1e-13 with zero gradient (1e-11), but not a linear field
 *     (error above 1e-3 somewhere). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#include "ryushi/corrected.h"
#include "ryushi/neighbor.h"

typedef struct cloud {
    int dim;
    size_t n;
    double *x[3];
    double *vol;
    ry_nlist nl;
    ry_kernel k;
} cloud;

static uint64_t rng_state = 88172645463325252ULL;
static double uniform(void) { /* xorshift64, in [0, 1) */
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

static void make_cloud(cloud *c, int dim, int per_side, ry_kernel_type kt) {
    memset(c, 0, sizeof *c);
    c->dim = dim;
    const double dx = 1.0 / per_side;
    size_t n = 1;
    for (int d = 0; d < dim; ++d) n *= (size_t)per_side;
    c->n = n;
    for (int d = 0; d < 3; ++d) c->x[d] = calloc(n, sizeof(double));
    c->vol = calloc(n, sizeof(double));
    for (size_t i = 0; i < n; ++i) {
        size_t rest = i;
        for (int d = 0; d < dim; ++d) {
            int idx = (int)(rest % (size_t)per_side);
            rest /= (size_t)per_side;
            c->x[d][i] = (idx + 0.5 + 0.5 * (uniform() - 0.5)) * dx;
        }
        c->vol[i] = pow(dx, dim) * (0.8 + 0.4 * uniform());
    }
    ry_error err;
    assert_int_equal(ry_kernel_init(&c->k, kt, dim, 1.3 * dx, &err), RY_OK);
    ry_box box = {.dim = dim, .lo = {-1, -1, -1}, .hi = {2, 2, 2}};
    const double *xs[3] = {c->x[0], c->x[1], dim > 2 ? c->x[2] : NULL};
    assert_int_equal(ry_nlist_build_brute(&c->nl, &box, c->k.radius, n, xs, &err), RY_OK);
}

static void free_cloud(cloud *c) {
    for (int d = 0; d < 3; ++d) free(c->x[d]);
    free(c->vol);
    ry_nlist_free(&c->nl);
}

/* Largest errors of value and gradient of f = a0 + a . x over all particles. */
static void field_errors(const cloud *c, ry_correction type, double a0, const double *a,
                         double *err_v, double *err_g) {
    double *f = malloc(c->n * sizeof *f);
    for (size_t i = 0; i < c->n; ++i) {
        f[i] = a0;
        for (int d = 0; d < c->dim; ++d) f[i] += a[d] * c->x[d][i];
    }
    const double *xs[3] = {c->x[0], c->x[1], c->dim > 2 ? c->x[2] : NULL};
    *err_v = 0;
    *err_g = 0;
    for (size_t i = 0; i < c->n; ++i) {
        double v, g[3];
        ry_error err;
        size_t o = c->nl.offset[i], nn = c->nl.offset[i + 1] - o;
        assert_int_equal(ry_corr_field(type, &c->k, i, nn, c->nl.j + o, xs, c->vol, f, &v, g, &err),
                         RY_OK);
        *err_v = fmax(*err_v, fabs(v - f[i]));
        for (int d = 0; d < c->dim; ++d) *err_g = fmax(*err_g, fabs(g[d] - a[d]));
    }
    free(f);
}

static void check_dim(int dim, int per_side, ry_kernel_type kt) {
    cloud c;
    make_cloud(&c, dim, per_side, kt);
    const double a[3] = {2.0, -3.0, 0.7}, zero[3] = {0, 0, 0};
    double ev, eg;
    field_errors(&c, RY_CORRECTION_LINEAR, 1.5, a, &ev, &eg);
    print_message("%dD %s linear:  value %.2e  gradient %.2e\n", dim, ry_kernel_name(kt), ev, eg);
    assert_true(ev <= 1e-12);
    assert_true(eg <= 1e-10);
    field_errors(&c, RY_CORRECTION_NONE, 1.5, a, &ev, &eg);
    print_message("%dD %s none:    value %.2e  gradient %.2e\n", dim, ry_kernel_name(kt), ev, eg);
    assert_true(ev > 0.05);
    assert_true(eg > 0.5);
    field_errors(&c, RY_CORRECTION_SHEPARD, 1.5, zero, &ev, &eg);
    print_message("%dD %s Shepard constant: value %.2e  gradient %.2e\n", dim, ry_kernel_name(kt),
                  ev, eg);
    assert_true(ev <= 1e-13);
    assert_true(eg <= 1e-11);
    field_errors(&c, RY_CORRECTION_SHEPARD, 1.5, a, &ev, &eg);
    print_message("%dD %s Shepard linear:   value %.2e  gradient %.2e\n", dim, ry_kernel_name(kt),
                  ev, eg);
    assert_true(ev > 1e-3);
    free_cloud(&c);
}

static void test_linear_2d(void **state) {
    (void)state;
    check_dim(2, 14, RY_KERNEL_WENDLAND_C2);
    check_dim(2, 14, RY_KERNEL_LUCY);
    check_dim(2, 14, RY_KERNEL_GAUSSIAN);
}

static void test_linear_3d(void **state) {
    (void)state;
    check_dim(3, 7, RY_KERNEL_WENDLAND_C2);
    check_dim(3, 7, RY_KERNEL_GAUSSIAN);
}

/* The corrected kernel is a partition of unity with exact first moments: sum V W~ = 1 and
 * sum V W~ (x_j - x_i) = 0 at a point that is not a particle (v_self = 0). */
static void test_kernel_moments(void **state) {
    (void)state;
    cloud c;
    make_cloud(&c, 2, 10, RY_KERNEL_WENDLAND_C2);
    const double *xs[3] = {c.x[0], c.x[1], NULL};
    const double p[3] = {0.03, 0.51, 0};
    uint32_t *nbr = malloc(c.n * sizeof *nbr);
    size_t nn = 0;
    for (size_t j = 0; j < c.n; ++j) {
        double dx = c.x[0][j] - p[0], dy = c.x[1][j] - p[1];
        if (sqrt(dx * dx + dy * dy) < c.k.radius) nbr[nn++] = (uint32_t)j;
    }
    ry_corr cr;
    ry_error err;
    assert_int_equal(
        ry_corr_build(&cr, RY_CORRECTION_LINEAR, &c.k, p, 0.0, nn, nbr, xs, c.vol, &err), RY_OK);
    double s0 = 0, s1[2] = {0, 0};
    for (size_t q = 0; q < nn; ++q) {
        double xj[3] = {c.x[0][nbr[q]], c.x[1][nbr[q]], 0};
        double w = c.vol[nbr[q]] * ry_corr_w(&cr, &c.k, p, xj);
        s0 += w;
        s1[0] += w * (xj[0] - p[0]);
        s1[1] += w * (xj[1] - p[1]);
    }
    assert_true(fabs(s0 - 1) < 1e-13);
    assert_true(fabs(s1[0]) < 1e-14 && fabs(s1[1]) < 1e-14);
    /* Too few neighbours: a clear error, not a silent NaN. */
    assert_int_equal(
        ry_corr_build(&cr, RY_CORRECTION_LINEAR, &c.k, p, 0.0, 1, nbr, xs, c.vol, &err),
        RY_ERR_RANGE);
    assert_non_null(strstr(err.msg, "singular"));
    free(nbr);
    free_cloud(&c);
}

/* The quadratic fit: gradient and second derivatives of f = 1 + 2x - 3y + 0.5x^2 + 1.5xy - y^2
 * (+ 0.7z + 0.4z^2 - 0.3yz) exact to round-off (1e-9; largest seen 6e-12) at every particle of
 * the irregular set,
 * boundary ones included; the linear correction misses the gradient there (error > 0.01). */
static void check_quadratic(int dim, int per_side) {
    cloud c;
    make_cloud(&c, dim, per_side, RY_KERNEL_WENDLAND_C2);
    const double *xs[3] = {c.x[0], c.x[1], dim > 2 ? c.x[2] : NULL};
    double *f = malloc(c.n * sizeof *f);
    for (size_t i = 0; i < c.n; ++i) {
        double x = c.x[0][i], y = c.x[1][i], z = dim > 2 ? c.x[2][i] : 0;
        f[i] = 1 + 2 * x - 3 * y + 0.5 * x * x + 1.5 * x * y - y * y + 0.7 * z + 0.4 * z * z -
               0.3 * y * z;
    }
    double eg = 0, eh = 0, elin = 0;
    for (size_t i = 0; i < c.n; ++i) {
        size_t o = c.nl.offset[i], nn = c.nl.offset[i + 1] - o;
        double *G = malloc(nn * 3 * sizeof *G), *H = malloc(nn * 9 * sizeof *H);
        double xi[3] = {c.x[0][i], c.x[1][i], dim > 2 ? c.x[2][i] : 0};
        ry_error err;
        assert_int_equal(
            ry_corr_quadratic_gradient(&c.k, xi, nn, c.nl.j + o, xs, c.vol, G, H, &err), RY_OK);
        double g[3] = {0, 0, 0}, h[9] = {0};
        for (size_t q = 0; q < nn; ++q) {
            double df = f[c.nl.j[o + q]] - f[i];
            for (int a = 0; a < dim; ++a) {
                g[a] += G[(size_t)dim * q + (size_t)a] * df;
                for (int b = 0; b < dim; ++b)
                    h[3 * a + b] += H[(size_t)dim * (size_t)dim * q + (size_t)(dim * a + b)] * df;
            }
        }
        const double x = xi[0], y = xi[1], z = xi[2];
        const double ge[3] = {2 + x + 1.5 * y, -3 + 1.5 * x - 2 * y - 0.3 * z,
                              0.7 + 0.8 * z - 0.3 * y};
        const double he[9] = {1, 1.5, 0, 1.5, -2, -0.3, 0, -0.3, 0.8};
        for (int a = 0; a < dim; ++a) {
            eg = fmax(eg, fabs(g[a] - ge[a]));
            for (int b = 0; b < dim; ++b) eh = fmax(eh, fabs(h[3 * a + b] - he[3 * a + b]));
        }
        double gl[3];
        assert_int_equal(ry_corr_field(RY_CORRECTION_LINEAR, &c.k, i, nn, c.nl.j + o, xs, c.vol, f,
                                       NULL, gl, &err),
                         RY_OK);
        for (int a = 0; a < dim; ++a) elin = fmax(elin, fabs(gl[a] - ge[a]));
        free(G);
        free(H);
    }
    print_message("%dD quadratic fit: gradient %.2e, second derivatives %.2e; linear correction "
                  "gradient %.2e\n",
                  dim, eg, eh, elin);
    assert_true(eg <= 1e-9);
    assert_true(eh <= 1e-9);
    assert_true(elin > 0.01);
    free(f);
    free_cloud(&c);
}

static void test_quadratic(void **state) {
    (void)state;
    check_quadratic(2, 12);
    check_quadratic(3, 6);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_linear_2d),
        cmocka_unit_test(test_linear_3d),
        cmocka_unit_test(test_kernel_moments),
        cmocka_unit_test(test_quadratic),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
