/* hamlie — the maps of a sweep over a grid in two variables: one value per
 * grid point (log10 max_dH, MEGNO) drawn as a filled square at the point,
 * its colour the value's band (plot.h's palette, bands of equal width
 * between the finite minimum and maximum; a legend names them), points
 * without a finite value left out.
 *
 *   hl_sweep_plot_write(dir, "png", "max_dH-euler-dt0.1", "log10 max |H - H0|, euler",
 *                       "q", "p", n, xs, ys, vs, err);
 *
 * writes DIR/<name>.<format> (DIR is created), whole or not at all
 * (plot.h).  Errors as hl_figure_write. */
#ifndef HAMLIE_SWEEPPLOT_H
#define HAMLIE_SWEEPPLOT_H

#include <stddef.h>

#include "hamlie/error.h"
#include "hamlie/plot.h"

#ifdef __cplusplus
extern "C" {
#endif

/* The number of colour bands of a map. */
#define HL_SWEEP_PLOT_BANDS 8

hl_figure *hl_sweep_map_figure(const char *title, const char *xlabel, const char *ylabel, size_t n,
                               const double *xs, const double *ys, const double *vs, hl_error *err);

hl_status hl_sweep_plot_write(const char *dir, const char *formats, const char *name,
                              const char *title, const char *xlabel, const char *ylabel, size_t n,
                              const double *xs, const double *ys, const double *vs, hl_error *err);

#ifdef __cplusplus
}
#endif

#endif
