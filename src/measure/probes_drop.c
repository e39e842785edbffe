/* Probes of drops: width, inner pressure and the Laplace jump, contact angle of a sessile drop,
 * and the pressure solver's iterations (listed by `ryushi probes`). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "measure/probes_internal.h"
#include "ryushi/probes.h"
#include "ryushi/surface_tension.h"

/* Centroid of the fluid particles; returns their number. */
static size_t fluid_centroid_of(const ry_sim *sim, int mat, double *c) {
    const ry_particles *ps = &sim->ps;
    size_t nf = 0;
    c[0] = c[1] = c[2] = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || (mat >= 0 && ps->material[i] != mat)) continue;
        for (int d = 0; d < sim->dim; ++d) c[d] += ps->f[RY_F_X + d][i];
        ++nf;
    }
    for (int d = 0; d < sim->dim && nf; ++d) c[d] /= (double)nf;
    return nf;
}

static size_t fluid_centroid(const ry_sim *sim, double *c) {
    return fluid_centroid_of(sim, -1, c);
}

static int cmp_double(const void *a, const void *b) {
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Width of a drop along x through its centroid: the fluid particles within 1.5 spacings of the
 * x axis through the centroid, sorted by x; from the one nearest the centroid the body extends
 * while neighbours are at most 3 spacings apart (particles thrown off do not count); the width
 * is the extent of that body plus one spacing. */
static ry_status width_x_of(const ry_sim *sim, int mat, double *v, ry_error *err) {
    const ry_particles *ps = &sim->ps;
    double c[3];
    *v = NAN;
    if (fluid_centroid_of(sim, mat, c) == 0) return RY_OK;
    double *xs = malloc((ps->n + 1) * sizeof *xs);
    RY_CHECK(err, xs != NULL, RY_ERR_NOMEM, "out of memory (width_x)");
    size_t k = 0;
    const double band = 1.5 * sim->dx;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || (mat >= 0 && ps->material[i] != mat)) continue;
        int in = 1;
        for (int d = 1; d < sim->dim; ++d) in &= fabs(ps->f[RY_F_X + d][i] - c[d]) < band;
        if (in) xs[k++] = ps->f[RY_F_X][i];
    }
    if (k > 0) {
        qsort(xs, k, sizeof *xs, cmp_double);
        size_t m = 0;
        for (size_t q = 1; q < k; ++q)
            if (fabs(xs[q] - c[0]) < fabs(xs[m] - c[0])) m = q;
        size_t lo = m, hi = m;
        while (lo > 0 && xs[lo] - xs[lo - 1] <= 3 * sim->dx) --lo;
        while (hi + 1 < k && xs[hi + 1] - xs[hi] <= 3 * sim->dx) ++hi;
        *v = xs[hi] - xs[lo] + sim->dx;
    }
    free(xs);
    return RY_OK;
}

static ry_status probe_width_x(const ry_sim *sim, double *v, ry_error *err) {
    return width_x_of(sim, -1, v, err);
}

/* The same for the particles of the second material (a drop inside another liquid). */
static ry_status probe_width_x_second(const ry_sim *sim, double *v, ry_error *err) {
    RY_CHECK(err, sim->nmat >= 2, RY_ERR_INPUT,
             "measurement 'width_x_second' needs two materials (it measures the second)");
    return width_x_of(sim, 1, v, err);
}

/* Mean pressure of the fluid particles within half the equivalent radius of the fluid's
 * centroid (a drop: R from the fluid volume N dx^d). */
/* Mean pressure of the fluid particles of material mat (-1: any) at a distance from c in
 * [r_lo, r_hi). */
static double mean_pressure_around(const ry_sim *sim, int mat, const double *c, double r_lo,
                                   double r_hi) {
    const ry_particles *ps = &sim->ps;
    double s = 0;
    size_t k = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || (mat >= 0 && ps->material[i] != mat)) continue;
        double r2 = 0;
        for (int d = 0; d < sim->dim; ++d) {
            const double e = ps->f[RY_F_X + d][i] - c[d];
            r2 += e * e;
        }
        if (r2 >= r_lo * r_lo && r2 < r_hi * r_hi) {
            s += ps->f[RY_F_P][i];
            ++k;
        }
    }
    return k ? s / (double)k : NAN;
}

/* The equivalent radius of nf particles (circle or sphere of their volume). */
static double equivalent_radius(const ry_sim *sim, size_t nf) {
    const double vol = (double)nf * pow(sim->dx, sim->dim);
    return sim->dim == 2 ? sqrt(vol / RY_PI) : cbrt(3 * vol / (4 * RY_PI));
}

