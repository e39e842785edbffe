/* Checkpoint files: named, typed records with a CRC-32 (zlib) over the whole file. */
#define _POSIX_C_SOURCE 200809L
#include "ryushi/checkpoint.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <zlib.h>

static const char MAGIC[8] = {'R', 'Y', 'U', 'S', 'H', 'I', 'C', 'K'};
static const uint32_t ORDER = 0x01020304u;
enum { HEADER_BYTES = 16, MAX_RECORDS = 1 << 20 };

const char *ry_ck_type_name(ry_ck_type type) {
    switch (type) {
    case RY_CK_F64:
        return "f64";
    case RY_CK_I64:
        return "i64";
    case RY_CK_U8:
        return "u8";
    }
    return "unknown";
}

static size_t type_size(int type) {
    return type == RY_CK_F64 || type == RY_CK_I64 ? 8 : type == RY_CK_U8 ? 1 : 0;
}

/* ---- writing ------------------------------------------------------------------------------ */

static void put_bytes(ry_ck_writer *w, const void *p, size_t n) {
    if (w->failed || n == 0) return;
    const unsigned char *b = p;
    /* zlib's crc32 takes a uInt length: feed large arrays in pieces. */
    for (size_t done = 0; done < n;) {
        size_t k = n - done < (1u << 30) ? n - done : (1u << 30);
        w->crc = crc32(w->crc, b + done, (uInt)k);
        done += k;
    }
    if (fwrite(p, 1, n, w->file.fp) != n) w->failed = errno ? errno : EIO;
}

ry_status ry_ck_begin(ry_ck_writer *w, const char *path, ry_error *err) {
    memset(w, 0, sizeof *w);
    RY_TRY(ry_atomic_open(&w->file, path, err));
    w->crc = crc32(0L, Z_NULL, 0);
    uint32_t v = RY_CHECKPOINT_VERSION;
    put_bytes(w, MAGIC, sizeof MAGIC);
    put_bytes(w, &v, 4);
    put_bytes(w, &ORDER, 4);
    return RY_OK;
}

static ry_status write_failed(ry_ck_writer *w, ry_error *err) {
    int e = w->failed;
    ry_status st =
        ry_error_set(err, RY_ERR_IO, "writing checkpoint %s failed: %s", w->file.path, strerror(e));
    ry_ck_abort(w);
    return st;
}

ry_status ry_ck_put(ry_ck_writer *w, const char *name, ry_ck_type type, const void *data,
                    size_t count, ry_error *err) {
    size_t len = strlen(name);
    if (len == 0 || len > 255 || type_size(type) == 0) {
        ry_ck_abort(w);
        return ry_error_set(err, RY_ERR_INTERNAL, "checkpoint record '%s': bad name or type", name);
    }
    uint16_t nl = (uint16_t)len;
    uint8_t t = (uint8_t)type;
    uint64_t c = count;
    put_bytes(w, &nl, 2);
    put_bytes(w, name, len);
    put_bytes(w, &t, 1);
    put_bytes(w, &c, 8);
    put_bytes(w, data, count * type_size(type));
    return w->failed ? write_failed(w, err) : RY_OK;
}

ry_status ry_ck_put_f64(ry_ck_writer *w, const char *name, double v, ry_error *err) {
    return ry_ck_put(w, name, RY_CK_F64, &v, 1, err);
}

ry_status ry_ck_put_i64(ry_ck_writer *w, const char *name, int64_t v, ry_error *err) {
    return ry_ck_put(w, name, RY_CK_I64, &v, 1, err);
}

ry_status ry_ck_put_text(ry_ck_writer *w, const char *name, const char *text, size_t len,
                         ry_error *err) {
    return ry_ck_put(w, name, RY_CK_U8, text, len, err);
}

ry_status ry_ck_commit(ry_ck_writer *w, ry_error *err) {
    uint16_t end = 0;
    put_bytes(w, &end, 2);
    uint32_t crc = (uint32_t)w->crc;
    if (!w->failed && fwrite(&crc, 1, 4, w->file.fp) != 4) w->failed = errno ? errno : EIO;
    if (w->failed) return write_failed(w, err);
    return ry_atomic_commit(&w->file, err);
}

