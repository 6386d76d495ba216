/* Taylor mode: an expression DAG compiled once into a list of nodes in
 * topological order, then evaluated coefficient by coefficient: step k
 * computes the D^k coefficient of every node from the coefficients below k
 * (Hairer, Norsett, Wanner, Solving ODEs I, §I.8; Jorba & Zou 2005).  With
 * u the argument and f = F(u):
 *   F' = G(f) known  =>  f_k = (1/k) sum_{j=1..k} j u_j g_{k-j}
 *   (exp: g = f; sin/cos: g = cos/-sin, computed together; tan: g = 1 + f^2);
 *   u^e (e rational):  f_k = 1/(k u_0) sum_{j=1..k} ((e+1) j - k) u_j f_{k-j};
 *   log, atan, asin, acos:  f = F(u_0) + integral of u'/R, R = u, 1 + u^2,
 *   sqrt(1 - u^2), by series division;
 *   atan2(y, x):  f = atan2(y_0, x_0) + integral of (x y' - y x')/(x^2 + y^2).
 * Only F(u_0) goes through the algebra layer (hl_alg_apply); the rest is
 * exact arithmetic on the coefficients.
 *
 * Coefficient-wise evaluation is what makes the order-by-order solver cost
 * O(n^2) products per node instead of O(n^3): a new order of the unknowns
 * only adds a coefficient.  Subtrees without symbols are folded to constants
 * by the algebra layer (exactly: sin(pi/3), sqrt(8)); integer powers become
 * products (so (D + x D^2)^3 needs no nonzero constant term); other powers
 * with constant exponents use the recurrence above, non-constant exponents
 * exp(b log a).  The compile walk is iterative (explicit stack) so that the
 * long sums hl_alg_to_expr writes cannot exhaust the C stack. */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "series/series_impl.h"

enum {
    OP_CONST, /* cst */
    OP_INPUT, /* the caller's series number sym */
    OP_NEG,
    OP_ADD,
    OP_SUB,
    OP_MUL,
    OP_DIV,  /* inv = 1/b_0 */
    OP_POWQ, /* a^e, inv = 1/a_0; fun = HL_SQRT: e = 1/2, value via hl_alg_apply */
    OP_FUN   /* fun(a), aux as below */
};

typedef struct tnode {
    int op;
    hl_fun fun;
    int a, b;         /* operand nodes, -1 if none */
    int sym;          /* OP_INPUT: index into the inputs */
    const char *name; /* OP_INPUT: the symbol (borrowed from the expression) */
    int has_e;
    fmpq_t e;    /* OP_POWQ */
    hl_alg cst;  /* OP_CONST */
    hl_alg inv;  /* the inverse of a constant term, see ops */
    hl_series v; /* the node's coefficients */
    hl_series aux[3];
} tnode;

struct series_prog {
    tnode *node;
    int nnode, anode;
    int *root;
    int nroot;
    int n; /* coefficients allocated */
    long max_terms; /* the budget of all coefficients together (0: none) */
    long terms;     /* their terms so far */
};

/* ---- nodes ----------------------------------------------------------------- */

static int new_node(series_prog *p, int op, int a, int b, const hl_alg_ctx *ctx)
{
    if (p->nnode == p->anode) {
        p->anode = p->anode ? 2 * p->anode : 32;
        p->node = hl_xrealloc(p->node, (size_t)p->anode * sizeof *p->node);
    }
    tnode *t = &p->node[p->nnode];
    memset(t, 0, sizeof *t);
    t->op = op;
    t->a = a;
    t->b = b;
    t->sym = -1;
    hl_alg_init(&t->cst, ctx);
    hl_alg_init(&t->inv, ctx);
    hl_series_init(&t->v, p->n, ctx);
    for (int i = 0; i < 3; i++)
        hl_series_init(&t->aux[i], 0, ctx);
    return p->nnode++;
}

