/* Surface tension for particle methods: CSF (curvature from the colour function) and the
 * potential model of Kondo et al. (2007), seed 003 eq. 9-12. See include/ryushi/surface_tension.h.
 */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "linalg/small.h"
#include "physics/gradient_mps_koshizuka1996.h"
#include "ryushi/surface_tension.h"

const char *const ry_st_model_names[] = {"none", "csf", "potential", NULL};
const char *const ry_st_curvature_names[] = {"divergence", "surface", NULL};

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

/* The pair stiffness summed into D(k) (ry_st_potential_lattice_omega2). */
static void lattice_dynamical(int dim, double l0, double re, double C, const double k[3],
                              double D[3][3]) {
    const int K = lattice_extent(l0, re);
    memset(D, 0, 9 * sizeof D[0][0]);
    for (int a = -K; a <= K; ++a)
        for (int b = -K; b <= K; ++b)
            for (int c = (dim > 2 ? -K : 0); c <= (dim > 2 ? K : 0); ++c) {
                const double x[3] = {a * l0, b * l0, c * l0};
                const double r = sqrt(x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
                if (r <= 0 || r >= re) continue;
                /* f and its derivative f' = 2 r - l0 - re */
                const double f = ry_st_potential_f(r, l0, re), fp = 2 * r - l0 - re;
                const double s = 1.0 - cos(k[0] * x[0] + k[1] * x[1] + k[2] * x[2]);
                for (int i = 0; i < 3; ++i)
                    for (int j = 0; j < 3; ++j) {
                        const double ee = x[i] * x[j] / (r * r);
                        D[i][j] += C * s * (fp * ee + f / r * ((i == j) - ee));
                    }
            }
}

double ry_st_potential_lattice_omega2(int dim, double l0, double re, double sigma, double rho,
                                      const double k[3], const double pol[3]) {
    const double C = ry_st_potential_coefficient(dim, l0, re, sigma);
    const double m = rho * pow(l0, dim);
    double D[3][3], num = 0, den = 0;
    lattice_dynamical(dim, l0, re, C, k, D);
    for (int i = 0; i < dim; ++i) {
        den += pol[i] * pol[i];
        for (int j = 0; j < dim; ++j) num += pol[i] * D[i][j] * pol[j];
    }
    return den > 0 ? num / (m * den) : 0.0;
}

double ry_st_potential_lattice_growth(int dim, double l0, double re, double sigma, double rho,
                                      double k_out[3]) {
    const int N = 16;
    const double C = ry_st_potential_coefficient(dim, l0, re, sigma);
    const double m = rho * pow(l0, dim), h = RY_PI / (N * l0);
    double worst = 0;
    if (k_out) k_out[0] = k_out[1] = k_out[2] = 0;
    /* the lattice's symmetry: kx >= ky >= kz >= 0 covers every direction */
    for (int ix = 1; ix <= N; ++ix)
        for (int iy = 0; iy <= ix; ++iy)
            for (int iz = 0; iz <= (dim > 2 ? iy : 0); ++iz) {
                const double k[3] = {ix * h, iy * h, iz * h};
                const double kn = sqrt(k[0] * k[0] + k[1] * k[1] + k[2] * k[2]);
                const double e[3] = {k[0] / kn, k[1] / kn, k[2] / kn};
                double D[3][3], lo;
                lattice_dynamical(dim, l0, re, C, k, D);
                if (dim == 2) {
                    const double t[2] = {-e[1], e[0]};
                    lo = t[0] * (D[0][0] * t[0] + D[0][1] * t[1]) +
                         t[1] * (D[1][0] * t[0] + D[1][1] * t[1]);
                } else { /* the smaller eigenvalue of D in the plane normal to k */
                    double t1[3] = {e[1], -e[0], 0}, n1 = hypot(e[0], e[1]);
                    if (n1 < 1e-12) {
                        t1[0] = 0, t1[1] = e[2], t1[2] = -e[1];
                        n1 = hypot(e[1], e[2]);
                    }
                    for (int d = 0; d < 3; ++d) t1[d] /= n1;
                    const double t2[3] = {e[1] * t1[2] - e[2] * t1[1], e[2] * t1[0] - e[0] * t1[2],
                                          e[0] * t1[1] - e[1] * t1[0]};
                    double a11 = 0, a12 = 0, a22 = 0;
                    for (int i = 0; i < 3; ++i)
                        for (int j = 0; j < 3; ++j) {
                            a11 += t1[i] * D[i][j] * t1[j];
                            a12 += t1[i] * D[i][j] * t2[j];
                            a22 += t2[i] * D[i][j] * t2[j];
                        }
                    lo = 0.5 * (a11 + a22) - sqrt(0.25 * (a11 - a22) * (a11 - a22) + a12 * a12);
                }
                lo /= m;
                if (lo < worst) {
                    worst = lo;
                    if (k_out)
                        for (int d = 0; d < 3; ++d) k_out[d] = k[d] / (RY_PI / l0);
                }
            }
    return worst < 0 ? sqrt(-worst) : 0.0;
}

/* CSF: the sum over one column of a flat half-space lattice (depths k = 1, 2, ... spacings
 * below the top layer) of the inward sum |sum_j w(r) x_ij / r| (its normal part): it spreads
 * the jump sigma kappa over the top layer and the layers under it (a discrete delta function;
 * the top layer carries g_top/S, 81 % in 2D at re = 3.1 l0). Its pressure is fixed (p = 0) in
 * MPS, and the pressure equation turns only part of the force on it into pressure inside
 * (docs/reference/mps.md, known limits). */
static double csf_delta_sum(int dim, double l0, double re, double *g_top) {
    const int K = lattice_extent(l0, re);
    double S = 0;
    for (int k = 0; k <= K; ++k) { /* the particle's depth */
        double g = 0;
        for (int s = -K; s <= K; ++s) /* s: the neighbour's depth less the particle's */
            for (int u = -K; u <= K; ++u)
                for (int v = (dim > 2 ? -K : 0); v <= (dim > 2 ? K : 0); ++v) {
                    if ((s == 0 && u == 0 && v == 0) || k + s < 0) continue;
                    const double r = l0 * sqrt((double)(s * s + u * u + v * v));
                    if (r >= re) continue;
                    g += ry_mps_weight_tamai(r, re) * s * l0 / r;
                }
        S += g;
        if (k == 0) *g_top = g;
    }
    return S;
}

ry_status ry_st_setup(ry_surface_tension *st, int model, int dim, double l0, double re,
                      double sigma, ry_error *err) {
    RY_CHECK(err, dim == 2 || dim == 3, RY_ERR_INPUT, "surface tension needs 2 or 3 dimensions");
    RY_CHECK(err, l0 > 0 && re > l0 && sigma >= 0, RY_ERR_INPUT,
             "surface tension: need spacing > 0, radius > spacing and sigma >= 0");
    st->model = model;
    st->curvature = RY_ST_CURV_DIVERGENCE;
    st->dim = dim;
    st->sigma = sigma;
    st->l0 = l0;
    st->re = re;
    st->C = ry_st_potential_coefficient(dim, l0, re, sigma);
    memset(st->wall_ratio, 0, sizeof st->wall_ratio);
    st->wall_group = NULL;
    st->cut = NULL;
    st->thin_normal = NULL;
    st->thin_layers = 1;
    st->pair_j = NULL;
    st->pair_r = NULL;
    st->pair_end = NULL;
    st->cross_ratio = 1.0;
    st->contact_angle = NAN;
    st->delta_sum = csf_delta_sum(dim, l0, re, &st->g_top);
    st->pressure_form = 0;
    st->smoothing = 0;
    return RY_OK;
}

ry_status ry_st_work_ensure(ry_st_work *w, size_t n, ry_error *err) {
    if (w->cap >= n) return RY_OK;
    double *b = realloc(w->p, 8 * n * sizeof *b);
    RY_CHECK(err, b != NULL, RY_ERR_NOMEM, "out of memory (surface tension)");
    w->p = b;
    uint8_t *t = realloc(w->tag, n);
    RY_CHECK(err, t != NULL, RY_ERR_NOMEM, "out of memory (surface tension)");
    w->tag = t;
    w->cap = n;
    return RY_OK;
}

void ry_st_work_free(ry_st_work *w) {
    free(w->p);
    free(w->tag);
    w->p = NULL;
    w->tag = NULL;
    w->cap = 0;
}

ry_status ry_st_read(ry_surface_tension *st, ry_case *c, int dim, double l0, double re_default,
                     double re_max, ry_error *err) {
    int model, curv = RY_ST_CURV_DIVERGENCE, pressure = 0;
    double sigma = 0, rst = re_default;
    long passes = 2;
    RY_TRY(ry_case_choice(c, "surface_tension.model", "none", ry_st_model_names, &model, err));
    if (model != RY_ST_NONE) {
        RY_TRY(ry_case_double(c, "surface_tension.sigma", NULL, 0.0, INFINITY, &sigma, err));
        RY_TRY(ry_case_double(c, "surface_tension.radius", &rst, 1.5, re_max, &rst, err));
    }
    if (model == RY_ST_CSF) {
        static const char *const forms[] = {"force", "pressure", NULL};
        RY_TRY(ry_case_choice(c, "surface_tension.csf_form", "pressure", forms, &pressure, err));
        /* The curvature that suits each form (docs/reference/mps.md): the surface divergence for
         * the pressure form; for the force form the full divergence, whose high reading makes up
         * for the part of the force the pressure equation does not take up. */
        RY_TRY(ry_case_choice(c, "surface_tension.curvature", pressure ? "surface" : "divergence",
                              ry_st_curvature_names, &curv, err));
        char where[256];
        RY_CHECK(err, pressure || !ry_case_has(c, "surface_tension.smoothing"), RY_ERR_INPUT,
                 "%s: key 'surface_tension.smoothing': applies to csf_form: pressure only",
                 ry_case_where(c, "surface_tension.smoothing", where, sizeof where));
        RY_TRY(ry_case_int(c, "surface_tension.smoothing", &passes, 0, 20, &passes, err));
    }
    RY_TRY(ry_st_setup(st, model, dim, l0, rst * l0, sigma, err));
    st->curvature = curv;
    st->pressure_form = pressure;
    st->smoothing = (int)passes;
    return RY_OK;
}

ry_status ry_st_read_sph(ry_surface_tension *st, ry_case *c, int dim, double dx, double *beta,
                         double *rc, double *e, ry_error *err) {
    RY_TRY(ry_st_read(st, c, dim, dx, 3.1, 6.0, err));
    const int pf = ry_st_pressure_form(st);
    char at[256];
    RY_CHECK(err, pf || !ry_case_has(c, "surface_tension.surface_threshold"), RY_ERR_INPUT,
             "%s: key 'surface_tension.surface_threshold': applies to model csf with csf_form: "
             "pressure only",
             ry_case_where(c, "surface_tension.surface_threshold", at, sizeof at));
    /* Two layers carry the jump: on a flat lattice the top layer has 0.77 of the full kernel
     * sum, the one under it 0.99 (Wendland C2, h = 1.4 dx). With the top layer alone (0.9 to
     * 0.97) an IISPH drop at rest grew a star of spikes within 5 ms: the layer under it, short
     * of neighbours, took a pressure under the jump (docs/reference/iisph.md). */
    double b = 0.995, r = pf ? 0.85 : 0.0, ce = 0.2;
    *beta = b;
    if (pf) RY_TRY(ry_case_double(c, "surface_tension.surface_threshold", &b, 0.5, 1.0, beta, err));
    /* The repulsion keeps surface particles at equal pressure apart, which the subtracted
     * pressure force does not. */
    RY_TRY(ry_case_double(c, "scheme.repulsion.distance", &r, 0.0, 1.0, rc, err));
    RY_TRY(ry_case_double(c, "scheme.repulsion.restitution", &ce, 0.0, 1.0, e, err));
    *rc *= dx;
    return RY_OK;
}

double ry_st_capillary_dt(const ry_surface_tension *st, const ry_sim *sim) {
    if (st->model == RY_ST_NONE || !(st->sigma > 0)) return INFINITY;
    double rho = INFINITY;
    for (int m = 0; m < sim->nmat; ++m) rho = fmin(rho, sim->mat[m].density);
    /* sigma alone, not the larger interfacial tension of two liquids (up to 2 sigma): that
     * limit shortens cases/mps_two_liquid_drop.yaml's step by 1/sqrt(2), and its first maximum
     * then comes 29.5 % late against 6 %. The potential model's motion is not converged in the
     * step (docs/validation.md, "Oscillating drops"), and its cases are validated at this one. */
    return sqrt(rho * st->l0 * st->l0 * st->l0 / (2 * RY_PI * st->sigma));
}

/* The pair (i, j)'s coefficient in st_sums, relative to C for the potential model; for CSF
 * whether j counts in the colour function (1 or 0). Inflow buffer particles are fluid about to
 * enter; walls count in CSF as liquid where a contact angle is set, and attract in the
 * potential model with the wall_ratio of the wall's group and the fluid's material; two different
 * liquids attract with cross_ratio. */
static double pair_coefficient(const ry_surface_tension *st, const ry_particles *ps, size_t i,
                               uint32_t j, int csf) {
    if (ps->kind[j] == RY_KIND_FLUID || ps->kind[j] == RY_KIND_INLET)
        return !csf && ps->material[j] != ps->material[i] ? st->cross_ratio : 1.0;
    if (ps->kind[j] != RY_KIND_WALL) return 0.0;
    if (csf) return isnan(st->contact_angle) ? 0.0 : 1.0;
    return st->wall_ratio[st->wall_group ? st->wall_group[j] : 0][ps->material[i]];
}

/* Potential model: the images of thin wall particle j (dx = x_j - x_i, pair coefficient c)
 * behind its sheet, on the side away from fluid particle i, add their forces to s; none where
 * j has no sheet or i lies within a quarter spacing of its plane (beside the sheet's edge). */
static void thin_images(const ry_surface_tension *st, int dim, uint32_t j, const double dx[3],
                        double c, double *s) {
    const double *nv = st->thin_normal + 3 * (size_t)j;
    const double sn = nv[0] * dx[0] + nv[1] * dx[1] + nv[2] * dx[2], re2 = st->re * st->re;
    if (fabs(sn) < 0.25 * st->l0) return;
    const double step = sn > 0 ? st->l0 : -st->l0;
    for (int m = 1; m < st->thin_layers; ++m) {
        double e[3], r2 = 0;
        for (int d = 0; d < 3; ++d) {
            e[d] = dx[d] + m * step * nv[d];
            r2 += e[d] * e[d];
        }
        if (r2 >= re2) return; /* the next image lies farther still */
        const double r = sqrt(r2), f = c * ry_st_potential_f(r, st->l0, st->re);
        for (int d = 0; d < dim; ++d) s[d] += f * e[d] / r;
    }
}

/* Inward sum of particle i over the fluid within re: sum_j w (x_j - x_i)/r (CSF; w the Tamai
 * weight) or the potential force sum_j f(r) (x_j - x_i)/r, with the images of thin walls
 * (thin_images); *count receives the neighbours. */
static void st_sums(const ry_surface_tension *st, const ry_sim *sim, size_t i, double *s,
                    double *count) {
    const ry_particles *ps = &sim->ps;
    const int csf = st->model == RY_ST_CSF;
    const int images = !csf && st->thin_normal && st->thin_layers > 1;
    const double re = st->re, re2 = re * re;
    /* the scheme's pairs (their distances known, the cut ones and most beyond re left out),
     * or the neighbour list */
    const int own = st->pair_j != NULL;
    const uint32_t *js = own ? st->pair_j : sim->nl.j;
    const size_t q0 = sim->nl.offset[i], q1 = own ? st->pair_end[i] : sim->nl.offset[i + 1];
    double s0 = 0, s1 = 0, s2 = 0, cnt = 0, im[3] = {0, 0, 0};
    for (size_t q = q0; q < q1; ++q) {
        if (!own && st->cut && st->cut[q]) continue;
        const uint32_t j = js[q];
        double dx[3], r;
        const double r2 = ry_sim_separation(sim, i, j, dx);
        if (own) {
            r = st->pair_r[q];
            if (r >= re || r <= 0) continue;
        } else {
            if (r2 >= re2 || r2 <= 0) continue; /* (a third of the list lies beyond re) */
            r = sqrt(r2);
        }
        const double c = pair_coefficient(st, ps, i, j, csf);
        if (c == 0.0) continue;
        const double f = c * (csf ? ry_mps_weight_tamai(r, re) : ry_st_potential_f(r, st->l0, re));
        const double g = f / r;
        cnt += csf ? f : 1.0;
        s0 += g * dx[0]; /* dx is zero beyond the dimension */
        s1 += g * dx[1];
        s2 += g * dx[2];
        if (images && ps->kind[j] == RY_KIND_WALL) thin_images(st, sim->dim, j, dx, c, im);
    }
    s[0] = s0 + im[0];
    s[1] = s1 + im[1];
    s[2] = s2 + im[2];
    *count = cnt;
}

/* Wetting (CSF): the wall normal n_w at fluid particle i, -sum_walls w x_ij / r normalised
 * (it points from the wall into the fluid), and the contact normal
 * n_theta = sin(theta) t + cos(theta) n_w, with t the outward normal n less its part along n_w,
 * normalised (it points along the wall away from the liquid). Returns 0 where there is no
 * wall within re, or n lies along n_w (a film: no t); *near says whether a wall particle lies
 * within 1.5 spacings. */
static int contact_frame(const ry_surface_tension *st, const ry_sim *sim, size_t i, const double *n,
                         double *nth, int *near) {
    const ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const double reach2 = 2.25 * st->l0 * st->l0, re2 = st->re * st->re;
    double nw[3] = {0, 0, 0};
    *near = 0;
    for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
        if (st->cut && st->cut[q]) continue;
        const uint32_t j = sim->nl.j[q];
        if (ps->kind[j] != RY_KIND_WALL) continue;
        double dx[3];
        const double r2 = ry_sim_separation(sim, i, j, dx);
        if (r2 >= re2 || r2 <= 0) continue;
        *near |= r2 < reach2;
        const double w = ry_mps_weight_tamai(sqrt(r2), st->re) / sqrt(r2);
        for (int d = 0; d < dim; ++d) nw[d] -= w * dx[d];
    }
    double nn = 0;
    for (int d = 0; d < dim; ++d) nn += nw[d] * nw[d];
    if (!(nn > 0)) return 0;
    nn = sqrt(nn);
    double t[3] = {0, 0, 0}, dot = 0, tn = 0;
    for (int d = 0; d < dim; ++d) dot += n[d] * nw[d] / nn;
    for (int d = 0; d < dim; ++d) {
        t[d] = n[d] - dot * nw[d] / nn;
        tn += t[d] * t[d];
    }
    if (tn < 1e-6) return 0;
    tn = sqrt(tn);
    const double ct = cos(st->contact_angle), sn = sin(st->contact_angle);
    for (int d = 0; d < 3; ++d) nth[d] = d < dim ? sn * t[d] / tn + ct * nw[d] / nn : 0.0;
    return 1;
}

