/* Figures: the figure object, axis ranges, the line-breaking rule, and the
 * drawing through PLplot (cairo devices).  The rules are documented in
 * hamlie/plot.h. */
#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include <plplot.h>

#include "base/buf.h"
#include "hamlie/plot.h"

/* Limits that keep a mistaken call from asking for gigabytes. */
#define HL_PLOT_MIN_PIXELS 16
#define HL_PLOT_MAX_PIXELS 10000
#define HL_PLOT_MAX_POINTS 100000000

typedef struct hl_plot_series {
    size_t n;
    double *x, *y;
    hl_draw draw;
    hl_color color;
    char *label;
} hl_plot_series;

struct hl_figure {
    char *title, *xlabel, *ylabel;
    hl_axis_scale yscale;
    int equal_aspect;
    hl_legend_pos legend;
    int w, h;           /* PNG pixels; SVG/PDF points */
    double xclip[2], yclip[2]; /* data units, NaN = no limit */
    double pole_frac;
    hl_plot_series *s;
    size_t ns, cap;
};

/* The world window of one drawing (y as drawn: log10 on a log axis). */
typedef struct hl_plot_layout {
    int ylog;
    double wx0, wx1, wy0, wy1;
} hl_plot_layout;

/* ---- colours ------------------------------------------------------------ */

static const struct {
    const char *name;
    unsigned char rgb[3];
} colors[HL_COLOR_COUNT] = {
    {"black", {0, 0, 0}},       {"red", {255, 0, 0}},       {"blue", {0, 0, 255}},
    {"green", {0, 160, 0}},     {"orange", {255, 140, 0}},  {"purple", {128, 0, 160}},
    {"cyan", {0, 170, 200}},    {"magenta", {220, 0, 220}}, {"brown", {140, 80, 20}},
    {"gray", {128, 128, 128}},
};

void hl_color_rgb(unsigned char out[3], hl_color c)
{
    if ((int)c < 0 || c >= HL_COLOR_COUNT) {
        out[0] = out[1] = out[2] = 0;
        return;
    }
    memcpy(out, colors[c].rgb, 3);
}

const char *hl_color_name(hl_color c)
{
    return ((int)c < 0 || c >= HL_COLOR_COUNT) ? NULL : colors[c].name;
}

int hl_color_from_name(const char *name)
{
    if (name == NULL)
        return -1;
    if (strcasecmp(name, "grey") == 0)
        return HL_COLOR_GRAY;
    for (int c = 0; c < HL_COLOR_COUNT; c++)
        if (strcasecmp(name, colors[c].name) == 0)
            return c;
    return -1;
}

/* ---- the figure ----------------------------------------------------------- */

static char *dup_or_null(const char *s)
{
    return s == NULL ? NULL : hl_xstrdup(s);
}

hl_figure *hl_figure_new(const char *title, const char *xlabel, const char *ylabel)
{
    hl_figure *fig = hl_xcalloc(1, sizeof *fig);
    fig->title = dup_or_null(title);
    fig->xlabel = dup_or_null(xlabel);
    fig->ylabel = dup_or_null(ylabel);
    fig->yscale = HL_AXIS_LINEAR;
    fig->legend = HL_LEGEND_TOP_RIGHT;
    fig->w = 800;
    fig->h = 600;
    fig->xclip[0] = fig->xclip[1] = NAN;
    fig->yclip[0] = fig->yclip[1] = NAN;
    fig->pole_frac = 0.25;
    return fig;
}

void hl_figure_free(hl_figure *fig)
{
    if (fig == NULL)
        return;
    for (size_t i = 0; i < fig->ns; i++) {
        free(fig->s[i].x);
        free(fig->s[i].y);
        free(fig->s[i].label);
    }
    free(fig->s);
    free(fig->title);
    free(fig->xlabel);
    free(fig->ylabel);
    free(fig);
}

void hl_figure_set_title(hl_figure *fig, const char *title)
{
    free(fig->title);
    fig->title = dup_or_null(title);
}

void hl_figure_set_labels(hl_figure *fig, const char *xlabel, const char *ylabel)
{
    free(fig->xlabel);
    free(fig->ylabel);
    fig->xlabel = dup_or_null(xlabel);
    fig->ylabel = dup_or_null(ylabel);
}

void hl_figure_set_yscale(hl_figure *fig, hl_axis_scale scale)
{
    fig->yscale = scale;
}