void series_prog_free(series_prog *p, const hl_alg_ctx *ctx)
{
    if (!p)
        return;
    for (int i = 0; i < p->nnode; i++) {
        tnode *t = &p->node[i];
        hl_alg_clear(&t->cst, ctx);
        hl_alg_clear(&t->inv, ctx);
        hl_series_clear(&t->v, ctx);
        for (int j = 0; j < 3; j++)
            hl_series_clear(&t->aux[j], ctx);
        if (t->has_e)
            fmpq_clear(t->e);
    }
    free(p->node);
    free(p->root);
    free(p);
}

const hl_series *series_prog_root(const series_prog *p, int i)
{
    return &p->node[p->root[i]].v;
}

/* ---- compilation ------------------------------------------------------------- */

typedef struct nmap { /* expression -> node, open addressing */
    const hl_expr **key;
    int *val;
    size_t cap, used;
} nmap;

static size_t nmap_slot(const nmap *m, const hl_expr *e)
{
    size_t i = ((size_t)((uintptr_t)e >> 4) * 0x9E3779B97F4A7C15ull) & (m->cap - 1);
    while (m->key[i] != NULL && m->key[i] != e)
        i = (i + 1) & (m->cap - 1);
    return i;
}

static int nmap_get(const nmap *m, const hl_expr *e)
{
    size_t i = nmap_slot(m, e);
    return m->key[i] ? m->val[i] : -1;
}

static void nmap_put(nmap *m, const hl_expr *e, int v)
{
    if (2 * (m->used + 1) > m->cap) {
        nmap old = *m;
        m->cap *= 2;
        m->key = hl_xcalloc(m->cap, sizeof *m->key);
        m->val = hl_xcalloc(m->cap, sizeof *m->val);
        for (size_t i = 0; i < old.cap; i++)
            if (old.key[i]) {
                size_t j = nmap_slot(m, old.key[i]);
                m->key[j] = old.key[i];
                m->val[j] = old.val[i];
            }
        free(old.key);
        free(old.val);
    }
    size_t i = nmap_slot(m, e);
    m->used += m->key[i] == NULL;
    m->key[i] = e;
    m->val[i] = v;
}

static int is_const(const series_prog *p, int i)
{
    return i >= 0 && p->node[i].op == OP_CONST;
}

/* Fold a node whose operands are constants. */
static int fold(series_prog *p, int *out, const hl_expr *x, int a, int b, hl_alg_ctx *ctx,
                hl_error *err)
{
    int i = new_node(p, OP_CONST, -1, -1, ctx);
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
        acc = new_node(p, OP_CONST, -1, -1, ctx);
        hl_alg_one(&p->node[acc].cst, ctx);
        return acc;
    }
    while (u != 0) {
        if (u & 1)
            acc = acc < 0 ? base : new_node(p, OP_MUL, acc, base, ctx);
        u >>= 1;
        if (u != 0)
            base = new_node(p, OP_MUL, base, base, ctx);
    }
    if (e < 0) {
        int one = new_node(p, OP_CONST, -1, -1, ctx);
        hl_alg_one(&p->node[one].cst, ctx);
        acc = new_node(p, OP_DIV, one, acc, ctx);
    }
    return acc;
}

static int powq_node(series_prog *p, int a, const fmpq_t e, hl_alg_ctx *ctx)
{
    int i = new_node(p, OP_POWQ, a, -1, ctx);
    fmpq_init(p->node[i].e);
    fmpq_set(p->node[i].e, e);
    p->node[i].has_e = 1;
    return i;
}

static int fun_node(series_prog *p, hl_fun f, int a, hl_alg_ctx *ctx)
{
    if (f == HL_SQRT) {
        fmpq_t h;
        fmpq_init(h);
        fmpq_set_si(h, 1, 2);
        int i = powq_node(p, a, h, ctx);
        p->node[i].fun = HL_SQRT;
        fmpq_clear(h);
        return i;
    }
    int i = new_node(p, OP_FUN, a, -1, ctx);
    p->node[i].fun = f;
    int naux = 0;
    switch (f) {
    case HL_SIN:
    case HL_COS:
    case HL_SINH:
    case HL_COSH:
    case HL_TAN:
    case HL_TANH:
        naux = 1;
        break;
    case HL_LOG:
        naux = 3;
        break;
    case HL_ATAN:
    case HL_ASIN:
    case HL_ACOS:
        naux = 3;
        break;
    default:
        break;
    }
    for (int j = 0; j < naux; j++)
        hl_series_zero(&p->node[i].aux[j], p->n, ctx);
    return i;
}