/* Wetting (CSF), the colour gradient g of a surface particle i within reach of a wall: walls
 * count as liquid only on the liquid's side of the surface that meets the wall at the
 * prescribed angle, the plane normal to n_theta half a spacing outside x_i (surface particles
 * sit half a spacing inside the free surface). The plane reaches the wall at the contact line;
 * the walls beyond it lie under the gas, for theta > 90 degrees in the wedge of gas under the
 * drop. Counted as liquid they tilt the normals of the surface above them towards the wall's
 * own, a false convex curvature at the contact line: a 150-degree drop spread to 136 degrees
 * (docs/reference/surface_tension.md, "Wetting"). */
static void wetted_colour(const ry_surface_tension *st, const ry_sim *sim, size_t i, double *g) {
    const ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const double re = st->re, re2 = re * re;
    double n[3] = {0, 0, 0}, nth[3], gn = 0;
    int near;
    for (int d = 0; d < dim; ++d) gn += g[d] * g[d];
    for (int d = 0; d < dim; ++d) n[d] = -g[d] / sqrt(gn);
    if (!contact_frame(st, sim, i, n, nth, &near)) return;
    /* g holds every wall (st_sums): take out those beyond the plane. */
    for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
        if (st->cut && st->cut[q]) continue;
        const uint32_t j = sim->nl.j[q];
        if (ps->kind[j] != RY_KIND_WALL) continue;
        double dx[3], out = 0;
        const double r2 = ry_sim_separation(sim, i, j, dx);
        if (r2 >= re2 || r2 <= 0) continue;
        for (int d = 0; d < dim; ++d) out += dx[d] * nth[d];
        if (out <= 0.5 * st->l0) continue;
        const double r = sqrt(r2), w = ry_mps_weight_tamai(r, re);
        for (int d = 0; d < dim; ++d) g[d] -= w * dx[d] / r;
    }
}

