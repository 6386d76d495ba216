/* Benchmark: hl_run_fixed (the scheme's stepper, H evaluated at every step
 * for max |H - H0|, no rows written) against the same scheme written by
 * hand in C, in the same process, for every scheme of the catalog that runs
 * on the pendulum H = p^2/2 - cos(q) from (1.3, 0), dt = 0.01, 10^6 steps.
 * Two hand-written figures: the step alone, and the step plus H at every
 * step (what the driver computes; the ratio that counts is hl_run / hand+H).
 * Also: the driver with the reference trajectory on (sigma at every step).
 *
 * The hand loops are what one would write for this H: explicit schemes
 * inline; implicit ones by Newton's method with the analytic Jacobian (the
 * Gauss methods by simplified Newton on the stages with the Jacobian at the
 * start of the step, as Hairer-Wanner do), from explicit Euler's
 * prediction, stopping at a correction at rounding level; AVF and Itoh-Abe
 * (the same scheme for a separable H) with the pendulum's closed-form
 * average (cos q - cos Q)/(Q - q), where hamlie integrates by Gauss-Legendre
 * quadrature (8 nodes) for any H.  The final states must agree with
 * hamlie's (|difference| < 1e-9; else exit 1), which shows that each loop is
 * the same scheme.
 *
 * Prints milliseconds (best of reps) and the ratios, then the worst ratio.
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

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* volatile sink so the compiler keeps the H evaluations */
static volatile double sink;

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

/* Yoshida: kdk with w1 D, w0 D, w1 D */
HAND(yoshida4, {
    const double c = cbrt(2.0), w1 = 1 / (2 - c), w0 = -c / (2 - c);
    kdk(&q, &p, w1 * D);
    kdk(&q, &p, w0 * D);
    kdk(&q, &p, w1 * D);
})

/* Lie series to D^4: the derivatives of (q, p) along q' = p, p' = -sin q */
HAND(lie4, {
    double s = sin(q), c = cos(q);
    double q1 = p, p1 = -s, q2 = -s, p2 = -c * p, q3 = -c * p, p3 = s * p * p + c * s;
    double q4 = p3, p4 = c * p * p * p - 3 * s * s * p + c * c * p;
    double d2 = D * D / 2, d3 = D * D * D / 6, d4 = D * D * D * D / 24;
    q = q + D * q1 + d2 * q2 + d3 * q3 + d4 * q4;
    p = p + D * p1 + d2 * p2 + d3 * p3 + d4 * p4;
})

/* ---- implicit: Newton ------------------------------------------------------ */

static int small(double d, double x)
{
    return fabs(d) <= 4 * DBL_EPSILON * fmax(1, fabs(x));
}

/* Q = q + D (p + P)/2, P = p - D sin((q + Q)/2): Newton on (Q, P) */
HAND(midpoint, {
    double Q = q + D * p, P = p - D * sin(q);
    for (int it = 0; it < 50; it++) {
        double s, c;
        sincos((q + Q) / 2, &s, &c);
        double f1 = Q - q - D * (p + P) / 2, f2 = P - p + D * s;
        double b = -D / 2, cc = D * c / 2, det = 1 - b * cc; /* J = [[1, b], [cc, 1]] */
        double dQ = -(f1 - b * f2) / det, dP = -(-cc * f1 + f2) / det;
        Q += dQ, P += dP;
        if (small(dQ, Q) && small(dP, P))
            break;
    }
    q = Q, p = P;
})

/* (cos q - cos Q)/(Q - q) = int_0^1 sin(q + s(Q - q)) ds, and its
 * derivative in Q; a series where Q - q is tiny */
static inline void avg_sin(double *g, double *dg, double q, double Q)
{
    double h = Q - q;
    if (fabs(h) < 1e-4) {
        double m = (q + Q) / 2, s = sin(m), c = cos(m);
        *g = s * (1 - h * h / 24);
        *dg = c / 2 - s * h / 12 - c * h * h / 48;
        return;
    }
    double cq = cos(q), sQ, cQ;
    sincos(Q, &sQ, &cQ);
    *g = (cq - cQ) / h;
    *dg = (sQ - *g) / h;
}

