/* hl_tape_jit: the tape's double evaluation compiled by libgccjit gives
 * bitwise the interpreter's results.  Random tapes over x, y, z (the
 * generator of t-eval.c: every opcode is reached, and the test checks that
 * it is), evaluated at random points by the interpreter, then by the
 * compiled code, compared bit for bit; the compiled code is also checked
 * against an independent recursive evaluator from libm (so it cannot be
 * the interpreter in disguise).  Also: constant prologues and outputs that
 * are inputs or constants, in == out, a tape without inputs, clearing, and
 * the failure path (a bad compiler option: HL_EUNSUP, interpreter intact).
 * Built without libgccjit, the test checks HL_EUNSUP and passes with a note. */
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/tape.h"

#include "tape_gen.h"

static int same_bits(const double *a, const double *b, int n)
{
    return memcmp(a, b, (size_t)n * sizeof *a) == 0;
}

/* ops seen in the bodies of the tapes that were compiled */
static int seen[HL_OP_COUNT];

static void note_ops(const hl_tape *t)
{
    char *s = hl_tape_print(t), *body = strstr(s, "body:\n");
    for (int op = 0; op < HL_OP_COUNT && body; op++) {
        char pat[32];
        snprintf(pat, sizeof pat, " = %s r", hl_op_name((hl_op)op));
        if (strstr(body, pat))
            seen[op] = 1;
    }
    free(s);
}

/* Under AddressSanitizer a compilation costs three times as much
 * (libgccjit's allocations go through the sanitizer's allocator) and the
 * memory checks need each path once, not 150 random tapes. */
#if defined(__SANITIZE_ADDRESS__)
#define RANDOM_TRIALS 40
#else
#define RANDOM_TRIALS 150
#endif

static void test_random(void)
{
    hl_pool *P = hl_pool_new();
    int bad = 0, badref = 0, total = 0, failed = 0;
    long iter_total = 0;
    for (int trial = 0; trial < RANDOM_TRIALS; trial++) {
        const hl_expr *outs[3];
        for (int j = 0; j < 3; j++)
            outs[j] = gen(P, 1 + rnd(4));
        if (trial == 0) /* w^(3/2) is rare in gen's draws: every run compiles it */
            outs[2] = hl_pow(
                P, hl_add(P, hl_mul(P, hl_sym(P, vars[0]), hl_sym(P, vars[0])), hl_num_si(P, 1)),
                hl_num_frac(P, 3, 2));
        hl_tape *t = NULL;
        hl_error err;
        int st = hl_tape_new(&t, outs, 3, vars, 3, &err);
        CHECK_MSG(st == HL_OK, "tape_new: %s", err.msg);
        if (st != HL_OK)
            continue;
        enum { NPT = 6 };
        double v[NPT][3], interp[NPT][3], jit[NPT][3];
        for (int pt = 0; pt < NPT; pt++) {
            double scale = pt < 4 ? 1 : 20; /* some points far out too */
            for (int i = 0; i < 3; i++)
                v[pt][i] = scale * (2.0 * rnd(1u << 30) / (1u << 30) - 1);
            hl_tape_eval_d(interp[pt], v[pt], t);
        }
        /* the tape as a map, iterated (some orbits leave the finite) */
        double zi[3] = {v[0][0], v[0][1], v[0][2]}, zj[3] = {v[0][0], v[0][1], v[0][2]};
        long ki = hl_tape_iterate(zi, 40, t);
        st = hl_tape_jit(t, &err);
        if (st != HL_OK || !hl_tape_jit_active(t)) {
            if (failed++ < 3)
                fprintf(stderr, "hl_tape_jit: %s\n", err.msg);
            hl_tape_free(t);
            continue;
        }
        note_ops(t);
        long kj = hl_tape_iterate(zj, 40, t);
        CHECK_MSG(ki == kj && same_bits(zi, zj, 3), "iterate: %ld vs %ld steps", ki, kj);
        iter_total += ki;
        for (int pt = 0; pt < NPT; pt++) {
            hl_tape_eval_d(jit[pt], v[pt], t);
            total++;
            if (!same_bits(jit[pt], interp[pt], 3) && bad++ < 5) {
                char *s = hl_tape_print(t);
                fprintf(stderr, "at (%.17g,%.17g,%.17g): jit %a %a %a interp %a %a %a\n%s",
                        v[pt][0], v[pt][1], v[pt][2], jit[pt][0], jit[pt][1], jit[pt][2],
                        interp[pt][0], interp[pt][1], interp[pt][2], s);
                free(s);
            }
            for (int j = 0; j < 3; j++) {
                double want = ref(outs[j], v[pt]);
                /* far out, cancellation may leave only a few digits; NaN or
                 * inf where the reference has them too */
                int ok = isfinite(want) ? relerr(jit[pt][j], want) < (pt < 4 ? 1e-12 : 1e-6)
                                        : !isfinite(jit[pt][j]);
                if (!ok && badref++ < 5)
                    fprintf(stderr, "output %d: jit %.17g ref %.17g\n", j, jit[pt][j], want);
            }
        }
        /* in place: out == in (the tape is square) */
        double io[3] = {v[0][0], v[0][1], v[0][2]};
        hl_tape_eval_d(io, io, t);
        CHECK(same_bits(io, interp[0], 3));
        /* back to the interpreter */
        hl_tape_jit_clear(t);
        CHECK(!hl_tape_jit_active(t));
        double again[3];
        hl_tape_eval_d(again, v[1], t);
        CHECK(same_bits(again, interp[1], 3));
        hl_tape_free(t);
    }
    CHECK_MSG(failed == 0, "hl_tape_jit failed on %d tapes", failed);
    CHECK_MSG(bad == 0, "%d of %d compiled evaluations differ from the interpreter", bad, total);
    CHECK_MSG(badref == 0, "%d compiled values far from the reference", badref);
    CHECK_MSG(iter_total > 150 * 10, "iterations too few to test (%ld)", iter_total);
    for (int op = 0; op < HL_OP_COUNT; op++)
        CHECK_MSG(seen[op], "opcode %s never compiled", hl_op_name((hl_op)op));
    hl_pool_free(P);
}

