/* The MPS operators on the pairs of a step (Koshizuka & Oka 1996; seed 003, eq. 3-8): the
 * lattice sums n0 and lambda of Tamai's weight (eq. 3, 4 and 8), the pairs within re_g and re_l
 * with their distances (from the neighbour list), the number density n_i = sum_j w(r_ij)
 * (eq. 4) with the roles it gives in the pressure equation (free surface where n* < beta n0,
 * wall and dummy particles), and the divergence of u* (eq. 6) for the source of Tanaka &
 * Masunaga (2010). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "neighbor/r2_simd.h"
#include "physics/gradient_mps_koshizuka1996.h"
#include "ryushi/mps.h"
#include "schemes/mps/mps_internal.h"

void ry_mps_lattice(int dim, double l0, double re, double *n0, double *lambda) {
    const int K = (int)floor(re / l0 + 1e-9);
    double s = 0, s2 = 0;
    for (int a = -K; a <= K; ++a)
        for (int b = -K; b <= K; ++b)
            for (int c = (dim > 2 ? -K : 0); c <= (dim > 2 ? K : 0); ++c) {
                if (a == 0 && b == 0 && c == 0) continue;
                const double r2 = l0 * l0 * (double)(a * a + b * b + c * c);
                const double w = ry_mps_weight_tamai(sqrt(r2), re);
                s += w;
                s2 += r2 * w;
            }
    *n0 = s;
    *lambda = s2 / s;
}

/* Squared distances from particle i to the nb particles nj[0..nb-1] into r2 (no periodic
 * sides; call with a literal dim, so that the loop unrolls and vectorises). */
static inline void row_r2(int dim, const double *const x[3], size_t i, const uint32_t *nj,
                          size_t nb, double *r2) {
    for (size_t k = 0; k < nb; ++k) {
        double s = 0;
        for (int d = 0; d < dim; ++d) {
            const double e = x[d][nj[k]] - x[d][i];
            s += e * e;
        }
        r2[k] = s;
    }
}

#ifdef RY_R2_SIMD
/* mps_pairs_build's row i (3D, no periodic sides) eight entries at a time: the squared distances
 * of the list's entries nj[0..nb-1] (to rb) and the lanes within the inner and the outer
 * radius that are not cut (to mk), then the pairs, the inner ones first, with their
 * distances; *a and *no are the counts. The same pairs in the same order, and the same bits
 * (the square root is exact to the rounding on either path), as the scalar loop. */
static inline void simd_pairs_row(const double *const x[3], size_t i, const uint32_t *nj,
                                  const uint8_t *cut, size_t nb, double ri2, double ro2, double *rb,
                                  uint8_t *mk, uint32_t *pj, double *pr, size_t *a, size_t *no) {
    const __m512d xi[3] = {_mm512_set1_pd(x[0][i]), _mm512_set1_pd(x[1][i]),
                           _mm512_set1_pd(x[2][i])};
    const __m512d vi = _mm512_set1_pd(ri2), vo = _mm512_set1_pd(ro2);
    const __m128i z8 = _mm_setzero_si128();
    size_t ni = 0;
    for (size_t k = 0, c = 0; k < nb; k += 8, c += 2) {
        const __mmask8 m = ry_simd_lanes(nb - k);
        const __m512d v = ry_simd_r2(x, xi, _mm256_maskz_loadu_epi32(m, nj + k), m);
        __mmask8 keep = m;
        if (cut)
            keep &= (__mmask8)_mm_cmpeq_epi8_mask(_mm_maskz_loadu_epi8((__mmask16)m, cut + k), z8);
        mk[c] = keep & _mm512_cmp_pd_mask(v, vi, _CMP_LT_OQ);
        mk[c + 1] =
            keep & _mm512_cmp_pd_mask(v, vi, _CMP_GE_OQ) & _mm512_cmp_pd_mask(v, vo, _CMP_LT_OQ);
        _mm512_mask_storeu_pd(rb + k, m, v);
        ni += (size_t)__builtin_popcount(mk[c]);
    }
    size_t qi = 0, qo = ni;
    for (size_t k = 0, c = 0; k < nb; k += 8, c += 2) {
        const __mmask8 in = mk[c], out = mk[c + 1], m = in | out;
        if (!m) continue;
        const __m256i idx = _mm256_maskz_loadu_epi32(m, nj + k);
        const __m512d r = _mm512_sqrt_pd(_mm512_maskz_loadu_pd(m, rb + k));
        qi += ry_simd_append(in, idx, r, pj + qi, pr + qi);
        qo += ry_simd_append(out, idx, r, pj + qo, pr + qo);
    }
    *a = ni;
    *no = qo - ni;
}
#endif

