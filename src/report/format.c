/* Formulas for people and scripts: elements, vector fields, series in D.
 *
 * Signs and rational factors are pulled out of each printed term so that a
 * sum reads "p ∂/∂x − x ∂/∂p" and "x + D*p - D^2/2*x" rather than
 * "(-1*x) ∂/∂p" or "D^2*(-x/2)". */
#include <stdlib.h>
#include <string.h>

#include <flint/fmpq.h>

#include "base/buf.h"
#include "hamlie/report.h"
#include "report/format_impl.h"

/* A result too large to print is not printed: a note stands in its place,
 * and the context records it so that a command can refuse its output.
 * Most results are small: they are printed at once with a node budget (the
 * print counts its nodes), and only one that overruns it pays for measuring
 * its tree size, a walk with a hash memo that cost as much as the print. */
#define PRINT_FIRST_NODES (1 << 20)
_Static_assert(PRINT_FIRST_NODES <= HL_PRINT_MAX_NODES, "a first print within budget is small");

static char *print_result(const hl_expr *e, hl_alg_ctx *ctx, hl_style style)
{
    char *s = hl_expr_print_within(e, style, PRINT_FIRST_NODES);
    if (s != NULL)
        return s;
    double nodes = hl_expr_tree_size(e);
    if (nodes > HL_PRINT_MAX_NODES) {
        hl_alg_ctx_note_unprinted(ctx, nodes);
        return hl_xstrdup("(too large to print)");
    }
    return hl_expr_print(e, style);
}

/* ---- polynomials without the expression DAG (issue 17) --------------------------
 * A polynomial in text or SymPy style is written from hl_alg_poly_split_text's
 * parts: the bytes the DAG path prints (split_num, scaled, series_term and
 * negate_leftmost below, then hl_expr_print), at a fifth of the cost.  Only
 * results the DAG path would print within its first budget take it, so a
 * result too large to print is still found and noted there. */

int hl_format_no_direct;

/* Terms a result may have for the direct path: each prints as at most
 * 4 nodes per symbol and a few more, well within PRINT_FIRST_NODES. */
static long direct_max_terms(const hl_alg_ctx *ctx)
{
    return hl_format_no_direct ? -1 : PRINT_FIRST_NODES / (4 * hl_alg_ctx_nbase(ctx) + 16);
}

/* rest as a factor: a sum in parentheses. */
static void put_rest(hl_buf *b, hl_alg_rest kind, const hl_buf *rest)
{
    if (kind == HL_ALG_REST_SUM)
        hl_buf_putc(b, '(');
    hl_buf_putn(b, rest->s, rest->len);
    if (kind == HL_ALG_REST_SUM)
        hl_buf_putc(b, ')');
}

/* The element r * rest, as hl_alg_to_expr writes it: "-3*x*y/2", "2*(x + y)". */
static void put_element(hl_buf *b, const fmpq_t r, hl_alg_rest kind, const hl_buf *rest)
{
    if (kind == HL_ALG_REST_NONE) {
        hl_expr_put_fmpq(b, r);
        return;
    }
    if (kind == HL_ALG_REST_SUM && fmpq_is_one(r)) {
        hl_buf_putn(b, rest->s, rest->len);
        return;
    }
    if (fmpq_sgn(r) < 0)
        hl_buf_putc(b, '-');
    if (!fmpz_is_pm1(fmpq_numref(r))) {
        fmpz_t n;
        fmpz_init(n);
        fmpz_abs(n, fmpq_numref(r));
        hl_expr_put_fmpz(b, n);
        fmpz_clear(n);
        hl_buf_putc(b, '*');
    }
    put_rest(b, kind, rest);
    if (!fmpz_is_one(fmpq_denref(r))) {
        hl_buf_putc(b, '/');
        hl_expr_put_fmpz(b, fmpq_denref(r));
    }
}

