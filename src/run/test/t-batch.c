/* Fixed-step runs of many members at once (hl_run_fixed_batch): every
 * member's status, final state, max |H - H0|, H0 and H at the end bit for
 * bit those of hl_run_fixed run alone without machine code (the scheme's
 * stepper and the interpreter: the other path through the code), for
 * Störmer–Verlet, RK4 and symplectic Euler on the pendulum, Hénon–Heiles
 * and Kepler, 11 members (not a multiple of 2, 4 or 8 lanes), with the SIMD
 * lanes (the machine's vector width) used when libgccjit is there; a member that blows up
 * (explicit Euler at an energy above Hénon–Heiles' escape energy) fails
 * with the message it has alone while the others go on; a member that
 * cannot start (Kepler at the origin) the same; 2 and 8 lanes; a run with
 * the reference or a progress callback goes one member at a time with the
 * same results.  Registered twice: run/t-batch-scalar runs it with
 * libgccjit unloadable and the interpreter's scalar loop
 * (HAMLIE_GCCJIT_LIB=/nonexistent HAMLIE_NO_AVX2=1), where the members
 * go one at a time and every comparison must still hold. */
#include <stdio.h>

#include "run_test.h"

#if defined(__SANITIZE_ADDRESS__)
#define STEPS 8000 /* the lanes still pay: 11 * 8000 > the loop's break-even with the cache */
#else
#define STEPS 30000
#endif
#define B 11

typedef struct result {
    hl_status st[B];
    double z[B][4];
    hl_run_stats s[B];
    char msg[B][HL_ERROR_MSG_MAX];
} result;

