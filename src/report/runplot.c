/* Figures for any run (runplot.h): the columns of `hamlie run`'s CSV drawn
 * with plot.h, several runs compared on each figure.
 *
 * Column roles come from the names, as cmd_run writes them: "t", then the
 * 2N phase variables (q_1..q_N, p_1..p_N), "H", then "sigma" when the run
 * had a reference, then the observers.  The figures (file base names):
 *   phase-<q>-<p>     each canonical pair (or the --phase projection)
 *   time-<v>          each phase variable in time
 *   energy-error      |H - H0| in time, log scale
 *   sigma             sigma = |z_n - z(t_n)|^2 in time, log scale (when the
 *                     runs have the column)
 *   observer-<k>-<f>  each observer in time
 * Names in files keep [A-Za-z0-9._-] and turn anything else into '_'.
 * Reading the CSV is in runplot_csv.c. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "base/buf.h"
#include "hamlie/plot.h"
#include "report/runplot_impl.h"

#define RP_MARKER_ROWS 400 /* runs with at most this many rows are drawn as markers */

/* The first column named "H" after "t", or -1. */
static int h_column(const hl_runplot *rp)
{
    for (int j = 1; j < rp->ncols; j++)
        if (strcmp(rp->names[j], "H") == 0)
            return j;
    return -1;
}

hl_runplot *hl_runplot_new(const char *label, int ncols, const char *const *names)
{
    hl_runplot *rp = hl_xcalloc(1, sizeof *rp);
    rp->label = hl_xstrdup(label != NULL ? label : "run");
    rp->ncols = ncols > 0 ? ncols : 0;
    rp->names = hl_xcalloc((size_t)rp->ncols + 1, sizeof *rp->names);
    for (int i = 0; i < rp->ncols; i++)
        rp->names[i] = hl_xstrdup(names != NULL && names[i] != NULL ? names[i] : "");
    rp->iH = h_column(rp);
    return rp;
}

void hl_runplot_free(hl_runplot *rp)
{
    if (rp == NULL)
        return;
    for (int i = 0; i < rp->ncols; i++)
        free(rp->names[i]);
    free(rp->names);
    free(rp->label);
    free(rp->v);
    free(rp->dH);
    free(rp);
}

size_t hl_runplot_nrows(const hl_runplot *rp) { return rp != NULL ? rp->nrows : 0; }

const char *hl_runplot_label(const hl_runplot *rp) { return rp != NULL ? rp->label : NULL; }

double hl_runplot_max_dH(const hl_runplot *rp)
{
    return rp != NULL && rp->iH >= 0 && rp->nrows > 0 ? rp->max_dH : NAN;
}

hl_status hl_runplot_add_row_dH_(hl_runplot *rp, const double *values, double dH, hl_error *err)
{
    if (rp == NULL || values == NULL || rp->ncols == 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "a run plot row needs its values");
    if (rp->nrows == rp->cap) {
        rp->cap = rp->cap ? 2 * rp->cap : 256;
        rp->v = hl_xrealloc(rp->v, rp->cap * (size_t)rp->ncols * sizeof *rp->v);
        rp->dH = hl_xrealloc(rp->dH, rp->cap * sizeof *rp->dH);
    }
    memcpy(rp->v + rp->nrows * (size_t)rp->ncols, values, (size_t)rp->ncols * sizeof *values);
    if (rp->iH >= 0 && isnan(dH))
        dH = fabs(values[rp->iH] - rp->v[rp->iH]); /* row 0's H */
    rp->dH[rp->nrows] = dH;
    if (rp->nrows == 0 || dH > rp->max_dH)
        rp->max_dH = dH;
    rp->nrows++;
    return HL_OK;
}

hl_status hl_runplot_add_row(hl_runplot *rp, const double *values, hl_error *err)
{
    return hl_runplot_add_row_dH_(rp, values, NAN, err);
}

/* ---- roles of the columns -------------------------------------------------- */

