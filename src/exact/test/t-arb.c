/* The 1-dof exact scheme in high precision (hl_exact_arb) against closed
 * forms computed in Arb and against the Arb Taylor integrator:
 *   pendulum q0 = 1.3: T = 4 K(sin^2(q0/2)) at 40 digits to 1e-37;
 *     a step of 1000 from (1.3, 0) at 30 digits equals the integrator
 *     carried over the whole t = 1000 to 1e-24 (the scheme integrates over
 *     1000 mod T only), and agrees with the double exact scheme to 1e-12;
 *   Morse V = (1 - exp(-q))^2 from (0.4, 0.3): T = 2 pi / sqrt(2 (1 - E)) at
 *     50 digits to 1e-47;
 *   pendulum librations (from the bottom, tiny, near the separatrix),
 *     rotations and the equilibrium against Jacobi's closed forms (mpmath
 *     values) at 30 digits;
 *   refused: 2 dof, a quadratic H, fewer than 16 digits; a separatrix point
 *     is an error. */
#include <math.h>
#include <stdlib.h>

#include <acb_elliptic.h>

#include "hl_test.h"
#include "hamlie/exact.h"
#include "hamlie/flow.h"
#include "hamlie/tape.h"

#define PREC 256

static hl_system *sys_new(const char *H)
{
    hl_system *s = NULL;
    hl_error err;
    hl_system_spec spec = {H, NULL, NULL, NULL, NULL};
    int st = hl_system_new(&s, &spec, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", H, err.msg);
    return s;
}

/* |a - b| / |b| as a double */
static double rel(const arb_t a, const arb_t b)
{
    arb_t d;
    arb_init(d);
    arb_sub(d, a, b, PREC);
    arb_div(d, d, b, PREC);
    double r = fabs(arf_get_d(arb_midref(d), ARF_RND_NEAR));
    arb_clear(d);
    return r;
}

static void test_pendulum(void)
{
    hl_system *s = sys_new("p^2/2 - cos(q)");
    hl_exact_arb *f = NULL;
    hl_error err;
    CHECK(hl_exact_arb_new(&f, s, 40, &err) == HL_OK);
    arb_ptr z = _arb_vec_init(2);
    arb_t T, Tref, m;
    acb_t k, a;
    arb_init(T), arb_init(Tref), arb_init(m);
    acb_init(k), acb_init(a);
    arb_set_str(z, "1.3", PREC);
    CHECK(hl_exact_arb_period(T, z, f, &err) == HL_OK);
    /* 4 K(m), m = sin^2(q0/2) */
    arb_mul_2exp_si(m, z, -1);
    arb_sin(m, m, PREC);
    arb_sqr(m, m, PREC);
    acb_set_arb(a, m);
    acb_elliptic_k(k, a, PREC);
    arb_mul_2exp_si(Tref, acb_realref(k), 2);
    double e = rel(T, Tref);
    printf("pendulum period at 40 digits: relative error %.3g\n", e);
    CHECK_MSG(e < 1e-37, "pendulum period: relative error %.3g", e);
    hl_exact_arb_free(f);

    /* a step of 1000 at 30 digits against the integrator over t = 1000 */
    CHECK(hl_exact_arb_new(&f, s, 30, &err) == HL_OK);
    arb_ptr w = _arb_vec_init(2);
    arb_t dt, t;
    arb_init(dt), arb_init(t);
    arb_set_si(dt, 1000);
    arb_set_str(z, "1.3", PREC), arb_zero(z + 1);
    CHECK(hl_exact_arb_step(z, dt, f, &err) == HL_OK);
    const char *names[2] = {"q", "p"};
    hl_tape *vf = NULL;
    CHECK(hl_tape_hamiltonian(&vf, hl_system_pool(s), hl_system_H_expr(s), 1, names, names + 1,
                              0, NULL, NULL, &err) == HL_OK);
    hl_flow_arb *fa = NULL;
    CHECK(hl_flow_arb_new(&fa, vf, 30, &err) == HL_OK);
    arb_set_str(w, "1.3", PREC), arb_zero(w + 1);
    CHECK(hl_flow_arb_evolve(fa, t, dt, w, &err) == HL_OK);
    arb_sub(t, z, w, PREC);
    double d0 = fabs(arf_get_d(arb_midref(t), ARF_RND_NEAR));
    arb_sub(t, z + 1, w + 1, PREC);
    double d1 = fabs(arf_get_d(arb_midref(t), ARF_RND_NEAR));
    printf("pendulum, one step of 1000 at 30 digits vs integrating to 1000: %.3g, %.3g\n", d0,
           d1);
    CHECK_MSG(d0 < 1e-24 && d1 < 1e-24, "step of 1000: %.3g %.3g", d0, d1);
    /* and the double exact scheme */
    hl_exact_flow *fd = NULL;
    double zd[2] = {1.3, 0};
    CHECK(hl_exact_flow_new(&fd, s, &err) == HL_OK && hl_exact_flow_step(zd, 1000, fd, &err) == HL_OK);
    CHECK(fabs(zd[0] - arf_get_d(arb_midref(z), ARF_RND_NEAR)) < 1e-12);
    CHECK(fabs(zd[1] - arf_get_d(arb_midref(z + 1), ARF_RND_NEAR)) < 1e-12);
    hl_exact_flow_free(fd);
    /* a separatrix point */
    arb_zero(z), arb_set_si(z + 1, 2);
    CHECK(hl_exact_arb_step(z, dt, f, &err) != HL_OK);
    printf("separatrix: %s\n", err.msg);
    hl_flow_arb_free(fa);
    hl_tape_free(vf);
    hl_exact_arb_free(f);
    _arb_vec_clear(z, 2), _arb_vec_clear(w, 2);
    arb_clear(T), arb_clear(Tref), arb_clear(m), arb_clear(dt), arb_clear(t);
    acb_clear(k), acb_clear(a);
    hl_system_free(s);
}


/* The pendulum against Jacobi's closed forms at 34 digits (python3 + mpmath
 * at 50 digits, the same formulas as t-flow.c's pendulum_cases: librations
 * sin(q/2) = k sn(t + t0 | k^2), p = 2 k cn, T = 4 K(k^2); rotations
 * q = 2 am(k0 t | 1/k0^2), p = 2 k0 dn, T = 2 K(1/k0^2)/k0; the initial
 * values are the doubles), at 30 digits: the period, and the state after
 * one step of t, each within tol relative to the orbit's amplitude a. */
static void test_pendulum_closed_forms(void)
{
    static const struct {
        double q0, p0, t, a, tol;
        const char *q, *p, *T, *what;
    } cases[] = {
        {0, 1.8, 4, 1, 1e-27, "0.9602479746707700815372279716990899",
         "-1.54487334735363177186431648597764", "9.12219655369108120197809318315364",
         "libration from the bottom"},
        {1e-8, 0, 4, 1e-8, 1e-25, "-6.53643620863611948015075640579948e-9",
         "7.568024953079282456915520036506579e-9", "6.283185307179586516195194936431423",
         "q0 = 1e-8"},
        {0, 1e-200, 4, 1e-200, 1e-25, "-7.568024953079282378260730127805124e-201",
         "-6.536436208636119029391188851256634e-201", "6.283185307179586476925286766559006",
         "p0 = 1e-200 (the linearised flow's p0 sin t, p0 cos t)"},
        {3.14, 0, 4, 1, 1e-24, "3.098101837642838397744375123633754",
         "-0.04345821456691528130089011816749309", "34.08718627715588690850400693368857",
         "near the separatrix"},
        {0, 2.5, 100, 1, 1e-25, "197.0317563811194164994561438609609",
         "1.728864241968679043730874777789878", "3.1924844442635670202979381429959", "rotation"},
        {0, -2.5, 4, 1, 1e-27, "-8.124811494434576364370708545514469",
         "-1.927417370414738941895581876302144", "3.1924844442635670202979381429959",
         "rotation, p < 0"},
    };
    hl_system *s = sys_new("p^2/2 - cos(q)");
    hl_error err;
    arb_ptr z = _arb_vec_init(2), ref = _arb_vec_init(2);
    arb_t T, Tref, dt, d;
    arb_init(T), arb_init(Tref), arb_init(dt), arb_init(d);
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        hl_exact_arb *f = NULL;
        CHECK(hl_exact_arb_new(&f, s, 30, &err) == HL_OK);
        arb_set_d(z, cases[i].q0), arb_set_d(z + 1, cases[i].p0);
        int st = hl_exact_arb_period(T, z, f, &err);
        CHECK_MSG(st == HL_OK, "%s: %s", cases[i].what, err.msg);
        arb_set_str(Tref, cases[i].T, PREC);
        double eT = rel(T, Tref);
        arb_set_d(dt, cases[i].t);
        if (st == HL_OK)
            st = hl_exact_arb_step(z, dt, f, &err);
        CHECK_MSG(st == HL_OK, "%s: %s", cases[i].what, err.msg);
        arb_set_str(ref, cases[i].q, PREC), arb_set_str(ref + 1, cases[i].p, PREC);
        double e = 0;
        for (int j = 0; j < 2; j++) {
            arb_sub(d, z + j, ref + j, PREC);
            e = fmax(e, fabs(arf_get_d(arb_midref(d), ARF_RND_NEAR)) / cases[i].a);
        }
        printf("pendulum at 30 digits, %s: period %.3g, state at t = %g %.3g (relative)\n",
               cases[i].what, eT, cases[i].t, e);
        CHECK_MSG(eT < 1e-27, "%s: period relative error %.3g", cases[i].what, eT);
        CHECK_MSG(e < cases[i].tol, "%s: state error %.3g", cases[i].what, e);
        hl_exact_arb_free(f);
    }
    /* one scheme through both rotations of the same energy: the period is
     * the same, q's advance a period is not (p < 0: -2 pi) */
    hl_exact_arb *f = NULL;
    CHECK(hl_exact_arb_new(&f, s, 30, &err) == HL_OK);
    for (int sgn = 1; sgn >= -1; sgn -= 2) {
        arb_zero(z), arb_set_d(z + 1, 2.5 * sgn);
        arb_set_d(dt, 4);
        CHECK(hl_exact_arb_step(z, dt, f, &err) == HL_OK);
        arb_set_str(ref, "8.124811494434576364370708545514469", PREC);
        arb_mul_si(ref, ref, sgn, PREC);
        arb_sub(d, z, ref, PREC);
        double e = fabs(arf_get_d(arb_midref(d), ARF_RND_NEAR));
        CHECK_MSG(e < 1e-27, "rotation of sign %d after the other: q off by %.3g", sgn, e);
    }
    hl_exact_arb_free(f);
    /* the equilibrium: the limit period 2 pi, and it stays */
    CHECK(hl_exact_arb_new(&f, s, 30, &err) == HL_OK);
    arb_zero(z), arb_zero(z + 1);
    CHECK(hl_exact_arb_period(T, z, f, &err) == HL_OK);
    arb_const_pi(Tref, PREC);
    arb_mul_2exp_si(Tref, Tref, 1);
    CHECK_MSG(rel(T, Tref) < 1e-28, "equilibrium period %.3g", rel(T, Tref));
    arb_set_d(dt, 0.5);
    CHECK(hl_exact_arb_step(z, dt, f, &err) == HL_OK);
    CHECK(arb_is_zero(z) && arb_is_zero(z + 1));
    hl_exact_arb_free(f);
    _arb_vec_clear(z, 2), _arb_vec_clear(ref, 2);
    arb_clear(T), arb_clear(Tref), arb_clear(dt), arb_clear(d);
    hl_system_free(s);
}

