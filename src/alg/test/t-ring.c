/* Field laws on random rational functions (FLINT randtest, fixed seed), with
 * and without a square-root atom, every result checked canonical. */
#include <stdlib.h>

#include "hamlie/alg.h"
#include "hl_test.h"

static hl_alg_ctx *ctx;
static flint_rand_t state;
static ulong *bounds;

/* a random rational function in the base symbols; with_atom mixes in
 * r = sqrt(x^2 + y^2 + 1) (given in r) */
static void random_elt(hl_alg *a, const hl_alg *r, int with_atom)
{
    const fmpz_mpoly_ctx_struct *mc = hl_alg_ctx_mpoly(ctx);
    hl_alg n, d;
    hl_alg_init(&n, ctx);
    hl_alg_init(&d, ctx);
    fmpz_mpoly_randtest_bounds(n.num, state, 1 + n_randint(state, 6), 10, bounds, mc);
    do
        fmpz_mpoly_randtest_bounds(d.num, state, 1 + n_randint(state, 4), 10, bounds, mc);
    while (fmpz_mpoly_is_zero(d.num, mc));
    if (with_atom) {
        hl_alg t;
        hl_alg_init(&t, ctx);
        fmpz_mpoly_randtest_bounds(t.num, state, 3, 10, bounds, mc);
        hl_alg_mul(&t, &t, r, ctx);
        hl_alg_add(&n, &n, &t, ctx);
        hl_alg_clear(&t, ctx);
    }
    hl_alg_div(a, &n, &d, ctx, NULL);
    hl_alg_clear(&n, ctx);
    hl_alg_clear(&d, ctx);
}

static int same(const hl_alg *a, const hl_alg *b)
{
    const fmpz_mpoly_ctx_struct *mc = hl_alg_ctx_mpoly(ctx);
    return fmpz_mpoly_equal(a->num, b->num, mc) && fmpz_mpoly_equal(a->den, b->den, mc);
}

