/* Case files: writing the resolved parameters (the values given and the defaults used) as
 * YAML. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/case_internal.h"
#include "ryushi/atomic_file.h"

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
        ryc_sb_add(b, s, n);
        return;
    }
    ryc_sb_str(b, "\"");
    for (size_t i = 0; i < n; i++) {
        unsigned char ch = (unsigned char)s[i];
        if (ch == '"' || ch == '\\') {
            char esc[2] = {'\\', (char)ch};
            ryc_sb_add(b, esc, 2);
        } else if (ch == '\n') {
            ryc_sb_str(b, "\\n");
        } else if (ch == '\t') {
            ryc_sb_str(b, "\\t");
        } else if (ch < 0x20 || ch == 0x7f) {
            ryc_sb_printf(b, "\\x%02x", ch);
        } else {
            ryc_sb_add(b, s + i, 1);
        }
    }
    ryc_sb_str(b, "\"");
}

/* Quoted scalars that hold a plain-safe text are written plain unless they would then read as
 * something else than a string (numbers, booleans). */
static void emit_scalar(sbuf *b, const node *n) {
    int plain = !n->quoted;
    if (n->quoted) {
        double x;
        node probe = *n;
        probe.quoted = 0;
        plain = !ryc_parse_number(&probe, &x) && strcmp(n->text, "true") != 0 &&
                strcmp(n->text, "false") != 0;
    }
    emit_text(b, n->text, n->len, plain);
}

static int flow_seq_ok(const node *n) {
    for (size_t i = 0; i < n->n; i++)
        if (n->items[i]->kind != N_SCALAR || ryc_is_empty_value(n->items[i])) return 0;
    return 1;
}

static void indent(sbuf *b, int k) {
    for (int i = 0; i < k; i++) ryc_sb_str(b, " ");
}

static void emit_block(sbuf *b, const node *n, int ind, int inline_first);

/* Writes a value after "key:" or "-". */
static void emit_value(sbuf *b, const node *v, int ind, int after_dash) {
    if (v->kind == N_SCALAR) {
        if (!ryc_is_empty_value(v)) {
            ryc_sb_str(b, " ");
            emit_scalar(b, v);
        }
        ryc_sb_str(b, "\n");
    } else if (v->n == 0) {
        ryc_sb_str(b, v->kind == N_MAP ? " {}\n" : " []\n");
    } else if (v->kind == N_SEQ && flow_seq_ok(v)) {
        ryc_sb_str(b, " [");
        for (size_t i = 0; i < v->n; i++) {
            if (i) ryc_sb_str(b, ", ");
            emit_scalar(b, v->items[i]);
        }
        ryc_sb_str(b, "]\n");
    } else if (after_dash) {
        ryc_sb_str(b, " ");
        emit_block(b, v, ind + 2, 1);
    } else {
        ryc_sb_str(b, "\n");
        emit_block(b, v, ind + 2, 0);
    }
}

static void emit_block(sbuf *b, const node *n, int ind, int inline_first) {
    for (size_t i = 0; i < n->n; i++) {
        if (i || !inline_first) indent(b, ind);
        if (n->kind == N_MAP) {
            emit_text(b, n->pairs[i].key, strlen(n->pairs[i].key), 1);
            ryc_sb_str(b, ":");
            emit_value(b, n->pairs[i].val, ind, 0);
        } else {
            ryc_sb_str(b, "-");
            emit_value(b, n->items[i], ind, 1);
        }
    }
}

ry_status ry_case_write_resolved(ry_case *c, const char *path, ry_error *err) {
    sbuf b = {0};
    ryc_sb_str(&b, "# resolved parameters of ");
    emit_text(&b, c->name, strlen(c->name), 0);
    ryc_sb_str(&b, "\n");
    if (c->root->n == 0)
        ryc_sb_str(&b, "{}\n");
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
