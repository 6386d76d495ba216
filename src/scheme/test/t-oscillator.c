/* The paper's three oscillator schemes (§4.1) and their relatives on
 * H = (p^2 + x^2)/2, against closed forms:
 *  - paper-dg, implicit midpoint, avf, gonzalez, itoh-abe and the user's
 *    equations in the paper's own form all expand to the Taylor series of
 *    X = (4x + 4Dp - D^2 x)/(4 + D^2), P = (4p - 4Dx - D^2 p)/(4 + D^2)
 *    (the paper's closed form; for a quadratic H every discrete gradient is
 *    the midpoint rule);
 *  - euler and paper-euler give x + D p, p - D x exactly (every higher
 *    coefficient zero);
 *  - exact-rotation gives x cos D + p sin D, p cos D - x sin D;
 *  - the D^2 coefficient of the midpoint map by hand: -x/2, -p/2. */
#include "sch.h"

#define NC 9

static void check_n(hl_system *sys, const char *name, const char *fx, const char *fp, int n)
{
    hl_scheme *s;
    hl_error err;
    int st = hl_scheme_new(&s, name, 0, sys, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", name, err.msg);
    if (st != HL_OK)
        return;
    hl_series *Z = expand(s, NC);
    CHECK_MSG(Z != NULL, "%s", name);
    if (Z) {
        CHECK_MSG(series_is(&Z[0], fx, n, sys), "%s: X is not %s", name, fx);
        CHECK_MSG(series_is(&Z[1], fp, n, sys), "%s: P is not %s", name, fp);
        free_series(Z, 2, hl_system_ctx(sys));
    }
    hl_scheme_free(s);
}

static void check(hl_system *sys, const char *name, const char *fx, const char *fp)
{
    check_n(sys, name, fx, fp, NC);
}

static void check_user(hl_system *sys, const char *text, int is_map, const char *fx,
                       const char *fp)
{
    hl_scheme *s;
    hl_error err;
    int st = is_map ? hl_scheme_from_map(&s, text, sys, &err)
                    : hl_scheme_from_equations(&s, text, sys, &err);
    CHECK_MSG(st == HL_OK, "'%s': %s", text, err.msg);
    if (st != HL_OK)
        return;
    hl_series *Z = expand(s, NC);
    CHECK(Z != NULL);
    if (Z) {
        CHECK_MSG(series_is(&Z[0], fx, NC, sys), "'%s': X is not %s", text, fx);
        CHECK_MSG(series_is(&Z[1], fp, NC, sys), "'%s': P is not %s", text, fp);
        free_series(Z, 2, hl_system_ctx(sys));
    }
    hl_scheme_free(s);
}

int main(void)
{
    hl_system *sys = make_system("(p^2 + x^2)/2");
    const char *dgx = "(4*x + 4*D*p - D^2*x)/(4 + D^2)";
    const char *dgp = "(4*p - 4*D*x - D^2*p)/(4 + D^2)";
    check(sys, "paper-dg", dgx, dgp);
    check(sys, "implicit-midpoint", dgx, dgp);
    check(sys, "avf", dgx, dgp);
    check(sys, "gonzalez", dgx, dgp);
    check(sys, "itoh-abe", dgx, dgp);
    check(sys, "euler", "x + D*p", "p - D*x");
    check(sys, "paper-euler", "x + D*p", "p - D*x");
    check(sys, "exact-rotation", "x*cos(D) + p*sin(D)", "p*cos(D) - x*sin(D)");
    /* the hand expansion of the midpoint map: 1/(4 + D^2) = (1 - D^2/4 + ...)/4 */
    check_n(sys, "implicit-midpoint", "x + D*p - D^2*x/2 - D^3*p/4 + D^4*x/8",
            "p - D*x - D^2*p/2 + D^3*x/4 + D^4*p/8", 5);
    /* the paper's equations as a user writes them, with X or a prime */
    check_user(sys, "(X-x)/D = (P^2-p^2)/(2*(P-p)); (P-p)/D = -(X^2-x^2)/(2*(X-x))", 0, dgx,
               dgp);
    check_user(sys, "(x'-x)/D = (p'+p)/2; (p'-p)/D = -(x'+x)/2", 0, dgx, dgp);
    check_user(sys, "X = x + D*p; P = p - D*x", 1, "x + D*p", "p - D*x");
    /* symplectic Euler written as a sequential map */
    check_user(sys, "X = x + D*p; P = p - D*X", 1, "x + D*p", "p - D*x - D^2*p");
    /* the comparison can fail: Euler is not the discrete gradient at D^2 */
    {
        hl_scheme *s;
        hl_error err;
        CHECK(hl_scheme_new(&s, "euler", 0, sys, &err) == HL_OK);
        hl_series *Z = expand(s, 3);
        CHECK(Z && !series_is(&Z[0], dgx, 3, sys) && series_is(&Z[0], dgx, 2, sys));
        if (Z)
            free_series(Z, 2, hl_system_ctx(sys));
        hl_scheme_free(s);
    }
    hl_system_free(sys);
    return HL_TEST_END();
}
