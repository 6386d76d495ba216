/* Element -> expression, written the way a mathematical physicist writes it
 * by hand.  Printing only: the canonical form is not touched, and
 * hl_alg_from_expr(hl_alg_to_expr(a)) == a (same num and den).
 *
 * 1. Term order.  Without a series symbol: the stored order (total degree
 *    descending, then variable order).  With one (hl_alg_ctx_set_step; the
 *    ham layer sets D): ascending power of it first, then descending total
 *    degree in the other variables, then the stored order; in a monomial the
 *    series symbol comes first.  So "p^2/2 - cos(q)", "x + D*p", "1 + D^2".
 *    Signs of denominator factors are normalised on the first term printed.
 * 2. Signs.  A negative term never prints as "-(a*b)": the sign sits on the
 *    first factor or on the coefficient, MUL(NEG(x), D) -> "-x*D",
 *    MUL(-3, x) -> "-3*x" (unary minus binds tighter than * and /, looser
 *    than ^, so "-p^4*sin(q)" is (-(p^4))*sin(q)); a sum keeps one minus in
 *    front: "-(x + y)/(2*(x^2 + y^2))".
 * 3. Square roots.  Over a non-constant denominator d, the numerator is split
 *    by its square-root atoms r = sqrt(u) (u not constant): a + b*r over d
 *    is the sum a/d + b*r/d, each part reduced by its own gcd with d, and
 *    b*r/(u^k*rest) is written b/(u^(k-1/2)*rest).  The sqrt-free part comes
 *    first.  Kepler: -((x^2+y^2)(x*px*py - y*px^2) + y*r)/(x^2+y^2) prints
 *    "-x*px*py + y*px^2 - y/sqrt(x^2 + y^2)".
 * 4. Common factors.  A rational factor common to the terms of a sum is
 *    pulled out ("(x + y + z)/3", "2*(x + y + z)") only when the text gets
 *    strictly shorter, and only for sums of at most PULL_MAX_TERMS terms;
 *    otherwise each term carries its own coefficient ("p^2/2 - cos(q)").
 * Denominators are factored (FLINT); factors are listed by degree, then
 * number of terms, then the monomial order: "x*y*(x + y)*(x - y)". */
#include <stdlib.h>
#include <string.h>

#include "alg/alg_internal.h"
#include <flint/fmpz_mpoly_factor.h>
#include "base/buf.h"
#include "expr/print_impl.h"

#define PULL_MAX_TERMS 64

/* var^e for e below this is built once per print and reused (a large
 * polynomial names the same few powers in every term). */
#define POW_MEMO_MAX 32

typedef struct printer {
    const hl_alg_ctx *ctx;
    const fmpz_mpoly_ctx_struct *mc;
    hl_pool *pool;
    int nv;               /* variables of the mpoly context */
    int nu;               /* of which in use: the base symbols and the atoms made (the
                           * context has room for 32 atoms; most systems make a few,
                           * and a loop over all per term was a tenth of a print) */
    int step;             /* the series symbol, or -1 */
    const hl_expr **atom; /* memo: expression of each atom */
    const hl_expr **pow;  /* memo: var_pow(v, e) at [v * POW_MEMO_MAX + e] */
    hl_buf scratch;       /* text_len's: reused */
    int seeded;           /* seeds made (seeds_make) */
    fmpz_mpoly_factor_t seeds; /* irreducibles tried first on a denominator */
} printer;

/* A term of a sum: its magnitude and whether it is subtracted. */
typedef struct sterm {
    const hl_expr *mag;
    int neg;
} sterm;

typedef struct terms {
    sterm *t;
    slong n, cap;
} terms;

static const hl_expr *frac_expr(printer *pr, const hl_alg *a);

/* ---- sums of signed terms ------------------------------------------------- */

static void terms_push(terms *L, const hl_expr *mag, int neg)
{
    if (L->n == L->cap) {
        L->cap = L->cap ? 2 * L->cap : 8;
        L->t = hl_xrealloc(L->t, (size_t)L->cap * sizeof *L->t);
    }
    L->t[L->n].mag = mag;
    L->t[L->n].neg = neg;
    L->n++;
}

/* -e with the sign on the first factor: -3*x, -x*D, -x/u, -(x + y)/2. */
static const hl_expr *negate_first(hl_pool *pool, const hl_expr *e)
{
    switch (e->kind) {
    case HL_NUM: {
        fmpq_t c;
        fmpq_init(c);
        fmpq_neg(c, e->num);
        const hl_expr *r = hl_num_fmpq(pool, c);
        fmpq_clear(c);
        return r;
    }
    case HL_MUL:
        return hl_mul(pool, negate_first(pool, e->a), e->b);
    case HL_DIV:
        return hl_div(pool, negate_first(pool, e->a), e->b);
    default:
        return hl_neg(pool, e);
    }
}

