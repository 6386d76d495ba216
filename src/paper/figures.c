/* The paper's 14 figures (§4): the oscillator H = (p^2 + x^2)/2 from
 * x(0) = 1, p(0) = 0 with D = 0.1 to t = 20, run with three catalog schemes
 * through run.h (the same stepper `hamlie run` uses), drawn with plot.h.
 *
 * Nothing here is written in: the trajectories come from the schemes, and
 * each figure's data is then compared with the scheme's closed form,
 *   exact-rotation  z_n = R(n D) z_0                     (the flow itself)
 *   paper-euler     z_n = (1+D^2)^(n/2) R(n atan D) z_0, so 2H_n = (1+D^2)^n
 *   paper-dg        z_n = R(n 2 atan(D/2)) z_0           (2H_n = 1)
 * where R(a) is the clockwise rotation (x, p) -> (x cos a + p sin a,
 * p cos a - x sin a), the exact flow over a time a.  The paper's errors are
 * squared distances at t = n D (§4.2):
 *   sigma(x,p) = (x(t) - x_n)^2 + (p(t) - p_n)^2,
 *   sigma(x/p) = (x(t)/p(t) - x_n/p_n)^2,
 *   sigma(2H)  = (p(t)^2 + x(t)^2 - p_n^2 - x_n^2)^2,
 * with x(t) = cos t, p(t) = -sin t. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>

#include "base/buf.h"
#include "hamlie/paper.h"
#include "hamlie/plot.h"
#include "hamlie/run.h"
#include "hamlie/scheme.h"

#define FIG_D 0.1
#define FIG_T 20.0
#define FIG_NS 201  /* scheme points t = n D, n = 0..200 */
#define FIG_NC 2001 /* samples of the exact curve, every 0.01 */
#define FIG_INV_CLIP 10.0 /* x/p is drawn in [-10, 10]: it has poles */

enum { S_EXACT, S_EULER, S_DG, S_COUNT };
enum { K_PHASE, K_X, K_P, K_INV, K_ERR };

static const struct {
    const char *catalog;  /* scheme name in scheme.h's catalog */
    const char *label;    /* in titles and legends */
    const char *observer; /* the invariant of the INV figure, or NULL */
} schemes[S_COUNT] = {
    {"exact-rotation", "exact scheme", NULL},
    {"paper-euler", "Euler", "x/p"},
    {"paper-dg", "discrete gradient", "H"},
};

static const struct {
    const char *name;
    int scheme, kind;
    const char *caption;
} table[HL_PAPER_NFIGURES] = {
    {"exact-phase", S_EXACT, K_PHASE, "Exact scheme: the trajectory in phase space (Exact-phase)"},
    {"exact-x", S_EXACT, K_X, "Exact scheme: x in time (Exact-x)"},
    {"exact-p", S_EXACT, K_P, "Exact scheme: p in time (Exact-p)"},
    {"exact-error", S_EXACT, K_ERR,
     "Exact scheme: the error sigma(x,p) in time, at round-off (Exact-error)"},
    {"euler-phase", S_EULER, K_PHASE, "Euler: the trajectory in phase space (Euler-phase)"},
    {"euler-x", S_EULER, K_X, "Euler: x in time (Euler-x)"},
    {"euler-p", S_EULER, K_P, "Euler: p in time (Euler-p)"},
    {"euler-inv", S_EULER, K_INV,
     "Euler: the invariant x/p of v_2 in time, poles at p = 0 (Euler-inv)"},
    {"euler-error", S_EULER, K_ERR,
     "Euler: the errors sigma(x,p) (black) and sigma(x/p) (green) in time (Euler-error)"},
    {"disgra-phase", S_DG, K_PHASE,
     "Discrete gradient: the trajectory in phase space (DisGra-phase)"},
    {"disgra-x", S_DG, K_X, "Discrete gradient: x in time (DisGra-x)"},
    {"disgra-p", S_DG, K_P, "Discrete gradient: p in time (DisGra-p)"},
    {"disgra-inv", S_DG, K_INV, "Discrete gradient: H in time (DisGra-inv)"},
    {"disgra-error", S_DG, K_ERR,
     "Discrete gradient: the errors sigma(x,p) (black) and sigma(2H) (green) in time; "
     "sigma(2H) is at round-off, and exactly 0 (no point on the log axis) at some steps "
     "(DisGra-error)"},
};

