/* The transport-velocity formulation of WCSPH (scheme.transport_velocity; Adami, Hu & Adams
 * (2013), J. Comput. Phys. 241: 292, eq. 8-13) and density by summation, rho_i = sum_j m_j
 * W_ij (or from the number density with the transport velocity), both over the neighbour
 * list. */
#include <math.h>

#include "schemes/wcsph/wcsph_internal.h"

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
    const double *x[3], *v[3], *vg[3], *vt[3];
    for (int d = 0; d < 3; ++d) {
        x[d] = ps->f[RY_F_X + (d < dim ? d : 0)];
        v[d] = ps->f[RY_F_VX + (d < dim ? d : 0)];
        vg[d] = ps->f[w->f_vg[d < dim ? d : 0]];
        vt[d] = ps->f[w->f_vt[d < dim ? d : 0]];
    }
    const double *restrict m = ps->f[RY_F_MASS];
    const double *restrict rho = ps->f[RY_F_RHO];
    const double *restrict p = ps->f[RY_F_P];
    const double *restrict vol = ps->f[w->f_vol];
    const double *restrict mu = ps->f[w->f_mu];
    const double *restrict isfl = ps->f[w->f_isfluid];
    const double *restrict vis = ps->f[w->f_visc];
    const uint32_t *restrict nb = sim->nl.j;
    const double rad2 = sim->nl_radius * sim->nl_radius;
    const double dnorm_h = k->dnorm * k->inv_h, inv_h = k->inv_h; /* (dW/dr)/r */
    const double rep_r02 = w->rep_r0 * w->rep_r0, rep_d = w->rep_d;
    const double rhoi = rho[i], pi = p[i], mui = mu[i], vi2 = vol[i] * vol[i];
    double ai[3] = {0, 0, 0}, bi[3] = {0, 0, 0}, Ai[3] = {0, 0, 0}, vi[3] = {0, 0, 0}, xi[3];
    double v2 = 0;
    /* A_i = rho_i v_i (v~_i - v_i), a tensor; A_i . grad W = rho_i v_i ((v~_i - v_i).gradW) */
    for (int d = 0; d < dim; ++d) {
        vi[d] = v[d][i];
        xi[d] = x[d][i];
        Ai[d] = vt[d][i] - vi[d];
        v2 += vi[d] * vi[d];
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
        const double rhoj = rho[j], vv = vi2 + vol[j] * vol[j];
        const double pij = (rhoj * pi + rhoi * p[j]) / (rhoi + rhoj);
        const double fj = isfl[j]; /* 0 or 1 */
        const double muj = fj * mu[j] + (1.0 - fj) * mui;
        const double etaij = (mui + muj) > 0 ? 2.0 * mui * muj / (mui + muj) : 0.0;
        /* (A_i + A_j)/2 . grad W; walls carry no extra stress. */
        double adi = 0, adj = 0;
        for (int d = 0; d < dim; ++d) {
            adi += Ai[d] * dx[d];
            adj += (vt[d][j] - v[d][j]) * dx[d];
        }
        adi *= fw;
        adj *= fw * fj;
        const double fr = wall_repulsion(r2, fj == 0.0 && r2 < rep_r02, rep_r02, rep_d) * m[i] / vv;
        const double visj = vis[j];
        for (int d = 0; d < dim; ++d) {
            const double vij = vi[d] - vg[d][j];
            double f = -pij * fw * dx[d] + fr * dx[d];
            f += 0.5 * (rhoi * vi[d] * adi + rhoj * v[d][j] * adj);
            f += visj * etaij * vij * fw; /* eta_ij v_ij (1/r) dW/dr */
            ai[d] += vv * f;
            bi[d] += vv * fw * dx[d];
        }
    }
    double a2 = 0;
    for (int d = 0; d < dim; ++d) {
        ai[d] = ai[d] / m[i] + sim->gravity[d];
        ps->f[RY_F_AX + d][i] = ai[d];
        ps->f[w->f_abg[d]][i] = -w->p_tvf / m[i] * bi[d];
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
