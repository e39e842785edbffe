/* ryushi validate: the full-resolution validation cases, compared with their references,
 * with plots. Each has a manifest, validation/NAME.yaml (its summary, whether plain `ryushi
 * validate` runs it, its tolerances), and either its runs as data (validate_runs.c) or, where
 * its measures need code, a function here that runs it; each run records its checks for the
 * report (validate_report.c). */
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "ryushi/atomic_file.h"
#include "ryushi/manifest.h"

/* The function that runs a validation, by its manifest's name. */
typedef struct validation {
    const char *name;
    int (*run)(const char *root, const char *out, int quick, int *failures);
} validation;

static const validation validations[] = {
    {"dam_break", ry_cli_validate_dam_break},
    {"cavity", ry_cli_validate_cavity},
    {"channel", ry_cli_validate_channel},
    {"cantilever", ry_cli_validate_cantilever},
    {"plate", ry_cli_validate_plate},
    {"buckling", ry_cli_validate_buckling},
    {"mps", ry_cli_validate_mps},
    {"rheology", ry_cli_validate_rheology},
    {"iisph", ry_cli_validate_iisph},
    {"rt", ry_cli_validate_rt},
    {"surface_tension", ry_cli_validate_surface_tension},
    {"air", ry_cli_validate_air},
    {"eye", ry_cli_validate_eye},
    {"eye_positions", ry_cli_validate_eye_positions},
    {"eye_clinical", ry_cli_validate_eye_clinical},
    {"eye_fine", ry_cli_validate_eye_fine},
    {"embolization", ry_cli_validate_embolization},
    {"embolization3d", ry_cli_validate_embolization3d},
    {"embolization3d_all", ry_cli_validate_embolization3d_all},
    {"embolization3d_wide", ry_cli_validate_embolization3d_wide},
    {"symmetry", ry_cli_validate_symmetry},
};
enum { NVALIDATIONS = sizeof validations / sizeof validations[0] };

static void usage(FILE *fp) {
    fprintf(fp,
            "usage: ryushi validate [NAME | all] [--quick] [-o DIR] [--threads N] [--root DIR]\n"
            "       ryushi validate --list | --report [-o DIR] [--into FILE] | --help\n"
            "\n"
            "Runs validation cases against their references, with plots and a PASS or FAIL line\n"
            "per check (exit code 1 when a check fails). Plain `ryushi validate` (or `all`) runs\n"
            "those --list marks as in `all`; NAME runs one. --quick: the short version (fewer\n"
            "resolutions). -o: the output folder (default out/validate). --root: the project\n"
            "folder with cases/, data/ and validation/ (default: the source tree). Each\n"
            "validation's summary and tolerances are in validation/NAME.yaml. Each run\n"
            "records its checks in DIR/results_NAME.csv; --report writes them, with the\n"
            "summaries, references, commands, times and plots, to DIR/validation_report.md,\n"
            "and with --into FILE also between the report's markers in FILE (the lines\n"
            "<!-- ryushi validate --report: begin --> and <!-- ... end -->).\n");
}

static const validation *runner(const char *name) {
    for (int k = 0; k < NVALIDATIONS; ++k)
        if (strcmp(name, validations[k].name) == 0) return &validations[k];
    return NULL;
}

