/* Fuzz target: bytes -> ry_stl_parse (binary or ASCII, told from the content); a surface that
 * reads is validated (degenerate triangles, closedness, exact and with the default tolerance)
 * and, when closed, filled on a coarse lattice (about 12 spacings across the largest side) as a
 * volume and as a one-layer shell, with at most 20000 particles. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "fuzz/fuzz.h"
#include "ryushi/geometry.h"
#include "ryushi/stl.h"

static void fill(const ry_stl *m, int layers) {
    double w = 0;
    for (int d = 0; d < 3; ++d) w = fmax(w, m->hi[d] - m->lo[d]);
    if (!(w > 0 && isfinite(w))) return;
    ry_particles ps;
    ry_error err;
    ry_error_clear(&err);
    if (ry_particles_init(&ps, 3, &err) != RY_OK) return;
    ry_body_style st = {RY_KIND_FLUID, 0, {0, 0, 0}};
    size_t added = 0;
    ry_status s = ry_fill_stl(&ps, m, w / 12, layers, &st, &added, &err);
    ry_fuzz_expect_clean(s, &err);
    if (s == RY_OK && added != ps.n) abort();
    ry_particles_free(&ps);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    ry_particles_set_limit(RY_FUZZ_MAX_PARTICLES);
    ry_stl m;
    ry_error err;
    ry_error_clear(&err);
    ry_status st = ry_stl_parse(&m, "fuzz.stl", data, size, &err);
    ry_fuzz_expect_clean(st, &err);
    if (st != RY_OK) return 0;
    (void)ry_stl_volume(&m);
    ry_error_clear(&err);
    st = ry_stl_check(&m, 0, &err);
    ry_fuzz_expect_clean(st, &err);
    ry_error_clear(&err);
    st = ry_stl_check(&m, ry_stl_default_tolerance(&m), &err);
    ry_fuzz_expect_clean(st, &err);
    if (st == RY_OK) {
        fill(&m, 0);
        fill(&m, 1);
    }
    ry_stl_free(&m);
    return 0;
}
