/* Symmetry planes: mirror copies as a serial run's halo (see symmetry.h). */
#include "sim/symmetry.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/guard_check.h"
#include "ryushi/open_boundary.h"
#include "ryushi/run.h"
#include "sim/writer.h"

#define MAX_PLANES 3 /* one per axis */
#define NSETS (1u << MAX_PLANES)

typedef struct mirror {
    int np;
    int axis[MAX_PLANES];   /* the plane's normal axis */
    int hi[MAX_PLANES];     /* the face at the box's hi (else lo) */
    double pos[MAX_PLANES]; /* its coordinate */
    /* per set s of planes (bit q: plane q; every s from 1 to 2^np - 1): */
    unsigned axes[NSETS];    /* the axes it mirrors */
    double at[NSETS][3];     /* the plane's coordinate on each of those axes */
    size_t nown;             /* particles [0, nown) are the set's own, [nown, n) copies */
    size_t ncopy, cap, scap; /* copies; room for them in src and set */
    size_t *src;             /* copy k (particle nown + k): its original */
    uint8_t *set;            /* ... and the planes it is mirrored across */
    uint8_t *halo;           /* per particle: a copy */
    size_t hcap;             /* room in halo */
    uint32_t *tmp;           /* a permutation's scratch */
    size_t tcap;
} mirror;

static mirror *get(const ry_sim *sim) {
    return (mirror *)sim->par_state;
}

static int odd_count(unsigned v) {
    int c = 0;
    for (; v; v &= v - 1) c ^= 1;
    return c;
}

/* Field fi's value v of an original, seen in its copy across the planes of set s. */
static inline double mapped(const mirror *M, const ry_field_info *fi, unsigned s, double v) {
    const unsigned a = M->axes[s];
    if ((fi->flags & RY_FIELD_POSITION) && fi->component >= 0 && (a >> fi->component & 1u))
        return 2.0 * M->at[s][fi->component] - v;
    return odd_count(fi->odd & a) ? -v : v;
}

static int grow(void **p, size_t *cap, size_t need, size_t size) {
    if (need <= *cap) return 1;
    const size_t c = need + need / 2 + 16;
    void *q = realloc(*p, c * size);
    if (!q) return 0;
    *p = q;
    *cap = c;
    return 1;
}

/* ---- the hooks ------------------------------------------------------------------------ */

static int sym_all(ry_sim *sim, int flag) {
    (void)sim;
    return flag;
}

static double sym_max(ry_sim *sim, double v) {
    (void)sim;
    return v;
}

/* A sum over the whole problem: each particle stands for itself and its images (an exact
 * scaling by a power of two, so that ratios of sums are the full run's bits). */
static double sym_sum(ry_sim *sim, double v) {
    return v * ry_box_mirrors(&sim->box);
}

/* Particle i of the set reflected across plane q (it crossed it): every field but, with
 * keep_ref, the search's reference positions (so that the drift since the search stays
 * bounded: the reflection brings the particle nearer to them). */
static void reflect(ry_sim *sim, const mirror *M, size_t i, int q, int keep_ref) {
    ry_particles *ps = &sim->ps;
    const unsigned s = 1u << q;
    for (int k = 0; k < ps->nfields; ++k) {
        if (!ps->f[k]) continue;
        if (keep_ref && k >= sim->f_xref && k < sim->f_xref + 3) continue;
        ps->f[k][i] = mapped(M, &ps->info[k], s, ps->f[k][i]);
    }
}

/* Reflects the set's particles that crossed a plane. */
static void reflect_crossers(ry_sim *sim, const mirror *M, int keep_ref) {
    for (int q = 0; q < M->np; ++q) {
        const double *x = sim->ps.f[RY_F_X + M->axis[q]], p = M->pos[q];
#pragma omp parallel for schedule(static) if (M->nown > 4096)
        for (size_t i = 0; i < M->nown; ++i)
            if (M->hi[q] ? x[i] > p : x[i] < p) reflect(sim, M, i, q, keep_ref);
    }
}

/* The planes within w of particle i (coordinates x: the positions, or those of the last
 * search). */
