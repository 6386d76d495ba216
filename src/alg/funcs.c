/* Functions of elements: each becomes an atom after the simplifications that
 * keep the canonical form small and unique (odd/even symmetry, exact values,
 * square factors pulled out of square roots). */
#include <stdlib.h>

#include "alg/alg_internal.h"
#include <flint/fmpz_factor.h>
#include "base/buf.h"

#define MAX_POW_EXP 100000

/* The sign convention: a is "negative" when num's leading coefficient is. */
static int is_negative(const hl_alg *a)
{
    return a->num->length > 0 && fmpz_sgn(a->num->coeffs + 0) < 0;
}

static int const_sgn(const hl_alg *a, const hl_alg_ctx *ctx)
{
    if (!fmpz_mpoly_is_fmpz(a->num, ctx->mctx) || !fmpz_mpoly_is_fmpz(a->den, ctx->mctx))
        return 2; /* not a constant */
    return a->num->length == 0 ? 0 : fmpz_sgn(a->num->coeffs + 0);
}

static int atom_value(hl_alg *r, alg_atom_kind kind, long q, const hl_alg *arg,
                      hl_alg_ctx *ctx, hl_error *err)
{
    int v;
    int status = alg_atom_get(&v, kind, q, arg, ctx, err);
    if (status == HL_OK)
        alg_set_var(r, v, ctx);
    return status;
}

hl_status hl_alg_pi(hl_alg *r, hl_alg_ctx *ctx, hl_error *err)
{
    return atom_value(r, ATOM_PI, 0, NULL, ctx, err);
}

/* c = s^2 t with t free of squares (for |c| < 2^128; larger ones keep t = c). */
static void square_part(fmpz_t s, fmpz_t t, const fmpz_t c)
{
    fmpz_one(s);
    fmpz_set(t, c);
    if (fmpz_bits(c) > 128 || fmpz_is_zero(c))
        return;
    fmpz_factor_t fac;
    fmpz_factor_init(fac);
    fmpz_factor(fac, c);
    fmpz_t pk;
    fmpz_init(pk);
    for (slong i = 0; i < fac->num; i++) {
        fmpz_pow_ui(pk, fac->p + i, fac->exp[i] / 2);
        fmpz_mul(s, s, pk);
    }
    fmpz_mul(pk, s, s);
    fmpz_divexact(t, c, pk);
    fmpz_clear(pk);
    fmpz_factor_clear(fac);
}

/* r = s * sqrt(u) / d for a polynomial u != 0; takes the square part of
 * the content out, and a perfect square u out entirely. */
static int sqrt_poly(hl_alg *r, const fmpz_mpoly_t u0, const fmpz_mpoly_t d, hl_alg_ctx *ctx,
                     hl_error *err)
{
    const fmpz_mpoly_ctx_struct *mc = ctx->mctx;
    fmpz_t c, s, t;
    fmpz_mpoly_t u, w;
    hl_alg arg, res;
    fmpz_init(c);
    fmpz_init(s);
    fmpz_init(t);
    fmpz_mpoly_init(u, mc);
    fmpz_mpoly_init(w, mc);
    hl_alg_init(&arg, ctx);
    hl_alg_init(&res, ctx);
    fmpz_mpoly_set(u, u0, mc);
    _fmpz_vec_content(c, u->coeffs, u->length);
    square_part(s, t, c);
    fmpz_mul(c, s, s);
    fmpz_mpoly_scalar_divexact_fmpz(u, u, c, mc);
    int status = HL_OK;
    if (fmpz_mpoly_sqrt(w, u, mc)) {
        if (w->length > 0 && fmpz_sgn(w->coeffs + 0) < 0)
            fmpz_mpoly_neg(w, w, mc);
        fmpz_mpoly_swap(res.num, w, mc);
    } else {
        alg_set_poly(&arg, u, ctx);
        status = atom_value(&res, ATOM_SQRT, 0, &arg, ctx, err);
    }
    if (status == HL_OK) {
        fmpz_mpoly_scalar_mul_fmpz(res.num, res.num, s, mc);
        fmpz_mpoly_set(res.den, d, mc);
        alg_canonicalise(&res, ctx);
        hl_alg_swap(r, &res, ctx);
    }
    fmpz_clear(c);
    fmpz_clear(s);
    fmpz_clear(t);
    fmpz_mpoly_clear(u, mc);
    fmpz_mpoly_clear(w, mc);
    hl_alg_clear(&arg, ctx);
    hl_alg_clear(&res, ctx);
    return status;
}

