/* hl_tape_native: the compiled Taylor-ODE recursion gives the interpreter's
 * coefficients, on tapes that use every op; and the exact oscillator series.
 * Run twice: through libgccjit (the default where hamlie has it) and through
 * the system compiler ($HL_CC = cc).  A backend that cannot run is skipped
 * (passes with a note). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/tape.h"
#include "tape/tape_impl.h"
#include "rules/rule.h"

static const char *const vars[] = {"x", "y", "z"};
static hl_pool *P;

static unsigned long rng = 777;
static unsigned rnd(unsigned n)
{
    rng = rng * 6364136223846793005UL + 1442695040888963407UL;
    return (unsigned)(rng >> 33) % n;
}

/* Each op at least once over the outputs, with arguments kept in domain
 * (and sqrt(w) w, which the compiled recursions take as w^(3/2)). */
static const hl_expr *op_expr(int which)
{
    const hl_expr *x = hl_sym(P, "x"), *y = hl_sym(P, "y"), *z = hl_sym(P, "z");
    const hl_expr *one = hl_num_si(P, 1), *two = hl_num_si(P, 2), *pi = hl_pi(P);
    const hl_expr *pos = hl_add(P, one, hl_pow(P, y, two));
    const hl_expr *sx = hl_call(P, HL_SIN, x), *half = hl_div(P, sx, two);
    switch (which % 17) {
    case 0: return hl_sub(P, hl_mul(P, x, y), hl_div(P, z, pos));
    case 1: return hl_add(P, hl_sub(P, pi, x), hl_div(P, hl_sub(P, y, pi), pi));
    case 2: return hl_div(P, pi, pos);
    case 3: return hl_pow(P, pos, hl_num_frac(P, -3, 2));
    case 4: return hl_call(P, HL_SQRT, pos);
    case 5: return hl_call(P, HL_EXP, half);
    case 6: return hl_call(P, HL_LOG, pos);
    case 7: return hl_add(P, sx, hl_call(P, HL_COS, z));
    case 8: return hl_call(P, HL_TAN, half);
    case 9: return hl_call(P, HL_TANH, y);
    case 10: return hl_call(P, HL_ATAN, z);
    case 11: return hl_call(P, HL_ASIN, half);
    case 12: return hl_call(P, HL_ACOS, half);
    case 13: return hl_mul(P, hl_call(P, HL_SINH, half), hl_call(P, HL_COSH, half));
    case 14: return hl_pow(P, x, hl_num_si(P, 5));
    case 16: return hl_div(P, x, hl_mul(P, hl_call(P, HL_SQRT, pos), pos)); /* Kepler's x/r^3 */
    default: return hl_neg(P, hl_mul(P, hl_pow(P, pos, x), pi)); /* non-constant exponent */
    }
}

static int compare(hl_tape *t, int order, const double *z0)
{
    const int S = order + 1;
    double *a = calloc(3 * (size_t)S, sizeof *a), *b = calloc(3 * (size_t)S, sizeof *b);
    for (int i = 0; i < 3; i++)
        a[i * S] = b[i * S] = z0[i];
    hl_error err;
    hl_tape_native_clear(t);
    hl_tape_taylor_ode_d(a, order, t, &err);
    int st = hl_tape_native(t, order, &err);
    if (st == HL_EUNSUP) {
        printf("skipped: %s\n", err.msg);
        free(a);
        free(b);
        return -1;
    }
    CHECK_MSG(st == HL_OK, "native: %s", err.msg);
    hl_tape_taylor_ode_d(b, order, t, &err);
    int bad = 0;
    for (int k = 0; k <= order; k++) {
        double scale = 0;
        for (int i = 0; i < 3; i++)
            scale = fmax(scale, fabs(a[i * S + k]));
        for (int i = 0; i < 3; i++)
            if (!(fabs(a[i * S + k] - b[i * S + k]) <= 1e-12 * scale))
                bad++;
    }
    free(a);
    free(b);
    return bad;
}

static void suite(void)
{
    /* the exact series first: oscillator x' = y, y' = -x (z' = 0) */
    {
        const hl_expr *f[3] = {hl_sym(P, "y"), hl_neg(P, hl_sym(P, "x")), hl_num_si(P, 0)};
        hl_tape *t = NULL;
        hl_error err;
        CHECK(hl_tape_new(&t, f, 3, vars, 3, &err) == HL_OK);
        int st = hl_tape_native(t, 20, &err);
        if (st == HL_EUNSUP) {
            printf("skipped: %s\n", err.msg);
            hl_tape_free(t);
            return;
        }
        CHECK_MSG(st == HL_OK, "%s", err.msg);
        double z[63] = {0};
        z[0] = 1;
        CHECK(hl_tape_taylor_ode_d(z, 20, t, &err) == HL_OK);
        double fact = 1;
        int bad = 0;
        for (int k = 0; k <= 20; k++) {
            fact *= k ? k : 1;
            double want = k % 2 ? 0 : ((k / 2) % 2 ? -1 : 1) / fact; /* cos t */
            if (fabs(z[k] - want) > 1e-15 * fabs(want))
                bad++;
        }
        CHECK_MSG(bad == 0, "native oscillator: %d coefficients wrong", bad);
        hl_tape_free(t);
    }
    /* every op: three outputs from the table, native vs interpreter */
    for (int trial = 0; trial < 6; trial++) {
        const hl_expr *f[3];
        for (int i = 0; i < 3; i++)
            f[i] = op_expr(3 * trial + i);
        if (trial == 5) /* and a mix */
            f[0] = hl_add(P, op_expr(rnd(16)), hl_mul(P, op_expr(rnd(16)), op_expr(rnd(16))));
        hl_tape *t = NULL;
        hl_error err;
        CHECK(hl_tape_new(&t, f, 3, vars, 3, &err) == HL_OK);
        double z0[3] = {0.3, -0.4, 0.2};
        int bad = compare(t, 12, z0);
        CHECK_MSG(bad <= 0, "trial %d: %d coefficients differ", trial, bad);
        hl_tape_free(t);
    }
}

/* The compiled recursions divide by k+1 as fma(f, hi, f lo) with
 * hl_rule_recip_split's hi + lo = 1/n: the quotient rounded once, i.e. the
 * division's bits, for n = 1..1000 and 200 random f each (a miss is
 * possible only within 2^-105 of a rounding boundary: none expected). */
static void test_recip_split(void)
{
    int miss = 0;
    for (int n = 1; n <= 1000; n++) {
        double hi, lo;
        hl_rule_recip_split(&hi, &lo, n);
        CHECK(hi == 1.0 / n && fabs(lo) <= 0x1p-53 * hi);
        for (int r = 0; r < 200; r++) {
            double f = ldexp((double)(rnd(1u << 30) + 1) / (1u << 30), (int)rnd(200) - 100);
            if (rnd(2))
                f = -f;
            miss += fma(f, hi, f * lo) != f / n;
        }
    }
    CHECK_MSG(miss == 0, "%d quotients differ from the division", miss);
}

int main(void)
{
    test_recip_split();
    P = hl_pool_new();
    unsetenv("HL_CC");
    printf("libgccjit%s\n", hl_tape_jit_available() ? "" : " (not built in: the system compiler)");
    suite();
    setenv("HL_CC", "cc", 1);
    printf("the system compiler\n");
    suite();
    hl_pool_free(P);
    flint_cleanup();
    return HL_TEST_END();
}
