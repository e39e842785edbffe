/* Status codes and error messages (see include/ryushi/status.h). */
#include "ryushi/status.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

ry_status ry_error_vset(ry_error *err, ry_status code, const char *fmt, va_list ap) {
    if (err) {
        err->code = code;
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    }
    return code;
}

ry_status ry_error_set(ry_error *err, ry_status code, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    ry_error_vset(err, code, fmt, ap);
    va_end(ap);
    return code;
}

void ry_error_prefix(ry_error *err, const char *fmt, ...) {
    if (!err) return;
    char head[RY_ERROR_MSG_MAX], old[RY_ERROR_MSG_MAX];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(head, sizeof head, fmt, ap);
    va_end(ap);
    memcpy(old, err->msg, sizeof old);
    size_t n = strlen(head);
    if (n >= sizeof err->msg) n = sizeof err->msg - 1;
    memcpy(err->msg, head, n);
    size_t m = strlen(old);
    if (m > sizeof err->msg - 1 - n) m = sizeof err->msg - 1 - n;
    memcpy(err->msg + n, old, m);
    err->msg[n + m] = '\0';
}

void ry_error_clear(ry_error *err) {
    if (!err) return;
    err->code = RY_OK;
    err->msg[0] = '\0';
}

const char *ry_status_name(ry_status code) {
    switch (code) {
    case RY_OK:
        return "ok";
    case RY_ERR_NOMEM:
        return "out of memory";
    case RY_ERR_INPUT:
        return "input error";
    case RY_ERR_IO:
        return "i/o error";
    case RY_ERR_RANGE:
        return "value out of range";
    case RY_ERR_UNSTABLE:
        return "simulation unstable";
    case RY_ERR_INTERRUPTED:
        return "interrupted";
    case RY_ERR_INTERNAL:
        return "internal error";
    }
    return "unknown error";
}

int ry_status_exit_code(ry_status code) {
    switch (code) {
    case RY_OK:
        return 0;
    case RY_ERR_INPUT:
    case RY_ERR_RANGE:
        return 2;
    case RY_ERR_IO:
        return 3;
    case RY_ERR_UNSTABLE:
        return 4;
    case RY_ERR_INTERRUPTED:
        return 130;
    case RY_ERR_NOMEM:
    case RY_ERR_INTERNAL:
        return 1;
    }
    return 1;
}

char *ry_strdup(const char *s) {
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}
