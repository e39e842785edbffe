/* The ryushi command-line program: run, info, bench, validate, plot. */
#define _POSIX_C_SOURCE 200809L
#include <omp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

#include "cli/cli.h"
#include "ryushi/case.h"
#include "ryushi/checkpoint.h"
#include "ryushi/probes.h"
#include "ryushi/ryushi.h"
#include "ryushi/run.h"
#include "ryushi/schemes.h"
#include "ryushi/sim.h"
#ifdef RY_MPI_CLI
#include "parallel/mpi_dd.h"
#endif

static volatile sig_atomic_t stop_requested = 0;

static void on_signal(int sig) {
    (void)sig;
    stop_requested = 1;
}

/* SIGINT and SIGTERM end a run cleanly (a checkpoint is written); a file-size limit reached is
 * a write error to report (like a full disk), not a kill. */
static void catch_signals_with(void (*handler)(int)) {
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = handler;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    signal(SIGXFSZ, SIG_IGN);
}

#ifdef RY_MPI_CLI
static void catch_signals(void) {
    catch_signals_with(on_signal);
}
#endif

/* The program's commands: how each is called and what it does (`ryushi help COMMAND`). */
static const struct command_help {
    const char *name, *synopsis, *text;
} commands[] = {
    {"run", "ryushi run CASE [-o DIR] [--threads N] [--set KEY=VALUE]... [--restart DIR]",
     "run a case file; output (VTK .vtp/.pvd, series.csv, case_resolved.yaml,\n"
     "checkpoints/) goes to DIR (default: the case's output.folder);\n"
     "--restart continues from the newest sound checkpoint in DIR"},
    {"checkpoint", "ryushi checkpoint FILE",
     "check a checkpoint file (checksum) and list its records"},
    {"info", "ryushi info CASE [--set KEY=VALUE]...",
     "set the case up and report particles, memory and methods without running"},
    {"validate", "ryushi validate [NAME | all] [--quick] [-o DIR] [--threads N]",
     "run the validation cases against their references, with plots (default output\n"
     "folder out/validate); --list names them, --report writes the report\n"
     "(ryushi validate --help)"},
    {"bench", "ryushi bench [sph | neighbors] [--quick] [--threads N]",
     "sph: WCSPH dam-break throughput (particle-steps/s) at 4k to 250k particles;\n"
     "neighbors: cell list against brute-force neighbour search, N = 1e3 .. 1e6"},
    {"plot", "ryushi plot kernels -o FILE.png",
     "the Lucy and Gaussian kernels and their derivatives (seed 000)"},
    {"schemes", "ryushi schemes", "list the schemes a case can name (scheme.name)"},
    {"probes", "ryushi probes", "list the measured quantities a case can name (measure)"},
    {"help", "ryushi help [COMMAND]", "this text, or one command's (also ryushi COMMAND --help)"},
};
enum { NCOMMANDS = sizeof commands / sizeof commands[0] };

static const char *const set_help =
    "KEY is a dotted path into the case file, e.g. --set time.end=0.3 or\n"
    "--set bodies[0].hi=[0.25,0.5]. Exit codes: 0 success, 1 internal error,\n"
    "2 bad input, 3 i/o error, 4 unstable run, 130 interrupted.\n"
    "RY_MAX_PARTICLES=N in the environment limits the particles of a case (an error\n"
    "beyond it, exit code 2).\n";

/* A command's text, indented by 8 after each line break. */
static void print_command(FILE *fp, const struct command_help *c, const char *indent) {
    fprintf(fp, "  %s\n%s", c->synopsis, indent);
    for (const char *t = c->text; *t; ++t) {
        fputc(*t, fp);
        if (*t == '\n') fputs(indent, fp);
    }
    fputc('\n', fp);
}

static void usage(FILE *fp) {
    fprintf(fp,
            "ryushi %s — meshfree particle methods (SPH, MPS) for fluids and soft solids\n"
            "\nusage:\n",
            RY_VERSION);
    for (int k = 0; k < NCOMMANDS; ++k) print_command(fp, &commands[k], "        ");
    fprintf(fp, "  ryushi --help | --version\n\n%s", set_help);
}

