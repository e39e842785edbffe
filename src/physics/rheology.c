/* Rheology models of a material (include/ryushi/rheology.h, docs/reference/rheology.md). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ryushi/rheology.h"

const char *const ry_rheology_names[] = {"newtonian", "power_law", "carreau",
                                         "oldroyd_b", "giesekus",  NULL};

static ry_status key_double(ry_case *c, const char *prefix, const char *key, const double *def,
                            double lo, double hi, double *out, ry_error *err) {
    char k[160];
    snprintf(k, sizeof k, "%s.rheology.%s", prefix, key);
    return ry_case_double(c, k, def, lo, hi, out, err);
}

ry_status ry_rheology_read(ry_case *c, const char *prefix, ry_rheology *r, ry_error *err) {
    char k[160], where[256];
    memset(r, 0, sizeof *r);
    snprintf(k, sizeof k, "%s.rheology.model", prefix);
    RY_TRY(ry_case_choice(c, k, "newtonian", ry_rheology_names, &r->model, err));
    const double zero = 0;
    switch (r->model) {
    case RY_RHEO_POWER_LAW:
        RY_TRY(key_double(c, prefix, "consistency", NULL, 1e-300, INFINITY, &r->consistency, err));
        RY_TRY(key_double(c, prefix, "index", NULL, 0.05, 3.0, &r->index, err));
        RY_TRY(key_double(c, prefix, "viscosity_min", &zero, 0.0, INFINITY, &r->nu_min, err));
        /* Required: at rest a shear-thinning fluid's viscosity is unbounded, and a
         * shear-thickening one's grows without bound with the rate. */
        RY_TRY(key_double(c, prefix, "viscosity_max", NULL, 1e-300, INFINITY, &r->nu_max, err));
        snprintf(k, sizeof k, "%s.rheology.viscosity_max", prefix);
        RY_CHECK(err, r->nu_max > r->nu_min, RY_ERR_INPUT,
                 "%s: key '%s': must exceed viscosity_min (%g)",
                 ry_case_where(c, k, where, sizeof where), k, r->nu_min);
        break;
    case RY_RHEO_CARREAU:
        RY_TRY(key_double(c, prefix, "viscosity_zero", NULL, 1e-300, INFINITY, &r->nu_zero, err));
        RY_TRY(key_double(c, prefix, "viscosity_infinity", &zero, 0.0, INFINITY, &r->nu_inf, err));
        RY_TRY(key_double(c, prefix, "time", NULL, 0.0, INFINITY, &r->time, err));
        RY_TRY(key_double(c, prefix, "index", NULL, 0.05, 1.0, &r->index, err));
        break;
    case RY_RHEO_OLDROYD_B:
    case RY_RHEO_GIESEKUS:
        RY_TRY(
            key_double(c, prefix, "polymer_viscosity", NULL, 0.0, INFINITY, &r->nu_polymer, err));
        RY_TRY(
            key_double(c, prefix, "relaxation_time", NULL, 1e-300, INFINITY, &r->relaxation, err));
        /* Above 1/2 the steady shear stress falls with the rate (an unstable constitutive
         * branch). */
        if (r->model == RY_RHEO_GIESEKUS)
            RY_TRY(key_double(c, prefix, "mobility", NULL, 0.0, 0.5, &r->mobility, err));
        break;
    default:
        break;
    }
    return RY_OK;
}

int ry_rheology_viscoelastic(const ry_rheology *r) {
    return r->model == RY_RHEO_OLDROYD_B || r->model == RY_RHEO_GIESEKUS;
}

int ry_rheology_generalised(const ry_rheology *r) {
    return r->model == RY_RHEO_POWER_LAW || r->model == RY_RHEO_CARREAU;
}

double ry_rheology_nu(const ry_rheology *r, double nu_newtonian, double gd) {
    switch (r->model) {
    case RY_RHEO_POWER_LAW: {
        /* k gd^(n-1), bounded; at gd = 0 the bound the exponent's sign picks. */
        const double nu = gd > 0 ? r->consistency * pow(gd, r->index - 1.0)
                                 : (r->index < 1   ? INFINITY
                                    : r->index > 1 ? 0.0
                                                   : r->consistency);
        return fmin(fmax(nu, r->nu_min), r->nu_max);
    }
    case RY_RHEO_CARREAU: {
        const double tg = r->time * gd;
        return r->nu_inf + (r->nu_zero - r->nu_inf) * pow(1.0 + tg * tg, 0.5 * (r->index - 1.0));
    }
    default:
        return nu_newtonian;
    }
}

