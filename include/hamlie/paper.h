/* hamlie — the paper's study, regenerated and checked (`hamlie reproduce`).
 *
 * Two halves that share nothing but this header:
 *   figures.c  the 14 figures of the paper (oscillator, x(0) = 1, p(0) = 0,
 *              D = 0.1, t in [0, 20]), their data checked against closed forms;
 *   formulas.c the paper's printed formulas, each recomputed and given a
 *              computed verdict ("agrees" / "differs");
 * and report.c, which writes the Markdown page and the LaTeX fragment.
 */
#ifndef HAMLIE_PAPER_H
#define HAMLIE_PAPER_H

#include "hamlie/error.h"
#include "hamlie/plot.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- figures ------------------------------------------------------------ */

#define HL_PAPER_NFIGURES 14

typedef struct hl_paper_figure {
    const char *name;    /* file base name, e.g. "euler-phase" */
    const char *caption; /* what the paper's figure shows */
    double check;        /* the closed-form check of its data: max deviation */
    double check_tol;    /* ... and the tolerance it must be under */
    const char *check_what; /* e.g. "2H_n = (1+D^2)^n" */
} hl_paper_figure;

/* Compute the data of the 14 figures, check each against its closed form,
 * and (when dir is not NULL) write dir/<name>.<fmt> for each format (dir is
 * created if missing).  figs gets HL_PAPER_NFIGURES entries (static
 * strings), in the paper's order: exact-{phase,x,p,error},
 * euler-{phase,x,p,inv,error}, disgra-{phase,x,p,inv,error}.
 *
 * The data is computed: the catalog schemes "exact-rotation", "paper-euler"
 * and "paper-dg" run through run.h (hl_run_fixed, observers x/p and H) on
 * H = (p^2 + x^2)/2.  The exact solution (cos t, -sin t) is the red line
 * (2001 samples), the scheme the blue dots (201 points t = nD).  Errors are
 * the paper's squared distances sigma(x,p), sigma(x/p), sigma(2H) on a log
 * axis; x/p is drawn in [-10, 10] with no line through its poles (p = 0).
 * A figure's check is the largest deviation of its data from the scheme's
 * closed form (Euler: 2H_n = (1+D^2)^n, z_n = (1+D^2)^(n/2) R(n atan D) z_0;
 * discrete gradient: the rotation by 2 atan(D/2) per step; exact scheme: the
 * flow, error at round-off); check <= check_tol is the verdict.
 * formats: "png,svg,pdf" or a subset (plot.h); NULL is "png".  HL_EINVAL
 * on a bad format list (before anything is written), HL_EIO on a file or a
 * directory that cannot be written, the run's error if a scheme fails. */
hl_status hl_paper_figures(hl_paper_figure *figs, const char *dir, const char *formats,
                           hl_error *err);

/* Figure i (0 .. HL_PAPER_NFIGURES-1, the order above) as an hl_figure, for
 * rendering or writing by the caller (hl_figure_free it); info (may be NULL)
 * is filled as by hl_paper_figures.  HL_EINVAL for i out of range. */
hl_status hl_paper_figure_get(hl_figure **fig, hl_paper_figure *info, int i, hl_error *err);

/* ---- formulas ----------------------------------------------------------- */

typedef enum hl_verdict { HL_VERDICT_AGREES = 0, HL_VERDICT_DIFFERS } hl_verdict;

typedef struct hl_paper_formula {
    const char *id;        /* e.g. "euler-v3" */
    const char *what;      /* "Euler: the error field v_3" */
    const char *paper_eq;  /* where in the paper (equation label or section) */
    char *printed;         /* the paper's print as transcribed (hamlie's syntax,
                              decorated by kind: "X = ..., P = ...") */
    char *printed_latex;   /* the print as read (canonical form), in LaTeX */
    char *computed;        /* hamlie's result, as text: where the verdict is
                              "differs", the correct expression */
    char *computed_latex;
    hl_verdict verdict;    /* computed: printed - computed == 0, decided exactly */
    char *how;             /* how it was checked (two computations, closed form);
                              a cross-check that failed says DIFFERS, DISAGREE,
                              FAILED or ": NO" in capitals */
} hl_paper_formula;

typedef struct hl_paper_formulas {
    int n;
    hl_paper_formula *f;
} hl_paper_formulas;

/* Recompute every formula and compare it with the print: the table
 * below (hl_paper_formula_rows) evaluated row by row.  out is filled in the
 * table's order; the verdict is printed - computed == 0 in hamlie's exact
 * algebra (alg.h), component by component. */
hl_status hl_paper_formulas_compute(hl_paper_formulas *out, hl_error *err);
void hl_paper_formulas_clear(hl_paper_formulas *fs);

/* The table as data, so that a caller (a test) can copy it, change a
 * printed entry and recompute.  printed is hamlie's formula syntax in the
 * oscillator's symbols x, p, D: a scalar, or the two components "a; b" of
 * a vector field a d/dx + b d/dp, of a map (X = a, P = b) or of the
 * discrete equations ((X-x)/D = a, (P-p)/D = b).  For the relations
 * between K and the v_k (kind HL_PAPER_REL) it is the printed right side as
 * terms "+1 v3 -2 g.v2 +1 v2.g" (coefficient, then a word of operators
 * composed right to left; v2.v2 is the paper's v_2^2). */
typedef enum hl_paper_kind {
    HL_PAPER_SCALAR = 0,
    HL_PAPER_FIELD,
    HL_PAPER_MAP,
    HL_PAPER_EQS,
    HL_PAPER_REL
} hl_paper_kind;

struct hl_alg;
struct hl_paper_work; /* formulas.c's computations, shared by the rows */

typedef struct hl_paper_formula_row {
    const char *id, *what, *paper_eq;
    hl_paper_kind kind;
    const char *printed;
    /* hamlie's value (1 or 2 components, in the oscillator's context, or
     * for HL_PAPER_REL the left side on the rows' test system) and how it
     * was checked; internal to formulas.c. */
    int (*compute)(struct hl_paper_work *w, const struct hl_paper_formula_row *row,
                   struct hl_alg *out, char **how, hl_error *err);
    int arg; /* the order k of a relation, or the k of v_k */
} hl_paper_formula_row;

/* The built-in table (*n rows; static storage). */
const hl_paper_formula_row *hl_paper_formula_rows(int *n);

/* The same as hl_paper_formulas_compute on any table (rows from
 * hl_paper_formula_rows, possibly with printed entries changed).  HL_EPARSE
 * when a printed entry does not read. */
hl_status hl_paper_formulas_compute_rows(hl_paper_formulas *out,
                                         const hl_paper_formula_row *rows, int n,
                                         hl_error *err);

/* ---- the report ---------------------------------------------------------- */

/* dir/report.md and dir/report.tex (a fragment to \input): the formula table
 * and the figures (figs may be NULL: no figure section), each figure with its
 * closed-form check; Markdown shows the png (else the first format), LaTeX
 * includes the pdf (else the first format).  dir is created if missing (with
 * its parents).  Each file is written to a temporary name in dir and renamed.
 * HL_EIO when dir or a file cannot be written; HL_EINVAL for dir or fs NULL. */
hl_status hl_paper_report_write(const char *dir, const hl_paper_formulas *fs,
                                const hl_paper_figure *figs, const char *formats,
                                hl_error *err);

#ifdef __cplusplus
}
#endif

#endif
