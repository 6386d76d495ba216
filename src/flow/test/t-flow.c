/* The Taylor integrator against closed forms, invariants, and its own Arb
 * version at 40 digits:
 *   oscillator (1,0) to t = 1e4 against cos/sin (dense output and evolve),
 *     backwards too;
 *   pendulum q0 = 1.3: energy drift over t = 1e3;
 *   Kepler e = 0.5: double vs Arb (40 digits) at t = 100, and the orbit
 *     closes after one period 2 pi;
 *   observed convergence: the error shrinks with the tolerance;
 *   failures: z' = z^2 from 1 blows up at t = 1, and the error names it. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/flow.h"

static hl_pool *P;

static hl_tape *make_tape(const hl_expr *const *f, const char *const *names, int n)
{
    hl_tape *t = NULL;
    hl_error err;
    int st = hl_tape_new(&t, f, n, names, n, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    return t;
}

static hl_tape *oscillator(void)
{
    const char *names[] = {"q", "p"};
    const hl_expr *f[] = {hl_sym(P, "p"), hl_neg(P, hl_sym(P, "q"))};
    return make_tape(f, names, 2);
}

static hl_tape *pendulum(void)
{
    const char *names[] = {"q", "p"};
    const hl_expr *f[] = {hl_sym(P, "p"), hl_neg(P, hl_call(P, HL_SIN, hl_sym(P, "q")))};
    return make_tape(f, names, 2);
}

static hl_tape *kepler(void)
{
    const char *names[] = {"x", "y", "px", "py"};
    const hl_expr *x = hl_sym(P, "x"), *y = hl_sym(P, "y"), *two = hl_num_si(P, 2);
    const hl_expr *r2 = hl_add(P, hl_pow(P, x, two), hl_pow(P, y, two));
    const hl_expr *r3i = hl_pow(P, r2, hl_num_frac(P, -3, 2));
    const hl_expr *f[] = {hl_sym(P, "px"), hl_sym(P, "py"), hl_neg(P, hl_mul(P, x, r3i)),
                          hl_neg(P, hl_mul(P, y, r3i))};
    return make_tape(f, names, 4);
}

static void test_oscillator(void)
{
    hl_tape *t = oscillator();
    hl_flow *fl = NULL;
    hl_error err;
    CHECK(hl_flow_new(&fl, t, 1e-15, 1e-15, &err) == HL_OK);
    double ts[10], out[20], z0[2] = {1, 0};
    for (int i = 0; i < 10; i++)
        ts[i] = 1000.0 * (i + 1);
    CHECK(hl_flow_eval_at(fl, 0, z0, ts, 10, out, &err) == HL_OK);
    double worst = 0;
    for (int i = 0; i < 10; i++)
        worst = fmax(worst, fmax(fabs(out[2 * i] - cos(ts[i])), fabs(out[2 * i + 1] + sin(ts[i]))));
    CHECK_MSG(worst < 1e-12, "oscillator dense output error %.3g", worst);
    printf("oscillator to 1e4: %ld steps, order %d, max error %.3g\n", hl_flow_nsteps(fl),
           hl_flow_order(fl), worst);

    double tt = 0, z[2] = {1, 0};
    CHECK(hl_flow_evolve(fl, &tt, 1e4, z, &err) == HL_OK);
    CHECK(tt == 1e4);
    CHECK_MSG(fabs(z[0] - cos(1e4)) < 1e-12 && fabs(z[1] + sin(1e4)) < 1e-12,
              "evolve error %.3g %.3g", z[0] - cos(1e4), z[1] + sin(1e4));

    /* backwards, and dense output in between step ends */
    double tb[3] = {-0.1, -3.3, -10}, ob[6];
    CHECK(hl_flow_eval_at(fl, 0, z0, tb, 3, ob, &err) == HL_OK);
    for (int i = 0; i < 3; i++)
        CHECK_MSG(fabs(ob[2 * i] - cos(tb[i])) < 1e-14 && fabs(ob[2 * i + 1] + sin(tb[i])) < 1e-14,
                  "backwards at %g", tb[i]);
    /* non-monotone output times are refused */
    double bad[2] = {1, 0.5};
    CHECK(hl_flow_eval_at(fl, 0, z0, bad, 2, ob, &err) == HL_EINVAL);
    hl_flow_free(fl);
    hl_flow_free(NULL);
    CHECK(hl_flow_new(&fl, t, 0, 1e-9, &err) == HL_EINVAL && fl == NULL);
    hl_tape_free(t);
}