static unsigned near_planes(const mirror *M, const double *const x[3], size_t i, double w) {
    unsigned m = 0;
    for (int q = 0; q < M->np; ++q) {
        const double v = x[M->axis[q]][i];
        if ((M->hi[q] ? M->pos[q] - v : v - M->pos[q]) < w) m |= 1u << q;
    }
    return m;
}

static void fill_copy(ry_sim *sim, const mirror *M, size_t k) {
    ry_particles *ps = &sim->ps;
    const size_t i = M->nown + k, s = M->src[k];
    const unsigned set = M->set[k];
    for (int f = 0; f < ps->nfields; ++f)
        if (ps->f[f]) ps->f[f][i] = mapped(M, &ps->info[f], set, ps->f[f][s]);
}

/* The copies of the particles within 2 * reach of a plane (by the coordinates x), in the
 * order of their originals (and of the sets of planes in each), after the set's own: the
 * order a restart makes again from the positions of the last search. */
static ry_status make_copies(ry_sim *sim, mirror *M, double reach, const double *const x[3],
                             ry_error *err) {
    ry_particles *ps = &sim->ps;
    const double w = (sim->halo_depth > 0 ? sim->halo_depth : 1) * reach;
    size_t count = 0;
    for (size_t i = 0; i < M->nown; ++i) {
        const unsigned m = near_planes(M, x, i, w);
        for (unsigned s = m; s; s = (s - 1) & m) ++count;
    }
    if (count == 0) return RY_OK;
    RY_CHECK(err,
             grow((void **)&M->src, &M->cap, count, sizeof *M->src) &&
                 grow((void **)&M->set, &M->scap, count, 1),
             RY_ERR_NOMEM, "out of memory (symmetry planes' copies)");
    for (size_t i = 0; i < M->nown; ++i) {
        const unsigned m = near_planes(M, x, i, w);
        for (unsigned s = m; s; s = (s - 1) & m) {
            M->src[M->ncopy] = i;
            M->set[M->ncopy++] = (uint8_t)s;
        }
    }
    const int64_t next = ps->next_id;
    size_t first;
    RY_TRY(ry_particles_add(ps, count, &first, err));
    ps->next_id = next;
    for (size_t k = 0; k < count; ++k) {
        const size_t i = first + k, s = M->src[k];
        ps->id[i] = ps->id[s];
        ps->kind[i] = ps->kind[s];
        ps->material[i] = ps->material[s];
        fill_copy(sim, M, k);
    }
    RY_CHECK(err, grow((void **)&M->halo, &M->hcap, ps->n, 1), RY_ERR_NOMEM,
             "out of memory (symmetry planes' copies)");
    memset(M->halo, 0, M->nown);
    memset(M->halo + M->nown, 1, count);
    sim->halo = M->halo;
    return RY_OK;
}

/* The copies go. Without the copies' flags (sim->halo NULL: a restart) all the particles
 * are the set's own. */
static void drop_copies(ry_sim *sim, mirror *M) {
    if (sim->halo == M->halo && M->ncopy) sim->ps.n = M->nown;
    M->nown = sim->ps.n;
    M->ncopy = 0;
    sim->halo = NULL;
}

static ry_status sym_redistribute(ry_sim *sim, double reach, ry_error *err) {
    mirror *M = get(sim);
    drop_copies(sim, M);
    reflect_crossers(sim, M, 0);
    const double *x[3];
    ry_particles_coords(&sim->ps, x);
    return make_copies(sim, M, reach, x, err);
}

static ry_status sym_redistribute_at_ref(ry_sim *sim, double reach, ry_error *err) {
    mirror *M = get(sim);
    drop_copies(sim, M);
    const double *x[3] = {NULL, NULL, NULL};
    for (int d = 0; d < sim->dim; ++d) x[d] = sim->ps.f[sim->f_xref + d];
    return make_copies(sim, M, reach, x, err);
}