static void test_morse(void)
{
    hl_system *s = sys_new("p^2/2 + (1-exp(-q))^2");
    hl_exact_arb *f = NULL;
    hl_error err;
    CHECK(hl_exact_arb_new(&f, s, 50, &err) == HL_OK);
    arb_ptr z = _arb_vec_init(2);
    arb_t T, Tref, E;
    arb_init(T), arb_init(Tref), arb_init(E);
    arb_set_str(z, "0.4", PREC), arb_set_str(z + 1, "0.3", PREC);
    CHECK(hl_exact_arb_period(T, z, f, &err) == HL_OK);
    /* E = p^2/2 + (1 - e^-q)^2; T = 2 pi / sqrt(2 (1 - E)) */
    arb_t half;
    arb_init(half);
    arb_neg(E, z);
    arb_exp(E, E, PREC);
    arb_sub_ui(E, E, 1, PREC);
    arb_sqr(E, E, PREC);
    arb_sqr(half, z + 1, PREC);
    arb_mul_2exp_si(half, half, -1);
    arb_add(E, E, half, PREC);
    arb_sub_ui(Tref, E, 1, PREC);
    arb_neg(Tref, Tref);
    arb_mul_2exp_si(Tref, Tref, 1);
    arb_sqrt(Tref, Tref, PREC);
    arb_const_pi(E, PREC);
    arb_mul_2exp_si(E, E, 1);
    arb_div(Tref, E, Tref, PREC);
    double e = rel(T, Tref);
    printf("Morse period at 50 digits: relative error %.3g\n", e);
    CHECK_MSG(e < 1e-47, "Morse period: relative error %.3g", e);
    arb_clear(T), arb_clear(Tref), arb_clear(E), arb_clear(half);
    _arb_vec_clear(z, 2);
    hl_exact_arb_free(f);
    hl_system_free(s);
}

static void test_refused(void)
{
    hl_error err;
    hl_exact_arb *f = NULL;
    hl_system *s2 = sys_new("(px^2+py^2)/2 - 1/sqrt(x^2+y^2)");
    CHECK(hl_exact_arb_new(&f, s2, 30, &err) == HL_EUNSUP && f == NULL);
    hl_system *sq = sys_new("(p^2+x^2)/2");
    CHECK(hl_exact_arb_new(&f, sq, 30, &err) == HL_EUNSUP && f == NULL);
    printf("quadratic: %s\n", err.msg);
    hl_system *sp = sys_new("p^2/2 - cos(q)");
    CHECK(hl_exact_arb_new(&f, sp, 10, &err) == HL_EINVAL && f == NULL);
    hl_system_free(s2), hl_system_free(sq), hl_system_free(sp);
}

int main(void)
{
    test_pendulum();
    test_pendulum_closed_forms();
    test_morse();
    test_refused();
    flint_cleanup();
    return HL_TEST_END();
}
