/* Neighbour-search benchmark: bench_neighbors [N ...] (default 1e3 1e4 1e5 1e6), 2D and 3D. */
#include <stdio.h>
#include <stdlib.h>

#include "ryushi/bench.h"

int main(int argc, char **argv) {
    size_t ns[32] = {1000, 10000, 100000, 1000000};
    int count = 4;
    if (argc > 1) {
        count = 0;
        for (int a = 1; a < argc && count < 32; ++a) {
            char *end;
            double v = strtod(argv[a], &end);
            if (*end != '\0' || !(v >= 1.0 && v <= 4e9)) {
                fprintf(stderr, "bench_neighbors: bad particle count '%s'\n", argv[a]);
                return 2;
            }
            ns[count++] = (size_t)v;
        }
    }
    for (int dim = 2; dim <= 3; ++dim) {
        ry_error err = {0};
        if (ry_bench_neighbors(stdout, dim, ns, count, &err) != RY_OK) {
            fprintf(stderr, "bench_neighbors: %s\n", err.msg);
            return ry_status_exit_code(err.code);
        }
        if (dim == 2) printf("\n");
    }
    return 0;
}
