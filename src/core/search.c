/* The neighbour search of a simulation: the list brought up to date (rebuilt or reused
 * within its skin), edited after in- and outflow, and the queries on the last search. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "neighbor/neighbor_internal.h"
#include "ryushi/sim.h"

/* Largest squared displacement since the last list build. Halo copies (a distributed run's,
 * symmetry planes') do not count: they follow their originals at their next update, and
 * until then hold what the step made of them. */
static double max_drift2(const ry_sim *sim) {
    const ry_particles *ps = &sim->ps;
    double m = 0;
    const size_t n = ps->n;
    const int dim = sim->dim;
    const double *x[3], *xr[3];
    ry_particles_coords(ps, x);
    for (int d = 0; d < dim; ++d) xr[d] = ps->f[sim->f_xref + d];
#pragma omp parallel for schedule(static) reduction(max : m)
    for (size_t i = 0; i < n; ++i) {
        if (ry_sim_is_halo(sim, i)) continue;
        double r2 = 0;
        for (int d = 0; d < dim; ++d) {
            double e = x[d][i] - xr[d][i];
            r2 += e * e;
        }
        m = fmax(m, r2);
    }
    return m;
}

const ry_cell_list *ry_sim_cells_within(const ry_sim *sim, double dist, double *drift) {
    const ry_cell_list *cl = &sim->cells;
    if (sim->par || sim->nopen > 0 || sim->nl_restore || !cl->start || cl->n != sim->ps.n ||
        sim->f_xref < 0)
        return NULL;
    double edge = INFINITY;
    for (int d = 0; d < sim->dim; ++d) edge = fmin(edge, cl->cell[d]);
    /* a pair now closer than dist was closer than dist + 2 drift at the search */
    *drift = sqrt(max_drift2(sim));
    return dist + 2 * *drift < edge ? cl : NULL;
}

ry_status ry_sim_neighbors(ry_sim *sim, double radius, ry_error *err) {
    ry_particles *ps = &sim->ps;
    const double skin = sim->nl_skin * radius;
    const int have = sim->cells_only ? sim->cells.start && sim->cells.n == ps->n
                                     : sim->nl.offset && sim->nl.n == ps->n;
    const int known = sim->drift_known;
    sim->drift_known = 0;
    int reuse = have && !sim->nl_restore && radius == sim->nl_radius && skin > 0 &&
                (known ? sim->drift2 : max_drift2(sim)) < 0.25 * skin * skin;
    /* A distributed run searches on every rank when any rank must. */
    if (sim->par) reuse = sim->par->all(sim, reuse);
    if (reuse) {
        sim->nl_reuses++;
        return sim->par ? sim->par->halo_update(sim, err) : RY_OK;
    }
    const double *x[3];
    const double reach = radius + skin;
    if (sim->par && !sim->par->redistribute_at_ref) sim->nl_restore = 0;
    if (sim->nl_restore && radius == sim->nl_radius && ps->n > 0) {
        /* After a restart: the list of the last build, from the positions it was built at,
         * then the same decision as in the uninterrupted run: reuse it, or search afresh
         * (which reorders the particles when the scheme sorts at every search). */
        sim->nl_restore = 0;
        if (sim->par) RY_TRY(sim->par->redistribute_at_ref(sim, reach, err));
        for (int d = 0; d < 3; ++d) x[d] = d < sim->dim ? ps->f[sim->f_xref + d] : NULL;
        RY_TRY(ry_cells_build(&sim->cells, &sim->box, reach, ps->n, x, err));
        sim->nl_generation++;
        if (!sim->cells_only)
            RY_TRY(ry_nlist_build_cells(&sim->nl, &sim->cells, &sim->box, reach, ps->n, x, err));
        if (skin > 0 && max_drift2(sim) < 0.25 * skin * skin) {
            sim->nl_reuses++;
            return sim->par ? sim->par->halo_update(sim, err) : RY_OK;
        }
    }
    sim->nl_restore = 0;
    if (sim->par) RY_TRY(sim->par->redistribute(sim, reach, err));
    ry_particles_coords(ps, x);
    RY_TRY(ry_cells_build(&sim->cells, &sim->box, reach, ps->n, x, err));
    if (sim->sort_always || (sim->reorder_every > 0 && sim->searches % sim->reorder_every == 0)) {
        if (sim->sort_always) ry_cells_sort_x(&sim->cells, x[0]);
        const int rebin = sim->par && sim->par->partition &&
                          sim->par->partition(sim, sim->cells.order); /* the copies last */
        RY_TRY(ry_particles_permute(ps, sim->cells.order, err));
        if (sim->par) sim->par->permuted(sim, sim->cells.order);
        ry_particles_coords(ps, x);
        if (rebin)
            RY_TRY(ry_cells_build(&sim->cells, &sim->box, reach, ps->n, x, err));
        else
            ry_cells_permuted(&sim->cells);
    }
    sim->searches++;
    sim->nl_generation++;
    sim->nl_radius = radius;
    for (int d = 0; d < sim->dim; ++d) memcpy(ps->f[sim->f_xref + d], x[d], ps->n * sizeof(double));
    if (sim->cells_only) return RY_OK;
    return ry_nlist_build_cells(&sim->nl, &sim->cells, &sim->box, reach, ps->n, x, err);
}

