/* Figures: the figure object, its colours, and its axis ranges (the rules
 * are documented in hamlie/plot.h).  Drawing through PLplot is in
 * plot_draw.c, writing files in plot_file.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "base/buf.h"
#include "report/plot_impl.h"

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
    if ((int)draw < HL_DRAW_LINE || draw > HL_DRAW_POINTS)
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

double hl_plot_ymap_(double y, int ylog)
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

void hl_plot_layout_compute_(hl_plot_layout *lay, const hl_figure *fig)
{
    double xr[2] = {INFINITY, -INFINITY}, yr[2] = {INFINITY, -INFINITY};
    int have = 0;

    lay->ylog = decide_log(fig);
    for (size_t i = 0; i < fig->ns; i++)
        for (size_t k = 0; k < fig->s[i].n; k++) {
            double x = fig->s[i].x[k], y = hl_plot_ymap_(fig->s[i].y[k], lay->ylog);
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

/* Liang–Barsky. */
int hl_plot_clip_segment_(const hl_plot_layout *lay, const double a[2], const double b[2],
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
