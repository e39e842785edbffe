/* Case files: typed getters, error messages, overrides, unknown keys, resolved output. */
#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "ryushi/case.h"

static ry_case *load(const char *text) {
    ry_case *c = NULL;
    ry_error e;
    ry_error_clear(&e);
    ry_status st = ry_case_load_string(&c, "case.yaml", text, &e);
    if (st != RY_OK) fail_msg("load failed: %s", e.msg);
    return c;
}

/* Loading text must fail with exactly msg. */
static void load_fails(const char *text, const char *msg) {
    ry_case *c = NULL;
    ry_error e;
    ry_error_clear(&e);
    assert_int_equal(ry_case_load_string(&c, "case.yaml", text, &e), RY_ERR_INPUT);
    assert_null(c);
    assert_string_equal(e.msg, msg);
}

static void write_file(const char *path, const char *text) {
    FILE *fp = fopen(path, "wb");
    assert_non_null(fp);
    fputs(text, fp);
    assert_int_equal(fclose(fp), 0);
}

static const char *const kernels[] = {"cubic", "wendland", "quintic", NULL};

static const char *dam = "name: dam break\n"                            /* 1 */
                         "time:\n"                                      /* 2 */
                         "  t_end: 1.5\n"                               /* 3 */
                         "  dt: 1e-3\n"                                 /* 4 */
                         "  steps: 200\n"                               /* 5 */
                         "kernel: wendland\n"                           /* 6 */
                         "gravity: [0, -9.81]\n"                        /* 7 */
                         "output:\n"                                    /* 8 */
                         "  vtk: true\n"                                /* 9 */
                         "  images: false\n"                            /* 10 */
                         "  prefix: \"run 1\"\n"                        /* 11 */
                         "bodies:\n"                                    /* 12 */
                         "  - type: box\n"                              /* 13 */
                         "    lo: [0, 0]\n"                             /* 14 */
                         "    hi: [1, 2]\n"                             /* 15 */
                         "  - {type: wall, lo: [-1, 0], hi: [3, 0]}\n"; /* 16 */

/* ---------------------------------------------------------------- getters */

static void test_getters(void **state) {
    (void)state;
    ry_case *c = load(dam);
    ry_error e;
    double x, v[2];
    long k;
    int b, ch;
    const char *s;
    size_t n;
    assert_string_equal(ry_case_name(c), "case.yaml");
    assert_int_equal(ry_case_double(c, "time.t_end", NULL, 0, INFINITY, &x, &e), RY_OK);
    assert_true(x == 1.5);
    assert_int_equal(ry_case_positive(c, "time.dt", NULL, &x, &e), RY_OK);
    assert_true(x == 1e-3);
    assert_int_equal(ry_case_int(c, "time.steps", NULL, 1, 1000, &k, &e), RY_OK);
    assert_int_equal(k, 200);
    assert_int_equal(ry_case_choice(c, "kernel", NULL, kernels, &ch, &e), RY_OK);
    assert_int_equal(ch, 1);
    assert_int_equal(ry_case_vector(c, "gravity", NULL, 2, v, &e), RY_OK);
    assert_true(v[0] == 0 && v[1] == -9.81);
    assert_int_equal(ry_case_bool(c, "output.vtk", NULL, &b, &e), RY_OK);
    assert_int_equal(b, 1);
    assert_int_equal(ry_case_bool(c, "output.images", NULL, &b, &e), RY_OK);
    assert_int_equal(b, 0);
    assert_int_equal(ry_case_string(c, "output.prefix", NULL, &s, &e), RY_OK);
    assert_string_equal(s, "run 1");
    assert_int_equal(ry_case_string(c, "name", NULL, &s, &e), RY_OK);
    assert_string_equal(s, "dam break");
    assert_int_equal(ry_case_count(c, "bodies", &n, &e), RY_OK);
    assert_int_equal(n, 2);
    assert_int_equal(ry_case_string(c, "bodies[0].type", NULL, &s, &e), RY_OK);
    assert_string_equal(s, "box");
    assert_int_equal(ry_case_string(c, "bodies[1].type", NULL, &s, &e), RY_OK);
    assert_string_equal(s, "wall");
    assert_int_equal(ry_case_vector(c, "bodies[1].lo", NULL, 2, v, &e), RY_OK);
    assert_true(v[0] == -1 && v[1] == 0);
    assert_int_equal(ry_case_count(c, "nothing", &n, &e), RY_OK);
    assert_int_equal(n, 0);
    assert_true(ry_case_has(c, "time.dt"));
    assert_true(ry_case_has(c, "bodies[1].hi"));
    assert_false(ry_case_has(c, "bodies[2]"));
    assert_false(ry_case_has(c, "time.dt.x"));
    assert_false(ry_case_has(c, "time.nope"));
    char where[64];
    assert_string_equal(ry_case_where(c, "time.dt", where, sizeof where), "case.yaml:4");
    assert_string_equal(ry_case_where(c, "bodies[1].type", where, sizeof where), "case.yaml:16");
    assert_string_equal(ry_case_where(c, "missing.key", where, sizeof where), "case.yaml");
    /* a number written in various forms */
    ry_case_free(c);
    c = load("a: -2.5E+2\nb: +3\nc: .5\nd: 1e-3\ne: 7\n");
    assert_int_equal(ry_case_double(c, "a", NULL, -INFINITY, INFINITY, &x, &e), RY_OK);
    assert_true(x == -250);
    assert_int_equal(ry_case_double(c, "b", NULL, -INFINITY, INFINITY, &x, &e), RY_OK);
    assert_true(x == 3);
    assert_int_equal(ry_case_double(c, "c", NULL, -INFINITY, INFINITY, &x, &e), RY_OK);
    assert_true(x == 0.5);
    assert_int_equal(ry_case_double(c, "d", NULL, -INFINITY, INFINITY, &x, &e), RY_OK);
    assert_true(x == 1e-3);
    assert_int_equal(ry_case_int(c, "b", NULL, LONG_MIN, LONG_MAX, &k, &e), RY_OK);
    assert_int_equal(k, 3);
    assert_int_equal(ry_case_string(c, "e", NULL, &s, &e), RY_OK);
    assert_string_equal(s, "7");
    assert_int_equal(ry_case_check_unused(c, &e), RY_OK);
    ry_case_free(c);
}

