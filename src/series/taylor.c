/* Taylor mode: an expression DAG compiled once into a list of nodes in
 * topological order, then evaluated coefficient by coefficient: step k
 * computes the D^k coefficient of every node from the coefficients below k
 * (Hairer, Norsett, Wanner, Solving ODEs I, §I.8; Jorba & Zou 2005).  Each
 * node is an operation of the tape (hl_op) and its coefficient k comes from
 * the operation's rule (src/rules), run by the exact back end of emit.c;
 * only point values F(u_0) go through the algebra layer (hl_alg_apply), the
 * rest is exact arithmetic on the coefficients.
 *
 * Coefficient-wise evaluation is what makes the order-by-order solver cost
 * O(n^2) products per node instead of O(n^3): a new order of the unknowns
 * only adds a coefficient.  Subtrees without symbols are folded to constants
 * by the algebra layer (exactly: sin(pi/3), sqrt(8)); integer powers become
 * products (so (D + x D^2)^3 needs no nonzero constant term); other powers
 * with constant exponents are the operation a^c, non-constant exponents
 * exp(b log a).  The compile walk is iterative (explicit stack) so that the
 * long sums hl_alg_to_expr writes cannot exhaust the C stack. */
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "base/memo.h"
#include "series/series_impl.h"

enum {
    NODE_CONST, /* cst */
    NODE_INPUT, /* the caller's series number sym */
    NODE_OP     /* an operation of the tape, computed by its rule */
};

typedef struct tnode {
    int kind;
    hl_op op;         /* NODE_OP */
    int second;       /* the node is the rule's second result X (cos beside sin) */
    int a, b;         /* operand nodes, -1 if none */
    int sym;          /* NODE_INPUT: index into the inputs */
    const char *name; /* NODE_INPUT: the symbol (borrowed from the expression) */
    int has_e;
    fmpq_t e;       /* HL_OP_POWK: the exponent, the rule's B */
    hl_alg cst;     /* NODE_CONST */
    hl_alg keep[2]; /* what the rule keeps from coefficient 0 */
    hl_series v;    /* the node's coefficients */
    hl_series aux;  /* the rule's other series (X, or D when second) */
} tnode;

struct series_prog {
    tnode *node;
    int nnode, anode;
    int *root;
    int nroot;
    int n; /* coefficients allocated */
    long max_terms; /* the budget of all coefficients together (0: none) */
    long terms;     /* their terms so far */
    series_em em;
};

/* ---- nodes ----------------------------------------------------------------- */

static series_prog *prog_new(int n, int nroot, hl_alg_ctx *ctx)
{
    series_prog *p = hl_xcalloc(1, sizeof *p);
    p->n = n;
    p->nroot = nroot;
    p->root = hl_xcalloc((size_t)(nroot > 0 ? nroot : 1), sizeof *p->root);
    series_em_init(&p->em, ctx);
    return p;
}

static int new_node(series_prog *p, int kind, int a, int b, const hl_alg_ctx *ctx)
{
    if (p->nnode == p->anode) {
        p->anode = p->anode ? 2 * p->anode : 32;
        p->node = hl_xrealloc(p->node, (size_t)p->anode * sizeof *p->node);
    }
    tnode *t = &p->node[p->nnode];
    memset(t, 0, sizeof *t);
    t->kind = kind;
    t->a = a;
    t->b = b;
    t->sym = -1;
    hl_alg_init(&t->cst, ctx);
    for (int i = 0; i < 2; i++)
        hl_alg_init(&t->keep[i], ctx);
    hl_series_init(&t->v, p->n, ctx);
    hl_series_init(&t->aux, 0, ctx);
    return p->nnode++;
}

/* The rules whose operation has a second series (X in rules/rule.h). */
static int has_aux(hl_op op)
{
    return op == HL_OP_SINCOS || op == HL_OP_SINHCOSH || op == HL_OP_TAN || op == HL_OP_TANH ||
           op == HL_OP_ATAN || op == HL_OP_ASIN || op == HL_OP_ACOS || op == HL_OP_ATAN2;
}