typedef struct roles {
    int n2;     /* phase variables: columns 1..n2 */
    int iH;     /* the H column, -1 if none */
    int isigma; /* the sigma column, -1 if none */
    int obs0;   /* first observer column (ncols if none) */
} roles;

static hl_status find_roles(roles *r, const hl_runplot *rp, hl_error *err)
{
    r->isigma = -1;
    r->iH = rp->iH;
    if (rp->ncols < 1 || strcmp(rp->names[0], "t") != 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "run '%s': the first column must be 't'", rp->label);
    if (r->iH < 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "run '%s': no column 'H' (hamlie run writes t, the variables, H, "
                            "sigma, the observers)",
                            rp->label);
    r->n2 = r->iH - 1;
    if (r->n2 < 2 || r->n2 % 2 != 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "run '%s': %d columns between 't' and 'H': the phase variables come "
                            "in pairs (q_1..q_N, p_1..p_N)",
                            rp->label, r->n2);
    r->obs0 = r->iH + 1;
    if (r->obs0 < rp->ncols && strcmp(rp->names[r->obs0], "sigma") == 0)
        r->isigma = r->obs0++;
    return HL_OK;
}

static int col_index(const hl_runplot *rp, const char *name, size_t n)
{
    for (int j = 0; j < rp->ncols; j++)
        if (strlen(rp->names[j]) == n && strncmp(rp->names[j], name, n) == 0)
            return j;
    return -1;
}

/* ---- figures --------------------------------------------------------------- */

/* Text for PLplot: '#' is its escape character. */
static char *pl_text(const char *s)
{
    hl_buf b;
    hl_buf_init(&b);
    for (; *s; s++) {
        if (*s == '#')
            hl_buf_putc(&b, '#');
        hl_buf_putc(&b, *s);
    }
    return hl_buf_take(&b);
}

static void file_part(hl_buf *b, const char *s)
{
    size_t n = 0;
    for (; *s && n < 60; s++, n++) {
        char c = *s;
        int ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                 c == '.' || c == '-' || c == '_';
        hl_buf_putc(b, ok ? c : '_');
    }
}

static const hl_color run_colors[] = {HL_COLOR_BLUE,   HL_COLOR_RED,   HL_COLOR_GREEN,
                                      HL_COLOR_ORANGE, HL_COLOR_PURPLE, HL_COLOR_CYAN,
                                      HL_COLOR_MAGENTA, HL_COLOR_BROWN, HL_COLOR_GRAY,
                                      HL_COLOR_BLACK};
static const hl_draw run_markers[] = {HL_DRAW_DOTS, HL_DRAW_SQUARES, HL_DRAW_TRIANGLES,
                                      HL_DRAW_DIAMONDS};

#define NCOLORS ((int)(sizeof run_colors / sizeof run_colors[0]))

/* What a figure plots against what: column ix (or t) and a y computed from
 * the row. */
typedef enum yk { Y_COL, Y_DH } yk;

typedef struct fig_spec {
    int ix, iy; /* columns */
    yk kind;
    int log;    /* log y axis (if any value > 0) */
    int phase;  /* a phase portrait: equal aspect when the spans compare */
} fig_spec;

static hl_status add_runs(hl_figure *f, hl_runplot *const *runs, int nruns, fig_spec sp,
                          int *any_pos, hl_error *err)
{
    hl_status st = HL_OK;
    *any_pos = 0;
    for (int r = 0; r < nruns && st == HL_OK; r++) {
        const hl_runplot *rp = runs[r];
        size_t n = rp->nrows, nc = (size_t)rp->ncols;
        double *x = hl_xmalloc((n + 1) * sizeof *x), *y = hl_xmalloc((n + 1) * sizeof *y);
        for (size_t i = 0; i < n; i++) {
            x[i] = rp->v[i * nc + (size_t)sp.ix];
            y[i] = sp.kind == Y_DH ? rp->dH[i] : rp->v[i * nc + (size_t)sp.iy];
            if (y[i] > 0 && isfinite(y[i]))
                *any_pos = 1;
        }
        char *lab = pl_text(rp->label);
        hl_draw d = n <= RP_MARKER_ROWS ? run_markers[r % 4] : HL_DRAW_LINE;
        st = hl_figure_add(f, n, x, y, d, run_colors[r % NCOLORS], lab, err);
        free(lab);
        free(x);
        free(y);
    }
    return st;
}

