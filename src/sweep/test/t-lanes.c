/* Lie members in SIMD lanes (issue 15 part 5):
 *   hl_run_adaptive_lanes against hl_run_adaptive, member by member, bit
 *   for bit (stats, state at the last row, status, message): the pendulum
 *   with more rows than one hl_flow_run call takes (80 000 rows at dt =
 *   1e-4: the restart between two calls), members of different spacings,
 *   a point outside H's domain, a blow-up (q^4 from q = 50), a member that
 *   leaves H's domain (log(q) with q falling to 0);
 *   the sweep's table with lanes on and off (HAMLIE_SWEEP_BATCH=1 / 0) and
 *   1 and 2 threads: the same bits, statuses and reasons, members ending
 *   ok, blown up and outside the domain side by side in one batch, with
 *   fixed-step schemes (through hl_run_fixed_batch when on: here its
 *   members one at a time, see below) and the chaos indicators beside
 *   them; the lanes ran (their member count) only when on.
 * Without libgccjit (the lanes one by one: a compilation a system would
 * cost a second or more); flow/t-batch has the compiled lanes' bits, and
 * tests/cli/sweep_lanes.sh a sweep's with them. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/run.h"
#include "hamlie/sweep.h"
#include "sweep/sweep_impl.h"

static hl_run *adaptive_run(hl_system **sys, const char *H)
{
    hl_system_spec ss = {H, NULL, NULL, NULL, NULL};
    hl_error err;
    hl_run *run = NULL;
    int st = hl_system_new(sys, &ss, &err);
    if (st == HL_OK)
        st = hl_run_new(&run, *sys, NULL, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    return run;
}

/* B members of H (N = 1) in lanes, each against its own hl_run_adaptive */
static void check_lanes(const char *H, double tol, double t, int B, const double *z0,
                        const double *dt, int expect_failures)
{
    hl_system *sys = NULL;
    hl_run *run = adaptive_run(&sys, H);
    if (run == NULL)
        return;
    hl_run_lanes *ls = NULL;
    hl_error err;
    CHECK_MSG(hl_run_lanes_new(&ls, run, tol, 4, &err) == HL_OK, "%s", err.msg);
    double *z = calloc((size_t)B * 2, sizeof *z);
    hl_run_stats *s = calloc((size_t)B, sizeof *s);
    hl_status *st = calloc((size_t)B, sizeof *st);
    hl_error *errs = calloc((size_t)B, sizeof *errs);
    hl_run_adaptive_lanes(ls, B, z0, dt, t, z, s, st, errs);
    int failures = 0;
    for (int i = 0; i < B; i++) {
        hl_run_stats s1;
        memset(&s1, 0, sizeof s1);
        hl_error e1;
        hl_error_clear(&e1);
        hl_status st1 = hl_run_check_start(run, z0 + 2 * i, &e1);
        if (st1 == HL_OK)
            st1 = hl_run_adaptive(run, z0 + 2 * i, tol, dt[i], t, 1, NULL, NULL, &s1, &e1);
        failures += st1 != HL_OK;
        const double *z1 = hl_run_state(run);
        int same = st1 == st[i] && (st1 == HL_OK || strcmp(e1.msg, errs[i].msg) == 0);
        if (same && (st1 == HL_OK || s1.nsteps > 0)) /* it started: its stats and state */
            same = !memcmp(&s1.t, &s[i].t, sizeof s1.t) && s1.steps == s[i].steps &&
                   s1.nsteps == s[i].nsteps && !memcmp(&s1.H0, &s[i].H0, sizeof s1.H0) &&
                   !memcmp(&s1.H, &s[i].H, sizeof s1.H) &&
                   !memcmp(&s1.max_dH, &s[i].max_dH, sizeof s1.max_dH) &&
                   s1.ref_steps == s[i].ref_steps && s1.failed == s[i].failed &&
                   !memcmp(z1, z + 2 * i, 2 * sizeof *z1);
        CHECK_MSG(same,
                  "%s member %d: status %d/%d (%s / %s), t %.17g/%.17g, rows %ld/%ld, steps "
                  "%ld/%ld, max_dH %.17g/%.17g, q %.17g/%.17g",
                  H, i, st1, st[i], e1.msg, errs[i].msg, s1.t, s[i].t, s1.steps, s[i].steps,
                  s1.ref_steps, s[i].ref_steps, s1.max_dH, s[i].max_dH, z1[0], z[2 * i]);
    }
    CHECK_MSG(failures == expect_failures, "%s: %d failures", H, failures);
    free(z), free(s), free(st), free(errs);
    hl_run_lanes_free(ls);
    hl_run_free(run);
    hl_system_free(sys);
}

static void test_run_lanes(void)
{
    /* the pendulum: 80 000 rows for member 0 (two calls of the flow) */
    double zp[10] = {1.3, 0.2, -2.0, 0.5, 0.1, 0, 3.0, 0.3, 2.5, -1.2};
    double dtp[5] = {1e-4, 0.1, 0.25, 0.5, 8};
    check_lanes("p^2/2 - cos(q)", 1e-14, 8, 5, zp, dtp, 0);
    /* q^4: from 50 it escapes in ~0.02; from 0.3 it stays */
    double zq[10] = {0.3, 0, 50, 0, -1.1, 0, 0.05, 0.1, 0.02, 0};
    double dtq[5] = {0.1, 0.01, 0.1, 0.05, 0.1};
    check_lanes("p^2/2 - q^4", 1e-13, 2, 5, zq, dtq, 2);
    /* log(q): q'' = -1/q takes q = 1, p = -1 to 0 at t = 0.66 (2, 0.5 at
     * 3.9; RK4 at h = 1e-4); q = -1 starts outside; q = 4, p = 1 stays */
    double zs[8] = {1, -1, -1, 0, 4, 1, 2, 0.5};
    double dts[4] = {0.1, 0.1, 0.05, 0.1};
    check_lanes("p^2/2 + log(q)", 1e-13, 2, 4, zs, dts, 2);
}

