/* The batch recursion (hl_tape_batch, jit_batch.c): each lane bit for bit
 * hl_tape_taylor_ode_d of that lane's state, for every operation of the
 * rules (the formulas of t-backends.c) at 4 lanes (and every fourth at 2
 * and 8: each case is a compilation), with lanes of different states; a
 * lane whose state is outside the domain (NaN) leaves the others as they
 * were; and the long recursions of Henon-Heiles and Kepler at the
 * integrator's order for tol 1e-15, at 1, 2, 4 and 8 lanes.  (Run with
 * HL_JIT_FLAGS=-ffp-contract=fast it fails: the comparison sees one
 * contracted rounding.) */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "tape/test/hamiltonian.h"
#include "hamlie/tape.h"
#include "tape/tape_impl.h"

/* Under AddressSanitizer every compilation costs three times as much; the
 * other widths run there in the integration tests below. */
#if defined(__SANITIZE_ADDRESS__)
#define SANITIZED 1
#else
#define SANITIZED 0
#endif

static hl_pool *P;

/* equal bits, or both NaN (a NaN's payload is not the contract) */
static int same(const double *x, const double *y, int n)
{
    for (int i = 0; i < n; i++)
        if (memcmp(&x[i], &y[i], sizeof *x) != 0 && !(isnan(x[i]) && isnan(y[i])))
            return 0;
    return 1;
}

/* Every lane of a batch of t at this order against the interpreter, from
 * the states z0[l * n + i]; returns the lanes that differ. */
static int lanes_differing(hl_tape *t, int order, int lanes, const double *z0)
{
    const int n = hl_tape_ninputs(t), S = order + 1;
    hl_tape_batch *b = NULL;
    hl_error err;
    CHECK_MSG(hl_tape_batch_new(&b, t, order, lanes, &err) == HL_OK, "%s", err.msg);
    if (b == NULL)
        return -1;
    CHECK(hl_tape_batch_compiled(b) == hl_tape_jit_available());
    double *z = hl_tape_batch_coefs(b);
    CHECK(((uintptr_t)z & ((size_t)lanes * sizeof(double) - 1)) == 0); /* aligned */
    for (int l = 0; l < lanes; l++)
        for (int i = 0; i < n; i++)
            z[(size_t)i * S * lanes + l] = z0[(size_t)l * n + i];
    hl_tape_batch_ode(b);
    double *want = calloc((size_t)n * S, sizeof *want), *got = calloc((size_t)n * S, sizeof *got);
    int bad = 0;
    for (int l = 0; l < lanes; l++) {
        for (int i = 0; i < n; i++)
            want[(size_t)i * S] = z0[(size_t)l * n + i];
        CHECK(hl_tape_taylor_ode_d(want, order, t, &err) == HL_OK);
        for (int i = 0; i < n; i++)
            for (int k = 0; k < S; k++)
                got[(size_t)i * S + k] = z[((size_t)i * S + k) * lanes + l];
        bad += !same(got, want, n * S);
    }
    free(want);
    free(got);
    hl_tape_batch_free(b);
    return bad;
}

/* the formulas of t-backends.c: together every hl_op */
static const char *const cases[] = {
    "-sin(a)", "a+b",     "a-b",        "a*b",      "a/b",       "a^2",        "a+pi",
    "a-pi",    "pi-a",    "a*pi",       "a/pi",     "pi/a",      "a^(3/4)",    "sqrt(a)",
    "exp(a)",  "log(a)",  "sin(a)",     "sinh(a)",  "tan(a)",    "tanh(a)",    "atan(a)",
    "asin(a)", "acos(a)", "atan2(a,b)", "asinh(a)", "sqrt(a)*a", "a^7*b^(-3)", "cos(a)*exp(b)",
};

