/* K(D) in closed form and the corrected scheme, on the oscillator.
 *  - Euler: psi = (x + D p, p - D x), psi_{-D} = (x - D p, p + D x),
 *    d psi/dD = (p, -x), so K = (p + D x, -x + D p) (by hand); its Taylor
 *    coefficients must equal hl_series_scheme_K's.
 *  - Euler with v_2..v_4 subtracted is RK4 exactly: on a linear system RK4 is
 *    the degree-4 Taylor polynomial of the flow, and Euler minus
 *    sum_{k=2}^4 D^k/k! v_k = Euler - (its D^2..D^4 terms) + (the flow's):
 *    compared with the rk4 catalog scheme's expansion to D^12 (both are
 *    polynomials of degree 4 in D) and with the map typed here; the corrected
 *    scheme, re-analysed, has order 4. */
#include <stdlib.h>

#include "hamlie/analysis.h"
#include "hamlie/scheme.h"
#include "hl_test.h"

#define NN 13

static hl_series *expand(hl_system *sys, const char *name, int n)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_series *Z = malloc(2 * sizeof *Z);
    hl_scheme *s;
    hl_error err;
    hl_series_init(&Z[0], 0, ctx);
    hl_series_init(&Z[1], 0, ctx);
    if (hl_scheme_new(&s, name, 0, sys, &err) != HL_OK || hl_scheme_expand(Z, s, n, &err) != HL_OK) {
        fprintf(stderr, "%s: %s\n", name, err.msg);
        exit(2);
    }
    hl_scheme_free(s);
    return Z;
}

static void free2(hl_series *Z, hl_alg_ctx *ctx)
{
    hl_series_clear(&Z[0], ctx);
    hl_series_clear(&Z[1], ctx);
    free(Z);
}

int main(void)
{
    hl_system *sys;
    hl_error err;
    hl_system_spec spec = {"(p^2+x^2)/2", NULL, NULL, NULL, NULL};
    if (hl_system_new(&sys, &spec, &err) != HL_OK)
        return 2;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int vars[2] = {0, 1}, vD = hl_system_var_D(sys);

    /* closed-form map of Euler and its K */
    hl_scheme *s;
    CHECK(hl_scheme_new(&s, "euler", 0, sys, &err) == HL_OK);
    hl_alg *img = hl_alg_vec_new(2, ctx), *K = hl_alg_vec_new(2, ctx), *w = hl_alg_vec_new(2, ctx);
    CHECK(hl_errors_scheme_map(img, s, &err) == HL_OK);
    CHECK(hl_system_read(&w[0], sys, "x + D*p", &err) == HL_OK);
    CHECK(hl_system_read(&w[1], sys, "p - D*x", &err) == HL_OK);
    CHECK(hl_alg_equal(&img[0], &w[0], ctx) && hl_alg_equal(&img[1], &w[1], ctx));
    CHECK(hl_errors_K_closed(K, img, sys, &err) == HL_OK);
    CHECK(hl_system_read(&w[0], sys, "p + D*x", &err) == HL_OK);
    CHECK(hl_system_read(&w[1], sys, "-x + D*p", &err) == HL_OK);
    CHECK(hl_alg_equal(&K[0], &w[0], ctx) && hl_alg_equal(&K[1], &w[1], ctx));
    hl_series *E = expand(sys, "euler", NN), *Ks = expand(sys, "euler", NN);
    CHECK(hl_series_scheme_K(Ks, 2, E, vars, vD, ctx, &err) == HL_OK);
    for (int i = 0; i < 2; i++) {
        hl_series ks;
        hl_series_init(&ks, 0, ctx);
        CHECK(hl_series_from_alg(&ks, &K[i], vD, NN - 1, ctx, &err) == HL_OK);
        CHECK(hl_series_equal(&ks, &Ks[i], ctx) && Ks[i].n == NN - 1);
        hl_series_clear(&ks, ctx);
    }

    /* corrected Euler = RK4 */
    hl_vfields e;
    CHECK(hl_vfields_compute(&e, E, sys, 4, &err) == HL_OK && e.agree);
    hl_series *C = expand(sys, "euler", NN), *R = expand(sys, "rk4", NN);
    hl_errors_correct_series(C, E, &e, 4, sys);
    CHECK(C[0].n == NN && hl_series_equal(&C[0], &R[0], ctx) && hl_series_equal(&C[1], &R[1], ctx));
    hl_errors_correct_map(img, &e, 4, sys);
    CHECK(hl_system_read(&w[0], sys, "(1 - D^2/2 + D^4/24)*x + (D - D^3/6)*p", &err) == HL_OK);
    CHECK(hl_system_read(&w[1], sys, "(1 - D^2/2 + D^4/24)*p - (D - D^3/6)*x", &err) == HL_OK);
    CHECK(hl_alg_equal(&img[0], &w[0], ctx) && hl_alg_equal(&img[1], &w[1], ctx));
    hl_vfields e2;
    CHECK(hl_vfields_compute(&e2, C, sys, 7, &err) == HL_OK);
    CHECK(e2.agree && e2.order == 4);
    hl_vfields_clear(&e2, sys);
    hl_vfields_clear(&e, sys);

    /* an implicit scheme has no closed-form map */
    hl_scheme *mid;
    CHECK(hl_scheme_new(&mid, "implicit-midpoint", 0, sys, &err) == HL_OK);
    CHECK(hl_errors_scheme_map(img, mid, &err) == HL_EINVAL);
    hl_scheme_free(mid);

    free2(E, ctx);
    free2(Ks, ctx);
    free2(C, ctx);
    free2(R, ctx);
    hl_alg_vec_free(img, 2, ctx);
    hl_alg_vec_free(K, 2, ctx);
    hl_alg_vec_free(w, 2, ctx);
    hl_scheme_free(s);
    hl_system_free(sys);
    return HL_TEST_END();
}