static int op_node(series_prog *p, hl_op op, int a, int b, hl_alg_ctx *ctx)
{
    int i = new_node(p, NODE_OP, a, b, ctx);
    p->node[i].op = op;
    if (has_aux(op))
        hl_series_zero(&p->node[i].aux, p->n, ctx);
    return i;
}

void series_prog_free(series_prog *p, const hl_alg_ctx *ctx)
{
    if (!p)
        return;
    for (int i = 0; i < p->nnode; i++) {
        tnode *t = &p->node[i];
        hl_alg_clear(&t->cst, ctx);
        for (int j = 0; j < 2; j++)
            hl_alg_clear(&t->keep[j], ctx);
        hl_series_clear(&t->v, ctx);
        hl_series_clear(&t->aux, ctx);
        if (t->has_e)
            fmpq_clear(t->e);
    }
    series_em_clear(&p->em);
    free(p->node);
    free(p->root);
    free(p);
}

const hl_series *series_prog_root(const series_prog *p, int i)
{
    return &p->node[p->root[i]].v;
}

/* ---- compilation ------------------------------------------------------------- */

static int is_const(const series_prog *p, int i)
{
    return i >= 0 && p->node[i].kind == NODE_CONST;
}

/* Fold a node whose operands are constants. */
static int fold(series_prog *p, int *out, const hl_expr *x, int a, int b, hl_alg_ctx *ctx,
                hl_error *err)
{
    int i = new_node(p, NODE_CONST, -1, -1, ctx);
    hl_alg *r = &p->node[i].cst;
    const hl_alg *ca = a >= 0 ? &p->node[a].cst : NULL, *cb = b >= 0 ? &p->node[b].cst : NULL;
    int status = HL_OK;
    switch (x->kind) {
    case HL_NUM:
        hl_alg_set_fmpq(r, x->num, ctx);
        break;
    case HL_PI:
        status = hl_alg_pi(r, ctx, err);
        break;
    case HL_NEG:
        hl_alg_neg(r, ca, ctx);
        break;
    case HL_ADD:
        hl_alg_add(r, ca, cb, ctx);
        break;
    case HL_SUB:
        hl_alg_sub(r, ca, cb, ctx);
        break;
    case HL_MUL:
        hl_alg_mul(r, ca, cb, ctx);
        break;
    case HL_DIV:
        status = hl_alg_div(r, ca, cb, ctx, err);
        break;
    case HL_POW:
        status = hl_alg_pow(r, ca, cb, ctx, err);
        break;
    case HL_FUN:
        status = x->b != NULL ? hl_alg_apply2(r, x->fun, ca, cb, ctx, err)
                              : hl_alg_apply(r, x->fun, ca, ctx, err);
        break;
    case HL_SYM:
        break; /* not reached */
    }
    *out = i;
    return status;
}

/* a^e for an integer e by binary powering into product nodes. */
static int int_power(series_prog *p, int a, long e, hl_alg_ctx *ctx)
{
    unsigned long u = e < 0 ? 0UL - (unsigned long)e : (unsigned long)e;
    int acc = -1, base = a;
    if (u == 0) {
        acc = new_node(p, NODE_CONST, -1, -1, ctx);
        hl_alg_one(&p->node[acc].cst, ctx);
        return acc;
    }
    while (u != 0) {
        if (u & 1)
            acc = acc < 0 ? base : op_node(p, HL_OP_MUL, acc, base, ctx);
        u >>= 1;
        if (u != 0)
            base = op_node(p, HL_OP_SQR, base, -1, ctx);
    }
    if (e < 0) {
        int one = new_node(p, NODE_CONST, -1, -1, ctx);
        hl_alg_one(&p->node[one].cst, ctx);
        acc = op_node(p, HL_OP_DIV, one, acc, ctx);
    }
    return acc;
}

