/* Domain decomposition on MPI (see mpi_dd.h and docs/parallel.md). */
#include "parallel/mpi_dd.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/guard_check.h"
#include "ryushi/atomic_file.h"
#include "ryushi/output.h"
#include "ryushi/clock.h"
#include "ryushi/open_boundary.h"
#include "ryushi/run.h"

/* Bisection steps per cut: the cut is placed to 2^-40 of the node's extent. */
#define ORB_ITERATIONS 40

typedef struct orb_node {
    int r0, r1; /* the ranks [r0, r1) share this node */
    int axis;   /* cut axis; -1 for a leaf */
    double cut;
    int lo, hi;                  /* children: x[axis] < cut, and the others */
    double box_lo[3], box_hi[3]; /* the domain box cut so far: picks the axis, bounds the search */
    double reg_lo[3], reg_hi[3]; /* the region owned: the same with the outer faces at infinity */
} orb_node;

typedef struct par {
    MPI_Comm comm;
    int rank, size;
    ry_sim *view; /* rank 0: the whole set, for output and checkpoints */
    double imbalance;
    orb_node *tree;
    int nnodes;
    int *leaf;    /* node of each rank's region */
    int nf, *fid; /* the particle fields in use */
    int *scount;  /* halo: particles sent to each rank */
    int *rcount;  /* halo: particles received from each rank */
    size_t *sidx; /* halo: the particles sent, grouped by destination */
    size_t nsend;
    size_t *rslot; /* halo: where the received ones are, grouped by source */
    size_t nrecv;
    uint8_t *halo; /* per particle: a halo copy */
    double *sbuf, *rbuf;
    size_t scap, rcap; /* doubles */
    MPI_Request *req;
    int canonical; /* the next search bisects afresh and puts the particles in id order */
    ry_mpi_stats st;
} par;

static par *get(const ry_sim *sim) {
    return (par *)sim->par_state;
}

/* Failures that leave the ranks out of step cannot be reported collectively. */
static void die(par *P, const char *what) {
    fprintf(stderr, "ryushi-mpi: rank %d: %s\n", P->rank, what);
    MPI_Abort(P->comm, 1);
}

static void *xrealloc(par *P, void *p, size_t bytes) {
    void *q = realloc(p, bytes ? bytes : 1);
    if (!q) die(P, "out of memory");
    return q;
}

static double *sbuf(par *P, size_t n) {
    if (n > P->scap) {
        P->scap = n + n / 2;
        P->sbuf = xrealloc(P, P->sbuf, P->scap * sizeof(double));
    }
    return P->sbuf;
}

static double *rbuf(par *P, size_t n) {
    if (n > P->rcap) {
        P->rcap = n + n / 2;
        P->rbuf = xrealloc(P, P->rbuf, P->rcap * sizeof(double));
    }
    return P->rbuf;
}

/* ---- particle records: id, kind, material and every field, as doubles ------------------ */

static int rec_size(const par *P) {
    return 3 + P->nf;
}

static void pack(const par *P, const ry_particles *ps, size_t i, double *r) {
    r[0] = (double)ps->id[i];
    r[1] = ps->kind[i];
    r[2] = ps->material[i];
    for (int k = 0; k < P->nf; ++k) r[3 + k] = ps->f[P->fid[k]][i];
}

static void unpack(const par *P, ry_particles *ps, size_t i, const double *r) {
    ps->id[i] = (int64_t)r[0];
    ps->kind[i] = (uint8_t)r[1];
    ps->material[i] = (uint8_t)r[2];
    for (int k = 0; k < P->nf; ++k) ps->f[P->fid[k]][i] = r[3 + k];
}

/* Appends count particles from records (ids kept; the set's next id unchanged). */
static void append(par *P, ry_particles *ps, const double *recs, size_t count) {
    if (!count) return;
    const int64_t next = ps->next_id;
    size_t first;
    ry_error e = {0};
    if (ry_particles_add(ps, count, &first, &e) != RY_OK) die(P, e.msg);
    ps->next_id = next;
    const int rs = rec_size(P);
    for (size_t k = 0; k < count; ++k) unpack(P, ps, first + k, recs + k * (size_t)rs);
}

/* Sends each rank its records (grouped by destination in send, cnt[r] records for rank r);
 * returns the received records (grouped by source, counts in rcnt) in P->rbuf. */