void hl_figure_set_equal_aspect(hl_figure *fig, int on)
{
    fig->equal_aspect = on != 0;
}

void hl_figure_set_legend(hl_figure *fig, hl_legend_pos pos)
{
    fig->legend = pos;
}

hl_status hl_figure_set_size(hl_figure *fig, int w, int h, hl_error *err)
{
    if (w < HL_PLOT_MIN_PIXELS || w > HL_PLOT_MAX_PIXELS || h < HL_PLOT_MIN_PIXELS ||
        h > HL_PLOT_MAX_PIXELS)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "figure size %dx%d outside %d..%d", w, h, HL_PLOT_MIN_PIXELS,
                            HL_PLOT_MAX_PIXELS);
    fig->w = w;
    fig->h = h;
    return HL_OK;
}

static hl_status set_clip(double clip[2], double lo, double hi, const char *axis,
                          hl_error *err)
{
    if (!isnan(lo) && !isnan(hi) && !(lo < hi))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "%s clip range [%g, %g] is empty",
                            axis, lo, hi);
    clip[0] = lo;
    clip[1] = hi;
    return HL_OK;
}

hl_status hl_figure_set_xclip(hl_figure *fig, double lo, double hi, hl_error *err)
{
    return set_clip(fig->xclip, lo, hi, "x", err);
}

hl_status hl_figure_set_yclip(hl_figure *fig, double lo, double hi, hl_error *err)
{
    return set_clip(fig->yclip, lo, hi, "y", err);
}

hl_status hl_figure_set_pole_frac(hl_figure *fig, double frac, hl_error *err)
{
    if (!(frac >= 0) || !isfinite(frac))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "pole fraction %g is not >= 0",
                            frac);
    fig->pole_frac = frac;
    return HL_OK;
}

hl_status hl_figure_add(hl_figure *fig, size_t n, const double *x, const double *y,
                        hl_draw draw, hl_color color, const char *label, hl_error *err)
{
    if (n > 0 && (x == NULL || y == NULL))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "series data is NULL");
    if ((int)color < 0 || color >= HL_COLOR_COUNT)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "unknown colour %d", (int)color);
    if ((int)draw < HL_DRAW_LINE || draw > HL_DRAW_DIAMONDS)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "unknown draw kind %d", (int)draw);
    if (n > HL_PLOT_MAX_POINTS)
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0, "series of %zu points (limit %d)",
                            n, HL_PLOT_MAX_POINTS);
    if (fig->ns == fig->cap) {
        fig->cap = fig->cap ? 2 * fig->cap : 4;
        fig->s = hl_xrealloc(fig->s, fig->cap * sizeof *fig->s);
    }
    hl_plot_series *s = &fig->s[fig->ns++];
    s->n = n;
    s->x = hl_xmalloc((n ? n : 1) * sizeof(double));
    s->y = hl_xmalloc((n ? n : 1) * sizeof(double));
    if (n) {
        memcpy(s->x, x, n * sizeof(double));
        memcpy(s->y, y, n * sizeof(double));
    }
    s->draw = draw;
    s->color = color;
    s->label = dup_or_null(label);
    return HL_OK;
}

size_t hl_figure_nseries(const hl_figure *fig)
{
    return fig->ns;
}

/* ---- ranges -------------------------------------------------------------- */

int hl_plot_is_pole_jump(double y0, double y1, double lo, double hi, double pole_frac)
{
    if (!(pole_frac > 0) || !(hi > lo))
        return 0;
    if (!((y0 < 0 && y1 > 0) || (y0 > 0 && y1 < 0)))
        return 0;
    double big = pole_frac * (hi - lo);
    return fabs(y0) >= big && fabs(y1) >= big;
}

/* The value drawn for y: itself, or log10(y) on a log axis; NaN if it has
 * no place on the axis. */
static double ymap(double y, int ylog)
{
    if (!isfinite(y))
        return NAN;
    if (ylog)
        return y > 0 ? log10(y) : NAN;
    return y;
}

