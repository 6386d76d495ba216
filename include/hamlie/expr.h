/* hamlie — the expression language.
 *
 * An expression is an immutable node in a hash-consed DAG owned by a pool:
 * two structurally equal expressions made in the same pool are the same
 * pointer, so `a == b` is structural equality.  Nodes live until the pool is
 * freed; nothing else frees them.
 *
 * The DAG is faithful to the syntax (a - b is HL_SUB, not a + (-1)*b): the
 * exact algebra layer (alg.h) does simplification.  The parser folds only
 * what makes a literal a literal: "-3" and "2/3" and "0.25" are numbers, so
 * parse(print(e)) == e for every e the parser returns.
 *
 * Grammar (precedence from loose to tight; see src/expr/prec.h):
 *   list    := [eqn {';' eqn}] [';']
 *   eqn     := expr ['=' expr]
 *   expr    := expr ('+'|'-') expr          left associative
 *            | expr ('*'|'/') expr          left associative
 *            | ('-'|'+') expr               unary, looser than ^: -x^2 = -(x^2)
 *            | expr ('^'|'**') expr         right associative: a^b^c = a^(b^c)
 *            | number | symbol | 'pi' | func '(' expr ')' | func2 '(' expr ',' expr ')'
 *            | '(' expr ')'
 *   number  := digits ['.' digits] [('e'|'E') ['+'|'-'] digits]   exact rational
 *   symbol  := letter {letter | digit | '_'}
 *   func    := sin cos tan exp log sqrt atan asin acos sinh cosh tanh
 *   func2   := atan2                  atan2(y, x): the angle of (x, y), in (-pi, pi]
 */
#ifndef HAMLIE_EXPR_H
#define HAMLIE_EXPR_H

#include <flint/fmpq.h>
#include "hamlie/error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef enum hl_expr_kind {
    HL_NUM, /* exact rational constant: num */
    HL_SYM, /* named symbol: name */
    HL_PI,  /* the constant pi */
    HL_NEG, /* -a */
    HL_ADD, /* a + b */
    HL_SUB, /* a - b */
    HL_MUL, /* a * b */
    HL_DIV, /* a / b */
    HL_POW, /* a ^ b */
    HL_FUN  /* fun(a), or fun(a, b) for a function of two arguments (atan2) */
} hl_expr_kind;

typedef enum hl_fun {
    HL_SIN, HL_COS, HL_TAN, HL_EXP, HL_LOG, HL_SQRT,
    HL_ATAN, HL_ASIN, HL_ACOS, HL_SINH, HL_COSH, HL_TANH,
    HL_ATAN2, /* atan2(y, x), two arguments: a = y, b = x (libm's order) */
    HL_ASINH,
    HL_FUN_COUNT
} hl_fun;

typedef struct hl_expr hl_expr;
struct hl_expr {
    hl_expr_kind kind;
    hl_fun fun;           /* HL_FUN only */
    unsigned id;          /* creation order in the pool: a stable total order */
    unsigned long hash;   /* structural hash */
    fmpq_t num;           /* HL_NUM only (canonical: reduced, positive denominator) */
    const char *name;     /* HL_SYM only; interned in the pool */
    const hl_expr *a, *b; /* operands: NEG and FUN use a (atan2 also b); binary kinds a, b */
};

typedef struct hl_pool hl_pool;

hl_pool *hl_pool_new(void);
void hl_pool_free(hl_pool *pool); /* NULL is a no-op */

/* Constructors.  Never NULL (an allocation failure aborts with a message:
 * memory is the one resource the library does not budget for the caller). */
const hl_expr *hl_num_si(hl_pool *pool, long n);
const hl_expr *hl_num_frac(hl_pool *pool, long p, unsigned long q); /* q > 0 */
const hl_expr *hl_num_fmpq(hl_pool *pool, const fmpq_t x);
const hl_expr *hl_sym(hl_pool *pool, const char *name);
const hl_expr *hl_pi(hl_pool *pool);
const hl_expr *hl_neg(hl_pool *pool, const hl_expr *a);
const hl_expr *hl_add(hl_pool *pool, const hl_expr *a, const hl_expr *b);
const hl_expr *hl_sub(hl_pool *pool, const hl_expr *a, const hl_expr *b);
const hl_expr *hl_mul(hl_pool *pool, const hl_expr *a, const hl_expr *b);
const hl_expr *hl_div(hl_pool *pool, const hl_expr *a, const hl_expr *b);
const hl_expr *hl_pow(hl_pool *pool, const hl_expr *a, const hl_expr *b);
const hl_expr *hl_call(hl_pool *pool, hl_fun f, const hl_expr *a);
/* A function of two arguments: f(a, b) (hl_fun_arity(f) == 2). */
const hl_expr *hl_call2(hl_pool *pool, hl_fun f, const hl_expr *a, const hl_expr *b);

