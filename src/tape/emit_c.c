/* Native code for the Taylor-ODE recursion (opt-in; see hl_tape_native in
 * hamlie/tape.h): the rules of src/rules emitted as C text, compiled by the
 * system C compiler and loaded.
 *
 * The interpreter pays, for every instruction and every coefficient, a
 * dispatch and a loop whose length changes with the coefficient.  For a
 * fixed order all of that is known in advance, so this file prints the
 * whole recursion of hl_tape_taylor_ode_d as one straight-line C function:
 * each rule run at each k through an emitter whose values are C
 * expressions, every sum written out, every register index a constant.  The
 * function works on the tape's own Taylor register file.  The expressions
 * are the interpreter's operations in the interpreter's order (rule.h), and
 * the compiler runs with -ffp-contract=off, so the coefficients are the
 * interpreter's to the last bit.
 *
 * This costs a compiler run (a fraction of a second for small tapes): worth
 * it for long runs, not for short ones.  Where libgccjit is built in, the
 * same program is built in process instead (jit_taylor.c) unless $HL_CC
 * names a compiler; where no compiler runs, the caller gets HL_EUNSUP and
 * the interpreter keeps working. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <fcntl.h>
#include <math.h>
#include <spawn.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "base/buf.h"
#include "rules/unroll.h"
#include "tape/tape_impl.h"

extern char **environ;

/* ---- the emitter: values are C expressions ----------------------------------- */

/* A value: its text, and the number itself when it is known now (so that
 * products of known numbers, such as a convolution's weights, are folded
 * here, with the same rounding the machine would apply). */
typedef struct cval {
    char *s;
    double v;
    int isnum;
} cval;

typedef struct cem {
    hl_em em;
    hl_buf *out;
    const hl_tape *t;
    const hl_instr *in;
    int i;   /* the instruction's index: names its kept values */
    int S;   /* stride of the register file: order + 1 */
    cval *v; /* the values made for the current instruction */
    int n, cap;
} cem;

static cem *CE(hl_em *em)
{
    return (cem *)em;
}

static hl_ev push(cem *E, char *s, int isnum, double v)
{
    if (E->n == E->cap) {
        E->cap = E->cap ? 2 * E->cap : 64;
        E->v = hl_xrealloc(E->v, (size_t)E->cap * sizeof *E->v);
    }
    E->v[E->n] = (cval){s, v, isnum};
    return (hl_ev){.i = E->n++};
}

static const cval *V(cem *E, hl_ev a)
{
    return &E->v[a.i];
}

/* the values of an instruction live until it is emitted */
static void drop_values(cem *E)
{
    for (int j = 0; j < E->n; j++)
        free(E->v[j].s);
    E->n = 0;
}