static int decide_log(const hl_figure *fig)
{
    if (fig->yscale == HL_AXIS_LOG)
        return 1;
    if (fig->yscale != HL_AXIS_AUTO)
        return 0;
    double lo = INFINITY, hi = 0;
    for (size_t i = 0; i < fig->ns; i++)
        for (size_t k = 0; k < fig->s[i].n; k++) {
            double y = fig->s[i].y[k];
            if (!isfinite(y))
                continue;
            if (y < 0)
                return 0;
            if (y > 0) {
                lo = fmin(lo, y);
                hi = fmax(hi, y);
            }
        }
    return hi > 0 && hi / lo > 1e3;
}

/* Widen a degenerate span, add the margin, intersect with the clip (already
 * mapped; NaN = none).  have = 0: no data, use the fallback. */
static void finish_range(double r[2], int have, double margin, const double clip[2],
                         double fallback_lo, double fallback_hi)
{
    if (!have) {
        r[0] = fallback_lo;
        r[1] = fallback_hi;
    }
    double mid = 0.5 * (r[0] + r[1]);
    if (r[1] - r[0] <= 1e-9 * fabs(mid)) {
        double half = mid != 0 ? 0.1 * fabs(mid) : 1.0;
        r[0] = mid - half;
        r[1] = mid + half;
    } else {
        double span = r[1] - r[0];
        r[0] -= margin * span;
        r[1] += margin * span;
    }
    double lo = r[0], hi = r[1];
    if (!isnan(clip[0]))
        lo = fmax(lo, clip[0]);
    if (!isnan(clip[1]))
        hi = fmin(hi, clip[1]);
    if (!(lo < hi)) {
        /* the data lie wholly outside the clip: show the clip window */
        double w = r[1] - r[0];
        lo = !isnan(clip[0]) ? clip[0] : clip[1] - w;
        hi = !isnan(clip[1]) ? clip[1] : clip[0] + w;
    }
    r[0] = lo;
    r[1] = hi;
}

static void map_clip(double out[2], const double clip[2], int ylog)
{
    for (int k = 0; k < 2; k++)
        out[k] = (isnan(clip[k]) || !ylog) ? clip[k] : (clip[k] > 0 ? log10(clip[k]) : NAN);
}

static void compute_layout(hl_plot_layout *lay, const hl_figure *fig)
{
    double xr[2] = {INFINITY, -INFINITY}, yr[2] = {INFINITY, -INFINITY};
    int have = 0;

    lay->ylog = decide_log(fig);
    for (size_t i = 0; i < fig->ns; i++)
        for (size_t k = 0; k < fig->s[i].n; k++) {
            double x = fig->s[i].x[k], y = ymap(fig->s[i].y[k], lay->ylog);
            if (!isfinite(x) || isnan(y))
                continue;
            have = 1;
            xr[0] = fmin(xr[0], x);
            xr[1] = fmax(xr[1], x);
            yr[0] = fmin(yr[0], y);
            yr[1] = fmax(yr[1], y);
        }
    double yclip[2];
    map_clip(yclip, fig->yclip, lay->ylog);
    finish_range(xr, have, fig->equal_aspect ? 0.05 : 0.02, fig->xclip, 0, 1);
    finish_range(yr, have, 0.05, yclip, lay->ylog ? -1 : 0, 1);
    lay->wx0 = xr[0];
    lay->wx1 = xr[1];
    lay->wy0 = yr[0];
    lay->wy1 = yr[1];
}

/* Liang–Barsky: clip the segment a + t (b - a), t in [0, 1], to the window;
 * returns 0 if nothing is left, else the kept [t0, t1]. */
static int clip_segment(const hl_plot_layout *lay, const double a[2], const double b[2],
                        double *t0, double *t1)
{
    double d[2] = {b[0] - a[0], b[1] - a[1]};
    double p[4] = {-d[0], d[0], -d[1], d[1]};
    double q[4] = {a[0] - lay->wx0, lay->wx1 - a[0], a[1] - lay->wy0, lay->wy1 - a[1]};
    double lo = 0, hi = 1;
    for (int k = 0; k < 4; k++) {
        if (p[k] == 0) {
            if (q[k] < 0)
                return 0;
            continue;
        }
        double r = q[k] / p[k];
        if (p[k] < 0)
            lo = fmax(lo, r);
        else
            hi = fmin(hi, r);
        if (lo > hi)
            return 0;
    }
    *t0 = lo;
    *t1 = hi;
    return 1;
}

/* ---- drawing (PLplot) ------------------------------------------------------ */

