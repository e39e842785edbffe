/* The tolerances of the validations' manifests (validation/NAME.yaml), for the short versions
 * in tests/physics: each stated once, there. Include after cmocka.h. */
#ifndef RYUSHI_TESTS_MANIFEST_TOL_H
#define RYUSHI_TESTS_MANIFEST_TOL_H

#include <math.h>
#include <stdio.h>

#include "ryushi/manifest.h"

/* Tolerance `key` of validation/name.yaml under the project folder; fails the test when
 * the manifest or the key is missing. */
static inline double manifest_tol(const char *project, const char *name, const char *key) {
    ry_manifest m;
    ry_error err = {0};
    double v = NAN;
    if (ry_manifest_load(&m, project, name, &err) == RY_OK) {
        if (ry_manifest_tol(&m, key, &v, &err) != RY_OK) v = NAN;
        ry_manifest_free(&m);
    }
    if (isnan(v)) fprintf(stderr, "%s\n", err.msg);
    assert_false(isnan(v));
    return v;
}

#endif
