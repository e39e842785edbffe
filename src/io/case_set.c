/* Case files: --set key=value overrides, which replace or add values in the tree. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/case_internal.h"

ry_status ry_case_override(ry_case *c, const char *assignment, ry_error *err) {
    size_t alen = strlen(assignment);
    char *origin = malloc(alen + 8);
    char **ov = realloc(c->origins, (c->n_origins + 1) * sizeof *ov);
    if (ov) c->origins = ov;
    if (!origin || !ov) {
        free(origin);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory applying --set %s", assignment);
    }
    snprintf(origin, alen + 8, "--set %s", assignment);
    c->origins[c->n_origins++] = origin; /* owned by the case from now on */

    const char *eq = strchr(assignment, '=');
    if (!eq || eq == assignment)
        return ry_error_set(err, RY_ERR_INPUT, "%s: expected key=value", origin);
    size_t plen = (size_t)(eq - assignment);
    cpath p;
    int rc = ryc_parse_path(assignment, plen, &p);
    if (rc == -2) return ry_error_set(err, RY_ERR_NOMEM, "out of memory applying %s", origin);
    if (rc)
        return ry_error_set(err, RY_ERR_INPUT, "%s: invalid key '%.*s'", origin, (int)plen,
                            assignment);
    node *val = NULL;
    const char *vtext = eq + 1;
    ry_status st = ryc_build_tree(c->name, origin, vtext, strlen(vtext), &val, err);
    if (st != RY_OK) {
        free(p.v);
        return st;
    }
    if (!val && !(val = ryc_scalar_new("", 0, 0, 0, origin))) {
        free(p.v);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory applying %s", origin);
    }

    node *cur = c->root;
    loc at = {origin, 0};
    char got[CASE_SHOW_MAX + 32];
    for (size_t i = 0; i < p.n; i++) {
        const comp *k = &p.v[i];
        int last = i + 1 == p.n;
        int prev = i ? (int)p.v[i - 1].end : 0;
        node **slot = NULL;
        if (k->key) {
            if (cur->kind != N_MAP) {
                ryc_describe(got, sizeof got, cur);
                st = ryc_key_error(c, RY_ERR_INPUT, at, assignment, prev, err,
                                   "expected a mapping, got %s", got);
                goto done;
            }
            pair *pr = ryc_map_find(cur, k->key, k->klen);
            if (pr) {
                slot = &pr->val;
            } else {
                if (!last && !p.v[i + 1].key && p.v[i + 1].index != 0) {
                    st = ry_error_set(err, RY_ERR_INPUT,
                                      "%s: key '%.*s': index %zu is past the end of the sequence "
                                      "(0 elements)",
                                      origin, (int)p.v[i + 1].end, assignment, p.v[i + 1].index);
                    goto done;
                }
                node *nn = last ? val : ryc_node_new(p.v[i + 1].key ? N_MAP : N_SEQ, 0, origin);
                char *key = ryc_dup_mem(k->key, k->klen);
                if (!nn || !key || ryc_map_append(cur, key, 0, nn)) {
                    if (nn != val) free(nn);
                    free(key);
                    goto nomem;
                }
                if (last) val = NULL;
                cur = nn;
                continue;
            }
        } else {
            if (cur->kind != N_SEQ) {
                ryc_describe(got, sizeof got, cur);
                st = ryc_key_error(c, RY_ERR_INPUT, at, assignment, prev, err,
                                   "expected a sequence, got %s", got);
                goto done;
            }
            if (k->index < cur->n) {
                slot = &cur->items[k->index];
            } else if (k->index == cur->n) {
                if (!last && !p.v[i + 1].key && p.v[i + 1].index != 0) {
                    st = ry_error_set(err, RY_ERR_INPUT,
                                      "%s: key '%.*s': index %zu is past the end of the sequence "
                                      "(0 elements)",
                                      origin, (int)p.v[i + 1].end, assignment, p.v[i + 1].index);
                    goto done;
                }
                node *nn = last ? val : ryc_node_new(p.v[i + 1].key ? N_MAP : N_SEQ, 0, origin);
                if (!nn || ryc_seq_append(cur, nn)) {
                    if (nn != val) free(nn);
                    goto nomem;
                }
                if (last) val = NULL;
                cur = nn;
                continue;
            } else {
                st = ry_error_set(err, RY_ERR_INPUT,
                                  "%s: key '%.*s': index %zu is past the end of the sequence "
                                  "(%zu elements)",
                                  origin, (int)k->end, assignment, k->index, cur->n);
                goto done;
            }
        }
        /* an existing value */
        if (last) {
            ryc_bury(c, *slot);
            *slot = val;
            val = NULL;
        } else {
            if ((*slot)->dflt) { /* a mapping made for defaults becomes a real one */
                (*slot)->dflt = 0;
                (*slot)->origin = origin;
            }
            cur = *slot;
        }
    }
    st = RY_OK;
done:
    ryc_node_free(val);
    free(p.v);
    return st;
nomem:
    st = ry_error_set(err, RY_ERR_NOMEM, "out of memory applying %s", origin);
    goto done;
}