/* atan2(y, x) of the nodes a = y, b = x: aux[0] = x^2 + y^2, aux[2] = the
 * derivative's series (step_atan2). */
static int atan2_node(series_prog *p, int a, int b, hl_alg_ctx *ctx)
{
    int i = new_node(p, OP_FUN, a, b, ctx);
    p->node[i].fun = HL_ATAN2;
    for (int j = 0; j < 3; j++)
        hl_series_zero(&p->node[i].aux[j], p->n, ctx);
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
        int l = fun_node(p, HL_LOG, a, ctx);
        int m = new_node(p, OP_MUL, b, l, ctx);
        i = fun_node(p, HL_EXP, m, ctx);
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
                *out = new_node(p, OP_INPUT, -1, -1, ctx);
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
        *out = new_node(p, OP_NEG, a, -1, ctx);
        break;
    case HL_ADD:
        *out = new_node(p, OP_ADD, a, b, ctx);
        break;
    case HL_SUB:
        *out = new_node(p, OP_SUB, a, b, ctx);
        break;
    case HL_MUL:
        *out = new_node(p, OP_MUL, a, b, ctx);
        break;
    case HL_DIV:
        *out = new_node(p, OP_DIV, a, b, ctx);
        break;
    case HL_POW:
        *out = pow_node(p, a, b, ctx);
        break;
    case HL_FUN:
        *out = x->b != NULL ? atan2_node(p, a, b, ctx) : fun_node(p, x->fun, a, ctx);
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
    series_prog *p = hl_xcalloc(1, sizeof *p);
    p->n = n;
    p->nroot = nroot;
    p->root = hl_xcalloc((size_t)(nroot > 0 ? nroot : 1), sizeof *p->root);
    nmap m = {hl_xcalloc(64, sizeof(const hl_expr *)), hl_xcalloc(64, sizeof(int)), 64, 0};
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
            if (nmap_get(&m, x) >= 0) {
                top--;
                continue;
            }
            int nc = children(x), pending = 0;
            const hl_expr *kid[2] = {x->a, x->b};
            for (int c = 0; c < nc; c++)
                if (nmap_get(&m, kid[c]) < 0) {
                    if (top == cap) {
                        cap *= 2;
                        stack = hl_xrealloc(stack, (size_t)cap * sizeof *stack);
                    }
                    stack[top++] = kid[c];
                    pending = 1;
                }
            if (pending)
                continue;
            int a = nc >= 1 ? nmap_get(&m, x->a) : -1, b = nc == 2 ? nmap_get(&m, x->b) : -1;
            int i = -1;
            status = emit(p, &i, x, a, b, nsym, names, ctx, err);
            if (status == HL_OK)
                nmap_put(&m, x, i);
            top--;
        }
        if (status == HL_OK)
            p->root[r] = nmap_get(&m, roots[r]);
    }
    free(stack);
    free(m.key);
    free(m.val);
    if (status != HL_OK) {
        series_prog_free(p, ctx);
        return status;
    }
    *out = p;
    return HL_OK;
}

/* ---- one coefficient of every node -------------------------------------------- */

/* (1/k) sum_{j=1..k} j u_j g_{k-j} */
static void conv_deriv(hl_alg *out, const hl_series *u, const hl_series *g, int k, hl_alg_ctx *ctx)
{
    hl_alg s, t;
    fmpq_t c;
    hl_alg_init(&s, ctx);
    hl_alg_init(&t, ctx);
    fmpq_init(c);
    for (int j = 1; j <= k; j++) {
        if (series_trivially_zero(&u->c[j], ctx) || series_trivially_zero(&g->c[k - j], ctx))
            continue;
        hl_alg_mul(&t, &u->c[j], &g->c[k - j], ctx);
        fmpq_set_si(c, j, (ulong)k);
        hl_alg_scalar_mul_fmpq(&t, &t, c, ctx);
        hl_alg_add(&s, &s, &t, ctx);
    }
    hl_alg_swap(out, &s, ctx);
    fmpq_clear(c);
    hl_alg_clear(&s, ctx);
    hl_alg_clear(&t, ctx);
}

