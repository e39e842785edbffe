/* Case files: building the tree from libfyaml's events (duplicate keys, libfyaml's
 * diagnostics turned into messages), and loading a case from a file or a string. */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <libfyaml.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/case_internal.h"

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
            if (out->n) ryc_sb_str(out, ".");
            ryc_sb_str(out, parent->pairs[parent->n - 1].key);
        } else {
            ryc_sb_printf(out, "[%zu]", parent->n - 1);
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
    if (path.n) ryc_sb_str(&path, ".");
    ryc_sb_str(&path, m->pairs[best].key);
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
            ryc_node_free(n);
            return build_error(b, line, "only one YAML document is allowed");
        }
        b->root = n;
        return RY_OK;
    }
    frame *f = &b->stack[b->depth];
    if (n->line == 0 && !b->origin)
        n->line = f->n->kind == N_MAP && f->key ? f->key_line : f->n->line;
    if (f->n->kind == N_SEQ) {
        if (ryc_seq_append(f->n, n)) {
            ryc_node_free(n);
            return ry_error_set(b->err, RY_ERR_NOMEM, "out of memory reading '%s'", b->name);
        }
        return RY_OK;
    }
    if (!f->key) { /* n is a key */
        int line = n->line;
        if (n->kind != N_SCALAR) {
            ryc_node_free(n);
            return build_error(b, line, "a key must be a plain name, not a mapping or sequence");
        }
        if (!ryc_valid_key(n->text, n->len)) {
            char t[CASE_SHOW_MAX + 8];
            ryc_show_text(t, sizeof t, n->text, n->len);
            ryc_node_free(n);
            return build_error(b, line,
                               "invalid key '%s' (keys must be non-empty and must not "
                               "contain '.', '[' or ']')",
                               t);
        }
        f->key = n->text;
        f->key_line = line;
        n->text = NULL;
        ryc_node_free(n);
        return RY_OK;
    }
    if (ryc_map_append(f->n, f->key, f->key_line, n)) {
        ryc_node_free(n);
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
        node *n = ryc_scalar_new(t, len, quoted, line, b->origin);
        if (!n) return ry_error_set(b->err, RY_ERR_NOMEM, "out of memory reading '%s'", b->name);
        return attach(b, n);
    }
    if (e->type == FYET_MAPPING_START || e->type == FYET_SEQUENCE_START) {
        if (b->depth + 1 >= CASE_MAX_DEPTH)
            return build_error(b, line, "nesting deeper than %d levels", CASE_MAX_DEPTH);
        node *n = ryc_node_new(e->type == FYET_MAPPING_START ? N_MAP : N_SEQ, line, b->origin);
        if (!n) return ry_error_set(b->err, RY_ERR_NOMEM, "out of memory reading '%s'", b->name);
        if (b->depth >= 0 && b->stack[b->depth].n->kind == N_MAP && !b->stack[b->depth].key) {
            ryc_node_free(n);
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
ry_status ryc_build_tree(const char *name, const char *origin, const char *text, size_t len,
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
        ryc_node_free(b->root);
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
    c->name = ryc_dup_mem(name, strlen(name));
    if (!c->name) {
        free(c);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory reading '%s'", name);
    }
    ry_status st = ryc_build_tree(c->name, NULL, text, len, &c->root, err);
    if (st != RY_OK) {
        ry_case_free(c);
        return st;
    }
    if (!c->root || ryc_is_empty_value(c->root)) {
        ryc_node_free(c->root);
        c->root = ryc_node_new(N_MAP, 0, NULL);
        if (!c->root) {
            ry_case_free(c);
            return ry_error_set(err, RY_ERR_NOMEM, "out of memory reading '%s'", name);
        }
    }
    if (c->root->kind != N_MAP) {
        char got[CASE_SHOW_MAX + 32];
        ryc_describe(got, sizeof got, c->root);
        loc l = {NULL, c->root->line};
        char where[RY_ERROR_MSG_MAX];
        ryc_where_str(c, l, where, sizeof where);
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
        char *q = ryc_grow(buf, &cap, n + 65536, 1);
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