/* Terms from..L->n-1 joined left to right; "0" when there are none. */
static const hl_expr *terms_join(printer *pr, const terms *L, slong from)
{
    const hl_expr *s = NULL;
    for (slong i = from; i < L->n; i++) {
        const sterm *t = &L->t[i];
        if (s == NULL)
            s = t->neg ? negate_first(pr->pool, t->mag) : t->mag;
        else
            s = t->neg ? hl_sub(pr->pool, s, t->mag) : hl_add(pr->pool, s, t->mag);
    }
    return s != NULL ? s : hl_num_si(pr->pool, 0);
}

/* ---- term order ------------------------------------------------------------- */

typedef struct tkey {
    ulong step, deg; /* power of the series symbol, total degree of the rest */
    slong i;         /* stored position */
} tkey;

static void term_key(tkey *k, printer *pr, const ulong *exp, slong i)
{
    k->step = exp[pr->step];
    k->deg = 0;
    for (int v = 0; v < pr->nu; v++)
        if (v != pr->step)
            k->deg += exp[v];
    k->i = i;
}

static int tkey_cmp(const void *a, const void *b)
{
    const tkey *x = a, *y = b;
    if (x->step != y->step)
        return x->step < y->step ? -1 : 1;
    if (x->deg != y->deg)
        return x->deg > y->deg ? -1 : 1;
    return (x->i > y->i) - (x->i < y->i);
}

/* The exponents of the variables in use of the terms of p, nu each
 * (malloc'd): read once, for the order and for the monomials. */
static ulong *term_exps(printer *pr, const fmpz_mpoly_t p)
{
    ulong *exps = hl_xmalloc((size_t)(p->length * pr->nu + 1) * sizeof *exps);
    for (slong i = 0; i < p->length; i++)
        for (int v = 0; v < pr->nu; v++)
            exps[i * pr->nu + v] = fmpz_mpoly_get_term_var_exp_ui(p, i, v, pr->mc);
    return exps;
}

/* Stored positions of the terms of p in printing order (malloc'd). */
static slong *term_order(printer *pr, const fmpz_mpoly_t p, const ulong *exps)
{
    slong n = p->length, *perm = hl_xmalloc((size_t)(n + 1) * sizeof *perm);
    if (pr->step < 0) {
        for (slong i = 0; i < n; i++)
            perm[i] = i;
        return perm;
    }
    tkey *k = hl_xmalloc((size_t)(n + 1) * sizeof *k);
    for (slong i = 0; i < n; i++)
        term_key(&k[i], pr, exps + i * pr->nu, i);
    qsort(k, (size_t)n, sizeof *k, tkey_cmp);
    for (slong i = 0; i < n; i++)
        perm[i] = k[i].i;
    free(k);
    return perm;
}

/* Stored position of the term of p printed first (p != 0). */
static slong first_term(printer *pr, const fmpz_mpoly_t p)
{
    if (pr->step < 0 || p->length <= 1)
        return 0;
    ulong *exp = hl_xmalloc((size_t)pr->nv * sizeof *exp);
    tkey best, k;
    fmpz_mpoly_get_term_exp_ui(exp, p, 0, pr->mc);
    term_key(&best, pr, exp, 0);
    for (slong i = 1; i < p->length; i++) {
        fmpz_mpoly_get_term_exp_ui(exp, p, i, pr->mc);
        term_key(&k, pr, exp, i);
        if (tkey_cmp(&k, &best) < 0)
            best = k;
    }
    free(exp);
    return best.i;
}

static int first_sign(printer *pr, const fmpz_mpoly_t p)
{
    return p->length == 0 ? 0 : fmpz_sgn(p->coeffs + first_term(pr, p));
}

/* ---- monomials and terms ------------------------------------------------------ */

