/* The walls of MPS (docs/reference/mps.md): wall particles, which take part in the pressure
 * equation, and dummy particles, which only add to the number density (their roles:
 * mps_number_density); thin walls (bodies[k].thin: a sheet's normals and the pairs it cuts, "Thin
 * walls"); the wall pressure for the gradient extrapolated from the fluid (as Adami et al. 2012 do
 * for SPH); and what the wall velocity of the viscous terms needs: the distances to the wall
 * surface of the mirrored no-slip wall (Morris et al. 1997) and the contact lines of two liquids,
 * where a wall gives no shear stress (Qian, Wang & Sheng 2003). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "boundary/walls_adami2012.h"
#include "schemes/mps/mps_internal.h"

/* Checks that bodies[k], named in key, has no particle of another kind than wall (a body may
 * be left with none, e.g. wholly beyond a symmetry plane). */
ry_status mps_body_is_wall(ry_sim *sim, ry_case *c, size_t k, const char *key, ry_error *err) {
    char where[256];
    size_t others = 0;
    for (size_t i = 0; i < sim->ps.n; ++i)
        others += ry_sim_body_of(sim, sim->ps.id[i]) == (int)k && sim->ps.kind[i] != RY_KIND_WALL;
    RY_CHECK(err, others == 0, RY_ERR_INPUT, "%s: key '%s': applies to a body of kind wall",
             ry_case_where(c, key, where, sizeof where), key);
    return RY_OK;
}

/* Thin walls (docs/reference/mps.md, "Thin walls"): bodies[k].thin. A wall of one layer with air
 * behind it reads a number density below the free-surface threshold, and as free surface (p = 0) it
 * could not hold the pressure of the fluid on its other side. The particles of such a body
 * with a fluid particle within reach always take part in the pressure equation. */
ry_status mps_body_thin(ry_sim *sim, ry_case *c, mps *M, ry_error *err) {
    char key[160];
    for (size_t k = 0; k < sim->nbodies; ++k) {
        snprintf(key, sizeof key, "bodies[%zu].thin", k);
        if (!ry_case_has(c, key)) continue;
        const int no = 0;
        int on;
        RY_TRY(ry_case_bool(c, key, &no, &on, err));
        if (!on) continue;
        RY_TRY(mps_body_is_wall(sim, c, k, key, err));
        if (!M->body_thin) {
            M->body_thin = calloc(sim->nbodies, 1);
            RY_CHECK(err, M->body_thin != NULL, RY_ERR_NOMEM, "out of memory");
        }
        M->body_thin[k] = 1;
    }
    return RY_OK;
}

/* Thin walls, part 2 (docs/reference/mps.md, "Thin walls"): pairs on the two sides of a thin wall
 * take no part in any term. Each thin wall particle k has the unit normal of its body's sheet (the
 * null direction of the second moment of the same body's particles within 1.5 l0; none where
 * the body turns a corner, so that it cuts nothing there). The pair
 * (i, j) is cut where it crosses the plane of some thin wall particle k near either end (both
 * ends at least l0/4 off the plane) within 0.75 l0 of k: a line through a sheet of particles
 * l0 apart passes within l0/sqrt(2) of one of them, and a line that passes the sheet's edge
 * (the catheter's tip) farther off is not cut. The test takes the pair in one order, so the
 * cut is symmetric, as the pressure matrix must be. */
static void thin_normals(ry_sim *sim, mps *M) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const double r2max = 2.25 * sim->dx * sim->dx;
    const int dim = sim->dim;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        double *nv = M->tnrm + 3 * i;
        nv[0] = nv[1] = nv[2] = 0;
        if (M->thin[i] < 0) continue;
        double c[3][3] = {{0}};
        for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) {
            const uint32_t j = sim->nl.j[q];
            double dx[3];
            if (M->thin[j] != M->thin[i] || ry_sim_separation(sim, i, j, dx) > r2max) continue;
            for (int a = 0; a < 3; ++a)
                for (int b = 0; b < 3; ++b) c[a][b] += dx[a] * dx[b];
        }
        if (dim == 2) { /* the sheet is a line: the normal is across its largest row */
            const int r =
                c[0][0] * c[0][0] + c[0][1] * c[0][1] >= c[1][0] * c[1][0] + c[1][1] * c[1][1] ? 0
                                                                                               : 1;
            nv[0] = -c[r][1];
            nv[1] = c[r][0];
        } else { /* rank 2: the largest cross product of two rows */
            double best = -1;
            for (int a = 0; a < 3; ++a) {
                const int b = (a + 1) % 3;
                const double x[3] = {c[a][1] * c[b][2] - c[a][2] * c[b][1],
                                     c[a][2] * c[b][0] - c[a][0] * c[b][2],
                                     c[a][0] * c[b][1] - c[a][1] * c[b][0]};
                const double m = x[0] * x[0] + x[1] * x[1] + x[2] * x[2];
                if (m > best) {
                    best = m;
                    memcpy(nv, x, sizeof x);
                }
            }
        }
        const double m = sqrt(nv[0] * nv[0] + nv[1] * nv[1] + nv[2] * nv[2]);
        for (int d = 0; d < 3; ++d) nv[d] = m > 0 ? nv[d] / m : 0;
        /* not a sheet here (a corner where the body turns): no normal, no cut */
        double q = 0;
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) q += nv[a] * c[a][b] * nv[b];
        if (q > 0.01 * (c[0][0] + c[1][1] + c[2][2])) nv[0] = nv[1] = nv[2] = 0;
    }
}

