/* The batch integrator (hl_flow_batch): every member ends where
 * hl_flow_evolve takes it alone, bit for bit (state, time, steps, status),
 * on the pendulum, Henon-Heiles and Kepler, with members of different
 * initial points, start and end times (backwards too, and none at all),
 * more members than lanes and not a multiple of them, at 1, 2, 4 and 8
 * lanes and two tolerances (two orders); a member that blows up (Kepler
 * from the origin; z' = z^2 past its pole) stops alone with the single
 * integrator's error, and the others go on. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/flow.h"
#include "tape/test/hamiltonian.h"

static hl_pool *P;

typedef struct system {
    const char *name, *H;
    int N;
    double z0[4]; /* member 0's state; the others are spread from it */
    double spread;
} sys;

static const sys systems[] = {
    {"pendulum", "px^2/2 - cos(x)", 1, {1.3, 0.2}, 0.37},
    {"Henon-Heiles",
     "(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3",
     2,
     {0.0, 0.1, 0.35, 0.2},
     0.031},
    {"Kepler", "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", 2, {1.0, 0.0, 0.0, 1.1}, 0.043},
};

/* member i's start: spread from z0 (a different orbit each), and times */
static void member(const sys *s, int i, double *z, double *t0, double *t1)
{
    int n = 2 * s->N;
    for (int j = 0; j < n; j++)
        z[j] = s->z0[j] + s->spread * sin(1.7 * i + 0.9 * j) * (j % 2 ? 1 : -1);
    *t0 = 0.25 * (i % 3);
    *t1 = i % 5 == 4 ? -7.5 : 10 + 3.3 * i; /* one in five backwards */
    if (i == 6)
        *t1 = *t0; /* nothing to do */
}

/* B members of s through a batch of `lanes`, each against hl_flow_evolve */
static void check_system(const sys *s, hl_tape *tape, double tol, int lanes, int B, int blow)
{
    const int n = 2 * s->N;
    hl_flow_batch *b = NULL;
    hl_error err;
    CHECK_MSG(hl_flow_batch_new(&b, tape, tol, tol, lanes, &err) == HL_OK, "%s", err.msg);
    if (b == NULL)
        return;
    CHECK(hl_flow_batch_compiled(b) == hl_tape_jit_available());
    double *z = calloc((size_t)B * n, sizeof *z), *t0 = calloc(B, sizeof *t0),
           *t1 = calloc(B, sizeof *t1);
    hl_status *st = calloc(B, sizeof *st);
    long *steps = calloc(B, sizeof *steps);
    hl_error *errs = calloc(B, sizeof *errs);
    for (int i = 0; i < B; i++)
        member(s, i, z + (size_t)i * n, &t0[i], &t1[i]);
    if (blow >= 0) /* Kepler from the origin: the field is infinite there */
        memset(z + (size_t)blow * n, 0, n * sizeof *z);
    double *t = malloc(B * sizeof *t);
    memcpy(t, t0, B * sizeof *t);
    hl_status all = hl_flow_batch_evolve(b, B, t, t1, z, st, steps, errs, &err);
    CHECK(all == (blow >= 0 ? HL_EDOM : HL_OK));
    if (blow >= 0)
        CHECK_MSG(strstr(err.msg, "member ") != NULL, "%s", err.msg);
    int differ = 0;
    for (int i = 0; i < B; i++) {
        double zs[4], ts;
        member(s, i, zs, &ts, &(double){0});
        if (i == blow)
            memset(zs, 0, sizeof zs);
        hl_flow *f = NULL;
        hl_error e1;
        CHECK(hl_flow_new(&f, tape, tol, tol, &e1) == HL_OK);
        hl_status s1 = hl_flow_evolve(f, &ts, t1[i], zs, &e1);
        int same = s1 == st[i] && memcmp(&ts, &t[i], sizeof ts) == 0 &&
                   memcmp(zs, z + (size_t)i * n, n * sizeof *zs) == 0 &&
                   hl_flow_nsteps(f) == steps[i] && (s1 == HL_OK || !strcmp(e1.msg, errs[i].msg));
        CHECK_MSG(same,
                  "%s tol %g, %d lanes, member %d of %d: status %d/%d, t %.17g/%.17g, "
                  "steps %ld/%ld, x %.17g/%.17g",
                  s->name, tol, lanes, i, B, s1, st[i], ts, t[i], hl_flow_nsteps(f), steps[i],
                  zs[0], z[(size_t)i * n]);
        differ += !same;
        CHECK(i == blow ? s1 == HL_EDOM : s1 == HL_OK);
        hl_flow_free(f);
    }
    (void)differ;
    free(z), free(t0), free(t1), free(t), free(st), free(steps), free(errs);
    hl_flow_batch_free(b);
}

