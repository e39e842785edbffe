/* Unit tests of the PNG line plots (include/ryushi/plot.h). */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <cmocka.h>

#include <cairo.h>
#include <dirent.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ryushi/plot.h"

/* Under LeakSanitizer: fontconfig, which cairo uses to find fonts, keeps a font pattern for the
 * life of the process that no library call frees; it is not a leak of this project. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void) {
    return "leak:libfontconfig.so\n";
}

typedef struct tmpdir {
    char path[512];
} tmpdir;

static int setup(void **state) {
    tmpdir *t = calloc(1, sizeof *t);
    if (!t) return -1;
    const char *base = getenv("TMPDIR");
    snprintf(t->path, sizeof t->path, "%s/ryushi-plot-XXXXXX", base && *base ? base : "/tmp");
    if (!mkdtemp(t->path)) {
        free(t);
        return -1;
    }
    *state = t;
    return 0;
}

static int teardown(void **state) {
    tmpdir *t = *state;
    DIR *d = opendir(t->path);
    if (d) {
        struct dirent *e;
        char file[1024];
        while ((e = readdir(d)) != NULL) {
            if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
            snprintf(file, sizeof file, "%s/%s", t->path, e->d_name);
            remove(file);
        }
        closedir(d);
    }
    rmdir(t->path);
    free(t);
    return 0;
}

/* Number of entries in a folder besides . and .. */
static int count_files(const char *dir) {
    DIR *d = opendir(dir);
    assert_non_null(d);
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        if (strcmp(e->d_name, ".") != 0 && strcmp(e->d_name, "..") != 0) n++;
    closedir(d);
    return n;
}

