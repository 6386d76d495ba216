/* The Taylor driver's loops are built twice (flow_poly.h): with AVX2 and
 * FMA instructions, and plain (fma() through libm), the one chosen when a
 * flow is made (HAMLIE_NO_AVX2=1 forces plain).  Both must give the same
 * bits, or a run's result would depend on the machine: hl_flow_evolve,
 * the outputs of hl_flow_eval_at (the step's polynomial at a time inside
 * it) and the batch's lanes, against each other, on the pendulum, Kepler
 * (two eccentricities) and Henon-Heiles at two tolerances, and a field of
 * 3 components (an odd count: the vector build's state update does two
 * components at a time, the last alone) at three, the lowest at an order
 * below the window of 6 (the step rule's loops not unrolled).  On a
 * machine without AVX2 both runs are plain and the test says so. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/flow.h"
#include "tape/test/hamiltonian.h"

static hl_pool *P;

typedef struct system {
    const char *name, *H;
    int N; /* degrees of freedom of H, or 0: the field F */
    double z0[4];
    const char *F[3];
} sys;

/* the state's size */
static int dim(const sys *s)
{
    return s->N > 0 ? 2 * s->N : 3;
}

static const sys systems[] = {
    {"pendulum", "px^2/2 - cos(x)", 1, {1.3, 0}, {NULL}},
    {"Kepler e=0.5", "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", 2, {0.5, 0, 0, 1.7320508075688772}, {NULL}},
    {"Kepler e=0.9", "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", 2, {0.1, 0, 0, 4.358898943540674}, {NULL}},
    {"Henon-Heiles",
     "(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3",
     2,
     {0.1, -0.1, 0.05, 0.1},
     {NULL}},
};

/* a free rigid body (Euler's equations): 3 components */
static const sys body = {"rigid body", NULL, 0, {0.3, 0.8, 0.5}, {"y*z", "-2*x*z", "x*y"}};

static hl_tape *field_tape(const sys *s)
{
    const char *names[] = {"x", "y", "z"};
    const hl_expr *f[3];
    hl_error err;
    for (int i = 0; i < 3; i++)
        CHECK_MSG(hl_parse(&f[i], P, s->F[i], &err) == HL_OK, "%s", s->F[i]);
    hl_tape *t = NULL;
    CHECK_MSG(hl_tape_new(&t, f, 3, names, 3, &err) == HL_OK, "%s", err.msg);
    return t;
}

#define T_END 30.0
#define NOUT 9

typedef struct result {
    double z[4], t, out[NOUT * 4], zb[4];
    long steps;
} result;

/* one run of s in the build that the environment chooses */
static void run(result *r, const sys *s, hl_tape *tape, double tol, int plain)
{
    const int n = dim(s);
    if (plain)
        setenv("HAMLIE_NO_AVX2", "1", 1);
    else
        unsetenv("HAMLIE_NO_AVX2");
    hl_flow *f = NULL;
    hl_flow_batch *b = NULL;
    hl_error err;
    CHECK_MSG(hl_flow_new(&f, tape, tol, tol, &err) == HL_OK, "%s", err.msg);
    CHECK_MSG(hl_flow_batch_new(&b, tape, tol, tol, 4, &err) == HL_OK, "%s", err.msg);
    memcpy(r->z, s->z0, sizeof r->z);
    r->t = 0;
    CHECK_MSG(hl_flow_evolve(f, &r->t, T_END, r->z, &err) == HL_OK, "%s", err.msg);
    r->steps = hl_flow_nsteps(f);
    double ts[NOUT];
    for (int j = 0; j < NOUT; j++)
        ts[j] = T_END * (j + 0.37) / NOUT; /* inside steps, not at their ends */
    CHECK_MSG(hl_flow_eval_at(f, 0, s->z0, ts, NOUT, r->out, &err) == HL_OK, "%s", err.msg);
    /* the batch: member 0 the same orbit, the others to keep the lanes busy */
    double zb[4 * 4], t0[4] = {0, 0, 0, 0}, t1[4] = {T_END, T_END / 2, T_END / 3, T_END / 5};
    hl_status st[4];
    for (int i = 0; i < 4; i++)
        memcpy(zb + i * n, s->z0, n * sizeof *zb);
    CHECK_MSG(hl_flow_batch_evolve(b, 4, t0, t1, zb, st, NULL, NULL, &err) == HL_OK, "%s", err.msg);
    memcpy(r->zb, zb, n * sizeof *zb);
    hl_flow_free(f);
    hl_flow_batch_free(b);
}

static void check_system(const sys *s, hl_tape *tape, double tol)
{
    const int n = dim(s);
    result v, p;
    run(&v, s, tape, tol, 0);
    run(&p, s, tape, tol, 1);
    CHECK_MSG(v.steps == p.steps && v.t == p.t && memcmp(v.z, p.z, n * sizeof *v.z) == 0,
              "%s tol %g: evolve, steps %ld/%ld, x %.17g/%.17g", s->name, tol, v.steps, p.steps,
              v.z[0], p.z[0]);
    CHECK_MSG(memcmp(v.out, p.out, NOUT * n * sizeof *v.out) == 0,
              "%s tol %g: outputs, x %.17g/%.17g", s->name, tol, v.out[0], p.out[0]);
    /* the batch's member 0, in either build, ends where the single run does */
    CHECK_MSG(memcmp(v.zb, v.z, n * sizeof *v.z) == 0 && memcmp(p.zb, p.z, n * sizeof *p.z) == 0,
              "%s tol %g: batch, x %.17g/%.17g/%.17g", s->name, tol, v.zb[0], p.zb[0], v.z[0]);
    /* not a run that stopped early */
    CHECK_MSG(v.t == T_END && isfinite(v.z[0]), "%s tol %g: t %g", s->name, tol, v.t);
}

int main(void)
{
    /* the recursion interpreted: what is compared is the driver's loops,
     * and a batch compiled anew for each run took seconds */
    setenv("HAMLIE_GCCJIT_LIB", "/nonexistent", 1);
    P = hl_pool_new();
    const char *was = getenv("HAMLIE_NO_AVX2");
    if (was != NULL && was[0] != '\0' && strcmp(was, "0") != 0)
        printf("t-vec: HAMLIE_NO_AVX2 set: both builds plain\n");
#if defined(__x86_64__) && defined(__GNUC__)
    if (!__builtin_cpu_supports("avx2") || !__builtin_cpu_supports("fma"))
#endif
        printf("t-vec: no AVX2 and FMA here: both builds plain\n");
    for (size_t s = 0; s < sizeof systems / sizeof *systems; s++) {
        hl_tape *t = test_hamiltonian(P, systems[s].H, systems[s].N);
        if (t == NULL)
            continue;
        check_system(&systems[s], t, 1e-15);
        check_system(&systems[s], t, 1e-10);
        hl_tape_free(t);
    }
    hl_tape *t = field_tape(&body);
    if (t != NULL) {
        check_system(&body, t, 1e-15);
        check_system(&body, t, 1e-10);
        check_system(&body, t, 1e-3); /* order 5 */
        hl_tape_free(t);
    }
    hl_pool_free(P);
    return HL_TEST_END();
}
