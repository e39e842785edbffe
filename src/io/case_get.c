/* Case files: the queries (has, touch, where) and the typed getters, which check types and
 * ranges and record the defaults they fall back on. */
#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io/case_internal.h"

/* ---------------------------------------------------------------- queries */

static void mark_all(node *n) {
    n->used = 1;
    for (size_t i = 0; i < n->n; i++) mark_all(n->kind == N_MAP ? n->pairs[i].val : n->items[i]);
}

int ry_case_has(const ry_case *c, const char *path) {
    found f;
    if (ryc_fetch(c, path, &f, NULL) != RY_OK) return 0;
    return f.val != NULL;
}

void ry_case_touch(ry_case *c, const char *path) {
    found f;
    if (ryc_fetch(c, path, &f, NULL) == RY_OK && f.val) mark_all(f.val);
}

const char *ry_case_where(ry_case *c, const char *path, char *buf, size_t size) {
    if (!buf || size == 0) return "";
    found f;
    loc l = {NULL, 0};
    if (ryc_fetch(c, path, &f, NULL) == RY_OK && f.val) l = f.at;
    ryc_where_str(c, l, buf, size);
    return buf;
}

/* ---------------------------------------------------------------- getters */

static ry_status missing(const ry_case *c, const char *path, const found *f, ry_error *err) {
    return ryc_key_error(c, RY_ERR_INPUT, f->at, path, -1, err, "required key is missing");
}

/* Parses a plain scalar entirely as a finite number. */
int ryc_parse_number(const node *n, double *out) {
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
    return ryc_scalar_new(t, strlen(t), 0, 0, NULL);
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
    RY_TRY(ryc_fetch(c, path, &f, err));
    char want[160], got[CASE_SHOW_MAX + 32];
    range_text(want, sizeof want, what, lo, hi);
    if (!f.val) {
        if (!def) return missing(c, path, &f, err);
        if (!(*def >= lo && *def <= hi))
            return ry_error_set(err, RY_ERR_INTERNAL, "default of key '%s' is not %s", path, want);
        node *d = number_node(*def);
        if (!d) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        RY_TRY(ryc_record_default(c, path, d, err));
        *out = *def;
        return RY_OK;
    }
    f.val->used = 1;
    double x;
    ryc_describe(got, sizeof got, f.val);
    if (!ryc_parse_number(f.val, &x))
        return ryc_key_error(c, RY_ERR_INPUT, f.at, path, -1, err, "expected %s, got %s", want,
                             got);
    if (!(x >= lo && x <= hi))
        return ryc_key_error(c, RY_ERR_RANGE, f.at, path, -1, err, "expected %s, got %s", want,
                             got);
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
    RY_TRY(ryc_fetch(c, path, &f, err));
    if (!f.val) {
        if (!def) return missing(c, path, &f, err);
        if (!(*def > 0))
            return ry_error_set(err, RY_ERR_INTERNAL, "default of key '%s' is not positive", path);
        node *d = number_node(*def);
        if (!d) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        RY_TRY(ryc_record_default(c, path, d, err));
        *out = *def;
        return RY_OK;
    }
    f.val->used = 1;
    double x;
    char got[CASE_SHOW_MAX + 32];
    ryc_describe(got, sizeof got, f.val);
    if (!ryc_parse_number(f.val, &x))
        return ryc_key_error(c, RY_ERR_INPUT, f.at, path, -1, err,
                             "expected a positive number, got %s", got);
    if (!(x > 0))
        return ryc_key_error(c, RY_ERR_RANGE, f.at, path, -1, err,
                             "expected a positive number, got %s", got);
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
    RY_TRY(ryc_fetch(c, path, &f, err));
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
        node *d = ryc_scalar_new(t, strlen(t), 0, 0, NULL);
        if (!d) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        RY_TRY(ryc_record_default(c, path, d, err));
        *out = *def;
        return RY_OK;
    }
    f.val->used = 1;
    long v = 0;
    ryc_describe(got, sizeof got, f.val);
    int rc = parse_long(f.val, &v);
    if (rc == 0)
        return ryc_key_error(c, RY_ERR_INPUT, f.at, path, -1, err, "expected %s, got %s", want,
                             got);
    if (rc < 0 || v < lo || v > hi)
        return ryc_key_error(c, RY_ERR_RANGE, f.at, path, -1, err, "expected %s, got %s", want,
                             got);
    *out = v;
    return RY_OK;
}

