/* The rules of src/rules/ run through the reference emitter (rules_ref.h)
 * on series held in arrays, checked by identities that do not come from the
 * rules themselves: exp(log a) = a, sin^2 + cos^2 = 1, tan = sin/cos,
 * atan(tan a) = a, asin(sin a) = a, acos = pi/2 - asin, sqrt(a)^2 = a,
 * a^c a^-c = 1, a^(3/2) = sqrt(a) a, (a/b) b = a, (k/a) a = k,
 * atan2(r sin t, r cos t) = t in all four quadrants, the linear ops'
 * inverses, at several points including awkward ones (a0 near 0,
 * negative, large); and by closed forms (the
 * Taylor coefficients of exp(c + t), log(1 + t), (1 + t)^c, atan t, ...).
 * Every operation is reached at least once.  Tolerance: 1e-13 relative to
 * the largest coefficient of the expected series up to k, since a
 * recurrence's error grows with the size of the coefficients before it. */
#include <math.h>
#include <string.h>

#include "hl_test.h"
#include "rules/test/rules_ref.h"

#define ORDER 16
#define N (ORDER + 1)
#define TOL 1e-13

typedef struct ser {
    double c[N];
} ser;

static ser op2(hl_op op, ser a, ser b)
{
    ser d, x;
    memset(&x, 0, sizeof x);
    ref_taylor(op, d.c, x.c, a.c, b.c, ORDER);
    return d;
}
static ser op1(hl_op op, ser a)
{
    return op2(op, a, a);
}

/* the auxiliary series X of op(a, b) */
static ser aux2(hl_op op, ser a, ser b)
{
    ser d, x;
    ref_taylor(op, d.c, x.c, a.c, b.c, ORDER);
    return x;
}
static ser aux1(hl_op op, ser a)
{
    return aux2(op, a, a);
}

static ser konst(double c)
{
    ser s;
    memset(&s, 0, sizeof s);
    s.c[0] = c;
    return s;
}

/* a0 + sum_{j>=1} s 0.3/(j+1) (-1)^[j%3==0] t^j: radius of convergence 1 */
static ser input(double a0, double s)
{
    ser a = konst(a0);
    for (int j = 1; j < N; j++)
        a.c[j] = s * 0.3 / (j + 1) * (j % 3 ? 1 : -1);
    return a;
}

static ser opk(hl_op op, ser a, double k)
{
    return op2(op, a, konst(k));
}

static void check_close(const char *what, double a0, ser got, ser want, double tol)
{
    double scale = 0, worst = 0;
    int at = -1;
    for (int k = 0; k < N; k++) {
        scale = fmax(scale, fabs(want.c[k]));
        double e = fabs(got.c[k] - want.c[k]) / (scale > 0 ? scale : 1);
        if (!(e <= worst)) { /* NaN counts as worst */
            worst = e;
            at = k;
        }
    }
    CHECK_MSG(worst <= tol, "%s at a0 = %g: relative error %.3g at k = %d (got %.17g, want %.17g)",
              what, a0, worst, at, got.c[at], want.c[at]);
}

static void test_exp_log(void)
{
    const double pts[] = {0.4, 3.0, 0.05, 20.0, -5.0};
    for (size_t i = 0; i < sizeof pts / sizeof *pts; i++) {
        /* near 0 a slow a(t): log's coefficients grow like (a'/a0)^k */
        ser a = input(pts[i], pts[i] > 0.1 ? 1 : pts[i] > 0 ? 0.01 : -1);
        if (pts[i] > 0)
            check_close("exp(log a)", pts[i], op1(HL_OP_EXP, op1(HL_OP_LOG, a)), a, TOL);
        check_close("log(exp a)", pts[i], op1(HL_OP_LOG, op1(HL_OP_EXP, a)), a, TOL);
        ser b = input(-0.3, 0.5);
        check_close("exp(a+b) = exp a exp b", pts[i], op1(HL_OP_EXP, op2(HL_OP_ADD, a, b)),
                    op2(HL_OP_MUL, op1(HL_OP_EXP, a), op1(HL_OP_EXP, b)), TOL);
    }
}

