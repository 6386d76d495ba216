/* The progress callback (hl_run_set_progress) and the initial point's
 * domain (hl_run_check_start).  Metamorphic: a run stopped by its callback
 * at step k is the run to t = k dt, bit for bit — its rows, its statistics
 * and its state — on every path of the driver (the reference, the plain
 * stepper, the compiled loop; the adaptive integrator against the same run
 * with a callback that never stops it, whose probes between rows restart
 * the integrator; Arb); the callback is called at a bounded rate, also
 * between rows far apart; a point where H is not finite is refused before
 * the first row, and the Lie series stops at its order. */
#include "run_test.h"

typedef struct stopper {
    double stop_at; /* ask to stop from this many steps on */
    long calls;
    double last;    /* done at the last call */
} stopper;

static int stop_fn(double done, double total, void *arg)
{
    stopper *s = arg;
    (void)total;
    CHECK(done > s->last); /* it advances */
    s->calls++;
    s->last = done;
    return done >= s->stop_at;
}

typedef struct rows {
    long n, last_k;
    double last_z[4];
} rows;

static int row_fn(const hl_run_row *row, void *arg)
{
    rows *r = arg;
    CHECK(row->k == 0 || row->k > r->last_k);
    r->n++;
    r->last_k = row->k;
    memcpy(r->last_z, row->z, 2 * sizeof *row->z);
    return 0;
}

