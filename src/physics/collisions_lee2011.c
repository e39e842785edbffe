/* Artificial repulsion between particles closer than a set distance (include/ryushi/sim.h). */
#include "ryushi/sim.h"
#include "ryushi/collisions.h"

/* The collision impulse s of fluid particle i from the entries q0..q1-1 of nj (inlined with a
 * literal dim, so that the sums stay in registers). */
static inline void collide_row(const ry_sim *sim, size_t i, size_t q0, size_t q1,
                               const uint32_t *nj, double rc2, double f, double s[3], int dim) {
    const ry_particles *ps = &sim->ps;
    for (size_t q = q0; q < q1; ++q) {
        const uint32_t j = nj[q];
        double dx[3];
        const double r2 = ry_sim_separation(sim, i, j, dx);
        if (r2 >= rc2 || r2 <= 0) continue;
        double vn = 0;
        for (int d = 0; d < dim; ++d) vn += (ps->f[RY_F_VX + d][j] - ps->f[RY_F_VX + d][i]) * dx[d];
        if (vn >= 0) continue;                                      /* separating */
        const double mj = ps->kind[j] == RY_KIND_FLUID ? 1.0 : 2.0; /* a wall: mirror */
        for (int d = 0; d < dim; ++d) s[d] += mj * f * vn * dx[d] / r2;
    }
}

void ry_collisions(ry_sim *sim, double rc, double restitution, double dt, const uint32_t *nj,
                   const size_t *row_end, double *dv) {
    if (rc <= 0) return;
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim;
    const size_t n = ps->n;
    const double rc2 = rc * rc, f = 0.5 * (1.0 + restitution);
    if (!nj) nj = sim->nl.j;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        double s[3] = {0, 0, 0};
        if (ps->kind[i] == RY_KIND_FLUID) {
            const size_t q0 = sim->nl.offset[i];
            const size_t q1 = row_end ? row_end[i] : sim->nl.offset[i + 1];
            if (dim == 3)
                collide_row(sim, i, q0, q1, nj, rc2, f, s, 3);
            else
                collide_row(sim, i, q0, q1, nj, rc2, f, s, 2);
        }
        for (int d = 0; d < dim; ++d) dv[dim * i + d] = s[d];
    }
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
        if (ps->kind[i] != RY_KIND_FLUID) continue;
        for (int d = 0; d < dim; ++d) {
            ps->f[RY_F_VX + d][i] += dv[dim * i + d];
            ps->f[RY_F_X + d][i] += dt * dv[dim * i + d];
        }
    }
}
