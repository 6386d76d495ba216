/* The scheme language's pieces, each against a closed form worked by hand:
 *  - H(a, b): Itoh-Abe written with H on the oscillator is the midpoint map
 *    (4x + 4Dp - D^2 x)/(4 + D^2);
 *  - dot(a, b): Q = q + D*Hp(q,p)*dot(q,q)/dot(q,q) is explicit Euler (HH);
 *  - int(s, vector): AVF written with a vector integrand on HH agrees with
 *    the catalog's avf (which integrates componentwise) — and, on the
 *    oscillator, with the midpoint map;
 *  - a symbolic parameter: H = k q^2/2 + p^2/2, "P = p - D*k*q" is Euler;
 *  - stages and elementwise functions: "k = sin(q); Q = q + D*p; P = p - D*k"
 *    on the pendulum is explicit Euler (sin q = dH/dq);
 *  - compositions: two half steps of Euler on the oscillator,
 *    X = (1 - D^2/4) x + D p, P = (1 - D^2/4) p - D x (M^2 by hand);
 *  - the Lie scheme's order parameter: lie with n = 2 on the oscillator is
 *    x + D p - D^2 x/2 exactly. */
#include "sch.h"

#define NC 7

static void same_as(hl_system *sys, hl_scheme *s, const char *fx, const char *fp,
                    const char *what)
{
    int N = hl_system_ndof(sys);
    hl_series *Z = expand(s, NC);
    CHECK_MSG(Z != NULL, "%s", what);
    if (Z == NULL)
        return;
    if (fx)
        CHECK_MSG(series_is(&Z[0], fx, NC, sys), "%s: Q is not %s", what, fx);
    if (fp)
        CHECK_MSG(series_is(&Z[N], fp, NC, sys), "%s: P is not %s", what, fp);
    free_series(Z, 2 * N, hl_system_ctx(sys));
}

static hl_scheme *text(hl_system *sys, const char *t)
{
    hl_scheme *s = NULL;
    hl_error err;
    int rc = hl_scheme_from_text(&s, t, sys, &err);
    CHECK_MSG(rc == HL_OK, "'%s': %s", t, err.msg);
    return s;
}

/* Two schemes agree on all 2N components to NC coefficients. */
static void agree(hl_system *sys, hl_scheme *a, hl_scheme *b)
{
    int N = hl_system_ndof(sys);
    hl_series *A = expand(a, NC), *B = expand(b, NC);
    CHECK(A && B);
    for (int i = 0; A && B && i < 2 * N; i++) {
        int ok = 1;
        for (int k = 0; ok && k < NC; k++)
            ok = hl_alg_equal(&A[i].c[k], &B[i].c[k], hl_system_ctx(sys));
        CHECK_MSG(ok, "%s and %s differ in component %d", a->name, b->name, i);
    }
    if (A)
        free_series(A, 2 * N, hl_system_ctx(sys));
    if (B)
        free_series(B, 2 * N, hl_system_ctx(sys));
}

int main(void)
{
    hl_system *osc = make_system("(p^2 + x^2)/2");
    hl_system *pend = make_system("p^2/2 - cos(q)");
    hl_system *hh = make_system("(px^2 + py^2)/2 + (x^2 + y^2)/2 + x^2*y - y^3/3");
    hl_system *kq = make_system("k*q^2/2 + p^2/2");
    const char *dgx = "(4*x + 4*D*p - D^2*x)/(4 + D^2)";
    const char *dgp = "(4*p - 4*D*x - D^2*p)/(4 + D^2)";
    hl_scheme *s;

    s = text(osc, "(Q-q)/D = (H(Q, P) - H(Q, p))/(P - p); (P-p)/D = -(H(Q, p) - H(q, p))/(Q - q)");
    if (s)
        same_as(osc, s, dgx, dgp, "Itoh-Abe with H()");
    hl_scheme_free(s);

    s = text(hh, "Q = q + D*Hp(q, p)*dot(q, q)/dot(q, q); P = p - D*Hq(q, p)");
    if (s) {
        CHECK(s->all_explicit);
        same_as(hh, s, "x + D*px", "px - D*(x + 2*x*y)", "dot()");
    }
    hl_scheme_free(s);

    s = text(hh, "Z = int(s, Hp(q + s*(Q-q), p + s*(P-p))); Q = q + D*Z; "
                 "P = p - D*int(u, Hq(q + u*(Q-q), p + u*(P-p)))");
    if (s) {
        CHECK(!s->all_explicit && s->nint == 4 && s->m == 6);
        hl_scheme *avf;
        hl_error err;
        CHECK(hl_scheme_new(&avf, "avf", 0, hh, &err) == HL_OK);
        agree(hh, s, avf);
        hl_scheme_free(avf);
    }
    hl_scheme_free(s);
    s = text(osc, "Q = q + D*int(s, Hp(q + s*(Q-q), p + s*(P-p))); "
                  "P = p - D*int(s, Hq(q + s*(Q-q), p + s*(P-p)))");
    if (s)
        same_as(osc, s, dgx, dgp, "avf on the oscillator");
    hl_scheme_free(s);

    s = text(kq, "Q = q + D*p; P = p - D*k*q");
    if (s)
        same_as(kq, s, "q + D*p", "p - D*k*q", "parameter");
    hl_scheme_free(s);

    s = text(pend, "k = sin(q); Q = q + D*p; P = p - D*k");
    if (s) {
        CHECK(s->all_explicit && s->m == 3);
        same_as(pend, s, "q + D*p", "p - D*sin(q)", "stage");
    }
    hl_scheme_free(s);

    {
        const char *c[] = {"1/2", "1/2"};
        hl_error err;
        CHECK(hl_scheme_compose(&s, "euler-twice", hl_scheme_text("euler"), 2, c, osc, &err) ==
              HL_OK);
        same_as(osc, s, "(1 - D^2/4)*x + D*p", "(1 - D^2/4)*p - D*x", "composition");
        hl_scheme_free(s);
        CHECK(hl_scheme_new(&s, "lie", 2, osc, &err) == HL_OK);
        same_as(osc, s, "x + D*p - D^2*x/2", "p - D*x - D^2*p/2", "lie n = 2");
        hl_scheme_free(s);
    }
    hl_system_free(osc);
    hl_system_free(pend);
    hl_system_free(hh);
    hl_system_free(kq);
    return HL_TEST_END();
}