/* Constants computed once in the prologue become immediates; outputs may be
 * inputs or constants; a tape may have no inputs. */
static void test_constants(void)
{
    hl_pool *P = hl_pool_new();
    hl_error err;
    hl_tape *t = NULL;
    const hl_expr *x = hl_sym(P, "x"), *y = hl_sym(P, "y");
    /* c1 = sin(1/3) + log(2), c2 = atan(pi) * sqrt(5), c3 = exp(-7/2) */
    const hl_expr *c1 = hl_add(P, hl_call(P, HL_SIN, hl_num_frac(P, 1, 3)),
                               hl_call(P, HL_LOG, hl_num_si(P, 2)));
    const hl_expr *c2 = hl_mul(P, hl_call(P, HL_ATAN, hl_pi(P)), hl_call(P, HL_SQRT, hl_num_si(P, 5)));
    const hl_expr *c3 = hl_call(P, HL_EXP, hl_num_frac(P, -7, 2));
    const hl_expr *outs[5] = {hl_add(P, hl_mul(P, c1, x), hl_mul(P, c2, y)), /* MULK, MULK, ADD */
                              hl_sub(P, c3, hl_call(P, HL_COS, hl_mul(P, x, y))),
                              y, c2, hl_num_frac(P, -5, 8)};
    CHECK(hl_tape_new(&t, outs, 5, vars, 3, &err) == HL_OK);
    double in[3] = {0.3, -1.7, 9}, interp[5], jit[5];
    hl_tape_eval_d(interp, in, t);
    int st = hl_tape_jit(t, &err);
    CHECK_MSG(st == HL_OK, "jit: %s", err.msg);
    hl_tape_eval_d(jit, in, t);
    CHECK(same_bits(jit, interp, 5));
    double k1 = sin(1.0 / 3) + log(2), k2 = atan(M_PI) * sqrt(5);
    CHECK(relerr(jit[0], k1 * 0.3 + k2 * -1.7) < 1e-15);
    CHECK(relerr(jit[1], exp(-3.5) - cos(0.3 * -1.7)) < 1e-15);
    CHECK(jit[2] == -1.7 && relerr(jit[3], k2) < 1e-15 && jit[4] == -0.625);
    hl_tape_free(t);

    /* no inputs at all: two constants */
    const hl_expr *k[2] = {c1, hl_num_si(P, 3)};
    CHECK(hl_tape_new(&t, k, 2, vars, 0, &err) == HL_OK);
    st = hl_tape_jit(t, &err);
    CHECK_MSG(st == HL_OK, "jit: %s", err.msg);
    double o[2];
    hl_tape_eval_d(o, NULL, t);
    CHECK(relerr(o[0], k1) < 1e-15 && o[1] == 3);
    hl_tape_free(t);
    hl_pool_free(P);
}