static int alg_sqrt(hl_alg *r, const hl_alg *a, hl_alg_ctx *ctx, hl_error *err)
{
    int sg = const_sgn(a, ctx);
    if (sg == 0) {
        hl_alg_zero(r, ctx);
        return HL_OK;
    }
    if (sg < 0)
        return hl_error_set(err, HL_EDOM, NULL, -1, 0, "square root of a negative number");
    /* sqrt(n/d) = sqrt(n d)/d */
    fmpz_mpoly_t u, d;
    fmpz_mpoly_init(u, ctx->mctx);
    fmpz_mpoly_init(d, ctx->mctx);
    fmpz_mpoly_mul(u, a->num, a->den, ctx->mctx);
    alg_reduce(u, ctx);
    fmpz_mpoly_set(d, a->den, ctx->mctx);
    int status = sqrt_poly(r, u, d, ctx, err);
    fmpz_mpoly_clear(u, ctx->mctx);
    fmpz_mpoly_clear(d, ctx->mctx);
    return status;
}

/* q-th root, q >= 3: (n/d)^(1/q) = (n d^(q-1))^(1/q) / d. */
static int alg_root(hl_alg *r, const hl_alg *a, long q, hl_alg_ctx *ctx, hl_error *err)
{
    const fmpz_mpoly_ctx_struct *mc = ctx->mctx;
    int sg = const_sgn(a, ctx);
    if (sg == 0) {
        hl_alg_zero(r, ctx);
        return HL_OK;
    }
    if (sg < 0 && q % 2 == 0)
        return hl_error_set(err, HL_EDOM, NULL, -1, 0, "even root of a negative number");
    int status = alg_check_pow_size(a, (unsigned long)(q - 1), ctx, err); /* den^(q-1) */
    if (status != HL_OK)
        return status;
    hl_alg arg, res;
    hl_alg_init(&arg, ctx);
    hl_alg_init(&res, ctx);
    fmpz_mpoly_pow_ui(arg.num, a->den, (ulong)(q - 1), mc);
    fmpz_mpoly_mul(arg.num, arg.num, a->num, mc);
    int neg = sg < 0;
    if (neg)
        fmpz_mpoly_neg(arg.num, arg.num, mc);
    alg_reduce(arg.num, ctx);
    fmpz_t m, rt;
    fmpz_init(m);
    fmpz_init(rt);
    if (sg == 1 || sg == -1) {
        fmpz_mpoly_get_fmpz(m, arg.num, mc);
        if (fmpz_root(rt, m, q) && (fmpz_pow_ui(m, rt, (ulong)q), 1)
            && fmpz_mpoly_equal_fmpz(arg.num, m, mc))
            fmpz_mpoly_set_fmpz(res.num, rt, mc);
        else
            status = atom_value(&res, ATOM_ROOT, q, &arg, ctx, err);
    } else {
        status = atom_value(&res, ATOM_ROOT, q, &arg, ctx, err);
    }
    if (status == HL_OK) {
        if (neg)
            fmpz_mpoly_neg(res.num, res.num, mc);
        fmpz_mpoly_set(res.den, a->den, mc);
        alg_canonicalise(&res, ctx);
        hl_alg_swap(r, &res, ctx);
    }
    fmpz_clear(m);
    fmpz_clear(rt);
    hl_alg_clear(&arg, ctx);
    hl_alg_clear(&res, ctx);
    return status;
}

hl_status hl_alg_pow_fmpq(hl_alg *r, const hl_alg *a, const fmpq_t e, hl_alg_ctx *ctx,
                          hl_error *err)
{
    const fmpz *p = fmpq_numref(e), *q = fmpq_denref(e);
    if (!fmpz_fits_si(p) || labs(fmpz_get_si(p)) > MAX_POW_EXP || !fmpz_fits_si(q)
        || fmpz_get_si(q) > MAX_POW_EXP) {
        if (const_sgn(a, ctx) == 0 && fmpz_sgn(p) > 0) {
            hl_alg_zero(r, ctx);
            return HL_OK;
        }
        if (hl_alg_is_fmpq(a, NULL, ctx) && fmpz_mpoly_is_one(a->num, ctx->mctx)
            && fmpz_mpoly_is_one(a->den, ctx->mctx)) {
            hl_alg_one(r, ctx);
            return HL_OK;
        }
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0, "exponent too large");
    }
    long pn = fmpz_get_si(p), qn = fmpz_get_si(q);
    if (qn == 1)
        return hl_alg_pow_si(r, a, pn, ctx, err);
    if (const_sgn(a, ctx) == 0)
        return pn > 0 ? (hl_alg_zero(r, ctx), HL_OK)
                      : hl_error_set(err, HL_EDOM, NULL, -1, 0, "division by zero");
    hl_alg b;
    hl_alg_init(&b, ctx);
    int status = qn == 2 ? alg_sqrt(&b, a, ctx, err) : alg_root(&b, a, qn, ctx, err);
    if (status == HL_OK)
        status = hl_alg_pow_si(r, &b, pn, ctx, err);
    hl_alg_clear(&b, ctx);
    return status;
}

