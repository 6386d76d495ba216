/* Events on the Taylor integrator and on the cubic Hermite interpolant,
 * against closed forms:
 *   oscillator q = cos t: q = 0 upwards at 3 pi/2 + 2 pi k, downwards at
 *     pi/2 + 2 pi k, both: every pi/2 + pi k; the start on the surface
 *     is not a crossing;
 *   pendulum from (q0, 0): q = 0 at T/4 + k T/2, T = 4 K(sin(q0/2)) with
 *     K by the arithmetic-geometric mean (independent of the integrator);
 *   a non-zero return stops hl_flow_evolve at the crossing;
 *   outputs and crossings come in the order of time;
 *   Hermite: crossings between exact states of the oscillator converge
 *     at order >= 4 in dt;
 *   close pairs: q = sin t crosses q = 1 - eps at pi/2 + 2 pi k -+ acos(1 - eps),
 *     two crossings about 2 sqrt(2 eps) apart, far inside one Taylor step
 *     (~0.8): none missed, each time right to the conditioning of the
 *     root (|dt| sin(acos(1 - eps)) < 1e-13). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "hamlie/event.h"
#include "hamlie/flow.h"
#include "hl_test.h"

static hl_pool *P;

static hl_tape *make_tape(const hl_expr *const *f, int nout)
{
    const char *names[] = {"q", "p"};
    hl_tape *t = NULL;
    hl_error err;
    int st = hl_tape_new(&t, f, nout, names, 2, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    return t;
}

static hl_tape *field(int pendulum)
{
    const hl_expr *q = hl_sym(P, "q");
    const hl_expr *f[] = {hl_sym(P, "p"), hl_neg(P, pendulum ? hl_call(P, HL_SIN, q) : q)};
    return make_tape(f, 2);
}

static hl_tape *surface_q(void)
{
    const hl_expr *g[] = {hl_sym(P, "q")};
    return make_tape(g, 1);
}

typedef struct seen {
    double t[4096];
    double z[4096][2];
    int n, stop_at;   /* stop_at > 0: stop at that crossing */
    char order[8192]; /* 'o' an output, 'x' a crossing, in the order called */
    int norder;
} seen;

static int on_cross(double t, const double *z, void *arg)
{
    seen *s = arg;
    if (s->n < 4096) {
        s->t[s->n] = t;
        s->z[s->n][0] = z[0], s->z[s->n][1] = z[1];
    }
    s->n++;
    if (s->norder < 8191)
        s->order[s->norder++] = 'x';
    return s->stop_at > 0 && s->n == s->stop_at ? 7 : 0;
}

static int on_output(double t, const double *z, void *arg)
{
    (void)t, (void)z;
    seen *s = arg;
    if (s->norder < 8191)
        s->order[s->norder++] = 'o';
    return 0;
}

/* Crossings of q = 0 in the direction dir for the oscillator to t1:
 * the k-th at t = first + k * spacing. */
static void oscillator_dir(hl_event_dir dir, double first, double spacing)
{
    hl_tape *f = field(0), *g = surface_q();
    hl_flow *fl = NULL;
    hl_event *ev = NULL;
    hl_error err;
    static seen s;
    memset(&s, 0, sizeof s);
    CHECK(hl_flow_new(&fl, f, 1e-15, 1e-15, &err) == HL_OK);
    CHECK(hl_event_new(&ev, g, dir, &err) == HL_OK);
    CHECK(hl_flow_set_event(fl, ev, on_cross, &s, &err) == HL_OK);
    /* starting on the surface: (0, -1) is q = -sin t, not recorded at t = 0 */
    double t = 0, z[2] = {0, -1}, t1 = 200;
    CHECK(hl_flow_evolve(fl, &t, t1, z, &err) == HL_OK);
    /* q = -sin t: the crossings are those of cos shifted by pi/2 */
    first -= M_PI / 2;
    while (first <= 0)
        first += spacing;
    int want = (int)floor((t1 - first) / spacing) + 1;
    CHECK_MSG(s.n == want, "direction %d: %d crossings, want %d", (int)dir, s.n, want);
    double worst = 0;
    for (int k = 0; k < s.n && k < want; k++) {
        double tk = first + k * spacing;
        worst = fmax(worst, fabs(s.t[k] - tk));
        worst = fmax(worst, fabs(s.z[k][0])); /* on the surface */
        worst = fmax(worst, fabs(fabs(s.z[k][1]) - 1));
        if (dir != HL_EVENT_BOTH)
            CHECK_MSG(-s.z[k][1] * dir < 0 || s.z[k][1] == 0, "crossing %d has p = %g", k,
                      s.z[k][1]);
    }
    CHECK_MSG(worst < 1e-12, "direction %d: worst error %.3g", (int)dir, worst);
    printf("oscillator, direction %+d: %d crossings to t = %g, max error %.3g\n", (int)dir, s.n, t1,
           worst);
    hl_event_free(ev);
    hl_flow_free(fl);
    hl_tape_free(f), hl_tape_free(g);
}

