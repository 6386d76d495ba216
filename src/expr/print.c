/* Printers: hamlie text, LaTeX, sympy, C.
 *
 * Text, sympy and C share the priority table of prec.h: an operand is put in
 * parentheses exactly when the parser's rule would regroup it, plus two
 * conventions for readability that cost no parse depth (see parse.c): a right
 * operand that starts with '-' is parenthesised ("x^(-2)", "a*(-b)"), and in
 * text a double negation is written "--x".  Text also avoids the two literal
 * foldings of the parser: NEG(3) prints "-(3)", 2 DIV 3 prints "2/(3)".
 *
 * Text round trip: parse(print(e)) == e for every DAG whose symbols are
 * identifiers (letter {letter|digit|_}) other than "pi" and the function
 * names, and whose printed form nests at most HL_PARSE_MAX_DEPTH levels
 * (always true of what the parser returns).  A symbol named "pi" or "sin",
 * or one that is not an identifier, cannot be written in the language.
 *
 * Both printers run on an explicit stack of pieces (a node to print or a
 * fixed text), not on the C stack: a node pushes what it prints, in order,
 * and a sum of 10^5 terms, a chain 10^5 deep, prints like any other. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "expr/print_impl.h"
#include "expr/prec.h"
#include "expr/sympy_names.h"

/* ---- numbers --------------------------------------------------------------- */

static int num_is_int(const hl_expr *e) { return fmpz_is_one(fmpq_denref(e->num)); }
static int num_sgn(const hl_expr *e) { return fmpz_sgn(fmpq_numref(e->num)); }

/* Most numbers printed are small: those are written here, without the
 * allocation and the GMP conversion fmpz_get_str costs (~500 instructions
 * a number, a sixth of printing a large series). */
void hl_expr_put_fmpz(hl_buf *b, const fmpz *x)
{
    if (!COEFF_IS_MPZ(*x)) {
        char digits[24], *end = digits + sizeof digits, *d = end;
        slong v = *x; /* |v| < 2^62: its negation cannot overflow */
        ulong u = v < 0 ? (ulong)-v : (ulong)v;
        do
            *--d = (char)('0' + u % 10);
        while ((u /= 10) != 0);
        if (v < 0)
            *--d = '-';
        hl_buf_putn(b, d, (size_t)(end - d));
        return;
    }
    char *s = fmpz_get_str(NULL, 10, x);
    hl_buf_puts(b, s);
    flint_free(s);
}

void hl_expr_put_fmpq(hl_buf *b, const fmpq *c)
{
    hl_expr_put_fmpz(b, fmpq_numref(c));
    if (!fmpz_is_one(fmpq_denref(c))) {
        hl_buf_putc(b, '/');
        hl_expr_put_fmpz(b, fmpq_denref(c));
    }
}

/* ---- text, sympy, C: priorities of printed forms ---------------------------- */

/* Priority a printed e shows to an operator on its right. */
static int right_prio(hl_style st, const hl_expr *e)
{
    switch (e->kind) {
    case HL_NUM:
        if (!num_is_int(e))
            return st == HL_STYLE_C ? HL_PREC_ATOM : hl_prec_table[HL_DIV].right;
        return num_sgn(e) < 0 ? HL_PREC_UNARY : HL_PREC_ATOM;
    case HL_NEG:
        return HL_PREC_UNARY;
    case HL_ADD: case HL_SUB: case HL_MUL: case HL_DIV: case HL_POW:
        if (st == HL_STYLE_C && e->kind == HL_POW)
            return HL_PREC_ATOM; /* pow(a, b) */
        return hl_prec_table[e->kind].right;
    default:
        return HL_PREC_ATOM;
    }
}

/* Priority a printed e shows to an operator on its left. */
static int left_prio(hl_style st, const hl_expr *e)
{
    switch (e->kind) {
    case HL_NUM:
        if (!num_is_int(e))
            return st == HL_STYLE_C ? HL_PREC_ATOM : hl_prec_table[HL_DIV].left;
        return HL_PREC_ATOM;
    case HL_NEG:
        return HL_PREC_UNARY;
    case HL_ADD: case HL_SUB: case HL_MUL: case HL_DIV: case HL_POW:
        if (st == HL_STYLE_C && e->kind == HL_POW)
            return HL_PREC_ATOM;
        return hl_prec_table[e->kind].left;
    default:
        return HL_PREC_ATOM;
    }
}

static int paren_left(hl_style st, hl_expr_kind op, const hl_expr *a)
{
    return right_prio(st, a) < hl_prec_table[op].left;
}