/* z' = z^2 from z0 = 1/(T - t0)... blows up at T: the member whose pole is
 * inside its interval fails there, the others reach their end */
static void test_blowup(void)
{
    const char *names[] = {"z"};
    const hl_expr *z = hl_sym(P, "z"), *f[] = {hl_mul(P, z, z)};
    hl_tape *t = NULL;
    hl_error err;
    CHECK(hl_tape_new(&t, f, 1, names, 1, &err) == HL_OK);
    hl_flow_batch *b = NULL;
    CHECK(hl_flow_batch_new(&b, t, 1e-12, 1e-12, 4, &err) == HL_OK);
    double zz[5] = {1, 0.5, 0.25, 0.2, 1.0 / 3}, tt[5] = {0, 0, 0, 0, 0},
           t1[5] = {0.5, 2.5, 3, 4.5, 2.5}; /* poles at 1, 2, 4, 5, 3 */
    hl_status st[5];
    hl_status all = hl_flow_batch_evolve(b, 5, tt, t1, zz, st, NULL, NULL, &err);
    CHECK(all != HL_OK && strstr(err.msg, "member 1") != NULL);
    CHECK(st[0] == HL_OK && st[1] != HL_OK && st[2] == HL_OK && st[3] == HL_OK && st[4] == HL_OK);
    CHECK(fabs(zz[0] - 2) < 1e-10 && fabs(zz[2] - 1) < 1e-10 && fabs(zz[3] - 2) < 1e-9);
    CHECK_MSG(fabs(tt[1] - 2) < 1e-6, "%.17g", tt[1]); /* the last good step, near the pole */
    hl_flow_batch_free(b);
    hl_tape_free(t);
}

static void test_errors(void)
{
    const char *names[] = {"a", "b"};
    const hl_expr *f[] = {hl_sym(P, "b")};
    hl_tape *t = NULL;
    hl_error err;
    CHECK(hl_tape_new(&t, f, 1, names, 2, &err) == HL_OK);
    hl_flow_batch *b = (hl_flow_batch *)&err;
    CHECK(hl_flow_batch_new(&b, t, 1e-10, 1e-10, 4, &err) == HL_EINVAL && b == NULL);
    hl_tape_free(t);
    t = test_hamiltonian(P, "px^2/2 + x^2/2", 1);
    CHECK(hl_flow_batch_new(&b, t, 1e-10, 0, 4, &err) == HL_EINVAL);
    CHECK(hl_flow_batch_new(&b, t, 1e-10, 1e-10, 6, &err) == HL_EINVAL);
    CHECK(hl_flow_batch_new(&b, t, 1e-10, 1e-10, 4, &err) == HL_OK);
    double z[2] = {1, 0}, t0 = 0, t1 = INFINITY;
    hl_status st;
    CHECK(hl_flow_batch_evolve(b, 1, &t0, &t1, z, &st, NULL, NULL, &err) == HL_EINVAL);
    CHECK(st == HL_EINVAL && strstr(err.msg, "finite") != NULL);
    CHECK(hl_flow_batch_evolve(b, 0, NULL, NULL, NULL, NULL, NULL, NULL, &err) == HL_OK);
    CHECK(hl_flow_batch_evolve(b, -1, NULL, NULL, NULL, NULL, NULL, NULL, &err) == HL_EINVAL);
    hl_flow_batch_free(b);
    hl_flow_batch_free(NULL);
    hl_tape_free(t);
}

int main(void)
{
    P = hl_pool_new();
    for (size_t s = 0; s < sizeof systems / sizeof *systems; s++) {
        hl_tape *t = test_hamiltonian(P, systems[s].H, systems[s].N);
        if (t == NULL)
            continue;
        int blow = s == 2 ? 5 : -1;
        check_system(&systems[s], t, 1e-15, 4, 11, blow);
        check_system(&systems[s], t, 1e-9, 4, 9, blow);
        check_system(&systems[s], t, 1e-13, 8, 13, -1);
        check_system(&systems[s], t, 1e-13, 2, 5, -1);
        check_system(&systems[s], t, 1e-13, 1, 3, -1);
        hl_tape_free(t);
    }
    test_blowup();
    test_errors();
    hl_pool_free(P);
    return HL_TEST_END();
}
