/* The watched iteration over lanes (hl_tape_iter_batch, jit_iter_batch.c):
 * each lane's state, steps and max |w - w0| bit for bit those of
 * hl_tape_iterate_watch (interpreted) for that lane alone, for maps that
 * between them use every operation of the rules (the formulas of
 * t-backends.c, seven to a map) at 4 lanes (and one map at 2 and 8), lanes
 * of different states and step sizes; a Störmer–Verlet step of the
 * pendulum (its sin q carried from one step to the next); a lane that
 * blows up (the oscillator's explicit Euler, which grows by sqrt(1 + h^2)
 * a step: at h = 0.5 it overflows at step 2 * 709.8 / log(1.25) or
 * sooner) stops the loop there, before the step, and is the only lane
 * whose outputs there are not finite; the others go on without it.
 * Without libgccjit (or compile 0) the lanes run through the interpreter
 * and every comparison holds the same way. */
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/tape.h"
#include "tape/tape_impl.h"

static hl_pool *P;

static int same(const double *x, const double *y, int n)
{
    return memcmp(x, y, (size_t)n * sizeof *x) == 0;
}

/* A tape over (a, b, h) with outputs (A, B, W) from the texts. */
static hl_tape *map(const char *A, const char *Bt, const char *W)
{
    const char *in[] = {"a", "b", "h"};
    const char *text[] = {A, Bt, W};
    const hl_expr *e[3];
    hl_error err;
    for (int i = 0; i < 3; i++)
        CHECK_MSG(hl_parse(&e[i], P, text[i], &err) == HL_OK, "%s: %s", text[i], err.msg);
    hl_tape *t = NULL;
    CHECK_MSG(hl_tape_new(&t, e, 3, in, 3, &err) == HL_OK, "%s", err.msg);
    return t;
}

/* n steps of lane l alone: hl_tape_iterate_watch from z0 (3 values). */
static long alone(hl_tape *t, const double *z0, double w0, long n, double *z, double *dev)
{
    memcpy(z, z0, 3 * sizeof *z);
    *dev = 0;
    return hl_tape_iterate_watch(z, n, w0, dev, t);
}

/* The batch of `lanes` lanes from z0[l * 3 + i], n steps: returns the steps
 * taken, after comparing every lane with its single run of that many. */
static long lanes_against_alone(hl_tape *t, int lanes, int compile, const double *z0, long n)
{
    hl_tape_iter_batch *b = NULL;
    hl_error err;
    CHECK_MSG(hl_tape_iter_batch_new(&b, t, lanes, compile, &err) == HL_OK, "%s", err.msg);
    if (b == NULL)
        return -1;
    CHECK(hl_tape_iter_batch_compiled(b) == (compile && hl_tape_jit_available()));
    double *z = hl_tape_iter_batch_state(b), w0[16], dev[16];
    CHECK(((uintptr_t)z & ((size_t)lanes * sizeof(double) - 1)) == 0); /* aligned */
    for (int l = 0; l < lanes; l++) {
        for (int i = 0; i < 3; i++)
            z[i * lanes + l] = z0[3 * l + i];
        w0[l] = 0.25 + 0.125 * l;
        dev[l] = 0;
    }
    long k = hl_tape_iter_batch_watch(b, n, w0, dev);
    long fewest = n;
    for (int l = 0; l < lanes; l++) {
        double want[3], got[3], d;
        long alone_steps = alone(t, z0 + 3 * l, w0[l], n, want, &d);
        fewest = alone_steps < fewest ? alone_steps : fewest;
        alone(t, z0 + 3 * l, w0[l], k, want, &d);
        for (int i = 0; i < 3; i++)
            got[i] = z[i * lanes + l];
        CHECK_MSG(same(got, want, 3) && memcmp(&dev[l], &d, sizeof d) == 0,
                  "lane %d of %d after %ld steps: %.17g/%.17g, dev %.17g/%.17g", l, lanes, k,
                  got[0], want[0], dev[l], d);
    }
    CHECK_MSG(k == fewest, "%ld steps, the shortest single run %ld", k, fewest);
    hl_tape_iter_batch_free(b);
    return k;
}