static hl_ev text(cem *E, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static hl_ev text(cem *E, const char *fmt, ...)
{
    char *s = NULL;
    va_list ap;
    va_start(ap, fmt);
    if (vasprintf(&s, fmt, ap) < 0)
        abort();
    va_end(ap);
    return push(E, s, 0, 0);
}

/* x exactly, in C: hexadecimal (reads back to the same bits) */
static hl_ev number(cem *E, double x)
{
    hl_ev r;
    if (isnan(x))
        r = text(E, "NAN");
    else if (isinf(x))
        r = text(E, "%sHUGE_VAL", x < 0 ? "-" : "");
    else
        r = text(E, signbit(x) ? "(%a)" : "%a", x);
    E->v[r.i].isnum = 1;
    E->v[r.i].v = x;
    return r;
}

static hl_ev c_num(hl_em *em, long p, long q)
{
    return number(CE(em), (double)p / (double)q);
}

static int reg_of(const hl_instr *in, hl_slot s)
{
    return s == HL_SLOT_D ? in->d : s == HL_SLOT_A ? in->a : s == HL_SLOT_B ? in->b : in->x;
}

static long cell(const cem *E, int reg, int j)
{
    return (long)reg * E->S + j;
}

/* A constant's coefficients are known now: (c, 0, 0, ...) as the
 * interpreter's layout holds them. */
static hl_ev c_coef(hl_em *em, hl_slot s, int j)
{
    cem *E = CE(em);
    int reg = reg_of(E->in, s);
    if (E->t->isconst[reg])
        return number(E, j == 0 ? E->t->rd[reg] : 0.0);
    return text(E, "R[%ld]", cell(E, reg, j));
}

static void c_store(hl_em *em, hl_slot s, int j, hl_ev v)
{
    cem *E = CE(em);
    hl_buf_printf(E->out, "    R[%ld] = %s;\n", cell(E, reg_of(E->in, s), j), V(E, v)->s);
}

static int both_known(cem *E, hl_ev a, hl_ev b)
{
    return V(E, a)->isnum && V(E, b)->isnum;
}

static hl_ev binary(cem *E, char op, hl_ev a, hl_ev b)
{
    if (both_known(E, a, b)) {
        double x = V(E, a)->v, y = V(E, b)->v;
        return number(E, op == '+' ? x + y : op == '-' ? x - y : op == '*' ? x * y : x / y);
    }
    return text(E, "(%s %c %s)", V(E, a)->s, op, V(E, b)->s);
}

static hl_ev c_add(hl_em *em, hl_ev a, hl_ev b)
{
    return binary(CE(em), '+', a, b);
}
static hl_ev c_sub(hl_em *em, hl_ev a, hl_ev b)
{
    return binary(CE(em), '-', a, b);
}
static hl_ev c_mul(hl_em *em, hl_ev a, hl_ev b)
{
    return binary(CE(em), '*', a, b);
}
static hl_ev c_div(hl_em *em, hl_ev a, hl_ev b)
{
    return binary(CE(em), '/', a, b);
}

static hl_ev c_neg(hl_em *em, hl_ev a)
{
    cem *E = CE(em);
    if (V(E, a)->isnum)
        return number(E, -V(E, a)->v);
    return text(E, "(-%s)", V(E, a)->s);
}

static hl_ev c_fma(hl_em *em, hl_ev a, hl_ev b, hl_ev c)
{
    cem *E = CE(em);
    if (both_known(E, a, b) && V(E, c)->isnum)
        return number(E, fma(V(E, a)->v, V(E, b)->v, V(E, c)->v));
    return text(E, "fma(%s, %s, %s)", V(E, a)->s, V(E, b)->s, V(E, c)->s);
}

/* libm's functions; pow is kept from the compiler's rewrites by
 * -fno-builtin-pow */
static hl_ev c_call(hl_em *em, hl_pfn f, hl_ev a, hl_ev b)
{
    cem *E = CE(em);
    if (hl_pfn_arity(f) == 2)
        return text(E, "%s(%s, %s)", hl_pfn_name(f), V(E, a)->s, V(E, b)->s);
    return text(E, "%s(%s)", hl_pfn_name(f), V(E, a)->s);
}

/* kept values: locals declared at k = 0, named by instruction and slot */
static void c_keep(hl_em *em, int slot, hl_ev v)
{
    cem *E = CE(em);
    hl_buf_printf(E->out, "    const double k%d_%d = %s;\n", E->i, slot, V(E, v)->s);
}

static hl_ev c_kept(hl_em *em, int slot)
{
    return text(CE(em), "k%d_%d", CE(em)->i, slot);
}

static const hl_em_ops c_ops = {c_num, c_coef, c_store,          c_add,  c_sub, c_mul, c_neg, c_div,
                                c_fma, c_call, hl_conv_unrolled, c_keep, c_kept};

/* ---- the program -------------------------------------------------------------- */

/* z[k+1] = f[k] / (k+1) for every input, as every double back end divides
 * (hl_tape_ode_source): fma(c, hi, c lo), or c hi where the reciprocal is
 * exact (lo = 0), which is the same number for every finite c and one
 * operation less on the chain from one order to the next */
static void put_ode_step(cem *E, int k)
{
    for (int i = 0; i < E->t->nin; i++) {
        hl_ode_source src;
        hl_tape_ode_source(&src, E->t, i, k);
        long f = cell(E, src.reg, src.k);
        if (src.lo == 0)
            hl_buf_printf(E->out, "    R[%ld] = R[%ld] * %a;\n", cell(E, i, k + 1), f, src.hi);
        else
            hl_buf_printf(E->out, "    R[%ld] = fma(R[%ld], %a, R[%ld] * %a);\n", cell(E, i, k + 1),
                          f, src.hi, f, src.lo);
    }
}

/* The C source of void hl_native(double *R): the recursion of
 * hl_tape_taylor_ode_d at this order on the register file R. */
static char *gen_source(const hl_tape *t, int order)
{
    hl_buf b;
    hl_buf_init(&b);
    cem E = {.em = {&c_ops}, .out = &b, .t = t, .S = order + 1};
    hl_buf_puts(&b, "/* generated by hamlie (src/tape/emit_c.c) */\n#include <math.h>\n"
                    "void hl_native(double *restrict R)\n{\n");
    for (int k = 0; k < order; k++) {
        hl_buf_printf(&b, "    /* coefficient %d */\n", k);
        for (int i = 0; i < t->ncode; i++) {
            E.in = &t->code[i];
            E.i = i;
            hl_rule_of(E.in->op)->taylor(&E.em, k);
            drop_values(&E);
        }
        put_ode_step(&E, k);
    }
    hl_buf_puts(&b, "}\n");
    free(E.v);
    return hl_buf_take(&b);
}

/* ---- compiling and loading ---------------------------------------------------- */

static int run_cc(const char *cc, const char *src, const char *so, hl_error *err)
{
    /* no contraction into FMA: the interpreter's roundings, one per operation */
    char *argv[] = {(char *)cc,         "-O1",       "-march=native", "-ffp-contract=off",
                    "-fno-builtin-pow", "-fPIC",     "-shared",       "-o",
                    (char *)so,         (char *)src, "-lm",           NULL};
    pid_t pid;
    posix_spawn_file_actions_t fa;
    posix_spawn_file_actions_init(&fa);
    /* the compiler's chatter is not ours to print */
    posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
    posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
    int rc = posix_spawnp(&pid, cc, &fa, NULL, argv, environ);
    posix_spawn_file_actions_destroy(&fa);
    if (rc != 0)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "cannot run the C compiler '%s'", cc);
    int status;
    if (waitpid(pid, &status, 0) < 0 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                            "the C compiler '%s' failed on the generated code", cc);
    return HL_OK;
}

