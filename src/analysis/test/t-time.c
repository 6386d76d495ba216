/* Time reparametrisation.  The paper's discrete gradient on the oscillator
 * is the Cayley map: M11 = (4 - D^2)/(4 + D^2), M12 = 4D/(4 + D^2), so
 * tan(tau/2) = M12/(1 + M11) = D/2, tau = 2 atan(D/2) (by hand), and two
 * steps of D are one of D2 with D2/2 = tan(2 atan(D/2)) = D/(1 - D^2/4),
 * D2 = 8D/(4 - D^2).  The order-by-order series tau(D) must be the Taylor
 * series of 2 atan(D/2) = D - D^3/12 + D^5/80 - ... for paper-dg and implicit
 * midpoint; it is D for the exact rotation; W = tau - D starts with -D^3/12
 * (so the paper's printed W = D - 2 atan(D/2) has the wrong sign for
 * psi = exp((D + W) g)).  Euler (v_2 a scaling) fails at k = 2, implicit
 * midpoint on the pendulum at k = 3 (v_3 not a constant multiple of g). */
#include <stdlib.h>

#include "hamlie/analysis.h"
#include "hamlie/scheme.h"
#include "hl_test.h"
#include "analysis_test.h"

#define NT 9

/* tau series of a catalog scheme; *ok, *fail_k as hl_errors_time_series. */
static int tau_of(hl_series *tau, int *ok, int *fail_k, hl_system *sys, const char *name)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int m = 2 * hl_system_ndof(sys);
    hl_series *Z = malloc((size_t)m * sizeof *Z);
    for (int i = 0; i < m; i++)
        hl_series_init(&Z[i], 0, ctx);
    hl_scheme *s;
    hl_error err;
    int st = hl_scheme_new(&s, name, 0, sys, &err);
    if (st == HL_OK)
        st = hl_scheme_expand(Z, s, NT + 1, &err);
    if (st == HL_OK)
        st = hl_errors_time_series(tau, ok, fail_k, Z, sys, NT, &err);
    if (st != HL_OK)
        fprintf(stderr, "%s: %s\n", name, err.msg);
    hl_scheme_free(s);
    for (int i = 0; i < m; i++)
        hl_series_clear(&Z[i], ctx);
    free(Z);
    return st;
}

static int series_is(const hl_series *a, const char *f, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg e;
    hl_series s;
    hl_error err;
    hl_alg_init(&e, ctx);
    hl_series_init(&s, 0, ctx);
    int ok = hl_system_read(&e, sys, f, &err) == HL_OK &&
             hl_series_from_alg(&s, &e, hl_system_var_D(sys), NT + 1, ctx, &err) == HL_OK &&
             a->n == NT + 1 && hl_series_equal(a, &s, ctx);
    hl_alg_clear(&e, ctx);
    hl_series_clear(&s, ctx);
    return ok;
}

int main(void)
{
    hl_system *sys = make_system("(p^2+x^2)/2");
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_error err;
    hl_series tau;
    int ok, fk;
    hl_series_init(&tau, 0, ctx);

    CHECK(tau_of(&tau, &ok, &fk, sys, "paper-dg") == HL_OK && ok);
    CHECK(series_is(&tau, "2*atan(D/2)", sys));
    fmpq_t c;
    fmpq_init(c);
    CHECK(hl_alg_is_fmpq(&tau.c[3], c, ctx) && fmpz_equal_si(fmpq_numref(c), -1) &&
          fmpz_equal_si(fmpq_denref(c), 12));
    fmpq_clear(c);
    CHECK(tau_of(&tau, &ok, &fk, sys, "implicit-midpoint") == HL_OK && ok);
    CHECK(series_is(&tau, "2*atan(D/2)", sys));
    CHECK(tau_of(&tau, &ok, &fk, sys, "exact-rotation") == HL_OK && ok);
    CHECK(series_is(&tau, "D", sys));
    CHECK(tau_of(&tau, &ok, &fk, sys, "euler") == HL_OK && !ok && fk == 2);

    /* closed forms from the paper's discrete-gradient map */
    hl_alg *img = hl_alg_vec_new(2, ctx), t, r, D2, w;
    hl_alg_init(&t, ctx);
    hl_alg_init(&r, ctx);
    hl_alg_init(&D2, ctx);
    hl_alg_init(&w, ctx);
    CHECK(hl_system_read_map(img, sys,
                             "X = (4*x+4*D*p-D^2*x)/(4+D^2); P = (4*p-4*D*x-D^2*p)/(4+D^2)",
                             &err) == HL_OK);
    int have;
    CHECK(hl_errors_time_closed(&t, &r, &ok, &D2, &have, img, sys, &err) == HL_OK && ok && have);
    CHECK(hl_system_read(&w, sys, "2*atan(D/2)", &err) == HL_OK && hl_alg_equal(&t, &w, ctx));
    CHECK(hl_system_read(&w, sys, "D/2", &err) == HL_OK && hl_alg_equal(&r, &w, ctx));
    CHECK(hl_system_read(&w, sys, "8*D/(4 - D^2)", &err) == HL_OK && hl_alg_equal(&D2, &w, ctx));
    /* Euler's map is not a rotation */
    CHECK(hl_system_read_map(img, sys, "X = x + D*p; P = p - D*x", &err) == HL_OK);
    CHECK(hl_errors_time_closed(&t, &r, &ok, &D2, &have, img, sys, &err) == HL_OK && !ok);
    /* the same from the series of the implicit schemes (to O(D^10)) */
    const char *imp[] = {"paper-dg", "implicit-midpoint", "euler", "exact-rotation"};
    for (int i = 0; i < 4; i++) {
        hl_series Z[2];
        hl_scheme *s;
        hl_series_init(&Z[0], 0, ctx);
        hl_series_init(&Z[1], 0, ctx);
        CHECK(hl_scheme_new(&s, imp[i], 0, sys, &err) == HL_OK &&
              hl_scheme_expand(Z, s, NT + 1, &err) == HL_OK);
        CHECK(hl_errors_time_closed_series(&t, &r, &ok, &D2, Z, sys, NT, &err) == HL_OK);
        if (i < 2) { /* Cayley: r = D/2 exactly */
            CHECK(ok);
            CHECK(hl_system_read(&w, sys, "2*atan(D/2)", &err) == HL_OK && hl_alg_equal(&t, &w, ctx));
            CHECK(hl_system_read(&w, sys, "8*D/(4 - D^2)", &err) == HL_OK &&
                  hl_alg_equal(&D2, &w, ctx));
        } else /* Euler: not a rotation; exact: r = tan(D/2) is not c D */
            CHECK_MSG(!ok, "%s", imp[i]);
        hl_scheme_free(s);
        hl_series_clear(&Z[0], ctx);
        hl_series_clear(&Z[1], ctx);
    }
    hl_alg_vec_free(img, 2, ctx);
    hl_alg_clear(&t, ctx);
    hl_alg_clear(&r, ctx);
    hl_alg_clear(&D2, ctx);
    hl_alg_clear(&w, ctx);
    hl_series_clear(&tau, ctx);
    hl_system_free(sys);

    hl_system *pend = make_system("p^2/2 - cos(q)");
    hl_series_init(&tau, 0, hl_system_ctx(pend));
    CHECK(tau_of(&tau, &ok, &fk, pend, "implicit-midpoint") == HL_OK && !ok && fk == 3);
    hl_series_clear(&tau, hl_system_ctx(pend));
    hl_system_free(pend);
    return HL_TEST_END();
}