typedef struct fig_list {
    hl_figure **f;
    char **name;
    int n;
} fig_list;

static void push(fig_list *l, hl_figure *f, char *name)
{
    l->f = hl_xrealloc(l->f, (size_t)(l->n + 1) * sizeof *l->f);
    l->name = hl_xrealloc(l->name, (size_t)(l->n + 1) * sizeof *l->name);
    l->f[l->n] = f;
    l->name[l->n++] = name;
}

static void list_clear(fig_list *l)
{
    for (int i = 0; i < l->n; i++) {
        hl_figure_free(l->f[i]);
        free(l->name[i]);
    }
    free(l->f);
    free(l->name);
    memset(l, 0, sizeof *l);
}

/* Are the spans of columns a and b (finite values, over all runs) within a
 * factor 4 of each other?  A phase portrait is then drawn with equal aspect
 * (a circle stays a circle); a rotating pendulum's q runs far and is not. */
static int comparable_spans(hl_runplot *const *runs, int nruns, int a, int b)
{
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    int col[2] = {a, b};
    for (int r = 0; r < nruns; r++)
        for (size_t i = 0; i < runs[r]->nrows; i++)
            for (int k = 0; k < 2; k++) {
                double v = runs[r]->v[i * (size_t)runs[r]->ncols + (size_t)col[k]];
                if (isfinite(v)) {
                    lo[k] = fmin(lo[k], v);
                    hi[k] = fmax(hi[k], v);
                }
            }
    double sa = hi[0] - lo[0], sb = hi[1] - lo[1];
    return sa > 0 && sb > 0 && isfinite(sa) && isfinite(sb) && sa <= 4 * sb && sb <= 4 * sa;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* A y range that leaves out poles.  With w the range of the middle 90% of
 * the finite values of column c (all runs; the 5th to the 95th percentile)
 * and [lo, hi] that range widened by w/2 on each side, clip to [lo, hi]
 * when the values spread over more than 5 w and some run leaves [lo, hi]
 * and comes back: a spike, as x/p near p = 0 (up to 1e16; the curve is
 * then drawn with breaks at the poles, plot.h).  A run that grows out of
 * the range and stays out (a blow-up, e^(2t)) is not clipped.  0 if no
 * clipping is needed. */
static int robust_range(double *lo, double *hi, hl_runplot *const *runs, int nruns, int c)
{
    size_t n = 0, cap = 0;
    for (int r = 0; r < nruns; r++)
        cap += runs[r]->nrows;
    double *v = hl_xmalloc((cap + 1) * sizeof *v);
    for (int r = 0; r < nruns; r++)
        for (size_t i = 0; i < runs[r]->nrows; i++) {
            double y = runs[r]->v[i * (size_t)runs[r]->ncols + (size_t)c];
            if (isfinite(y))
                v[n++] = y;
        }
    int clip = 0;
    if (n >= 50) {
        qsort(v, n, sizeof *v, cmp_double);
        double q0 = v[(size_t)(0.05 * (double)(n - 1))], q1 = v[(size_t)(0.95 * (double)(n - 1))];
        double w = q1 - q0;
        *lo = q0 - 0.5 * w;
        *hi = q1 + 0.5 * w;
        if (w > 0 && v[n - 1] - v[0] > 5 * w)
            for (int r = 0; r < nruns && !clip; r++) {
                int out = 0;
                for (size_t i = 0; i < runs[r]->nrows && !clip; i++) {
                    double y = runs[r]->v[i * (size_t)runs[r]->ncols + (size_t)c];
                    if (isnan(y))
                        continue;
                    if (!(y >= *lo && y <= *hi))
                        out = 1;
                    else if (out)
                        clip = 1;
                }
            }
    }
    free(v);
    return clip;
}

/* The legend's corner: the one whose box covers the fewest points.  The box
 * is taken as 45% of the plot's width and 5% + 6% per run of its height
 * (about what plot.h draws at the default size), in fractions of the data's
 * range (of the clipped range, of log10 y on a log axis). */
static hl_legend_pos legend_corner(hl_runplot *const *runs, int nruns, fig_spec sp, int ylog,
                                   const double *clip)
{
    double x0 = INFINITY, x1 = -INFINITY, y0 = INFINITY, y1 = -INFINITY;
    long count[4] = {0, 0, 0, 0};
    for (int pass = 0; pass < 2; pass++) {
        if (pass == 1) {
            if (clip != NULL)
                y0 = clip[0], y1 = clip[1];
            if (!(x1 > x0 && y1 > y0))
                return HL_LEGEND_TOP_RIGHT;
        }
        double lw = 0.45, lh = 0.05 + 0.06 * nruns;
        for (int r = 0; r < nruns; r++) {
            const hl_runplot *rp = runs[r];
            size_t nc = (size_t)rp->ncols;
            for (size_t i = 0; i < rp->nrows; i++) {
                double x = rp->v[i * nc + (size_t)sp.ix];
                double y = sp.kind == Y_DH ? rp->dH[i] : rp->v[i * nc + (size_t)sp.iy];
                if (ylog)
                    y = y > 0 ? log10(y) : NAN;
                if (!isfinite(x) || !isfinite(y) ||
                    (clip != NULL && !(y >= clip[0] && y <= clip[1])))
                    continue;
                if (pass == 0) {
                    x0 = fmin(x0, x), x1 = fmax(x1, x), y0 = fmin(y0, y), y1 = fmax(y1, y);
                    continue;
                }
                double fx = (x - x0) / (x1 - x0), fy = (y - y0) / (y1 - y0);
                int top = fy > 1 - lh, bottom = fy < lh, right = fx > 1 - lw, left = fx < lw;
                count[HL_LEGEND_TOP_RIGHT] += top && right;
                count[HL_LEGEND_TOP_LEFT] += top && left;
                count[HL_LEGEND_BOTTOM_RIGHT] += bottom && right;
                count[HL_LEGEND_BOTTOM_LEFT] += bottom && left;
            }
        }
    }
    int best = 0;
    for (int k = 1; k < 4; k++)
        if (count[k] < count[best])
            best = k;
    return (hl_legend_pos)best;
}

/* One figure: title, labels, the runs, the axis. */
static hl_status one(fig_list *l, hl_runplot *const *runs, int nruns, fig_spec sp,
                     const char *title, const char *xl, const char *yl, char *name,
                     hl_error *err)
{
    char *t = pl_text(title), *x = pl_text(xl), *y = pl_text(yl);
    hl_figure *f = hl_figure_new(t, x, y);
    free(t), free(x), free(y);
    int any_pos = 0;
    hl_status st = add_runs(f, runs, nruns, sp, &any_pos, err);
    if (st != HL_OK) {
        hl_figure_free(f);
        free(name);
        return st;
    }
    if (sp.log)
        hl_figure_set_yscale(f, any_pos ? HL_AXIS_LOG : HL_AXIS_LINEAR);
    if (sp.phase && comparable_spans(runs, nruns, sp.ix, sp.iy))
        hl_figure_set_equal_aspect(f, 1);
    double clip[2];
    int clipped = !sp.log && !sp.phase && sp.kind == Y_COL &&
                  robust_range(&clip[0], &clip[1], runs, nruns, sp.iy);
    if (clipped)
        st = hl_figure_set_yclip(f, clip[0], clip[1], err);
    if (st != HL_OK) {
        hl_figure_free(f);
        free(name);
        return st;
    }
    hl_figure_set_legend(f, nruns > 1 ? legend_corner(runs, nruns, sp, sp.log && any_pos,
                                                      clipped ? clip : NULL)
                                      : HL_LEGEND_NONE);
    push(l, f, name);
    return HL_OK;
}

static char *fname(const char *prefix, const char *a, const char *b)
{
    hl_buf s;
    hl_buf_init(&s);
    hl_buf_puts(&s, prefix);
    if (a != NULL) {
        hl_buf_putc(&s, '-');
        file_part(&s, a);
    }
    if (b != NULL) {
        hl_buf_putc(&s, '-');
        file_part(&s, b);
    }
    return hl_buf_take(&s);
}

/* The runs' names in a title: "euler" or "3 runs". */
static void who(char *out, size_t n, hl_runplot *const *runs, int nruns)
{
    if (nruns == 1)
        snprintf(out, n, "%s", runs[0]->label);
    else
        snprintf(out, n, "%d runs", nruns);
}

static hl_status check_runs(roles *ro, hl_runplot *const *runs, int nruns, hl_error *err)
{
    if (runs == NULL || nruns < 1)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no run to plot");
    for (int r = 0; r < nruns; r++)
        if (runs[r] == NULL || runs[r]->nrows == 0)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "run %d has no rows", r + 1);
    hl_status st = find_roles(ro, runs[0], err);
    if (st != HL_OK)
        return st;
    for (int r = 1; r < nruns; r++) {
        const hl_runplot *a = runs[0], *b = runs[r];
        /* the same variables and H; sigma and the observers may differ only
         * if they are absent: compare the whole header */
        int same = a->ncols == b->ncols;
        for (int j = 0; same && j < a->ncols; j++)
            same = strcmp(a->names[j], b->names[j]) == 0;
        if (!same)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "runs '%s' and '%s' have different columns: runs compared on "
                                "one figure need the same system, observers and sigma",
                                a->label, b->label);
    }
    return HL_OK;
}