/* K(sin(q0/2)) = pi / (2 agm(1, cos(q0/2))) */
static double agm_K(double q0)
{
    double a = 1, b = cos(q0 / 2);
    for (int i = 0; i < 40; i++) {
        double an = (a + b) / 2;
        b = sqrt(a * b);
        a = an;
    }
    return M_PI / (2 * a);
}

/* q0 near pi: the period is sensitive to the energy (dT/dE ~ 1/(2 - E)),
 * so the integrator's drift in H moves later crossings; periods bounds the
 * run. */
static void pendulum(double q0, int periods)
{
    hl_tape *f = field(1), *g = surface_q();
    hl_flow *fl = NULL;
    hl_event *ev = NULL;
    hl_error err;
    static seen s;
    memset(&s, 0, sizeof s);
    CHECK(hl_flow_new(&fl, f, 1e-15, 1e-15, &err) == HL_OK);
    CHECK(hl_event_new(&ev, g, HL_EVENT_BOTH, &err) == HL_OK);
    CHECK(hl_flow_set_event(fl, ev, on_cross, &s, &err) == HL_OK);
    double t = 0, z[2] = {q0, 0}, T = 4 * agm_K(q0);
    CHECK(hl_flow_evolve(fl, &t, periods * T, z, &err) == HL_OK);
    CHECK_MSG(s.n == 2 * periods, "pendulum q0 = %g: %d crossings in %d periods", q0, s.n, periods);
    double worst = 0;
    for (int k = 0; k < s.n && k < 4096; k++)
        worst = fmax(worst, fabs(s.t[k] - (T / 4 + k * T / 2)));
    CHECK_MSG(worst < 1e-12, "pendulum q0 = %g: worst %.3g", q0, worst);
    printf("pendulum q0 = %g: %d crossings to t = %d T = %g, max |t_k - (T/4 + k T/2)| %.3g\n", q0,
           s.n, periods, periods * T, worst);
    hl_event_free(ev);
    hl_flow_free(fl);
    hl_tape_free(f), hl_tape_free(g);
}

/* A non-zero return stops at the crossing; outputs interleave in time. */
static void stop_and_order(void)
{
    hl_tape *f = field(0), *g = surface_q();
    hl_flow *fl = NULL;
    hl_event *ev = NULL;
    hl_error err;
    static seen s;
    memset(&s, 0, sizeof s);
    s.stop_at = 3;
    CHECK(hl_flow_new(&fl, f, 1e-15, 1e-15, &err) == HL_OK);
    CHECK(hl_event_new(&ev, g, HL_EVENT_UP, &err) == HL_OK);
    CHECK(hl_flow_set_event(fl, ev, on_cross, &s, &err) == HL_OK);
    double t = 0, z[2] = {1, 0};
    CHECK(hl_flow_evolve(fl, &t, 100, z, &err) == 7);
    double want = 1.5 * M_PI + 4 * M_PI;
    CHECK_MSG(fabs(t - want) < 1e-13 && fabs(z[0]) < 1e-13 && fabs(z[1] - 1) < 1e-13,
              "stopped at t = %.17g (want %.17g), z = (%g, %g)", t, want, z[0], z[1]);
    /* outputs every 1 from 0.5: crossings at 4.71, 10.99, 17.28 between */
    memset(&s, 0, sizeof s);
    CHECK(hl_flow_set_event(fl, ev, on_cross, &s, &err) == HL_OK);
    double ts[20], z0[2] = {1, 0};
    for (int i = 0; i < 20; i++)
        ts[i] = 0.5 + i;
    CHECK(hl_flow_run(fl, 0, z0, ts, 20, on_output, &s, &err) == HL_OK);
    s.order[s.norder] = '\0';
    CHECK_STR(s.order, "oooooxooooooxooooooxooo");
    /* a surface of the wrong dimension */
    const char *names3[] = {"q", "p", "r"};
    const hl_expr *g3[] = {hl_sym(P, "r")};
    hl_tape *t3 = NULL;
    hl_event *e3 = NULL;
    CHECK(hl_tape_new(&t3, g3, 1, names3, 3, &err) == HL_OK);
    CHECK(hl_event_new(&e3, t3, HL_EVENT_UP, &err) == HL_OK);
    CHECK(hl_flow_set_event(fl, e3, on_cross, &s, &err) == HL_EINVAL);
    hl_event_free(e3);
    CHECK(hl_event_new(&e3, f, HL_EVENT_UP, &err) == HL_EINVAL); /* two outputs */
    CHECK(e3 == NULL);
    hl_tape_free(t3);
    hl_event_free(ev);
    hl_flow_free(fl);
    hl_tape_free(f), hl_tape_free(g);
}

