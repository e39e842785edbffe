/* ryushi — numeric CSV tables with one header row (reference data, series.csv). */
#ifndef RYUSHI_CSV_H
#define RYUSHI_CSV_H

#include <stddef.h>

#include "ryushi/status.h"

typedef struct ry_table {
    int ncols;
    size_t nrows;
    char **names; /* ncols column names */
    double *data; /* row-major nrows x ncols */
} ry_table;

/* Reads a CSV file of numbers with a header row; errors name the file, line and column. An
 * empty field reads as NAN (not recorded: the earlier rows of a series after a restart that
 * added a measurement). */
ry_status ry_table_read(ry_table *t, const char *path, ry_error *err);
void ry_table_free(ry_table *t);
/* Column index by name, -1 when absent. */
int ry_table_col(const ry_table *t, const char *name);
static inline double ry_table_at(const ry_table *t, size_t row, int col) {
    return t->data[row * (size_t)t->ncols + (size_t)col];
}
/* Copies a column into a new array (caller frees). */
double *ry_table_column(const ry_table *t, int col);
/* Linear interpolation of y(x) at xq for x ascending; NAN outside [x0, xn]. */
double ry_interp_linear(const double *x, const double *y, size_t n, double xq);

#endif
