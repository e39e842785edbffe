/* Sub-commands of the ryushi program, one file each. */
#ifndef RYUSHI_CLI_H
#define RYUSHI_CLI_H

#include <stdio.h>

#include "ryushi/csv.h"
#include "ryushi/plot.h"
#include "ryushi/run.h"
#include "ryushi/sim.h"

int ry_cli_bench(int argc, char **argv);
int ry_cli_plot(int argc, char **argv);
int ry_cli_validate(int argc, char **argv);
struct ry_manifest;
/* The report of `ryushi validate --report` from the manifests all[0..n-1] and the results in
 * out (validate_report.c): out/validation_report.md, and between the report's markers in into
 * (NULL: none); returns the exit code. */
int ry_cli_validate_report(struct ry_manifest *all, int n, const char *out, const char *into);
/* out/results_NAME.csv: the checks of the last run of validation name. */
void ry_cli_results_path(char *buf, size_t size, const char *out, const char *name);
/* Runs root/case_file with overrides into out/sub and reads its series.csv into *series;
 * keeps the final state in *sim (the caller frees it; freed here when the series cannot be
 * read) and the run's statistics in *stats (validate_common.c). */
ry_status ry_cli_run_series(const char *root, const char *out, const char *case_file,
                            const char *sub, int nset, const char *const *sets, ry_sim *sim,
                            ry_run_stats *stats, ry_table *series, ry_error *err);
/* Adds column cy against column cx of a table, each scaled, as a series of a plot panel
 * (validate_cmd.c); an error names a missing column. */
ry_status ry_cli_add_series(ry_plot *p, int panel, const char *label, const ry_table *t,
                            const char *cx, double sx, const char *cy, double sy,
                            ry_plot_style style, ry_error *err);
/* The WCSPH validations (validate_wcsph.c): dam break against Martin & Moyce, the lid-driven
 * cavity against Ghia et al., the channel with in- and outflow; each adds its failed checks to
 * *failures. */
int ry_cli_validate_dam_break(const char *root, const char *out, int quick, int *failures);
int ry_cli_validate_cavity(const char *root, const char *out, int quick, int *failures);
int ry_cli_validate_channel(const char *root, const char *out, int quick, int *failures);
/* The cantilever validation (validate_solid.c); adds its failed checks to *failures. */
int ry_cli_validate_cantilever(const char *root, const char *out, int quick, int *failures);
/* The oscillating plate and the filament buckling (validate_solid.c). */
int ry_cli_validate_plate(const char *root, const char *out, int quick, int *failures);
int ry_cli_validate_buckling(const char *root, const char *out, int quick, int *failures);

/* The MPS scheme: hydrostatic column, oscillating drops, drop at rest (validate_mps.c). */
int ry_cli_validate_mps(const char *root, const char *out, int quick, int *failures);
/* A validation given as data alone: the runs and figures of validation/name.yaml
 * (validate_runs.c); adds its failed checks to *failures. */
int ry_cli_validate_runs(const char *root, const char *out, int quick, const char *name,
                         int *failures);
/* Whether a validation's manifest gives its runs as data. */
int ry_cli_manifest_has_runs(struct ry_manifest *m);
/* The tolerances keys[0..n-1] of validation/name.yaml into values; 0, or 1 with the error
 * printed and counted as a failure. */
int ry_cli_tolerances(const char *root, const char *name, int n, const char *const *keys,
                      double *values, int *failures);
/* Prints a validation's error and counts a failure; returns 1. */
int ry_cli_fail(int *failures, const ry_error *err);
/* Prints a validation check's line (PASS or FAIL), counts a failure, and records the check
 * as a CSV row ("check",verdict) in the file given to ry_cli_results (NULL: none). */
void ry_cli_check(const char *what, int ok, int *failures);
/* The same for a check of one measured figure against a tolerance (ok: the check's verdict),
 * both recorded for the report. */
void ry_cli_check_figure(const char *what, double figure, double tolerance, int ok, int *failures);
void ry_cli_results(FILE *fp);
/* Writes plot p as out/name (PNG) and prints where; a failure is printed and counted. */
void ry_cli_write_plot(ry_plot *p, const char *out, const char *name, int *failures);
/* A series column times k in a new array (the caller frees it); NULL when the column is
 * missing. */
