/* The Taylor integrator where Taylor coefficients vanish by symmetry
 * (issue 13, defect 1).  From q = 0 in the well q^4/4, q(t) has nonzero
 * coefficients only at the orders 1 mod 4 and p(t) at 0 mod 4 (q^6/6:
 * 1 and 0 mod 6), so the last two orders of a step can both be 0; a step
 * rule that reads only them took one unbounded step (H = 4.8e45).
 *
 * Truths, none from the integrator:
 *   periods by quadrature, T = 4 qmax / sqrt(2E) * B(1/n, 1/2) / n for
 *     H = p^2/2 + q^n/n (qmax = (n E)^(1/n)), in mpmath at 30 digits:
 *       python3 -c "from mpmath import *; mp.dps = 30; n, E = 4, mpf(1)/2;
 *         print(4*(n*E)**(1/mpf(n))/sqrt(2*E)*beta(1/mpf(n), 0.5)/n)"
 *     so after one period the orbit is back at its start;
 *   energy (and angular momentum for the rotation-invariant 2-dof quartic)
 *     conserved, and a radial orbit stays on its line;
 *   the equilibrium (0, 0) does not move at all, and a free fall, whose
 *     series terminates, is one exact step;
 *   the quartic's scaling: from (a, 0) the period is T(1, 0) / a.
 * And low orders (loose tolerances), which see little of the series
 * anywhere. */
#include <math.h>
#include <stdlib.h>

#include "hl_test.h"
#include "hamlie/flow.h"

static hl_pool *P;

/* periods from the initial points used below (see the header) */
#define T_QUARTIC_E1_2 6.236338999021644921159185 /* q^4/4, E = 1/2 */
#define T_QUARTIC_E1_4 7.416298709205487673735401 /* q^4/4, E = 1/4 */
#define T_SEXTIC_E1_2 5.833312628520677158766765  /* q^6/6, E = 1/2 */
#define T_DECIC_E1_2 5.32012498212865707707456    /* q^10/10, E = 1/2 */
#define T_QUARTIC_E5_8 5.897965279223985341910745 /* q^4/4, E = 5/8 */
#define DIGITS_OF(x) DIGITS_OF_(x)                /* a period as text, for Arb */
#define DIGITS_OF_(x) #x

typedef struct system {
    hl_tape *vf; /* the vector field */
    hl_tape *H;  /* H and, for N = 2, x py - y px */
    int n;
} system_t;

static system_t make_system(const char *H, int N)
{
    static const char *q1[] = {"q"}, *p1[] = {"p"}, *q2[] = {"x", "y"}, *p2[] = {"px", "py"};
    static const char *names1[] = {"q", "p"}, *names2[] = {"x", "y", "px", "py"};
    system_t s = {NULL, NULL, 2 * N};
    const hl_expr *e[2];
    hl_error err;
    CHECK_MSG(hl_parse(&e[0], P, H, &err) == HL_OK, "%s", err.msg);
    CHECK_MSG(hl_tape_hamiltonian(&s.vf, P, e[0], N, N == 1 ? q1 : q2, N == 1 ? p1 : p2, 0, NULL,
                                  NULL, &err) == HL_OK,
              "%s", err.msg);
    if (N == 2)
        CHECK(hl_parse(&e[1], P, "x*py - y*px", &err) == HL_OK);
    CHECK(hl_tape_new(&s.H, e, N, N == 1 ? names1 : names2, 2 * N, &err) == HL_OK);
    return s;
}

static void free_system(system_t *s)
{
    hl_tape_free(s->vf);
    hl_tape_free(s->H);
}

typedef struct watch {
    system_t *s;
    double inv0[2], drift; /* the invariants at the start, their worst drift */
    double off_line;       /* |y - slope x|, for a radial orbit */
    double slope;
} watch;