/* The pairs within re_g and re_l (the fields pj, pr, gend, lend of mps) from the neighbour
 * list, whose reach is the largest radius and a skin: the loops over them need neither the
 * distances nor the pairs beyond their radius again. Within each radius the pairs keep the
 * order of the list. Each row's squared distances go to a buffer of the thread, and the
 * split into the inner and the outer pairs stores every entry and advances by a comparison
 * (the branches it replaces fail unpredictably). */
ry_status mps_pairs_build(ry_sim *sim, mps *M, int fluid_rows, ry_error *err) {
    const size_t n = sim->ps.n, nq = sim->nl.offset[n];
    if (M->pq_cap < nq) {
        const size_t c = nq + nq / 4 + 16;
        uint32_t *j = realloc(M->pj, c * sizeof *j);
        if (j) M->pj = j;
        double *r = realloc(M->pr, c * sizeof *r);
        if (r) M->pr = r;
        RY_CHECK(err, j && r, RY_ERR_NOMEM, "out of memory (MPS pairs: %zu)", nq);
        M->pq_cap = c;
    }
    const double ri = fmin(M->re_g, M->re_l), ro = fmax(M->re_g, M->re_l);
    const double ri2 = ri * ri, ro2 = ro * ro;
    const int g_inner = M->re_g <= M->re_l, dim = sim->dim;
    const uint8_t *cut = M->st.cut; /* thin walls' cut pairs, or NULL */
    int periodic = 0;
    for (int d = 0; d < dim; ++d) periodic |= sim->box.periodic[d];
    size_t rowmax = 0;
    for (size_t i = 0; i < n; ++i)
        if (sim->nl.offset[i + 1] - sim->nl.offset[i] > rowmax)
            rowmax = sim->nl.offset[i + 1] - sim->nl.offset[i];
    const double *x[3];
    for (int d = 0; d < 3; ++d) x[d] = sim->ps.f[RY_F_X + (d < dim ? d : 0)];
    int ok = 1;
#pragma omp parallel reduction(&& : ok)
    {
        /* the row's squared distances; the outer pairs, until they follow the inner ones */
        double *rb = malloc((rowmax + 1) * sizeof *rb);
        uint32_t *oj = malloc((rowmax + 1) * sizeof *oj);
        double *orr = malloc((rowmax + 1) * sizeof *orr);
        uint8_t *mk = malloc(2 * (rowmax / 8 + 2)); /* (the SIMD path's masks) */
        ok = rb && oj && orr && mk;
#pragma omp for schedule(dynamic, 64)
        for (size_t i = 0; i < n; ++i) {
            if (!ok) continue;
            const size_t lo = sim->nl.offset[i], nb = sim->nl.offset[i + 1] - lo;
            if (fluid_rows && sim->ps.kind[i] != RY_KIND_FLUID) {
                M->gend[i] = M->lend[i] = lo;
                continue;
            }
            const uint32_t *nj = sim->nl.j + lo;
            uint32_t *pj = M->pj + lo;
            double *pr = M->pr + lo;
            size_t a = 0, no = 0;
#ifdef RY_R2_SIMD
            if (dim == 3 && !periodic) { /* eight entries at a time: the same pairs, in order */
                simd_pairs_row(x, i, nj, cut ? cut + lo : NULL, nb, ri2, ro2, rb, mk, pj, pr, &a,
                               &no);
            } else
#endif
            {
                if (periodic) {
                    double dx[3];
                    for (size_t k = 0; k < nb; ++k) rb[k] = ry_sim_separation(sim, i, nj[k], dx);
                } else if (dim == 3) {
                    row_r2(3, x, i, nj, nb, rb);
                } else if (dim == 2) {
                    row_r2(2, x, i, nj, nb, rb);
                } else {
                    row_r2(1, x, i, nj, nb, rb);
                }
                for (size_t k = 0; k < nb; ++k) {
                    const double v = rb[k];
                    const uint32_t j = nj[k];
                    const int keep = !cut || !cut[lo + k];
                    pj[a] = j;
                    pr[a] = v;
                    oj[no] = j;
                    orr[no] = v;
                    a += keep & (v < ri2);
                    no += keep & (v >= ri2) & (v < ro2);
                }
                memcpy(pj + a, oj, no * sizeof *oj);
                memcpy(pr + a, orr, no * sizeof *orr);
                for (size_t k = 0; k < a + no; ++k) pr[k] = sqrt(pr[k]);
            }
            M->gend[i] = lo + (g_inner ? a : a + no);
            M->lend[i] = lo + (g_inner ? a + no : a);
        }
        free(rb);
        free(oj);
        free(orr);
        free(mk);
    }
    RY_CHECK(err, ok, RY_ERR_NOMEM, "out of memory (MPS pairs)");
    /* the surface tension reads them where they reach its radius (until the particles move) */
    const int st_own = M->st.re <= ro && !sim->par;
    M->st.pair_j = st_own ? M->pj : NULL;
    M->st.pair_r = st_own ? M->pr : NULL;
    M->st.pair_end = st_own ? (g_inner ? M->lend : M->gend) : NULL;
    return RY_OK;
}

