/* The WCSPH pair term on two hand-placed particles against the equations by hand, through
 * both pair loops (the neighbour list in double precision, the cell ranges in single).
 *
 * Two fluid particles of a 2D lattice of spacing dx = 0.01 m (mass 0.1 kg each), i at
 * (0.005, 0.005) and j at (0.013, 0.011): x_ij = (-0.008, -0.006), r = 0.01 m; Wendland C2,
 * h = 1.4 dx, so q = 0.714 and dW/dr = sigma / h^3 f'(q) with sigma = 7 / (4 pi),
 * f'(q) = -10 s (1 - s)^3, s = q / 2. Densities 1010 and 995 kg/m^3, velocities (0.1, 0.05) and
 * (-0.2, 0) m/s, set after the set-up. Linear equation of state p = c0^2 (rho - rho0) with
 * c0 = 10 m/s; Monaghan's artificial viscosity alpha = 0.1 (the pair approaches);
 * kinematic viscosity nu = 1e-3 m^2/s (mu = rho nu); delta-SPH after Molteni & Colagrossi,
 * delta = 0.1; gravity (0, -9.81). By hand, with grad_i W = dW/dr x_ij / r, V_j = m_j / rho_j
 * and eta^2 = 0.01 h^2:
 *   a_i = -m_j (p_i / rho_i^2 + p_j / rho_j^2 + Pi_ij) grad_i W
 *         + 1/rho_i V_j (mu_i + mu_j) x_ij . grad_i W / (r^2 + eta^2) v_ij + g,
 *   Pi_ij = -alpha c0 mu_ij / rho_bar, mu_ij = h v_ij . x_ij / (r^2 + eta^2),
 *   drho_i/dt = rho_i V_j v_ij . grad_i W - 2 delta h c0 (rho_j - rho_i) V_j
 *               x_ij . grad_i W / (r^2 + eta^2),
 * and the same for j with i and j exchanged.
 * Tolerances: the list loop 1e-12 of each quantity's scale (a few roundings of double
 * precision); the cell loop 2e-6 (single precision, 2^-24 = 6e-8, over some 20 operations).
 *
 * The pair function itself (src/schemes/wcsph/wcsph_pair.h), in double and single precision,
 * is also checked alone in 3D on the terms the two-particle runs do not reach: the energy rate,
 * the hydrostatic term of Fourtakas et al. (2019), different sound speeds, a wall neighbour
 * (its ghost velocity, viscous factor and the fluid's viscosity) and the wall repulsion of
 * Monaghan (1994), with its cap on (r0/r)^2 at 1e3. The kernel factor fw = (dW/dr)/r is an
 * input of the pair function (the traversal's); any value serves. So is the transport-velocity
 * pair term (src/schemes/wcsph/wcsph_tvf_pair.h; Adami, Hu & Adams 2013, eq. 8 and 13), on a
 * fluid and a wall neighbour, within 1e-12. */
#define _POSIX_C_SOURCE 200809L /* mkdtemp (tmpdir.h) */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <cmocka.h>

#define RY_TMPDIR_PREFIX "ryushi_pair_"
#include "tmpdir.h"
#include "ryushi/run.h"
#include "schemes/wcsph/wcsph_pair.h"
#include "schemes/wcsph/wcsph_tvf_pair.h"

#define PI 3.14159265358979323846

static const double dx = 0.01, rho0 = 1000.0, c0 = 10.0, alpha = 0.1, nu = 1e-3, delta = 0.1;
static const double g[2] = {0.0, -9.81};