static size_t exchange(par *P, const double *send, const int *cnt, int *rcnt) {
    const int rs = rec_size(P), n = P->size;
    MPI_Alltoall(cnt, 1, MPI_INT, rcnt, 1, MPI_INT, P->comm);
    int *sc = xrealloc(P, NULL, 4 * (size_t)n * sizeof(int));
    int *sd = sc + n, *rc = sc + 2 * n, *rd = sc + 3 * n;
    size_t total = 0, stotal = 0;
    for (int r = 0; r < n; ++r) {
        sc[r] = cnt[r] * rs;
        rc[r] = rcnt[r] * rs;
        sd[r] = (int)stotal;
        rd[r] = (int)total;
        stotal += (size_t)sc[r];
        total += (size_t)rc[r];
    }
    if (stotal > 2147483647u || total > 2147483647u) die(P, "exchange larger than 2^31 values");
    double *recv = rbuf(P, total);
    MPI_Alltoallv(send, sc, sd, MPI_DOUBLE, recv, rc, rd, MPI_DOUBLE, P->comm);
    free(sc);
    return total / (size_t)rs;
}

/* ---- orthogonal recursive bisection ---------------------------------------------------- */

/* The coordinates the decomposition follows (sim->dd_x). */
static void dd_coords(const ry_sim *sim, const double *x[3]) {
    for (int d = 0; d < 3; ++d) x[d] = d < sim->dim ? sim->ps.f[sim->dd_x[d]] : NULL;
}

static int owner(const par *P, const double *x[3], size_t i) {
    int n = 0;
    while (P->tree[n].axis >= 0) {
        const orb_node *o = &P->tree[n];
        n = x[o->axis][i] < o->cut ? o->lo : o->hi;
    }
    return P->tree[n].r0;
}

/* Squared distance from particle i to rank r's region. */
static double dist2(const par *P, const double *x[3], int dim, size_t i, int r) {
    const orb_node *o = &P->tree[P->leaf[r]];
    double s = 0;
    for (int d = 0; d < dim; ++d) {
        const double e = fmax(fmax(o->reg_lo[d] - x[d][i], x[d][i] - o->reg_hi[d]), 0.0);
        s += e * e;
    }
    return s;
}

/* The other ranks whose regions lie within w of particle i, found by descending the bisection
 * tree into the sides of each cut that w reaches (O(log P) per particle); returns how many. */
static int near_ranks(const par *P, const double *x[3], int dim, size_t i, double w, int *out) {
    int stack[128], sp = 0, k = 0;
    stack[sp++] = 0;
    while (sp > 0) {
        const orb_node *o = &P->tree[stack[--sp]];
        if (o->axis < 0) {
            if (o->r0 != P->rank && dist2(P, x, dim, i, o->r0) < w * w) out[k++] = o->r0;
            continue;
        }
        const double xi = x[o->axis][i];
        if (xi - w < o->cut && sp < 128) stack[sp++] = o->lo;
        if (xi + w >= o->cut && sp < 128) stack[sp++] = o->hi;
    }
    return k;
}

/* Bisects the particles of all ranks (each counted once: with round_robin, every rank holds the
 * whole set and counts every size-th particle) into one region per rank, balanced by count.
 * Each cut is found by bisection on its coordinate with the global counts, so that the tree
 * depends only on the set of positions, not on where the particles are held. */