typedef struct energy {
    double H0, worst;
    int calls;
} energy;

static int pendulum_energy(double t, const double *z, void *arg)
{
    energy *e = arg;
    double H = z[1] * z[1] / 2 - cos(z[0]);
    e->worst = fmax(e->worst, fabs(H - e->H0));
    e->calls++;
    return 0;
}

static void test_pendulum(void)
{
    hl_tape *t = pendulum();
    hl_flow *fl = NULL;
    hl_error err;
    CHECK(hl_flow_new(&fl, t, 1e-15, 1e-15, &err) == HL_OK);
    double ts[1000], z0[2] = {1.3, 0};
    for (int i = 0; i < 1000; i++)
        ts[i] = i + 1.0;
    energy e = {-cos(1.3), 0, 0};
    CHECK(hl_flow_run(fl, 0, z0, ts, 1000, pendulum_energy, &e, &err) == HL_OK);
    CHECK(e.calls == 1000);
    CHECK_MSG(e.worst < 1e-13, "pendulum energy drift %.3g", e.worst);
    printf("pendulum to 1e3: %ld steps, energy drift %.3g\n", hl_flow_nsteps(fl), e.worst);
    hl_flow_free(fl);
    hl_tape_free(t);
}

static void kepler_double(double *z, double T, double tol, long *steps)
{
    hl_tape *t = kepler();
    hl_flow *fl = NULL;
    hl_error err;
    CHECK(hl_flow_new(&fl, t, tol, tol, &err) == HL_OK);
    z[0] = 0.5;
    z[1] = 0;
    z[2] = 0;
    z[3] = sqrt(3);
    double tt = 0;
    CHECK_MSG(hl_flow_evolve(fl, &tt, T, z, &err) == HL_OK, "%s", err.msg);
    if (steps)
        *steps = hl_flow_nsteps(fl);
    hl_flow_free(fl);
    hl_tape_free(t);
}

/* Kepler in Arb from the same (double) start; returns midpoints as doubles */
static void kepler_arb(double *out, double T, double digits, int one_period)
{
    hl_tape *t = kepler();
    hl_flow_arb *fl = NULL;
    hl_error err;
    CHECK(hl_flow_arb_new(&fl, t, digits, &err) == HL_OK);
    arb_ptr z = _arb_vec_init(4);
    arb_t t0, t1;
    arb_init(t0);
    arb_init(t1);
    arb_set_d(z, 0.5);
    arb_set_d(z + 3, sqrt(3));
    arb_set_d(t1, T);
    if (one_period) {
        /* the period of the double start: E = py^2/2 - 1/x, a = -1/(2E), T = 2 pi a^(3/2) */
        slong prec = hl_flow_arb_prec(fl);
        arb_t E, a;
        arb_init(E);
        arb_init(a);
        arb_sqr(E, z + 3, prec);
        arb_mul_2exp_si(E, E, -1);
        arb_sub_si(E, E, 2, prec);
        arb_mul_si(a, E, -2, prec);
        arb_inv(a, a, prec);
        arb_sqrt(t1, a, prec);
        arb_mul(t1, t1, a, prec);
        arb_const_pi(a, prec);
        arb_mul(t1, t1, a, prec);
        arb_mul_2exp_si(t1, t1, 1);
        arb_clear(E);
        arb_clear(a);
    }
    CHECK_MSG(hl_flow_arb_evolve(fl, t0, t1, z, &err) == HL_OK, "%s", err.msg);
    CHECK(arb_equal(t0, t1));
    for (int i = 0; i < 4; i++)
        out[i] = arf_get_d(arb_midref(z + i), ARF_RND_NEAR);
    printf("kepler arb %g digits to %g: order %d, %ld steps\n", digits, T, hl_flow_arb_order(fl),
           hl_flow_arb_nsteps(fl));
    _arb_vec_clear(z, 4);
    arb_clear(t0);
    arb_clear(t1);
    hl_flow_arb_free(fl);
    hl_tape_free(t);
}