static int starts_minus(hl_style st, const hl_expr *e)
{
    for (;;) {
        switch (e->kind) {
        case HL_NUM:
            return num_sgn(e) < 0 && !(st == HL_STYLE_C && !num_is_int(e));
        case HL_NEG:
            return 1;
        case HL_ADD: case HL_SUB: case HL_MUL: case HL_DIV: case HL_POW:
            if ((st == HL_STYLE_C && e->kind == HL_POW) || paren_left(st, e->kind, e->a))
                return 0;
            e = e->a;
            break;
        default:
            return 0;
        }
    }
}

static int paren_right(hl_style st, hl_expr_kind op, const hl_expr *a, const hl_expr *b)
{
    if (left_prio(st, b) <= hl_prec_table[op].right || starts_minus(st, b))
        return 1;
    /* text: "2/3" would be read as the number 2/3 */
    return st == HL_STYLE_TEXT && op == HL_DIV && a->kind == HL_NUM && b->kind == HL_NUM;
}

static int paren_neg(hl_style st, const hl_expr *a)
{
    if (a->kind == HL_NEG)
        return st != HL_STYLE_TEXT; /* C would read "--" as a decrement */
    if (left_prio(st, a) <= HL_PREC_UNARY)
        return 1;
    if (starts_minus(st, a))
        return st != HL_STYLE_TEXT; /* C would read "--" as a decrement */
    /* text: "-3" would be read as the number -3 */
    return st == HL_STYLE_TEXT && a->kind == HL_NUM;
}

/* sympy_is_reserved: is name one sympify would not read as a plain symbol
 * (a Python keyword or one of sympy's own names)?  Printed as Symbol('E').
 * The table is sorted (byte order) so a lookup is a binary search: this is
 * asked for every symbol printed, and a linear scan of ~250 strcmp was a
 * third of the time of printing a large series. */

static int cmp_name(const void *key, const void *entry)
{
    return strcmp(key, *(const char *const *)entry);
}

static int sympy_is_reserved(const char *name)
{
    return bsearch(name, hl_sympy_reserved, sizeof hl_sympy_reserved / sizeof *hl_sympy_reserved,
                   sizeof *hl_sympy_reserved, cmp_name) != NULL;
}

/* ---- the stack of pieces still to print ----------------------------------- */

/* A piece: a node (e) or a fixed text (text); neither is an empty piece. */
typedef struct piece {
    const hl_expr *e;
    const char *text;
} piece;

typedef struct pieces {
    piece *p;
    size_t n, cap;
} pieces;

#define NODE(x) ((piece){(x), NULL})
#define TEXT(s) ((piece){NULL, (s)})
#define IF_TEXT(c, s) ((piece){NULL, (c) ? (s) : NULL})

/* Push p[0..n-1] so that p[0] is printed first. */
static void push(pieces *S, int n, const piece *p)
{
    if (S->n + (size_t)n > S->cap) {
        S->cap = 2 * S->cap + (size_t)n;
        S->p = hl_xrealloc(S->p, S->cap * sizeof *S->p);
    }
    for (int i = n - 1; i >= 0; i--)
        if (p[i].e != NULL || p[i].text != NULL)
            S->p[S->n++] = p[i];
}

#define PUSH(S, ...) push((S), sizeof((piece[]){__VA_ARGS__}) / sizeof(piece), (piece[]){__VA_ARGS__})

/* e, in parentheses (open, close) when paren */
#define GROUP(e, paren, open, close) IF_TEXT(paren, open), NODE(e), IF_TEXT(paren, close)

/* How a node prints: writes what it can at once, pushes the rest, and
 * returns how many nodes of the tree it stands for (2 when it printed a
 * child itself, as LaTeX's \sin^{2} q does). */
typedef int print_fn(hl_buf *b, pieces *S, hl_style st, const hl_expr *e);

/* Print from root, each node handed to print_node; 0 (and the print left
 * unfinished) once more than max_nodes tree nodes were printed. */
static int print_all(hl_buf *b, const hl_expr *root, hl_style st, print_fn *print_node,
                     double max_nodes)
{
    pieces S = {NULL, 0, 0};
    double nodes = 0;
    PUSH(&S, NODE(root));
    while (S.n > 0 && nodes <= max_nodes) {
        piece p = S.p[--S.n];
        if (p.text != NULL)
            hl_buf_puts(b, p.text);
        else
            nodes += print_node(b, &S, st, p.e);
    }
    free(S.p);
    return nodes <= max_nodes;
}

/* ---- text, sympy, C: printing --------------------------------------------- */

