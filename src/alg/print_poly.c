/* Polynomials written straight to text, for large results (issue 17): the
 * bytes hl_expr_print(hl_alg_to_expr(a)) gives, without building the
 * expression DAG (interning every node) and walking it again to print.
 * A Lie series of Hénon–Heiles to order 12 is ~1,000 terms; through the
 * DAG its printing cost four times the series' own computation.
 *
 * Only what the DAG path does for a polynomial in the base symbols (print.c
 * rules 1, 2 and 4; rule 3 and factored denominators need a non-constant
 * denominator) is done here, in text and SymPy styles; anything else returns
 * 0 and the caller takes the DAG path.  src/report/test/t-print-direct.c
 * compares the two on random polynomials and series. */
#include <stdlib.h>
#include <string.h>

#include "alg/alg_internal.h"
#include "base/buf.h"

#define PULL_MAX_TERMS 64 /* print.c's: a common factor is tried on at most this many */

typedef struct pwriter {
    const fmpz_mpoly_ctx_struct *mc;
    int nbase, nused, step; /* nused: base symbols and the atoms made */
    const char *pow_op;     /* "^" or "**" */
    const char **names;     /* base symbols as the style prints them */
    ulong *exps;            /* the terms' exponents, nbase each */
    slong *order;           /* stored positions in printing order */
    fmpq_t q;               /* scratch */
} pwriter;

/* Decimal digits, without printf's cost (most numbers here are small). */
static void put_digits(hl_buf *b, ulong u, int minus)
{
    char digits[24], *end = digits + sizeof digits, *d = end;
    do
        *--d = (char)('0' + u % 10);
    while ((u /= 10) != 0);
    if (minus)
        *--d = '-';
    hl_buf_putn(b, d, (size_t)(end - d));
}

/* ---- term order (print.c rule 1) ---------------------------------------------- */

typedef struct okey {
    ulong step, deg;
    slong i;
} okey;

static int okey_cmp(const void *a, const void *b)
{
    const okey *x = a, *y = b;
    if (x->step != y->step)
        return x->step < y->step ? -1 : 1;
    if (x->deg != y->deg)
        return x->deg > y->deg ? -1 : 1;
    return (x->i > y->i) - (x->i < y->i);
}

/* Read p's exponents (0 if a term involves an atom: not for this writer)
 * and its printing order. */
static int read_terms(pwriter *w, const fmpz_mpoly_t p)
{
    slong n = p->length;
    w->exps = hl_xrealloc(w->exps, (size_t)(n * w->nbase + 1) * sizeof *w->exps);
    w->order = hl_xrealloc(w->order, (size_t)(n + 1) * sizeof *w->order);
    for (slong i = 0; i < n; i++) {
        for (int v = w->nbase; v < w->nused; v++)
            if (fmpz_mpoly_get_term_var_exp_ui(p, i, v, w->mc) != 0)
                return 0;
        for (int v = 0; v < w->nbase; v++)
            w->exps[i * w->nbase + v] = fmpz_mpoly_get_term_var_exp_ui(p, i, v, w->mc);
        w->order[i] = i;
    }
    if (w->step < 0 || n < 2)
        return 1;
    okey *k = hl_xmalloc((size_t)n * sizeof *k);
    for (slong i = 0; i < n; i++) {
        const ulong *e = w->exps + i * w->nbase;
        k[i].step = e[w->step];
        k[i].deg = 0;
        for (int v = 0; v < w->nbase; v++)
            if (v != w->step)
                k[i].deg += e[v];
        k[i].i = i;
    }
    qsort(k, (size_t)n, sizeof *k, okey_cmp);
    for (slong i = 0; i < n; i++)
        w->order[i] = k[i].i;
    free(k);
    return 1;
}

/* ---- terms and sums (print.c rules 2 and 4) ------------------------------------- */

