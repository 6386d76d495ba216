/* Printers: exact strings in each style for a hand-written table; symbol
 * names in LaTeX; then two checks by other programs: sympy reads the SYMPY
 * strings and a C compiler compiles the C strings, and both must give the
 * value hl_expr_eval_d gives at a point (skipped, and said so, if python3
 * with sympy or cc is missing). */
#include <math.h>
#include <stdlib.h>
#include <unistd.h>

#include "gen.h"
#include "hl_test.h"
#include "expr/sympy_names.h"
#include "sx.h"

static const struct {
    const char *e, *text, *latex, *sympy, *c;
} table[] = {
    {"(add x (mul D p))", "x + D*p", "x + D\\,p", "x + D*p", "x + D*p"},
    {"(neg (pow x 2))", "-x^2", "-x^{2}", "-x**2", "-pow(x, 2.0)"},
    {"(pow x -1/2)", "x^(-1/2)", "x^{-\\frac{1}{2}}", "x**(-1/2)", "pow(x, (-1.0/2.0))"},
    {"(pow (add x 1) 2)", "(x + 1)^2", "\\left(x + 1\\right)^{2}", "(x + 1)**2",
     "pow(x + 1.0, 2.0)"},
    {"(sub a (sub b c))", "a - (b - c)", "a - \\left(b - c\\right)", "a - (b - c)",
     "a - (b - c)"},
    {"(div a (mul b c))", "a/(b*c)", "\\frac{a}{b\\,c}", "a/(b*c)", "a/(b*c)"},
    {"(mul -3 x)", "-3*x", "-3\\,x", "-3*x", "-3.0*x"},
    {"(pow 2/3 x)", "(2/3)^x", "\\left(\\frac{2}{3}\\right)^{x}", "(2/3)**x",
     "pow((2.0/3.0), x)"},
    {"(neg -2)", "--2", "-\\left(-2\\right)", "-(-2)", "-(-2.0)"},
    {"(neg (neg x))", "--x", "-\\left(-x\\right)", "-(-x)", "-(-x)"},
    {"(mul 2 3)", "2*3", "2 \\cdot 3", "2*3", "2.0*3.0"},
    {"(mul x 2)", "x*2", "x \\cdot 2", "x*2", "x*2.0"},
    {"(mul 2 (pow x 2))", "2*x^2", "2\\,x^{2}", "2*x**2", "2.0*pow(x, 2.0)"},
    {"(sin q)", "sin(q)", "\\sin q", "sin(q)", "sin(q)"},
    {"(sin (add q 1))", "sin(q + 1)", "\\sin\\left(q + 1\\right)", "sin(q + 1)",
     "sin(q + 1.0)"},
    {"(pow (sin x) 2)", "sin(x)^2", "\\sin^{2} x", "sin(x)**2", "pow(sin(x), 2.0)"},
    {"(pow (sin x) -1)", "sin(x)^(-1)", "\\left(\\sin x\\right)^{-1}", "sin(x)**(-1)",
     "pow(sin(x), -1.0)"},
    {"(sqrt (add (pow x 2) (pow y 2)))", "sqrt(x^2 + y^2)", "\\sqrt{x^{2} + y^{2}}",
     "sqrt(x**2 + y**2)", "sqrt(pow(x, 2.0) + pow(y, 2.0))"},
    {"(atan x)", "atan(x)", "\\arctan x", "atan(x)", "atan(x)"},
    {"(acos (asin x))", "acos(asin(x))", "\\arccos\\left(\\arcsin x\\right)",
     "acos(asin(x))", "acos(asin(x))"},
    {"(tanh (cosh (sinh 2)))", "tanh(cosh(sinh(2)))",
     "\\tanh\\left(\\cosh\\left(\\sinh 2\\right)\\right)", "tanh(cosh(sinh(2)))",
     "tanh(cosh(sinh(2.0)))"},
    {"(exp (neg (pow x 2)))", "exp(-x^2)", "\\exp\\left(-x^{2}\\right)", "exp(-x**2)",
     "exp(-pow(x, 2.0))"},
    {"(log (tan x))", "log(tan(x))", "\\log\\left(\\tan x\\right)", "log(tan(x))",
     "log(tan(x))"},
    {"pi", "pi", "\\pi", "pi", "M_PI"},
    {"(mul (mul 2 pi) omega)", "2*pi*omega", "2\\,\\pi\\,\\omega", "2*pi*omega",
     "2.0*M_PI*omega"},
    {"(div 2 3)", "2/(3)", "\\frac{2}{3}", "2/3", "2.0/3.0"},
    {"-2/3", "-2/3", "-\\frac{2}{3}", "-2/3", "(-2.0/3.0)"},
    {"(neg 3)", "-(3)", "-3", "-3", "-3.0"},
    {"(mul x -3)", "x*(-3)", "x \\cdot \\left(-3\\right)", "x*(-3)", "x*(-3.0)"},
    {"(sub x -2/3)", "x - (-2/3)", "x - \\left(-\\frac{2}{3}\\right)", "x - (-2/3)",
     "x - (-2.0/3.0)"},
    {"(add x (neg y))", "x + (-y)", "x + \\left(-y\\right)", "x + (-y)", "x + (-y)"},
    {"(div (mul 2 x) (add x 1))", "2*x/(x + 1)", "\\frac{2\\,x}{x + 1}", "2*x/(x + 1)",
     "2.0*x/(x + 1.0)"},
    {"(pow x (pow y z))", "x^y^z", "x^{y^{z}}", "x**y**z", "pow(x, pow(y, z))"},
    {"(pow (pow x y) z)", "(x^y)^z", "\\left(x^{y}\\right)^{z}", "(x**y)**z",
     "pow(pow(x, y), z)"},
    {"(pow (neg x) 2)", "(-x)^2", "\\left(-x\\right)^{2}", "(-x)**2", "pow(-x, 2.0)"},
    {"(neg (add x y))", "-(x + y)", "-\\left(x + y\\right)", "-(x + y)", "-(x + y)"},
    {"(mul (neg x) y)", "-x*y", "-x\\,y", "-x*y", "-x*y"},
    {"(neg (mul x y))", "-(x*y)", "-x\\,y", "-(x*y)", "-(x*y)"},
    {"(mul (add a b) (sub a b))", "(a + b)*(a - b)",
     "\\left(a + b\\right)\\,\\left(a - b\\right)", "(a + b)*(a - b)", "(a + b)*(a - b)"},
    {"(mul omega q1)", "omega*q1", "\\omega\\,q_{1}", "omega*q1", "omega*q1"},
    {"(add p_2 px)", "p_2 + px", "p_{2} + p_{x}", "p_2 + px", "p_2 + px"},
    {"(mul E lambda)", "E*lambda", "E\\,\\lambda", "Symbol('E')*Symbol('lambda')",
     "E*lambda"},
    {"(mul 2 1/2)", "2*(1/2)", "2 \\cdot \\frac{1}{2}", "2*(1/2)", "2.0*(1.0/2.0)"},
    {"(mul x -1/2)", "x*(-1/2)", "x \\cdot \\left(-\\frac{1}{2}\\right)", "x*(-1/2)",
     "x*(-1.0/2.0)"},
    {"(sin 2/3)", "sin(2/3)", "\\sin\\left(\\frac{2}{3}\\right)", "sin(2/3)", "sin(2.0/3.0)"},
    {"(div 1 (mul 2 m))", "1/(2*m)", "\\frac{1}{2\\,m}", "1/(2*m)", "1.0/(2.0*m)"},
    {"(div (div a b) c)", "a/b/c", "\\frac{\\frac{a}{b}}{c}", "a/b/c", "a/b/c"},
    {"(sub (div (add (pow px 2) (pow py 2)) 2) (div 1 (sqrt (add (pow x 2) (pow y 2)))))",
     "(px^2 + py^2)/2 - 1/sqrt(x^2 + y^2)",
     "\\frac{p_{x}^{2} + p_{y}^{2}}{2} - \\frac{1}{\\sqrt{x^{2} + y^{2}}}",
     "(px**2 + py**2)/2 - 1/sqrt(x**2 + y**2)",
     "(pow(px, 2.0) + pow(py, 2.0))/2.0 - 1.0/sqrt(pow(x, 2.0) + pow(y, 2.0))"},
};