/* the formulas of t-backends.c, seven to a map: together every hl_op */
static const char *const cases[] = {
    "-sin(a)", "a+b",     "a-b",        "a*b",      "a/b",       "a^2",        "a+pi",
    "a-pi",    "pi-a",    "a*pi",       "a/pi",     "pi/a",      "a^(3/4)",    "sqrt(a)",
    "exp(a)",  "log(a)",  "sin(a)",     "sinh(a)",  "tan(a)",    "tanh(a)",    "atan(a)",
    "asin(a)", "acos(a)", "atan2(a,b)", "asinh(a)", "sqrt(a)*a", "a^7*b^(-3)", "cos(a)*exp(b)",
};

/* a, b stay in (0.05, 0.85): a' = b, b' = 0.45 + 0.4 sin(f + h a), w = f */
static void test_operations(void)
{
    int covered[HL_OP_COUNT] = {0};
    const int per = 7, nmaps = (int)(sizeof cases / sizeof *cases) / per;
    for (int m = 0; m < nmaps; m++) {
        char f[512] = "exp(-b)"; /* a NEG: a bare minus is carried as a scale */
        for (int c = 0; c < per; c++) {
            size_t len = strlen(f);
            snprintf(f + len, sizeof f - len, " + (%s)/%d", cases[m * per + c], 3 + c);
        }
        char Bt[600];
        snprintf(Bt, sizeof Bt, "0.45 + 0.4*sin(%s + h*a)", f);
        hl_tape *t = map("b", Bt, f);
        if (t == NULL)
            continue;
        for (int i = 0; i < t->ncode; i++)
            covered[t->code[i].op] = 1;
        double z0[3 * 8];
        for (int l = 0; l < 8; l++) {
            z0[3 * l] = 0.3 + 0.05 * l;
            z0[3 * l + 1] = 0.6 - 0.04 * l;
            z0[3 * l + 2] = 0.1 * (l + 1);
        }
        for (int lanes = 2; lanes <= 8; lanes *= 2) {
            if (lanes != 4 && m != 0)
                continue; /* 2 and 8 lanes: the same emitter, other vector widths */
            CHECK_MSG(lanes_against_alone(t, lanes, 1, z0, 500) == 500, "map %d, %d lanes", m,
                      lanes);
        }
        if (m == 0)
            CHECK(lanes_against_alone(t, 4, 0, z0, 500) == 500); /* the interpreter's lanes */
        hl_tape_free(t);
    }
    for (int op = 0; op < HL_OP_COUNT; op++)
        CHECK_MSG(covered[op], "no map for %s", hl_op_name((hl_op)op));
}

/* The pendulum's Störmer–Verlet step (its sin q carried between steps). */
static void test_verlet(void)
{
    const char *Q = "a + h*(b - h/2*sin(a))";
    char Pt[256];
    snprintf(Pt, sizeof Pt, "b - h/2*(sin(a) + sin(%s))", Q);
    hl_tape *t = map(Q, Pt, "b^2/2 - cos(a)");
    if (t == NULL)
        return;
    double z0[3 * 4];
    for (int l = 0; l < 4; l++) {
        z0[3 * l] = 0.5 + 0.6 * l; /* up to the separatrix's neighbourhood */
        z0[3 * l + 1] = 0.1 * l;
        z0[3 * l + 2] = 0.01 * (1 + l % 2);
    }
    CHECK(lanes_against_alone(t, 4, 1, z0, 20000) == 20000);
    hl_tape_free(t);
}