/* The surviving entries of the old row o, renumbered, into out (NULL: counted only). */
static size_t row_survivors(const ry_nlist *nl, size_t o, const size_t *newidx, uint32_t *out) {
    size_t c = 0;
    for (size_t q = nl->offset[o]; q < nl->offset[o + 1]; ++q)
        if (newidx[nl->j[q]] != SIZE_MAX) {
            if (out) out[c] = (uint32_t)newidx[nl->j[q]];
            ++c;
        }
    return c;
}

int ry_sim_body_of(const ry_sim *sim, int64_t id) {
    const size_t n = sim->nbodies;
    if (!sim->body_first_id || n == 0 || id < sim->body_first_id[0] || id >= sim->body_first_id[n])
        return -1;
    size_t lo = 0, hi = n; /* first_id[lo] <= id < first_id[hi] */
    while (hi - lo > 1) {
        const size_t mid = (lo + hi) / 2;
        if (sim->body_first_id[mid] <= id)
            lo = mid;
        else
            hi = mid;
    }
    return (int)lo;
}

/* The list after ry_open_update (see sim.h). Pairs are those of a build from the reference
 * positions (each row holds j with |xref_i - xref_j| < reach, sorted): the surviving rows keep
 * their surviving entries, renumbered (the compaction keeps the order, so the rows stay
 * sorted); a new particle takes its position as its reference and pairs with every particle
 * within reach of it, found by a scan of all of them (a few new particles against a search of
 * every row). */
ry_status ry_sim_list_edit(ry_sim *sim, size_t n_old, size_t nspawn, const uint8_t *remove,
                           ry_error *err) {
    ry_particles *ps = &sim->ps;
    ry_nlist *nl = &sim->nl;
    const size_t n = ps->n;
    /* Otherwise the next call of ry_sim_neighbors searches afresh (the count differs). */
    if (sim->cells_only || sim->par || sim->nl_restore || !nl->offset || nl->n != n_old ||
        !(sim->nl_skin > 0) || !(sim->nl_radius > 0) || (nspawn == 0 && !remove))
        return RY_OK;
    const int dim = sim->dim;
    const double reach = sim->nl_radius + sim->nl_skin * sim->nl_radius; /* as the search */
    const double r2max = reach * reach;
    const double *xc[3]; /* the reference positions */
    for (int d = 0; d < 3; ++d) xc[d] = d < dim ? ps->f[sim->f_xref + d] : NULL;
    const size_t first = n - nspawn; /* the new particles, last after the compaction */
    for (size_t k = first; k < n; ++k)
        for (int d = 0; d < dim; ++d) ps->f[sim->f_xref + d][k] = ps->f[RY_F_X + d][k];
    size_t *newidx = malloc((n_old + 1) * sizeof *newidx); /* old -> new, SIZE_MAX: removed */
    size_t *oldof = malloc((n + 1) * sizeof *oldof);       /* new -> old (survivors) */
    size_t *add = calloc(n + 1, sizeof *add);              /* new pairs per particle */
    const size_t cap_n = n + n / 4 + 16; /* room to grow, as the search's own arrays */
    size_t *off = malloc((cap_n + 1) * sizeof *off), cap_hits = 64, nhits = 0, cap_j = 0;
    uint32_t *hits = malloc(2 * cap_hits * sizeof *hits); /* (i, k) with i < k or new */
    uint32_t *nj = NULL;
    ry_status st = RY_OK;
    if (!newidx || !oldof || !add || !off || !hits) goto nomem;
    for (size_t o = 0, a = 0; o < n_old; ++o) {
        newidx[o] = remove && remove[o] ? SIZE_MAX : a;
        if (newidx[o] != SIZE_MAX) oldof[a++] = o;
    }
    ry_nb_geom g;
    ry_nb_geom_init(&g, &sim->box);
    for (size_t k = first; k < n; ++k)
        for (size_t i = 0; i < n; ++i) {
            if (i == k || ry_nb_r2(&g, dim, xc, i, k) >= r2max) continue;
            if (nhits == cap_hits) {
                uint32_t *h = realloc(hits, 4 * cap_hits * sizeof *h);
                if (!h) goto nomem;
                hits = h;
                cap_hits *= 2;
            }
            hits[2 * nhits] = (uint32_t)i;
            hits[2 * nhits++ + 1] = (uint32_t)k;
            if (i < first) add[i]++; /* pairs to append to the old row i */
            add[k]++;                /* the length of the new row k */
        }
    /* Row lengths, their prefix sums, the rows. The new particles' own rows hold their hits
     * (by i ascending); a surviving row gets its new neighbours after the old ones (the new
     * indices are the largest). */
    const long long nn = (long long)n;
#pragma omp parallel for schedule(static)
    for (long long aa = 0; aa < nn; ++aa) {
        const size_t a = (size_t)aa;
        off[a + 1] = add[a] + (a < first ? row_survivors(nl, oldof[a], newidx, NULL) : 0);
    }
    off[0] = 0;
    size_t maxrow = 0;
    for (size_t a = 0; a < n; ++a) {
        if (off[a + 1] > maxrow) maxrow = off[a + 1];
        off[a + 1] += off[a];
    }
    cap_j = off[n] + off[n] / 8 + 16;
    nj = malloc(cap_j * sizeof *nj);
    if (!nj) goto nomem;
#pragma omp parallel for schedule(static)
    for (long long aa = 0; aa < nn; ++aa)
        if ((size_t)aa < first) row_survivors(nl, oldof[aa], newidx, nj + off[aa]);
    /* the hits in the order found, k ascending and then i ascending: row i (old) takes the new
     * particles ascending after its old entries, row k its hits */
    for (size_t h = 0; h < nhits; ++h) {
        const size_t i = hits[2 * h], k = hits[2 * h + 1];
        if (i < first) nj[off[i + 1] - add[i]--] = (uint32_t)k;
        nj[off[k + 1] - add[k]--] = (uint32_t)i;
    }
    free(nl->j);
    free(nl->offset);
    nl->j = nj;
    nl->offset = off;
    nl->cap_j = cap_j;
    nl->cap_n = cap_n;
    nl->n = n;
    nl->max_row = maxrow;
    nj = NULL;
    off = NULL;
    sim->nl_edits++;
    sim->nl_generation++;
    /* the cells as a search from the reference positions would leave them */
    st = ry_cells_build(&sim->cells, &sim->box, reach, n, xc, err);
    goto done;
nomem:
    st = ry_error_set(err, RY_ERR_NOMEM, "out of memory (neighbour list after in- and outflow)");
done:
    free(newidx);
    free(oldof);
    free(add);
    free(off);
    free(hits);
    free(nj);
    return st;
}

