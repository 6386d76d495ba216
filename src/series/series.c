/* Truncated power series with exact coefficients: memory and the ring
 * operations.  Products are the plain O(n^2) Cauchy product: coefficients are
 * rational functions whose cost dwarfs any saving a faster product would
 * bring at the orders used (n ~ 10). */
#include <stdlib.h>

#include "base/buf.h"
#include "series/series_impl.h"

/* ---- memory ---------------------------------------------------------------- */

static void reserve(hl_series *s, int n, const hl_alg_ctx *ctx)
{
    if (n <= s->alloc)
        return;
    s->c = hl_xrealloc(s->c, (size_t)n * sizeof(hl_alg));
    for (int k = s->alloc; k < n; k++)
        hl_alg_init(&s->c[k], ctx);
    s->alloc = n;
}

void hl_series_init(hl_series *s, int n, const hl_alg_ctx *ctx)
{
    s->c = NULL;
    s->n = 0;
    s->alloc = 0;
    hl_series_zero(s, n, ctx);
}

void hl_series_clear(hl_series *s, const hl_alg_ctx *ctx)
{
    for (int k = 0; k < s->alloc; k++)
        hl_alg_clear(&s->c[k], ctx);
    free(s->c);
    s->c = NULL;
    s->n = s->alloc = 0;
}

void hl_series_set_length(hl_series *s, int n, const hl_alg_ctx *ctx)
{
    if (n < 0)
        n = 0;
    reserve(s, n, ctx);
    for (int k = s->n; k < n; k++)
        hl_alg_zero(&s->c[k], ctx);
    s->n = n;
}

void hl_series_zero(hl_series *r, int n, const hl_alg_ctx *ctx)
{
    r->n = 0;
    hl_series_set_length(r, n, ctx);
}

void hl_series_set(hl_series *r, const hl_series *a, const hl_alg_ctx *ctx)
{
    if (r == a)
        return;
    reserve(r, a->n, ctx);
    for (int k = 0; k < a->n; k++)
        hl_alg_set(&r->c[k], &a->c[k], ctx);
    r->n = a->n;
}

void hl_series_swap(hl_series *a, hl_series *b)
{
    hl_series t = *a;
    *a = *b;
    *b = t;
}

void hl_series_set_alg(hl_series *r, const hl_alg *a, int n, const hl_alg_ctx *ctx)
{
    hl_alg t; /* a may be one of r's coefficients */
    hl_alg_init(&t, ctx);
    hl_alg_set(&t, a, ctx);
    hl_series_zero(r, n, ctx);
    if (n > 0)
        hl_alg_swap(&r->c[0], &t, ctx);
    hl_alg_clear(&t, ctx);
}

void hl_series_set_var(hl_series *r, const hl_alg *a, int n, const hl_alg_ctx *ctx)
{
    hl_series_set_alg(r, a, n, ctx);
    if (n > 1)
        hl_alg_one(&r->c[1], ctx);
}

/* ---- predicates ------------------------------------------------------------ */

int hl_series_valuation(const hl_series *a, hl_alg_ctx *ctx)
{
    int k = 0;
    while (k < a->n && hl_alg_is_zero(&a->c[k], ctx))
        k++;
    return k;
}

int hl_series_is_zero(const hl_series *a, hl_alg_ctx *ctx)
{
    return hl_series_valuation(a, ctx) == a->n;
}

int hl_series_equal(const hl_series *a, const hl_series *b, hl_alg_ctx *ctx)
{
    int n = a->n < b->n ? a->n : b->n;
    for (int k = 0; k < n; k++)
        if (!hl_alg_equal(&a->c[k], &b->c[k], ctx))
            return 0;
    return 1;
}

/* ---- ring operations --------------------------------------------------------- */

static int min2(int a, int b)
{
    return a < b ? a : b;
}

void hl_series_add(hl_series *r, const hl_series *a, const hl_series *b, hl_alg_ctx *ctx)
{
    int n = min2(a->n, b->n);
    reserve(r, n, ctx);
    for (int k = 0; k < n; k++)
        hl_alg_add(&r->c[k], &a->c[k], &b->c[k], ctx);
    r->n = n;
}

void hl_series_sub(hl_series *r, const hl_series *a, const hl_series *b, hl_alg_ctx *ctx)
{
    int n = min2(a->n, b->n);
    reserve(r, n, ctx);
    for (int k = 0; k < n; k++)
        hl_alg_sub(&r->c[k], &a->c[k], &b->c[k], ctx);
    r->n = n;
}

void hl_series_neg(hl_series *r, const hl_series *a, hl_alg_ctx *ctx)
{
    reserve(r, a->n, ctx);
    for (int k = 0; k < a->n; k++)
        hl_alg_neg(&r->c[k], &a->c[k], ctx);
    r->n = a->n;
}

void hl_series_mul(hl_series *r, const hl_series *a, const hl_series *b, hl_alg_ctx *ctx)
{
    int n = min2(a->n, b->n);
    hl_series t;
    hl_alg p;
    hl_series_init(&t, n, ctx);
    hl_alg_init(&p, ctx);
    for (int i = 0; i < n; i++) {
        if (series_trivially_zero(&a->c[i], ctx))
            continue; /* sparse inputs (D, constants) are common */
        for (int j = 0; i + j < n; j++) {
            hl_alg_mul(&p, &a->c[i], &b->c[j], ctx);
            hl_alg_add(&t.c[i + j], &t.c[i + j], &p, ctx);
        }
    }
    hl_alg_clear(&p, ctx);
    hl_series_swap(r, &t);
    hl_series_clear(&t, ctx);
}