static void orb_build(par *P, const ry_sim *sim, int round_robin) {
    const ry_particles *ps = &sim->ps;
    const int dim = sim->dim, size = P->size;
    const size_t n = ps->n;
    const double *x[3];
    dd_coords(sim, x);
    P->nnodes = 1;
    orb_node *root = &P->tree[0];
    memset(root, 0, sizeof *root);
    root->r0 = 0;
    root->r1 = size;
    root->axis = -1;
    for (int d = 0; d < 3; ++d) {
        root->box_lo[d] = d < dim ? sim->box.lo[d] : 0;
        root->box_hi[d] = d < dim ? sim->box.hi[d] : 0;
        root->reg_lo[d] = -INFINITY;
        root->reg_hi[d] = INFINITY;
    }
    int *node_of = xrealloc(P, NULL, n * sizeof(int));
    for (size_t i = 0; i < n; ++i)
        node_of[i] = (!round_robin || (int)(i % (size_t)size) == P->rank) ? 0 : -1;
    int *front = xrealloc(P, NULL, (size_t)size * sizeof(int));
    int *fmap = xrealloc(P, NULL, 2 * (size_t)size * sizeof(int));
    long *cnt = xrealloc(P, NULL, 2 * (size_t)size * sizeof(long));
    long *tot = cnt + size;
    double *a = xrealloc(P, NULL, 3 * (size_t)size * sizeof(double));
    double *b = a + size, *target = a + 2 * size;
    int nfront = size > 1;
    front[0] = 0;
    while (nfront > 0) {
        for (int k = 0; k < 2 * size; ++k) fmap[k] = -1;
        for (int f = 0; f < nfront; ++f) {
            orb_node *o = &P->tree[front[f]];
            int ax = 0;
            for (int d = 1; d < dim; ++d)
                if (o->box_hi[d] - o->box_lo[d] > o->box_hi[ax] - o->box_lo[ax]) ax = d;
            o->axis = ax;
            a[f] = o->box_lo[ax];
            b[f] = o->box_hi[ax];
            fmap[front[f]] = f;
            cnt[f] = 0;
        }
        for (size_t i = 0; i < n; ++i)
            if (node_of[i] >= 0 && fmap[node_of[i]] >= 0) cnt[fmap[node_of[i]]]++;
        MPI_Allreduce(cnt, tot, nfront, MPI_LONG, MPI_SUM, P->comm);
        for (int f = 0; f < nfront; ++f) {
            const orb_node *o = &P->tree[front[f]];
            const int k = o->r1 - o->r0, klo = k / 2;
            target[f] = (double)tot[f] * klo / k;
        }
        for (int it = 0; it < ORB_ITERATIONS; ++it) {
            for (int f = 0; f < nfront; ++f) cnt[f] = 0;
            for (size_t i = 0; i < n; ++i) {
                if (node_of[i] < 0) continue;
                const int f = fmap[node_of[i]];
                if (f < 0) continue;
                const int ax = P->tree[front[f]].axis;
                cnt[f] += x[ax][i] < 0.5 * (a[f] + b[f]);
            }
            MPI_Allreduce(MPI_IN_PLACE, cnt, nfront, MPI_LONG, MPI_SUM, P->comm);
            for (int f = 0; f < nfront; ++f) {
                const double mid = 0.5 * (a[f] + b[f]);
                if ((double)cnt[f] < target[f])
                    a[f] = mid;
                else
                    b[f] = mid;
            }
        }
        int next = 0;
        for (int f = 0; f < nfront; ++f) {
            const int id = front[f];
            orb_node *o = &P->tree[id];
            const int ax = o->axis, klo = (o->r1 - o->r0) / 2;
            o->cut = b[f];
            o->lo = P->nnodes++;
            o->hi = P->nnodes++;
            orb_node *lo = &P->tree[o->lo], *hi = &P->tree[o->hi];
            *lo = *o;
            *hi = *o;
            lo->axis = hi->axis = -1;
            lo->r1 = o->r0 + klo;
            hi->r0 = o->r0 + klo;
            lo->box_hi[ax] = lo->reg_hi[ax] = o->cut;
            hi->box_lo[ax] = hi->reg_lo[ax] = o->cut;
            if (lo->r1 - lo->r0 > 1) front[next++] = o->lo;
            if (hi->r1 - hi->r0 > 1) front[next++] = o->hi;
        }
        for (size_t i = 0; i < n; ++i) {
            if (node_of[i] < 0) continue;
            const orb_node *o = &P->tree[node_of[i]];
            if (o->axis >= 0) node_of[i] = x[o->axis][i] < o->cut ? o->lo : o->hi;
        }
        nfront = next;
    }
    for (int k = 0; k < P->nnodes; ++k)
        if (P->tree[k].axis < 0) P->leaf[P->tree[k].r0] = k;
    free(node_of);
    free(front);
    free(fmap);
    free(cnt);
    free(a);
    P->st.rebalances++;
}

/* ---- collective hooks ------------------------------------------------------------------ */

static int par_all(ry_sim *sim, int flag) {
    par *P = get(sim);
    double t0 = MPI_Wtime();
    int r;
    MPI_Allreduce(&flag, &r, 1, MPI_INT, MPI_LAND, P->comm);
    P->st.reduce_s += MPI_Wtime() - t0;
    return r;
}

static double par_max(ry_sim *sim, double v) {
    par *P = get(sim);
    if (isnan(v)) v = INFINITY; /* a NaN anywhere must reach every rank */
    double t0 = MPI_Wtime(), r;
    MPI_Allreduce(&v, &r, 1, MPI_DOUBLE, MPI_MAX, P->comm);
    P->st.reduce_s += MPI_Wtime() - t0;
    return r;
}

static double par_sum(ry_sim *sim, double v) {
    par *P = get(sim);
    double t0 = MPI_Wtime(), r;
    MPI_Allreduce(&v, &r, 1, MPI_DOUBLE, MPI_SUM, P->comm);
    P->st.reduce_s += MPI_Wtime() - t0;
    return r;
}

/* The halo exchange between searches: nv packed values per particle sent, received. */
static double *halo_exchange(par *P, int nv) {
    double *recv = rbuf(P, P->nrecv * (size_t)nv);
    int nreq = 0;
    size_t off = 0;
    for (int r = 0; r < P->size; ++r) {
        if (P->rcount[r] > 0)
            MPI_Irecv(recv + off * (size_t)nv, P->rcount[r] * nv, MPI_DOUBLE, r, 7, P->comm,
                      &P->req[nreq++]);
        off += (size_t)P->rcount[r];
    }
    off = 0;
    for (int r = 0; r < P->size; ++r) {
        if (P->scount[r] > 0)
            MPI_Isend(P->sbuf + off * (size_t)nv, P->scount[r] * nv, MPI_DOUBLE, r, 7, P->comm,
                      &P->req[nreq++]);
        off += (size_t)P->scount[r];
    }
    MPI_Waitall(nreq, P->req, MPI_STATUSES_IGNORE);
    return recv;
}