/* sum_{i=lo..k-lo} a_i b_{k-i} */
static void cauchy(hl_alg *out, const hl_series *a, const hl_series *b, int k, int lo,
                   hl_alg_ctx *ctx)
{
    hl_alg s, t;
    hl_alg_init(&s, ctx);
    hl_alg_init(&t, ctx);
    for (int i = lo; i <= k - lo; i++) {
        if (series_trivially_zero(&a->c[i], ctx) || series_trivially_zero(&b->c[k - i], ctx))
            continue;
        hl_alg_mul(&t, &a->c[i], &b->c[k - i], ctx);
        hl_alg_add(&s, &s, &t, ctx);
    }
    hl_alg_swap(out, &s, ctx);
    hl_alg_clear(&s, ctx);
    hl_alg_clear(&t, ctx);
}

static int inverse_of(hl_alg *inv, const hl_alg *c, const char *what, hl_alg_ctx *ctx,
                      hl_error *err)
{
    if (hl_alg_is_zero(c, ctx))
        return hl_error_set(err, HL_EDOM, NULL, -1, 0, "%s of a series that vanishes at D = 0",
                            what);
    hl_alg_one(inv, ctx);
    return hl_alg_div(inv, inv, c, ctx, err);
}

static int step_div(tnode *t, const tnode *A, const tnode *B, int k, hl_alg_ctx *ctx, hl_error *err)
{
    if (k == 0) {
        int status = inverse_of(&t->inv, &B->v.c[0], "division by", ctx, err);
        if (status == HL_OK)
            hl_alg_mul(&t->v.c[0], &A->v.c[0], &t->inv, ctx);
        return status;
    }
    hl_alg s; /* (a_k - sum_{j=1..k} b_j q_{k-j}) / b_0 */
    hl_alg_init(&s, ctx);
    cauchy(&s, &B->v, &t->v, k, 1, ctx); /* j = 1..k: b_j q_{k-j}, with q_{0..k-1} */
    {
        /* cauchy runs i = 1..k-1; add b_k q_0 */
        hl_alg x;
        hl_alg_init(&x, ctx);
        hl_alg_mul(&x, &B->v.c[k], &t->v.c[0], ctx);
        hl_alg_add(&s, &s, &x, ctx);
        hl_alg_clear(&x, ctx);
    }
    hl_alg_sub(&s, &A->v.c[k], &s, ctx);
    hl_alg_mul(&t->v.c[k], &s, &t->inv, ctx);
    hl_alg_clear(&s, ctx);
    return HL_OK;
}

static int step_powq(tnode *t, const tnode *A, int k, hl_alg_ctx *ctx, hl_error *err)
{
    const hl_series *u = &A->v;
    if (k == 0) {
        int status = inverse_of(&t->inv, &u->c[0], t->fun == HL_SQRT ? "sqrt" : "non-integer power",
                                ctx, err);
        if (status != HL_OK)
            return status;
        return t->fun == HL_SQRT ? hl_alg_apply(&t->v.c[0], HL_SQRT, &u->c[0], ctx, err)
                                 : hl_alg_pow_fmpq(&t->v.c[0], &u->c[0], t->e, ctx, err);
    }
    hl_alg s, x;
    fmpq_t c, ik;
    hl_alg_init(&s, ctx);
    hl_alg_init(&x, ctx);
    fmpq_init(c);
    fmpq_init(ik);
    fmpq_set_si(ik, 1, (ulong)k);
    for (int j = 1; j <= k; j++) {
        if (series_trivially_zero(&u->c[j], ctx))
            continue;
        fmpq_add_si(c, t->e, 1); /* ((e+1) j - k)/k */
        fmpq_mul_si(c, c, j);
        fmpq_sub_si(c, c, k);
        fmpq_mul(c, c, ik);
        hl_alg_mul(&x, &u->c[j], &t->v.c[k - j], ctx);
        hl_alg_scalar_mul_fmpq(&x, &x, c, ctx);
        hl_alg_add(&s, &s, &x, ctx);
    }
    hl_alg_mul(&t->v.c[k], &s, &t->inv, ctx);
    fmpq_clear(c);
    fmpq_clear(ik);
    hl_alg_clear(&s, ctx);
    hl_alg_clear(&x, ctx);
    return HL_OK;
}