/* ---- exp and log ---------------------------------------------------------- */

static int alg_exp(hl_alg *r, const hl_alg *a, hl_alg_ctx *ctx, hl_error *err)
{
    if (fmpz_mpoly_is_zero(a->num, ctx->mctx)) {
        hl_alg_one(r, ctx);
        return HL_OK;
    }
    if (!is_negative(a))
        return atom_value(r, ATOM_EXP, 0, a, ctx, err);
    hl_alg m, e;
    hl_alg_init(&m, ctx);
    hl_alg_init(&e, ctx);
    hl_alg_neg(&m, a, ctx);
    int status = atom_value(&e, ATOM_EXP, 0, &m, ctx, err);
    if (status == HL_OK)
        status = hl_alg_pow_si(r, &e, -1, ctx, err);
    hl_alg_clear(&m, ctx);
    hl_alg_clear(&e, ctx);
    return status;
}

static int alg_log(hl_alg *r, const hl_alg *a, hl_alg_ctx *ctx, hl_error *err)
{
    int sg = const_sgn(a, ctx);
    if (sg == 0 || sg == -1)
        return hl_error_set(err, HL_EDOM, NULL, -1, 0, "logarithm of %s",
                            sg == 0 ? "zero" : "a negative number");
    if (fmpz_mpoly_is_one(a->num, ctx->mctx) && fmpz_mpoly_is_one(a->den, ctx->mctx)) {
        hl_alg_zero(r, ctx);
        return HL_OK;
    }
    return atom_value(r, ATOM_LOG, 0, a, ctx, err);
}

/* sinh, cosh, tanh from E = exp(a). */
static int hyperbolic(hl_alg *r, hl_fun f, const hl_alg *a, hl_alg_ctx *ctx, hl_error *err)
{
    hl_alg e, ei, t, u;
    hl_alg_init(&e, ctx);
    hl_alg_init(&ei, ctx);
    hl_alg_init(&t, ctx);
    hl_alg_init(&u, ctx);
    int status = alg_exp(&e, a, ctx, err);
    if (status == HL_OK)
        status = hl_alg_pow_si(&ei, &e, -1, ctx, err);
    if (status == HL_OK) {
        fmpq_t half;
        fmpq_init(half);
        fmpq_set_si(half, 1, 2);
        hl_alg_sub(&t, &e, &ei, ctx); /* 2 sinh */
        hl_alg_add(&u, &e, &ei, ctx); /* 2 cosh */
        if (f == HL_SINH)
            hl_alg_scalar_mul_fmpq(r, &t, half, ctx);
        else if (f == HL_COSH)
            hl_alg_scalar_mul_fmpq(r, &u, half, ctx);
        else
            status = hl_alg_div(r, &t, &u, ctx, err);
        fmpq_clear(half);
    }
    hl_alg_clear(&e, ctx);
    hl_alg_clear(&ei, ctx);
    hl_alg_clear(&t, ctx);
    hl_alg_clear(&u, ctx);
    return status;
}

/* ---- trigonometric ----------------------------------------------------------- */

/* If a = (k/12) pi for an integer k, set *k and return 1. */
static int pi_twelfths(long *k, const hl_alg *a, const hl_alg_ctx *ctx)
{
    const fmpz_mpoly_ctx_struct *mc = ctx->mctx;
    if (a->num->length != 1 || !fmpz_mpoly_is_fmpz(a->den, mc))
        return 0;
    int pv = -1;
    for (int j = 0; j < ctx->natoms; j++)
        if (ctx->atoms[j].kind == ATOM_PI)
            pv = ctx->atoms[j].var;
    if (pv < 0 || fmpz_mpoly_total_degree_si(a->num, mc) != 1
        || fmpz_mpoly_degree_si(a->num, pv, mc) != 1)
        return 0;
    fmpz_t t, d;
    fmpz_init(t);
    fmpz_init(d);
    fmpz_mul_ui(t, a->num->coeffs + 0, 12);
    fmpz_mpoly_get_fmpz(d, a->den, mc);
    int ok = fmpz_divisible(t, d);
    if (ok) {
        fmpz_divexact(t, t, d);
        *k = (long)fmpz_fdiv_ui(t, 24);
    }
    fmpz_clear(t);
    fmpz_clear(d);
    return ok;
}