/* a^e, e a rational constant: the rule's B is e (its coefficient 0) */
static int powq_node(series_prog *p, int a, const fmpq_t e, hl_alg_ctx *ctx)
{
    int i = op_node(p, HL_OP_POWK, a, -1, ctx);
    fmpq_init(p->node[i].e);
    fmpq_set(p->node[i].e, e);
    p->node[i].has_e = 1;
    return i;
}


static int fun_node(series_prog *p, hl_fun f, int a, int b, hl_alg_ctx *ctx)
{
    int second;
    int i = op_node(p, hl_fun_op(f, &second), a, b, ctx);
    p->node[i].second = second;
    return i;
}

/* The node for x^b, b's node known. */
static int pow_node(series_prog *p, int a, int b, hl_alg_ctx *ctx)
{
    fmpq_t e;
    fmpq_init(e);
    int i;
    if (is_const(p, b) && hl_alg_is_fmpq(&p->node[b].cst, e, ctx)) {
        if (fmpz_is_one(fmpq_denref(e)) && fmpz_fits_si(fmpq_numref(e)))
            i = int_power(p, a, fmpz_get_si(fmpq_numref(e)), ctx);
        else
            i = powq_node(p, a, e, ctx);
    } else { /* exp(b log a) */
        int l = fun_node(p, HL_LOG, a, -1, ctx);
        int m = op_node(p, HL_OP_MUL, b, l, ctx);
        i = fun_node(p, HL_EXP, m, -1, ctx);
    }
    fmpq_clear(e);
    return i;
}

static int children(const hl_expr *e)
{
    switch (e->kind) {
    case HL_FUN:
        return e->b != NULL ? 2 : 1; /* atan2(y, x): two */
    case HL_NEG:
        return 1;
    case HL_ADD:
    case HL_SUB:
    case HL_MUL:
    case HL_DIV:
    case HL_POW:
        return 2;
    default:
        return 0;
    }
}

/* Node for x, its children compiled. */
static int emit(series_prog *p, int *out, const hl_expr *x, int a, int b, int nsym,
                const char *const *names, hl_alg_ctx *ctx, hl_error *err)
{
    int nc = children(x);
    if (x->kind == HL_SYM) {
        for (int i = 0; i < nsym; i++)
            if (strcmp(names[i], x->name) == 0) {
                *out = new_node(p, NODE_INPUT, -1, -1, ctx);
                p->node[*out].sym = i;
                p->node[*out].name = x->name;
                return HL_OK;
            }
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no value for symbol '%s'", x->name);
    }
    if ((nc == 0) || (is_const(p, a) && (nc == 1 || is_const(p, b))))
        return fold(p, out, x, a, b, ctx, err);
    switch (x->kind) {
    case HL_NEG:
        *out = op_node(p, HL_OP_NEG, a, -1, ctx);
        break;
    case HL_ADD:
        *out = op_node(p, HL_OP_ADD, a, b, ctx);
        break;
    case HL_SUB:
        *out = op_node(p, HL_OP_SUB, a, b, ctx);
        break;
    case HL_MUL:
        *out = op_node(p, HL_OP_MUL, a, b, ctx);
        break;
    case HL_DIV:
        *out = op_node(p, HL_OP_DIV, a, b, ctx);
        break;
    case HL_POW:
        *out = pow_node(p, a, b, ctx);
        break;
    case HL_FUN:
        *out = fun_node(p, x->fun, a, b, ctx);
        break;
    default:
        break; /* leaves handled above */
    }
    return HL_OK;
}