double ry_sim_bytes_per_particle(const ry_sim *sim) {
    const size_t n = sim->ps.n;
    double b = (double)ry_particles_bytes_per_particle(&sim->ps) +
               ry_cells_bytes_per_particle(&sim->cells) + ry_nlist_bytes_per_particle(&sim->nl);
    if (n && sim->scheme && sim->scheme->bytes && sim->scheme_state)
        b += (double)sim->scheme->bytes(sim->scheme_state) / (double)n;
    return b;
}

size_t ry_sim_count_within(const ry_sim *sim, size_t i, double radius) {
    const ry_cell_list *cl = &sim->cells;
    const ry_particles *ps = &sim->ps;
    if (!cl->start || cl->n != ps->n) return 0;
    int per[3];
    for (int d = 0; d < 3; ++d) per[d] = d < sim->dim && sim->box.periodic[d];
    size_t cells[27], count = 0;
    const int nc = ry_cells_neighbours(cl, per, cl->cell_of[i], cells);
    for (int c = 0; c < nc; ++c)
        for (size_t q = cl->start[cells[c]]; q < cl->start[cells[c] + 1]; ++q) {
            const uint32_t j = cl->order[q];
            double dx[3] = {0, 0, 0}, r2 = 0;
            for (int d = 0; d < sim->dim; ++d) dx[d] = ps->f[RY_F_X + d][i] - ps->f[RY_F_X + d][j];
            ry_box_min_image(&sim->box, dx);
            for (int d = 0; d < sim->dim; ++d) r2 += dx[d] * dx[d];
            count += j != i && r2 < radius * radius;
        }
    return count;
}

size_t ry_sim_count_outside(const ry_sim *sim) {
    size_t count = 0;
    const ry_particles *ps = &sim->ps;
    for (size_t i = 0; i < ps->n; ++i)
        for (int d = 0; d < sim->dim; ++d) {
            double x = ps->f[RY_F_X + d][i];
            if (!(x >= sim->box.lo[d] && x < sim->box.hi[d])) {
                ++count;
                break;
            }
        }
    return count;
}

void ry_sim_drift_measured(ry_sim *sim, double drift2) {
    sim->drift2 = drift2;
    sim->drift_known = 1;
}
