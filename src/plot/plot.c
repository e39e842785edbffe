/* Line plots to PNG with cairo (see include/ryushi/plot.h). */
#include "ryushi/plot.h"

#include <cairo.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ryushi/atomic_file.h"

#define PLOT_PI 3.14159265358979323846
#define PLOT_FONT "sans-serif"

typedef struct plot_series {
    char *label; /* NULL: no legend entry */
    size_t n;
    double *x, *y;
    ry_plot_style style;
    int color; /* resolved palette index */
} plot_series;

typedef struct plot_panel {
    char *title, *xlabel, *ylabel;
    plot_series *series;
    size_t nseries, cap;
    int fixed_x, fixed_y;
    double xlo, xhi, ylo, yhi;
    ry_plot_legend_pos legend;
    int next_color;
} plot_panel;

struct ry_plot {
    int rows, cols, width, height;
    char *title;
    plot_panel *panels;
};

/* Tableau 10, the usual categorical palette of plotting programs. */
static const unsigned char palette[RY_PLOT_PALETTE_SIZE][3] = {
    {31, 119, 180}, {255, 127, 14},  {44, 160, 44},   {214, 39, 40},  {148, 103, 189},
    {140, 86, 75},  {227, 119, 194}, {127, 127, 127}, {188, 189, 34}, {23, 190, 207},
};

void ry_plot_palette_rgb(int i, double rgb[3]) {
    int k = ((i % RY_PLOT_PALETTE_SIZE) + RY_PLOT_PALETTE_SIZE) % RY_PLOT_PALETTE_SIZE;
    for (int c = 0; c < 3; c++) rgb[c] = palette[k][c] / 255.0;
}

ry_plot_style ry_plot_style_line(void) {
    ry_plot_style s = {0};
    s.line = 1;
    s.color = RY_PLOT_COLOR_AUTO;
    return s;
}

ry_plot_style ry_plot_style_markers(ry_plot_marker marker) {
    ry_plot_style s = {0};
    s.marker = marker;
    s.color = RY_PLOT_COLOR_AUTO;
    return s;
}

/* A copy of s, or NULL for NULL or "" (then *ok stays 1); *ok = 0 when out of memory. */
static char *dup_opt(const char *s, int *ok) {
    if (!s || !*s) return NULL;
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (!d) {
        *ok = 0;
        return NULL;
    }
    memcpy(d, s, n);
    return d;
}

ry_status ry_plot_new(ry_plot **out, int rows, int cols, int width_px, int height_px,
                      ry_error *err) {
    RY_CHECK(err, out != NULL, RY_ERR_INTERNAL, "ry_plot_new: no output pointer");
    *out = NULL;
    RY_CHECK(err, rows >= 1 && rows <= RY_PLOT_MAX_GRID && cols >= 1 && cols <= RY_PLOT_MAX_GRID,
             RY_ERR_RANGE, "plot: %d x %d panels, rows and columns must be in 1..%d", rows, cols,
             RY_PLOT_MAX_GRID);
    RY_CHECK(err,
             width_px >= RY_PLOT_MIN_PX && width_px <= RY_PLOT_MAX_PX &&
                 height_px >= RY_PLOT_MIN_PX && height_px <= RY_PLOT_MAX_PX,
             RY_ERR_RANGE, "plot: size %d x %d pixels, each side must be in %d..%d", width_px,
             height_px, RY_PLOT_MIN_PX, RY_PLOT_MAX_PX);
    ry_plot *p = calloc(1, sizeof *p);
    if (p) p->panels = calloc((size_t)rows * (size_t)cols, sizeof *p->panels);
    if (!p || !p->panels) {
        free(p);
        return ry_error_set(err, RY_ERR_NOMEM, "plot: out of memory");
    }
    p->rows = rows;
    p->cols = cols;
    p->width = width_px;
    p->height = height_px;
    for (int i = 0; i < rows * cols; i++) p->panels[i].legend = RY_PLOT_LEGEND_NE;
    *out = p;
    return RY_OK;
}