static ry_status sym_halo_update(ry_sim *sim, ry_error *err) {
    (void)err;
    mirror *M = get(sim);
    reflect_crossers(sim, M, 1);
#pragma omp parallel for schedule(static) if (M->ncopy > 4096)
    for (size_t k = 0; k < M->ncopy; ++k) fill_copy(sim, M, k);
    return RY_OK;
}

static void sym_sync(ry_sim *sim, double *a, int nc, unsigned odd) {
    const mirror *M = get(sim);
    for (size_t k = 0; k < M->ncopy; ++k) {
        const size_t i = M->nown + k, s = M->src[k];
        const unsigned ax = M->axes[M->set[k]];
        if (nc == 3)
            for (int c = 0; c < 3; ++c)
                a[3 * i + c] = (ax >> c & 1u) ? -a[3 * s + c] : a[3 * s + c];
        else if (nc == 1)
            a[i] = odd_count(odd & ax) ? -a[s] : a[s];
        else
            for (int c = 0; c < nc; ++c) a[(size_t)nc * i + c] = a[(size_t)nc * s + c];
    }
}

static void sym_sync_field(ry_sim *sim, int f) {
    const mirror *M = get(sim);
    ry_particles *ps = &sim->ps;
    for (size_t k = 0; k < M->ncopy; ++k)
        ps->f[f][M->nown + k] = mapped(M, &ps->info[f], M->set[k], ps->f[f][M->src[k]]);
}

/* The set's own particles in the cells' order, then the copies in the order of their
 * originals (make_copies' order). */
static int sym_partition(ry_sim *sim, uint32_t *order) {
    mirror *M = get(sim);
    if (M->ncopy == 0) return 0;
    const size_t n = sim->ps.n, nown = M->nown;
    if (!grow((void **)&M->tmp, &M->tcap, n + nown + 1, sizeof *M->tmp)) abort();
    uint32_t *out = M->tmp, *first = M->tmp + n; /* first[o]: o's first copy (then counts) */
    memset(first, 0, (nown + 1) * sizeof *first);
    for (size_t k = 0; k < M->ncopy; ++k) first[M->src[k] + 1]++;
    for (size_t o = 0; o < nown; ++o) first[o + 1] += first[o];
    size_t a = 0, b = nown;
    for (size_t q = 0; q < n; ++q)
        if (order[q] < nown) {
            const uint32_t o = order[q];
            out[a++] = o;
            for (uint32_t c = first[o]; c < first[o + 1]; ++c) out[b++] = (uint32_t)(nown + c);
        }
    memcpy(order, out, n * sizeof *order);
    return 1;
}

static void sym_permuted(ry_sim *sim, const uint32_t *order) {
    mirror *M = get(sim);
    if (M->ncopy == 0) return;
    const size_t n = sim->ps.n;
    if (!grow((void **)&M->tmp, &M->tcap, n, sizeof *M->tmp)) abort();
    uint32_t *inv = M->tmp;
    for (size_t k = 0; k < n; ++k) inv[order[k]] = (uint32_t)k;
    size_t *src = malloc(M->ncopy * sizeof *src);
    uint8_t *set = malloc(M->ncopy);
    if (!src || !set) abort();
    for (size_t k = 0; k < M->ncopy; ++k) {
        const size_t old = order[M->nown + k] - M->nown;
        src[k] = inv[M->src[old]];
        set[k] = M->set[old];
    }
    memcpy(M->src, src, M->ncopy * sizeof *src);
    memcpy(M->set, set, M->ncopy);
    free(src);
    free(set);
}

/* The tallies counted the copies too (which lie outside the domain): where they found
 * anything, counted again over the set's own particles. */
static ry_status sym_verdict(const ry_sim *sim, size_t bad, size_t fluid, size_t outside,
                             ry_error *err) {
    if (bad == 0 && outside == 0) return RY_OK;
    ry_check_ctx c;
    double inv_rho0[256];
    ry_check_init(sim, &c, inv_rho0);
    size_t b = 0, f = 0, o = 0;
    const size_t nown = get(sim)->nown;
    for (size_t i = 0; i < nown; ++i)
        ry_check_tally(&c, i, sim->dim, inv_rho0[sim->ps.material[i]], &b, &f, &o);
    (void)fluid;
    return ry_check_verdict_here(sim, b, f, o, err);
}

