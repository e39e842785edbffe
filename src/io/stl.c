/* STL surfaces: reading, writing, validation (see include/ryushi/stl.h). */
#define _POSIX_C_SOURCE 200809L
#include "ryushi/stl.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "util/cell_key.h"
#include "ryushi/atomic_file.h"

enum { STL_HEADER = 80, STL_RECORD = 50, STL_TOKEN_SHOW = 40 };

void ry_stl_free(ry_stl *m) {
    if (!m) return;
    free(m->name);
    free(m->v);
    free(m->line);
    memset(m, 0, sizeof *m);
}

static void update_bounds(ry_stl *m) {
    for (int d = 0; d < 3; ++d) {
        m->lo[d] = INFINITY;
        m->hi[d] = -INFINITY;
    }
    for (size_t i = 0; i < 3 * m->ntri; ++i)
        for (int d = 0; d < 3; ++d) {
            m->lo[d] = fmin(m->lo[d], m->v[3 * i + d]);
            m->hi[d] = fmax(m->hi[d], m->v[3 * i + d]);
        }
}

static ry_status stl_begin(ry_stl *m, const char *name, size_t ntri, int with_lines,
                           ry_error *err) {
    memset(m, 0, sizeof *m);
    m->name = ry_strdup(name);
    m->v = malloc((ntri ? ntri : 1) * 9 * sizeof *m->v);
    if (with_lines) m->line = malloc((ntri ? ntri : 1) * sizeof *m->line);
    if (!m->name || !m->v || (with_lines && !m->line)) {
        ry_stl_free(m);
        return ry_error_set(err, RY_ERR_NOMEM, "%s: out of memory for %zu triangles", name, ntri);
    }
    return RY_OK;
}

ry_status ry_stl_from_triangles(ry_stl *m, const char *name, const double *v, size_t ntri,
                                ry_error *err) {
    RY_CHECK(err, ntri > 0 && ntri <= RY_STL_MAX_TRIANGLES, RY_ERR_INPUT,
             "%s: %zu triangles (1 to %d allowed)", name, ntri, (int)RY_STL_MAX_TRIANGLES);
    RY_TRY(stl_begin(m, name, ntri, 0, err));
    memcpy(m->v, v, ntri * 9 * sizeof *v);
    m->ntri = ntri;
    update_bounds(m);
    return RY_OK;
}

const char *ry_stl_where(const ry_stl *m, size_t t, char *buf, size_t size) {
    if (m->line)
        snprintf(buf, size, "%s:%d", m->name, m->line[t]);
    else if (m->binary)
        snprintf(buf, size, "%s: triangle %zu (byte %zu)", m->name, t,
                 (size_t)STL_HEADER + 4 + t * STL_RECORD);
    else
        snprintf(buf, size, "%s: triangle %zu", m->name, t);
    return buf;
}

/* ---------------------------------------------------------------- binary */

static uint32_t le32(const unsigned char *p) {
    return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 | (uint32_t)p[3] << 24;
}

static float le_float(const unsigned char *p) {
    uint32_t u = le32(p);
    float f;
    memcpy(&f, &u, sizeof f);
    return f;
}

static ry_status parse_binary(ry_stl *m, const char *name, const unsigned char *p, ry_error *err) {
    size_t n = le32(p + STL_HEADER);
    RY_CHECK(err, n > 0, RY_ERR_INPUT, "%s: binary STL with no triangle (count 0 at byte 80)",
             name);
    RY_CHECK(err, n <= RY_STL_MAX_TRIANGLES, RY_ERR_INPUT,
             "%s: binary STL: %zu triangles (byte 80), more than the limit %d", name, n,
             (int)RY_STL_MAX_TRIANGLES);
    RY_TRY(stl_begin(m, name, n, 0, err));
    m->binary = 1;
    for (size_t t = 0; t < n; ++t) {
        const unsigned char *r = p + STL_HEADER + 4 + t * STL_RECORD + 12; /* skip the normal */
        for (int k = 0; k < 9; ++k) {
            float f = le_float(r + 4 * k);
            if (!isfinite(f)) {
                size_t off = (size_t)(r - p) + 4 * (size_t)k;
                ry_stl_free(m);
                return ry_error_set(err, RY_ERR_INPUT,
                                    "%s: triangle %zu (byte %zu): vertex %d coordinate %c is not "
                                    "a finite number",
                                    name, t, off, k / 3 + 1, "xyz"[k % 3]);
            }
            m->v[9 * t + k] = f;
        }
    }
    m->ntri = n;
    return RY_OK;
}

