/* Benchmark: hl_run_fixed (the scheme's stepper, H evaluated at every step
 * for max |H - H0|, no rows written) against the same scheme written by
 * hand in C, in the same process, for every scheme of the catalog that runs
 * on the pendulum H = p^2/2 - cos(q) from (1.3, 0), dt = 0.01, 10^6 steps.
 * Two hand-written figures: the step alone, and the step plus H at every
 * step (what the driver computes; the ratio that counts is hl_run / hand+H).
 * Also: the driver with the reference trajectory on (sigma at every step).
 *
 * The hand loops are what one would write for this H: explicit schemes
 * inline (a force shared by two kicks at the same q computed once); the
 * implicit ones by Newton's method with the analytic Jacobian of the
 * pendulum's equations, from explicit Euler's prediction, stopping when the
 * correction is at rounding level (|dU| <= 4 eps max(1, |U|)) or after 50
 * iterations (a hit is an error): the implicit midpoint rule and Gonzalez
 * on (Q, P), the Gauss methods on the 2s stage increments (full Newton: the
 * Jacobian at the current stages), AVF on P (Q = q + D (p + P)/2 given by
 * P).  Rows "/P" and "/q": the midpoint rule on P alone and the Gauss
 * methods on the s q increments alone, the equations linear in the others
 * eliminated by hand, as hamlie eliminates them (Newton then converges in 2
 * iterations, not 3).  AVF and Itoh-Abe (the same scheme for a separable H,
 * coordinates q then p) use the pendulum's closed-form average
 * (cos q - cos Q)/(Q - q) = sin(m) sin(h/2)/(h/2), Gonzalez its remainder
 * in closed form; hamlie, for any H, integrates by the Taylor series at
 * s = 1/2 to degree 14 (or Gauss-Legendre, 8 nodes, where that is cheaper:
 * step.c) and forms the Gonzalez remainder as the integral of
 * (grad H(z + s dz) - grad H(m)).dz.
 * The final states must agree with hamlie's (|difference| < 1e-9; else
 * exit 1), which shows that each loop is the same scheme.
 *
 * Prints milliseconds (best of reps) and the ratios, then the worst ratio
 * and the rows over 1.3 (the goal of issue 5).
 * Arguments: [reps] (default 3) [jit] (hl_run_set_jit: machine code for
 * long runs, as the CLI does). */
#define _GNU_SOURCE /* sincos */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hamlie/run.h"

#define DT 0.01
#define NSTEPS 1000000L
#define NEWTON_MAX 50

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* volatile sink so the compiler keeps the H evaluations */
static volatile double sink;

/* the hand Newton's iterations, and the steps where it stopped at
 * NEWTON_MAX without converging (it: the index of the last iteration, or
 * NEWTON_MAX) */
static long newton_its, capped;
#define NEWTON_DONE(it) (newton_its += (it) + ((it) < NEWTON_MAX), capped += (it) == NEWTON_MAX)

/* A hand loop: the step (the rest of the arguments: a block that may hold
 * commas) advances q, p, the loop's locals, by DT. */
#define HAND(name, ...)                                                                       \
    static void name(double *z, int withH)                                                  \
    {                                                                                        \
        double q = z[0], p = z[1], H0 = p * p / 2 - cos(q), m = 0;                           \
        for (long k = 0; k < NSTEPS; k++) {                                                  \
            __VA_ARGS__;                                                                     \
            if (withH)                                                                       \
                m = fmax(m, fabs(p * p / 2 - cos(q) - H0));                                  \
        }                                                                                    \
        z[0] = q, z[1] = p, sink = m;                                                        \
    }

static const double D = DT;

/* ---- explicit ------------------------------------------------------------ */

/* Z = z + D J grad H(z); the paper's Euler method is the same map */
HAND(euler, {
    double Q = q + D * p, P = p - D * sin(q);
    q = Q, p = P;
})

/* P = p - D Hq(q, P), Q = q + D Hp(q, P) */
HAND(symplectic_euler_a, {
    p = p - D * sin(q);
    q = q + D * p;
})

/* Q = q + D Hp(Q, p), P = p - D Hq(Q, p) */
HAND(symplectic_euler_b, {
    q = q + D * p;
    p = p - D * sin(q);
})