static ry_status probe_drop_pressure(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    double c[3];
    const size_t nf = fluid_centroid(sim, c);
    *v = nf ? mean_pressure_around(sim, -1, c, 0.0, 0.5 * equivalent_radius(sim, nf)) : NAN;
    return RY_OK;
}

/* A drop of the second material in the first: the mean pressure within half its equivalent
 * radius of its centroid less that of the first material more than 5 spacings outside it. */
static ry_status probe_pressure_jump_second(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    double c[3];
    const size_t nf = sim->nmat > 1 ? fluid_centroid_of(sim, 1, c) : 0;
    if (nf == 0) {
        *v = NAN;
        return RY_OK;
    }
    const double R = equivalent_radius(sim, nf);
    *v = mean_pressure_around(sim, 1, c, 0.0, 0.5 * R) -
         mean_pressure_around(sim, 0, c, R + 5 * sim->dx, INFINITY);
    return RY_OK;
}

static ry_status probe_ppe_iterations(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    if (!ry_scheme_stat(sim, "pressure_iterations", v)) *v = 0;
    return RY_OK;
}

double ry_cap_contact_angle(int dim, double h, double size) {
    if (!(h > 0) || !(size > 0)) return NAN;
    if (dim > 2) {
        const double q = RY_PI * h * h * h / (3.0 * size);
        return acos(fmax(-1.0, fmin(1.0, (1.0 - 2.0 * q) / (1.0 + q)))) * 180.0 / RY_PI;
    }
    const double target = h * h / size; /* rises from 0 (theta = 0) to 4/pi (theta = pi) */
    if (target >= 4.0 / RY_PI) return 180.0;
    double lo = 1e-9, hi = RY_PI;
    for (int it = 0; it < 100; ++it) {
        const double t = 0.5 * (lo + hi), c = cos(t);
        if ((1 - c) * (1 - c) / (t - sin(t) * c) < target)
            lo = t;
        else
            hi = t;
    }
    return 0.5 * (lo + hi) * 180.0 / RY_PI;
}

/* Whether fluid particle i of the second material has a particle of another fluid material
 * within 1.5 spacings: the outer layer of a drop of it in the first. */
static int on_interface(const ry_sim *sim, size_t i) {
    const ry_particles *ps = &sim->ps;
    const double reach2 = 2.25 * sim->dx * sim->dx;
    for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
        const uint32_t j = sim->nl.j[q];
        if (ps->kind[j] != RY_KIND_FLUID || ps->material[j] == ps->material[i]) continue;
        double e[3] = {0, 0, 0}, r2 = 0;
        for (int d = 0; d < sim->dim; ++d) e[d] = ps->f[RY_F_X + d][j] - ps->f[RY_F_X + d][i];
        ry_box_min_image(&sim->box, e);
        for (int d = 0; d < sim->dim; ++d) r2 += e[d] * e[d];
        if (r2 < reach2) return 1;
    }
    return 0;
}

/* Sessile drop on a floor (walls below the fluid along the last axis, "up"): a circle (2D) or
 * sphere (3D) fitted by least squares (Kasa's algebraic fit: |x|^2 + D.x + F = 0, linear in D
 * and F) to the drop's surface more than two spacings above the floor's surface (its top wall
 * layer plus half a spacing); the radius is that fit's plus half a spacing (the surface layer
 * sits half a spacing inside the surface), and cos theta = -h_c / R with h_c the centre's
 * height above the floor. mat < 0: the fluid's free-surface particles; mat >= 0: a drop of
 * that material in another liquid, its particles beside the other (on_interface). */