void ry_plot_free(ry_plot *p) {
    if (!p) return;
    for (int i = 0; i < p->rows * p->cols; i++) {
        plot_panel *pn = &p->panels[i];
        for (size_t s = 0; s < pn->nseries; s++) {
            free(pn->series[s].label);
            free(pn->series[s].x);
            free(pn->series[s].y);
        }
        free(pn->series);
        free(pn->title);
        free(pn->xlabel);
        free(pn->ylabel);
    }
    free(p->panels);
    free(p->title);
    free(p);
}

ry_status ry_plot_title(ry_plot *p, const char *title, ry_error *err) {
    RY_CHECK(err, p != NULL, RY_ERR_INTERNAL, "plot: no figure");
    int ok = 1;
    char *t = dup_opt(title, &ok);
    if (!ok) return ry_error_set(err, RY_ERR_NOMEM, "plot: out of memory");
    free(p->title);
    p->title = t;
    return RY_OK;
}

static ry_status get_panel(ry_plot *p, int panel, plot_panel **out, ry_error *err) {
    RY_CHECK(err, p != NULL, RY_ERR_INTERNAL, "plot: no figure");
    RY_CHECK(err, panel >= 0 && panel < p->rows * p->cols, RY_ERR_RANGE,
             "plot: panel %d does not exist (the figure has %d)", panel, p->rows * p->cols);
    *out = &p->panels[panel];
    return RY_OK;
}

ry_status ry_plot_panel(ry_plot *p, int panel, const char *title, const char *xlabel,
                        const char *ylabel, ry_error *err) {
    plot_panel *pn = NULL;
    RY_TRY(get_panel(p, panel, &pn, err));
    int ok = 1;
    char *t = dup_opt(title, &ok), *xl = dup_opt(xlabel, &ok), *yl = dup_opt(ylabel, &ok);
    if (!ok) {
        free(t);
        free(xl);
        free(yl);
        return ry_error_set(err, RY_ERR_NOMEM, "plot: out of memory");
    }
    free(pn->title);
    free(pn->xlabel);
    free(pn->ylabel);
    pn->title = t;
    pn->xlabel = xl;
    pn->ylabel = yl;
    return RY_OK;
}

ry_status ry_plot_series(ry_plot *p, int panel, const char *label, size_t n, const double *x,
                         const double *y, ry_plot_style style, ry_error *err) {
    plot_panel *pn = NULL;
    RY_TRY(get_panel(p, panel, &pn, err));
    const char *name = label && *label ? label : "(unlabelled)";
    RY_CHECK(err, n >= 1, RY_ERR_INPUT, "plot: series '%s' has no points", name);
    RY_CHECK(err, x != NULL && y != NULL, RY_ERR_INPUT, "plot: series '%s' has no data", name);
    RY_CHECK(err, n <= SIZE_MAX / sizeof(double), RY_ERR_RANGE,
             "plot: series '%s' has too many points", name);
    RY_CHECK(err, (int)style.marker >= 0 && style.marker < RY_PLOT_MARKER_COUNT, RY_ERR_INPUT,
             "plot: series '%s': unknown marker %d", name, (int)style.marker);
    RY_CHECK(err, (int)style.dash >= 0 && style.dash < RY_PLOT_DASH_COUNT, RY_ERR_INPUT,
             "plot: series '%s': unknown line pattern %d", name, (int)style.dash);
    RY_CHECK(err, style.line || style.marker != RY_PLOT_MARKER_NONE, RY_ERR_INPUT,
             "plot: series '%s' is drawn with neither a line nor markers", name);
    RY_CHECK(err,
             style.color == RY_PLOT_COLOR_AUTO ||
                 (style.color >= 0 && style.color < RY_PLOT_PALETTE_SIZE),
             RY_ERR_RANGE, "plot: series '%s': colour %d is not in the palette (0..%d)", name,
             style.color, RY_PLOT_PALETTE_SIZE - 1);
    if (pn->nseries == pn->cap) {
        size_t cap = pn->cap ? 2 * pn->cap : 4;
        plot_series *s = realloc(pn->series, cap * sizeof *s);
        if (!s) return ry_error_set(err, RY_ERR_NOMEM, "plot: out of memory");
        pn->series = s;
        pn->cap = cap;
    }
    plot_series s = {0};
    int ok = 1;
    s.label = dup_opt(label, &ok);
    s.x = malloc(n * sizeof(double));
    s.y = malloc(n * sizeof(double));
    if (!ok || !s.x || !s.y) {
        free(s.label);
        free(s.x);
        free(s.y);
        return ry_error_set(err, RY_ERR_NOMEM, "plot: out of memory for series '%s'", name);
    }
    memcpy(s.x, x, n * sizeof(double));
    memcpy(s.y, y, n * sizeof(double));
    s.n = n;
    s.style = style;
    s.color =
        style.color == RY_PLOT_COLOR_AUTO ? pn->next_color++ % RY_PLOT_PALETTE_SIZE : style.color;
    pn->series[pn->nseries++] = s;
    return RY_OK;
}

