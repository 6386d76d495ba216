/* Differentiation: exact results for simple cases (derived by hand from the
 * rules in diff.c), derivatives of every function and operator against
 * central finite differences of hl_expr_eval_d, random DAGs likewise, and a
 * DAG whose tree is exponentially large against forward-mode values. */
#include <math.h>
#include <stdlib.h>

#include "gen.h"
#include "hl_test.h"
#include "sx.h"

static const struct {
    const char *e, *var, *want;
} exact[] = {
    {"x^3*y", "x", "3*x^2*y"},
    {"x^3*y", "y", "x^3"},
    {"x^2 + 3*x + 1", "x", "2*x + 3"},
    {"p^2/2 + x^2/2", "p", "p"},
    {"p^2/2 + x^2/2", "x", "x"},
    {"sin(x)", "x", "cos(x)"},
    {"cos(x)", "x", "-sin(x)"},
    {"exp(2*x)", "x", "2*exp(2*x)"},
    {"log(x)", "x", "1/x"},
    {"x^y", "x", "y*x^(y - 1)"},
    {"x^y", "y", "x^y*log(x)"},
    {"5", "x", "0"},
    {"pi*x", "x", "pi"},
    {"-x^2", "x", "-(2*x)"},
    {"sqrt(x)", "x", "1/(2*sqrt(x))"},
    {"x^(1/2)", "x", "1/2*x^(-1/2)"},
    {"y", "x", "0"},
    {"x - x", "x", "0"},
    {"sin(y)", "x", "0"},
    {"0^x", "x", "0"},
};

/* Formulas valid for x, y in (0.1, 0.9). */
static const char *const numeric[] = {
    "x^3*y - 2*x*y^2 + 7", "(px^2 + py^2)/2 - 1/sqrt(x^2 + y^2)", "sin(x)*cos(y*x)",
    "tan(x)", "exp(-x^2/2)", "log(1 + x*y)", "sqrt(x + y)", "atan(x/y)", "asin(x*y)",
    "acos(x - y/2)", "sinh(x)", "cosh(2*x)", "tanh(x*y)", "x^y", "y^x", "x^x",
    "(x + 1)^(-3/2)", "-x^2", "x/(1 + x^2)", "1/x/y", "pi*x^2", "2^x", "x^-2",
    "--x*sin(x)", "log(x)^2", "exp(sin(x))^2 + x^(1/3)", "(x^2 - y)/(x + y)^2",
    "atan(x)^x", "sqrt(1 - x^2)*x", "cos(x)^2 + sin(x)^2",
};

static const char *const vars[] = {"x", "y", "px", "py"};

static double eval_at(const hl_expr *e, const double *v)
{
    double r = NAN;
    hl_expr_eval_d(&r, e, 4, vars, v, NULL);
    return r;
}

/* Central difference in x (v[0]) with step h. */
static double fd(const hl_expr *e, const double *v, double h)
{
    double p[4], m[4];
    memcpy(p, v, sizeof p);
    memcpy(m, v, sizeof m);
    p[0] += h;
    m[0] -= h;
    return (eval_at(e, p) - eval_at(e, m)) / (2 * h);
}

static double unit(uint64_t *s) /* in (0, 1) */
{
    *s = *s * 6364136223846793005ULL + 1442695040888963407ULL;
    return ((*s >> 11) + 0.5) / 9007199254740992.0;
}

static void check_exact(void)
{
    hl_pool *pool = hl_pool_new();
    for (size_t i = 0; i < sizeof exact / sizeof *exact; i++) {
        const hl_expr *e;
        CHECK(hl_parse(&e, pool, exact[i].e, NULL) == HL_OK);
        const hl_expr *d = hl_expr_diff(pool, e, exact[i].var);
        char *s = hl_expr_print(d, HL_STYLE_TEXT);
        CHECK_MSG(strcmp(s, exact[i].want) == 0, "d/d%s %s: got \"%s\", want \"%s\"",
                  exact[i].var, exact[i].e, s, exact[i].want);
        free(s);
    }
    /* the exact DAG, not only its spelling */
    const hl_expr *e;
    hl_parse(&e, pool, "x^3*y", NULL);
    CHECK(hl_expr_diff(pool, e, "x") == sx(pool, "(mul (mul 3 (pow x 2)) y)"));
    hl_pool_free(pool);
}

static void check_numeric(void)
{
    hl_pool *pool = hl_pool_new();
    uint64_t s = 42;
    for (size_t i = 0; i < sizeof numeric / sizeof *numeric; i++) {
        const hl_expr *e;
        hl_error err;
        CHECK_MSG(hl_parse(&e, pool, numeric[i], &err) == HL_OK, "%s: %s", numeric[i], err.msg);
        const hl_expr *d = hl_expr_diff(pool, e, "x");
        for (int k = 0; k < 5; k++) {
            double v[4] = {0.1 + 0.8 * unit(&s), 0.1 + 0.8 * unit(&s), unit(&s), unit(&s)};
            double got = eval_at(d, v), want = fd(e, v, 1e-5);
            CHECK_MSG(fabs(got - want) <= 1e-6 * (1 + fabs(want)), "d/dx %s at x=%g y=%g: %.12g vs %.12g",
                      numeric[i], v[0], v[1], got, want);
        }
    }
    hl_pool_free(pool);
}