/* Name of a function as written ("sin"), and lookup by name (-1 if none). */
const char *hl_fun_name(hl_fun f);
int hl_fun_lookup(const char *name, int len);
/* How many arguments f takes: 1, or 2 for atan2. */
int hl_fun_arity(hl_fun f);

/* ---- parsing ---------------------------------------------------------- */

/* Parse one expression.  On error returns HL_EPARSE (or HL_EDOM for a
 * division by zero between literals, HL_ELIMIT for nesting deeper than
 * HL_PARSE_MAX_DEPTH or more than HL_PARSE_MAX_NODES operands and
 * operators) with err->pos at the offending character and err->src set to
 * src; the message says what was expected.  The depth limit is the only one
 * in the layer: every walk over an expression is iterative, so a sum of
 * 10^5 terms (a chain 10^5 deep) is fine. */
#define HL_PARSE_MAX_DEPTH 200
#define HL_PARSE_MAX_NODES 1000000
hl_status hl_parse(const hl_expr **out, hl_pool *pool, const char *src, hl_error *err);

/* One item of a ';'-separated list: "lhs = rhs", or a bare expression
 * (then rhs is NULL).  pos is the byte offset where the item starts. */
typedef struct hl_eqn {
    const hl_expr *lhs, *rhs;
    int pos;
} hl_eqn;

/* Parse a list of at most max items into out[0..*n-1]. */
hl_status hl_parse_list(hl_eqn *out, int max, int *n, hl_pool *pool, const char *src,
                        hl_error *err);

/* ---- extending the grammar -------------------------------------------- *
 * A language written in formulas (the scheme language of scheme.h: "Q = q +
 * D*Hp(q, P)") reads its text with this parser and gives meaning to the
 * tree afterwards.  What it adds to the grammar is calls of its own names:
 *   call := name '(' expr {',' expr} ')'     name not a func or func2
 * Each is handed, arguments parsed, to the extension's call(), which makes
 * the node standing for it (typically a symbol the grammar cannot spell,
 * such as "#3", keyed to the call in the caller's own table) or refuses it
 * with err set at a position in src.  Without an extension such a call is
 * "unknown function". */
#define HL_PARSE_MAX_ARGS 8

typedef struct hl_parse_call {
    const char *src;  /* the whole text */
    const char *name; /* the called name, len bytes (not NUL-terminated) */
    int len;
    int pos, end; /* byte offsets of the name and of the closing ')' */
    int nargs;    /* 1 .. HL_PARSE_MAX_ARGS */
    const hl_expr *const *args;
    const int *arg_pos; /* byte offset where each argument starts */
} hl_parse_call;

typedef struct hl_parse_ext {
    /* Make *out for the call c, or return an error status with err set. */
    hl_status (*call)(const hl_expr **out, void *arg, const hl_parse_call *c, hl_error *err);
    void *arg;
    int equations; /* nonzero: every item must be "lhs = rhs" ("expected '='") */
} hl_parse_ext;

/* hl_parse_list with an extension (ext NULL: hl_parse_list itself). */
hl_status hl_parse_list_ext(hl_eqn *out, int max, int *n, hl_pool *pool, const char *src,
                            const hl_parse_ext *ext, hl_error *err);

/* Byte offset of the first token in src that is the symbol `name`, or -1.
 * Lets later layers point at a symbol they reject ("unknown symbol 'z'"). */
int hl_symbol_pos(const char *src, const char *name);

/* ---- printing --------------------------------------------------------- */

typedef enum hl_style {
    HL_STYLE_TEXT,  /* hamlie's own syntax; parses back to the same DAG */
    HL_STYLE_LATEX, /* for a paper: \frac, \sin, p_{x}, \omega */
    HL_STYLE_SYMPY, /* sympy.sympify parses it: **, pi, the user's names */
    HL_STYLE_C      /* a C expression over doubles: pow(), sin(), M_PI */
} hl_style;

/* Print an expression; the string is malloc'd and owned by the caller.
 * No depth or size limit: a caller printing a result for a person checks
 * hl_expr_tree_size against HL_PRINT_MAX_NODES first. */
char *hl_expr_print(const hl_expr *e, hl_style style);

/* hl_expr_print, or NULL when the printed form has more than max_nodes
 * nodes (hl_expr_tree_size > max_nodes): the print stops there, so a
 * caller can print and check the size in one pass. */
char *hl_expr_print_within(const hl_expr *e, hl_style style, double max_nodes);