/* The two particles' rates by hand: a[k][d] and drho[k], k = 0 for i, 1 for j. */
static void by_hand(const double x[2][2], const double v[2][2], const double rho[2], double m,
                    double a[2][2], double drho[2]) {
    const double h = 1.4 * dx, eta2 = 0.01 * h * h, sigma = 7.0 / (4.0 * PI);
    for (int k = 0; k < 2; ++k) {
        const int o = 1 - k;
        const double xij[2] = {x[k][0] - x[o][0], x[k][1] - x[o][1]};
        const double vij[2] = {v[k][0] - v[o][0], v[k][1] - v[o][1]};
        const double r = sqrt(xij[0] * xij[0] + xij[1] * xij[1]), q = r / h, s = 0.5 * q;
        const double dwdr = sigma / (h * h * h) * (-10.0 * s * pow(1.0 - s, 3));
        const double gw[2] = {dwdr * xij[0] / r, dwdr * xij[1] / r};
        const double xg = xij[0] * gw[0] + xij[1] * gw[1], vx = vij[0] * xij[0] + vij[1] * xij[1];
        const double vg = vij[0] * gw[0] + vij[1] * gw[1];
        const double pk = c0 * c0 * (rho[k] - rho0), po = c0 * c0 * (rho[o] - rho0);
        const double muij = vx < 0 ? h * vx / (r * r + eta2) : 0.0;
        const double pi_ij = -alpha * c0 * muij / (0.5 * (rho[k] + rho[o]));
        const double vol = m / rho[o], musum = (rho[k] + rho[o]) * nu;
        for (int d = 0; d < 2; ++d)
            a[k][d] = -m * (pk / (rho[k] * rho[k]) + po / (rho[o] * rho[o]) + pi_ij) * gw[d] +
                      vol * musum * xg / (r * r + eta2) * vij[d] / rho[k] + g[d];
        drho[k] = rho[k] * vol * vg -
                  2.0 * delta * h * c0 * (rho[o] - rho[k]) * vol * xg / (r * r + eta2);
    }
}

static void check_loop(const char *loop, double tol) {
    char text[1024];
    snprintf(text, sizeof text,
             "dimension: 2\nspacing: %g\n"
             "kernel: {type: wendland_c2, h_over_dx: 1.4}\n"
             "materials: [{name: water, density: %g, viscosity: %g}]\n"
             "gravity: [%g, %g]\n"
             "bodies:\n"
             "  - {type: box, lo: [0, 0], hi: [0.01, 0.01]}\n"
             "  - {type: box, lo: [0.008, 0.006], hi: [0.018, 0.016]}\n"
             "domain: {lo: [-0.05, -0.05], hi: [0.07, 0.07]}\n"
             "scheme: {name: wcsph, eos: linear, sound_speed: %g, artificial_viscosity: "
             "{alpha: %g}, density_diffusion: molteni, delta: %g, pair_loop: %s}\n"
             "time: {end: 0.01}\n"
             "output: {vtk: false}\n",
             dx, rho0, nu, g[0], g[1], c0, alpha, delta, loop);
    ry_case *c = NULL;
    ry_sim sim;
    ry_error err = {0};
    memset(&sim, 0, sizeof sim);
    assert_int_equal(ry_case_load_string(&c, "pair.yaml", text, &err), RY_OK);
    if (ry_sim_setup(&sim, c, tmpdir, &err) != RY_OK) fprintf(stderr, "%s\n", err.msg);
    assert_int_equal(sim.ps.n, 2);
    ry_particles *ps = &sim.ps;
    /* particle i: the one at the lower left */
    const size_t i = ps->f[RY_F_X][0] < ps->f[RY_F_X][1] ? 0 : 1, j = 1 - i;
    const double rho[2] = {1010.0, 995.0}, v[2][2] = {{0.1, 0.05}, {-0.2, 0.0}};
    double x[2][2];
    const size_t idx[2] = {i, j};
    for (int k = 0; k < 2; ++k) {
        ps->f[RY_F_RHO][idx[k]] = rho[k];
        for (int d = 0; d < 2; ++d) {
            ps->f[RY_F_VX + d][idx[k]] = v[k][d];
            x[k][d] = ps->f[RY_F_X + d][idx[k]];
        }
    }
    assert_true(fabs(x[0][0] - 0.005) < 1e-12 && fabs(x[1][1] - 0.011) < 1e-12);
    const double m = ps->f[RY_F_MASS][i];
    assert_true(fabs(m - rho0 * dx * dx) < 1e-15);
    double dt;
    assert_int_equal(sim.scheme->stable_dt(&sim, sim.scheme_state, &dt, &err), RY_OK);
    double a[2][2], drho[2];
    by_hand(x, v, rho, m, a, drho);
    for (int k = 0; k < 2; ++k) {
        const double ascale = fabs(a[k][0]) + fabs(a[k][1]), dscale = fabs(drho[k]);
        print_message("%s loop, particle %c: a = (%.9g, %.9g) by hand (%.9g, %.9g); drho/dt = "
                      "%.9g by hand %.9g\n",
                      loop, k ? 'j' : 'i', ps->f[RY_F_AX][idx[k]], ps->f[RY_F_AY][idx[k]], a[k][0],
                      a[k][1], ps->f[RY_F_DRHO][idx[k]], drho[k]);
        for (int d = 0; d < 2; ++d)
            assert_true(fabs(ps->f[RY_F_AX + d][idx[k]] - a[k][d]) <= tol * ascale);
        assert_true(fabs(ps->f[RY_F_DRHO][idx[k]] - drho[k]) <= tol * dscale);
    }
    ry_sim_free(&sim);
    ry_case_free(c);
}

