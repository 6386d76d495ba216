/* Native code for the Taylor-ODE recursion (opt-in; see hl_tape_native in
 * hamlie/tape.h).
 *
 * The interpreter pays, for every instruction and every coefficient, a
 * dispatch and a loop whose length changes with the coefficient.  For a
 * fixed order all of that is known in advance, so this file prints the
 * whole recursion of hl_tape_taylor_ode_d as one straight-line C function
 * (every sum written out, every register index a constant, sums as balanced
 * trees so that their additions overlap), compiles it with the system C
 * compiler into a shared object and loads it.  The function works on the
 * tape's own Taylor register file, so the interpreter and the native code
 * share layout, constants and results (up to the order of additions).
 *
 * This costs a compiler run (a fraction of a second for small tapes): worth
 * it for long runs, not for short ones.  Where no compiler runs, the caller
 * gets HL_EUNSUP and the interpreter keeps working.
 *
 * Where hamlie has libgccjit, the same program is built in process instead
 * (jit.c, hl_tape_jit_taylor: the same balanced sums as trees), unless
 * $HL_CC asks for a compiler by name; this file's C printer is then the
 * fallback. */
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
#include "tape/tape_impl.h"

extern char **environ;

/* ---- sums of terms, printed as balanced trees ------------------------------ */

/* A sum's terms: those known a round ago (t[0..n-1]), and apart the fresh
 * ones, which read a coefficient k computed in this round (j = 0 or j = k
 * in a convolution), with the register they read it from (f, freg). */
typedef struct terms {
    char (*t)[128];
    int n, cap;
    char f[2][128];
    int freg[2], nf;
} terms;

/* fresh: the register whose coefficient k the term reads, else -1 */
static void term(terms *ts, int fresh, const char *fmt, ...) __attribute__((format(printf, 3, 4)));
static void term(terms *ts, int fresh, const char *fmt, ...)
{
    if (ts->nf == 2) /* a convolution has at most two */
        fresh = -1;
    if (fresh < 0 && ts->n == ts->cap) {
        ts->cap = ts->cap ? 2 * ts->cap : 64;
        ts->t = hl_xrealloc(ts->t, (size_t)ts->cap * sizeof *ts->t);
    }
    if (fresh >= 0)
        ts->freg[ts->nf] = fresh;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(fresh >= 0 ? ts->f[ts->nf++] : ts->t[ts->n++], sizeof ts->t[0], fmt, ap);
    va_end(ap);
}

static void put_sum(hl_buf *b, const terms *ts, int lo, int hi)
{
    if (hi - lo == 1) {
        hl_buf_puts(b, ts->t[lo]);
        return;
    }
    int mid = (lo + hi) / 2;
    hl_buf_putc(b, '(');
    put_sum(b, ts, lo, mid);
    hl_buf_puts(b, " + ");
    put_sum(b, ts, mid, hi);
    hl_buf_putc(b, ')');
}

/* "(sum)" of the collected terms, or "0.0"; resets the list.  As jit.c's
 * tsum: the known terms as a balanced tree, then the fresh ones one by one,
 * the higher register last, so that the chain from one order to the next
 * goes through one multiplication and one addition per instruction. */
static void sum(hl_buf *b, terms *ts)
{
    if (ts->n == 0 && ts->nf == 0)
        hl_buf_puts(b, "0.0");
    int order[2] = {0, 1};
    if (ts->nf == 2 && ts->freg[0] > ts->freg[1])
        order[0] = 1, order[1] = 0;
    for (int i = 0; i < ts->nf + (ts->n > 0) - 1; i++)
        hl_buf_putc(b, '(');
    if (ts->n > 0)
        put_sum(b, ts, 0, ts->n);
    for (int i = 0; i < ts->nf; i++) {
        if (i > 0 || ts->n > 0)
            hl_buf_puts(b, " + ");
        hl_buf_puts(b, ts->f[order[i]]);
        if (i > 0 || ts->n > 0)
            hl_buf_putc(b, ')');
    }
    ts->n = ts->nf = 0;
}

/* ---- one instruction at coefficient k ------------------------------------------ */

#define R(reg, j) ((long)(reg) * S + (j))