/* sin/cos, sinh/cosh: v and its companion aux[0]. */
static int step_pair(tnode *t, const hl_series *u, int k, hl_alg_ctx *ctx, hl_error *err)
{
    int trig = t->fun == HL_SIN || t->fun == HL_COS;
    int is_first = t->fun == HL_SIN || t->fun == HL_SINH; /* v is sin/sinh */
    hl_series *s = is_first ? &t->v : &t->aux[0], *c = is_first ? &t->aux[0] : &t->v;
    if (k == 0) {
        int status = hl_alg_apply(&s->c[0], trig ? HL_SIN : HL_SINH, &u->c[0], ctx, err);
        if (status == HL_OK)
            status = hl_alg_apply(&c->c[0], trig ? HL_COS : HL_COSH, &u->c[0], ctx, err);
        return status;
    }
    conv_deriv(&s->c[k], u, c, k, ctx); /* s' = u' c */
    conv_deriv(&c->c[k], u, s, k, ctx); /* c' = -u' s (trig), u' s (hyperbolic) */
    if (trig)
        hl_alg_neg(&c->c[k], &c->c[k], ctx);
    return HL_OK;
}

/* tan (w = 1 + v^2), tanh (w = 1 - v^2): v' = u' w. */
static int step_tan(tnode *t, const hl_series *u, int k, hl_alg_ctx *ctx, hl_error *err)
{
    hl_series *w = &t->aux[0];
    if (k == 0) {
        int status = hl_alg_apply(&t->v.c[0], t->fun, &u->c[0], ctx, err);
        if (status != HL_OK)
            return status;
    } else {
        conv_deriv(&t->v.c[k], u, w, k, ctx);
    }
    cauchy(&w->c[k], &t->v, &t->v, k, 0, ctx);
    if (t->fun == HL_TANH)
        hl_alg_neg(&w->c[k], &w->c[k], ctx);
    if (k == 0) {
        hl_alg one;
        hl_alg_init(&one, ctx);
        hl_alg_one(&one, ctx);
        hl_alg_add(&w->c[0], &w->c[0], &one, ctx);
        hl_alg_clear(&one, ctx);
    }
    return HL_OK;
}

/* log, atan, asin, acos: v = F(u_0) + integral of u'/R.
 * aux[0] = R (log: unused, R = u), aux[1] = 1 - u^2 (asin, acos), aux[2] = g = u'/R. */