double ry_rheology_nu_max(const ry_rheology *r, double nu_newtonian) {
    switch (r->model) {
    case RY_RHEO_POWER_LAW:
        return r->nu_max;
    case RY_RHEO_CARREAU:
        return fmax(r->nu_zero, r->nu_inf);
    default:
        return nu_newtonian;
    }
}

double ry_rheology_shear_nu(const ry_rheology *r, double nu_newtonian, double gd) {
    if (!ry_rheology_viscoelastic(r)) return ry_rheology_nu(r, nu_newtonian, gd);
    /* Oldroyd-B is alpha = 0: q = 0, f = 0, the polymer's nu_p at every rate */
    const double a = r->model == RY_RHEO_GIESEKUS ? r->mobility : 0.0;
    const double wi = r->relaxation * gd, q = 8.0 * a * (1.0 - a) * wi * wi;
    /* chi^2 = (sqrt(1 + 2q) - 1) / q, written without the cancellation at small q */
    const double chi = q > 0 ? sqrt(2.0 / (sqrt(1.0 + 2.0 * q) + 1.0)) : 1.0;
    const double f = (1.0 - chi) / (1.0 + (1.0 - 2.0 * a) * chi);
    return nu_newtonian + r->nu_polymer * (1.0 - f) * (1.0 - f) / (1.0 + (1.0 - 2.0 * a) * f);
}

/* The symmetric polymer stress by components: in 2D xx, yy, xy; in 3D xx, yy, zz, xy, xz, yz. */
static const int tau_a[6] = {0, 1, 2, 0, 0, 1}, tau_b[6] = {0, 1, 2, 1, 2, 2};

int ry_tau_count(int dim) {
    return dim == 2 ? 3 : 6;
}

void ry_tau_index(int dim, int k, int *a, int *b) {
    const int c = dim == 2 && k == 2 ? 3 : k;
    *a = tau_a[c];
    *b = tau_b[c];
}

unsigned ry_tau_odd(int dim, int k) {
    int a, b;
    ry_tau_index(dim, k, &a, &b);
    return (1u << a) ^ (1u << b);
}

const char *ry_tau_name(int dim, int k) {
    static const char *const names[6] = {"tau_xx", "tau_yy", "tau_zz",
                                         "tau_xy", "tau_xz", "tau_yz"};
    return names[dim == 2 && k == 2 ? 3 : k];
}

double ry_tau_norm2(int dim, const double *tau) {
    double n2 = 0;
    for (int k = 0; k < ry_tau_count(dim); ++k) {
        int p, q;
        ry_tau_index(dim, k, &p, &q);
        n2 += (p == q ? 1.0 : 2.0) * tau[k] * tau[k];
    }
    return n2;
}

/* Index of the stored component of tau_pq (p, q < dim). */
static int tau_component(int dim, int p, int q) {
    if (p == q) return p;
    const int lo = p < q ? p : q, hi = p < q ? q : p;
    if (dim == 2) return 2;
    return lo == 0 ? 2 + hi : 5; /* xy 3, xz 4, yz 5 */
}

/* Solves the n x n system A x = b (row-major, n <= 6) by elimination with partial pivoting;
 * A and b are overwritten. Returns 0 if a pivot is not positive and finite in size. */
static int solve_small(int n, double *A, double *b) {
    for (int c = 0; c < n; ++c) {
        int piv = c;
        for (int r = c + 1; r < n; ++r)
            if (fabs(A[r * n + c]) > fabs(A[piv * n + c])) piv = r;
        if (!(fabs(A[piv * n + c]) > 0) || !isfinite(A[piv * n + c])) return 0;
        if (piv != c) {
            for (int k = 0; k < n; ++k) {
                const double t = A[c * n + k];
                A[c * n + k] = A[piv * n + k];
                A[piv * n + k] = t;
            }
            const double t = b[c];
            b[c] = b[piv];
            b[piv] = t;
        }
        for (int r = c + 1; r < n; ++r) {
            const double f = A[r * n + c] / A[c * n + c];
            for (int k = c; k < n; ++k) A[r * n + k] -= f * A[c * n + k];
            b[r] -= f * b[c];
        }
    }
    for (int r = n - 1; r >= 0; --r) {
        double s = b[r];
        for (int k = r + 1; k < n; ++k) s -= A[r * n + k] * b[k];
        b[r] = s / A[r * n + r];
    }
    return 1;
}