double *ry_cli_scaled_column(const ry_table *s, const char *name, double k);
/* Markers of the particles of a 3D run within half of the plane y = 0 into a panel, x and z in
 * mm: walls, the first and the second material, labelled label[0..2] when legend is set. */
void ry_cli_slice_markers(ry_plot *p, int panel, const ry_sim *sim, double half,
                          const char *const label[3], int legend);
/* A slice of a 3D run: the particles with lo <= x[normal] <= hi, drawn at (x[ax], x[ay]) in mm;
 * with mirror, those with x[ax] >= 0 only, each also at (-x[ax], x[ay]) (a symmetric part). */
typedef struct ry_cli_slice {
    int normal;
    double lo, hi;
    int ax, ay, mirror;
    double marker_size;
} ry_cli_slice;
/* Runs a case (overrides sets) into odir, from the newest checkpoint there if there is one,
 * printing its progress every 5 minutes; Ctrl-C or SIGTERM stops it with a checkpoint
 * (RY_ERR_INTERRUPTED, sim kept). On other failures sim is freed. */
ry_status ry_cli_run_or_resume(const char *cpath, int nset, const char *const *sets,
                               const char *odir, ry_sim *sim, ry_run_stats *stats, ry_error *err);
/* ry_cli_slice_markers for any slice. */
void ry_cli_slice_markers_in(ry_plot *p, int panel, const ry_sim *sim, const ry_cli_slice *sl,
                             const char *const label[3], int legend);
/* The 2D embolization tank: droplet, volumes, Tate's law (validate_embolization.c). */
int ry_cli_validate_embolization(const char *root, const char *out, int quick, int *failures);
/* The coarse 3D embolization tank until its droplet detaches, resumable
 * (validate_embolization3d.c). */
int ry_cli_validate_embolization3d(const char *root, const char *out, int quick, int *failures);
/* The same tank as it is and with an Oldroyd-B embolic liquid: the detachment times compared
 * (validate_embolization3d.c). */
int ry_cli_validate_embolization3d_all(const char *root, const char *out, int quick, int *failures);
/* ryushi validate embolization3d_wide: the wide tanks alone, the tip's face at 120 and 180 degrees
 * (validate_embolization3d.c). */
int ry_cli_validate_embolization3d_wide(const char *root, const char *out, int quick,
                                        int *failures);
/* Non-Newtonian channel flows (validate_rheology.c). */
/* Symmetry planes: cases whole and cut, their series compared (validate_symmetry.c). */
int ry_cli_validate_symmetry(const char *root, const char *out, int quick, int *failures);
int ry_cli_validate_rheology(const char *root, const char *out, int quick, int *failures);
/* IISPH and two-phase validation (validate_iisph.c). */
int ry_cli_validate_iisph(const char *root, const char *out, int quick, int *failures);
/* Only its Rayleigh-Taylor part (ryushi validate rt). */
int ry_cli_validate_rt(const char *root, const char *out, int quick, int *failures);
/* Oscillating drops of small amplitude against Lamb, at two spacings and steps
 * (validate_surface_tension.c). */
int ry_cli_validate_surface_tension(const char *root, const char *out, int quick, int *failures);
/* Water and air in motion (IISPH with a light phase): the dam break under air and a standing
 * wave (part of ry_cli_validate_iisph). */
int ry_cli_validate_air(const char *root, const char *out, int quick, int *failures);
/* The eye case in segments with slice pictures (validate_eye.c). */
int ry_cli_validate_eye(const char *root, const char *out, int quick, int *failures);
int ry_cli_validate_eye_positions(const char *root, const char *out, int quick, int *failures);
int ry_cli_validate_eye_clinical(const char *root, const char *out, int quick, int *failures);
int ry_cli_validate_eye_fine(const char *root, const char *out, int quick, int *failures);
/* The eye cases' tamponade: the cavity's radius (bodies[0]), the saline's and the oil's
 * densities (materials 0 and 1), their tension (scheme.surface_tension) and the Bond number
 * (rho_s - rho_o) g R^2 / sigma at head_position's g (validate_eye.c). */
ry_status ry_cli_eye_bond(ry_case *c, double *R, double *rho_s, double *rho_o, double *sigma,
                          double *bond, ry_error *err);

#endif
