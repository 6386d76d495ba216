/* Every operation through every double back end, bit for bit against the
 * reference emitter of src/rules/test/rules_ref.h (the rules run eagerly,
 * one IEEE operation per emitter call, written from rule.h's contract).
 *
 * For each of the 24 hl_op (and the fused w^(3/2) of sqrt(w) w) a tape of
 * one or two instructions is built from a formula; the reference runs the
 * rules over the tape's own instruction list, and each back end of the table
 * below must give the same bits (memcmp) in Taylor mode, in the ODE
 * recursion (z[k+1] = f[k] / (k+1) as hl_tape_ode_source says: here b' = a,
 * whose chained form is taken) and at a
 * point.  A compiled back end joins by adding a row to `backends`; the
 * compiled ones (gccjit, C text) run the ODE recursion and point values.
 *
 * The recorded interpreter has two loops (prog_run.c): AVX2 and scalar.
 * This test runs the one the processor picks, and again as
 * tape/t-backends-scalar with HAMLIE_NO_AVX2=1 (CMakeLists.txt), which must
 * select the scalar one: check_loop says so. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/tape.h"
#include "rules/test/rules_ref.h"
#include "tape/test/ode_ref.h"
#include "tape/prog_impl.h"
#include "tape/tape_impl.h"

#define ORDER 12
#define S (ORDER + 1)

/* ---- the reference: the rules over a tape's instruction list ------------- */

static void ref_enter(ref_em *g, double *reg, int stride, const hl_instr *in)
{
    g->s[HL_SLOT_D] = reg + (size_t)in->d * stride;
    g->s[HL_SLOT_A] = reg + (size_t)in->a * stride;
    g->s[HL_SLOT_B] = in->b >= 0 ? reg + (size_t)in->b * stride : NULL;
    g->s[HL_SLOT_X] = in->x >= 0 ? reg + (size_t)in->x * stride : NULL;
}

/* a register file of stride S with the constants in place */
static double *ref_regs(const hl_tape *t)
{
    double *r = calloc((size_t)t->nregs * S, sizeof *r);
    for (int i = 0; i < t->nregs; i++)
        if (t->isconst[i])
            r[(size_t)i * S] = t->rd[i];
    return r;
}

/* coefficient k of every instruction; keeps[2 i ..] instruction i's kept values */
static void ref_step(const hl_tape *t, double *r, double *keeps, int k)
{
    for (int i = 0; i < t->ncode; i++) {
        ref_em g = {{&ref_ops}, {NULL, NULL, NULL, NULL}, {keeps[2 * i], keeps[2 * i + 1]}};
        ref_enter(&g, r, S, &t->code[i]);
        hl_rule_of((hl_op)t->code[i].op)->taylor(&g.em, k);
        keeps[2 * i] = g.keep[0];
        keeps[2 * i + 1] = g.keep[1];
    }
}

static void ref_tape_taylor(double *out, const double *in, const hl_tape *t)
{
    double *r = ref_regs(t), *keeps = calloc(2 * (size_t)t->ncode + 1, sizeof *keeps);
    memcpy(r, in, (size_t)t->nin * S * sizeof *r);
    for (int k = 0; k <= ORDER; k++)
        ref_step(t, r, keeps, k);
    for (int j = 0; j < t->nout; j++)
        memcpy(out + (size_t)j * S, r + (size_t)t->outreg[j] * S, S * sizeof *out);
    free(r);
    free(keeps);
}

static void ref_tape_ode(double *z, const hl_tape *t)
{
    double *r = ref_regs(t), *keeps = calloc(2 * (size_t)t->ncode + 1, sizeof *keeps);
    for (int i = 0; i < t->nin; i++)
        r[(size_t)i * S] = z[(size_t)i * S];
    for (int k = 0; k < ORDER; k++) {
        ref_step(t, r, keeps, k);
        ref_ode_step(r, t, k, S);
    }
    memcpy(z, r, (size_t)t->nin * S * sizeof *z);
    free(r);
    free(keeps);
}