/* Wetting (CSF): the normal of a fluid particle with a normal and a wall particle within 1.5
 * spacings becomes n_theta (contact_frame). */
static void contact_normals(const ry_surface_tension *st, const ry_sim *sim, double *nrm) {
    const ry_particles *ps = &sim->ps;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < ps->n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || isnan(nrm[3 * i])) continue;
        double nth[3];
        int near;
        if (!contact_frame(st, sim, i, nrm + 3 * i, nth, &near) || !near) continue;
        for (int d = 0; d < sim->dim; ++d) nrm[3 * i + d] = nth[d];
    }
}

/* CSF curvature from the colour function (c = 1 on the fluid): the outward normal
 * n = -g/|g|, g_i = sum_j w x_ij / r (the colour gradient up to a factor), where |g| exceeds a
 * tenth of its value on a flat surface; kappa = div n by the corrected (moment-matrix) divergence
 * over the neighbours that have a normal, exact for a linear normal field however one-sided the
 * neighbourhood; limited to radii of two spacings and up, then averaged over the neighbours
 * that have a normal. With st->curvature == RY_ST_CURV_SURFACE the normal comes from g smoothed
 * over the neighbours and the divergence is the surface divergence (see below). kappa holds
 * 8 n doubles: kappa, then work space. */