/* ---------------------------------------------------------------- getter errors */

static const char *bad = "a: abc\n"                  /* 1 */
                         "b: 1.0x\n"                 /* 2 */
                         "c: nan\n"                  /* 3 */
                         "d: inf\n"                  /* 4 */
                         "e: \"1.5\"\n"              /* 5 */
                         "f: {x: 1}\n"               /* 6 */
                         "g: [1, 2]\n"               /* 7 */
                         "h:\n"                      /* 8 */
                         "i: 1e999\n"                /* 9 */
                         "j: 2.5\n"                  /* 10 */
                         "k: 99999999999999999999\n" /* 11 */
                         "l: yes\n"                  /* 12 */
                         "m: 'true'\n"               /* 13 */
                         "n: -1\n"                   /* 14 */
                         "o: 0\n"                    /* 15 */
                         "p: .inf\n"                 /* 16 */
                         "q: 0x10\n"                 /* 17 */
                         "r:\n"                      /* 18 */
                         "  s: 1\n";                 /* 19 */

static void expect_double(ry_case *c, const char *path, double lo, double hi, ry_status code,
                          const char *msg) {
    ry_error e;
    double x;
    ry_error_clear(&e);
    assert_int_equal(ry_case_double(c, path, NULL, lo, hi, &x, &e), code);
    assert_int_equal(e.code, code);
    assert_string_equal(e.msg, msg);
}