static const hl_expr *atom_expr(printer *pr, int k)
{
    if (pr->atom[k] != NULL)
        return pr->atom[k];
    const alg_atom *at = &pr->ctx->atoms[k];
    const hl_expr *arg = at->kind == ATOM_PI ? NULL : frac_expr(pr, &at->arg), *e = NULL;
    static const hl_fun fun[] = {HL_SQRT, HL_SQRT, HL_SIN, HL_COS, HL_EXP,
                                 HL_LOG, HL_ATAN, HL_ASIN, HL_ACOS, HL_SQRT};
    if (at->kind == ATOM_PI)
        e = hl_pi(pr->pool);
    else if (at->kind == ATOM_ATAN2)
        e = hl_call2(pr->pool, HL_ATAN2, arg, frac_expr(pr, &at->arg2));
    else if (at->kind == ATOM_ROOT)
        e = hl_pow(pr->pool, arg, hl_num_frac(pr->pool, 1, (ulong)at->q));
    else
        e = hl_call(pr->pool, fun[at->kind], arg);
    pr->atom[k] = e;
    return e;
}

static const hl_expr *var_pow_new(printer *pr, int v, ulong e);

/* v^e for a variable (e > 0). */
static const hl_expr *var_pow(printer *pr, int v, ulong e)
{
    if (e >= POW_MEMO_MAX)
        return var_pow_new(pr, v, e);
    const hl_expr **slot = &pr->pow[v * POW_MEMO_MAX + (int)e];
    if (*slot == NULL)
        *slot = var_pow_new(pr, v, e);
    return *slot;
}

static const hl_expr *var_pow_new(printer *pr, int v, ulong e)
{
    const hl_alg_ctx *ctx = pr->ctx;
    if (v < ctx->nbase) {
        const hl_expr *x = hl_sym(pr->pool, ctx->names[v]);
        return e == 1 ? x : hl_pow(pr->pool, x, hl_num_si(pr->pool, (long)e));
    }
    int k = v - ctx->nbase;
    const alg_atom *at = &ctx->atoms[k];
    if (at->kind == ATOM_ROOT && e > 1) { /* u^(e/q), not (u^(1/q))^e */
        const hl_expr *u = frac_expr(pr, &at->arg);
        return hl_pow(pr->pool, u, hl_num_frac(pr->pool, (long)e, (ulong)at->q));
    }
    const hl_expr *x = atom_expr(pr, k);
    return e == 1 ? x : hl_pow(pr->pool, x, hl_num_si(pr->pool, (long)e));
}

/* |c| times the monomial with exponents exp (of the nu variables in use),
 * built left to right as it is read (3*D*x*y/2 is (((3*D)*x)*y)/2), the
 * series symbol first. */
static const hl_expr *term_mag(printer *pr, const fmpq_t c, const ulong *exp)
{
    hl_pool *pool = pr->pool;
    int constant = 1;
    for (int v = 0; v < pr->nu; v++)
        constant &= exp[v] == 0;
    fmpq_t a, n;
    fmpq_init(a);
    fmpq_init(n);
    fmpq_abs(a, c);
    const hl_expr *m = NULL;
    if (constant) {
        m = hl_num_fmpq(pool, a); /* a constant term: one literal */
    } else {
        if (!fmpz_is_one(fmpq_numref(a))) {
            fmpz_set(fmpq_numref(n), fmpq_numref(a));
            m = hl_num_fmpq(pool, n);
        }
        for (int j = -1; j < pr->nu; j++) { /* j = -1: the series symbol */
            int v = j < 0 ? pr->step : j;
            if (v < 0 || exp[v] == 0 || (j >= 0 && v == pr->step))
                continue;
            const hl_expr *f = var_pow(pr, v, exp[v]);
            m = m == NULL ? f : hl_mul(pool, m, f);
        }
        if (!fmpz_is_one(fmpq_denref(a))) {
            fmpz_set(fmpq_numref(n), fmpq_denref(a));
            m = hl_div(pool, m, hl_num_fmpq(pool, n));
        }
    }
    fmpq_clear(a);
    fmpq_clear(n);
    return m;
}

/* ---- polynomials ---------------------------------------------------------------- */

/* The terms of p/c (c > 0), each with its own coefficient. */
static void plain_append(printer *pr, terms *L, const fmpz_mpoly_t p, const fmpz_t c)
{
    /* own exponents: printing an atom's argument reuses the printer */
    ulong *exps = term_exps(pr, p);
    slong *perm = term_order(pr, p, exps);
    fmpq_t q;
    fmpq_init(q);
    for (slong j = 0; j < p->length; j++) {
        slong i = perm[j];
        fmpz_set(fmpq_numref(q), p->coeffs + i);
        fmpz_set(fmpq_denref(q), c);
        fmpq_canonicalise(q);
        terms_push(L, term_mag(pr, q, exps + i * pr->nu), fmpq_sgn(q) < 0);
    }
    fmpq_clear(q);
    free(perm);
    free(exps);
}