/* One scheme's run: rows t = n D. */
typedef struct traj {
    double t[FIG_NS], x[FIG_NS], p[FIG_NS], obs[FIG_NS];
    long rows;
    int nobs;
} traj;

static int keep_row(const hl_run_row *row, void *arg)
{
    traj *tr = arg;
    if (tr->rows >= FIG_NS)
        return HL_ELIMIT; /* cannot happen: 200 steps, every row */
    tr->t[tr->rows] = row->t;
    tr->x[tr->rows] = row->z[0];
    tr->p[tr->rows] = row->z[1];
    tr->obs[tr->rows] = tr->nobs > 0 ? row->obs[0] : NAN;
    tr->rows++;
    return 0;
}

/* Run scheme k on the oscillator (the reference is not needed: the exact
 * solution is cos t, -sin t). */
static hl_status run_scheme(traj *tr, int k, hl_error *err)
{
    hl_system *sys = NULL;
    hl_scheme *sc = NULL;
    hl_run *r = NULL;
    hl_system_spec spec = {"(p^2 + x^2)/2", "x:p", NULL, NULL, NULL};
    double z0[2];
    memset(tr, 0, sizeof *tr);
    int st = hl_system_new(&sys, &spec, err);
    if (st == HL_OK)
        st = hl_scheme_new(&sc, schemes[k].catalog, 0, sys, err);
    if (st == HL_OK)
        st = hl_run_new(&r, sys, sc, err);
    if (st == HL_OK && schemes[k].observer != NULL)
        st = hl_run_observe(r, schemes[k].observer, err);
    if (st == HL_OK)
        st = hl_run_init_values(z0, sys, "x=1,p=0", err);
    if (st == HL_OK) {
        hl_run_set_reference(r, 0, 1e-15);
        tr->nobs = hl_run_nobservers(r);
        st = hl_run_fixed(r, z0, FIG_D, FIG_T, 1, keep_row, tr, NULL, err);
    }
    if (st == HL_OK && tr->rows != FIG_NS)
        st = hl_error_set(err, HL_EINVAL, NULL, -1, 0, "%s: %ld rows instead of %d",
                          schemes[k].catalog, tr->rows, FIG_NS);
    if (st != HL_OK)
        hl_error_prefix(err, "the paper's figures (%s)", schemes[k].catalog);
    hl_run_free(r);
    hl_scheme_free(sc);
    hl_system_free(sys);
    return (hl_status)st;
}

/* ---- closed forms --------------------------------------------------------- */

/* The scheme's own closed form at step n: radius and angle of z_n. */
static void closed_form(double *x, double *p, int k, int n)
{
    double r = 1, a = n * FIG_D;
    if (k == S_EULER) {
        r = pow(1 + FIG_D * FIG_D, 0.5 * n);
        a = n * atan(FIG_D);
    } else if (k == S_DG)
        a = n * 2 * atan(FIG_D / 2);
    *x = r * cos(a);
    *p = -r * sin(a);
}

static double sq(double v) { return v * v; }

/* sigma(x,p) of the data at step n against the exact solution. */
static double sigma_xp(const traj *tr, int n)
{
    return sq(cos(tr->t[n]) - tr->x[n]) + sq(-sin(tr->t[n]) - tr->p[n]);
}

/* The closed form of sigma(x,p) at step n: |r e^{-ia} - e^{-it}|^2
 * = r^2 + 1 - 2 r cos(a - t), written with a sine so that it keeps its
 * relative accuracy when a is close to t: (r - 1)^2 + 4 r sin^2((a - t)/2). */