static ry_status sym_open_update(ry_sim *sim, ry_error *err) {
    mirror *M = get(sim);
    drop_copies(sim, M); /* the next search makes them afresh */
    const ry_par_ops *par = sim->par;
    sim->par = NULL;
    const ry_status st = ry_open_update(sim, err);
    sim->par = par;
    return st;
}

static int sym_copy_of(const ry_sim *sim, size_t i, size_t *orig, unsigned *axes) {
    const mirror *M = get(sim);
    if (!sim->halo || i < M->nown || i >= M->nown + M->ncopy) return 0;
    *orig = M->src[i - M->nown];
    *axes = M->axes[M->set[i - M->nown]];
    return 1;
}

static int is_mirror(const ry_sim *sim) {
    return sim->par && sim->par->partition == sym_partition;
}

void ry_symmetry_hide(ry_sim *sim, ry_symmetry_hidden *h) {
    h->n = sim->ps.n;
    h->halo = sim->halo;
    h->par = sim->par;
    sim->ps.n = ry_symmetry_owned(sim);
    sim->halo = NULL;
    if (is_mirror(sim)) sim->par = NULL;
}

void ry_symmetry_show(ry_sim *sim, const ry_symmetry_hidden *h) {
    sim->ps.n = h->n;
    sim->halo = h->halo;
    sim->par = h->par;
}

ry_status ry_symmetry_measure(ry_sim *sim, ry_measure_fn fn, void *ctx, ry_error *err) {
    if (!is_mirror(sim)) return fn(sim, ctx, err);
    const mirror *M = get(sim);
    ry_particles *ps = &sim->ps;
    const size_t n = ps->n, own = ry_symmetry_owned(sim), nc = n - own;
    const unsigned nsets = (1u << M->np) - 1;
    /* the copies aside (a scheme's values of them, which the images would overwrite) */
    double *keep = malloc((nc * (size_t)ps->nfields + 1) * sizeof *keep);
    int64_t *kid = malloc((nc + 1) * sizeof *kid);
    uint8_t *kk = malloc(2 * nc + 1);
    RY_CHECK(err, keep && kid && kk, RY_ERR_NOMEM, "out of memory (symmetry planes' images)");
    for (int f = 0; f < ps->nfields; ++f)
        if (ps->f[f]) memcpy(keep + (size_t)f * nc, ps->f[f] + own, nc * sizeof *keep);
    memcpy(kid, ps->id + own, nc * sizeof *kid);
    memcpy(kk, ps->kind + own, nc);
    memcpy(kk + nc, ps->material + own, nc);
    /* the images of every particle across each set of planes */
    ps->n = own;
    const int64_t next = ps->next_id;
    size_t first = own;
    ry_status st = ry_particles_add(ps, own * (size_t)nsets, &first, err);
    ps->next_id = next;
    size_t at = own;
    for (unsigned s = 1; st == RY_OK && s <= nsets; ++s) {
        for (size_t i = 0; i < own; ++i, ++at) {
            ps->id[at] = ps->id[i];
            ps->kind[at] = ps->kind[i];
            ps->material[at] = ps->material[i];
            for (int f = 0; f < ps->nfields; ++f)
                if (ps->f[f]) ps->f[f][at] = mapped(M, &ps->info[f], s, ps->f[f][i]);
        }
    }
    /* their cells and list (the search radius, or the kernel's for a scheme that has none) */
    const ry_cell_list cells = sim->cells;
    const ry_nlist nl = sim->nl;
    memset(&sim->cells, 0, sizeof sim->cells);
    memset(&sim->nl, 0, sizeof sim->nl);
    const double r =
        (sim->nl_radius > 0 ? sim->nl_radius : sim->kernel.radius) * (1 + sim->nl_skin);
    const double *x[3];
    ry_particles_coords(ps, x);
    if (st == RY_OK) st = ry_cells_build(&sim->cells, &sim->box, r, ps->n, x, err);
    if (st == RY_OK) st = ry_nlist_build_cells(&sim->nl, &sim->cells, &sim->box, r, ps->n, x, err);
    /* the whole domain: the box mirrored across its planes */
    const ry_par_ops *par = sim->par;
    const uint8_t *halo = sim->halo;
    const ry_box box = sim->box;
    for (int q = 0; q < M->np; ++q) {
        const int d = M->axis[q];
        if (M->hi[q])
            sim->box.hi[d] = 2 * box.hi[d] - box.lo[d];
        else
            sim->box.lo[d] = 2 * box.lo[d] - box.hi[d];
    }
    /* the open boundaries' counts: their images' too */
    const int whole = ry_box_mirrors(&box);
    for (int q = 0; q < sim->nopen; ++q) sim->open[q].count *= whole;
    sim->par = NULL;
    sim->halo = NULL;
    if (st == RY_OK) st = fn(sim, ctx, err);
    sim->par = par;
    sim->halo = halo;
    sim->box = box;
    for (int q = 0; q < sim->nopen; ++q) sim->open[q].count /= whole;
    ry_cells_free(&sim->cells);
    ry_nlist_free(&sim->nl);
    sim->cells = cells;
    sim->nl = nl;
    /* the copies back */
    ps->n = n;
    for (int f = 0; f < ps->nfields; ++f)
        if (ps->f[f]) memcpy(ps->f[f] + own, keep + (size_t)f * nc, nc * sizeof *keep);
    memcpy(ps->id + own, kid, nc * sizeof *kid);
    memcpy(ps->kind + own, kk, nc);
    memcpy(ps->material + own, kk + nc, nc);
    free(keep);
    free(kid);
    free(kk);
    return st;
}