static inline void kdk(double *q, double *p, double h)
{
    double ph = *p - h / 2 * sin(*q);
    *q = *q + h * ph;
    *p = ph - h / 2 * sin(*q);
}

HAND(verlet_kdk, kdk(&q, &p, D))

/* qh = q + D/2 p, P = p - D sin(qh), Q = qh + D/2 P */
HAND(verlet_dkd, {
    double qh = q + D / 2 * p;
    p = p - D * sin(qh);
    q = qh + D / 2 * p;
})

HAND(rk4, {
    double k1q = p, k1p = -sin(q);
    double k2q = p + D / 2 * k1p, k2p = -sin(q + D / 2 * k1q);
    double k3q = p + D / 2 * k2p, k3p = -sin(q + D / 2 * k2q);
    double k4q = p + D * k3p, k4p = -sin(q + D * k3q);
    q += D / 6 * (k1q + 2 * k2q + 2 * k3q + k4q);
    p += D / 6 * (k1p + 2 * k2p + 2 * k3p + k4p);
})

/* Yoshida: kdk with w1 D, w0 D, w1 D, w1 = 1/(2 - 2^(1/3)), w0 = -2^(1/3) w1.
 * The force at the end of one kdk is the force at the start of the next
 * (the same q): computed once, 4 sines a step instead of 6, the same
 * arithmetic as three separate kdk steps. */
HAND(yoshida4, {
    const double c = cbrt(2.0), w[3] = {1 / (2 - c), -c / (2 - c), 1 / (2 - c)};
    double f = sin(q);
    for (int i = 0; i < 3; i++) {
        double h = w[i] * D, ph = p - h / 2 * f;
        q = q + h * ph;
        f = sin(q);
        p = ph - h / 2 * f;
    }
})

/* Lie series to D^4: L^k q and L^k p for L = p d/dq - sin q d/dp (the
 * derivatives along q' = p, p' = -sin q):
 *   q: p, -s, -c p, p^2 s + s c
 *   p: -s, -c p, p^2 s + s c, p^3 c + p c^2 - 3 p s^2 */
HAND(lie4, {
    double s = sin(q), c = cos(q);
    double q1 = p, p1 = -s, q2 = -s, p2 = -c * p, q3 = -c * p, p3 = s * p * p + c * s;
    double q4 = p3, p4 = c * p * p * p - 3 * s * s * p + c * c * p;
    double d2 = D * D / 2, d3 = D * D * D / 6, d4 = D * D * D * D / 24;
    q = q + D * q1 + d2 * q2 + d3 * q3 + d4 * q4;
    p = p + D * p1 + d2 * p2 + d3 * p3 + d4 * p4;
})

/* ---- implicit: Newton ------------------------------------------------------ */

static inline int small(double d, double x)
{
    return fabs(d) <= 4 * DBL_EPSILON * fmax(1, fabs(x));
}

/* Q = q + D (p + P)/2, P = p - D sin((q + Q)/2): Newton on (Q, P) */
HAND(midpoint, {
    double Q = q + D * p, P = p - D * sin(q);
    int it;
    for (it = 0; it < NEWTON_MAX; it++) {
        double s, c;
        sincos((q + Q) / 2, &s, &c);
        double f1 = Q - q - D * (p + P) / 2, f2 = P - p + D * s;
        double b = -D / 2, cc = D * c / 2, det = 1 - b * cc; /* J = [[1, b], [cc, 1]] */
        double dQ = -(f1 - b * f2) / det, dP = -(-cc * f1 + f2) / det;
        Q += dQ, P += dP;
        if (small(dQ, Q) && small(dP, P))
            break;
    }
    NEWTON_DONE(it);
    q = Q, p = P;
})

/* The same, Q = q + D (p + P)/2 eliminated (as hamlie does: that equation
 * gives Q explicitly): P = p - D sin(q + D (p + P)/4), Newton on P */
HAND(midpoint_p, {
    double P = p - D * sin(q);
    int it;
    for (it = 0; it < NEWTON_MAX; it++) {
        double s, c;
        sincos(q + D * (p + P) / 4, &s, &c);
        double dP = -(P - p + D * s) / (1 + D * D / 4 * c);
        P += dP;
        if (small(dP, P))
            break;
    }
    NEWTON_DONE(it);
    q = q + D * (p + P) / 2, p = P;
})

