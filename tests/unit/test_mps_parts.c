/* Unit tests of the MPS building blocks: lattice constants n0 and lambda (seed eq. 4, 8), the
 * potential model's coefficient C (seed eq. 11-12) against a hand computation, the CSF lattice
 * constant, and the conjugate-gradient solver.
 *
 * Tolerances: sums of a handful of terms written out by hand, 1e-12 relative (rounding only);
 * the hand-evaluated decimal value of the 2D pair sum, 1e-5 (its 6 printed digits); the
 * conjugate-gradient solution of a 1D Poisson problem against its exact solution, 1e-8
 * relative (solver tolerance 1e-12). */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <string.h>
#include <cmocka.h>

#include "linalg/sparse.h"
#include "ryushi/mps.h"
#include "ryushi/surface_tension.h"

static void assert_rel(double got, double want, double tol, const char *what) {
    if (!(fabs(got - want) <= tol * fabs(want)))
        fail_msg("%s: got %.15g, expected %.15g (relative tolerance %g)", what, got, want, tol);
}

/* Tamai weight on the square lattice, re = 2.1 l0: neighbours at 1 (4), sqrt 2 (4) and 2 (4). */
static void test_lattice_constants_2d(void **state) {
    (void)state;
    const double l0 = 1e-4, re = 2.1 * l0;
    const double w1 = pow(1 / 2.1 - 1, 2), w2 = pow(sqrt(2.0) / 2.1 - 1, 2),
                 w4 = pow(2 / 2.1 - 1, 2);
    const double n0 = 4 * (w1 + w2 + w4);
    const double lambda = 4 * l0 * l0 * (1 * w1 + 2 * w2 + 4 * w4) / n0;
    double n0c, lc;
    ry_mps_lattice(2, l0, re, &n0c, &lc);
    assert_rel(n0c, n0, 1e-12, "n0 (2D, re = 2.1 l0)");
    assert_rel(lc, lambda, 1e-12, "lambda (2D, re = 2.1 l0)");
}

/* Eq. 11 in 2D with re = 3.1 l0, by hand: a particle of A at depth a + 1/2 and one of B at
 * height b + 1/2 spacings are s = a + b + 1 apart normal to the split (s pairs (a, b) for each
 * s), u spacings apart along it; pairs within 3.1 l0: s = 1, u = 0, +-1, +-2; s = 2, u = 0,
 * +-1, +-2; s = 3, u = 0. In units of l0^3: phi(1) = -1.5435, phi(sqrt 2) = -1.38705,
 * phi(sqrt 5) = -0.568761, phi(2) = -0.826833, phi(sqrt 8) = -0.0707622, phi(3) = -0.0101667;
 * the sum is -9.69734. */
static void test_potential_coefficient_2d(void **state) {
    (void)state;
    const double l0 = 1e-4, re = 3.1 * l0, sigma = 0.0728;
#define PHI(r) ry_st_potential_phi((r)*l0, l0, re)
    const double by_hand = 1 * (PHI(1) + 2 * PHI(sqrt(2.0)) + 2 * PHI(sqrt(5.0))) +
                           2 * (PHI(2) + 2 * PHI(sqrt(5.0)) + 2 * PHI(sqrt(8.0))) + 3 * PHI(3);
#undef PHI
    const double l3 = l0 * l0 * l0;
    assert_rel(ry_st_potential_phi(l0, l0, re) / l3, -1.5435, 1e-12, "phi(l0)");
    assert_rel(ry_st_potential_phi(3 * l0, l0, re) / l3, -0.0305 / 3, 1e-12, "phi(3 l0)");
    assert_rel(by_hand / l3, -9.69734, 1e-5, "hand sum (decimal)");
    assert_rel(ry_st_potential_pair_sum(2, l0, re), by_hand, 1e-12, "pair sum (2D)");
    const double C = 2 * sigma * l0 / by_hand; /* per unit depth */
    assert_rel(ry_st_potential_coefficient(2, l0, re, sigma), C, 1e-12, "C (2D)");
    assert_true(C < 0); /* f = -dphi/dr: a negative C makes the far pairs attract */
    ry_surface_tension st;
    ry_error err = {0};
    assert_int_equal(ry_st_setup(&st, RY_ST_POTENTIAL, 2, l0, re, sigma, &err), RY_OK);
    assert_rel(st.C, C, 1e-12, "C from ry_st_setup");
}

