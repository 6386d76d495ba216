/* The cost model (cost.c): when compiling pays.  The break-evens are those
 * the drivers used before the model was one function, so the choices of a
 * run do not change: hl_tape_jit for evaluations, 25 ms + 0.1 ms per
 * instruction against 2.4 ns saved per instruction; the fused loop of
 * hamlie run, 50 ns more a step; the flow's compiled recursion, a million
 * steps; the compiled Newton solve, a million solves.  Also: the answer
 * flips exactly at the break-even, a longer tape breaks even sooner, a
 * loop sooner than plain evaluations, and nothing without instructions or
 * without a tape.  Without libgccjit, hl_tape_jit never pays. */
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>

#include "hl_test.h"
#include "hamlie/tape.h"

static const char *const xu[] = {"x", "u"};

static hl_tape *tape_of(hl_pool *P, const hl_expr **e, int nout, int nin)
{
    hl_tape *t = NULL;
    hl_error err;
    CHECK(hl_tape_new(&t, e, nout, xu, nin, &err) == HL_OK);
    return t;
}

/* x sin(x) wrapped n times in exp(. x): 2 + 2n instructions */
static hl_tape *chain(hl_pool *P, int n)
{
    const hl_expr *x = hl_sym(P, "x");
    const hl_expr *e = hl_mul(P, x, hl_call(P, HL_SIN, x));
    for (int i = 0; i < n; i++)
        e = hl_call(P, HL_EXP, hl_mul(P, e, x));
    return tape_of(P, &e, 1, 1);
}

static void check_flip(const hl_tape *t, hl_compile_kind kind)
{
    long b = hl_tape_compile_breakeven(t, kind);
    CHECK_MSG(b > 0 && b < LONG_MAX, "kind %d: break-even %ld", (int)kind, b);
    CHECK(hl_tape_compile_pays(t, kind, b));
    CHECK(!hl_tape_compile_pays(t, kind, b - 1));
}

static void test_jit(hl_pool *P)
{
    hl_tape *t2 = chain(P, 0), *t42 = chain(P, 20), *t0 = NULL;
    const hl_expr *x = hl_sym(P, "x");
    t0 = tape_of(P, &x, 1, 1);
    CHECK(hl_tape_nops(t2) == 2 && hl_tape_nops(t42) == 42);
    if (!hl_tape_jit_available()) {
        CHECK(hl_tape_compile_breakeven(t2, HL_COMPILE_EVAL) == LONG_MAX);
        CHECK(!hl_tape_compile_pays(t2, HL_COMPILE_LOOP, LONG_MAX));
        printf("t-cost: no libgccjit, hl_tape_jit never pays\n");
    } else {
        for (int i = 0; i < 2; i++) {
            hl_tape *t = i ? t42 : t2;
            double n = hl_tape_nops(t);
            long eval = hl_tape_compile_breakeven(t, HL_COMPILE_EVAL);
            long loop = hl_tape_compile_breakeven(t, HL_COMPILE_LOOP);
            CHECK_MSG(eval == (long)((25e6 + 1e5 * n) / (2.4 * n)), "%g ops: eval %ld", n, eval);
            CHECK_MSG(loop == (long)((25e6 + 1e5 * n) / (50 + 2.4 * n)), "%g ops: loop %ld", n,
                      loop);
            CHECK(loop < eval);
            CHECK(hl_tape_jit_breakeven(t) == eval);
            check_flip(t, HL_COMPILE_EVAL);
            check_flip(t, HL_COMPILE_LOOP);
        }
        CHECK(hl_tape_compile_breakeven(t42, HL_COMPILE_EVAL) <
              hl_tape_compile_breakeven(t2, HL_COMPILE_EVAL));
    }
    /* no instructions: nothing to save, never */
    CHECK(hl_tape_compile_breakeven(t0, HL_COMPILE_EVAL) == LONG_MAX);
    CHECK(hl_tape_compile_breakeven(t0, HL_COMPILE_TAYLOR) == LONG_MAX);
    CHECK(!hl_tape_compile_pays(t0, HL_COMPILE_EVAL, LONG_MAX));
    CHECK(!hl_tape_compile_pays(NULL, HL_COMPILE_EVAL, LONG_MAX));
    hl_tape_free(t0);
    hl_tape_free(t2);
    hl_tape_free(t42);
}

/* The recursion: a million steps, whatever the tape (and with or without
 * libgccjit: hl_tape_native also has the system compiler). */
static void test_taylor(hl_pool *P)
{
    hl_tape *t2 = chain(P, 0), *t42 = chain(P, 20);
    CHECK(hl_tape_compile_breakeven(t2, HL_COMPILE_TAYLOR) == 1000000);
    CHECK(hl_tape_compile_breakeven(t42, HL_COMPILE_TAYLOR) == 1000000);
    check_flip(t42, HL_COMPILE_TAYLOR);
    hl_tape_free(t2);
    hl_tape_free(t42);
}

/* Newton on u - x = 0: pays from a million solves, with libgccjit. */
static void test_newton(hl_pool *P)
{
    const hl_expr *x = hl_sym(P, "x"), *u = hl_sym(P, "u");
    const hl_expr *f = hl_sub(P, u, x), *fj[2] = {f, hl_num_si(P, 1)};
    hl_tape *start = tape_of(P, &x, 1, 1), *F = tape_of(P, &f, 1, 2), *FJ = tape_of(P, fj, 2, 2);
    hl_newton *nw = NULL;
    hl_error err;
    CHECK(hl_newton_new(&nw, start, F, FJ, 10, &err) == HL_OK);
    int can = hl_tape_jit_available();
    CHECK(hl_newton_compile_pays(nw, 1000000) == can);
    CHECK(!hl_newton_compile_pays(nw, 999999));
    CHECK(!hl_newton_compile_pays(NULL, LONG_MAX));
    hl_newton_free(nw);
    hl_tape_free(start);
    hl_tape_free(F);
    hl_tape_free(FJ);
}

int main(void)
{
    /* the model alone: a kept or keepable compilation changes the answer
     * (t-jit_cache tests that) */
    setenv("HAMLIE_CACHE", "off", 1);
    hl_pool *P = hl_pool_new();
    test_jit(P);
    test_taylor(P);
    test_newton(P);
    hl_pool_free(P);
    return HL_TEST_END();
}