/* `ryushi help COMMAND`: its synopsis and text; 2 for an unknown command. */
static int command_help(const char *name) {
    for (int k = 0; k < NCOMMANDS; ++k)
        if (strcmp(commands[k].name, name) == 0) {
            printf("usage:\n");
            print_command(stdout, &commands[k], "  ");
            if (strcmp(name, "run") == 0 || strcmp(name, "info") == 0) printf("\n%s", set_help);
            return 0;
        }
    fprintf(stderr, "ryushi: no command '%s' (see ryushi --help)\n", name);
    return 2;
}

static int fail(const ry_error *err) {
    fprintf(stderr, "ryushi: %s: %s\n", ry_status_name(err->code), err->msg);
    return ry_status_exit_code(err->code);
}

static int bad_usage(const char *fmt, const char *arg) {
    fprintf(stderr, "ryushi: ");
    fprintf(stderr, fmt, arg);
    fprintf(stderr, "\n(see ryushi --help)\n");
    return 2;
}

typedef struct run_args {
    const char *case_path;
    const char *out_dir;
    int threads;
    int nset;
    const char **sets;
    int quick;
    const char *restart; /* --restart DIR */
} run_args;

/* Parses CASE, -o DIR, --threads N, --set K=V, --quick. */
static int parse_args(int argc, char **argv, int first, run_args *a, int need_case) {
    memset(a, 0, sizeof *a);
    a->sets = calloc((size_t)argc, sizeof *a->sets);
    if (!a->sets) return bad_usage("%s", "out of memory");
    for (int i = first; i < argc; ++i) {
        const char *s = argv[i];
        if ((strcmp(s, "-o") == 0 || strcmp(s, "--output") == 0) && i + 1 < argc) {
            a->out_dir = argv[++i];
        } else if (strcmp(s, "--threads") == 0 && i + 1 < argc) {
            char *end;
            long t = strtol(argv[++i], &end, 10);
            if (*end || t < 1 || t > 1024)
                return bad_usage("--threads: expected a whole number from 1 to 1024, got '%s'",
                                 argv[i]);
            a->threads = (int)t;
        } else if (strcmp(s, "--set") == 0 && i + 1 < argc) {
            a->sets[a->nset++] = argv[++i];
        } else if (strncmp(s, "--set=", 6) == 0) {
            a->sets[a->nset++] = s + 6;
        } else if (strcmp(s, "--restart") == 0 && i + 1 < argc) {
            a->restart = argv[++i];
        } else if (strcmp(s, "--quick") == 0) {
            a->quick = 1;
        } else if (s[0] == '-' && s[1] != '\0') {
            return bad_usage("unknown or incomplete option '%s'", s);
        } else if (!a->case_path && need_case) {
            a->case_path = s;
        } else {
            return bad_usage("unexpected argument '%s'", s);
        }
    }
    if (need_case && !a->case_path) return bad_usage("%s", "a case file is required");
    if (a->threads > 0) omp_set_num_threads(a->threads);
    return 0;
}

static ry_status load_case(const run_args *a, ry_case **c, ry_error *err) {
    RY_TRY(ry_case_load(c, a->case_path, err));
    for (int i = 0; i < a->nset; ++i) {
        ry_status st = ry_case_override(*c, a->sets[i], err);
        if (st != RY_OK) {
            ry_case_free(*c);
            *c = NULL;
            return st;
        }
    }
    return RY_OK;
}

typedef struct progress_ctx {
    int tty;
} progress_ctx;

static void fmt_duration(char *buf, size_t size, double s) {
    if (s < 60)
        snprintf(buf, size, "%.0fs", s);
    else if (s < 3600)
        snprintf(buf, size, "%dm%02ds", (int)(s / 60), (int)s % 60);
    else
        snprintf(buf, size, "%dh%02dm", (int)(s / 3600), ((int)s % 3600) / 60);
}

/* Reads the case named on the command line, applies --set and sets the simulation up. */
static ry_status setup_case(const run_args *a, ry_case **c, ry_sim *sim, ry_error *err) {
    memset(sim, 0, sizeof *sim);
    *c = NULL;
    RY_TRY(load_case(a, c, err));
    return ry_sim_setup(sim, *c, a->out_dir, err);
}