/* int_0^1 sin(q + s(Q - q)) ds = (cos q - cos Q)/(Q - q) = sin(m) S(h/2),
 * m = (q + Q)/2, h = Q - q, S(x) = sin(x)/x (cos q - cos Q = 2 sin(m)
 * sin(h/2)): no cancellation, where the difference of cosines loses
 * eps/|h| and Newton's correction then never reaches rounding level.  S and
 * S' by their series where |x| < 0.05 (the first term left out < 1e-20),
 * which is every step here (|h| <= D |p| < 0.02).  g and dg/dQ. */
static inline void avg_sin(double *g, double *dg, double q, double Q)
{
    double x = (Q - q) / 2, x2 = x * x, S, dS, s, c;
    if (fabs(x) < 0.05) {
        S = 1 + x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040 + x2 / 362880)));
        dS = x * (-1.0 / 3 + x2 * (1.0 / 30 + x2 * (-1.0 / 840 + x2 / 45360)));
    } else {
        double sx, cx;
        sincos(x, &sx, &cx);
        S = sx / x, dS = (cx - S) / x;
    }
    sincos((q + Q) / 2, &s, &c);
    *g = s * S;
    *dg = (c * S + s * dS) / 2;
}

/* AVF = Itoh-Abe (coordinates q, then p) for a separable H:
 * Q = q + D (p + P)/2, P = p - D (cos q - cos Q)/(Q - q): Newton on P */
HAND(avf, {
    double P = p - D * sin(q);
    int it;
    for (it = 0; it < NEWTON_MAX; it++) {
        double Q = q + D * (p + P) / 2, g, dg;
        avg_sin(&g, &dg, q, Q);
        double f = P - p + D * g, df = 1 + D * dg * D / 2, dP = -f / df;
        P += dP;
        if (small(dP, P))
            break;
    }
    NEWTON_DONE(it);
    q = q + D * (p + P) / 2, p = P;
})

/* 2 sin(h/2) - h and its derivative cos(h/2) - 1 = -2 sin(h/4)^2 */
static inline void phi(double *f, double *df, double h)
{
    double s, c;
    sincos(h / 4, &s, &c);
    *f = 4 * s * c - h;
    *df = -2 * s * s;
}

/* Gonzalez: Z - z = D J gbar, gbar = grad H(m) + R/|dz|^2 dz, m the
 * midpoint, R = H(Z) - H(z) - grad H(m).dz.  For the pendulum the p parts
 * cancel exactly and cos q - cos Q = 2 sin(m_q) sin(h/2) (h = Q - q,
 * v = P - p), so R = sin(m_q) phi(h), phi(h) = 2 sin(h/2) - h, with no
 * cancellation of O(1) terms.  With r = phi(h)/(h^2 + v^2):
 *   F1 = h - D ((p + P)/2 + sin(m_q) r v) = 0,
 *   F2 = v + D sin(m_q) (1 + r h) = 0.
 * Newton on (Q, P) with the analytic Jacobian. */
HAND(gonzalez, {
    double Q = q + D * p, P = p - D * sin(q);
    int it;
    for (it = 0; it < NEWTON_MAX; it++) {
        double h = Q - q, v = P - p, n2 = h * h + v * v, s, c, f, df;
        sincos((q + Q) / 2, &s, &c);
        phi(&f, &df, h);
        double r = 0, rh = 0, rv = 0;
        if (n2 > 0)
            r = f / n2, rh = (df - 2 * h * r) / n2, rv = -2 * v * r / n2;
        double F1 = h - D * ((p + P) / 2 + s * r * v), F2 = v + D * s * (1 + r * h);
        double a11 = 1 - D * (c / 2 * r * v + s * rh * v), a12 = -D * (0.5 + s * (rv * v + r));
        double a21 = D * (c / 2 * (1 + r * h) + s * (rh * h + r)), a22 = 1 + D * s * rv * h;
        double det = a11 * a22 - a12 * a21;
        double dQ = -(a22 * F1 - a12 * F2) / det, dP = -(-a21 * F1 + a11 * F2) / det;
        Q += dQ, P += dP;
        if (small(dQ, Q) && small(dP, P))
            break;
    }
    NEWTON_DONE(it);
    q = Q, p = P;
})