static void test_number_errors(void **state) {
    (void)state;
    ry_case *c = load(bad);
    const double I = INFINITY;
    expect_double(c, "a", -I, I, RY_ERR_INPUT,
                  "case.yaml:1: key 'a': expected a number, got 'abc'");
    expect_double(c, "b", -I, I, RY_ERR_INPUT,
                  "case.yaml:2: key 'b': expected a number, got '1.0x'");
    expect_double(c, "c", -I, I, RY_ERR_INPUT,
                  "case.yaml:3: key 'c': expected a number, got 'nan'");
    expect_double(c, "d", -I, I, RY_ERR_INPUT,
                  "case.yaml:4: key 'd': expected a number, got 'inf'");
    expect_double(c, "e", -I, I, RY_ERR_INPUT,
                  "case.yaml:5: key 'e': expected a number, got the quoted string '1.5'");
    expect_double(c, "f", -I, I, RY_ERR_INPUT,
                  "case.yaml:6: key 'f': expected a number, got a mapping");
    expect_double(c, "g", -I, I, RY_ERR_INPUT,
                  "case.yaml:7: key 'g': expected a number, got a sequence");
    expect_double(c, "h", -I, I, RY_ERR_INPUT,
                  "case.yaml:8: key 'h': expected a number, got an empty value");
    expect_double(c, "i", -I, I, RY_ERR_INPUT,
                  "case.yaml:9: key 'i': expected a number, got '1e999'");
    expect_double(c, "p", -I, I, RY_ERR_INPUT,
                  "case.yaml:16: key 'p': expected a number, got '.inf'");
    expect_double(c, "q", -I, I, RY_ERR_INPUT,
                  "case.yaml:17: key 'q': expected a number, got '0x10'");
    expect_double(c, "r", -I, I, RY_ERR_INPUT,
                  "case.yaml:18: key 'r': expected a number, got a mapping");
    expect_double(c, "j", 0, 1, RY_ERR_RANGE,
                  "case.yaml:10: key 'j': expected a number in [0, 1], got '2.5'");
    expect_double(c, "n", 0, I, RY_ERR_RANGE,
                  "case.yaml:14: key 'n': expected a number >= 0, got '-1'");
    expect_double(c, "j", -I, 0.5, RY_ERR_RANGE,
                  "case.yaml:10: key 'j': expected a number <= 0.5, got '2.5'");
    expect_double(c, "r.s.t", -I, I, RY_ERR_INPUT,
                  "case.yaml:19: key 'r.s': expected a mapping, got '1'");
    expect_double(c, "r[0]", -I, I, RY_ERR_INPUT,
                  "case.yaml:18: key 'r': expected a sequence, got a mapping");

    ry_error e;
    double x;
    assert_int_equal(ry_case_positive(c, "o", NULL, &x, &e), RY_ERR_RANGE);
    assert_string_equal(e.msg, "case.yaml:15: key 'o': expected a positive number, got '0'");
    assert_int_equal(ry_case_positive(c, "n", NULL, &x, &e), RY_ERR_RANGE);
    assert_string_equal(e.msg, "case.yaml:14: key 'n': expected a positive number, got '-1'");
    assert_int_equal(ry_case_positive(c, "a", NULL, &x, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:1: key 'a': expected a positive number, got 'abc'");

    long k;
    assert_int_equal(ry_case_int(c, "j", NULL, LONG_MIN, LONG_MAX, &k, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:10: key 'j': expected an integer, got '2.5'");
    assert_int_equal(ry_case_int(c, "k", NULL, LONG_MIN, LONG_MAX, &k, &e), RY_ERR_RANGE);
    assert_string_equal(e.msg,
                        "case.yaml:11: key 'k': expected an integer, got '99999999999999999999'");
    assert_int_equal(ry_case_int(c, "n", NULL, 0, 10, &k, &e), RY_ERR_RANGE);
    assert_string_equal(e.msg, "case.yaml:14: key 'n': expected an integer in [0, 10], got '-1'");
    assert_int_equal(ry_case_int(c, "n", NULL, 0, LONG_MAX, &k, &e), RY_ERR_RANGE);
    assert_string_equal(e.msg, "case.yaml:14: key 'n': expected an integer >= 0, got '-1'");
    assert_int_equal(ry_case_int(c, "o", NULL, LONG_MIN, -5, &k, &e), RY_ERR_RANGE);
    assert_string_equal(e.msg, "case.yaml:15: key 'o': expected an integer <= -5, got '0'");
    assert_int_equal(ry_case_int(c, "d", NULL, LONG_MIN, LONG_MAX, &k, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:4: key 'd': expected an integer, got 'inf'");

    int b;
    assert_int_equal(ry_case_bool(c, "l", NULL, &b, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:12: key 'l': expected true or false, got 'yes'");
    assert_int_equal(ry_case_bool(c, "m", NULL, &b, &e), RY_ERR_INPUT);
    assert_string_equal(
        e.msg, "case.yaml:13: key 'm': expected true or false, got the quoted string 'true'");
    assert_int_equal(ry_case_bool(c, "o", NULL, &b, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:15: key 'o': expected true or false, got '0'");

    const char *s;
    assert_int_equal(ry_case_string(c, "f", NULL, &s, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:6: key 'f': expected a string, got a mapping");
    assert_int_equal(ry_case_string(c, "h", NULL, &s, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:8: key 'h': expected a string, got an empty value");

    int ch;
    assert_int_equal(ry_case_choice(c, "a", NULL, kernels, &ch, &e), RY_ERR_INPUT);
    assert_string_equal(
        e.msg, "case.yaml:1: key 'a': expected one of cubic, wendland, quintic; got 'abc'");
    assert_int_equal(ry_case_choice(c, "g", NULL, kernels, &ch, &e), RY_ERR_INPUT);
    assert_string_equal(
        e.msg, "case.yaml:7: key 'g': expected one of cubic, wendland, quintic; got a sequence");

    double v[3];
    assert_int_equal(ry_case_vector(c, "g", NULL, 3, v, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg,
                        "case.yaml:7: key 'g': expected a sequence of 3 numbers, got 2 elements");
    assert_int_equal(ry_case_vector(c, "a", NULL, 3, v, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:1: key 'a': expected a sequence of 3 numbers, got 'abc'");

    size_t n;
    assert_int_equal(ry_case_count(c, "f", &n, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:6: key 'f': expected a sequence, got a mapping");
    assert_int_equal(ry_case_count(c, "a", &n, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:1: key 'a': expected a sequence, got 'abc'");

    /* a malformed path is a bug of the caller */
    assert_int_equal(ry_case_double(c, "a..b", NULL, -I, I, &x, &e), RY_ERR_INTERNAL);
    assert_string_equal(e.msg, "invalid key path 'a..b'");
    assert_int_equal(ry_case_double(c, "a[x]", NULL, -I, I, &x, &e), RY_ERR_INTERNAL);
    assert_int_equal(ry_case_double(c, "", NULL, -I, I, &x, &e), RY_ERR_INTERNAL);
    ry_case_free(c);
}

static void test_vector_element_error(void **state) {
    (void)state;
    ry_case *c = load("geo:\n  lo:\n    - 0\n    - x\n  hi: [1, '2']\n");
    ry_error e;
    double v[2];
    assert_int_equal(ry_case_vector(c, "geo.lo", NULL, 2, v, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:4: key 'geo.lo[1]': expected a number, got 'x'");
    assert_int_equal(ry_case_vector(c, "geo.hi", NULL, 2, v, &e), RY_ERR_INPUT);
    assert_string_equal(
        e.msg, "case.yaml:5: key 'geo.hi[1]': expected a number, got the quoted string '2'");
    ry_case_free(c);
}

static void test_missing_required(void **state) {
    (void)state;
    ry_case *c = load(dam);
    ry_error e;
    double x;
    assert_int_equal(ry_case_double(c, "rho", NULL, 0, INFINITY, &x, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml: key 'rho': required key is missing");
    assert_int_equal(ry_case_positive(c, "time.cfl", NULL, &x, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:2: key 'time.cfl': required key is missing");
    assert_int_equal(ry_case_positive(c, "bodies[1].rho", NULL, &x, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:16: key 'bodies[1].rho': required key is missing");
    assert_int_equal(ry_case_positive(c, "bodies[5].rho", NULL, &x, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:12: key 'bodies[5].rho': required key is missing");
    const char *s;
    assert_int_equal(ry_case_string(c, "a.b.c", NULL, &s, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml: key 'a.b.c': required key is missing");
    long k;
    assert_int_equal(ry_case_int(c, "time.n", NULL, 0, 5, &k, &e), RY_ERR_INPUT);
    int b;
    assert_int_equal(ry_case_bool(c, "output.x", NULL, &b, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:8: key 'output.x': required key is missing");
    int ch;
    assert_int_equal(ry_case_choice(c, "kern", NULL, kernels, &ch, &e), RY_ERR_INPUT);
    double v[2];
    assert_int_equal(ry_case_vector(c, "lo", NULL, 2, v, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml: key 'lo': required key is missing");
    ry_case_free(c);
}

/* ---------------------------------------------------------------- defaults, resolved output */

static void test_defaults_resolved(void **state) {
    (void)state;
    const char *path = "test_case_defaults.yaml", *out = "test_case_defaults.resolved.yaml";
    write_file(path, "time:\n  t_end: 2\nbodies:\n  - type: box\nlabel: x\n");
    ry_case *c = NULL;
    ry_error e;
    assert_int_equal(ry_case_load(&c, path, &e), RY_OK);
    double x, v[3];
    long k;
    int b, ch;
    const char *s;
    const double d_dt = 0.1, d_g[3] = {0, 0, -9.81}, d_rho = 1000;
    const long d_steps = 7;
    const int d_vtk = 1;
    assert_int_equal(ry_case_double(c, "time.t_end", NULL, 0, INFINITY, &x, &e), RY_OK);
    assert_true(x == 2);
    assert_int_equal(ry_case_positive(c, "time.dt", &d_dt, &x, &e), RY_OK);
    assert_true(x == 0.1);
    assert_int_equal(ry_case_int(c, "time.steps", &d_steps, 1, 100, &k, &e), RY_OK);
    assert_int_equal(k, 7);
    assert_int_equal(ry_case_vector(c, "physics.gravity", d_g, 3, v, &e), RY_OK);
    assert_true(v[2] == -9.81);
    assert_int_equal(ry_case_bool(c, "output.vtk", &d_vtk, &b, &e), RY_OK);
    assert_int_equal(b, 1);
    assert_int_equal(ry_case_string(c, "output.prefix", "run: #1", &s, &e), RY_OK);
    assert_string_equal(s, "run: #1");
    assert_int_equal(ry_case_choice(c, "kernel", "quintic", kernels, &ch, &e), RY_OK);
    assert_int_equal(ch, 2);
    assert_int_equal(ry_case_double(c, "bodies[0].rho", &d_rho, 0, INFINITY, &x, &e), RY_OK);
    assert_int_equal(ry_case_double(c, "bodies[3].rho", &d_rho, 0, INFINITY, &x, &e), RY_OK);
    assert_int_equal(ry_case_string(c, "bodies[0].type", NULL, &s, &e), RY_OK);
    assert_int_equal(ry_case_string(c, "label", "y", &s, &e), RY_OK);
    assert_string_equal(s, "x");
    /* defaults are not input: has() does not see them, a second default replaces the first */
    assert_false(ry_case_has(c, "time.dt"));
    assert_false(ry_case_has(c, "physics"));
    const double d_dt2 = 0.2;
    assert_int_equal(ry_case_positive(c, "time.dt", &d_dt2, &x, &e), RY_OK);
    assert_true(x == 0.2);
    /* a default that does not fit the range is a bug */
    const double d_bad = -1;
    assert_int_equal(ry_case_double(c, "zz", &d_bad, 0, 1, &x, &e), RY_ERR_INTERNAL);
    assert_int_equal(ry_case_choice(c, "zk", "nope", kernels, &ch, &e), RY_ERR_INTERNAL);
    assert_int_equal(ry_case_check_unused(c, &e), RY_OK);
    assert_int_equal(ry_case_write_resolved(c, out, &e), RY_OK);
    ry_case_free(c);

    /* the resolved file holds every value, without defaults */
    assert_int_equal(ry_case_load(&c, out, &e), RY_OK);
    assert_int_equal(ry_case_double(c, "time.t_end", NULL, 0, INFINITY, &x, &e), RY_OK);
    assert_true(x == 2);
    assert_int_equal(ry_case_positive(c, "time.dt", NULL, &x, &e), RY_OK);
    assert_true(x == 0.2);
    assert_int_equal(ry_case_int(c, "time.steps", NULL, 1, 100, &k, &e), RY_OK);
    assert_int_equal(k, 7);
    assert_int_equal(ry_case_vector(c, "physics.gravity", NULL, 3, v, &e), RY_OK);
    assert_true(v[0] == 0 && v[1] == 0 && v[2] == -9.81);
    assert_int_equal(ry_case_bool(c, "output.vtk", NULL, &b, &e), RY_OK);
    assert_int_equal(b, 1);
    assert_int_equal(ry_case_string(c, "output.prefix", NULL, &s, &e), RY_OK);
    assert_string_equal(s, "run: #1");
    assert_int_equal(ry_case_choice(c, "kernel", NULL, kernels, &ch, &e), RY_OK);
    assert_int_equal(ch, 2);
    assert_int_equal(ry_case_double(c, "bodies[0].rho", NULL, 0, INFINITY, &x, &e), RY_OK);
    assert_true(x == 1000);
    assert_int_equal(ry_case_string(c, "bodies[0].type", NULL, &s, &e), RY_OK);
    assert_string_equal(s, "box");
    assert_int_equal(ry_case_string(c, "label", NULL, &s, &e), RY_OK);
    assert_string_equal(s, "x");
    size_t n;
    assert_int_equal(ry_case_count(c, "bodies", &n, &e), RY_OK);
    assert_int_equal(n, 1); /* no element was made up for bodies[3] */
    assert_false(ry_case_has(c, "zz"));
    assert_int_equal(ry_case_check_unused(c, &e), RY_OK);
    ry_case_free(c);
    remove(path);
    remove(out);
}

static void test_resolved_round_trip_styles(void **state) {
    (void)state;
    const char *out = "test_case_styles.resolved.yaml";
    ry_case *c = load("s1: '1.5'\ns2: \"true\"\ns3: \"a\\tb \\\"q\\\"\"\ns4: |\n  two\n  lines\n"
                      "list:\n  - [1, 2]\n  - {a: 1}\n  -\n  - x\nempty_map: {}\nempty_seq: []\n"
                      "k e y: v\n");
    ry_error e;
    ry_case_touch(c, "list");
    ry_case_touch(c, "empty_map");
    ry_case_touch(c, "empty_seq");
    ry_case_touch(c, "k e y");
    const char *s;
    assert_int_equal(ry_case_string(c, "s1", NULL, &s, &e), RY_OK);
    assert_int_equal(ry_case_string(c, "s2", NULL, &s, &e), RY_OK);
    assert_int_equal(ry_case_string(c, "s3", NULL, &s, &e), RY_OK);
    assert_int_equal(ry_case_string(c, "s4", NULL, &s, &e), RY_OK);
    assert_int_equal(ry_case_write_resolved(c, out, &e), RY_OK);
    ry_case_free(c);
    assert_int_equal(ry_case_load(&c, out, &e), RY_OK);
    double x;
    assert_int_equal(ry_case_double(c, "s1", NULL, -INFINITY, INFINITY, &x, &e), RY_ERR_INPUT);
    int b;
    assert_int_equal(ry_case_bool(c, "s2", NULL, &b, &e), RY_ERR_INPUT);
    assert_int_equal(ry_case_string(c, "s3", NULL, &s, &e), RY_OK);
    assert_string_equal(s, "a\tb \"q\"");
    assert_int_equal(ry_case_string(c, "s4", NULL, &s, &e), RY_OK);
    assert_string_equal(s, "two\nlines\n");
    double v[2];
    assert_int_equal(ry_case_vector(c, "list[0]", NULL, 2, v, &e), RY_OK);
    assert_true(v[1] == 2);
    assert_int_equal(ry_case_double(c, "list[1].a", NULL, -INFINITY, INFINITY, &x, &e), RY_OK);
    assert_int_equal(ry_case_string(c, "list[2]", NULL, &s, &e), RY_ERR_INPUT);
    assert_int_equal(ry_case_string(c, "list[3]", NULL, &s, &e), RY_OK);
    assert_string_equal(s, "x");
    size_t n;
    assert_int_equal(ry_case_count(c, "empty_seq", &n, &e), RY_OK);
    assert_int_equal(n, 0);
    assert_true(ry_case_has(c, "empty_map"));
    assert_int_equal(ry_case_string(c, "k e y", NULL, &s, &e), RY_OK);
    assert_string_equal(s, "v");
    ry_case_free(c);
    remove(out);

    /* an empty case writes an empty mapping */
    c = load("");
    assert_int_equal(ry_case_write_resolved(c, out, &e), RY_OK);
    ry_case_free(c);
    assert_int_equal(ry_case_load(&c, out, &e), RY_OK);
    assert_false(ry_case_has(c, "a"));
    ry_case_free(c);
    remove(out);

    c = load("a: 1\n");
    assert_int_equal(ry_case_write_resolved(c, "no-such-folder/x.yaml", &e), RY_ERR_IO);
    ry_case_free(c);
}

/* ---------------------------------------------------------------- overrides */

static void test_overrides(void **state) {
    (void)state;
    ry_case *c = load(dam);
    ry_error e;
    double x, v[2];
    const char *s;
    const char *name_before;
    assert_int_equal(ry_case_string(c, "name", NULL, &name_before, &e), RY_OK);
    assert_int_equal(ry_case_override(c, "time.t_end=3.5", &e), RY_OK);      /* existing key */
    assert_int_equal(ry_case_override(c, "time.cfl=0.2", &e), RY_OK);        /* new key */
    assert_int_equal(ry_case_override(c, "fluid.water.rho=998", &e), RY_OK); /* new parents */
    assert_int_equal(ry_case_override(c, "bodies[1].lo=[5, 6]", &e), RY_OK); /* in an element */
    assert_int_equal(ry_case_override(c, "bodies[2]={type: box, lo: [7, 8]}", &e), RY_OK);
    assert_int_equal(ry_case_override(c, "gravity[1]=-1", &e), RY_OK);
    assert_int_equal(ry_case_override(c, "probes[0].at=[1, 1]", &e), RY_OK); /* new sequence */
    assert_int_equal(ry_case_override(c, "name=other", &e), RY_OK);
    assert_int_equal(ry_case_override(c, "note=", &e), RY_OK);
    assert_int_equal(ry_case_override(c, "title=a=b", &e), RY_OK);
    assert_string_equal(name_before, "dam break"); /* still valid */
    assert_int_equal(ry_case_double(c, "time.t_end", NULL, 0, INFINITY, &x, &e), RY_OK);
    assert_true(x == 3.5);
    assert_int_equal(ry_case_positive(c, "time.cfl", NULL, &x, &e), RY_OK);
    assert_true(x == 0.2);
    assert_int_equal(ry_case_positive(c, "fluid.water.rho", NULL, &x, &e), RY_OK);
    assert_true(x == 998);
    assert_int_equal(ry_case_vector(c, "bodies[1].lo", NULL, 2, v, &e), RY_OK);
    assert_true(v[0] == 5 && v[1] == 6);
    assert_int_equal(ry_case_vector(c, "bodies[2].lo", NULL, 2, v, &e), RY_OK);
    assert_true(v[0] == 7 && v[1] == 8);
    assert_int_equal(ry_case_vector(c, "gravity", NULL, 2, v, &e), RY_OK);
    assert_true(v[0] == 0 && v[1] == -1);
    assert_int_equal(ry_case_vector(c, "probes[0].at", NULL, 2, v, &e), RY_OK);
    assert_int_equal(ry_case_string(c, "name", NULL, &s, &e), RY_OK);
    assert_string_equal(s, "other");
    assert_int_equal(ry_case_string(c, "title", NULL, &s, &e), RY_OK);
    assert_string_equal(s, "a=b");
    size_t n;
    assert_int_equal(ry_case_count(c, "bodies", &n, &e), RY_OK);
    assert_int_equal(n, 3);
    char where[128];
    assert_string_equal(ry_case_where(c, "time.cfl", where, sizeof where), "--set time.cfl=0.2");
    assert_string_equal(ry_case_where(c, "fluid.water", where, sizeof where),
                        "--set fluid.water.rho=998");

    /* errors in overridden values name the assignment */
    assert_int_equal(ry_case_override(c, "time.dt=abc", &e), RY_OK);
    assert_int_equal(ry_case_positive(c, "time.dt", NULL, &x, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg,
                        "--set time.dt=abc: key 'time.dt': expected a positive number, got 'abc'");
    assert_int_equal(ry_case_override(c, "output.vtk=[1, x]", &e), RY_OK);
    assert_int_equal(ry_case_vector(c, "output.vtk", NULL, 2, v, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg,
                        "--set output.vtk=[1, x]: key 'output.vtk[1]': expected a number, got 'x'");
    int b;
    assert_int_equal(ry_case_bool(c, "note", NULL, &b, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg,
                        "--set note=: key 'note': expected true or false, got an empty value");
    ry_case_free(c);
}

static void expect_override_error(const char *assignment, const char *msg) {
    ry_case *c = load(dam);
    ry_error e;
    ry_error_clear(&e);
    assert_int_equal(ry_case_override(c, assignment, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, msg);
    ry_case_free(c);
}

static void test_override_errors(void **state) {
    (void)state;
    expect_override_error("time.t_end", "--set time.t_end: expected key=value");
    expect_override_error("=3", "--set =3: expected key=value");
    expect_override_error("a..b=3", "--set a..b=3: invalid key 'a..b'");
    expect_override_error("a[=3", "--set a[=3: invalid key 'a['");
    expect_override_error("name.first=x",
                          "--set name.first=x: key 'name': expected a mapping, got 'dam break'");
    expect_override_error("time[0]=x", "--set time[0]=x: key 'time': expected a sequence, got a "
                                       "mapping");
    expect_override_error("bodies[5].type=box", "--set bodies[5].type=box: key 'bodies[5]': index "
                                                "5 is past the end of the sequence (2 elements)");
    expect_override_error("newlist[2]=1", "--set newlist[2]=1: key 'newlist[2]': index 2 is past "
                                          "the end of the sequence (0 elements)");
    expect_override_error("time.t_end=[1, 2",
                          "--set time.t_end=[1, 2: invalid value: syntax error: flow sequence "
                          "without a closing bracket");
    expect_override_error("time.t_end=*x",
                          "--set time.t_end=*x: invalid value: anchors and aliases are not "
                          "supported");
    expect_override_error("a={b: 1, b: 2}", "--set a={b: 1, b: 2}: key 'b': duplicate key");
}

/* ---------------------------------------------------------------- unknown keys */

static void expect_unused(const char *text, void (*use)(ry_case *), const char *msg) {
    ry_case *c = load(text);
    ry_error e;
    ry_error_clear(&e);
    use(c);
    if (msg) {
        assert_int_equal(ry_case_check_unused(c, &e), RY_ERR_INPUT);
        assert_string_equal(e.msg, msg);
    } else {
        assert_int_equal(ry_case_check_unused(c, &e), RY_OK);
    }
    ry_case_free(c);
}

static void use_dam(ry_case *c) {
    ry_error e;
    double x, v[2];
    long k;
    int b, ch;
    const char *s;
    const double d_cfl = 0.25;
    size_t n;
    assert_int_equal(ry_case_string(c, "name", NULL, &s, &e), RY_OK);
    assert_int_equal(ry_case_double(c, "time.t_end", NULL, 0, INFINITY, &x, &e), RY_OK);
    assert_int_equal(ry_case_positive(c, "time.dt", NULL, &x, &e), RY_OK);
    assert_int_equal(ry_case_positive(c, "time.cfl", &d_cfl, &x, &e), RY_OK);
    assert_int_equal(ry_case_int(c, "time.steps", NULL, 0, 1000, &k, &e), RY_OK);
    assert_int_equal(ry_case_choice(c, "kernel", NULL, kernels, &ch, &e), RY_OK);
    assert_int_equal(ry_case_vector(c, "gravity", NULL, 2, v, &e), RY_OK);
    assert_int_equal(ry_case_bool(c, "output.vtk", NULL, &b, &e), RY_OK);
    assert_int_equal(ry_case_bool(c, "output.images", NULL, &b, &e), RY_OK);
    assert_int_equal(ry_case_string(c, "output.prefix", NULL, &s, &e), RY_OK);
    assert_int_equal(ry_case_count(c, "bodies", &n, &e), RY_OK);
    for (size_t i = 0; i < n && i < 2; i++) {
        char p[64];
        snprintf(p, sizeof p, "bodies[%zu].type", i);
        assert_int_equal(ry_case_string(c, p, NULL, &s, &e), RY_OK);
        snprintf(p, sizeof p, "bodies[%zu].lo", i);
        assert_int_equal(ry_case_vector(c, p, NULL, 2, v, &e), RY_OK);
        snprintf(p, sizeof p, "bodies[%zu].hi", i);
        assert_int_equal(ry_case_vector(c, p, NULL, 2, v, &e), RY_OK);
    }
}

static void use_dam_touch_output(ry_case *c) {
    use_dam(c);
    ry_case_touch(c, "output");
    ry_case_touch(c, "notes");
}

static void use_nothing(ry_case *c) {
    (void)c;
}

static void use_bodies_count(ry_case *c) {
    ry_error e;
    size_t n;
    assert_int_equal(ry_case_count(c, "bodies", &n, &e), RY_OK);
}

static void test_unknown_keys(void **state) {
    (void)state;
    expect_unused(dam, use_dam, NULL);
    char text[2048];
    snprintf(text, sizeof text, "%sextra: 1\n", dam);
    expect_unused(text, use_dam, "case.yaml:17: unknown key 'extra'");
    snprintf(text, sizeof text, "%snotes:\n  a: 1\n  b: [2]\n", dam);
    expect_unused(text, use_dam, "case.yaml:17: unknown key 'notes'");
    expect_unused(text, use_dam_touch_output, NULL);
    snprintf(text, sizeof text, "verbose: true\n%s", dam);
    expect_unused(text, use_dam, "case.yaml:1: unknown key 'verbose'");
    /* nested, with a suggestion */
    expect_unused("name: x\ntime:\n  t_end: 1\n  dt: 0.1\n  steps: 1\n  cfll: 0.3\nkernel: cubic\n"
                  "gravity: [0, 0]\noutput: {vtk: true, images: true, prefix: p}\n",
                  use_dam, "case.yaml:6: unknown key 'time.cfll' (did you mean 'time.cfl'?)");
    /* inside a sequence element */
    expect_unused("name: x\ntime: {t_end: 1, dt: 1, steps: 1}\nkernel: cubic\ngravity: [0, 0]\n"
                  "output: {vtk: true, images: true, prefix: p}\n"
                  "bodies:\n  - type: box\n    lo: [0, 0]\n    hi: [1, 1]\n    hj: [1, 1]\n",
                  use_dam,
                  "case.yaml:10: unknown key 'bodies[0].hj' (did you mean 'bodies[0].hi'?)");
    expect_unused("name: x\ntime: {t_end: 1, dt: 1, steps: 1}\nkernel: cubic\ngravity: [0, 0]\n"
                  "output: {vtk: true, images: true, prefix: p}\n"
                  "bodies:\n  - {type: box, lo: [0, 0], hi: [1, 1]}\n"
                  "  - {type: box, lo: [0, 0], hi: [1, 1]}\n  - {type: box, rho: 1}\n",
                  use_dam, "case.yaml:9: unknown key 'bodies[2].type'");
    expect_unused("bodies:\n  - 1\n", use_bodies_count, "case.yaml:2: unknown key 'bodies[0]'");
    expect_unused("bodies: []\n", use_bodies_count, NULL);
    expect_unused("", use_nothing, NULL);
    expect_unused("a: 1\nb: 2\n", use_nothing, "case.yaml:1: unknown key 'a'");
    /* no suggestion for short keys or far ones */
    expect_unused("name: x\ntime: {t_end: 1, dt: 1, steps: 1, zzz: 1}\nkernel: cubic\n"
                  "gravity: [0, 0]\noutput: {vtk: true, images: true, prefix: p}\n",
                  use_dam, "case.yaml:2: unknown key 'time.zzz'");

    /* keys added on the command line */
    ry_case *c = load(dam);
    ry_error e;
    assert_int_equal(ry_case_override(c, "time.dtt=1", &e), RY_OK);
    use_dam(c);
    assert_int_equal(ry_case_check_unused(c, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg,
                        "--set time.dtt=1: unknown key 'time.dtt' (did you mean 'time.dt'?)");
    ry_case_free(c);
}

/* ---------------------------------------------------------------- load errors */

static void test_load_errors(void **state) {
    (void)state;
    load_fails("a: 1\nb: 2\na: 3\n", "case.yaml:3: key 'a': duplicate key (first given on line 1)");
    load_fails("a: 1\nb:\n  c: 1\n  d: 2\n  c: 3\n",
               "case.yaml:5: key 'b.c': duplicate key (first given on line 3)");
    load_fails("list:\n  - {x: 1, x: 2}\n",
               "case.yaml:2: key 'list[0].x': duplicate key (first given on line 2)");
    load_fails("a: 1\nb: [1, 2\nc: 3\n",
               "case.yaml:4: syntax error: flow sequence without a closing bracket");
    load_fails("a: 1\nb: 2\nc: @x\nd: 4\n",
               "case.yaml:3: syntax error: plain scalar cannot start with '@'");
    load_fails("a: 1\nb: 'abc\n", "case.yaml:2: syntax error: single-quoted scalar without closing "
                                  "quote");
    load_fails("- 1\n- 2\n",
               "case.yaml:1: the top level must be a mapping of keys, got a sequence");
    load_fails("just text\n", "case.yaml:1: the top level must be a mapping of keys, got 'just "
                              "text'");
    load_fails("a: &x 1\nb: *x\n", "case.yaml:1: anchors and aliases are not supported");
    load_fails("base: {a: 1}\nc:\n  <<: *base\n", "case.yaml:3: anchors and aliases are not "
                                                  "supported");
    load_fails("a: !!str 1\n", "case.yaml:1: tags are not supported");
    load_fails("a: 1\n---\nb: 2\n", "case.yaml:3: only one YAML document is allowed");
    load_fails("? [a]\n: 1\n",
               "case.yaml:1: a key must be a plain name, not a mapping or sequence");
    load_fails("a.b: 1\n", "case.yaml:1: invalid key 'a.b' (keys must be non-empty and must not "
                           "contain '.', '[' or ']')");
    load_fails("\"\": 1\n", "case.yaml:1: invalid key '' (keys must be non-empty and must not "
                            "contain '.', '[' or ']')");
    load_fails("a: \"x\\0y\"\n", "case.yaml:1: a value contains a NUL character");

    /* hostile nesting */
    size_t depth = 100000;
    char *deep = malloc(2 * depth + 8);
    assert_non_null(deep);
    memcpy(deep, "a: ", 3);
    memset(deep + 3, '[', depth);
    memset(deep + 3 + depth, ']', depth);
    deep[3 + 2 * depth] = '\0';
    ry_case *c = NULL;
    ry_error e;
    assert_int_equal(ry_case_load_string(&c, "case.yaml", deep, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "case.yaml:1: nesting deeper than 100 levels");
    free(deep);

    /* a huge number and a long value are reported briefly */
    char *big = malloc(5000);
    assert_non_null(big);
    memcpy(big, "a: ", 3);
    memset(big + 3, '9', 4000);
    big[4003] = '\0';
    c = load(big);
    double x;
    assert_int_equal(ry_case_double(c, "a", NULL, -INFINITY, INFINITY, &x, &e), RY_ERR_INPUT);
    assert_true(strlen(e.msg) < 200);
    ry_case_free(c);
    free(big);
}

static void test_files(void **state) {
    (void)state;
    ry_case *c = NULL;
    ry_error e;
    assert_int_equal(ry_case_load(&c, "no-such-case.yaml", &e), RY_ERR_IO);
    assert_null(c);
    assert_string_equal(e.msg, "cannot read 'no-such-case.yaml': No such file or directory");

    const char *path = "test_case_file.yaml";
    write_file(path, "");
    assert_int_equal(ry_case_load(&c, path, &e), RY_OK);
    double x;
    assert_int_equal(ry_case_double(c, "a", NULL, 0, 1, &x, &e), RY_ERR_INPUT);
    assert_string_equal(e.msg, "test_case_file.yaml: key 'a': required key is missing");
    assert_int_equal(ry_case_check_unused(c, &e), RY_OK);
    ry_case_free(c);

    write_file(path, "# only a comment\n");
    assert_int_equal(ry_case_load(&c, path, &e), RY_OK);
    assert_false(ry_case_has(c, "a"));
    ry_case_free(c);

    write_file(path, "# header\n\nsteps: 2.5\n");
    assert_int_equal(ry_case_load(&c, path, &e), RY_OK);
    long k;
    assert_int_equal(ry_case_int(c, "steps", NULL, 0, 10, &k, &e), RY_ERR_INPUT);
    assert_string_equal(
        e.msg, "test_case_file.yaml:3: key 'steps': expected an integer in [0, 10], got '2.5'");
    ry_case_free(c);

    write_file(path, "a: 1\n  b: 2\n");
    assert_int_equal(ry_case_load(&c, path, &e), RY_ERR_INPUT);
    assert_true(strncmp(e.msg, "test_case_file.yaml:", 20) == 0);
    assert_non_null(strstr(e.msg, "syntax error"));
    remove(path);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_getters),
        cmocka_unit_test(test_number_errors),
        cmocka_unit_test(test_vector_element_error),
        cmocka_unit_test(test_missing_required),
        cmocka_unit_test(test_defaults_resolved),
        cmocka_unit_test(test_resolved_round_trip_styles),
        cmocka_unit_test(test_overrides),
        cmocka_unit_test(test_override_errors),
        cmocka_unit_test(test_unknown_keys),
        cmocka_unit_test(test_load_errors),
        cmocka_unit_test(test_files),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
