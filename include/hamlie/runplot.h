/* hamlie — figures for any run: phase portraits, coordinates in time,
 * invariants in time, sigma against the reference, energy error.
 *
 * A run plot holds the columns of one run (the layout of `hamlie run`'s CSV:
 * t, the 2N phase variables q then p, H, sigma, then the observers) and draws
 * them with plot.h.  Several runs (schemes) can share one set of figures.
 *
 *   hl_runplot *rp = hl_runplot_new("euler", ncols, names);
 *   for each row: hl_runplot_add_row(rp, values, err);
 *   hl_runplot_opts o = HL_RUNPLOT_OPTS_DEFAULT;
 *   hl_runplot_write(&rp, 1, "out/run", &o, err);
 *   hl_runplot_free(rp);
 */
#ifndef HAMLIE_RUNPLOT_H
#define HAMLIE_RUNPLOT_H

#include <stddef.h>

#include "hamlie/error.h"
#include "hamlie/plot.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_runplot hl_runplot;

/* label: the run's name in legends (a scheme name); names: the ncols column
 * names (copied), the first being "t".  Which columns are phase variables
 * is decided from the names as hamlie run writes them: the columns between
 * "t" and "H" are q_1..q_N, p_1..p_N. */
hl_runplot *hl_runplot_new(const char *label, int ncols, const char *const *names);
void hl_runplot_free(hl_runplot *rp); /* NULL is a no-op */

/* One row of ncols values (copied). */
hl_status hl_runplot_add_row(hl_runplot *rp, const double *values, hl_error *err);

size_t hl_runplot_nrows(const hl_runplot *rp);     /* 0 for NULL */

/* max over rows of |H - H0| (H0: the first row's H), NaN without an H
 * column or rows.  The energy error of the figures is this |H - H0|: read
 * from a CSV whose H has more digits than a double (hamlie run --digits),
 * it is computed in Arb from the text, so that a difference of 1e-30 in
 * H = 0.5 is not drawn as 0. */
double hl_runplot_max_dH(const hl_runplot *rp);
const char *hl_runplot_label(const hl_runplot *rp); /* NULL for NULL */

/* Read a CSV file written by `hamlie run` (a header line of names, then rows
 * of numbers; "inf", "nan" accepted).  label NULL: the file's base name
 * without ".csv".  Names may be quoted ("a,b", "" for a quote); blank lines
 * and a final "\r" are ignored.  Errors name the file, the line and the
 * column (1-based field number and its name): "run.csv: line 7, column 3
 * (p): 'abc' is not a number"; HL_EINVAL for a bad file (first column not
 * "t", a row with too few or too many values, no data rows), HL_EIO when it
 * cannot be read.  The roles of the columns are checked when plotting. */
hl_status hl_runplot_read_csv(hl_runplot **out, const char *path, const char *label,
                              hl_error *err);

typedef struct hl_runplot_opts {
    const char *formats; /* "png,svg,pdf" or a subset (plot.h) */
    const char *phase;   /* "x:px": one projection; NULL: each canonical pair */
    int width, height;   /* PNG pixels, SVG/PDF points (plot.h: 16..10000);
                            0, 0: plot.h's default 800 x 600 */
} hl_runplot_opts;

#define HL_RUNPLOT_OPTS_DEFAULT {"png", NULL, 0, 0}

/* Write the figures of nruns runs (same columns) into dir (created if
 * missing); the runs are compared on each figure.  Files are written whole
 * or not at all (plot.h).  *written (may be NULL) gets the number of files.
 *
 * The figures (file base names; names of columns keep [A-Za-z0-9._-], any
 * other character becomes '_'):
 *   phase-<q>-<p>       each canonical pair (q_j, p_j), or only the
 *                       projection opts->phase ("x:px": any two columns)
 *   time-<v>            each phase variable in time
 *   energy-error        |H - H0| in time (H0: the run's first row), log scale
 *   sigma               sigma in time, log scale (when the runs have it)
 *   observer-<k>-<f>    each observer in time (k = 1, 2, ...)
 * A log axis falls back to linear when no value is positive (H conserved
 * exactly).  A quantity in time with poles (x/p where p = 0) keeps a
 * readable range: with w the range of its middle 90% (5th to 95th
 * percentile, all runs), when its values spread over more than 5 w and a
 * run leaves that middle range widened by w/2 on each side and comes back
 * (a spike, not a blow-up at the end), the y axis shows only the widened
 * range, and lines break at the poles (plot.h).  Run r is drawn in colour r (blue, red, green, orange, purple,
 * cyan, magenta, brown, gray, black, then again) as a line, or, when it has
 * at most 400 rows, as markers (dots, squares, triangles, diamonds); with
 * several runs a legend gives their labels (in the corner of the plot that
 * covers the fewest points), with one its label is in the titles.  HL_EINVAL: no run, a run without rows, runs with different
 * columns, columns not in hamlie run's layout (no "t" first, no "H", an odd
 * number of variables), an unknown --phase column, a bad format list (all
 * before anything is written); HL_EIO: a file or the directory cannot be
 * written. */
hl_status hl_runplot_write(hl_runplot *const *runs, int nruns, const char *dir,
                           const hl_runplot_opts *opts, int *written, hl_error *err);

/* The same figures as hl_figure objects (for rendering in memory, plot.h):
 * *nfig figures and their file base names, freed with
 * hl_runplot_figures_free.  Errors as hl_runplot_write. */
hl_status hl_runplot_figures(hl_figure ***figs, char ***names, int *nfig,
                             hl_runplot *const *runs, int nruns, const hl_runplot_opts *opts,
                             hl_error *err);
void hl_runplot_figures_free(hl_figure **figs, char **names, int nfig);

#ifdef __cplusplus
}
#endif

#endif
