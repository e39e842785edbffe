/* ryushi — case files.
 *
 * A case is a YAML document (read with libfyaml). Access is strict: every value is fetched
 * through a typed getter that checks its type and range, and after a case has been set up
 * ry_case_check_unused() reports any key nobody asked for. Every error message names the file,
 * the line and the key, e.g.
 *     cases/dam.yaml:12: key 'time.t_end': expected a number, got 'abc'
 * Values given on the command line (--set key=value) replace or add keys and are reported as
 *     --set time.t_end=abc: key 'time.t_end': expected a number, got 'abc'
 *
 * Paths are dotted, with [k] for sequence elements: "time.t_end", "bodies[2].lo".
 * Getters with a NULL default pointer make the key required. Every value fetched (defaults
 * included) is recorded so that ry_case_write_resolved() writes the fully resolved parameters. */
#ifndef RYUSHI_CASE_H
#define RYUSHI_CASE_H

#include <stddef.h>

#include "ryushi/status.h"

typedef struct ry_case ry_case;

/* Reads a case file. Syntax errors are reported with file and line. */
ry_status ry_case_load(ry_case **out, const char *path, ry_error *err);
/* Reads a case from text; name stands in for the file name in messages. */
ry_status ry_case_load_string(ry_case **out, const char *name, const char *text, ry_error *err);
void ry_case_free(ry_case *c);
/* The file name the case was read from. */
const char *ry_case_name(const ry_case *c);

/* Applies "path=value" (value parsed as a YAML scalar or flow sequence such as [1, 2]).
 * Creates the key (and parent mappings) when absent. */
ry_status ry_case_override(ry_case *c, const char *assignment, ry_error *err);

/* 1 if the key is present (marks nothing as used). */
int ry_case_has(const ry_case *c, const char *path);
/* Marks a key and everything below it as used (for keys read by someone else or ignored on
 * purpose, e.g. a documentation section). */
void ry_case_touch(ry_case *c, const char *path);
/* "file:line" of a key (or of the case file when absent), for messages of other modules. */
const char *ry_case_where(ry_case *c, const char *path, char *buf, size_t size);

/* Numbers within [lo, hi] (use -INFINITY / INFINITY for no bound). */
ry_status ry_case_double(ry_case *c, const char *path, const double *def, double lo, double hi,
                         double *out, ry_error *err);
/* A number > 0. */
ry_status ry_case_positive(ry_case *c, const char *path, const double *def, double *out,
                           ry_error *err);
/* An integer within [lo, hi]. */
ry_status ry_case_int(ry_case *c, const char *path, const long *def, long lo, long hi, long *out,
                      ry_error *err);
/* true/false. */
ry_status ry_case_bool(ry_case *c, const char *path, const int *def, int *out, ry_error *err);
/* A string; *out points into the case (valid until ry_case_free). */
ry_status ry_case_string(ry_case *c, const char *path, const char *def, const char **out,
                         ry_error *err);
/* One of names[0..] (NULL-terminated); *out is the index. The error lists the allowed names. */
ry_status ry_case_choice(ry_case *c, const char *path, const char *def, const char *const *names,
                         int *out, ry_error *err);
/* A sequence of exactly n numbers (e.g. a point in dim dimensions). */
ry_status ry_case_vector(ry_case *c, const char *path, const double *def, int n, double *out,
                         ry_error *err);
/* Number of elements of a sequence (0 when the key is absent); an error when it is not one. */
ry_status ry_case_count(ry_case *c, const char *path, size_t *n, ry_error *err);

/* RY_ERR_INPUT naming file, line and key of the first key that was never fetched. */
ry_status ry_case_check_unused(ry_case *c, ry_error *err);
/* Writes the resolved parameters (the case as read, with overrides applied and every default
 * that was used filled in) as YAML, atomically (temporary file, then rename). */
ry_status ry_case_write_resolved(ry_case *c, const char *path, ry_error *err);

#endif