/* Gauss methods: stages Y_i = z + D sum_j a_ij f(Y_j), f = (p, -sin q).
 * Newton on the stage increments W_i = Y_i - z, 2s unknowns:
 *   F_i = W_i - D sum_j a_ij f(z + W_j),
 *   dF_i/dW_j = delta_ij I - D a_ij [[0, 1], [-cos(q + Wq_j), 0]].
 * The matrix is I + O(D) (|D a_ij cos| < 0.01 here), strictly diagonally
 * dominant: Gaussian elimination without pivoting. */
#define MAXS 3

static inline void solve(double *M, double *r, int n)
{
    for (int c = 0; c < n; c++) {
        double inv = 1 / M[c * n + c];
        for (int i = c + 1; i < n; i++) {
            double f = M[i * n + c] * inv;
            for (int j = c + 1; j < n; j++)
                M[i * n + j] -= f * M[c * n + j];
            r[i] -= f * r[c];
        }
    }
    for (int i = n - 1; i >= 0; i--) {
        for (int j = i + 1; j < n; j++)
            r[i] -= M[i * n + j] * r[j];
        r[i] /= M[i * n + i];
    }
}

static inline __attribute__((always_inline)) void
gauss_step(double *q, double *p, const int s, const double *a, const double *b)
{
    const int n = 2 * s;
    double M[4 * MAXS * MAXS], W[2 * MAXS], r[2 * MAXS], sn[MAXS], cs[MAXS];
    double sq0 = sin(*q);
    for (int i = 0; i < s; i++) { /* W from explicit Euler's prediction, c_i D f(z) */
        double ci = 0;
        for (int j = 0; j < s; j++)
            ci += a[i * s + j];
        W[2 * i] = ci * D * *p, W[2 * i + 1] = -ci * D * sq0;
    }
    int it;
    for (it = 0; it < NEWTON_MAX; it++) {
        for (int j = 0; j < s; j++)
            sincos(*q + W[2 * j], &sn[j], &cs[j]);
        for (int i = 0; i < s; i++) {
            double sq = 0, sp = 0;
            for (int j = 0; j < s; j++) {
                double Da = D * a[i * s + j], *B = M + (2 * i) * n + 2 * j, d = i == j;
                sq += a[i * s + j] * (*p + W[2 * j + 1]), sp -= a[i * s + j] * sn[j];
                B[0] = d, B[1] = -Da, B[n] = Da * cs[j], B[n + 1] = d;
            }
            r[2 * i] = -(W[2 * i] - D * sq), r[2 * i + 1] = -(W[2 * i + 1] - D * sp);
        }
        solve(M, r, n);
        int done = 1;
        for (int i = 0; i < n; i++) {
            W[i] += r[i];
            done &= small(r[i], W[i]);
        }
        if (done)
            break;
    }
    NEWTON_DONE(it);
    double sq = 0, sp = 0;
    for (int j = 0; j < s; j++)
        sq += b[j] * (*p + W[2 * j + 1]), sp -= b[j] * sin(*q + W[2 * j]);
    *q += D * sq, *p += D * sp;
}

/* The same with the p increments eliminated (as hamlie does: with Hp = p
 * the q stages are linear in them), Newton on the s q increments:
 *   Wp_i = -D sum_j a_ij sin(q + Wq_j),
 *   F_i = Wq_i - c_i D p + D^2 sum_j (A^2)_ij sin(q + Wq_j),
 *   dF_i/dWq_j = delta_ij + D^2 (A^2)_ij cos(q + Wq_j). */