/* sin(k pi/12) for the k where it is a rational times sqrt(1, 2 or 3). */
static int sin_twelfths(hl_alg *r, long k, hl_alg_ctx *ctx, hl_error *err)
{
    static const int tab[12][3] = {{0, 1, 1}, {-1}, {1, 2, 1}, {1, 2, 2}, {1, 2, 3}, {-1},
                                   {1, 1, 1}, {-1}, {1, 2, 3}, {1, 2, 2}, {1, 2, 1}, {-1}};
    long j = ((k % 24) + 24) % 24;
    const int *e = tab[j % 12];
    if (e[0] < 0)
        return -1; /* not a known value */
    hl_alg s;
    hl_alg_init(&s, ctx);
    hl_alg_set_si(&s, e[2], ctx);
    int status = e[2] == 1 ? HL_OK : alg_sqrt(&s, &s, ctx, err);
    if (status == HL_OK) {
        fmpq_t c;
        fmpq_init(c);
        fmpq_set_si(c, j >= 12 ? -e[0] : e[0], (ulong)e[1]);
        hl_alg_scalar_mul_fmpq(r, &s, c, ctx);
        fmpq_clear(c);
    }
    hl_alg_clear(&s, ctx);
    return status;
}

/* If a = s atan2(y, x) (s = +-1, the atom alone), its atom; else NULL. */
static const alg_atom *signed_atan2(int *s, const hl_alg *a, const hl_alg_ctx *ctx)
{
    const fmpz_mpoly_ctx_struct *mc = ctx->mctx;
    if (a->num->length != 1 || !fmpz_mpoly_is_one(a->den, mc) ||
        fmpz_mpoly_total_degree_si(a->num, mc) != 1 || !fmpz_is_pm1(a->num->coeffs))
        return NULL;
    for (int k = 0; k < ctx->natoms; k++)
        if (ctx->atoms[k].kind == ATOM_ATAN2 &&
            fmpz_mpoly_degree_si(a->num, ctx->atoms[k].var, mc) == 1) {
            *s = fmpz_sgn(a->num->coeffs);
            return &ctx->atoms[k];
        }
    return NULL;
}

/* sin and cos of s atan2(y, x): s y/r and x/r, r = sqrt(x^2 + y^2). */
static int sincos_atan2(hl_alg *r, int want_cos, int s, const alg_atom *at, hl_alg_ctx *ctx,
                        hl_error *err)
{
    hl_alg rad, t;
    hl_alg_init(&rad, ctx);
    hl_alg_init(&t, ctx);
    hl_alg_mul(&rad, &at->arg, &at->arg, ctx);
    hl_alg_mul(&t, &at->arg2, &at->arg2, ctx);
    hl_alg_add(&rad, &rad, &t, ctx);
    hl_alg_set(&t, want_cos ? &at->arg2 : &at->arg, ctx);
    int status = alg_sqrt(&rad, &rad, ctx, err);
    if (status == HL_OK)
        status = hl_alg_div(r, &t, &rad, ctx, err);
    if (status == HL_OK && s < 0 && !want_cos)
        hl_alg_neg(r, r, ctx);
    hl_alg_clear(&rad, ctx);
    hl_alg_clear(&t, ctx);
    return status;
}

static int alg_sincos(hl_alg *r, int want_cos, const hl_alg *a, hl_alg_ctx *ctx, hl_error *err)
{
    int s;
    const alg_atom *at = signed_atan2(&s, a, ctx);
    if (at != NULL)
        return sincos_atan2(r, want_cos, s, at, ctx, err);
    if (fmpz_mpoly_is_zero(a->num, ctx->mctx)) {
        hl_alg_set_si(r, want_cos, ctx);
        return HL_OK;
    }
    long k;
    if (pi_twelfths(&k, a, ctx)) {
        int status = sin_twelfths(r, want_cos ? k + 6 : k, ctx, err);
        if (status >= 0)
            return status;
    }
    int neg = is_negative(a);
    hl_alg m;
    hl_alg_init(&m, ctx);
    hl_alg_set(&m, a, ctx);
    if (neg)
        hl_alg_neg(&m, &m, ctx);
    int status = atom_value(r, want_cos ? ATOM_COS : ATOM_SIN, 0, &m, ctx, err);
    if (status == HL_OK && neg && !want_cos)
        hl_alg_neg(r, r, ctx);
    hl_alg_clear(&m, ctx);
    return status;
}