void ry_st_curvature(const ry_surface_tension *st, const ry_sim *sim, double *kappa) {
    const ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const size_t n = ps->n;
    double *nrm = kappa + n;     /* 3 per particle; NAN in [0] where there is none */
    double *raw = kappa + 4 * n; /* the curvature before averaging */
    double *gs = kappa + 5 * n;  /* 3 per particle: the colour gradient g */
    const double gmin = 0.1 * st->g_top;
    const double re2 = st->re * st->re;
    /* In 3D the rule threw particles off a 90-degree drop (docs/reference/mps.md): measured and
     * used in 2D only. */
    const int wet = !isnan(st->contact_angle) && dim == 2;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        gs[3 * i] = gs[3 * i + 1] = gs[3 * i + 2] = 0;
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        double g[3], count, gn = 0;
        st_sums(st, sim, i, g, &count);
        for (int d = 0; d < dim; ++d) gn += g[d] * g[d];
        if (sqrt(gn) <= gmin) continue;
        if (wet) wetted_colour(st, sim, i, g);
        for (int d = 0; d < dim; ++d) gs[3 * i + d] = g[d];
    }
    /* A distributed run: each pass reads its neighbours' results of the pass before, which
     * the halo copies take from their owners. */
    ry_sim *ms = (ry_sim *)sim;
    if (sim->par) sim->par->sync(ms, gs, 3, 0);
    /* RY_ST_CURV_SURFACE: the normal from g smoothed over the neighbours (weights w, the
     * particle itself 1). On a staircase (a lattice circle) or a disordered surface the single
     * g_i tilt back and forth with the particle's position, and a protruding particle, with the
     * larger g, also reads the larger curvature: the force-weighted curvature of a lattice
     * circle of radius 20 l0 is 1.50 times 1/R with the plain divergence of the unsmoothed
     * normals, 1.20 times with this form (1.05 on concentric rings). */
    const int surf = st->curvature == RY_ST_CURV_SURFACE;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        nrm[3 * i] = NAN;
        if (gs[3 * i] == 0 && gs[3 * i + 1] == 0 && gs[3 * i + 2] == 0) continue;
        double g[3] = {gs[3 * i], gs[3 * i + 1], gs[3 * i + 2]}, gn = 0;
        for (size_t q = sim->nl.offset[i]; surf && q < sim->nl.offset[i + 1]; ++q) {
            if (st->cut && st->cut[q]) continue;
            const uint32_t j = sim->nl.j[q];
            double dx[3];
            if (ps->kind[j] != RY_KIND_FLUID) continue;
            const double r2 = ry_sim_separation(sim, i, j, dx);
            if (r2 >= re2 || r2 <= 0) continue;
            const double w = ry_mps_weight_tamai(sqrt(r2), st->re);
            for (int d = 0; d < dim; ++d) g[d] += w * gs[3 * j + d];
        }
        for (int d = 0; d < dim; ++d) gn += g[d] * g[d];
        gn = sqrt(gn);
        if (!(gn > 0)) continue;
        for (int d = 0; d < 3; ++d) nrm[3 * i + d] = d < dim ? -g[d] / gn : 0.0;
    }
    if (!isnan(st->contact_angle)) contact_normals(st, sim, nrm);
    if (sim->par) sim->par->sync(ms, nrm, 3, 0);
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        raw[i] = 0;
        if (isnan(nrm[3 * i])) continue;
        double m[3][3] = {{0}}, h[3][3] = {{0}};
        for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
            if (st->cut && st->cut[q]) continue;
            const uint32_t j = sim->nl.j[q];
            if (ps->kind[j] != RY_KIND_FLUID || isnan(nrm[3 * j])) continue;
            double dx[3] = {0, 0, 0}, r2 = 0;
            for (int d = 0; d < dim; ++d) dx[d] = ps->f[RY_F_X + d][j] - ps->f[RY_F_X + d][i];
            ry_box_min_image(&sim->box, dx);
            for (int d = 0; d < dim; ++d) r2 += dx[d] * dx[d];
            if (r2 >= re2 || r2 <= 0) continue;
            const double wr = ry_mps_weight_tamai(sqrt(r2), st->re) / r2;
            ry_grad_moment_add(m, wr, dx, dim);
            for (int a = 0; a < dim; ++a)
                ry_grad_value_add(h[a], wr, nrm[3 * j + a] - nrm[3 * i + a], dx, dim);
        }
        /* H[a][b] = d n_a / d x_b. RY_ST_CURV_SURFACE: the surface divergence
         * tr((I - n n) H) = div n - n.H.n. The normal part n.H.n (d|n|^2/2 along n, zero for
         * an exact unit field) is not zero on a noisy surface: the normals deeper in the band
         * tilt more, their component along the surface normal falls inward, and div n reads
         * too high. */
        double div = 0, y[3], H[3][3] = {{0}};
        int ok = 1;
        for (int a = 0; a < dim && ok; ++a) {
            ok = ry_solve_small(dim, m, h[a], y);
            for (int b = 0; b < dim; ++b) H[a][b] = y[b];
        }
        for (int a = 0; a < dim && ok; ++a)
            for (int b = 0; b < dim; ++b)
                div += ((a == b) - (surf ? nrm[3 * i + a] * nrm[3 * i + b] : 0.0)) * H[a][b];
        /* No curvature radius below two spacings: what is sharper is not resolved. */
        const double kmax = (dim - 1) / (2.0 * st->l0);
        raw[i] = ok ? fmax(fmin(div, kmax), -kmax) : 0.0;
    }
    if (sim->par) sim->par->sync(ms, raw, 1, 0);
        /* Averaged over the neighbours that have a normal (weights w, the particle itself 1). */
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        kappa[i] = 0;
        if (isnan(nrm[3 * i])) continue;
        double ks = raw[i], ws = 1.0;
        for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
            if (st->cut && st->cut[q]) continue;
            const uint32_t j = sim->nl.j[q];
            if (ps->kind[j] != RY_KIND_FLUID || isnan(nrm[3 * j])) continue;
            double dx[3] = {0, 0, 0}, r2 = 0;
            for (int d = 0; d < dim; ++d) dx[d] = ps->f[RY_F_X + d][j] - ps->f[RY_F_X + d][i];
            ry_box_min_image(&sim->box, dx);
            for (int d = 0; d < dim; ++d) r2 += dx[d] * dx[d];
            if (r2 >= re2) continue;
            const double w = ry_mps_weight_tamai(sqrt(r2), st->re);
            ks += w * raw[j];
            ws += w;
        }
        kappa[i] = ks / ws;
    }
    if (sim->par) sim->par->sync(ms, kappa, 1, 0);
}

