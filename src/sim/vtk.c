/* VTK XML PolyData writer with raw appended binary arrays, and the .pvd collection. */
#include <errno.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/atomic_file.h"
#include "ryushi/output.h"

typedef enum { T_F64, T_I64, T_U8 } vtk_type;

typedef struct vtk_array {
    const char *name;
    vtk_type type;
    int ncomp;
    /* Source: either component arrays of doubles, or a typed array. */
    const double *comp[3];
    const void *data;
    int iota; /* 1: 0..n-1 (connectivity), 2: 1..n (offsets) */
} vtk_array;

static const char *type_name(vtk_type t) {
    return t == T_F64 ? "Float64" : t == T_I64 ? "Int64" : "UInt8";
}
static size_t type_size(vtk_type t) {
    return t == T_U8 ? 1 : 8;
}

static void header_array(FILE *fp, const vtk_array *a, uint64_t *offset, size_t n) {
    fprintf(fp,
            "        <DataArray type=\"%s\" Name=\"%s\" NumberOfComponents=\"%d\" "
            "format=\"appended\" offset=\"%llu\"/>\n",
            type_name(a->type), a->name, a->ncomp, (unsigned long long)*offset);
    *offset += sizeof(uint64_t) + (uint64_t)n * a->ncomp * type_size(a->type);
}

/* Writes array a of the n particles idx[0..n-1] (all particles when idx is NULL). */
static int write_array(FILE *fp, const vtk_array *a, size_t n, const size_t *idx, void *buf,
                       size_t chunk) {
    uint64_t bytes = (uint64_t)n * a->ncomp * type_size(a->type);
    if (fwrite(&bytes, sizeof bytes, 1, fp) != 1) return -1;
    if (a->iota) {
        int64_t *b = buf;
        for (size_t i0 = 0; i0 < n; i0 += chunk) {
            size_t m = n - i0 < chunk ? n - i0 : chunk;
            for (size_t i = 0; i < m; ++i) b[i] = (int64_t)(i0 + i) + (a->iota == 2);
            if (fwrite(b, sizeof *b, m, fp) != m) return -1;
        }
        return 0;
    }
    if (a->data && !idx) {
        size_t sz = type_size(a->type);
        return n && fwrite(a->data, sz, n, fp) != n ? -1 : 0;
    }
    if (a->data) { /* a subset of a typed array, through the buffer */
        const size_t sz = type_size(a->type);
        unsigned char *b = buf;
        for (size_t i0 = 0; i0 < n; i0 += chunk) {
            size_t m = n - i0 < chunk ? n - i0 : chunk;
            for (size_t i = 0; i < m; ++i)
                memcpy(b + i * sz, (const unsigned char *)a->data + idx[i0 + i] * sz, sz);
            if (fwrite(b, sz, m, fp) != m) return -1;
        }
        return 0;
    }
    /* Interleave components, zero-filling missing ones (z in 2D). */
    double *b = buf;
    for (size_t i0 = 0; i0 < n; i0 += chunk) {
        size_t m = n - i0 < chunk ? n - i0 : chunk;
        for (size_t i = 0; i < m; ++i)
            for (int c = 0; c < a->ncomp; ++c)
                b[i * a->ncomp + c] = a->comp[c] ? a->comp[c][idx ? idx[i0 + i] : i0 + i] : 0.0;
        if (fwrite(b, sizeof(double) * a->ncomp, m, fp) != m) return -1;
    }
    return 0;
}

enum { MAX_ARRAYS = 256 };

/* The point data written for a set: velocity, pressure, density, mass, kind, material, id and
 * every field flagged RY_FIELD_OUTPUT; returns how many. */
static int point_data(const ry_particles *ps, vtk_array *pd) {
    const int dim = ps->dim;
    int npd = 0;
    pd[npd++] = (vtk_array){
        "velocity",
        T_F64,
        3,
        {ps->f[RY_F_VX], dim > 1 ? ps->f[RY_F_VY] : NULL, dim > 2 ? ps->f[RY_F_VZ] : NULL},
        NULL,
        0};
    pd[npd++] = (vtk_array){"pressure", T_F64, 1, {ps->f[RY_F_P]}, NULL, 0};
    pd[npd++] = (vtk_array){"density", T_F64, 1, {ps->f[RY_F_RHO]}, NULL, 0};
    pd[npd++] = (vtk_array){"mass", T_F64, 1, {ps->f[RY_F_MASS]}, NULL, 0};
    pd[npd++] = (vtk_array){"kind", T_U8, 1, {NULL}, ps->kind, 0};
    pd[npd++] = (vtk_array){"material", T_U8, 1, {NULL}, ps->material, 0};
    pd[npd++] = (vtk_array){"id", T_I64, 1, {NULL}, ps->id, 0};
    for (int k = 0; k < ps->nfields && npd < MAX_ARRAYS; ++k)
        if ((ps->info[k].flags & RY_FIELD_OUTPUT) && ps->f[k])
            pd[npd++] = (vtk_array){ps->info[k].name, T_F64, 1, {ps->f[k]}, NULL, 0};
    return npd;
}

