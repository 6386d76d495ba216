/* The compiled recursion (libgccjit) against the interpreter, bit for bit
 * (memcmp), at every coefficient up to order 16, where t-backends stops at
 * order 12: convolutions of every length from 0 to 20 terms (every count
 * of terms left over rule.h's four lanes; squares long enough to have
 * several), each op with a convolution negated and not (jit_taylor.c folds
 * a negation into a known factor: (-a) c = a (-c), the ODE step's
 * fma(-s, h, z) = fma(s, -h, z)), from a state and from zeros of both
 * signs, so that a zero of the wrong sign would show; and the ODEs of the
 * benchmark (the pendulum and Kepler; Henon-Heiles's products are among
 * the ops).  Skipped (passes with a note) without libgccjit.  Six
 * compilations in all, some 0.2 s of CPU each: the CI has little time. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/tape.h"
#include "tape/tape_impl.h"

#define ORDER 16
#if defined(__SANITIZE_ADDRESS__)
#define SANITIZED 1 /* two compilations, not six: the CI's time */
#else
#define SANITIZED 0
#endif
#define NV 4
#define NSTATES 2

static const char *const vars[NV] = {"x", "y", "u", "v"};
static hl_pool *P;

static const hl_expr *sym(const char *s)
{
    return hl_sym(P, s);
}
static const hl_expr *num(long p, long q)
{
    return hl_num_frac(P, p, q);
}

/* z' = f(z) from each state of z0: the interpreter's coefficients and the
 * compiled code's; 1 when all have the same bits, 0 when not, -1 when
 * skipped */
static int same_bits(const hl_expr *const f[NV], const double z0[NSTATES][NV], const char *what)
{
    hl_tape *t = NULL;
    hl_error err;
    CHECK_MSG(hl_tape_new(&t, f, NV, vars, NV, &err) == HL_OK, "%s: %s", what, err.msg);
    const int S = ORDER + 1;
    double a[NSTATES][NV * (ORDER + 1)] = {{0}}, b[NSTATES][NV * (ORDER + 1)] = {{0}};
    for (int s = 0; s < NSTATES; s++)
        for (int i = 0; i < NV; i++)
            a[s][i * S] = b[s][i * S] = z0[s][i];
    hl_tape_native_clear(t);
    for (int s = 0; s < NSTATES; s++)
        CHECK(hl_tape_taylor_ode_d(a[s], ORDER, t, &err) == HL_OK);
    int st = hl_tape_native(t, ORDER, &err);
    if (st == HL_EUNSUP) {
        printf("skipped: %s\n", err.msg);
        hl_tape_free(t);
        return -1;
    }
    CHECK_MSG(st == HL_OK, "%s: native: %s", what, err.msg);
    int ok = 1;
    for (int s = 0; s < NSTATES; s++) {
        CHECK(hl_tape_taylor_ode_d(b[s], ORDER, t, &err) == HL_OK);
        int first = -1;
        for (int i = 0; i < NV * S && first < 0; i++)
            if (memcmp(&a[s][i], &b[s][i], sizeof a[s][i]) != 0)
                first = i;
        int at = first < 0 ? 0 : first;
        CHECK_MSG(first < 0, "%s, state %d: coefficient %d of z%d: interpreter %.17g, native %.17g",
                  what, s, at % S, at / S, a[s][at], b[s][at]);
        ok &= first < 0;
    }
    hl_tape_free(t);
    return ok;
}

/* two systems of bench/work_precision.c (the pendulum with a fourth
 * component), the pendulum from a state and from rest */
static void benchmark_systems(void)
{
    const hl_expr *x = sym("x"), *y = sym("y"), *u = sym("u"), *v = sym("v");
    const hl_expr *r2 = hl_add(P, hl_mul(P, x, x), hl_mul(P, y, y));
    const hl_expr *r3 = hl_mul(P, hl_call(P, HL_SQRT, r2), r2);
    const hl_expr *pend[NV] = {u, hl_neg(P, hl_call(P, HL_SIN, x)), hl_num_si(P, 0), v};
    const hl_expr *kepler[NV] = {u, v, hl_neg(P, hl_div(P, x, r3)), hl_neg(P, hl_div(P, y, r3))};
    const double z[NSTATES][NV] = {{1.3, 0.4, -0.2, 0.7}, {0, -0.0, 0, -0.0}}; /* and at rest */
    const double kz[NSTATES][NV] = {{0.5, 0, 0, 1.7320508075688772}, {-1, 0.25, -0.5, 0.75}};
    if (same_bits(pend, z, "pendulum") < 0)
        return;
    if (!SANITIZED)
        same_bits(kepler, kz, "Kepler");
}

/* every op with a convolution, negated and not, two at a time */
static void convolution_ops(void)
{
    const hl_expr *x = sym("x"), *y = sym("y"), *u = sym("u"), *v = sym("v");
    const hl_expr *pos = hl_add(P, hl_num_si(P, 2), hl_mul(P, y, y));
    const hl_expr *e[] = {
        hl_mul(P, x, u),
        hl_neg(P, hl_mul(P, x, x)),
        hl_div(P, u, pos),
        hl_div(P, num(-3, 7), pos),
        hl_pow(P, pos, num(-3, 2)),
        hl_neg(P, hl_pow(P, pos, num(1, 3))),
        hl_mul(P, hl_call(P, HL_SQRT, pos), pos),
        hl_call(P, HL_SQRT, pos),
        hl_neg(P, hl_call(P, HL_EXP, hl_mul(P, num(1, 3), x))),
        hl_call(P, HL_LOG, pos),
        hl_neg(P, hl_call(P, HL_COS, x)),
        hl_mul(P, hl_call(P, HL_SINH, u), num(-1, 5)),
        hl_call(P, HL_TAN, hl_mul(P, num(1, 4), x)),
        hl_call(P, HL_ATAN, u),
        hl_neg(P, hl_call(P, HL_ASIN, hl_mul(P, num(1, 4), x))),
        hl_div(P, hl_neg(P, v), num(3, 1)),
    };
    const int n = (int)(sizeof e / sizeof *e);
    const double z[NSTATES][NV] = {{0.3, -0.4, 0.2, -0.6}, {-0.0, 0, -0.0, 0}};
    int step = SANITIZED ? n : NV; /* under the sanitizers the first tape alone */
    for (int i = 0; i + NV <= n; i += step) { /* four ops a tape: z' = (e_i, ..., e_i+3) */
        char what[48];
        snprintf(what, sizeof what, "ops %d to %d", i, i + NV - 1);
        if (same_bits(&e[i], z, what) < 0)
            return;
    }
}

int main(void)
{
    P = hl_pool_new();
    unsetenv("HL_CC"); /* libgccjit, the back end under test */
    benchmark_systems();
    convolution_ops();
    hl_pool_free(P);
    flint_cleanup();
    return HL_TEST_END();
}