/* (1) The single curvatures are noisy enough to drive a 3D MPS drop at rest unstable (a drop of
 * 8 spacings' radius at 1.5 ms, one of 12 spacings slowly) unless averaged; the average over
 * the wider surface-tension radius also smooths the corners of an oscillating cube and slows
 * it (cube of 20^3: period +37 %), so MPS averages over its gradient radius. (2) The surface
 * particles sit half a spacing inside the free surface (as in the hydrostatic column), and the
 * curvature read at them is that of their own layer: a sphere of radius R - l0/2 rather than
 * R. Each principal curvature k of the layer becomes k / (1 + k l0/2) at the surface; with
 * kappa = (d - 1) k, kappa_s = kappa / (1 + kappa l0 / (2 (d - 1))). Only convex curvatures
 * are corrected: enlarging the concave ones by the same rule made the oscillating 30^3 cube
 * unstable. */
void ry_st_laplace_pressure(const ry_surface_tension *st, const ry_sim *sim, const uint8_t *tag,
                            uint8_t surface, double radius, double *pd) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    double *tmp = pd + n; /* the curvature's work space is free after it */
    ry_st_curvature(st, sim, pd);
    for (int pass = 0; pass < st->smoothing; ++pass) {
#pragma omp parallel for schedule(dynamic, 64)
        for (size_t i = 0; i < n; ++i) {
            tmp[i] = pd[i];
            if (tag[i] != surface || ps->kind[i] != RY_KIND_FLUID) continue;
            double ks = pd[i], ws = 1.0;
            for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
                if (st->cut && st->cut[q]) continue;
                const uint32_t j = sim->nl.j[q];
                if (tag[j] != surface || ps->kind[j] != RY_KIND_FLUID) continue;
                double dx[3];
                const double r2 = ry_sim_separation(sim, i, j, dx);
                if (r2 >= radius * radius || r2 <= 0) continue;
                const double w = ry_mps_weight_tamai(sqrt(r2), radius);
                ks += w * pd[j];
                ws += w;
            }
            tmp[i] = ks / ws;
        }
        memcpy(pd, tmp, n * sizeof *pd);
        if (sim->par) sim->par->sync((ry_sim *)sim, pd, 1, 0);
    }
    const double shift = st->l0 / (2.0 * (sim->dim - 1));
    for (size_t i = 0; i < n; ++i) pd[i] = st->sigma * pd[i] / (1.0 + fmax(pd[i], 0.0) * shift);
}