/* which register's coefficient k the term x[j] y[k-j] reads, or -1 */
static int fresh_of(int x, int y, int j, int k)
{
    return j == k ? x : j == 0 ? y : -1;
}

/* terms x[j] y[k-j], j = lo..hi */
static void conv(terms *ts, int x, int y, int lo, int hi, int k, int S)
{
    for (int j = lo; j <= hi; j++)
        term(ts, fresh_of(x, y, j, k), "R[%ld]*R[%ld]", R(x, j), R(y, k - j));
}

/* terms (wa*j + wb) x[j] y[k-j], j = lo..hi; the fresh x[k] as
 * (w y[0]) x[k] (jit.c's twconv) */
static void wconv(terms *ts, int x, int y, int lo, int hi, int k, int wa, int wb, int S)
{
    for (int j = lo; j <= hi; j++) {
        if (j == k && k > 0)
            term(ts, x, "%d.0*R[%ld]*R[%ld]", wa * j + wb, R(y, k - j), R(x, j));
        else
            term(ts, fresh_of(x, y, j, k), "%d.0*R[%ld]*R[%ld]", wa * j + wb, R(x, j), R(y, k - j));
    }
}

/* the terms j = lo..k-lo of (x*x)[k], using symmetry */
static void sqr_terms_from(terms *ts, int x, int k, int lo, int S)
{
    for (int j = lo; 2 * j < k; j++)
        term(ts, j == 0 ? x : -1, "2.0*R[%ld]*R[%ld]", R(x, j), R(x, k - j));
    if (k % 2 == 0 && k / 2 >= lo)
        term(ts, k == 0 ? x : -1, "R[%ld]*R[%ld]", R(x, k / 2), R(x, k / 2));
}

static void sqr_terms(terms *ts, int x, int k, int S)
{
    sqr_terms_from(ts, x, k, 0, S);
}

int *hl_tape_defs_(const hl_tape *t)
{
    int *def = hl_xmalloc(((size_t)t->nregs + 1) * sizeof *def);
    for (int r = 0; r <= t->nregs; r++)
        def[r] = -1;
    for (int i = 0; i < t->ncode; i++)
        def[t->code[i].d] = i;
    return def;
}

int hl_tape_sqrt_times_(const hl_tape *t, const int *def, const hl_instr *in)
{
    if (in->op != HL_OP_MUL)
        return -1;
    int a = in->a, b = in->b;
    if (def[a] >= 0 && t->code[def[a]].op == HL_OP_SQRT && t->code[def[a]].a == b)
        return b;
    if (def[b] >= 0 && t->code[def[b]].op == HL_OP_SQRT && t->code[def[b]].a == a)
        return a;
    return -1;
}

void hl_tape_recip_split(double *hi, double *lo, int n)
{
    *hi = 1.0 / n;
    *lo = fma(-*hi, (double)n, 1.0) / n; /* the residual 1 - hi n is exact */
}

/* As jit.c: the reciprocal of a divisor's coefficient 0 is kept in a
 * local (inv<i>, declared at k = 0 after the line that sets the divisor),
 * and later coefficients multiply by it and by 1/k. */
static void keep_inverse(hl_buf *b, int i, const char *fmt, long reg)
{
    hl_buf_printf(b, "    const double inv%d = 1.0 / (", i);
    hl_buf_printf(b, fmt, reg);
    hl_buf_puts(b, ");\n");
}

/* DIV, KDIV (jit.c's keep_ratio): rat<i> = d[0] * inv<i> */
static void keep_ratio(hl_buf *b, int i, long d0)
{
    hl_buf_printf(b, "    const double rat%d = R[%ld] * inv%d;\n", i, d0, i);
}

