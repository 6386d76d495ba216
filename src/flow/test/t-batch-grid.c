/* The batch integrator's outputs on a grid (hl_flow_batch_grid): every
 * member's outputs, steps and status are those of hl_flow_run over the
 * same times called in the same segments (one flow per member, as
 * hl_run_adaptive calls it), bit for bit: the pendulum and Henon-Heiles at
 * 1 and 4 lanes, segments of 7 outputs (restarts mid-run), of 1, and
 * none; members of different spacings and lengths, one with no outputs;
 * a callback's stop ends its member alone with its status and message;
 * z' = z^2 blows up in one member with the single run's error.
 * The lanes run lane by lane, not compiled (no libgccjit: a compilation a
 * case would cost seconds): that the compiled recursion gives the same
 * coefficients is flow/t-batch's; the driver tested here is the same
 * either way. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/flow.h"
#include "tape/test/hamiltonian.h"

static hl_pool *P;

#define MAXOUT 4000

/* What a member's outputs were: count, times, the states' bits summed
 * into a hash with their order, and the last state. */
typedef struct seen {
    long n, stop_at; /* stop_at: the callback stops at this k (0: never) */
    long k_last;
    double t_last, z_last[4];
    unsigned long long hash;
    int dim;
} seen;

static void see(seen *s, long k, double t, const double *z)
{
    unsigned long long u;
    for (int i = 0; i < s->dim; i++) {
        memcpy(&u, &z[i], sizeof u);
        s->hash = (s->hash ^ u ^ (unsigned long long)k) * 0x100000001b3ull;
    }
    memcpy(&u, &t, sizeof u);
    s->hash = (s->hash ^ u) * 0x100000001b3ull;
    s->n++;
    s->k_last = k;
    s->t_last = t;
    memcpy(s->z_last, z, (size_t)s->dim * sizeof *z);
}

static int batch_fn(int member, long k, double t, const double *z, hl_error *err, void *arg)
{
    seen *s = (seen *)arg + member;
    see(s, k, t, z);
    if (k == s->stop_at)
        return hl_error_set(err, HL_ESTOP, NULL, -1, 0, "stopped at %ld", k);
    return 0;
}

typedef struct single_arg {
    seen *s;
    long k;
} single_arg;

static int single_fn(double t, const double *z, void *arg)
{
    single_arg *a = arg;
    long k = ++a->k;
    see(a->s, k, t, z);
    return k == a->s->stop_at ? HL_ESTOP : 0;
}

/* hl_run_adaptive's way: hl_flow_run over `segment` times at a time, each
 * from the last output's state. */
static hl_status single(hl_tape *tape, double tol, const double *z0, double dt, long k0, long k1,
                        long segment, seen *s, long *steps, hl_error *err)
{
    int n = hl_tape_ninputs(tape);
    hl_flow *f = NULL;
    CHECK(hl_flow_new(&f, tape, tol, tol, err) == HL_OK);
    double *ts = malloc((size_t)(k1 - k0 + 1) * sizeof *ts), z[4];
    memcpy(z, z0, (size_t)n * sizeof *z);
    single_arg a = {s, k0};
    hl_status st = HL_OK;
    while (st == HL_OK && a.k < k1) {
        long m = 0, seg = segment > 0 ? segment : k1 - k0;
        for (long k = a.k + 1; k <= k1 && m < seg; k++)
            ts[m++] = (double)k * dt;
        st = hl_flow_run(f, (double)a.k * dt, z, ts, (int)m, single_fn, &a, err);
        if (st == HL_ESTOP)
            hl_error_set(err, HL_ESTOP, NULL, -1, 0, "stopped at %ld", a.k);
        memcpy(z, s->z_last, (size_t)n * sizeof *z);
    }
    *steps = hl_flow_nsteps(f);
    hl_flow_free(f);
    free(ts);
    return st;
}

static void check(const char *what, hl_tape *tape, double tol, int lanes, long segment, int B,
                  const double *z0, const double *dt, const long *k0, const long *k1,
                  const long *stop_at)
{
    int n = hl_tape_ninputs(tape);
    hl_flow_batch *b = NULL;
    hl_error err;
    CHECK_MSG(hl_flow_batch_new(&b, tape, tol, tol, lanes, &err) == HL_OK, "%s", err.msg);
    seen *sb = calloc((size_t)B, sizeof *sb), *ss = calloc((size_t)B, sizeof *ss);
    double *z = malloc((size_t)B * n * sizeof *z);
    memcpy(z, z0, (size_t)B * n * sizeof *z);
    hl_status *st = calloc((size_t)B, sizeof *st);
    long *steps = calloc((size_t)B, sizeof *steps);
    hl_error *errs = calloc((size_t)B, sizeof *errs);
    for (int i = 0; i < B; i++) {
        sb[i].dim = ss[i].dim = n;
        sb[i].stop_at = ss[i].stop_at = stop_at ? stop_at[i] : 0;
    }
    hl_flow_batch_grid(b, B, dt, k0, k1, segment, z, batch_fn, sb, st, steps, errs, &err);
    for (int i = 0; i < B; i++) {
        long s1steps;
        hl_error e1;
        hl_error_clear(&e1);
        hl_status s1 = single(tape, tol, z0 + (size_t)i * n, dt[i], k0[i], k1[i], segment, &ss[i],
                              &s1steps, &e1);
        int same = s1 == st[i] && sb[i].n == ss[i].n && sb[i].hash == ss[i].hash &&
                   s1steps == steps[i] && (s1 == HL_OK || strcmp(e1.msg, errs[i].msg) == 0);
        CHECK_MSG(same,
                  "%s, %d lanes, segment %ld, member %d: status %d/%d, outputs %ld/%ld, steps "
                  "%ld/%ld, last x %.17g/%.17g (%s / %s)",
                  what, lanes, segment, i, s1, st[i], ss[i].n, sb[i].n, s1steps, steps[i],
                  ss[i].z_last[0], sb[i].z_last[0], e1.msg, errs[i].msg);
        if (s1 == HL_OK) /* every output there, the last at its end */
            CHECK(sb[i].n == k1[i] - k0[i] && (sb[i].n == 0 || sb[i].k_last == k1[i]));
    }
    free(sb), free(ss), free(z), free(st), free(steps), free(errs);
    hl_flow_batch_free(b);
}