static ry_status check_range(double lo, double hi, const char *axis, ry_error *err) {
    RY_CHECK(err, isfinite(lo) && isfinite(hi) && lo < hi && isfinite(hi - lo), RY_ERR_RANGE,
             "plot: %s range [%g, %g] must be finite with lo < hi", axis, lo, hi);
    return RY_OK;
}

ry_status ry_plot_xrange(ry_plot *p, int panel, double lo, double hi, ry_error *err) {
    plot_panel *pn = NULL;
    RY_TRY(get_panel(p, panel, &pn, err));
    RY_TRY(check_range(lo, hi, "x", err));
    pn->fixed_x = 1;
    pn->xlo = lo;
    pn->xhi = hi;
    return RY_OK;
}

ry_status ry_plot_yrange(ry_plot *p, int panel, double lo, double hi, ry_error *err) {
    plot_panel *pn = NULL;
    RY_TRY(get_panel(p, panel, &pn, err));
    RY_TRY(check_range(lo, hi, "y", err));
    pn->fixed_y = 1;
    pn->ylo = lo;
    pn->yhi = hi;
    return RY_OK;
}

ry_status ry_plot_legend(ry_plot *p, int panel, ry_plot_legend_pos pos, ry_error *err) {
    plot_panel *pn = NULL;
    RY_TRY(get_panel(p, panel, &pn, err));
    RY_CHECK(err, (int)pos >= 0 && pos < RY_PLOT_LEGEND_COUNT, RY_ERR_INPUT,
             "plot: unknown legend position %d", (int)pos);
    pn->legend = pos;
    return RY_OK;
}

/* ---- axes and ticks ---- */

enum { MAX_TICKS = 64, TICK_LABEL_MAX = 32 };

typedef struct plot_axis {
    double lo, hi, step;
    int nticks;
    double ticks[MAX_TICKS];
    char labels[MAX_TICKS][TICK_LABEL_MAX];
} plot_axis;

/* 1, 2 or 5 times a power of ten near span / target. */
static double nice_step(double span, int target) {
    double raw = span / target;
    double mag = pow(10.0, floor(log10(raw)));
    double f = raw / mag;
    double nf = f < 1.5 ? 1.0 : f < 3.0 ? 2.0 : f < 7.0 ? 5.0 : 10.0;
    return nf * mag;
}

/* Data extent of a panel along x (which = 0) or y (which = 1); returns 0 when no finite point. */
static int data_extent(const plot_panel *pn, int which, double *lo, double *hi) {
    double a = INFINITY, b = -INFINITY;
    for (size_t s = 0; s < pn->nseries; s++) {
        const plot_series *se = &pn->series[s];
        for (size_t i = 0; i < se->n; i++) {
            double x = se->x[i], y = se->y[i];
            if (!isfinite(x) || !isfinite(y)) continue;
            /* With the other axis fixed, only the points inside it count. */
            if (which == 1 && pn->fixed_x && (x < pn->xlo || x > pn->xhi)) continue;
            if (which == 0 && pn->fixed_y && (y < pn->ylo || y > pn->yhi)) continue;
            double v = which ? y : x;
            if (v < a) a = v;
            if (v > b) b = v;
        }
    }
    *lo = a;
    *hi = b;
    return a <= b;
}

static void format_tick(char *buf, double v, double step, double maxabs) {
    if (fabs(v) < 1e-9 * step) v = 0.0;
    if (maxabs >= 1e6 || maxabs < 1e-4) {
        int prec = (int)(floor(log10(maxabs > 0.0 ? maxabs : 1.0)) - floor(log10(step))) + 1;
        if (prec < 1) prec = 1;
        if (prec > 15) prec = 15;
        snprintf(buf, TICK_LABEL_MAX, "%.*g", prec, v);
    } else {
        int dec = step >= 1.0 ? 0 : (int)ceil(-log10(step) - 1e-9);
        snprintf(buf, TICK_LABEL_MAX, "%.*f", dec, v);
    }
}