/* Does a thin wall particle k near one end of the pair separate particles a and b? The list
 * ks[0..nk-1] holds the thin particles near the end `own` (a, or b where own_b), with
 * own_d[4 m] = x_own - x_k and its part along k's normal; the other end's are computed. */
static int thin_between(ry_sim *sim, const mps *M, size_t a, size_t b, int own_b,
                        const uint32_t *ks, const double *own_d, size_t nk) {
    const double l0 = sim->dx, off = 0.25 * l0, reach2 = 0.5625 * l0 * l0;
    const size_t far = own_b ? a : b;
    for (size_t m = 0; m < nk; ++m) {
        const uint32_t k = ks[m];
        if (k == a || k == b) continue;
        const double *od = own_d + 4 * m;
        if (fabs(od[3]) < off) continue;
        const double *nv = M->tnrm + 3 * k;
        double fd[3];
        ry_sim_separation(sim, k, far, fd);
        const double fs = nv[0] * fd[0] + nv[1] * fd[1] + nv[2] * fd[2];
        if (fabs(fs) < off) continue;
        const double *da = own_b ? fd : od, *db = own_b ? od : fd;
        const double sa = own_b ? fs : od[3], sb = own_b ? od[3] : fs;
        if (!(sa * sb < 0)) continue;
        const double t = sa / (sa - sb);
        double c2 = 0;
        for (int d = 0; d < 3; ++d) {
            const double c = da[d] + t * (db[d] - da[d]);
            c2 += c * c;
        }
        if (c2 < reach2) return 1;
    }
    return 0;
}

static ry_status thin_cut(ry_sim *sim, mps *M, int fluid_rows, ry_error *err) {
    const ry_particles *ps = &sim->ps;
    const size_t n = ps->n, nq = sim->nl.offset[n];
    thin_normals(sim, M);
    M->st.cut = NULL;
    M->ncut = 0;
    if (!M->thin_cut_on) return RY_OK;
    /* the thin wall particles within 2.3 l0 of each particle: the crossing lies within half
     * the pair's length (at most re, 3.1 l0) of one end, and k within 0.75 l0 of it. The list
     * is symmetric, so they come from the rows of the thin particles, which are few: rows far
     * from every thin wall are not read. */
    const double r2k = 2.3 * 2.3 * sim->dx * sim->dx;
    uint32_t *cnt = M->tn_off + 1;
    memset(M->tn_off, 0, (n + 1) * sizeof *M->tn_off);
    for (size_t k = 0; k < n; ++k) {
        if (M->thin[k] < 0) continue;
        for (size_t q = sim->nl.offset[k]; q < sim->nl.offset[k + 1]; ++q) {
            double dx[3];
            const uint32_t j = sim->nl.j[q];
            cnt[j] += ry_sim_separation(sim, j, k, dx) < r2k;
        }
    }
    for (size_t i = 0; i < n; ++i) M->tn_off[i + 1] += M->tn_off[i];
    if (M->tn_cap < M->tn_off[n] || !M->tn_j || !M->tn_d) {
        const size_t c = M->tn_off[n] + M->tn_off[n] / 4 + 16;
        uint32_t *t = realloc(M->tn_j, c * sizeof *t);
        if (t) M->tn_j = t;
        double *td = realloc(M->tn_d, 4 * c * sizeof *td);
        if (td) M->tn_d = td;
        RY_CHECK(err, t && td, RY_ERR_NOMEM, "out of memory (thin walls)");
        M->tn_cap = c;
    }
    if (M->cut_cap < nq || !M->cut) {
        const size_t c = nq + nq / 4 + 16;
        uint8_t *t = realloc(M->cut, c);
        RY_CHECK(err, t != NULL, RY_ERR_NOMEM, "out of memory (thin walls)");
        M->cut = t;
        M->cut_cap = c;
    }
    /* fill each particle's list from its end down: tn_off[i + 1] ends at i's start, and one
     * shift makes it the start again */
    const uint32_t total = M->tn_off[n];
    for (size_t k = 0; k < n; ++k) {
        if (M->thin[k] < 0) continue;
        for (size_t q = sim->nl.offset[k]; q < sim->nl.offset[k + 1]; ++q) {
            double dx[3];
            const uint32_t j = sim->nl.j[q];
            if (ry_sim_separation(sim, j, k, dx) < r2k) M->tn_j[--cnt[j]] = (uint32_t)k;
        }
    }
    memmove(M->tn_off, M->tn_off + 1, n * sizeof *M->tn_off);
    M->tn_off[n] = total;
    /* each particle's separation from its thin neighbours, and the part along their normals */
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i)
        for (uint32_t m = M->tn_off[i]; m < M->tn_off[i + 1]; ++m) {
            const uint32_t k = M->tn_j[m];
            const double *nv = M->tnrm + 3 * k;
            double *td = M->tn_d + 4 * (size_t)m;
            ry_sim_separation(sim, k, i, td);
            td[3] = nv[0] * td[0] + nv[1] * td[1] + nv[2] * td[2];
        }
    /* the rows with a pair that may be cut: a particle with a thin one near, and its
     * neighbours */
    uint8_t *act = M->cut_row;
    memset(act, 0, n);
    for (size_t i = 0; i < n; ++i) {
        if (M->tn_off[i + 1] == M->tn_off[i]) continue;
        act[i] = 1;
        for (size_t q = sim->nl.offset[i]; q < sim->nl.offset[i + 1]; ++q) act[sim->nl.j[q]] = 1;
    }
    /* the cut pairs within the interaction radius are counted for the statistic cut_pairs */
    const double rm2 = M->re_max * M->re_max;
    size_t nc = 0;