/* The process's peak resident memory so far, MB (getrusage: kB on Linux). */
static double peak_rss_mb(void) {
    struct rusage u;
    return getrusage(RUSAGE_SELF, &u) == 0 ? (double)u.ru_maxrss / 1024.0 : 0.0;
}

/* The handle a signal asks to stop (ryushi run). */
static ry_sim *volatile running;

static void on_signal_run(int sig) {
    on_signal(sig);
    if (running) ry_sim_request_stop(running);
}

static void api_progress(void *ctx, double t, double t_end, long step, double dt, double rate,
                         double eta) {
    const progress_ctx *p = ctx;
    char e[32];
    fmt_duration(e, sizeof e, eta);
    if (p->tty) {
        fprintf(stderr,
                "\r  t = %.4g / %.4g s  step %ld  dt = %.3g s  %.3g particle-steps/s  "
                "ETA %s   ",
                t, t_end, step, dt, rate, e);
        fflush(stderr);
    } else {
        fprintf(stdout,
                "progress t=%.6g t_end=%.6g step=%ld dt=%.4g particle_steps_per_s=%.4g "
                "eta_s=%.0f\n",
                t, t_end, step, dt, rate, eta);
        fflush(stdout);
    }
}

#ifdef RY_MPI_CLI
static void on_progress(void *ctx, const ry_sim *sim, double rate, double eta) {
    api_progress(ctx, sim->t, sim->t_end, sim->step, sim->dt, rate, eta);
}
#endif

static int api_fail(int rc) {
    fprintf(stderr, "ryushi: %s\n", ry_last_error());
    return rc;
}

static double stat_of(const ry_sim *sim, const char *name) {
    double v = 0;
    return ry_sim_stat(sim, name, &v) == 0 ? v : 0.0;
}

/* ryushi run: through the library's interface (include/ryushi/ryushi.h). */
static int cmd_run(int argc, char **argv) {
    run_args a;
    int rc = parse_args(argc, argv, 2, &a, 1);
    if (rc) {
        free(a.sets);
        return rc;
    }
    if (a.restart && !a.out_dir) a.out_dir = a.restart; /* continue in the same folder */
    /* (before the set-up: a signal during it stops the run at its first step) */
    catch_signals_with(on_signal_run);
    ry_sim *sim = NULL;
    rc = ry_sim_load(&sim, a.case_path, a.nset, a.sets, a.out_dir);
    if (rc == 0) rc = ry_sim_set_threads(sim, a.threads);
    char used[4300] = "", skipped[2048] = "";
    if (rc == 0 && a.restart)
        rc = ry_sim_restart(sim, a.restart, used, sizeof used, skipped, sizeof skipped);
    if (skipped[0])
        fprintf(stderr, "ryushi: warning: skipped damaged checkpoint(s): %s\n", skipped);
    if (rc) {
        api_fail(rc);
        ry_sim_destroy(sim);
        free(a.sets);
        return rc;
    }
    progress_ctx pc = {isatty(STDERR_FILENO)};
    printf("ryushi %s: case %s, %s, %dD, %zu particles, %d thread(s), output in %s\n", ry_version(),
           a.case_path, ry_sim_scheme(sim), ry_sim_dimension(sim), ry_sim_count(sim),
           omp_get_max_threads(), ry_sim_output_dir(sim));
    if (used[0])
        printf("restarting from %s (step %ld, t = %.6g s)\n", used, ry_sim_step_count(sim),
               ry_sim_time(sim));
    fflush(stdout);
    running = sim;
    if (stop_requested) ry_sim_request_stop(sim);
    ry_sim_set_progress(sim, api_progress, &pc, pc.tty ? 0.5 : 10.0);
    rc = ry_sim_run(sim);
    running = NULL;
    if (pc.tty) fprintf(stderr, "\n");
    if (rc) api_fail(rc);
    if (rc == 0 && ry_sim_stop_reason(sim)[0]) printf("%s\n", ry_sim_stop_reason(sim));
    char scheme_stats[256] = "";
    ry_sim_report(sim, scheme_stats + 1, sizeof scheme_stats - 1);
    if (scheme_stats[1]) scheme_stats[0] = ' ';
    printf("summary status=%s steps=%ld particles=%zu t=%.6g wall_s=%.3f "
           "particle_steps_per_s=%.4g threads=%d%s searches=%ld list_edits=%ld outputs=%d "
           "bytes_per_particle=%.0f peak_rss_mb=%.1f output=%s\n",
           rc == 0 ? "ok" : ry_last_error_kind(), (long)stat_of(sim, "steps"), ry_sim_count(sim),
           ry_sim_time(sim), stat_of(sim, "wall_s"), stat_of(sim, "particle_steps_per_s"),
           omp_get_max_threads(), scheme_stats, (long)stat_of(sim, "searches"),
           (long)stat_of(sim, "list_edits"), (int)stat_of(sim, "outputs"),
           stat_of(sim, "bytes_per_particle"), peak_rss_mb(), ry_sim_output_dir(sim));
    ry_sim_destroy(sim);
    free(a.sets);
    return rc;
}

