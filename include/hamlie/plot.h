/* hamlie — figures: 2-D line and dot plots drawn with PLplot (cairo).
 *
 * A figure holds a title, axis labels and series (copies of the caller's
 * data); it draws nothing until it is written to files (PNG, SVG, PDF) or
 * rendered into a caller's RGB buffer.  The data comes from elsewhere (a
 * trajectory, an error sequence): this module only draws.
 *
 *   hl_figure *f = hl_figure_new("Euler: x/p in time", "t", "x/p");
 *   hl_figure_add(f, n, t, xp_exact, HL_DRAW_LINE, HL_COLOR_RED, "exact", err);
 *   hl_figure_add(f, m, tn, xp_euler, HL_DRAW_DOTS, HL_COLOR_BLUE, "Euler", err);
 *   hl_figure_set_yclip(f, -10, 10);          // x/p has poles where p = 0
 *   hl_figure_write(f, "out/euler-inv", "png,svg,pdf", err);
 *   hl_figure_free(f);
 *
 * Text (title, labels, legend) is UTF-8 (σ, Δ, ∂ are drawn as such) and may
 * use PLplot's escapes: #gs = σ, #gD = Δ, #u..#d superscript, ## = '#'.
 *
 * AXES.  x is linear.  y is linear, log10, or automatic: log when no value is
 * negative and the positive values span more than 3 decades
 * (max/min > 1e3).  On a log axis values <= 0 are dropped (a line breaks
 * there), never drawn at -inf.  The range of each axis is that of the finite
 * data (positive data on a log axis) widened by a margin (2% in x, 5% in y,
 * of the span; in decades on a log axis), then intersected with the clip
 * range the caller set, if any.  A range of zero width (H constant to
 * rounding, |hi - lo| <= 1e-9 |mid|) is widened to mid ± 10% (± 1 if mid=0).
 * Equal aspect (phase portraits) makes one unit of x as long as one of y.
 *
 * LINES break (no segment drawn between points i and i+1) when
 *   - either point is not finite (NaN, ±inf), or <= 0 on a log axis; or
 *   - the values cross a pole: y_i and y_{i+1} have opposite signs and both
 *     |y_i| and |y_{i+1}| are at least pole_frac × (hi − lo) of the plotted y
 *     range (default pole_frac = 0.25; see hl_plot_is_pole_jump).  A smooth
 *     curve crossing zero has small |y| on both sides of the crossing; a pole
 *     (x/p where p = 0) jumps from a large value to a large one of the other
 *     sign.  A curve sampled so coarsely that it crosses zero in one step from
 *     beyond ±pole_frac of the range is broken too: sample finer or lower
 *     pole_frac with hl_figure_set_pole_frac (0 turns the rule off).
 * Segments are clipped to the plotted window before they reach PLplot, so
 * huge values near a pole cannot overflow its integer device coordinates.
 *
 * PLplot is process-global: calls that draw are serialised by a mutex and
 * each uses a stream of its own (plmkstrm … plend1), restoring the caller's
 * current stream.  While drawing, PLplot's abort and exit handlers are
 * replaced (plsabort, plsexit) and its error messages go to a buffer
 * (plsError), so they are not printed and a fatal PLplot error returns HL_EIO
 * (longjmp out of its exit handler; that stream is then abandoned) instead of
 * ending the process; the handlers are reset to PLplot's defaults
 * afterwards (a caller's own plsexit/plsabort handler is lost).  PLplot's
 * warnings (plwarn) have no hook and would still reach stderr; none occur in
 * the tests.  Under LeakSanitizer, fontconfig's process-wide caches show as
 * leaks (suppressed in the tests with leak:libfontconfig.so).  Files are opened by hamlie before PLplot sees
 * them, so a bad path is an hl_error, never a prompt or an exit() in PLplot.
 */
#ifndef HAMLIE_PLOT_H
#define HAMLIE_PLOT_H

#include <stddef.h>

#include "hamlie/error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_figure hl_figure;

typedef enum hl_axis_scale {
    HL_AXIS_LINEAR = 0,
    HL_AXIS_LOG,  /* log10 */
    HL_AXIS_AUTO  /* log when the data span more than 3 decades (see above) */
} hl_axis_scale;

typedef enum hl_draw {
    HL_DRAW_LINE = 0,   /* continuous line (breaks: see above) */
    HL_DRAW_DOTS,       /* filled circles, one per point */
    HL_DRAW_SQUARES,    /* filled squares: a second scheme on one figure */
    HL_DRAW_TRIANGLES,  /* filled triangles: a third */
    HL_DRAW_DIAMONDS,   /* filled diamonds: a fourth */
    HL_DRAW_POINTS      /* small filled circles: thousands of points that must
                           not merge (surfaces of section) */
} hl_draw;

typedef enum hl_color {
    HL_COLOR_BLACK = 0, /* (0, 0, 0) */
    HL_COLOR_RED,       /* (255, 0, 0)   the exact solution in the paper */
    HL_COLOR_BLUE,      /* (0, 0, 255)   the scheme in the paper */
    HL_COLOR_GREEN,     /* (0, 160, 0)   invariant errors in the paper */
    HL_COLOR_ORANGE,    /* (255, 140, 0) */
    HL_COLOR_PURPLE,    /* (128, 0, 160) */
    HL_COLOR_CYAN,      /* (0, 170, 200) */
    HL_COLOR_MAGENTA,   /* (220, 0, 220) */
    HL_COLOR_BROWN,     /* (140, 80, 20) */
    HL_COLOR_GRAY,      /* (128, 128, 128) */
    HL_COLOR_COUNT
} hl_color;