/* cmap0: 0 background, 1 axes and text, 2 + c the colour c. */
#define COL_BG 0
#define COL_FG 1
#define COL_SERIES(c) (2 + (int)(c))

/* Sizes as fractions of the page height (mm), so a figure reads the same at
 * any pixel size: text 14 px and dots of radius 3.5 px at 600 px tall. */
#define CHAR_FRAC (14.0 / 600.0)
#define DOT_FRAC (3.5 / 600.0)
#define LINE_WIDTH 2.0

static pthread_mutex_t plot_lock = PTHREAD_MUTEX_INITIALIZER;
static jmp_buf plot_jmp;
static char plot_fatal[256];

/* PLplot calls this before exit(): jump back to the drawing call instead. */
static int on_plexit(PLCHAR_VECTOR msg)
{
    snprintf(plot_fatal, sizeof plot_fatal, "%s", msg ? msg : "");
    longjmp(plot_jmp, 1);
}

static void on_plabort(PLCHAR_VECTOR msg)
{
    (void)msg; /* recorded through plsError */
}

static void set_palette(void)
{
    PLINT r[2 + HL_COLOR_COUNT], g[2 + HL_COLOR_COUNT], b[2 + HL_COLOR_COUNT];
    r[COL_BG] = g[COL_BG] = b[COL_BG] = 255;
    r[COL_FG] = g[COL_FG] = b[COL_FG] = 0;
    for (int c = 0; c < HL_COLOR_COUNT; c++) {
        r[COL_SERIES(c)] = colors[c].rgb[0];
        g[COL_SERIES(c)] = colors[c].rgb[1];
        b[COL_SERIES(c)] = colors[c].rgb[2];
    }
    plscmap0(r, g, b, 2 + HL_COLOR_COUNT);
}

static int have_device(const char *dev)
{
    const char *menu[128], *names[128];
    const char **pm = menu, **pn = names;
    int n = 128;
    plgDevs(&pm, &pn, &n);
    for (int i = 0; i < n; i++)
        if (strcmp(pn[i], dev) == 0)
            return 1;
    return 0;
}

/* Polyline under construction, flushed to plline at each break. */
typedef struct polyline {
    PLFLT *x, *y;
    size_t n;
} polyline;

static void pl_flush(polyline *pl)
{
    if (pl->n >= 2)
        plline((PLINT)pl->n, pl->x, pl->y);
    pl->n = 0;
}

static void pl_push(polyline *pl, double x, double y)
{
    pl->x[pl->n] = x;
    pl->y[pl->n] = y;
    pl->n++;
}

static void draw_line(const hl_plot_series *s, const hl_plot_layout *lay, double pole_frac)
{
    polyline pl;
    /* each segment adds at most two points: 2n bounds the buffer */
    pl.x = hl_xmalloc((2 * s->n + 2) * sizeof(PLFLT));
    pl.y = hl_xmalloc((2 * s->n + 2) * sizeof(PLFLT));
    pl.n = 0;
    for (size_t i = 0; i + 1 < s->n; i++) {
        double a[2] = {s->x[i], ymap(s->y[i], lay->ylog)};
        double b[2] = {s->x[i + 1], ymap(s->y[i + 1], lay->ylog)};
        double t0, t1;
        if (!isfinite(a[0]) || !isfinite(b[0]) || isnan(a[1]) || isnan(b[1]) ||
            hl_plot_is_pole_jump(a[1], b[1], lay->wy0, lay->wy1, pole_frac) ||
            !clip_segment(lay, a, b, &t0, &t1)) {
            pl_flush(&pl);
            continue;
        }
        if (t0 > 0)
            pl_flush(&pl);
        if (pl.n == 0)
            pl_push(&pl, a[0] + t0 * (b[0] - a[0]), a[1] + t0 * (b[1] - a[1]));
        pl_push(&pl, a[0] + t1 * (b[0] - a[0]), a[1] + t1 * (b[1] - a[1]));
        if (t1 < 1)
            pl_flush(&pl);
    }
    pl_flush(&pl);
    free(pl.x);
    free(pl.y);
}

