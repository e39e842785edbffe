/* The transport-velocity formulation of WCSPH (scheme.transport_velocity; Adami, Hu & Adams
 * (2013), J. Comput. Phys. 241: 292, eq. 8-13) and density by summation, rho_i = sum_j m_j
 * W_ij (or from the number density with the transport velocity), both over the neighbour
 * list. */
#include <math.h>

#include "schemes/wcsph/wcsph_internal.h"
#include "schemes/wcsph/wcsph_tvf_pair.h"

/* Density by summation for fluid particles (walls keep their extrapolated density):
 * rho_i = sum_j m_j W_ij, or with the transport velocity rho_i = m_i sum_j W_ij (Adami et al.
 * 2013). (Variable h needs the continuity equation, so h is the reference one here.) dim, the
 * kernel and `periodic` are literals at each call site, as for the force loops. */
static inline __attribute__((always_inline)) void
density_particle(const ry_sim *sim, const wcsph *w, size_t i, const int dim,
                 const ry_kernel_type kt, const int periodic) {
    const ry_particles *ps = &sim->ps;
    if (ps->kind[i] != RY_KIND_FLUID) return;
    const ry_kernel *k = &sim->kernel;
    const double *restrict m = ps->f[RY_F_MASS];
    const double *restrict x0 = ps->f[RY_F_X], *restrict x1 = ps->f[RY_F_Y];
    const double *restrict x2 = dim > 2 ? ps->f[RY_F_Z] : x0;
    const size_t q1 = sim->nl.offset[i + 1];
    const uint32_t *restrict nb = sim->nl.j;
    const double rad2 = sim->nl_radius * sim->nl_radius, inv_h = k->inv_h;
    const double xi = x0[i], yi = x1[i], zi = dim > 2 ? x2[i] : 0.0;
    const int numden = w->tvf;
    double s = 0.0;
    for (size_t q = sim->nl.offset[i]; q < q1; ++q) {
        const uint32_t j = nb[q];
        double dx[3] = {xi - x0[j], yi - x1[j], dim > 2 ? zi - x2[j] : 0.0};
        if (periodic) ry_box_min_image(&sim->box, dx);
        const double r2 = dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2];
        const double wq = r2 < rad2 ? ry_kernel_shape(kt, sqrt(r2) * inv_h) : 0.0;
        s += (numden ? 1.0 : m[j]) * wq;
    }
    ps->f[RY_F_RHO][i] =
        m[i] * k->norm * ry_kernel_shape(kt, 0.0) + (numden ? m[i] : 1.0) * k->norm * s;
}

typedef void (*density_driver)(ry_sim *sim, const wcsph *w);
#define RY_DENSITY_DRIVER_(DIM, KT, PER)                                                           \
    static void density_##DIM##_##KT##_##PER(ry_sim *sim, const wcsph *w) {                        \
        const size_t n = sim->ps.n;                                                                \
        _Pragma("omp parallel for schedule(static)") for (size_t i = 0; i < n; ++i)                \
            density_particle(sim, w, i, DIM, KT, PER);                                             \
    }

/* The transport-velocity record of particle j (wcsph_tvf_pair.h) from the fields that
 * wc_prepare_pairs fills (for a fluid particle the velocity viscous terms see is its own). */
typedef struct tvf_fields {
    const double *v[3], *vg[3], *vt[3], *m, *rho, *p, *vol, *mu, *isfl, *vis;
} tvf_fields;

static inline __attribute__((always_inline)) wc_tvf_rec tvf_record(const tvf_fields *F, size_t j,
                                                                   const int dim) {
    wc_tvf_rec r;
    r.rho = F->rho[j];
    r.p = F->p[j];
    r.mu = F->mu[j];
    r.vol2 = F->vol[j] * F->vol[j];
    r.mass = F->m[j];
    r.fluid = F->isfl[j]; /* 0 or 1 */
    r.visc = F->vis[j];
    for (int d = 0; d < 3; ++d) r.v[d] = r.vg[d] = r.dv[d] = 0.0;
    for (int d = 0; d < dim; ++d) {
        r.v[d] = F->v[d][j];
        r.vg[d] = F->vg[d][j];
        r.dv[d] = F->vt[d][j] - F->v[d][j];
    }
    return r;
}

/* Transport-velocity formulation (Adami, Hu & Adams 2013, eq. 8 and 13): pressure with the
 * density-weighted inter-particle average, the extra stress A = rho v (v~ - v), the viscous
 * term with the inter-particle averaged viscosity, and the background-pressure acceleration
 * that moves particles with v~. V_i = m_i / rho_i. */