/* Euler on the oscillator: lane 2 (h = 0.5) overflows; the others go on. */
static void test_blow_up(void)
{
    hl_tape *t = map("a + h*b", "b - h*a", "(a^2 + b^2)/2");
    if (t == NULL)
        return;
    double z0[3 * 4];
    for (int l = 0; l < 4; l++) {
        z0[3 * l] = 1 - 0.1 * l;
        z0[3 * l + 1] = 0.2 * l;
        z0[3 * l + 2] = l == 2 ? 0.5 : 0.001;
    }
    long k = lanes_against_alone(t, 4, 1, z0, 100000);
    double bound = 2 * log(DBL_MAX) / log(1.25);
    CHECK_MSG(k > 0.45 * bound && k < bound, "stopped at %ld (overflow by %g)", k, bound);
    /* at the stop, only lane 2's outputs are not finite */
    hl_tape_iter_batch *b = NULL;
    CHECK(hl_tape_iter_batch_new(&b, t, 4, 1, NULL) == HL_OK);
    double *z = hl_tape_iter_batch_state(b), w0[4] = {0, 0, 0, 0}, dev[4] = {0, 0, 0, 0};
    for (int l = 0; l < 4; l++)
        for (int i = 0; i < 3; i++)
            z[i * 4 + l] = z0[3 * l + i];
    CHECK(hl_tape_iter_batch_watch(b, 100000, w0, dev) == k);
    for (int l = 0; l < 4; l++) {
        double in[3] = {z[l], z[4 + l], z[8 + l]}, out[3];
        hl_tape_eval_d(out, in, t);
        int finite = isfinite(out[0]) && isfinite(out[1]) && isfinite(out[2]);
        CHECK_MSG(finite == (l != 2), "lane %d", l);
    }
    /* lane 2 replaced by a copy of lane 0: the others go on to the end */
    for (int i = 0; i < 3; i++)
        z[i * 4 + 2] = z[i * 4];
    CHECK(hl_tape_iter_batch_watch(b, 100000 - k, w0, dev) == 100000 - k);
    double want[3], d;
    alone(t, z0 + 3, 0, 100000, want, &d);
    CHECK(z[1] == want[0] && z[5] == want[1] && dev[1] == d);
    hl_tape_iter_batch_free(b);
    hl_tape_free(t);
}

static void test_errors(void)
{
    hl_tape *t = map("a + h*b", "b - h*a", "(a^2 + b^2)/2");
    const hl_expr *e[1];
    const char *in[] = {"a", "b"};
    hl_error err;
    CHECK(hl_parse(&e[0], P, "a*b", &err) == HL_OK);
    hl_tape *one = NULL;
    CHECK(hl_tape_new(&one, e, 1, in, 2, &err) == HL_OK);
    hl_tape_iter_batch *b = (hl_tape_iter_batch *)&err; /* set to NULL on failure */
    CHECK(hl_tape_iter_batch_new(&b, one, 4, 1, &err) == HL_EINVAL && b == NULL);
    CHECK(strstr(err.msg, "as many outputs") != NULL);
    CHECK(hl_tape_iter_batch_new(&b, t, 3, 1, &err) == HL_EINVAL);
    CHECK(strstr(err.msg, "power of 2") != NULL);
    CHECK(hl_tape_iter_batch_new(&b, t, 32, 1, &err) == HL_EINVAL);
    CHECK(hl_tape_iter_batch_new(&b, t, 4, 0, &err) == HL_OK);
    CHECK(hl_tape_iter_batch_watch(b, 0, NULL, NULL) == 0);
    hl_tape_iter_batch_free(b);
    hl_tape_iter_batch_free(NULL);
    hl_tape_free(one);
    hl_tape_free(t);
}

int main(void)
{
    P = hl_pool_new();
    if (!hl_tape_jit_available())
        printf("no libgccjit: the lanes run through the interpreter\n");
    test_operations();
    test_verlet();
    test_blow_up();
    test_errors();
    hl_pool_free(P);
    return HL_TEST_END();
}