/* Unit outlines of the markers (radius 1), closed by plfill. */
static int marker_shape(hl_draw draw, double *ux, double *uy)
{
    static const double sq[4][2] = {{-0.85, -0.85}, {0.85, -0.85}, {0.85, 0.85}, {-0.85, 0.85}};
    static const double tri[3][2] = {{0, 1.2}, {-1.04, -0.6}, {1.04, -0.6}};
    static const double dia[4][2] = {{0, 1.2}, {1.2, 0}, {0, -1.2}, {-1.2, 0}};
    int n = 0;
    switch (draw) {
    case HL_DRAW_SQUARES:
        for (n = 0; n < 4; n++)
            ux[n] = sq[n][0], uy[n] = sq[n][1];
        break;
    case HL_DRAW_TRIANGLES:
        for (n = 0; n < 3; n++)
            ux[n] = tri[n][0], uy[n] = tri[n][1];
        break;
    case HL_DRAW_DIAMONDS:
        for (n = 0; n < 4; n++)
            ux[n] = dia[n][0], uy[n] = dia[n][1];
        break;
    default:
        for (n = 0; n < 16; n++)
            ux[n] = cos(2 * M_PI * n / 16), uy[n] = sin(2 * M_PI * n / 16);
    }
    return n;
}

static void draw_markers(const hl_plot_series *s, const hl_plot_layout *lay)
{
    PLFLT vx0, vx1, vy0, vy1, px0, px1, py0, py1;
    plgvpd(&vx0, &vx1, &vy0, &vy1);
    plgspa(&px0, &px1, &py0, &py1);
    /* marker radius in world units along each axis (equal in mm) */
    double r_mm = DOT_FRAC * (py1 - py0);
    double rx = r_mm * (lay->wx1 - lay->wx0) / ((vx1 - vx0) * (px1 - px0));
    double ry = r_mm * (lay->wy1 - lay->wy0) / ((vy1 - vy0) * (py1 - py0));
    double ux[16], uy[16];
    PLFLT mx[16], my[16];
    int m = marker_shape(s->draw, ux, uy);
    for (size_t i = 0; i < s->n; i++) {
        double x = s->x[i], y = ymap(s->y[i], lay->ylog);
        if (!isfinite(x) || isnan(y) || x < lay->wx0 - rx || x > lay->wx1 + rx ||
            y < lay->wy0 - ry || y > lay->wy1 + ry)
            continue;
        for (int k = 0; k < m; k++) {
            mx[k] = x + rx * ux[k];
            my[k] = y + ry * uy[k];
        }
        plfill(m, mx, my);
    }
}

static const char *legend_symbol(hl_draw draw)
{
    switch (draw) {
    case HL_DRAW_SQUARES:
        return "■";
    case HL_DRAW_TRIANGLES:
        return "▲";
    case HL_DRAW_DIAMONDS:
        return "◆";
    default:
        return "●";
    }
}

static void draw_legend(const hl_figure *fig)
{
    static const PLINT pos[] = {
        PL_POSITION_TOP | PL_POSITION_RIGHT, PL_POSITION_TOP | PL_POSITION_LEFT,
        PL_POSITION_BOTTOM | PL_POSITION_RIGHT, PL_POSITION_BOTTOM | PL_POSITION_LEFT};
    size_t n = 0;
    if ((int)fig->legend < 0 || fig->legend >= HL_LEGEND_NONE)
        return;
    for (size_t i = 0; i < fig->ns; i++)
        n += fig->s[i].label != NULL;
    if (n == 0)
        return;
    PLINT *opt = hl_xcalloc(n, sizeof *opt), *tcol = hl_xcalloc(n, sizeof *tcol);
    PLINT *lcol = hl_xcalloc(n, sizeof *lcol), *lsty = hl_xcalloc(n, sizeof *lsty);
    PLINT *scol = hl_xcalloc(n, sizeof *scol), *snum = hl_xcalloc(n, sizeof *snum);
    PLFLT *lwid = hl_xcalloc(n, sizeof *lwid), *ssca = hl_xcalloc(n, sizeof *ssca);
    const char **text = hl_xcalloc(n, sizeof *text), **sym = hl_xcalloc(n, sizeof *sym);
    size_t k = 0;
    for (size_t i = 0; i < fig->ns; i++) {
        const hl_plot_series *s = &fig->s[i];
        if (s->label == NULL)
            continue;
        opt[k] = s->draw == HL_DRAW_LINE ? PL_LEGEND_LINE : PL_LEGEND_SYMBOL;
        tcol[k] = COL_FG;
        text[k] = s->label;
        lcol[k] = scol[k] = COL_SERIES(s->color);
        lsty[k] = 1;
        lwid[k] = LINE_WIDTH;
        ssca[k] = 0.8;
        snum[k] = 3;
        sym[k] = legend_symbol(s->draw);
        k++;
    }
    PLFLT w, h;
    pllegend(&w, &h, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX,
             PL_POSITION_INSIDE | PL_POSITION_VIEWPORT | pos[fig->legend], 0.02, 0.03, 0.08,
             COL_BG, COL_FG, 1, 0, 0, (PLINT)n, opt, 1.0, 0.9, 2.0, 0.0, tcol, text, NULL,
             NULL, NULL, NULL, lcol, lsty, lwid, scol, ssca, snum, sym);
    free(opt), free(tcol), free(lcol), free(lsty), free(scol), free(snum);
    free(lwid), free(ssca), free(text), free(sym);
}