int series_prog_compile(series_prog **out, int nroot, const hl_expr *const *roots, int nsym,
                        const char *const *names, int n, hl_alg_ctx *ctx, hl_error *err)
{
    *out = NULL;
    if (n < 0 || n > HL_SERIES_MAX_N)
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0, "series length %d outside 0..%d", n,
                            HL_SERIES_MAX_N);
    series_prog *p = prog_new(n, nroot, ctx);
    hl_memo m; /* expression -> node */
    hl_memo_init(&m);
    const hl_expr **stack = NULL;
    int top = 0, cap = 0, status = HL_OK;
    for (int r = 0; status == HL_OK && r < nroot; r++) {
        if (top == cap) {
            cap = cap ? 2 * cap : 64;
            stack = hl_xrealloc(stack, (size_t)cap * sizeof *stack);
        }
        stack[top++] = roots[r];
        while (status == HL_OK && top > 0) {
            const hl_expr *x = stack[top - 1];
            if (hl_memo_get(&m, x)) {
                top--;
                continue;
            }
            int nc = children(x), pending = 0;
            const hl_expr *kid[2] = {x->a, x->b};
            for (int c = 0; c < nc; c++)
                if (!hl_memo_get(&m, kid[c])) {
                    if (top == cap) {
                        cap *= 2;
                        stack = hl_xrealloc(stack, (size_t)cap * sizeof *stack);
                    }
                    stack[top++] = kid[c];
                    pending = 1;
                }
            if (pending)
                continue;
            int a = nc >= 1 ? hl_memo_get(&m, x->a)->i : -1,
                b = nc == 2 ? hl_memo_get(&m, x->b)->i : -1;
            int i = -1;
            status = emit(p, &i, x, a, b, nsym, names, ctx, err);
            if (status == HL_OK)
                hl_memo_put(&m, x)->i = i;
            top--;
        }
        if (status == HL_OK)
            p->root[r] = hl_memo_get(&m, roots[r])->i;
    }
    free(stack);
    hl_memo_clear(&m);
    if (status != HL_OK) {
        series_prog_free(p, ctx);
        return status;
    }
    *out = p;
    return HL_OK;
}

/* ---- one coefficient of every node -------------------------------------------- */

/* The error when the rule of op divides by a coefficient 0 that is zero. */
static const char *vanishing(hl_op op)
{
    switch (op) {
    case HL_OP_DIV:
        return "division by a series that vanishes at D = 0";
    case HL_OP_SQRT:
        return "sqrt of a series that vanishes at D = 0";
    case HL_OP_LOG:
        return "log of a series that vanishes at D = 0";
    case HL_OP_ATAN:
        return "atan of a series that vanishes at D = 0";
    case HL_OP_POWK:
        return "non-integer power of a series that vanishes at D = 0";
    case HL_OP_ASIN:
        return "asin of a series equal to 1 or -1 at D = 0";
    case HL_OP_ACOS:
        return "acos of a series equal to 1 or -1 at D = 0";
    default:
        return "atan2 of a series that vanishes at D = 0";
    }
}

/* Coefficient k of an operation's node, by the operation's rule. */
static int step_op(series_prog *p, tnode *t, int k, hl_error *err)
{
    series_em *E = &p->em;
    E->slot[HL_SLOT_D] = t->second ? &t->aux : &t->v;
    E->slot[HL_SLOT_X] = t->second ? &t->v : &t->aux;
    E->slot[HL_SLOT_A] = t->a >= 0 ? &p->node[t->a].v : NULL;
    E->slot[HL_SLOT_B] = t->b >= 0 ? &p->node[t->b].v : NULL;
    E->keep = t->keep;
    E->exponent = t->has_e ? t->e : NULL;
    E->vanishing = vanishing(t->op);
    return series_em_run(E, hl_rule_of(t->op), k, err);
}