static size_t text_len(printer *pr, const hl_expr *e)
{
    return hl_expr_print_len(e, HL_STYLE_TEXT, &pr->scratch);
}

/* p/c (c > 0) as terms; with a common factor f = content/c != 1 pulled out
 * (one term f*(...)) when that is strictly shorter (rule 4). */
static void poly_append(printer *pr, terms *L, const fmpz_mpoly_t p, const fmpz_t c)
{
    slong start = L->n;
    plain_append(pr, L, p, c);
    if (p->length < 2 || p->length > PULL_MAX_TERMS)
        return;
    fmpq_t f;
    fmpz_t g;
    fmpq_init(f);
    fmpz_init(g);
    _fmpz_vec_content(g, p->coeffs, p->length);
    fmpq_set_fmpz_frac(f, g, c); /* p/c = f * (p/g) */
    if (!fmpq_is_one(f)) {
        hl_pool *pool = pr->pool;
        int neg = first_sign(pr, p) < 0;
        fmpz_mpoly_t s;
        fmpz_mpoly_init(s, pr->mc);
        fmpz_mpoly_scalar_divexact_fmpz(s, p, g, pr->mc);
        if (neg)
            fmpz_mpoly_neg(s, s, pr->mc);
        terms in = {0};
        fmpz_t one;
        fmpz_init_set_ui(one, 1);
        plain_append(pr, &in, s, one);
        const hl_expr *mag = terms_join(pr, &in, 0);
        fmpq_t k;
        fmpq_init(k);
        if (!fmpz_is_one(fmpq_numref(f))) {
            fmpz_set(fmpq_numref(k), fmpq_numref(f));
            mag = hl_mul(pool, hl_num_fmpq(pool, k), mag);
        }
        if (!fmpz_is_one(fmpq_denref(f))) {
            fmpz_set(fmpq_numref(k), fmpq_denref(f));
            mag = hl_div(pool, mag, hl_num_fmpq(pool, k));
        }
        const hl_expr *pulled = neg ? negate_first(pool, mag) : mag;
        if (text_len(pr, pulled) < text_len(pr, terms_join(pr, L, start))) {
            L->n = start;
            terms_push(L, mag, neg);
        }
        fmpq_clear(k);
        fmpz_clear(one);
        free(in.t);
        fmpz_mpoly_clear(s, pr->mc);
    }
    fmpz_clear(g);
    fmpq_clear(f);
}

/* p (integer coefficients) as one expression, rule 4 included. */
static const hl_expr *poly_expr(printer *pr, const fmpz_mpoly_t p)
{
    terms L = {0};
    fmpz_t one;
    fmpz_init_set_ui(one, 1);
    poly_append(pr, &L, p, one);
    const hl_expr *e = terms_join(pr, &L, 0);
    fmpz_clear(one);
    free(L.t);
    return e;
}

/* ---- denominators ------------------------------------------------------------ */

/* A factor of a denominator: poly^e, or u^(e - 1/2) for a square root's
 * argument (atom >= 0). */
typedef struct dfactor {
    const fmpz_mpoly_struct *poly;
    long e;
    int atom;
} dfactor;

/* Order factors as a person lists them: lower degree first, then fewer
 * terms, then the larger in the monomial order first, as terms are (x*y,
 * not y*x; the output does not depend on the order factorisation found
 * them in). */
static int factor_before(const dfactor *a, const dfactor *b, const fmpz_mpoly_ctx_t mc)
{
    slong da = fmpz_mpoly_total_degree_si(a->poly, mc);
    slong db = fmpz_mpoly_total_degree_si(b->poly, mc);
    if (da != db)
        return da < db;
    if (a->poly->length != b->poly->length)
        return a->poly->length < b->poly->length;
    return fmpz_mpoly_cmp(a->poly, b->poly, mc) > 0;
}

/* ---- factoring denominators ---------------------------------------------------
 * Denominators are mostly powers of the atoms' arguments (Kepler's
 * (x^2 + y^2)^k): fmpz_mpoly_factor took ~2 million instructions on each,
 * and a gcd with the numerator about as much.  So the irreducible factors
 * of the atoms' arguments (factored once per print) are tried first, by
 * division, and only a cofactor left over is factored in full.  The result
 * is the same factorization (unique up to the signs of the factors, which
 * den_expr normalises), found cheaply. */

/* Append the irreducible factors of atom k's argument to the seeds,
 * skipping one already there up to sign. */