static double maxdiff(const double *a, const double *b, int n)
{
    double m = 0;
    for (int i = 0; i < n; i++)
        m = fmax(m, fabs(a[i] - b[i]));
    return m;
}

static void test_kepler(void)
{
    double zd[4], za[4];
    long steps;
    kepler_double(zd, 100, 1e-15, &steps);
    kepler_arb(za, 100, 40, 0);
    double d = maxdiff(zd, za, 4);
    CHECK_MSG(d < 1e-12, "kepler double vs arb at t = 100: %.3g", d);
    printf("kepler double to 100: %ld steps, differs from 40-digit arb by %.3g\n", steps, d);

    /* a = 1 (E = -1/2), so the period is 2 pi: the orbit closes */
    kepler_double(zd, 2 * M_PI, 1e-15, NULL);
    double start[4] = {0.5, 0, 0, sqrt(3)};
    d = maxdiff(zd, start, 4);
    CHECK_MSG(d < 1e-12, "kepler after one period: off by %.3g", d);
    kepler_arb(za, 2 * M_PI, 40, 1);
    d = maxdiff(za, start, 4);
    CHECK_MSG(d < 1e-30, "kepler arb after one period: off by %.3g", d);

    /* observed convergence against the 40-digit run at t = 10 */
    double ref[4], prev = INFINITY;
    kepler_arb(ref, 10, 40, 0);
    for (double tol = 1e-6; tol > 1e-14; tol *= 1e-3) {
        kepler_double(zd, 10, tol, &steps);
        double e = maxdiff(zd, ref, 4);
        printf("kepler to 10 at tol %g: %ld steps, error %.3g\n", tol, steps, e);
        CHECK_MSG(e < 1e4 * tol && e < prev, "tol %g: error %.3g (previous %.3g)", tol, e, prev);
        prev = e;
    }
}

static void test_blowup(void)
{
    /* z' = z^2, z(0) = 1: z = 1/(1-t) */
    const char *names[] = {"z"};
    const hl_expr *f[] = {hl_pow(P, hl_sym(P, "z"), hl_num_si(P, 2))};
    hl_tape *t = make_tape(f, names, 1);
    hl_flow *fl = NULL;
    hl_error err;
    CHECK(hl_flow_new(&fl, t, 1e-12, 1e-12, &err) == HL_OK);
    double tt = 0, z = 1;
    int st = hl_flow_evolve(fl, &tt, 2, &z, &err);
    CHECK(st == HL_ENOCONV || st == HL_EDOM);
    /* the computed solution's pole moves with rounding: allow 1e-9 */
    CHECK_MSG(fabs(tt - 1) < 1e-9, "stopped at t = %.17g", tt);
    CHECK_MSG(strstr(err.msg, "at t = 0.99") != NULL || strstr(err.msg, "at t = 1") != NULL,
              "message: %s", err.msg);
    CHECK(z > 1e8);
    /* before the blow-up it is right */
    double z5 = 1, t5 = 0;
    CHECK(hl_flow_evolve(fl, &t5, 0.5, &z5, &err) == HL_OK && fabs(z5 - 2) < 1e-12);
    hl_flow_free(fl);
    hl_tape_free(t);
}

static int stop_at_third(double t, const double *z, void *arg)
{
    return ++*(int *)arg == 3 ? 7 : 0;
}