/* One pair in 3D by hand: particle i and neighbour j (fluid or wall, with the velocity that
 * viscous terms see ug), x_ij, the kernel factor fw; the rates a[3], div, diff and de as
 * wcsph_pair.h defines them. */
typedef struct hand_pair {
    double ui[3], uj[3], ugj[3], rhoi, rhoj, pi, pj, mui, muj, ci, cj, mj, fluid, visc;
    double x[3], fw, h, alpha, beta, g[3], rho0, c0, rep_d, rep_r0;
} hand_pair;

static void pair_by_hand(const hand_pair *P, double a[3], double *div, double *diff, double *de) {
    const double r2 = P->x[0] * P->x[0] + P->x[1] * P->x[1] + P->x[2] * P->x[2];
    const double eta2 = 0.01 * P->h * P->h, volj = P->mj / P->rhoj;
    double vg[3], vx = 0, vw = 0, gx = 0;
    for (int d = 0; d < 3; ++d) {
        vg[d] = P->ui[d] - P->ugj[d];
        vx += vg[d] * P->x[d];
        vw += (P->ui[d] - P->uj[d]) * P->x[d];
        gx += P->g[d] * P->x[d];
    }
    const double mu = vx < 0 ? P->h * vx / (r2 + eta2) : 0.0;
    const double Pi =
        (-P->alpha * 0.5 * (P->ci + P->cj) * mu + P->beta * mu * mu) / (0.5 * (P->rhoi + P->rhoj));
    const double S = P->pi / (P->rhoi * P->rhoi) + P->pj / (P->rhoj * P->rhoj) + Pi;
    const double L = volj * P->fw * r2 / (r2 + eta2);   /* Morris: V_j x.gradW / (r^2 + eta^2) */
    const double mu_j = P->fluid > 0 ? P->muj : P->mui; /* a wall takes the fluid's */
    double rep = 0;
    if (P->fluid == 0 && r2 < P->rep_r0 * P->rep_r0) {
        const double q2 = fmin(P->rep_r0 * P->rep_r0 / r2, 1e3);
        rep = P->rep_d * (pow(q2, 6) - pow(q2, 2)) / r2;
    }
    for (int d = 0; d < 3; ++d)
        a[d] = -P->mj * S * P->fw * P->x[d] + P->visc * (P->mui + mu_j) / P->rhoi * L * vg[d] +
               rep * P->x[d];
    *div = volj * vw * P->fw;
    *diff = P->fluid * (P->rhoj - P->rhoi + P->rho0 * gx / (P->c0 * P->c0)) * L;
    *de = 0.5 * P->mj * S * vx * P->fw;
}

/* The pair function in double (reference density 1000, so that the deviations are exercised)
 * and in single precision against pair_by_hand. */