static const struct {
    const char *name, *latex;
} names[] = {
    {"omega", "\\omega"}, {"Omega", "\\Omega"}, {"q1", "q_{1}"}, {"q12", "q_{12}"},
    {"p_2", "p_{2}"}, {"px", "p_{x}"}, {"x", "x"}, {"H", "H"}, {"mass", "\\mathrm{mass}"},
    {"mass2", "\\mathrm{mass}_{2}"}, {"theta12", "\\theta_{12}"}, {"ptheta", "p_{\\theta}"},
    {"x_old", "x_{\\mathrm{old}}"}, {"a_b_c", "a_{b_{c}}"}, {"alpha_1", "\\alpha_{1}"},
    {"x_", "\\mathrm{x\\_}"}, {"lambda", "\\lambda"}, {"p_x", "p_{x}"},
};

static void check_table(void)
{
    hl_pool *pool = hl_pool_new();
    for (size_t i = 0; i < sizeof table / sizeof *table; i++) {
        const hl_expr *e = sx(pool, table[i].e);
        const char *want[4] = {table[i].text, table[i].latex, table[i].sympy, table[i].c};
        for (int st = 0; st < 4; st++) {
            char *s = hl_expr_print(e, (hl_style)st);
            CHECK_MSG(strcmp(s, want[st]) == 0, "%s style %d: got \"%s\", want \"%s\"",
                      table[i].e, st, s, want[st]);
            free(s);
        }
    }
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        char *s = hl_symbol_latex(names[i].name);
        CHECK_STR(s, names[i].latex);
        free(s);
    }
    hl_pool_free(pool);
}

