/* A case file loaded, overridden, set up and run in one call. */
#include <string.h>

#include "ryushi/run.h"

ry_status ry_setup_case_file(const char *path, int nset, const char *const *sets,
                             const char *out_dir, ry_sim *sim, ry_error *err) {
    ry_case *c = NULL;
    memset(sim, 0, sizeof *sim);
    ry_status st = ry_case_load(&c, path, err);
    for (int i = 0; i < nset && st == RY_OK; ++i) st = ry_case_override(c, sets[i], err);
    if (st == RY_OK) st = ry_sim_setup(sim, c, out_dir, err);
    if (st == RY_OK) st = ry_sim_open_output(sim, c, err);
    ry_case_free(c);
    if (st != RY_OK) ry_sim_free(sim);
    return st;
}

ry_status ry_run_case_file(const char *path, int nset, const char *const *sets, const char *out_dir,
                           ry_sim *sim, ry_run_stats *stats, ry_error *err) {
    RY_TRY(ry_setup_case_file(path, nset, sets, out_dir, sim, err));
    const ry_status st = ry_run(sim, NULL, stats, err);
    if (st != RY_OK) ry_sim_free(sim);
    return st;
}
