/* The paper's formulas (paper.h): what formulas.c (the rows and the
 * table), work.c (the computations the rows share) and relations.c (the
 * relations between K and the v_k) share.  Internal to src/paper. */
#ifndef HAMLIE_PAPER_FORMULAS_IMPL_H
#define HAMLIE_PAPER_FORMULAS_IMPL_H

#include <flint/fmpq.h>

#include "base/buf.h"
#include "hamlie/analysis.h"
#include "hamlie/ham.h"
#include "hamlie/paper.h"
#include "hamlie/report.h"
#include "hamlie/scheme.h"
#include "hamlie/series.h"

#define NV 8   /* v_2..v_8 on the oscillator */
#define NCUB 5 /* v_2..v_5 on the cubic system */
#define NREL 2 /* schemes on the cubic system the relations are checked on */

static const char *const REL_NAMES[NREL] = {"explicit Euler", "implicit midpoint"};
static const char *const NAMES[2] = {"x", "p"};

/* A scheme and its analysis (which borrows it). */
typedef struct analysed {
    hl_scheme *s;
    hl_analysis *a;
} analysed;

struct hl_paper_work {
    hl_system *osc, *lin2, *cub;
    hl_alg *g;                              /* generator, osc */
    hl_alg *exact_map, *euler_map, *dg_map; /* closed maps, osc */
    /* the library's analysis of each scheme (hl_analysis_compute): psi, the
     * v_k two ways, K's series (cub), the leading field and tau (dg) */
    analysed exact, euler, dg, rel[NREL]; /* rel: on cub */
    hl_alg *g_cub;                        /* generator, cub */
    hl_alg *psiT_cub[NREL]; /* the cubic system's psi truncated after D^NCUB, as elements */
    char *euler_map_how, *dg_map_how;
};

typedef struct hl_paper_formula_row row_t;

/* ---- work.c ---- */
int paper_work_init(struct hl_paper_work *w, hl_error *err);
void paper_work_clear(struct hl_paper_work *w);
/* A scheme (a catalog name, else its text) analysed to v_n (HL_ANALYSIS_* parts). */
int paper_expand_catalog(analysed *out, const char *name, const char *text, unsigned parts,
                         hl_system *sys, int n, hl_error *err);
void paper_analysed_clear(analysed *x);
/* ncomp components "a; b" of a printed formula, read in sys. */
int paper_read_comps(hl_alg *out, int ncomp, hl_system *sys, const char *text, hl_error *err);
void paper_alg_D(hl_alg *r, hl_system *sys);        /* the step D */
void paper_alg_z(hl_alg *r, int i, hl_system *sys); /* x (i = 0) or p (i = 1) */
/* Does the closed map agree with the series psi to O(D^n)? (-1: could not
 * expand the map) */
int paper_map_matches_series(const hl_alg *map, const hl_series *psi, int n, hl_system *sys);
char *paper_strf(const char *fmt, const char *a); /* fmt with one %s, malloc'd */
const char *paper_agree_text(const hl_vfields *e);

/* ---- relations.c: the printed relations between K and the v_k ---- */
int paper_f_rel(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how, hl_error *err);
/* The printed right side evaluated for test scheme sch, term flip (-1:
 * none) with the opposite sign; *nterms its number of terms. */
int paper_eval_rel(hl_alg *out, int *nterms, struct hl_paper_work *w, int sch, const char *text,
                   int flip, hl_error *err);
int paper_rel_holds(struct hl_paper_work *w, const char *text, int flip, int k, int from);
int paper_rel_sign_fix(struct hl_paper_work *w, const char *text, int k, int nterms);
char *paper_rel_flipped(const char *text, int j);
char *paper_rel_term(const char *text, int j);

#endif
