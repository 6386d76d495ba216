/* Atoms and their relations: exact identities decided without the numeric
 * test, exact values, domain errors, and identities that need the numeric
 * test (and say so through the context's flag). */
#include "hamlie/alg.h"
#include "hl_test.h"

static hl_pool *pool;
static hl_alg_ctx *ctx;

/* Read s; returns the status. */
static int rd(hl_alg *r, const char *s)
{
    const hl_expr *e;
    hl_error err;
    hl_error_clear(&err);
    int st = hl_parse(&e, pool, s, &err);
    if (st != HL_OK) {
        fprintf(stderr, "parse error in '%s': %s\n", s, err.msg);
        return st;
    }
    return hl_alg_from_expr(r, e, ctx, &err);
}

/* Is s exactly zero (num == 0 after canonicalisation, no numeric test)? */
static int exact_zero(const char *s)
{
    hl_alg a;
    hl_alg_init(&a, ctx);
    hl_alg_ctx_reset_numeric_used(ctx);
    int ok = rd(&a, s) == HL_OK && fmpz_mpoly_is_zero(a.num, hl_alg_ctx_mpoly(ctx))
             && hl_alg_is_zero(&a, ctx) && !hl_alg_ctx_numeric_used(ctx)
             && hl_alg_is_canonical(&a, ctx);
    hl_alg_clear(&a, ctx);
    return ok;
}

/* Are s and t equal as elements (same num and den)? */
static int same(const char *s, const char *t)
{
    hl_alg a, b;
    hl_alg_init(&a, ctx);
    hl_alg_init(&b, ctx);
    const fmpz_mpoly_ctx_struct *mc = hl_alg_ctx_mpoly(ctx);
    int ok = rd(&a, s) == HL_OK && rd(&b, t) == HL_OK && fmpz_mpoly_equal(a.num, b.num, mc)
             && fmpz_mpoly_equal(a.den, b.den, mc) && hl_alg_is_canonical(&a, ctx);
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&b, ctx);
    return ok;
}

static int status_of(const char *s)
{
    hl_alg a;
    hl_alg_init(&a, ctx);
    int st = rd(&a, s);
    hl_alg_clear(&a, ctx);
    return st;
}

