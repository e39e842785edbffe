/* ryushi — checkpoints: the whole state of a run in one self-describing, versioned file.
 *
 * File layout (little-endian):
 *   magic      8 bytes  "RYUSHICK"
 *   version    u32      RY_CHECKPOINT_VERSION
 *   order      u32      0x01020304 as written (detects a file from a big-endian machine)
 *   records    any number of { name_len u16, name bytes, type u8, count u64, data }
 *   end        u16 0 (an empty name), then crc32 (u32) of every byte before it
 * Record types: f64 and i64 arrays, u8 arrays (also text). Every record is named, so a file can
 * be listed and read by name (`ryushi checkpoint FILE` lists it) and new records can be added
 * without breaking old readers. The reader checks the magic, version, byte order, sizes and
 * the checksum before any value is used; a truncated or damaged file is an error, never a
 * crash.
 *
 * A simulation's checkpoint holds every particle array (all fields, ids, kinds, materials),
 * the clock and step, the neighbour-list bookkeeping, the scheme's own state variables, the
 * output state (.pvd entries and series.csv so far) and the profile sums, so that a restarted
 * run continues bitwise identically. */
#ifndef RYUSHI_CHECKPOINT_H
#define RYUSHI_CHECKPOINT_H

#include <stddef.h>
#include <stdint.h>

#include "ryushi/atomic_file.h"
#include "ryushi/status.h"

enum { RY_CHECKPOINT_VERSION = 1 };

typedef enum ry_ck_type { RY_CK_F64 = 1, RY_CK_I64 = 2, RY_CK_U8 = 3 } ry_ck_type;

/* ---- writing ---- */
typedef struct ry_ck_writer {
    ry_atomic_file file;
    unsigned long crc;
    int failed;
} ry_ck_writer;

/* Starts a checkpoint at path (written under a temporary name until committed). */
ry_status ry_ck_begin(ry_ck_writer *w, const char *path, ry_error *err);
ry_status ry_ck_put(ry_ck_writer *w, const char *name, ry_ck_type type, const void *data,
                    size_t count, ry_error *err);
ry_status ry_ck_put_f64(ry_ck_writer *w, const char *name, double v, ry_error *err);
ry_status ry_ck_put_i64(ry_ck_writer *w, const char *name, int64_t v, ry_error *err);
ry_status ry_ck_put_text(ry_ck_writer *w, const char *name, const char *text, size_t len,
                         ry_error *err);
/* Writes the end mark and checksum, then renames the file onto its final name. */
ry_status ry_ck_commit(ry_ck_writer *w, ry_error *err);
void ry_ck_abort(ry_ck_writer *w);

/* ---- reading ---- */
typedef struct ry_ck_record {
    char name[256];
    ry_ck_type type;
    size_t count;
    const unsigned char *data; /* into the reader's buffer; unaligned */
} ry_ck_record;

typedef struct ry_ck_reader {
    char *path;
    unsigned char *buf;
    size_t size;
    int nrec;
    ry_ck_record *rec;
} ry_ck_reader;

/* Reads and checks a whole checkpoint file. */
ry_status ry_ck_open(ry_ck_reader *r, const char *path, ry_error *err);
/* Checks a checkpoint held in memory (the bytes are copied); path names it in messages. */
ry_status ry_ck_open_memory(ry_ck_reader *r, const char *path, const void *data, size_t size,
                            ry_error *err);
void ry_ck_close(ry_ck_reader *r);
/* The record of that name (NULL when absent). */
const ry_ck_record *ry_ck_find(const ry_ck_reader *r, const char *name);
/* Copies a record of the given type and exact count into out; an error naming the file and
 * record when it is missing or has another type or size. */
ry_status ry_ck_get(const ry_ck_reader *r, const char *name, ry_ck_type type, size_t count,
                    void *out, ry_error *err);
ry_status ry_ck_get_f64(const ry_ck_reader *r, const char *name, double *v, ry_error *err);
ry_status ry_ck_get_i64(const ry_ck_reader *r, const char *name, int64_t *v, ry_error *err);
/* A text record as a malloc'd, NUL-terminated string. */
ry_status ry_ck_get_text(const ry_ck_reader *r, const char *name, char **text, size_t *len,
                         ry_error *err);
const char *ry_ck_type_name(ry_ck_type type);

/* Replaces the state of a simulation by the checkpoint's (ry_sim_checkpoint_read without the
 * file; sim.h). */
struct ry_sim;
ry_status ry_sim_checkpoint_load(struct ry_sim *sim, const ry_ck_reader *r, ry_error *err);

#endif