static void check_pair(const hand_pair *P, const char *what) {
    double a[3], div, diff, de;
    pair_by_hand(P, a, &div, &diff, &de);
    const double rho_ref = 1000.0, fh = P->rho0 / (P->c0 * P->c0);
    const double r2 = P->x[0] * P->x[0] + P->x[1] * P->x[1] + P->x[2] * P->x[2];
    const wc_pair_k_d K = {P->h,    0.01 * P->h * P->h, P->alpha,
                           P->beta, P->rep_d,           P->rep_r0 * P->rep_r0};
    const wc_pair_i_d I = {P->ui[0],
                           P->ui[1],
                           P->ui[2],
                           P->rhoi - rho_ref,
                           2.0 * rho_ref + (P->rhoi - rho_ref),
                           P->pi / (P->rhoi * P->rhoi),
                           P->mui,
                           1.0 / P->rhoi,
                           P->ci,
                           fh * P->g[0],
                           fh * P->g[1],
                           fh * P->g[2]};
    const wc_pair_j_d J = {P->uj[0],
                           P->uj[1],
                           P->uj[2],
                           P->ugj[0],
                           P->ugj[1],
                           P->ugj[2],
                           P->rhoj - rho_ref,
                           P->pj / (P->rhoj * P->rhoj),
                           P->mj / P->rhoj,
                           P->muj,
                           P->cj,
                           P->mj,
                           P->fluid,
                           P->visc};
    const wc_pair_out_d o = wc_pair_d(&K, &I, &J, P->x[0], P->x[1], P->x[2], r2, P->fw, 3, 1, 1);
    /* The same records rounded to single precision. */
    const wc_pair_k_f Kf = {(float)K.h,    (float)K.eta2,  (float)K.alpha,
                            (float)K.beta, (float)K.rep_d, (float)K.rep_r02};
    const wc_pair_i_f If = {(float)I.ux,   (float)I.uy,    (float)I.uz,  (float)I.drho,
                            (float)I.rho2, (float)I.prho2, (float)I.mu,  (float)I.inv_rho,
                            (float)I.cs,   (float)I.fgx,   (float)I.fgy, (float)I.fgz};
    const wc_pair_j_f Jf = {(float)J.ux,  (float)J.uy,   (float)J.uz,    (float)J.ugx, (float)J.ugy,
                            (float)J.ugz, (float)J.drho, (float)J.prho2, (float)J.vol, (float)J.mu,
                            (float)J.cs,  (float)J.mass, (float)J.fluid, (float)J.visc};
    const wc_pair_out_f of = wc_pair_f(&Kf, &If, &Jf, (float)P->x[0], (float)P->x[1],
                                       (float)P->x[2], (float)r2, (float)P->fw, 3, 1, 1);
    const double as = fabs(a[0]) + fabs(a[1]) + fabs(a[2]);
    const double got_d[6] = {o.ax, o.ay, o.az, o.div, o.diff, o.de};
    const double got_f[6] = {of.ax, of.ay, of.az, of.div, of.diff, of.de};
    const double want[6] = {a[0], a[1], a[2], div, diff, de};
    const double scale[6] = {as, as, as, fabs(div), fabs(diff), fabs(de)};
    print_message("%s: a = (%.9g, %.9g, %.9g), div %.9g, diff %.9g, de %.9g\n", what, a[0], a[1],
                  a[2], div, diff, de);
    for (int k = 0; k < 6; ++k) {
        assert_true(fabs(got_d[k] - want[k]) <= 1e-12 * scale[k]);
        assert_true(fabs(got_f[k] - want[k]) <= 2e-6 * scale[k]);
    }
}

static void test_pair_function(void **state) {
    (void)state;
    /* Two fluid particles approaching, sound speeds 12 and 14 m/s, Fourtakas' term. */
    hand_pair P = {{0.1, 0.05, -0.02},
                   {-0.2, 0.0, 0.03},
                   {-0.2, 0.0, 0.03},
                   1010.0,
                   995.0,
                   150.0,
                   -60.0,
                   1.01,
                   0.995,
                   12.0,
                   14.0,
                   1e-3,
                   1.0,
                   1.0,
                   {0.003, -0.004, 0.012},
                   -2.5e6,
                   0.01,
                   0.1,
                   0.2,
                   {0.0, 0.0, -9.81},
                   1000.0,
                   12.0,
                   0.0,
                   0.0};
    check_pair(&P, "fluid pair, approaching");
    /* Receding: no artificial viscosity. */
    for (int d = 0; d < 3; ++d) P.uj[d] = P.ugj[d] = -P.uj[d];
    check_pair(&P, "fluid pair, receding");
    /* A wall neighbour within the repulsion radius: its ghost velocity and viscous factor,
     * the fluid's viscosity, no density diffusion, the repulsion. */
    hand_pair W = P;
    W.fluid = 0.0;
    W.visc = 0.5;
    W.muj = 7.0;
    for (int d = 0; d < 3; ++d) {
        W.uj[d] = 0.0;
        W.ugj[d] = 0.3 - 0.1 * d;
    }
    W.rep_d = 2e-3;
    W.rep_r0 = 0.02;
    check_pair(&W, "wall neighbour, repulsion");
    /* Closer than r0 / sqrt(1e3): the repulsion's cap. */
    for (int d = 0; d < 3; ++d) W.x[d] *= 0.02;
    check_pair(&W, "wall neighbour, repulsion capped");
}