static char *format_alg_direct(const hl_alg *a, hl_alg_ctx *ctx, hl_pool *pool, hl_style style)
{
    hl_buf rest, out;
    fmpq_t r;
    hl_alg_rest kind;
    hl_buf_init(&rest);
    fmpq_init(r);
    char *s = NULL;
    if (hl_alg_poly_split_text(&rest, r, &kind, a, ctx, pool, style, direct_max_terms(ctx))) {
        hl_buf_init(&out);
        put_element(&out, r, kind, &rest);
        s = hl_buf_take(&out);
    }
    fmpq_clear(r);
    hl_buf_clear(&rest);
    return s;
}

char *hl_format_alg(const hl_alg *a, hl_alg_ctx *ctx, hl_pool *pool, hl_style style)
{
    char *s = format_alg_direct(a, ctx, pool, style);
    return s ? s : print_result(hl_alg_to_expr(a, ctx, pool), ctx, style);
}

/* Split e = r * rest, taking r from the numbers on the left spine of the
 * products and quotients (and from negations).  rest is NULL when e is a
 * number. */
static const hl_expr *split_num(fmpq_t r, const hl_expr *e, hl_pool *pool)
{
    const hl_expr *a;
    switch (e->kind) {
    case HL_NUM:
        fmpq_set(r, e->num);
        return NULL;
    case HL_NEG:
        a = split_num(r, e->a, pool);
        fmpq_neg(r, r);
        return a;
    case HL_MUL:
        a = split_num(r, e->a, pool);
        return a ? hl_mul(pool, a, e->b) : e->b;
    case HL_DIV:
        a = split_num(r, e->a, pool);
        if (e->b->kind == HL_NUM && !fmpq_is_zero(e->b->num)) {
            fmpq_div(r, r, e->b->num);
            return a;
        }
        return hl_div(pool, a ? a : hl_num_si(pool, 1), e->b);
    default:
        fmpq_one(r);
        return e;
    }
}

static int is_one(const hl_expr *e)
{
    return e->kind == HL_NUM && fmpq_is_one(e->num);
}

/* f*rest written left to right: f*(a*b) as f*a*b, f*(a/b) as f*a/b, which
 * is the same value and reads without parentheses; f*(1/b) as f/b. */
static const hl_expr *mul_flat(const hl_expr *f, const hl_expr *rest, hl_pool *pool)
{
    if (is_one(rest))
        return f;
    if (rest->kind == HL_MUL)
        return hl_mul(pool, mul_flat(f, rest->a, pool), rest->b);
    if (rest->kind == HL_DIV)
        return hl_div(pool, mul_flat(f, rest->a, pool), rest->b);
    return hl_mul(pool, f, rest);
}

static int is_sum(const hl_expr *e)
{
    return e->kind == HL_ADD || e->kind == HL_SUB;
}

/* |r| * rest as an expression (r != 0): "rest", "3*rest", "3*rest/2", "3/2". */
static const hl_expr *scaled(const fmpq_t r, const hl_expr *rest, hl_pool *pool)
{
    fmpq_t a;
    fmpq_init(a);
    fmpq_abs(a, r);
    const hl_expr *e;
    if (rest == NULL)
        e = hl_num_fmpq(pool, a);
    else {
        e = rest;
        if (!fmpz_is_one(fmpq_numref(a))) {
            fmpq_t n;
            fmpq_init(n);
            fmpz_set(fmpq_numref(n), fmpq_numref(a));
            e = mul_flat(hl_num_fmpq(pool, n), e, pool);
            fmpq_clear(n);
        }
        if (!fmpz_is_one(fmpq_denref(a))) {
            fmpq_t d;
            fmpq_init(d);
            fmpz_set(fmpq_numref(d), fmpq_denref(a));
            e = hl_div(pool, e, hl_num_fmpq(pool, d));
            fmpq_clear(d);
        }
    }
    fmpq_clear(a);
    return e;
}

