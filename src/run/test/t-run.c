/* The fixed-step driver against closed forms, and its errors:
 *   Euler on the oscillator from (1, 0), dt = 0.1: x_n + i p_n = (1 - i dt)^n
 *     exactly, hence 2 H_n = (1 + dt^2)^n; sigma against cos t, -sin t;
 *   observers (x/p, 2H - x^2 - p^2) evaluated independently;
 *   --every: which rows are delivered;
 *   the adaptive run on the oscillator against cos/sin;
 *   errors: t unreachable (the message), dt = 0, < 0, inf, a missing or
 *   unknown initial value, a blow-up (Euler on the quartic oscillator:
 *   bounded exact solution), a Newton failure; rows before a failure are
 *   finite and stop before the failing step. */
#include "run_test.h"

/* (1 - i dt)^n = r^n e^{-i n atan dt}, r = sqrt(1 + dt^2): real and imaginary parts */
static void euler_exact(double *x, double *p, double dt, double n)
{
    double rn = pow(1 + dt * dt, n / 2), th = -n * atan(dt);
    *x = rn * cos(th), *p = rn * sin(th);
}

typedef struct euler_check {
    double dt, worst_H, worst_z, worst_sigma, worst_obs;
    long rows;
} euler_check;

static int euler_fn(const hl_run_row *row, void *arg)
{
    euler_check *c = arg;
    double wx, wp;
    euler_exact(&wx, &wp, c->dt, (double)row->k);
    double H = 0.5 * pow(1 + c->dt * c->dt, (double)row->k);
    c->worst_H = fmax(c->worst_H, fabs(row->H - H) / H);
    c->worst_z = fmax(c->worst_z, hypot(row->z[0] - wx, row->z[1] - wp) / hypot(wx, wp));
    double s = pow(row->z[0] - cos(row->t), 2) + pow(row->z[1] + sin(row->t), 2);
    c->worst_sigma = fmax(c->worst_sigma, fabs(row->sigma - s) / fmax(s, 1e-300));
    c->worst_obs = fmax(c->worst_obs, fabs(row->obs[0] - row->z[0] / row->z[1]) /
                                          fmax(1, fabs(row->z[0] / row->z[1])));
    c->worst_obs = fmax(c->worst_obs, fabs(row->obs[1]) / (1 + row->H));
    CHECK(fabs(row->t - row->k * c->dt) == 0);
    c->rows++;
    return 0;
}

