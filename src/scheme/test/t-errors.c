/* Bad input: each rejected with a clear message (and a position where the
 * text has a bad spot), nothing leaked (the sanitizer build checks). */
#include "sch.h"

static hl_system *osc, *pend, *hh;

/* text, parsed as a language definition (kind 0), map (1) or equations (2),
 * then expanded; the failure must come with status st and mention want. */
static void bad(int kind, hl_system *sys, const char *text, int st, const char *want, int pos)
{
    hl_scheme *s = NULL;
    hl_error err;
    hl_error_clear(&err);
    int got = kind == 0   ? hl_scheme_from_text(&s, text, sys, &err)
              : kind == 1 ? hl_scheme_from_map(&s, text, sys, &err)
                          : hl_scheme_from_equations(&s, text, sys, &err);
    if (got == HL_OK) {
        CHECK(s != NULL);
        hl_series *Z = new_series(2 * s->N, hl_system_ctx(sys));
        got = hl_scheme_expand(Z, s, 4, &err);
        free_series(Z, 2 * s->N, hl_system_ctx(sys));
        hl_scheme_free(s);
    } else
        CHECK(s == NULL);
    if (getenv("HL_SHOW"))
        printf("%-50s -> %s\n", text, err.msg);
    CHECK_MSG(got == st, "'%s': status %d (%s), want %d", text, got, err.msg, st);
    CHECK_MSG(strstr(err.msg, want) != NULL, "'%s': message '%s' lacks '%s'", text, err.msg,
              want);
    if (pos >= 0)
        CHECK_MSG(err.pos == pos, "'%s': position %d, want %d", text, err.pos, pos);
}

int main(void)
{
    osc = make_system("(p^2 + x^2)/2");
    pend = make_system("p^2/2 - cos(q)");
    hh = make_system("(px^2 + py^2)/2 + (x^2 + y^2)/2 + x^2*y - y^3/3");

    /* language definitions */
    bad(0, pend, "Q = q + D*foo(q, p); P = p", HL_EINVAL, "unknown function 'foo'", 10);
    bad(0, pend, "Q = q + D*z; P = p", HL_EINVAL, "unknown name 'z'", 10);
    bad(0, hh, "Q = q + D*Hp(q, p)", HL_EINVAL, "wrong number of equations: 2 scalar equations "
                                                "for 4 unknowns (X, Y, PX, PY)", -1);
    bad(0, pend, "Q = q + D*Hp(q, p); P = p; k = p; Q = q", HL_EINVAL, "4 scalar equations for 3 unknowns (Q, P, k)",
        -1);
    bad(0, pend, "Q = q + D*Hp(q p); P = p", HL_EPARSE, "expected ','", 15);
    bad(0, pend, "Q = q + ; P = p", HL_EPARSE, "", 8);
    bad(0, pend, "Q = q + D*Hp(q, p); P = p - D*Hq(q, p); k = k + D", HL_EINVAL,
        "cannot determine the value of 'k' at D = 0", -1);
    bad(0, pend, "Q = q + D*int(s, int(t, p)); P = p", HL_EUNSUP, "int() inside an int()", -1);
    bad(0, pend, "Q = q + 1; P = p", HL_EINVAL, "not the identity at D = 0", -1);
    bad(0, pend, "Q = q + 2*D*Hp(q, p); P = p - D*Hq(q, p)", HL_EINVAL, "not consistent", -1);
    bad(0, pend, "k = p; k = q; Q = q; P = p", HL_EINVAL, "stage 'k' is defined twice", 7);

    /* maps and equations in the system's names */
    bad(1, osc, "X = x + 1; P = p", HL_EINVAL, "not the identity at D = 0: X = x + 1", -1);
    bad(1, osc, "X = x + 2*D*p; P = p - D*x", HL_EINVAL,
        "the D^1 coefficient of X is 2*p, the generator gives dH/dp = p", -1);
    bad(1, osc, "X = x + D*p", HL_EINVAL, "wrong number of equations", -1);
    bad(1, osc, "X = x + D*p; P = p - D*z", HL_EINVAL, "unknown symbol 'z'", 23);
    bad(1, osc, "X = x + D*p; x + D = p", HL_EINVAL, "must name the next value", 13);
    bad(1, osc, "X = x + D*p; X = p", HL_EINVAL, "gives an image twice", -1);
    /* implicit: the solver's messages */
    bad(2, osc, "(X - x)*(1 + D) = 1 + D*p; P - p = -D*x", HL_EINVAL,
        "not the identity at D = 0", -1);
    bad(2, osc, "(X - x)^2 = D^2*p^2; P - p = -D*x", HL_EINVAL, "does not determine", -1);

    /* catalog refusals */
    {
        hl_scheme *s = NULL;
        hl_error err;
        CHECK(hl_scheme_new(&s, "exact-rotation", 0, pend, &err) == HL_EINVAL && s == NULL);
        CHECK(strstr(err.msg, "only valid for the one-dof oscillator") != NULL);
        CHECK(hl_scheme_new(&s, "paper-dg", 0, hh, &err) == HL_EINVAL && s == NULL);
        CHECK(hl_scheme_new(&s, "no-such", 0, pend, &err) == HL_EINVAL && s == NULL);
        CHECK(strstr(err.msg, "unknown scheme 'no-such' (known: euler,") != NULL);
        CHECK(hl_scheme_new(&s, "exact-rotation", 0, osc, &err) == HL_OK && s != NULL);
        hl_scheme_free(s);
    }
    hl_system_free(osc);
    hl_system_free(pend);
    hl_system_free(hh);
    return HL_TEST_END();
}