static ry_status write_vtp(const char *path, const ry_particles *ps, const uint8_t *skip,
                           double time, ry_error *err) {
    const int dim = ps->dim;
    vtk_array pts = {
        "Points", T_F64,
        3,        {ps->f[RY_F_X], dim > 1 ? ps->f[RY_F_Y] : NULL, dim > 2 ? ps->f[RY_F_Z] : NULL},
        NULL,     0};
    vtk_array pd[MAX_ARRAYS];
    const int npd = point_data(ps, pd);
    size_t n = ps->n, *idx = NULL;
    if (skip) {
        idx = malloc((ps->n ? ps->n : 1) * sizeof *idx);
        RY_CHECK(err, idx != NULL, RY_ERR_NOMEM, "out of memory (writing '%s')", path);
        n = 0;
        for (size_t i = 0; i < ps->n; ++i)
            if (!skip[i]) idx[n++] = i;
    }
    ry_status st = RY_OK;
    vtk_array conn = {"connectivity", T_I64, 1, {NULL}, NULL, 1};
    vtk_array offs = {"offsets", T_I64, 1, {NULL}, NULL, 2};

    ry_atomic_file f;
    st = ry_atomic_open(&f, path, err);
    if (st != RY_OK) {
        free(idx);
        return st;
    }
    FILE *fp = f.fp;
    uint64_t off = 0;
    fprintf(fp, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" "
                "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <PolyData>\n");
    fprintf(fp,
            "    <FieldData>\n      <DataArray type=\"Float64\" Name=\"TimeValue\" "
            "NumberOfTuples=\"1\" format=\"ascii\">%.17g</DataArray>\n    </FieldData>\n",
            time);
    fprintf(fp, "    <Piece NumberOfPoints=\"%zu\" NumberOfVerts=\"%zu\">\n", n, n);
    fprintf(fp, "      <PointData Scalars=\"pressure\" Vectors=\"velocity\">\n");
    for (int a = 0; a < npd; ++a) header_array(fp, &pd[a], &off, n);
    fprintf(fp, "      </PointData>\n      <Points>\n");
    header_array(fp, &pts, &off, n);
    fprintf(fp, "      </Points>\n      <Verts>\n");
    header_array(fp, &conn, &off, n);
    header_array(fp, &offs, &off, n);
    fprintf(fp,
            "      </Verts>\n    </Piece>\n  </PolyData>\n  <AppendedData encoding=\"raw\">\n_");
    size_t chunk = 4096;
    void *buf = malloc(chunk * 3 * sizeof(double));
    int bad = buf == NULL;
    for (int a = 0; a < npd && !bad; ++a) bad = write_array(fp, &pd[a], n, idx, buf, chunk) != 0;
    if (!bad) bad = write_array(fp, &pts, n, idx, buf, chunk) != 0;
    if (!bad) bad = write_array(fp, &conn, n, NULL, buf, chunk) != 0;
    if (!bad) bad = write_array(fp, &offs, n, NULL, buf, chunk) != 0;
    int e = errno, oom = buf == NULL;
    free(buf);
    free(idx);
    if (bad) {
        ry_atomic_abort(&f);
        return ry_error_set(err, RY_ERR_IO, "writing '%s' failed: %s", path,
                            oom ? "out of memory" : strerror(e));
    }
    fprintf(fp, "\n  </AppendedData>\n</VTKFile>\n");
    return ry_atomic_commit(&f, err);
}

ry_status ry_vtk_write_particles(const char *path, const ry_particles *ps, double time,
                                 ry_error *err) {
    return write_vtp(path, ps, NULL, time, err);
}

ry_status ry_vtk_write_piece(const char *path, const ry_particles *ps, const uint8_t *skip,
                             double time, ry_error *err) {
    return write_vtp(path, ps, skip, time, err);
}

ry_status ry_pvtp_write(const char *path, const ry_particles *ps, int npieces, const char *dir,
                        double time, ry_error *err) {
    vtk_array pd[MAX_ARRAYS];
    const int npd = point_data(ps, pd);
    ry_atomic_file f;
    RY_TRY(ry_atomic_open(&f, path, err));
    FILE *fp = f.fp;
    fprintf(fp, "<?xml version=\"1.0\"?>\n<VTKFile type=\"PPolyData\" version=\"1.0\" "
                "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n"
                "  <PPolyData GhostLevel=\"0\">\n");
    fprintf(fp,
            "    <FieldData>\n      <DataArray type=\"Float64\" Name=\"TimeValue\" "
            "NumberOfTuples=\"1\" format=\"ascii\">%.17g</DataArray>\n    </FieldData>\n",
            time);
    fprintf(fp, "    <PPointData Scalars=\"pressure\" Vectors=\"velocity\">\n");
    for (int a = 0; a < npd; ++a)
        fprintf(fp, "      <PDataArray type=\"%s\" Name=\"%s\" NumberOfComponents=\"%d\"/>\n",
                type_name(pd[a].type), pd[a].name, pd[a].ncomp);
    fprintf(fp, "    </PPointData>\n    <PPoints>\n      <PDataArray type=\"Float64\" "
                "NumberOfComponents=\"3\"/>\n    </PPoints>\n");
    for (int r = 0; r < npieces; ++r)
        fprintf(fp, "    <Piece Source=\"%s/piece_%04d.vtp\"/>\n", dir, r);
    fprintf(fp, "  </PPolyData>\n</VTKFile>\n");
    return ry_atomic_commit(&f, err);
}

ry_status ry_pvd_write(const char *path, int n, char *const *files, const double *times,
                       ry_error *err) {
    ry_atomic_file f;
    RY_TRY(ry_atomic_open(&f, path, err));
    fprintf(f.fp, "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" "
                  "byte_order=\"LittleEndian\">\n  <Collection>\n");
    for (int i = 0; i < n; ++i)
        fprintf(f.fp, "    <DataSet timestep=\"%.9g\" group=\"\" part=\"0\" file=\"%s\"/>\n",
                times[i], files[i]);
    fprintf(f.fp, "  </Collection>\n</VTKFile>\n");
    return ry_atomic_commit(&f, err);
}