static int step_inverse(tnode *t, const hl_series *u, int k, hl_alg_ctx *ctx, hl_error *err)
{
    hl_fun f = t->fun;
    const hl_series *R = f == HL_LOG ? u : &t->aux[0];
    hl_series *S = &t->aux[1], *g = &t->aux[2];
    int status = HL_OK;
    /* R_k */
    if (f == HL_ATAN) {
        cauchy(&t->aux[0].c[k], u, u, k, 0, ctx);
        if (k == 0) {
            hl_alg one;
            hl_alg_init(&one, ctx);
            hl_alg_one(&one, ctx);
            hl_alg_add(&t->aux[0].c[0], &t->aux[0].c[0], &one, ctx);
            hl_alg_clear(&one, ctx);
        }
    } else if (f != HL_LOG) { /* R = sqrt(S), S = 1 - u^2 */
        cauchy(&S->c[k], u, u, k, 0, ctx);
        hl_alg_neg(&S->c[k], &S->c[k], ctx);
        if (k == 0) {
            hl_alg one;
            hl_alg_init(&one, ctx);
            hl_alg_one(&one, ctx);
            hl_alg_add(&S->c[0], &S->c[0], &one, ctx);
            hl_alg_clear(&one, ctx);
            if (hl_alg_is_zero(&S->c[0], ctx))
                return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                                    "%s of a series equal to 1 or -1 at D = 0", hl_fun_name(f));
            status = hl_alg_apply(&t->aux[0].c[0], HL_SQRT, &S->c[0], ctx, err);
        } else { /* R_k = (S_k - sum_{j=1..k-1} R_j R_{k-j}) / (2 R_0) */
            hl_alg s;
            hl_alg_init(&s, ctx);
            cauchy(&s, &t->aux[0], &t->aux[0], k, 1, ctx);
            hl_alg_sub(&s, &S->c[k], &s, ctx);
            fmpq_t h;
            fmpq_init(h);
            fmpq_set_si(h, 1, 2);
            hl_alg_scalar_mul_fmpq(&s, &s, h, ctx);
            fmpq_clear(h);
            hl_alg_mul(&t->aux[0].c[k], &s, &t->inv, ctx);
            hl_alg_clear(&s, ctx);
        }
    }
    if (status != HL_OK)
        return status;
    if (k == 0) {
        status = inverse_of(&t->inv, &R->c[0], hl_fun_name(f), ctx, err);
        if (status == HL_OK)
            status = hl_alg_apply(&t->v.c[0], f, &u->c[0], ctx, err);
        return status;
    }
    /* g_{k-1} = (k u_k - sum_{j=1..k-1} R_j g_{k-1-j}) / R_0, v_k = +-g_{k-1}/k */
    hl_alg s, x;
    fmpq_t c;
    hl_alg_init(&s, ctx);
    hl_alg_init(&x, ctx);
    fmpq_init(c);
    for (int j = 1; j <= k - 1; j++) {
        if (series_trivially_zero(&R->c[j], ctx))
            continue;
        hl_alg_mul(&x, &R->c[j], &g->c[k - 1 - j], ctx);
        hl_alg_add(&s, &s, &x, ctx);
    }
    fmpq_set_si(c, k, 1);
    hl_alg_scalar_mul_fmpq(&x, &u->c[k], c, ctx);
    hl_alg_sub(&s, &x, &s, ctx);
    hl_alg_mul(&g->c[k - 1], &s, &t->inv, ctx);
    fmpq_set_si(c, f == HL_ACOS ? -1 : 1, (ulong)k);
    hl_alg_scalar_mul_fmpq(&t->v.c[k], &g->c[k - 1], c, ctx);
    fmpq_clear(c);
    hl_alg_clear(&s, ctx);
    hl_alg_clear(&x, ctx);
    return HL_OK;
}

/* atan2(y, x): v' = g = h/R with h = x y' - y x', R = x^2 + y^2 (aux[0]);
 * g_{k-1} = (h_{k-1} - sum_{j=1..k-1} R_j g_{k-1-j}) / R_0 (aux[2]),
 * h_{k-1} = sum_{j=1..k} j (y_j x_{k-j} - x_j y_{k-j}); v_k = g_{k-1}/k. */
static int step_atan2(tnode *t, const hl_series *y, const hl_series *x, int k, hl_alg_ctx *ctx,
                      hl_error *err)
{
    hl_series *R = &t->aux[0], *g = &t->aux[2];
    hl_alg s, u;
    hl_alg_init(&s, ctx);
    hl_alg_init(&u, ctx);
    cauchy(&s, x, x, k, 0, ctx);
    cauchy(&u, y, y, k, 0, ctx);
    hl_alg_add(&R->c[k], &s, &u, ctx);
    int status = HL_OK;
    if (k == 0) {
        status = hl_alg_apply2(&t->v.c[0], HL_ATAN2, &y->c[0], &x->c[0], ctx, err);
        if (status == HL_OK)
            status = inverse_of(&t->inv, &R->c[0], "atan2", ctx, err);
    } else {
        fmpq_t c;
        fmpq_init(c);
        conv_deriv(&s, y, x, k, ctx); /* h_{k-1} / k */
        conv_deriv(&u, x, y, k, ctx);
        hl_alg_sub(&s, &s, &u, ctx);
        fmpq_set_si(c, k, 1);
        hl_alg_scalar_mul_fmpq(&s, &s, c, ctx);
        for (int j = 1; j <= k - 1; j++) {
            hl_alg_mul(&u, &R->c[j], &g->c[k - 1 - j], ctx);
            hl_alg_sub(&s, &s, &u, ctx);
        }
        hl_alg_mul(&g->c[k - 1], &s, &t->inv, ctx);
        fmpq_set_si(c, 1, (ulong)k);
        hl_alg_scalar_mul_fmpq(&t->v.c[k], &g->c[k - 1], c, ctx);
        fmpq_clear(c);
    }
    hl_alg_clear(&s, ctx);
    hl_alg_clear(&u, ctx);
    return status;
}