static void axis_setup(plot_axis *a, const plot_panel *pn, int which, int target) {
    int fixed = which ? pn->fixed_y : pn->fixed_x;
    double lo, hi;
    if (fixed) {
        lo = which ? pn->ylo : pn->xlo;
        hi = which ? pn->yhi : pn->xhi;
    } else if (!data_extent(pn, which, &lo, &hi)) {
        lo = 0.0;
        hi = 1.0;
    }
    if (!fixed && !(hi - lo > 1e-12 * fmax(fabs(lo), fabs(hi)))) {
        double pad = lo != 0.0 ? 0.5 * fabs(lo) : 1.0;
        lo -= pad;
        hi += pad;
    }
    if (!isfinite(hi - lo)) { /* data spanning the whole double range */
        lo = -1e300;
        hi = 1e300;
    }
    if (target < 2) target = 2;
    double step = nice_step(hi - lo, target);
    if (!fixed) {
        lo = floor(lo / step + 1e-9) * step;
        hi = ceil(hi / step - 1e-9) * step;
    }
    a->lo = lo;
    a->hi = hi;
    a->step = step;
    a->nticks = 0;
    double first = ceil(lo / step - 1e-9);
    double maxabs = fmax(fabs(lo), fabs(hi));
    for (int i = 0; a->nticks < MAX_TICKS; i++) {
        double v = (first + i) * step;
        if (v > hi + 1e-9 * step) break;
        a->ticks[a->nticks] = v;
        format_tick(a->labels[a->nticks], v, step, maxabs);
        a->nticks++;
    }
}

/* ---- drawing helpers ---- */

/* Draws text with its anchor at (x, y): ha 0 left, 0.5 centre, 1 right; va 0 top, 0.5 middle,
 * 1 bottom (of the font's ascent and descent). angle in radians, counterclockwise. */
static void draw_text(cairo_t *cr, double x, double y, const char *s, double ha, double va,
                      double angle) {
    cairo_text_extents_t te;
    cairo_font_extents_t fe;
    cairo_text_extents(cr, s, &te);
    cairo_font_extents(cr, &fe);
    double h = fe.ascent + fe.descent;
    cairo_save(cr);
    cairo_translate(cr, x, y);
    cairo_rotate(cr, -angle);
    cairo_move_to(cr, -ha * te.x_advance, -va * h + fe.ascent);
    cairo_show_text(cr, s);
    cairo_restore(cr);
}

static double text_width(cairo_t *cr, const char *s) {
    cairo_text_extents_t te;
    cairo_text_extents(cr, s, &te);
    return te.x_advance;
}

static double font_height(cairo_t *cr) {
    cairo_font_extents_t fe;
    cairo_font_extents(cr, &fe);
    return fe.ascent + fe.descent;
}

static void set_font(cairo_t *cr, double size, int bold) {
    cairo_select_font_face(cr, PLOT_FONT, CAIRO_FONT_SLANT_NORMAL,
                           bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, size);
}

static void set_color(cairo_t *cr, int color) {
    double rgb[3];
    ry_plot_palette_rgb(color, rgb);
    cairo_set_source_rgb(cr, rgb[0], rgb[1], rgb[2]);
}

static double style_line_width(const ry_plot_style *st) {
    return st->line_width > 0.0 ? st->line_width : 2.0;
}

static double style_marker_size(const ry_plot_style *st) {
    return st->marker_size > 0.0 ? st->marker_size : 8.0;
}