static int step_node(series_prog *p, int i, int k, const hl_series *inputs, hl_alg_ctx *ctx,
                     hl_error *err)
{
    tnode *t = &p->node[i];
    hl_alg *out = &t->v.c[k];
    switch (t->kind) {
    case NODE_CONST:
        if (k == 0)
            hl_alg_set(out, &t->cst, ctx);
        else
            hl_alg_zero(out, ctx);
        return HL_OK;
    case NODE_INPUT:
        if (inputs[t->sym].n <= k)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "the series of '%s' has %d coefficients, %d needed",
                                t->name ? t->name : "?", inputs[t->sym].n, k + 1);
        hl_alg_set(out, &inputs[t->sym].c[k], ctx);
        return HL_OK;
    default:
        return step_op(p, t, k, err);
    }
}

int series_prog_step(series_prog *p, int k, const hl_series *inputs, hl_alg_ctx *ctx, hl_error *err)
{
    if (k < 0 || k >= p->n)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "coefficient %d outside 0..%d", k,
                            p->n - 1);
    for (int i = 0; i < p->nnode; i++) {
        int status = step_node(p, i, k, inputs, ctx, err);
        if (status != HL_OK)
            return status;
        if (p->max_terms == 0)
            continue;
        p->terms += hl_alg_length(&p->node[i].v.c[k], ctx);
        if (p->terms > p->max_terms)
            return hl_error_set(err, HL_ELIMIT, NULL, -1, 0,
                                "the coefficients passed the budget of %ld terms",
                                p->max_terms);
    }
    return HL_OK;
}

void series_prog_set_budget(series_prog *p, long max_terms) { p->max_terms = max_terms; }

int series_prog_run(series_prog *p, int n, const hl_series *inputs, hl_alg_ctx *ctx, hl_error *err)
{
    for (int k = 0; k < n; k++) {
        int status = series_prog_step(p, k, inputs, ctx, err);
        if (status != HL_OK)
            return status;
    }
    return HL_OK;
}

/* ---- public entry points -------------------------------------------------------- */

hl_status hl_series_eval_expr(hl_series *out, const hl_expr *e, int nsym, const char *const *names,
                              const hl_series *vals, int n, hl_alg_ctx *ctx, hl_error *err)
{
    series_prog *p;
    int status = series_prog_compile(&p, 1, &e, nsym, names, n, ctx, err);
    if (status != HL_OK)
        return status;
    status = series_prog_run(p, n, vals, ctx, err);
    if (status == HL_OK)
        hl_series_set(out, series_prog_root(p, 0), ctx);
    series_prog_free(p, ctx);
    return status;
}

/* A one-node program on the input a: a^e when f is HL_FUN_COUNT, else f(a). */
static int apply_node(hl_series *r, const hl_series *a, hl_fun f, const fmpq_t e, hl_alg_ctx *ctx,
                      hl_error *err)
{
    series_prog *p = prog_new(a->n, 1, ctx);
    int in = new_node(p, NODE_INPUT, -1, -1, ctx);
    p->node[in].sym = 0;
    p->root[0] = f == HL_FUN_COUNT ? powq_node(p, in, e, ctx) : fun_node(p, f, in, -1, ctx);
    int status = series_prog_run(p, a->n, a, ctx, err);
    if (status == HL_OK)
        hl_series_set(r, series_prog_root(p, 0), ctx);
    series_prog_free(p, ctx);
    return status;
}

hl_status hl_series_apply(hl_series *r, hl_fun f, const hl_series *a, hl_alg_ctx *ctx,
                          hl_error *err)
{
    if ((unsigned)f >= HL_FUN_COUNT || hl_fun_arity(f) != 1)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "unknown function of one argument");
    return apply_node(r, a, f, NULL, ctx, err);
}

hl_status hl_series_pow_fmpq(hl_series *r, const hl_series *a, const fmpq_t e, hl_alg_ctx *ctx,
                             hl_error *err)
{
    if (fmpz_is_one(fmpq_denref(e)) && fmpz_fits_si(fmpq_numref(e)))
        return hl_series_pow_si(r, a, fmpz_get_si(fmpq_numref(e)), ctx, err);
    return apply_node(r, a, HL_FUN_COUNT, e, ctx, err);
}
