/* Fuzz target: bytes -> ry_ck_open_memory (header, records, lengths, checksum) -> the record
 * index -> ry_sim_checkpoint_load into the small simulation of fuzz/checkpoint_case.yaml
 * (scheme, dimension, materials and fields must fit; counts and values are checked) ->
 * ry_sim_check. Nothing is written. In the libFuzzer build the checksum is not enforced
 * (FUZZING_BUILD_MODE_UNSAFE_FOR_PRODUCTION), so that mutations reach the record parser and the
 * restore; the replay in the test suite checks it as a run does. Any failure must be a clean
 * error with a message. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz/fuzz.h"
#include "ryushi/case.h"
#include "ryushi/checkpoint.h"
#include "ryushi/particles.h"
#include "ryushi/sim.h"
#include "ryushi/run.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    ry_particles_set_limit(RY_FUZZ_MAX_PARTICLES);
    ry_error err;
    ry_error_clear(&err);
    ry_ck_reader r;
    ry_status st = ry_ck_open_memory(&r, "fuzz.ryc", data, size, &err);
    ry_fuzz_expect_clean(st, &err);
    if (st != RY_OK) return 0;
    for (int i = 0; i < r.nrec; ++i) /* every record lies inside the buffer, named and typed */
        if (r.rec[i].data < r.buf || r.rec[i].data > r.buf + r.size || !r.rec[i].name[0] ||
            !ry_ck_find(&r, r.rec[i].name))
            abort();
    ry_case *c = NULL;
    ry_error_clear(&err);
    st = ry_case_load(&c, RY_FUZZ_SOURCE_DIR "/fuzz/checkpoint_case.yaml", &err);
    if (st != RY_OK) abort(); /* the fixed case must load */
    ry_sim sim;
    st = ry_sim_setup(&sim, c, NULL, &err);
    if (st != RY_OK) abort();
    ry_error_clear(&err);
    st = ry_sim_checkpoint_load(&sim, &r, &err);
    ry_fuzz_expect_clean(st, &err);
    if (st == RY_OK) {
        ry_error_clear(&err);
        ry_fuzz_expect_clean(ry_sim_check(&sim, &err), &err);
    }
    ry_sim_free(&sim);
    ry_case_free(c);
    ry_ck_close(&r);
    return 0;
}