hl_status hl_runplot_figures(hl_figure ***figs, char ***names, int *nfig,
                             hl_runplot *const *runs, int nruns, const hl_runplot_opts *opts,
                             hl_error *err)
{
    *figs = NULL;
    *names = NULL;
    *nfig = 0;
    roles ro = {0};
    hl_status st = check_runs(&ro, runs, nruns, err);
    if (st != HL_OK)
        return st;
    const hl_runplot *r0 = runs[0];
    int N = ro.n2 / 2;
    fig_list l = {NULL, NULL, 0};
    char w[200], title[600];
    who(w, sizeof w, runs, nruns);

    /* phase portraits */
    const char *ph = opts != NULL ? opts->phase : NULL;
    if (ph != NULL) {
        const char *c = strchr(ph, ':');
        int a = c != NULL ? col_index(r0, ph, (size_t)(c - ph)) : -1;
        int b = c != NULL ? col_index(r0, c + 1, strlen(c + 1)) : -1;
        if (c == NULL || a < 0 || b < 0) {
            hl_buf cols;
            hl_buf_init(&cols);
            for (int j = 0; j < r0->ncols; j++)
                hl_buf_printf(&cols, "%s%s", j ? ", " : "", r0->names[j]);
            st = hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                              c == NULL ? "--phase wants two columns 'a:b', not '%s' (columns: %s)"
                                        : "--phase '%s': no such column (columns: %s)",
                              ph, cols.s);
            hl_buf_clear(&cols);
            return st;
        }
        snprintf(title, sizeof title, "%s: projection (%s, %s)", w, r0->names[a], r0->names[b]);
        st = one(&l, runs, nruns, (fig_spec){a, b, Y_COL, 0, 1}, title, r0->names[a],
                 r0->names[b], fname("phase", r0->names[a], r0->names[b]), err);
    } else
        for (int j = 0; j < N && st == HL_OK; j++) {
            int a = 1 + j, b = 1 + N + j;
            snprintf(title, sizeof title, "%s: phase portrait (%s, %s)", w, r0->names[a],
                     r0->names[b]);
            st = one(&l, runs, nruns, (fig_spec){a, b, Y_COL, 0, 1}, title, r0->names[a],
                     r0->names[b], fname("phase", r0->names[a], r0->names[b]), err);
        }
    /* coordinates in time */
    for (int j = 1; j <= ro.n2 && st == HL_OK; j++) {
        snprintf(title, sizeof title, "%s: %s in time", w, r0->names[j]);
        st = one(&l, runs, nruns, (fig_spec){0, j, Y_COL, 0, 0}, title, "t", r0->names[j],
                 fname("time", r0->names[j], NULL), err);
    }
    /* the energy error */
    if (st == HL_OK) {
        snprintf(title, sizeof title, "%s: energy error |H - H0|", w);
        st = one(&l, runs, nruns, (fig_spec){0, ro.iH, Y_DH, 1, 0}, title, "t", "|H - H0|",
                 fname("energy-error", NULL, NULL), err);
    }
    /* sigma against the reference */
    if (st == HL_OK && ro.isigma >= 0) {
        /* the title has PLplot escapes: set after one(), which escapes '#' */
        char *we = pl_text(w);
        snprintf(title, sizeof title, "%s: #gs = |z#dn#u - z(t#dn#u)|#u2#d against the reference",
                 we);
        free(we);
        st = one(&l, runs, nruns, (fig_spec){0, ro.isigma, Y_COL, 1, 0}, "", "t", "sigma",
                 fname("sigma", NULL, NULL), err);
        if (st == HL_OK) {
            hl_figure_set_title(l.f[l.n - 1], title);
            hl_figure_set_labels(l.f[l.n - 1], "t", "#gs");
        }
    }
    /* observers */
    for (int j = ro.obs0, k = 1; j < r0->ncols && st == HL_OK; j++, k++) {
        char num[32];
        snprintf(num, sizeof num, "observer-%d", k);
        snprintf(title, sizeof title, "%s: %s in time", w, r0->names[j]);
        st = one(&l, runs, nruns, (fig_spec){0, j, Y_COL, 0, 0}, title, "t", r0->names[j],
                 fname(num, r0->names[j], NULL), err);
    }
    for (int i = 0; i < l.n && st == HL_OK && opts != NULL && (opts->width || opts->height); i++)
        st = hl_figure_set_size(l.f[i], opts->width, opts->height, err);
    if (st != HL_OK) {
        list_clear(&l);
        return st;
    }
    *figs = l.f;
    *names = l.name;
    *nfig = l.n;
    return HL_OK;
}