int ry_cli_validate(int argc, char **argv) {
    const char *root = RY_SOURCE_DIR, *out = "out/validate", *into = NULL;
    enum { RUN, LIST, REPORT } mode = RUN;
    int quick = 0, failures = 0;
    const char *root_env = getenv("RY_SOURCE_DIR");
    if (root_env && *root_env) root = root_env;
    const char *what = "all";
    for (int i = 2; i < argc; ++i) {
        if (strcmp(argv[i], "--quick") == 0)
            quick = 1;
        else if (strcmp(argv[i], "--help") == 0 || strcmp(argv[i], "-h") == 0) {
            usage(stdout);
            return 0;
        } else if (strcmp(argv[i], "--list") == 0)
            mode = LIST;
        else if (strcmp(argv[i], "--report") == 0)
            mode = REPORT;
        else if (strcmp(argv[i], "-o") == 0 && i + 1 < argc)
            out = argv[++i];
        else if (strcmp(argv[i], "--into") == 0 && i + 1 < argc)
            into = argv[++i];
        else if (strcmp(argv[i], "--root") == 0 && i + 1 < argc)
            root = argv[++i];
        else if (strcmp(argv[i], "--threads") == 0 && i + 1 < argc)
            omp_set_num_threads(atoi(argv[++i]) > 0 ? atoi(argv[i]) : 1);
        else if (argv[i][0] != '-')
            what = argv[i];
        else {
            fprintf(stderr, "ryushi: validate: unknown option '%s' (see ryushi validate --help)\n",
                    argv[i]);
            return 2;
        }
    }
    ry_error err = {0};
    ry_manifest *all;
    int n;
    if (ry_manifest_all(root, &all, &n, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        return ry_status_exit_code(err.code);
    }
    int rc = 0;
    for (int k = 0; k < n && !rc; ++k)
        if (!runner(all[k].name) && !ry_cli_manifest_has_runs(&all[k])) {
            fprintf(stderr, "ryushi: validate: %s: no validation of that name in the program\n",
                    all[k].path);
            rc = 1;
        }
    const ry_manifest *one = NULL;
    for (int k = 0; k < n; ++k)
        if (strcmp(what, all[k].name) == 0) one = &all[k];
    const int every = strcmp(what, "all") == 0;
    if (!rc && mode == REPORT) {
        rc = ry_cli_validate_report(all, n, out, into);
    } else if (!rc && mode == LIST) {
        for (int k = 0; k < n; ++k)
            printf("%-20s %-4s %s\n", all[k].name, all[k].in_all ? "all" : "", all[k].summary);
    } else if (!rc && into) {
        fprintf(stderr, "ryushi: validate: --into goes with --report\n");
        rc = 2;
    } else if (!rc && !every && !one) {
        fprintf(stderr, "ryushi: validate: no validation '%s' (ryushi validate --list)\n", what);
        rc = 2;
    } else if (!rc && ry_mkdir_p(out, &err) != RY_OK) {
        fprintf(stderr, "ryushi: validate: %s\n", err.msg);
        rc = 3;
    } else if (!rc) {
        int rec_failed = 0;
        for (int k = 0; k < n; ++k)
            if (every ? all[k].in_all : &all[k] == one) {
                /* the checks recorded for --report (the first line says which version) */
                char rp[4300];
                ry_cli_results_path(rp, sizeof rp, out, all[k].name);
                ry_atomic_file af = {0};
                const int rec = ry_atomic_open(&af, rp, &err) == RY_OK;
                if (rec)
                    fprintf(af.fp, "# ryushi validate %s%s\n", all[k].name,
                            quick ? " --quick" : "");
                ry_cli_results(rec ? af.fp : NULL);
                const double t0 = omp_get_wtime();
                if (runner(all[k].name))
                    runner(all[k].name)->run(root, out, quick, &failures);
                else
                    ry_cli_validate_runs(root, out, quick, all[k].name, &failures);
                ry_cli_results(NULL);
                if (rec)
                    fprintf(af.fp, "# wall_s,%.1f\n# threads,%d\n", omp_get_wtime() - t0,
                            omp_get_max_threads());
                if (rec && ry_atomic_commit(&af, &err) != RY_OK) rec_failed = 1;
                if (!rec || rec_failed) {
                    fprintf(stderr, "ryushi: validate: %s\n", err.msg);
                    ++failures;
                }
            }
        printf("validate: %s (%d failure(s)); output in %s\n", failures ? "FAILED" : "passed",
               failures, out);
        rc = failures ? 1 : 0;
    }
    for (int k = 0; k < n; ++k) ry_manifest_free(&all[k]);
    free(all);
    return rc;
}
