/* Internal to the figures of src/report (plot.c, plot_draw.c, plot_file.c):
 * the figure object and the world window of one drawing. */
#ifndef HAMLIE_REPORT_PLOT_IMPL_H
#define HAMLIE_REPORT_PLOT_IMPL_H

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
    int w, h;                  /* PNG pixels; SVG/PDF points */
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

/* The value drawn for y: itself, or log10(y) on a log axis; NaN if it has
 * no place on the axis. */
double hl_plot_ymap_(double y, int ylog);

/* The window of fig's data: the y scale decided, margins added, clipped. */
void hl_plot_layout_compute_(hl_plot_layout *lay, const hl_figure *fig);

/* Clip the segment a + t (b - a), t in [0, 1], to the window (Liang–Barsky):
 * 0 if nothing is left, else 1 and the kept [t0, t1]. */
int hl_plot_clip_segment_(const hl_plot_layout *lay, const double a[2], const double b[2],
                          double *t0, double *t1);

/* Draw fig into the existing file through the PLplot device dev (one drawing
 * at a time: PLplot's state is global). */
hl_status hl_plot_draw_file_(const hl_figure *fig, const char *dev, const char *file,
                             hl_error *err);

#endif