void hl_runplot_figures_free(hl_figure **figs, char **names, int nfig)
{
    fig_list l = {figs, names, nfig};
    list_clear(&l);
}

/* ---- writing ------------------------------------------------------------- */

hl_status hl_runplot_write(hl_runplot *const *runs, int nruns, const char *dir,
                           const hl_runplot_opts *opts, int *written, hl_error *err)
{
    if (written != NULL)
        *written = 0;
    const char *formats = opts != NULL && opts->formats != NULL ? opts->formats : "png";
    int nfmt;
    hl_status st = hl_figure_count_formats(&nfmt, formats, err);
    if (st != HL_OK)
        return st;
    if (dir == NULL || *dir == '\0')
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no output directory given");
    hl_figure **figs;
    char **names;
    int nfig;
    if ((st = hl_runplot_figures(&figs, &names, &nfig, runs, nruns, opts, err)) != HL_OK)
        return st;
    if ((st = hl_figure_drawable(err)) != HL_OK || (st = hl_figure_mkdir(dir, err)) != HL_OK) {
        hl_runplot_figures_free(figs, names, nfig);
        return st;
    }
    hl_buf path;
    hl_buf_init(&path);
    for (int i = 0; i < nfig && st == HL_OK; i++) {
        path.len = 0;
        hl_buf_printf(&path, "%s/%s", dir, names[i]);
        st = hl_figure_write(figs[i], path.s, formats, err);
        if (st == HL_OK && written != NULL)
            *written += nfmt;
    }
    hl_buf_clear(&path);
    hl_runplot_figures_free(figs, names, nfig);
    return st;
}