/* Member i alone, machine code off: the stepper's path. */
static void alone(fixture *f, const double *z0, int n2, double dt, double t, result *r)
{
    hl_run_set_jit(f->run, 0);
    for (int i = 0; i < B; i++) {
        hl_error err;
        hl_error_clear(&err);
        memset(&r->s[i], 0, sizeof r->s[i]);
        r->st[i] = hl_run_fixed(f->run, z0 + i * n2, dt, t, 1, NULL, NULL, &r->s[i], &err);
        /* a member that cannot start keeps z0 in the batch's contract */
        int started = r->st[i] == HL_OK || r->s[i].failed;
        memcpy(r->z[i], started ? hl_run_state(f->run) : z0 + i * n2, (size_t)n2 * sizeof(double));
        snprintf(r->msg[i], sizeof r->msg[i], "%s", r->st[i] == HL_OK ? "" : err.msg);
    }
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* The batch's member i against the single run's: 1 if equal. */
static int same_member(const result *a, const result *b, int i, int n2)
{
    const hl_run_stats *x = &a->s[i], *y = &b->s[i];
    if (a->st[i] != b->st[i] || strcmp(a->msg[i], b->msg[i]) != 0)
        return 0;
    for (int c = 0; c < n2; c++)
        if (!same_bits(a->z[i][c], b->z[i][c]))
            return 0;
    return x->steps == y->steps && x->nsteps == y->nsteps && x->failed == y->failed &&
           same_bits(x->H0, y->H0) && same_bits(x->H, y->H) && same_bits(x->max_dH, y->max_dH) &&
           same_bits(x->t, y->t);
}

/* The batch with machine code on; returns the lanes it used. */
static int batched(fixture *f, const double *z0, int n2, double dt, double t, result *r)
{
    hl_run_set_jit(f->run, 1);
    int lanes = hl_run_batch_lanes(f->run, B, dt, t);
    hl_error errs[B], err;
    hl_error_clear(&err);
    double z[B * 4];
    hl_run_fixed_batch(f->run, B, z0, dt, t, z, r->s, r->st, errs, &err);
    for (int i = 0; i < B; i++) {
        memcpy(r->z[i], z + i * n2, (size_t)n2 * sizeof(double));
        snprintf(r->msg[i], sizeof r->msg[i], "%s", r->st[i] == HL_OK ? "" : errs[i].msg);
    }
    return lanes;
}

/* Every member of a batch against its single run; returns the lanes. */
static int compare(fixture *f, const double *z0, int n2, double dt, double t, const char *what)
{
    static result one, many;
    alone(f, z0, n2, dt, t, &one);
    int lanes = batched(f, z0, n2, dt, t, &many);
    for (int i = 0; i < B; i++)
        CHECK_MSG(same_member(&many, &one, i, n2),
                  "%s, member %d: status %d/%d, max dH %.17g/%.17g, x %.17g/%.17g (%s | %s)", what,
                  i, many.st[i], one.st[i], many.s[i].max_dH, one.s[i].max_dH, many.z[i][0],
                  one.z[i][0], many.msg[i], one.msg[i]);
    return lanes;
}

/* B members around z, all different (c + 3 is prime to 11) */
static void spread(double *z0, const double *z, int n2, double scale)
{
    for (int i = 0; i < B; i++)
        for (int c = 0; c < n2; c++)
            z0[i * n2 + c] = z[c] + scale * (double)((i * (c + 3)) % 11 - 5) / 10;
}

static void test_catalog(void)
{
    static const char *const H[] = {PENDULUM, HENON, KEPLER};
    static const char *const init[] = {"q=1.3,p=0.1", "x=0,y=0.1,px=0.3,py=0.05",
                                       "x=1,y=0,px=0,py=1.1"};
    static const char *const schemes[] = {"stormer-verlet-kdk", "rk4", "symplectic-euler-a"};
    for (int s = 0; s < 3; s++)
        for (int h = 0; h < 3; h++) {
            fixture f;
            if (!fixture_new(&f, H[h], schemes[s], init[h]))
                continue;
            hl_run_set_reference(f.run, 0, 0);
            int n2 = h == 0 ? 2 : 4;
            double z0[B * 4];
            spread(z0, f.z0, n2, h == 1 ? 0.05 : 0.2);
            char what[128];
            snprintf(what, sizeof what, "%s on %s", schemes[s], H[h]);
            int lanes = compare(&f, z0, n2, 0.01, 0.01 * STEPS, what);
            CHECK_MSG(lanes == (hl_tape_jit_available() ? hl_tape_lanes_native() : 1),
                      "%s: %d lanes", what, lanes);
            fixture_clear(&f);
        }
}

/* Euler on Hénon–Heiles, dt = 0.001: member 3 far above the escape energy
 * 1/6 blows up long before the end; the others, near the origin, do not. */
static void test_blow_up(void)
{
    fixture f;
    if (!fixture_new(&f, HENON, "euler", "x=0,y=0.1,px=0.3,py=0.05"))
        return;
    hl_run_set_reference(f.run, 0, 0);
    double z0[B * 4];
    spread(z0, f.z0, 4, 0.05);
    z0[3 * 4 + 2] = 1; /* E > 1/2: escapes at once */
    static result one;
    alone(&f, z0, 4, 0.001, 0.001 * STEPS, &one);
    CHECK_MSG(one.st[3] == HL_EDOM && one.s[3].steps < STEPS, "member 3 alone: %d at %ld",
              one.st[3], one.s[3].steps);
    for (int i = 0; i < B; i++)
        CHECK(i == 3 || one.st[i] == HL_OK);
    compare(&f, z0, 4, 0.001, 0.001 * STEPS, "euler on Henon-Heiles, member 3 escapes");
    /* the call's own status: member 3's, named */
    hl_error err;
    hl_status st[B];
    double z[B * 4];
    CHECK(hl_run_fixed_batch(f.run, B, z0, 0.001, 0.001 * STEPS, z, NULL, st, NULL, &err) ==
          HL_EDOM);
    CHECK_MSG(strncmp(err.msg, "member 3: blow-up", 17) == 0, "%s", err.msg);
    fixture_clear(&f);
}

/* Kepler from the origin: H is not finite there; the others go on. */
static void test_bad_start(void)
{
    fixture f;
    if (!fixture_new(&f, KEPLER, "stormer-verlet-kdk", "x=1,y=0,px=0,py=1.1"))
        return;
    hl_run_set_reference(f.run, 0, 0);
    double z0[B * 4];
    spread(z0, f.z0, 4, 0.2);
    z0[5 * 4] = z0[5 * 4 + 1] = 0;
    compare(&f, z0, 4, 0.01, 0.01 * STEPS, "Kepler, member 5 at the origin");
    static result many;
    batched(&f, z0, 4, 0.01, 0.01 * STEPS, &many);
    CHECK(many.st[5] == HL_EDOM && strstr(many.msg[5], "outside H's domain") != NULL);
    CHECK(many.s[5].steps == 0 && many.s[5].max_dH == 0);
    fixture_clear(&f);
}

static int keep_going(double done, double total, void *arg)
{
    (void)done, (void)total, (void)arg;
    return 0;
}

/* 2 and 8 lanes; z aliasing z0; with the reference or a progress callback
 * one member at a time; lanes that are not a power of 2 refused. */
static void test_settings(void)
{
    fixture f;
    if (!fixture_new(&f, HENON, "stormer-verlet-kdk", "x=0,y=0.1,px=0.3,py=0.05"))
        return;
    hl_run_set_reference(f.run, 0, 0);
    double z0[B * 4];
    spread(z0, f.z0, 4, 0.05);
    int jit = hl_tape_jit_available();
    for (int lanes = 2; lanes <= 8; lanes *= 4) {
        CHECK(hl_run_set_lanes(f.run, lanes, NULL) == HL_OK);
        CHECK(compare(&f, z0, 4, 0.01, 0.01 * STEPS, "lanes") == (jit ? lanes : 1));
    }
    CHECK(hl_run_set_lanes(f.run, 0, NULL) == HL_OK);
    static result one;
    alone(&f, z0, 4, 0.01, 0.01 * STEPS, &one);
    hl_run_set_jit(f.run, 1);
    hl_status st[B];
    CHECK(hl_run_fixed_batch(f.run, B, z0, 0.01, 0.01 * STEPS, z0, NULL, st, NULL, NULL) == HL_OK);
    for (int i = 0; i < B; i++)
        CHECK(memcmp(z0 + 4 * i, one.z[i], 4 * sizeof(double)) == 0);
    spread(z0, f.z0, 4, 0.05);
    hl_run_set_progress(f.run, keep_going, NULL);
    CHECK(hl_run_batch_lanes(f.run, B, 0.01, 0.01 * STEPS) == 1);
    compare(&f, z0, 4, 0.01, 0.01 * STEPS, "with a progress callback");
    hl_run_set_progress(f.run, NULL, NULL);
    hl_run_set_reference(f.run, 1, 0);
    CHECK(hl_run_batch_lanes(f.run, B, 0.01, 0.01 * STEPS) == 1);
    compare(&f, z0, 4, 0.01, 1, "with the reference");
    hl_error err;
    CHECK(hl_run_set_lanes(f.run, 3, &err) == HL_EINVAL && strstr(err.msg, "power of 2"));
    CHECK(hl_run_set_lanes(f.run, 32, &err) == HL_EINVAL);
    CHECK(hl_run_fixed_batch(f.run, B, z0, 0.3, 20, z0, NULL, st, NULL, &err) == HL_EINVAL);
    CHECK(st[0] == HL_EINVAL && st[B - 1] == HL_EINVAL);
    CHECK(hl_run_fixed_batch(f.run, 0, z0, 0.01, 1, z0, NULL, st, NULL, &err) == HL_OK);
    fixture_clear(&f);
}

int main(void)
{
    if (!hl_tape_jit_available())
        printf("no libgccjit: the members go one at a time\n");
    test_catalog();
    test_blow_up();
    test_bad_start();
    test_settings();
    return HL_TEST_END();
}