/* atan and asin are odd; acos(-u) = pi - acos(u) is left alone. */
static int alg_odd_atom(hl_alg *r, alg_atom_kind kind, const hl_alg *a, hl_alg_ctx *ctx,
                        hl_error *err)
{
    if (fmpz_mpoly_is_zero(a->num, ctx->mctx)) {
        hl_alg_zero(r, ctx);
        return HL_OK;
    }
    if (!is_negative(a))
        return atom_value(r, kind, 0, a, ctx, err);
    hl_alg m;
    hl_alg_init(&m, ctx);
    hl_alg_neg(&m, a, ctx);
    int status = atom_value(r, kind, 0, &m, ctx, err);
    if (status == HL_OK)
        hl_alg_neg(r, r, ctx);
    hl_alg_clear(&m, ctx);
    return status;
}

/* |a| > 1 for a constant a? */
static int outside_unit(const hl_alg *a, const hl_alg_ctx *ctx)
{
    fmpq_t c;
    fmpq_init(c);
    int out = hl_alg_is_fmpq(a, c, ctx) && fmpz_cmpabs(fmpq_numref(c), fmpq_denref(c)) > 0;
    fmpq_clear(c);
    return out;
}

/* asinh u = log(u + sqrt(u^2 + 1)) for every real u: the algebra keeps no
 * atom of its own for asinh, so its relations to log and sqrt come free. */
static int alg_asinh(hl_alg *r, const hl_alg *a, hl_alg_ctx *ctx, hl_error *err)
{
    hl_alg w, one;
    hl_alg_init(&w, ctx);
    hl_alg_init(&one, ctx);
    hl_alg_one(&one, ctx);
    hl_alg_mul(&w, a, a, ctx);
    hl_alg_add(&w, &w, &one, ctx);
    int status = alg_sqrt(&w, &w, ctx, err);
    if (status == HL_OK) {
        hl_alg_add(&w, &w, a, ctx);
        status = alg_log(r, &w, ctx, err);
    }
    hl_alg_clear(&w, ctx);
    hl_alg_clear(&one, ctx);
    return status;
}

hl_status hl_alg_apply(hl_alg *r, hl_fun f, const hl_alg *a, hl_alg_ctx *ctx, hl_error *err)
{
    hl_alg s, c;
    int status;
    switch (f) {
    case HL_SIN: return alg_sincos(r, 0, a, ctx, err);
    case HL_COS: return alg_sincos(r, 1, a, ctx, err);
    case HL_TAN:
        hl_alg_init(&s, ctx);
        hl_alg_init(&c, ctx);
        status = alg_sincos(&s, 0, a, ctx, err);
        if (status == HL_OK)
            status = alg_sincos(&c, 1, a, ctx, err);
        if (status == HL_OK)
            status = hl_alg_div(r, &s, &c, ctx, err);
        hl_alg_clear(&s, ctx);
        hl_alg_clear(&c, ctx);
        return status;
    case HL_EXP: return alg_exp(r, a, ctx, err);
    case HL_LOG: return alg_log(r, a, ctx, err);
    case HL_SQRT: return alg_sqrt(r, a, ctx, err);
    case HL_ATAN: return alg_odd_atom(r, ATOM_ATAN, a, ctx, err);
    case HL_ASIN:
    case HL_ACOS:
        if (outside_unit(a, ctx))
            return hl_error_set(err, HL_EDOM, NULL, -1, 0, "%s of a number outside [-1, 1]",
                                hl_fun_name(f));
        if (f == HL_ASIN)
            return alg_odd_atom(r, ATOM_ASIN, a, ctx, err);
        if (fmpz_mpoly_is_zero(a->num, ctx->mctx)) { /* acos 0 = pi/2 */
            fmpq_t h;
            fmpq_init(h);
            fmpq_set_si(h, 1, 2);
            status = hl_alg_pi(r, ctx, err);
            if (status == HL_OK)
                hl_alg_scalar_mul_fmpq(r, r, h, ctx);
            fmpq_clear(h);
            return status;
        }
        return atom_value(r, ATOM_ACOS, 0, a, ctx, err);
    case HL_SINH:
    case HL_COSH:
    case HL_TANH: return hyperbolic(r, f, a, ctx, err);
    case HL_ASINH: return alg_asinh(r, a, ctx, err);
    case HL_ATAN2: return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "'atan2' takes two arguments");
    default: return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "unknown function");
    }
}

