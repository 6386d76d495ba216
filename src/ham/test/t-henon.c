/* Hénon–Heiles H = (px^2+py^2)/2 + (x^2+y^2)/2 + x^2 y - y^3/3:
 * H is an integral; L = x py - y px is not.  By hand, with V the potential,
 *   {L, H} = y dV/dx - x dV/dy = y (x + 2xy) - x (y + x^2 - y^2) = 3 x y^2 - x^3. */
#include "ham_test.h"

int main(void)
{
    hl_system *sys = sys_new("(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3", NULL);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg f, r;
    hl_alg_init(&f, ctx), hl_alg_init(&r, ctx);
    int yes = 0;

    rd(&f, sys, "H");
    CHECK(hl_check_integral(&yes, &r, &f, sys, NULL) == HL_OK);
    CHECK(yes);
    rd(&f, sys, "x*py - y*px");
    CHECK(hl_check_integral(&yes, &r, &f, sys, NULL) == HL_OK);
    CHECK(!yes);
    CHECK(eq_formula(&r, sys, "3*x*y^2 - x^3"));

    /* the generator: xi = (px, py), eta = -(x + 2xy, y + x^2 - y^2) */
    hl_alg xi[2], eta[2];
    for (int j = 0; j < 2; j++)
        hl_alg_init(&xi[j], ctx), hl_alg_init(&eta[j], ctx);
    CHECK(hl_generator(xi, eta, sys, NULL) == HL_OK);
    CHECK(eq_formula(&xi[0], sys, "px"));
    CHECK(eq_formula(&xi[1], sys, "py"));
    CHECK(eq_formula(&eta[0], sys, "-x - 2*x*y"));
    CHECK(eq_formula(&eta[1], sys, "-y - x^2 + y^2"));
    CHECK(!hl_alg_ctx_numeric_used(ctx)); /* polynomials: every zero exact */
    for (int j = 0; j < 2; j++)
        hl_alg_clear(&xi[j], ctx), hl_alg_clear(&eta[j], ctx);
    hl_alg_clear(&f, ctx), hl_alg_clear(&r, ctx);
    hl_system_free(sys);
    return HL_TEST_END();
}
