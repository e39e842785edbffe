/* A temporary folder for one test program: created before its tests, removed after them
 * (cmocka group set-up and tear-down). The including file defines RY_TMPDIR_PREFIX. */
#ifndef RYUSHI_TESTS_TMPDIR_H
#define RYUSHI_TESTS_TMPDIR_H

#include <stdio.h>
#include <stdlib.h>

static char tmpdir[256];

static int make_tmpdir(void **state) {
    (void)state;
    snprintf(tmpdir, sizeof tmpdir, "/tmp/%sXXXXXX", RY_TMPDIR_PREFIX);
    return mkdtemp(tmpdir) ? 0 : -1;
}

static int remove_tmpdir(void **state) {
    (void)state;
    char cmd[300];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", tmpdir);
    return system(cmd) == 0 ? 0 : -1;
}

#endif
