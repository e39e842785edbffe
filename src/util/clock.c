/* The wall clock. */
#define _POSIX_C_SOURCE 200809L
#include <time.h>

#include "ryushi/clock.h"

double ry_wall_time(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
