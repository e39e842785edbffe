/* Line profiles (the case file's `profiles` section): velocity, pressure and density sampled
 * at evenly spaced points along a segment, at every output time, optionally averaged in time.
 *
 * A sample is a Shepard (normalised kernel) interpolation over fluid and wall particles within
 * the kernel support of the point, sum_j V_j W_j f_j / sum_j V_j W_j with V = m / rho; walls
 * contribute their own (prescribed) velocity, so a profile that reaches a no-slip wall ends at
 * the wall's velocity. Points with no particle within the support are written as nan. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/atomic_file.h"
#include "ryushi/sim.h"
#include "ryushi/probes.h"

/* Values per point: velocity components (dim), pressure, density. */
static int nvalues(int dim) {
    return dim + 2;
}

static const char *pkey(char *buf, size_t size, size_t i, const char *name) {
    snprintf(buf, size, "profiles[%zu].%s", i, name);
    return buf;
}

ry_status ry_profiles_setup(ry_sim *sim, ry_case *c, ry_error *err) {
    size_t n;
    RY_TRY(ry_case_count(c, "profiles", &n, err));
    if (n == 0) return RY_OK;
    sim->profiles = calloc(n, sizeof *sim->profiles);
    RY_CHECK(err, sim->profiles != NULL, RY_ERR_NOMEM, "out of memory");
    const int dim = sim->dim;
    for (size_t i = 0; i < n; ++i) {
        ry_profile *pf = &sim->profiles[i];
        sim->nprofiles++;
        char k[96], where[256];
        const char *name;
        RY_TRY(ry_case_string(c, pkey(k, sizeof k, i, "name"), NULL, &name, err));
        RY_CHECK(
            err,
            name[0] != '\0' &&
                strspn(name, "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") ==
                    strlen(name),
            RY_ERR_INPUT, "%s: key '%s': a profile name is letters, digits, '_' and '-'",
            ry_case_where(c, k, where, sizeof where), k);
        for (size_t j = 0; j < i; ++j)
            RY_CHECK(err, strcmp(sim->profiles[j].name, name) != 0, RY_ERR_INPUT,
                     "%s: key '%s': profile name '%s' is used twice",
                     ry_case_where(c, k, where, sizeof where), k, name);
        pf->name = ry_strdup(name);
        RY_CHECK(err, pf->name != NULL, RY_ERR_NOMEM, "out of memory");
        RY_TRY(ry_case_vector(c, pkey(k, sizeof k, i, "from"), NULL, dim, pf->from, err));
        RY_TRY(ry_case_vector(c, pkey(k, sizeof k, i, "to"), NULL, dim, pf->to, err));
        long np, def_np = 101;
        RY_TRY(ry_case_int(c, pkey(k, sizeof k, i, "points"), &def_np, 2, 100000, &np, err));
        pf->npoints = (int)np;
        pkey(k, sizeof k, i, "average_from");
        if (ry_case_has(c, k)) {
            RY_TRY(ry_case_double(c, k, NULL, 0.0, INFINITY, &pf->average_from, err));
            pf->averaged = 1;
        }
        pf->sum = calloc((size_t)pf->npoints * (size_t)nvalues(dim), sizeof *pf->sum);
        RY_CHECK(err, pf->sum != NULL, RY_ERR_NOMEM, "out of memory");
    }
    return RY_OK;
}

void ry_profiles_free(ry_sim *sim) {
    for (int i = 0; i < sim->nprofiles; ++i) {
        free(sim->profiles[i].name);
        free(sim->profiles[i].sum);
    }
    free(sim->profiles);
    sim->profiles = NULL;
    sim->nprofiles = 0;
}

void ry_profile_point(const ry_sim *sim, const ry_profile *pf, int k, double *x) {
    const double s = pf->npoints > 1 ? (double)k / (pf->npoints - 1) : 0.0;
    for (int d = 0; d < 3; ++d)
        x[d] = d < sim->dim ? pf->from[d] + s * (pf->to[d] - pf->from[d]) : 0.0;
}