static void set_dash(cairo_t *cr, ry_plot_dash dash, double lw) {
    double u = lw > 1.0 ? lw : 1.0;
    double dashed[] = {5.0 * u, 3.0 * u};
    double dotted[] = {0.01, 2.2 * u};
    double dashdot[] = {6.0 * u, 2.5 * u, 0.01, 2.5 * u};
    cairo_set_line_cap(cr, dash == RY_PLOT_DASH_DOTTED || dash == RY_PLOT_DASH_DASHDOT
                               ? CAIRO_LINE_CAP_ROUND
                               : CAIRO_LINE_CAP_BUTT);
    switch (dash) {
    case RY_PLOT_DASH_DASHED:
        cairo_set_dash(cr, dashed, 2, 0.0);
        break;
    case RY_PLOT_DASH_DOTTED:
        cairo_set_dash(cr, dotted, 2, 0.0);
        break;
    case RY_PLOT_DASH_DASHDOT:
        cairo_set_dash(cr, dashdot, 4, 0.0);
        break;
    default:
        cairo_set_dash(cr, NULL, 0, 0.0);
        break;
    }
}

static void draw_marker(cairo_t *cr, double x, double y, const ry_plot_style *st, int color) {
    double s = style_marker_size(st), r = 0.5 * s;
    cairo_new_path(cr);
    switch (st->marker) {
    case RY_PLOT_MARKER_CIRCLE:
        cairo_arc(cr, x, y, r, 0.0, 2.0 * PLOT_PI);
        break;
    case RY_PLOT_MARKER_SQUARE:
        cairo_rectangle(cr, x - 0.9 * r, y - 0.9 * r, 1.8 * r, 1.8 * r);
        break;
    case RY_PLOT_MARKER_TRIANGLE:
        cairo_move_to(cr, x, y - 1.1 * r);
        cairo_line_to(cr, x + r, y + 0.7 * r);
        cairo_line_to(cr, x - r, y + 0.7 * r);
        cairo_close_path(cr);
        break;
    case RY_PLOT_MARKER_DIAMOND:
        cairo_move_to(cr, x, y - 1.15 * r);
        cairo_line_to(cr, x + 0.8 * r, y);
        cairo_line_to(cr, x, y + 1.15 * r);
        cairo_line_to(cr, x - 0.8 * r, y);
        cairo_close_path(cr);
        break;
    case RY_PLOT_MARKER_CROSS:
        cairo_move_to(cr, x - 0.8 * r, y - 0.8 * r);
        cairo_line_to(cr, x + 0.8 * r, y + 0.8 * r);
        cairo_move_to(cr, x - 0.8 * r, y + 0.8 * r);
        cairo_line_to(cr, x + 0.8 * r, y - 0.8 * r);
        break;
    case RY_PLOT_MARKER_PLUS:
        cairo_move_to(cr, x - r, y);
        cairo_line_to(cr, x + r, y);
        cairo_move_to(cr, x, y - r);
        cairo_line_to(cr, x, y + r);
        break;
    default:
        return;
    }
    cairo_set_dash(cr, NULL, 0, 0.0);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
    if (st->marker == RY_PLOT_MARKER_CROSS || st->marker == RY_PLOT_MARKER_PLUS) {
        set_color(cr, color);
        cairo_set_line_width(cr, s > 6.0 ? 2.0 : 1.2);
        cairo_stroke(cr);
    } else if (st->hollow) {
        cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
        cairo_fill_preserve(cr);
        set_color(cr, color);
        cairo_set_line_width(cr, s > 6.0 ? 1.5 : 1.0);
        cairo_stroke(cr);
    } else {
        set_color(cr, color);
        cairo_fill(cr);
    }
}

/* Pixel position of a data value, kept within a range cairo's fixed point handles. */
static double to_px(double v, double lo, double hi, double p0, double len, int flip) {
    double t = (v - lo) / (hi - lo);
    if (flip) t = 1.0 - t;
    double px = p0 + t * len;
    if (px > 1e6) px = 1e6;
    if (px < -1e6) px = -1e6;
    return px;
}

/* ---- panels ---- */

typedef struct rect {
    double x, y, w, h;
} rect;

