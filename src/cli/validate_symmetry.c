/* ryushi validate symmetry: cases run whole and cut by symmetry planes (docs/reference/
 * symmetry.md), every column of their series compared. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "ryushi/csv.h"
#include "ryushi/plot.h"
#include "sim/symmetry.h"

/* A case run whole and cut: its overrides (both), the cut's, and the label; and whole with
 * perturb (a change of the problem by about one part in 1e9), whose deviation from the whole
 * measures how far the run's sensitivity carries a rounding-sized difference. */
typedef struct sym_pair {
    const char *label, *case_file, *sub;
    const char *sets[4];
    const char *cut[2];
    const char *perturb;
} sym_pair;

/* Runs a case with overrides into out/sub; its series, simulated particles and seconds. */
/* Runs a pair's case whole (cut 0), cut (1) or whole perturbed (2) into out/sub; its series,
 * particles simulated (without the mirror copies) and seconds. */
static ry_status run_one(const char *root, const char *out, const sym_pair *c, int cut,
                         const char *sub, ry_table *series, size_t *particles, double *wall_s,
                         ry_error *err) {
    const char *sets[7];
    int n = 0;
    for (int k = 0; k < 4 && c->sets[k]; ++k) sets[n++] = c->sets[k];
    for (int k = 0; cut == 1 && k < 2; ++k) sets[n++] = c->cut[k];
    if (cut == 2) sets[n++] = c->perturb;
    ry_sim sim;
    ry_run_stats stats;
    RY_TRY(ry_cli_run_series(root, out, c->case_file, sub, n, sets, &sim, &stats, series, err));
    *particles = ry_symmetry_owned(&sim);
    *wall_s = stats.wall_s;
    ry_sim_free(&sim);
    return RY_OK;
}

/* Whether a column is compared: not the time, the step's count and length, which follow the
 * solution's state by thresholds, nor the solvers' iteration counts. */
static int compared(const char *name) {
    return strcmp(name, "t") != 0 && strcmp(name, "step") != 0 && strcmp(name, "dt") != 0 &&
           !strstr(name, "iterations");
}

/* Per column j of a, dev[j]: the largest relative deviation of b's values from a's over the
 * rows (values below 1e-12 in size compared absolutely); -1 where the column is not compared.
 * Non-zero where the tables' shapes or columns differ. */
static int deviations(const ry_table *a, const ry_table *b, double *dev) {
    if (a->ncols != b->ncols || a->nrows != b->nrows || a->ncols > 64) return 1;
    for (int j = 0; j < a->ncols; ++j) {
        if (strcmp(a->names[j], b->names[j]) != 0) return 1;
        dev[j] = compared(a->names[j]) ? 0.0 : -1.0;
        for (size_t r = 0; r < a->nrows && dev[j] >= 0; ++r) {
            const double x = ry_table_at(a, r, j), y = ry_table_at(b, r, j);
            const double d = fabs(x - y) / (fabs(x) > 1e-12 ? fabs(x) : 1.0);
            dev[j] = d <= dev[j] ? dev[j] : isnan(d) ? INFINITY : d;
        }
    }
    return 0;
}