static void put_number(hl_buf *b, hl_style st, const hl_expr *e)
{
    if (st != HL_STYLE_C) {
        hl_expr_put_fmpz(b, fmpq_numref(e->num));
        if (!num_is_int(e)) {
            hl_buf_putc(b, '/');
            hl_expr_put_fmpz(b, fmpq_denref(e->num));
        }
        return;
    }
    /* C: doubles, and a fraction as one parenthesised quotient */
    if (!num_is_int(e))
        hl_buf_putc(b, '(');
    hl_expr_put_fmpz(b, fmpq_numref(e->num));
    hl_buf_puts(b, ".0");
    if (!num_is_int(e)) {
        hl_buf_putc(b, '/');
        hl_expr_put_fmpz(b, fmpq_denref(e->num));
        hl_buf_puts(b, ".0)");
    }
}

static const char *op_text(hl_style st, hl_expr_kind k)
{
    switch (k) {
    case HL_ADD: return " + ";
    case HL_SUB: return " - ";
    case HL_MUL: return "*";
    case HL_DIV: return "/";
    default: return st == HL_STYLE_SYMPY ? "**" : "^";
    }
}

static int print_plain(hl_buf *b, pieces *S, hl_style st, const hl_expr *e)
{
    switch (e->kind) {
    case HL_NUM:
        put_number(b, st, e);
        break;
    case HL_SYM:
        if (st == HL_STYLE_SYMPY && sympy_is_reserved(e->name))
            hl_buf_printf(b, "Symbol('%s')", e->name);
        else
            hl_buf_puts(b, e->name);
        break;
    case HL_PI:
        hl_buf_puts(b, st == HL_STYLE_C ? "M_PI" : "pi");
        break;
    case HL_NEG:
        hl_buf_putc(b, '-');
        PUSH(S, GROUP(e->a, paren_neg(st, e->a), "(", ")"));
        break;
    case HL_FUN: /* C prints a fraction in parentheses already */
        hl_buf_puts(b, hl_fun_name(e->fun));
        if (e->b != NULL) { /* atan2(y, x): the same name in text, SymPy and C */
            PUSH(S, TEXT("("), NODE(e->a), TEXT(", "), NODE(e->b), TEXT(")"));
            break;
        }
        PUSH(S, GROUP(e->a, !(st == HL_STYLE_C && e->a->kind == HL_NUM && !num_is_int(e->a)),
                      "(", ")"));
        break;
    default:
        if (st == HL_STYLE_C && e->kind == HL_POW) {
            hl_buf_puts(b, "pow(");
            PUSH(S, NODE(e->a), TEXT(", "), NODE(e->b), TEXT(")"));
            break;
        }
        PUSH(S, GROUP(e->a, paren_left(st, e->kind, e->a), "(", ")"),
             TEXT(op_text(st, e->kind)),
             GROUP(e->b, paren_right(st, e->kind, e->a, e->b), "(", ")"));
    }
    return 1;
}

/* ---- LaTeX ------------------------------------------------------------------ */

static const char *const greek[] = {
    "alpha", "beta", "gamma", "delta", "epsilon", "varepsilon", "zeta", "eta", "theta",
    "vartheta", "iota", "kappa", "lambda", "mu", "nu", "xi", "pi", "varpi", "rho",
    "varrho", "sigma", "varsigma", "tau", "upsilon", "phi", "varphi", "chi", "psi",
    "omega", "Gamma", "Delta", "Theta", "Lambda", "Xi", "Pi", "Sigma", "Upsilon",
    "Phi", "Psi", "Omega",
};

static int is_greek(const char *s, size_t n)
{
    for (size_t i = 0; i < sizeof greek / sizeof *greek; i++)
        if (strlen(greek[i]) == n && memcmp(greek[i], s, n) == 0)
            return 1;
    return 0;
}

static int all_digits(const char *s, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (s[i] < '0' || s[i] > '9')
            return 0;
    return n > 0;
}

/* A name without '_': greek, letter, letter+digits, letter+letter, letter+greek. */
static void latex_name(hl_buf *b, const char *s, size_t n)
{
    size_t k = n;
    while (k > 0 && s[k - 1] >= '0' && s[k - 1] <= '9')
        k--;
    if (k > 0 && k < n) { /* q1, omega0, mass2 */
        latex_name(b, s, k);
        hl_buf_puts(b, "_{");
        hl_buf_putn(b, s + k, n - k);
        hl_buf_putc(b, '}');
    } else if (n == 1 || all_digits(s, n)) {
        hl_buf_putn(b, s, n);
    } else if (is_greek(s, n)) {
        hl_buf_putc(b, '\\');
        hl_buf_putn(b, s, n);
    } else if (n == 2 || is_greek(s + 1, n - 1)) { /* px, ptheta */
        hl_buf_putc(b, s[0]);
        hl_buf_puts(b, "_{");
        latex_name(b, s + 1, n - 1);
        hl_buf_putc(b, '}');
    } else {
        hl_buf_puts(b, "\\mathrm{");
        hl_buf_putn(b, s, n);
        hl_buf_putc(b, '}');
    }
}