/* Labels on a log axis: PLplot's, one per decade, up to 10 decades (returns
 * 0); beyond that every 2, 5, 10, 20, ... decades (at most 8 labels), with
 * a minor tick per decade (returns 1 with the step in decades). */
static int log_ticks(double *step, int *sub, const hl_plot_layout *lay)
{
    static const double steps[] = {1, 2, 5, 10, 20, 50, 100};
    double span = lay->wy1 - lay->wy0;
    if (!lay->ylog || span <= 10)
        return 0;
    int k = 0;
    while (k < 6 && span / steps[k] > 8)
        k++;
    *step = steps[k];
    *sub = steps[k] <= 10 ? (int)steps[k] : 10;
    return 1;
}

/* Draw the whole figure on the current (initialised) stream. */
static void draw_figure(const hl_figure *fig, const hl_plot_layout *lay)
{
    PLFLT px0, px1, py0, py1;
    pladv(0);
    plgspa(&px0, &px1, &py0, &py1);
    plschr(CHAR_FRAC * (py1 - py0), 1.0);
    if (fig->equal_aspect)
        plvpas(0.12, 0.96, 0.11, 0.92, (lay->wy1 - lay->wy0) / (lay->wx1 - lay->wx0));
    else
        plvpor(0.12, 0.96, 0.11, 0.92);
    plwind(lay->wx0, lay->wx1, lay->wy0, lay->wy1);
    plcol0(COL_FG);
    plwidth(1.0);
    double ystep = 0;
    int ysub = 0;
    if (log_ticks(&ystep, &ysub, lay)) {
        /* PLplot labels every decade of a log axis: over many decades they
         * overlap.  Draw it as a linear axis in log10 units, labelled 10^k. */
        plbox("bcnst", 0, 0, "bcst", ystep, ysub);
        char text[32];
        for (double k = ceil(lay->wy0 / ystep) * ystep; k <= lay->wy1; k += ystep) {
            snprintf(text, sizeof text, "10#u%d#d", (int)k);
            plmtex("lv", 0.7, (k - lay->wy0) / (lay->wy1 - lay->wy0), 1.0, text);
        }
    } else {
        plbox("bcnst", 0, 0, lay->ylog ? "bcnstlv" : "bcnstv", 0, 0);
    }
    pllab(fig->xlabel ? fig->xlabel : "", fig->ylabel ? fig->ylabel : "",
          fig->title ? fig->title : "");
    for (size_t i = 0; i < fig->ns; i++) {
        const hl_plot_series *s = &fig->s[i];
        plcol0(COL_SERIES(s->color));
        plwidth(LINE_WIDTH);
        if (s->draw == HL_DRAW_LINE)
            draw_line(s, lay, fig->pole_frac);
        else
            draw_markers(s, lay);
    }
    plwidth(1.0);
    draw_legend(fig);
}

/* Where to draw: a file (PLplot writes an already created file) or memory. */
typedef struct target {
    const char *dev;
    const char *file;   /* or NULL */
    unsigned char *rgb; /* memcairo */
    int w, h;
} target;

/* One drawing on a fresh stream; the caller holds plot_lock.  After a
 * longjmp out of on_plexit only `old` and `err` are used, and neither is
 * changed after setjmp. */
