/* ryushi — validations as data: one manifest per validation (validation/NAME.yaml) with its
 * name, summary, cases, reference and the tolerances of its checks, read by `ryushi validate`
 * and by the short versions in tests/physics, so that each tolerance lives in one place. */
#ifndef RYUSHI_MANIFEST_H
#define RYUSHI_MANIFEST_H

#include "ryushi/case.h"
#include "ryushi/status.h"

typedef struct ry_manifest {
    char path[4096];
    ry_case *doc;
    const char *name, *summary;
    int in_all; /* run by plain `ryushi validate` */
    long order; /* its place in that run and in --list */
} ry_manifest;

/* Reads root/validation/name.yaml. */
ry_status ry_manifest_load(ry_manifest *m, const char *root, const char *name, ry_error *err);
void ry_manifest_free(ry_manifest *m);
/* Tolerance `key` (tolerances.key, a number); an error names the file and the key. */
ry_status ry_manifest_tol(ry_manifest *m, const char *key, double *value, ry_error *err);
/* Text `key` of the manifest, or def when absent. */
const char *ry_manifest_text(ry_manifest *m, const char *key, const char *def);
/* Item i (from 0) of list `key` of the manifest (a single text counts as a list of one), or
 * NULL past its end or when absent. */
const char *ry_manifest_item(ry_manifest *m, const char *key, int i);
/* Every manifest under root/validation, in their order (*n of them; free each with
 * ry_manifest_free, then the array). */
ry_status ry_manifest_all(const char *root, ry_manifest **all, int *n, ry_error *err);

#endif
