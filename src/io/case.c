/* Case files (see include/ryushi/case.h).
 *
 * The YAML text is read with libfyaml's event parser into a small tree of our own (mappings,
 * sequences, scalars), which keeps for every node the line it came from, or the --set
 * assignment that produced it, and whether a getter used it. Defaults that getters fall back
 * on are inserted into the tree as "default" nodes: lookups treat them as absent, the resolved
 * output writes them.
 *
 * Design decisions:
 *   - anchors, aliases (and so merge keys), explicit tags and directives are rejected;
 *   - a number is a plain (unquoted) scalar that parses entirely as a finite decimal number;
 *   - booleans are exactly the plain scalars true and false;
 *   - an empty value ("key:") is neither a number nor a string: getters reject it;
 *   - keys must be non-empty scalars without '.', '[' or ']' (they could not be addressed);
 *   - nesting is limited to CASE_MAX_DEPTH levels, so hostile input cannot exhaust the stack. */
#define _POSIX_C_SOURCE 200809L
#include "ryushi/case.h"

#include <errno.h>
#include <libfyaml.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/atomic_file.h"

enum { CASE_MAX_DEPTH = 100, CASE_SHOW_MAX = 60 };

typedef enum node_kind { N_SCALAR, N_MAP, N_SEQ } node_kind;

typedef struct node node;

typedef struct pair {
    char *key;
    int key_line; /* 1-based, 0 when the key came from an override or a default */
    node *val;
} pair;

struct node {
    node_kind kind;
    int line;           /* 1-based line of the value, 0 when unknown */
    const char *origin; /* the "--set ..." text that produced the node, NULL for the file */
    unsigned char used; /* fetched by a getter or touched */
    unsigned char dflt; /* inserted for a default: invisible to lookups */
    unsigned char quoted;
    unsigned char live; /* scratch: used, or something below is */
    char *text;         /* scalar text (NUL-terminated) */
    size_t len;
    size_t n, cap;
    pair *pairs;  /* N_MAP */
    node **items; /* N_SEQ */
};

struct ry_case {
    char *name;
    node *root;
    char **origins; /* "--set ..." strings, owned */
    size_t n_origins;
    node **graveyard; /* replaced nodes, kept so that pointers handed out stay valid */
    size_t n_graveyard;
};

/* ---------------------------------------------------------------- small helpers */

static char *dup_mem(const char *s, size_t n) {
    char *d = malloc(n + 1);
    if (!d) return NULL;
    if (n) memcpy(d, s, n);
    d[n] = '\0';
    return d;
}

static void *grow(void *p, size_t *cap, size_t need, size_t elem) {
    if (need <= *cap) return p;
    size_t c = *cap ? *cap : 4;
    while (c < need) {
        if (c > SIZE_MAX / 2 / elem) return NULL;
        c *= 2;
    }
    void *q = realloc(p, c * elem);
    if (q) *cap = c;
    return q;
}

typedef struct sbuf {
    char *s;
    size_t n, cap;
    int failed;
} sbuf;

static void sb_add(sbuf *b, const char *s, size_t n) {
    if (b->failed) return;
    char *q = grow(b->s, &b->cap, b->n + n + 1, 1);
    if (!q) {
        b->failed = 1;
        return;
    }
    b->s = q;
    memcpy(b->s + b->n, s, n);
    b->n += n;
    b->s[b->n] = '\0';
}

static void sb_str(sbuf *b, const char *s) {
    sb_add(b, s, strlen(s));
}