/* ---- vector fields ---------------------------------------------------------- */

static void put_operator(hl_buf *b, const char *name, hl_style style)
{
    if (style == HL_STYLE_LATEX) {
        char *l = hl_symbol_latex(name);
        hl_buf_printf(b, "\\frac{\\partial}{\\partial %s}", l);
        free(l);
    } else
        hl_buf_printf(b, "\u2202/\u2202%s", name);
}

char *hl_format_vector_field(int n, const char *const *names, const hl_alg *c,
                             hl_alg_ctx *ctx, hl_pool *pool, hl_style style)
{
    int latex = style == HL_STYLE_LATEX, first = 1;
    hl_buf b;
    fmpq_t r;
    hl_buf_init(&b);
    fmpq_init(r);
    for (int i = 0; i < n; i++) {
        if (hl_alg_is_zero(&c[i], ctx))
            continue;
        const hl_expr *rest = split_num(r, hl_alg_to_expr(&c[i], ctx, pool), pool);
        const hl_expr *mag = scaled(r, rest, pool);
        int neg = fmpq_sgn(r) < 0;
        if (first)
            hl_buf_puts(&b, neg ? (latex ? "-" : "\u2212") : "");
        else
            hl_buf_puts(&b, neg ? (latex ? " - " : " \u2212 ") : " + ");
        first = 0;
        if (!is_one(mag)) {
            char *s = print_result(mag, ctx, latex ? HL_STYLE_LATEX : HL_STYLE_TEXT);
            if (is_sum(mag))
                hl_buf_printf(&b, latex ? "\\left(%s\\right) " : "(%s) ", s);
            else
                hl_buf_printf(&b, "%s ", s);
            free(s);
        }
        put_operator(&b, names[i], style);
    }
    fmpq_clear(r);
    if (first)
        hl_buf_puts(&b, "0");
    return hl_buf_take(&b);
}

void hl_json_vector_field(hl_json *j, int n, const char *const *names, const hl_alg *c,
                          hl_alg_ctx *ctx, hl_pool *pool, hl_style style)
{
    hl_json_object_begin(j);
    for (int i = 0; i < n; i++) {
        char *s = hl_format_alg(&c[i], ctx, pool, style);
        hl_json_kv_string(j, names[i], s);
        free(s);
    }
    hl_json_object_end(j);
}

/* ---- series ---------------------------------------------------------------- */

/* e/d (d = 0: e): one fraction when e is one already, D^2/(2*q^2) rather
 * than D^2/2/q^2 (in LaTeX a fraction in a fraction). */
static const hl_expr *with_denominator(const hl_expr *e, const fmpq_t d, hl_pool *pool)
{
    if (fmpq_is_zero(d))
        return e;
    const hl_expr *den = hl_num_fmpq(pool, d);
    if (e->kind == HL_DIV)
        return hl_div(pool, e->a, hl_mul(pool, den, e->b));
    return hl_div(pool, e, den);
}

/* |r| var^k * rest, written "var^k/2*rest", "3*var^k*rest", "var^k*a/(2*b)" ... */
static const hl_expr *series_term(const fmpq_t r, int k, const hl_expr *var,
                                  const hl_expr *rest, hl_pool *pool)
{
    fmpq_t a, num, den;
    fmpq_init(a);
    fmpq_init(num);
    fmpq_init(den);
    fmpq_abs(a, r);
    fmpz_set(fmpq_numref(num), fmpq_numref(a));
    if (!fmpz_is_one(fmpq_denref(a)))
        fmpz_set(fmpq_numref(den), fmpq_denref(a)); /* else den = 0: none */
    const hl_expr *f = NULL;
    if (k == 1)
        f = var;
    else if (k > 1)
        f = hl_pow(pool, var, hl_num_si(pool, k));
    const hl_expr *e;
    if (f == NULL) /* k = 0: the scaled rest itself, or the number */
        e = rest ? scaled(a, rest, pool) : hl_num_fmpq(pool, a);
    else {
        if (!fmpq_is_one(num))
            f = hl_mul(pool, hl_num_fmpq(pool, num), f);
        if (rest != NULL && rest->kind == HL_DIV) /* D^2/(2*q^2) */
            e = with_denominator(mul_flat(f, rest, pool), den, pool);
        else { /* the Taylor coefficient first: D^2/2*x */
            f = with_denominator(f, den, pool);
            e = rest ? mul_flat(f, rest, pool) : f;
        }
    }
    fmpq_clear(a);
    fmpq_clear(num);
    fmpq_clear(den);
    return e;
}