static int watch_fn(double t, const double *z, void *arg)
{
    watch *w = arg;
    double inv[2];
    hl_tape_eval_d(inv, z, w->s->H);
    for (int i = 0; i < w->s->n / 2; i++)
        w->drift = fmax(w->drift, fabs(inv[i] - w->inv0[i]));
    if (w->s->n == 4)
        w->off_line = fmax(w->off_line, fabs(z[1] - w->slope * z[0]));
    if (!isfinite(z[0]))
        w->drift = INFINITY;
    return 0;
}

/* Run s from z0 over one period T with 200 outputs in between; the worst
 * drift of the invariants, and the distance of z(T) from z0.  The run must
 * succeed and take more than one step per output's worth of orbit. */
static void one_period(watch *w, double *back, system_t *s, const double *z0, double T, double atol,
                       double rtol, long *steps)
{
    enum { NOUT = 200 };
    hl_flow *fl = NULL;
    hl_error err;
    CHECK(hl_flow_new(&fl, s->vf, atol, rtol, &err) == HL_OK);
    double ts[NOUT], zT[4];
    for (int i = 0; i < NOUT; i++)
        ts[i] = T * (i + 1) / NOUT;
    w->s = s;
    w->drift = w->off_line = 0;
    hl_tape_eval_d(w->inv0, z0, s->H);
    int st = hl_flow_run(fl, 0, z0, ts, NOUT, watch_fn, w, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    double t = 0;
    for (int i = 0; i < s->n; i++)
        zT[i] = z0[i];
    long before = hl_flow_nsteps(fl);
    CHECK_MSG(hl_flow_evolve(fl, &t, T, zT, &err) == HL_OK, "%s", err.msg);
    *steps = hl_flow_nsteps(fl) - before;
    *back = 0;
    for (int i = 0; i < s->n; i++)
        *back = fmax(*back, fabs(zT[i] - z0[i]));
    if (!isfinite(*back))
        *back = INFINITY;
    hl_flow_free(fl);
}

static void check_period(const char *what, system_t *s, const double *z0, double T, double tol,
                         double max_drift, double max_back)
{
    watch w = {0};
    w.slope = s->n == 4 && z0[2] != 0 ? z0[3] / z0[2] : 0;
    double back;
    long steps;
    one_period(&w, &back, s, z0, T, tol, tol, &steps);
    printf("%-34s tol %g: %5ld steps, invariants drift %.3g, back at the start within %.3g\n", what,
           tol, steps, w.drift, back);
    CHECK_MSG(w.drift < max_drift, "%s: invariants drift %.3g", what, w.drift);
    CHECK_MSG(back < max_back, "%s: after one period %.3g from the start", what, back);
    CHECK_MSG(steps > 5, "%s: %ld steps for one period", what, steps);
    if (s->n == 4)
        CHECK_MSG(w.off_line < 1e-13, "%s: off the line y = %g x by %.3g", what, w.slope,
                  w.off_line);
}

/* energy conservation alone, over one period from near a point of symmetry */
static void check_drift(const char *what, system_t *s, const double *z0, double T)
{
    watch w = {0};
    double back;
    long steps;
    one_period(&w, &back, s, z0, T, 1e-15, 1e-15, &steps);
    CHECK_MSG(w.drift < 1e-13, "%s: energy drift %.3g", what, w.drift);
}

static void test_quartic(void)
{
    system_t s = make_system("p^2/2 + q^4/4", 1);
    /* from q = 0: the last two orders vanish at every tolerance whose
     * order p is 2 or 3 mod 4 (1e-15: p = 19) */
    const double mid[2] = {0, 1}, turn[2] = {1, 0}, neg[2] = {0, -1};
    check_period("quartic from (0, 1)", &s, mid, T_QUARTIC_E1_2, 1e-15, 1e-13, 1e-12);
    check_period("quartic from (0, -1)", &s, neg, T_QUARTIC_E1_2, 1e-15, 1e-13, 1e-12);
    check_period("quartic from (0, 1)", &s, mid, T_QUARTIC_E1_2, 1e-12, 1e-10, 1e-9);
    check_period("quartic from (0, 1)", &s, mid, T_QUARTIC_E1_2, 1e-9, 1e-7, 1e-6);
    check_period("quartic from the turning point (1, 0)", &s, turn, T_QUARTIC_E1_4, 1e-15, 1e-13,
                 1e-12);
    /* near q = 0 the coefficients of those orders are not 0 but tiny */
    const double near[2] = {1e-9, 1};
    check_drift("quartic from (1e-9, 1)", &s, near, T_QUARTIC_E1_2);
    free_system(&s);
}

/* a tiny amplitude: the period scales as 1/a; relative tolerance only */
static void test_tiny_amplitude(void)
{
    system_t s = make_system("p^2/2 + q^4/4", 1);
    const double a = 1e-8, z0[2] = {a, 0};
    watch w = {0};
    double back;
    long steps;
    one_period(&w, &back, &s, z0, T_QUARTIC_E1_4 / a, 1e-300, 1e-15, &steps);
    printf("quartic from (1e-8, 0) over T = %.6g: %ld steps, back within %.3g (relative)\n",
           T_QUARTIC_E1_4 / a, steps, back / a);
    CHECK_MSG(back / a < 1e-12, "tiny amplitude: back within %.3g of a", back / a);
    CHECK_MSG(w.drift < 1e-13 * w.inv0[0], "tiny amplitude: relative energy drift %.3g",
              w.drift / w.inv0[0]);
    free_system(&s);
}

static void test_sextic_decic(void)
{
    system_t s = make_system("p^2/2 + q^6/6", 1);
    const double mid[2] = {0, 1};
    check_period("sextic from (0, 1)", &s, mid, T_SEXTIC_E1_2, 1e-12, 1e-10, 1e-9);
    check_period("sextic from (0, 1)", &s, mid, T_SEXTIC_E1_2, 1e-15, 1e-13, 1e-12);
    free_system(&s);
    /* q^10/10 from q = 0 at order 19: the orders 12..19 are all 0 */
    s = make_system("p^2/2 + q^10/10", 1);
    check_period("decic from (0, 1)", &s, mid, T_DECIC_E1_2, 1e-15, 1e-13, 1e-12);
    /* near q = 0: the orders 12..19 are tiny, not 0, and the window is
     * blind to them; the first step of a run is checked by its defect */
    const double near[2] = {1e-9, 1};
    check_drift("decic from (1e-9, 1)", &s, near, T_DECIC_E1_2);
    free_system(&s);
}

/* Loose tolerances give low orders (tol 1e-2: 4), whose few coefficients
 * say little of the series, at any point: every step is checked there.
 * Energy over t = 20 (3-4 periods, 100-200 steps of local error tol)
 * within 10 tol (the steps it guards against lost 500 to 1e15), from q = 0
 * and from q = 0.3, no point of symmetry. */
static void test_low_orders(void)
{
    const char *Hs[] = {"p^2/2 + q^6/6", "p^2/2 + q^8/8", "p^2/2 + q^10/10"};
    const double starts[2][2] = {{0, 1}, {0.3, 1}}, tols[] = {1e-2, 1e-3, 1e-5};
    for (int i = 0; i < 3; i++) {
        system_t s = make_system(Hs[i], 1);
        for (int j = 0; j < 2; j++)
            for (int k = 0; k < 3; k++) {
                watch w = {0};
                double back;
                long steps;
                one_period(&w, &back, &s, starts[j], 20, tols[k], tols[k], &steps);
                CHECK_MSG(w.drift < 10 * tols[k], "%s from (%g, 1) at tol %g: energy drift %.3g",
                          Hs[i], starts[j][0], tols[k], w.drift);
            }
        free_system(&s);
    }
}

/* (x^2 + y^2)^2/4 written out: from the origin the orbit is radial, on the
 * line y = x py0/px0, with u'' = -u^3 along it (E = 5/8) */
static void test_quartic_2dof(void)
{
    system_t s = make_system("(px^2+py^2)/2 + (x^4+y^4)/4 + x^2*y^2/2", 2);
    const double z0[4] = {0, 0, 1, 0.5};
    check_period("2-dof quartic from (0, 0, 1, 0.5)", &s, z0, T_QUARTIC_E5_8, 1e-15, 1e-13, 1e-12);
    free_system(&s);
}

/* the equilibrium: every coefficient past order 0 is 0, and the point
 * stays; a free fall: the series stops at order 2, and one step is exact,
 * q = t - t^2/2 */
static void test_equilibrium_free_fall(void)
{
    system_t s = make_system("p^2/2 + q^4/4", 1);
    hl_flow *fl = NULL;
    hl_error err;
    CHECK(hl_flow_new(&fl, s.vf, 1e-15, 1e-15, &err) == HL_OK);
    double t = 0, z[2] = {0, 0};
    CHECK_MSG(hl_flow_evolve(fl, &t, 1e3, z, &err) == HL_OK, "%s", err.msg);
    CHECK(t == 1e3 && z[0] == 0 && z[1] == 0);
    hl_flow_free(fl);
    free_system(&s);
    s = make_system("p^2/2 + q", 1);
    CHECK(hl_flow_new(&fl, s.vf, 1e-15, 1e-15, &err) == HL_OK);
    t = 0, z[0] = 0, z[1] = 1;
    CHECK_MSG(hl_flow_evolve(fl, &t, 10, z, &err) == HL_OK, "%s", err.msg);
    CHECK_MSG(z[0] == -40 && z[1] == -9 && hl_flow_nsteps(fl) == 1, "free fall: %g %g, %ld steps",
              z[0], z[1], hl_flow_nsteps(fl));
    hl_flow_free(fl);
    free_system(&s);
}

/* the same in Arb: back at the start after one period, to digits - 5.  At
 * 26 digits the order is 31, 27: 33, so that the last two orders vanish
 * (3 and 2 mod 4; 3 and 2 mod 6) */
static void arb_period(const char *what, const char *H, double digits, const char *T_digits)
{
    system_t s = make_system(H, 1);
    hl_flow_arb *fl = NULL;
    hl_error err;
    CHECK(hl_flow_arb_new(&fl, s.vf, digits, &err) == HL_OK);
    slong prec = hl_flow_arb_prec(fl);
    arb_ptr z = _arb_vec_init(2);
    arb_t t, T;
    arb_init(t);
    arb_init(T);
    arb_one(z + 1);
    arb_set_str(T, T_digits, prec);
    int st = hl_flow_arb_evolve(fl, t, T, z, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    double dq = arf_get_d(arb_midref(z), ARF_RND_NEAR);
    arb_sub_si(z + 1, z + 1, 1, prec);
    double dp = arf_get_d(arb_midref(z + 1), ARF_RND_NEAR);
    printf("%s in Arb at %g digits (order %d): %ld steps, back within %.3g %.3g\n", what, digits,
           hl_flow_arb_order(fl), hl_flow_arb_nsteps(fl), dq, dp);
    double tol = pow(10, 5 - digits);
    CHECK_MSG(fabs(dq) < tol && fabs(dp) < tol, "%s: arb back within %.3g %.3g", what, dq, dp);
    CHECK(hl_flow_arb_nsteps(fl) > 5);
    arb_clear(t);
    arb_clear(T);
    _arb_vec_clear(z, 2);
    hl_flow_arb_free(fl);
    free_system(&s);
}

int main(void)
{
    P = hl_pool_new();
    test_quartic();
    test_tiny_amplitude();
    test_sextic_decic();
    test_quartic_2dof();
    test_low_orders();
    test_equilibrium_free_fall();
    arb_period("quartic from (0, 1)", "p^2/2 + q^4/4", 26, DIGITS_OF(T_QUARTIC_E1_2));
    arb_period("quartic from (0, 1)", "p^2/2 + q^4/4", 20, DIGITS_OF(T_QUARTIC_E1_2));
    arb_period("sextic from (0, 1)", "p^2/2 + q^6/6", 27, DIGITS_OF(T_SEXTIC_E1_2));
    hl_pool_free(P);
    flint_cleanup();
    return HL_TEST_END();
}
