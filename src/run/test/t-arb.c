/* The adaptive run in Arb (--digits):
 *   the oscillator from (1, 0) at 50 digits, 20 outputs to t = 10: x = cos t,
 *     p = -sin t (Arb's own cos and sin at the same precision) to 1e-45, and
 *     the times are exactly T k / n;
 *   initial values read at full precision: py = sqrt(3) agrees with Arb's
 *     sqrt(3) to 1e-55 at 60 digits (a double would be off by 1e-16);
 *   Kepler e = 0.5 at 40 digits: after one period 2 pi the orbit closes to
 *     1e-35, H is kept to 1e-35. */
#include "run_test.h"

typedef struct osc {
    slong prec;
    double worst, worst_t;
    long rows;
} osc;

static int osc_fn(const hl_run_row_arb *row, void *arg)
{
    osc *o = arg;
    arb_t c, tk, d;
    arb_init(c), arb_init(tk), arb_init(d);
    arb_set_si(tk, 10 * row->k); /* t_k = 10 k / 20 */
    arb_div_si(tk, tk, 20, o->prec);
    arb_sub(d, tk, row->t, o->prec);
    o->worst_t = fmax(o->worst_t, fabs(arf_get_d(arb_midref(d), ARF_RND_NEAR)));
    arb_cos(c, tk, o->prec);
    arb_sub(d, row->z, c, o->prec);
    o->worst = fmax(o->worst, fabs(arf_get_d(arb_midref(d), ARF_RND_NEAR)));
    arb_sin(c, tk, o->prec);
    arb_add(d, row->z + 1, c, o->prec);
    o->worst = fmax(o->worst, fabs(arf_get_d(arb_midref(d), ARF_RND_NEAR)));
    o->rows++;
    arb_clear(c), arb_clear(tk), arb_clear(d);
    return 0;
}

static void test_oscillator(void)
{
    fixture f;
    if (!fixture_new(&f, OSC, NULL, "x=1,p=0"))
        return;
    hl_error err;
    slong prec = hl_run_arb_prec(50);
    arb_ptr z0 = _arb_vec_init(2);
    CHECK(hl_run_init_values_arb(z0, f.sys, "x=1,p=0", prec, &err) == HL_OK);
    osc o = {prec, 0, 0, 0};
    hl_run_stats s;
    int st = hl_run_adaptive_arb(f.run, z0, 50, "10", 20, 1, osc_fn, &o, &s, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    CHECK(o.rows == 21 && s.rows == 21 && s.steps == 20);
    CHECK_MSG(o.worst < 1e-45, "oscillator at 50 digits: error %.3g", o.worst);
    CHECK(o.worst_t == 0);
    printf("oscillator, 50 digits, t = 10: max error %.3g, %ld Taylor steps\n", o.worst,
           s.ref_steps);
    _arb_vec_clear(z0, 2);
    fixture_clear(&f);
}

static int last_fn(const hl_run_row_arb *row, void *arg)
{
    _arb_vec_set(arg, row->z, 4);
    return 0;
}

static void test_kepler(void)
{
    fixture f;
    if (!fixture_new(&f, KEPLER, NULL, "x=0.5,y=0,px=0,py=sqrt(3)"))
        return;
    hl_error err;
    slong prec = hl_run_arb_prec(60);
    arb_ptr z0 = _arb_vec_init(4), z1 = _arb_vec_init(4);
    CHECK(hl_run_init_values_arb(z0, f.sys, "x=0.5,y=0,px=0,py=sqrt(3)", prec, &err) == HL_OK);
    arb_t r3;
    arb_init(r3);
    arb_sqrt_ui(r3, 3, prec);
    arb_sub(r3, r3, z0 + 3, prec);
    CHECK(arb_is_finite(r3) && fabs(arf_get_d(arb_midref(r3), ARF_RND_NEAR)) < 1e-55);
    CHECK(f.z0[3] == sqrt(3.0));
    prec = hl_run_arb_prec(40);
    /* one period is 2 pi (a = 1), given as text to 64 digits */
    const char *twopi = "6.2831853071795864769252867665590057683943387987502116419498891846";
    hl_run_stats s;
    int st = hl_run_adaptive_arb(f.run, z0, 40, twopi, 1, 1, last_fn, z1, &s, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    double worst = 0;
    for (int i = 0; i < 4; i++) {
        arb_sub(r3, z1 + i, z0 + i, prec);
        worst = fmax(worst, fabs(arf_get_d(arb_midref(r3), ARF_RND_NEAR)));
    }
    printf("Kepler, 40 digits, one period: orbit closes to %.3g, max |dH| %.3g\n", worst,
           s.max_dH);
    CHECK_MSG(worst < 1e-35, "Kepler orbit closes to %.3g", worst);
    CHECK(s.max_dH < 1e-35);
    arb_clear(r3);
    _arb_vec_clear(z0, 4), _arb_vec_clear(z1, 4);
    fixture_clear(&f);
}

int main(void)
{
    test_oscillator();
    test_kepler();
    flint_cleanup();
    return HL_TEST_END();
}