/* -t with the minus on the leftmost factor: -D^3/12, not -(D^3/12) (unary
 * minus binds tighter than * and /, so this is the same value). */
static const hl_expr *negate_leftmost(const hl_expr *t, hl_pool *pool)
{
    if (t->kind == HL_MUL)
        return hl_mul(pool, negate_leftmost(t->a, pool), t->b);
    if (t->kind == HL_DIV)
        return hl_div(pool, negate_leftmost(t->a, pool), t->b);
    return hl_neg(pool, t);
}

/* A negated number as expr/print.c writes NEG(NUM a): "-(3)" in text (else
 * it would read as the number -3), "-3" and "-(3/2)" in SymPy. */
static void put_neg_number(hl_buf *b, const fmpq_t a, hl_style style)
{
    int paren = style == HL_STYLE_TEXT || !fmpz_is_one(fmpq_denref(a));
    hl_buf_puts(b, paren ? "-(" : "-");
    hl_expr_put_fmpq(b, a);
    if (paren)
        hl_buf_putc(b, ')');
}

/* The series term r D^k rest as series_term builds it and the sum prints it;
 * first: the series' first term (a minus then on its leftmost factor, as
 * negate_leftmost puts it). */
static void put_series_term(hl_buf *b, const fmpq_t r, int k, const char *Dk, hl_alg_rest kind,
                            const hl_buf *rest, int first, hl_style style)
{
    int neg = fmpq_sgn(r) < 0;
    fmpq_t a;
    fmpq_init(a);
    fmpq_abs(a, r);
    if (!first)
        hl_buf_puts(b, neg ? " - " : " + ");
    int lead_minus = first && neg;
    if (k == 0 && kind == HL_ALG_REST_NONE) { /* one number */
        if (lead_minus)
            put_neg_number(b, a, style);
        else
            hl_expr_put_fmpq(b, a);
    } else if (k == 0 && kind == HL_ALG_REST_SUM && fmpq_is_one(a)) { /* the sum itself */
        if (first && !neg)
            hl_buf_putn(b, rest->s, rest->len);
        else {
            hl_buf_puts(b, lead_minus ? "-" : "");
            put_rest(b, kind, rest);
        }
    } else {
        fmpq_t n;
        fmpq_init(n);
        fmpz_set(fmpq_numref(n), fmpq_numref(a));
        if (!fmpz_is_one(fmpq_numref(a))) {
            if (lead_minus)
                put_neg_number(b, n, style);
            else
                hl_expr_put_fmpz(b, fmpq_numref(a));
            hl_buf_putc(b, '*');
        } else if (lead_minus)
            hl_buf_putc(b, '-');
        fmpq_clear(n);
        if (k > 0) {
            hl_buf_puts(b, Dk);
            if (!fmpz_is_one(fmpq_denref(a))) {
                hl_buf_putc(b, '/');
                hl_expr_put_fmpz(b, fmpq_denref(a));
            }
            if (kind != HL_ALG_REST_NONE) {
                hl_buf_putc(b, '*');
                put_rest(b, kind, rest);
            }
        } else {
            put_rest(b, kind, rest);
            if (!fmpz_is_one(fmpq_denref(a))) {
                hl_buf_putc(b, '/');
                hl_expr_put_fmpz(b, fmpq_denref(a));
            }
        }
    }
    fmpq_clear(a);
}