/* The Hermite interpolant between exact states of the oscillator: the
 * crossing of q = 0 near t = pi/2 from steps of dt straddling it; the error
 * falls at least like dt^4. */
static double hermite_error(double dt)
{
    hl_tape *g = surface_q();
    hl_event *ev = NULL;
    hl_error err;
    CHECK(hl_event_new(&ev, g, HL_EVENT_DOWN, &err) == HL_OK);
    double t0 = floor(M_PI / 2 / dt - 0.3) * dt; /* the crossing off-centre in the step */
    double z0[2] = {cos(t0), -sin(t0)}, f0[2] = {z0[1], -z0[0]};
    double t1 = t0 + dt, z1[2] = {cos(t1), -sin(t1)}, f1[2] = {z1[1], -z1[0]};
    double tau = NAN, z[2];
    int hit = hl_event_hermite(ev, z0, f0, z1, f1, dt, 0, hl_event_value(ev, z0), &tau, z);
    CHECK(hit == 1);
    hl_event_free(ev);
    hl_tape_free(g);
    return fabs(t0 + tau - M_PI / 2);
}

static void hermite(void)
{
    double e1 = hermite_error(0.2), e2 = hermite_error(0.1), e3 = hermite_error(0.05);
    double o1 = log2(e1 / e2), o2 = log2(e2 / e3);
    printf("hermite: errors %.3g %.3g %.3g at dt = 0.2, 0.1, 0.05: orders %.2f %.2f\n", e1, e2, e3,
           o1, o2);
    CHECK_MSG(o1 > 3.7 && o2 > 3.7, "Hermite crossing orders %.2f %.2f", o1, o2);
    CHECK(e3 < 1e-5);
}

/* q = a with a = 1 - eps near q = sin t's maximum, in the direction dir. */
static void close_pair(double eps, hl_event_dir dir)
{
    hl_tape *f = field(0);
    hl_error err;
    char text[64];
    snprintf(text, sizeof text, "q - (1 - %.17g)", eps);
    const hl_expr *g[1];
    CHECK(hl_parse(&g[0], P, text, &err) == HL_OK);
    hl_tape *gt = make_tape(g, 1);
    hl_flow *fl = NULL;
    hl_event *ev = NULL;
    static seen s;
    memset(&s, 0, sizeof s);
    CHECK(hl_flow_new(&fl, f, 1e-13, 1e-13, &err) == HL_OK);
    CHECK(hl_event_new(&ev, gt, dir, &err) == HL_OK);
    CHECK(hl_flow_set_event(fl, ev, on_cross, &s, &err) == HL_OK);
    double t = 0, z[2] = {0, 1}, t1 = 60, a = 1 - eps, d = acos(a), slope = sqrt(1 - a * a);
    CHECK(hl_flow_evolve(fl, &t, t1, z, &err) == HL_OK);
    double want[64];
    int n = 0;
    for (int k = 0; k < 10; k++)
        for (int side = -1; side <= 1; side += 2) {
            double tk = M_PI / 2 + 2 * M_PI * k + side * d;
            if (tk < t1 && (dir == HL_EVENT_BOTH || side == -dir))
                want[n++] = tk;
        }
    CHECK_MSG(s.n == n, "eps %g, direction %d: %d crossings, want %d", eps, (int)dir, s.n, n);
    double worst = 0;
    for (int k = 0; k < s.n && k < n; k++)
        worst = fmax(worst, fabs(s.t[k] - want[k]) * slope);
    CHECK_MSG(worst < 1e-13, "eps %g: worst |dt| slope %.3g", eps, worst);
    printf("close pair eps = %g (%.3g apart), direction %+d: %d crossings, max |dt| slope %.3g\n",
           eps, 2 * d, (int)dir, s.n, worst);
    hl_event_free(ev);
    hl_flow_free(fl);
    hl_tape_free(f), hl_tape_free(gt);
}

int main(void)
{
    P = hl_pool_new();
    oscillator_dir(HL_EVENT_UP, 1.5 * M_PI, 2 * M_PI);
    oscillator_dir(HL_EVENT_DOWN, 0.5 * M_PI, 2 * M_PI);
    oscillator_dir(HL_EVENT_BOTH, 0.5 * M_PI, M_PI);
    pendulum(1.3, 100);
    pendulum(2.5, 20);
    stop_and_order();
    hermite();
    for (int dir = -1; dir <= 1; dir++)
        for (double eps = 1e-4; eps > 1e-15; eps *= 1e-4)
            close_pair(eps, (hl_event_dir)dir);
    hl_pool_free(P);
    return HL_TEST_END();
}