static void draw_legend(cairo_t *cr, const plot_panel *pn, rect area, double fs) {
    if (pn->legend == RY_PLOT_LEGEND_NONE) return;
    set_font(cr, 0.85 * fs, 0);
    double tw = 0.0;
    int count = 0;
    for (size_t s = 0; s < pn->nseries; s++) {
        if (!pn->series[s].label) continue;
        double w = text_width(cr, pn->series[s].label);
        if (w > tw) tw = w;
        count++;
    }
    if (count == 0) return;
    double row = 1.45 * font_height(cr), pad = 0.5 * fs, sample = 2.6 * fs, gap = 0.5 * fs;
    double bw = pad + sample + gap + tw + pad, bh = 2.0 * pad + count * row - 0.3 * row;
    double inset = 0.6 * fs;
    int right = pn->legend == RY_PLOT_LEGEND_NE || pn->legend == RY_PLOT_LEGEND_SE;
    int top = pn->legend == RY_PLOT_LEGEND_NE || pn->legend == RY_PLOT_LEGEND_NW;
    double bx = right ? area.x + area.w - inset - bw : area.x + inset;
    double by = top ? area.y + inset : area.y + area.h - inset - bh;
    cairo_save(cr);
    cairo_rectangle(cr, floor(bx) + 0.5, floor(by) + 0.5, ceil(bw), ceil(bh));
    cairo_set_source_rgba(cr, 1.0, 1.0, 1.0, 0.88);
    cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0.7, 0.7, 0.7);
    cairo_set_line_width(cr, 1.0);
    cairo_set_dash(cr, NULL, 0, 0.0);
    cairo_stroke(cr);
    int k = 0;
    for (size_t s = 0; s < pn->nseries; s++) {
        const plot_series *se = &pn->series[s];
        if (!se->label) continue;
        double cy = by + pad + (k + 0.35) * row;
        double x0 = bx + pad, x1 = x0 + sample;
        if (se->style.line) {
            double lw = style_line_width(&se->style);
            set_color(cr, se->color);
            cairo_set_line_width(cr, lw);
            set_dash(cr, se->style.dash, lw);
            cairo_move_to(cr, x0, cy);
            cairo_line_to(cr, x1, cy);
            cairo_stroke(cr);
        }
        if (se->style.marker != RY_PLOT_MARKER_NONE)
            draw_marker(cr, 0.5 * (x0 + x1), cy, &se->style, se->color);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        draw_text(cr, x1 + gap, cy, se->label, 0.0, 0.5, 0.0);
        k++;
    }
    cairo_restore(cr);
}

static void draw_series(cairo_t *cr, const plot_series *se, const plot_axis *ax,
                        const plot_axis *ay, rect area) {
    const ry_plot_style *st = &se->style;
    if (st->line) {
        cairo_save(cr);
        cairo_rectangle(cr, area.x, area.y, area.w, area.h);
        cairo_clip(cr);
        double lw = style_line_width(st);
        set_color(cr, se->color);
        cairo_set_line_width(cr, lw);
        cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
        set_dash(cr, st->dash, lw);
        int pen = 0;
        cairo_new_path(cr);
        for (size_t i = 0; i < se->n; i++) {
            double x = se->x[i], y = se->y[i];
            if (!isfinite(x) || !isfinite(y)) {
                pen = 0;
                continue;
            }
            double px = to_px(x, ax->lo, ax->hi, area.x, area.w, 0);
            double py = to_px(y, ay->lo, ay->hi, area.y, area.h, 1);
            if (pen)
                cairo_line_to(cr, px, py);
            else
                cairo_move_to(cr, px, py);
            pen = 1;
        }
        cairo_stroke(cr);
        cairo_restore(cr);
    }
    if (st->marker != RY_PLOT_MARKER_NONE) {
        double m = style_marker_size(st);
        cairo_save(cr);
        cairo_rectangle(cr, area.x - m, area.y - m, area.w + 2.0 * m, area.h + 2.0 * m);
        cairo_clip(cr);
        double ex = 1e-9 * (ax->hi - ax->lo), ey = 1e-9 * (ay->hi - ay->lo);
        for (size_t i = 0; i < se->n; i++) {
            double x = se->x[i], y = se->y[i];
            if (!isfinite(x) || !isfinite(y)) continue;
            if (x < ax->lo - ex || x > ax->hi + ex || y < ay->lo - ey || y > ay->hi + ey) continue;
            draw_marker(cr, to_px(x, ax->lo, ax->hi, area.x, area.w, 0),
                        to_px(y, ay->lo, ay->hi, area.y, area.h, 1), st, se->color);
        }
        cairo_restore(cr);
    }
}

