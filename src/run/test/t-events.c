/* Events in runs and surfaces of section:
 *   the adaptive run: q = 0 crossings of the oscillator at closed-form
 *     times, with H; stop after N returns HL_OK with the count;
 *   a fixed-step run of the exact rotation (a caller's stepper): the
 *     Hermite crossings' error falls like dt^4; stormer-verlet's crossings
 *     like dt^2 (the scheme's own error);
 *   surfaces: "x", "x = 0", "0.5 = y" read (var and value), errors with
 *     positions; the Arb run refuses events;
 *   sections of Henon-Heiles at E = 1/8: the solved px gives H = E to
 *     1e-15 and px = sqrt(2 (E - V)); crossings on x = 0 with px > 0 and
 *     H = E to 1e-13; an energy below the minimum is refused; explicit
 *     Euler's section drifts in H, stormer-verlet-kdk's stays within
 *     O(dt^2) (measured: both printed). */
#include "run_test.h"
#include "hamlie/section.h"

#define OSC "(p^2+x^2)/2"
#define HH "(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3"

typedef struct got {
    long n;
    int n2; /* the state's size (0: 4) */
    double t[1024], H[1024], z[1024][4];
} got;

static int keep(const hl_run_crossing *c, void *arg)
{
    got *g = arg;
    if (g->n < 1024) {
        g->t[g->n] = c->t;
        g->H[g->n] = c->H;
        memcpy(g->z[g->n], c->z, (size_t)(g->n2 ? g->n2 : 4) * sizeof *c->z);
    }
    CHECK(c->i == g->n);
    g->n++;
    return 0;
}

static void adaptive_oscillator(void)
{
    fixture f;
    if (!fixture_new(&f, OSC, NULL, "x=1,p=0"))
        return;
    static got g;
    memset(&g, 0, sizeof g);
    g.n2 = 2;
    hl_error err;
    hl_run_stats s;
    /* x = cos t: upwards (p = -sin t > 0) at 3 pi/2 + 2 pi k */
    CHECK(hl_run_event(f.run, "x", HL_EVENT_UP, 0, keep, &g, &err) == HL_OK);
    CHECK(hl_run_event_order(f.run) == 0);
    CHECK(hl_run_adaptive(f.run, f.z0, 1e-15, 1, 100, 1, NULL, NULL, &s, &err) == HL_OK);
    CHECK_MSG(g.n == 16 && s.crossings == 16 && !s.event_stop, "%ld crossings", g.n);
    double worst = 0;
    for (int k = 0; k < g.n && k < 16; k++)
        worst = fmax(worst, fmax(fabs(g.t[k] - (1.5 + 2 * k) * M_PI), fabs(g.H[k] - 0.5)));
    CHECK_MSG(worst < 1e-12, "adaptive oscillator crossings: %.3g", worst);
    /* stop after 3: HL_OK, event_stop, t_crossing */
    memset(&g, 0, sizeof g);
    g.n2 = 2;
    CHECK(hl_run_event(f.run, "x = 0", HL_EVENT_BOTH, 3, keep, &g, &err) == HL_OK);
    CHECK(hl_run_adaptive(f.run, f.z0, 1e-15, 1, 100, 1, NULL, NULL, &s, &err) == HL_OK);
    CHECK(g.n == 3 && s.crossings == 3 && s.event_stop);
    CHECK_MSG(fabs(s.t_crossing - 2.5 * M_PI) < 1e-13, "stopped at %.17g", s.t_crossing);
    fixture_clear(&f);
}

static hl_status rotation(double *z, double dt, void *arg, hl_error *err)
{
    (void)arg, (void)err;
    double x = z[0], p = z[1], c = cos(dt), s = sin(dt);
    z[0] = x * c + p * s;
    z[1] = p * c - x * s;
    return 0;
}