static void gen_instr(hl_buf *b, terms *ts, const hl_instr *in, int i, int k, int S, int w)
{
    const int d = in->d, a = in->a, bb = in->b, x = in->x;
    const int op = in->op;
    const double rk = k > 0 ? 1.0 / k : 0; /* printed %.17g: reads back exactly */
    hl_buf_printf(b, "    R[%ld] = ", R(d, k));
    switch (op) {
    case HL_OP_NEG: hl_buf_printf(b, "-R[%ld];\n", R(a, k)); return;
    case HL_OP_ADD: hl_buf_printf(b, "R[%ld] + R[%ld];\n", R(a, k), R(bb, k)); return;
    case HL_OP_SUB: hl_buf_printf(b, "R[%ld] - R[%ld];\n", R(a, k), R(bb, k)); return;
    case HL_OP_MUL:
        if (w >= 0) { /* sqrt(w) w as w^(3/2): jit.c, hl_tape_sqrt_times_ */
            if (k == 0) {
                hl_buf_printf(b, "R[%ld]*R[%ld];\n", R(a, 0), R(bb, 0));
                keep_inverse(b, i, "R[%ld]", R(w, 0));
                hl_buf_printf(b, "    const double rat%d = 1.5*R[%ld] * inv%d;\n", i, R(d, 0), i);
                return;
            }
            for (int m = 1; m < k; m++)
                term(ts, -1, "%.17g*R[%ld]*R[%ld]", 2.5 * m - k, R(w, m), R(d, k - m));
            sum(b, ts);
            hl_buf_printf(b, " * inv%d * %.17g + R[%ld] * rat%d;\n", i, rk, R(w, k), i);
            return;
        }
        conv(ts, a, bb, 0, k, k, S);
        break;
    case HL_OP_SQR: sqr_terms(ts, a, k, S); break;
    case HL_OP_DIV:
        if (k == 0) {
            hl_buf_printf(b, "R[%ld] / R[%ld];\n", R(a, 0), R(bb, 0));
            keep_inverse(b, i, "R[%ld]", R(bb, 0));
            keep_ratio(b, i, R(d, 0));
            return;
        }
        hl_buf_printf(b, "(R[%ld] - ", R(a, k));
        conv(ts, bb, d, 1, k - 1, k, S); /* the known terms */
        sum(b, ts);
        hl_buf_printf(b, ") * inv%d - R[%ld] * rat%d;\n", i, R(bb, k), i);
        return;
    case HL_OP_ADDK:
    case HL_OP_SUBK:
    case HL_OP_KSUB:
        if (k == 0 && op == HL_OP_KSUB)
            hl_buf_printf(b, "R[%ld] - R[%ld];\n", R(bb, 0), R(a, 0));
        else if (k == 0)
            hl_buf_printf(b, "R[%ld] %c R[%ld];\n", R(a, 0), op == HL_OP_ADDK ? '+' : '-', R(bb, 0));
        else
            hl_buf_printf(b, "%sR[%ld];\n", op == HL_OP_KSUB ? "-" : "", R(a, k));
        return;
    case HL_OP_MULK: hl_buf_printf(b, "R[%ld] * R[%ld];\n", R(a, k), R(bb, 0)); return;
    case HL_OP_DIVK: hl_buf_printf(b, "R[%ld] / R[%ld];\n", R(a, k), R(bb, 0)); return;
    case HL_OP_KDIV:
        if (k == 0) {
            hl_buf_printf(b, "R[%ld] / R[%ld];\n", R(bb, 0), R(a, 0));
            keep_inverse(b, i, "R[%ld]", R(a, 0));
            keep_ratio(b, i, R(d, 0));
            return;
        }
        hl_buf_puts(b, "-");
        conv(ts, a, d, 1, k - 1, k, S); /* the known terms */
        sum(b, ts);
        hl_buf_printf(b, " * inv%d - R[%ld] * rat%d;\n", i, R(a, k), i);
        return;
    case HL_OP_POWK:
        if (k == 0) {
            hl_buf_printf(b, "pow(R[%ld], R[%ld]);\n", R(a, 0), R(bb, 0));
            keep_inverse(b, i, "R[%ld]", R(a, 0));
            return;
        }
        /* sum_{m=1..k} ((c+1) m - k) a[m] d[k-m] / (k a[0]) */
        for (int m = 1; m <= k; m++)
            term(ts, m == k ? a : -1, "((R[%ld] + 1.0) * %d.0 - %d.0)*R[%ld]*R[%ld]", R(bb, 0), m, k, R(a, m),
                 R(d, k - m));
        sum(b, ts);
        hl_buf_printf(b, " * inv%d * %.17g;\n", i, rk);
        return;
    case HL_OP_SQRT:
        if (k == 0) {
            hl_buf_printf(b, "sqrt(R[%ld]);\n", R(a, 0));
            keep_inverse(b, i, "2.0 * R[%ld]", R(d, 0));
            return;
        }
        hl_buf_printf(b, "(R[%ld] - ", R(a, k));
        sqr_terms_from(ts, d, k, 1, S);
        sum(b, ts);
        hl_buf_printf(b, ") * inv%d;\n", i);
        return;
    case HL_OP_EXP:
        if (k == 0) {
            hl_buf_printf(b, "exp(R[%ld]);\n", R(a, 0));
            return;
        }
        wconv(ts, a, d, 1, k, k, 1, 0, S);
        sum(b, ts);
        hl_buf_printf(b, " * %.17g;\n", rk);
        return;
    case HL_OP_LOG:
        if (k == 0) {
            hl_buf_printf(b, "log(R[%ld]);\n", R(a, 0));
            keep_inverse(b, i, "R[%ld]", R(a, 0));
            return;
        }
        hl_buf_printf(b, "(%d.0 * R[%ld] - ", k, R(a, k));
        wconv(ts, a, d, 1, k - 1, k, -1, k, S);
        sum(b, ts);
        hl_buf_printf(b, ") * inv%d * %.17g;\n", i, rk);
        return;
    case HL_OP_SINCOS:
    case HL_OP_SINHCOSH: {
        int trig = op == HL_OP_SINCOS;
        if (k == 0) {
            hl_buf_printf(b, "%s(R[%ld]);\n    R[%ld] = %s(R[%ld]);\n", trig ? "sin" : "sinh", R(a, 0),
                          R(x, 0), trig ? "cos" : "cosh", R(a, 0));
            return;
        }
        wconv(ts, a, x, 1, k, k, 1, 0, S);
        sum(b, ts);
        hl_buf_printf(b, " * %.17g;\n    R[%ld] = %s", rk, R(x, k), trig ? "-" : "");
        wconv(ts, a, d, 1, k, k, 1, 0, S);
        sum(b, ts);
        hl_buf_printf(b, " * %.17g;\n", rk);
        return;
    }
    case HL_OP_TAN:
    case HL_OP_TANH: {
        int t = op == HL_OP_TAN;
        if (k == 0) {
            hl_buf_printf(b, "%s(R[%ld]);\n", t ? "tan" : "tanh", R(a, 0));
        } else {
            hl_buf_printf(b, "R[%ld] %s ", R(a, k), t ? "+" : "-");
            wconv(ts, a, x, 1, k, k, 1, 0, S);
            sum(b, ts);
            hl_buf_printf(b, " * %.17g;\n", rk);
        }
        hl_buf_printf(b, "    R[%ld] = ", R(x, k));
        sqr_terms(ts, d, k, S);
        break;
    }
    case HL_OP_ATAN:
    case HL_OP_ASIN:
    case HL_OP_ACOS:
        /* first the aux series x, then d */
        hl_buf_printf(b, "0.0;\n    R[%ld] = ", R(x, k));
        if (op == HL_OP_ATAN) {
            if (k == 0)
                hl_buf_puts(b, "1.0 + ");
            conv(ts, a, a, 0, k, k, S);
            sum(b, ts);
            hl_buf_puts(b, ";\n");
        } else if (k == 0) {
            hl_buf_printf(b, "sqrt(1.0 - R[%ld]*R[%ld]);\n", R(a, 0), R(a, 0));
        } else {
            hl_buf_puts(b, "(-");
            conv(ts, a, a, 0, k, k, S);
            sum(b, ts);
            hl_buf_puts(b, " - ");
            conv(ts, x, x, 1, k - 1, k, S);
            sum(b, ts);
            hl_buf_printf(b, ") * inv%d * 0.5;\n", i);
        }
        hl_buf_printf(b, "    R[%ld] = ", R(d, k));
        if (k == 0) {
            hl_buf_printf(b, "%s(R[%ld]);\n", op == HL_OP_ATAN ? "atan" : op == HL_OP_ASIN ? "asin" : "acos",
                          R(a, 0));
            keep_inverse(b, i, "R[%ld]", R(x, 0));
            return;
        }
        hl_buf_printf(b, "(%s%d.0 * R[%ld] - ", op == HL_OP_ACOS ? "-" : "", k, R(a, k));
        wconv(ts, x, d, 1, k - 1, k, -1, k, S);
        sum(b, ts);
        hl_buf_printf(b, ") * inv%d * %.17g;\n", i, rk);
        return;
    case HL_OP_ATAN2: /* x = a^2 + b^2 first, then d */
        hl_buf_printf(b, "0.0;\n    R[%ld] = ", R(x, k));
        conv(ts, a, a, 0, k, k, S);
        conv(ts, bb, bb, 0, k, k, S);
        sum(b, ts);
        hl_buf_printf(b, ";\n    R[%ld] = ", R(d, k));
        if (k == 0) {
            hl_buf_printf(b, "atan2(R[%ld], R[%ld]);\n", R(a, 0), R(bb, 0));
            keep_inverse(b, i, "R[%ld]", R(x, 0));
            return;
        }
        hl_buf_puts(b, "(");
        wconv(ts, a, bb, 1, k, k, 1, 0, S);
        sum(b, ts);
        hl_buf_puts(b, " - ");
        wconv(ts, bb, a, 1, k, k, 1, 0, S);
        sum(b, ts);
        hl_buf_puts(b, " - ");
        wconv(ts, x, d, 1, k - 1, k, -1, k, S);
        sum(b, ts);
        hl_buf_printf(b, ") * inv%d * %.17g;\n", i, rk);
        return;
    }
    sum(b, ts);
    hl_buf_puts(b, ";\n");
}

