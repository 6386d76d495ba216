/* hl_vfields_compute_direct: the same v_k, leading field and order as
 * hl_vfields_compute (which also recomputes them from K(D)), without the
 * cross-check, and says so (checked = agree = 0) — on RK4 for Henon-Heiles,
 * the implicit midpoint for the pendulum and Euler for the oscillator. */
#include <stdlib.h>

#include "analysis_test.h"
#include "hamlie/analysis.h"
#include "hamlie/scheme.h"
#include "hl_test.h"

#define ORDER 6

static void same_fields(const char *H, const char *scheme, int want_order)
{
    hl_system *sys = make_system(H);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int m = 2 * hl_system_ndof(sys);
    hl_scheme *s = NULL;
    hl_series *psi = malloc((size_t)m * sizeof *psi);
    for (int i = 0; i < m; i++)
        hl_series_init(&psi[i], 0, ctx);
    hl_vfields both = {0}, direct = {0};
    hl_error err;
    hl_status st = hl_scheme_new(&s, scheme, 0, sys, &err);
    if (st == HL_OK)
        st = hl_scheme_expand(psi, s, ORDER + 1, &err);
    hl_status st1 = st == HL_OK ? hl_vfields_compute(&both, psi, sys, ORDER, &err) : st;
    hl_status st2 = st == HL_OK ? hl_vfields_compute_direct(&direct, psi, sys, ORDER, &err) : st;
    CHECK_MSG(st1 == HL_OK && st2 == HL_OK, "%s on %s: %s", scheme, H, err.msg);
    if (st1 == HL_OK && st2 == HL_OK) {
        CHECK(both.checked && both.agree && !direct.checked && !direct.agree);
        CHECK_MSG(direct.order == want_order && both.order == want_order &&
                      direct.leading == both.leading,
                  "%s on %s: orders %d / %d, want %d", scheme, H, direct.order, both.order,
                  want_order);
        int same = 1;
        for (int k = 2; k <= ORDER; k++)
            for (int i = 0; i < m; i++)
                same = same &&
                       hl_alg_equal(&hl_vfields_v(&direct, k)[i], &hl_vfields_v(&both, k)[i], ctx);
        CHECK_MSG(same, "%s on %s: the direct v_k differ", scheme, H);
    }
    hl_vfields_clear(&both, sys);
    hl_vfields_clear(&direct, sys);
    for (int i = 0; i < m; i++)
        hl_series_clear(&psi[i], ctx);
    free(psi);
    hl_scheme_free(s);
    hl_system_free(sys);
}

int main(void)
{
    same_fields("(px^2+py^2)/2+(x^2+y^2)/2+x^2*y-y^3/3", "rk4", 4);
    same_fields("p^2/2 - cos(q)", "implicit-midpoint", 2);
    same_fields("(p^2+x^2)/2", "euler", 1);
    return HL_TEST_END();
}