typedef enum hl_legend_pos {
    HL_LEGEND_TOP_RIGHT = 0, /* inside the plot box */
    HL_LEGEND_TOP_LEFT,
    HL_LEGEND_BOTTOM_RIGHT,
    HL_LEGEND_BOTTOM_LEFT,
    HL_LEGEND_NONE
} hl_legend_pos;

/* The colour's RGB (out[3]); the name ("red"), or NULL if c is out of range. */
void hl_color_rgb(unsigned char out[3], hl_color c);
const char *hl_color_name(hl_color c);
/* By name, case-insensitive ("red", "blue", "grey" too); -1 if unknown. */
int hl_color_from_name(const char *name);

/* ---- building a figure -------------------------------------------------- */

/* Any text may be NULL (nothing drawn).  Strings are copied.  Aborts only if
 * memory runs out (as every allocation in hamlie). */
hl_figure *hl_figure_new(const char *title, const char *xlabel, const char *ylabel);
void hl_figure_free(hl_figure *fig); /* NULL is a no-op */

void hl_figure_set_title(hl_figure *fig, const char *title);
void hl_figure_set_labels(hl_figure *fig, const char *xlabel, const char *ylabel);
void hl_figure_set_yscale(hl_figure *fig, hl_axis_scale scale);
void hl_figure_set_equal_aspect(hl_figure *fig, int on);
void hl_figure_set_legend(hl_figure *fig, hl_legend_pos pos);
/* Pixel size of PNG output (default 800 x 600); SVG and PDF get a page of
 * the same proportions (w x h points).  HL_EINVAL outside 16..10000. */
hl_status hl_figure_set_size(hl_figure *fig, int w, int h, hl_error *err);
/* Clip the automatic range to [lo, hi] (data units, also on a log axis);
 * either may be NaN for "no limit".  HL_EINVAL if lo >= hi. */
hl_status hl_figure_set_xclip(hl_figure *fig, double lo, double hi, hl_error *err);
hl_status hl_figure_set_yclip(hl_figure *fig, double lo, double hi, hl_error *err);
/* See LINES above; frac >= 0 (0: no pole breaks).  HL_EINVAL otherwise. */
hl_status hl_figure_set_pole_frac(hl_figure *fig, double frac, hl_error *err);

/* Add a series of n points (copied).  n = 0 is allowed (legend entry only).
 * HL_EINVAL: NULL arrays with n > 0, a colour or draw kind out of range;
 * HL_ELIMIT: more than 1e8 points.  label may be NULL (no legend entry). */
hl_status hl_figure_add(hl_figure *fig, size_t n, const double *x, const double *y,
                        hl_draw draw, hl_color color, const char *label, hl_error *err);

size_t hl_figure_nseries(const hl_figure *fig);

/* ---- output ------------------------------------------------------------ */

/* Write path.png, path.svg and/or path.pdf: formats is a comma-separated list
 * ("png,svg,pdf", case-insensitive).  Each file is drawn into a temporary
 * file beside it and renamed into place only when complete, so a file is
 * either written whole or not at all (an earlier format of the same call
 * stays if a later one fails).  HL_EINVAL: unknown or empty format list
 * (checked before anything is written); HL_EIO: a file cannot be created or
 * written (the message names it), or PLplot failed. */
hl_status hl_figure_write(const hl_figure *fig, const char *path, const char *formats,
                          hl_error *err);

/* The number of distinct formats in a list as hl_figure_write reads it
 * ("png,svg"; spaces and commas between, case-insensitive): HL_EINVAL for
 * an unknown name or an empty list, so a caller can refuse before writing
 * anything. */
hl_status hl_figure_count_formats(int *n, const char *formats, hl_error *err);

/* HL_OK if figures can be drawn: PLplot is loaded on the first drawing (or
 * by this call); else HL_EUNSUP naming what to install.  Asked before
 * creating folders, so that a missing PLplot leaves nothing behind. */
hl_status hl_figure_drawable(hl_error *err);

/* Create the folder dir and its parents (mkdir -p); HL_EIO naming the part
 * that cannot be created, or when a file of that name is in the way. */
hl_status hl_figure_mkdir(const char *dir, hl_error *err);

/* Where the plot box landed: the viewport as fractions of the image (x from
 * the left, y from the bottom) and the world window (on a log axis, y is
 * log10 of the data).  Filled by hl_figure_render_rgb. */
typedef struct hl_plot_frame {
    double vx0, vx1, vy0, vy1;
    double wx0, wx1, wy0, wy1;
    int ylog;
} hl_plot_frame;

/* Render into rgb (w*h*3 bytes, rows top to bottom, R G B), through the same
 * drawing code as the files (PLplot's memcairo device).  frame may be NULL.
 * HL_EINVAL: size outside 16..10000 or rgb NULL. */
hl_status hl_figure_render_rgb(const hl_figure *fig, int w, int h, unsigned char *rgb,
                               hl_plot_frame *frame, hl_error *err);

/* Pixel position (column from the left, row from the top, fractional; pixel
 * (i, j) covers [i, i+1) x [j, j+1)) of the data point (x, y) in an image of
 * w x h rendered with that frame.  Returns 0 if y cannot be placed (y <= 0 on
 * a log axis, not finite). */
int hl_plot_frame_pixel(const hl_plot_frame *frame, int w, int h, double x, double y,
                        double *px, double *py);

/* The pole rule of LINES: nonzero if a line from y0 to y1 must not be drawn
 * on a y range [lo, hi] with the given pole_frac. */
int hl_plot_is_pole_jump(double y0, double y1, double lo, double hi, double pole_frac);

#ifdef __cplusplus
}
#endif

#endif