static void test_operations(void)
{
    const char *ab[] = {"a", "b"};
    int covered[HL_OP_COUNT] = {0};
    for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
        const hl_expr *e[2];
        hl_error err;
        CHECK_MSG(hl_parse(&e[0], P, cases[c], &err) == HL_OK, "%s", cases[c]);
        CHECK(hl_parse(&e[1], P, "a*b-1/2", &err) == HL_OK); /* square, for the ODE */
        hl_tape *t = NULL;
        CHECK_MSG(hl_tape_new(&t, e, 2, ab, 2, &err) == HL_OK, "%s: %s", cases[c], err.msg);
        if (t == NULL)
            continue;
        for (int i = 0; i < t->ncode; i++)
            covered[t->code[i].op] = 1;
        for (int lanes = 2; lanes <= 8; lanes *= 2) {
            if (lanes != 4 && (c % 4 != 0 || SANITIZED))
                continue; /* 2 and 8 lanes: the same emitter, other vector widths */
            double z0[2 * 8];
            for (int l = 0; l < lanes; l++) { /* a in (0, 1) (log, asin), b > 0 (div) */
                z0[2 * l] = 0.4 + 0.05 * l;
                z0[2 * l + 1] = 0.9 + 0.1 * l;
            }
            CHECK_MSG(lanes_differing(t, 13, lanes, z0) == 0, "%s at %d lanes", cases[c], lanes);
            z0[2] = -0.5; /* lane 1 outside log's, asin's... domain: NaN there alone */
            CHECK_MSG(lanes_differing(t, 13, lanes, z0) == 0, "%s at %d lanes, lane 1 out",
                      cases[c], lanes);
        }
        hl_tape_free(t);
    }
    for (int op = 0; op < HL_OP_COUNT; op++)
        CHECK_MSG(covered[op], "no case for %s", hl_op_name((hl_op)op));
}

/* Henon-Heiles and Kepler at order 20 (tol 1e-15 in the flow), 2, 4 and
 * 8 lanes, and 1 lane: the single recursion's degenerate batch */
static void test_systems(void)
{
    static const char *const H[] = {"(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3",
                                    "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)"};
    double z0[4 * 8], zk[4 * 8]; /* lanes of different states */
    for (int l = 0; l < 8; l++)
        for (int i = 0; i < 4; i++) {
            z0[4 * l + i] = 0.05 * ((l + 3 * i) % 7) - 0.12;
            zk[4 * l + i] = (i < 2 ? 0.4 : 0.2) + 0.13 * ((l * (i + 1)) % 5) * (i % 2 ? -1 : 1);
        }
    for (int s = 0; s < 2; s++) {
        hl_tape *t = test_hamiltonian(P, H[s], 2);
        if (t == NULL)
            continue;
        const double *z = s == 0 ? z0 : zk;
        for (int lanes = 1; lanes <= 8; lanes *= 2)
            CHECK_MSG(lanes_differing(t, 20, lanes, z) == 0, "%s, %d lanes", H[s], lanes);
        hl_tape_free(t);
    }
}

static void test_errors(void)
{
    const hl_expr *e[1], *e2[1];
    hl_error err;
    const char *a[] = {"a", "b"};
    CHECK(hl_parse(&e[0], P, "a*b", &err) == HL_OK);
    CHECK(hl_parse(&e2[0], P, "a^2", &err) == HL_OK);
    hl_tape *t = NULL, *sq = NULL;
    CHECK(hl_tape_new(&t, e, 1, a, 2, &err) == HL_OK);
    hl_tape_batch *b = (hl_tape_batch *)&err; /* set to NULL on failure */
    CHECK(hl_tape_batch_new(&b, t, 10, 4, &err) == HL_EINVAL && b == NULL);
    CHECK(strstr(err.msg, "as many outputs") != NULL);
    CHECK(hl_tape_new(&sq, e2, 1, a, 1, &err) == HL_OK);
    CHECK(hl_tape_batch_new(&b, sq, 10, 3, &err) == HL_EINVAL && b == NULL);
    CHECK(strstr(err.msg, "power of 2") != NULL);
    CHECK(hl_tape_batch_new(&b, sq, 10, 32, &err) == HL_EINVAL);
    CHECK(hl_tape_batch_new(&b, sq, -1, 4, &err) == HL_EINVAL);
    hl_tape_batch_free(NULL);
    hl_tape_free(t);
    hl_tape_free(sq);
}

int main(void)
{
    P = hl_pool_new();
    test_operations();
    test_systems();
    test_errors();
    hl_pool_free(P);
    return HL_TEST_END();
}