/* max error of the x = 0 crossing times to t = 20 (closed form pi/2 + k pi) */
static double fixed_error(hl_run *run, double dt, long *n)
{
    static got g;
    memset(&g, 0, sizeof g);
    g.n2 = 2;
    hl_error err;
    hl_run_stats s;
    double z0[2] = {1, 0};
    CHECK(hl_run_event(run, "x", HL_EVENT_BOTH, 0, keep, &g, &err) == HL_OK);
    hl_run_set_reference(run, 0, 0);
    CHECK_MSG(hl_run_fixed(run, z0, dt, 20, 1, NULL, NULL, &s, &err) == HL_OK, "%s", err.msg);
    double worst = 0;
    for (int k = 0; k < g.n && k < 1024; k++)
        worst = fmax(worst, fabs(g.t[k] - (0.5 + k) * M_PI));
    *n = g.n;
    return worst;
}

static void fixed_orders(void)
{
    fixture f;
    if (!fixture_new(&f, OSC, "stormer-verlet-kdk", "x=1,p=0"))
        return;
    hl_run *rot = NULL;
    hl_error err;
    CHECK(hl_run_new_stepper(&rot, f.sys, rotation, NULL, &err) == HL_OK);
    CHECK(hl_run_event_order(rot) == 4);
    long n1, n2;
    double e1 = fixed_error(rot, 0.2, &n1), e2 = fixed_error(rot, 0.1, &n2);
    printf("Hermite on the exact rotation: %ld crossings, errors %.3g (dt 0.2) %.3g (dt 0.1): "
           "order %.2f\n",
           n1, e1, e2, log2(e1 / e2));
    CHECK(n1 == 6 && n2 == 6);
    CHECK_MSG(log2(e1 / e2) > 3.5 && e2 < 1e-5, "Hermite order %.2f", log2(e1 / e2));
    double s1 = fixed_error(f.run, 0.02, &n1), s2 = fixed_error(f.run, 0.01, &n2);
    printf("stormer-verlet-kdk: errors %.3g (dt 0.02) %.3g (dt 0.01): order %.2f\n", s1, s2,
           log2(s1 / s2));
    CHECK_MSG(fabs(log2(s1 / s2) - 2) < 0.2, "stormer-verlet crossing order %.2f", log2(s1 / s2));
    hl_run_free(rot);
    fixture_clear(&f);
}

static void surfaces(void)
{
    fixture f;
    if (!fixture_new(&f, HH, NULL, "x=0,y=0,px=0,py=0"))
        return;
    hl_run_surface_info info;
    hl_error err;
    CHECK(hl_run_surface(&info, f.sys, "x", &err) == HL_OK && info.var == -1);
    CHECK(hl_run_surface(&info, f.sys, "x = 0", &err) == HL_OK && info.var == 0 && info.value == 0);
    CHECK(hl_run_surface(&info, f.sys, "1/2 = y", &err) == HL_OK && info.var == 1 &&
          info.value == 0.5);
    CHECK(hl_run_surface(&info, f.sys, "py = -1", &err) == HL_OK && info.var == 3);
    CHECK(hl_run_surface(&info, f.sys, "x + y = 0", &err) == HL_OK && info.var == -1);
    CHECK(hl_run_surface(&info, f.sys, "H = 1", &err) == HL_OK);
    /* errors, with positions */
    CHECK(hl_run_surface(&info, f.sys, "x = ", &err) == HL_EPARSE && err.pos >= 3);
    CHECK(hl_run_surface(&info, f.sys, "x = z", &err) == HL_EINVAL && err.pos == 4);
    CHECK_MSG(strstr(err.msg, "unknown symbol 'z'") != NULL, "%s", err.msg);
    CHECK(hl_run_surface(&info, f.sys, "x = 0; y = 1", &err) == HL_EPARSE && err.pos == 7);
    CHECK(hl_run_surface(&info, f.sys, "2 = 1", &err) == HL_EINVAL);
    CHECK_MSG(strstr(err.msg, "never crossed") != NULL, "%s", err.msg);
    CHECK(hl_run_surface(&info, f.sys, "x +* 1", &err) == HL_EPARSE && err.pos == 3);
    /* section surfaces must be coordinate = constant */
    hl_section *sec = NULL;
    CHECK(hl_section_new(&sec, f.sys, "x + y = 0", HL_EVENT_UP, 0.125, &err) == HL_EINVAL);
    CHECK(hl_section_new(&sec, f.sys, "px = 0", HL_EVENT_UP, 0.125, &err) == HL_EINVAL);
    /* the Arb run refuses events */
    arb_ptr za = _arb_vec_init(4);
    CHECK(hl_run_event(f.run, "x", HL_EVENT_UP, 0, NULL, NULL, &err) == HL_OK);
    CHECK(hl_run_adaptive_arb(f.run, za, 30, "1", 10, 1, NULL, NULL, NULL, &err) == HL_EUNSUP);
    _arb_vec_clear(za, 4);
    fixture_clear(&f);
}