static void draw_panel(cairo_t *cr, const plot_panel *pn, rect cell) {
    double fs = fmin(cell.w / 50.0, cell.h / 34.0);
    fs = fs < 10.0 ? 10.0 : fs > 22.0 ? 22.0 : fs;
    double pad = 0.8 * fs, gap = 0.45 * fs, tick_len = 0.35 * fs, tfs = 0.85 * fs;

    set_font(cr, 1.1 * fs, 1);
    double title_h = pn->title ? font_height(cr) + gap : 0.0;
    set_font(cr, fs, 0);
    double label_h = font_height(cr);
    set_font(cr, tfs, 0);
    double tick_h = font_height(cr);

    /* y ticks first (their labels set the left margin), then x ticks. */
    double top = pad + title_h;
    double bottom = pad + (pn->xlabel ? label_h + gap : 0.0) + tick_h + tick_len + gap;
    plot_axis ay, ax;
    int ytarget = (int)((cell.h - top - bottom) / (3.2 * fs));
    axis_setup(&ay, pn, 1, ytarget > 10 ? 10 : ytarget);
    double yw = 0.0;
    for (int i = 0; i < ay.nticks; i++) yw = fmax(yw, text_width(cr, ay.labels[i]));
    double left = pad + (pn->ylabel ? label_h + gap : 0.0) + yw + tick_len + gap;
    double right = pad + 1.2 * fs;
    int xtarget = (int)((cell.w - left - right) / (6.0 * fs));
    axis_setup(&ax, pn, 0, xtarget > 10 ? 10 : xtarget);

    rect area = {floor(cell.x + left), floor(cell.y + top), 0.0, 0.0};
    area.w = floor(cell.x + cell.w - right) - area.x;
    area.h = floor(cell.y + cell.h - bottom) - area.y;
    if (area.w < 4.0 || area.h < 4.0) return; /* no room to draw */

    /* Background and grid. */
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_rectangle(cr, area.x, area.y, area.w, area.h);
    cairo_fill(cr);
    cairo_set_line_width(cr, 1.0);
    cairo_set_dash(cr, NULL, 0, 0.0);
    cairo_set_line_cap(cr, CAIRO_LINE_CAP_BUTT);
    cairo_set_source_rgb(cr, 0.88, 0.88, 0.88);
    for (int i = 0; i < ax.nticks; i++) {
        double px = floor(to_px(ax.ticks[i], ax.lo, ax.hi, area.x, area.w, 0)) + 0.5;
        cairo_move_to(cr, px, area.y);
        cairo_line_to(cr, px, area.y + area.h);
    }
    for (int i = 0; i < ay.nticks; i++) {
        double py = floor(to_px(ay.ticks[i], ay.lo, ay.hi, area.y, area.h, 1)) + 0.5;
        cairo_move_to(cr, area.x, py);
        cairo_line_to(cr, area.x + area.w, py);
    }
    cairo_stroke(cr);

    for (size_t s = 0; s < pn->nseries; s++) draw_series(cr, &pn->series[s], &ax, &ay, area);

    /* Frame, ticks and tick labels. */
    cairo_set_source_rgb(cr, 0.15, 0.15, 0.15);
    cairo_set_line_width(cr, 1.0);
    cairo_set_dash(cr, NULL, 0, 0.0);
    cairo_rectangle(cr, area.x + 0.5, area.y + 0.5, area.w - 1.0, area.h - 1.0);
    cairo_stroke(cr);
    set_font(cr, tfs, 0);
    for (int i = 0; i < ax.nticks; i++) {
        double px = floor(to_px(ax.ticks[i], ax.lo, ax.hi, area.x, area.w, 0)) + 0.5;
        cairo_move_to(cr, px, area.y + area.h);
        cairo_line_to(cr, px, area.y + area.h + tick_len);
        cairo_stroke(cr);
        draw_text(cr, px, area.y + area.h + tick_len + 0.3 * gap, ax.labels[i], 0.5, 0.0, 0.0);
    }
    for (int i = 0; i < ay.nticks; i++) {
        double py = floor(to_px(ay.ticks[i], ay.lo, ay.hi, area.y, area.h, 1)) + 0.5;
        cairo_move_to(cr, area.x - tick_len, py);
        cairo_line_to(cr, area.x, py);
        cairo_stroke(cr);
        draw_text(cr, area.x - tick_len - 0.5 * gap, py, ay.labels[i], 1.0, 0.5, 0.0);
    }

    /* Labels and title. */
    set_font(cr, fs, 0);
    if (pn->xlabel)
        draw_text(cr, area.x + 0.5 * area.w, cell.y + cell.h - pad, pn->xlabel, 0.5, 1.0, 0.0);
    if (pn->ylabel)
        draw_text(cr, cell.x + pad, area.y + 0.5 * area.h, pn->ylabel, 0.5, 0.0, 0.5 * PLOT_PI);
    if (pn->title) {
        set_font(cr, 1.1 * fs, 1);
        draw_text(cr, area.x + 0.5 * area.w, cell.y + pad, pn->title, 0.5, 0.0, 0.0);
    }

    draw_legend(cr, pn, area, fs);
}