void ry_ck_abort(ry_ck_writer *w) {
    if (w->file.fp) ry_atomic_abort(&w->file);
}

/* ---- reading ------------------------------------------------------------------------------ */

void ry_ck_close(ry_ck_reader *r) {
    free(r->path);
    free(r->buf);
    free(r->rec);
    memset(r, 0, sizeof *r);
}

static ry_status bad(ry_ck_reader *r, ry_error *err, const char *fmt, const char *what, size_t at) {
    char msg[512];
    snprintf(msg, sizeof msg, fmt, what, at);
    ry_status st = ry_error_set(err, RY_ERR_INPUT, "checkpoint %s: %s", r->path, msg);
    ry_ck_close(r);
    return st;
}

/* Indexes the records of r->buf; every length is checked against the bytes left. */
static ry_status parse(ry_ck_reader *r, ry_error *err) {
    const unsigned char *b = r->buf;
    const size_t size = r->size;
    if (size < HEADER_BYTES || memcmp(b, MAGIC, sizeof MAGIC) != 0)
        return bad(r, err, "not a ryushi checkpoint (%s, %zu bytes)", "no RYUSHICK header", size);
    uint32_t version, order;
    memcpy(&version, b + 8, 4);
    memcpy(&order, b + 12, 4);
    if (order != ORDER)
        return bad(r, err, "%s (byte %zu)", "written with another byte order", (size_t)12);
    if (version != RY_CHECKPOINT_VERSION) {
        char v[64];
        snprintf(v, sizeof v, "format version %u, this ryushi reads version %d", version,
                 RY_CHECKPOINT_VERSION);
        return bad(r, err, "%s (byte %zu)", v, (size_t)8);
    }
    size_t pos = HEADER_BYTES;
    int cap = 0;
    for (;;) {
        if (size - pos < 2) return bad(r, err, "truncated: %s at byte %zu", "no end mark", pos);
        uint16_t nl;
        memcpy(&nl, b + pos, 2);
        if (nl == 0) {
            pos += 2;
            break;
        }
        const size_t start = pos;
        if (nl >= sizeof r->rec[0].name)
            return bad(r, err, "%s (record at byte %zu)", "record name longer than 255 bytes",
                       start);
        if (size - pos < 2u + nl + 9u)
            return bad(r, err, "truncated: %s at byte %zu", "record header cut short", start);
        pos += 2;
        if (r->nrec == cap) {
            if (cap >= MAX_RECORDS)
                return bad(r, err, "%s (at byte %zu)", "too many records", start);
            cap = cap ? 2 * cap : 64;
            ry_ck_record *p = realloc(r->rec, (size_t)cap * sizeof *p);
            if (!p) {
                ry_ck_close(r);
                return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
            }
            r->rec = p;
        }
        ry_ck_record *rec = &r->rec[r->nrec];
        memcpy(rec->name, b + pos, nl);
        rec->name[nl] = '\0';
        pos += nl;
        if (memchr(rec->name, '\0', nl))
            return bad(r, err, "%s (record at byte %zu)", "record name contains NUL", start);
        uint8_t t = b[pos++];
        uint64_t count;
        memcpy(&count, b + pos, 8);
        pos += 8;
        size_t es = type_size(t);
        if (es == 0) return bad(r, err, "record '%s' at byte %zu: unknown type", rec->name, start);
        if (count > (size - pos) / es)
            return bad(r, err, "truncated: record '%s' (at byte %zu) runs past the end", rec->name,
                       start);
        rec->type = (ry_ck_type)t;
        rec->count = (size_t)count;
        rec->data = b + pos;
        pos += (size_t)count * es;
        r->nrec++;
    }
    if (size - pos != 4)
        return bad(r, err, "%s (checksum expected at byte %zu)",
                   size - pos < 4 ? "truncated" : "trailing bytes after the end mark", pos);
    uint32_t want;
    memcpy(&want, b + pos, 4);
    unsigned long crc = crc32(0L, Z_NULL, 0);
    for (size_t done = 0; done < pos;) {
        size_t k = pos - done < (1u << 30) ? pos - done : (1u << 30);
        crc = crc32(crc, b + done, (uInt)k);
        done += k;
    }
#ifdef FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION
    want = (uint32_t)crc; /* fuzzing: let mutated files reach the records */
#endif
    if ((uint32_t)crc != want)
        return bad(r, err, "%s (over %zu bytes): the file is damaged", "checksum mismatch", pos);
    return RY_OK;
}