/* A fixed-step run stopped at 3000 steps against the run to that step. */
static void stopped_fixed(const char *scheme, int reference, long every, int jit)
{
    fixture f;
    if (!fixture_new(&f, PENDULUM, scheme, "q=1.3,p=0"))
        return;
    hl_run_set_reference(f.run, reference, 1e-15);
    hl_run_set_jit(f.run, jit);
    stopper sp = {3000, 0, 0};
    hl_run_set_progress(f.run, stop_fn, &sp);
    rows a = {0, -1, {0}}, b = {0, -1, {0}};
    hl_run_stats sa, sb;
    hl_error err;
    double dt = 0.01;
    /* n = 10^6 steps: the compiled loop's break-even is passed */
    int st = hl_run_fixed(f.run, f.z0, dt, 1e4, every, row_fn, &a, &sa, &err);
    CHECK_MSG(st == HL_ESTOP, "%s: status %d (%s)", scheme, st, err.msg);
    CHECK(strstr(err.msg, "stopped at step") != NULL);
    long k = sa.steps;
    CHECK_MSG(k >= 3000 && k <= 3000 + 65536, "%s: stopped at %ld", scheme, k);
    CHECK(sp.calls >= 1 && sp.calls <= k / 1024 + 2);
    double za[2];
    memcpy(za, hl_run_state(f.run), sizeof za);
    hl_run_set_progress(f.run, NULL, NULL);
    st = hl_run_fixed(f.run, f.z0, dt, (double)k * dt, every, row_fn, &b, &sb, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", scheme, err.msg);
    CHECK(sb.steps == k);
    CHECK_MSG(memcmp(za, hl_run_state(f.run), sizeof za) == 0, "%s: the states differ", scheme);
    CHECK(sa.max_dH == sb.max_dH && sa.H == sb.H && sa.t == sb.t);
    if (reference)
        CHECK(sa.max_err == sb.max_err);
    /* the rows up to the stop are those of the shorter run (which also
     * delivers its last step) */
    CHECK(a.last_k <= k && b.last_k == k && a.n <= b.n && b.n - a.n <= 1);
    if (a.last_k == k)
        CHECK(memcmp(a.last_z, b.last_z, sizeof a.last_z / 2) == 0);
    fixture_clear(&f);
}

static int never_fn(double done, double total, void *arg)
{
    (void)done, (void)total;
    ++*(long *)arg;
    return 0;
}

static void stopped_adaptive(void)
{
    fixture f;
    if (!fixture_new(&f, PENDULUM, NULL, "q=1.3,p=0"))
        return;
    stopper sp = {40, 0, 0};
    hl_run_set_progress(f.run, stop_fn, &sp);
    hl_run_stats sa, sb, sc;
    hl_error err;
    int st = hl_run_adaptive(f.run, f.z0, 1e-12, 0.5, 1000, 1, NULL, NULL, &sa, &err);
    CHECK(st == HL_ESTOP && sa.steps == 40 && sp.calls >= 40);
    double za[2], zc[2];
    memcpy(za, hl_run_state(f.run), sizeof za);
    long calls = 0; /* the same run to that row, with a callback: the same bits */
    hl_run_set_progress(f.run, never_fn, &calls);
    st = hl_run_adaptive(f.run, f.z0, 1e-12, 0.5, 20, 1, NULL, NULL, &sb, &err);
    CHECK(st == HL_OK && sb.steps == 40);
    CHECK(memcmp(za, hl_run_state(f.run), sizeof za) == 0);
    CHECK(sa.max_dH == sb.max_dH);
    /* rows far apart (4 rows of 500 time units, ~10^4 Taylor steps each):
     * the callback is still called every few thousand steps, and the run
     * agrees with the one without a callback to the tolerance */
    calls = 0;
    st = hl_run_adaptive(f.run, f.z0, 1e-14, 500, 2000, 1, NULL, NULL, &sb, &err);
    memcpy(za, hl_run_state(f.run), sizeof za);
    CHECK_MSG(st == HL_OK && calls >= sb.ref_steps / 4096 && calls > 4, "%ld calls, %ld steps",
              calls, sb.ref_steps);
    hl_run_set_progress(f.run, NULL, NULL);
    st = hl_run_adaptive(f.run, f.z0, 1e-14, 500, 2000, 1, NULL, NULL, &sc, &err);
    memcpy(zc, hl_run_state(f.run), sizeof zc);
    CHECK(st == HL_OK && sc.steps == 4);
    CHECK_MSG(fabs(za[0] - zc[0]) < 1e-9 && fabs(za[1] - zc[1]) < 1e-9, "%g %g",
              za[0] - zc[0], za[1] - zc[1]);
    /* Arb */
    arb_ptr z0 = _arb_vec_init(2);
    hl_run_init_values_arb(z0, f.sys, "q=1.3,p=0", hl_run_arb_prec(30), &err);
    sp = (stopper){7, 0, 0};
    hl_run_set_progress(f.run, stop_fn, &sp);
    st = hl_run_adaptive_arb(f.run, z0, 30, "100", 200, 1, NULL, NULL, &sa, &err);
    CHECK(st == HL_ESTOP && sa.steps == 7 && fabs(sa.t - 3.5) < 1e-15);
    _arb_vec_clear(z0, 2);
    fixture_clear(&f);
}

/* Kepler at the origin: refused before any row, as outside H's domain. */
static void outside_domain(void)
{
    fixture f;
    if (!fixture_new(&f, KEPLER, "rk4", "x=0,y=0,px=0,py=1"))
        return;
    rows a = {0, -1, {0}};
    hl_run_stats s;
    hl_error err;
    CHECK(hl_run_check_start(f.run, f.z0, &err) == HL_EDOM);
    CHECK(strstr(err.msg, "(x = 0, y = 0, px = 0, py = 1) is outside H's domain") != NULL);
    CHECK(hl_run_fixed(f.run, f.z0, 0.1, 1, 1, row_fn, &a, &s, &err) == HL_EDOM);
    CHECK(a.n == 0 && strstr(err.msg, "outside H's domain") != NULL);
    double z1[4] = {1, 0, 0, 1};
    CHECK(hl_run_check_start(f.run, z1, &err) == HL_OK);
    fixture_clear(&f);
}

/* init values: a number that underflows in double is refused; 0 and a
 * value whose ball holds 0 are not */
static void underflow(void)
{
    fixture f;
    if (!fixture_new(&f, OSC, "rk4", "x=1,p=0"))
        return;
    double z[2];
    hl_error err;
    CHECK(hl_run_init_values(z, f.sys, "x=1e-400,p=0", &err) == HL_EDOM);
    CHECK(strstr(err.msg, "underflows") != NULL && err.pos == 2 && err.len == 6);
    CHECK(hl_run_init_values(z, f.sys, "x=1,p=2^(-1100)", &err) == HL_EDOM);
    CHECK(hl_run_init_values(z, f.sys, "x=1e-300,p=sin(pi)", &err) == HL_OK);
    CHECK(z[0] == 1e-300 && fabs(z[1]) < 1e-15);
    CHECK(hl_run_init_values(z, f.sys, "x=0,p=1-1", &err) == HL_OK && z[0] == 0 && z[1] == 0);
    fixture_clear(&f);
}

static int lie_stop(double done, double total, void *arg)
{
    (void)total;
    ++*(int *)arg;
    return done >= 3;
}

static void lie_stopped(void)
{
    hl_system_spec spec = {PENDULUM, NULL, NULL, NULL, NULL};
    hl_system *sys;
    hl_error err;
    if (hl_system_new(&sys, &spec, &err) != HL_OK)
        return;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg *a = hl_alg_vec_new(11, ctx), *b = hl_alg_vec_new(4, ctx), q;
    hl_alg_init(&q, ctx);
    hl_alg_gen(&q, hl_system_var_q(sys, 0), ctx);
    int calls = 0;
    CHECK(hl_lie_terms_watched(a, &q, 10, sys, lie_stop, &calls, &err) == HL_ESTOP);
    CHECK(calls == 3 && strstr(err.msg, "stopped at order 3 of 10") != NULL);
    CHECK(hl_lie_terms(b, &q, 3, sys, &err) == HL_OK);
    for (int k = 0; k <= 3; k++)
        CHECK(hl_alg_equal(&a[k], &b[k], ctx));
    hl_alg_clear(&q, ctx);
    hl_alg_vec_free(a, 11, ctx);
    hl_alg_vec_free(b, 4, ctx);
    hl_system_free(sys);
}

int main(void)
{
    stopped_fixed("rk4", 1, 1, 0);      /* against the reference */
    stopped_fixed("rk4", 0, 1, 0);      /* the stepper alone */
    stopped_fixed("rk4", 0, 100000, 1); /* the compiled loop, rows sparse */
    stopped_fixed("implicit-midpoint", 0, 7, 0);
    stopped_adaptive();
    outside_domain();
    underflow();
    lie_stopped();
    return HL_TEST_END();
}