/* One step of the stress equation (ry_polymer_step) with mobility a (0: Oldroyd-B). The
 * upper-convected term K tau = L tau + tau L^T and the relaxation are taken at the midpoint
 * (Crank-Nicolson; the relaxation's weight th moves towards implicit where dt exceeds lambda,
 * so that its factor stays positive), the quadratic term explicit:
 *   (1 + th dt/lambda - dt/2 K) tau' = (1 - (1 - th) dt/lambda + dt/2 K) tau
 *                                      + dt (2 eta_p D / lambda - a/eta_p tau . tau).
 * A steady state of the equation is one of the step; a rotation (L antisymmetric) turns tau
 * without stretching it, where an explicit term multiplied its size by sqrt(1 + (dt omega)^2)
 * every step. */
static void polymer_substep(int dim, const double L[9], const double *K, double eta_p,
                            double lambda, double a, double dt, double *tau) {
    const int nt = ry_tau_count(dim);
    const double th = fmax(0.5, 1.0 - 0.5 * lambda / dt);
    double t[3][3] = {{0}}, A[36], b[6];
    for (int k = 0; k < nt; ++k) {
        int p, q;
        ry_tau_index(dim, k, &p, &q);
        t[p][q] = t[q][p] = tau[k];
    }
    for (int k = 0; k < nt; ++k) {
        int p, q;
        ry_tau_index(dim, k, &p, &q);
        double kt = 0, tt = 0; /* (K tau)_pq and (tau . tau)_pq */
        for (int m = 0; m < nt; ++m) kt += K[k * nt + m] * tau[m];
        for (int c = 0; c < dim; ++c) tt += t[p][c] * t[c][q];
        const double dpq = 0.5 * (L[3 * p + q] + L[3 * q + p]);
        b[k] = (1.0 - (1.0 - th) * dt / lambda) * tau[k] +
               dt * (0.5 * kt + 2.0 * eta_p * dpq / lambda - (a > 0 ? a / eta_p * tt : 0));
        for (int m = 0; m < nt; ++m)
            A[k * nt + m] = (k == m ? 1.0 + th * dt / lambda : 0.0) - 0.5 * dt * K[k * nt + m];
    }
    if (solve_small(nt, A, b))
        for (int k = 0; k < nt; ++k) tau[k] = b[k];
}

void ry_polymer_step(int dim, const ry_rheology *r, const double L[9], double rho, double dt,
                     double *tau) {
    const double eta_p = rho * r->nu_polymer;
    const double a = r->model == RY_RHEO_GIESEKUS && eta_p > 0 ? r->mobility : 0.0;
    const int nt = ry_tau_count(dim);
    /* K tau = L tau + tau L^T on the stored components: (K tau)_pq = sum_c L_pc tau_cq +
     * tau_pc L_qc. It holds for every part of the step. */
    double K[36] = {0};
    for (int k = 0; k < nt; ++k) {
        int p, q;
        ry_tau_index(dim, k, &p, &q);
        for (int c = 0; c < dim; ++c) {
            K[k * nt + tau_component(dim, c, q)] += L[3 * p + c];
            K[k * nt + tau_component(dim, p, c)] += L[3 * q + c];
        }
    }
    /* Parts: dt |L| <= 1 keeps the matrix of the step regular (|dt/2 K| <= dt |L|_F <= 1 against
     * the diagonal 1 + th dt/lambda), and dt alpha |tau| / eta_p <= 1/4 the quadratic term's
     * explicit part stable. */
    double l2 = 0; /* |L|_F^2 */
    for (int k = 0; k < 9; ++k) l2 += L[k] * L[k];
    const double x =
        fmax(dt * sqrt(l2), a > 0 ? 4.0 * dt * a * sqrt(ry_tau_norm2(dim, tau)) / eta_p : 0.0);
    const int parts = x > 1 ? (int)fmin(ceil(x), 1000.0) : 1;
    for (int s = 0; s < parts; ++s)
        polymer_substep(dim, L, K, eta_p, r->relaxation, a, dt / parts, tau);
}
