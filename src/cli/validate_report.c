/* ryushi validate --report: the validation report, from the manifests (validation/NAME.yaml) and
 * the checks the runs recorded (OUT/results_NAME.csv), into OUT/validation_report.md and, with
 * --into FILE, between the report's markers in FILE (docs/validation.md). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "ryushi/atomic_file.h"
#include "ryushi/manifest.h"

#define BEGIN_MARK "<!-- ryushi validate --report: begin -->"
#define END_MARK "<!-- ryushi validate --report: end -->"

/* One check of a run: "what",figure,tolerance,verdict. */
typedef struct check_row {
    char what[512], figure[32], tolerance[32];
    int ok;
} check_row;

/* What a run recorded: its version, wall time, threads and checks. */
typedef struct run_result {
    int found, quick, threads;
    double wall_s;
    int nchecks, passed;
    check_row *checks;
} run_result;

void ry_cli_results_path(char *buf, size_t size, const char *out, const char *name) {
    snprintf(buf, size, "%s/results_%s.csv", out, name);
}

/* Splits a results line into its check; 0 when it is not one. */
static int parse_check(char *line, check_row *c) {
    line[strcspn(line, "\r\n")] = '\0';
    char *c3 = strrchr(line, ',');
    if (!c3 || line[0] == '#') return 0;
    *c3 = '\0';
    char *c2 = strrchr(line, ',');
    if (!c2) return 0;
    *c2 = '\0';
    char *c1 = strrchr(line, ',');
    if (!c1) return 0;
    *c1 = '\0';
    /* the text, unquoted (CSV: "text", inner quotes doubled) */
    size_t m = 0;
    const char *s = line, *e = c1;
    if (line[0] == '"' && c1 > line + 1 && c1[-1] == '"') ++s, --e;
    for (; s < e && m + 1 < sizeof c->what; ++s) {
        c->what[m++] = *s;
        if (*s == '"' && s + 1 < e && s[1] == '"') ++s;
    }
    c->what[m] = '\0';
    snprintf(c->figure, sizeof c->figure, "%s", c1 + 1);
    snprintf(c->tolerance, sizeof c->tolerance, "%s", c2 + 1);
    c->ok = strncmp(c3 + 1, "PASS", 4) == 0;
    return 1;
}

static void read_result(run_result *r, const char *out, const char *name) {
    memset(r, 0, sizeof *r);
    char path[4300], line[1024];
    ry_cli_results_path(path, sizeof path, out, name);
    FILE *fp = fopen(path, "r");
    if (!fp) return;
    r->found = 1;
    int cap = 0;
    while (fgets(line, sizeof line, fp)) {
        if (strncmp(line, "# ryushi validate", 17) == 0) r->quick = strstr(line, "--quick") != NULL;
        if (sscanf(line, "# wall_s,%lf", &r->wall_s) == 1) continue;
        if (sscanf(line, "# threads,%d", &r->threads) == 1) continue;
        check_row c;
        if (!parse_check(line, &c)) continue;
        if (r->nchecks == cap) {
            cap = cap ? 2 * cap : 16;
            check_row *p = realloc(r->checks, (size_t)cap * sizeof *p);
            if (!p) break;
            r->checks = p;
        }
        r->checks[r->nchecks++] = c;
        r->passed += c.ok;
    }
    fclose(fp);
}

/* A table cell: '|' escaped. */
static void cell(FILE *md, const char *s) {
    for (; *s; ++s) {
        if (*s == '|') fputc('\\', md);
        fputc(*s, md);
    }
}

static void wall_time(FILE *md, const run_result *r) {
    if (r->wall_s <= 0)
        fputs("-", md);
    else if (r->wall_s < 120)
        fprintf(md, "%.0f s", r->wall_s);
    else
        fprintf(md, "%.1f min", r->wall_s / 60);
}

/* The items of a manifest's list, as code spans joined by ", " ("-" when none); with a
 * prefix, as links to prefix/item. */
static void items(FILE *md, ry_manifest *m, const char *key, const char *link) {
    const char *s;
    int i = 0;
    int shown = 0;
    for (; (s = ry_manifest_item(m, key, i)) != NULL; ++i) {
        if (strcmp(s, "none") == 0) continue; /* (a reference: none) */
        if (shown++) fputs(", ", md);
        if (link)
            fprintf(md, "[%s](%s%s)", s, link, s);
        else
            fprintf(md, "`%s`", s);
    }
    if (shown == 0) fputs("-", md);
}

/* The report's body: the table of every validation, then one section per validation. plots:
 * the folder the plots are linked in (NULL: named only, with the output folder). */
