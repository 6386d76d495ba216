/* Canonical maps (paper §2: {Q_i,P_j} = delta_ij, {Q_i,Q_j} = {P_i,P_j} = 0).
 *
 * 1. The exact oscillator flow X = x cos D + p sin D, P = p cos D - x sin D:
 *    {X, P} = cos^2 D + sin^2 D = 1 for every D: canonical.
 * 2. Explicit Euler for the oscillator, X = x + D p, P = p - D x:
 *    {X, P} = 1*1 - (D)(-D) = 1 + D^2: not canonical.
 * 3. Symplectic Euler for the non-separable H = q p^2/2 (H_q = p^2/2,
 *    H_p = q p).  The scheme P = p - D H_q(q, P), Q = q + D H_p(q, P) gives
 *    P = p - D P^2/2, whose root near p is P = (sqrt(1 + 2 D p) - 1)/D, and
 *    Q = q (1 + D P) = q sqrt(1 + 2 D p).  By hand
 *    {Q, P} = sqrt(1+2Dp) * (1/D) * 2D/(2 sqrt(1+2Dp)) - 0 = 1: canonical.
 *    Explicit Euler for the same H, Q = q + D q p, P = p - D p^2/2:
 *    {Q, P} = (1 + D p)(1 - D p) - 0 = 1 - D^2 p^2: not canonical.
 * 4. Two degrees of freedom: a rotation in (x, px) and a drift in (y, py) is
 *    canonical; replacing Y = y + D py by Y = y + D px breaks {X, Y} = 0:
 *    {X, Y} = dX/dx dY/dpx = D cos D, and {Y, PX} = -dY/dpx dPX/dx = D sin D. */
#include <string.h>

#include "ham_test.h"

static hl_system *map_sys(const char *map, const char *pairs)
{
    const char *extra[] = {map, NULL};
    hl_system_spec spec = {NULL, pairs, NULL, extra, NULL};
    hl_system *sys = NULL;
    hl_error err;
    hl_error_clear(&err);
    if (hl_system_new(&sys, &spec, &err) != HL_OK) {
        fprintf(stderr, "system of '%s': %s\n", map, err.msg);
        exit(1);
    }
    return sys;
}

/* Run the check; *br gets the 2N x 2N matrix (caller frees, N2*N2 entries). */
static int canon(hl_alg **br, hl_system *sys, const char *map)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N2 = 2 * hl_system_ndof(sys), yes = -1;
    hl_alg *img = hl_alg_vec_new(N2, ctx);
    hl_error err;
    hl_error_clear(&err);
    *br = hl_alg_vec_new(N2 * N2, ctx);
    CHECK_MSG(hl_system_read_map(img, sys, map, &err) == HL_OK, "%s", err.msg);
    CHECK(hl_check_canonical(&yes, *br, img, sys, &err) == HL_OK);
    hl_alg_vec_free(img, N2, ctx);
    return yes;
}

static void one(const char *map, const char *pairs, int want, int a, int b, const char *val)
{
    hl_system *sys = map_sys(map, pairs);
    int N2 = 2 * hl_system_ndof(sys);
    hl_alg *br;
    int yes = canon(&br, sys, map);
    CHECK_MSG(yes == want, "canonical(%s) = %d", map, yes);
    if (val != NULL)
        CHECK_MSG(eq_formula(&br[a * N2 + b], sys, val), "bracket %d,%d of %s", a, b, map);
    hl_alg_vec_free(br, N2 * N2, hl_system_ctx(sys));
    hl_system_free(sys);
}

int main(void)
{
    one("X = x*cos(D) + p*sin(D); P = p*cos(D) - x*sin(D)", NULL, 1, 0, 1, "1");
    one("X = x + D*p; P = p - D*x", NULL, 0, 0, 1, "1 + D^2");
    one("x + D*p; p - D*x", NULL, 0, 1, 0, "-1 - D^2");   /* by order */
    one("x' = x + D*p; p' = p - D*x", NULL, 0, 0, 1, "1 + D^2"); /* primes */
    one("P = (sqrt(1 + 2*D*p) - 1)/D; Q = q*sqrt(1 + 2*D*p)", NULL, 1, 0, 1, "1");
    one("Q = q + D*q*p; P = p - D*p^2/2", NULL, 0, 0, 1, "1 - D^2*p^2");
    const char *pairs = "x:px,y:py";
    one("X = x*cos(D) + px*sin(D); Y = y + D*py; PX = px*cos(D) - x*sin(D); PY = py",
        pairs, 1, 0, 2, "1");
    one("X = x*cos(D) + px*sin(D); Y = y + D*px; PX = px*cos(D) - x*sin(D); PY = py",
        pairs, 0, 0, 1, "D*cos(D)");
    one("X = x*cos(D) + px*sin(D); Y = y + D*px; Px = px*cos(D) - x*sin(D); Py = py",
        pairs, 0, 1, 2, "D*sin(D)");
    return HL_TEST_END();
}
