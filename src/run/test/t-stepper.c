/* hl_run_new_stepper: a caller's stepper through the same runner.
 *  - the oscillator's exact rotation written here: sigma at round-off over
 *    t = 20 (the reference is the Taylor integrator), H kept to 1e-13;
 *  - explicit Euler written here gives the rows of the catalog's "euler"
 *    (to 1e-15) and its observed order is 1;
 *  - a stepper that fails at step 5, or returns NaN at step 3: the run
 *    stops there, names the step, and the state is the last good one. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hamlie/run.h"
#include "hl_test.h"

#define OSC "(p^2+x^2)/2"

typedef struct osc_arg {
    int calls;
    int fail_at, nan_at;
} osc_arg;

static hl_status rotation(double *z, double dt, void *arg, hl_error *err)
{
    (void)arg, (void)err;
    double x = z[0], p = z[1], c = cos(dt), s = sin(dt);
    z[0] = x * c + p * s;
    z[1] = p * c - x * s;
    return 0;
}

static hl_status euler(double *z, double dt, void *arg, hl_error *err)
{
    osc_arg *a = arg;
    a->calls++;
    if (a->calls == a->fail_at)
        return hl_error_set(err, HL_ENOCONV, NULL, -1, 0, "did not converge (on purpose)");
    double x = z[0], p = z[1];
    z[0] = x + dt * p;
    z[1] = a->calls == a->nan_at ? NAN : p - dt * x;
    return 0;
}

typedef struct rows {
    long n;
    double z[201][2];
} rows;

static int keep(const hl_run_row *row, void *arg)
{
    rows *r = arg;
    if (r->n < 201) {
        r->z[r->n][0] = row->z[0];
        r->z[r->n][1] = row->z[1];
    }
    r->n++;
    return 0;
}

static hl_system *oscillator(void)
{
    hl_system *sys;
    hl_error err;
    hl_system_spec spec = {OSC, NULL, NULL, NULL, NULL};
    if (hl_system_new(&sys, &spec, &err) != HL_OK)
        exit(2);
    return sys;
}

int main(void)
{
    hl_system *sys = oscillator();
    hl_error err;
    hl_run *run = NULL;
    hl_run_stats s;
    double z0[2] = {1, 0};

    /* exact rotation: the reference agrees to round-off */
    CHECK(hl_run_new_stepper(&run, sys, rotation, NULL, &err) == HL_OK);
    CHECK(hl_run_fixed(run, z0, 0.1, 20, 1, NULL, NULL, &s, &err) == HL_OK);
    CHECK_MSG(s.max_err < 1e-13 && s.max_dH < 1e-13 && s.steps == 200,
              "rotation: max error %.3g, max dH %.3g", s.max_err, s.max_dH);
    hl_run_free(run);

    /* hand Euler = the catalog's */
    osc_arg a = {0, 0, 0};
    rows mine = {0}, cat = {0};
    CHECK(hl_run_new_stepper(&run, sys, euler, &a, &err) == HL_OK);
    CHECK(hl_run_fixed(run, z0, 0.1, 20, 1, keep, &mine, &s, &err) == HL_OK);
    double dts[3] = {0.01, 0.005, 0.0025}, e[3], ord[3];
    CHECK(hl_run_orders(e, NULL, ord, run, z0, dts, 3, 1.0, &err) == HL_OK);
    CHECK_MSG(fabs(ord[1] - 1) < 0.05 && fabs(ord[2] - 1) < 0.05, "Euler orders %.3f %.3f",
              ord[1], ord[2]);
    hl_run_free(run);
    hl_scheme *sch = NULL;
    CHECK(hl_scheme_new(&sch, "euler", 0, sys, &err) == HL_OK);
    CHECK(hl_run_new(&run, sys, sch, &err) == HL_OK);
    CHECK(hl_run_fixed(run, z0, 0.1, 20, 1, keep, &cat, &s, &err) == HL_OK);
    int same = mine.n == 201 && cat.n == 201;
    for (long k = 0; same && k < 201; k++)
        for (int i = 0; i < 2; i++)
            same = same && fabs(mine.z[k][i] - cat.z[k][i]) <= 1e-15 * (1 + fabs(cat.z[k][i]));
    CHECK_MSG(same, "hand Euler differs from the catalog's (%ld / %ld rows)", mine.n, cat.n);
    hl_run_free(run);
    hl_scheme_free(sch);

    /* a failure at step 5: stops after 4 good steps, the state is step 4's */
    osc_arg f = {0, 5, 0};
    double want[2] = {1, 0};
    for (int k = 0; k < 4; k++) {
        double x = want[0], p = want[1];
        want[0] = x + 0.1 * p, want[1] = p - 0.1 * x;
    }
    CHECK(hl_run_new_stepper(&run, sys, euler, &f, &err) == HL_OK);
    int st = hl_run_fixed(run, z0, 0.1, 20, 1, NULL, NULL, &s, &err);
    CHECK_MSG(st == HL_ENOCONV && strstr(err.msg, "step 5") && s.steps == 4 && s.failed,
              "failure: status %d, '%s', steps %ld", st, err.msg, s.steps);
    const double *z = hl_run_state(run);
    CHECK(z[0] == want[0] && z[1] == want[1]);
    hl_run_free(run);

    /* NaN at step 3: a blow-up, the state is step 2's */
    osc_arg g = {0, 0, 3};
    CHECK(hl_run_new_stepper(&run, sys, euler, &g, &err) == HL_OK);
    st = hl_run_fixed(run, z0, 0.1, 20, 1, NULL, NULL, &s, &err);
    CHECK_MSG(st == HL_EDOM && strstr(err.msg, "blow-up") && strstr(err.msg, "step 3") &&
                  s.steps == 2,
              "NaN: status %d, '%s', steps %ld", st, err.msg, s.steps);
    z = hl_run_state(run);
    double x1 = 1, p1 = -0.1; /* after step 1; step 2 by the same operations */
    CHECK(z[0] == x1 + 0.1 * p1 && z[1] == p1 - 0.1 * x1);
    hl_run_free(run);

    CHECK(hl_run_new_stepper(&run, sys, NULL, NULL, &err) == HL_EINVAL && run == NULL);
    hl_system_free(sys);
    return HL_TEST_END();
}