/* Eq. 11 in 3D by brute force over two blocks of the lattice (a different route from the
 * library's multiplicity sum): A = one column x = y = 0, z = -1/2, -3/2, ...; B = all sites
 * with z = +1/2, +3/2, ... */
static void test_potential_coefficient_3d(void **state) {
    (void)state;
    const double l0 = 1e-4, re = 3.1 * l0, sigma = 0.0728;
    double sum = 0;
    for (int a = 0; a < 5; ++a)
        for (int x = -5; x <= 5; ++x)
            for (int y = -5; y <= 5; ++y)
                for (int b = 0; b < 5; ++b) {
                    const double dz = (b + 0.5) - (-a - 0.5);
                    const double r = l0 * sqrt(x * x + y * y + dz * dz);
                    sum += ry_st_potential_phi(r, l0, re);
                }
    assert_rel(ry_st_potential_pair_sum(3, l0, re), sum, 1e-12, "pair sum (3D)");
    assert_rel(ry_st_potential_coefficient(3, l0, re, sigma), 2 * sigma * l0 * l0 / sum, 1e-12,
               "C (3D)");
}

/* The force is minus the derivative of the potential (eq. 10 and 12), zero at r = l0. */
static void test_potential_force_is_derivative(void **state) {
    (void)state;
    const double l0 = 1.0, re = 3.1, h = 1e-6;
    for (double r = 0.5; r < 3.1 - 2 * h; r += 0.05) {
        const double fd =
            -(ry_st_potential_phi(r + h, l0, re) - ry_st_potential_phi(r - h, l0, re)) / (2 * h);
        if (fabs(fd - ry_st_potential_f(r, l0, re)) > 1e-8)
            fail_msg("r = %g: f = %.10g, -dphi/dr = %.10g", r, ry_st_potential_f(r, l0, re), fd);
    }
    assert_true(ry_st_potential_f(l0, l0, re) == 0.0);
    assert_true(ry_st_potential_f(3.2, l0, re) == 0.0 && ry_st_potential_phi(3.2, l0, re) == 0.0);
}

/* CSF lattice constants in 2D, re = 3.1 l0: the inward sum sum_j w x_ij/r of a particle in the
 * top layer of a flat surface, by hand: neighbours 1 to 3 rows down (s) and u columns across,
 * normal component w s / r: s = 1: u = 0, +-1, +-2; s = 2: u = 0, +-1, +-2; s = 3: u = 0. */
static void test_csf_lattice(void **state) {
    (void)state;
    const double l0 = 1e-4, re = 3.1e-4;
#define W(r) ry_mps_weight_tamai((r)*l0, re)
    const double g_top = W(1) + 2 * W(sqrt(2.0)) / sqrt(2.0) + 2 * W(sqrt(5.0)) / sqrt(5.0) + W(2) +
                         2 * 2 * W(sqrt(5.0)) / sqrt(5.0) + 2 * 2 * W(sqrt(8.0)) / sqrt(8.0) + W(3);
#undef W
    ry_surface_tension st;
    ry_error err = {0};
    assert_int_equal(ry_st_setup(&st, RY_ST_CSF, 2, l0, re, 0.0728, &err), RY_OK);
    assert_rel(st.g_top, g_top, 1e-12, "top-layer inward sum");
    assert_true(st.delta_sum > st.g_top);
    assert_int_equal(ry_st_setup(&st, RY_ST_CSF, 4, l0, re, 0.0728, &err), RY_ERR_INPUT);
}

/* -u'' = 1 on (0, 1), u(0) = u(1) = 0, by second differences on n interior points: the
 * discrete solution is exact for a quadratic, u = x (1 - x) / 2. */
