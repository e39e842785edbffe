/* The scheme registry: every scheme a case can name in `scheme.name`. */
#include <string.h>

#include "ryushi/schemes.h"
#include "schemes/mps/mps.h"
#include "schemes/solid/solid.h"
#include "schemes/iisph/iisph.h"
#include "schemes/wcsph/wcsph.h"

/* "static": particles stay where they are (for setting up and inspecting geometry). */
static ry_status static_init(ry_sim *sim, ry_case *c, void **state, ry_error *err) {
    (void)sim;
    (void)c;
    (void)err;
    *state = NULL;
    return RY_OK;
}
static ry_status static_dt(ry_sim *sim, void *state, double *dt, ry_error *err) {
    (void)state;
    (void)err;
    *dt = sim->output_interval;
    return RY_OK;
}
static ry_status static_step(ry_sim *sim, void *state, double dt, ry_error *err) {
    (void)sim;
    (void)state;
    (void)dt;
    (void)err;
    return RY_OK;
}
static void static_free(void *state) {
    (void)state;
}

static const ry_scheme_type scheme_static = {
    .name = "static",
    .summary = "particles do not move (geometry set-up and output only)",
    .init = static_init,
    .stable_dt = static_dt,
    .step = static_step,
    .free = static_free,
    .caps = 0};

static const ry_scheme_type *const all_schemes[] = {
    &ry_scheme_wcsph, &ry_scheme_iisph, &ry_scheme_mps, &ry_scheme_solid, &scheme_static, NULL};

const ry_scheme_type *const *ry_schemes(void) {
    return all_schemes;
}

const ry_scheme_type *ry_scheme_find(const char *name) {
    for (int i = 0; all_schemes[i]; ++i)
        if (strcmp(all_schemes[i]->name, name) == 0) return all_schemes[i];
    return NULL;
}