/* hl_tape_iterate on x -> c x with c = 2 held fixed: from 1, 2^1023 is the
 * last finite power, so the run stops after 1023 steps at 2^1023; a tape
 * with more outputs than inputs is refused.  Interpreter and compiled. */
static void test_iterate(void)
{
    hl_pool *P = hl_pool_new();
    hl_error err;
    hl_tape *t = NULL;
    const char *xc[2] = {"x", "c"};
    const hl_expr *e = hl_mul(P, hl_sym(P, "x"), hl_sym(P, "c"));
    CHECK(hl_tape_new(&t, &e, 1, xc, 2, &err) == HL_OK);
    for (int pass = 0; pass < 2; pass++) {
        double z[2] = {1, 2};
        CHECK(hl_tape_iterate(z, 10, t) == 10 && z[0] == 1024 && z[1] == 2);
        z[0] = 1;
        CHECK(hl_tape_iterate(z, 5000, t) == 1023 && z[0] == ldexp(1, 1023));
        CHECK(hl_tape_iterate(z, 0, t) == 0 && z[0] == ldexp(1, 1023));
        z[0] = 3, z[1] = -0.5;
        CHECK(hl_tape_iterate(z, 3, t) == 3 && z[0] == -0.375);
        if (pass == 0)
            CHECK(hl_tape_jit(t, &err) == HL_OK);
    }
    hl_tape_free(t);
    const hl_expr *two[2] = {hl_sym(P, "x"), hl_mul(P, hl_sym(P, "x"), hl_sym(P, "x"))};
    CHECK(hl_tape_new(&t, two, 2, xc, 1, &err) == HL_OK);
    double z1[2] = {1, 2};
    CHECK(hl_tape_iterate(z1, 1, t) == -1);
    CHECK(hl_tape_jit(t, &err) == HL_OK && hl_tape_iterate(z1, 1, t) == -1);
    hl_tape_free(t);
    hl_pool_free(P);
}

/* hl_tape_iterate_watch on (x, c) -> (c x, x - 1/2) with w0 = 1/2 watched:
 * w - w0 = x - 1 at the state each step leaves, so from x = 1, c = 2 after
 * n steps dev = 2^(n-1) - 1; the overflow stops it after 1023 steps.  A
 * tape of another shape is refused.  Interpreter and compiled agree. */
