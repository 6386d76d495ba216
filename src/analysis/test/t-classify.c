/* Classification of leading error fields, by hand:
 *  - the map psi = exp(D g) + D^2/2 lambda g with lambda = x^2 + p^2 on the
 *    oscillator: psi_x = x + D p - D^2 x/2 + D^2 (x^2+p^2) p/2, psi_p likewise;
 *    v_2 = lambda g: parallel to g with lambda = x^2 + p^2, and Hamiltonian
 *    since 2H J grad H = J grad H^2: h = (x^2 + p^2)^2/4.
 *  - explicit Euler on the pendulum: [D^2] psi = 0, so v_2 = -g^2 z =
 *    (sin q, p cos q); not parallel to g = (p, -sin q), not a scaling, and
 *    da/dq + db/dp = 2 cos q != 0: general, not Hamiltonian. */
#include <stdlib.h>

#include "hamlie/analysis.h"
#include "hamlie/scheme.h"
#include "hl_test.h"

static int leading(hl_vfields *e, hl_system *sys, hl_scheme *s, int n)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_series Z[2];
    hl_error err;
    hl_series_init(&Z[0], 0, ctx);
    hl_series_init(&Z[1], 0, ctx);
    int st = hl_scheme_expand(Z, s, n + 1, &err);
    if (st == HL_OK)
        st = hl_vfields_compute(e, Z, sys, n, &err);
    if (st != HL_OK)
        fprintf(stderr, "%s\n", err.msg);
    hl_series_clear(&Z[0], ctx);
    hl_series_clear(&Z[1], ctx);
    return st;
}

int main(void)
{
    hl_error err;
    hl_system *sys;
    hl_system_spec spec = {"(p^2+x^2)/2", NULL, NULL, NULL, NULL};
    if (hl_system_new(&sys, &spec, &err) != HL_OK)
        return 2;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_scheme *s;
    hl_vfields e;
    hl_errfield F;
    hl_alg w;
    hl_alg_init(&w, ctx);
    CHECK(hl_scheme_from_map(&s, "X = x + D*p - D^2*x/2 + D^2*(x^2+p^2)*p/2; "
                                 "P = p - D*x - D^2*p/2 - D^2*(x^2+p^2)*x/2",
                             sys, &err) == HL_OK);
    CHECK(leading(&e, sys, s, 4) == HL_OK && e.agree && e.leading == 2);
    CHECK(hl_errfield_classify(&F, hl_vfields_v(&e, 2), sys, &err) == HL_OK);
    CHECK(F.kind == HL_ERRFIELD_PARALLEL);
    CHECK(hl_system_read(&w, sys, "x^2 + p^2", &err) == HL_OK && hl_alg_equal(&F.lambda, &w, ctx));
    CHECK(F.hamiltonian && F.have_h);
    CHECK(hl_system_read(&w, sys, "(x^2 + p^2)^2/4", &err) == HL_OK && hl_alg_equal(&F.h, &w, ctx));
    hl_errfield_clear(&F, sys);
    hl_vfields_clear(&e, sys);
    hl_scheme_free(s);
    hl_alg_clear(&w, ctx);
    hl_system_free(sys);

    spec.H = "p^2/2 - cos(q)";
    if (hl_system_new(&sys, &spec, &err) != HL_OK)
        return 2;
    ctx = hl_system_ctx(sys);
    hl_alg_init(&w, ctx);
    CHECK(hl_scheme_new(&s, "euler", 0, sys, &err) == HL_OK);
    CHECK(leading(&e, sys, s, 3) == HL_OK && e.agree && e.leading == 2);
    CHECK(hl_system_read(&w, sys, "sin(q)", &err) == HL_OK &&
          hl_alg_equal(&hl_vfields_v(&e, 2)[0], &w, ctx));
    CHECK(hl_system_read(&w, sys, "p*cos(q)", &err) == HL_OK &&
          hl_alg_equal(&hl_vfields_v(&e, 2)[1], &w, ctx));
    CHECK(hl_errfield_classify(&F, hl_vfields_v(&e, 2), sys, &err) == HL_OK);
    CHECK(F.kind == HL_ERRFIELD_GENERAL && !F.hamiltonian);
    hl_errfield_clear(&F, sys);
    hl_vfields_clear(&e, sys);
    hl_scheme_free(s);
    hl_alg_clear(&w, ctx);
    hl_system_free(sys);
    return HL_TEST_END();
}