static hl_status draw_on_stream(const hl_figure *fig, const target *t, hl_plot_frame *frame,
                                hl_error *err)
{
    PLINT old, strm, code = 0;
    char msg[1024] = "";
    hl_plot_layout lay;

    if (!have_device(t->dev))
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                            "PLplot device '%s' is not installed (plplot-driver-cairo)", t->dev);
    compute_layout(&lay, fig);
    plgstrm(&old);
    plot_fatal[0] = '\0';
    plsexit(on_plexit);
    plsabort(on_plabort);
    if (setjmp(plot_jmp) != 0) {
        /* PLplot wanted to exit: its stream is in an unknown state, leave it */
        plsexit(NULL);
        plsabort(NULL);
        plsstrm(old);
        return hl_error_set(err, HL_EIO, NULL, -1, 0, "PLplot failed: %s", plot_fatal);
    }
    plmkstrm(&strm);
    plsError(&code, msg);
    plsdev(t->dev);
    set_palette();
    plspause(0);
    if (t->rgb != NULL) {
        plsmem(t->w, t->h, t->rgb);
    } else {
        plsfnam(t->file);
        plspage(0, 0, t->w, t->h, 0, 0);
    }
    plinit();
    draw_figure(fig, &lay);
    if (frame != NULL) {
        PLFLT a, b, c, d;
        plgvpd(&a, &b, &c, &d);
        frame->vx0 = a, frame->vx1 = b, frame->vy0 = c, frame->vy1 = d;
        frame->wx0 = lay.wx0, frame->wx1 = lay.wx1, frame->wy0 = lay.wy0;
        frame->wy1 = lay.wy1, frame->ylog = lay.ylog;
    }
    plend1();
    plsstrm(old);
    plsexit(NULL);
    plsabort(NULL);
    if (code != 0)
        return hl_error_set(err, HL_EIO, NULL, -1, 0, "PLplot: %s", msg);
    return HL_OK;
}

hl_status hl_figure_render_rgb(const hl_figure *fig, int w, int h, unsigned char *rgb,
                               hl_plot_frame *frame, hl_error *err)
{
    if (rgb == NULL || w < HL_PLOT_MIN_PIXELS || w > HL_PLOT_MAX_PIXELS ||
        h < HL_PLOT_MIN_PIXELS || h > HL_PLOT_MAX_PIXELS)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "bad image %dx%d", w, h);
    /* memcairo draws over what the buffer holds: start from the background */
    memset(rgb, 255, (size_t)w * (size_t)h * 3);
    target t = {"memcairo", NULL, rgb, w, h};
    pthread_mutex_lock(&plot_lock);
    hl_status st = draw_on_stream(fig, &t, frame, err);
    pthread_mutex_unlock(&plot_lock);
    return st;
}

int hl_plot_frame_pixel(const hl_plot_frame *frame, int w, int h, double x, double y,
                        double *px, double *py)
{
    double wy = ymap(y, frame->ylog);
    if (!isfinite(x) || isnan(wy))
        return 0;
    double fx = frame->vx0 + (x - frame->wx0) / (frame->wx1 - frame->wx0) *
                                 (frame->vx1 - frame->vx0);
    double fy = frame->vy0 + (wy - frame->wy0) / (frame->wy1 - frame->wy0) *
                                 (frame->vy1 - frame->vy0);
    *px = fx * w;
    *py = (1 - fy) * h;
    return 1;
}

/* ---- files ------------------------------------------------------------------ */

static const struct {
    const char *ext, *dev;
} formats_known[] = {{"png", "pngcairo"}, {"svg", "svgcairo"}, {"pdf", "pdfcairo"}};
#define NFORMATS 3

/* Parse "png,svg,pdf" into want[]; HL_EINVAL on an unknown or empty list. */
static hl_status parse_formats(int want[NFORMATS], const char *formats, hl_error *err)
{
    int any = 0;
    memset(want, 0, NFORMATS * sizeof *want);
    if (formats == NULL)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no figure format given");
    const char *p = formats;
    while (*p) {
        while (*p == ' ' || *p == ',')
            p++;
        size_t len = strcspn(p, ", ");
        if (len == 0)
            break;
        int k;
        for (k = 0; k < NFORMATS; k++)
            if (strlen(formats_known[k].ext) == len &&
                strncasecmp(p, formats_known[k].ext, len) == 0)
                break;
        if (k == NFORMATS)
            return hl_error_set(err, HL_EINVAL, formats, (int)(p - formats), (int)len,
                                "unknown figure format '%.*s' (png, svg, pdf)", (int)len, p);
        want[k] = any = 1;
        p += len;
    }
    if (!any)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no figure format given");
    return HL_OK;
}

