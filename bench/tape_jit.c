/* Benchmark: tape evaluation by the interpreter, by libgccjit's machine
 * code (hl_tape_jit), and by the same functions written by hand in C, in
 * one process; ns per evaluation, ratios, and compile times.
 *
 *   Hénon–Heiles vector field (4 in, 4 out, from H via hl_tape_hamiltonian)
 *   Kepler vector field (the same, H = |p|^2/2 - 1/|q|)
 *   Störmer–Verlet step on Hénon–Heiles: one tape (q, p, D) -> (Q, P), the
 *     shape of the scheme stepper's explicit tape, iterated 1e6 steps
 *   Yoshida's 4th-order composition of three such steps (a longer tape)
 *
 * Each loop feeds the result into the next evaluation (as an integrator
 * does), so the figures are latency per evaluation, best of several runs.
 * Also checks that the compiled and interpreted runs end bitwise equal.
 * Argument: [reps] (default 5).  Without libgccjit prints the interpreter
 * only. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hamlie/tape.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static const char *const qn[2] = {"q1", "q2"}, *const pn[2] = {"p1", "p2"};
static const char *const svin[5] = {"q1", "q2", "p1", "p2", "D"};

static const hl_expr *parse(hl_pool *P, const char *s)
{
    const hl_expr *e = NULL;
    hl_error err;
    if (hl_parse(&e, P, s, &err) != HL_OK) {
        fprintf(stderr, "parse '%s': %s\n", s, err.msg);
        exit(1);
    }
    return e;
}

/* ---- hand-written references ------------------------------------------------ */

static void hh_vf(const double *z, double *f)
{
    double x = z[0], y = z[1];
    f[0] = z[2];
    f[1] = z[3];
    f[2] = -(x + 2 * x * y);
    f[3] = -(y + x * x - y * y);
}

static void kepler_vf(const double *z, double *f)
{
    double r2 = z[0] * z[0] + z[1] * z[1];
    double r3 = r2 * sqrt(r2);
    f[0] = z[2];
    f[1] = z[3];
    f[2] = -z[0] / r3;
    f[3] = -z[1] / r3;
}

/* in: q1 q2 p1 p2 D; out: Q1 Q2 P1 P2 */
static void hh_sv(const double *in, double *out)
{
    double x = in[0], y = in[1], D = in[4], h = D / 2;
    double a = in[2] - h * (x + 2 * x * y), b = in[3] - h * (y + x * x - y * y);
    x += D * a;
    y += D * b;
    out[0] = x;
    out[1] = y;
    out[2] = a - h * (x + 2 * x * y);
    out[3] = b - h * (y + x * x - y * y);
}

static const double yw1 = 1.3512071919596578, yw0 = -1.7024143839193153; /* 1/(2-2^(1/3)) */

static void hh_sv4(const double *in, double *out)
{
    double z[5] = {in[0], in[1], in[2], in[3], yw1 * in[4]};
    hh_sv(z, z);
    z[4] = yw0 * in[4];
    hh_sv(z, z);
    z[4] = yw1 * in[4];
    hh_sv(z, out);
}

/* ---- the tapes --------------------------------------------------------------- */

static hl_tape *ham_tape(hl_pool *P, const char *H)
{
    hl_tape *t = NULL;
    hl_error err;
    if (hl_tape_hamiltonian(&t, P, parse(P, H), 2, qn, pn, 0, NULL, NULL, &err) != HL_OK) {
        fprintf(stderr, "%s\n", err.msg);
        exit(1);
    }
    return t;
}

/* One Störmer–Verlet step of H = |p|^2/2 + V(q) as expressions over
 * (q, p, D), given the step size as an expression Dx of D. */
static void sv_exprs(const hl_expr **out, hl_pool *P, const hl_expr *V, const hl_expr *const *z,
                     const hl_expr *Dx)
{
    const hl_expr *h = hl_div(P, Dx, hl_num_si(P, 2)), *ph[2], *Q[2];
    for (int i = 0; i < 2; i++)
        ph[i] = hl_sub(P, z[2 + i],
                       hl_mul(P, h, hl_expr_subst(P, hl_expr_diff(P, V, qn[i]), 2, qn, z)));
    for (int i = 0; i < 2; i++)
        Q[i] = hl_add(P, z[i], hl_mul(P, Dx, ph[i]));
    for (int i = 0; i < 2; i++) {
        out[i] = Q[i];
        out[2 + i] =
            hl_sub(P, ph[i], hl_mul(P, h, hl_expr_subst(P, hl_expr_diff(P, V, qn[i]), 2, qn, Q)));
    }
}