static void seeds_add(printer *pr, int k)
{
    const fmpz_mpoly_ctx_struct *mc = pr->mc;
    const struct alg_arg_factors *af = alg_atom_arg_factors(pr->ctx, k);
    if (!af->ok)
        return;
    fmpz_mpoly_t neg;
    fmpz_mpoly_init(neg, mc);
    for (slong i = 0; i < af->f->num; i++) {
        int known = 0;
        fmpz_mpoly_neg(neg, af->f->poly + i, mc);
        for (slong j = 0; j < pr->seeds->num && !known; j++)
            known = fmpz_mpoly_equal(pr->seeds->poly + j, af->f->poly + i, mc) ||
                    fmpz_mpoly_equal(pr->seeds->poly + j, neg, mc);
        if (!known) {
            slong n = pr->seeds->num;
            fmpz_mpoly_factor_fit_length(pr->seeds, n + 1, mc);
            fmpz_mpoly_set(pr->seeds->poly + n, af->f->poly + i, mc);
            fmpz_one(pr->seeds->exp + n);
            pr->seeds->num = n + 1;
        }
    }
    fmpz_mpoly_clear(neg, mc);
}

static void seeds_make(printer *pr)
{
    if (pr->seeded)
        return;
    pr->seeded = 1;
    for (int k = 0; k < pr->ctx->natoms; k++) {
        const alg_atom *at = &pr->ctx->atoms[k];
        if (at->kind != ATOM_PI && !fmpz_mpoly_is_fmpz(at->arg.num, pr->mc))
            seeds_add(pr, k);
    }
}

/* Push factor^e onto f. */
static void factor_push(fmpz_mpoly_factor_t f, const fmpz_mpoly_t factor, slong e,
                        const fmpz_mpoly_ctx_t mc)
{
    fmpz_mpoly_factor_fit_length(f, f->num + 1, mc);
    fmpz_mpoly_set(f->poly + f->num, factor, mc);
    fmpz_set_si(f->exp + f->num, e);
    f->num++;
}

/* d (not constant) = f->constant * prod f->poly[i]^f->exp[i], irreducible
 * factors; 0 if FLINT could not factor (f then untouched). */
static int den_factor(fmpz_mpoly_factor_t f, printer *pr, const fmpz_mpoly_t d)
{
    const fmpz_mpoly_ctx_struct *mc = pr->mc;
    fmpz_mpoly_t rest, t;
    fmpz_mpoly_init(rest, mc);
    fmpz_mpoly_init(t, mc);
    fmpz_mpoly_set(rest, d, mc);
    seeds_make(pr);
    fmpz_mpoly_factor_t found;
    fmpz_mpoly_factor_init(found, mc);
    for (slong i = 0; i < pr->seeds->num && !fmpz_mpoly_is_fmpz(rest, mc); i++) {
        slong e = 0;
        while (!fmpz_mpoly_is_fmpz(rest, mc) &&
               fmpz_mpoly_divides(t, rest, pr->seeds->poly + i, mc)) {
            fmpz_mpoly_swap(rest, t, mc);
            e++;
        }
        if (e > 0)
            factor_push(found, pr->seeds->poly + i, e, mc);
    }
    int ok = 1;
    if (fmpz_mpoly_is_fmpz(rest, mc)) {
        fmpz_mpoly_get_fmpz(found->constant, rest, mc);
    } else if ((ok = fmpz_mpoly_factor(f, rest, mc))) { /* a cofactor: in full */
        fmpz_set(found->constant, f->constant);
        for (slong i = 0; i < f->num; i++)
            factor_push(found, f->poly + i, fmpz_get_si(f->exp + i), mc);
    }
    if (ok)
        fmpz_mpoly_factor_swap(f, found, mc);
    fmpz_mpoly_factor_clear(found, mc);
    fmpz_mpoly_clear(rest, mc);
    fmpz_mpoly_clear(t, mc);
    return ok;
}

/* gcd(n, d) with d not constant, as fmpz_mpoly_gcd gives it (positive
 * leading coefficient), from d's factorization: the content's gcd times
 * each factor of d to the power it divides n (up to its power in d). */
