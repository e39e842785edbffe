/* Case files: the check for keys nobody asked for, with a suggestion of a similar key that was
 * used (edit distance). */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/case_internal.h"

static void sb_truncate(sbuf *b, size_t n) {
    if (!b->failed && n <= b->n) {
        b->n = n;
        if (b->s) b->s[n] = '\0';
    }
}

static int compute_live(node *n) {
    int live = n->used;
    for (size_t i = 0; i < n->n; i++)
        live |= compute_live(n->kind == N_MAP ? n->pairs[i].val : n->items[i]);
    n->live = (unsigned char)live;
    return live;
}

static size_t edit_distance(const char *a, const char *b) {
    size_t na = strlen(a), nb = strlen(b);
    if (na > 64 || nb > 64) return SIZE_MAX;
    size_t row[65];
    for (size_t j = 0; j <= nb; j++) row[j] = j;
    for (size_t i = 1; i <= na; i++) {
        size_t diag = row[0];
        row[0] = i;
        for (size_t j = 1; j <= nb; j++) {
            size_t up = row[j];
            size_t best = diag + (a[i - 1] != b[j - 1]);
            if (up + 1 < best) best = up + 1;
            if (row[j - 1] + 1 < best) best = row[j - 1] + 1;
            row[j] = best;
            diag = up;
        }
    }
    return row[nb];
}

typedef struct unused_hit {
    const node *parent; /* the mapping holding the key, or NULL */
    const pair *pr;     /* the key, or NULL for a sequence element */
    const node *elem;
} unused_hit;

/* Finds the first unused key below n; path holds n's path and is extended with the hit's. */
static int find_unused(const node *n, sbuf *path, unused_hit *hit) {
    size_t keep = path->n;
    for (size_t i = 0; i < n->n; i++) {
        if (n->kind == N_MAP) {
            const pair *pr = &n->pairs[i];
            if (pr->val->dflt) continue;
            if (path->n) ryc_sb_str(path, ".");
            ryc_sb_str(path, pr->key);
            if (!pr->val->live) {
                *hit = (unused_hit){n, pr, NULL};
                return 1;
            }
            if (find_unused(pr->val, path, hit)) return 1;
        } else {
            const node *e = n->items[i];
            ryc_sb_printf(path, "[%zu]", i);
            if (!e->live) {
                if (e->kind == N_MAP && e->n > 0) {
                    ryc_sb_str(path, ".");
                    ryc_sb_str(path, e->pairs[0].key);
                    *hit = (unused_hit){e, &e->pairs[0], NULL};
                } else {
                    *hit = (unused_hit){NULL, NULL, e};
                }
                return 1;
            }
            if (find_unused(e, path, hit)) return 1;
        }
        sb_truncate(path, keep);
    }
    return 0;
}

ry_status ry_case_check_unused(ry_case *c, ry_error *err) {
    compute_live(c->root);
    c->root->live = 1;
    sbuf path = {0};
    unused_hit hit = {0};
    if (!find_unused(c->root, &path, &hit)) {
        free(path.s);
        return RY_OK;
    }
    if (path.failed) {
        free(path.s);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
    }
    loc l = hit.pr ? (loc){hit.pr->val->origin, hit.pr->val->origin ? 0 : hit.pr->key_line}
                   : ryc_node_loc(hit.elem);
    char where[RY_ERROR_MSG_MAX];
    ryc_where_str(c, l, where, sizeof where);
    const pair *best = NULL;
    size_t best_d = 3;
    if (hit.pr) {
        size_t klen = strlen(hit.pr->key);
        for (size_t i = 0; i < hit.parent->n; i++) {
            const pair *q = &hit.parent->pairs[i];
            if (q == hit.pr || !q->val->live) continue;
            size_t d = edit_distance(hit.pr->key, q->key);
            if (d < best_d && d < klen) {
                best_d = d;
                best = q;
            }
        }
    }
    ry_status st;
    if (best) {
        size_t klen = strlen(hit.pr->key);
        st = ry_error_set(err, RY_ERR_INPUT, "%s: unknown key '%s' (did you mean '%.*s%s'?)", where,
                          path.s, (int)(path.n - klen), path.s, best->key);
    } else {
        st = ry_error_set(err, RY_ERR_INPUT, "%s: unknown key '%s'", where, path.s);
    }
    free(path.s);
    return st;
}
