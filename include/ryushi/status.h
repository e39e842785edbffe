/* ryushi — status codes and error context.
 *
 * Every library function that can fail returns an ry_status and, on failure, fills an
 * ry_error with a message that carries its context (file, line, key, particle id). The
 * library never prints and never exits; the command-line program reports the message. */
#ifndef RYUSHI_STATUS_H
#define RYUSHI_STATUS_H

#include <stdarg.h>

typedef enum ry_status {
    RY_OK = 0,
    RY_ERR_NOMEM,       /* an allocation failed */
    RY_ERR_INPUT,       /* bad input: case file, command line, data file */
    RY_ERR_IO,          /* a file could not be read or written */
    RY_ERR_RANGE,       /* a value outside its allowed range */
    RY_ERR_UNSTABLE,    /* the simulation went unstable (NaN, particles leaving the domain) */
    RY_ERR_INTERRUPTED, /* the run was interrupted (SIGINT/SIGTERM) */
    RY_ERR_INTERNAL     /* a broken invariant: a bug */
} ry_status;

enum { RY_ERROR_MSG_MAX = 1024 };

typedef struct ry_error {
    ry_status code;
    char msg[RY_ERROR_MSG_MAX];
} ry_error;

/* Records code and a printf-style message in err (err may be NULL); returns code. */
ry_status ry_error_set(ry_error *err, ry_status code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
ry_status ry_error_vset(ry_error *err, ry_status code, const char *fmt, va_list ap);
/* Prefixes the message already in err with more context ("while reading X: ..."). */
void ry_error_prefix(ry_error *err, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
void ry_error_clear(ry_error *err);
/* A short name for a status code ("input error", ...). */
const char *ry_status_name(ry_status code);
/* The process exit code the command-line program uses for a status (2 for bad input). */
int ry_status_exit_code(ry_status code);

/* A malloc'd copy of s (NULL when out of memory). */
char *ry_strdup(const char *s);

/* Propagates a failing status to the caller. */
#define RY_TRY(call)                                                                               \
    do {                                                                                           \
        ry_status ry_try_status_ = (call);                                                         \
        if (ry_try_status_ != RY_OK) return ry_try_status_;                                        \
    } while (0)

/* Returns code with a formatted message when cond does not hold. */
#define RY_CHECK(err, cond, code, ...)                                                             \
    do {                                                                                           \
        if (!(cond)) return ry_error_set((err), (code), __VA_ARGS__);                              \
    } while (0)

#endif
