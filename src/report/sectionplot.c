/* The figure of a surface of section (see hamlie/sectionplot.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "hamlie/sectionplot.h"

hl_figure *hl_section_figure(const char *title, const char *xlabel, const char *ylabel, int norbits,
                             const size_t *counts, const double *const *xs, const double *const *ys,
                             hl_error *err)
{
    hl_figure *f = hl_figure_new(title, xlabel, ylabel);
    hl_figure_set_equal_aspect(f, 1);
    /* a legend of dozens of orbits would hide the section */
    hl_figure_set_legend(f, norbits <= 8 ? HL_LEGEND_TOP_RIGHT : HL_LEGEND_NONE);
    char label[32];
    for (int i = 0; i < norbits; i++) {
        hl_color c = (hl_color)(1 + i % (HL_COLOR_COUNT - 1));
        snprintf(label, sizeof label, "orbit %d", i);
        if (hl_figure_add(f, counts[i], xs[i], ys[i], HL_DRAW_DOTS, c, label, err) != HL_OK) {
            hl_figure_free(f);
            return NULL;
        }
    }
    return f;
}

hl_status hl_section_plot_write(const char *dir, const char *formats, const char *title,
                                const char *xlabel, const char *ylabel, int norbits,
                                const size_t *counts, const double *const *xs,
                                const double *const *ys, hl_error *err)
{
    hl_figure *f = hl_section_figure(title, xlabel, ylabel, norbits, counts, xs, ys, err);
    if (f == NULL)
        return err != NULL ? err->status : HL_EINVAL;
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
