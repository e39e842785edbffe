/* Numeric CSV reader (see include/ryushi/csv.h). */
#define _POSIX_C_SOURCE 200809L
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/csv.h"

static void strip(char *s) {
    size_t n = strlen(s);
    while (n && (s[n - 1] == '\n' || s[n - 1] == '\r' || s[n - 1] == ' ')) s[--n] = '\0';
}

void ry_table_free(ry_table *t) {
    for (int c = 0; c < t->ncols; ++c) free(t->names[c]);
    free(t->names);
    free(t->data);
    memset(t, 0, sizeof *t);
}

ry_status ry_table_read(ry_table *t, const char *path, ry_error *err) {
    memset(t, 0, sizeof *t);
    FILE *fp = fopen(path, "r");
    if (!fp) return ry_error_set(err, RY_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
    char *line = NULL;
    size_t cap = 0, rows_cap = 0;
    ry_status st = RY_OK;
    long lineno = 0;
    while (getline(&line, &cap, fp) >= 0) {
        ++lineno;
        strip(line);
        if (line[0] == '\0') continue;
        if (!t->names) {
            int n = 1;
            for (char *s = line; *s; ++s) n += *s == ',';
            t->names = calloc((size_t)n, sizeof *t->names);
            if (!t->names) {
                st = ry_error_set(err, RY_ERR_NOMEM, "out of memory");
                break;
            }
            char *save = NULL;
            for (char *tok = strtok_r(line, ",", &save); tok; tok = strtok_r(NULL, ",", &save))
                t->names[t->ncols++] = strdup(tok);
            continue;
        }
        if (t->nrows == rows_cap) {
            rows_cap = rows_cap ? 2 * rows_cap : 64;
            double *d = realloc(t->data, rows_cap * (size_t)t->ncols * sizeof *d);
            if (!d) {
                st = ry_error_set(err, RY_ERR_NOMEM, "out of memory");
                break;
            }
            t->data = d;
        }
        char *s = line;
        for (int c = 0; c < t->ncols && st == RY_OK; ++c) {
            /* an empty field is a value not recorded (a restart's earlier rows, in a column
             * that run did not measure): NAN */
            const int empty = *s == ',' || *s == '\0';
            char *end = s;
            const double v = empty ? NAN : strtod(s, &end);
            if ((end == s && !empty) || (*end != ',' && *end != '\0') ||
                (c + 1 < t->ncols && *end != ','))
                st = ry_error_set(err, RY_ERR_INPUT, "%s:%ld: column '%s': not a number", path,
                                  lineno, t->names[c]);
            t->data[t->nrows * (size_t)t->ncols + (size_t)c] = v;
            s = *end ? end + 1 : end;
        }
        if (st != RY_OK) break;
        t->nrows++;
    }
    free(line);
    fclose(fp);
    if (st == RY_OK && !t->names) st = ry_error_set(err, RY_ERR_INPUT, "%s: empty file", path);
    if (st != RY_OK) ry_table_free(t);
    return st;
}

int ry_table_col(const ry_table *t, const char *name) {
    for (int c = 0; c < t->ncols; ++c)
        if (strcmp(t->names[c], name) == 0) return c;
    return -1;
}

double *ry_table_column(const ry_table *t, int col) {
    double *v = malloc((t->nrows ? t->nrows : 1) * sizeof *v);
    if (!v) return NULL;
    for (size_t r = 0; r < t->nrows; ++r) v[r] = ry_table_at(t, r, col);
    return v;
}

double ry_interp_linear(const double *x, const double *y, size_t n, double xq) {
    if (n == 0 || xq < x[0] || xq > x[n - 1]) return NAN;
    size_t lo = 0, hi = n - 1;
    while (hi - lo > 1) {
        size_t mid = (lo + hi) / 2;
        if (x[mid] <= xq)
            lo = mid;
        else
            hi = mid;
    }
    if (x[hi] == x[lo]) return y[lo];
    double s = (xq - x[lo]) / (x[hi] - x[lo]);
    return y[lo] + s * (y[hi] - y[lo]);
}