static void contact_angle_of(const ry_sim *sim, int mat, double *v) {
    const ry_particles *ps = &sim->ps;
    const int dim = sim->dim, up = dim - 1, fs = ry_particles_field(ps, "free_surface");
    *v = NAN;
    if (fs < 0 && mat < 0) return;
    /* Only the surface within 2 equivalent radii of the drop's centroid (not a particle thrown
     * off). */
    double cen[3];
    const size_t nf = fluid_centroid_of(sim, mat, cen);
    if (nf == 0 || (mat >= 0 && sim->nl.offset == NULL)) return;
    const double vol = (double)nf * pow(sim->dx, dim);
    const double reach = 2 * (dim == 2 ? sqrt(vol / RY_PI) : cbrt(3 * vol / (4 * RY_PI)));
    /* The floor: the top wall layer below the centroid and within reach of it sideways (not
     * the side walls of a tank). */
    double top_wall = -INFINITY;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_WALL || ps->f[RY_F_X + up][i] > cen[up]) continue;
        double e2 = 0;
        for (int d = 0; d < up; ++d) e2 += pow(ps->f[RY_F_X + d][i] - cen[d], 2);
        if (e2 < reach * reach) top_wall = fmax(top_wall, ps->f[RY_F_X + up][i]);
    }
    if (!isfinite(top_wall)) return;
    const double floor = top_wall + 0.5 * sim->dx;
    /* Normal equations of sum (|x|^2 + D.x + F)^2 -> min over (D, F): unknowns u = (D, F). */
    double A[4][4] = {{0}}, b[4] = {0};
    const int nu = dim + 1;
    size_t k = 0;
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        if (mat < 0 ? ps->f[fs][i] < 0.5 : ps->material[i] != mat || !on_interface(sim, i))
            continue;
        if (ps->f[RY_F_X + up][i] < floor + 2 * sim->dx) continue;
        double row[4], r2 = 0, e2 = 0;
        for (int d = 0; d < dim; ++d) {
            const double e = ps->f[RY_F_X + d][i] - cen[d];
            e2 += e * e;
        }
        if (e2 > reach * reach) continue;
        for (int d = 0; d < dim; ++d) {
            row[d] = ps->f[RY_F_X + d][i];
            r2 += row[d] * row[d];
        }
        row[dim] = 1.0;
        for (int a = 0; a < nu; ++a) {
            b[a] -= row[a] * r2;
            for (int c = 0; c < nu; ++c) A[a][c] += row[a] * row[c];
        }
        ++k;
    }
    if (k < (size_t)(3 * nu)) return;
    /* Gaussian elimination with partial pivoting. */
    for (int c = 0; c < nu; ++c) {
        int p = c;
        for (int r = c + 1; r < nu; ++r)
            if (fabs(A[r][c]) > fabs(A[p][c])) p = r;
        for (int q = 0; q < nu; ++q) {
            const double t = A[c][q];
            A[c][q] = A[p][q];
            A[p][q] = t;
        }
        const double t = b[c];
        b[c] = b[p];
        b[p] = t;
        if (fabs(A[c][c]) < 1e-300) return;
        for (int r = c + 1; r < nu; ++r) {
            const double f = A[r][c] / A[c][c];
            for (int q = c; q < nu; ++q) A[r][q] -= f * A[c][q];
            b[r] -= f * b[c];
        }
    }
    double u[4];
    for (int r = nu - 1; r >= 0; --r) {
        double s = b[r];
        for (int q = r + 1; q < nu; ++q) s -= A[r][q] * u[q];
        u[r] = s / A[r][r];
    }
    double c2 = 0;
    for (int d = 0; d < dim; ++d) c2 += 0.25 * u[d] * u[d];
    const double R2 = c2 - u[dim];
    if (!(R2 > 0)) return;
    const double R = sqrt(R2) + 0.5 * sim->dx, hc = -0.5 * u[up] - floor;
    *v = acos(fmax(-1.0, fmin(1.0, -hc / R))) * 180.0 / RY_PI;
}

static ry_status probe_contact_angle(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    contact_angle_of(sim, -1, v);
    return RY_OK;
}

static ry_status probe_contact_angle_second(const ry_sim *sim, double *v, ry_error *err) {
    (void)err;
    *v = NAN;
    if (sim->nmat > 1) contact_angle_of(sim, 1, v);
    return RY_OK;
}

const ry_probe ry_probe_width_x = {
    "width_x",
    "drop width along x through the fluid's centroid [m] (the body within 1.5 spacings of the "
    "axis, particles thrown off left out, plus one spacing)",
    probe_width_x, NULL, 0};
const ry_probe ry_probe_width_x_second = {
    "width_x_second",
    "width along x through its centroid of the second material's body (as width_x) [m]",
    probe_width_x_second, NULL, 0};
const ry_probe ry_probe_drop_pressure = {
    "drop_pressure",
    "mean pressure of the fluid within half the equivalent radius of its centroid [Pa]",
    probe_drop_pressure, NULL, 0};
const ry_probe ry_probe_pressure_jump_second = {
    "pressure_jump_second",
    "drop of the second material in the first: mean pressure within half its equivalent radius "
    "of its centroid less the first material's beyond 5 spacings outside it [Pa]",
    probe_pressure_jump_second, NULL, 0};
const ry_probe ry_probe_contact_angle = {
    "contact_angle",
    "sessile drop on a floor: contact angle [degrees] of a circle (sphere) fitted to the free "
    "surface more than two spacings above the floor",
    probe_contact_angle, NULL, 0};
const ry_probe ry_probe_contact_angle_second = {
    "contact_angle_second",
    "sessile drop of the second material in the first, on a floor: contact angle [degrees] "
    "through the drop, of a circle (sphere) fitted to its particles beside the first liquid "
    "more than two spacings above the floor",
    probe_contact_angle_second, NULL, 0};
const ry_probe ry_probe_ppe_iterations = {
    "ppe_iterations", "scheme mps: conjugate-gradient iterations of the last pressure solve",
    probe_ppe_iterations, NULL, 0};