/* A rational number as every printer writes it, "3", "-3", "3/2", appended
 * to b (small integers without fmpz_get_str's allocation). */
typedef struct hl_buf hl_buf;
void hl_expr_put_fmpz(hl_buf *b, const fmpz *x);
void hl_expr_put_fmpq(hl_buf *b, const fmpq *c);

/* The number of nodes of e written out as a tree, a shared node counted
 * each time it is referenced: the size of its printed form in operands and
 * operators (exponential in the DAG's depth at worst, hence a double). */
double hl_expr_tree_size(const hl_expr *e);

/* A result whose printed form would have more nodes than this is said to be
 * too large to print (tens of megabytes of text), not printed. */
#define HL_PRINT_MAX_NODES 5000000

/* A symbol name in LaTeX: "omega" -> "\omega", "q1" -> "q_{1}",
 * "p_2" -> "p_{2}", "px" -> "p_{x}".  malloc'd. */
char *hl_symbol_latex(const char *name);

/* ---- structure -------------------------------------------------------- */

/* Distinct symbol names in order of first appearance (left to right).
 * Writes at most max names (borrowed from the pool) and returns how many
 * distinct symbols there are in all. */
int hl_expr_symbols(const hl_expr *e, const char **names, int max);

/* Call visit(arg, node) once for every distinct node of roots[0..n-1],
 * each node after its operands (post-order, roots[0]'s nodes first, a
 * before b), on an explicit stack: a chain as deep as memory allows is
 * walked.  A nonzero return of visit stops the walk and is returned. */
int hl_expr_postorder(const hl_expr *const *roots, int n,
                      int (*visit)(void *arg, const hl_expr *node), void *arg);

/* Does e mention the symbol? */
int hl_expr_has_symbol(const hl_expr *e, const char *name);

/* Does e divide by a d with is_bad(d, arg) != 0?  The divisors are the b of
 * every a / b and the base of every a ^ b whose exponent is not a number
 * >= 0; is_bad is asked once per distinct divisor node. */
int hl_expr_divides_by(const hl_expr *e, int (*is_bad)(const hl_expr *d, void *arg), void *arg);

/* A rough cost of evaluating e[0..n-1] once in double, a node shared
 * between them counted once: 1 an arithmetic node, 4 a division, 20 a
 * function, 40 a power that is not an integer one (the calls dominate).
 * For choosing between two formulas of the same value. */
double hl_expr_cost(const hl_expr *const *e, int n);

/* Replace each symbol names[i] by vals[i] (simultaneously). */
const hl_expr *hl_expr_subst(hl_pool *pool, const hl_expr *e, int n,
                             const char *const *names, const hl_expr *const *vals);

/* hl_expr_subst on each of e[0..ne-1], in place, in one walk: the nodes the
 * formulas share are substituted once. */
void hl_expr_subst_each(hl_pool *pool, const hl_expr **e, int ne, int n,
                        const char *const *names, const hl_expr *const *vals);

/* The same formula with the terms of every sum and the factors of every
 * product in a fixed order that depends on their structure and names only
 * (a - b + c stays signed terms, a*b/c stays divisions), so that writings of
 * a formula that differ only in those orders give the same DAG and evaluate
 * to the same bits.  Minus signs move out of products into their sum. */
const hl_expr *hl_expr_ordered(hl_pool *pool, const hl_expr *e);

/* Derivative with respect to a symbol, lightly simplified (0 and 1 folded,
 * rational constants combined) so that tapes built from it stay small. */
const hl_expr *hl_expr_diff(hl_pool *pool, const hl_expr *e, const char *var);

/* Taylor coefficients in a symbol: out[k] = [t^k] e|_(var = at + t), k =
 * 0..K, as expressions over the other symbols (and at's), folded like
 * hl_expr_diff: a coefficient that vanishes is the number 0 (so a
 * polynomial's stop at its degree).  By the recurrences of Taylor mode
 * (tape.h), every function and power included: O(K^2) nodes for each node
 * of e that depends on var (O(K) where the arguments are linear in it, as
 * sin(q + s h)).  A node that does not depend on var is kept as it is. */
void hl_expr_taylor(const hl_expr **out, hl_pool *pool, const hl_expr *e, const char *var,
                    const hl_expr *at, int K);

/* Evaluate in double with the given symbol values.  Errors (HL_EINVAL) on a
 * symbol without a value; the result may be inf or nan, which the caller
 * checks.  A reference evaluator for tests: tape.h is the fast path. */
hl_status hl_expr_eval_d(double *out, const hl_expr *e, int n, const char *const *names,
                         const double *vals, hl_error *err);

#ifdef __cplusplus
}
#endif

#endif
