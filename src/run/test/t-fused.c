/* The fast path of long fixed-step runs (drive.c: an explicit step and H
 * fused into one compiled tape, iterated between rows) gives the rows,
 * statistics and failures of the stepper's path:
 *   Euler on the oscillator, dt = 0.05, 8e5 steps: 2 H_n = (1 + dt^2)^n
 *     exactly, so x^2 + p^2 overflows at step log(DBL_MAX)/log(1.0025) =
 *     284,268: the run stops there with the stepper's message; rows
 *     every 10^4 steps are those of the run without machine code, and
 *     max |H - H0| is H's value at the last finite state minus 1/2;
 *   Stormer-Verlet on the pendulum, 5e5 steps, rows every 1000: the same
 *     rows, final state and max |H - H0| as without machine code (to
 *     round-off: sin may be computed by sincos), and max |H - H0| below
 *     the O(dt^2) bound of a symplectic method;
 *   a run that returns from its callback stops at once with that value.
 * Without libgccjit both runs take the same path and the checks hold
 * trivially (said on stdout). */
#include <stdio.h>

#include "run_test.h"

#define MAXROWS 1024

typedef struct rows {
    long n, k[MAXROWS];
    double z[MAXROWS][2], H[MAXROWS];
    long stop_at; /* return 7 from the callback at this step (0: never) */
} rows;

static int keep_row(const hl_run_row *row, void *arg)
{
    rows *r = arg;
    if (r->n < MAXROWS) {
        r->k[r->n] = row->k;
        r->z[r->n][0] = row->z[0], r->z[r->n][1] = row->z[1];
        r->H[r->n++] = row->H;
    }
    return r->stop_at != 0 && row->k >= r->stop_at ? 7 : 0;
}

/* Run twice, machine code off and on; returns the statuses. */
static void both(fixture *f, double dt, double t, long every, rows *r, hl_run_stats *s, int *st,
                 char msg[2][HL_ERROR_MSG_MAX])
{
    hl_error err;
    for (int jit = 0; jit < 2; jit++) {
        hl_run_set_reference(f->run, 0, 0);
        hl_run_set_jit(f->run, jit);
        long stop = r[jit].stop_at;
        memset(&r[jit], 0, sizeof r[jit]);
        r[jit].stop_at = stop;
        hl_error_clear(&err);
        st[jit] = hl_run_fixed(f->run, f->z0, dt, t, every, keep_row, &r[jit], &s[jit], &err);
        memcpy(msg[jit], st[jit] == HL_OK ? "" : err.msg, st[jit] == HL_OK ? 1 : sizeof err.msg);
    }
}

static int same_rows(const rows *a, const rows *b, double tol)
{
    if (a->n != b->n)
        return 0;
    for (long i = 0; i < a->n; i++)
        if (a->k[i] != b->k[i] || !(fabs(a->z[i][0] - b->z[i][0]) <= tol) ||
            !(fabs(a->z[i][1] - b->z[i][1]) <= tol) || !(fabs(a->H[i] - b->H[i]) <= tol))
            return 0;
    return 1;
}

static void test_blow_up(void)
{
    fixture f;
    if (!fixture_new(&f, OSC, "euler", "x=1,p=0"))
        return;
    static rows r[2];
    hl_run_stats s[2];
    int st[2];
    char msg[2][HL_ERROR_MSG_MAX];
    both(&f, 0.05, 40000, 10000, r, s, st, msg);
    printf("blow-up without / with machine code:\n  %s\n  %s\n", msg[0], msg[1]);
    long expect = (long)(log(DBL_MAX) / log(1 + 0.05 * 0.05));
    CHECK(st[0] == HL_EDOM && st[1] == HL_EDOM && s[0].failed && s[1].failed);
    CHECK_MSG(strcmp(msg[0], msg[1]) == 0, "messages differ");
    CHECK_MSG(labs(s[1].steps - expect) <= 2, "stopped at %ld, expected about %ld", s[1].steps,
              expect);
    CHECK(s[0].steps == s[1].steps && same_rows(&r[0], &r[1], 0));
    CHECK(r[1].n == s[1].steps / 10000 + 1 && r[1].k[r[1].n - 1] % 10000 == 0);
    double H_last = 0.5 * pow(1 + 0.05 * 0.05, (double)s[1].steps);
    CHECK_MSG(fabs(s[1].max_dH - (H_last - 0.5)) <= 1e-9 * H_last, "max dH %g vs %g",
              s[1].max_dH, H_last - 0.5);
    CHECK(s[0].max_dH == s[1].max_dH);
    fixture_clear(&f);
}

static void test_long_run(void)
{
    fixture f;
    if (!fixture_new(&f, PENDULUM, "stormer-verlet-kdk", "q=1.3,p=0"))
        return;
    static rows r[2];
    hl_run_stats s[2];
    int st[2];
    char msg[2][HL_ERROR_MSG_MAX];
    both(&f, 0.01, 5000, 1000, r, s, st, msg);
    CHECK(st[0] == HL_OK && st[1] == HL_OK);
    CHECK(s[0].steps == 500000 && s[1].steps == 500000 && r[1].n == 501);
    CHECK_MSG(same_rows(&r[0], &r[1], 1e-12), "rows differ");
    CHECK_MSG(fabs(s[0].max_dH - s[1].max_dH) <= 1e-15, "max dH %.17g vs %.17g", s[0].max_dH,
              s[1].max_dH);
    /* Verlet's energy error: O(dt^2), about dt^2/8 * |U''| p^2 ~ 2e-5 here */
    CHECK(s[1].max_dH > 1e-7 && s[1].max_dH < 1e-4);
    printf("Verlet, 5e5 steps: max |H - H0| %.6g (both paths)\n", s[1].max_dH);
    /* the callback stops the run: its value comes back, nothing failed */
    r[0].stop_at = r[1].stop_at = 250000;
    both(&f, 0.01, 5000, 1000, r, s, st, msg);
    CHECK(st[0] == 7 && st[1] == 7 && !s[1].failed && r[1].k[r[1].n - 1] == 250000);
    CHECK(same_rows(&r[0], &r[1], 1e-12));
    fixture_clear(&f);
}

int main(void)
{
    if (!hl_tape_jit_available())
        printf("no libgccjit: both runs take the stepper's path\n");
    test_blow_up();
    test_long_run();
    return HL_TEST_END();
}
