/* Running a sweep (sweep.h):
 *   the table is the same bits with 1, 2 and 3 threads and with the
 *   members listed backwards (explicit, implicit and adaptive schemes,
 *   the reference, orders, chaos);
 *   a member's row equals a single run of its own (a fresh system and
 *   hl_run_fixed or hl_run_adaptive: final state and max |H - H0| bit for
 *   bit), and its
 *   chaos columns a fresh hl_chaos_run;
 *   Stormer-Verlet's observed order is 2 on the pendulum away from the
 *   separatrix;
 *   failures are rows: a blow-up (H = p^2/2 - q^4 from q = 50, escaping
 *   in finite time ~0.93/q0: q0 = 0.05 and 0.02 stay to t = 10) and a
 *   point outside H's domain (Kepler at the origin), the others done;
 *   a callback's stop ends the sweep with HL_ESTOP, its results valid;
 *   the CSV: same table, same bytes; an unwritable path leaves nothing; an
 *   incomplete table is refused;
 *   the journal: an interrupted sweep resumed (with a torn last record)
 *   gives the same table; another sweep's journal is refused. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "hl_test.h"
#include "hamlie/chaos.h"
#include "hamlie/run.h"
#include "hamlie/sweep.h"

static hl_sweep *make(const hl_sweep_spec *spec)
{
    hl_sweep *sw = NULL;
    hl_error err;
    hl_error_clear(&err);
    int st = hl_sweep_new(&sw, spec, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    return sw;
}

static hl_sweep_table *run_all(hl_sweep *sw, const long *members, long n, int threads)
{
    hl_sweep_table *tab = hl_sweep_table_new(sw);
    hl_error err;
    hl_error_clear(&err);
    int st = hl_sweep_run(sw, members, members ? n : hl_sweep_count(sw), threads,
                          hl_sweep_table_store, tab, NULL, NULL, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
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
            fprintf(stderr, "member %ld differs\n", m);
            return 0;
        }
    }
    return 1;
}

static const hl_sweep_spec MIXED = {.H = "p^2/2 - cos(q)",
                                    .grid = "q=-2:2:5,p=-0.5:0.5:3",
                                    .schemes = "stormer-verlet-kdk,implicit-midpoint,lie",
                                    .dts = "0.2,0.1",
                                    .t = 4,
                                    .tol = 1e-13,
                                    .reference = 1,
                                    .order = 1,
                                    .chaos = 1};

static void test_threads(void)
{
    hl_sweep *sw = make(&MIXED);
    if (sw == NULL)
        return;
    long n = hl_sweep_count(sw);
    CHECK(n == 15 * 3 * 2);
    hl_sweep_table *one = run_all(sw, NULL, 0, 1), *two = run_all(sw, NULL, 0, 2),
                   *three = run_all(sw, NULL, 0, 3);
    long *back = malloc((size_t)n * sizeof *back);
    for (long i = 0; i < n; i++)
        back[i] = n - 1 - i;
    hl_sweep_table *rev = run_all(sw, back, n, 2);
    CHECK(hl_sweep_table_done(one) == n);
    for (long m = 0; m < n; m++)
        CHECK_MSG(hl_sweep_table_status(one, m) == HL_OK, "member %ld: %s", m,
                  hl_sweep_table_reason(one, m));
    CHECK(same_tables(sw, one, two));
    CHECK(same_tables(sw, one, three));
    CHECK(same_tables(sw, one, rev));
    free(back);
    hl_sweep_table_free(one);
    hl_sweep_table_free(two);
    hl_sweep_table_free(three);
    hl_sweep_table_free(rev);
    hl_sweep_free(sw);
}

/* Member m of MIXED against a fresh run of its own. */
static void test_single_run(void)
{
    hl_sweep *sw = make(&MIXED);
    if (sw == NULL)
        return;
    hl_sweep_table *tab = run_all(sw, NULL, 0, 2);
    /* point 8: q index 2 (q = 0), p index 2 (p = 0.5); scheme 0, dt index 1 (0.1) */
    long m = ((8 * 1 + 0) * 3 + 0) * 2 + 1;
    const double *row = hl_sweep_table_row(tab, m);
    hl_system *sys = NULL;
    hl_system_spec ss = {"p^2/2 - cos(q)", NULL, NULL, NULL, NULL};
    hl_scheme *sch = NULL;
    hl_run *run = NULL;
    hl_error err;
    int st = hl_system_new(&sys, &ss, &err);
    if (st == HL_OK)
        st = hl_scheme_new(&sch, "stormer-verlet-kdk", 4, sys, &err);
    if (st == HL_OK)
        st = hl_run_new(&run, sys, sch, &err);
    if (st == HL_OK)
        hl_run_set_reference(run, 1, 1e-13);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    double z0[2] = {0, 0.5};
    hl_run_stats s;
    if (st == HL_OK && row != NULL) {
        CHECK(row[hl_sweep_column_index(sw, "q0")] == 0 &&
              row[hl_sweep_column_index(sw, "p0")] == 0.5 && row[4] == 0.1);
        st = hl_run_fixed(run, z0, 0.1, 4, 1, NULL, NULL, &s, &err);
        CHECK(st == HL_OK);
        const double *z = hl_run_state(run);
        CHECK(row[hl_sweep_column_index(sw, "q")] == z[0]);
        CHECK(row[hl_sweep_column_index(sw, "p")] == z[1]);
        CHECK(row[hl_sweep_column_index(sw, "max_dH")] == s.max_dH);
        CHECK(row[hl_sweep_column_index(sw, "max_err")] == s.max_err);
        CHECK(row[hl_sweep_column_index(sw, "steps")] == 40);
        /* order 2 +- 0.05 (pendulum, well inside the separatrix) */
        double order = row[hl_sweep_column_index(sw, "order")];
        CHECK_MSG(fabs(order - 2) < 0.05, "order %g", order);
        hl_chaos *c = NULL;
        hl_chaos_result res;
        st = hl_chaos_new(&c, sys, 1e-13, &err);
        if (st == HL_OK)
            st = hl_chaos_run(c, z0, NULL, 4, 0, NULL, NULL, &res, &err);
        CHECK(st == HL_OK && row[hl_sweep_column_index(sw, "megno")] == res.megno_mean &&
              row[hl_sweep_column_index(sw, "mlce")] == res.mlce);
        hl_chaos_free(c);
        /* the adaptive member (scheme 2) of the same point: a fresh run without
         * a progress callback (which would restart the integrator, run.h) */
        const double *lie = hl_sweep_table_row(tab, ((8 * 1 + 0) * 3 + 2) * 2 + 1);
        hl_run *ad = NULL;
        st = hl_run_new(&ad, sys, NULL, &err);
        if (st == HL_OK)
            st = hl_run_adaptive(ad, z0, 1e-13, 0.1, 4, 1, NULL, NULL, &s, &err);
        CHECK(st == HL_OK && lie != NULL &&
              lie[hl_sweep_column_index(sw, "q")] == hl_run_state(ad)[0] &&
              lie[hl_sweep_column_index(sw, "p")] == hl_run_state(ad)[1] &&
              lie[hl_sweep_column_index(sw, "max_dH")] == s.max_dH);
        hl_run_free(ad);
    }
    hl_run_free(run);
    hl_scheme_free(sch);
    hl_system_free(sys);
    hl_sweep_table_free(tab);
    hl_sweep_free(sw);
}

