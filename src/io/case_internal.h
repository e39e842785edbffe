/* Internal to the case reader (include/ryushi/case.h), shared by its parts:
 *   case_tree.c    the node tree, the string buffer, locations and key errors, freeing a case;
 *   case_read.c    building the tree from libfyaml events, loading a case;
 *   case_path.c    key paths, lookups and the recording of defaults;
 *   case_get.c     the queries and the typed getters;
 *   case_set.c     --set overrides;
 *   case_unused.c  the check for unused keys;
 *   case_write.c   the resolved output.
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
#ifndef RYUSHI_CASE_INTERNAL_H
#define RYUSHI_CASE_INTERNAL_H

#include <stddef.h>

#include "ryushi/case.h"

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

typedef struct sbuf {
    char *s;
    size_t n, cap;
    int failed;
} sbuf;

typedef struct loc {
    const char *origin; /* "--set ..." or NULL */
    int line;           /* 0: the file alone */
} loc;

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

typedef struct found {
    node *val; /* NULL when absent */
    loc at;    /* of the value, or of the deepest existing parent when absent */
} found;

/* case_tree.c: small helpers and the string buffer */
char *ryc_dup_mem(const char *s, size_t n);
void *ryc_grow(void *p, size_t *cap, size_t need, size_t elem);
void ryc_sb_add(sbuf *b, const char *s, size_t n);
void ryc_sb_str(sbuf *b, const char *s);
void ryc_sb_printf(sbuf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* case_tree.c: nodes */
node *ryc_node_new(node_kind kind, int line, const char *origin);
node *ryc_scalar_new(const char *text, size_t len, int quoted, int line, const char *origin);
void ryc_node_free(node *n);
int ryc_map_append(node *m, char *key, int key_line, node *val);
int ryc_seq_append(node *s, node *val);
pair *ryc_map_find(node *m, const char *key, size_t klen);
int ryc_is_empty_value(const node *n);
int ryc_valid_key(const char *k, size_t n);
void ryc_show_text(char *buf, size_t size, const char *s, size_t n);
void ryc_describe(char *buf, size_t size, const node *n);

/* case_tree.c: locations and errors, the case */
loc ryc_node_loc(const node *n);
void ryc_where_str(const ry_case *c, loc l, char *buf, size_t size);
ry_status ryc_key_error(const ry_case *c, ry_status code, loc l, const char *path, int plen,
                        ry_error *err, const char *fmt, ...) __attribute__((format(printf, 7, 8)));
void ryc_bury(ry_case *c, node *n);

/* case_read.c */
ry_status ryc_build_tree(const char *name, const char *origin, const char *text, size_t len,
                         node **out, ry_error *err);

/* case_path.c */
int ryc_parse_path(const char *s, size_t len, cpath *out);
ry_status ryc_fetch(const ry_case *c, const char *path, found *f, ry_error *err);
ry_status ryc_record_default(ry_case *c, const char *path, node *val, ry_error *err);

/* case_get.c */
int ryc_parse_number(const node *n, double *out);

#endif