/* The transport-velocity pair by hand: m_i dv_i/dt gains (V_i^2 + V_j^2) (-p~ fw x + 1/2 (rho_i
 * v_i (v~_i - v_i) + rho_j v_j (v~_j - v_j)) . fw x + eta_ij (v_i - vg_j) fw) plus the
 * repulsion times m_i, and the background sum (V_i^2 + V_j^2) fw x. */
static void check_tvf(const wc_tvf_rec *I, const wc_tvf_rec *J, const double x[3], double fw,
                      double r02, double D, const char *what) {
    const double r2 = x[0] * x[0] + x[1] * x[1] + x[2] * x[2], vv = I->vol2 + J->vol2;
    const double pt = (J->rho * I->p + I->rho * J->p) / (I->rho + J->rho);
    const double mj = J->fluid > 0 ? J->mu : I->mu, eta = 2.0 * I->mu * mj / (I->mu + mj);
    double Ai = 0, Aj = 0;
    for (int d = 0; d < 3; ++d) {
        Ai += I->dv[d] * x[d] * fw;
        Aj += J->fluid * J->dv[d] * x[d] * fw;
    }
    double rep = 0;
    if (J->fluid == 0 && r2 < r02) {
        const double q2 = fmin(r02 / r2, 1e3);
        rep = D * (pow(q2, 6) - pow(q2, 2)) / r2;
    }
    const wc_tvf_out o = wc_tvf_pair(I, J, x, r2, fw, 3, r02, D);
    for (int d = 0; d < 3; ++d) {
        const double a =
            vv * (-pt * fw * x[d] + 0.5 * (I->rho * I->v[d] * Ai + J->rho * J->v[d] * Aj) +
                  J->visc * eta * (I->v[d] - J->vg[d]) * fw) +
            rep * I->mass * x[d];
        const double b = vv * fw * x[d];
        print_message("%s: a[%d] = %.9g (%.9g), b[%d] = %.9g\n", what, d, o.a[d], a, d, b);
        assert_true(fabs(o.a[d] - a) <= 1e-12 * fabs(a));
        assert_true(fabs(o.b[d] - b) <= 1e-12 * fabs(b));
    }
}

static void test_tvf_pair_function(void **state) {
    (void)state;
    const wc_tvf_rec I = {{0.1, 0.05, -0.02},
                          {0.1, 0.05, -0.02},
                          {0.01, -0.02, 0.005},
                          1010.0,
                          150.0,
                          1.01,
                          1e-12,
                          1e-3,
                          1.0,
                          1.0};
    wc_tvf_rec J = {{-0.2, 0.0, 0.03},
                    {-0.2, 0.0, 0.03},
                    {-0.03, 0.01, 0.02},
                    995.0,
                    -60.0,
                    3.0,
                    1.1e-12,
                    1e-3,
                    1.0,
                    1.0};
    const double x[3] = {0.003, -0.004, 0.012};
    check_tvf(&I, &J, x, -2.5e6, 0.0, 0.0, "tvf, fluid pair");
    /* A wall: no extra stress, the fluid's viscosity, its ghost velocity and viscous factor,
     * the repulsion. */
    J.fluid = 0.0;
    J.visc = 0.5;
    J.vg[0] = 0.4;
    check_tvf(&I, &J, x, -2.5e6, 0.02 * 0.02, 2e-3, "tvf, wall neighbour");
}

static void test_list_loop(void **state) {
    (void)state;
    check_loop("list", 1e-12);
}

static void test_cell_loop(void **state) {
    (void)state;
    check_loop("cells", 2e-6);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_list_loop),
        cmocka_unit_test(test_cell_loop),
        cmocka_unit_test(test_pair_function),
        cmocka_unit_test(test_tvf_pair_function),
    };
    return cmocka_run_group_tests(tests, make_tmpdir, remove_tmpdir);
}