static void test_failures(void)
{
    hl_sweep_spec spec = {.H = "p^2/2 - q^4",
                          .grid = "q=0.05,50,0.02,p=0",
                          .schemes = "euler",
                          .dts = "0.1",
                          .t = 10};
    hl_sweep *sw = make(&spec);
    if (sw != NULL) {
        hl_sweep_table *tab = run_all(sw, NULL, 0, 2);
        CHECK(hl_sweep_table_done(tab) == 3);
        CHECK(hl_sweep_table_status(tab, 0) == HL_OK && hl_sweep_table_status(tab, 2) == HL_OK);
        CHECK(hl_sweep_table_status(tab, 1) == HL_EDOM);
        CHECK_MSG(strstr(hl_sweep_table_reason(tab, 1), "blow-up") != NULL, "%s",
                  hl_sweep_table_reason(tab, 1));
        const double *row = hl_sweep_table_row(tab, 1);
        CHECK(row[hl_sweep_column_index(sw, "t")] < 10); /* the last good step */
        hl_sweep_table_free(tab);
    }
    hl_sweep_free(sw);
    hl_sweep_spec kepler = {
        .H = "p^2/2 - 1/sqrt(q^2)", .grid = "q=1,0,p=0.5", .schemes = "rk4", .dts = "0.01", .t = 1};
    sw = make(&kepler);
    if (sw != NULL) {
        hl_sweep_table *tab = run_all(sw, NULL, 0, 1);
        CHECK(hl_sweep_table_status(tab, 0) == HL_OK);
        CHECK(hl_sweep_table_status(tab, 1) == HL_EDOM);
        hl_sweep_table_free(tab);
    }
    hl_sweep_free(sw);
}

typedef struct stopper {
    hl_sweep_table *tab;
    int left;
} stopper;

static int stop_soon(const hl_sweep_result *r, void *arg)
{
    stopper *s = arg;
    hl_sweep_table_store(r, s->tab);
    return --s->left <= 0;
}

static void test_stop(void)
{
    hl_sweep_spec spec = {
        .H = "p^2/2 - cos(q)", .grid = "q=0:1:40,p=0", .schemes = "rk4", .dts = "0.01", .t = 10};
    hl_sweep *sw = make(&spec);
    if (sw == NULL)
        return;
    stopper s = {hl_sweep_table_new(sw), 3};
    hl_error err;
    int st = hl_sweep_run(sw, NULL, hl_sweep_count(sw), 2, stop_soon, &s, NULL, NULL, &err);
    CHECK(st == HL_ESTOP);
    CHECK(hl_sweep_table_done(s.tab) >= 3 && hl_sweep_table_done(s.tab) <= 5);
    CHECK(hl_sweep_write(sw, s.tab, "/nonexistent-dir/x.csv", &err) == HL_EINVAL);
    hl_sweep_table_free(s.tab);
    hl_sweep_free(sw);
}

