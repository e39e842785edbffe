/* Shared by the fuzz targets (fuzz/fuzz_*.c). Each target defines LLVMFuzzerTestOneInput; built
 * with -DRY_FUZZ=ON it links libFuzzer, otherwise fuzz/replay.c drives it over files (the seed
 * corpus and fuzz/regressions/) in the ordinary test suite. */
#ifndef RYUSHI_FUZZ_H
#define RYUSHI_FUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

#include "ryushi/status.h"

enum { RY_FUZZ_MAX_PARTICLES = 20000 };

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* A failure must be a clean error: a message, a code that matches, and no internal error. */
static inline void ry_fuzz_expect_clean(ry_status st, const ry_error *err) {
    if (st == RY_OK) return;
    if (st == RY_ERR_INTERNAL || err->code != st || err->msg[0] == '\0') {
        fprintf(stderr, "unclean failure: status %d, error code %d, message '%s'\n", (int)st,
                (int)err->code, err->msg);
        abort();
    }
}

#endif
