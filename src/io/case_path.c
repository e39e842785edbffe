/* Case files: key paths ("time.t_end", "bodies[2].lo"), their lookup in the tree and the
 * recording of the defaults that getters fall back on. */
#include <stdlib.h>
#include <string.h>

#include "io/case_internal.h"

/* 0 on success, -1 for a malformed path, -2 when out of memory. */
int ryc_parse_path(const char *s, size_t len, cpath *out) {
    size_t cap = 0, i = 0;
    out->v = NULL;
    out->n = 0;
    for (;;) {
        size_t start = i;
        while (i < len && s[i] != '.' && s[i] != '[' && s[i] != ']') i++;
        if (i == start || !ryc_valid_key(s + start, i - start)) goto bad;
        comp *v = ryc_grow(out->v, &cap, out->n + 1, sizeof *v);
        if (!v) goto nomem;
        out->v = v;
        out->v[out->n++] = (comp){s + start, i - start, 0, i};
        while (i < len && s[i] == '[') {
            size_t idx = 0, d0 = ++i;
            while (i < len && s[i] >= '0' && s[i] <= '9') {
                if (idx > 100000000) goto bad;
                idx = idx * 10 + (size_t)(s[i] - '0');
                i++;
            }
            if (i == d0 || i >= len || s[i] != ']') goto bad;
            i++;
            v = ryc_grow(out->v, &cap, out->n + 1, sizeof *v);
            if (!v) goto nomem;
            out->v = v;
            out->v[out->n++] = (comp){NULL, 0, idx, i};
        }
        if (out->n > CASE_MAX_DEPTH) goto bad;
        if (i == len) return 0;
        if (s[i] != '.') goto bad;
        i++;
    }
bad:
    free(out->v);
    out->v = NULL;
    return -1;
nomem:
    free(out->v);
    out->v = NULL;
    return -2;
}

static ry_status path_error(int rc, const char *path, ry_error *err) {
    if (rc == -2) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
    return ry_error_set(err, RY_ERR_INTERNAL, "invalid key path '%s'", path);
}

/* Where a mapping value is reported: scalars at their own line, containers at their key. */
static loc pair_loc(const pair *p) {
    loc l = {p->val->origin, 0};
    if (!l.origin) l.line = (p->val->kind == N_SCALAR && p->val->line) ? p->val->line : p->key_line;
    return l;
}

/* Follows a path through the tree; default nodes count as absent. An error when the path runs
 * through a value of the wrong kind. */
static ry_status walk(const ry_case *c, const char *path, const cpath *p, found *f, ry_error *err) {
    node *cur = c->root;
    loc at = {NULL, 0};
    char got[CASE_SHOW_MAX + 32];
    f->val = NULL;
    for (size_t i = 0; i < p->n; i++) {
        const comp *k = &p->v[i];
        int plen = i ? (int)p->v[i - 1].end : 0;
        if (k->key) {
            if (cur->kind != N_MAP) {
                ryc_describe(got, sizeof got, cur);
                return ryc_key_error(c, RY_ERR_INPUT, at, path, plen, err,
                                     "expected a mapping, got %s", got);
            }
            pair *pr = ryc_map_find(cur, k->key, k->klen);
            if (!pr || pr->val->dflt) {
                f->at = at;
                return RY_OK;
            }
            cur = pr->val;
            at = pair_loc(pr);
        } else {
            if (cur->kind != N_SEQ) {
                ryc_describe(got, sizeof got, cur);
                return ryc_key_error(c, RY_ERR_INPUT, at, path, plen, err,
                                     "expected a sequence, got %s", got);
            }
            if (k->index >= cur->n) {
                f->at = at;
                return RY_OK;
            }
            cur = cur->items[k->index];
            at = ryc_node_loc(cur);
        }
    }
    f->val = cur;
    f->at = at;
    return RY_OK;
}

/* Looks a key up for a getter: parses the path and walks it. */
ry_status ryc_fetch(const ry_case *c, const char *path, found *f, ry_error *err) {
    cpath p;
    int rc = ryc_parse_path(path, strlen(path), &p);
    if (rc) return path_error(rc, path, err);
    ry_status st = walk(c, path, &p, f, err);
    free(p.v);
    return st;
}

/* Inserts a default value at path (taking ownership of val). Paths that would need a new
 * sequence element are not recorded. */
ry_status ryc_record_default(ry_case *c, const char *path, node *val, ry_error *err) {
    cpath p;
    int rc = ryc_parse_path(path, strlen(path), &p);
    if (rc) {
        ryc_node_free(val);
        return path_error(rc, path, err);
    }
    val->dflt = 1;
    val->used = 1;
    node *cur = c->root;
    for (size_t i = 0; i < p.n; i++) {
        const comp *k = &p.v[i];
        int last = i + 1 == p.n;
        if (!k->key) {
            if (cur->kind != N_SEQ || k->index >= cur->n || last) goto skip;
            cur = cur->items[k->index];
            continue;
        }
        if (cur->kind != N_MAP) goto skip;
        pair *pr = ryc_map_find(cur, k->key, k->klen);
        if (last) {
            if (pr && !pr->val->dflt) goto skip;
            if (pr) {
                ryc_bury(c, pr->val);
                pr->val = val;
            } else {
                char *key = ryc_dup_mem(k->key, k->klen);
                if (!key || ryc_map_append(cur, key, 0, val)) {
                    free(key);
                    goto nomem;
                }
            }
            free(p.v);
            return RY_OK;
        }
        if (!pr) {
            if (!p.v[i + 1].key) goto skip;
            node *m = ryc_node_new(N_MAP, 0, NULL);
            char *key = ryc_dup_mem(k->key, k->klen);
            if (!m || !key || ryc_map_append(cur, key, 0, m)) {
                free(m);
                free(key);
                goto nomem;
            }
            m->dflt = 1;
            m->used = 1;
            cur = m;
        } else {
            cur = pr->val;
        }
    }
skip:
    ryc_node_free(val);
    free(p.v);
    return RY_OK;
nomem:
    ryc_node_free(val);
    free(p.v);
    return ry_error_set(err, RY_ERR_NOMEM, "out of memory recording the default of '%s'", path);
}