static void test_callback_stop(void)
{
    hl_tape *t = oscillator();
    hl_flow *fl = NULL;
    hl_error err;
    CHECK(hl_flow_new(&fl, t, 1e-10, 1e-10, &err) == HL_OK);
    double ts[5] = {0, 1, 2, 3, 4}, z0[2] = {1, 0};
    int calls = 0;
    CHECK(hl_flow_run(fl, 0, z0, ts, 5, stop_at_third, &calls, &err) == 7);
    CHECK(calls == 3);
    hl_flow_free(fl);
    hl_tape_free(t);
}

/* z' = 1 (the series stops: one step), z' = z (exp) */
static void test_simple(void)
{
    const char *names[] = {"z"};
    const hl_expr *one[] = {hl_num_si(P, 1)}, *id[] = {hl_sym(P, "z")};
    hl_tape *t = make_tape(one, names, 1);
    hl_flow *fl = NULL;
    hl_error err;
    CHECK(hl_flow_new(&fl, t, 1e-12, 1e-12, &err) == HL_OK);
    double tt = 0, z = 0;
    CHECK(hl_flow_evolve(fl, &tt, 5, &z, &err) == HL_OK && z == 5 && hl_flow_nsteps(fl) == 1);
    hl_flow_free(fl);
    hl_tape_free(t);
    t = make_tape(id, names, 1);
    CHECK(hl_flow_new(&fl, t, 1e-15, 1e-15, &err) == HL_OK);
    tt = 0, z = 1;
    CHECK(hl_flow_evolve(fl, &tt, 10, &z, &err) == HL_OK);
    CHECK_MSG(fabs(z / exp(10) - 1) < 1e-14, "exp(10): relative error %.3g", z / exp(10) - 1);
    hl_flow_free(fl);
    hl_tape_free(t);
}

typedef struct arb_check {
    slong prec;
    double worst;
    int calls;
} arb_check;

/* the oscillator from (1, 0): z = (cos t, -sin t) */
static int osc_arb_fn(const arb_t t, arb_srcptr z, void *arg)
{
    arb_check *c = arg;
    arb_t s, co;
    arb_init(s);
    arb_init(co);
    arb_sin_cos(s, co, t, c->prec);
    arb_sub(co, co, z, c->prec);
    arb_add(s, s, z + 1, c->prec);
    double e = fmax(fabs(arf_get_d(arb_midref(co), ARF_RND_NEAR)),
                    fabs(arf_get_d(arb_midref(s), ARF_RND_NEAR)));
    c->worst = fmax(c->worst, e);
    c->calls++;
    arb_clear(s);
    arb_clear(co);
    return 0;
}

static void test_arb_run(void)
{
    hl_tape *t = oscillator();
    hl_flow_arb *fl = NULL;
    hl_error err;
    CHECK(hl_flow_arb_new(&fl, t, 30, &err) == HL_OK);
    hl_flow_arb *bad = NULL;
    CHECK(hl_flow_arb_new(&bad, t, 0, &err) == HL_EINVAL && bad == NULL);
    arb_ptr ts = _arb_vec_init(4), z0 = _arb_vec_init(2);
    arb_t t0;
    arb_init(t0);
    for (int i = 0; i < 4; i++)
        arb_set_si(ts + i, 7 * i); /* 0, 7, 14, 21 */
    arb_one(z0);
    arb_check c = {hl_flow_arb_prec(fl), 0, 0};
    CHECK(hl_flow_arb_run(fl, t0, z0, ts, 4, osc_arb_fn, &c, &err) == HL_OK);
    CHECK(c.calls == 4);
    CHECK_MSG(c.worst < 1e-28, "arb oscillator (30 digits): error %.3g", c.worst);
    hl_flow_arb_free(fl);

    /* 100 digits: order 117; check the midpoints against sin/cos directly */
    CHECK(hl_flow_arb_new(&fl, t, 100, &err) == HL_OK);
    CHECK(hl_flow_arb_order(fl) == 117);
    arb_ptr z = _arb_vec_init(2);
    arb_t t1, e;
    arb_init(t1);
    arb_init(e);
    arb_one(z);
    arb_zero(t0);
    arb_set_si(t1, 10);
    CHECK(hl_flow_arb_evolve(fl, t0, t1, z, &err) == HL_OK);
    slong prec = hl_flow_arb_prec(fl);
    arb_cos(e, t1, prec);
    arb_sub(e, e, z, prec);
    CHECK_MSG(arf_cmpabs_2exp_si(arb_midref(e), -325) < 0, "cos(10) at 100 digits: %g",
              arf_get_d(arb_midref(e), ARF_RND_NEAR));
    arb_sin(e, t1, prec);
    arb_add(e, e, z + 1, prec);
    CHECK(arf_cmpabs_2exp_si(arb_midref(e), -325) < 0);
    arb_clear(t1);
    arb_clear(e);
    _arb_vec_clear(z, 2);
    _arb_vec_clear(ts, 4);
    _arb_vec_clear(z0, 2);
    arb_clear(t0);
    hl_flow_arb_free(fl);
    hl_flow_arb_free(NULL);
    hl_tape_free(t);
}