int ry_cli_validate_symmetry(const char *root, const char *out, int quick, int *failures) {
    static const char *const keys[2] = {"series_max_dev", "sensitivity_factor"};
    double tol[2];
    if (ry_cli_tolerances(root, "symmetry", 2, keys, tol, failures)) return 1;
    const char *dx = quick ? "spacing=0.025" : "spacing=0.0125";
    const char *end = quick ? "time.end=0.3" : "time.end=0.6";
    const char *half[2] = {"domain.hi=[1.1,0.125,1.5]", "domain.symmetry=[y_hi]"};
    const char *g = "gravity=[0,0,-9.81000001]";
    const sym_pair pairs[] = {
        {"3D dam break, WCSPH, half",
         "cases/dam_break_3d.yaml",
         "wcsph_dam",
         {dx, end, "time.output_interval=0.02", "output.vtk=false"},
         {half[0], half[1]},
         g},
        {"3D dam break, MPS, half",
         "cases/mps_dam_break_3d.yaml",
         "mps_dam",
         {dx, end, "time.output_interval=0.02", "output.vtk=false"},
         {half[0], half[1]},
         g},
        {"IISPH column, half",
         "cases/hydrostatic_iisph.yaml",
         "iisph_column",
         {quick ? "time.end=0.4" : "time.end=1.0", "time.output_interval=0.05", "output.vtk=false",
          NULL},
         {"domain.lo=[0.2,-0.02]", "domain.symmetry=[x_lo]"},
         "gravity=[0,-9.81000001]"},
        {"IISPH drop (CSF), quarter",
         "cases/iisph_drop_rest_2d.yaml",
         "iisph_drop",
         {quick ? "time.end=0.004" : "time.end=0.01", "time.output_interval=0.0005", NULL, NULL},
         {"domain.lo=[0,0]", "domain.symmetry=[x_lo,y_lo]"},
         "surface_tension.sigma=0.0728000001"},
    };
    ry_error err = {0};
    ry_plot *p = NULL;
    if (ry_plot_new(&p, 1, 2, 1400, 600, &err) != RY_OK) return ry_cli_fail(failures, &err);
    ry_plot_panel(p, 0, "3D dam break: surge front", "t (s)", "x (m)", &err);
    ry_plot_panel(p, 1, "3D dam break: kinetic energy", "t (s)", "E (J)", &err);
    printf("Symmetry planes: each case whole and cut, every column of series.csv compared; a\n"
           "column may deviate by %g, or up to %g times as far as the whole does with its gravity\n"
           "(surface tension) changed by 1e-9: the spread a rounding-sized difference grows to\n",
           tol[0], tol[1]);
    printf("  %-28s %9s %9s %8s %8s %-16s %10s %10s\n", "case", "whole", "simulated", "whole_s",
           "part_s", "worst column", "cut", "perturbed");
    for (size_t k = 0; k < sizeof pairs / sizeof pairs[0]; ++k) {
        const sym_pair *c = &pairs[k];
        ry_table a = {0}, b = {0}, e = {0};
        size_t na = 0, nb = 0, ne = 0;
        double wa = 0, wb = 0, we = 0;
        char sa[128], sb[128], se[128];
        snprintf(sa, sizeof sa, "%s_whole", c->sub);
        snprintf(sb, sizeof sb, "%s_part", c->sub);
        snprintf(se, sizeof se, "%s_whole_perturbed", c->sub);
        if (run_one(root, out, c, 0, sa, &a, &na, &wa, &err) != RY_OK ||
            run_one(root, out, c, 1, sb, &b, &nb, &wb, &err) != RY_OK ||
            run_one(root, out, c, 2, se, &e, &ne, &we, &err) != RY_OK) {
            ry_table_free(&a);
            ry_table_free(&b);
            ry_cli_fail(failures, &err);
            continue;
        }
        double dcut[64], dpert[64];
        int bad = deviations(&a, &b, dcut) || deviations(&a, &e, dpert);
        /* the worst column: the largest deviation over what it may deviate */
        double ratio = bad ? INFINITY : 0;
        int worst = -1; /* (none: every compared column the same) */
        for (int j = 0; !bad && j < a.ncols; ++j) {
            if (dcut[j] < 0) continue;
            const double allowed = fmax(tol[0], tol[1] * dpert[j]);
            if (!(dcut[j] / allowed <= ratio)) {
                ratio = dcut[j] / allowed;
                worst = j;
            }
        }
        const char *wname = bad ? "(tables differ)" : worst < 0 ? "(all equal)" : a.names[worst];
        printf("  %-28s %9zu %9zu %8.1f %8.1f %-16s %10.2e %10.2e\n", c->label, na, nb, wa, wb,
               wname, worst < 0 ? 0.0 : dcut[worst], worst < 0 ? 0.0 : dpert[worst]);
        char what[240];
        snprintf(what, sizeof what,
                 "%s: largest relative deviation from the whole over what it may reach %s",
                 c->label, wname);
        ry_cli_check_figure(what, ratio, 1.0, ratio <= 1.0, failures);
        if (k < 2) {
            char label[96];
            const ry_plot_style line = ry_plot_style_line();
            ry_plot_style dashed = line;
            dashed.dash = RY_PLOT_DASH_DASHED;
            for (int panel = 0; panel < 2; ++panel) {
                const char *y = panel ? "kinetic_energy" : "front_x";
                snprintf(label, sizeof label, "%s, whole", k ? "MPS" : "WCSPH");
                ry_cli_add_series(p, panel, label, &a, "t", 1, y, 1, line, &err);
                snprintf(label, sizeof label, "%s, half", k ? "MPS" : "WCSPH");
                ry_cli_add_series(p, panel, label, &b, "t", 1, y, 1, dashed, &err);
            }
        }
        ry_table_free(&a);
        ry_table_free(&b);
        ry_table_free(&e);
    }
    ry_plot_legend(p, 0, RY_PLOT_LEGEND_SE, &err);
    ry_plot_legend(p, 1, RY_PLOT_LEGEND_NE, &err);
    ry_cli_write_plot(p, out, "symmetry_dam_break.png", failures);
    ry_plot_free(p);
    return 0;
}