static hl_sweep_table *table(const hl_sweep_spec *spec, const char *mode, int threads,
                             long *in_lanes, hl_sweep **swp)
{
    setenv("HAMLIE_SWEEP_BATCH", mode, 1);
    hl_error err;
    hl_sweep *sw = NULL;
    CHECK_MSG(hl_sweep_new(&sw, spec, &err) == HL_OK, "%s", err.msg);
    if (sw == NULL)
        return NULL;
    hl_sweep_table *tab = hl_sweep_table_new(sw);
    long before = sweep_lanes_members();
    int st = hl_sweep_run(sw, NULL, hl_sweep_count(sw), threads, hl_sweep_table_store, tab, NULL,
                          NULL, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    *in_lanes = sweep_lanes_members() - before;
    *swp = sw;
    return tab;
}

static int same_tables(const hl_sweep *sw, const hl_sweep_table *a, const hl_sweep_table *b)
{
    for (long m = 0; m < hl_sweep_count(sw); m++) {
        const double *ra = hl_sweep_table_row(a, m), *rb = hl_sweep_table_row(b, m);
        if (ra == NULL || rb == NULL ||
            memcmp(ra, rb, (size_t)hl_sweep_ncols(sw) * sizeof *ra) != 0 ||
            hl_sweep_table_status(a, m) != hl_sweep_table_status(b, m) ||
            strcmp(hl_sweep_table_reason(a, m), hl_sweep_table_reason(b, m)) != 0) {
            fprintf(stderr, "member %ld differs: %s / %s\n", m, hl_sweep_table_reason(a, m),
                    hl_sweep_table_reason(b, m));
            return 0;
        }
    }
    return 1;
}

/* spec's table with lanes off (1 thread) against on (1 and 2 threads);
 * lie_members: how many lie members may be run in lanes */
static void check_sweep(const hl_sweep_spec *spec, long lie_members, int want_ok, int want_fail)
{
    hl_sweep *sw0 = NULL, *sw1 = NULL, *sw2 = NULL;
    long n0 = -1, n1 = -1, n2 = -1;
    hl_sweep_table *off = table(spec, "0", 1, &n0, &sw0), *on1 = table(spec, "1", 1, &n1, &sw1),
                   *on2 = table(spec, "1", 2, &n2, &sw2);
    if (off != NULL && on1 != NULL && on2 != NULL) {
        CHECK(same_tables(sw0, off, on1));
        CHECK(same_tables(sw0, off, on2));
        CHECK_MSG(n0 == 0 && n1 > 0 && n1 <= lie_members && n2 == n1, "%ld %ld %ld", n0, n1, n2);
        int ok = 0, fail = 0;
        for (long m = 0; m < hl_sweep_count(sw0); m++)
            hl_sweep_table_status(off, m) == HL_OK ? ok++ : fail++;
        CHECK_MSG(ok == want_ok && fail == want_fail, "%d ok, %d failed", ok, fail);
    }
    hl_sweep_table_free(off), hl_sweep_table_free(on1), hl_sweep_table_free(on2);
    hl_sweep_free(sw0), hl_sweep_free(sw1), hl_sweep_free(sw2);
}

static void test_sweep_tables(void)
{
    /* from rest at q0, q escapes at about 0.93 / q0: q0 = 50 and 1.2 before
     * t = 3 (every scheme fails), the others after 4.6; 8 points x 3
     * schemes x 2 steps */
    hl_sweep_spec q4 = {.H = "p^2/2 - q^4",
                        .grid = "q=0.05,50,0.02,-0.1,0.15,0.1,1.2,0.2,p=0",
                        .schemes = "lie,euler,stormer-verlet-kdk",
                        .dts = "0.1,0.05",
                        .t = 3,
                        .tol = 1e-13};
    check_sweep(&q4, 16, 36, 12);
    /* log(q): outside the domain at the start (q = -1, both p), and
     * later: q reaches 0 at t = 0.66 from (1, -1) and 1.31 from (2, -1),
     * at 2.6 and more from the others (RK4 at h = 1e-4); with the chaos
     * indicators of each point.  (Not sqrt(q): reading it factors, and
     * flint's table of primes stays in each thread: a leak to LSan.) */
    hl_sweep_spec sq = {.H = "p^2/2 + log(q)",
                        .grid = "q=1,-1,4,2,5,p=-1,1",
                        .schemes = "lie",
                        .dts = "0.5",
                        .t = 2,
                        .tol = 1e-12,
                        .chaos = 1};
    check_sweep(&sq, 10, 6, 4);
}

int main(void)
{
    setenv("HAMLIE_GCCJIT_LIB", "/nonexistent/libgccjit.so", 1); /* see above */
    test_run_lanes();
    test_sweep_tables();
    unsetenv("HAMLIE_SWEEP_BATCH");
    return HL_TEST_END();
}