static hl_tape *sv_tape(hl_pool *P, int stages)
{
    const hl_expr *V = parse(P, "(q1^2 + q2^2)/2 + q1^2*q2 - q2^3/3");
    const hl_expr *z[4], *D = hl_sym(P, "D"), *outs[4];
    for (int i = 0; i < 4; i++)
        z[i] = hl_sym(P, svin[i]);
    if (stages == 1) {
        sv_exprs(outs, P, V, z, D);
    } else if (stages != 3) { /* m equal substeps D/m: long tapes, for the compile-time scaling */
        const hl_expr *cur[4] = {z[0], z[1], z[2], z[3]};
        for (int s = 0; s < stages; s++) {
            sv_exprs(outs, P, V, cur, hl_div(P, D, hl_num_si(P, stages)));
            memcpy(cur, outs, sizeof cur);
        }
    } else { /* Yoshida: w1, w0, w1 as exact-enough rationals are not needed: w's as parsed text */
        const hl_expr *w1 = parse(P, "1/(2 - 2^(1/3))"), *w0 = parse(P, "-2^(1/3)/(2 - 2^(1/3))");
        const hl_expr *ws[3] = {w1, w0, w1};
        const hl_expr *cur[4] = {z[0], z[1], z[2], z[3]};
        for (int s = 0; s < 3; s++) {
            sv_exprs(outs, P, V, cur, hl_mul(P, ws[s], D));
            memcpy(cur, outs, sizeof cur);
        }
    }
    hl_tape *t = NULL;
    hl_error err;
    if (hl_tape_new(&t, outs, 4, svin, 5, &err) != HL_OK) {
        fprintf(stderr, "%s\n", err.msg);
        exit(1);
    }
    return t;
}

/* ---- timing ------------------------------------------------------------------ */

typedef void (*fn_t)(const double *in, double *out);

/* Integrator-like loops: vector field z += 1e-3 f(z); step z = step(z, D). */
static double run_vf(fn_t f, hl_tape *t, const double *z0, long n, double *zend)
{
    double z[4], fz[4];
    memcpy(z, z0, sizeof z);
    double t0 = now();
    for (long k = 0; k < n; k++) {
        if (f)
            f(z, fz);
        else
            hl_tape_eval_d(fz, z, t);
        for (int i = 0; i < 4; i++)
            z[i] += 1e-3 * fz[i];
    }
    double dt = now() - t0;
    memcpy(zend, z, sizeof z);
    return dt;
}

static double run_step(fn_t f, hl_tape *t, const double *z0, long n, double *zend)
{
    double in[5], out[4];
    memcpy(in, z0, 4 * sizeof *in);
    in[4] = 0.01;
    double t0 = now();
    for (long k = 0; k < n; k++) {
        if (f)
            f(in, out);
        else
            hl_tape_eval_d(out, in, t);
        memcpy(in, out, sizeof out);
    }
    double dt = now() - t0;
    memcpy(zend, in, 4 * sizeof *in);
    return dt;
}

/* The same run through hl_tape_iterate: the whole loop is one call. */
static double run_iter(fn_t f, hl_tape *t, const double *z0, long n, double *zend)
{
    double in[5];
    memcpy(in, z0, 4 * sizeof *in);
    in[4] = 0.01;
    double t0 = now();
    long k = hl_tape_iterate(in, n, t);
    double dt = now() - t0;
    if (k != n)
        fprintf(stderr, "iterate stopped after %ld steps\n", k);
    memcpy(zend, in, 4 * sizeof *in);
    return dt;
}

/* Hand-written and inlined into the loop: the best C can do (the issue's
 * "hand-written" figure). */
static double run_inline_sv(fn_t f, hl_tape *t, const double *z0, long n, double *zend)
{
    double in[5];
    memcpy(in, z0, 4 * sizeof *in);
    in[4] = 0.01;
    double t0 = now();
    for (long k = 0; k < n; k++)
        hh_sv(in, in);
    double dt = now() - t0;
    memcpy(zend, in, 4 * sizeof *in);
    return dt;
}

static double run_inline_sv4(fn_t f, hl_tape *t, const double *z0, long n, double *zend)
{
    double in[5];
    memcpy(in, z0, 4 * sizeof *in);
    in[4] = 0.01;
    double t0 = now();
    for (long k = 0; k < n; k++)
        hh_sv4(in, in);
    double dt = now() - t0;
    memcpy(zend, in, 4 * sizeof *in);
    return dt;
}

static double best_of(int reps, double (*run)(fn_t, hl_tape *, const double *, long, double *),
                      fn_t f, hl_tape *t, const double *z0, long n, double *zend)
{
    double best = INFINITY;
    for (int r = 0; r < reps; r++)
        best = fmin(best, run(f, t, z0, n, zend));
    return 1e9 * best / (double)n;
}