/* Create a fresh temporary file beside final; its name goes to tmp. */
static hl_status make_temp(char **tmp, const char *final, hl_error *err)
{
    static unsigned counter;
    hl_buf b;
    for (int tries = 0; tries < 100; tries++) {
        hl_buf_init(&b);
        hl_buf_printf(&b, "%s.tmp%ld.%u", final, (long)getpid(), counter++);
        int fd = open(b.s, O_WRONLY | O_CREAT | O_EXCL, 0666);
        if (fd >= 0) {
            close(fd);
            *tmp = hl_buf_take(&b);
            return HL_OK;
        }
        int e = errno;
        hl_buf_clear(&b);
        if (e != EEXIST)
            return hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write '%s': %s", final,
                                strerror(e));
    }
    return hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write '%s': no free temporary name",
                        final);
}

static hl_status write_one(const hl_figure *fig, const char *path, int k, hl_error *err)
{
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_printf(&b, "%s.%s", path, formats_known[k].ext);
    char *final = hl_buf_take(&b), *tmp = NULL;
    hl_status st = make_temp(&tmp, final, err);
    if (st == HL_OK) {
        target t = {formats_known[k].dev, tmp, NULL, fig->w, fig->h};
        pthread_mutex_lock(&plot_lock);
        st = draw_on_stream(fig, &t, NULL, err);
        pthread_mutex_unlock(&plot_lock);
        struct stat sb;
        if (st == HL_OK && (stat(tmp, &sb) != 0 || sb.st_size == 0))
            st = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write '%s': PLplot wrote nothing",
                              final);
        else if (st != HL_OK)
            hl_error_prefix(err, "writing '%s'", final);
        if (st == HL_OK && rename(tmp, final) != 0)
            st = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write '%s': %s", final,
                              strerror(errno));
        if (st != HL_OK)
            unlink(tmp);
    }
    free(tmp);
    free(final);
    return st;
}

hl_status hl_figure_write(const hl_figure *fig, const char *path, const char *formats,
                          hl_error *err)
{
    int want[NFORMATS];
    hl_status st = parse_formats(want, formats, err);
    if (st != HL_OK)
        return st;
    if (path == NULL || *path == '\0')
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "empty figure path");
    for (int k = 0; k < NFORMATS && st == HL_OK; k++)
        if (want[k])
            st = write_one(fig, path, k, err);
    return st;
}

/* ---- files ------------------------------------------------------------- */

/* The formats of a list as plot.h reads it ("png,svg", spaces and commas
 * between, case-insensitive; each counted once): HL_EINVAL before anything
 * is written when a name is unknown or none is given. */
hl_status hl_figure_count_formats(int *n, const char *formats, hl_error *err)
{
    static const char *const known[3] = {"png", "svg", "pdf"};
    int want[3] = {0, 0, 0};
    *n = 0;
    for (const char *p = formats != NULL ? formats : ""; *p;) {
        while (*p == ' ' || *p == ',')
            p++;
        size_t len = strcspn(p, ", ");
        if (len == 0)
            break;
        int k = 0;
        while (k < 3 && !(len == 3 && strncasecmp(p, known[k], 3) == 0))
            k++;
        if (k == 3)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "unknown figure format '%.*s' (png, svg, pdf)", (int)len, p);
        *n += !want[k];
        want[k] = 1;
        p += len;
    }
    return *n > 0 ? HL_OK : hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no figure format given");
}

hl_status hl_figure_mkdir(const char *dir, hl_error *err)
{
    char *d = hl_xstrdup(dir);
    hl_status st = HL_OK;
    for (char *s = d + 1; *s && st == HL_OK; s++) {
        if (*s != '/')
            continue;
        *s = '\0';
        if (mkdir(d, 0777) != 0 && errno != EEXIST)
            st = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot create directory '%s': %s", d,
                              strerror(errno));
        *s = '/';
    }
    struct stat sb;
    if (st == HL_OK && mkdir(d, 0777) != 0 &&
        !(errno == EEXIST && stat(d, &sb) == 0 && S_ISDIR(sb.st_mode)))
        st = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot create directory '%s': %s", d,
                          errno == EEXIST ? "a file of that name exists" : strerror(errno));
    free(d);
    return st;
}