/* Divergence of u* (eq. 6) at particle i over fluid and wall neighbours within re_g. */
static double divergence(const ry_sim *sim, const mps *M, size_t i) {
    const ry_particles *ps = &sim->ps;
    const double re = M->re_g;
    const int dim = sim->dim;
    /* u* of the fluid, the velocity of the rest */
    const double *us[3], *uv[3];
    double ui[3] = {0, 0, 0};
    for (int d = 0; d < dim; ++d) {
        us[d] = ps->f[M->f_vs[d]];
        uv[d] = ps->f[RY_F_VX + d];
        ui[d] = ps->kind[i] == RY_KIND_FLUID ? us[d][i] : uv[d][i];
    }
    double s = 0;
    for (size_t q = sim->nl.offset[i]; q < M->gend[i]; ++q) {
        const uint32_t j = M->pj[q];
        double dx[3];
        const double r2 = ry_sim_separation(sim, i, j, dx);
        if (r2 <= 0) continue;
        const double *const *u = ps->kind[j] == RY_KIND_FLUID ? us : uv;
        double du = 0;
        for (int d = 0; d < dim; ++d) du += (u[d][j] - ui[d]) * dx[d];
        s += ry_mps_divergence_term(du, r2, ry_mps_weight_tamai(M->pr[q], re));
    }
    return ry_mps_divergence(s, sim->dim, M->n0g);
}

/* divergence() of particle i as a vector loop and a sum (3D, no periodic side): u[d] the
 * velocity each particle brings (u* of the fluid, the velocity of the rest), bt and br2 room
 * for the row's terms and squared distances. The same terms, summed in the same order. */