/* The monomial with exponents e, the series symbol first: "D^2*x*y^3". */
static void put_monomial(hl_buf *b, const pwriter *w, const ulong *e)
{
    int first = 1;
    for (int j = -1; j < w->nbase; j++) {
        int v = j < 0 ? w->step : j;
        if (v < 0 || e[v] == 0 || (j >= 0 && v == w->step))
            continue;
        if (!first)
            hl_buf_putc(b, '*');
        first = 0;
        hl_buf_puts(b, w->names[v]);
        if (e[v] != 1) {
            hl_buf_puts(b, w->pow_op);
            put_digits(b, e[v], 0);
        }
    }
}

static int is_constant(const pwriter *w, const ulong *e)
{
    for (int v = 0; v < w->nbase; v++)
        if (e[v] != 0)
            return 0;
    return 1;
}

/* |c| * monomial: "3/2", "3*x*y/2", "x". */
static void put_term(hl_buf *b, pwriter *w, const fmpq_t c, const ulong *e)
{
    if (is_constant(w, e)) {
        fmpz_abs(fmpq_numref(w->q), fmpq_numref(c)); /* w->q may be c: fine */
        fmpz_set(fmpq_denref(w->q), fmpq_denref(c));
        hl_expr_put_fmpq(b, w->q);
        return;
    }
    if (!fmpz_is_pm1(fmpq_numref(c))) {
        fmpz_t a;
        fmpz_init(a);
        fmpz_abs(a, fmpq_numref(c));
        hl_expr_put_fmpz(b, a);
        fmpz_clear(a);
        hl_buf_putc(b, '*');
    }
    put_monomial(b, w, e);
    if (!fmpz_is_one(fmpq_denref(c))) {
        hl_buf_putc(b, '/');
        hl_expr_put_fmpz(b, fmpq_denref(c));
    }
}

/* The terms of p/c (read_terms done), each with its own coefficient:
 * "-x^2 + 3*x*y/2 - 1".  sign = -1 negates p. */
static void put_plain(hl_buf *b, pwriter *w, const fmpz_mpoly_t p, const fmpz_t c, int sign)
{
    fmpq_t q;
    fmpq_init(q);
    for (slong j = 0; j < p->length; j++) {
        slong i = w->order[j];
        fmpz_set(fmpq_numref(q), p->coeffs + i);
        if (sign < 0)
            fmpz_neg(fmpq_numref(q), fmpq_numref(q));
        fmpz_set(fmpq_denref(q), c);
        fmpq_canonicalise(q);
        int neg = fmpq_sgn(q) < 0;
        if (j == 0)
            hl_buf_puts(b, neg ? "-" : "");
        else
            hl_buf_puts(b, neg ? " - " : " + ");
        put_term(b, w, q, w->exps + i * w->nbase);
    }
    fmpq_clear(q);
}

static size_t fmpz_text_len(const fmpz_t x)
{
    hl_buf b;
    hl_buf_init(&b);
    hl_expr_put_fmpz(&b, x);
    size_t n = b.len;
    hl_buf_clear(&b);
    return n;
}

/* Is the common factor f pulled out shorter, in text style, than the plain
 * sum of length plain_len (print.c's poly_append)?  inner_len: the length
 * of p/g with its first term positive. */
static int pull_is_shorter(const fmpq_t f, int neg, size_t inner_len, size_t plain_len)
{
    size_t n = (size_t)neg + inner_len + 2; /* "-(...)" */
    if (!fmpz_is_one(fmpq_numref(f)))
        n += fmpz_text_len(fmpq_numref(f)) + 1; /* "3*" */
    if (!fmpz_is_one(fmpq_denref(f)))
        n += fmpz_text_len(fmpq_denref(f)) + 1; /* "/2" */
    return n < plain_len;
}

/* The sign of the term of p printed first. */
static int first_sign(const pwriter *w, const fmpz_mpoly_t p)
{
    return p->length == 0 ? 0 : fmpz_sgn(p->coeffs + w->order[0]);
}

/* Names as the style prints them; 0 if SymPy would need Symbol('...') for
 * one (the DAG path writes that). */
