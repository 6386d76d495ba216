/* Random expressions in x, p and D (fixed seed): the Taylor-mode series
 * against the exact coefficients (d/dD)^k f |_{D=0} / k! computed by the
 * algebra layer alone (hl_alg_diff in D, then hl_alg_subst D = 0).  The
 * expressions stay inside the domains (divisions by 2 + u^2, log(1 + u^2),
 * sqrt(1 + u^2)), but have shared subterms and every function. */
#include "sr.h"

enum { VX, VP, VD };
#define N 5

static unsigned long long seed = 0x5eed5e7u;
static unsigned rnd(unsigned m)
{
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return (unsigned)((seed >> 33) % m);
}

static const hl_expr *gen(int depth, const hl_expr **shared, int *nshared)
{
    const hl_expr *sq, *u;
    if (depth == 0 || rnd(5) == 0) {
        switch (rnd(5)) {
        case 0:
            return hl_sym(pool, "x");
        case 1:
            return hl_sym(pool, "p");
        case 2:
            return hl_sym(pool, "D");
        case 3:
            return hl_num_frac(pool, (long)rnd(7) - 3, 1 + rnd(3));
        default:
            return *nshared ? shared[rnd((unsigned)*nshared)] : hl_sym(pool, "D");
        }
    }
    const hl_expr *a = gen(depth - 1, shared, nshared), *r;
    switch (rnd(14)) {
    case 0:
        r = hl_add(pool, a, gen(depth - 1, shared, nshared));
        break;
    case 1:
        r = hl_sub(pool, a, gen(depth - 1, shared, nshared));
        break;
    case 2:
        r = hl_mul(pool, a, gen(depth - 1, shared, nshared));
        break;
    case 3: /* a / (2 + b^2) */
        u = gen(depth - 1, shared, nshared);
        r = hl_div(pool, a, hl_add(pool, hl_num_si(pool, 2), hl_mul(pool, u, u)));
        break;
    case 4:
        r = hl_pow(pool, a, hl_num_si(pool, 2 + (long)rnd(2)));
        break;
    case 5:
        r = hl_neg(pool, a);
        break;
    case 6:
        r = hl_call(pool, HL_SIN, a);
        break;
    case 7:
        r = hl_call(pool, HL_COS, a);
        break;
    case 8:
        r = hl_call(pool, HL_EXP, a);
        break;
    case 9:
        r = hl_call(pool, HL_ATAN, a);
        break;
    case 10:
        sq = hl_add(pool, hl_num_si(pool, 1), hl_mul(pool, a, a));
        r = hl_call(pool, rnd(2) ? HL_SQRT : HL_LOG, sq);
        break;
    case 11:
        r = hl_call(pool, HL_TANH, a);
        break;
    case 12:
        r = hl_call(pool, rnd(2) ? HL_SINH : HL_COSH, a);
        break;
    default:
        sq = hl_add(pool, hl_num_si(pool, 3), hl_mul(pool, a, a));
        r = hl_pow(pool, sq, hl_num_frac(pool, rnd(2) ? -1 : 1, 2 + rnd(2)));
        break;
    }
    if (*nshared < 16)
        shared[(*nshared)++] = r;
    return r;
}

/* One expression in a fresh context (atoms would pile up across them).
 * Returns 0 if the algebra layer could not read it. */
static int checked; /* coefficients compared */

static int one(const hl_expr *e)
{
    const char *names[] = {"x", "p", "D"};
    ctx = hl_alg_ctx_new(3, names, 64);
    hl_series vals[3], s;
    hl_alg g, a, d, w, zero;
    hl_error err;
    for (int i = 0; i < 3; i++)
        hl_series_init(&vals[i], 0, ctx);
    hl_series_init(&s, 0, ctx);
    hl_alg_init(&g, ctx);
    hl_alg_init(&a, ctx);
    hl_alg_init(&d, ctx);
    hl_alg_init(&w, ctx);
    hl_alg_init(&zero, ctx);
    hl_alg_gen(&g, VX, ctx);
    hl_series_set_alg(&vals[VX], &g, N, ctx);
    hl_alg_gen(&g, VP, ctx);
    hl_series_set_alg(&vals[VP], &g, N, ctx);
    hl_series_set_var(&vals[VD], &zero, N, ctx);

    int usable = hl_alg_from_expr(&a, e, ctx, &err) == HL_OK;
    if (!usable)
        fprintf(stderr, "skipped: %s\n", err.msg);
    char *txt = hl_expr_print(e, HL_STYLE_TEXT);
    int st = usable ? hl_series_eval_expr(&s, e, 3, names, vals, N, ctx, &err) : HL_OK;
    CHECK_MSG(st == HL_OK, "%s: %s", txt, st ? err.msg : "");
    fmpq_t c;
    fmpq_init(c);
    hl_alg_set(&d, &a, ctx);
    long fact = 1;
    /* the oracle's derivatives can grow huge (50000 terms at D^3 for some
     * nested atoms): stop comparing an expression there */
    for (int k = 0; usable && st == HL_OK && k < N && hl_alg_length(&d, ctx) < 4000; k++) {
        int vd = VD;
        CHECK(hl_alg_subst(&w, &d, 1, &vd, &zero, ctx, &err) == HL_OK);
        fact *= k > 0 ? k : 1;
        fmpq_set_si(c, 1, (ulong)fact);
        hl_alg_scalar_mul_fmpq(&w, &w, c, ctx);
        CHECK_MSG(hl_alg_equal(&s.c[k], &w, ctx), "%s at D^%d", txt, k);
        checked++;
        CHECK(hl_alg_diff(&d, &d, VD, ctx, &err) == HL_OK);
    }
    fmpq_clear(c);
    free(txt);
    for (int i = 0; i < 3; i++)
        hl_series_clear(&vals[i], ctx);
    hl_series_clear(&s, ctx);
    hl_alg_clear(&g, ctx);
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&d, ctx);
    hl_alg_clear(&w, ctx);
    hl_alg_clear(&zero, ctx);
    hl_alg_ctx_free(ctx);
    return usable;
}

int main(void)
{
    pool = hl_pool_new();
    int tried = 0;
    for (int t = 0; t < 100; t++) {
        const hl_expr *shared[16];
        int nshared = 0;
        tried += one(gen(4, shared, &nshared));
    }
    CHECK_MSG(tried >= 80, "only %d expressions were usable", tried);
    CHECK_MSG(checked >= 400, "only %d coefficients compared", checked);
    printf("%d expressions, %d coefficients compared\n", tried, checked);
    hl_pool_free(pool);
    flint_cleanup();
    return HL_TEST_END();
}