static void test_trig(void)
{
    const double pts[] = {0.4, -2.0, 1e-3, 0.0, 10.0, 100.0};
    for (size_t i = 0; i < sizeof pts / sizeof *pts; i++) {
        ser a = input(pts[i], 1), one = konst(1);
        ser s = op1(HL_OP_SINCOS, a), c = aux1(HL_OP_SINCOS, a);
        ser ss = op1(HL_OP_SQR, s), cc = op1(HL_OP_SQR, c);
        check_close("sin^2 + cos^2", pts[i], op2(HL_OP_ADD, ss, cc), one, TOL);
        ser t = op1(HL_OP_TAN, a);
        check_close("tan = sin/cos", pts[i], t, op2(HL_OP_DIV, s, c), TOL);
        check_close("tan's aux = tan^2", pts[i], aux1(HL_OP_TAN, a), op2(HL_OP_MUL, t, t), TOL);
        if (fabs(pts[i]) > 5)
            continue;
        ser sh = op1(HL_OP_SINHCOSH, a), ch = aux1(HL_OP_SINHCOSH, a);
        ser d = op2(HL_OP_SUB, op1(HL_OP_SQR, ch), op1(HL_OP_SQR, sh));
        check_close("cosh^2 - sinh^2", pts[i], d, one, TOL * cosh(pts[i]) * cosh(pts[i]));
        check_close("tanh = sinh/cosh", pts[i], op1(HL_OP_TANH, a), op2(HL_OP_DIV, sh, ch), TOL);
    }
}

static void test_inverse_trig(void)
{
    const double pts[] = {0.0, 1e-3, -1e-3, 0.4, -1.0, 1.3};
    for (size_t i = 0; i < sizeof pts / sizeof *pts; i++) {
        ser a = input(pts[i], 0.5);
        check_close("atan(tan a)", pts[i], op1(HL_OP_ATAN, op1(HL_OP_TAN, a)), a, TOL);
        ser aa = op2(HL_OP_ADDK, op1(HL_OP_SQR, a), konst(1));
        check_close("atan's aux = 1 + a^2", pts[i], aux1(HL_OP_ATAN, a), aa, TOL);
        check_close("asinh(sinh a)", pts[i], op1(HL_OP_ASINH, op1(HL_OP_SINHCOSH, a)), a, TOL);
        check_close("asinh's aux = sqrt(1 + a^2)", pts[i], aux1(HL_OP_ASINH, a),
                    op1(HL_OP_SQRT, aa), TOL);
        if (fabs(pts[i]) >= 1.2)
            continue;
        check_close("asin(sin a)", pts[i], op1(HL_OP_ASIN, op1(HL_OP_SINCOS, a)), a, TOL);
        ser u = input(sin(pts[i]) * 0.9, 0.3);
        ser rest = opk(HL_OP_KSUB, op1(HL_OP_ASIN, u), M_PI / 2);
        check_close("acos = pi/2 - asin", pts[i], op1(HL_OP_ACOS, u), rest, TOL);
        /* cos near pi/2 has an absolute error of an ulp of pi/2, large beside a small u */
        check_close("cos(acos u) = u", pts[i], aux1(HL_OP_SINCOS, op1(HL_OP_ACOS, u)), u,
                    TOL * fmax(1, 0.01 / fabs(u.c[0])));
        ser root = op1(HL_OP_SQRT, opk(HL_OP_KSUB, op1(HL_OP_SQR, u), 1));
        check_close("asin's aux = sqrt(1 - u^2)", pts[i], aux1(HL_OP_ASIN, u), root, TOL);
        check_close("acos's aux = sqrt(1 - u^2)", pts[i], aux1(HL_OP_ACOS, u), root, TOL);
    }
}