/* The 1D Poisson matrix tridiag(-1, 2, -1) of n rows. */
static void poisson_1d(ry_csr *a, size_t n) {
    ry_error err = {0};
    assert_int_equal(ry_csr_reserve(a, n, 3 * n, &err), RY_OK);
    size_t p = 0;
    for (size_t i = 0; i < n; ++i) {
        a->row[i] = p;
        if (i > 0) {
            a->col[p] = (uint32_t)(i - 1);
            a->val[p++] = -1;
        }
        a->col[p] = (uint32_t)i;
        a->val[p++] = 2;
        a->diag[i] = 2;
        if (i + 1 < n) {
            a->col[p] = (uint32_t)(i + 1);
            a->val[p++] = -1;
        }
    }
    a->row[n] = p;
}

static void test_pcg_poisson_1d(void **state) {
    (void)state;
    enum { n = 200 };
    const double h = 1.0 / (n + 1);
    ry_csr a = {0};
    ry_error err = {0};
    poisson_1d(&a, n);
    double b[n], x[n];
    for (size_t i = 0; i < n; ++i) {
        b[i] = h * h;
        x[i] = 0;
    }
    int it;
    double res;
    assert_int_equal(ry_csr_pcg(&a, b, x, 1e-12, 1000, &it, &res, NULL, &err), RY_OK);
    for (size_t i = 0; i < n; ++i) {
        const double xi = (i + 1) * h;
        assert_rel(x[i], 0.5 * xi * (1 - xi), 1e-8, "CG solution");
    }
    assert_true(it <= n + 1 && res <= 1e-12);
    /* Too few iterations: an error naming the residual. */
    for (size_t i = 0; i < n; ++i) x[i] = 0;
    assert_int_equal(ry_csr_pcg(&a, b, x, 1e-12, 5, &it, &res, NULL, &err), RY_ERR_UNSTABLE);
    assert_non_null(strstr(err.msg, "did not converge"));
    ry_csr_free(&a);
}

/* Three systems with one matrix solved together: each solution, iteration count and residual
 * the same, to the bit, as solved alone, though they stop at different iterations (a smooth
 * right-hand side, a zero one, a rough one from a non-zero start). */
static void test_pcg_multi_as_single(void **state) {
    (void)state;
    enum { n = 300 };
    ry_csr a = {0};
    ry_error err = {0};
    poisson_1d(&a, n);
    static double b[3][n], x0[3][n], xs[3][n], xm[3][n];
    for (size_t i = 0; i < n; ++i) {
        const double t = (i + 0.5) / n;
        b[0][i] = sin(RY_PI * t) / (n * n);
        b[1][i] = 0;
        b[2][i] = (i % 7 < 3 ? 1.0 : -0.5) * t / n;
        x0[0][i] = 0;
        x0[1][i] = 0.25;
        x0[2][i] = cos(3 * t);
    }
    int its[3], itm[3];
    double rs[3], rm[3];
    for (int k = 0; k < 3; ++k) {
        memcpy(xs[k], x0[k], sizeof xs[k]);
        memcpy(xm[k], x0[k], sizeof xm[k]);
        assert_int_equal(ry_csr_pcg(&a, b[k], xs[k], 1e-10, 1000, &its[k], &rs[k], NULL, &err),
                         RY_OK);
    }
    const double *bb[3] = {b[0], b[1], b[2]};
    double *xx[3] = {xm[0], xm[1], xm[2]};
    assert_int_equal(ry_csr_pcg_multi(&a, 3, bb, xx, 1e-10, 1000, itm, rm, NULL, &err), RY_OK);
    assert_true(its[0] != its[2] && its[1] == 0);
    for (int k = 0; k < 3; ++k) {
        assert_int_equal(its[k], itm[k]);
        assert_memory_equal(&rs[k], &rm[k], sizeof rs[k]);
        assert_memory_equal(xs[k], xm[k], sizeof xs[k]);
    }
    assert_int_equal(
        ry_csr_pcg_multi(&a, RY_CSR_MAX_RHS + 1, bb, xx, 1e-10, 1000, itm, rm, NULL, &err),
        RY_ERR_INTERNAL);
    ry_csr_free(&a);
}