static void den_gcd(fmpz_mpoly_t g, printer *pr, const fmpz_mpoly_t n, const fmpz_mpoly_t d)
{
    const fmpz_mpoly_ctx_struct *mc = pr->mc;
    fmpz_mpoly_factor_t f;
    fmpz_mpoly_factor_init(f, mc);
    if (fmpz_mpoly_is_zero(n, mc) || !den_factor(f, pr, d)) {
        if (!fmpz_mpoly_gcd(g, n, d, mc))
            fmpz_mpoly_one(g, mc); /* as before: no reduction */
        fmpz_mpoly_factor_clear(f, mc);
        return;
    }
    fmpz_t c;
    fmpz_init(c);
    _fmpz_vec_content(c, n->coeffs, n->length);
    fmpz_gcd(c, c, f->constant); /* the factors are primitive: f->constant is d's content */
    fmpz_mpoly_set_fmpz(g, c, mc);
    fmpz_mpoly_t rest, t;
    fmpz_mpoly_init(rest, mc);
    fmpz_mpoly_init(t, mc);
    fmpz_mpoly_set(rest, n, mc);
    for (slong i = 0; i < f->num; i++) {
        slong e = fmpz_get_si(f->exp + i);
        for (slong k = 0; k < e && fmpz_mpoly_divides(t, rest, f->poly + i, mc); k++) {
            fmpz_mpoly_swap(rest, t, mc);
            fmpz_mpoly_mul(g, g, f->poly + i, mc);
        }
    }
    if (fmpz_sgn(g->coeffs + 0) < 0) /* coeffs[0]: the leading term */
        fmpz_mpoly_neg(g, g, mc);
    fmpz_clear(c);
    fmpz_mpoly_clear(rest, mc);
    fmpz_mpoly_clear(t, mc);
    fmpz_mpoly_factor_clear(f, mc);
}

/* The expression of d * prod_h u_h^(e_h - 1/2) with its sign in *sign.
 * d != 0; the factors of d are made unit-normal on their first printed term
 * (the roots' arguments keep their sign: they are what the sqrt shows). */
static const hl_expr *den_expr(int *sign, printer *pr, const fmpz_mpoly_t d,
                               const dfactor *half, int nhalf)
{
    const fmpz_mpoly_ctx_struct *mc = pr->mc;
    hl_pool *pool = pr->pool;
    fmpz_mpoly_factor_t f;
    fmpz_mpoly_factor_init(f, mc);
    if (fmpz_mpoly_is_fmpz(d, mc)) {
        fmpz_mpoly_get_fmpz(f->constant, d, mc);
    } else if (!den_factor(f, pr, d)) {
        fmpz_mpoly_factor_fit_length(f, 1, mc);
        fmpz_one(f->constant);
        fmpz_mpoly_set(f->poly + 0, d, mc);
        fmpz_one(f->exp + 0);
        f->num = 1;
    }
    for (slong i = 0; i < f->num; i++)
        if (first_sign(pr, f->poly + i) < 0) {
            fmpz_mpoly_neg(f->poly + i, f->poly + i, mc);
            if (fmpz_is_odd(f->exp + i))
                fmpz_neg(f->constant, f->constant);
        }
    int n = (int)f->num + nhalf;
    dfactor *fac = hl_xmalloc((size_t)(n + 1) * sizeof *fac);
    for (slong i = 0; i < f->num; i++) {
        fac[i].poly = f->poly + i;
        fac[i].e = fmpz_get_si(f->exp + i);
        fac[i].atom = -1;
    }
    for (int h = 0; h < nhalf; h++)
        fac[f->num + h] = half[h];
    for (int i = 1; i < n; i++)
        for (int j = i; j > 0 && factor_before(&fac[j], &fac[j - 1], mc); j--) {
            dfactor t = fac[j];
            fac[j] = fac[j - 1];
            fac[j - 1] = t;
        }
    *sign = fmpz_sgn(f->constant);
    const hl_expr *den = NULL;
    fmpz_abs(f->constant, f->constant);
    if (!fmpz_is_one(f->constant)) {
        fmpq_t c;
        fmpq_init(c);
        fmpz_set(fmpq_numref(c), f->constant);
        den = hl_num_fmpq(pool, c);
        fmpq_clear(c);
    }
    for (int i = 0; i < n; i++) {
        const hl_expr *p;
        long e = fac[i].e;
        if (fac[i].atom >= 0) {
            const hl_expr *u = frac_expr(pr, &pr->ctx->atoms[fac[i].atom].arg);
            p = e == 1 ? hl_call(pool, HL_SQRT, u) : hl_pow(pool, u, hl_num_frac(pool, 2 * e - 1, 2));
        } else {
            const hl_expr *b = poly_expr(pr, fac[i].poly);
            p = e == 1 ? b : hl_pow(pool, b, hl_num_si(pool, e));
        }
        den = den == NULL ? p : hl_mul(pool, den, p);
    }
    free(fac);
    fmpz_mpoly_factor_clear(f, mc);
    return den;
}

/* ---- fractions --------------------------------------------------------------- */