static inline __attribute__((always_inline)) void
tvf_particle(const ry_sim *sim, const wcsph *w, size_t i, const int dim, const ry_kernel_type kt,
             const int periodic, double *amax2, double *vmax2) {
    const ry_particles *ps = &sim->ps;
    if (ps->kind[i] != RY_KIND_FLUID) return;
    const ry_kernel *k = &sim->kernel;
    const double *x[3];
    tvf_fields F;
    for (int d = 0; d < 3; ++d) {
        x[d] = ps->f[RY_F_X + (d < dim ? d : 0)];
        F.v[d] = ps->f[RY_F_VX + (d < dim ? d : 0)];
        F.vg[d] = ps->f[w->f_vg[d < dim ? d : 0]];
        F.vt[d] = ps->f[w->f_vt[d < dim ? d : 0]];
    }
    F.m = ps->f[RY_F_MASS];
    F.rho = ps->f[RY_F_RHO];
    F.p = ps->f[RY_F_P];
    F.vol = ps->f[w->f_vol];
    F.mu = ps->f[w->f_mu];
    F.isfl = ps->f[w->f_isfluid];
    F.vis = ps->f[w->f_visc];
    const uint32_t *restrict nb = sim->nl.j;
    const double rad2 = sim->nl_radius * sim->nl_radius;
    const double dnorm_h = k->dnorm * k->inv_h, inv_h = k->inv_h; /* (dW/dr)/r */
    const double rep_r02 = w->rep_r0 * w->rep_r0, rep_d = w->rep_d;
    const wc_tvf_rec I = tvf_record(&F, i, dim);
    double ai[3] = {0, 0, 0}, bi[3] = {0, 0, 0}, xi[3] = {0, 0, 0};
    double v2 = 0;
    for (int d = 0; d < dim; ++d) {
        xi[d] = x[d][i];
        v2 += I.v[d] * I.v[d];
    }
    const size_t q1 = sim->nl.offset[i + 1];
    for (size_t q = sim->nl.offset[i]; q < q1; ++q) {
        const uint32_t j = nb[q];
        double dx[3] = {0, 0, 0}, r2 = 0;
        for (int d = 0; d < dim; ++d) dx[d] = xi[d] - x[d][j];
        if (periodic) ry_box_min_image(&sim->box, dx);
        for (int d = 0; d < dim; ++d) r2 += dx[d] * dx[d];
        if (r2 >= rad2 || r2 <= 0) continue;
        const double fw = dnorm_h * ry_kernel_dshape_over_q(kt, sqrt(r2) * inv_h); /* gradW/x */
        const wc_tvf_rec J = tvf_record(&F, j, dim);
        const wc_tvf_out o = wc_tvf_pair(&I, &J, dx, r2, fw, dim, rep_r02, rep_d);
        for (int d = 0; d < dim; ++d) {
            ai[d] += o.a[d];
            bi[d] += o.b[d];
        }
    }
    double a2 = 0;
    for (int d = 0; d < dim; ++d) {
        ai[d] = ai[d] / I.mass + sim->gravity[d];
        ps->f[RY_F_AX + d][i] = ai[d];
        ps->f[w->f_abg[d]][i] = -w->p_tvf / I.mass * bi[d];
        a2 += ai[d] * ai[d];
    }
    *amax2 = a2 > *amax2 ? a2 : *amax2;
    *vmax2 = v2 > *vmax2 ? v2 : *vmax2;
}

typedef void (*tvf_driver)(ry_sim *sim, const wcsph *w, force_out *res);
#define RY_TVF_DRIVER_(DIM, KT, PER)                                                               \
    static void tvf_##DIM##_##KT##_##PER(ry_sim *sim, const wcsph *w, force_out *res) {            \
        double amax2 = 0, vmax2 = 0;                                                               \
        const size_t n = sim->ps.n;                                                                \
        _Pragma("omp parallel for schedule(dynamic, 64) reduction(max : amax2, vmax2)") for (      \
            size_t i = 0; i < n; ++i) tvf_particle(sim, w, i, DIM, KT, PER, &amax2, &vmax2);       \
        res->amax2 = amax2;                                                                        \
        res->vmax2 = vmax2;                                                                        \
    }
#define RY_TVF_DRIVERS_(KT)                                                                        \
    RY_TVF_DRIVER_(2, KT, 0)                                                                       \
    RY_TVF_DRIVER_(2, KT, 1)                                                                       \
    RY_TVF_DRIVER_(3, KT, 0)                                                                       \
    RY_TVF_DRIVER_(3, KT, 1)                                                                       \
    RY_DENSITY_DRIVER_(2, KT, 0)                                                                   \
    RY_DENSITY_DRIVER_(2, KT, 1) RY_DENSITY_DRIVER_(3, KT, 0) RY_DENSITY_DRIVER_(3, KT, 1)
RY_FOR_EACH_KERNEL_(RY_TVF_DRIVERS_)
#define RY_TVF_ROW_(KT) RY_DRIVER_ROW_(tvf, KT),
static const tvf_driver tvf_drivers[RY_KERNEL_COUNT][2][2] = {RY_FOR_EACH_KERNEL_(RY_TVF_ROW_)};
#define RY_DENSITY_ROW_(KT) RY_DRIVER_ROW_(density, KT),
static const density_driver density_drivers[RY_KERNEL_COUNT][2][2] = {
    RY_FOR_EACH_KERNEL_(RY_DENSITY_ROW_)};
#undef RY_TVF_ROW_
#undef RY_DENSITY_ROW_
#undef RY_TVF_DRIVERS_
#undef RY_TVF_DRIVER_
#undef RY_DENSITY_DRIVER_

void wc_density_summation(ry_sim *sim, const wcsph *w) {
    density_drivers[sim->kernel.type][sim->dim - 2][is_periodic(sim)](sim, w);
}

void wc_tvf_forces(ry_sim *sim, const wcsph *w, force_out *res) {
    tvf_drivers[sim->kernel.type][sim->dim - 2][is_periodic(sim)](sim, w, res);
}
