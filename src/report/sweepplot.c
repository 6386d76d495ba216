/* The maps of a sweep (see hamlie/sweepplot.h): values at grid points in
 * colour bands, one series of filled squares per band. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "hamlie/sweepplot.h"

/* Cold to hot, black left for the axes. */
static const hl_color band_color[HL_SWEEP_PLOT_BANDS] = {
    HL_COLOR_BLUE,   HL_COLOR_CYAN,    HL_COLOR_GREEN, HL_COLOR_GRAY,
    HL_COLOR_ORANGE, HL_COLOR_MAGENTA, HL_COLOR_RED,   HL_COLOR_BROWN};

static void finite_range(size_t n, const double *vs, double *lo, double *hi)
{
    *lo = INFINITY;
    *hi = -INFINITY;
    for (size_t i = 0; i < n; i++)
        if (isfinite(vs[i])) {
            *lo = vs[i] < *lo ? vs[i] : *lo;
            *hi = vs[i] > *hi ? vs[i] : *hi;
        }
}

static int band_of(double v, double lo, double width)
{
    int b = width > 0 ? (int)((v - lo) / width) : 0;
    return b < 0 ? 0 : b >= HL_SWEEP_PLOT_BANDS ? HL_SWEEP_PLOT_BANDS - 1 : b;
}

hl_figure *hl_sweep_map_figure(const char *title, const char *xlabel, const char *ylabel, size_t n,
                               const double *xs, const double *ys, const double *vs, hl_error *err)
{
    double lo, hi;
    finite_range(n, vs, &lo, &hi);
    double width = hi > lo ? (hi - lo) / HL_SWEEP_PLOT_BANDS : 0;
    double *bx = hl_xmalloc((n ? n : 1) * sizeof *bx), *by = hl_xmalloc((n ? n : 1) * sizeof *by);
    hl_figure *f = hl_figure_new(title, xlabel, ylabel);
    hl_figure_set_legend(f, HL_LEGEND_TOP_RIGHT);
    int st = HL_OK;
    for (int b = 0; st == HL_OK && b < HL_SWEEP_PLOT_BANDS; b++) {
        size_t m = 0;
        for (size_t i = 0; i < n; i++)
            if (isfinite(vs[i]) && band_of(vs[i], lo, width) == b) {
                bx[m] = xs[i];
                by[m++] = ys[i];
            }
        if (m == 0 && !(width > 0 && isfinite(lo)))
            continue;
        char label[64];
        snprintf(label, sizeof label, "%.3g .. %.3g", lo + b * width, lo + (b + 1) * width);
        st = hl_figure_add(f, m, bx, by, HL_DRAW_SQUARES, band_color[b], label, err);
    }
    free(bx);
    free(by);
    if (st != HL_OK) {
        hl_figure_free(f);
        return NULL;
    }
    return f;
}

hl_status hl_sweep_plot_write(const char *dir, const char *formats, const char *name,
                              const char *title, const char *xlabel, const char *ylabel, size_t n,
                              const double *xs, const double *ys, const double *vs, hl_error *err)
{
    hl_figure *f = hl_sweep_map_figure(title, xlabel, ylabel, n, xs, ys, vs, err);
    if (f == NULL)
        return err != NULL ? err->status : HL_EINVAL;
    int st = hl_figure_mkdir(dir, err);
    if (st == HL_OK) {
        size_t len = strlen(dir) + strlen(name) + 2;
        char *path = hl_xmalloc(len);
        snprintf(path, len, "%s/%s", dir, name);
        st = hl_figure_write(f, path, formats, err);
        free(path);
    }
    hl_figure_free(f);
    return st;
}