int ry_sample_point(const ry_sim *sim, const double *x, double *out) {
    const ry_particles *ps = &sim->ps;
    const ry_kernel *k = &sim->kernel;
    const int dim = sim->dim, nv = nvalues(dim);
    const double r2max = k->radius * k->radius;
    double sw = 0, acc[5] = {0, 0, 0, 0, 0};
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID && ps->kind[i] != RY_KIND_WALL) continue;
        double r2 = 0;
        for (int d = 0; d < dim; ++d) {
            double e = ps->f[RY_F_X + d][i] - x[d];
            r2 += e * e;
        }
        if (r2 >= r2max) continue;
        const double wv = ry_kernel_w(k, sqrt(r2)) * ps->f[RY_F_MASS][i] / ps->f[RY_F_RHO][i];
        sw += wv;
        for (int d = 0; d < dim; ++d) acc[d] += wv * ps->f[RY_F_VX + d][i];
        acc[dim] += wv * ps->f[RY_F_P][i];
        acc[dim + 1] += wv * ps->f[RY_F_RHO][i];
    }
    for (int v = 0; v < nv; ++v) out[v] = sw > 0 ? acc[v] / sw : NAN;
    return sw > 0;
}

/* The profile's file: s, coordinates, velocity, p, rho, samples (the mean so far). */
static ry_status write_profile(const ry_sim *sim, const ry_profile *pf, ry_error *err) {
    static const char *const xn[3] = {"x", "y", "z"}, *const vn[3] = {"u", "v", "w"};
    const int dim = sim->dim, nv = nvalues(dim);
    char path[4096];
    snprintf(path, sizeof path, "%s/profile_%s.csv", sim->out_dir, pf->name);
    ry_atomic_file f;
    RY_TRY(ry_atomic_open(&f, path, err));
    fprintf(f.fp, "s");
    for (int d = 0; d < dim; ++d) fprintf(f.fp, ",%s", xn[d]);
    for (int d = 0; d < dim; ++d) fprintf(f.fp, ",%s", vn[d]);
    fprintf(f.fp, ",p,rho,samples\n");
    double len = 0;
    for (int d = 0; d < dim; ++d) len += (pf->to[d] - pf->from[d]) * (pf->to[d] - pf->from[d]);
    len = sqrt(len);
    for (int k = 0; k < pf->npoints; ++k) {
        double x[3];
        ry_profile_point(sim, pf, k, x);
        fprintf(f.fp, "%.10g", len * k / (pf->npoints - 1));
        for (int d = 0; d < dim; ++d) fprintf(f.fp, ",%.10g", x[d]);
        const double *s = pf->sum + (size_t)k * nv;
        for (int v = 0; v < nv; ++v)
            fprintf(f.fp, ",%.10g", pf->nsamples > 0 ? s[v] / pf->nsamples : NAN);
        fprintf(f.fp, ",%d\n", pf->nsamples);
    }
    return ry_atomic_commit(&f, err);
}

ry_status ry_profiles_output(ry_sim *sim, ry_error *err) {
    const int nv = nvalues(sim->dim);
    for (int i = 0; i < sim->nprofiles; ++i) {
        ry_profile *pf = &sim->profiles[i];
        const size_t nval = (size_t)pf->npoints * (size_t)nv;
        if (!pf->averaged) { /* the state at this output time */
            memset(pf->sum, 0, nval * sizeof *pf->sum);
            pf->nsamples = 0;
        } else if (sim->t < pf->average_from * (1.0 - 1e-12)) {
            continue; /* averaging has not started */
        }
        double *sum = pf->sum;
#pragma omp parallel for schedule(static)
        for (int k = 0; k < pf->npoints; ++k) {
            double x[3], v[5];
            ry_profile_point(sim, pf, k, x);
            ry_sample_point(sim, x, v);
            for (int q = 0; q < nv; ++q) sum[(size_t)k * nv + q] += v[q];
        }
        pf->nsamples++;
        RY_TRY(write_profile(sim, pf, err));
    }
    return RY_OK;
}

const ry_profile *ry_profile_find(const ry_sim *sim, const char *name) {
    for (int i = 0; i < sim->nprofiles; ++i)
        if (strcmp(sim->profiles[i].name, name) == 0) return &sim->profiles[i];
    return NULL;
}

double ry_profile_mean(const ry_sim *sim, const ry_profile *pf, int k, int value) {
    const int nv = nvalues(sim->dim);
    if (pf->nsamples <= 0 || k < 0 || k >= pf->npoints || value < 0 || value >= nv) return NAN;
    return pf->sum[(size_t)k * nv + value] / pf->nsamples;
}
