/* ryushi — STL surfaces (triangle meshes), ASCII and binary.
 *
 * Reading: the format is detected from the content, not the file name. A file whose size is
 * 84 + 50 n bytes, where n is the triangle count in bytes 80..83, is binary even when its header
 * starts with "solid" (many exporters write that), unless every byte is printable text; a file
 * that starts with "solid" otherwise is ASCII. Hard limits (RY_STL_MAX_BYTES, RY_STL_MAX_TRIANGLES)
 * keep an absurd file from exhausting memory. Every error names the file and, for ASCII, the line
 * ("mesh.stl:12: expected 'vertex', got 'vertx'"), for binary the triangle and its byte offset,
 * and what was expected. Non-finite coordinates are errors at reading.
 *
 * Validation (ry_stl_check): no degenerate triangle (zero area), and a closed surface: after
 * merging vertices that coincide within a tolerance, every edge is shared by exactly two
 * triangles that run along it in opposite directions (a watertight, consistently oriented
 * surface). The first offending edge in file order is reported with its position. */
#ifndef RYUSHI_STL_H
#define RYUSHI_STL_H

#include <stddef.h>

#include "ryushi/status.h"

#define RY_STL_MAX_BYTES ((size_t)1 << 30) /* 1 GiB */
enum { RY_STL_MAX_TRIANGLES = 20000000 };

typedef struct ry_stl {
    char *name;   /* file name for messages */
    size_t ntri;  /* triangles */
    double *v;    /* 9 per triangle: vertices a, b, c, each x, y, z */
    int *line;    /* ASCII: line of each triangle's 'facet'; NULL for binary */
    int binary;   /* 1 when read from a binary file */
    double lo[3]; /* bounding box */
    double hi[3];
} ry_stl;

/* Parses an STL held in memory; name stands for the file in messages. */
ry_status ry_stl_parse(ry_stl *m, const char *name, const void *data, size_t size, ry_error *err);
/* Reads an STL file (a regular file of at most RY_STL_MAX_BYTES). */
ry_status ry_stl_read(ry_stl *m, const char *path, ry_error *err);
/* Writes an STL file, binary or ASCII, atomically. */
ry_status ry_stl_write(const ry_stl *m, const char *path, int binary, ry_error *err);
void ry_stl_free(ry_stl *m);

/* Sets the triangles (9 doubles each, copied); for building meshes in code. */
ry_status ry_stl_from_triangles(ry_stl *m, const char *name, const double *v, size_t ntri,
                                ry_error *err);
/* x -> scale x + translate (translate may be NULL), bounding box updated. */
void ry_stl_transform(ry_stl *m, double scale, const double *translate);
/* Signed enclosed volume (divergence theorem): positive for outward-facing triangles. */
double ry_stl_volume(const ry_stl *m);
/* Where triangle t came from: "mesh.stl:12" (ASCII) or "mesh.stl: triangle 3 (byte 234)". */
const char *ry_stl_where(const ry_stl *m, size_t t, char *buf, size_t size);

/* Degenerate triangles and closedness, vertices merged within tol (a length; 0: exact). */
ry_status ry_stl_check(const ry_stl *m, double tol, ry_error *err);
/* The merge tolerance used for bodies: 1e-6 of the bounding-box diagonal. */
double ry_stl_default_tolerance(const ry_stl *m);

#endif