static void test_iterate_watch(void)
{
    hl_pool *P = hl_pool_new();
    hl_error err;
    hl_tape *t = NULL;
    const char *xc[2] = {"x", "c"};
    const hl_expr *x = hl_sym(P, "x");
    const hl_expr *e[2] = {hl_mul(P, x, hl_sym(P, "c")), hl_sub(P, x, hl_num_frac(P, 1, 2))};
    CHECK(hl_tape_new(&t, e, 2, xc, 2, &err) == HL_OK);
    for (int pass = 0; pass < 2; pass++) {
        double z[2] = {1, 2}, dev = 0;
        CHECK(hl_tape_iterate_watch(z, 10, 0.5, &dev, t) == 10 && z[0] == 1024 && z[1] == 2);
        CHECK_MSG(dev == 511, "pass %d: dev %g", pass, dev);
        z[0] = 1, dev = 0;
        CHECK(hl_tape_iterate_watch(z, 5000, 0.5, &dev, t) == 1023 && z[0] == ldexp(1, 1023));
        CHECK(dev == ldexp(1, 1022) - 1);
        dev = 7;
        CHECK(hl_tape_iterate_watch(z, 0, 0.5, &dev, t) == 0 && dev == 7);
        z[0] = -3, z[1] = 0.5, dev = 0;
        CHECK(hl_tape_iterate_watch(z, 2, 0.5, &dev, t) == 2 && z[0] == -0.75 && dev == 4);
        if (pass == 0)
            CHECK(hl_tape_jit(t, &err) == HL_OK);
    }
    hl_tape_free(t);
    CHECK(hl_tape_new(&t, e, 1, xc, 2, &err) == HL_OK); /* 1 output: no watched one */
    double z1[2] = {1, 2}, dev = 0;
    CHECK(hl_tape_iterate_watch(z1, 1, 0, &dev, t) == -1);
    hl_tape_free(t);
    hl_pool_free(P);
}

/* Loop-carried calls (jit.c: carry): Stormer-Verlet's kick-drift-kick map
 * with H watched, whose sin Q at a step's end is sin q at the next's start
 * (and cos q, read by H, is carried with it), and a map with q^(3/2) and
 * Q^(3/2); the compiled loops equal the interpreter's bit for bit over
 * 10^4 steps, and both stop at the same step where x leaves the domain. */
static void test_carried(void)
{
    hl_pool *P = hl_pool_new();
    hl_error err;
    const char *in[3] = {"q", "p", "D"};
    const hl_expr *q = hl_sym(P, "q"), *p = hl_sym(P, "p"), *D = hl_sym(P, "D");
    const hl_expr *h2 = hl_div(P, D, hl_num_si(P, 2));
    const hl_expr *ph = hl_sub(P, p, hl_mul(P, h2, hl_call(P, HL_SIN, q)));
    const hl_expr *Q = hl_add(P, q, hl_mul(P, D, ph));
    const hl_expr *H = hl_sub(P, hl_div(P, hl_mul(P, p, p), hl_num_si(P, 2)), hl_call(P, HL_COS, q));
    const hl_expr *kdk[3] = {Q, hl_sub(P, ph, hl_mul(P, h2, hl_call(P, HL_SIN, Q))), H};
    /* q -> Q = q - D q^(3/2) - p, p -> p + Q^(3/2) / 1000: POW3H on q and
     * on Q; q decreases through 0, where the power is NaN */
    const hl_expr *c32 = hl_num_frac(P, 3, 2);
    const hl_expr *Q2 = hl_sub(P, hl_sub(P, q, hl_mul(P, D, hl_pow(P, q, c32))), p);
    const hl_expr *pw[2] = {Q2, hl_add(P, p, hl_div(P, hl_pow(P, Q2, c32), hl_num_si(P, 1000)))};
    for (int which = 0; which < 2; which++) {
        hl_tape *a = NULL, *b = NULL;
        const hl_expr *const *outs = which ? pw : kdk;
        int nout = which ? 2 : 3;
        CHECK(hl_tape_new(&a, outs, nout, in, 3, &err) == HL_OK);
        CHECK(hl_tape_new(&b, outs, nout, in, 3, &err) == HL_OK);
        CHECK(hl_tape_jit(b, &err) == HL_OK);
        double za[3] = {which ? 0.4 : 1.3, which ? 0.001 : 0, which ? 0.5 : 0.01}, zb[3];
        memcpy(zb, za, sizeof zb);
        long na, nb;
        if (which == 0) {
            double H0 = -cos(1.3), da = 0, db = 0;
            na = hl_tape_iterate_watch(za, 10000, H0, &da, a);
            nb = hl_tape_iterate_watch(zb, 10000, H0, &db, b);
            CHECK_MSG(da == db && da > 0 && da < 1e-3, "dev %.17g vs %.17g", da, db);
        } else {
            na = hl_tape_iterate(za, 10000, a);
            nb = hl_tape_iterate(zb, 10000, b);
        }
        CHECK_MSG(na == nb && same_bits(za, zb, 3), "%d: %ld vs %ld steps, %.17g vs %.17g", which,
                  na, nb, za[0], zb[0]);
        CHECK_MSG(which ? na > 10 && na < 10000 : na == 10000, "%d: %ld steps", which, na);
        hl_tape_free(a);
        hl_tape_free(b);
    }
    hl_pool_free(P);
}