/* ---------------------------------------------------------------- ASCII */

typedef struct lexer {
    const char *name;
    const char *p, *end;
    int line;
    const char *tok; /* current token */
    size_t len;
    int tok_line;
} lexer;

/* Advances to the next whitespace-separated token; len 0 at the end. */
static void next_token(lexer *lx) {
    while (lx->p < lx->end && (*lx->p == ' ' || *lx->p == '\t' || *lx->p == '\r' ||
                               *lx->p == '\n' || *lx->p == '\f' || *lx->p == '\v')) {
        if (*lx->p == '\n') lx->line++;
        lx->p++;
    }
    lx->tok = lx->p;
    lx->tok_line = lx->line;
    while (lx->p < lx->end && !(*lx->p == ' ' || *lx->p == '\t' || *lx->p == '\r' ||
                                *lx->p == '\n' || *lx->p == '\f' || *lx->p == '\v'))
        lx->p++;
    lx->len = (size_t)(lx->p - lx->tok);
}

/* Skips the rest of the current line (names after solid / endsolid). */
static void skip_line(lexer *lx) {
    while (lx->p < lx->end && *lx->p != '\n') lx->p++;
}

static int is(const lexer *lx, const char *word) {
    size_t n = strlen(word);
    return lx->len == n && memcmp(lx->tok, word, n) == 0;
}

static ry_status expected(const lexer *lx, const char *what, ry_error *err) {
    if (lx->len == 0)
        return ry_error_set(err, RY_ERR_INPUT, "%s:%d: expected %s, got the end of the file",
                            lx->name, lx->tok_line, what);
    char shown[STL_TOKEN_SHOW + 4];
    size_t n = lx->len < STL_TOKEN_SHOW ? lx->len : STL_TOKEN_SHOW;
    for (size_t i = 0; i < n; ++i) {
        unsigned char ch = (unsigned char)lx->tok[i];
        shown[i] = (ch < 0x20 || ch >= 0x7f) ? '?' : (char)ch;
    }
    if (lx->len > n) memcpy(shown + n, "...", 3), n += 3;
    shown[n] = '\0';
    return ry_error_set(err, RY_ERR_INPUT, "%s:%d: expected %s, got '%s'", lx->name, lx->tok_line,
                        what, shown);
}

static ry_status expect_word(lexer *lx, const char *word, ry_error *err) {
    next_token(lx);
    if (is(lx, word)) return RY_OK;
    char what[32];
    snprintf(what, sizeof what, "'%s'", word);
    return expected(lx, what, err);
}

static ry_status read_number(lexer *lx, const char *what, double *out, ry_error *err) {
    next_token(lx);
    char buf[64];
    if (lx->len == 0 || lx->len >= sizeof buf) return expected(lx, what, err);
    memcpy(buf, lx->tok, lx->len);
    buf[lx->len] = '\0';
    char *end;
    double x = strtod(buf, &end);
    if (*end != '\0' || end == buf) return expected(lx, what, err);
    if (!isfinite(x))
        return ry_error_set(err, RY_ERR_INPUT, "%s:%d: %s '%s' is not a finite number", lx->name,
                            lx->tok_line, what, buf);
    *out = x;
    return RY_OK;
}

static ry_status parse_facets(ry_stl *m, lexer *lx, size_t *cap, ry_error *err) {
    static const char *const coord[3] = {"a number (vertex x)", "a number (vertex y)",
                                         "a number (vertex z)"};
    for (;;) {
        next_token(lx);
        if (is(lx, "endsolid")) {
            skip_line(lx);
            return RY_OK;
        }
        if (!is(lx, "facet")) return expected(lx, "'facet' or 'endsolid'", err);
        int line = lx->tok_line;
        RY_TRY(expect_word(lx, "normal", err));
        double nrm;
        for (int k = 0; k < 3; ++k) RY_TRY(read_number(lx, "a number (normal)", &nrm, err));
        RY_TRY(expect_word(lx, "outer", err));
        RY_TRY(expect_word(lx, "loop", err));
        if (m->ntri == *cap) {
            RY_CHECK(err, m->ntri < RY_STL_MAX_TRIANGLES, RY_ERR_INPUT,
                     "%s:%d: more than %d triangles", lx->name, line, (int)RY_STL_MAX_TRIANGLES);
            size_t c = *cap * 2;
            double *v = realloc(m->v, c * 9 * sizeof *v);
            if (v) m->v = v;
            int *l = realloc(m->line, c * sizeof *l);
            if (l) m->line = l;
            RY_CHECK(err, v && l, RY_ERR_NOMEM, "%s:%d: out of memory", lx->name, line);
            *cap = c;
        }
        double *v = m->v + 9 * m->ntri;
        for (int k = 0; k < 3; ++k) {
            RY_TRY(expect_word(lx, "vertex", err));
            for (int d = 0; d < 3; ++d) RY_TRY(read_number(lx, coord[d], &v[3 * k + d], err));
        }
        next_token(lx);
        if (!is(lx, "endloop"))
            return expected(
                lx, is(lx, "vertex") ? "'endloop' (a facet has exactly 3 vertices)" : "'endloop'",
                err);
        RY_TRY(expect_word(lx, "endfacet", err));
        m->line[m->ntri++] = line;
    }
}