hl_status hl_series_div(hl_series *r, const hl_series *a, const hl_series *b, hl_alg_ctx *ctx,
                        hl_error *err)
{
    int n = min2(a->n, b->n);
    if (n == 0) {
        hl_series_zero(r, 0, ctx);
        return HL_OK;
    }
    if (hl_alg_is_zero(&b->c[0], ctx))
        return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                            "division by a series that vanishes at D = 0");
    hl_series q;
    hl_alg inv, s, p;
    hl_series_init(&q, n, ctx);
    hl_alg_init(&inv, ctx);
    hl_alg_init(&s, ctx);
    hl_alg_init(&p, ctx);
    hl_alg_one(&inv, ctx);
    int status = hl_alg_div(&inv, &inv, &b->c[0], ctx, err);
    /* q_k = (a_k - sum_{j=1..k} b_j q_{k-j}) / b_0 */
    for (int k = 0; status == HL_OK && k < n; k++) {
        hl_alg_set(&s, &a->c[k], ctx);
        for (int j = 1; j <= k; j++) {
            if (series_trivially_zero(&b->c[j], ctx))
                continue;
            hl_alg_mul(&p, &b->c[j], &q.c[k - j], ctx);
            hl_alg_sub(&s, &s, &p, ctx);
        }
        hl_alg_mul(&q.c[k], &s, &inv, ctx);
    }
    if (status == HL_OK)
        hl_series_swap(r, &q);
    hl_series_clear(&q, ctx);
    hl_alg_clear(&inv, ctx);
    hl_alg_clear(&s, ctx);
    hl_alg_clear(&p, ctx);
    return status;
}

void hl_series_scalar_mul(hl_series *r, const hl_series *a, const hl_alg *c, hl_alg_ctx *ctx)
{
    hl_alg t; /* c may be one of r's or a's coefficients */
    hl_alg_init(&t, ctx);
    hl_alg_set(&t, c, ctx);
    reserve(r, a->n, ctx);
    for (int k = 0; k < a->n; k++)
        hl_alg_mul(&r->c[k], &a->c[k], &t, ctx);
    r->n = a->n;
    hl_alg_clear(&t, ctx);
}

void hl_series_scalar_mul_fmpq(hl_series *r, const hl_series *a, const fmpq_t c, hl_alg_ctx *ctx)
{
    reserve(r, a->n, ctx);
    for (int k = 0; k < a->n; k++)
        hl_alg_scalar_mul_fmpq(&r->c[k], &a->c[k], c, ctx);
    r->n = a->n;
}

hl_status hl_series_pow_si(hl_series *r, const hl_series *a, long e, hl_alg_ctx *ctx, hl_error *err)
{
    hl_series base, acc;
    int status = HL_OK;
    hl_series_init(&base, 0, ctx);
    hl_series_init(&acc, a->n, ctx);
    if (a->n > 0)
        hl_alg_one(&acc.c[0], ctx);
    hl_series_set(&base, a, ctx);
    if (e < 0) {
        hl_series one;
        hl_series_init(&one, a->n, ctx);
        if (a->n > 0)
            hl_alg_one(&one.c[0], ctx);
        status = hl_series_div(&base, &one, a, ctx, err);
        hl_series_clear(&one, ctx);
    }
    /* |e| by binary powering; -(LONG_MIN) is taken bit by bit, no overflow */
    unsigned long u = e < 0 ? 0UL - (unsigned long)e : (unsigned long)e;
    while (status == HL_OK && u != 0) {
        if (u & 1)
            hl_series_mul(&acc, &acc, &base, ctx);
        u >>= 1;
        if (u != 0)
            hl_series_mul(&base, &base, &base, ctx);
    }
    if (status == HL_OK)
        hl_series_swap(r, &acc);
    hl_series_clear(&base, ctx);
    hl_series_clear(&acc, ctx);
    return status;
}

/* ---- calculus in D ------------------------------------------------------------ */

void hl_series_derivative(hl_series *r, const hl_series *a, hl_alg_ctx *ctx)
{
    int n = a->n > 0 ? a->n - 1 : 0;
    hl_series t;
    hl_series_init(&t, n, ctx);
    for (int k = 0; k < n; k++) {
        fmpq_t c;
        fmpq_init(c);
        fmpq_set_si(c, k + 1, 1);
        hl_alg_scalar_mul_fmpq(&t.c[k], &a->c[k + 1], c, ctx);
        fmpq_clear(c);
    }
    hl_series_swap(r, &t);
    hl_series_clear(&t, ctx);
}

void hl_series_reflect(hl_series *r, const hl_series *a, hl_alg_ctx *ctx)
{
    hl_series_set(r, a, ctx);
    for (int k = 1; k < r->n; k += 2)
        hl_alg_neg(&r->c[k], &r->c[k], ctx);
}

void hl_series_shift(hl_series *r, const hl_series *a, int k, hl_alg_ctx *ctx)
{
    hl_series t;
    hl_series_init(&t, a->n + k, ctx);
    for (int i = 0; i < a->n; i++)
        hl_alg_set(&t.c[i + k], &a->c[i], ctx);
    hl_series_swap(r, &t);
    hl_series_clear(&t, ctx);
}

hl_series *hl_series_vec_new(int m, int n, const hl_alg_ctx *ctx)
{
    hl_series *s = hl_xmalloc((size_t)m * sizeof *s);
    for (int i = 0; i < m; i++)
        hl_series_init(&s[i], n, ctx);
    return s;
}

void hl_series_vec_free(hl_series *s, int m, const hl_alg_ctx *ctx)
{
    if (s == NULL)
        return;
    for (int i = 0; i < m; i++)
        hl_series_clear(&s[i], ctx);
    free(s);
}