/* The part n * prod_{v in sv} v / d of a numerator (n free of the square
 * roots sv, d != 0 not constant), reduced on its own (rule 3), appended. */
static void part_append(printer *pr, terms *L, const fmpz_mpoly_t n0, const int *sv, int ns,
                        const fmpz_mpoly_t d0, int reduce)
{
    const fmpz_mpoly_ctx_struct *mc = pr->mc;
    hl_pool *pool = pr->pool;
    fmpz_mpoly_t n, d, g, t;
    fmpz_mpoly_init(n, mc);
    fmpz_mpoly_init(d, mc);
    fmpz_mpoly_init(g, mc);
    fmpz_mpoly_init(t, mc);
    fmpz_mpoly_set(n, n0, mc);
    fmpz_mpoly_set(d, d0, mc);
    if (reduce && !fmpz_mpoly_is_fmpz(d, mc)) {
        den_gcd(g, pr, n, d);
#ifdef HL_CHECK_DEN_GCD
        fmpz_mpoly_t g2;
        fmpz_mpoly_init(g2, mc);
        fmpz_mpoly_gcd(g2, n, d, mc);
        if (!fmpz_mpoly_equal(g, g2, mc))
            abort();
        fmpz_mpoly_clear(g2, mc);
#endif
    }
    if (reduce && !fmpz_mpoly_is_fmpz(d, mc) && !fmpz_mpoly_is_one(g, mc)) {
        fmpz_mpoly_divides(n, n, g, mc);
        fmpz_mpoly_divides(d, d, g, mc);
    }
    /* sqrt(u)/u^k = 1/u^(k-1/2) */
    dfactor *half = hl_xmalloc((size_t)(ns + 1) * sizeof *half);
    int nhalf = 0;
    for (int j = 0; j < ns; j++) {
        const alg_atom *at = alg_var_atom(pr->ctx, sv[j]);
        long k = 0;
        while (!fmpz_mpoly_is_fmpz(d, mc) && fmpz_mpoly_divides(t, d, at->arg.num, mc)) {
            fmpz_mpoly_swap(d, t, mc);
            k++;
        }
        if (k > 0) {
            half[nhalf].poly = at->arg.num;
            half[nhalf].e = k;
            half[nhalf].atom = (int)(at - pr->ctx->atoms);
            nhalf++;
        } else {
            fmpz_mpoly_gen(t, sv[j], mc);
            fmpz_mpoly_mul(n, n, t, mc);
        }
    }
    if (nhalf == 0 && fmpz_mpoly_is_fmpz(d, mc)) { /* a polynomial part */
        fmpz_t c;
        fmpz_init(c);
        fmpz_mpoly_get_fmpz(c, d, mc);
        if (fmpz_sgn(c) < 0) {
            fmpz_neg(c, c);
            fmpz_mpoly_neg(n, n, mc);
        }
        poly_append(pr, L, n, c);
        fmpz_clear(c);
    } else {
        int dsign;
        const hl_expr *den = den_expr(&dsign, pr, d, half, nhalf);
        int neg = first_sign(pr, n) < 0;
        if (neg)
            fmpz_mpoly_neg(n, n, mc);
        const hl_expr *num;
        if (n->length == 1) {
            fmpq_t c;
            fmpq_init(c);
            fmpz_set(fmpq_numref(c), n->coeffs + 0);
            ulong *exp = term_exps(pr, n);
            num = term_mag(pr, c, exp);
            free(exp);
            fmpq_clear(c);
        } else {
            num = poly_expr(pr, n);
        }
        terms_push(L, hl_div(pool, num, den), neg != (dsign < 0));
    }
    free(half);
    fmpz_mpoly_clear(n, mc);
    fmpz_mpoly_clear(d, mc);
    fmpz_mpoly_clear(g, mc);
    fmpz_mpoly_clear(t, mc);
}

/* A group of numerator terms sharing the same square roots. */
typedef struct group {
    unsigned char *key; /* key[j]: has square root j */
    int pop;
    slong first;
    fmpz_mpoly_t c; /* the terms with those roots divided out */
} group;

static int group_cmp(const void *a, const void *b)
{
    const group *x = *(const group *const *)a, *y = *(const group *const *)b;
    if (x->pop != y->pop)
        return x->pop < y->pop ? -1 : 1;
    return (x->first > y->first) - (x->first < y->first);
}