#pragma omp parallel for reduction(+ : nc) schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        const size_t q0 = sim->nl.offset[i], q1 = sim->nl.offset[i + 1];
        if (fluid_rows && ps->kind[i] != RY_KIND_FLUID) continue; /* rows not read (x^n) */
        if (!act[i]) {
            memset(M->cut + q0, 0, q1 - q0);
            continue;
        }
        for (size_t q = q0; q < q1; ++q) {
            const uint32_t j = sim->nl.j[q];
            const size_t a = i < j ? i : j, b = i < j ? j : i;
            uint8_t cut = 0;
            double dx[3];
            /* (the pairs of the list's skin take part in nothing) */
            const int near = M->tn_off[a + 1] > M->tn_off[a] || M->tn_off[b + 1] > M->tn_off[b];
            if (near && (ps->kind[a] != RY_KIND_WALL || ps->kind[b] != RY_KIND_WALL) &&
                ry_sim_separation(sim, i, j, dx) < rm2)
                cut = (uint8_t)(thin_between(sim, M, a, b, 0, M->tn_j + M->tn_off[a],
                                             M->tn_d + 4 * (size_t)M->tn_off[a],
                                             M->tn_off[a + 1] - M->tn_off[a]) ||
                                thin_between(sim, M, a, b, 1, M->tn_j + M->tn_off[b],
                                             M->tn_d + 4 * (size_t)M->tn_off[b],
                                             M->tn_off[b + 1] - M->tn_off[b]));
            M->cut[q] = cut;
            nc += cut;
        }
    }
    M->st.cut = M->cut;
    M->ncut = nc;
    return RY_OK;
}

/* Each wall particle's body, every step (ids survive reordering): its wetting group
 * (bodies[k].contact_angle) and whether it is thin, with the pairs thin walls cut. */
ry_status mps_wall_bodies(ry_sim *sim, mps *M, int fluid_rows, ry_error *err) {
    if (!M->body_group && !M->body_thin) return RY_OK;
    const ry_particles *ps = &sim->ps;
    /* the particles keep their places between searches and edits of the set (a serial run) */
    const long key[3] = {sim->searches, sim->nl_edits, (long)ps->n};
    const int same = !sim->par && M->wb_valid && memcmp(key, M->wb_key, sizeof key) == 0;
    memcpy(M->wb_key, key, sizeof key);
    M->wb_valid = 1;
    for (size_t i = 0; i < ps->n && !same; ++i) {
        const int b = ps->kind[i] == RY_KIND_WALL ? ry_sim_body_of(sim, ps->id[i]) : -1;
        if (M->body_group) M->wgroup[i] = b >= 0 ? M->body_group[b] : 0;
        if (M->body_thin) M->thin[i] = b >= 0 && M->body_thin[b] ? b : -1;
    }
    if (M->body_group) M->st.wall_group = M->wgroup;
    if (!M->body_thin) return RY_OK;
    RY_TRY(thin_cut(sim, M, fluid_rows, err));
    M->st.thin_normal = M->tnrm; /* the potential model's images of thin walls */
    return RY_OK;
}

