/* The compiled Taylor-ODE recursions (hl_tape_native: libgccjit, and the C
 * text through the system compiler with $HL_CC = cc) against the rules run
 * by the reference emitter (rules/test/rules_ref.h) over the tape's own
 * register file, bit for bit: one ODE whose every equation is one operation,
 * z_i' = op_i(z_i, z_{i+1}), so that each operation's coefficients are an
 * output, at orders 1..20.  A back end that cannot run is skipped (passes
 * with a note). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/expr.h"
#include "hamlie/tape.h"
#include "rules/test/rules_ref.h"
#include "tape/test/ode_ref.h"
#include "tape/tape_impl.h"

/* every operation the tape compiler makes, with A = z_i and B = z_{i+1} */
static const char *const op_text[] = {
    "-A + B",    "A + B",         "A - B",    "A*B",     "A/B",     "A^2",     "A + 2.5",
    "A - 2.5",   "2.5 - A",       "A*2.5",    "A/2.5",   "2.5/A",   "A^(3/4)", "A^(-3/2)",
    "A^B",       "sqrt(A)",       "exp(A)",   "log(A)",  "sin(A)",  "cos(A)",  "sinh(A)",
    "cosh(B)",   "tan(A)",        "tanh(A)",  "atan(A)", "asin(A)", "acos(A)", "atan2(A, B)",
    "sqrt(A)*A", "B/(A*sqrt(A))", "pi*B - A",
};
enum { NOPS = sizeof op_text / sizeof op_text[0] };

static const char *subst(const char *text, int i)
{
    static char out[128];
    char *o = out;
    for (const char *c = text; *c; c++)
        o += *c == 'A'   ? sprintf(o, "z%d", i)
             : *c == 'B' ? sprintf(o, "z%d", (i + 1) % NOPS)
                         : sprintf(o, "%c", *c);
    return out;
}

/* z_i' = op_i(z_i, z_{i+1}) */
static hl_tape *every_op_tape(hl_pool *P)
{
    const hl_expr *f[NOPS];
    char names[NOPS][8];
    const char *in[NOPS];
    hl_error err;
    for (int i = 0; i < NOPS; i++) {
        snprintf(names[i], sizeof names[i], "z%d", i);
        in[i] = names[i];
        CHECK_MSG(hl_parse(&f[i], P, subst(op_text[i], i), &err) == HL_OK, "%s: %s",
                  subst(op_text[i], i), err.msg);
    }
    hl_tape *t = NULL;
    CHECK_MSG(hl_tape_new(&t, f, NOPS, in, NOPS, &err) == HL_OK, "%s", err.msg);
    return t;
}

/* The recursion of hl_tape_taylor_ode_d by the reference emitter, on a
 * register file laid out as the interpreter's. */
static void reference_ode(const hl_tape *t, double *z, int order)
{
    const int S = order + 1;
    double *R = calloc((size_t)t->nregs * S, sizeof *R);
    ref_em *em = calloc((size_t)t->ncode + 1, sizeof *em);
    for (int r = 0; r < t->nregs; r++)
        if (t->isconst[r])
            R[r * S] = t->rd[r];
    for (int i = 0; i < t->nin; i++)
        R[i * S] = z[i * S];
    for (int i = 0; i < t->ncode; i++) {
        const hl_instr *in = &t->code[i];
        em[i] = (ref_em){{&ref_ops},
                         {R + in->d * S, R + in->a * S, in->b >= 0 ? R + in->b * S : NULL,
                          in->x >= 0 ? R + in->x * S : NULL},
                         {0, 0}};
    }
    for (int k = 0; k < order; k++) {
        for (int i = 0; i < t->ncode; i++)
            hl_rule_of(t->code[i].op)->taylor(&em[i].em, k);
        ref_ode_step(R, t, k, S);
    }
    memcpy(z, R, (size_t)t->nin * S * sizeof *z);
    free(R);
    free(em);
}