ry_status ry_case_bool(ry_case *c, const char *path, const int *def, int *out, ry_error *err) {
    found f;
    RY_TRY(ryc_fetch(c, path, &f, err));
    if (!f.val) {
        if (!def) return missing(c, path, &f, err);
        const char *t = *def ? "true" : "false";
        node *d = ryc_scalar_new(t, strlen(t), 0, 0, NULL);
        if (!d) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        RY_TRY(ryc_record_default(c, path, d, err));
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
    ryc_describe(got, sizeof got, v);
    return ryc_key_error(c, RY_ERR_INPUT, f.at, path, -1, err, "expected true or false, got %s",
                         got);
}

ry_status ry_case_string(ry_case *c, const char *path, const char *def, const char **out,
                         ry_error *err) {
    found f;
    RY_TRY(ryc_fetch(c, path, &f, err));
    if (!f.val) {
        if (!def) return missing(c, path, &f, err);
        node *d = ryc_scalar_new(def, strlen(def), 1, 0, NULL);
        if (!d) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        RY_TRY(ryc_record_default(c, path, d, err));
        *out = def;
        return RY_OK;
    }
    f.val->used = 1;
    if (f.val->kind != N_SCALAR || ryc_is_empty_value(f.val)) {
        char got[CASE_SHOW_MAX + 32];
        ryc_describe(got, sizeof got, f.val);
        return ryc_key_error(c, RY_ERR_INPUT, f.at, path, -1, err, "expected a string, got %s",
                             got);
    }
    *out = f.val->text;
    return RY_OK;
}

ry_status ry_case_choice(ry_case *c, const char *path, const char *def, const char *const *names,
                         int *out, ry_error *err) {
    found f;
    RY_TRY(ryc_fetch(c, path, &f, err));
    const char *text;
    if (!f.val) {
        if (!def) return missing(c, path, &f, err);
        text = def;
    } else {
        f.val->used = 1;
        text = f.val->kind == N_SCALAR && !ryc_is_empty_value(f.val) ? f.val->text : NULL;
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
            if (i) ryc_sb_str(&list, ", ");
            ryc_sb_str(&list, names[i]);
        }
        char got[CASE_SHOW_MAX + 32];
        if (f.val)
            ryc_describe(got, sizeof got, f.val);
        else
            snprintf(got, sizeof got, "'%s'", def);
        ry_status st;
        if (list.failed)
            st = ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        else if (!f.val)
            st = ry_error_set(err, RY_ERR_INTERNAL, "default %s of key '%s' is not one of %s", got,
                              path, list.s ? list.s : "");
        else
            st = ryc_key_error(c, RY_ERR_INPUT, f.at, path, -1, err, "expected one of %s; got %s",
                               list.s ? list.s : "", got);
        free(list.s);
        return st;
    }
    if (!f.val) {
        node *d = ryc_scalar_new(def, strlen(def), 1, 0, NULL);
        if (!d) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        RY_TRY(ryc_record_default(c, path, d, err));
    }
    *out = idx;
    return RY_OK;
}

ry_status ry_case_vector(ry_case *c, const char *path, const double *def, int n, double *out,
                         ry_error *err) {
    found f;
    RY_TRY(ryc_fetch(c, path, &f, err));
    if (!f.val) {
        if (!def) return missing(c, path, &f, err);
        node *s = ryc_node_new(N_SEQ, 0, NULL);
        if (!s) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
        for (int i = 0; i < n; i++) {
            node *d = number_node(def[i]);
            if (!d || ryc_seq_append(s, d)) {
                ryc_node_free(d);
                ryc_node_free(s);
                return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
            }
        }
        RY_TRY(ryc_record_default(c, path, s, err));
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
            ryc_describe(got, sizeof got, v);
        return ryc_key_error(c, RY_ERR_INPUT, f.at, path, -1, err,
                             "expected a sequence of %d number%s, got %s", n, n == 1 ? "" : "s",
                             got);
    }
    for (int i = 0; i < n; i++) v->items[i]->used = 1;
    for (int i = 0; i < n; i++) {
        node *e = v->items[i];
        double x;
        if (!ryc_parse_number(e, &x)) {
            ryc_describe(got, sizeof got, e);
            char where[RY_ERROR_MSG_MAX];
            ryc_where_str(c, ryc_node_loc(e), where, sizeof where);
            return ry_error_set(err, RY_ERR_INPUT, "%s: key '%s[%d]': expected a number, got %s",
                                where, path, i, got);
        }
        out[i] = x;
    }
    return RY_OK;
}

ry_status ry_case_count(ry_case *c, const char *path, size_t *n, ry_error *err) {
    found f;
    RY_TRY(ryc_fetch(c, path, &f, err));
    if (!f.val) {
        *n = 0;
        return RY_OK;
    }
    if (f.val->kind != N_SEQ) {
        char got[CASE_SHOW_MAX + 32];
        ryc_describe(got, sizeof got, f.val);
        return ryc_key_error(c, RY_ERR_INPUT, f.at, path, -1, err, "expected a sequence, got %s",
                             got);
    }
    f.val->used = 1;
    *n = f.val->n;
    return RY_OK;
}
