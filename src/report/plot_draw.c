/* Figures drawn through PLplot (cairo devices): the palette, lines broken at
 * poles and clipped to the window, markers, the legend, and one drawing on a
 * fresh PLplot stream, into memory (hl_figure_render_rgb) or a file. */
#include <math.h>
#include <pthread.h>
#include <setjmp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "report/plplot_api.h" /* PLplot, loaded on the first drawing */

#include "base/buf.h"
#include "report/plot_impl.h"

/* cmap0: 0 background, 1 axes and text, 2 + c the colour c. */
#define COL_BG 0
#define COL_FG 1
#define COL_SERIES(c) (2 + (int)(c))

/* Sizes as fractions of the page height (mm), so a figure reads the same at
 * any pixel size: text 14 px and dots of radius 3.5 px at 600 px tall. */
#define CHAR_FRAC (14.0 / 600.0)
#define DOT_FRAC (3.5 / 600.0)
#define POINT_FRAC (1.1 / 600.0) /* HL_DRAW_POINTS: a section's fine structure */
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
        unsigned char rgb[3];
        hl_color_rgb(rgb, (hl_color)c);
        r[COL_SERIES(c)] = rgb[0];
        g[COL_SERIES(c)] = rgb[1];
        b[COL_SERIES(c)] = rgb[2];
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
        double a[2] = {s->x[i], hl_plot_ymap_(s->y[i], lay->ylog)};
        double b[2] = {s->x[i + 1], hl_plot_ymap_(s->y[i + 1], lay->ylog)};
        double t0, t1;
        if (!isfinite(a[0]) || !isfinite(b[0]) || isnan(a[1]) || isnan(b[1]) ||
            hl_plot_is_pole_jump(a[1], b[1], lay->wy0, lay->wy1, pole_frac) ||
            !hl_plot_clip_segment_(lay, a, b, &t0, &t1)) {
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
    double r_mm = (s->draw == HL_DRAW_POINTS ? POINT_FRAC : DOT_FRAC) * (py1 - py0);
    double rx = r_mm * (lay->wx1 - lay->wx0) / ((vx1 - vx0) * (px1 - px0));
    double ry = r_mm * (lay->wy1 - lay->wy0) / ((vy1 - vy0) * (py1 - py0));
    double ux[16], uy[16];
    PLFLT mx[16], my[16];
    int m = marker_shape(s->draw, ux, uy);
    for (size_t i = 0; i < s->n; i++) {
        double x = s->x[i], y = hl_plot_ymap_(s->y[i], lay->ylog);
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
             PL_POSITION_INSIDE | PL_POSITION_VIEWPORT | pos[fig->legend], 0.02, 0.03, 0.08, COL_BG,
             COL_FG, 1, 0, 0, (PLINT)n, opt, 1.0, 0.9, 2.0, 0.0, tcol, text, NULL, NULL, NULL, NULL,
             lcol, lsty, lwid, scol, ssca, snum, sym);
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

    hl_status loaded = hl_plplot_load(err);
    if (loaded != HL_OK)
        return loaded;
    if (!have_device(t->dev))
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                            "PLplot device '%s' is not installed (plplot-driver-cairo)", t->dev);
    hl_plot_layout_compute_(&lay, fig);
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
    if (rgb == NULL || w < HL_PLOT_MIN_PIXELS || w > HL_PLOT_MAX_PIXELS || h < HL_PLOT_MIN_PIXELS ||
        h > HL_PLOT_MAX_PIXELS)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "bad image %dx%d", w, h);
    /* memcairo draws over what the buffer holds: start from the background */
    memset(rgb, 255, (size_t)w * (size_t)h * 3);
    target t = {"memcairo", NULL, rgb, w, h};
    pthread_mutex_lock(&plot_lock);
    hl_status st = draw_on_stream(fig, &t, frame, err);
    pthread_mutex_unlock(&plot_lock);
    return st;
}

int hl_plot_frame_pixel(const hl_plot_frame *frame, int w, int h, double x, double y, double *px,
                        double *py)
{
    double wy = hl_plot_ymap_(y, frame->ylog);
    if (!isfinite(x) || isnan(wy))
        return 0;
    double fx =
        frame->vx0 + (x - frame->wx0) / (frame->wx1 - frame->wx0) * (frame->vx1 - frame->vx0);
    double fy =
        frame->vy0 + (wy - frame->wy0) / (frame->wy1 - frame->wy0) * (frame->vy1 - frame->vy0);
    *px = fx * w;
    *py = (1 - fy) * h;
    return 1;
}

hl_status hl_plot_draw_file_(const hl_figure *fig, const char *dev, const char *file, hl_error *err)
{
    target t = {dev, file, NULL, fig->w, fig->h};
    pthread_mutex_lock(&plot_lock);
    hl_status st = draw_on_stream(fig, &t, NULL, err);
    pthread_mutex_unlock(&plot_lock);
    return st;
}