static void bench(const char *name, hl_tape *t, fn_t hand, int is_step, int reps)
{
    double (*inl)(fn_t, hl_tape *, const double *, long, double *) = hand == hh_sv ? run_inline_sv
                                                                     : hand == hh_sv4
                                                                         ? run_inline_sv4
                                                                         : NULL;
    static const double z0[4] = {0.1, -0.2, 0.3, 0.15};
    const long n = 2000000;
    double (*run)(fn_t, hl_tape *, const double *, long, double *) = is_step ? run_step : run_vf;
    double zi[4], zj[4], zh[4];
    double ns_hand = best_of(reps, run, hand, NULL, z0, n, zh);
    double ns_int = best_of(reps, run, NULL, t, z0, n, zi);
    printf("%-24s %3d ops  hand %6.2f ns  interp %6.2f ns (%5.1fx)", name, hl_tape_nops(t), ns_hand,
           ns_int, ns_int / ns_hand);
    hl_error err;
    double best_ms = INFINITY;
    for (int r = 0; r < 5; r++) { /* compile time: best of 5 */
        double c0 = now();
        if (hl_tape_jit(t, &err) != HL_OK) {
            printf("  jit: %s\n", err.msg);
            return;
        }
        best_ms = fmin(best_ms, 1e3 * (now() - c0));
    }
    double ns_jit = best_of(reps, run, NULL, t, z0, n, zj);
    printf("  jit %6.2f ns (%4.2fx hand, %4.1fx faster)  compile %5.1f ms  break-even %.0fk evals  "
           "%s\n",
           ns_jit, ns_jit / ns_hand, ns_int / ns_jit, best_ms,
           ns_int > ns_jit ? best_ms * 1e6 / (ns_int - ns_jit) / 1e3 : INFINITY,
           memcmp(zi, zj, sizeof zi) == 0 ? "bitwise = interp" : "DIFFERS from interp");
    if (is_step) { /* a fixed-step run: the whole loop compiled vs written by hand, inlined */
        double zk[4];
        double ns_inl = best_of(reps, inl, NULL, NULL, z0, n, zh);
        double ns_it = best_of(reps, run_iter, NULL, t, z0, n, zk);
        hl_tape_jit_clear(t);
        double ns_iti = best_of(reps, run_iter, NULL, t, z0, n / 4, zi);
        printf(
            "%-24s          hand inlined %6.2f ns  hl_tape_iterate: interp %6.2f ns, jit %6.2f ns "
            "(%4.2fx hand inlined)  %s\n",
            "", ns_inl, ns_iti, ns_it, ns_it / ns_inl,
            memcmp(zk, zj, sizeof zk) == 0 ? "bitwise = eval loop" : "DIFFERS from eval loop");
    }
    hl_tape_jit_clear(t);
}

int main(int argc, char **argv)
{
    int reps = argc > 1 ? atoi(argv[1]) : 5;
    if (reps < 1)
        reps = 1;
    hl_pool *P = hl_pool_new();
    hl_tape *hh = ham_tape(P, "(p1^2 + p2^2)/2 + (q1^2 + q2^2)/2 + q1^2*q2 - q2^3/3");
    hl_tape *kep = ham_tape(P, "(p1^2 + p2^2)/2 - 1/sqrt(q1^2 + q2^2)");
    hl_tape *sv = sv_tape(P, 1), *sv4 = sv_tape(P, 3);
    printf("libgccjit: %s; ns per evaluation, best of %d runs of 2e6\n",
           hl_tape_jit_available() ? "yes" : "no (interpreter only)", reps);
    bench("Henon-Heiles field", hh, hh_vf, 0, reps);
    bench("Kepler field", kep, kepler_vf, 0, reps);
    bench("Stormer-Verlet HH step", sv, hh_sv, 1, reps);
    bench("Yoshida-4 SV HH step", sv4, hh_sv4, 1, reps);
    if (hl_tape_jit_available()) {
        printf("\ncompile time against tape length (Stormer-Verlet, m substeps in one tape):\n");
        for (int m = 2; m <= 162; m *= 3) {
            hl_tape *tm = sv_tape(P, m);
            const double z0[4] = {0.1, -0.2, 0.3, 0.15};
            double zi[4], zj[4];
            long n = 20000000 / (m * 10);
            double ns_int = best_of(reps, run_step, NULL, tm, z0, n, zi);
            hl_error err;
            double c0 = now();
            if (hl_tape_jit(tm, &err) != HL_OK) {
                printf("jit: %s\n", err.msg);
                break;
            }
            double ms = 1e3 * (now() - c0);
            double ns_jit = best_of(reps, run_step, NULL, tm, z0, n, zj);
            printf("  m %3d: %5d ops  compile %6.1f ms  interp %8.1f ns  jit %7.1f ns (%4.1fx)  "
                   "break-even %6.0fk evals  %s\n",
                   m, hl_tape_nops(tm), ms, ns_int, ns_jit, ns_int / ns_jit,
                   ms * 1e6 / (ns_int - ns_jit) / 1e3,
                   memcmp(zi, zj, sizeof zi) == 0 ? "bitwise = interp" : "DIFFERS");
            hl_tape_free(tm);
        }
    }
    hl_tape_free(hh);
    hl_tape_free(kep);
    hl_tape_free(sv);
    hl_tape_free(sv4);
    hl_pool_free(P);
    return 0;
}