static void latex_symbol(hl_buf *b, const char *name)
{
    const char *u = strchr(name, '_');
    if (u == NULL || u == name || u[1] == '\0') {
        if (u != NULL) { /* a leading or trailing '_' has no subscript reading */
            hl_buf_puts(b, "\\mathrm{");
            for (const char *c = name; *c; c++)
                hl_buf_puts(b, *c == '_' ? "\\_" : (char[2]){*c, 0});
            hl_buf_putc(b, '}');
            return;
        }
        latex_name(b, name, strlen(name));
        return;
    }
    latex_name(b, name, (size_t)(u - name));
    hl_buf_puts(b, "_{");
    latex_symbol(b, u + 1);
    hl_buf_putc(b, '}');
}

char *hl_symbol_latex(const char *name)
{
    hl_buf b;
    hl_buf_init(&b);
    latex_symbol(&b, name);
    return hl_buf_take(&b);
}

static const char *const latex_fun[HL_FUN_COUNT] = {
    [HL_SIN] = "\\sin", [HL_COS] = "\\cos", [HL_TAN] = "\\tan", [HL_EXP] = "\\exp",
    [HL_LOG] = "\\log", [HL_SQRT] = "\\sqrt", [HL_ATAN] = "\\arctan",
    [HL_ASIN] = "\\arcsin", [HL_ACOS] = "\\arccos", [HL_SINH] = "\\sinh",
    [HL_COSH] = "\\cosh", [HL_TANH] = "\\tanh", [HL_ATAN2] = "\\operatorname{atan2}",
    [HL_ASINH] = "\\operatorname{arsinh}",
};

static int latex_atom(const hl_expr *e) /* needs no parentheses under ^ */
{
    return e->kind == HL_SYM || e->kind == HL_PI ||
           (e->kind == HL_NUM && num_is_int(e) && num_sgn(e) >= 0);
}

static int latex_sum(const hl_expr *e) { return e->kind == HL_ADD || e->kind == HL_SUB; }

static int latex_minus(const hl_expr *e) /* printed form starts with '-' */
{
    while (e->kind == HL_ADD || e->kind == HL_SUB || e->kind == HL_MUL)
        e = e->a;
    return e->kind == HL_NEG || (e->kind == HL_NUM && num_sgn(e) < 0);
}

/* sin, cos, tan and the hyperbolic ones take sin^{2} x */
static int latex_power_fun(hl_fun f)
{
    return f == HL_SIN || f == HL_COS || f == HL_TAN || f == HL_SINH || f == HL_COSH ||
           f == HL_TANH;
}

static int latex_fun_power(const hl_expr *e) /* \sin^{2} q */
{
    return e->kind == HL_POW && e->a->kind == HL_FUN && latex_power_fun(e->a->fun) &&
           e->b->kind == HL_NUM && num_is_int(e->b) && num_sgn(e->b) > 0;
}

/* Does the LaTeX of e start with a digit?  (Then a factor before it needs
 * a \cdot.)  Follows the leftmost piece down, as latex_node prints it. */
static int latex_starts_digit(const hl_expr *e)
{
    for (;;) {
        switch (e->kind) {
        case HL_NUM:
            return num_is_int(e) && num_sgn(e) >= 0;
        case HL_SYM: {
            hl_buf t;
            hl_buf_init(&t);
            latex_symbol(&t, e->name);
            int digit = t.s[0] >= '0' && t.s[0] <= '9';
            hl_buf_clear(&t);
            return digit;
        }
        case HL_ADD:
        case HL_SUB:
            e = e->a;
            break;
        case HL_MUL:
            if (latex_sum(e->a))
                return 0; /* \left( */
            e = e->a;
            break;
        case HL_POW:
            if (latex_fun_power(e) || !latex_atom(e->a))
                return 0;
            e = e->a;
            break;
        default: /* -, \pi, \sin, \frac */
            return 0;
        }
    }
}

