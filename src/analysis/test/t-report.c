/* hl_analysis_compute on the oscillator H = (p^2 + x^2)/2 against results
 * derived by hand (paper §4), not from the code:
 *   explicit Euler, psi = M z with M = [[1, D], [-D, 1]] = sqrt(1+D^2) R(atan D):
 *     order 1, v_2 = x d/dx + p d/dp (a scaling by 1, not Hamiltonian);
 *     K(D) = (d/dD psi)(psi_{-D} z) = (p + D x, D p - x);
 *     D f~ = log M = ln(1+D^2)/2 I + atan(D) J, so f_2 = z/2, f_3 = -g/3,
 *     f_4 = -z/4, f_5 = g/5 (no modified Hamiltonian: f_2 is a scaling);
 *     v_2 has no polynomial invariant (it scales every monomial);
 *     corrected with v_2..v_4 it is RK4: (1 - D^2/2 + D^4/24) z + (D - D^3/6) J z,
 *     of order 4 with v_5 = -g;
 *   implicit midpoint, the rotation by tau = 2 atan(D/2) = D - D^3/12 + D^5/80 - ...:
 *     order 2, v_3 = -g/2 (time shift c = -1/2, Hamiltonian with h = -H/2);
 *     tau's series; tan(tau/2) = D/2, two steps one of 2D/(1 - D^2/4);
 *     f~ = (tau/D) g: f_2 = f_4 = 0, f_3 = -g/12, f_5 = g/80, H~ = (tau/D) H;
 *   exact-rotation: no error to the order computed, tau = D.
 * Also: a budget of 1 term leaves the check out but not the v_k. */
#include <stdlib.h>

#include "hamlie/analysis.h"
#include "hamlie/report.h"
#include "hamlie/scheme.h"
#include "hl_test.h"
#include "analysis_test.h"

#define OSC "(p^2+x^2)/2"

/* Is a equal to the formula text (in x, p, D)? */
static int is(const hl_alg *a, const char *text, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg want;
    hl_error err;
    hl_alg_init(&want, ctx);
    int ok = hl_system_read(&want, sys, text, &err) == HL_OK && hl_alg_equal(a, &want, ctx);
    if (!ok) {
        char *got = hl_format_alg(a, ctx, hl_system_pool(sys), HL_STYLE_TEXT);
        fprintf(stderr, "  got %s, want %s\n", got, text);
        free(got);
    }
    hl_alg_clear(&want, ctx);
    return ok;
}

/* A two-component field (x, p) equal to the formulas cx, cp? */
static int is2(const hl_alg *v, const char *cx, const char *cp, hl_system *sys)
{
    return is(&v[0], cx, sys) && is(&v[1], cp, sys);
}

static hl_analysis *analyse(hl_scheme **s, const char *name, const hl_analysis_opts *o,
                            hl_system *sys)
{
    hl_analysis *A = NULL;
    hl_error err;
    if (hl_scheme_new(s, name, 0, sys, &err) != HL_OK ||
        hl_analysis_compute(&A, o, *s, sys, &err) != HL_OK) {
        fprintf(stderr, "%s: %s\n", name, err.msg);
        exit(2);
    }
    return A;
}

static void test_euler(hl_system *sys)
{
    hl_analysis_opts o;
    hl_analysis_opts_default(&o);
    o.order = 6;
    o.correct = 4;
    hl_scheme *s;
    hl_analysis *A = analyse(&s, "euler", &o, sys);
    CHECK(A->fields.checked && A->fields.agree);
    CHECK(A->fields.order == 1 && A->fields.leading == 2);
    CHECK(A->have_leading && A->leading.kind == HL_ERRFIELD_SCALING);
    CHECK(A->have_leading && is2(A->leading.scale, "1", "1", sys) && !A->leading.hamiltonian);
    CHECK(is2(hl_vfields_v(&A->fields, 2), "x", "p", sys));
    CHECK(A->closed && is2(A->map, "x + D*p", "p - D*x", sys));
    CHECK(A->have_K && is2(A->K, "p + D*x", "D*p - x", sys));
    CHECK(A->K_series != NULL && A->K_series[0].n >= o.order);
    CHECK(A->inv_poly_applicable && A->n_inv_poly == 0);
    CHECK(!A->tried_tau); /* a scaling is no time shift */
    CHECK(A->nmod == 5 && !A->mod_H_all);
    CHECK(is2(A->mod_fields + 1 * 2, "p", "-x", sys));
    CHECK(is2(A->mod_fields + 2 * 2, "x/2", "p/2", sys));
    CHECK(is2(A->mod_fields + 3 * 2, "-p/3", "x/3", sys));
    CHECK(is2(A->mod_fields + 4 * 2, "-x/4", "-p/4", sys));
    CHECK(is2(A->mod_fields + 5 * 2, "p/5", "-x/5", sys));
    CHECK(A->correct == 4 && A->cmap != NULL);
    CHECK(A->cmap != NULL && is2(A->cmap, "(1 - D^2/2 + D^4/24)*x + (D - D^3/6)*p",
                                 "(1 - D^2/2 + D^4/24)*p - (D - D^3/6)*x", sys));
    CHECK(A->have_cfields && A->cfields.order == 4 && A->cfields.leading == 5);
    CHECK(A->have_cleading && A->cleading.kind == HL_ERRFIELD_TIME_SHIFT &&
          is(&A->cleading.lambda, "-1", sys));
    hl_analysis_free(A);
    hl_scheme_free(s);
}