static ry_status parse_ascii(ry_stl *m, const char *name, const char *text, size_t size,
                             ry_error *err) {
    size_t cap = 64;
    RY_TRY(stl_begin(m, name, cap, 1, err));
    lexer lx = {name, text, text + size, 1, text, 0, 1};
    ry_status st = RY_OK;
    int solids = 0;
    for (;;) {
        next_token(&lx);
        if (lx.len == 0 && solids > 0) break;
        if (!is(&lx, "solid")) {
            st = expected(&lx, solids ? "'solid' or the end of the file" : "'solid'", err);
            break;
        }
        skip_line(&lx);
        ++solids;
        st = parse_facets(m, &lx, &cap, err);
        if (st != RY_OK) break;
    }
    if (st == RY_OK && m->ntri == 0)
        st = ry_error_set(err, RY_ERR_INPUT, "%s: ASCII STL with no facet", name);
    if (st != RY_OK) ry_stl_free(m);
    return st;
}

/* ---------------------------------------------------------------- detection */

static int starts_with_solid(const unsigned char *p, size_t size) {
    size_t i = 0;
    while (i < size && (p[i] == ' ' || p[i] == '\t' || p[i] == '\r' || p[i] == '\n')) ++i;
    return size - i >= 5 && memcmp(p + i, "solid", 5) == 0 &&
           (size - i == 5 || p[i + 5] == ' ' || p[i + 5] == '\t' || p[i + 5] == '\r' ||
            p[i + 5] == '\n');
}

static int all_text(const unsigned char *p, size_t size) {
    for (size_t i = 0; i < size; ++i)
        if (!((p[i] >= 0x20 && p[i] < 0x7f) || p[i] == '\n' || p[i] == '\r' || p[i] == '\t'))
            return 0;
    return 1;
}

ry_status ry_stl_parse(ry_stl *m, const char *name, const void *data, size_t size, ry_error *err) {
    memset(m, 0, sizeof *m);
    const unsigned char *p = data;
    RY_CHECK(err, size <= RY_STL_MAX_BYTES, RY_ERR_INPUT, "%s: %zu bytes, more than the limit %zu",
             name, size, RY_STL_MAX_BYTES);
    int solid = starts_with_solid(p, size);
    int size_fits = 0;
    size_t n = 0;
    if (size >= STL_HEADER + 4) {
        n = le32(p + STL_HEADER);
        size_fits =
            (size - STL_HEADER - 4) % STL_RECORD == 0 && (size - STL_HEADER - 4) / STL_RECORD == n;
    }
    if (size_fits && !(solid && all_text(p, size))) {
        RY_TRY(parse_binary(m, name, p, err));
        update_bounds(m);
        return RY_OK;
    }
    if (solid) {
        RY_TRY(parse_ascii(m, name, (const char *)p, size, err));
        update_bounds(m);
        return RY_OK;
    }
    if (size < STL_HEADER + 4)
        return ry_error_set(err, RY_ERR_INPUT,
                            "%s: not an STL file: %zu bytes, too short for binary (84 bytes at "
                            "least) and no ASCII 'solid' at the start",
                            name, size);
    return ry_error_set(err, RY_ERR_INPUT,
                        "%s: binary STL: the header (byte 80) gives %zu triangles, which need "
                        "84 + 50 x %zu = %.0f bytes, but the file has %zu bytes (truncated, or "
                        "not an STL file)",
                        name, n, n, 84.0 + 50.0 * (double)n, size);
}