/* AVF = Itoh-Abe for a separable H: Q = q + D (p + P)/2,
 * P = p - D (cos q - cos Q)/(Q - q): Newton on P */
HAND(avf, {
    double P = p - D * sin(q);
    for (int it = 0; it < 50; it++) {
        double Q = q + D * (p + P) / 2, g, dg;
        avg_sin(&g, &dg, q, Q);
        double f = P - p + D * g, df = 1 + D * dg * D / 2, dP = -f / df;
        P += dP;
        if (small(dP, P))
            break;
    }
    q = q + D * (p + P) / 2, p = P;
})

/* Gonzalez: Z - z = D J gbar, gbar = grad H(m) + R/|dz|^2 dz, m the
 * midpoint, R = H(Z) - H(z) - grad H(m).dz.  Simplified Newton with the
 * midpoint rule's Jacobian at the prediction; stops at rounding level or
 * when tiny corrections no longer shrink (R is a difference of O(1)
 * terms) */
HAND(gonzalez, {
    double Q = q + D * p, P = p - D * sin(q), H = p * p / 2 - cos(q);
    double c0 = cos((q + Q) / 2), b = -D / 2, cc = D * c0 / 2, det = 1 - b * cc, last = INFINITY;
    for (int it = 0; it < 50; it++) {
        double dq = Q - q, dp = P - p, mid = (q + Q) / 2, pm = (p + P) / 2, n2 = dq * dq + dp * dp;
        double gq = sin(mid), gp = pm;
        if (n2 > 0) {
            double R = (P * P / 2 - cos(Q)) - H - (gq * dq + gp * dp);
            gq += R / n2 * dq, gp += R / n2 * dp;
        }
        double f1 = dq - D * gp, f2 = dp + D * gq;
        double eQ = -(f1 - b * f2) / det, eP = -(-cc * f1 + f2) / det;
        Q += eQ, P += eP;
        double dn = fmax(fabs(eQ), fabs(eP)), un = fmax(1, fmax(fabs(Q), fabs(P)));
        if (dn <= 4 * DBL_EPSILON * un || (dn <= 1e-12 * un && dn >= 0.5 * last))
            break;
        last = dn;
    }
    q = Q, p = P;
})

/* Gauss methods: stages Y_i = z + D sum_j a_ij f(Y_j); simplified Newton on
 * the stage increments W_i = Y_i - z with J = I - D (A x f'(z)), f'(z) =
 * [[0, 1], [-cos q, 0]], factored once per step (Gaussian elimination with
 * partial pivoting, 2s x 2s). */
#define MAXS 3
static void lu(double *M, int *piv, int n)
{
    for (int c = 0; c < n; c++) {
        int r = c;
        for (int i = c + 1; i < n; i++)
            if (fabs(M[i * n + c]) > fabs(M[r * n + c]))
                r = i;
        piv[c] = r;
        for (int j = 0; j < n; j++) {
            double t = M[r * n + j];
            M[r * n + j] = M[c * n + j], M[c * n + j] = t;
        }
        for (int i = c + 1; i < n; i++) {
            double f = M[i * n + c] /= M[c * n + c];
            for (int j = c + 1; j < n; j++)
                M[i * n + j] -= f * M[c * n + j];
        }
    }
}
static void lu_solve(const double *M, const int *piv, double *x, int n)
{
    for (int c = 0; c < n; c++) {
        double t = x[piv[c]];
        x[piv[c]] = x[c], x[c] = t;
        for (int i = c + 1; i < n; i++)
            x[i] -= M[i * n + c] * x[c];
    }
    for (int i = n - 1; i >= 0; i--) {
        for (int j = i + 1; j < n; j++)
            x[i] -= M[i * n + j] * x[j];
        x[i] /= M[i * n + i];
    }
}