static void par_sync(ry_sim *sim, double *a, int nc, unsigned odd) {
    par *P = get(sim);
    (void)odd; /* (no mirrors) */
    const double t0 = MPI_Wtime();
    double *send = sbuf(P, P->nsend * (size_t)nc);
    for (size_t k = 0; k < P->nsend; ++k)
        for (int c = 0; c < nc; ++c) send[k * (size_t)nc + c] = a[P->sidx[k] * (size_t)nc + c];
    const double *recv = halo_exchange(P, nc);
    for (size_t k = 0; k < P->nrecv; ++k)
        for (int c = 0; c < nc; ++c) a[P->rslot[k] * (size_t)nc + c] = recv[k * (size_t)nc + c];
    P->st.halo_s += MPI_Wtime() - t0;
}

static void par_sync_field(ry_sim *sim, int k) {
    par_sync(sim, sim->ps.f[k], 1, 0);
}

static int cmp_id(const void *a, const void *b) {
    const int64_t x = *(const int64_t *)a, y = *(const int64_t *)b;
    return (x > y) - (x < y);
}

/* Sorts a set by id. */
static void sort_by_id(par *P, ry_particles *ps) {
    const size_t n = ps->n;
    uint32_t *order = xrealloc(P, NULL, n * sizeof(uint32_t));
    int64_t *ids = xrealloc(P, NULL, n * sizeof(int64_t) * 2);
    for (size_t i = 0; i < n; ++i) {
        ids[2 * i] = ps->id[i];
        ids[2 * i + 1] = (int64_t)i;
    }
    qsort(ids, n, 2 * sizeof(int64_t), cmp_id);
    for (size_t i = 0; i < n; ++i) order[i] = (uint32_t)ids[2 * i + 1];
    ry_error e = {0};
    if (ry_particles_permute(ps, order, &e) != RY_OK) die(P, e.msg);
    free(ids);
    free(order);
}

static void drop_halo(par *P, ry_sim *sim) {
    if (P->nrecv) ry_particles_remove(&sim->ps, P->halo);
    P->nrecv = P->nsend = 0;
    sim->halo = NULL;
}

static ry_status par_redistribute(ry_sim *sim, double reach, ry_error *err) {
    (void)err;
    par *P = get(sim);
    ry_particles *ps = &sim->ps;
    const int dim = sim->dim, size = P->size, rs = rec_size(P);
    const double t0 = MPI_Wtime();
    /* 1. The old halo goes. */
    drop_halo(P, sim);
    /* 2. A fresh bisection when asked for or when the load is uneven. */
    long mine = (long)ps->n, most, all;
    MPI_Allreduce(&mine, &most, 1, MPI_LONG, MPI_MAX, P->comm);
    MPI_Allreduce(&mine, &all, 1, MPI_LONG, MPI_SUM, P->comm);
    if (P->canonical || (double)most > P->imbalance * (double)all / size) orb_build(P, sim, 0);
    /* 3. Particles move to the ranks that own their positions. */
    const double *x[3];
    dd_coords(sim, x);
    size_t n = ps->n;
    int *dest = xrealloc(P, NULL, n * sizeof(int));
    int *cnt = xrealloc(P, NULL, 2 * (size_t)size * sizeof(int)), *rcnt = cnt + size;
    size_t *pos = xrealloc(P, NULL, ((size_t)size + 1) * sizeof(size_t));
    memset(cnt, 0, (size_t)size * sizeof(int));
    for (size_t i = 0; i < n; ++i) {
        dest[i] = owner(P, x, i);
        if (dest[i] != P->rank) cnt[dest[i]]++;
    }
    pos[0] = 0;
    for (int r = 0; r < size; ++r) pos[r + 1] = pos[r] + (size_t)cnt[r];
    double *send = sbuf(P, pos[size] * (size_t)rs);
    uint8_t *gone = xrealloc(P, NULL, n ? n : 1);
    for (size_t i = 0; i < n; ++i) {
        gone[i] = dest[i] != P->rank;
        if (gone[i]) pack(P, ps, i, send + (pos[dest[i]]++) * (size_t)rs);
    }
    const size_t got = exchange(P, send, cnt, rcnt);
    ry_particles_remove(ps, gone);
    append(P, ps, P->rbuf, got);
    free(gone);
    free(dest);
    /* 4. After a checkpoint (and at the start), the owned particles in id order. */
    if (P->canonical) {
        sort_by_id(P, ps);
        P->canonical = 0;
    }
    /* 5. The halo: each particle within 2 * reach of another rank's region goes there. */
    dd_coords(sim, x);
    n = ps->n;
    const double w = sim->halo_depth * reach;
    int *near = xrealloc(P, NULL, (size_t)size * sizeof(int));
    memset(cnt, 0, (size_t)size * sizeof(int));
    for (size_t i = 0; i < n; ++i) {
        const int k = near_ranks(P, x, dim, i, w, near);
        for (int q = 0; q < k; ++q) cnt[near[q]]++;
    }
    pos[0] = 0;
    for (int r = 0; r < size; ++r) pos[r + 1] = pos[r] + (size_t)cnt[r];
    P->nsend = pos[size];
    P->sidx = xrealloc(P, P->sidx, P->nsend * sizeof(size_t));
    for (size_t i = 0; i < n; ++i) {
        const int k = near_ranks(P, x, dim, i, w, near);
        for (int q = 0; q < k; ++q) P->sidx[pos[near[q]]++] = i;
    }
    free(near);
    send = sbuf(P, P->nsend * (size_t)rs);
    for (size_t k = 0; k < P->nsend; ++k) pack(P, ps, P->sidx[k], send + k * (size_t)rs);
    memcpy(P->scount, cnt, (size_t)size * sizeof(int));
    P->nrecv = exchange(P, send, cnt, P->rcount);
    const size_t nown = ps->n;
    append(P, ps, P->rbuf, P->nrecv);
    P->rslot = xrealloc(P, P->rslot, P->nrecv * sizeof(size_t));
    for (size_t k = 0; k < P->nrecv; ++k) P->rslot[k] = nown + k;
    P->halo = xrealloc(P, P->halo, ps->n ? ps->n : 1);
    memset(P->halo, 0, nown);
    memset(P->halo + nown, 1, P->nrecv);
    sim->halo = P->halo;
    free(cnt);
    free(pos);
    long own = (long)nown, omax;
    MPI_Allreduce(&own, &omax, 1, MPI_LONG, MPI_MAX, P->comm);
    P->st.owned_max = (size_t)omax;
    P->st.halo = P->nrecv;
    P->st.redist_s += MPI_Wtime() - t0;
    return RY_OK;
}