ry_status ry_stl_read(ry_stl *m, const char *path, ry_error *err) {
    memset(m, 0, sizeof *m);
    FILE *fp = fopen(path, "rb");
    if (!fp) return ry_error_set(err, RY_ERR_IO, "cannot read '%s': %s", path, strerror(errno));
    struct stat sb;
    if (fstat(fileno(fp), &sb) != 0 || !S_ISREG(sb.st_mode)) {
        fclose(fp);
        return ry_error_set(err, RY_ERR_IO, "cannot read '%s': not a regular file", path);
    }
    if ((unsigned long long)sb.st_size > (unsigned long long)RY_STL_MAX_BYTES) {
        fclose(fp);
        return ry_error_set(err, RY_ERR_INPUT, "%s: %lld bytes, more than the limit %zu", path,
                            (long long)sb.st_size, RY_STL_MAX_BYTES);
    }
    size_t size = (size_t)sb.st_size;
    unsigned char *buf = malloc(size ? size : 1);
    if (!buf) {
        fclose(fp);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory reading '%s'", path);
    }
    size_t got = fread(buf, 1, size, fp);
    int e = ferror(fp) ? errno : 0;
    fclose(fp);
    if (got != size) {
        free(buf);
        return ry_error_set(err, RY_ERR_IO, "cannot read '%s': %s", path,
                            e ? strerror(e) : "the file changed while it was read");
    }
    ry_status st = ry_stl_parse(m, path, buf, size, err);
    free(buf);
    return st;
}

/* ---------------------------------------------------------------- writing */

/* (b - a) x (c - a) of the triangle t (9 doubles): twice its area along its normal. */
static void area_vector(const double *t, double *c) {
    double u[3], w[3];
    for (int d = 0; d < 3; ++d) {
        u[d] = t[3 + d] - t[d];
        w[d] = t[6 + d] - t[d];
    }
    c[0] = u[1] * w[2] - u[2] * w[1];
    c[1] = u[2] * w[0] - u[0] * w[2];
    c[2] = u[0] * w[1] - u[1] * w[0];
}

static void normal_of(const double *t, double *nrm) {
    area_vector(t, nrm);
    double a = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
    for (int d = 0; d < 3; ++d) nrm[d] = a > 0 ? nrm[d] / a : 0.0;
}

static void put_le32(unsigned char *p, uint32_t u) {
    for (int k = 0; k < 4; ++k) p[k] = (unsigned char)(u >> (8 * k));
}

static void put_float(unsigned char *p, double x) {
    float f = (float)x;
    uint32_t u;
    memcpy(&u, &f, sizeof u);
    put_le32(p, u);
}

ry_status ry_stl_write(const ry_stl *m, const char *path, int binary, ry_error *err) {
    ry_atomic_file f;
    RY_TRY(ry_atomic_open(&f, path, err));
    double nrm[3];
    if (binary) {
        unsigned char head[STL_HEADER + 4] = {0}, rec[STL_RECORD];
        memcpy(head, "binary STL written by ryushi", 28);
        put_le32(head + STL_HEADER, (uint32_t)m->ntri);
        fwrite(head, 1, sizeof head, f.fp);
        for (size_t t = 0; t < m->ntri; ++t) {
            const double *v = m->v + 9 * t;
            memset(rec, 0, sizeof rec);
            normal_of(v, nrm);
            for (int k = 0; k < 3; ++k) put_float(rec + 4 * k, nrm[k]);
            for (int k = 0; k < 9; ++k) put_float(rec + 12 + 4 * k, v[k]);
            fwrite(rec, 1, sizeof rec, f.fp);
        }
    } else {
        fprintf(f.fp, "solid ryushi\n");
        for (size_t t = 0; t < m->ntri; ++t) {
            const double *v = m->v + 9 * t;
            normal_of(v, nrm);
            fprintf(f.fp, "  facet normal %.9g %.9g %.9g\n    outer loop\n", nrm[0], nrm[1],
                    nrm[2]);
            for (int k = 0; k < 3; ++k)
                fprintf(f.fp, "      vertex %.17g %.17g %.17g\n", v[3 * k], v[3 * k + 1],
                        v[3 * k + 2]);
            fprintf(f.fp, "    endloop\n  endfacet\n");
        }
        fprintf(f.fp, "endsolid ryushi\n");
    }
    return ry_atomic_commit(&f, err);
}

/* ---------------------------------------------------------------- geometry */