#ifdef RY_MPI_CLI
/* ryushi-mpi run: the case on every rank of MPI_COMM_WORLD (src/parallel/mpi_dd.h). Every
 * rank sets the case up; rank 0 also keeps a second copy through which output and
 * checkpoints are written. Rank 0 reports. */
static int cmd_run_mpi(int argc, char **argv) {
    int rank, size;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    run_args a;
    int rc = parse_args(argc, argv, 2, &a, 1);
    if (rc) {
        free(a.sets);
        return rc;
    }
    const char *imb = getenv("RY_MPI_IMBALANCE");
    double imbalance = 1.1;
    if (imb && *imb) {
        char *end;
        imbalance = strtod(imb, &end);
        if (*end || !(imbalance >= 1.0) || !(imbalance < 1e6)) {
            free(a.sets);
            return rank == 0
                       ? bad_usage("RY_MPI_IMBALANCE: expected a number from 1 up, got '%s'", imb)
                       : 2;
        }
    }
    ry_error err = {0};
    ry_case *c = NULL, *cv = NULL;
    ry_sim sim, view;
    memset(&view, 0, sizeof view);
    if (a.restart && !a.out_dir) a.out_dir = a.restart;
    char used[4300] = "", skipped[2048] = "";
    ry_status st = setup_case(&a, &c, &sim, &err);
    if (st == RY_OK && a.restart)
        st = ry_restart_newest(&sim, a.restart, used, sizeof used, skipped, sizeof skipped, &err);
    if (st == RY_OK && rank == 0) {
        st = setup_case(&a, &cv, &view, &err);
        if (st == RY_OK) st = ry_sim_open_output(&view, cv, &err);
        if (st == RY_OK && a.restart)
            st = ry_restart_newest(&view, a.restart, used, sizeof used, skipped, sizeof skipped,
                                   &err);
    }
    if (st == RY_OK)
        st = ry_mpi_attach(&sim, rank == 0 ? &view : NULL, MPI_COMM_WORLD, imbalance, &err);
    /* The lowest rank that failed reports; all stop. */
    int mine = st != RY_OK ? rank : size, who;
    MPI_Allreduce(&mine, &who, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    if (who < size) {
        rc = rank == who ? fail(&err) : ry_status_exit_code(RY_ERR_INPUT);
        MPI_Bcast(&rc, 1, MPI_INT, who, MPI_COMM_WORLD);
        goto out;
    }
    if (rank == 0 && skipped[0])
        fprintf(stderr, "ryushi: warning: skipped damaged checkpoint(s): %s\n", skipped);
    progress_ctx pc = {isatty(STDERR_FILENO)};
    if (rank == 0) {
        printf("ryushi %s: case %s, %s, %dD, %zu particles, %d rank(s) x %d thread(s), output in "
               "%s\n",
               RY_VERSION, a.case_path, sim.scheme->name, sim.dim, view.ps.n, size,
               omp_get_max_threads(), view.out_dir);
        if (used[0]) printf("restarting from %s (step %ld, t = %.6g s)\n", used, sim.step, sim.t);
        fflush(stdout);
    }
    catch_signals();
    ry_run_hooks hooks = {rank == 0 ? on_progress : NULL, &pc, pc.tty ? 0.5 : 10.0,
                          &stop_requested};
    ry_run_stats stats = {0};
    st = ry_run(&sim, &hooks, &stats, &err);
    /* Out of memory or a broken invariant strikes one rank: the others cannot be told. */
    if (st == RY_ERR_NOMEM || st == RY_ERR_INTERNAL) {
        fprintf(stderr, "ryushi-mpi: rank %d: ", rank);
        MPI_Abort(MPI_COMM_WORLD, fail(&err));
    }
    if (rank == 0 && pc.tty) fprintf(stderr, "\n");
    rc = st != RY_OK ? ry_status_exit_code(st) : 0;
    if (st != RY_OK && rank == 0) fail(&err);
    if (st == RY_OK && rank == 0 && sim.stop_reason[0]) printf("%s\n", sim.stop_reason);
    ry_mpi_stats ms;
    ry_mpi_get_stats(&sim, &ms);
    double comm_max, wall_max, part[3] = {ms.redist_s, ms.halo_s, ms.reduce_s}, part_max[3];
    long halo = (long)ms.halo, halo_tot;
    MPI_Reduce(&ms.comm_s, &comm_max, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
    MPI_Reduce(part, part_max, 3, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
    MPI_Reduce(&stats.wall_s, &wall_max, 1, MPI_DOUBLE, MPI_MAX, 0, MPI_COMM_WORLD);
    MPI_Reduce(&halo, &halo_tot, 1, MPI_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
    if (rank == 0) {
        /* Particle-steps of the whole set (halo copies are not counted as work). */
        const double psteps = (double)view.ps.n * (double)stats.steps;
        printf("summary status=%s steps=%ld particles=%zu t=%.6g wall_s=%.3f "
               "particle_steps_per_s=%.4g ranks=%d threads=%d comm_s=%.3f comm_share=%.3f "
               "redist_s=%.3f halo_s=%.3f reduce_s=%.3f halo=%ld halo_fields=%d owned_max=%zu "
               "rebalances=%ld "
               "outputs=%d output=%s\n",
               st == RY_OK ? "ok" : ry_status_name(st), stats.steps, view.ps.n, sim.t, wall_max,
               psteps / (wall_max > 0 ? wall_max : 1e-9), size, omp_get_max_threads(), comm_max,
               wall_max > 0 ? comm_max / wall_max : 0.0, part_max[0], part_max[1], part_max[2],
               halo_tot, ms.fields, ms.owned_max, ms.rebalances, sim.output_index, view.out_dir);
    }
out:
    ry_mpi_detach(&sim);
    ry_sim_free(&sim);
    ry_sim_free(&view);
    ry_case_free(c);
    ry_case_free(cv);
    free(a.sets);
    return rc;
}
#endif

static int cmd_info(int argc, char **argv) {
    run_args a;
    int rc = parse_args(argc, argv, 2, &a, 1);
    if (rc) {
        free(a.sets);
        return rc;
    }
    ry_error err = {0};
    ry_case *c;
    ry_sim sim;
    ry_status st = setup_case(&a, &c, &sim, &err);
    if (st == RY_OK) st = ry_sim_neighbors(&sim, sim.kernel.radius, &err);
    if (st != RY_OK) {
        rc = fail(&err);
    } else {
        size_t count[RY_KIND_COUNT] = {0};
        for (size_t i = 0; i < sim.ps.n; ++i) count[sim.ps.kind[i]]++;
        printf("case            %s\n", a.case_path);
        printf("dimension       %d\n", sim.dim);
        printf("scheme          %s\n", sim.scheme->name);
        printf("particles       %zu", sim.ps.n);
        for (int k = 0; k < RY_KIND_COUNT; ++k)
            if (count[k]) printf("  %s %zu", ry_kind_name((ry_kind)k), count[k]);
        printf("\nspacing         %g m\n", sim.dx);
        printf("kernel          %s, h = %g m (%.3g dx), support radius %g m\n",
               ry_kernel_name(sim.kernel.type), sim.kernel.h, sim.h_over_dx, sim.kernel.radius);
        printf("domain          [%g, %g] x [%g, %g]", sim.box.lo[0], sim.box.hi[0], sim.box.lo[1],
               sim.box.hi[1]);
        if (sim.dim > 2) printf(" x [%g, %g]", sim.box.lo[2], sim.box.hi[2]);
        printf("\nmaterials      ");
        for (int m = 0; m < sim.nmat; ++m) {
            const ry_material *mt = &sim.mat[m];
            const ry_rheology *r = &mt->rheo;
            printf(" %s (rho0 %g kg/m^3, ", mt->name, mt->density);
            switch (r->model) {
            case RY_RHEO_POWER_LAW:
                printf("power law k %g m^2 s^(n-2), n %g, nu in [%g, %g] m^2/s)", r->consistency,
                       r->index, r->nu_min, r->nu_max);
                break;
            case RY_RHEO_CARREAU:
                printf("Carreau nu_0 %g, nu_inf %g m^2/s, t %g s, n %g)", r->nu_zero, r->nu_inf,
                       r->time, r->index);
                break;
            case RY_RHEO_OLDROYD_B:
            case RY_RHEO_GIESEKUS:
                printf("%s: solvent nu %g, polymer nu %g m^2/s, lambda %g s",
                       r->model == RY_RHEO_GIESEKUS ? "Giesekus" : "Oldroyd-B", mt->viscosity,
                       r->nu_polymer, r->relaxation);
                if (r->model == RY_RHEO_GIESEKUS) printf(", alpha %g", r->mobility);
                printf(")");
                break;
            default:
                printf("nu %g m^2/s)", mt->viscosity);
            }
        }
        /* Pairs within the support (the run's list, if the scheme keeps one, also holds the
         * skin). */
        size_t pairs = 0;
        for (size_t i = 0; i < sim.ps.n; ++i)
            pairs += ry_sim_count_within(&sim, i, sim.kernel.radius);
        printf("\nneighbours      %.1f per particle (mean, within the support)\n",
               sim.ps.n ? (double)pairs / (double)sim.ps.n : 0.0);
        double bpp_ps = (double)ry_particles_bytes_per_particle(&sim.ps);
        double bpp_cl = ry_cells_bytes_per_particle(&sim.cells);
        double bpp_nl = ry_nlist_bytes_per_particle(&sim.nl);
        printf("bytes/particle  %.0f (fields %.0f, cell list %.0f, neighbour list %.0f; the "
               "scheme's buffers come at the first step)\n",
               bpp_ps + bpp_cl + bpp_nl, bpp_ps, bpp_cl, bpp_nl);
        printf("time            end %g s, output every %g s\n", sim.t_end, sim.output_interval);
        printf("output          %s\n", sim.out_dir);
    }
    ry_sim_free(&sim);
    ry_case_free(c);
    free(a.sets);
    return rc;
}

static int cmd_checkpoint(int argc, char **argv) {
    if (argc != 3) return bad_usage("%s", "usage: ryushi checkpoint FILE");
    ry_error err = {0};
    ry_ck_reader r;
    if (ry_ck_open(&r, argv[2], &err) != RY_OK) return fail(&err);
    printf("checkpoint %s: format version %d, %zu bytes, checksum good, %d records\n", argv[2],
           RY_CHECKPOINT_VERSION, r.size, r.nrec);
    for (int i = 0; i < r.nrec; ++i) {
        const ry_ck_record *rec = &r.rec[i];
        printf("  %-32s %-4s %10zu", rec->name, ry_ck_type_name(rec->type), rec->count);
        if (rec->count == 1 && rec->type == RY_CK_F64) {
            double v;
            memcpy(&v, rec->data, sizeof v);
            printf("  %.17g", v);
        } else if (rec->count == 1 && rec->type == RY_CK_I64) {
            int64_t v;
            memcpy(&v, rec->data, sizeof v);
            printf("  %lld", (long long)v);
        } else if (rec->type == RY_CK_U8 && rec->count <= 60 && strncmp(rec->name, "meta/", 5) == 0)
            printf("  %.*s", (int)rec->count, (const char *)rec->data);
        printf("\n");
    }
    ry_ck_close(&r);
    return 0;
}

static int cmd_list(int schemes) {
    if (schemes) {
        const ry_scheme_type *const *s = ry_schemes();
        for (int i = 0; s[i]; ++i) printf("%-12s %s\n", s[i]->name, s[i]->summary);
    } else {
        const ry_probe *const *p = ry_probes();
        for (int i = 0; p[i]; ++i) printf("%-16s %s\n", p[i]->name, p[i]->summary);
    }
    return 0;
}

#ifdef RY_MPI_CLI
int main_serial(int argc, char **argv);

static int main_mpi(int argc, char **argv) {
    int size;
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (argc >= 2 && strcmp(argv[1], "run") == 0) return cmd_run_mpi(argc, argv);
    /* On one process, the other commands are ryushi's. */
    if (size == 1 && argc >= 2 && strcmp(argv[1], "--help") != 0) return main_serial(argc, argv);
    if (argc >= 2 && strcmp(argv[1], "--version") == 0) {
        printf("ryushi-mpi %s\n", RY_VERSION);
        return 0;
    }
    fprintf(argc >= 2 && strcmp(argv[1], "--help") == 0 ? stdout : stderr,
            "usage: mpirun -np N ryushi-mpi run CASE [-o DIR] [--threads N] [--set KEY=VALUE]... "
            "[--restart DIR]\n"
            "  the case on N ranks (domain decomposition; docs/parallel.md); the other commands "
            "are ryushi's\n");
    return argc >= 2 && strcmp(argv[1], "--help") == 0 ? 0 : 2;
}

int main(int argc, char **argv) {
    setvbuf(stdout, NULL, _IOLBF, 0);
    MPI_Init(&argc, &argv);
    int rc = main_mpi(argc, argv);
    MPI_Finalize();
    return rc;
}
#define main main_serial
#endif

int main(int argc, char **argv) {
    setvbuf(stdout, NULL, _IOLBF, 0); /* reports appear line by line, also in a pipe or file */
    if (argc < 2) {
        usage(stderr);
        return 2;
    }
    const char *limit = getenv("RY_MAX_PARTICLES");
    if (limit && *limit) {
        char *end;
        unsigned long long v = strtoull(limit, &end, 10);
        if (*end || v == 0 || limit[0] == '-')
            return bad_usage("RY_MAX_PARTICLES: expected a positive whole number, got '%s'", limit);
        ry_particles_set_limit((size_t)v);
    }
    const char *cmd = argv[1];
    if (strcmp(cmd, "help") == 0 && argc >= 3) return command_help(argv[2]);
    if (strcmp(cmd, "--help") == 0 || strcmp(cmd, "-h") == 0 || strcmp(cmd, "help") == 0) {
        usage(stdout);
        return 0;
    }
    /* COMMAND --help, except validate's own */
    for (int i = 2; i < argc && strcmp(cmd, "validate") != 0; ++i)
        if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) return command_help(cmd);
    if (strcmp(cmd, "--version") == 0) {
        printf("ryushi %s\n", RY_VERSION);
        return 0;
    }
    if (strcmp(cmd, "run") == 0) return cmd_run(argc, argv);
    if (strcmp(cmd, "info") == 0) return cmd_info(argc, argv);
    if (strcmp(cmd, "checkpoint") == 0) return cmd_checkpoint(argc, argv);
    if (strcmp(cmd, "bench") == 0) return ry_cli_bench(argc, argv);
    if (strcmp(cmd, "plot") == 0) return ry_cli_plot(argc, argv);
    if (strcmp(cmd, "validate") == 0) return ry_cli_validate(argc, argv);
    if (strcmp(cmd, "schemes") == 0) return cmd_list(1);
    if (strcmp(cmd, "probes") == 0) return cmd_list(0);
    return bad_usage("unknown command '%s'", cmd);
}