/* The 3D Poisson matrix (7-point, Dirichlet outside) on a k^3 grid, row i = x + k (y + k z). */
static void poisson_3d(ry_csr *a, size_t k) {
    ry_error err = {0};
    const size_t n = k * k * k;
    assert_int_equal(ry_csr_reserve(a, n, 7 * n, &err), RY_OK);
    size_t p = 0;
    for (size_t i = 0; i < n; ++i) {
        const size_t c[3] = {i % k, i / k % k, i / (k * k)}, s[3] = {1, k, k * k};
        a->row[i] = p;
        for (int d = 2; d >= 0; --d)
            if (c[d] > 0) {
                a->col[p] = (uint32_t)(i - s[d]);
                a->val[p++] = -1;
            }
        a->col[p] = (uint32_t)i;
        a->val[p++] = 6;
        a->diag[i] = 6;
        for (int d = 0; d < 3; ++d)
            if (c[d] + 1 < k) {
                a->col[p] = (uint32_t)(i + s[d]);
                a->val[p++] = -1;
            }
    }
    a->row[n] = p;
}

/* Deflated CG on a 24^3 Poisson problem, aggregates of 4^3 grid points: the solution agrees
 * with plain CG's to the tolerance (both stop at a relative residual of 1e-10; their
 * difference, relative to the solution, is bounded by the condition number times that, about
 * 1e-7 here: checked at 1e-6), its residual checked independently, in under half the
 * iterations. With every unknown its own aggregate, the coarse solve is exact: no iteration. */
static void test_pcg_deflated(void **state) {
    (void)state;
    enum { k = 24, n = k * k * k, g = 4 };
    ry_csr a = {0};
    ry_csr_deflation d = {0};
    ry_error err = {0};
    poisson_3d(&a, k);
    static double b[n], x0[n], x1[n], ax[n];
    for (size_t i = 0; i < n; ++i) {
        const double t = (double)i / n;
        b[i] = 1.0 + (i % 5 < 2 ? 0.5 : -0.25) + sin(7 * t);
        x0[i] = x1[i] = 0.1 * cos(3 * t);
    }
    int it0, it1;
    double r0, r1;
    const double *bp[1] = {b};
    double *xp[1] = {x1};
    assert_int_equal(ry_csr_pcg(&a, b, x0, 1e-10, 5000, &it0, &r0, NULL, &err), RY_OK);
    assert_int_equal(ry_csr_deflation_reserve(&d, n, (k / g) * (k / g) * (k / g), &err), RY_OK);
    for (size_t i = 0; i < n; ++i)
        d.agg[i] = (uint32_t)(i % k / g + (k / g) * (i / k % k / g + (k / g) * (i / (k * k) / g)));
    d.m = (k / g) * (k / g) * (k / g);
    assert_int_equal(ry_csr_pcg_deflated(&a, 1, bp, xp, &d, 1e-10, 5000, &it1, &r1, &err), RY_OK);
    ry_csr_mul(&a, x1, ax);
    double rr = 0, bb = 0, dx = 0, xx = 0;
    for (size_t i = 0; i < n; ++i) {
        rr += (b[i] - ax[i]) * (b[i] - ax[i]);
        bb += b[i] * b[i];
        dx += (x1[i] - x0[i]) * (x1[i] - x0[i]);
        xx += x0[i] * x0[i];
    }
    assert_true(r1 <= 1e-10 && sqrt(rr / bb) <= 2e-10);
    if (!(sqrt(dx / xx) <= 1e-6))
        fail_msg("deflated against plain CG: relative difference %g", sqrt(dx / xx));
    if (!(2 * it1 < it0)) fail_msg("deflated CG: %d iterations, plain %d", it1, it0);
    /* three systems together, each the same to the bit as alone */
    static double bm[3][n], xm[3][n], xs[n];
    for (size_t i = 0; i < n; ++i) {
        bm[0][i] = b[i];
        bm[1][i] = 0;
        bm[2][i] = cos(0.01 * (double)i);
        xm[0][i] = xm[1][i] = xm[2][i] = 0.1 * cos(3 * ((double)i / n));
    }
    const double *bmp[3] = {bm[0], bm[1], bm[2]};
    double *xmp[3] = {xm[0], xm[1], xm[2]};
    int itm[3];
    double rm[3];
    assert_int_equal(ry_csr_pcg_deflated(&a, 3, bmp, xmp, &d, 1e-10, 5000, itm, rm, &err), RY_OK);
    assert_memory_equal(xm[0], x1, sizeof xs);
    assert_int_equal(itm[0], it1);
    assert_int_equal(itm[1], 0);
    for (size_t i = 0; i < n; ++i) xs[i] = 0.1 * cos(3 * ((double)i / n));
    const double *b2[1] = {bm[2]};
    double *x2[1] = {xs};
    int its;
    double rs;
    assert_int_equal(ry_csr_pcg_deflated(&a, 1, b2, x2, &d, 1e-10, 5000, &its, &rs, &err), RY_OK);
    assert_memory_equal(xm[2], xs, sizeof xs);
    assert_int_equal(itm[2], its);
    ry_csr_deflation_free(&d);
    ry_csr_free(&a);
    /* every unknown its own aggregate (6^3) */
    poisson_3d(&a, 6);
    assert_int_equal(ry_csr_deflation_reserve(&d, 216, 216, &err), RY_OK);
    for (size_t i = 0; i < 216; ++i) {
        d.agg[i] = (uint32_t)i;
        x1[i] = 0;
    }
    d.m = 216;
    assert_int_equal(ry_csr_pcg_deflated(&a, 1, bp, xp, &d, 1e-10, 5000, &it1, &r1, &err), RY_OK);
    assert_int_equal(it1, 0);
    assert_true(r1 <= 1e-10);
    ry_csr_deflation_free(&d);
    ry_csr_free(&a);
}