static double sigma_xp_closed(int k, int n)
{
    double r = 1, a = n * FIG_D;
    if (k == S_EULER) {
        r = pow(1 + FIG_D * FIG_D, 0.5 * n);
        a = n * atan(FIG_D);
    } else if (k == S_DG)
        a = n * 2 * atan(FIG_D / 2);
    return sq(r - 1) + 4 * r * sq(sin(0.5 * (a - n * FIG_D)));
}

/* Deviation of the trajectory from the closed form, relative to its radius;
 * for Euler also the relative deviation of 2H_n from (1+D^2)^n. */
static double check_traj(const traj *tr, int k)
{
    double dev = 0;
    for (int n = 0; n < FIG_NS; n++) {
        double xc, pc;
        closed_form(&xc, &pc, k, n);
        double r = hypot(xc, pc);
        dev = fmax(dev, hypot(tr->x[n] - xc, tr->p[n] - pc) / r);
        if (k == S_EULER) {
            double h2 = pow(1 + FIG_D * FIG_D, n);
            dev = fmax(dev, fabs(sq(tr->x[n]) + sq(tr->p[n]) - h2) / h2);
        }
    }
    return dev;
}

/* Euler's x/p (the observer) against -cot(n atan D), relative to the size
 * of the value; the DG's H (the observer) against 1/2. */
static double check_inv(const traj *tr, int k)
{
    double dev = 0;
    for (int n = 1; n < FIG_NS; n++) {
        if (k == S_EULER) {
            double a = n * atan(FIG_D), c = -cos(a) / sin(a);
            dev = fmax(dev, fabs(tr->obs[n] - c) / fmax(1, fabs(c)));
        } else
            dev = fmax(dev, fabs(tr->obs[n] - 0.5));
    }
    return dev;
}

/* The error figures: sigma(x,p) against its closed form (relative, above a
 * floor of 1e-24 for sigma = 0 at n = 0); for Euler also sigma(x/p) through
 * its square root cot(n D) - cot(n atan D) (relative to |cot| + |cot|: the
 * size of the terms cancelling); for the DG sigma(2H) (closed form 0) by its
 * square root.  For the exact scheme: the distance sqrt(sigma), round-off. */
static double check_err(const traj *tr, int k)
{
    double dev = 0;
    for (int n = 0; n < FIG_NS; n++) {
        double s = sigma_xp(tr, n);
        if (k == S_EXACT) {
            dev = fmax(dev, sqrt(s));
            continue;
        }
        double sc = sigma_xp_closed(k, n);
        dev = fmax(dev, fabs(s - sc) / fmax(sc, 1e-24));
        if (k == S_EULER && n > 0) {
            double t = n * FIG_D, a = n * atan(FIG_D);
            double d = tr->x[n] / tr->p[n] - cos(t) / -sin(t);
            double dc = cos(a) / -sin(a) - cos(t) / -sin(t);
            double scale = fabs(cos(a) / sin(a)) + fabs(cos(t) / sin(t));
            dev = fmax(dev, fabs(fabs(d) - fabs(dc)) / scale);
        } else if (k == S_DG)
            dev = fmax(dev, fabs(1 - sq(tr->x[n]) - sq(tr->p[n])));
    }
    return dev;
}

static void fill_check(hl_paper_figure *info, const traj *tr, int i)
{
    int k = table[i].scheme;
    switch (table[i].kind) {
    case K_INV:
        info->check = check_inv(tr, k);
        info->check_tol = k == S_EULER ? 1e-10 : 1e-14;
        info->check_what = k == S_EULER ? "x_n/p_n = -cot(n atan D) (relative)"
                                        : "H_n = 1/2 (absolute)";
        break;
    case K_ERR:
        info->check = check_err(tr, k);
        info->check_tol = k == S_EXACT ? 1e-12 : 1e-10;
        info->check_what =
            k == S_EXACT ? "sqrt(sigma(x,p)) at round-off"
            : k == S_EULER
                ? "sigma(x,p) = (r_n-1)^2 + 4 r_n sin^2(n(atan D - D)/2), r_n = (1+D^2)^(n/2); "
                  "sigma(x/p) = (cot nD - cot(n atan D))^2 (relative)"
                : "sigma(x,p) = 4 sin^2(n(2 atan(D/2) - D)/2) (relative); sigma(2H) = 0";
        break;
    default:
        info->check = check_traj(tr, k);
        info->check_tol = 1e-12;
        info->check_what = k == S_EXACT ? "z_n = R(nD) z_0 (the flow; relative)"
                           : k == S_EULER
                               ? "2H_n = (1+D^2)^n and z_n = (1+D^2)^(n/2) R(n atan D) z_0 "
                                 "(relative)"
                               : "z_n = R(n 2 atan(D/2)) z_0 (relative)";
    }
}