/* D^k as the style writes it. */
static void put_power(hl_buf *b, const char *D, int k, hl_style style)
{
    b->len = 0;
    hl_buf_puts(b, D);
    if (k > 1)
        hl_buf_printf(b, "%s%d", style == HL_STYLE_SYMPY ? "**" : "^", k);
}

/* The series without the DAG, or NULL when a term is not for the direct path. */
static char *format_series_direct(const hl_alg *terms, int order, const char *var, int factorial,
                                  hl_alg_ctx *ctx, hl_pool *pool, hl_style style)
{
    long total = 0, max_terms = direct_max_terms(ctx);
    for (int k = 0; k <= order; k++)
        total += terms[k].num->length;
    if (total > max_terms || (style != HL_STYLE_TEXT && style != HL_STYLE_SYMPY))
        return NULL;
    char *D = hl_expr_print(hl_sym(pool, var), style);
    hl_buf out, rest, Dk;
    hl_buf_init(&out);
    hl_buf_init(&rest);
    hl_buf_init(&Dk);
    fmpq_t r, kf;
    fmpq_init(r);
    fmpq_init(kf);
    fmpq_one(kf);
    int first = 1, ok = 1;
    for (int k = 0; k <= order && ok; k++) {
        if (factorial && k > 0)
            fmpz_mul_ui(fmpq_denref(kf), fmpq_denref(kf), (ulong)k); /* kf = 1/k! */
        if (hl_alg_is_zero(&terms[k], ctx))
            continue;
        hl_alg_rest kind;
        rest.len = 0;
        if (!(ok = hl_alg_poly_split_text(&rest, r, &kind, &terms[k], ctx, pool, style, max_terms)))
            break;
        fmpq_mul(r, r, kf);
        put_power(&Dk, D, k, style);
        put_series_term(&out, r, k, Dk.s, kind, &rest, first, style);
        first = 0;
    }
    if (ok && first)
        hl_buf_putc(&out, '0');
    fmpq_clear(r);
    fmpq_clear(kf);
    hl_buf_clear(&rest);
    hl_buf_clear(&Dk);
    free(D);
    if (!ok) {
        hl_buf_clear(&out);
        return NULL;
    }
    return hl_buf_take(&out);
}

char *hl_format_series(const hl_alg *terms, int order, const char *var, int factorial,
                       hl_alg_ctx *ctx, hl_pool *pool, hl_style style)
{
    char *direct = format_series_direct(terms, order, var, factorial, ctx, pool, style);
    if (direct != NULL)
        return direct;
    const hl_expr *sum = NULL, *v = hl_sym(pool, var);
    fmpq_t r, kf;
    fmpq_init(r);
    fmpq_init(kf);
    fmpq_one(kf);
    for (int k = 0; k <= order; k++) {
        if (factorial && k > 0) {
            fmpz_t kk;
            fmpz_init_set_ui(kk, (ulong)k);
            fmpq_div_fmpz(kf, kf, kk); /* kf = 1/k! */
            fmpz_clear(kk);
        }
        if (hl_alg_is_zero(&terms[k], ctx))
            continue;
        const hl_expr *rest = split_num(r, hl_alg_to_expr(&terms[k], ctx, pool), pool);
        fmpq_mul(r, r, kf);
        const hl_expr *t = series_term(r, k, v, rest, pool);
        int neg = fmpq_sgn(r) < 0;
        if (sum == NULL)
            sum = neg ? negate_leftmost(t, pool) : t;
        else
            sum = neg ? hl_sub(pool, sum, t) : hl_add(pool, sum, t);
    }
    fmpq_clear(r);
    fmpq_clear(kf);
    if (sum == NULL)
        sum = hl_num_si(pool, 0);
    return print_result(sum, ctx, style);
}