static double divergence_lanes(const ry_sim *sim, const mps *M, size_t i, const double *const u[3],
                               double *bt, double *br2) {
    const double *x0 = sim->ps.f[RY_F_X], *x1 = sim->ps.f[RY_F_X + 1], *x2 = sim->ps.f[RY_F_X + 2],
                 re = M->re_g;
    const size_t q0 = sim->nl.offset[i], nb = M->gend[i] - q0;
    const uint32_t *jj = M->pj + q0;
    const double *rr = M->pr + q0, xi0 = x0[i], xi1 = x1[i], xi2 = x2[i];
    const double ui0 = u[0][i], ui1 = u[1][i], ui2 = u[2][i];
#pragma omp simd
    for (size_t k = 0; k < nb; ++k) {
        const uint32_t j = jj[k];
        const double e0 = x0[j] - xi0, e1 = x1[j] - xi1, e2 = x2[j] - xi2;
        double du = 0.0;
        du += (u[0][j] - ui0) * e0;
        du += (u[1][j] - ui1) * e1;
        du += (u[2][j] - ui2) * e2;
        const double r2 = e0 * e0 + e1 * e1 + e2 * e2, sr = rr[k] / re - 1.0;
        br2[k] = r2;
        bt[k] = ry_mps_divergence_term(du, r2, rr[k] < re ? sr * sr : 0.0);
    }
    double s = 0;
    for (size_t k = 0; k < nb; ++k)
        if (br2[k] > 0) s += bt[k];
    return ry_mps_divergence(s, 3, M->n0g);
}

/* Number density (ratio n/n0) of every particle at the current positions, and the roles: free
 * surface (p = 0) for fluid and wall particles with n < beta n0 (walls above the water line);
 * the other wall particles with a fluid neighbour within re take part in the pressure
 * equation (those of thin bodies whatever their number density), the rest are dummies. */
void mps_number_density(ry_sim *sim, mps *M) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const double re = M->re_g, reach = M->wall_reach;
    double *nd = ps->f[M->f_nd], *surf = ps->f[M->f_surf];
    const int div = M->gamma < 1.0, lanes = div && ry_box_plain(&sim->box) == 3;
    /* (lanes) the velocity each particle brings to the divergence, in M->b, which the
     * pressure equation fills only later */
    double *u[3] = {M->b, M->b + n, M->b + 2 * n};
    size_t rowmax = 0;
    for (size_t i = 0; lanes && i < n; ++i) {
        const int fl = ps->kind[i] == RY_KIND_FLUID;
        for (int d = 0; d < 3; ++d) u[d][i] = (fl ? ps->f[M->f_vs[d]] : ps->f[RY_F_VX + d])[i];
        if (M->gend[i] - sim->nl.offset[i] > rowmax) rowmax = M->gend[i] - sim->nl.offset[i];
    }
#pragma omp parallel
    {
        double *buf = lanes ? malloc(2 * (rowmax + 1) * sizeof *buf) : NULL;
#pragma omp for schedule(dynamic, 64)
        for (size_t i = 0; i < n; ++i) {
            double s = 0;
            int fluid_near = 0;
            for (size_t q = sim->nl.offset[i]; q < M->gend[i]; ++q) {
                const double r = M->pr[q];
                s += ry_mps_weight_tamai(r, re);
                if (ps->kind[M->pj[q]] == RY_KIND_FLUID && r < reach) fluid_near = 1;
            }
            nd[i] = s / M->n0g;
            if (ps->kind[i] == RY_KIND_FLUID) {
                M->role[i] = nd[i] < M->beta ? ROLE_SURFACE : ROLE_FLUID;
            } else {
                const int thin = M->thin && M->thin[i] >= 0;
                const int closed = thin || (!M->inlet_surface && ps->kind[i] == RY_KIND_INLET) ||
                                   (M->wall_neumann && ps->kind[i] == RY_KIND_WALL);
                M->role[i] = !fluid_near                  ? ROLE_DUMMY
                             : nd[i] < M->beta && !closed ? ROLE_SURFACE
                                                          : ROLE_WALL;
            }
            surf[i] = M->role[i] == ROLE_SURFACE && ps->kind[i] == RY_KIND_FLUID;
            /* the source's divergence of u* for the unknowns, while the row's pairs are at
             * hand */
            if (div &&
                (M->role[i] == ROLE_FLUID || (M->role[i] == ROLE_WALL && !wall_out(sim, M, i))))
                M->divu[i] = buf ? divergence_lanes(sim, M, i, (const double *const *)u, buf,
                                                    buf + rowmax + 1)
                                 : divergence(sim, M, i);
        }
        free(buf);
    }
}