static void latex_call(hl_buf *b, pieces *S, hl_fun f, const hl_expr *arg,
                       const hl_expr *power)
{
    hl_buf_puts(b, latex_fun[f]);
    if (f == HL_SQRT) {
        PUSH(S, TEXT("{"), NODE(arg), TEXT("}"));
        return;
    }
    PUSH(S, IF_TEXT(power, "^{"), NODE(power), IF_TEXT(power, "}"),
         IF_TEXT(latex_atom(arg), " "), GROUP(arg, !latex_atom(arg), "\\left(", "\\right)"));
}

static void latex_number(hl_buf *b, const hl_expr *e)
{
    if (num_is_int(e)) {
        hl_expr_put_fmpz(b, fmpq_numref(e->num));
        return;
    }
    if (num_sgn(e) < 0)
        hl_buf_putc(b, '-');
    hl_buf_puts(b, "\\frac{");
    fmpz_t t;
    fmpz_init(t);
    fmpz_abs(t, fmpq_numref(e->num));
    hl_expr_put_fmpz(b, t);
    fmpz_clear(t);
    hl_buf_puts(b, "}{");
    hl_expr_put_fmpz(b, fmpq_denref(e->num));
    hl_buf_putc(b, '}');
}

static int latex_node(hl_buf *b, pieces *S, hl_style st, const hl_expr *e)
{
    (void)st;
    switch (e->kind) {
    case HL_NUM:
        latex_number(b, e);
        break;
    case HL_SYM:
        latex_symbol(b, e->name);
        break;
    case HL_PI:
        hl_buf_puts(b, "\\pi");
        break;
    case HL_NEG:
        hl_buf_putc(b, '-');
        PUSH(S, GROUP(e->a, latex_sum(e->a) || latex_minus(e->a), "\\left(", "\\right)"));
        break;
    case HL_FUN:
        if (e->b != NULL) { /* \operatorname{atan2}\left(y, x\right) */
            hl_buf_puts(b, latex_fun[e->fun]);
            PUSH(S, TEXT("\\left("), NODE(e->a), TEXT(", "), NODE(e->b), TEXT("\\right)"));
            break;
        }
        latex_call(b, S, e->fun, e->a, NULL);
        break;
    case HL_ADD:
    case HL_SUB:
        PUSH(S, NODE(e->a), TEXT(e->kind == HL_ADD ? " + " : " - "),
             GROUP(e->b, latex_minus(e->b) || (e->kind == HL_SUB && latex_sum(e->b)),
                   "\\left(", "\\right)"));
        break;
    case HL_MUL: {
        int paren_b = latex_sum(e->b) || latex_minus(e->b);
        /* a number after a factor needs a dot: 2\cdot 3, 2\cdot\frac{1}{2} */
        int dot = e->b->kind == HL_NUM || (!paren_b && latex_starts_digit(e->b));
        PUSH(S, GROUP(e->a, latex_sum(e->a), "\\left(", "\\right)"),
             TEXT(dot ? " \\cdot " : "\\,"), GROUP(e->b, paren_b, "\\left(", "\\right)"));
        break;
    }
    case HL_DIV:
        PUSH(S, TEXT("\\frac{"), NODE(e->a), TEXT("}{"), NODE(e->b), TEXT("}"));
        break;
    case HL_POW:
        if (latex_fun_power(e)) {
            latex_call(b, S, e->a->fun, e->a->a, e->b); /* \sin^{2} q */
            return 2;                                   /* e and its child e->a */
        }
        PUSH(S, GROUP(e->a, !latex_atom(e->a), "\\left(", "\\right)"), TEXT("^{"),
             NODE(e->b), TEXT("}"));
        break;
    }
    return 1;
}

/* ---- entry ------------------------------------------------------------------ */

static print_fn *printer_of(hl_style style)
{
    return style == HL_STYLE_LATEX ? latex_node : print_plain;
}

char *hl_expr_print(const hl_expr *e, hl_style style)
{
    hl_buf b;
    hl_buf_init(&b);
    print_all(&b, e, style, printer_of(style), HUGE_VAL);
    return hl_buf_take(&b);
}

char *hl_expr_print_within(const hl_expr *e, hl_style style, double max_nodes)
{
    hl_buf b;
    hl_buf_init(&b);
    if (!print_all(&b, e, style, printer_of(style), max_nodes)) {
        hl_buf_clear(&b);
        return NULL;
    }
    return hl_buf_take(&b);
}

/* ---- printed length ---------------------------------------------------------- */

size_t hl_expr_print_len(const hl_expr *e, hl_style st, hl_buf *scratch)
{
    scratch->len = 0; /* the text is written (and thrown away): its length is
                       * all that is asked, and the buffer is reused */
    print_all(scratch, e, st, printer_of(st), HUGE_VAL);
    return scratch->len;
}
