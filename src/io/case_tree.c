/* Case files: the node tree, the string buffer and the location of messages, shared by the
 * other parts of the case reader (see case_internal.h), and the freeing of a case. */
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/case_internal.h"

/* ---------------------------------------------------------------- small helpers */

char *ryc_dup_mem(const char *s, size_t n) {
    char *d = malloc(n + 1);
    if (!d) return NULL;
    if (n) memcpy(d, s, n);
    d[n] = '\0';
    return d;
}

void *ryc_grow(void *p, size_t *cap, size_t need, size_t elem) {
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

void ryc_sb_add(sbuf *b, const char *s, size_t n) {
    if (b->failed) return;
    char *q = ryc_grow(b->s, &b->cap, b->n + n + 1, 1);
    if (!q) {
        b->failed = 1;
        return;
    }
    b->s = q;
    memcpy(b->s + b->n, s, n);
    b->n += n;
    b->s[b->n] = '\0';
}

void ryc_sb_str(sbuf *b, const char *s) {
    ryc_sb_add(b, s, strlen(s));
}

void ryc_sb_printf(sbuf *b, const char *fmt, ...) {
    char tmp[64];
    va_list ap;
    va_start(ap, fmt);
    int k = vsnprintf(tmp, sizeof tmp, fmt, ap);
    va_end(ap);
    if (k < 0 || (size_t)k >= sizeof tmp) {
        b->failed = 1;
        return;
    }
    ryc_sb_add(b, tmp, (size_t)k);
}

/* ---------------------------------------------------------------- nodes */

node *ryc_node_new(node_kind kind, int line, const char *origin) {
    node *n = calloc(1, sizeof *n);
    if (!n) return NULL;
    n->kind = kind;
    n->line = line;
    n->origin = origin;
    return n;
}

node *ryc_scalar_new(const char *text, size_t len, int quoted, int line, const char *origin) {
    node *n = ryc_node_new(N_SCALAR, line, origin);
    if (!n) return NULL;
    n->text = ryc_dup_mem(text ? text : "", text ? len : 0);
    if (!n->text) {
        free(n);
        return NULL;
    }
    n->len = text ? len : 0;
    n->quoted = (unsigned char)(quoted != 0);
    return n;
}

void ryc_node_free(node *n) {
    if (!n) return;
    for (size_t i = 0; i < n->n; i++) {
        if (n->kind == N_MAP) {
            free(n->pairs[i].key);
            ryc_node_free(n->pairs[i].val);
        } else if (n->kind == N_SEQ) {
            ryc_node_free(n->items[i]);
        }
    }
    free(n->pairs);
    free(n->items);
    free(n->text);
    free(n);
}

/* Appends a pair; takes ownership of key and val only on success. */
int ryc_map_append(node *m, char *key, int key_line, node *val) {
    pair *p = ryc_grow(m->pairs, &m->cap, m->n + 1, sizeof *p);
    if (!p) return -1;
    m->pairs = p;
    m->pairs[m->n].key = key;
    m->pairs[m->n].key_line = key_line;
    m->pairs[m->n].val = val;
    m->n++;
    return 0;
}

int ryc_seq_append(node *s, node *val) {
    node **p = ryc_grow(s->items, &s->cap, s->n + 1, sizeof *p);
    if (!p) return -1;
    s->items = p;
    s->items[s->n++] = val;
    return 0;
}

pair *ryc_map_find(node *m, const char *key, size_t klen) {
    for (size_t i = 0; i < m->n; i++) {
        const char *k = m->pairs[i].key;
        if (strncmp(k, key, klen) == 0 && k[klen] == '\0') return &m->pairs[i];
    }
    return NULL;
}

int ryc_is_empty_value(const node *n) {
    return n->kind == N_SCALAR && !n->quoted && n->len == 0;
}

int ryc_valid_key(const char *k, size_t n) {
    if (n == 0 || memchr(k, '\0', n)) return 0;
    for (size_t i = 0; i < n; i++)
        if (k[i] == '.' || k[i] == '[' || k[i] == ']') return 0;
    return 1;
}

/* A short printable rendering of a scalar for messages. */
void ryc_show_text(char *buf, size_t size, const char *s, size_t n) {
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

void ryc_describe(char *buf, size_t size, const node *n) {
    char t[CASE_SHOW_MAX + 8];
    if (n->kind == N_MAP) {
        snprintf(buf, size, "a mapping");
    } else if (n->kind == N_SEQ) {
        snprintf(buf, size, "a sequence");
    } else if (ryc_is_empty_value(n)) {
        snprintf(buf, size, "an empty value");
    } else {
        ryc_show_text(t, sizeof t, n->text, n->len);
        snprintf(buf, size, n->quoted ? "the quoted string '%s'" : "'%s'", t);
    }
}

/* ---------------------------------------------------------------- locations and errors */

loc ryc_node_loc(const node *n) {
    loc l = {n->origin, n->origin ? 0 : n->line};
    return l;
}

void ryc_where_str(const ry_case *c, loc l, char *buf, size_t size) {
    if (l.origin)
        snprintf(buf, size, "%s", l.origin);
    else if (l.line > 0)
        snprintf(buf, size, "%s:%d", c->name, l.line);
    else
        snprintf(buf, size, "%s", c->name);
}

ry_status ryc_key_error(const ry_case *c, ry_status code, loc l, const char *path, int plen,
                        ry_error *err, const char *fmt, ...) {
    char where[RY_ERROR_MSG_MAX], what[RY_ERROR_MSG_MAX];
    ryc_where_str(c, l, where, sizeof where);
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(what, sizeof what, fmt, ap);
    va_end(ap);
    if (plen < 0) plen = (int)strlen(path);
    return ry_error_set(err, code, "%s: key '%.*s': %s", where, plen, path, what);
}

/* ---------------------------------------------------------------- the case */

void ryc_bury(ry_case *c, node *n) {
    size_t cap = c->n_graveyard; /* grown one at a time; replacements are rare */
    node **g = realloc(c->graveyard, (cap + 1) * sizeof *g);
    if (!g) {
        ryc_node_free(n); /* nothing handed out can be kept valid then; rare enough */
        return;
    }
    c->graveyard = g;
    c->graveyard[c->n_graveyard++] = n;
}

void ry_case_free(ry_case *c) {
    if (!c) return;
    ryc_node_free(c->root);
    for (size_t i = 0; i < c->n_graveyard; i++) ryc_node_free(c->graveyard[i]);
    free(c->graveyard);
    for (size_t i = 0; i < c->n_origins; i++) free(c->origins[i]);
    free(c->origins);
    free(c->name);
    free(c);
}

const char *ry_case_name(const ry_case *c) {
    return c->name;
}