static void test_pendulum_hh(void)
{
    hl_tape *pend = test_hamiltonian(P, "px^2/2 - cos(x)", 1);
    double zp[12] = {1.3, 0.2, -2.0, 0.5, 0.1, 0, 3.0, 0.3, 2.5, -1.2, 0.7, 0.7};
    double dtp[6] = {0.1, 0.05, 0.3, 0.1, 0.125, 0.2};
    long k0p[6] = {0, 0, 3, 0, 0, 0}, k1p[6] = {150, 40, 90, 0, 200, 33};
    long stop[6] = {0, 0, 0, 0, 57, 0};
    for (long seg = 0; seg <= 7; seg += 7) {
        check("pendulum", pend, 1e-14, 4, seg, 6, zp, dtp, k0p, k1p, NULL);
        check("pendulum", pend, 1e-14, 1, seg, 6, zp, dtp, k0p, k1p, NULL);
    }
    check("pendulum", pend, 1e-10, 4, 1, 6, zp, dtp, k0p, k1p, stop);
    check("pendulum", pend, 1e-14, 2, 7, 6, zp, dtp, k0p, k1p, stop);
    hl_tape_free(pend);
    hl_tape *hh = test_hamiltonian(P, "(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3", 2);
    double zh[20] = {0,   0.1, 0.35, 0.2, 0.05, -0.1, 0.3, 0.25, 0,   0.3,
                     0.3, 0.1, 0.1,  0,   0.2,  0.4,  0,   -0.2, 0.4, 0.1};
    double dth[5] = {0.5, 0.25, 1, 0.5, 0.75};
    long k0h[5] = {0, 0, 0, 2, 0}, k1h[5] = {100, 300, 60, 70, 90};
    check("Henon-Heiles", hh, 1e-15, 4, 7, 5, zh, dth, k0h, k1h, NULL);
    check("Henon-Heiles", hh, 1e-15, 4, 0, 5, zh, dth, k0h, k1h, NULL);
    hl_tape_free(hh);
}

/* z' = z^2 from 1/T: its pole at T; the member whose grid passes its pole
 * fails there, as the single run does */
static void test_blowup(void)
{
    const char *names[] = {"z"};
    const hl_expr *zz = hl_sym(P, "z"), *f[] = {hl_mul(P, zz, zz)};
    hl_tape *t = NULL;
    hl_error err;
    CHECK(hl_tape_new(&t, f, 1, names, 1, &err) == HL_OK);
    double z0[4] = {1, 0.5, 0.25, 0.2}, dt[4] = {0.125, 0.25, 0.5, 0.25};
    long k0[4] = {0, 0, 0, 0}, k1[4] = {6, 12, 7, 16}; /* 0.75 < 1, 3 > 2, 3.5 < 4, 4 < 5 */
    check("z' = z^2", t, 1e-12, 4, 5, 4, z0, dt, k0, k1, NULL);
    hl_flow_batch *b = NULL;
    CHECK(hl_flow_batch_new(&b, t, 1e-12, 1e-12, 4, &err) == HL_OK);
    seen s[4] = {{.dim = 1}, {.dim = 1}, {.dim = 1}, {.dim = 1}};
    hl_status st[4];
    double z[4];
    memcpy(z, z0, sizeof z);
    CHECK(hl_flow_batch_grid(b, 4, dt, k0, k1, 0, z, batch_fn, s, st, NULL, NULL, &err) != HL_OK);
    CHECK(st[0] == HL_OK && st[1] != HL_OK && st[2] == HL_OK && st[3] == HL_OK);
    CHECK(strstr(err.msg, "member 1") != NULL);
    CHECK(fabs(s[0].z_last[0] - 4) < 1e-9); /* 1/(1 - 0.75) */
    long bad[1] = {-1};
    CHECK(hl_flow_batch_grid(b, 1, dt, k0, bad, 0, z, batch_fn, s, st, NULL, NULL, &err) ==
              HL_EINVAL &&
          st[0] == HL_EINVAL);
    CHECK(hl_flow_batch_grid(b, 1, dt, k0, k1, 0, z, NULL, s, st, NULL, NULL, &err) == HL_EINVAL);
    hl_flow_batch_free(b);
    hl_tape_free(t);
}

int main(void)
{
    setenv("HAMLIE_GCCJIT_LIB", "/nonexistent/libgccjit.so", 1); /* see above */
    P = hl_pool_new();
    test_pendulum_hh();
    test_blowup();
    hl_pool_free(P);
    return HL_TEST_END();
}
