/* ryushi bench: throughput of the neighbour search and of the WCSPH dam break. */
#define _POSIX_C_SOURCE 200809L
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"
#include "ryushi/bench.h"
#include "ryushi/sim.h"
#include "ryushi/run.h"

/* The seed dam break (cases/dam_break_seed.yaml) in 2D or extruded in 3D, without output. */
static int dam_break_text(char *buf, size_t size, int dim, double dx, long steps) {
    if (dim == 2)
        return snprintf(
            buf, size,
            "dimension: 2\nspacing: %.17g\nkernel: {type: wendland_c2, h_over_dx: 1.4}\n"
            "gravity: [0, -9.81]\nmaterials: [{name: water, density: 1000, viscosity: 1e-6}]\n"
            "bodies:\n  - {type: box, lo: [0, 0], hi: [0.25, 0.5]}\n"
            "  - {type: tank, lo: [0, 0], hi: [1.0, 0.55], layers: 3, open_top: true}\n"
            "domain: {lo: [-0.1, -0.1], hi: [1.1, 1.5]}\n"
            "scheme: {name: wcsph, sound_speed: 30, artificial_viscosity: {alpha: 0.02}, "
            "density_diffusion: fourtakas, hydrostatic_init: true, wall_repulsion_radius: 0.9}\n"
            "time: {end: 10, cfl: 0.3, max_steps: %ld, output_interval: 100}\n"
            "output: {vtk: false}\n",
            dx, steps);
    return snprintf(
        buf, size,
        "dimension: 3\nspacing: %.17g\nkernel: {type: wendland_c2, h_over_dx: 1.4}\n"
        "gravity: [0, 0, -9.81]\nmaterials: [{name: water, density: 1000, viscosity: 1e-6}]\n"
        "bodies:\n  - {type: box, lo: [0, 0, 0], hi: [0.25, 0.25, 0.5]}\n"
        "  - {type: tank, lo: [0, 0, 0], hi: [1.0, 0.25, 0.55], layers: 3, open_top: true}\n"
        "domain: {lo: [-0.1, -0.1, -0.1], hi: [1.1, 0.35, 1.5]}\n"
        "scheme: {name: wcsph, sound_speed: 30, artificial_viscosity: {alpha: 0.02}, "
        "density_diffusion: fourtakas, hydrostatic_init: true, wall_repulsion_radius: 0.9}\n"
        "time: {end: 10, cfl: 0.3, max_steps: %ld, output_interval: 100}\n"
        "output: {vtk: false}\n",
        dx, steps);
}

/* One timed run; returns particle-steps/s (0 on failure, with the message printed). */
static double bench_once(int dim, double dx, long steps, const char *out_dir, size_t *np,
                         double *bpp) {
    char text[2048];
    dam_break_text(text, sizeof text, dim, dx, steps);
    ry_error err = {0};
    ry_case *c = NULL;
    ry_sim sim;
    memset(&sim, 0, sizeof sim);
    ry_run_stats stats = {0};
    ry_status st = ry_case_load_string(&c, "bench_dam_break", text, &err);
    if (st == RY_OK) st = ry_sim_setup(&sim, c, out_dir, &err);
    if (st == RY_OK) st = ry_sim_open_output(&sim, c, &err);
    sim.ckpt.at_end = 0; /* throughput only: no checkpoint of the final state */
    if (st == RY_OK) st = ry_run(&sim, NULL, &stats, &err);
    if (st != RY_OK) fprintf(stderr, "ryushi: bench: %s\n", err.msg);
    *np = sim.ps.n;
    *bpp = ry_sim_bytes_per_particle(&sim);
    ry_sim_free(&sim);
    ry_case_free(c);
    return st == RY_OK ? stats.particle_steps_per_s : 0.0;
}

static int cmp_double(const void *a, const void *b) {
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static int bench_sph(int quick, int max_threads) {
    /* Steps so that each run is at least 1e7 particle-steps (about a second at 1e7
     * particle-steps/s): shorter runs measure start-up and scheduler noise. */
    struct {
        int dim;
        double dx;
        long steps;
        const char *label;
    } sizes[] = {{2, 0.00625, 2400, "2D dam break 40x80"},
                 {2, 0.00145, 160, "2D dam break 172x344"},
                 {2, 0.0007, 40, "2D dam break 357x714"},
                 {3, 0.0068, 200, "3D dam break 36x36x73"}};
    int nsizes = quick ? 1 : 4;
    int reps = quick ? 1 : 3;
    char dir[] = "/tmp/ryushi_bench_XXXXXX";
    if (!mkdtemp(dir)) {
        fprintf(stderr, "ryushi: bench: cannot create a temporary folder\n");
        return 3;
    }
    printf("# WCSPH dam break throughput (all particles, fluid and wall, x steps / wall s);\n"
           "# median of %d runs; machine: %ld online processors\n",
           reps, sysconf(_SC_NPROCESSORS_ONLN));
    printf("%-24s %10s %8s %7s %8s %16s\n", "case", "particles", "steps", "threads", "B/part",
           "particle_steps/s");
    for (int s = 0; s < nsizes; ++s) {
        size_t np = 0;
        double bpp = 0;
        const long steps = quick ? 20 : sizes[s].steps;
        double base = 0;
        for (int t = 1; t <= max_threads; t *= 2) {
            omp_set_num_threads(t);
            double r[8];
            for (int k = 0; k < reps; ++k)
                r[k] = bench_once(sizes[s].dim, sizes[s].dx, steps, dir, &np, &bpp);
            qsort(r, (size_t)reps, sizeof *r, cmp_double);
            double med = r[reps / 2];
            if (t == 1) base = med;
            printf("%-24s %10zu %8ld %7d %8.0f %16.4g", sizes[s].label, np, steps, t, bpp, med);
            if (t > 1 && base > 0) printf("  speed-up %.2fx", med / base);
            printf("\n");
            fflush(stdout);
        }
    }
    char path[64];
    snprintf(path, sizeof path, "%s/series.csv", dir);
    remove(path);
    snprintf(path, sizeof path, "%s/case_resolved.yaml", dir);
    remove(path);
    rmdir(dir);
    return 0;
}

int ry_cli_bench(int argc, char **argv) {
    const char *what = "sph";
    int quick = 0, threads = omp_get_max_threads();
    for (int i = 2; i < argc; ++i) {
        if (strcmp(argv[i], "--quick") == 0)
            quick = 1;
        else if (strcmp(argv[i], "--threads") == 0 && i + 1 < argc)
            threads = atoi(argv[++i]);
        else if (argv[i][0] != '-')
            what = argv[i];
        else {
            fprintf(stderr, "ryushi: bench: unknown option '%s'\n", argv[i]);
            return 2;
        }
    }
    if (threads < 1) threads = 1;
    if (strcmp(what, "neighbors") == 0) {
        size_t all[] = {1000, 10000, 100000, 1000000};
        omp_set_num_threads(threads);
        ry_error err = {0};
        for (int dim = 2; dim <= 3; ++dim)
            if (ry_bench_neighbors(stdout, dim, all, quick ? 2 : 4, &err) != RY_OK) {
                fprintf(stderr, "ryushi: bench: %s\n", err.msg);
                return ry_status_exit_code(err.code);
            }
        return 0;
    }
    if (strcmp(what, "sph") == 0) return bench_sph(quick, threads);
    fprintf(stderr, "ryushi: bench: expected 'sph' or 'neighbors', got '%s'\n", what);
    return 2;
}