static void sb_printf(sbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void sb_printf(sbuf *b, const char *fmt, ...) {
    char tmp[64];
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (k < 0 || (size_t)k >= sizeof tmp) {
        b->failed = 1;
        return;
    }
    sb_add(b, tmp, (size_t)k);
}

static void sb_truncate(sbuf *b, size_t n) {
    if (!b->failed && n <= b->n) {
        b->n = n;
        if (b->s) b->s[n] = '\0';
    }
}

/* ---------------------------------------------------------------- nodes */

static node *node_new(node_kind kind, int line, const char *origin) {
    node *n = calloc(1, sizeof *n);
    if (!n) return NULL;
    n->kind = kind;
    n->line = line;
    n->origin = origin;
    return n;
}

static node *scalar_new(const char *text, size_t len, int quoted, int line, const char *origin) {
    node *n = node_new(N_SCALAR, line, origin);
    if (!n) return NULL;
    n->text = dup_mem(text ? text : "", text ? len : 0);
    if (!n->text) {
        free(n);
        return NULL;
    }
    n->len = text ? len : 0;
    n->quoted = (unsigned char)(quoted != 0);
    return n;
}

static void node_free(node *n) {
    if (!n) return;
    for (size_t i = 0; i < n->n; i++) {
        if (n->kind == N_MAP) {
            free(n->pairs[i].key);
            node_free(n->pairs[i].val);
        } else if (n->kind == N_SEQ) {
            node_free(n->items[i]);
        }
    }
    free(n->pairs);
    free(n->items);
    free(n->text);
    free(n);
}

/* Appends a pair; takes ownership of key and val only on success. */
static int map_append(node *m, char *key, int key_line, node *val) {
    pair *p = grow(m->pairs, &m->cap, m->n + 1, sizeof *p);
    if (!p) return -1;
    m->pairs = p;
    m->pairs[m->n].key = key;
    m->pairs[m->n].key_line = key_line;
    m->pairs[m->n].val = val;
    m->n++;
    return 0;
}

static int seq_append(node *s, node *val) {
    node **p = grow(s->items, &s->cap, s->n + 1, sizeof *p);
    if (!p) return -1;
    s->items = p;
    s->items[s->n++] = val;
    return 0;
}

static pair *map_find(node *m, const char *key, size_t klen) {
    for (size_t i = 0; i < m->n; i++) {
        const char *k = m->pairs[i].key;
        if (strncmp(k, key, klen) == 0 && k[klen] == '\0') return &m->pairs[i];
    }
    return NULL;
}

static void mark_all(node *n) {
    n->used = 1;
    for (size_t i = 0; i < n->n; i++) mark_all(n->kind == N_MAP ? n->pairs[i].val : n->items[i]);
}

static int is_empty_value(const node *n) {
    return n->kind == N_SCALAR && !n->quoted && n->len == 0;
}

static int valid_key(const char *k, size_t n) {
    if (n == 0 || memchr(k, '\0', n)) return 0;
    for (size_t i = 0; i < n; i++)
        if (k[i] == '.' || k[i] == '[' || k[i] == ']') return 0;
    return 1;
}

/* A short printable rendering of a scalar for messages. */
static void show_text(char *buf, size_t size, const char *s, size_t n) {
    size_t o = 0, lim = n > CASE_SHOW_MAX ? CASE_SHOW_MAX : n;
    for (size_t i = 0; i < lim && o + 1 < size; i++) {
        unsigned char ch = (unsigned char)s[i];
        buf[o++] = (ch < 0x20 || ch == 0x7f) ? '?' : (char)ch;
    }
    if (n > lim) {
        for (int k = 0; k < 3 && o + 1 < size; k++) buf[o++] = '.';
    }
    buf[o] = '\0';
}

static void describe(char *buf, size_t size, const node *n) {
    char t[CASE_SHOW_MAX + 8];
    if (n->kind == N_MAP) {
        snprintf(buf, size, "a mapping");
    } else if (n->kind == N_SEQ) {
        snprintf(buf, size, "a sequence");
    } else if (is_empty_value(n)) {
        snprintf(buf, size, "an empty value");
    } else {
        show_text(t, sizeof t, n->text, n->len);
        snprintf(buf, size, n->quoted ? "the quoted string '%s'" : "'%s'", t);
    }
}

/* ---------------------------------------------------------------- locations and errors */

typedef struct loc {
    const char *origin; /* "--set ..." or NULL */
    int line;           /* 0: the file alone */
} loc;

static loc node_loc(const node *n) {
    loc l = {n->origin, n->origin ? 0 : n->line};
    return l;
}

/* Where a mapping value is reported: scalars at their own line, containers at their key. */
static loc pair_loc(const pair *p) {
    loc l = {p->val->origin, 0};
    if (!l.origin) l.line = (p->val->kind == N_SCALAR && p->val->line) ? p->val->line : p->key_line;
    return l;
}

static void where_str(const ry_case *c, loc l, char *buf, size_t size) {
    if (l.origin)
        snprintf(buf, size, "%s", l.origin);
    else if (l.line > 0)
        snprintf(buf, size, "%s:%d", c->name, l.line);
    else
        snprintf(buf, size, "%s", c->name);
}

static ry_status key_error(const ry_case *c, ry_status code, loc l, const char *path, int plen,
                           ry_error *err, const char *fmt, ...)
    __attribute__((format(printf, 7, 8)));
static ry_status key_error(const ry_case *c, ry_status code, loc l, const char *path, int plen,
                           ry_error *err, const char *fmt, ...) {
    char where[RY_ERROR_MSG_MAX], what[RY_ERROR_MSG_MAX];
    where_str(c, l, where, sizeof where);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    if (plen < 0) plen = (int)strlen(path);
    return ry_error_set(err, code, "%s: key '%.*s': %s", where, plen, path, what);
}

/* ---------------------------------------------------------------- paths */

typedef struct comp {
    const char *key; /* NULL for an index */
    size_t klen;
    size_t index;
    size_t end; /* offset just after this component in the path text */
} comp;

typedef struct cpath {
    comp *v;
    size_t n;
} cpath;

/* 0 on success, -1 for a malformed path, -2 when out of memory. */
static int parse_path(const char *s, size_t len, cpath *out) {
    size_t cap = 0, i = 0;
    out->v = NULL;
    out->n = 0;
    for (;;) {
        size_t start = i;
        while (i < len && s[i] != '.' && s[i] != '[' && s[i] != ']') i++;
        if (i == start || !valid_key(s + start, i - start)) goto bad;
        comp *v = grow(out->v, &cap, out->n + 1, sizeof *v);
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
            v = grow(out->v, &cap, out->n + 1, sizeof *v);
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

typedef struct found {
    node *val; /* NULL when absent */
    loc at;    /* of the value, or of the deepest existing parent when absent */
} found;

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
                describe(got, sizeof got, cur);
                return key_error(c, RY_ERR_INPUT, at, path, plen, err, "expected a mapping, got %s",
                                 got);
            }
            pair *pr = map_find(cur, k->key, k->klen);
            if (!pr || pr->val->dflt) {
                f->at = at;
                return RY_OK;
            }
            cur = pr->val;
            at = pair_loc(pr);
        } else {
            if (cur->kind != N_SEQ) {
                describe(got, sizeof got, cur);
                return key_error(c, RY_ERR_INPUT, at, path, plen, err,
                                 "expected a sequence, got %s", got);
            }
            if (k->index >= cur->n) {
                f->at = at;
                return RY_OK;
            }
            cur = cur->items[k->index];
            at = node_loc(cur);
        }
    }
    f->val = cur;
    f->at = at;
    return RY_OK;
}

/* Looks a key up for a getter: parses the path and walks it. */
static ry_status fetch(const ry_case *c, const char *path, found *f, ry_error *err) {
    cpath p;
    int rc = parse_path(path, strlen(path), &p);
    if (rc) return path_error(rc, path, err);
    ry_status st = walk(c, path, &p, f, err);
    free(p.v);
    return st;
}

static void bury(ry_case *c, node *n) {
    size_t cap = c->n_graveyard; /* grown one at a time; replacements are rare */
    node **g = realloc(c->graveyard, (cap + 1) * sizeof *g);
    if (!g) {
        node_free(n); /* nothing handed out can be kept valid then; rare enough */
        return;
    }
    c->graveyard = g;
    c->graveyard[c->n_graveyard++] = n;
}

/* Inserts a default value at path (taking ownership of val). Paths that would need a new
 * sequence element are not recorded. */