int main(void)
{
    const char *names[] = {"x", "y", "q", "p"};
    pool = hl_pool_new();
    ctx = hl_alg_ctx_new(4, names, 0);
    const fmpz_mpoly_ctx_struct *mc = hl_alg_ctx_mpoly(ctx);

    CHECK(exact_zero("sin(q)^2 + cos(q)^2 - 1"));
    CHECK(exact_zero("sin(x+y)^4 - (1 - cos(x+y)^2)^2"));
    CHECK(exact_zero("sqrt(x^2+y^2)^2 - (x^2 + y^2)"));
    CHECK(exact_zero("sqrt(x^2+y^2)^3 - (x^2 + y^2)*sqrt(x^2+y^2)"));
    CHECK(exact_zero("tan(q) - sin(q)/cos(q)"));
    CHECK(exact_zero("cosh(x)^2 - sinh(x)^2 - 1"));
    CHECK(exact_zero("tanh(x) - sinh(x)/cosh(x)"));
    CHECK(exact_zero("exp(x)*exp(-x) - 1"));
    CHECK(exact_zero("sin(-q) + sin(q)"));
    CHECK(exact_zero("cos(-q) - cos(q)"));
    CHECK(exact_zero("1/(1 + sqrt(x)) - (1 - sqrt(x))/(1 - x)"));
    CHECK(exact_zero("sqrt(1 + sqrt(x))^2 - 1 - sqrt(x)"));
    CHECK(exact_zero("1/sqrt(1 + sqrt(x)) - sqrt(1 + sqrt(x))/(1 + sqrt(x))"));
    CHECK(exact_zero("sin(sqrt(x^2+y^2))^2 + cos(sqrt(x^2+y^2))^2 - 1"));
    CHECK(exact_zero("sqrt(8) - 2*sqrt(2)"));
    CHECK(exact_zero("sqrt(4*x) - 2*sqrt(x)"));
    CHECK(exact_zero("x^(3/2) - x*sqrt(x)"));
    CHECK(exact_zero("(x^(1/3))^3 - x") && exact_zero("(x^(1/3))^4 - x*x^(1/3)"));
    CHECK(exact_zero("log(1)"));
    CHECK(exact_zero("sin(0) + cos(0) - 1 + exp(0) - 1"));
    CHECK(exact_zero("cos(pi/3) - 1/2"));
    CHECK(exact_zero("sin(pi/4) - sqrt(2)/2"));
    CHECK(exact_zero("sin(pi) + cos(pi) + 1"));
    CHECK(exact_zero("8^(1/3) - 2"));

    /* the denominator of 1/sqrt(x^2+y^2) is free of the square root */
    hl_alg a, b;
    hl_alg_init(&a, ctx);
    hl_alg_init(&b, ctx);
    CHECK(rd(&a, "1/sqrt(x^2+y^2)") == HL_OK);
    CHECK(hl_alg_ctx_natoms(ctx) > 0);
    int free_of_atoms = 1;
    for (int v = hl_alg_ctx_nbase(ctx); v < hl_alg_ctx_nbase(ctx) + hl_alg_ctx_natoms(ctx); v++)
        free_of_atoms &= fmpz_mpoly_degree_si(a.den, v, mc) <= 0;
    CHECK(free_of_atoms);
    CHECK(hl_alg_is_canonical(&a, ctx));
    /* ... and its numerator is the square root itself */
    CHECK(rd(&b, "sqrt(x^2+y^2)") == HL_OK);
    CHECK(fmpz_mpoly_equal(a.num, b.num, mc));
    CHECK(rd(&b, "x^2+y^2") == HL_OK);
    CHECK(fmpz_mpoly_equal(a.den, b.num, mc));

    /* sin(q) made twice is one atom; cos(q) with it */
    int n0 = hl_alg_ctx_natoms(ctx);
    CHECK(rd(&a, "sin(q) + cos(q) + sin(q)*cos(q)") == HL_OK);
    CHECK(hl_alg_ctx_natoms(ctx) == n0);

    /* exact constants */
    fmpq_t c;
    fmpq_init(c);
    fmpq_set_si(c, 0, 1);
    CHECK(rd(&a, "sqrt(9/4)") == HL_OK && hl_alg_is_fmpq(&a, c, ctx));
    CHECK(fmpz_equal_si(fmpq_numref(c), 3) && fmpz_equal_si(fmpq_denref(c), 2));
    CHECK(rd(&a, "sqrt(0)") == HL_OK && fmpz_mpoly_is_zero(a.num, mc));
    CHECK(same("sqrt(x/y)", "sqrt(x*y)/y"));

    /* domain errors are statuses, not aborts */
    CHECK(status_of("sqrt(-1)") == HL_EDOM);
    CHECK(status_of("log(0)") == HL_EDOM);
    CHECK(status_of("log(-2)") == HL_EDOM);
    CHECK(status_of("1/(x - x)") == HL_EDOM);
    CHECK(status_of("x/(sin(q)^2 + cos(q)^2 - 1)") == HL_EDOM);
    CHECK(status_of("asin(2)") == HL_EDOM);
    CHECK(status_of("(-4)^(1/2)") == HL_EDOM);
    CHECK(status_of("0^(-1)") == HL_EDOM);
    CHECK(status_of("tan(pi/2)") == HL_EDOM);
    CHECK(status_of("z + 1") == HL_EINVAL);

    /* the numeric test: exp(log(x)) = x needs it, and says so */
    hl_alg_ctx_reset_numeric_used(ctx);
    CHECK(rd(&a, "exp(log(x)) - x") == HL_OK);
    CHECK(!fmpz_mpoly_is_zero(a.num, mc));
    CHECK(hl_alg_is_zero(&a, ctx));
    CHECK(hl_alg_ctx_numeric_used(ctx));
    hl_alg_ctx_reset_numeric_used(ctx);
    CHECK(rd(&a, "sqrt(2)*sqrt(3) - sqrt(6)") == HL_OK);
    CHECK(hl_alg_is_zero(&a, ctx));
    CHECK(hl_alg_ctx_numeric_used(ctx));
    hl_alg_ctx_reset_numeric_used(ctx);
    CHECK(rd(&a, "sin(2*x) - 2*sin(x)*cos(x)") == HL_OK);
    CHECK(hl_alg_is_zero(&a, ctx));
    CHECK(hl_alg_ctx_numeric_used(ctx));

    /* and non-zeros are not zero */
    hl_alg_ctx_reset_numeric_used(ctx);
    CHECK(rd(&a, "sin(x) - x") == HL_OK);
    CHECK(!hl_alg_is_zero(&a, ctx));
    CHECK(rd(&a, "exp(log(x)) - x - 1/10^30") == HL_OK);
    CHECK(!hl_alg_is_zero(&a, ctx));
    CHECK(!hl_alg_ctx_numeric_used(ctx));
    CHECK(rd(&a, "sin(2*x) - sin(x)*cos(x)") == HL_OK);
    CHECK(!hl_alg_is_zero(&a, ctx));
    CHECK(rd(&b, "sin(x)") == HL_OK);

    /* the atom limit is an error */
    hl_alg_ctx *small = hl_alg_ctx_new(4, names, 2);
    hl_alg_ctx *save = ctx;
    ctx = small;
    CHECK(status_of("sin(x)") == HL_OK);
    CHECK(status_of("exp(x)") == HL_ELIMIT);
    ctx = save;
    hl_alg_ctx_free(small);

    fmpq_clear(c);
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&b, ctx);
    hl_alg_ctx_free(ctx);
    hl_pool_free(pool);
    return HL_TEST_END();
}