static inline __attribute__((always_inline)) void
gauss_step_q(double *q, double *p, const int s, const double *a, const double *b)
{
    double A2[MAXS * MAXS], ci[MAXS], M[MAXS * MAXS], W[MAXS], r[MAXS], sn[MAXS], cs[MAXS];
    double sq0 = sin(*q);
    for (int i = 0; i < s; i++) {
        ci[i] = 0;
        for (int j = 0; j < s; j++) {
            ci[i] += a[i * s + j], A2[i * s + j] = 0;
            for (int k = 0; k < s; k++)
                A2[i * s + j] += a[i * s + k] * a[k * s + j];
        }
    }
    for (int i = 0; i < s; i++) { /* explicit Euler's prediction */
        double w = ci[i] * D * *p;
        for (int j = 0; j < s; j++)
            w -= D * D * A2[i * s + j] * sq0;
        W[i] = w;
    }
    int it;
    for (it = 0; it < NEWTON_MAX; it++) {
        for (int j = 0; j < s; j++)
            sincos(*q + W[j], &sn[j], &cs[j]);
        for (int i = 0; i < s; i++) {
            double t = 0;
            for (int j = 0; j < s; j++) {
                t += A2[i * s + j] * sn[j];
                M[i * s + j] = (i == j) + D * D * A2[i * s + j] * cs[j];
            }
            r[i] = -(W[i] - ci[i] * D * *p + D * D * t);
        }
        solve(M, r, s);
        int done = 1;
        for (int i = 0; i < s; i++) {
            W[i] += r[i];
            done &= small(r[i], W[i]);
        }
        if (done)
            break;
    }
    NEWTON_DONE(it);
    double fp[MAXS], sq = 0, sp = 0;
    for (int j = 0; j < s; j++)
        fp[j] = -sin(*q + W[j]);
    for (int j = 0; j < s; j++) {
        double wp = 0;
        for (int k = 0; k < s; k++)
            wp += D * a[j * s + k] * fp[k];
        sq += b[j] * (*p + wp), sp += b[j] * fp[j];
    }
    *q += D * sq, *p += D * sp;
}

#define R3 1.7320508075688772
static const double g2a[] = {0.25, 0.25 - R3 / 6, 0.25 + R3 / 6, 0.25}, g2b[] = {0.5, 0.5};
#define R15 3.872983346207417
static const double g3a[] = {5.0 / 36, 2.0 / 9 - R15 / 15, 5.0 / 36 - R15 / 30,
                             5.0 / 36 + R15 / 24, 2.0 / 9, 5.0 / 36 - R15 / 24,
                             5.0 / 36 + R15 / 30, 2.0 / 9 + R15 / 15, 5.0 / 36};
static const double g3b[] = {5.0 / 18, 4.0 / 9, 5.0 / 18};

HAND(gauss2, gauss_step(&q, &p, 2, g2a, g2b))
HAND(gauss3, gauss_step(&q, &p, 3, g3a, g3b))
HAND(gauss2_q, gauss_step_q(&q, &p, 2, g2a, g2b))
HAND(gauss3_q, gauss_step_q(&q, &p, 3, g3a, g3b))

/* ---- the table ------------------------------------------------------------ */

typedef struct entry {
    const char *label, *name; /* the row's, hamlie's scheme */
    void (*hand)(double *, int);
    const char *note;
} entry;

/* Rows "/P" and "/q": the implicit midpoint rule and the Gauss methods
 * again, the hand loop solving for fewer unknowns, as hamlie does. */
static const entry table[] = {
    {"euler", "euler", euler, ""},
    {"paper-euler", "paper-euler", euler, "hand: the euler loop"},
    {"symplectic-euler-a", "symplectic-euler-a", symplectic_euler_a, ""},
    {"symplectic-euler-b", "symplectic-euler-b", symplectic_euler_b, ""},
    {"stormer-verlet-kdk", "stormer-verlet-kdk", verlet_kdk, ""},
    {"stormer-verlet-dkd", "stormer-verlet-dkd", verlet_dkd, ""},
    {"yoshida4", "yoshida4", yoshida4, ""},
    {"rk4", "rk4", rk4, ""},
    {"lie4", "lie4", lie4, ""},
    {"implicit-midpoint", "implicit-midpoint", midpoint, "hand: Newton on (Q, P)"},
    {"implicit-midpoint/P", "implicit-midpoint", midpoint_p, "hand: Newton on P"},
    {"gauss2", "gauss2", gauss2, "hand: Newton on the 4 stage increments"},
    {"gauss2/q", "gauss2", gauss2_q, "hand: Newton on the 2 q increments"},
    {"gauss3", "gauss3", gauss3, "hand: Newton on the 6 stage increments"},
    {"gauss3/q", "gauss3", gauss3_q, "hand: Newton on the 3 q increments"},
    {"avf", "avf", avf, "hand: closed-form average, Newton on P"},
    {"itoh-abe", "itoh-abe", avf, "hand: the avf loop"},
    {"gonzalez", "gonzalez", gonzalez, "hand: closed-form remainder, Newton on (Q, P)"},
};