static ry_status record_default(ry_case *c, const char *path, node *val, ry_error *err) {
    cpath p;
    int rc = parse_path(path, strlen(path), &p);
    if (rc) {
        node_free(val);
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
        pair *pr = map_find(cur, k->key, k->klen);
        if (last) {
            if (pr && !pr->val->dflt) goto skip;
            if (pr) {
                bury(c, pr->val);
                pr->val = val;
            } else {
                char *key = dup_mem(k->key, k->klen);
                if (!key || map_append(cur, key, 0, val)) {
                    free(key);
                    goto nomem;
                }
            }
            free(p.v);
            return RY_OK;
        }
        if (!pr) {
            if (!p.v[i + 1].key) goto skip;
            node *m = node_new(N_MAP, 0, NULL);
            char *key = dup_mem(k->key, k->klen);
            if (!m || !key || map_append(cur, key, 0, m)) {
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
    node_free(val);
    free(p.v);
    return RY_OK;
nomem:
    node_free(val);
    free(p.v);
    return ry_error_set(err, RY_ERR_NOMEM, "out of memory recording the default of '%s'", path);
}

/* ---------------------------------------------------------------- reading YAML */

typedef struct diag_sink {
    char last[256]; /* the last message libfyaml tried to print */
} diag_sink;

static void diag_output(struct fy_diag *diag, void *user, const char *buf, size_t len) {
    (void)diag;
    diag_sink *s = user;
    size_t n = len < sizeof s->last - 1 ? len : sizeof s->last - 1;
    memcpy(s->last, buf, n);
    while (n > 0 && (s->last[n - 1] == '\n' || s->last[n - 1] == ' ')) n--;
    s->last[n] = '\0';
}

typedef struct frame {
    node *n;
    char *key; /* mapping: the key waiting for its value */
    int key_line;
} frame;

typedef struct builder {
    const char *name;   /* file name for messages */
    const char *origin; /* set for --set values: messages name it instead of file:line */
    ry_error *err;
    frame stack[CASE_MAX_DEPTH + 1];
    int depth;
    node *root;
} builder;

static ry_status build_error(builder *b, int line, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static ry_status build_error(builder *b, int line, const char *fmt, ...) {
    char what[RY_ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    if (b->origin)
        return ry_error_set(b->err, RY_ERR_INPUT, "%s: invalid value: %s", b->origin, what);
    if (line > 0) return ry_error_set(b->err, RY_ERR_INPUT, "%s:%d: %s", b->name, line, what);
    return ry_error_set(b->err, RY_ERR_INPUT, "%s: %s", b->name, what);
}

/* The dotted path of the container at stack level lvl (for messages). Containers are attached
 * when they start, so each one is the last entry of its parent. */
static void frame_path(const builder *b, int lvl, sbuf *out) {
    for (int i = 1; i <= lvl; i++) {
        const node *parent = b->stack[i - 1].n;
        if (parent->kind == N_MAP) {
            if (out->n) sb_str(out, ".");
            sb_str(out, parent->pairs[parent->n - 1].key);
        } else {
            sb_printf(out, "[%zu]", parent->n - 1);
        }
    }
}

typedef struct key_ref {
    const char *key;
    size_t idx;
} key_ref;

static int key_ref_cmp(const void *a, const void *b) {
    const key_ref *x = a, *y = b;
    int r = strcmp(x->key, y->key);
    if (r) return r;
    return x->idx < y->idx ? -1 : x->idx > y->idx;
}

/* Reports the first (in document order) repeated key of the mapping on top of the stack. */
static ry_status check_duplicates(builder *b) {
    node *m = b->stack[b->depth].n;
    if (m->n < 2) return RY_OK;
    key_ref *r = malloc(m->n * sizeof *r);
    if (!r) return ry_error_set(b->err, RY_ERR_NOMEM, "out of memory reading '%s'", b->name);
    for (size_t i = 0; i < m->n; i++) r[i] = (key_ref){m->pairs[i].key, i};
    qsort(r, m->n, sizeof *r, key_ref_cmp);
    size_t best = SIZE_MAX, first = 0;
    for (size_t i = 1; i < m->n; i++) {
        if (strcmp(r[i].key, r[i - 1].key) != 0) continue;
        size_t g = i - 1;
        while (g > 0 && strcmp(r[g - 1].key, r[i].key) == 0) g--;
        if (r[i].idx < best) {
            best = r[i].idx;
            first = r[g].idx;
        }
    }
    free(r);
    if (best == SIZE_MAX) return RY_OK;
    /* report with the stack still describing this mapping */
    sbuf path = {0};
    frame_path(b, b->depth, &path);
    if (path.n) sb_str(&path, ".");
    sb_str(&path, m->pairs[best].key);
    ry_status st;
    if (path.failed) {
        st = ry_error_set(b->err, RY_ERR_NOMEM, "out of memory reading '%s'", b->name);
    } else {
        if (b->origin)
            st = ry_error_set(b->err, RY_ERR_INPUT, "%s: key '%s': duplicate key", b->origin,
                              path.s);
        else
            st = ry_error_set(b->err, RY_ERR_INPUT,
                              "%s:%d: key '%s': duplicate key (first given on line %d)", b->name,
                              m->pairs[best].key_line, path.s, m->pairs[first].key_line);
    }
    free(path.s);
    return st;
}

/* Hangs a new node (or key) into the container on top of the stack. Takes ownership of n. */
static ry_status attach(builder *b, node *n) {
    if (b->depth < 0) {
        if (b->root) {
            int line = n->line;
            node_free(n);
            return build_error(b, line, "only one YAML document is allowed");
        }
        b->root = n;
        return RY_OK;
    }
    frame *f = &b->stack[b->depth];
    if (n->line == 0 && !b->origin)
        n->line = f->n->kind == N_MAP && f->key ? f->key_line : f->n->line;
    if (f->n->kind == N_SEQ) {
        if (seq_append(f->n, n)) {
            node_free(n);
            return ry_error_set(b->err, RY_ERR_NOMEM, "out of memory reading '%s'", b->name);
        }
        return RY_OK;
    }
    if (!f->key) { /* n is a key */
        int line = n->line;
        if (n->kind != N_SCALAR) {
            node_free(n);
            return build_error(b, line, "a key must be a plain name, not a mapping or sequence");
        }
        if (!valid_key(n->text, n->len)) {
            char t[CASE_SHOW_MAX + 8];
            show_text(t, sizeof t, n->text, n->len);
            node_free(n);
            return build_error(b, line,
                               "invalid key '%s' (keys must be non-empty and must not "
                               "contain '.', '[' or ']')",
                               t);
        }
        f->key = n->text;
        f->key_line = line;
        n->text = NULL;
        node_free(n);
        return RY_OK;
    }
    if (map_append(f->n, f->key, f->key_line, n)) {
        node_free(n);
        return ry_error_set(b->err, RY_ERR_NOMEM, "out of memory reading '%s'", b->name);
    }
    f->key = NULL;
    return RY_OK;
}

static ry_status on_event(builder *b, struct fy_event *e) {
    const struct fy_mark *m = fy_event_start_mark(e);
    int line = m ? m->line + 1 : 0;
    if (b->origin) line = 0;
    struct fy_token *anchor = NULL, *tag = NULL;
    switch (e->type) {
    case FYET_ALIAS:
        return build_error(b, line, "anchors and aliases are not supported");
    case FYET_SCALAR:
        anchor = e->scalar.anchor;
        tag = e->scalar.tag;
        break;
    case FYET_MAPPING_START:
        anchor = e->mapping_start.anchor;
        tag = e->mapping_start.tag;
        break;
    case FYET_SEQUENCE_START:
        anchor = e->sequence_start.anchor;
        tag = e->sequence_start.tag;
        break;
    default:
        break;
    }
    if (anchor) return build_error(b, line, "anchors and aliases are not supported");
    if (tag) return build_error(b, line, "tags are not supported");

    if (e->type == FYET_SCALAR) {
        size_t len = 0;
        const char *t = NULL;
        if (e->scalar.value) {
            t = fy_token_get_text(e->scalar.value, &len);
            if (!t)
                return ry_error_set(b->err, RY_ERR_NOMEM, "out of memory reading '%s'", b->name);
        }
        if (t && memchr(t, '\0', len))
            return build_error(b, line, "a value contains a NUL character");
        int quoted = fy_token_scalar_style(e->scalar.value) != FYSS_PLAIN;
        node *n = scalar_new(t, len, quoted, line, b->origin);
        if (!n) return ry_error_set(b->err, RY_ERR_NOMEM, "out of memory reading '%s'", b->name);
        return attach(b, n);
    }
    if (e->type == FYET_MAPPING_START || e->type == FYET_SEQUENCE_START) {
        if (b->depth + 1 >= CASE_MAX_DEPTH)
            return build_error(b, line, "nesting deeper than %d levels", CASE_MAX_DEPTH);
        node *n = node_new(e->type == FYET_MAPPING_START ? N_MAP : N_SEQ, line, b->origin);
        if (!n) return ry_error_set(b->err, RY_ERR_NOMEM, "out of memory reading '%s'", b->name);
        if (b->depth >= 0 && b->stack[b->depth].n->kind == N_MAP && !b->stack[b->depth].key) {
            node_free(n);
            return build_error(b, line, "a key must be a plain name, not a mapping or sequence");
        }
        RY_TRY(attach(b, n));
        b->depth++;
        b->stack[b->depth] = (frame){n, NULL, 0};
        return RY_OK;
    }
    if (e->type == FYET_MAPPING_END || e->type == FYET_SEQUENCE_END) {
        if (b->depth < 0) return build_error(b, line, "unbalanced collection");
        if (e->type == FYET_MAPPING_END) RY_TRY(check_duplicates(b));
        b->depth--;
        return RY_OK;
    }
    return RY_OK;
}

/* Parses text into a tree. *out is NULL for an empty stream. */
static ry_status build_tree(const char *name, const char *origin, const char *text, size_t len,
                            node **out, ry_error *err) {
    *out = NULL;
    /* Directives (%YAML, %TAG) have no use in a case, and libfyaml 0.7 can loop forever on a
     * malformed one (found by fuzzing): refused before parsing. A line ends at LF, CR LF or a
     * lone CR, as YAML has it (a '%' after a lone CR also hung the parser). */
    for (size_t i = 0, line = 1; i < len; ++i) {
        if (text[i] == '%' && (i == 0 || text[i - 1] == '\n' || text[i - 1] == '\r')) {
            builder b = {.name = name, .origin = origin, .err = err};
            return build_error(&b, origin ? 0 : (int)line,
                               "YAML directives (lines starting with '%%') are not supported");
        }
        if (text[i] == '\n' || (text[i] == '\r' && (i + 1 == len || text[i + 1] != '\n'))) ++line;
    }
    diag_sink sink;
    sink.last[0] = '\0';
    struct fy_diag_cfg dcfg;
    fy_diag_cfg_default(&dcfg);
    dcfg.fp = NULL;
    dcfg.output_fn = diag_output;
    dcfg.user = &sink;
    dcfg.colorize = false;
    struct fy_diag *diag = fy_diag_create(&dcfg);
    if (!diag) return ry_error_set(err, RY_ERR_NOMEM, "out of memory reading '%s'", name);
    fy_diag_set_collect_errors(diag, true);
    struct fy_parse_cfg pcfg;
    memset(&pcfg, 0, sizeof pcfg);
    pcfg.flags = FYPCF_QUIET;
    pcfg.diag = diag;
    struct fy_parser *fyp = fy_parser_create(&pcfg);
    if (!fyp) {
        fy_diag_destroy(diag);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory reading '%s'", name);
    }
    builder *b = calloc(1, sizeof *b);
    if (!b) {
        fy_parser_destroy(fyp);
        fy_diag_destroy(diag);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory reading '%s'", name);
    }
    b->name = name;
    b->origin = origin;
    b->err = err;
    b->depth = -1;
    ry_status st = RY_OK;
    int ended = 0;
    if (fy_parser_set_string(fyp, len ? text : "", len) != 0) {
        st = ry_error_set(err, RY_ERR_NOMEM, "out of memory reading '%s'", name);
    } else {
        struct fy_event *e;
        while (st == RY_OK && (e = fy_parser_parse(fyp)) != NULL) {
            if (e->type == FYET_STREAM_END) ended = 1;
            st = on_event(b, e);
            fy_parser_event_free(fyp, e);
        }
        if (st == RY_OK && (!ended || fy_parser_get_stream_error(fyp))) {
            void *it = NULL;
            struct fy_diag_error *de;
            const struct fy_diag_error *first = NULL;
            while ((de = fy_diag_errors_iterate(diag, &it)) != NULL)
                if (!first && de->type >= FYET_ERROR) first = de;
            if (first)
                st = build_error(b, origin ? 0 : first->line, "syntax error: %s",
                                 first->msg ? first->msg : "invalid YAML");
            else
                st = build_error(b, 0, "syntax error: %s",
                                 sink.last[0] ? sink.last : "invalid YAML");
        }
    }
    for (int i = 0; i <= b->depth; i++) free(b->stack[i].key);
    if (st == RY_OK)
        *out = b->root;
    else
        node_free(b->root);
    free(b);
    fy_parser_destroy(fyp);
    fy_diag_destroy(diag);
    return st;
}

static ry_status case_from_text(ry_case **out, const char *name, const char *text, size_t len,
                                ry_error *err) {
    *out = NULL;
    ry_case *c = calloc(1, sizeof *c);
    if (!c) return ry_error_set(err, RY_ERR_NOMEM, "out of memory reading '%s'", name);
    c->name = dup_mem(name, strlen(name));
    if (!c->name) {
        free(c);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory reading '%s'", name);
    }
    ry_status st = build_tree(c->name, NULL, text, len, &c->root, err);
    if (st != RY_OK) {
        ry_case_free(c);
        return st;
    }
    if (!c->root || is_empty_value(c->root)) {
        node_free(c->root);
        c->root = node_new(N_MAP, 0, NULL);
        if (!c->root) {
            ry_case_free(c);
            return ry_error_set(err, RY_ERR_NOMEM, "out of memory reading '%s'", name);
        }
    }
    if (c->root->kind != N_MAP) {
        char got[CASE_SHOW_MAX + 32];
        describe(got, sizeof got, c->root);
        loc l = {NULL, c->root->line};
        char where[RY_ERROR_MSG_MAX];
        where_str(c, l, where, sizeof where);
        ry_error_set(err, RY_ERR_INPUT, "%s: the top level must be a mapping of keys, got %s",
                     where, got);
        ry_case_free(c);
        return RY_ERR_INPUT;
    }
    *out = c;
    return RY_OK;
}

ry_status ry_case_load_string(ry_case **out, const char *name, const char *text, ry_error *err) {
    return case_from_text(out, name, text, strlen(text), err);
}

ry_status ry_case_load(ry_case **out, const char *path, ry_error *err) {
    *out = NULL;
    FILE *fp = fopen(path, "rb");
    if (!fp) return ry_error_set(err, RY_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
    char *buf = NULL;
    size_t n = 0, cap = 0;
    for (;;) {
        char *q = grow(buf, &cap, n + 65536, 1);
        if (!q) {
            free(buf);
            fclose(fp);
            return ry_error_set(err, RY_ERR_NOMEM, "out of memory reading '%s'", path);
        }
        buf = q;
        size_t k = fread(buf + n, 1, cap - n, fp);
        n += k;
        if (k == 0) break;
    }
    int e = ferror(fp) ? errno : 0;
    fclose(fp);
    if (e) {
        free(buf);
        return ry_error_set(err, RY_ERR_IO, "cannot read '%s': %s", path, strerror(e));
    }
    ry_status st = case_from_text(out, path, buf, n, err);
    free(buf);
    return st;
}

void ry_case_free(ry_case *c) {
    if (!c) return;
    node_free(c->root);
    for (size_t i = 0; i < c->n_graveyard; i++) node_free(c->graveyard[i]);
    free(c->graveyard);
    for (size_t i = 0; i < c->n_origins; i++) free(c->origins[i]);
    free(c->origins);
    free(c->name);
    free(c);
}

const char *ry_case_name(const ry_case *c) {
    return c->name;
}

/* ---------------------------------------------------------------- overrides */

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
    int rc = parse_path(assignment, plen, &p);
    if (rc == -2) return ry_error_set(err, RY_ERR_NOMEM, "out of memory applying %s", origin);
    if (rc)
        return ry_error_set(err, RY_ERR_INPUT, "%s: invalid key '%.*s'", origin, (int)plen,
                            assignment);
    node *val = NULL;
    const char *vtext = eq + 1;
    ry_status st = build_tree(c->name, origin, vtext, strlen(vtext), &val, err);
    if (st != RY_OK) {
        free(p.v);
        return st;
    }
    if (!val && !(val = scalar_new("", 0, 0, 0, origin))) {
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
                describe(got, sizeof got, cur);
                st = key_error(c, RY_ERR_INPUT, at, assignment, prev, err,
                               "expected a mapping, got %s", got);
                goto done;
            }
            pair *pr = map_find(cur, k->key, k->klen);
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
                node *nn = last ? val : node_new(p.v[i + 1].key ? N_MAP : N_SEQ, 0, origin);
                char *key = dup_mem(k->key, k->klen);
                if (!nn || !key || map_append(cur, key, 0, nn)) {
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
                describe(got, sizeof got, cur);
                st = key_error(c, RY_ERR_INPUT, at, assignment, prev, err,
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
                node *nn = last ? val : node_new(p.v[i + 1].key ? N_MAP : N_SEQ, 0, origin);
                if (!nn || seq_append(cur, nn)) {
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
            bury(c, *slot);
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
    node_free(val);
    free(p.v);
    return st;
nomem:
    st = ry_error_set(err, RY_ERR_NOMEM, "out of memory applying %s", origin);
    goto done;
}

/* ---------------------------------------------------------------- queries */

int ry_case_has(const ry_case *c, const char *path) {
    found f;
    if (fetch(c, path, &f, NULL) != RY_OK) return 0;
    return f.val != NULL;
}

void ry_case_touch(ry_case *c, const char *path) {
    found f;
    if (fetch(c, path, &f, NULL) == RY_OK && f.val) mark_all(f.val);
}

const char *ry_case_where(ry_case *c, const char *path, char *buf, size_t size) {
    if (!buf || size == 0) return "";
    found f;
    loc l = {NULL, 0};
    if (fetch(c, path, &f, NULL) == RY_OK && f.val) l = f.at;
    where_str(c, l, buf, size);
    return buf;
}

/* ---------------------------------------------------------------- getters */

static ry_status missing(const ry_case *c, const char *path, const found *f, ry_error *err) {
    return key_error(c, RY_ERR_INPUT, f->at, path, -1, err, "required key is missing");
}

/* Parses a plain scalar entirely as a finite number. */
static int parse_number(const node *n, double *out) {
    if (n->kind != N_SCALAR || n->quoted || n->len == 0) return 0;
    for (size_t i = 0; i < n->len; i++) {
        char ch = n->text[i];
        if (!((ch >= '0' && ch <= '9') || ch == '.' || ch == 'e' || ch == 'E' || ch == '+' ||
              ch == '-'))
            return 0;
    }
    char *end;
    errno = 0;
    double x = strtod(n->text, &end);
    if (end != n->text + n->len || !isfinite(x)) return 0;
    if (errno == ERANGE && fabs(x) > 1.0) return 0;
    *out = x;
    return 1;
}

static void fmt_double(char *buf, size_t size, double x) {
    for (int prec = 15; prec <= 17; prec++) {
        snprintf(buf, size, "%.*g", prec, x);
        if (strtod(buf, NULL) == x) return;
    }
}

static node *number_node(double x) {
    char t[40];
    fmt_double(t, sizeof t, x);
    return scalar_new(t, strlen(t), 0, 0, NULL);
}

static void range_text(char *buf, size_t size, const char *what, double lo, double hi) {
    char a[40], b[40];
    fmt_double(a, sizeof a, lo);
    fmt_double(b, sizeof b, hi);
    if (isfinite(lo) && isfinite(hi))
        snprintf(buf, size, "%s in [%s, %s]", what, a, b);
    else if (isfinite(lo))
        snprintf(buf, size, "%s >= %s", what, a);
    else if (isfinite(hi))
        snprintf(buf, size, "%s <= %s", what, b);
    else
        snprintf(buf, size, "%s", what);
}

static ry_status get_number(ry_case *c, const char *path, const double *def, double lo, double hi,
                            const char *what, double *out, ry_error *err) {
    found f;
    RY_TRY(fetch(c, path, &f, err));
    char want[160], got[CASE_SHOW_MAX + 32];
    range_text(want, sizeof want, what, lo, hi);
    if (!f.val) {
        if (!def) return missing(c, path, &f, err);
        if (!(*def >= lo && *def <= hi))
            return ry_error_set(err, RY_ERR_INTERNAL, "default of key '%s' is not %s", path, want);
        node *d = number_node(*def);
        if (!d) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        RY_TRY(record_default(c, path, d, err));
        *out = *def;
        return RY_OK;
    }
    f.val->used = 1;
    double x;
    describe(got, sizeof got, f.val);
    if (!parse_number(f.val, &x))
        return key_error(c, RY_ERR_INPUT, f.at, path, -1, err, "expected %s, got %s", want, got);
    if (!(x >= lo && x <= hi))
        return key_error(c, RY_ERR_RANGE, f.at, path, -1, err, "expected %s, got %s", want, got);
    *out = x;
    return RY_OK;
}

ry_status ry_case_double(ry_case *c, const char *path, const double *def, double lo, double hi,
                         double *out, ry_error *err) {
    return get_number(c, path, def, lo, hi, "a number", out, err);
}

ry_status ry_case_positive(ry_case *c, const char *path, const double *def, double *out,
                           ry_error *err) {
    found f;
    RY_TRY(fetch(c, path, &f, err));
    if (!f.val) {
        if (!def) return missing(c, path, &f, err);
        if (!(*def > 0))
            return ry_error_set(err, RY_ERR_INTERNAL, "default of key '%s' is not positive", path);
        node *d = number_node(*def);
        if (!d) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        RY_TRY(record_default(c, path, d, err));
        *out = *def;
        return RY_OK;
    }
    f.val->used = 1;
    double x;
    char got[CASE_SHOW_MAX + 32];
    describe(got, sizeof got, f.val);
    if (!parse_number(f.val, &x))
        return key_error(c, RY_ERR_INPUT, f.at, path, -1, err, "expected a positive number, got %s",
                         got);
    if (!(x > 0))
        return key_error(c, RY_ERR_RANGE, f.at, path, -1, err, "expected a positive number, got %s",
                         got);
    *out = x;
    return RY_OK;
}

/* Parses a plain scalar entirely as an integer; 1 ok, 0 not an integer, -1 out of range. */
static int parse_long(const node *n, long *out) {
    if (n->kind != N_SCALAR || n->quoted || n->len == 0) return 0;
    for (size_t i = 0; i < n->len; i++) {
        char ch = n->text[i];
        if (!((ch >= '0' && ch <= '9') || ((ch == '+' || ch == '-') && i == 0))) return 0;
    }
    char *end;
    errno = 0;
    long v = strtol(n->text, &end, 10);
    if (end != n->text + n->len) return 0;
    if (errno == ERANGE) return -1;
    *out = v;
    return 1;
}

ry_status ry_case_int(ry_case *c, const char *path, const long *def, long lo, long hi, long *out,
                      ry_error *err) {
    found f;
    RY_TRY(fetch(c, path, &f, err));
    char want[160], got[CASE_SHOW_MAX + 32];
    if (lo > LONG_MIN && hi < LONG_MAX)
        snprintf(want, sizeof want, "an integer in [%ld, %ld]", lo, hi);
    else if (lo > LONG_MIN)
        snprintf(want, sizeof want, "an integer >= %ld", lo);
    else if (hi < LONG_MAX)
        snprintf(want, sizeof want, "an integer <= %ld", hi);
    else
        snprintf(want, sizeof want, "an integer");
    if (!f.val) {
        if (!def) return missing(c, path, &f, err);
        if (*def < lo || *def > hi)
            return ry_error_set(err, RY_ERR_INTERNAL, "default of key '%s' is not %s", path, want);
        char t[32];
        snprintf(t, sizeof t, "%ld", *def);
        node *d = scalar_new(t, strlen(t), 0, 0, NULL);
        if (!d) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        RY_TRY(record_default(c, path, d, err));
        *out = *def;
        return RY_OK;
    }
    f.val->used = 1;
    long v = 0;
    describe(got, sizeof got, f.val);
    int rc = parse_long(f.val, &v);
    if (rc == 0)
        return key_error(c, RY_ERR_INPUT, f.at, path, -1, err, "expected %s, got %s", want, got);
    if (rc < 0 || v < lo || v > hi)
        return key_error(c, RY_ERR_RANGE, f.at, path, -1, err, "expected %s, got %s", want, got);
    *out = v;
    return RY_OK;
}

ry_status ry_case_bool(ry_case *c, const char *path, const int *def, int *out, ry_error *err) {
    found f;
    RY_TRY(fetch(c, path, &f, err));
    if (!f.val) {
        if (!def) return missing(c, path, &f, err);
        const char *t = *def ? "true" : "false";
        node *d = scalar_new(t, strlen(t), 0, 0, NULL);
        if (!d) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        RY_TRY(record_default(c, path, d, err));
        *out = *def != 0;
        return RY_OK;
    }
    f.val->used = 1;
    const node *v = f.val;
    if (v->kind == N_SCALAR && !v->quoted && strcmp(v->text, "true") == 0) {
        *out = 1;
        return RY_OK;
    }
    if (v->kind == N_SCALAR && !v->quoted && strcmp(v->text, "false") == 0) {
        *out = 0;
        return RY_OK;
    }
    char got[CASE_SHOW_MAX + 32];
    describe(got, sizeof got, v);
    return key_error(c, RY_ERR_INPUT, f.at, path, -1, err, "expected true or false, got %s", got);
}

ry_status ry_case_string(ry_case *c, const char *path, const char *def, const char **out,
                         ry_error *err) {
    found f;
    RY_TRY(fetch(c, path, &f, err));
    if (!f.val) {
        if (!def) return missing(c, path, &f, err);
        node *d = scalar_new(def, strlen(def), 1, 0, NULL);
        if (!d) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        RY_TRY(record_default(c, path, d, err));
        *out = def;
        return RY_OK;
    }
    f.val->used = 1;
    if (f.val->kind != N_SCALAR || is_empty_value(f.val)) {
        char got[CASE_SHOW_MAX + 32];
        describe(got, sizeof got, f.val);
        return key_error(c, RY_ERR_INPUT, f.at, path, -1, err, "expected a string, got %s", got);
    }
    *out = f.val->text;
    return RY_OK;
}

ry_status ry_case_choice(ry_case *c, const char *path, const char *def, const char *const *names,
                         int *out, ry_error *err) {
    found f;
    RY_TRY(fetch(c, path, &f, err));
    const char *text;
    if (!f.val) {
        if (!def) return missing(c, path, &f, err);
        text = def;
    } else {
        f.val->used = 1;
        text = f.val->kind == N_SCALAR && !is_empty_value(f.val) ? f.val->text : NULL;
    }
    int idx = -1;
    for (int i = 0; text && names[i]; i++) {
        if (strcmp(names[i], text) == 0) {
            idx = i;
            break;
        }
    }
    if (idx < 0) {
        sbuf list = {0};
        for (int i = 0; names[i]; i++) {
            if (i) sb_str(&list, ", ");
            sb_str(&list, names[i]);
        }
        char got[CASE_SHOW_MAX + 32];
        if (f.val)
            describe(got, sizeof got, f.val);
        else
            snprintf(got, sizeof got, "'%s'", def);
        ry_status st;
        if (list.failed)
            st = ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        else if (!f.val)
            st = ry_error_set(err, RY_ERR_INTERNAL, "default %s of key '%s' is not one of %s", got,
                              path, list.s ? list.s : "");
        else
            st = key_error(c, RY_ERR_INPUT, f.at, path, -1, err, "expected one of %s; got %s",
                           list.s ? list.s : "", got);
        free(list.s);
        return st;
    }
    if (!f.val) {
        node *d = scalar_new(def, strlen(def), 1, 0, NULL);
        if (!d) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        RY_TRY(record_default(c, path, d, err));
    }
    *out = idx;
    return RY_OK;
}

ry_status ry_case_vector(ry_case *c, const char *path, const double *def, int n, double *out,
                         ry_error *err) {
    found f;
    RY_TRY(fetch(c, path, &f, err));
    if (!f.val) {
        if (!def) return missing(c, path, &f, err);
        node *s = node_new(N_SEQ, 0, NULL);
        if (!s) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        for (int i = 0; i < n; i++) {
            node *d = number_node(def[i]);
            if (!d || seq_append(s, d)) {
                node_free(d);
                node_free(s);
                return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
            }
        }
        RY_TRY(record_default(c, path, s, err));
        for (int i = 0; i < n; i++) out[i] = def[i];
        return RY_OK;
    }
    node *v = f.val;
    v->used = 1;
    char got[CASE_SHOW_MAX + 32];
    if (v->kind != N_SEQ || v->n != (size_t)n) {
        if (v->kind == N_SEQ)
            snprintf(got, sizeof got, "%zu element%s", v->n, v->n == 1 ? "" : "s");
        else
            describe(got, sizeof got, v);
        return key_error(c, RY_ERR_INPUT, f.at, path, -1, err,
                         "expected a sequence of %d number%s, got %s", n, n == 1 ? "" : "s", got);
    }
    for (int i = 0; i < n; i++) v->items[i]->used = 1;
    for (int i = 0; i < n; i++) {
        node *e = v->items[i];
        double x;
        if (!parse_number(e, &x)) {
            describe(got, sizeof got, e);
            char where[RY_ERROR_MSG_MAX];
            where_str(c, node_loc(e), where, sizeof where);
            return ry_error_set(err, RY_ERR_INPUT, "%s: key '%s[%d]': expected a number, got %s",
                                where, path, i, got);
        }
        out[i] = x;
    }
    return RY_OK;
}

ry_status ry_case_count(ry_case *c, const char *path, size_t *n, ry_error *err) {
    found f;
    RY_TRY(fetch(c, path, &f, err));
    if (!f.val) {
        *n = 0;
        return RY_OK;
    }
    if (f.val->kind != N_SEQ) {
        char got[CASE_SHOW_MAX + 32];
        describe(got, sizeof got, f.val);
        return key_error(c, RY_ERR_INPUT, f.at, path, -1, err, "expected a sequence, got %s", got);
    }
    f.val->used = 1;
    *n = f.val->n;
    return RY_OK;
}

/* ---------------------------------------------------------------- unused keys */

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
            if (path->n) sb_str(path, ".");
            sb_str(path, pr->key);
            if (!pr->val->live) {
                *hit = (unused_hit){n, pr, NULL};
                return 1;
            }
            if (find_unused(pr->val, path, hit)) return 1;
        } else {
            const node *e = n->items[i];
            sb_printf(path, "[%zu]", i);
            if (!e->live) {
                if (e->kind == N_MAP && e->n > 0) {
                    sb_str(path, ".");
                    sb_str(path, e->pairs[0].key);
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
                   : node_loc(hit.elem);
    char where[RY_ERROR_MSG_MAX];
    where_str(c, l, where, sizeof where);
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

/* ---------------------------------------------------------------- resolved output */

static int plain_safe(const char *s, size_t n) {
    if (n == 0 || s[n - 1] == ' ') return 0;
    unsigned char c0 = (unsigned char)s[0];
    int first_ok = (c0 >= '0' && c0 <= '9') || (c0 >= 'a' && c0 <= 'z') ||
                   (c0 >= 'A' && c0 <= 'Z') || c0 == '_' || c0 == '.' || c0 == '/' || c0 == '(';
    if ((c0 == '-' || c0 == '+') && n > 1 && s[1] != ' ') first_ok = 1;
    if (!first_ok) return 0;
    for (size_t i = 0; i < n; i++) {
        unsigned char ch = (unsigned char)s[i];
        int ok = (ch >= '0' && ch <= '9') || (ch >= 'a' && ch <= 'z') || (ch >= 'A' && ch <= 'Z') ||
                 ch == '_' || ch == '.' || ch == '/' || ch == '+' || ch == '-' || ch == '(' ||
                 ch == ')' || (ch == ' ' && s[i - 1] != ' ');
        if (!ok) return 0;
    }
    return 1;
}

static void emit_text(sbuf *b, const char *s, size_t n, int may_be_plain) {
    if (may_be_plain && plain_safe(s, n)) {
        sb_add(b, s, n);
        return;
    }
    sb_str(b, "\"");
    for (size_t i = 0; i < n; i++) {
        unsigned char ch = (unsigned char)s[i];
        if (ch == '"' || ch == '\\') {
            char esc[2] = {'\\', (char)ch};
            sb_add(b, esc, 2);
        } else if (ch == '\n') {
            sb_str(b, "\\n");
        } else if (ch == '\t') {
            sb_str(b, "\\t");
        } else if (ch < 0x20 || ch == 0x7f) {
            sb_printf(b, "\\x%02x", ch);
        } else {
            sb_add(b, s + i, 1);
        }
    }
    sb_str(b, "\"");
}

/* Quoted scalars that hold a plain-safe text are written plain unless they would then read as
 * something else than a string (numbers, booleans). */
static void emit_scalar(sbuf *b, const node *n) {
    int plain = !n->quoted;
    if (n->quoted) {
        double x;
        node probe = *n;
        probe.quoted = 0;
        plain = !parse_number(&probe, &x) && strcmp(n->text, "true") != 0 &&
                strcmp(n->text, "false") != 0;
    }
    emit_text(b, n->text, n->len, plain);
}

static int flow_seq_ok(const node *n) {
    for (size_t i = 0; i < n->n; i++)
        if (n->items[i]->kind != N_SCALAR || is_empty_value(n->items[i])) return 0;
    return 1;
}

static void indent(sbuf *b, int k) {
    for (int i = 0; i < k; i++) sb_str(b, " ");
}

static void emit_block(sbuf *b, const node *n, int ind, int inline_first);

/* Writes a value after "key:" or "-". */
static void emit_value(sbuf *b, const node *v, int ind, int after_dash) {
    if (v->kind == N_SCALAR) {
        if (!is_empty_value(v)) {
            sb_str(b, " ");
            emit_scalar(b, v);
        }
        sb_str(b, "\n");
    } else if (v->n == 0) {
        sb_str(b, v->kind == N_MAP ? " {}\n" : " []\n");
    } else if (v->kind == N_SEQ && flow_seq_ok(v)) {
        sb_str(b, " [");
        for (size_t i = 0; i < v->n; i++) {
            if (i) sb_str(b, ", ");
            emit_scalar(b, v->items[i]);
        }
        sb_str(b, "]\n");
    } else if (after_dash) {
        sb_str(b, " ");
        emit_block(b, v, ind + 2, 1);
    } else {
        sb_str(b, "\n");
        emit_block(b, v, ind + 2, 0);
    }
}

static void emit_block(sbuf *b, const node *n, int ind, int inline_first) {
    for (size_t i = 0; i < n->n; i++) {
        if (i || !inline_first) indent(b, ind);
        if (n->kind == N_MAP) {
            emit_text(b, n->pairs[i].key, strlen(n->pairs[i].key), 1);
            sb_str(b, ":");
            emit_value(b, n->pairs[i].val, ind, 0);
        } else {
            sb_str(b, "-");
            emit_value(b, n->items[i], ind, 1);
        }
    }
}

ry_status ry_case_write_resolved(ry_case *c, const char *path, ry_error *err) {
    sbuf b = {0};
    sb_str(&b, "# resolved parameters of ");
    emit_text(&b, c->name, strlen(c->name), 0);
    sb_str(&b, "\n");
    if (c->root->n == 0)
        sb_str(&b, "{}\n");
    else
        emit_block(&b, c->root, 0, 0);
    if (b.failed) {
        free(b.s);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory writing '%s'", path);
    }
    ry_status st = ry_atomic_write(path, b.s, b.n, err);
    free(b.s);
    return st;
}
