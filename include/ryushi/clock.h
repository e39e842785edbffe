/* ryushi — the wall clock. */
#ifndef RYUSHI_CLOCK_H
#define RYUSHI_CLOCK_H

/* Monotonic wall clock in seconds. */
double ry_wall_time(void);

#endif