static double best_hand(void (*f)(double *, int), int withH, int reps, double *z)
{
    double best = 1e300;
    for (int r = 0; r < reps; r++) {
        z[0] = 1.3, z[1] = 0;
        double t0 = now();
        f(z, withH);
        best = fmin(best, now() - t0);
    }
    return best;
}

int main(int argc, char **argv)
{
    int reps = argc > 1 ? atoi(argv[1]) : 3, bad = 0;
    int jit = argc > 2 && strcmp(argv[2], "jit") == 0;
    if (reps < 1)
        reps = 1;
    hl_error err;
    hl_system_spec spec = {"p^2/2 - cos(q)", NULL, NULL, NULL, NULL};
    hl_system *sys = NULL;
    if (hl_system_new(&sys, &spec, &err) != HL_OK) {
        fprintf(stderr, "run_fixed: %s\n", err.msg);
        return 1;
    }
    printf("pendulum, dt = %g, %ld steps, best of %d (ms)%s\n", DT, NSTEPS, reps,
           jit ? ", machine code on (as the CLI)" : "");
    printf("%-20s %9s %9s %9s %7s %7s %12s  %s\n", "scheme", "hand", "hand+H", "hl_run", "ratio",
           "ratioH", "hl_run+ref", "");
    double worst = 0;
    const char *worst_name = "";
    char over[512] = "";
    for (size_t i = 0; i < sizeof table / sizeof table[0]; i++) {
        const entry *e = &table[i];
        hl_scheme *s = NULL;
        hl_run *run = NULL;
        if (hl_scheme_new(&s, e->name, 0, sys, &err) != HL_OK ||
            hl_run_new(&run, sys, s, &err) != HL_OK) {
            fprintf(stderr, "run_fixed: %s: %s\n", e->name, err.msg);
            return 1;
        }
        double zh[2], zhh[2], z0[2] = {1.3, 0};
        capped = newton_its = 0;
        double th = best_hand(e->hand, 0, reps, zh), thh = best_hand(e->hand, 1, reps, zhh);
        double td = 1e300, tr = 1e300, first = 0;
        hl_run_set_reference(run, 0, 0);
        hl_run_set_jit(run, jit);
        for (int r = 0; r < reps; r++) {
            double t0 = now();
            if (hl_run_fixed(run, z0, DT, NSTEPS * DT, 1, NULL, NULL, NULL, &err) != HL_OK) {
                fprintf(stderr, "run_fixed: %s: %s\n", e->name, err.msg);
                return 1;
            }
            double t = now() - t0;
            if (r == 0)
                first = t;
            td = fmin(td, t);
        }
        const double *z = hl_run_state(run);
        double diff = fmax(fabs(z[0] - zh[0]), fabs(z[1] - zh[1]));
        if (!(diff < 1e-9)) {
            fprintf(stderr, "run_fixed: %s: final states differ by %.3g\n", e->label, diff);
            bad = 1;
        }
        if (capped > 0) {
            fprintf(stderr, "run_fixed: %s: the hand Newton hit %d iterations in %ld steps\n",
                    e->label, NEWTON_MAX, capped);
            bad = 1;
        }
        hl_run_set_reference(run, 1, 1e-15);
        double t0 = now();
        hl_run_fixed(run, z0, DT, NSTEPS * DT, 1, NULL, NULL, NULL, &err);
        tr = now() - t0;
        printf("%-20s %9.1f %9.1f %9.1f %7.2f %7.2f %12.1f  first run %.1f; |diff| %.1e",
               e->label, 1e3 * th, 1e3 * thh, 1e3 * td, td / th, td / thh, 1e3 * tr, 1e3 * first,
               diff);
        if (newton_its > 0)
            printf("; hand Newton %.2f its/step", (double)newton_its / (2.0 * reps * NSTEPS));
        printf("%s%s\n", *e->note ? "; " : "", e->note);
        if (td / thh > worst)
            worst = td / thh, worst_name = e->label;
        if (td / thh > 1.3 && strlen(over) + strlen(e->label) + 2 < sizeof over)
            strcat(strcat(over, " "), e->label);
        hl_run_free(run);
        hl_scheme_free(s);
    }
    printf("worst ratio to the hand loop with H: %.2f (%s)\n", worst, worst_name);
    printf("over 1.3:%s\n", *over ? over : " none");
    hl_system_free(sys);
    return bad;
}