/* pi * num/den */
static int pi_times(hl_alg *r, long num, ulong den, hl_alg_ctx *ctx, hl_error *err)
{
    int status = hl_alg_pi(r, ctx, err);
    if (status == HL_OK) {
        fmpq_t c;
        fmpq_init(c);
        fmpq_set_si(c, num, den);
        hl_alg_scalar_mul_fmpq(r, r, c, ctx);
        fmpq_clear(c);
    }
    return status;
}

/* atan2(y, x) for a constant x: atan(y/x), plus pi sgn(y) for x < 0 where
 * y is a constant too; x = 0 gives pi/2 sgn(y).  Returns -1 where neither
 * applies. */
static int atan2_const_x(hl_alg *r, const hl_alg *y, const hl_alg *x, hl_alg_ctx *ctx,
                         hl_error *err)
{
    int sx = const_sgn(x, ctx), sy = const_sgn(y, ctx);
    if (sx == 2 || (sx <= 0 && sy == 2))
        return -1;
    if (sx == 0 && sy == 0)
        return hl_error_set(err, HL_EDOM, NULL, -1, 0, "atan2(0, 0) is undefined");
    if (sx == 0)
        return pi_times(r, sy, 2, ctx, err);
    hl_alg t, c;
    hl_alg_init(&t, ctx);
    hl_alg_init(&c, ctx);
    int status = hl_alg_div(&t, y, x, ctx, err);
    if (status == HL_OK)
        status = alg_odd_atom(r, ATOM_ATAN, &t, ctx, err);
    if (status == HL_OK && sx < 0) /* y = 0, x < 0: pi, the upper side of the cut */
        status = pi_times(&c, sy < 0 ? -1 : 1, 1, ctx, err);
    if (status == HL_OK && sx < 0)
        hl_alg_add(r, r, &c, ctx);
    hl_alg_clear(&t, ctx);
    hl_alg_clear(&c, ctx);
    return status;
}

/* atan2(y, x), odd in y: -atan2(-y, x) for a "negative" y. */
static int alg_atan2(hl_alg *r, const hl_alg *y, const hl_alg *x, hl_alg_ctx *ctx, hl_error *err)
{
    int status = atan2_const_x(r, y, x, ctx, err);
    if (status >= 0)
        return status;
    if (!is_negative(y)) {
        int v;
        status = alg_atom_get2(&v, ATOM_ATAN2, 0, y, x, ctx, err);
        if (status == HL_OK)
            alg_set_var(r, v, ctx);
        return status;
    }
    hl_alg m;
    hl_alg_init(&m, ctx);
    hl_alg_neg(&m, y, ctx);
    status = alg_atan2(r, &m, x, ctx, err);
    if (status == HL_OK)
        hl_alg_neg(r, r, ctx);
    hl_alg_clear(&m, ctx);
    return status;
}

hl_status hl_alg_apply2(hl_alg *r, hl_fun f, const hl_alg *a, const hl_alg *b, hl_alg_ctx *ctx,
                        hl_error *err)
{
    if (f != HL_ATAN2)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "'%s' takes one argument",
                            hl_fun_name(f));
    return alg_atan2(r, a, b, ctx, err);
}

hl_status hl_alg_pow(hl_alg *r, const hl_alg *a, const hl_alg *b, hl_alg_ctx *ctx, hl_error *err)
{
    fmpq_t e;
    fmpq_init(e);
    int status;
    if (hl_alg_is_fmpq(b, e, ctx)) {
        status = hl_alg_pow_fmpq(r, a, e, ctx, err);
    } else {
        hl_alg l;
        hl_alg_init(&l, ctx);
        status = alg_log(&l, a, ctx, err);
        if (status == HL_OK) {
            hl_alg_mul(&l, &l, b, ctx);
            status = alg_exp(r, &l, ctx, err);
        }
        hl_alg_clear(&l, ctx);
    }
    fmpq_clear(e);
    return status;
}