/* 1: the same bits; 0: not; -1: the back end cannot run */
static int same_bits(hl_tape *t, int order)
{
    const int S = order + 1;
    double *want = calloc((size_t)NOPS * S, sizeof *want),
           *got = calloc((size_t)NOPS * S, sizeof *got);
    for (int i = 0; i < NOPS; i++)
        want[i * S] = got[i * S] = 0.3 + 0.01 * i; /* in every domain */
    reference_ode(t, want, order);
    hl_error err;
    int st = hl_tape_native(t, order, &err), same = -1;
    if (st == HL_OK) {
        CHECK(hl_tape_taylor_ode_d(got, order, t, &err) == HL_OK);
        same = memcmp(want, got, (size_t)NOPS * S * sizeof *got) == 0;
        for (int q = 0; !same && q < NOPS * S; q++)
            if (memcmp(&want[q], &got[q], sizeof *got) != 0) {
                printf("order %d: %s, coefficient %d: %.17g, reference %.17g\n", order,
                       op_text[q / S], q % S, got[q], want[q]);
                break;
            }
    } else {
        CHECK_MSG(st == HL_EUNSUP, "native: %s", err.msg);
        printf("skipped: %s\n", err.msg);
    }
    hl_tape_native_clear(t);
    free(want);
    free(got);
    return same;
}

/* Point evaluation compiled by hl_tape_jit (jit.c's emit, the rules'
 * point()) against the point rules run by the reference emitter, bit for
 * bit, the tape's constants and instructions walked in order. */
static void point_same_bits(hl_tape *t)
{
    double *R = calloc((size_t)t->nregs, sizeof *R), in[NOPS], got[NOPS];
    for (int r = 0; r < t->nregs; r++)
        R[r] = t->isconst[r] ? t->rd[r] : 0;
    for (int i = 0; i < NOPS; i++)
        R[i] = in[i] = 0.3 + 0.01 * i;
    for (int i = 0; i < t->ncode; i++) {
        const hl_instr *c = &t->code[i];
        ref_point(c->op, R + c->d, c->x >= 0 ? R + c->x : NULL, R + c->a,
                  c->b >= 0 ? R + c->b : NULL);
    }
    hl_error err;
    int st = hl_tape_jit(t, &err);
    if (st != HL_OK) {
        CHECK_MSG(st == HL_EUNSUP, "jit: %s", err.msg);
        printf("point evaluation skipped: %s\n", err.msg);
        free(R);
        return;
    }
    hl_tape_eval_d(got, in, t);
    for (int i = 0; i < NOPS; i++)
        CHECK_MSG(memcmp(&got[i], &R[t->outreg[i]], sizeof *got) == 0,
                  "point %s: %.17g, reference %.17g", op_text[i], got[i], R[t->outreg[i]]);
    hl_tape_jit_clear(t);
    free(R);
}

static void suite(hl_tape *t, const int *orders, int n)
{
    for (int i = 0; i < n; i++) {
        int same = same_bits(t, orders[i]);
        if (same < 0)
            return;
        CHECK_MSG(same == 1, "order %d: the compiled recursion differs from the rules", orders[i]);
    }
}

int main(void)
{
    hl_pool *P = hl_pool_new();
    hl_tape *t = every_op_tape(P);
    static const int jit_orders[] = {1, 2, 3, 5, 8, 13, 20};
    static const int cc_orders[] = {1, 4, 20};
    (void)ref_taylor; /* the reference header's entry for series in arrays */
    point_same_bits(t);
    unsetenv("HL_CC");
    printf("libgccjit%s\n", hl_tape_jit_available() ? "" : " (not built in: the system compiler)");
    suite(t, jit_orders, sizeof jit_orders / sizeof *jit_orders);
    setenv("HL_CC", "cc", 1);
    printf("the system compiler\n");
    suite(t, cc_orders, sizeof cc_orders / sizeof *cc_orders);
    hl_tape_free(t);
    hl_pool_free(P);
    flint_cleanup();
    return HL_TEST_END();
}
