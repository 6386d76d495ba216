/* The scheme reader (read.c) as a pass over the formula parser's tree: the
 * positions of its refusals (the caret of every kind of error), the values
 * it gives (vectors componentwise, a scalar with every component, an
 * integrand's variable inside its int() only), and the functions of two
 * arguments the formula grammar brings (atan2). */
#include "sch.h"

static const struct {
    const char *text;
    int status, pos;
    const char *msg; /* the start of the message */
} bad[] = {
    {"Q = q + D*foo(q, p); P = p", HL_EINVAL, 10, "unknown function 'foo'"},
    {"Q = q + D*z; P = p", HL_EINVAL, 10, "unknown name 'z'"},
    {"Q = q + D*Hp(q p); P = p", HL_EPARSE, 15, "expected ','"},
    {"Q = q + D*Hp(q); P = p", HL_EPARSE, 14, "expected ',': 'Hp' takes two arguments"},
    {"Q = q + D*Hp(q, p, p); P = p", HL_EPARSE, 17, "'Hp' takes two arguments"},
    {"Q = q + D*int(s, int(t, p)); P = p", HL_EUNSUP, 17, "an int() inside an int()"},
    {"Q = q + D*int(2, p); P = p", HL_EPARSE, 14, "expected the integration variable"},
    {"Q = q + D*int(H(q, p), p); P = p", HL_EPARSE, 14, "expected the integration variable"},
    /* the variable is bound inside its int() only: the caret skips it */
    {"Q = q + D*int(s, s*p) + s; P = p", HL_EINVAL, 24, "unknown name 's'"},
    {"Q = q + D*int(s, s*p); P = p - s*int(s, s)", HL_EINVAL, 31, "unknown name 's'"},
    {"k = p; k = q; Q = q; P = p", HL_EINVAL, 7, "stage 'k' is defined twice"},
    {"Q = q + D*p; P = p - D*q; w", HL_EPARSE, 27, "expected '=', found 'end of formula'"},
    {"Q = q + D*(p; P = p", HL_EPARSE, 12, "expected ')' to close '('"},
    {"Q = q + D*p); P = p", HL_EPARSE, 11, "unmatched ')'"},
    {"Q = q + D*$; P = p", HL_EPARSE, 10, "unexpected character '$'"},
    {"Q = q + D*sin(q, p); P = p", HL_EPARSE, 15, "'sin' takes one argument"},
    {"Q = q = p; P = p", HL_EPARSE, 6, "only one '=' is allowed"},
};

static void check_bad(hl_system *pend)
{
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        hl_scheme *s = NULL;
        hl_error err;
        int st = hl_scheme_from_text(&s, bad[i].text, pend, &err);
        CHECK_MSG(st == bad[i].status && err.pos == bad[i].pos, "'%s': status %d at %d (%s)",
                  bad[i].text, st, err.pos, err.msg);
        CHECK_MSG(strncmp(err.msg, bad[i].msg, strlen(bad[i].msg)) == 0, "'%s': '%s'", bad[i].text,
                  err.msg);
        CHECK(err.src == bad[i].text && s == NULL);
    }
}

/* The right side of the equation that defines the unknown shown as `name`,
 * printed. */
static char *rhs_of(const hl_scheme *s, const char *name)
{
    for (int i = 0; i < s->m; i++)
        if (s->defines[i] >= 0 && strcmp(s->display[s->defines[i]], name) == 0)
            return hl_expr_print(s->rhs[i], HL_STYLE_TEXT);
    return NULL;
}

static void check_rhs(const hl_scheme *s, const char *name, const char *want)
{
    char *got = rhs_of(s, name);
    CHECK_MSG(got != NULL && strcmp(got, want) == 0, "%s = %s, want %s", name, got, want);
    free(got);
}

static hl_scheme *read_ok(hl_system *sys, const char *text)
{
    hl_scheme *s = NULL;
    hl_error err;
    CHECK_MSG(hl_scheme_from_text(&s, text, sys, &err) == HL_OK, "'%s': %s", text, err.msg);
    return s;
}

static void check_values(hl_system *hh)
{
    /* componentwise, a scalar with every component; atan2 pairs the
     * components of its two vector arguments */
    hl_scheme *s = read_ok(hh, "Q = q + D*atan2(p, q); P = p - D*dot(q, q)*q");
    if (s != NULL) {
        check_rhs(s, "X", "x + D*atan2(px, x)");
        check_rhs(s, "Y", "y + D*atan2(py, y)");
        check_rhs(s, "PX", "px - D*(x*x + y*y)*x");
        check_rhs(s, "PY", "py - D*(x*x + y*y)*y");
    }
    hl_scheme_free(s);
    /* a stage is a vector of unknowns; H(a, b) a scalar at the point (a, b) */
    s = read_ok(hh, "k = H(q, 2*p)*q; Q = q + D*k; P = p");
    if (s != NULL) {
        check_rhs(s, "X", "x + D*k#1");
        check_rhs(s, "k[2]", "(y*x^2 + ((2*px)^2 + (2*py)^2)/2 + (x^2 + y^2)/2 - y^3/3)*y");
    }
    hl_scheme_free(s);
    /* the integrand's variable is s# inside int(); the same name outside
     * it (here a stage) keeps its own meaning */
    s = read_ok(hh, "u = p; Q = q + D*int(u, u*u)*Hp(q, u); P = p");
    if (s != NULL) {
        CHECK(s->nint == 1);
        char *body = s->nint == 1 ? hl_expr_print(s->int_body[0], HL_STYLE_TEXT) : NULL;
        CHECK_MSG(body != NULL && strcmp(body, "s#*s#") == 0, "integrand %s", body);
        free(body);
        check_rhs(s, "X", "x + D*I#1*u#1");
    }
    hl_scheme_free(s);
}

int main(void)
{
    hl_system *pend = make_system("p^2/2 - cos(q)");
    hl_system *hh = make_system("(px^2 + py^2)/2 + (x^2 + y^2)/2 + x^2*y - y^3/3");
    check_bad(pend);
    check_values(hh);
    hl_system_free(pend);
    hl_system_free(hh);
    return HL_TEST_END();
}