static int step_node(series_prog *p, int i, int k, const hl_series *inputs, hl_alg_ctx *ctx,
                     hl_error *err)
{
    tnode *t = &p->node[i];
    const tnode *A = t->a >= 0 ? &p->node[t->a] : NULL, *B = t->b >= 0 ? &p->node[t->b] : NULL;
    hl_alg *out = &t->v.c[k];
    switch (t->op) {
    case OP_CONST:
        if (k == 0)
            hl_alg_set(out, &t->cst, ctx);
        else
            hl_alg_zero(out, ctx);
        return HL_OK;
    case OP_INPUT:
        if (inputs[t->sym].n <= k)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "the series of '%s' has %d coefficients, %d needed",
                                t->name ? t->name : "?", inputs[t->sym].n, k + 1);
        hl_alg_set(out, &inputs[t->sym].c[k], ctx);
        return HL_OK;
    case OP_NEG:
        hl_alg_neg(out, &A->v.c[k], ctx);
        return HL_OK;
    case OP_ADD:
        hl_alg_add(out, &A->v.c[k], &B->v.c[k], ctx);
        return HL_OK;
    case OP_SUB:
        hl_alg_sub(out, &A->v.c[k], &B->v.c[k], ctx);
        return HL_OK;
    case OP_MUL:
        cauchy(out, &A->v, &B->v, k, 0, ctx);
        return HL_OK;
    case OP_DIV:
        return step_div(t, A, B, k, ctx, err);
    case OP_POWQ:
        return step_powq(t, A, k, ctx, err);
    case OP_FUN:
        switch (t->fun) {
        case HL_EXP:
            if (k == 0)
                return hl_alg_apply(out, HL_EXP, &A->v.c[0], ctx, err);
            conv_deriv(out, &A->v, &t->v, k, ctx);
            return HL_OK;
        case HL_SIN:
        case HL_COS:
        case HL_SINH:
        case HL_COSH:
            return step_pair(t, &A->v, k, ctx, err);
        case HL_TAN:
        case HL_TANH:
            return step_tan(t, &A->v, k, ctx, err);
        case HL_LOG:
        case HL_ATAN:
        case HL_ASIN:
        case HL_ACOS:
            return step_inverse(t, &A->v, k, ctx, err);
        case HL_ATAN2:
            return step_atan2(t, &A->v, &B->v, k, ctx, err);
        default:
            break;
        }
        break;
    }
    return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "unknown function");
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

/* A one-node program on the input a. */
static int apply_node(hl_series *r, const hl_series *a, int op, hl_fun f, const fmpq_t e,
                      hl_alg_ctx *ctx, hl_error *err)
{
    series_prog *p = hl_xcalloc(1, sizeof *p);
    p->n = a->n;
    p->nroot = 1;
    p->root = hl_xcalloc(1, sizeof *p->root);
    int in = new_node(p, OP_INPUT, -1, -1, ctx);
    p->node[in].sym = 0;
    p->root[0] = op == OP_POWQ ? powq_node(p, in, e, ctx) : fun_node(p, f, in, ctx);
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
    return apply_node(r, a, OP_FUN, f, NULL, ctx, err);
}

hl_status hl_series_pow_fmpq(hl_series *r, const hl_series *a, const fmpq_t e, hl_alg_ctx *ctx,
                             hl_error *err)
{
    if (fmpz_is_one(fmpq_denref(e)) && fmpz_fits_si(fmpq_numref(e)))
        return hl_series_pow_si(r, a, fmpz_get_si(fmpq_numref(e)), ctx, err);
    return apply_node(r, a, OP_POWQ, HL_SQRT /* unused */, e, ctx, err);
}
