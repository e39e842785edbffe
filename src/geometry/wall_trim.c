/* Wall particles beyond the reach of the fluid removed (domain.wall_layers). The particles are
 * binned in voxels of one spacing over their bounding box (a margin of one voxel around it);
 * the space the fluid can reach is flooded from the voxels of the non-wall particles through
 * the voxels no wall particle occupies (faces shared), into the open boundaries' zones but not
 * out of them (fluid leaves a zone only back where it came from, or is removed); the wall
 * voxels touching that space (faces, edges or corners) are layer 1, those touching layer k are
 * layer k + 1; wall particles whose voxel is deeper than the layers kept, or never reached, are
 * removed. On a lattice-aligned wall this keeps exactly the first `layers` layers facing the
 * fluid, on every side the fluid can reach (the outside of an open-top tank included); a wall
 * that does not sit on the lattice leaves gaps in its voxels, so the flood passes through and
 * more is kept, never less. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/geometry.h"

enum { V_EMPTY = 0, V_WALL = 1, V_REACHED = 2, V_ZONE = 4 };

/* The flood may pass from voxel k to voxel q. */
static int passes(const uint8_t *v, size_t k, size_t q) {
    return !(v[q] & (V_WALL | V_REACHED)) && !((v[k] & V_ZONE) && !(v[q] & V_ZONE));
}

ry_status ry_walls_trim(ry_particles *ps, double dx, int layers, const double *zones, int nzones,
                        size_t *removed, ry_error *err) {
    *removed = 0;
    const size_t n = ps->n;
    const int dim = ps->dim;
    size_t nwall = 0;
    for (size_t i = 0; i < n; ++i) nwall += ps->kind[i] == RY_KIND_WALL;
    if (nwall == 0 || nwall == n || layers <= 0) return RY_OK;
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (int d = 0; d < dim; ++d) {
        lo[d] = hi[d] = ps->f[RY_F_X + d][0];
        for (size_t i = 1; i < n; ++i) {
            lo[d] = fmin(lo[d], ps->f[RY_F_X + d][i]);
            hi[d] = fmax(hi[d], ps->f[RY_F_X + d][i]);
        }
    }
    size_t nv[3] = {1, 1, 1}, total = 1;
    for (int d = 0; d < dim; ++d) {
        const double span = (hi[d] - lo[d]) / dx;
        RY_CHECK(err, isfinite(span) && span < 1e6, RY_ERR_RANGE,
                 "domain.wall_layers: the particles span %g spacings", span);
        nv[d] = (size_t)floor(span + 0.5) + 3; /* a voxel of margin on either side */
        lo[d] -= dx;
        total *= nv[d];
    }
    RY_CHECK(err, total <= (size_t)1 << 31, RY_ERR_RANGE,
             "domain.wall_layers: %zu voxels of one spacing over the particles' box", total);
    uint8_t *v = calloc(total, 1);
    int32_t *layer = malloc(total * sizeof *layer);
    uint32_t *queue = malloc(total * sizeof *queue);
    size_t *vox = malloc(n * sizeof *vox);
    uint8_t *gone = calloc(n, 1);
    if (!v || !layer || !queue || !vox || !gone) {
        free(v);
        free(layer);
        free(queue);
        free(vox);
        free(gone);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory (domain.wall_layers: %zu voxels)",
                            total);
    }
    const size_t stride[3] = {1, nv[0], nv[0] * nv[1]};
    for (size_t i = 0; i < n; ++i) {
        size_t k = 0;
        for (int d = 0; d < dim; ++d) {
            const double f = floor((ps->f[RY_F_X + d][i] - lo[d]) / dx + 0.5);
            k += (size_t)(f < 0 ? 0 : f >= (double)nv[d] ? (double)nv[d] - 1 : f) * stride[d];
        }
        vox[i] = k;
        if (ps->kind[i] == RY_KIND_WALL) v[k] = V_WALL;
    }
    for (int z = 0; z < nzones; ++z) { /* the zones' voxels: centres in the box */
        const double *zlo = zones + 6 * z, *zhi = zlo + 3;
        size_t a[3] = {0, 0, 0}, b[3] = {0, 0, 0};
        int empty = 0;
        for (int d = 0; d < dim; ++d) {
            const double f0 = ceil((zlo[d] - lo[d]) / dx - 1e-9),
                         f1 = floor((zhi[d] - lo[d]) / dx + 1e-9);
            a[d] = (size_t)fmax(f0, 0.0);
            b[d] = (size_t)fmin(f1, (double)nv[d] - 1);
            empty |= f1 < 0 || f0 > (double)nv[d] - 1 || f0 > f1;
        }
        if (empty) continue;
        for (size_t x = a[0]; x <= b[0]; ++x)
            for (size_t y = a[1]; y <= b[1]; ++y)
                for (size_t w = a[2]; w <= b[2]; ++w)
                    v[x + y * stride[1] + w * stride[2]] |= V_ZONE;
    }
    /* the flood from the other particles' voxels through the empty ones */
    size_t head = 0, tail = 0;
    for (size_t i = 0; i < n; ++i)
        if (ps->kind[i] != RY_KIND_WALL && !(v[vox[i]] & (V_WALL | V_REACHED))) {
            v[vox[i]] |= V_REACHED;
            queue[tail++] = (uint32_t)vox[i];
        }
    while (head < tail) {
        const size_t k = queue[head++];
        for (int d = 0; d < dim; ++d) {
            const size_t c = k / stride[d] % nv[d];
            if (c > 0 && passes(v, k, k - stride[d])) {
                v[k - stride[d]] |= V_REACHED;
                queue[tail++] = (uint32_t)(k - stride[d]);
            }
            if (c + 1 < nv[d] && passes(v, k, k + stride[d])) {
                v[k + stride[d]] |= V_REACHED;
                queue[tail++] = (uint32_t)(k + stride[d]);
            }
        }
    }
    /* the wall voxels' layers: from the reached space, through wall voxels, corners counting */
    for (size_t k = 0; k < total; ++k) layer[k] = v[k] & V_REACHED ? 0 : -1;
    head = tail = 0;
    for (size_t k = 0; k < total; ++k)
        if (v[k] & V_REACHED) queue[tail++] = (uint32_t)k;
    while (head < tail) {
        const size_t k = queue[head++];
        if (layer[k] >= layers) continue;
        size_t c[3] = {0, 0, 0};
        for (int d = 0; d < dim; ++d) c[d] = k / stride[d] % nv[d];
        const int zr = dim == 3 ? 1 : 0;
        for (int a = -1; a <= 1; ++a)
            for (int b = -1; b <= 1; ++b)
                for (int e = -zr; e <= zr; ++e) {
                    const int o[3] = {a, b, e};
                    size_t q = 0;
                    int inside = 1;
                    for (int d = 0; d < dim; ++d) {
                        const long cc = (long)c[d] + o[d];
                        inside &= cc >= 0 && cc < (long)nv[d];
                        q += (size_t)(cc < 0 ? 0 : cc) * stride[d];
                    }
                    if (!inside || !(v[q] & V_WALL) || layer[q] >= 0) continue;
                    layer[q] = layer[k] + 1;
                    queue[tail++] = (uint32_t)q;
                }
    }
    size_t count = 0;
    for (size_t i = 0; i < n; ++i)
        if (ps->kind[i] == RY_KIND_WALL && (layer[vox[i]] < 0 || layer[vox[i]] > layers)) {
            gone[i] = 1;
            ++count;
        }
    if (count) ry_particles_remove(ps, gone);
    *removed = count;
    free(v);
    free(layer);
    free(queue);
    free(vox);
    free(gone);
    return RY_OK;
}