/* The lattice's plane waves (ry_st_potential_lattice_omega2) against the forces themselves: a
 * periodic lattice of N^d sites displaced by +-A pol sin(k.x), the pair forces C f(r) summed
 * directly over the nearest images; their central difference in A at a crest is -m omega^2 A pol
 * up to O(A^2) (A = 1e-6 l0: 1e-6 relative). Then the growth of the transverse waves: the seed's
 * 3.1 l0 unstable in 2D and 3D, 4.1 l0 stable in 3D, and sqrt(sigma / (rho l0^3)) scaling. */
static double lattice_force(int dim, int N, double l0, double re, double C, const double k[3],
                            const double pol[3], double A, int site) {
    /* the displaced position of each site, and the force along pol on the given one */
    const double L = N * l0;
    const int n = dim > 2 ? N * N * N : N * N;
    double xs[1000][3];
    assert_true(n <= 1000);
    for (int s = 0; s < n; ++s) {
        const int idx[3] = {s % N, (s / N) % N, dim > 2 ? s / (N * N) : 0};
        double ph = 0;
        for (int d = 0; d < 3; ++d) ph += k[d] * idx[d] * l0;
        for (int d = 0; d < 3; ++d) xs[s][d] = idx[d] * l0 + A * pol[d] * sin(ph);
    }
    double f = 0;
    for (int j = 0; j < n; ++j) {
        if (j == site) continue;
        double dx[3], r2 = 0;
        for (int d = 0; d < dim; ++d) {
            dx[d] = xs[j][d] - xs[site][d];
            dx[d] -= L * round(dx[d] / L);
            r2 += dx[d] * dx[d];
        }
        const double r = sqrt(r2);
        if (r >= re) continue;
        const double g = C * ry_st_potential_f(r, l0, re) / r;
        for (int d = 0; d < dim; ++d) f += g * dx[d] * pol[d];
    }
    return f;
}