static ry_status par_halo_update(ry_sim *sim, ry_error *err) {
    (void)err;
    par *P = get(sim);
    ry_particles *ps = &sim->ps;
    const int nf = P->nf;
    const double t0 = MPI_Wtime();
    double *send = sbuf(P, P->nsend * (size_t)nf);
    for (size_t k = 0; k < P->nsend; ++k)
        for (int q = 0; q < nf; ++q) send[k * (size_t)nf + q] = ps->f[P->fid[q]][P->sidx[k]];
    const double *recv = halo_exchange(P, nf);
    for (size_t k = 0; k < P->nrecv; ++k)
        for (int q = 0; q < nf; ++q) ps->f[P->fid[q]][P->rslot[k]] = recv[k * (size_t)nf + q];
    P->st.halo_s += MPI_Wtime() - t0;
    return RY_OK;
}

static void par_permuted(ry_sim *sim, const uint32_t *order) {
    par *P = get(sim);
    const size_t n = sim->ps.n;
    uint32_t *inv = xrealloc(P, NULL, n * sizeof(uint32_t));
    uint8_t *h = xrealloc(P, NULL, n ? n : 1);
    for (size_t k = 0; k < n; ++k) {
        inv[order[k]] = (uint32_t)k;
        h[k] = P->halo[order[k]];
    }
    memcpy(P->halo, h, n);
    for (size_t k = 0; k < P->nsend; ++k) P->sidx[k] = inv[P->sidx[k]];
    for (size_t k = 0; k < P->nrecv; ++k) P->rslot[k] = inv[P->rslot[k]];
    free(inv);
    free(h);
}

/* Open boundaries: each rank converts, creates and removes its own particles (the halo is
 * dropped first, so the next search rebuilds it); the particles created get ids after all
 * those of the ranks before. */
static ry_status par_open_update(ry_sim *sim, ry_error *err) {
    par *P = get(sim);
    drop_halo(P, sim);
    const int64_t first = sim->ps.next_id;
    if (ry_open_update(sim, err) != RY_OK) die(P, err->msg);
    const double t0 = MPI_Wtime();
    long made = (long)(sim->ps.next_id - first), before = 0, all;
    MPI_Exscan(&made, &before, 1, MPI_LONG, MPI_SUM, P->comm);
    MPI_Allreduce(&made, &all, 1, MPI_LONG, MPI_SUM, P->comm);
    if (P->rank == 0) before = 0; /* MPI_Exscan leaves rank 0's undefined */
    for (size_t i = 0; i < sim->ps.n; ++i)
        if (sim->ps.id[i] >= first) sim->ps.id[i] += before;
    sim->ps.next_id = first + all;
    P->st.reduce_s += MPI_Wtime() - t0;
    return RY_OK;
}