static void draw_figure(cairo_t *cr, const ry_plot *p) {
    cairo_set_source_rgb(cr, 1.0, 1.0, 1.0);
    cairo_paint(cr);
    double top = 0.0;
    if (p->title) {
        double fs = fmin(p->width / (40.0 * p->cols), p->height / 30.0);
        fs = 1.25 * (fs < 9.0 ? 9.0 : fs > 22.0 ? 22.0 : fs);
        set_font(cr, fs, 1);
        double h = font_height(cr);
        cairo_set_source_rgb(cr, 0.1, 0.1, 0.1);
        draw_text(cr, 0.5 * p->width, 0.5 * h, p->title, 0.5, 0.0, 0.0);
        top = 1.8 * h;
    }
    double cw = (double)p->width / p->cols, ch = (p->height - top) / p->rows;
    for (int r = 0; r < p->rows; r++) {
        for (int c = 0; c < p->cols; c++) {
            rect cell = {c * cw, top + r * ch, cw, ch};
            cairo_save(cr);
            draw_panel(cr, &p->panels[r * p->cols + c], cell);
            cairo_restore(cr);
        }
    }
}

static cairo_status_t png_write_cb(void *closure, const unsigned char *data, unsigned int len) {
    FILE *fp = closure;
    return fwrite(data, 1, len, fp) == len ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

ry_status ry_plot_write_png(const ry_plot *p, const char *path, ry_error *err) {
    RY_CHECK(err, p != NULL, RY_ERR_INTERNAL, "plot: no figure");
    RY_CHECK(err, path != NULL && *path, RY_ERR_INPUT, "plot: no output file name");
    cairo_surface_t *surf = cairo_image_surface_create(CAIRO_FORMAT_RGB24, p->width, p->height);
    cairo_status_t cs = cairo_surface_status(surf);
    if (cs != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(surf);
        return ry_error_set(err, cs == CAIRO_STATUS_NO_MEMORY ? RY_ERR_NOMEM : RY_ERR_INTERNAL,
                            "plot '%s': cannot create the image: %s", path,
                            cairo_status_to_string(cs));
    }
    cairo_t *cr = cairo_create(surf);
    draw_figure(cr, p);
    cs = cairo_status(cr);
    cairo_destroy(cr);
    if (cs != CAIRO_STATUS_SUCCESS) {
        cairo_surface_destroy(surf);
        return ry_error_set(err, cs == CAIRO_STATUS_NO_MEMORY ? RY_ERR_NOMEM : RY_ERR_INTERNAL,
                            "plot '%s': drawing failed: %s", path, cairo_status_to_string(cs));
    }
    cairo_surface_flush(surf);
    ry_atomic_file f;
    ry_status st = ry_atomic_open(&f, path, err);
    if (st != RY_OK) {
        cairo_surface_destroy(surf);
        return st;
    }
    cs = cairo_surface_write_to_png_stream(surf, png_write_cb, f.fp);
    cairo_surface_destroy(surf);
    if (cs != CAIRO_STATUS_SUCCESS) {
        ry_atomic_abort(&f);
        return ry_error_set(err, RY_ERR_IO, "plot '%s': writing the PNG failed: %s", path,
                            cairo_status_to_string(cs));
    }
    return ry_atomic_commit(&f, err);
}

void ry_plot_release_caches(void) {
    cairo_debug_reset_static_data();
}