/* `scheme.contact_line_slip`: marks the fluid particles that have a fluid particle of another
 * material within the Laplacian's radius, the liquids' interface. Where such a particle meets a
 * wall, the wall gives it no shear stress (wall_beta 0), so that the line where the interface
 * meets the wall can slide while the wall holds each liquid elsewhere: the slip of the
 * generalised Navier boundary condition, which is confined to the contact line (Qian, Wang &
 * Sheng 2003), at the resolution of the particles. */
void mps_contact_lines(ry_sim *sim, mps *M) {
    const ry_particles *ps = &sim->ps;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < ps->n; ++i) {
        uint8_t c = 0;
        if (ps->kind[i] == RY_KIND_FLUID)
            for (size_t q = sim->nl.offset[i]; q < M->lend[i] && !c; ++q) {
                const uint32_t j = M->pj[q];
                c = ps->kind[j] == RY_KIND_FLUID && ps->material[j] != ps->material[i];
            }
        M->cline[i] = c;
    }
}

/* The distances of the mirrored wall velocity (wall_beta): each particle's to the nearest particle
 * of the other kind within re_l, less half a spacing. */
void mps_wall_distances(ry_sim *sim, mps *M) {
    const ry_particles *ps = &sim->ps;
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < ps->n; ++i) {
        const int fi = ps->kind[i] == RY_KIND_FLUID;
        double rmin = INFINITY;
        for (size_t q = sim->nl.offset[i]; q < M->lend[i]; ++q)
            if ((ps->kind[M->pj[q]] == RY_KIND_FLUID) != fi) rmin = fmin(rmin, M->pr[q]);
        M->wd[i] = isfinite(rmin) ? fmax(rmin - 0.5 * sim->dx, 0.0) : INFINITY;
    }
}

/* Wall pressure for the gradient extrapolated from the fluid (boundary/walls_adami2012.h, eq.
 * 27, with the MPS weight and each liquid's density) over the fluid within re_g, not negative.
 * Kept in the xs work array (the PPE values stay in the pressure field). */
void mps_extrapolate_walls(ry_sim *sim, mps *M) {
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n;
    const double re = M->re_g;
    double *pw = M->xs + n;
    const double *p = ps->f[RY_F_P];
#pragma omp parallel for schedule(dynamic, 64)
    for (size_t i = 0; i < n; ++i) {
        pw[i] = p[i];
        if (M->role[i] != ROLE_WALL || !(M->wall_extrapolate || thin_out(M, i))) continue;
        ry_adami_sums all = {0, 0, {0, 0, 0}}, sides[2] = {{0, 0, {0, 0, 0}}, {0, 0, {0, 0, 0}}};
        const double *tn = thin_normal(M, i);
        for (size_t q = sim->nl.offset[i]; q < M->gend[i]; ++q) {
            const uint32_t j = M->pj[q];
            if (ps->kind[j] != RY_KIND_FLUID) continue;
            double dx[3];
            ry_sim_separation(sim, i, j, dx); /* x_j - x_i */
            const double dwf[3] = {-dx[0], -dx[1], -dx[2]};
            const double w = ry_mps_weight_tamai(M->pr[q], re);
            const double head =
                ry_adami_head(sim->gravity, dwf, sim->dim, sim->mat[ps->material[j]].density);
            ry_adami_add_pressure(&all, w, p[j], head);
            if (tn) { /* a thin wall: the fluid on either side of its sheet apart */
                const int side = tn[0] * dx[0] + tn[1] * dx[1] + tn[2] * dx[2] < 0;
                ry_adami_add_pressure(&sides[side], w, p[j], head);
            }
        }
        if (all.sw > 0) pw[i] = fmax(ry_adami_pressure(&all), 0.0);
        if (tn)
            for (int side = 0; side < 2; ++side)
                M->tpw[2 * i + side] =
                    sides[side].sw > 0 ? fmax(ry_adami_pressure(&sides[side]), 0.0) : pw[i];
    }
    for (size_t i = 0; i < n; ++i)
        if (M->role[i] == ROLE_WALL) ps->f[RY_F_P][i] = pw[i];
}
