/* Atomic file writes (see include/ryushi/atomic_file.h). */
#define _POSIX_C_SOURCE 200809L
#include "ryushi/atomic_file.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

ry_status ry_atomic_open(ry_atomic_file *f, const char *path, ry_error *err) {
    memset(f, 0, sizeof *f);
    size_t n = strlen(path);
    f->path = ry_strdup(path);
    f->tmp_path = malloc(n + 32);
    if (!f->path || !f->tmp_path) {
        free(f->path);
        free(f->tmp_path);
        f->path = f->tmp_path = NULL;
        return ry_error_set(err, RY_ERR_NOMEM, "out of memory opening '%s'", path);
    }
    snprintf(f->tmp_path, n + 32, "%s.tmp.%ld", path, (long)getpid());
    f->fp = fopen(f->tmp_path, "wb");
    if (!f->fp) {
        int e = errno;
        free(f->path);
        free(f->tmp_path);
        f->path = f->tmp_path = NULL;
        return ry_error_set(err, RY_ERR_IO, "cannot write '%s': %s", path, strerror(e));
    }
    return RY_OK;
}

ry_status ry_atomic_commit(ry_atomic_file *f, ry_error *err) {
    ry_status st = RY_OK;
    int bad = ferror(f->fp) != 0;
    if (fflush(f->fp) != 0) bad = 1;
    if (!bad && fsync(fileno(f->fp)) != 0 && errno != EINVAL) bad = 1;
    int e = errno;
    if (fclose(f->fp) != 0) {
        bad = 1;
        e = errno;
    }
    f->fp = NULL;
    if (bad) {
        remove(f->tmp_path);
        st = ry_error_set(err, RY_ERR_IO, "writing '%s' failed: %s", f->path, strerror(e));
    } else if (rename(f->tmp_path, f->path) != 0) {
        e = errno;
        remove(f->tmp_path);
        st = ry_error_set(err, RY_ERR_IO, "cannot rename onto '%s': %s", f->path, strerror(e));
    }
    free(f->path);
    free(f->tmp_path);
    f->path = f->tmp_path = NULL;
    return st;
}

void ry_atomic_abort(ry_atomic_file *f) {
    if (f->fp) fclose(f->fp);
    if (f->tmp_path) remove(f->tmp_path);
    free(f->path);
    free(f->tmp_path);
    memset(f, 0, sizeof *f);
}

ry_status ry_atomic_write(const char *path, const void *data, size_t size, ry_error *err) {
    ry_atomic_file f;
    RY_TRY(ry_atomic_open(&f, path, err));
    if (size && fwrite(data, 1, size, f.fp) != size) {
        int e = errno;
        ry_atomic_abort(&f);
        return ry_error_set(err, RY_ERR_IO, "writing '%s' failed: %s", path, strerror(e));
    }
    return ry_atomic_commit(&f, err);
}

ry_status ry_mkdir_p(const char *path, ry_error *err) {
    char *p = ry_strdup(path);
    if (!p) return ry_error_set(err, RY_ERR_NOMEM, "out of memory");
    size_t n = strlen(p);
    for (size_t i = 1; i <= n; ++i) {
        if (p[i] == '/' || p[i] == '\0') {
            char c = p[i];
            p[i] = '\0';
            if (mkdir(p, 0777) != 0 && errno != EEXIST) {
                int e = errno;
                ry_error_set(err, RY_ERR_IO, "cannot create folder '%s': %s", p, strerror(e));
                free(p);
                return RY_ERR_IO;
            }
            p[i] = c;
        }
    }
    struct stat sb;
    if (stat(path, &sb) != 0 || !S_ISDIR(sb.st_mode)) {
        free(p);
        return ry_error_set(err, RY_ERR_IO, "'%s' is not a folder", path);
    }
    if (access(path, W_OK) != 0) {
        free(p);
        return ry_error_set(err, RY_ERR_IO, "folder '%s' cannot be written", path);
    }
    free(p);
    return RY_OK;
}