static char *slurp(const char *path, size_t *n)
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return NULL;
    char *buf = malloc(1 << 20);
    *n = fread(buf, 1, 1 << 20, fp);
    fclose(fp);
    return buf;
}

static void test_write_and_journal(void)
{
    char dir[] = "/tmp/hl-sweep-XXXXXX";
    if (mkdtemp(dir) == NULL)
        return;
    char out[64], out2[64], journal[80];
    snprintf(out, sizeof out, "%s/a.csv", dir);
    snprintf(out2, sizeof out2, "%s/b.csv", dir);
    snprintf(journal, sizeof journal, "%s.journal", out);
    hl_sweep_spec spec = {.H = "p^2/2 - cos(q)",
                          .grid = "q=-1:1:7,p=0:1:2",
                          .schemes = "stormer-verlet-kdk,rk4",
                          .dts = "0.1",
                          .t = 2,
                          .chaos = 1,
                          .tol = 1e-12};
    hl_sweep *sw = make(&spec);
    if (sw == NULL)
        return;
    hl_error err;
    hl_sweep_table *full = run_all(sw, NULL, 0, 2);
    CHECK(hl_sweep_write(sw, full, out, &err) == HL_OK);
    CHECK(hl_sweep_write(sw, full, out2, &err) == HL_OK);
    size_t na = 0, nb = 0;
    char *a = slurp(out, &na), *b = slurp(out2, &nb);
    CHECK(a != NULL && b != NULL && na == nb && na > 0 && memcmp(a, b, na) == 0);
    CHECK(a != NULL && strncmp(a, "member,point,paramset,scheme,dt,q0,p0,t,", 40) == 0);
    free(a);
    free(b);
    CHECK(hl_sweep_write(sw, full, "/nonexistent-dir/x.csv", &err) == HL_EIO);
    CHECK(access("/nonexistent-dir", F_OK) != 0);

    /* interrupted: the first 10 members journaled, then a torn record */
    hl_sweep_table *part = hl_sweep_table_new(sw);
    hl_sweep_journal *j = NULL;
    CHECK(hl_sweep_journal_open(&j, sw, out, 0, part, &err) == HL_OK);
    long first[10];
    for (int i = 0; i < 10; i++)
        first[i] = 3 * i;
    if (j != NULL)
        CHECK(hl_sweep_run(sw, first, 10, 2, hl_sweep_journal_append, j, NULL, NULL, &err) ==
              HL_OK);
    hl_sweep_journal_close(j, 0);
    FILE *fp = fopen(journal, "ab");
    fwrite("\x05\x00\x00\x00\x00\x00\x00\x00garbage", 1, 15, fp);
    fclose(fp);
    hl_sweep_table *resumed = hl_sweep_table_new(sw);
    CHECK(hl_sweep_journal_open(&j, sw, out, 1, resumed, &err) == HL_OK);
    CHECK(hl_sweep_table_done(resumed) == 10 && hl_sweep_table_has(resumed, 27));
    long n = 0, *rest = malloc((size_t)hl_sweep_count(sw) * sizeof *rest);
    for (long m = 0; m < hl_sweep_count(sw); m++)
        if (!hl_sweep_table_has(resumed, m))
            rest[n++] = m;
    if (j != NULL) /* the rest journaled too, after the torn tail was cut */
        CHECK(hl_sweep_run(sw, rest, n, 2, hl_sweep_journal_append, j, NULL, NULL, &err) == HL_OK);
    hl_sweep_journal_close(j, 0);
    hl_sweep_table *again = hl_sweep_table_new(sw);
    CHECK(hl_sweep_journal_open(&j, sw, out, 1, again, &err) == HL_OK);
    hl_sweep_journal_close(j, 1);
    CHECK(access(journal, F_OK) != 0);
    CHECK(hl_sweep_table_done(again) == hl_sweep_count(sw));
    CHECK(same_tables(sw, full, again));
    free(rest);

    /* another sweep's journal */
    spec.t = 4;
    hl_sweep *other = make(&spec);
    CHECK(hl_sweep_journal_open(&j, sw, out, 0, part, &err) == HL_OK);
    hl_sweep_journal_close(j, 0);
    hl_sweep_table *ot = other ? hl_sweep_table_new(other) : NULL;
    if (other != NULL) {
        CHECK(hl_sweep_journal_open(&j, other, out, 1, ot, &err) == HL_EINVAL);
        CHECK_MSG(strstr(err.msg, "another sweep") != NULL, "%s", err.msg);
    }
    remove(journal);
    remove(out);
    remove(out2);
    rmdir(dir);
    hl_sweep_table_free(ot);
    hl_sweep_free(other);
    hl_sweep_table_free(full);
    hl_sweep_table_free(part);
    hl_sweep_table_free(resumed);
    hl_sweep_table_free(again);
    hl_sweep_free(sw);
}

int main(void)
{
    test_threads();
    test_single_run();
    test_failures();
    test_stop();
    test_write_and_journal();
    return HL_TEST_END();
}