static ry_status series(ry_sim *sim, void *ctx, ry_error *err) {
    (void)ctx;
    return ry_output_write_series(sim, err);
}

/* The VTK file holds the set's own particles; the measurements are the whole problem's. */
static ry_status sym_output(ry_sim *sim, ry_error *err) {
    ry_symmetry_hidden h;
    ry_symmetry_hide(sim, &h);
    const ry_status st = ry_output_write_vtk(sim, err);
    ry_symmetry_show(sim, &h);
    RY_TRY(st);
    return ry_symmetry_measure(sim, series, NULL, err);
}

static ry_status sym_checkpoint(ry_sim *sim, char *path, size_t path_size, ry_error *err) {
    ry_symmetry_hidden h;
    ry_symmetry_hide(sim, &h);
    const ry_status st = ry_sim_checkpoint_now(sim, path, path_size, err);
    ry_symmetry_show(sim, &h);
    return st;
}

static const ry_par_ops ops = {.all = sym_all,
                               .max = sym_max,
                               .sum = sym_sum,
                               .sync = sym_sync,
                               .sync_field = sym_sync_field,
                               .redistribute = sym_redistribute,
                               .redistribute_at_ref = sym_redistribute_at_ref,
                               .halo_update = sym_halo_update,
                               .partition = sym_partition,
                               .permuted = sym_permuted,
                               .verdict = sym_verdict,
                               .open_update = sym_open_update,
                               .output = sym_output,
                               .checkpoint = sym_checkpoint,
                               .copy_of = sym_copy_of};

size_t ry_symmetry_owned(const ry_sim *sim) {
    return is_mirror(sim) && sim->halo ? get(sim)->nown : sim->ps.n;
}

/* ---- set-up ----------------------------------------------------------------------------- */

static const char *const face_names[] = {"x_lo", "x_hi", "y_lo", "y_hi", "z_lo", "z_hi", NULL};