/* Every reserved name prints as Symbol('name') (the lookup is a binary
 * search: an entry out of order would be missed), names next to them do
 * not, and the table is in strcmp order. */
static void check_sympy_reserved(void)
{
    hl_pool *pool = hl_pool_new();
    size_t n = sizeof hl_sympy_reserved / sizeof *hl_sympy_reserved;
    for (size_t i = 0; i < n; i++) {
        const char *name = hl_sympy_reserved[i];
        if (i > 0)
            CHECK_MSG(strcmp(hl_sympy_reserved[i - 1], name) < 0, "table out of order at %s", name);
        char *s = hl_expr_print(hl_sym(pool, name), HL_STYLE_SYMPY), want[64];
        snprintf(want, sizeof want, "Symbol('%s')", name);
        CHECK_STR(s, want);
        free(s);
    }
    static const char *const plain[] = {"A", "Ab", "Absx", "x", "px", "zz", "zzz", "e", "Ea"};
    for (size_t i = 0; i < sizeof plain / sizeof *plain; i++) {
        char *s = hl_expr_print(hl_sym(pool, plain[i]), HL_STYLE_SYMPY);
        CHECK_STR(s, plain[i]);
        free(s);
    }
    hl_pool_free(pool);
}

/* ---- other programs read our output --------------------------------------- */

static const char *const vars[] = {"x", "y", "px", "q_1", "omega", "D", "e", "E"};
static const double point[] = {0.7, -1.3, 0.45, 2.1, 1.7, 0.3, 1.1, -0.6};

#define NSAMPLE 300

/* Well conditioned at point: every subexpression has a moderate value, so
 * double rounding cannot explain a disagreement (sin(1e30) could). */
static int tame(const hl_expr *e)
{
    double v;
    if (hl_expr_eval_d(&v, e, 8, vars, point, NULL) != HL_OK || !isfinite(v) ||
        fabs(v) > 1e3 || (v != 0 && fabs(v) < 1e-3))
        return 0;
    return (e->a == NULL || tame(e->a)) && (e->b == NULL || tame(e->b));
}

/* Random well-conditioned expressions and their values at point. */
static int sample(hl_pool *pool, const hl_expr **out, double *val)
{
    gen g = {.s = 99, .small = 1};
    int n = 0;
    while (n < NSAMPLE) {
        const hl_expr *e = gen_expr(&g, pool, 1 + n % 5);
        double v;
        if (tame(e) && hl_expr_eval_d(&v, e, 8, vars, point, NULL) == HL_OK) {
            out[n] = e;
            val[n++] = v;
        }
    }
    return n;
}

static int run(const char *cmd)
{
    int r = system(cmd);
    return r;
}