static void test_roots_powers(void)
{
    const double pts[] = {0.4, 0.05, 50.0, 3.0};
    const double cs[] = {0.75, 1.5, -2.5, 1.0 / 3};
    for (size_t i = 0; i < sizeof pts / sizeof *pts; i++) {
        ser a = input(pts[i], pts[i] < 0.1 ? 0.01 : 1), one = konst(1);
        ser r = op1(HL_OP_SQRT, a);
        check_close("sqrt(a)^2", pts[i], op1(HL_OP_SQR, r), a, TOL);
        check_close("sqrt(a) sqrt(a)", pts[i], op2(HL_OP_MUL, r, r), a, TOL);
        check_close("a^(1/2) = sqrt a", pts[i], opk(HL_OP_POWK, a, 0.5), r, TOL);
        check_close("a^(3/2) = sqrt(a) a", pts[i], opk(HL_OP_POWK, a, 1.5), op2(HL_OP_MUL, r, a),
                    TOL);
        check_close("pow3h(a) = sqrt(a) a", pts[i], op1(HL_OP_POW3H, a), op2(HL_OP_MUL, r, a), TOL);
        check_close("pow3h(a) = a^(3/2)", pts[i], op1(HL_OP_POW3H, a), opk(HL_OP_POWK, a, 1.5),
                    TOL);
        for (size_t j = 0; j < sizeof cs / sizeof *cs; j++) {
            ser p = op2(HL_OP_MUL, opk(HL_OP_POWK, a, cs[j]), opk(HL_OP_POWK, a, -cs[j]));
            check_close("a^c a^-c", pts[i], p, one, TOL);
        }
    }
}

static void test_quotients(void)
{
    const double pts[] = {0.4, -0.05, 30.0, -3.0};
    for (size_t i = 0; i < sizeof pts / sizeof *pts; i++) {
        ser a = input(0.7, 1), b = input(pts[i], fabs(pts[i]) < 0.1 ? 0.02 : 0.5);
        check_close("(a/b) b", pts[i], op2(HL_OP_MUL, op2(HL_OP_DIV, a, b), b), a, TOL);
        const double ks[] = {2.5, -1.0 / 3, 1e5};
        for (int j = 0; j < 3; j++) {
            ser q = op2(HL_OP_MUL, opk(HL_OP_KDIV, b, ks[j]), b);
            check_close("(k/b) b", pts[i], q, konst(ks[j]), TOL);
        }
    }
}

/* atan2(r sin t, r cos t) = t, t0 in each quadrant and near the cut */
static void test_atan2(void)
{
    const double ts[] = {0.5, 2.5, -2.5, -0.5, 3.1, -3.1, 1e-3};
    for (size_t i = 0; i < sizeof ts / sizeof *ts; i++) {
        ser t = input(ts[i], 0.7), r = input(2.0, 0.4);
        ser y = op2(HL_OP_MUL, r, op1(HL_OP_SINCOS, t));
        ser x = op2(HL_OP_MUL, r, aux1(HL_OP_SINCOS, t));
        check_close("atan2(r sin t, r cos t)", ts[i], op2(HL_OP_ATAN2, y, x), t, TOL);
        ser rr = op2(HL_OP_MUL, r, r);
        check_close("atan2's aux = r^2", ts[i], aux2(HL_OP_ATAN2, y, x), rr, TOL);
    }
}

/* the linear ops and the square: exact inverses up to a rounding each */
static void test_linear(void)
{
    ser a = input(0.4, 1), b = input(-1.7, 0.3);
    const double ks[] = {2.5, -0.1, 1e3};
    check_close("-(-a)", 0.4, op1(HL_OP_NEG, op1(HL_OP_NEG, a)), a, 0);
    check_close("(a + b) - b", 0.4, op2(HL_OP_SUB, op2(HL_OP_ADD, a, b), b), a, TOL);
    check_close("a^2 = a a", 0.4, op1(HL_OP_SQR, a), op2(HL_OP_MUL, a, a), TOL);
    for (int i = 0; i < 3; i++) {
        check_close("(a + k) - k", ks[i], opk(HL_OP_SUBK, opk(HL_OP_ADDK, a, ks[i]), ks[i]), a,
                    TOL);
        check_close("k - (k - a)", ks[i], opk(HL_OP_KSUB, opk(HL_OP_KSUB, a, ks[i]), ks[i]), a,
                    TOL);
        check_close("(a k) / k", ks[i], opk(HL_OP_DIVK, opk(HL_OP_MULK, a, ks[i]), ks[i]), a, TOL);
    }
}

/* Closed forms along a = c + t (or t): coefficients from calculus, not from
 * a recurrence. */