/* Every subexpression finite and moderate at v: double overflow inside a
 * constant (543/0, (7/2)^788) is not the derivative's fault. */
static int tame(const hl_expr *e, const char *const *names, const double *v)
{
    double r;
    if (hl_expr_eval_d(&r, e, 8, names, v, NULL) || !isfinite(r) || fabs(r) > 1e6)
        return 0;
    if (e->kind == HL_POW && hl_expr_eval_d(&r, e->a, 8, names, v, NULL) == HL_OK && r <= 0)
        return 0; /* 0^b, (-2)^b: log(a) in the derivative, no real power around */
    if (e->kind == HL_FUN && (e->fun == HL_ASIN || e->fun == HL_ACOS) &&
        hl_expr_eval_d(&r, e->a, 8, names, v, NULL) == HL_OK && fabs(r) >= 1)
        return 0; /* asin(-1): the edge of the domain, derivative infinite */
    return (e->a == NULL || tame(e->a, names, v)) && (e->b == NULL || tame(e->b, names, v));
}

/* Random DAGs: where the function is smooth near the point (two step sizes
 * agree), the derivative must match. */
static void check_random(void)
{
    hl_pool *pool = hl_pool_new();
    gen g = {.s = 7, .small = 1};
    uint64_t s = 9;
    int compared = 0, bad = 0, nonzero = 0;
    static const char *const gvars[] = {"x", "y", "px", "q_1", "omega", "D", "e", "E"};
    for (int i = 0; i < 3000; i++) {
        const hl_expr *e = gen_expr(&g, pool, 1 + i % 5);
        const char *first;
        if (hl_expr_symbols(e, &first, 1) == 0)
            continue;
        int iv = 0; /* differentiate in the first symbol, perturb its value */
        while (strcmp(gvars[iv], first) != 0)
            iv++;
        const hl_expr *d = hl_expr_diff(pool, e, first);
        double v[8];
        for (int k = 0; k < 8; k++)
            v[k] = 0.2 + unit(&s);
        double f0, dv, p[8], m[8], f1, f2;
        if (!tame(e, gvars, v) || hl_expr_eval_d(&f0, e, 8, gvars, v, NULL))
            continue;
        double est[2];
        for (int j = 0; j < 2; j++) {
            double h = j ? 1e-4 : 1e-5;
            memcpy(p, v, sizeof p);
            memcpy(m, v, sizeof m);
            p[iv] += h;
            m[iv] -= h;
            hl_expr_eval_d(&f1, e, 8, gvars, p, NULL);
            hl_expr_eval_d(&f2, e, 8, gvars, m, NULL);
            est[j] = (f1 - f2) / (2 * h);
        }
        if (!isfinite(est[0]) || fabs(est[0] - est[1]) > 1e-7 * (1 + fabs(est[0])))
            continue; /* not smooth enough here to judge */
        if (hl_expr_eval_d(&dv, d, 8, gvars, v, NULL) != HL_OK)
            bad++;
        compared++;
        nonzero += fabs(est[0]) > 1e-6;
        if (!(fabs(dv - est[0]) <= 1e-6 * (1 + fabs(est[0])))) {
            char *t = hl_expr_print(e, HL_STYLE_TEXT);
            if (++bad < 12)
                fprintf(stderr, "d/d%s %s: %.12g vs %.12g\n", first, t, dv, est[0]);
            free(t);
        }
    }
    CHECK_MSG(bad == 0, "%d of %d random derivatives wrong", bad, compared);
    CHECK_MSG(compared > 1000, "only %d random derivatives compared", compared);
    CHECK_MSG(nonzero > 300, "only %d nonzero derivatives", nonzero);
    printf("%d random derivatives checked, %d of them nonzero\n", compared, nonzero);
    hl_pool_free(pool);
}

/* e_{k+1} = sin(e_k) + cos(e_k)*x: its tree has 2^k copies of e_0, the DAG
 * 5k nodes.  Forward mode in double gives the reference derivative. */
static void check_shared(void)
{
    hl_pool *pool = hl_pool_new();
    const hl_expr *x = hl_sym(pool, "x"), *e = x;
    double xv = 0.6, v = xv, dv = 1;
    for (int k = 0; k < 80; k++) {
        e = hl_add(pool, hl_call(pool, HL_SIN, e), hl_mul(pool, hl_call(pool, HL_COS, e), x));
        double nv = sin(v) + cos(v) * xv;
        dv = cos(v) * dv - sin(v) * dv * xv + cos(v);
        v = nv;
    }
    const hl_expr *d = hl_expr_diff(pool, e, "x");
    const char *names[] = {"x"};
    double got, got_v;
    CHECK(hl_expr_eval_d(&got_v, e, 1, names, &xv, NULL) == HL_OK);
    CHECK(hl_expr_eval_d(&got, d, 1, names, &xv, NULL) == HL_OK);
    CHECK_MSG(fabs(got_v - v) <= 1e-12 * (1 + fabs(v)), "%.17g vs %.17g", got_v, v);
    CHECK_MSG(fabs(got - dv) <= 1e-9 * (1 + fabs(dv)), "%.17g vs %.17g", got, dv);
    hl_pool_free(pool);
}

int main(void)
{
    check_exact();
    check_numeric();
    check_random();
    check_shared();
    return HL_TEST_END();
}