/* Sends rank root's error (status and message) to all ranks. */
static ry_status share_error(par *P, int root, ry_status st, ry_error *err) {
    int code = (int)st;
    MPI_Bcast(&code, 1, MPI_INT, root, P->comm);
    if (code != RY_OK) {
        MPI_Bcast(err->msg, (int)sizeof err->msg, MPI_CHAR, root, P->comm);
        err->code = (ry_status)code;
    }
    return (ry_status)code;
}

static ry_status par_verdict(const ry_sim *sim, size_t bad, size_t fluid, size_t outside,
                             ry_error *err) {
    par *P = get(sim);
    const double t0 = MPI_Wtime();
    long loc[3] = {(long)bad, (long)fluid, (long)outside}, glob[3];
    MPI_Allreduce(loc, glob, 3, MPI_LONG, MPI_SUM, P->comm);
    if (glob[0] == 0 && glob[2] == 0) {
        P->st.reduce_s += MPI_Wtime() - t0;
        return RY_OK;
    }
    /* Something to report: the tallies again, over owned particles only. */
    ry_check_ctx c;
    double inv_rho0[256];
    ry_check_init(sim, &c, inv_rho0);
    size_t b = 0, f = 0, o = 0;
    for (size_t i = 0; i < sim->ps.n; ++i)
        if (!ry_sim_is_halo(sim, i))
            ry_check_tally(&c, i, sim->dim, inv_rho0[sim->ps.material[i]], &b, &f, &o);
    loc[0] = (long)b;
    loc[1] = (long)f;
    loc[2] = (long)o;
    MPI_Allreduce(loc, glob, 3, MPI_LONG, MPI_SUM, P->comm);
    const double frac = sim->guard.max_outside_fraction;
    const int unstable =
        glob[0] > 0 || (frac > 0 && glob[1] > 0 && (double)glob[2] > frac * (double)glob[1]);
    if (!unstable) return RY_OK;
    /* The lowest rank holding a bad (or an outside) particle names it. */
    int mine = (glob[0] > 0 ? loc[0] > 0 : loc[2] > 0) ? P->rank : P->size, who;
    MPI_Allreduce(&mine, &who, 1, MPI_INT, MPI_MIN, P->comm);
    ry_status st = RY_ERR_UNSTABLE;
    if (P->rank == who)
        st = ry_check_verdict_here(sim, (size_t)loc[0], (size_t)glob[1], (size_t)glob[2], err);
    st = share_error(P, who, st, err);
    P->st.reduce_s += MPI_Wtime() - t0;
    return st;
}

/* Copies the whole state into the view on rank 0 (particles in id order). */
static void gather(par *P, ry_sim *sim) {
    const ry_particles *ps = &sim->ps;
    const int rs = rec_size(P);
    size_t nown = 0;
    for (size_t i = 0; i < ps->n; ++i) nown += !ry_sim_is_halo(sim, i);
    double *send = sbuf(P, nown * (size_t)rs);
    size_t k = 0;
    for (size_t i = 0; i < ps->n; ++i)
        if (!ry_sim_is_halo(sim, i)) pack(P, ps, i, send + (k++) * (size_t)rs);
    int cnt = (int)(nown * (size_t)rs);
    int *rc = NULL, *rd = NULL;
    size_t total = 0;
    if (P->rank == 0) {
        rc = xrealloc(P, NULL, 2 * (size_t)P->size * sizeof(int));
        rd = rc + P->size;
    }
    MPI_Gather(&cnt, 1, MPI_INT, rc, 1, MPI_INT, 0, P->comm);
    if (P->rank == 0)
        for (int r = 0; r < P->size; ++r) {
            rd[r] = (int)total;
            total += (size_t)rc[r];
        }
    double *recv = P->rank == 0 ? rbuf(P, total) : NULL;
    MPI_Gatherv(send, cnt, MPI_DOUBLE, recv, rc, rd, MPI_DOUBLE, 0, P->comm);
    /* The open boundaries' counters: each rank counts its own conversions. */
    for (int q = 0; q < sim->nopen; ++q) {
        long c = sim->open[q].count, sum = 0;
        MPI_Reduce(&c, &sum, 1, MPI_LONG, MPI_SUM, 0, P->comm);
        if (P->rank == 0) P->view->open[q].count = sum;
    }
    if (P->rank != 0) return;
    ry_sim *v = P->view;
    /* The whole set in id order (open boundaries change it: the view follows). */
    const size_t m = total / (size_t)rs;
    int64_t *key = xrealloc(P, NULL, 2 * (m ? m : 1) * sizeof(int64_t));
    for (size_t q = 0; q < m; ++q) {
        key[2 * q] = (int64_t)recv[q * (size_t)rs];
        key[2 * q + 1] = (int64_t)q;
    }
    qsort(key, m, 2 * sizeof(int64_t), cmp_id);
    if (m > v->ps.n) {
        size_t first;
        ry_error e = {0};
        if (ry_particles_add(&v->ps, m - v->ps.n, &first, &e) != RY_OK) die(P, e.msg);
    }
    v->ps.n = m;
    for (size_t q = 0; q < m; ++q) unpack(P, &v->ps, q, recv + (size_t)key[2 * q + 1] * (size_t)rs);
    v->ps.next_id = sim->ps.next_id;
    free(key);
    free(rc);
    /* The clock and the scheme's scalars (the same on every rank). */
    v->t = sim->t;
    v->dt = sim->dt;
    v->step = sim->step;
    v->next_output = sim->next_output;
    v->finished = sim->finished;
    v->ckpt.next_t = sim->ckpt.next_t;
    v->searches = sim->searches;
    v->nl_reuses = sim->nl_reuses;
    v->nl_radius = sim->nl_radius;
    v->output_index = sim->output_index;
    if (sim->scheme->state_vars) {
        ry_state_var a[64], b[64];
        const int na = sim->scheme->state_vars(sim->scheme_state, a, 64);
        const int nb = v->scheme->state_vars(v->scheme_state, b, 64);
        for (int q = 0; q < na && q < nb; ++q) {
            if (a[q].f64) *b[q].f64 = *a[q].f64;
            if (a[q].i32) *b[q].i32 = *a[q].i32;
            if (a[q].i64) *b[q].i64 = *a[q].i64;
        }
    }
}