/* V on x = 0 */
static double V0(double y)
{
    return y * y / 2 - y * y * y / 3;
}

static void henon_heiles(void)
{
    fixture f;
    if (!fixture_new(&f, HH, NULL, "x=0,y=0,px=0,py=0"))
        return;
    hl_section *sec = NULL;
    hl_error err;
    const double E = 0.125;
    CHECK(hl_section_new(&sec, f.sys, "x=0", HL_EVENT_UP, E, &err) == HL_OK);
    enum { M = 8 };
    double zs[4 * M], lo, hi;
    CHECK_MSG(hl_section_spread(sec, zs, M, &lo, &hi, &err) == HL_OK, "%s", err.msg);
    /* the allowed interval: V0(y) = E at its ends */
    CHECK_MSG(fabs(V0(lo) - E) < 1e-15 && fabs(V0(hi) - E) < 1e-15 && lo < 0 && hi > 0,
              "interval [%.17g, %.17g]", lo, hi);
    double worst_seed = 0;
    for (int i = 0; i < M; i++) {
        double *z = zs + 4 * i, y = z[1], px = z[2];
        CHECK(z[0] == 0 && z[3] == 0 && px > 0);
        worst_seed = fmax(worst_seed, fabs(px - sqrt(2 * (E - V0(y)))));
    }
    CHECK_MSG(worst_seed < 1e-15, "solved px against sqrt(2 (E - V)): %.3g", worst_seed);
    /* crossings: x = 0, px > 0, H = E */
    static got g;
    memset(&g, 0, sizeof g);
    hl_section_opts adaptive = {1e-13, 0, 1e4};
    hl_run_stats s;
    CHECK_MSG(hl_section_orbit(sec, f.run, zs + 4 * 3, 200, &adaptive, keep, &g, &s, &err) == HL_OK,
              "%s", err.msg);
    double worst = 0;
    for (int k = 0; k < g.n && k < 1024; k++) {
        worst = fmax(worst, fmax(fabs(g.z[k][0]), fabs(g.H[k] - E)));
        CHECK(g.z[k][2] > 0);
    }
    CHECK(g.n == 200);
    CHECK_MSG(worst < 1e-13, "HH crossings: |x|, |H - E| up to %.3g", worst);
    printf("Henon-Heiles E = 1/8: y in [%.6f, %.6f]; 200 crossings to t = %.1f, max |x|, "
           "|H - E| %.3g\n",
           lo, hi, s.t_crossing, worst);
    /* a point outside the allowed region */
    double z[4] = {0, 0.9, 0, 0};
    CHECK(hl_section_complete(sec, z, &err) == HL_EDOM);
    CHECK_MSG(strstr(err.msg, "no real solution") != NULL, "%s", err.msg);
    hl_section_free(sec);
    /* E below the minimum (0 at the origin) */
    CHECK(hl_section_new(&sec, f.sys, "x=0", HL_EVENT_UP, -0.01, &err) == HL_OK);
    CHECK(hl_section_spread(sec, zs, M, NULL, NULL, &err) == HL_EDOM);
    hl_section_free(sec);
    fixture_clear(&f);
}