int main(void)
{
    const char *names[] = {"x", "y", "z", "w"};
    ctx = hl_alg_ctx_new(4, names, 0);
    const fmpz_mpoly_ctx_struct *mc = hl_alg_ctx_mpoly(ctx);
    flint_randinit(state);
    int nv = (int)mc->minfo->nvars;
    bounds = malloc((size_t)nv * sizeof *bounds);
    for (int v = 0; v < nv; v++)
        bounds[v] = v < 4 ? 3 : 1; /* base symbols only, degree <= 2 each */

    hl_alg a, b, c, s, t, u, r;
    hl_alg_init(&a, ctx);
    hl_alg_init(&b, ctx);
    hl_alg_init(&c, ctx);
    hl_alg_init(&s, ctx);
    hl_alg_init(&t, ctx);
    hl_alg_init(&u, ctx);
    hl_alg_init(&r, ctx);
    /* r = sqrt(x^2 + y^2 + 1) */
    hl_alg_gen(&s, 0, ctx);
    hl_alg_mul(&s, &s, &s, ctx);
    hl_alg_gen(&t, 1, ctx);
    hl_alg_mul(&t, &t, &t, ctx);
    hl_alg_add(&s, &s, &t, ctx);
    hl_alg_one(&t, ctx);
    hl_alg_add(&s, &s, &t, ctx);
    CHECK(hl_alg_apply(&r, HL_SQRT, &s, ctx, NULL) == HL_OK);

    int fails[8] = {0}, noncanon = 0;
    for (int iter = 0; iter < 300; iter++) {
        int with_atom = iter % 2;
        random_elt(&a, &r, with_atom);
        random_elt(&b, &r, with_atom);
        random_elt(&c, &r, with_atom);
        noncanon += !hl_alg_is_canonical(&a, ctx) + !hl_alg_is_canonical(&b, ctx);
        /* commutativity */
        hl_alg_add(&s, &a, &b, ctx);
        hl_alg_add(&t, &b, &a, ctx);
        fails[0] += !same(&s, &t);
        noncanon += !hl_alg_is_canonical(&s, ctx);
        hl_alg_mul(&s, &a, &b, ctx);
        hl_alg_mul(&t, &b, &a, ctx);
        fails[1] += !same(&s, &t);
        noncanon += !hl_alg_is_canonical(&s, ctx);
        /* associativity */
        hl_alg_add(&s, &a, &b, ctx);
        hl_alg_add(&s, &s, &c, ctx);
        hl_alg_add(&t, &b, &c, ctx);
        hl_alg_add(&t, &a, &t, ctx);
        fails[2] += !same(&s, &t);
        hl_alg_mul(&s, &a, &b, ctx);
        hl_alg_mul(&s, &s, &c, ctx);
        hl_alg_mul(&t, &b, &c, ctx);
        hl_alg_mul(&t, &a, &t, ctx);
        fails[3] += !same(&s, &t);
        noncanon += !hl_alg_is_canonical(&s, ctx);
        /* distributivity: a (b - c) = ab - ac */
        hl_alg_sub(&s, &b, &c, ctx);
        hl_alg_mul(&s, &a, &s, ctx);
        hl_alg_mul(&t, &a, &b, ctx);
        hl_alg_mul(&u, &a, &c, ctx);
        hl_alg_sub(&t, &t, &u, ctx);
        fails[4] += !same(&s, &t);
        noncanon += !hl_alg_is_canonical(&t, ctx);
        /* a - a = 0 (aliased) */
        hl_alg_set(&s, &a, ctx);
        hl_alg_sub(&s, &s, &s, ctx);
        fails[5] += !fmpz_mpoly_is_zero(s.num, mc) || !fmpz_mpoly_is_one(s.den, mc);
        /* (a/b)*b = a, and (a^3)^-1 * a^2 = 1/a */
        if (!fmpz_mpoly_is_zero(b.num, mc)) {
            CHECK(hl_alg_div(&s, &a, &b, ctx, NULL) == HL_OK);
            noncanon += !hl_alg_is_canonical(&s, ctx);
            hl_alg_mul(&s, &s, &b, ctx);
            fails[6] += !same(&s, &a);
        }
        if (!fmpz_mpoly_is_zero(a.num, mc)) {
            CHECK(hl_alg_pow_si(&s, &a, -3, ctx, NULL) == HL_OK);
            noncanon += !hl_alg_is_canonical(&s, ctx);
            CHECK(hl_alg_pow_si(&t, &a, 2, ctx, NULL) == HL_OK);
            hl_alg_mul(&s, &s, &t, ctx);
            hl_alg_one(&t, ctx);
            CHECK(hl_alg_div(&t, &t, &a, ctx, NULL) == HL_OK);
            fails[7] += !same(&s, &t);
        }
    }
    for (int k = 0; k < 8; k++)
        CHECK_MSG(fails[k] == 0, "law %d failed %d times", k, fails[k]);
    CHECK_MSG(noncanon == 0, "%d results not canonical", noncanon);

    /* division by zero is a status */
    hl_error err;
    hl_alg_zero(&b, ctx);
    CHECK(hl_alg_div(&s, &a, &b, ctx, &err) == HL_EDOM);
    CHECK(hl_alg_pow_si(&s, &b, -1, ctx, &err) == HL_EDOM);

    /* integer contents cancel: (2x)/(4y) = x/(2y), with den lc > 0 */
    hl_alg_gen(&a, 0, ctx);
    fmpq_t q;
    fmpq_init(q);
    fmpq_set_si(q, 2, 1);
    hl_alg_scalar_mul_fmpq(&a, &a, q, ctx);
    hl_alg_gen(&b, 1, ctx);
    fmpq_set_si(q, -4, 1);
    hl_alg_scalar_mul_fmpq(&b, &b, q, ctx);
    CHECK(hl_alg_div(&s, &a, &b, ctx, NULL) == HL_OK);
    CHECK(hl_alg_is_canonical(&s, ctx));
    CHECK(s.num->length == 1 && fmpz_equal_si(s.num->coeffs + 0, -1));
    CHECK(s.den->length == 1 && fmpz_equal_si(s.den->coeffs + 0, 2));
    /* scalar_mul by 1/2 then 2 is the identity */
    random_elt(&a, &r, 1);
    fmpq_set_si(q, 1, 2);
    hl_alg_scalar_mul_fmpq(&s, &a, q, ctx);
    CHECK(hl_alg_is_canonical(&s, ctx));
    fmpq_set_si(q, 2, 1);
    hl_alg_scalar_mul_fmpq(&s, &s, q, ctx);
    CHECK(same(&s, &a));
    fmpq_clear(q);

    hl_alg_clear(&a, ctx);
    hl_alg_clear(&b, ctx);
    hl_alg_clear(&c, ctx);
    hl_alg_clear(&s, ctx);
    hl_alg_clear(&t, ctx);
    hl_alg_clear(&u, ctx);
    hl_alg_clear(&r, ctx);
    free(bounds);
    flint_randclear(state);
    hl_alg_ctx_free(ctx);
    return HL_TEST_END();
}
