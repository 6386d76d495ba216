/* The harmonic oscillator H = (p^2 + x^2)/2 (paper §3.2):
 *   g = p d/dx - x d/dp;  g^k x cycles x, p, -x, -p;
 *   exp(D g) x = x cos D + p sin D, so the order-n Lie series of x is the
 *   Taylor polynomial sum_{2k<=n} (-1)^k D^{2k}/(2k)! x
 *                  + sum_{2k+1<=n} (-1)^k D^{2k+1}/(2k+1)! p,
 * with the factorials computed here, independently of lie.c. */
#include "ham_test.h"

static void test_generator(hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg xi, eta;
    hl_alg_init(&xi, ctx), hl_alg_init(&eta, ctx);
    CHECK(hl_generator(&xi, &eta, sys, NULL) == HL_OK);
    CHECK(eq_formula(&xi, sys, "p"));
    CHECK(eq_formula(&eta, sys, "-x"));
    hl_alg_clear(&xi, ctx), hl_alg_clear(&eta, ctx);
}

static void test_cycle(hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    const char *want[4] = {"x", "p", "-x", "-p"};
    int order = 13;
    hl_alg *t = hl_alg_vec_new(order + 1, ctx), x;
    hl_alg_init(&x, ctx);
    rd(&x, sys, "x");
    CHECK(hl_lie_terms(t, &x, order, sys, NULL) == HL_OK);
    for (int k = 0; k <= order; k++)
        CHECK_MSG(eq_formula(&t[k], sys, want[k % 4]), "g^%d x", k);
    hl_alg_vec_free(t, order + 1, ctx);
    hl_alg_clear(&x, ctx);
}

/* Taylor polynomial of x cos D + p sin D to D^n, built term by term. */
static void taylor(hl_alg *r, int n, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg x, p, Dk, t;
    fmpz_t fact;
    fmpq_t c;
    hl_alg_init(&x, ctx), hl_alg_init(&p, ctx), hl_alg_init(&Dk, ctx), hl_alg_init(&t, ctx);
    fmpz_init(fact);
    fmpq_init(c);
    rd(&x, sys, "x");
    rd(&p, sys, "p");
    hl_alg_one(&Dk, ctx);
    hl_alg_zero(r, ctx);
    fmpz_one(fact);
    for (int k = 0; k <= n; k++) {
        if (k > 0) {
            fmpz_mul_ui(fact, fact, (ulong)k);
            rd(&t, sys, "D");
            hl_alg_mul(&Dk, &Dk, &t, ctx);
        }
        /* cos D = sum (-1)^j D^{2j}/(2j)!, sin D = sum (-1)^j D^{2j+1}/(2j+1)! */
        int j = k / 2;
        fmpq_set_si(c, 1, 1);
        fmpq_div_fmpz(c, c, fact); /* 1/k! */
        if (j % 2)
            fmpq_neg(c, c);
        hl_alg_mul(&t, &Dk, k % 2 ? &p : &x, ctx);
        hl_alg_scalar_mul_fmpq(&t, &t, c, ctx);
        hl_alg_add(r, r, &t, ctx);
    }
    hl_alg_clear(&x, ctx), hl_alg_clear(&p, ctx), hl_alg_clear(&Dk, ctx), hl_alg_clear(&t, ctx);
    fmpz_clear(fact);
    fmpq_clear(c);
}

static void test_series(hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg x, s, w;
    hl_alg_init(&x, ctx), hl_alg_init(&s, ctx), hl_alg_init(&w, ctx);
    rd(&x, sys, "x");
    for (int n = 0; n <= 16; n++) {
        CHECK(hl_lie_series(&s, &x, n, sys, NULL) == HL_OK);
        taylor(&w, n, sys);
        CHECK_MSG(hl_alg_equal(&s, &w, ctx), "series of x to order %d", n);
    }
    /* a hand-written one, to pin the convention: x + D p - D^2/2 x - D^3/6 p */
    CHECK(hl_lie_series(&s, &x, 3, sys, NULL) == HL_OK);
    CHECK(eq_formula(&s, sys, "x + D*p - D^2*x/2 - D^3*p/6"));
    hl_alg_clear(&x, ctx), hl_alg_clear(&s, ctx), hl_alg_clear(&w, ctx);
}

static void test_limits(hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg x, s;
    hl_error err;
    hl_alg_init(&x, ctx), hl_alg_init(&s, ctx);
    rd(&x, sys, "x");
    hl_error_clear(&err);
    CHECK(hl_lie_series(&s, &x, HL_LIE_MAX_ORDER + 1, sys, &err) == HL_ELIMIT);
    CHECK(strstr(err.msg, "200") != NULL);
    CHECK(hl_lie_series(&s, &x, -1, sys, &err) == HL_EINVAL);
    hl_alg_clear(&x, ctx), hl_alg_clear(&s, ctx);
}

int main(void)
{
    hl_system *sys = sys_new("(p^2 + x^2)/2", NULL);
    CHECK_STR(hl_system_coord(sys, 0), "x");
    CHECK_STR(hl_system_momentum(sys, 0), "p");
    test_generator(sys);
    test_cycle(sys);
    test_series(sys);
    test_limits(sys);
    hl_system_free(sys);
    return HL_TEST_END();
}
