/* Surface tension for particle methods: CSF after Nomura et al. (2001) and the potential model
 * of Kondo et al. (2007), seed 003 eq. 9-12. See include/ryushi/surface_tension.h. */
#include <math.h>
#include <stdlib.h>

#include "ryushi/surface_tension.h"

const char *const ry_st_model_names[] = {"none", "csf", "potential", NULL};

double ry_st_potential_f(double r, double l0, double re) {
    return r <= re ? (r - l0) * (r - re) : 0.0;
}

double ry_st_potential_phi(double r, double l0, double re) {
    if (r > re) return 0.0;
    const double s = r - re;
    return (1.0 / 3.0) * (1.5 * l0 - 0.5 * re - r) * s * s;
}

/* Largest lattice offset (in spacings) within re along one axis. */
static int lattice_extent(double l0, double re) {
    return (int)floor(re / l0 + 1e-9);
}

double ry_st_potential_pair_sum(int dim, double l0, double re) {
    /* Site i of A at height -(a + 1/2) l0 (a >= 0), site j of B at +(b + 1/2) l0 (b >= 0): the
     * normal distance is s = a + b + 1 spacings, reached by s pairs (a, b). j runs over all
     * lateral offsets. */
    const int K = lattice_extent(l0, re);
    double sum = 0.0;
    for (int s = 1; s <= K; ++s)
        for (int u = -K; u <= K; ++u)
            for (int v = (dim > 2 ? -K : 0); v <= (dim > 2 ? K : 0); ++v) {
                const double r = l0 * sqrt((double)(s * s + u * u + v * v));
                sum += s * ry_st_potential_phi(r, l0, re);
            }
    return sum;
}

double ry_st_potential_coefficient(int dim, double l0, double re, double sigma) {
    const double area = dim > 2 ? l0 * l0 : l0; /* per unit depth in 2D */
    return 2.0 * sigma * area / ry_st_potential_pair_sum(dim, l0, re);
}

/* CSF lattice constants: neighbours within re (self excluded), and the fraction of them at or
 * below the plane of a particle on a flat surface. */
static void csf_lattice(int dim, double l0, double re, double *count0, double *flat) {
    const int K = lattice_extent(l0, re);
    long all = 0, below = 0;
    for (int s = -K; s <= K; ++s)
        for (int u = -K; u <= K; ++u)
            for (int v = (dim > 2 ? -K : 0); v <= (dim > 2 ? K : 0); ++v) {
                if (s == 0 && u == 0 && v == 0) continue;
                if (l0 * sqrt((double)(s * s + u * u + v * v)) >= re) continue;
                ++all;
                if (s <= 0) ++below;
            }
    *count0 = (double)all;
    *flat = (double)below / (double)all;
}

ry_status ry_st_setup(ry_surface_tension *st, int model, int dim, double l0, double re,
                      double sigma, ry_error *err) {
    RY_CHECK(err, dim == 2 || dim == 3, RY_ERR_INPUT, "surface tension needs 2 or 3 dimensions");
    RY_CHECK(err, l0 > 0 && re > l0 && sigma >= 0, RY_ERR_INPUT,
             "surface tension: need spacing > 0, radius > spacing and sigma >= 0");
    st->model = model;
    st->dim = dim;
    st->sigma = sigma;
    st->l0 = l0;
    st->re = re;
    st->C = ry_st_potential_coefficient(dim, l0, re, sigma);
    csf_lattice(dim, l0, re, &st->count0, &st->flat_fraction);
    return RY_OK;
}

/* Curvature of the surface through a particle after Nomura et al. (2001): the fluid seen
 * within re fills a sector (2D) or cone (3D) of half-angle theta about the inward normal; a
 * surface of radius R through the particle cuts the circle of radius re at cos(theta) =
 * re / (2R). The fraction seen is shifted by that of a flat surface less one half (the
 * particle's centre lies half a spacing inside the surface). kappa = 1/R (2D), 2/R (3D). */
static double csf_curvature(const ry_surface_tension *st, double count) {
    double f = count / st->count0 - (st->flat_fraction - 0.5);
    f = fmin(fmax(f, 0.0), 1.0);
    if (st->dim == 2) return 2.0 * cos(RY_PI * f) / st->re;
    return 4.0 * (1.0 - 2.0 * f) / st->re;
}

/* Inward sum of particle i over the fluid within re: sum_j w (x_j - x_i)/r (CSF; w the Tamai
 * weight) or the potential force sum_j f(r) (x_j - x_i)/r; *count receives the neighbours. */