static int names_for(pwriter *w, const hl_alg_ctx *ctx, hl_pool *pool, hl_style style)
{
    for (int v = 0; v < w->nbase; v++) {
        w->names[v] = ctx->names[v];
        if (style == HL_STYLE_SYMPY) {
            char *s = hl_expr_print(hl_sym(pool, ctx->names[v]), style);
            int same = strcmp(s, ctx->names[v]) == 0;
            free(s);
            if (!same)
                return 0;
        }
    }
    return 1;
}

/* p/c (c > 0, at least two terms) as a sum: the plain one (r = 1) or, when
 * shorter in text style, the common factor r pulled out (rule 4). */
static void split_sum(hl_buf *rest, fmpq_t r, pwriter *w, const fmpz_mpoly_t p, const fmpz_t c,
                      const char *pow_op)
{
    fmpz_t g;
    fmpz_init(g);
    _fmpz_vec_content(g, p->coeffs, p->length);
    fmpq_set_fmpz_frac(r, g, c);
    int pull = 0, neg = first_sign(w, p) < 0;
    if (p->length <= PULL_MAX_TERMS && !fmpq_is_one(r)) {
        hl_buf plain, inner; /* the lengths decide in text style, as print.c's do */
        hl_buf_init(&plain);
        hl_buf_init(&inner);
        w->pow_op = "^";
        put_plain(&plain, w, p, c, 1);
        put_plain(&inner, w, p, g, neg ? -1 : 1);
        pull = pull_is_shorter(r, neg, inner.len, plain.len);
        w->pow_op = pow_op;
        hl_buf_clear(&plain);
        hl_buf_clear(&inner);
    }
    if (pull) {
        put_plain(rest, w, p, g, neg ? -1 : 1);
        if (neg)
            fmpq_neg(r, r);
    } else {
        put_plain(rest, w, p, c, 1);
        fmpq_one(r);
    }
    fmpz_clear(g);
}

/* p/c (c > 0) split as format.c's split_num splits hl_alg_to_expr's
 * expression of it. */
static void split(hl_buf *rest, fmpq_t r, hl_alg_rest *kind, pwriter *w, const fmpz_mpoly_t p,
                  const fmpz_t c)
{
    *kind = HL_ALG_REST_NONE;
    if (p->length == 0) {
        fmpq_zero(r);
        return;
    }
    if (p->length >= 2) {
        split_sum(rest, r, w, p, c, w->pow_op);
        *kind = HL_ALG_REST_SUM;
        return;
    }
    fmpz_set(fmpq_numref(r), p->coeffs + 0);
    fmpz_set(fmpq_denref(r), c);
    fmpq_canonicalise(r);
    if (!is_constant(w, w->exps)) {
        put_monomial(rest, w, w->exps);
        *kind = HL_ALG_REST_PRODUCT;
    }
}

int hl_alg_poly_split_text(hl_buf *rest, fmpq_t r, hl_alg_rest *kind, const hl_alg *a,
                           const hl_alg_ctx *ctx, hl_pool *pool, hl_style style, long max_terms)
{
    const fmpz_mpoly_struct *p = a->num;
    if ((style != HL_STYLE_TEXT && style != HL_STYLE_SYMPY) || p->length > max_terms ||
        !fmpz_mpoly_is_fmpz(a->den, ctx->mctx))
        return 0;
    pwriter w = {ctx->mctx,
                 ctx->nbase,
                 ctx->nbase + ctx->natoms,
                 ctx->step,
                 style == HL_STYLE_SYMPY ? "**" : "^",
                 NULL,
                 NULL,
                 NULL,
                 {{0, 1}}};
    fmpz_t c;
    fmpz_init(c);
    fmpz_mpoly_get_fmpz(c, a->den, w.mc);
    w.names = hl_xmalloc((size_t)(w.nbase + 1) * sizeof *w.names);
    fmpq_init(w.q);
    int ok = fmpz_sgn(c) > 0 && names_for(&w, ctx, pool, style) && read_terms(&w, p);
    if (ok)
        split(rest, r, kind, &w, p, c);
    fmpq_clear(w.q);
    free(w.exps);
    free(w.order);
    free(w.names);
    fmpz_clear(c);
    return ok;
}