/* Checks that path is a PNG of w x h pixels; returns the number of pixels close to rgb. */
static long check_png(const char *path, int w, int h, const double rgb[3]) {
    static const unsigned char magic[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
    unsigned char head[8];
    FILE *fp = fopen(path, "rb");
    assert_non_null(fp);
    assert_int_equal(fread(head, 1, 8, fp), 8);
    fclose(fp);
    assert_memory_equal(head, magic, 8);
    cairo_surface_t *s = cairo_image_surface_create_from_png(path);
    assert_int_equal(cairo_surface_status(s), CAIRO_STATUS_SUCCESS);
    assert_int_equal(cairo_image_surface_get_width(s), w);
    assert_int_equal(cairo_image_surface_get_height(s), h);
    cairo_surface_flush(s);
    const unsigned char *data = cairo_image_surface_get_data(s);
    int stride = cairo_image_surface_get_stride(s);
    long hits = 0;
    for (int j = 0; j < h; j++) {
        const uint32_t *row = (const uint32_t *)(const void *)(data + (size_t)j * stride);
        for (int i = 0; i < w; i++) {
            uint32_t px = row[i];
            double c[3] = {((px >> 16) & 255) / 255.0, ((px >> 8) & 255) / 255.0,
                           (px & 255) / 255.0};
            if (fabs(c[0] - rgb[0]) < 0.03 && fabs(c[1] - rgb[1]) < 0.03 &&
                fabs(c[2] - rgb[2]) < 0.03)
                hits++;
        }
    }
    cairo_surface_destroy(s);
    return hits;
}

static void test_write_png(void **state) {
    tmpdir *t = *state;
    ry_error err;
    ry_error_clear(&err);
    ry_plot *p = NULL;
    assert_int_equal(ry_plot_new(&p, 2, 2, 900, 640, &err), RY_OK);
    assert_int_equal(ry_plot_title(p, "Test figure", &err), RY_OK);
    enum { N = 200 };
    double x[N], y[N], y2[N];
    for (int i = 0; i < N; i++) {
        x[i] = 0.05 * i;
        y[i] = sin(x[i]);
        y2[i] = i == 50 ? NAN : 1e4 * cos(x[i]);
    }
    /* Panel 0: a line only, coloured 3, so its colour can be found in the image. */
    ry_plot_style line = ry_plot_style_line();
    line.color = 3;
    line.line_width = 3.0;
    assert_int_equal(ry_plot_panel(p, 0, "sine", "t (s)", "x (m)", &err), RY_OK);
    assert_int_equal(ry_plot_series(p, 0, "sin t", N, x, y, line, &err), RY_OK);
    /* Panel 1: several styles, a break at a NaN, large values, a fixed x range. */
    assert_int_equal(ry_plot_panel(p, 1, "styles", "t", NULL, &err), RY_OK);
    ry_plot_style dashed = ry_plot_style_line();
    dashed.dash = RY_PLOT_DASH_DASHED;
    assert_int_equal(ry_plot_series(p, 1, "dashed", N, x, y2, dashed, &err), RY_OK);
    for (int m = RY_PLOT_MARKER_CIRCLE; m < RY_PLOT_MARKER_COUNT; m++) {
        ry_plot_style ms = ry_plot_style_markers((ry_plot_marker)m);
        ms.hollow = m % 2;
        ms.line = m == RY_PLOT_MARKER_SQUARE;
        ms.dash = RY_PLOT_DASH_DOTTED;
        double xm[3] = {m, m + 0.5, m + 1.0}, ym[3] = {-5e3, 0.0, 5e3 * m};
        assert_int_equal(ry_plot_series(p, 1, m % 3 ? "markers" : NULL, 3, xm, ym, ms, &err),
                         RY_OK);
    }
    assert_int_equal(ry_plot_xrange(p, 1, 0.0, 7.5, &err), RY_OK);
    assert_int_equal(ry_plot_legend(p, 1, RY_PLOT_LEGEND_SW, &err), RY_OK);
    /* Panel 2: a constant series (degenerate range) and fixed y range. */
    double c[3] = {2.0, 2.0, 2.0}, cx[3] = {1.0, 1.0, 1.0};
    ry_plot_style dd = ry_plot_style_line();
    dd.dash = RY_PLOT_DASH_DASHDOT;
    assert_int_equal(ry_plot_series(p, 2, "constant", 3, cx, c, dd, &err), RY_OK);
    assert_int_equal(ry_plot_yrange(p, 2, -1e-6, 1e-6, &err), RY_OK);
    assert_int_equal(ry_plot_legend(p, 2, RY_PLOT_LEGEND_NONE, &err), RY_OK);
    /* Panel 3 stays empty. */

    char path[1024];
    snprintf(path, sizeof path, "%s/figure.png", t->path);
    assert_int_equal(ry_plot_write_png(p, path, &err), RY_OK);
    double red[3];
    ry_plot_palette_rgb(3, red);
    assert_true(check_png(path, 900, 640, red) > 100);
    double white[3] = {1.0, 1.0, 1.0};
    assert_true(check_png(path, 900, 640, white) > 900 * 640 / 2);
    /* Written atomically: no temporary file left behind. */
    assert_int_equal(count_files(t->path), 1);
    /* Overwriting works. */
    assert_int_equal(ry_plot_write_png(p, path, &err), RY_OK);
    assert_int_equal(count_files(t->path), 1);
    ry_plot_free(p);
}

static void test_single_panel_extremes(void **state) {
    tmpdir *t = *state;
    ry_error err;
    ry_plot *p = NULL;
    assert_int_equal(ry_plot_new(&p, 1, 1, 64, 64, &err), RY_OK);
    double x[4] = {-1e300, 0.0, 1e300, INFINITY}, y[4] = {1e-300, -1e300, 1e300, 0.0};
    assert_int_equal(ry_plot_series(p, 0, "huge", 4, x, y, ry_plot_style_line(), &err), RY_OK);
    char path[1024];
    snprintf(path, sizeof path, "%s/tiny.png", t->path);
    assert_int_equal(ry_plot_write_png(p, path, &err), RY_OK);
    double white[3] = {1.0, 1.0, 1.0};
    assert_true(check_png(path, 64, 64, white) > 0);
    ry_plot_free(p);
    ry_plot_free(NULL);
}

static void test_bad_input(void **state) {
    tmpdir *t = *state;
    ry_error err;
    ry_error_clear(&err);
    ry_plot *p = NULL;
    assert_int_equal(ry_plot_new(&p, 0, 1, 400, 300, &err), RY_ERR_RANGE);
    assert_null(p);
    assert_int_equal(ry_plot_new(&p, 1, RY_PLOT_MAX_GRID + 1, 400, 300, &err), RY_ERR_RANGE);
    assert_int_equal(ry_plot_new(&p, 1, 1, 10, 300, &err), RY_ERR_RANGE);
    assert_int_equal(ry_plot_new(&p, 1, 1, 400, RY_PLOT_MAX_PX + 1, &err), RY_ERR_RANGE);
    assert_int_equal(ry_plot_new(&p, 1, 2, 400, 300, &err), RY_OK);

    double x[2] = {0.0, 1.0}, y[2] = {1.0, 2.0};
    ry_plot_style line = ry_plot_style_line();
    ry_error_clear(&err);
    assert_int_equal(ry_plot_series(p, 0, "empty", 0, x, y, line, &err), RY_ERR_INPUT);
    assert_non_null(strstr(err.msg, "no points"));
    assert_int_equal(ry_plot_series(p, 0, "null", 2, NULL, y, line, &err), RY_ERR_INPUT);
    assert_int_equal(ry_plot_series(p, 2, "panel", 2, x, y, line, &err), RY_ERR_RANGE);
    assert_int_equal(ry_plot_series(p, -1, "panel", 2, x, y, line, &err), RY_ERR_RANGE);
    ry_plot_style nothing = {0};
    assert_int_equal(ry_plot_series(p, 0, "nothing", 2, x, y, nothing, &err), RY_ERR_INPUT);
    ry_plot_style badc = ry_plot_style_line();
    badc.color = RY_PLOT_PALETTE_SIZE;
    assert_int_equal(ry_plot_series(p, 0, "colour", 2, x, y, badc, &err), RY_ERR_RANGE);
    ry_plot_style badm = ry_plot_style_markers(RY_PLOT_MARKER_COUNT);
    assert_int_equal(ry_plot_series(p, 0, "marker", 2, x, y, badm, &err), RY_ERR_INPUT);
    assert_int_equal(ry_plot_xrange(p, 0, 1.0, 1.0, &err), RY_ERR_RANGE);
    assert_int_equal(ry_plot_xrange(p, 0, 0.0, NAN, &err), RY_ERR_RANGE);
    assert_int_equal(ry_plot_yrange(p, 0, 2.0, -2.0, &err), RY_ERR_RANGE);
    assert_int_equal(ry_plot_yrange(p, 5, 0.0, 1.0, &err), RY_ERR_RANGE);
    assert_int_equal(ry_plot_legend(p, 0, RY_PLOT_LEGEND_COUNT, &err), RY_ERR_INPUT);
    assert_int_equal(ry_plot_panel(p, 3, "t", "x", "y", &err), RY_ERR_RANGE);

    /* A folder that does not exist: an I/O error and no file. */
    assert_int_equal(ry_plot_series(p, 0, "ok", 2, x, y, line, &err), RY_OK);
    char path[1024];
    snprintf(path, sizeof path, "%s/no-such-folder/figure.png", t->path);
    ry_error_clear(&err);
    assert_int_equal(ry_plot_write_png(p, path, &err), RY_ERR_IO);
    assert_non_null(strstr(err.msg, "no-such-folder"));
    assert_int_equal(count_files(t->path), 0);
    assert_int_equal(ry_plot_write_png(p, "", &err), RY_ERR_INPUT);
    ry_plot_free(p);
}

static void test_kernel_comparison_figure(void **state) {
    tmpdir *t = *state;
    ry_error err;
    ry_error_clear(&err);
    char path[1024];
    snprintf(path, sizeof path, "%s/kernels.png", t->path);
    assert_int_equal(ry_plot_kernel_comparison(path, &err), RY_OK);
    double blue[3];
    ry_plot_palette_rgb(0, blue);
    assert_true(check_png(path, 1500, 620, blue) > 500);
    snprintf(path, sizeof path, "%s/missing/kernels.png", t->path);
    assert_int_equal(ry_plot_kernel_comparison(path, &err), RY_ERR_IO);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_setup_teardown(test_write_png, setup, teardown),
        cmocka_unit_test_setup_teardown(test_single_panel_extremes, setup, teardown),
        cmocka_unit_test_setup_teardown(test_bad_input, setup, teardown),
        cmocka_unit_test_setup_teardown(test_kernel_comparison_figure, setup, teardown),
    };
    int failed = cmocka_run_group_tests(tests, NULL, NULL);
    ry_plot_release_caches();
    return failed;
}