void ry_st_potential_particle(const ry_surface_tension *st, const ry_sim *sim, size_t i,
                              double *const a[3]) {
    double s[3], count;
    st_sums(st, sim, i, s, &count);
    for (int d = 0; d < sim->dim; ++d) a[d][i] += st->C * s[d] / sim->ps.f[RY_F_MASS][i];
}

ry_status ry_st_accelerate(const ry_surface_tension *st, const ry_sim *sim, double *const a[3],
                           ry_error *err) {
    if (st->model == RY_ST_NONE || st->sigma == 0.0) return RY_OK;
    const ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const size_t n = ps->n;
    const double l0 = st->l0, area = dim > 2 ? l0 * l0 : l0;
    const double *m = ps->f[RY_F_MASS];
    if (st->model == RY_ST_POTENTIAL) {
#pragma omp parallel for schedule(dynamic, 64)
        for (size_t i = 0; i < n; ++i)
            if (ps->kind[i] == RY_KIND_FLUID) ry_st_potential_particle(st, sim, i, a);
        return RY_OK;
    }
    double *kappa = malloc(8 * n * sizeof *kappa);
    RY_CHECK(err, kappa != NULL, RY_ERR_NOMEM, "out of memory (surface tension)");
    ry_st_curvature(st, sim, kappa);
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID || kappa[i] == 0.0) continue;
        double s[3], count;
        st_sums(st, sim, i, s, &count);
        /* a_i = sigma kappa_i g_i l0^(d-1) / (m_i S): over a column across a flat surface the
         * forces add up to sigma kappa l0^(d-1). */
        const double fac = st->sigma * kappa[i] * area / (m[i] * st->delta_sum);
        for (int d = 0; d < dim; ++d) a[d][i] += fac * s[d];
    }
    free(kappa);
    return RY_OK;
}