/* output.pieces: each rank writes its own particles as OUT/CASE_NNNNN/piece_RRRR.vtp. */
static ry_status write_pieces(par *P, ry_sim *sim, ry_error *err) {
    char dir[4400], path[4500];
    snprintf(dir, sizeof dir, "%s/%s_%05d", sim->out_dir, sim->case_name, sim->output_index);
    ry_status st = ry_mkdir_p(dir, err);
    if (st == RY_OK) {
        snprintf(path, sizeof path, "%s/piece_%04d.vtp", dir, P->rank);
        st = ry_vtk_write_piece(path, &sim->ps, sim->halo, sim->t, err);
    }
    /* The lowest rank that failed reports for all. */
    int mine = st != RY_OK ? P->rank : P->size, who;
    MPI_Allreduce(&mine, &who, 1, MPI_INT, MPI_MIN, P->comm);
    return who < P->size ? share_error(P, who, st, err) : RY_OK;
}

static ry_status par_output(ry_sim *sim, ry_error *err) {
    par *P = get(sim);
    const int pieces = sim->write_vtk && sim->write_pieces;
    if (pieces) RY_TRY(write_pieces(P, sim, err));
    gather(P, sim);
    if (P->rank == 0) P->view->vtk_pieces = pieces ? P->size : 0;
    ry_status st = RY_OK;
    if (P->rank == 0) {
        ry_sim *v = P->view;
        /* The cells and the list some measurements search, over the whole set (the ranks'
         * search radius, or the kernel's for a scheme that does not search). */
        const double r = sim->nl_radius > 0 ? sim->nl_radius : sim->kernel.radius;
        const double *x[3];
        ry_particles_coords(&v->ps, x);
        st = ry_cells_build(&v->cells, &v->box, r * (1 + sim->nl_skin), v->ps.n, x, err);
        if (st == RY_OK)
            st = ry_nlist_build_cells(&v->nl, &v->cells, &v->box, r * (1 + sim->nl_skin), v->ps.n,
                                      x, err);
        if (st == RY_OK) st = ry_output_write(v, err);
    }
    st = share_error(P, 0, st, err);
    int idx[2] = {P->rank == 0 ? P->view->output_index : 0, P->rank == 0 ? P->view->finished : 0};
    MPI_Bcast(idx, 2, MPI_INT, 0, P->comm);
    sim->output_index = idx[0];
    sim->finished = idx[1]; /* time.stop_when, measured on rank 0's view */
    if (P->rank == 0) memcpy(sim->stop_reason, P->view->stop_reason, sizeof sim->stop_reason);
    return st;
}

static ry_status par_checkpoint(ry_sim *sim, char *path, size_t path_size, ry_error *err) {
    par *P = get(sim);
    gather(P, sim);
    ry_status st = RY_OK;
    char file[4300] = "";
    if (P->rank == 0) st = ry_sim_checkpoint_now(P->view, file, sizeof file, err);
    st = share_error(P, 0, st, err);
    MPI_Bcast(file, (int)sizeof file, MPI_CHAR, 0, P->comm);
    if (path) snprintf(path, path_size, "%s", file);
    sim->ckpt.last_wall = ry_wall_time();
    /* At a checkpoint of the simulated schedule: what a restart from it does, a fresh,
     * canonical partition (so that the restart is bitwise the same run). Not at one of the
     * wall clock's or a signal's, so that a run's results never depend on when those came. */
    if (sim->ckpt.scheduled) {
        P->canonical = 1;
        sim->nl_radius = -1; /* the next step searches afresh, whatever the drift */
    }
    return st;
}