void ry_stl_transform(ry_stl *m, double scale, const double *translate) {
    for (size_t i = 0; i < 3 * m->ntri; ++i)
        for (int d = 0; d < 3; ++d)
            m->v[3 * i + d] = scale * m->v[3 * i + d] + (translate ? translate[d] : 0.0);
    update_bounds(m);
}

double ry_stl_volume(const ry_stl *m) {
    double vol = 0;
    for (size_t t = 0; t < m->ntri; ++t) {
        const double *a = m->v + 9 * t, *b = a + 3, *c = a + 6;
        vol += a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
               a[2] * (b[0] * c[1] - b[1] * c[0]);
    }
    return vol / 6.0;
}

double ry_stl_default_tolerance(const ry_stl *m) {
    double d2 = 0;
    for (int d = 0; d < 3; ++d) d2 += (m->hi[d] - m->lo[d]) * (m->hi[d] - m->lo[d]);
    return 1e-6 * sqrt(d2);
}

/* ---------------------------------------------------------------- closedness */

static uint32_t uf_find(uint32_t *parent, uint32_t i) {
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

static void uf_union(uint32_t *parent, uint32_t a, uint32_t b) {
    a = uf_find(parent, a);
    b = uf_find(parent, b);
    if (a < b)
        parent[b] = a;
    else if (b < a)
        parent[a] = b;
}

/* Vertex ids after merging: id[i] is the smallest vertex index of i's group. */
static ry_status merge_vertices(const ry_stl *m, double tol, uint32_t *id, ry_error *err) {
    size_t nv = 3 * m->ntri;
    ry_cell_key *k = malloc(nv * sizeof *k);
    RY_CHECK(err, k != NULL, RY_ERR_NOMEM, "%s: out of memory", m->name);
    for (size_t i = 0; i < nv; ++i) {
        id[i] = (uint32_t)i;
        k[i].i = (uint32_t)i;
        for (int d = 0; d < 3; ++d) {
            double x = m->v[3 * i + d];
            if (tol > 0) {
                double q = floor((x - m->lo[d]) / tol);
                if (!(q < 9.0e15)) {
                    free(k);
                    return ry_error_set(err, RY_ERR_INPUT,
                                        "%s: merge tolerance %g too small for the size", m->name,
                                        tol);
                }
                k[i].c[d] = (int64_t)q;
            } else {
                x += 0.0; /* -0 and +0 are the same point */
                memcpy(&k[i].c[d], &x, sizeof x);
            }
        }
    }
    qsort(k, nv, sizeof *k, ry_cell_key_cmp);
    if (tol <= 0) {
        for (size_t i = 1; i < nv; ++i)
            if (ry_cell_same(k[i].c, k[i - 1].c)) uf_union(id, k[i].i, k[i - 1].i);
    } else {
        for (size_t i = 0; i < nv; ++i) {
            const double *p = m->v + 3 * (size_t)k[i].i;
            for (int dx = -1; dx <= 1; ++dx)
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dz = -1; dz <= 1; ++dz) {
                        int64_t c[3] = {k[i].c[0] + dx, k[i].c[1] + dy, k[i].c[2] + dz};
                        for (size_t j = ry_cell_key_find(k, nv, c);
                             j < nv && ry_cell_same(k[j].c, c); ++j) {
                            const double *q = m->v + 3 * (size_t)k[j].i;
                            if (fabs(p[0] - q[0]) <= tol && fabs(p[1] - q[1]) <= tol &&
                                fabs(p[2] - q[2]) <= tol)
                                uf_union(id, k[i].i, k[j].i);
                        }
                    }
        }
    }
    free(k);
    for (size_t i = 0; i < nv; ++i) id[i] = uf_find(id, (uint32_t)i);
    return RY_OK;
}

typedef struct edge {
    uint32_t a, b; /* merged vertex ids, a < b */
    uint32_t tri;
    int8_t dir; /* +1: the triangle runs a -> b; -1: b -> a */
    uint8_t k;  /* edge k of the triangle: from vertex k to vertex k + 1 */
} edge;

static int edge_cmp(const void *x, const void *y) {
    const edge *e = x, *f = y;
    if (e->a != f->a) return e->a < f->a ? -1 : 1;
    if (e->b != f->b) return e->b < f->b ? -1 : 1;
    return e->tri < f->tri ? -1 : e->tri > f->tri;
}