static inline void gauss_step(double *q, double *p, int s, const double *a, const double *b)
{
    const int n = 2 * s;
    double M[4 * MAXS * MAXS], W[2 * MAXS], r[2 * MAXS], fq[MAXS], fp[MAXS];
    int piv[2 * MAXS];
    double c0 = cos(*q);
    for (int i = 0; i < s; i++)
        for (int j = 0; j < s; j++) { /* block (i, j) = delta_ij I - D a_ij f'(z) */
            double *B = M + (2 * i) * n + 2 * j, d = i == j;
            B[0] = d, B[1] = -D * a[i * s + j];
            B[n] = D * a[i * s + j] * c0, B[n + 1] = d;
        }
    lu(M, piv, n);
    for (int i = 0; i < s; i++) { /* W from explicit Euler's prediction */
        double ci = 0;
        for (int j = 0; j < s; j++)
            ci += a[i * s + j];
        W[2 * i] = ci * D * *p, W[2 * i + 1] = -ci * D * sin(*q);
    }
    for (int it = 0; it < 50; it++) {
        for (int j = 0; j < s; j++)
            fq[j] = *p + W[2 * j + 1], fp[j] = -sin(*q + W[2 * j]);
        for (int i = 0; i < s; i++) {
            double sq = 0, sp = 0;
            for (int j = 0; j < s; j++)
                sq += a[i * s + j] * fq[j], sp += a[i * s + j] * fp[j];
            r[2 * i] = -(W[2 * i] - D * sq), r[2 * i + 1] = -(W[2 * i + 1] - D * sp);
        }
        lu_solve(M, piv, r, n);
        int done = 1;
        for (int i = 0; i < n; i++) {
            W[i] += r[i];
            done &= small(r[i], W[i] + (i % 2 ? *p : *q));
        }
        if (done)
            break;
    }
    double sq = 0, sp = 0;
    for (int j = 0; j < s; j++)
        sq += b[j] * (*p + W[2 * j + 1]), sp += b[j] * -sin(*q + W[2 * j]);
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

/* ---- the table ------------------------------------------------------------ */

typedef struct entry {
    const char *name;
    void (*hand)(double *, int);
    const char *note;
} entry;

static const entry table[] = {
    {"euler", euler, ""},
    {"paper-euler", euler, ""},
    {"symplectic-euler-a", symplectic_euler_a, ""},
    {"symplectic-euler-b", symplectic_euler_b, ""},
    {"stormer-verlet-kdk", verlet_kdk, ""},
    {"stormer-verlet-dkd", verlet_dkd, ""},
    {"yoshida4", yoshida4, ""},
    {"rk4", rk4, ""},
    {"lie", lie4, ""},
    {"implicit-midpoint", midpoint, ""},
    {"gauss2", gauss2, ""},
    {"gauss3", gauss3, ""},
    {"avf", avf, "hand: closed-form average"},
    {"itoh-abe", avf, "hand: closed-form average"},
    {"gonzalez", gonzalez, ""},
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
    hl_system_spec spec = {"p^2/2 - cos(q)", NULL, NULL, NULL};
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
            fprintf(stderr, "run_fixed: %s: final states differ by %.3g\n", e->name, diff);
            bad = 1;
        }
        hl_run_set_reference(run, 1, 1e-15);
        double t0 = now();
        hl_run_fixed(run, z0, DT, NSTEPS * DT, 1, NULL, NULL, NULL, &err);
        tr = now() - t0;
        printf("%-20s %9.1f %9.1f %9.1f %7.2f %7.2f %12.1f  first run %.1f%s%s\n", e->name,
               1e3 * th, 1e3 * thh, 1e3 * td, td / th, td / thh, 1e3 * tr, 1e3 * first,
               *e->note ? "; " : "", e->note);
        if (td / thh > worst)
            worst = td / thh, worst_name = e->name;
        hl_run_free(run);
        hl_scheme_free(s);
    }
    printf("worst ratio to the hand loop with H: %.2f (%s)\n", worst, worst_name);
    hl_system_free(sys);
    return bad;
}