static const ry_par_ops ops = {par_all,        par_max,          par_sum,     par_sync,
                               par_sync_field, par_redistribute, NULL,        par_halo_update,
                               NULL,           par_permuted,     par_verdict, par_open_update,
                               par_output,     par_checkpoint,   NULL};

/* Puts a set in id order and checks that no id is repeated. */
static ry_status ids_in_order(par *P, ry_particles *ps, ry_error *err) {
    sort_by_id(P, ps);
    for (size_t i = 1; i < ps->n; ++i)
        RY_CHECK(err, ps->id[i] > ps->id[i - 1], RY_ERR_INPUT, "particle id %lld is repeated",
                 (long long)ps->id[i]);
    return RY_OK;
}

ry_status ry_mpi_attach(ry_sim *sim, ry_sim *view, MPI_Comm comm, double imbalance, ry_error *err) {
    int nranks;
    MPI_Comm_size(comm, &nranks);
    const int periodic = sim->box.periodic[0] || sim->box.periodic[1] || sim->box.periodic[2];
    RY_CHECK(err, !sim->par && !(nranks > 1 && periodic), RY_ERR_INPUT,
             "%s only so far; run with ryushi",
             sim->par ? "symmetry planes (domain.symmetry) run in the serial program"
                      : "periodic domains run on one rank");
    par *P = calloc(1, sizeof *P);
    RY_CHECK(err, P, RY_ERR_NOMEM, "out of memory");
    P->comm = comm;
    MPI_Comm_rank(comm, &P->rank);
    P->size = nranks;
    P->view = view;
    P->imbalance = imbalance;
    const size_t size = (size_t)P->size;
    P->tree = calloc(2 * size, sizeof *P->tree);
    P->leaf = calloc(size, sizeof(int));
    P->scount = calloc(size, sizeof(int));
    P->rcount = calloc(size, sizeof(int));
    P->req = calloc(2 * size, sizeof(MPI_Request));
    P->fid = calloc((size_t)sim->ps.nfields + 1, sizeof(int));
    if (!P->tree || !P->leaf || !P->scount || !P->rcount || !P->req || !P->fid)
        die(P, "out of memory");
    for (int f = 0; f < sim->ps.nfields; ++f)
        if (sim->ps.f[f]) P->fid[P->nf++] = f;
    sim->par = &ops;
    sim->par_state = P;
    RY_TRY(ids_in_order(P, &sim->ps, err));
    if (view) RY_TRY(ids_in_order(P, &view->ps, err));
    /* Every rank holds the whole set: each counts every size-th particle for the bisection,
     * then keeps its own. */
    orb_build(P, sim, 1);
    const double *x[3];
    dd_coords(sim, x);
    uint8_t *gone = malloc(sim->ps.n ? sim->ps.n : 1);
    if (!gone) die(P, "out of memory");
    for (size_t i = 0; i < sim->ps.n; ++i) gone[i] = owner(P, x, i) != P->rank;
    ry_particles_remove(&sim->ps, gone);
    free(gone);
    /* The open boundaries' counters are summed over the ranks: rank 0 keeps the whole set's
     * (after a restart), the others start from none. */
    if (P->rank != 0)
        for (int q = 0; q < sim->nopen; ++q) sim->open[q].count = 0;
    /* The first search re-partitions canonically, as after a checkpoint. */
    P->canonical = 1;
    sim->nl_radius = -1;
    sim->nl_restore = 0;
    sim->guard.snapshot_every = 0;
    ry_sim_snapshot_free(sim);
    return RY_OK;
}

void ry_mpi_get_stats(const ry_sim *sim, ry_mpi_stats *s) {
    memset(s, 0, sizeof *s);
    if (sim->par == &ops) *s = get(sim)->st;
    s->comm_s = s->redist_s + s->halo_s + s->reduce_s;
    if (sim->par == &ops) s->fields = get(sim)->nf;
}

void ry_mpi_detach(ry_sim *sim) {
    par *P = get(sim);
    if (!P || sim->par != &ops) return; /* (not attached: a serial run's hooks, or none) */
    free(P->tree);
    free(P->leaf);
    free(P->fid);
    free(P->scount);
    free(P->rcount);
    free(P->sidx);
    free(P->rslot);
    free(P->halo);
    free(P->sbuf);
    free(P->rbuf);
    free(P->req);
    free(P);
    sim->par = NULL;
    sim->par_state = NULL;
    sim->halo = NULL;
}
