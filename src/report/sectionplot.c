/* The figure of a surface of section (see hamlie/sectionplot.h). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "hamlie/sectionplot.h"

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* A section of a scheme that blows up (explicit Euler) has its last
 * crossings far out, even near overflow, where the automatic range would
 * squash the rest or fail: the axis is clipped to the median +- 10 median
 * absolute deviations (a section's own spread is within about 3) when the
 * data go beyond. */
static void robust_clip(hl_figure *f, int axis, int norbits, const size_t *counts,
                        const double *const *v)
{
    size_t n = 0;
    for (int i = 0; i < norbits; i++)
        n += counts[i];
    double *all = hl_xmalloc((n ? n : 1) * sizeof *all);
    size_t m = 0;
    for (int i = 0; i < norbits; i++)
        for (size_t k = 0; k < counts[i]; k++)
            if (isfinite(v[i][k]))
                all[m++] = v[i][k];
    if (m >= 8) {
        qsort(all, m, sizeof *all, by_value);
        double med = all[m / 2], lo = all[0], hi = all[m - 1];
        for (size_t k = 0; k < m; k++)
            all[k] = fabs(all[k] - med);
        qsort(all, m, sizeof *all, by_value);
        double mad = all[m / 2], a = med - 10 * mad, b = med + 10 * mad;
        if (mad > 0 && (lo < a || hi > b)) {
            if (axis == 0)
                hl_figure_set_xclip(f, a, b, NULL);
            else
                hl_figure_set_yclip(f, a, b, NULL);
        }
    }
    free(all);
}

hl_figure *hl_section_figure(const char *title, const char *xlabel, const char *ylabel, int norbits,
                             const size_t *counts, const double *const *xs, const double *const *ys,
                             hl_error *err)
{
    hl_figure *f = hl_figure_new(title, xlabel, ylabel);
    hl_figure_set_equal_aspect(f, 1);
    robust_clip(f, 0, norbits, counts, xs);
    robust_clip(f, 1, norbits, counts, ys);
    /* a legend of dozens of orbits would hide the section */
    hl_figure_set_legend(f, norbits <= 8 ? HL_LEGEND_TOP_RIGHT : HL_LEGEND_NONE);
    char label[32];
    for (int i = 0; i < norbits; i++) {
        hl_color c = (hl_color)(1 + i % (HL_COLOR_COUNT - 1));
        snprintf(label, sizeof label, "orbit %d", i);
        if (hl_figure_add(f, counts[i], xs[i], ys[i], HL_DRAW_POINTS, c, label, err) != HL_OK) {
            hl_figure_free(f);
            return NULL;
        }
    }
    return f;
}

/* DIR/section.<formats>, f freed. */
static hl_status write_figure(hl_figure *f, const char *dir, const char *formats, hl_error *err)
{
    int st = hl_figure_mkdir(dir, err);
    if (st == HL_OK) {
        size_t n = strlen(dir) + 16;
        char *path = hl_xmalloc(n);
        snprintf(path, n, "%s/section", dir);
        st = hl_figure_write(f, path, formats, err);
        free(path);
    }
    hl_figure_free(f);
    return st;
}

hl_status hl_section_plot_write(const char *dir, const char *formats, const char *title,
                                const char *xlabel, const char *ylabel, int norbits,
                                const size_t *counts, const double *const *xs,
                                const double *const *ys, hl_error *err)
{
    hl_figure *f = hl_section_figure(title, xlabel, ylabel, norbits, counts, xs, ys, err);
    if (f == NULL)
        return err != NULL ? err->status : HL_EINVAL;
    return write_figure(f, dir, formats, err);
}

/* The points of the orbits of class c, end to end. */
static size_t class_points(double **x, double **y, int norbits, const size_t *counts,
                           const double *const *xs, const double *const *ys, const int *cls, int c)
{
    size_t n = 0;
    for (int i = 0; i < norbits; i++)
        n += cls[i] == c ? counts[i] : 0;
    *x = hl_xmalloc((n ? n : 1) * sizeof **x);
    *y = hl_xmalloc((n ? n : 1) * sizeof **y);
    size_t m = 0;
    for (int i = 0; i < norbits; i++)
        if (cls[i] == c && counts[i] > 0) {
            memcpy(*x + m, xs[i], counts[i] * sizeof **x);
            memcpy(*y + m, ys[i], counts[i] * sizeof **y);
            m += counts[i];
        }
    return n;
}

hl_status hl_section_plot_classes_write(const char *dir, const char *formats, const char *title,
                                        const char *xlabel, const char *ylabel, int norbits,
                                        const size_t *counts, const double *const *xs,
                                        const double *const *ys, const int *cls, int nclasses,
                                        const hl_color *colors, const char *const *labels,
                                        hl_error *err)
{
    hl_figure *f = hl_figure_new(title, xlabel, ylabel);
    hl_figure_set_equal_aspect(f, 1);
    robust_clip(f, 0, norbits, counts, xs);
    robust_clip(f, 1, norbits, counts, ys);
    hl_figure_set_legend(f, HL_LEGEND_TOP_RIGHT);
    hl_status st = HL_OK;
    for (int c = 0; c < nclasses && st == HL_OK; c++) {
        double *x, *y;
        size_t n = class_points(&x, &y, norbits, counts, xs, ys, cls, c);
        st = hl_figure_add(f, n, x, y, HL_DRAW_POINTS, colors[c], labels ? labels[c] : NULL, err);
        free(x), free(y);
    }
    if (st != HL_OK) {
        hl_figure_free(f);
        return st;
    }
    return write_figure(f, dir, formats, err);
}