/* max |H - E| over the crossings of one orbit of a scheme at step dt */
static double scheme_section(const char *scheme, double dt, long ncross, double *drift)
{
    fixture f;
    if (!fixture_new(&f, HH, scheme, "x=0,y=0,px=0,py=0"))
        return NAN;
    hl_section *sec = NULL;
    hl_error err;
    const double E = 0.125;
    double zs[4 * 5];
    CHECK(hl_section_new(&sec, f.sys, "x=0", HL_EVENT_UP, E, &err) == HL_OK);
    CHECK(hl_section_spread(sec, zs, 5, NULL, NULL, &err) == HL_OK);
    static got g;
    memset(&g, 0, sizeof g);
    hl_section_opts o = {0, dt, 1e4};
    int st = hl_section_orbit(sec, f.run, zs + 4 * 1, ncross, &o, keep, &g, NULL, &err);
    CHECK_MSG(st == HL_OK, "%s at dt %g: %s", scheme, dt, err.msg);
    double worst = 0;
    for (int k = 0; k < g.n && k < 1024; k++)
        worst = fmax(worst, fabs(g.H[k] - E));
    *drift = g.n > 1 ? g.H[g.n - 1] - g.H[0] : NAN;
    hl_section_free(sec);
    fixture_clear(&f);
    return worst;
}

static void schemes_on_section(void)
{
    double d1, d2, d3, d4; /* H at the last crossing - at the first */
    double sv1 = scheme_section("stormer-verlet-kdk", 0.1, 100, &d1);
    double sv2 = scheme_section("stormer-verlet-kdk", 0.05, 100, &d2);
    /* Euler's H grows like e^(t dt) on an oscillation: 30 crossings (t ~ 200)
     * at dt 1e-3 stay below the escape energy 1/6 */
    double eu1 = scheme_section("euler", 1e-3, 30, &d3);
    double eu2 = scheme_section("euler", 5e-4, 30, &d4);
    printf("HH E = 1/8, max |H - E| on the section: stormer-verlet-kdk %.3g (dt 0.1), %.3g "
           "(dt 0.05), ratio %.2f (100 crossings); euler %.3g (dt 1e-3), %.3g (dt 5e-4), H "
           "first->last crossing %+.3g %+.3g (30 crossings)\n",
           sv1, sv2, sv1 / sv2, eu1, eu2, d3, d4);
    CHECK_MSG(sv1 / sv2 > 3.5 && sv1 / sv2 < 4.5 && sv1 < 0.01 * 0.125, "stormer-verlet: %.3g %.3g",
              sv1, sv2);
    /* Euler gains energy: the section spirals out, the more so the longer dt */
    CHECK_MSG(d3 > 10 * sv1 && d4 > 0 && d3 / d4 > 1.8 && d3 / d4 < 2.6, "euler drift %.3g %.3g",
              d3, d4);
}

/* A free particle leaves x = 0 for good: the section says so. */
static void never_crossed(void)
{
    fixture f;
    if (!fixture_new(&f, "(px^2+py^2)/2", NULL, "x=0,y=0,px=0,py=0"))
        return;
    hl_section *sec = NULL;
    hl_error err;
    CHECK(hl_section_new(&sec, f.sys, "x=0", HL_EVENT_UP, 0.5, &err) == HL_OK);
    double z[4] = {0, 0, 0, 0.5};
    CHECK(hl_section_complete(sec, z, &err) == HL_OK);
    CHECK_MSG(fabs(z[2] - sqrt(0.75)) < 1e-15, "px = %.17g", z[2]);
    hl_section_opts o = {1e-13, 0, 100};
    CHECK(hl_section_orbit(sec, f.run, z, 3, &o, NULL, NULL, NULL, &err) == HL_ENOCONV);
    CHECK_MSG(strstr(err.msg, "0 of 3 crossings") != NULL, "%s", err.msg);
    /* its allowed region along y is unbounded */
    double zs[8];
    CHECK(hl_section_spread(sec, zs, 2, NULL, NULL, &err) == HL_EDOM);
    CHECK_MSG(strstr(err.msg, "unbounded") != NULL, "%s", err.msg);
    hl_section_free(sec);
    fixture_clear(&f);
}

int main(void)
{
    adaptive_oscillator();
    fixed_orders();
    surfaces();
    henon_heiles();
    schemes_on_section();
    never_crossed();
    return HL_TEST_END();
}