static void body(FILE *md, ry_manifest *all, const run_result *res, int n, const char *out,
                 const char *plots) {
    fprintf(md, "| validation | version run | checks | passed | time | command |\n"
                "|---|---|---|---|---|---|\n");
    for (int k = 0; k < n; ++k) {
        const run_result *r = &res[k];
        fprintf(md, "| [%s](#%s) | %s | %d | %d | ", all[k].name, all[k].name,
                !r->found  ? "not run"
                : r->quick ? "quick"
                           : "full",
                r->nchecks, r->passed);
        wall_time(md, r);
        fprintf(md, " | `ryushi validate %s%s` |\n", all[k].name,
                r->found && r->quick ? " --quick" : "");
    }
    for (int k = 0; k < n; ++k) {
        ry_manifest *m = &all[k];
        const run_result *r = &res[k];
        const char *version = r->found && r->quick ? "quick" : "full";
        fprintf(md, "\n### %s\n\n%s.\n\n| | |\n|---|---|\n| reference | ", m->name, m->summary);
        items(md, m, "reference", NULL);
        fputs(" |\n| cases | ", md);
        items(md, m, "cases", NULL);
        fprintf(md, " |\n| resolution (%s) | ", version);
        cell(md, ry_manifest_text(m, version, "-"));
        fprintf(md, " |\n| command | `ryushi validate %s%s` |\n| time | ", m->name,
                r->found && r->quick ? " --quick" : "");
        wall_time(md, r);
        if (r->threads > 0) fprintf(md, " on %d thread%s", r->threads, r->threads > 1 ? "s" : "");
        fputs(" |\n| in `make test` | ", md);
        items(md, m, "make_test", NULL);
        fputs(" |\n| plots | ", md);
        if (!plots) fprintf(md, "in `%s/`: ", out);
        items(md, m, "plots", plots);
        fputs(" |\n\n", md);
        if (!r->found) {
            fputs("Not run.\n", md);
            continue;
        }
        fputs("| check | figure | tolerance | verdict |\n|---|---|---|---|\n", md);
        for (int c = 0; c < r->nchecks; ++c) {
            const check_row *row = &r->checks[c];
            fputs("| ", md);
            cell(md, row->what);
            fprintf(md, " | %s | %s | %s |\n", row->figure[0] ? row->figure : "-",
                    row->tolerance[0] ? row->tolerance : "-", row->ok ? "PASS" : "**FAIL**");
        }
    }
}

static int fail_io(const ry_error *err) {
    fprintf(stderr, "ryushi: validate: %s\n", err->msg);
    return 3;
}

/* FILE with the part between its markers replaced by the report's body. */
static int write_into(const char *path, ry_manifest *all, const run_result *res, int n,
                      const char *out) {
    FILE *fp = fopen(path, "rb");
    if (!fp) {
        fprintf(stderr, "ryushi: validate: cannot read '%s'\n", path);
        return 3;
    }
    char *text = NULL;
    size_t len = 0, cap = 0, got;
    char buf[65536];
    while ((got = fread(buf, 1, sizeof buf, fp)) > 0) {
        if (len + got + 1 > cap) {
            cap = 2 * (len + got + 1);
            char *p = realloc(text, cap);
            if (!p) break;
            text = p;
        }
        memcpy(text + len, buf, got);
        len += got;
    }
    fclose(fp);
    if (!text) {
        fprintf(stderr, "ryushi: validate: cannot read '%s' (empty or out of memory)\n", path);
        return 3;
    }
    text[len] = '\0';
    char *b = strstr(text, BEGIN_MARK), *e = b ? strstr(b, END_MARK) : NULL;
    if (!b || !e) {
        fprintf(stderr,
                "ryushi: validate: '%s' has no lines '" BEGIN_MARK "' and '" END_MARK
                "' for the report to go between\n",
                path);
        free(text);
        return 2;
    }
    ry_error err = {0};
    ry_atomic_file af = {0};
    if (ry_atomic_open(&af, path, &err) != RY_OK) {
        free(text);
        return fail_io(&err);
    }
    fwrite(text, 1, (size_t)(b - text) + strlen(BEGIN_MARK), af.fp);
    fprintf(af.fp,
            "\n<!-- written by `ryushi validate --report -o %s --into %s`; edit the manifests "
            "(validation/) instead -->\n\n",
            out, path);
    body(af.fp, all, res, n, out, NULL);
    fputc('\n', af.fp);
    fputs(e, af.fp);
    free(text);
    if (ry_atomic_commit(&af, &err) != RY_OK) return fail_io(&err);
    printf("validate: report written into %s\n", path);
    return 0;
}

int ry_cli_validate_report(ry_manifest *all, int n, const char *out, const char *into) {
    run_result *res = calloc((size_t)(n ? n : 1), sizeof *res);
    if (!res) {
        fprintf(stderr, "ryushi: validate: out of memory\n");
        return 1;
    }
    for (int k = 0; k < n; ++k) read_result(&res[k], out, all[k].name);
    char path[4200];
    snprintf(path, sizeof path, "%s/validation_report.md", out);
    ry_error err = {0};
    ry_atomic_file af = {0};
    int rc = 0;
    if (ry_atomic_open(&af, path, &err) != RY_OK) {
        rc = fail_io(&err);
    } else {
        fprintf(af.fp,
                "# Validation report\n\nWritten by `ryushi validate --report` (ryushi %s) from "
                "the results in %s: each validation's checks as its last run gave them. The "
                "tolerances are in validation/NAME.yaml.\n\n",
                RY_VERSION, out);
        body(af.fp, all, res, n, out, "");
        if (ry_atomic_commit(&af, &err) != RY_OK)
            rc = fail_io(&err);
        else
            printf("validate: report in %s\n", path);
    }
    if (!rc && into) rc = write_into(into, all, res, n, out);
    for (int k = 0; k < n; ++k) free(res[k].checks);
    free(res);
    return rc;
}