/* Source written to a temporary directory, compiled, loaded; the files
 * removed (a loaded object stays mapped). */
static hl_status compile_and_load(const char *cc, const hl_tape *t, int order, void **so_handle,
                                  void (**fn)(double *), hl_error *err)
{
    const char *tmp = getenv("TMPDIR");
    hl_buf path;
    hl_buf_init(&path);
    hl_buf_printf(&path, "%s/hamlie-XXXXXX", tmp && *tmp ? tmp : "/tmp");
    char *dir = hl_buf_take(&path);
    if (mkdtemp(dir) == NULL) {
        free(dir);
        return hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot make a temporary directory");
    }
    hl_buf_printf(&path, "%s/taylor.c", dir);
    char *src = hl_buf_take(&path);
    hl_buf_printf(&path, "%s/taylor.so", dir);
    char *so = hl_buf_take(&path);

    hl_status status = HL_OK;
    char *code = gen_source(t, order);
    FILE *f = fopen(src, "w");
    if (f == NULL || fputs(code, f) < 0 || fclose(f) != 0)
        status = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write '%s'", src);
    free(code);
    if (status == HL_OK)
        status = run_cc(cc, src, so, err);
    void *h = NULL;
    if (status == HL_OK && (h = dlopen(so, RTLD_NOW | RTLD_LOCAL)) == NULL)
        status = hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "cannot load the compiled code");
    if (h != NULL && (*(void **)fn = dlsym(h, "hl_native")) == NULL) {
        dlclose(h);
        h = NULL;
        status = hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "compiled code lacks its entry point");
    }
    remove(so);
    remove(src);
    rmdir(dir);
    free(dir);
    free(src);
    free(so);
    *so_handle = h;
    return status;
}

hl_status hl_tape_native(hl_tape *t, int order, hl_error *err)
{
    if (order < 1 || order > 1000)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "native order must be 1..1000 (got %d)",
                            order);
    if (t->nin != t->nout)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "an ODE tape needs as many outputs as inputs (%d inputs, %d outputs)",
                            t->nin, t->nout);
    /* the source grows as instructions * order^2 / 2 sums' terms */
    if ((double)t->ncode * (order + 1) * (order + 1) / 2 > 4e6)
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0,
                            "tape too large for native code at order %d (%d instructions)", order,
                            t->ncode);
    const char *cc = getenv("HL_CC");
    /* libgccjit when there is one and no compiler was asked for by name:
     * the same program, built in process (no files, no process) */
    if (cc == NULL || *cc == '\0') {
        void *res = NULL;
        void (*jfn)(double *) = NULL;
        if (hl_tape_jit_taylor(&res, &jfn, t, order, err) == HL_OK) {
            hl_tape_native_clear(t);
            t->native_jit = res;
            t->native_fn = jfn;
            t->native_order = order;
            return HL_OK;
        }
        cc = "cc";
    }
    void *h = NULL;
    void (*fn)(double *) = NULL;
    hl_status status = compile_and_load(cc, t, order, &h, &fn, err);
    if (status != HL_OK)
        return status;
    hl_tape_native_clear(t);
    t->native_so = h;
    t->native_fn = fn;
    t->native_order = order;
    return HL_OK;
}

void hl_tape_native_clear(hl_tape *t)
{
    if (t->native_so)
        dlclose(t->native_so);
    hl_tape_jit_release(t->native_jit);
    t->native_jit = NULL;
    t->native_so = NULL;
    t->native_fn = NULL;
    t->native_order = 0;
}
