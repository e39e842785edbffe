/* Points binned in integer cells (3 coordinates), sorted, and looked up by cell: for finding
 * coincident or nearby points in O(n log n) without a fixed domain. */
#ifndef RYUSHI_CELL_KEY_H
#define RYUSHI_CELL_KEY_H

#include <stddef.h>
#include <stdint.h>

typedef struct ry_cell_key {
    int64_t c[3]; /* cell */
    uint32_t i;   /* point index */
} ry_cell_key;

/* qsort order: by cell, then by index. */
static inline int ry_cell_key_cmp(const void *a, const void *b) {
    const ry_cell_key *x = a, *y = b;
    for (int d = 0; d < 3; ++d)
        if (x->c[d] != y->c[d]) return x->c[d] < y->c[d] ? -1 : 1;
    return x->i < y->i ? -1 : x->i > y->i;
}

static inline int ry_cell_same(const int64_t *a, const int64_t *b) {
    return a[0] == b[0] && a[1] == b[1] && a[2] == b[2];
}

/* First entry of the sorted keys k[0..n) whose cell is not below c. */
static inline size_t ry_cell_key_find(const ry_cell_key *k, size_t n, const int64_t *c) {
    ry_cell_key probe = {{c[0], c[1], c[2]}, 0};
    size_t lo = 0, hi = n;
    while (lo < hi) {
        size_t mid = lo + (hi - lo) / 2;
        if (ry_cell_key_cmp(&k[mid], &probe) < 0)
            lo = mid + 1;
        else
            hi = mid;
    }
    return lo;
}

#endif
