/* Fuzz target: case-file text -> ry_case -> ry_sim_setup (materials, kernel, bodies filled with
 * particles, domain, measurements, profiles, scheme), without running and without writing any
 * file. Particles are limited to 20000 so that no input allocates gigabytes; going beyond is a
 * clean error. The case is named as if it lay in cases/, so `file: geometry/cube.stl` reaches
 * the example STL surfaces. Any failure must be a clean error with a message: an internal error
 * or an empty message aborts (a finding). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz/fuzz.h"
#include "ryushi/case.h"
#include "ryushi/particles.h"
#include "ryushi/sim.h"
#include "ryushi/run.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    ry_particles_set_limit(RY_FUZZ_MAX_PARTICLES);
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    ry_error err;
    ry_error_clear(&err);
    ry_case *c = NULL;
    ry_status st = ry_case_load_string(&c, RY_FUZZ_SOURCE_DIR "/cases/fuzz.yaml", text, &err);
    ry_fuzz_expect_clean(st, &err);
    if (st == RY_OK) {
        ry_sim sim;
        ry_error_clear(&err);
        st = ry_sim_setup(&sim, c, NULL, &err);
        ry_fuzz_expect_clean(st, &err);
        ry_sim_free(&sim);
        ry_case_free(c);
    }
    free(text);
    return 0;
}