static void test_euler(void)
{
    fixture f;
    if (!fixture_new(&f, OSC, "euler", "x=1,p=0"))
        return;
    hl_error err;
    CHECK(hl_run_observe(f.run, "x/p", &err) == HL_OK);
    CHECK(hl_run_observe(f.run, "2*H - x^2 - p^2", &err) == HL_OK);
    CHECK(hl_run_nobservers(f.run) == 2);
    euler_check c = {0.1, 0, 0, 0, 0, 0};
    hl_run_stats s;
    int st = hl_run_fixed(f.run, f.z0, 0.1, 20, 1, euler_fn, &c, &s, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    CHECK(c.rows == 201 && s.steps == 200 && s.rows == 201 && !s.failed);
    CHECK_MSG(c.worst_H < 1e-12, "2H_n vs (1+dt^2)^n: %.3g", c.worst_H);
    CHECK_MSG(c.worst_z < 1e-12, "z_n vs (1 - i dt)^n: %.3g", c.worst_z);
    CHECK_MSG(c.worst_sigma < 1e-9, "sigma vs cos/sin: %.3g", c.worst_sigma);
    CHECK_MSG(c.worst_obs < 1e-12, "observers: %.3g", c.worst_obs);
    double Hn = 0.5 * pow(1.01, 200);
    CHECK(fabs(s.max_dH - (Hn - 0.5)) < 1e-12 * Hn);
    CHECK(fabs(s.t - 20) == 0);
    const double *z = hl_run_state(f.run);
    double wx, wp;
    euler_exact(&wx, &wp, 0.1, 200);
    CHECK(hypot(z[0] - wx, z[1] - wp) < 1e-12 * hypot(wx, wp));
    CHECK(fabs(s.err_final - sqrt(pow(z[0] - cos(20.0), 2) + pow(z[1] + sin(20.0), 2))) <
          1e-12);

    /* every 7th row, and the last */
    c = (euler_check){0.1, 0, 0, 0, 0, 0};
    st = hl_run_fixed(f.run, f.z0, 0.1, 20, 7, euler_fn, &c, &s, &err);
    CHECK(st == HL_OK && c.rows == 30 && s.rows == 30);
    fixture_clear(&f);
}

static int adaptive_fn(const hl_run_row *row, void *arg)
{
    double *worst = arg;
    *worst = fmax(*worst, fmax(fabs(row->z[0] - cos(row->t)), fabs(row->z[1] + sin(row->t))));
    CHECK(isnan(row->sigma));
    return 0;
}

static void test_adaptive(void)
{
    fixture f;
    if (!fixture_new(&f, OSC, NULL, "x=1,p=0"))
        return;
    hl_error err;
    double worst = 0;
    hl_run_stats s;
    int st = hl_run_adaptive(f.run, f.z0, 1e-15, 0.5, 1000, 1, adaptive_fn, &worst, &s, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    CHECK(s.rows == 2001);
    CHECK_MSG(worst < 1e-12, "adaptive vs cos/sin: %.3g", worst);
    CHECK(s.max_dH < 1e-13);
    CHECK(hl_run_fixed(f.run, f.z0, 0.1, 1, 1, NULL, NULL, NULL, &err) == HL_EINVAL);
    fixture_clear(&f);
}

typedef struct fail_check {
    long rows, last;
    int finite;
} fail_check;

static int fail_fn(const hl_run_row *row, void *arg)
{
    fail_check *c = arg;
    c->rows++;
    c->last = row->k;
    if (!isfinite(row->H) || !isfinite(row->z[0]) || !isfinite(row->z[1]))
        c->finite = 0;
    return 0;
}

static void test_errors(void)
{
    fixture f;
    hl_error err;
    long n;
    CHECK(hl_run_nsteps(&n, 0.3, 20, &err) == HL_EINVAL);
    CHECK_STR(err.msg, "t = 20 is not reachable with dt = 0.3: 66.67 steps");
    CHECK(hl_run_nsteps(&n, 0, 20, &err) == HL_EINVAL);
    CHECK(strstr(err.msg, "positive") != NULL);
    CHECK(hl_run_nsteps(&n, -0.1, 20, &err) == HL_EINVAL);
    CHECK(hl_run_nsteps(&n, INFINITY, 20, &err) == HL_EINVAL);
    CHECK(hl_run_nsteps(&n, NAN, 20, &err) == HL_EINVAL);
    CHECK(hl_run_nsteps(&n, 0.01, 1e4, &err) == HL_OK && n == 1000000);
    CHECK(hl_run_nsteps(&n, 0.1, 0.3, &err) == HL_OK && n == 3);

    if (!fixture_new(&f, OSC, "euler", "x=1,p=0"))
        return;
    double z[2];
    CHECK(hl_run_init_values(z, f.sys, "x=1", &err) == HL_EINVAL);
    CHECK_STR(err.msg, "no initial value for 'p'");
    CHECK(hl_run_init_values(z, f.sys, "x=1,p=0,y=2", &err) == HL_EINVAL);
    CHECK(err.src != NULL && err.pos == 8);
    CHECK(hl_run_init_values(z, f.sys, "x=1,x=2,p=0", &err) == HL_EINVAL);
    CHECK(hl_run_init_values(z, f.sys, "x=1,p=(", &err) == HL_EPARSE);
    CHECK(err.pos >= 6);
    CHECK(hl_run_init_values(z, f.sys, "x=pi/2, p = -sqrt(4)", &err) == HL_OK);
    CHECK(z[0] == M_PI / 2 && z[1] == -2);
    CHECK(hl_run_init_values(z, f.sys, "x=1.3,p=1.7320508075688772", &err) == HL_OK);
    CHECK(z[0] == 1.3 && z[1] == 1.7320508075688772); /* correctly rounded */
    CHECK(hl_run_observe(f.run, "x/zeta", &err) == HL_EINVAL);
    CHECK(err.pos == 2 && err.len == 4);
    CHECK(hl_run_fixed(f.run, f.z0, 0.3, 20, 1, NULL, NULL, NULL, &err) == HL_EINVAL);
    CHECK(hl_run_fixed(f.run, f.z0, -0.1, 20, 1, NULL, NULL, NULL, &err) == HL_EINVAL);
    fixture_clear(&f);

    /* blow-up: Euler on the quartic oscillator (bounded exact solution) */
    if (!fixture_new(&f, "p^2/2 + q^4/4", "euler", "q=2,p=0"))
        return;
    hl_run_set_reference(f.run, 0, 0);
    fail_check c = {0, -1, 1};
    hl_run_stats s;
    int st = hl_run_fixed(f.run, f.z0, 0.5, 100, 1, fail_fn, &c, &s, &err);
    printf("blow-up: %s\n", err.msg);
    CHECK(st == HL_EDOM && s.failed);
    CHECK(strstr(err.msg, "step") != NULL && strstr(err.msg, "blow-up") != NULL);
    CHECK(c.finite && c.rows > 1 && c.last == s.steps && s.steps < 200);
    /* the same with the reference on */
    hl_run_set_reference(f.run, 1, 0);
    c = (fail_check){0, -1, 1};
    st = hl_run_fixed(f.run, f.z0, 0.5, 100, 1, fail_fn, &c, &s, &err);
    CHECK_MSG(st == HL_EDOM && s.failed && c.finite && c.last == s.steps, "%d %s %ld %ld",
              st, err.msg, c.last, s.steps);
    fixture_clear(&f);

    /* the reference failing: z' = ... with q -> inf in finite time */
    if (!fixture_new(&f, "p^2/2 - q^4/4", "rk4", "q=1,p=1"))
        return;
    st = hl_run_fixed(f.run, f.z0, 0.01, 10, 1, NULL, NULL, &s, &err);
    printf("reference failure: %s (%d)\n", err.msg, st);
    CHECK(st != HL_OK && s.failed);
    fixture_clear(&f);

    /* Newton failure: gauss3, a step far too large (Newton from the Euler
     * prediction fails at the first step) */
    if (!fixture_new(&f, PENDULUM, "gauss3", "q=1.3,p=0"))
        return;
    c = (fail_check){0, -1, 1};
    CHECK(hl_run_fixed(f.run, f.z0, 0.1, 1, 1, NULL, NULL, NULL, &err) == HL_OK);
    st = hl_run_fixed(f.run, f.z0, 50, 1000, 1, fail_fn, &c, &s, &err);
    printf("newton: %s (%d)\n", err.msg, st);
    CHECK(strncmp(err.msg, "step 1 (t = 0,", 14) == 0); /* counted from this run */
    CHECK(st == HL_ENOCONV && strstr(err.msg, "Newton") != NULL);
    CHECK(s.failed && c.finite && c.last == s.steps && s.steps == 0 && c.rows == 1);
    fixture_clear(&f);

    /* a parameter without a value */
    hl_system *sys = NULL;
    hl_system_spec spec = {"p^2/2 + k*q^2/2", NULL, NULL, NULL, NULL};
    hl_run *r = NULL;
    CHECK(hl_system_new(&sys, &spec, &err) == HL_OK);
    CHECK(hl_run_new(&r, sys, NULL, &err) == HL_EINVAL);
    CHECK(strstr(err.msg, "'k'") != NULL);
    hl_system_free(sys);
}

static int stop_fn(const hl_run_row *row, void *arg) { return row->k == 5 ? 42 : 0; }

static void test_stop(void)
{
    fixture f;
    if (!fixture_new(&f, OSC, "rk4", "x=1,p=0"))
        return;
    hl_run_stats s;
    hl_error err;
    CHECK(hl_run_fixed(f.run, f.z0, 0.1, 2, 1, stop_fn, NULL, &s, &err) == 42);
    CHECK(s.steps == 5 && !s.failed);
    fixture_clear(&f);
}

int main(void)
{
    test_euler();
    test_adaptive();
    test_errors();
    test_stop();
    return HL_TEST_END();
}
