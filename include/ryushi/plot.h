/* ryushi — line plots written to PNG (drawn with cairo).
 *
 * A figure is a grid of rows x cols panels, numbered row by row from 0. Each panel has an
 * optional title and axis labels, x and y ranges (automatic from its data, rounded out to
 * tick values, unless fixed), ticks with numeric labels, a grid, and any number of series;
 * each series is drawn as a line and/or markers in a colour of a fixed palette, and every
 * series with a label gets a legend entry. Non-finite points are skipped (a line is broken
 * there). The PNG is written atomically. No function prints.
 *
 *   ry_plot *p;
 *   RY_TRY(ry_plot_new(&p, 1, 2, 1400, 600, err));
 *   ry_plot_panel(p, 0, "Surge front", "t (s)", "x (m)", err);
 *   ry_plot_series(p, 0, "simulation", n, t, x, ry_plot_style_line(), err);
 *   ry_plot_series(p, 0, "experiment", m, te, xe, ry_plot_style_markers(RY_PLOT_MARKER_CIRCLE),
 *                  err);
 *   ry_plot_write_png(p, "front.png", err);
 *   ry_plot_free(p);
 */
#ifndef RYUSHI_PLOT_H
#define RYUSHI_PLOT_H

#include <stddef.h>

#include "ryushi/status.h"

typedef struct ry_plot ry_plot;

typedef enum ry_plot_marker {
    RY_PLOT_MARKER_NONE = 0,
    RY_PLOT_MARKER_CIRCLE,
    RY_PLOT_MARKER_SQUARE,
    RY_PLOT_MARKER_TRIANGLE,
    RY_PLOT_MARKER_DIAMOND,
    RY_PLOT_MARKER_CROSS, /* x */
    RY_PLOT_MARKER_PLUS,  /* + */
    RY_PLOT_MARKER_COUNT
} ry_plot_marker;

typedef enum ry_plot_dash {
    RY_PLOT_DASH_SOLID = 0,
    RY_PLOT_DASH_DASHED,
    RY_PLOT_DASH_DOTTED,
    RY_PLOT_DASH_DASHDOT,
    RY_PLOT_DASH_COUNT
} ry_plot_dash;

/* Where a panel's legend goes (inside the plot area); NONE hides it. */
typedef enum ry_plot_legend_pos {
    RY_PLOT_LEGEND_NE = 0, /* top right (the default) */
    RY_PLOT_LEGEND_NW,
    RY_PLOT_LEGEND_SE,
    RY_PLOT_LEGEND_SW,
    RY_PLOT_LEGEND_NONE,
    RY_PLOT_LEGEND_COUNT
} ry_plot_legend_pos;

enum {
    RY_PLOT_PALETTE_SIZE = 10, /* colours of the fixed palette */
    RY_PLOT_COLOR_AUTO = -1,   /* the panel's next palette colour */
    RY_PLOT_MAX_GRID = 8,      /* at most this many rows and columns */
    RY_PLOT_MIN_PX = 64,       /* figure size limits in pixels */
    RY_PLOT_MAX_PX = 16384
};

typedef struct ry_plot_style {
    int line;              /* nonzero: a polyline through the points */
    ry_plot_dash dash;     /* pattern of the line */
    ry_plot_marker marker; /* marker at every point, or none */
    int hollow;            /* nonzero: markers are outlined, not filled */
    int color;             /* palette index 0..RY_PLOT_PALETTE_SIZE-1 or RY_PLOT_COLOR_AUTO */
    double line_width;     /* pixels; <= 0: the default (2) */
    double marker_size;    /* marker width in pixels; <= 0: the default (8) */
} ry_plot_style;

/* A solid line in the next palette colour. */
ry_plot_style ry_plot_style_line(void);
/* Markers only, in the next palette colour. */
ry_plot_style ry_plot_style_markers(ry_plot_marker marker);
/* The palette colour i (taken modulo the palette size) as r, g, b in [0, 1]. */
void ry_plot_palette_rgb(int i, double rgb[3]);

/* A new empty figure of rows x cols panels (1..RY_PLOT_MAX_GRID each) and width x height
 * pixels (RY_PLOT_MIN_PX..RY_PLOT_MAX_PX each). *out is NULL on failure. */
ry_status ry_plot_new(ry_plot **out, int rows, int cols, int width_px, int height_px,
                      ry_error *err);
void ry_plot_free(ry_plot *p);

/* A title above the whole figure (NULL or "" for none). */
ry_status ry_plot_title(ry_plot *p, const char *title, ry_error *err);
/* The title and axis labels of panel (NULL or "" for none). */
ry_status ry_plot_panel(ry_plot *p, int panel, const char *title, const char *xlabel,
                        const char *ylabel, ry_error *err);
/* Adds a series of n >= 1 points (x[i], y[i]), copied. label NULL or "": no legend entry. The
 * style must draw something (a line or a marker). */
ry_status ry_plot_series(ry_plot *p, int panel, const char *label, size_t n, const double *x,
                         const double *y, ry_plot_style style, ry_error *err);
/* Fixes an axis range (lo < hi, both finite); otherwise it follows the data. */
ry_status ry_plot_xrange(ry_plot *p, int panel, double lo, double hi, ry_error *err);
ry_status ry_plot_yrange(ry_plot *p, int panel, double lo, double hi, ry_error *err);
/* Moves or hides the legend of a panel. */
ry_status ry_plot_legend(ry_plot *p, int panel, ry_plot_legend_pos pos, ry_error *err);

/* Draws the figure and writes it to path as a PNG (atomically). */
ry_status ry_plot_write_png(const ry_plot *p, const char *path, ry_error *err);

/* Releases the font and glyph caches cairo keeps between figures, so that leak checkers see
 * no memory left at exit. Call it at most once, at the end of the program, when no thread
 * is drawing; plotting again afterwards is allowed (the caches are rebuilt). */
void ry_plot_release_caches(void);

/* The seed-000 comparison figure: W and dW/dx of the Lucy and Gaussian kernels, with the
 * cubic spline for reference, in 1D with h = 1 (src/plot/kernel_figure.c). */
ry_status ry_plot_kernel_comparison(const char *png_path, ry_error *err);

#endif