static void check_sympy(hl_pool *pool, const hl_expr **es, const double *vals, int n)
{
    if (run("python3 -c 'import sympy' >/dev/null 2>&1") != 0) {
        printf("skipped: python3 with sympy not found\n");
        return;
    }
    char in[] = "/tmp/hl-sympy-XXXXXX";
    int fd = mkstemp(in);
    FILE *f = fdopen(fd, "w");
    fprintf(f, "import sympy, sys\n"
               "names = ['x','y','px','q_1','omega','D','e','E']\n"
               "vals = [0.7,-1.3,0.45,2.1,1.7,0.3,1.1,-0.6]\n"
               "subs = {sympy.Symbol(a): sympy.Float(v, 30) for a, v in zip(names, vals)}\n"
               "exprs = [\n");
    for (int i = 0; i < n; i++) {
        char *s = hl_expr_print(es[i], HL_STYLE_SYMPY);
        fprintf(f, "  \"%s\",\n", s);
        free(s);
    }
    fprintf(f, "]\n"
               "for s in exprs:\n"
               "    e = sympy.sympify(s)\n"
               "    extra = e.free_symbols - set(subs)\n"
               "    v = complex(e.subs(subs).evalf(30)) if not extra else float('nan')\n"
               "    print(repr(v.real) if abs(v.imag) <= 1e-9 * max(1, abs(v)) else 'nan')\n");
    fclose(f);
    char cmd[256];
    snprintf(cmd, sizeof cmd, "timeout 300 python3 %s", in);
    FILE *p = popen(cmd, "r");
    int bad = 0, got = 0;
    for (int i = 0; i < n; i++) {
        double v;
        char line[128];
        if (fgets(line, sizeof line, p) == NULL)
            break;
        got++;
        v = strtod(line, NULL);
        if (!(fabs(v - vals[i]) <= 1e-8 * (1 + fabs(vals[i])))) {
            char *s = hl_expr_print(es[i], HL_STYLE_SYMPY);
            if (++bad < 5)
                fprintf(stderr, "sympy: %s = %s, hamlie %.17g\n", s, line, vals[i]);
            free(s);
        }
    }
    CHECK_MSG(pclose(p) == 0 && got == n, "python3 failed on %s", in);
    CHECK_MSG(bad == 0, "%d of %d sympy values differ", bad, n);
    printf("sympy agreed on %d of %d expressions\n", got - bad, n);
    if (!getenv("HL_KEEP")) unlink(in);
    (void)pool;
}

static void check_c(const hl_expr **es, const double *vals, int n)
{
    if (run("cc --version >/dev/null 2>&1") != 0) {
        printf("skipped: no C compiler\n");
        return;
    }
    char dir[] = "/tmp/hl-c-XXXXXX";
    if (mkdtemp(dir) == NULL)
        return;
    char src[64], exe[64], cmd[256];
    snprintf(src, sizeof src, "%s/t.c", dir);
    snprintf(exe, sizeof exe, "%s/t", dir);
    FILE *f = fopen(src, "w");
    fprintf(f, "#define _DEFAULT_SOURCE\n#include <math.h>\n#include <stdio.h>\n"
               "int main(void) {\n"
               "  double x = 0.7, y = -1.3, px = 0.45, q_1 = 2.1, omega = 1.7, D = 0.3,"
               " e = 1.1, E = -0.6;\n"
               "  (void)x; (void)y; (void)px; (void)q_1; (void)omega; (void)D; (void)e;"
               " (void)E;\n");
    for (int i = 0; i < n; i++) {
        char *s = hl_expr_print(es[i], HL_STYLE_C);
        fprintf(f, "  printf(\"%%.17g\\n\", (double)(%s));\n", s);
        free(s);
    }
    fprintf(f, "  return 0;\n}\n");
    fclose(f);
    snprintf(cmd, sizeof cmd, "cc -std=c99 -w -o %s %s -lm", exe, src);
    CHECK_MSG(run(cmd) == 0, "the C printer's output did not compile: %s", src);
    FILE *p = popen(exe, "r");
    int bad = 0, got = 0;
    for (int i = 0; p && i < n; i++) {
        char line[128];
        if (fgets(line, sizeof line, p) == NULL)
            break;
        got++;
        double v = strtod(line, NULL);
        if (!(fabs(v - vals[i]) <= 1e-9 * (1 + fabs(vals[i])))) {
            char *s = hl_expr_print(es[i], HL_STYLE_C);
            if (++bad < 5)
                fprintf(stderr, "C: %s = %s, hamlie %.17g\n", s, line, vals[i]);
            free(s);
        }
    }
    if (p)
        pclose(p);
    CHECK_MSG(bad == 0 && got == n, "%d of %d C values differ (%d read)", bad, n, got);
    printf("C agreed on %d of %d expressions\n", got - bad, n);
    unlink(src);
    unlink(exe);
    rmdir(dir);
}

int main(void)
{
    check_table();
    check_sympy_reserved();
    hl_pool *pool = hl_pool_new();
    const hl_expr *es[NSAMPLE];
    double vals[NSAMPLE];
    int n = sample(pool, es, vals);
    check_sympy(pool, es, vals, n);
    check_c(es, vals, n);
    hl_pool_free(pool);
    return HL_TEST_END();
}
