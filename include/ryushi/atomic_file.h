/* ryushi — files written atomically: written under a temporary name in the same folder, flushed,
 * then renamed over the final name, so an interrupted run never leaves a half-written file. */
#ifndef RYUSHI_ATOMIC_FILE_H
#define RYUSHI_ATOMIC_FILE_H

#include <stdio.h>

#include "ryushi/status.h"

typedef struct ry_atomic_file {
    FILE *fp;       /* write through this */
    char *path;     /* final name */
    char *tmp_path; /* temporary name */
} ry_atomic_file;

/* Opens path's temporary file for writing (binary). */
ry_status ry_atomic_open(ry_atomic_file *f, const char *path, ry_error *err);
/* Flushes, checks for write errors, closes and renames onto the final name. On failure the
 * temporary file is removed and the final name is untouched. */
ry_status ry_atomic_commit(ry_atomic_file *f, ry_error *err);
/* Closes and removes the temporary file without touching the final name. */
void ry_atomic_abort(ry_atomic_file *f);
/* Writes a whole buffer to path atomically. */
ry_status ry_atomic_write(const char *path, const void *data, size_t size, ry_error *err);
/* Creates a folder and its parents (like mkdir -p); an error when it cannot be written. */
ry_status ry_mkdir_p(const char *path, ry_error *err);

#endif