static ry_status degenerate_check(const ry_stl *m, const uint32_t *id, ry_error *err) {
    char where[512];
    for (size_t t = 0; t < m->ntri; ++t) {
        const double *v = m->v + 9 * t;
        double l2 = 0;
        for (int k = 0; k < 3; ++k)
            for (int d = 0; d < 3; ++d) {
                double e = v[3 * ((k + 1) % 3) + d] - v[3 * k + d];
                l2 = fmax(l2, e * e);
            }
        double c[3];
        area_vector(v, c);
        double a2 = c[0] * c[0] + c[1] * c[1] + c[2] * c[2];
        int merged = id[3 * t] == id[3 * t + 1] || id[3 * t + 1] == id[3 * t + 2] ||
                     id[3 * t] == id[3 * t + 2];
        if (merged || !(sqrt(a2) > 1e-12 * l2))
            return ry_error_set(err, RY_ERR_INPUT,
                                "%s: degenerate triangle (zero area) with vertices (%g, %g, %g), "
                                "(%g, %g, %g), (%g, %g, %g)",
                                ry_stl_where(m, t, where, sizeof where), v[0], v[1], v[2], v[3],
                                v[4], v[5], v[6], v[7], v[8]);
    }
    return RY_OK;
}

ry_status ry_stl_check(const ry_stl *m, double tol, ry_error *err) {
    RY_CHECK(err, m->ntri > 0, RY_ERR_INPUT, "%s: no triangle", m->name);
    size_t nv = 3 * m->ntri;
    uint32_t *id = malloc(nv * sizeof *id);
    edge *e = malloc(nv * sizeof *e);
    if (!id || !e) {
        free(id);
        free(e);
        return ry_error_set(err, RY_ERR_NOMEM, "%s: out of memory", m->name);
    }
    ry_status st = merge_vertices(m, tol, id, err);
    if (st == RY_OK) st = degenerate_check(m, id, err);
    if (st != RY_OK) {
        free(id);
        free(e);
        return st;
    }
    for (size_t t = 0; t < m->ntri; ++t)
        for (int k = 0; k < 3; ++k) {
            uint32_t p = id[3 * t + k], q = id[3 * t + (k + 1) % 3];
            e[3 * t + k] = (edge){p < q ? p : q, p < q ? q : p, (uint32_t)t,
                                  (int8_t)(p < q ? 1 : -1), (uint8_t)k};
        }
    qsort(e, nv, sizeof *e, edge_cmp);
    /* The offending edge group whose first triangle comes first in the file. */
    size_t bad = SIZE_MAX, bad_count = 0;
    for (size_t i = 0; i < nv;) {
        size_t j = i + 1;
        while (j < nv && e[j].a == e[i].a && e[j].b == e[i].b) ++j;
        int ok = j - i == 2 && e[i].dir != e[i + 1].dir;
        if (!ok && (bad == SIZE_MAX || e[i].tri < e[bad].tri)) {
            bad = i;
            bad_count = j - i;
        }
        i = j;
    }
    if (bad != SIZE_MAX) {
        const edge *b = &e[bad];
        const double *p = m->v + 9 * (size_t)b->tri + 3 * b->k;
        const double *q = m->v + 9 * (size_t)b->tri + 3 * ((b->k + 1) % 3);
        char where[512];
        ry_stl_where(m, b->tri, where, sizeof where);
        if (bad_count == 1)
            st = ry_error_set(err, RY_ERR_INPUT,
                              "%s: the surface is not closed: the edge from (%g, %g, %g) to "
                              "(%g, %g, %g) belongs to no other triangle",
                              where, p[0], p[1], p[2], q[0], q[1], q[2]);
        else if (bad_count > 2)
            st = ry_error_set(err, RY_ERR_INPUT,
                              "%s: the surface is not a closed manifold: the edge from (%g, %g, "
                              "%g) to (%g, %g, %g) is shared by %zu triangles (2 expected)",
                              where, p[0], p[1], p[2], q[0], q[1], q[2], bad_count);
        else {
            char other[512];
            ry_stl_where(m, e[bad + 1].tri, other, sizeof other);
            st = ry_error_set(err, RY_ERR_INPUT,
                              "%s: inconsistent orientation: this triangle and the one at %s run "
                              "along their shared edge from (%g, %g, %g) to (%g, %g, %g) in the "
                              "same direction",
                              where, other, p[0], p[1], p[2], q[0], q[1], q[2]);
        }
    }
    free(id);
    free(e);
    return st;
}