static void check_lattice_wave(int dim, int N, double re_l0, const double kn[3],
                               const double pol[3]) {
    const double l0 = 1e-4, re = re_l0 * l0, sigma = 0.0728, rho = 1000.0, A = 1e-6 * l0;
    const double C = ry_st_potential_coefficient(dim, l0, re, sigma), m = rho * pow(l0, dim);
    double k[3], pn = 0;
    for (int d = 0; d < 3; ++d) k[d] = 2 * RY_PI * kn[d] / (N * l0);
    for (int d = 0; d < 3; ++d) pn += pol[d] * pol[d];
    /* a crest: the site whose phase is nearest pi/2 */
    int site = 0;
    double best = -2;
    const int n = dim > 2 ? N * N * N : N * N;
    for (int s = 0; s < n; ++s) {
        const int idx[3] = {s % N, (s / N) % N, dim > 2 ? s / (N * N) : 0};
        double ph = 0;
        for (int d = 0; d < 3; ++d) ph += k[d] * idx[d] * l0;
        if (sin(ph) > best) best = sin(ph), site = s;
    }
    const double df = 0.5 * (lattice_force(dim, N, l0, re, C, k, pol, A, site) -
                             lattice_force(dim, N, l0, re, C, k, pol, -A, site));
    const double w2 = -df / (m * A * best * pn);
    char what[96];
    snprintf(what, sizeof what, "omega^2 (%dD, re = %.1f l0, k = %g %g %g)", dim, re_l0, kn[0],
             kn[1], kn[2]);
    assert_rel(ry_st_potential_lattice_omega2(dim, l0, re, sigma, rho, k, pol), w2, 1e-6, what);
}

static void test_potential_lattice_waves(void **state) {
    (void)state;
    const double k1[3] = {2, 1, 0}, p1[3] = {-1, 2, 0}, p1l[3] = {2, 1, 0};
    check_lattice_wave(2, 10, 3.1, k1, p1);
    check_lattice_wave(2, 10, 3.1, k1, p1l);
    const double k2[3] = {3, 1, 1}, p2[3] = {0, 1, -1}, p3[3] = {1, -3, 0};
    check_lattice_wave(3, 10, 3.1, k2, p2);
    check_lattice_wave(3, 10, 4.1, k2, p3);
    const double l0 = 1e-4, sigma = 0.0728, rho = 1000.0;
    double kw[3];
    const double g3 = ry_st_potential_lattice_growth(3, l0, 3.1 * l0, sigma, rho, kw);
    const double g2 = ry_st_potential_lattice_growth(2, l0, 3.1 * l0, sigma, rho, NULL);
    print_message("transverse growth, seed fluid: 3D 3.1 l0 %.4g 1/s (k = %.3g %.3g %.3g pi/l0), "
                  "2D 3.1 l0 %.4g 1/s, 3D 4.1 l0 %.4g 1/s\n",
                  g3, kw[0], kw[1], kw[2], g2,
                  ry_st_potential_lattice_growth(3, l0, 4.1 * l0, sigma, rho, NULL));
    assert_true(g3 > 1e3 && g2 > 1e3);
    assert_true(ry_st_potential_lattice_growth(3, l0, 4.1 * l0, sigma, rho, NULL) == 0.0);
    assert_rel(ry_st_potential_lattice_growth(3, l0, 3.1 * l0, 4 * sigma, rho, NULL), 2 * g3, 1e-9,
               "growth ~ sqrt(sigma)");
    assert_rel(ry_st_potential_lattice_growth(3, 2 * l0, 6.2 * l0, sigma, rho, NULL),
               g3 / pow(2.0, 1.5), 1e-9, "growth ~ l0^-1.5");
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_lattice_constants_2d),
        cmocka_unit_test(test_potential_coefficient_2d),
        cmocka_unit_test(test_potential_coefficient_3d),
        cmocka_unit_test(test_potential_force_is_derivative),
        cmocka_unit_test(test_potential_lattice_waves),
        cmocka_unit_test(test_csf_lattice),
        cmocka_unit_test(test_pcg_poisson_1d),
        cmocka_unit_test(test_pcg_multi_as_single),
        cmocka_unit_test(test_pcg_deflated),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