/* ---- drawing ---------------------------------------------------------------- */

/* The exact solution, sampled finely. */
typedef struct curve {
    double t[FIG_NC], x[FIG_NC], p[FIG_NC], v[FIG_NC];
} curve;

static void exact_curve(curve *c)
{
    for (int i = 0; i < FIG_NC; i++) {
        c->t[i] = FIG_T * i / (FIG_NC - 1);
        c->x[i] = cos(c->t[i]);
        c->p[i] = -sin(c->t[i]);
    }
}

/* Exact red line, scheme blue dots. */
static hl_status pair(hl_figure *f, const double *xe, const double *ye, const double *xn,
                      const double *yn, const char *label, hl_error *err)
{
    hl_status st =
        hl_figure_add(f, FIG_NC, xe, ye, HL_DRAW_LINE, HL_COLOR_RED, "exact solution", err);
    return st != HL_OK ? st
                       : hl_figure_add(f, FIG_NS, xn, yn, HL_DRAW_DOTS, HL_COLOR_BLUE, label, err);
}

static hl_status build(hl_figure **out, const traj *tr, int i, hl_error *err)
{
    int k = table[i].scheme;
    const char *lab = schemes[k].label;
    char title[160];
    curve *c = hl_xmalloc(sizeof *c);
    exact_curve(c);
    hl_figure *f = hl_figure_new(NULL, "t", NULL);
    hl_status st = HL_OK;
    double a[FIG_NS], b[FIG_NS];
    switch (table[i].kind) {
    case K_PHASE:
        /* a legend inside the box would hide part of the orbit, which
         * passes near every corner: the title says which is which */
        snprintf(title, sizeof title, "%s: phase space, #gD = 0.1 (red: exact, blue: scheme)",
                 lab);
        hl_figure_set_labels(f, "x", "p");
        hl_figure_set_equal_aspect(f, 1);
        hl_figure_set_legend(f, HL_LEGEND_NONE);
        st = pair(f, c->x, c->p, tr->x, tr->p, lab, err);
        break;
    case K_X:
    case K_P: {
        int isx = table[i].kind == K_X;
        snprintf(title, sizeof title, "%s: %s(t), #gD = 0.1", lab, isx ? "x" : "p");
        hl_figure_set_labels(f, "t", isx ? "x" : "p");
        hl_figure_set_legend(f, HL_LEGEND_BOTTOM_LEFT);
        st = pair(f, c->t, isx ? c->x : c->p, tr->t, isx ? tr->x : tr->p, lab, err);
        break;
    }
    case K_INV:
        if (k == S_EULER) {
            snprintf(title, sizeof title, "%s: the invariant x/p in time", lab);
            hl_figure_set_labels(f, "t", "x/p");
            for (int j = 0; j < FIG_NC; j++)
                c->v[j] = c->x[j] / c->p[j];
            st = hl_figure_set_yclip(f, -FIG_INV_CLIP, FIG_INV_CLIP, err);
            hl_figure_set_legend(f, HL_LEGEND_BOTTOM_LEFT);
        } else {
            snprintf(title, sizeof title, "%s: H in time", lab);
            hl_figure_set_labels(f, "t", "H");
            for (int j = 0; j < FIG_NC; j++)
                c->v[j] = 0.5 * (c->x[j] * c->x[j] + c->p[j] * c->p[j]);
            hl_figure_set_legend(f, HL_LEGEND_BOTTOM_RIGHT);
        }
        if (st == HL_OK)
            st = pair(f, c->t, c->v, tr->t, tr->obs, lab, err);
        break;
    default: /* K_ERR */
        snprintf(title, sizeof title, "%s: %s", lab,
                 k == S_EXACT ? "the error #gs(x,p) in phase space (round-off)"
                              : "errors in time (log scale)");
        hl_figure_set_labels(f, "t", k == S_EXACT ? "#gs(x,p)" : "#gs");
        hl_figure_set_yscale(f, HL_AXIS_LOG);
        hl_figure_set_legend(f, HL_LEGEND_BOTTOM_RIGHT);
        for (int n = 0; n < FIG_NS; n++) {
            a[n] = sigma_xp(tr, n);
            if (k == S_EULER) /* n = 0: p = 0, not finite: a break */
                b[n] = sq(cos(tr->t[n]) / -sin(tr->t[n]) - tr->x[n] / tr->p[n]);
            else
                b[n] = sq(1 - tr->x[n] * tr->x[n] - tr->p[n] * tr->p[n]);
        }
        st = hl_figure_add(f, FIG_NS, tr->t, a, HL_DRAW_LINE, HL_COLOR_BLACK, "#gs(x,p)", err);
        if (st == HL_OK && k != S_EXACT)
            st = hl_figure_add(f, FIG_NS, tr->t, b, HL_DRAW_LINE, HL_COLOR_GREEN,
                     k == S_EULER ? "#gs(x/p)" : "#gs(2H)", err);
        if (k == S_EXACT)
            hl_figure_set_legend(f, HL_LEGEND_NONE); /* one curve: the label says it */
    }
    free(c);
    if (st != HL_OK) {
        hl_figure_free(f);
        *out = NULL;
        return st;
    }
    hl_figure_set_title(f, title);
    *out = f;
    return HL_OK;
}