static void test_closed_forms(void)
{
    ser t = konst(0), e, l, p, p32, at, inv;
    t.c[1] = 1;
    ser ct = t, lt = t;
    ct.c[0] = 0.3;
    lt.c[0] = 1;
    for (int k = 0; k < N; k++) {
        e.c[k] = exp(0.3) / tgamma(k + 1.0);                     /* exp(0.3 + t) */
        l.c[k] = k == 0 ? 0 : (k % 2 ? 1.0 : -1.0) / k;          /* log(1 + t) */
        p.c[k] = k == 0 ? 1 : p.c[k - 1] * (0.75 - (k - 1)) / k; /* (1 + t)^(3/4) */
        p32.c[k] = k == 0 ? 1 : p32.c[k - 1] * (1.5 - (k - 1)) / k; /* (1 + t)^(3/2) */
        at.c[k] = k % 2 ? (k % 4 == 1 ? 1.0 : -1.0) / k : 0;     /* atan t */
        inv.c[k] = 1;                                            /* 1/(1 - t) */
    }
    check_close("exp(0.3 + t)", 0.3, op1(HL_OP_EXP, ct), e, TOL);
    check_close("log(1 + t)", 1, op1(HL_OP_LOG, lt), l, TOL);
    check_close("(1 + t)^(3/4)", 1, opk(HL_OP_POWK, lt, 0.75), p, TOL);
    check_close("(1 + t)^(3/2)", 1, op1(HL_OP_POW3H, lt), p32, TOL);
    check_close("atan t", 0, op1(HL_OP_ATAN, t), at, TOL);
    check_close("1/(1 - t)", 1, opk(HL_OP_KDIV, opk(HL_OP_KSUB, t, 1), 1), inv, TOL);
    ser s = op1(HL_OP_SINCOS, t), sh = op1(HL_OP_SINHCOSH, t);
    for (int k = 0; k < N; k++) {
        double f = 1 / tgamma(k + 1.0);
        CHECK_MSG(fabs(s.c[k] - (k % 2 ? (k % 4 == 1 ? f : -f) : 0)) <= TOL * f, "sin t at %d", k);
        CHECK_MSG(fabs(sh.c[k] - (k % 2 ? f : 0)) <= TOL * f, "sinh t at %d", k);
    }
}

/* The point rules against libm, and each Taylor rule's coefficient 0 equal
 * to its point rule bit for bit. */
static void test_points(void)
{
    for (int op = 0; op < HL_OP_COUNT; op++) {
        const hl_rule *r = hl_rule_of((hl_op)op);
        CHECK_MSG(r && r->name && r->point && r->taylor, "op %d has no rule", op);
        double a[N] = {0.3, 0.1}, b[N] = {0.8, 0.2}, d0, x0 = 0, d[N], x[N];
        ref_point((hl_op)op, &d0, &x0, a, b);
        ref_taylor((hl_op)op, d, x, a, b, 0);
        CHECK_MSG(memcmp(&d0, d, sizeof d0) == 0, "%s: point %.17g, taylor[0] %.17g", r->name, d0,
                  d[0]);
    }
    const struct {
        hl_op op;
        double want;
    } v[] = {{HL_OP_SQRT, sqrt(0.3)},         {HL_OP_EXP, exp(0.3)},
             {HL_OP_LOG, log(0.3)},           {HL_OP_SINCOS, sin(0.3)},
             {HL_OP_TAN, tan(0.3)},           {HL_OP_ATAN, atan(0.3)},
             {HL_OP_ASIN, asin(0.3)},         {HL_OP_ACOS, acos(0.3)},
             {HL_OP_ATAN2, atan2(0.3, -0.8)}, {HL_OP_POWK, pow(0.3, -0.8)},
             {HL_OP_KDIV, -0.8 / 0.3},        {HL_OP_DIV, 0.3 / -0.8},
             {HL_OP_ASINH, asinh(0.3)},       {HL_OP_POW3H, 0.3 * sqrt(0.3)}};
    for (size_t i = 0; i < sizeof v / sizeof *v; i++) {
        double a = 0.3, b = -0.8, d, x;
        ref_point(v[i].op, &d, &x, &a, &b);
        CHECK_MSG(d == v[i].want, "%s point: %.17g, libm %.17g", hl_op_name(v[i].op), d, v[i].want);
    }
}

int main(void)
{
    test_exp_log();
    test_trig();
    test_inverse_trig();
    test_roots_powers();
    test_quotients();
    test_atan2();
    test_linear();
    test_closed_forms();
    test_points();
    return HL_TEST_END();
}
