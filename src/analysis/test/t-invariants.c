/* Invariants of leading error fields on the oscillator (by hand):
 *  Euler: v_2 = x d/dx + p d/dp (see t-oscillator) scales every monomial of
 *    degree d by d, so it has no polynomial first integral, and the Darboux
 *    polynomials x, p (eigenvalue 1) give the rational integral x/p (or p/x).
 *  paper-dg: v_3 = -g/2 = -(p d/dx - x d/dp)/2, a rotation field: its
 *    polynomial integrals of degree <= 2 are the multiples of x^2 + p^2 (the
 *    degree-1 part rotates, the degree-2 part has the one-dimensional kernel
 *    x^2 + p^2 since v(x^2) = -xp, v(p^2) = xp, v(xp) = (x^2 - p^2)/2).
 *  Pendulum midpoint: v_3 involves sin q: not a polynomial field. */
#include <stdlib.h>

#include "hamlie/analysis.h"
#include "hamlie/scheme.h"
#include "hl_test.h"
#include "analysis_test.h"

static int errors_of(hl_vfields *e, hl_system *sys, const char *name, int n)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_series Z[2];
    hl_scheme *s;
    hl_error err;
    hl_series_init(&Z[0], 0, ctx);
    hl_series_init(&Z[1], 0, ctx);
    int st = hl_scheme_new(&s, name, 0, sys, &err);
    if (st == HL_OK)
        st = hl_scheme_expand(Z, s, n + 1, &err);
    if (st == HL_OK)
        st = hl_vfields_compute(e, Z, sys, n, &err);
    hl_scheme_free(s);
    hl_series_clear(&Z[0], ctx);
    hl_series_clear(&Z[1], ctx);
    return st;
}

int main(void)
{
    hl_system *sys = make_system("(p^2+x^2)/2");
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_vfields e;
    hl_error err;
    hl_alg *phi, a, b;
    int n, app;
    hl_alg_init(&a, ctx);
    hl_alg_init(&b, ctx);

    CHECK(errors_of(&e, sys, "euler", 3) == HL_OK);
    CHECK(hl_field_poly_invariants(&phi, &n, &app, hl_vfields_v(&e, 2), 3, sys, &err) == HL_OK);
    CHECK(app && n == 0);
    hl_alg_vec_free(phi, n, ctx);
    CHECK(hl_field_darboux_invariants(&phi, &n, &app, hl_vfields_v(&e, 2), 2, sys, &err) == HL_OK);
    CHECK(app && n == 1);
    CHECK(hl_system_read(&a, sys, "x/p", &err) == HL_OK);
    CHECK(hl_system_read(&b, sys, "p/x", &err) == HL_OK);
    CHECK(n == 1 && (hl_alg_equal(&phi[0], &a, ctx) || hl_alg_equal(&phi[0], &b, ctx)));
    hl_alg_vec_free(phi, n, ctx);
    hl_vfields_clear(&e, sys);

    CHECK(errors_of(&e, sys, "paper-dg", 3) == HL_OK);
    CHECK(hl_field_poly_invariants(&phi, &n, &app, hl_vfields_v(&e, 3), 2, sys, &err) == HL_OK);
    CHECK(app && n == 1);
    CHECK(hl_system_read(&a, sys, "x^2 + p^2", &err) == HL_OK);
    if (n == 1) {
        fmpq_t c;
        fmpq_init(c);
        CHECK(hl_alg_div(&b, &phi[0], &a, ctx, &err) == HL_OK && hl_alg_is_fmpq(&b, c, ctx) &&
              !fmpq_is_zero(c));
        fmpq_clear(c);
    }
    hl_alg_vec_free(phi, n, ctx);
    hl_vfields_clear(&e, sys);
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&b, ctx);
    hl_system_free(sys);

    hl_system *pend = make_system("p^2/2 - cos(q)");
    CHECK(errors_of(&e, pend, "implicit-midpoint", 3) == HL_OK);
    CHECK(hl_field_poly_invariants(&phi, &n, &app, hl_vfields_v(&e, 3), 2, pend, &err) == HL_OK);
    CHECK(!app && n == 0);
    hl_vfields_clear(&e, pend);
    hl_system_free(pend);
    return HL_TEST_END();
}
