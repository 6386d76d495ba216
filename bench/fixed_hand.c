/* The peer of `hamlie run --scheme S --no-reference --json` as a whole
 * process (issue 17): the same fixed-step scheme written by hand in C for
 * one system, H evaluated at every step for max |H - H0|, as a program of
 * its own (bench/run-fixed-process.sh times both processes).
 *
 * Usage: bench-fixed_hand SYSTEM SCHEME DT STEPS
 *   SYSTEM: pendulum (q=1.3, p=0), henon-heiles (x=.1, y=-.1, px=.05,
 *   py=.1), kepler (e = 0.5 from perihelion: x=.5, y=0, px=0, py=sqrt(3));
 *   SCHEME: stormer-verlet-kdk or rk4.
 * Prints the final state and max |H - H0|, one number a line (%.17g).
 *
 * The loops are what one would write: the force twice per kdk step (at q
 * and at the new q; not carried over to the next step, as hamlie's step
 * does not either), H from the state after each step. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAXN 4

typedef struct sys {
    const char *name;
    int n; /* degrees of freedom */
    double z0[2 * MAXN];
} sys;

static const sys systems[] = {
    {"pendulum", 1, {1.3, 0}},
    {"henon-heiles", 2, {0.1, -0.1, 0.05, 0.1}},
    {"kepler", 2, {0.5, 0, 0, 1.7320508075688772}},
};

/* ---- the three systems: -grad V(q) and H ----------------------------------- */

static inline void force_pendulum(const double *q, double *f) { f[0] = -sin(q[0]); }
static inline double H_pendulum(const double *q, const double *p)
{
    return p[0] * p[0] / 2 - cos(q[0]);
}

static inline void force_hh(const double *q, double *f)
{
    f[0] = -(q[0] + 2 * q[0] * q[1]);
    f[1] = -(q[1] + q[0] * q[0] - q[1] * q[1]);
}
static inline double H_hh(const double *q, const double *p)
{
    return (p[0] * p[0] + p[1] * p[1]) / 2 + (q[0] * q[0] + q[1] * q[1]) / 2 +
           q[0] * q[0] * q[1] - q[1] * q[1] * q[1] / 3;
}

static inline void force_kepler(const double *q, double *f)
{
    double r2 = q[0] * q[0] + q[1] * q[1], r3 = r2 * sqrt(r2);
    f[0] = -q[0] / r3;
    f[1] = -q[1] / r3;
}
static inline double H_kepler(const double *q, const double *p)
{
    return (p[0] * p[0] + p[1] * p[1]) / 2 - 1 / sqrt(q[0] * q[0] + q[1] * q[1]);
}

/* ---- the two schemes, as one loop per system -------------------------------- */

#define LOOPS(S, N)                                                                       \
    static double kdk_##S(double *z, double h, long steps)                               \
    {                                                                                    \
        double *q = z, *p = z + N, f[N], H0 = H_##S(q, p), m = 0;                        \
        for (long k = 0; k < steps; k++) {                                               \
            force_##S(q, f);                                                             \
            for (int i = 0; i < N; i++)                                                  \
                p[i] += h / 2 * f[i];                                                    \
            for (int i = 0; i < N; i++)                                                  \
                q[i] += h * p[i];                                                        \
            force_##S(q, f);                                                             \
            for (int i = 0; i < N; i++)                                                  \
                p[i] += h / 2 * f[i];                                                    \
            m = fmax(m, fabs(H_##S(q, p) - H0));                                         \
        }                                                                                \
        return m;                                                                        \
    }                                                                                    \
    static double rk4_##S(double *z, double h, long steps)                               \
    {                                                                                    \
        double *q = z, *p = z + N, H0 = H_##S(q, p), m = 0;                              \
        double kq[4][N], kp[4][N], qs[N], ps[N];                                         \
        static const double c[4] = {0, 0.5, 0.5, 1};                                     \
        for (long k = 0; k < steps; k++) {                                               \
            for (int s = 0; s < 4; s++) {                                                \
                for (int i = 0; i < N; i++) {                                            \
                    qs[i] = q[i] + (s ? c[s] * h * kq[s - 1][i] : 0);                    \
                    ps[i] = p[i] + (s ? c[s] * h * kp[s - 1][i] : 0);                    \
                }                                                                        \
                for (int i = 0; i < N; i++)                                              \
                    kq[s][i] = ps[i];                                                    \
                force_##S(qs, kp[s]);                                                    \
            }                                                                            \
            for (int i = 0; i < N; i++) {                                                \
                q[i] += h / 6 * (kq[0][i] + 2 * kq[1][i] + 2 * kq[2][i] + kq[3][i]);     \
                p[i] += h / 6 * (kp[0][i] + 2 * kp[1][i] + 2 * kp[2][i] + kp[3][i]);     \
            }                                                                            \
            m = fmax(m, fabs(H_##S(q, p) - H0));                                         \
        }                                                                                \
        return m;                                                                        \
    }

LOOPS(pendulum, 1)
LOOPS(hh, 2)
LOOPS(kepler, 2)

int main(int argc, char **argv)
{
    if (argc != 5) {
        fprintf(stderr, "usage: %s SYSTEM SCHEME DT STEPS\n", argv[0]);
        return 2;
    }
    int s = -1, kdk = strcmp(argv[2], "stormer-verlet-kdk") == 0;
    for (int i = 0; i < 3; i++)
        if (strcmp(argv[1], systems[i].name) == 0)
            s = i;
    if (s < 0 || (!kdk && strcmp(argv[2], "rk4") != 0)) {
        fprintf(stderr, "unknown system or scheme\n");
        return 2;
    }
    double h = atof(argv[3]), z[2 * MAXN];
    long steps = (long)atof(argv[4]);
    memcpy(z, systems[s].z0, sizeof z);
    double m = s == 0   ? (kdk ? kdk_pendulum : rk4_pendulum)(z, h, steps)
               : s == 1 ? (kdk ? kdk_hh : rk4_hh)(z, h, steps)
                        : (kdk ? kdk_kepler : rk4_kepler)(z, h, steps);
    for (int i = 0; i < 2 * systems[s].n; i++)
        printf("%.17g\n", z[i]);
    printf("%.17g\n", m);
    return 0;
}