/* ---- public ------------------------------------------------------------------ */

hl_status hl_paper_figure_get(hl_figure **fig, hl_paper_figure *info, int i, hl_error *err)
{
    *fig = NULL;
    if (i < 0 || i >= HL_PAPER_NFIGURES)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "no paper figure %d (they are numbered 0..%d)", i,
                            HL_PAPER_NFIGURES - 1);
    traj *tr = hl_xmalloc(sizeof *tr);
    hl_status st = run_scheme(tr, table[i].scheme, err);
    if (st == HL_OK) {
        if (info != NULL) {
            info->name = table[i].name;
            info->caption = table[i].caption;
            fill_check(info, tr, i);
        }
        st = build(fig, tr, i, err);
    }
    free(tr);
    return st;
}

hl_status hl_paper_figures(hl_paper_figure *figs, const char *dir, const char *formats,
                           hl_error *err)
{
    hl_status st = HL_OK;
    int nfmt;
    if (formats == NULL)
        formats = "png";
    if (dir != NULL &&
        ((st = hl_figure_count_formats(&nfmt, formats, err)) != HL_OK ||
         (st = hl_figure_drawable(err)) != HL_OK || (st = hl_figure_mkdir(dir, err)) != HL_OK))
        return st;
    traj *tr = hl_xmalloc(S_COUNT * sizeof *tr);
    for (int k = 0; k < S_COUNT && st == HL_OK; k++)
        st = run_scheme(&tr[k], k, err);
    hl_buf path;
    hl_buf_init(&path);
    for (int i = 0; i < HL_PAPER_NFIGURES && st == HL_OK; i++) {
        const traj *t = &tr[table[i].scheme];
        figs[i].name = table[i].name;
        figs[i].caption = table[i].caption;
        fill_check(&figs[i], t, i);
        if (dir == NULL)
            continue;
        hl_figure *f;
        if ((st = build(&f, t, i, err)) != HL_OK)
            break;
        path.len = 0;
        hl_buf_printf(&path, "%s/%s", dir, table[i].name);
        st = hl_figure_write(f, path.s, formats, err);
        hl_figure_free(f);
    }
    hl_buf_clear(&path);
    free(tr);
    return st;
}
