/* hamlie — the figure of a surface of section: the crossings of every
 * orbit as dots, a colour per orbit (the palette of plot.h, repeated after
 * HL_COLOR_COUNT - 1 orbits: black is left for axes), on equal axes.
 *
 *   hl_section_plot_write(dir, "png", "Henon-Heiles E = 1/8, x = 0, px > 0",
 *                         "y", "py", norbits, counts, xs, ys, err);
 *
 * writes DIR/section.<format> (DIR is created), whole or not at all
 * (plot.h).  Errors as hl_figure_write. */
#ifndef HAMLIE_SECTIONPLOT_H
#define HAMLIE_SECTIONPLOT_H

#include <stddef.h>

#include "hamlie/error.h"
#include "hamlie/plot.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Orbit i has counts[i] points (xs[i][k], ys[i][k]). */
hl_figure *hl_section_figure(const char *title, const char *xlabel, const char *ylabel, int norbits,
                             const size_t *counts, const double *const *xs, const double *const *ys,
                             hl_error *err);

hl_status hl_section_plot_write(const char *dir, const char *formats, const char *title,
                                const char *xlabel, const char *ylabel, int norbits,
                                const size_t *counts, const double *const *xs,
                                const double *const *ys, hl_error *err);

/* The orbits in classes instead of a colour each (a chaos indicator's
 * regular / chaotic): orbit i belongs to class cls[i] (0 .. nclasses-1;
 * any other value: not drawn), class c is drawn in colors[c] with the
 * legend entry labels[c] (NULL: none), classes in order (the last on top).
 * Writes DIR/section.<format> as hl_section_plot_write. */
hl_status hl_section_plot_classes_write(const char *dir, const char *formats, const char *title,
                                        const char *xlabel, const char *ylabel, int norbits,
                                        const size_t *counts, const double *const *xs,
                                        const double *const *ys, const int *cls, int nclasses,
                                        const hl_color *colors, const char *const *labels,
                                        hl_error *err);

#ifdef __cplusplus
}
#endif

#endif