static void ref_tape_point(double *out, const double *in, const hl_tape *t)
{
    double *r = malloc((size_t)t->nregs * sizeof *r);
    memcpy(r, t->rd, (size_t)t->nregs * sizeof *r);
    memcpy(r, in, (size_t)t->nin * sizeof *r);
    for (int i = 0; i < t->ncode; i++) {
        ref_em g = {{&ref_ops}, {NULL, NULL, NULL, NULL}, {0, 0}};
        ref_enter(&g, r, 1, &t->code[i]);
        hl_rule_of((hl_op)t->code[i].op)->point(&g.em);
    }
    for (int j = 0; j < t->nout; j++)
        out[j] = r[t->outreg[j]];
    free(r);
}

/* ---- the back ends -------------------------------------------------------- */

typedef struct backend {
    const char *name;
    int (*prepare)(hl_tape *t); /* 0: not available here (skipped) */
    void (*taylor)(double *out, const double *in, hl_tape *t);
    void (*ode)(double *z, hl_tape *t);
    void (*point)(double *out, const double *in, hl_tape *t);
} backend;

static int interp_prepare(hl_tape *t)
{
    return t != NULL;
}
static void interp_taylor(double *out, const double *in, hl_tape *t)
{
    hl_tape_taylor_d(out, in, ORDER, t);
}
static void interp_ode(double *z, hl_tape *t)
{
    hl_error err;
    CHECK(hl_tape_taylor_ode_d(z, ORDER, t, &err) == HL_OK);
}
static void interp_point(double *out, const double *in, hl_tape *t)
{
    hl_tape_eval_d(out, in, t);
}

/* The compiled ODE recursion (hl_tape_native) through libgccjit, and with
 * it the compiled point evaluation (hl_tape_jit); then through the system
 * C compiler ($HL_CC).  Taylor mode on given inputs is the interpreter's
 * alone (no row: NULL). */
static int native_prepare(hl_tape *t, const char *cc)
{
    hl_error err;
    if (cc != NULL)
        setenv("HL_CC", cc, 1);
    else
        unsetenv("HL_CC");
    hl_status st = hl_tape_native(t, ORDER, &err);
    unsetenv("HL_CC");
    CHECK_MSG(st == HL_OK || st == HL_EUNSUP, "native: %s", err.msg);
    return st == HL_OK;
}
static int gccjit_prepare(hl_tape *t)
{
    hl_error err;
    if (!hl_tape_jit_available())
        return 0;
    CHECK(hl_tape_jit(t, &err) == HL_OK);
    return native_prepare(t, NULL) && t->native_jit != NULL;
}
static int cc_prepare(hl_tape *t)
{
    return native_prepare(t, "cc");
}

static const backend backends[] = {
    {"interpreter", interp_prepare, interp_taylor, interp_ode, interp_point},
    {"gccjit", gccjit_prepare, NULL, interp_ode, interp_point},
    {"C text (cc)", cc_prepare, NULL, interp_ode, NULL},
};

/* ---- the operations --------------------------------------------------------- */

/* A formula over a, b whose tape holds op (and for the fused case, POW3H). */
static const struct {
    hl_op op;
    const char *f;
} cases[] = {
    {HL_OP_NEG, "-sin(a)"},    {HL_OP_ADD, "a+b"},         {HL_OP_SUB, "a-b"},
    {HL_OP_MUL, "a*b"},        {HL_OP_DIV, "a/b"},         {HL_OP_SQR, "a^2"},
    {HL_OP_ADDK, "a+pi"},      {HL_OP_SUBK, "a-pi"},       {HL_OP_KSUB, "pi-a"},
    {HL_OP_MULK, "a*pi"},      {HL_OP_DIVK, "a/pi"},       {HL_OP_KDIV, "pi/a"},
    {HL_OP_POWK, "a^(3/4)"},   {HL_OP_SQRT, "sqrt(a)"},    {HL_OP_EXP, "exp(a)"},
    {HL_OP_LOG, "log(a)"},     {HL_OP_SINCOS, "sin(a)"},   {HL_OP_SINHCOSH, "sinh(a)"},
    {HL_OP_TAN, "tan(a)"},     {HL_OP_TANH, "tanh(a)"},    {HL_OP_ATAN, "atan(a)"},
    {HL_OP_ASIN, "asin(a)"},   {HL_OP_ACOS, "acos(a)"},    {HL_OP_ATAN2, "atan2(a,b)"},
    {HL_OP_ASINH, "asinh(a)"}, {HL_OP_POW3H, "sqrt(a)*a"}, /* the fused w^(3/2) */
};