ry_status ry_symmetry_read(ry_sim *sim, ry_case *c, ry_error *err) {
    ry_box *b = &sim->box;
    memset(b->symmetry, 0, sizeof b->symmetry);
    if (!ry_case_has(c, "domain.symmetry")) return RY_OK;
    size_t n;
    char key[64], where[256];
    RY_TRY(ry_case_count(c, "domain.symmetry", &n, err));
    for (size_t k = 0; k < n; ++k) {
        int f;
        snprintf(key, sizeof key, "domain.symmetry[%zu]", k);
        RY_TRY(ry_case_choice(c, key, NULL, face_names, &f, err));
        const int d = f / 2, bit = 1 << (f % 2);
        RY_CHECK(err, d < sim->dim && !b->periodic[d] && !b->symmetry[d], RY_ERR_INPUT,
                 "%s: key '%s': '%s' %s", ry_case_where(c, key, where, sizeof where), key,
                 face_names[f],
                 d >= sim->dim    ? "is beyond the case's dimension"
                 : b->periodic[d] ? "is a face of a periodic direction"
                                  : "is a second plane across the same axis (one per axis)");
        b->symmetry[d] |= bit;
    }
    /* The particles beyond the planes go (their mirror images take their place); those left
     * must not lie on a plane, where a copy would coincide with its original. */
    ry_particles *ps = &sim->ps;
    uint8_t *gone = calloc(ps->n ? ps->n : 1, 1);
    RY_CHECK(err, gone, RY_ERR_NOMEM, "out of memory");
    ry_status st = RY_OK;
    for (size_t i = 0; i < ps->n && st == RY_OK; ++i)
        for (int d = 0; d < sim->dim; ++d) {
            const double x = ps->f[RY_F_X + d][i];
            const double dlo = x - b->lo[d], dhi = b->hi[d] - x;
            if (((b->symmetry[d] & 1) && dlo < 0) || ((b->symmetry[d] & 2) && dhi < 0)) {
                gone[i] = 1;
            } else if (((b->symmetry[d] & 1) && dlo < 0.25 * sim->dx) ||
                       ((b->symmetry[d] & 2) && dhi < 0.25 * sim->dx)) {
                st = ry_error_set(
                    err, RY_ERR_INPUT,
                    "%s: key 'domain.symmetry': particle %lld lies within a "
                    "quarter spacing of the plane %c = %g, where its mirror "
                    "image would coincide with it: put the plane between two "
                    "lattice layers (half a spacing from the particles)",
                    ry_case_where(c, "domain.symmetry", where, sizeof where), (long long)ps->id[i],
                    "xyz"[d], (b->symmetry[d] & 1) && dlo < 0.25 * sim->dx ? b->lo[d] : b->hi[d]);
                break;
            }
        }
    if (st == RY_OK) ry_particles_remove(ps, gone);
    free(gone);
    return st;
}

ry_status ry_symmetry_attach(ry_sim *sim, ry_error *err) {
    const ry_box *b = &sim->box;
    if (!(b->symmetry[0] || b->symmetry[1] || b->symmetry[2])) return RY_OK;
    RY_CHECK(err, !sim->par, RY_ERR_INTERNAL, "symmetry planes: the run has hooks already");
    mirror *M = calloc(1, sizeof *M);
    RY_CHECK(err, M, RY_ERR_NOMEM, "out of memory");
    for (int d = 0; d < sim->dim; ++d)
        for (int side = 0; side < 2; ++side)
            if (b->symmetry[d] & (1 << side)) {
                M->axis[M->np] = d;
                M->hi[M->np] = side;
                M->pos[M->np++] = side ? b->hi[d] : b->lo[d];
            }
    for (unsigned s = 1; s < (1u << M->np); ++s)
        for (int q = 0; q < M->np; ++q)
            if (s >> q & 1u) {
                M->axes[s] |= 1u << M->axis[q];
                M->at[s][M->axis[q]] = M->pos[q];
            }
    M->nown = sim->ps.n;
    sim->par = &ops;
    sim->par_state = M;
    sim->halo = NULL;
    /* the last good state would hold copies the hooks no longer know: not kept */
    sim->guard.snapshot_every = 0;
    ry_sim_snapshot_free(sim);
    return RY_OK;
}

void ry_symmetry_detach(ry_sim *sim) {
    if (!is_mirror(sim)) return;
    mirror *M = get(sim);
    free(M->src);
    free(M->set);
    free(M->halo);
    free(M->tmp);
    free(M);
    sim->par = NULL;
    sim->par_state = NULL;
    sim->halo = NULL;
}