/* num/den, den not constant: split by square roots (rule 3). */
static void split_append(printer *pr, terms *L, const hl_alg *a)
{
    const hl_alg_ctx *ctx = pr->ctx;
    const fmpz_mpoly_ctx_struct *mc = pr->mc;
    const fmpz_mpoly_struct *num = a->num;
    int *sv = hl_xmalloc((size_t)ctx->natoms * sizeof *sv + 1), ns = 0;
    for (int k = 0; k < ctx->natoms; k++) {
        const alg_atom *at = &ctx->atoms[k];
        if (at->kind == ATOM_SQRT && !fmpz_mpoly_is_fmpz(at->arg.num, mc)
            && alg_poly_has_var(num, at->var, ctx))
            sv[ns++] = at->var;
    }
    if (ns == 0) {
        part_append(pr, L, num, NULL, 0, a->den, 0);
        free(sv);
        return;
    }
    ulong *exp = hl_xmalloc((size_t)pr->nv * sizeof *exp);
    unsigned char *key = hl_xmalloc((size_t)ns);
    group *gs = NULL;
    int ng = 0;
    for (slong i = 0; i < num->length; i++) {
        fmpz_mpoly_get_term_exp_ui(exp, num, i, mc);
        for (int j = 0; j < ns; j++) {
            key[j] = exp[sv[j]] != 0;
            exp[sv[j]] = 0; /* degree <= 1 in each root (canonical form) */
        }
        int gi = 0;
        while (gi < ng && memcmp(gs[gi].key, key, (size_t)ns) != 0)
            gi++;
        if (gi == ng) {
            gs = hl_xrealloc(gs, (size_t)(ng + 1) * sizeof *gs);
            gs[ng].key = hl_xmalloc((size_t)ns);
            memcpy(gs[ng].key, key, (size_t)ns);
            gs[ng].pop = 0;
            for (int j = 0; j < ns; j++)
                gs[ng].pop += key[j];
            gs[ng].first = i;
            fmpz_mpoly_init(gs[ng].c, mc);
            ng++;
        }
        fmpz_mpoly_push_term_fmpz_ui(gs[gi].c, num->coeffs + i, exp, mc);
    }
    group **order = hl_xmalloc((size_t)ng * sizeof *order);
    for (int gi = 0; gi < ng; gi++) {
        fmpz_mpoly_sort_terms(gs[gi].c, mc);
        fmpz_mpoly_combine_like_terms(gs[gi].c, mc);
        order[gi] = &gs[gi];
    }
    qsort(order, (size_t)ng, sizeof *order, group_cmp);
    int *roots = hl_xmalloc((size_t)ns * sizeof *roots);
    for (int gi = 0; gi < ng; gi++) {
        int nr = 0;
        for (int j = 0; j < ns; j++)
            if (order[gi]->key[j])
                roots[nr++] = sv[j];
        part_append(pr, L, order[gi]->c, roots, nr, a->den, ng > 1);
    }
    for (int gi = 0; gi < ng; gi++) {
        free(gs[gi].key);
        fmpz_mpoly_clear(gs[gi].c, mc);
    }
    free(roots);
    free(order);
    free(gs);
    free(key);
    free(exp);
    free(sv);
}

static const hl_expr *frac_expr(printer *pr, const hl_alg *a)
{
    terms L = {0};
    if (fmpz_mpoly_is_fmpz(a->den, pr->mc)) {
        fmpz_t c;
        fmpz_init(c);
        fmpz_mpoly_get_fmpz(c, a->den, pr->mc);
        poly_append(pr, &L, a->num, c);
        fmpz_clear(c);
    } else {
        split_append(pr, &L, a);
    }
    const hl_expr *e = terms_join(pr, &L, 0);
    free(L.t);
    return e;
}

const hl_expr *hl_alg_to_expr(const hl_alg *a, const hl_alg_ctx *ctx, hl_pool *pool)
{
    printer pr;
    pr.ctx = ctx;
    pr.mc = ctx->mctx;
    pr.pool = pool;
    pr.nv = alg_nvars(ctx);
    pr.nu = ctx->nbase + ctx->natoms;
    pr.step = ctx->step;
    pr.atom = hl_xcalloc((size_t)ctx->natoms + 1, sizeof *pr.atom);
    pr.pow = hl_xcalloc((size_t)pr.nu * POW_MEMO_MAX + 1, sizeof *pr.pow);
    hl_buf_init(&pr.scratch);
    pr.seeded = 0;
    fmpz_mpoly_factor_init(pr.seeds, pr.mc);
    const hl_expr *e = frac_expr(&pr, a);
    fmpz_mpoly_factor_clear(pr.seeds, pr.mc);
    hl_buf_clear(&pr.scratch);
    free(pr.pow);
    free(pr.atom);
    return e;
}