/* The C source of void hl_native(double *R): the recursion of
 * hl_tape_taylor_ode_d at this order on the register file R. */
static char *gen_source(const hl_tape *t, int order)
{
    const int S = order + 1;
    hl_buf b;
    terms ts = {0};
    int *def = hl_tape_defs_(t);
    hl_buf_init(&b);
    hl_buf_puts(&b, "/* generated by hamlie (src/tape/native.c) */\n#include <math.h>\n"
                    "#ifdef __FMA__ /* f/n rounded once: fma(f, hi, f lo) (jit.c's over_k1) */\n"
                    "#define HL_OVER(f, hi, lo, n) fma((f), (hi), (f) * (lo))\n"
                    "#else\n#define HL_OVER(f, hi, lo, n) ((f) / (n))\n#endif\n"
                    "void hl_native(double *restrict R)\n{\n");
    for (int k = 0; k < order; k++) {
        hl_buf_printf(&b, "    /* coefficient %d */\n", k);
        for (int i = 0; i < t->ncode; i++)
            gen_instr(&b, &ts, &t->code[i], i, k, S, hl_tape_sqrt_times_(t, def, &t->code[i]));
        for (int i = 0; i < t->nin; i++) { /* / (k+1) as jit.c's over_k1 */
            double hi, lo;
            hl_tape_recip_split(&hi, &lo, k + 1);
            long to = R(i, k + 1), from = R(t->outreg[i], k);
            if (lo == 0)
                hl_buf_printf(&b, "    R[%ld] = R[%ld] * %a;\n", to, from, hi);
            else
                hl_buf_printf(&b, "    R[%ld] = HL_OVER(R[%ld], %a, %a, %d.0);\n", to, from, hi,
                              lo, k + 1);
        }
    }
    hl_buf_puts(&b, "}\n");
    free(ts.t);
    free(def);
    return hl_buf_take(&b);
}

/* ---- compiling and loading ---------------------------------------------------- */

static int run_cc(const char *cc, const char *src, const char *so, hl_error *err)
{
    char *argv[] = {(char *)cc, "-O1", "-march=native", "-fPIC", "-shared", "-o", (char *)so, (char *)src, "-lm", NULL};
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
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "the C compiler '%s' failed on the generated code", cc);
    return HL_OK;
}

hl_status hl_tape_native(hl_tape *t, int order, hl_error *err)
{
    if (order < 1 || order > 1000)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "native order must be 1..1000 (got %d)", order);
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

    int status = HL_OK;
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
    void (*fn)(double *) = NULL;
    if (h != NULL && (*(void **)&fn = dlsym(h, "hl_native")) == NULL) {
        dlclose(h);
        h = NULL;
        status = hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "compiled code lacks its entry point");
    }
    remove(so); /* a loaded object stays mapped */
    remove(src);
    rmdir(dir);
    free(dir);
    free(src);
    free(so);
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