ry_status ry_ck_open_memory(ry_ck_reader *r, const char *path, const void *data, size_t size,
                            ry_error *err) {
    memset(r, 0, sizeof *r);
    r->path = ry_strdup(path);
    r->buf = malloc(size ? size : 1);
    if (!r->path || !r->buf) {
        ry_ck_close(r);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
    }
    if (size) memcpy(r->buf, data, size);
    r->size = size;
    return parse(r, err);
}

ry_status ry_ck_open(ry_ck_reader *r, const char *path, ry_error *err) {
    memset(r, 0, sizeof *r);
    FILE *fp = fopen(path, "rb");
    if (!fp)
        return ry_error_set(err, RY_ERR_IO, "cannot open checkpoint %s: %s", path, strerror(errno));
    struct stat sb;
    if (fstat(fileno(fp), &sb) != 0 || !S_ISREG(sb.st_mode)) {
        fclose(fp);
        return ry_error_set(err, RY_ERR_IO, "checkpoint %s: not a regular file", path);
    }
    r->path = ry_strdup(path);
    r->size = (size_t)sb.st_size;
    r->buf = malloc(r->size ? r->size : 1);
    if (!r->path || !r->buf) {
        fclose(fp);
        ry_ck_close(r);
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory reading checkpoint %s", path);
    }
    size_t got = fread(r->buf, 1, r->size, fp);
    int e = ferror(fp) ? errno : 0;
    fclose(fp);
    if (got != r->size) {
        ry_status st = ry_error_set(err, RY_ERR_IO, "reading checkpoint %s failed: %s", path,
                                    e ? strerror(e) : "short read");
        ry_ck_close(r);
        return st;
    }
    return parse(r, err);
}

const ry_ck_record *ry_ck_find(const ry_ck_reader *r, const char *name) {
    for (int i = 0; i < r->nrec; ++i)
        if (strcmp(r->rec[i].name, name) == 0) return &r->rec[i];
    return NULL;
}

ry_status ry_ck_get(const ry_ck_reader *r, const char *name, ry_ck_type type, size_t count,
                    void *out, ry_error *err) {
    const ry_ck_record *rec = ry_ck_find(r, name);
    RY_CHECK(err, rec != NULL, RY_ERR_INPUT, "checkpoint %s: record '%s' is missing", r->path,
             name);
    RY_CHECK(err, rec->type == type && rec->count == count, RY_ERR_INPUT,
             "checkpoint %s: record '%s' holds %zu %s value(s), expected %zu %s", r->path, name,
             rec->count, ry_ck_type_name(rec->type), count, ry_ck_type_name(type));
    if (count) memcpy(out, rec->data, count * type_size(type));
    return RY_OK;
}

ry_status ry_ck_get_f64(const ry_ck_reader *r, const char *name, double *v, ry_error *err) {
    return ry_ck_get(r, name, RY_CK_F64, 1, v, err);
}

ry_status ry_ck_get_i64(const ry_ck_reader *r, const char *name, int64_t *v, ry_error *err) {
    return ry_ck_get(r, name, RY_CK_I64, 1, v, err);
}

ry_status ry_ck_get_text(const ry_ck_reader *r, const char *name, char **text, size_t *len,
                         ry_error *err) {
    const ry_ck_record *rec = ry_ck_find(r, name);
    RY_CHECK(err, rec != NULL && rec->type == RY_CK_U8, RY_ERR_INPUT,
             "checkpoint %s: text record '%s' is missing", r->path, name);
    *text = malloc(rec->count + 1);
    RY_CHECK(err, *text != NULL, RY_ERR_NOMEM, "out of memory");
    if (rec->count) memcpy(*text, rec->data, rec->count);
    (*text)[rec->count] = '\0';
    if (len) *len = rec->count;
    return RY_OK;
}