static void test_midpoint(hl_system *sys)
{
    hl_analysis_opts o;
    hl_analysis_opts_default(&o);
    o.order = 6;
    hl_scheme *s;
    hl_analysis *A = analyse(&s, "implicit-midpoint", &o, sys);
    CHECK(A->fields.agree && A->fields.order == 2 && A->fields.leading == 3);
    CHECK(A->have_leading && A->leading.kind == HL_ERRFIELD_TIME_SHIFT &&
          is(&A->leading.lambda, "-1/2", sys));
    CHECK(A->have_leading && A->leading.hamiltonian && A->leading.have_h &&
          is(&A->leading.h, "-(p^2+x^2)/4", sys));
    CHECK(!A->closed && A->map == NULL); /* implicit: no closed map */
    CHECK(A->tried_tau && A->tau_ok);
    hl_alg t;
    hl_alg_init(&t, hl_system_ctx(sys));
    hl_series_to_alg(&t, &A->tau, hl_system_var_D(sys), hl_system_ctx(sys));
    CHECK(is(&t, "D - D^3/12 + D^5/80", sys));
    hl_alg_clear(&t, hl_system_ctx(sys));
    CHECK(A->tau_closed && A->tau_series_only && A->have_D2);
    CHECK(A->tau_closed && is(&A->tau_forms[1], "D/2", sys));
    CHECK(A->have_D2 && is(&A->tau_forms[2], "2*D/(1 - D^2/4)", sys));
    CHECK(A->nmod == 5 && A->mod_H_all);
    CHECK(is2(A->mod_fields + 2 * 2, "0", "0", sys));
    CHECK(is2(A->mod_fields + 3 * 2, "-p/12", "x/12", sys));
    CHECK(is2(A->mod_fields + 4 * 2, "0", "0", sys));
    CHECK(is2(A->mod_fields + 5 * 2, "p/80", "-x/80", sys));
    CHECK(is(&A->mod_H[3], "-(p^2+x^2)/24", sys) && is(&A->mod_H[5], "(p^2+x^2)/160", sys));
    hl_analysis_free(A);
    hl_scheme_free(s);
}

static void test_exact_and_budget(hl_system *sys)
{
    hl_analysis_opts o;
    hl_analysis_opts_default(&o);
    o.order = 5;
    hl_scheme *s;
    hl_analysis *A = analyse(&s, "exact-rotation", &o, sys);
    CHECK(A->fields.leading == 0 && A->fields.order == 5 && !A->have_leading);
    CHECK(A->tried_tau && A->tau_ok);
    hl_analysis_free(A);
    hl_scheme_free(s);

    /* a budget too small for the K route: one way only, same v_k */
    o.K_route_budget = 1;
    o.parts = 0;
    A = analyse(&s, "rk4", &o, sys);
    CHECK(A->fields.over_budget && !A->fields.checked);
    CHECK(A->fields.leading == 5 && is2(hl_vfields_v(&A->fields, 5), "-p", "x", sys));
    CHECK(A->map == NULL && A->mod_fields == NULL && !A->tried_tau);
    hl_analysis_free(A);
    hl_scheme_free(s);

    /* the options are checked */
    hl_error err;
    o.order = 41;
    CHECK(hl_scheme_new(&s, "euler", 0, sys, &err) == HL_OK);
    A = (hl_analysis *)&o; /* must be set to NULL */
    CHECK(hl_analysis_compute(&A, &o, s, sys, &err) == HL_EINVAL && A == NULL);
    hl_scheme_free(s);
    hl_analysis_free(NULL);

    /* no options: the defaults (order 4, every part) */
    CHECK(hl_scheme_new(&s, "euler", 0, sys, &err) == HL_OK);
    CHECK(hl_analysis_compute(&A, NULL, s, sys, &err) == HL_OK && A->n == 4 && A->closed &&
          A->nmod == 4 && A->fields.leading == 2);
    hl_analysis_free(A);
    hl_scheme_free(s);
}

int main(void)
{
    hl_system *sys = make_system(OSC);
    test_euler(sys);
    test_midpoint(sys);
    test_exact_and_budget(sys);
    hl_system_free(sys);
    return HL_TEST_END();
}