static int has_op(const hl_tape *t, hl_op op)
{
    for (int i = 0; i < t->ncode; i++)
        if (t->code[i].op == (int)op)
            return 1;
    return 0;
}

static int same(const double *x, const double *y, int n)
{
    return memcmp(x, y, n * sizeof *x) == 0;
}

/* inputs a(t), b(t) with a0 in (0, 1) (log, asin), b0 > 0 (div) */
static void inputs(double *in)
{
    for (int j = 0; j <= ORDER; j++) {
        in[j] = j == 0 ? 0.4 : 0.3 / (j + 1) * (j % 3 ? 1 : -1);
        in[S + j] = j == 0 ? 0.9 : 0.2 / (j + 2);
    }
}

static void check_backend(const backend *be, hl_tape *t, const char *f)
{
    double in[2 * S], want[2 * S], got[2 * S];
    inputs(in);
    if (be->taylor != NULL) {
        ref_tape_taylor(want, in, t);
        be->taylor(got, in, t);
        CHECK_MSG(same(got, want, 2 * S), "%s: Taylor of %s differs from the rules", be->name, f);
    }
    double z0[2 * S] = {0}, z1[2 * S] = {0};
    z0[0] = z1[0] = 0.4;
    z0[S] = z1[S] = 0.9;
    ref_tape_ode(z0, t);
    be->ode(z1, t);
    CHECK_MSG(same(z0, z1, 2 * S), "%s: ODE of %s differs from the rules", be->name, f);
    if (be->point == NULL)
        return;
    double p[2] = {0.4, 0.9}, pw[2], pg[2];
    ref_tape_point(pw, p, t);
    be->point(pg, p, t);
    CHECK_MSG(same(pw, pg, 2), "%s: point value of %s differs from the rules", be->name, f);
}

/* The interpreter's loop is the one HAMLIE_NO_AVX2 and the processor ask
 * for, so that the -scalar run does cover the scalar loop. */
static void check_loop(hl_tape *t)
{
    double in[2 * S], out[2 * S];
    inputs(in);
    hl_tape_taylor_d(out, in, ORDER, t);
    const char *no = getenv("HAMLIE_NO_AVX2");
    int forced = no != NULL && no[0] != '\0' && strcmp(no, "0") != 0;
    const char *want = "scalar";
#if defined(__x86_64__) && defined(__GNUC__)
    if (!forced && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
        want = "avx2";
#endif
    CHECK_MSG(strcmp(hl_prog_loop(t->tprog), want) == 0, "the interpreter runs its %s loop, not %s",
              hl_prog_loop(t->tprog), want);
}

int main(void)
{
    hl_pool *P = hl_pool_new();
    const char *ab[] = {"a", "b"};
    int covered[HL_OP_COUNT] = {0};
    for (size_t c = 0; c < sizeof cases / sizeof *cases; c++) {
        const hl_expr *e[2];
        hl_error err;
        CHECK_MSG(hl_parse(&e[0], P, cases[c].f, &err) == HL_OK, "%s", cases[c].f);
        CHECK(hl_parse(&e[1], P, "a", &err) == HL_OK); /* square, for the ODE */
        hl_tape *t = NULL;
        CHECK_MSG(hl_tape_new(&t, e, 2, ab, 2, &err) == HL_OK, "%s: %s", cases[c].f, err.msg);
        if (t == NULL)
            continue;
        CHECK_MSG(has_op(t, cases[c].op), "%s does not compile to %s", cases[c].f,
                  hl_op_name(cases[c].op));
        covered[cases[c].op] = 1;
        if (c == 0)
            check_loop(t);
        for (size_t b = 0; b < sizeof backends / sizeof *backends; b++)
            if (backends[b].prepare(t))
                check_backend(&backends[b], t, cases[c].f);
        hl_tape_free(t);
    }
    for (int op = 0; op < HL_OP_COUNT; op++)
        CHECK_MSG(covered[op], "no case for %s", hl_op_name((hl_op)op));
    hl_pool_free(P);
    return HL_TEST_END();
}
