/* Validation manifests (include/ryushi/manifest.h), read with the case-file reader. */
#include "ryushi/manifest.h"

#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

ry_status ry_manifest_load(ry_manifest *m, const char *root, const char *name, ry_error *err) {
    memset(m, 0, sizeof *m);
    snprintf(m->path, sizeof m->path, "%s/validation/%s.yaml", root, name);
    RY_TRY(ry_case_load(&m->doc, m->path, err));
    const int no = 0;
    const long last = 1000;
    ry_status st = ry_case_string(m->doc, "name", NULL, &m->name, err);
    if (st == RY_OK && strcmp(m->name, name) != 0)
        st = ry_error_set(err, RY_ERR_INPUT, "%s: key 'name': '%s', the file is named '%s'",
                          m->path, m->name, name);
    if (st == RY_OK) st = ry_case_string(m->doc, "summary", NULL, &m->summary, err);
    if (st == RY_OK) st = ry_case_bool(m->doc, "in_all", &no, &m->in_all, err);
    if (st == RY_OK) st = ry_case_int(m->doc, "order", &last, 1, 1000, &m->order, err);
    if (st != RY_OK) ry_manifest_free(m);
    return st;
}

void ry_manifest_free(ry_manifest *m) {
    ry_case_free(m->doc);
    m->doc = NULL;
}

ry_status ry_manifest_tol(ry_manifest *m, const char *key, double *value, ry_error *err) {
    char path[256];
    snprintf(path, sizeof path, "tolerances.%s", key);
    RY_CHECK(err, ry_case_has(m->doc, path), RY_ERR_INPUT, "%s: no tolerance '%s'", m->path, key);
    return ry_case_double(m->doc, path, NULL, -INFINITY, INFINITY, value, err);
}

const char *ry_manifest_text(ry_manifest *m, const char *key, const char *def) {
    const char *s = def;
    ry_error e;
    if (ry_case_has(m->doc, key) && ry_case_string(m->doc, key, def, &s, &e) != RY_OK) s = def;
    return s;
}

const char *ry_manifest_item(ry_manifest *m, const char *key, int i) {
    size_t n = 0;
    ry_error e;
    if (!ry_case_has(m->doc, key) || i < 0) return NULL;
    if (ry_case_count(m->doc, key, &n, &e) != RY_OK)
        return i == 0 ? ry_manifest_text(m, key, NULL) : NULL;
    if ((size_t)i >= n) return NULL;
    char path[256];
    snprintf(path, sizeof path, "%s[%d]", key, i);
    return ry_manifest_text(m, path, NULL);
}

static int by_order(const void *a, const void *b) {
    const ry_manifest *x = a, *y = b;
    return x->order != y->order ? (x->order < y->order ? -1 : 1) : strcmp(x->name, y->name);
}

ry_status ry_manifest_all(const char *root, ry_manifest **all, int *n, ry_error *err) {
    *all = NULL;
    *n = 0;
    char dir[4200];
    snprintf(dir, sizeof dir, "%s/validation", root);
    DIR *d = opendir(dir);
    RY_CHECK(err, d != NULL, RY_ERR_IO, "%s: cannot open the folder of validations", dir);
    ry_status st = RY_OK;
    int cap = 0;
    struct dirent *e;
    while (st == RY_OK && (e = readdir(d)) != NULL) {
        const size_t len = strlen(e->d_name);
        if (len < 6 || strcmp(e->d_name + len - 5, ".yaml") != 0) continue;
        char name[256];
        snprintf(name, sizeof name, "%.*s", (int)(len - 5), e->d_name);
        if (*n == cap) {
            cap = cap ? 2 * cap : 32;
            ry_manifest *p = realloc(*all, (size_t)cap * sizeof *p);
            if (!p) {
                st = ry_error_set(err, RY_ERR_NOMEM, "out of memory");
                break;
            }
            *all = p;
        }
        st = ry_manifest_load(&(*all)[*n], root, name, err);
        if (st == RY_OK) ++*n;
    }
    closedir(d);
    if (st != RY_OK) {
        for (int k = 0; k < *n; ++k) ry_manifest_free(&(*all)[k]);
        free(*all);
        *all = NULL;
        *n = 0;
        return st;
    }
    qsort(*all, (size_t)*n, sizeof **all, by_order);
    return RY_OK;
}