static void st_sums(const ry_surface_tension *st, const ry_sim *sim, size_t i, double *s,
                    double *count) {
    const ry_particles *ps = &sim->ps;
    const int dim = sim->dim, csf = st->model == RY_ST_CSF;
    const double re = st->re, re2 = re * re;
    s[0] = s[1] = s[2] = 0;
    *count = 0;
    for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
        const uint32_t j = sim->nl.j[q];
        if (ps->kind[j] != RY_KIND_FLUID) continue;
        double dx[3] = {0, 0, 0}, r2 = 0;
        for (int d = 0; d < dim; ++d) dx[d] = ps->f[RY_F_X + d][j] - ps->f[RY_F_X + d][i];
        ry_box_min_image(&sim->box, dx);
        for (int d = 0; d < dim; ++d) r2 += dx[d] * dx[d];
        if (r2 >= re2 || r2 <= 0) continue;
        const double r = sqrt(r2);
        const double f = csf ? ry_mps_weight_tamai(r, re) : ry_st_potential_f(r, st->l0, re);
        *count += 1.0;
        for (int d = 0; d < dim; ++d) s[d] += f * dx[d] / r;
    }
}

/* Curvature of every surface particle (0 elsewhere): Nomura's estimate, averaged over the
 * surface particles within re (weights w, the particle itself with weight 1) to damp the noise
 * of the count. */
void ry_st_curvature(const ry_surface_tension *st, const ry_sim *sim, const double *surface,
                     double *kappa) {
    const ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const size_t n = ps->n;
    double *raw = kappa + n; /* second half of the caller's 2 n */
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        raw[i] = 0;
        if (ps->kind[i] != RY_KIND_FLUID || !(surface && surface[i] != 0.0)) continue;
        double s[3], count;
        st_sums(st, sim, i, s, &count);
        /* A particle that sees much more than half a neighbourhood lies below the surface
         * layer (flagged by a passing dip of its number density): no estimate. */
        raw[i] =
            count / st->count0 - (st->flat_fraction - 0.5) > 0.6 ? NAN : csf_curvature(st, count);
    }
    const double re2 = st->re * st->re;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        kappa[i] = 0;
        if (ps->kind[i] != RY_KIND_FLUID || !(surface && surface[i] != 0.0)) continue;
        double ks = isnan(raw[i]) ? 0.0 : raw[i], ws = isnan(raw[i]) ? 0.0 : 1.0;
        for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
            const uint32_t j = sim->nl.j[q];
            if (ps->kind[j] != RY_KIND_FLUID || !(surface[j] != 0.0) || isnan(raw[j])) continue;
            double dx[3] = {0, 0, 0}, r2 = 0;
            for (int d = 0; d < dim; ++d) dx[d] = ps->f[RY_F_X + d][j] - ps->f[RY_F_X + d][i];
            ry_box_min_image(&sim->box, dx);
            for (int d = 0; d < dim; ++d) r2 += dx[d] * dx[d];
            if (r2 >= re2) continue;
            const double w = ry_mps_weight_tamai(sqrt(r2), st->re);
            ks += w * raw[j];
            ws += w;
        }
        kappa[i] = ws > 0 ? ks / ws : 0.0;
    }
}

ry_status ry_st_accelerate(const ry_surface_tension *st, const ry_sim *sim, const double *surface,
                           double *const a[3], ry_error *err) {
    if (st->model == RY_ST_NONE || st->sigma == 0.0) return RY_OK;
    const ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const size_t n = ps->n;
    const double l0 = st->l0, area = dim > 2 ? l0 * l0 : l0;
    const double *m = ps->f[RY_F_MASS];
    if (st->model == RY_ST_POTENTIAL) {
#pragma omp parallel for schedule(dynamic, 64)
        for (size_t i = 0; i < n; ++i) {
            if (ps->kind[i] != RY_KIND_FLUID) continue;
            double s[3], count;
            st_sums(st, sim, i, s, &count);
            for (int d = 0; d < dim; ++d) a[d][i] += st->C * s[d] / m[i];
        }
        return RY_OK;
    }
    double *kappa = malloc(2 * n * sizeof *kappa);
    RY_CHECK(err, kappa != NULL, RY_ERR_NOMEM, "out of memory (surface tension)");
    ry_st_curvature(st, sim, surface, kappa);
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || !(surface && surface[i] != 0.0)) continue;
        double s[3], count;
        st_sums(st, sim, i, s, &count);
        double norm = 0;
        for (int d = 0; d < dim; ++d) norm += s[d] * s[d];
        if (norm <= 0) continue;
        norm = sqrt(norm);
        const double fac = st->sigma * kappa[i] * area / (m[i] * norm);
        for (int d = 0; d < dim; ++d) a[d][i] += fac * s[d];
    }
    free(kappa);
    return RY_OK;
}