/* The policy's estimate: 1e7/n + 4e4 evaluations for n instructions,
 * decreasing with length; no instructions, never worth it. */
static void test_breakeven(void)
{
    hl_pool *P = hl_pool_new();
    hl_error err;
    hl_tape *t1 = NULL, *t2 = NULL, *t0 = NULL;
    const hl_expr *x = hl_sym(P, "x");
    const hl_expr *e1 = hl_mul(P, x, hl_call(P, HL_SIN, x)); /* SINCOS, MUL */
    const hl_expr *e2 = e1;
    for (int i = 0; i < 20; i++)
        e2 = hl_call(P, HL_EXP, hl_mul(P, e2, x));
    CHECK(hl_tape_new(&t1, &e1, 1, vars, 1, &err) == HL_OK);
    CHECK(hl_tape_new(&t2, &e2, 1, vars, 1, &err) == HL_OK);
    CHECK(hl_tape_new(&t0, &x, 1, vars, 1, &err) == HL_OK);
    long b1 = hl_tape_jit_breakeven(t1), b2 = hl_tape_jit_breakeven(t2);
    CHECK_MSG(hl_tape_nops(t1) == 2 && labs(b1 - (long)(25e6 / 4.8 + 1e5 / 2.4)) <= 1, "b1 %ld", b1);
    CHECK_MSG(b2 < b1 && b2 > 40000, "b2 %ld", b2);
    CHECK(hl_tape_jit_breakeven(t0) == LONG_MAX);
    hl_tape_free(t0);
    hl_tape_free(t1);
    hl_tape_free(t2);
    hl_pool_free(P);
}

/* libgccjit refusing (here: an option it does not know) is HL_EUNSUP, and
 * the tape still evaluates, by the interpreter. */
static void test_failure(void)
{
    hl_pool *P = hl_pool_new();
    hl_error err;
    hl_tape *t = NULL;
    const hl_expr *x = hl_sym(P, "x");
    const hl_expr *e = hl_mul(P, hl_call(P, HL_SIN, x), x);
    CHECK(hl_tape_new(&t, &e, 1, vars, 1, &err) == HL_OK);
    setenv("HL_JIT_FLAGS", "-fno-such-option-hamlie", 1);
    int st = hl_tape_jit(t, &err);
    unsetenv("HL_JIT_FLAGS");
    CHECK_MSG(st == HL_EUNSUP, "status %d: %s", st, err.msg);
    CHECK(!hl_tape_jit_active(t));
    double in = 0.9, out;
    hl_tape_eval_d(&out, &in, t);
    CHECK(out == sin(0.9) * 0.9);
    hl_tape_jit_clear(t); /* harmless when nothing was compiled */
    hl_tape_free(t);
    hl_pool_free(P);
}

int main(void)
{
    if (!hl_tape_jit_available()) {
        hl_pool *P = hl_pool_new();
        hl_error err;
        hl_tape *t = NULL;
        const hl_expr *x = hl_sym(P, "x");
        CHECK(hl_tape_new(&t, &x, 1, vars, 1, &err) == HL_OK);
        CHECK(hl_tape_jit(t, &err) == HL_EUNSUP && !hl_tape_jit_active(t));
        double in = 2, out = 0;
        hl_tape_eval_d(&out, &in, t);
        CHECK(out == 2);
        hl_tape_free(t);
        hl_pool_free(P);
        printf("note: built without libgccjit; only the HL_EUNSUP path was tested\n");
    } else {
        test_random();
        test_constants();
        test_iterate();
        test_iterate_watch();
        test_carried();
        test_breakeven();
        test_failure();
    }
    flint_cleanup();
    return HL_TEST_END();
}