/* hl_flow_native_for: a run that foresees more steps than the break-even
 * (hl_tape_compile_breakeven, HL_COMPILE_TAYLOR) compiles its recursion
 * after the probe (and stays on the oscillator's closed form); one that
 * does not, does not.  The run is cut short: the decision needs only the
 * probe. */
static void test_native_for(void)
{
    hl_error err;
    hl_tape *probe = oscillator(); /* can this machine compile a recursion at all? */
    int can = hl_tape_native(probe, 5, &err) == HL_OK;
    hl_tape_free(probe);
    for (int longrun = 0; longrun < 2; longrun++) {
        hl_tape *t = oscillator();
        hl_flow *fl = NULL;
        CHECK(hl_flow_new(&fl, t, 1e-15, 1e-15, &err) == HL_OK);
        hl_flow_native_for(fl, longrun ? 2e6 : 1e5);
        double tt = 0, z[2] = {1, 0};
        CHECK(hl_flow_evolve(fl, &tt, 3000, z, &err) == HL_OK);
        CHECK(hl_flow_nsteps(fl) > 2 * HL_FLOW_NATIVE_PROBE);
        int want = longrun && can;
        CHECK_MSG(hl_flow_native_active(fl) == want, "t_end %g: native %d", longrun ? 2e6 : 1e5,
                  hl_flow_native_active(fl));
        CHECK(fabs(z[0] - cos(3000.0)) < 1e-12 && fabs(z[1] + sin(3000.0)) < 1e-12);
        hl_flow_free(fl);
        hl_tape_free(t);
    }
}

/* The oscillator from (1, 0) to t = 300 (about 300 steps, under half the
 * probe) after hl_flow_native_for(t_end); z: the state there. */
static int short_run(double t_end, double *z)
{
    hl_error err;
    hl_tape *t = oscillator();
    hl_flow *fl = NULL;
    CHECK(hl_flow_new(&fl, t, 1e-15, 1e-15, &err) == HL_OK);
    if (t_end > 0)
        hl_flow_native_for(fl, t_end);
    double tt = 0;
    z[0] = 1, z[1] = 0;
    CHECK(hl_flow_evolve(fl, &tt, 300, z, &err) == HL_OK);
    CHECK(hl_flow_nsteps(fl) > 200 && hl_flow_nsteps(fl) < HL_FLOW_NATIVE_PROBE / 2);
    int native = hl_flow_native_active(fl);
    hl_flow_free(fl);
    hl_tape_free(t);
    return native;
}

/* A recursion kept in the disk cache is loaded after 100 steps, for a run
 * shorter than the probe, when the steps foreseen repay the load
 * (t_end = 2e4: 20 000 steps, too few to compile on a miss); not when
 * they do not (t_end = 400: 300 steps left, the oscillator's load repaid
 * from about 3000), nor when the cache does not hold it.  The native run
 * gives the interpreter's bits. */
static void test_native_kept(void)
{
    char dir[] = "/tmp/hamlie-t-flow-XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    setenv("HAMLIE_CACHE_DIR", dir, 1);
    unsetenv("HAMLIE_CACHE");
    double interp[2], z[2];
    CHECK(short_run(0, interp) == 0);
    CHECK(fabs(interp[0] - cos(300.0)) < 1e-13 && fabs(interp[1] + sin(300.0)) < 1e-13);
    CHECK(short_run(2e4, z) == 0); /* nothing kept yet */
    CHECK(memcmp(z, interp, sizeof z) == 0);
    /* fill the cache: the recursion at the flow's order */
    hl_error err;
    hl_tape *t = oscillator();
    hl_flow *fl = NULL;
    CHECK(hl_flow_new(&fl, t, 1e-15, 1e-15, &err) == HL_OK);
    int can = hl_tape_native(t, hl_flow_order(fl), &err) == HL_OK;
    hl_flow_free(fl);
    hl_tape_free(t);
    CHECK_MSG(short_run(2e4, z) == can, "kept, 2e4 foreseen: native %d", !can);
    CHECK(memcmp(z, interp, sizeof z) == 0);
    CHECK(short_run(400, z) == 0);
    CHECK(memcmp(z, interp, sizeof z) == 0);
    setenv("HAMLIE_CACHE", "off", 1);
    CHECK(short_run(2e4, z) == 0);
    char cmd[64];
    snprintf(cmd, sizeof cmd, "rm -rf %s", dir);
    CHECK(system(cmd) == 0);
}

/* A callback that runs the flow's own tape in Taylor mode at another
 * order: the flow reads the step's coefficients in the tape's registers
 * (hl_tape_taylor_ode_lend), which that call lays out anew; the flow must
 * copy them before it calls back, so that the run's outputs are those of a
 * run whose callback leaves the tape alone, to the bit. */
typedef struct reuse {
    hl_tape *t;
    int calls, use_tape;
    double *out;
} reuse;

static int reuse_tape(double t, const double *z, void *arg)
{
    reuse *r = arg;
    if (r->use_tape) {
        double c[2 * 8] = {0};
        c[0] = z[0] + 1; /* another state, another order: other registers */
        c[8] = z[1] - 1;
        hl_error err;
        CHECK(hl_tape_taylor_ode_d(c, 7, r->t, &err) == HL_OK);
    }
    memcpy(r->out + 2 * r->calls++, z, 2 * sizeof *z);
    return 0;
}

static void test_callback_reuses_tape(void)
{
    hl_tape *t = pendulum();
    double ts[40], z0[2] = {1.3, 0}, out[2][2 * 40];
    for (int i = 0; i < 40; i++)
        ts[i] = 0.77 * (i + 1); /* inside steps */
    for (int pass = 0; pass < 2; pass++) {
        hl_flow *fl = NULL;
        hl_error err;
        CHECK(hl_flow_new(&fl, t, 1e-12, 1e-12, &err) == HL_OK);
        reuse r = {t, 0, pass, out[pass]};
        CHECK(hl_flow_run(fl, 0, z0, ts, 40, reuse_tape, &r, &err) == HL_OK);
        CHECK(r.calls == 40);
        hl_flow_free(fl);
    }
    CHECK_MSG(memcmp(out[0], out[1], sizeof out[0]) == 0, "x at t = %g: %.17g / %.17g", ts[39],
              out[0][78], out[1][78]);
    CHECK_MSG(fabs(out[0][79] * out[0][79] / 2 - cos(out[0][78]) + cos(1.3)) < 1e-12,
              "energy %.17g", out[0][79] * out[0][79] / 2 - cos(out[0][78]));
    hl_tape_free(t);
}

int main(void)
{
    /* the cost model without the disk cache, whose entries (a kept
     * recursion compiles for any run) would change test_native_for's
     * answer; tape/t-jit_cache tests the cache's part */
    setenv("HAMLIE_CACHE", "off", 1);
    P = hl_pool_new();
    test_simple();
    test_arb_run();
    test_oscillator();
    test_pendulum();
    test_kepler();
    test_blowup();
    test_callback_stop();
    test_callback_reuses_tape();
    test_native_for();
    test_native_kept();
    hl_pool_free(P);
    flint_cleanup();
    return HL_TEST_END();
}
