/* The tape compiler: expression DAG -> straight-line program.
 *
 * One register per DAG node (a map keyed by node pointer: the pool
 * hash-conses, so this is common-subexpression elimination) and one per
 * distinct instruction (a map keyed by (op, a, b): this shares what the
 * lowering creates, e.g. the SINCOS behind both sin(a) and cos(a), or the a^2
 * inside a^3 and a^2).  An instruction whose operands are all constants goes
 * to the prologue, evaluated once per precision; the body sees its result as
 * a constant register and uses the K-variants of the ops (MULK ...), which in
 * Taylor mode cost O(1) per coefficient instead of a convolution. */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "base/memo.h"
#include "rules/rule.h"
#include "tape/arb_em_impl.h"
#include "tape/prog_impl.h"

typedef struct slot {
    uintptr_t key1;
    long key2;
    int reg; /* -1 = empty */
} slot;

typedef struct map {
    slot *s;
    size_t n, used; /* n a power of two */
} map;

static void map_init(map *m)
{
    m->n = 256;
    m->used = 0;
    m->s = hl_xmalloc(m->n * sizeof *m->s);
    for (size_t i = 0; i < m->n; i++)
        m->s[i].reg = -1;
}

static size_t map_hash(uintptr_t k1, long k2)
{
    uint64_t h = (uint64_t)k1 * 0x9e3779b97f4a7c15ULL ^ (uint64_t)k2 * 0xc2b2ae3d27d4eb4fULL;
    return (size_t)(h ^ (h >> 29));
}

static int map_get(const map *m, uintptr_t k1, long k2)
{
    for (size_t i = map_hash(k1, k2) & (m->n - 1);; i = (i + 1) & (m->n - 1)) {
        if (m->s[i].reg < 0)
            return -1;
        if (m->s[i].key1 == k1 && m->s[i].key2 == k2)
            return m->s[i].reg;
    }
}

static void map_put(map *m, uintptr_t k1, long k2, int reg)
{
    if (2 * (m->used + 1) > m->n) {
        map old = *m;
        m->n *= 2;
        m->used = 0;
        m->s = hl_xmalloc(m->n * sizeof *m->s);
        for (size_t i = 0; i < m->n; i++)
            m->s[i].reg = -1;
        for (size_t i = 0; i < old.n; i++)
            if (old.s[i].reg >= 0)
                map_put(m, old.s[i].key1, old.s[i].key2, old.s[i].reg);
        free(old.s);
    }
    size_t i = map_hash(k1, k2) & (m->n - 1);
    while (m->s[i].reg >= 0)
        i = (i + 1) & (m->n - 1);
    m->s[i].key1 = k1;
    m->s[i].key2 = k2;
    m->s[i].reg = reg;
    m->used++;
}

typedef struct comp {
    hl_tape *t;
    hl_memo exprs; /* hl_expr* -> index into vreg / vscale (the library's memo) */
    map leaves;    /* a rational's hash -> index into t->leaf */
    map ins;       /* (op, a, b) -> destination register */
    int *leafof;   /* register -> index in t->leaf, or -1 */
    hl_instr *def; /* register -> the instruction that made it (op -1: none) */
    int *vreg;     /* compiled nodes: node i is vscale[i] * register vreg[i] */
    fmpq *vscale;
    int nval, capval;
    int capregs, capcode, cappro, capleaf;
    const char *const *inputs;
    hl_error *err;
    int in_walk; /* inside compile's post-order walk */
} comp;

static int new_reg(comp *c, int isconst)
{
    hl_tape *t = c->t;
    if (t->nregs == c->capregs) {
        c->capregs = c->capregs ? 2 * c->capregs : 64;
        t->isconst = hl_xrealloc(t->isconst, (size_t)c->capregs);
        c->leafof = hl_xrealloc(c->leafof, (size_t)c->capregs * sizeof *c->leafof);
        c->def = hl_xrealloc(c->def, (size_t)c->capregs * sizeof *c->def);
    }
    t->isconst[t->nregs] = (unsigned char)isconst;
    c->leafof[t->nregs] = -1;
    c->def[t->nregs] = (hl_instr){-1, t->nregs, -1, -1, -1};
    return t->nregs++;
}

static int has_aux(int op)
{
    return op >= HL_OP_SINCOS && op <= HL_OP_ATAN2; /* the ops with an X */
}

/* Emit op(a, b) (b = -1 if unary) unless an identical instruction exists;
 * returns its destination (the aux register is destination + 1). */
static int emit(comp *c, int op, int a, int b)
{
    /* sqrt(w)^2 = w (as everywhere here, for w where sqrt is defined):
     * differentiating 1/sqrt(w) writes it */
    if (op == HL_OP_SQR && c->def[a].op == HL_OP_SQRT)
        return c->def[a].a;
    long key2 = ((long)op << 48) ^ ((long)(b + 1) << 24);
    int d = map_get(&c->ins, (uintptr_t)a, key2);
    if (d >= 0)
        return d;
    hl_tape *t = c->t;
    int isconst = t->isconst[a] && (b < 0 || t->isconst[b]);
    d = new_reg(c, isconst);
    int x = has_aux(op) ? new_reg(c, isconst) : -1;
    hl_instr in = {op, d, a, b, x};
    if (isconst) {
        if (t->npro == c->cappro) {
            c->cappro = c->cappro ? 2 * c->cappro : 16;
            t->pro = hl_xrealloc(t->pro, (size_t)c->cappro * sizeof *t->pro);
        }
        t->pro[t->npro++] = in;
    } else {
        if (t->ncode == c->capcode) {
            c->capcode = c->capcode ? 2 * c->capcode : 64;
            t->code = hl_xrealloc(t->code, (size_t)c->capcode * sizeof *t->code);
        }
        t->code[t->ncode++] = in;
    }
    map_put(&c->ins, (uintptr_t)a, key2, d);
    c->def[d] = in;
    return d;
}

static int leaf(comp *c, const hl_expr *e)
{
    hl_tape *t = c->t;
    if (t->nleaf == c->capleaf) {
        c->capleaf = c->capleaf ? 2 * c->capleaf : 16;
        t->leaf = hl_xrealloc(t->leaf, (size_t)c->capleaf * sizeof *t->leaf);
    }
    hl_leaf *l = &t->leaf[t->nleaf++];
    l->reg = new_reg(c, 1);
    c->leafof[l->reg] = (int)(l - t->leaf);
    l->is_pi = e->kind == HL_PI;
    fmpq_init(l->q);
    if (e->kind == HL_NUM)
        fmpq_set(l->q, e->num);
    return l->reg;
}

/* The register of the rational constant q (one per value).  Found through
 * the node map under keys (2, hash + i), probing i = 0, 1, ... */
static long fmpq_hash(const fmpq_t q)
{
    ulong h = fmpz_fdiv_ui(fmpq_numref(q), 2147483629UL) * 0x9e3779b97f4a7c15UL;
    h ^= fmpz_fdiv_ui(fmpq_denref(q), 2147483587UL) + (ulong)fmpz_sgn(fmpq_numref(q));
    return (long)(h >> 2);
}

static int rational_leaf(comp *c, const fmpq_t q)
{
    hl_tape *t = c->t;
    long h = fmpq_hash(q);
    int i;
    for (;; h++) {
        if ((i = map_get(&c->leaves, (uintptr_t)2, h)) < 0)
            break;
        if (fmpq_equal(t->leaf[i].q, q))
            return t->leaf[i].reg;
    }
    if (t->nleaf == c->capleaf) {
        c->capleaf = c->capleaf ? 2 * c->capleaf : 16;
        t->leaf = hl_xrealloc(t->leaf, (size_t)c->capleaf * sizeof *t->leaf);
    }
    map_put(&c->leaves, (uintptr_t)2, h, t->nleaf);
    hl_leaf *l = &t->leaf[t->nleaf++];
    l->reg = new_reg(c, 1);
    c->leafof[l->reg] = (int)(l - t->leaf);
    l->is_pi = 0;
    fmpq_init(l->q);
    fmpq_set(l->q, q);
    return l->reg;
}

static int const_si(comp *c, long v)
{
    fmpq_t q;
    fmpq_init(q);
    fmpq_set_si(q, v, 1);
    int r = rational_leaf(c, q);
    fmpq_clear(q);
    return r;
}

/* Is register r a rational constant?  Then q = its value. */
static int is_rational(comp *c, int r, fmpq_t q)
{
    int i = c->leafof[r];
    if (i < 0 || c->t->leaf[i].is_pi)
        return 0;
    fmpq_set(q, c->t->leaf[i].q);
    return 1;
}

/* Is register r made as 1/u (KDIV u 1)? */
static int is_one_over(comp *c, int r)
{
    const hl_instr *d = &c->def[r];
    if (d->op != HL_OP_KDIV)
        return 0;
    int i = c->leafof[d->b];
    return i >= 0 && !c->t->leaf[i].is_pi && fmpq_is_one(c->t->leaf[i].q);
}

/* r = sqrt(w)? */
static int is_sqrt_of(comp *c, int r, int w)
{
    return c->def[r].op == HL_OP_SQRT && c->def[r].a == w;
}

/* sqrt(w) w as w^(3/2) (Kepler's r^3): one recurrence instead of two, and
 * written here, in the tape, so that every back end computes the same
 * (rules/pow3h.c: w sqrt(w) at a point, not pow()). */
static int three_halves(comp *c, int w)
{
    return emit(c, HL_OP_POW3H, w, -1);
}

/* Binary op with the K-variants when one side is constant. */
static int binop(comp *c, hl_expr_kind kind, int a, int b)
{
    const unsigned char *k = c->t->isconst;
    int ka = k[a] && !k[b], kb = k[b] && !k[a];
    switch (kind) {
    case HL_ADD:
        if (kb) return emit(c, HL_OP_ADDK, a, b);
        if (ka) return emit(c, HL_OP_ADDK, b, a);
        return emit(c, HL_OP_ADD, a, b);
    case HL_SUB:
        if (kb) return emit(c, HL_OP_SUBK, a, b);
        if (ka) return emit(c, HL_OP_KSUB, b, a);
        return emit(c, HL_OP_SUB, a, b);
    case HL_MUL:
        if (a == b) return emit(c, HL_OP_SQR, a, -1);
        /* a * (1/u) = a / u: a DIV costs what a MUL does, and the 1/u
         * may then go unused */
        if (!k[a] && is_one_over(c, b)) return emit(c, HL_OP_DIV, a, c->def[b].a);
        if (!k[b] && is_one_over(c, a)) return emit(c, HL_OP_DIV, b, c->def[a].a);
        if (kb) return emit(c, HL_OP_MULK, a, b);
        if (ka) return emit(c, HL_OP_MULK, b, a);
        if (is_sqrt_of(c, a, b))
            return three_halves(c, b);
        if (is_sqrt_of(c, b, a))
            return three_halves(c, a);
        return emit(c, HL_OP_MUL, a, b);
    default: /* HL_DIV */
        if (kb) return emit(c, HL_OP_DIVK, a, b);
        if (ka) return emit(c, HL_OP_KDIV, b, a);
        /* (x/u)/w = x/(u w): the same count, and u w is shared when
         * several components divide by both (x/r/r^2, y/r/r^2 in Kepler) */
        if (c->def[a].op == HL_OP_DIV && !k[c->def[a].b])
            return emit(c, HL_OP_DIV, c->def[a].a, binop(c, HL_MUL, c->def[a].b, b));
        return emit(c, HL_OP_DIV, a, b);
    }
}

/* a^n by binary powering; the map shares the partial powers. */
static int powi(comp *c, int a, long n)
{
    if (n < 0)
        return binop(c, HL_DIV, const_si(c, 1), powi(c, a, -n));
    if (n == 0)
        return const_si(c, 1);
    if (n == 1)
        return a;
    int h = powi(c, a, n / 2);
    int sq = emit(c, HL_OP_SQR, h, -1);
    return n % 2 ? binop(c, HL_MUL, sq, a) : sq;
}

/* ---- scaled values -----------------------------------------------------------
 * A compiled subexpression is s * r: a rational scale s (never 0) times a
 * register r.  Rational factors then travel up the tree and meet instead of
 * each costing an instruction: differentiation writes d(p^2/2)/dp as
 * (2*p)/2, which compiles to p itself; -(-(x)) to x; 3*x + 6*y to
 * 3*(x + 2*y).  A scale becomes an instruction only where it must
 * (materialize): under a function, a non-integer power, or at an output.
 * Like any algebraic folding this takes x - x and 0*x to be 0 even where
 * x would be inf or NaN. */

static int materialize(comp *c, int r, const fmpq_t s)
{
    if (fmpq_is_one(s))
        return r;
    fmpq_t q;
    fmpq_init(q);
    int out;
    if (is_rational(c, r, q)) {
        fmpq_mul(q, q, s);
        out = rational_leaf(c, q);
    } else if (fmpz_is_one(fmpq_denref(s)) && fmpz_equal_si(fmpq_numref(s), -1)) {
        out = emit(c, HL_OP_NEG, r, -1);
    } else {
        out = binop(c, HL_MUL, r, rational_leaf(c, s));
    }
    fmpq_clear(q);
    return out;
}

static int compile(comp *c, const hl_expr *e, int *reg, fmpq_t s);

/* Compile and materialize. */
static int compile_reg(comp *c, const hl_expr *e, int *reg)
{
    fmpq_t s;
    fmpq_init(s);
    int status = compile(c, e, reg, s);
    if (status == HL_OK)
        *reg = materialize(c, *reg, s);
    fmpq_clear(s);
    return status;
}

static int compile_pow(comp *c, const hl_expr *e, int *reg, fmpq_t s)
{
    const hl_expr *x = e->b;
    int a, status;
    if (x->kind == HL_NUM && fmpz_is_one(fmpq_denref(x->num))
        && fmpz_fits_si(fmpq_numref(x->num))
        && labs(fmpz_get_si(fmpq_numref(x->num))) <= HL_TAPE_POWI_MAX) {
        long n = fmpz_get_si(fmpq_numref(x->num));
        if ((status = compile(c, e->a, &a, s)) != HL_OK)
            return status;
        fmpq_t q;
        fmpq_init(q);
        if (is_rational(c, a, q) && (n >= 0 || !fmpq_is_zero(q))) {
            fmpq_mul(q, q, s);
            fmpq_pow_si(q, q, n);
            *reg = rational_leaf(c, q);
            fmpq_one(s);
        } else {
            *reg = powi(c, a, n);
            fmpq_pow_si(s, s, n); /* s != 0 */
        }
        fmpq_clear(q);
        return HL_OK;
    }
    fmpq_one(s);
    if ((status = compile_reg(c, e->a, &a)) != HL_OK)
        return status;
    if (x->kind == HL_NUM && fmpz_is_one(fmpq_numref(x->num))
        && fmpz_cmp_ui(fmpq_denref(x->num), 2) == 0) {
        *reg = emit(c, HL_OP_SQRT, a, -1);
        return HL_OK;
    }
    if (x->kind == HL_NUM && fmpz_equal_si(fmpq_numref(x->num), 3) &&
        fmpz_equal_si(fmpq_denref(x->num), 2)) {
        *reg = three_halves(c, a);
        return HL_OK;
    }
    int b;
    if ((status = compile_reg(c, x, &b)) != HL_OK)
        return status;
    if (c->t->isconst[b]) {
        *reg = emit(c, HL_OP_POWK, a, b);
        return HL_OK;
    }
    /* a^b = exp(b log a) */
    int l = emit(c, HL_OP_LOG, a, -1);
    *reg = emit(c, HL_OP_EXP, binop(c, HL_MUL, b, l), -1);
    return HL_OK;
}

/* f(a) by the op of the rules' table; cos and cosh are their pair's second
 * result, its aux register d + 1 */
static int compile_fun(comp *c, hl_fun f, int a)
{
    int second;
    if (f == HL_ATAN2)
        return -1;
    return emit(c, hl_fun_op(f, &second), a, -1) + second;
}

/* s = sa*a (+ or -) sb*b as (register, scale) */
static void compile_addsub(comp *c, int sub, int a, const fmpq_t sa, int b, const fmpq_t sb,
                           int *reg, fmpq_t s)
{
    fmpq_t qa, qb, rho;
    fmpq_init(qa);
    fmpq_init(qb);
    fmpq_init(rho);
    int ra = is_rational(c, a, qa), rb = is_rational(c, b, qb);
    fmpq_set(s, sb);
    if (sub)
        fmpq_neg(s, s); /* s = signed scale of b */
    if (ra && rb) {
        fmpq_mul(qa, qa, sa);
        fmpq_mul(qb, qb, s);
        fmpq_add(qa, qa, qb);
        *reg = rational_leaf(c, qa);
        fmpq_one(s);
    } else if (ra) {
        /* sa qa + s b = s (b + sa qa / s) */
        fmpq_mul(qa, qa, sa);
        fmpq_div(qa, qa, s);
        *reg = fmpq_is_zero(qa) ? b : binop(c, HL_ADD, b, rational_leaf(c, qa));
    } else if (rb) {
        /* sa a + s qb = sa (a + s qb / sa) */
        fmpq_mul(qb, qb, s);
        fmpq_div(qb, qb, sa);
        *reg = fmpq_is_zero(qb) ? a : binop(c, HL_ADD, a, rational_leaf(c, qb));
        fmpq_set(s, sa);
    } else if (a == b) {
        /* sa a + s a = (sa + s) a */
        fmpq_add(s, s, sa);
        *reg = a;
        if (fmpq_is_zero(s)) {
            *reg = const_si(c, 0);
            fmpq_one(s);
        }
    } else {
        /* sa (a + rho b), rho = s / sa */
        fmpq_div(rho, s, sa);
        int neg = fmpq_sgn(rho) < 0;
        if (neg)
            fmpq_neg(rho, rho);
        *reg = binop(c, neg ? HL_SUB : HL_ADD, a, materialize(c, b, rho));
        fmpq_set(s, sa);
    }
    fmpq_clear(qa);
    fmpq_clear(qb);
    fmpq_clear(rho);
}

/* sa*a * sb*b, or sa*a / sb*b */
static void compile_muldiv(comp *c, int div, int a, const fmpq_t sa, int b, const fmpq_t sb,
                           int *reg, fmpq_t s)
{
    fmpq_t qa, qb;
    fmpq_init(qa);
    fmpq_init(qb);
    int ra = is_rational(c, a, qa), rb = is_rational(c, b, qb);
    if (div)
        fmpq_div(s, sa, sb);
    else
        fmpq_mul(s, sa, sb);
    if (rb && !(div && fmpq_is_zero(qb))) {
        if (div)
            fmpq_div(s, s, qb);
        else
            fmpq_mul(s, s, qb);
        *reg = a; /* a may itself be rational: its scale stays in s */
    } else if (ra && !rb) {
        fmpq_mul(s, s, qa);
        *reg = div ? binop(c, HL_DIV, const_si(c, 1), b) : b;
    } else {
        *reg = binop(c, div ? HL_DIV : HL_MUL, a, b);
    }
    if (fmpq_is_zero(s)) { /* 0 * anything: the constant 0 */
        *reg = const_si(c, 0);
        fmpq_one(s);
    }
    fmpq_clear(qa);
    fmpq_clear(qb);
}

static int compile_node(comp *c, const hl_expr *e, int *reg, fmpq_t s);

static int compiled(comp *c, const hl_expr *e, int *reg, fmpq_t s)
{
    const hl_memo_val *v = hl_memo_get(&c->exprs, e);
    if (v == NULL)
        return 0;
    *reg = c->vreg[v->i];
    fmpq_set(s, c->vscale + v->i);
    return 1;
}

static int compile_visit(void *arg, const hl_expr *e)
{
    int reg;
    fmpq_t s;
    fmpq_init(s);
    int status = compile(arg, e, &reg, s);
    fmpq_clear(s);
    return status;
}

/* Generated expressions (derivatives, expansions) can be far deeper than
 * anything the parser accepts: the nodes are compiled in post-order
 * (hl_expr_postorder), so each finds its operands compiled and nothing
 * recurses on the C stack. */
static int compile(comp *c, const hl_expr *e, int *reg, fmpq_t s)
{
    if (compiled(c, e, reg, s))
        return HL_OK;
    if (c->in_walk)
        return compile_node(c, e, reg, s);
    c->in_walk = 1;
    int status = hl_expr_postorder(&e, 1, compile_visit, c);
    c->in_walk = 0;
    if (status == HL_OK && !compiled(c, e, reg, s))
        status = compile_node(c, e, reg, s);
    return status;
}

/* compile() for a node not compiled yet. */
static int compile_node(comp *c, const hl_expr *e, int *reg, fmpq_t s)
{
    int a = -1, b = -1, r = -1, status = HL_OK;
    fmpq_t sa, sb;
    fmpq_init(sa);
    fmpq_init(sb);
    fmpq_one(s);
    switch (e->kind) {
    case HL_NUM:
        r = rational_leaf(c, e->num);
        break;
    case HL_PI:
        r = leaf(c, e);
        break;
    case HL_SYM:
        for (int i = 0; i < c->t->nin; i++)
            if (strcmp(c->inputs[i], e->name) == 0)
                r = i;
        if (r < 0)
            status = hl_error_set(c->err, HL_EINVAL, NULL, -1, 0, "unknown symbol '%s'", e->name);
        break;
    case HL_NEG:
        if ((status = compile(c, e->a, &r, s)) == HL_OK)
            fmpq_neg(s, s);
        break;
    case HL_ADD:
    case HL_SUB:
    case HL_MUL:
    case HL_DIV:
        if ((status = compile(c, e->a, &a, sa)) != HL_OK || (status = compile(c, e->b, &b, sb)) != HL_OK)
            break;
        if (e->kind == HL_ADD || e->kind == HL_SUB)
            compile_addsub(c, e->kind == HL_SUB, a, sa, b, sb, &r, s);
        else
            compile_muldiv(c, e->kind == HL_DIV, a, sa, b, sb, &r, s);
        break;
    case HL_POW:
        status = compile_pow(c, e, &r, s);
        break;
    case HL_FUN:
        if ((status = compile_reg(c, e->a, &a)) != HL_OK)
            break;
        if (e->b != NULL) { /* atan2(y, x) */
            if ((status = compile_reg(c, e->b, &b)) == HL_OK)
                r = emit(c, HL_OP_ATAN2, a, b);
            break;
        }
        r = compile_fun(c, e->fun, a);
        if (r < 0)
            status = hl_error_set(c->err, HL_EUNSUP, NULL, -1, 0,
                                  "function '%s' not supported by tapes", hl_fun_name(e->fun));
        break;
    }
    fmpq_clear(sa);
    fmpq_clear(sb);
    if (status != HL_OK)
        return status;
    /* a scale on a constant costs nothing at run time: fold it in now */
    if (c->t->isconst[r] && !fmpq_is_one(s)) {
        r = materialize(c, r, s);
        fmpq_one(s);
    }
    if (c->nval == c->capval) {
        c->capval = c->capval ? 2 * c->capval : 64;
        c->vreg = hl_xrealloc(c->vreg, (size_t)c->capval * sizeof *c->vreg);
        c->vscale = hl_xrealloc(c->vscale, (size_t)c->capval * sizeof *c->vscale);
    }
    c->vreg[c->nval] = r;
    fmpq_init(c->vscale + c->nval);
    fmpq_set(c->vscale + c->nval, s);
    hl_memo_put(&c->exprs, e)->i = c->nval++;
    *reg = r;
    return HL_OK;
}

/* Drop instructions whose results nobody reads (the peepholes above can
 * leave some, e.g. a 1/u whose uses all became divisions). */
static void prune(hl_tape *t)
{
    unsigned char *live = hl_xcalloc((size_t)t->nregs + 1, 1);
    for (int j = 0; j < t->nout; j++)
        live[t->outreg[j]] = 1;
    hl_instr *lists[2] = {t->code, t->pro};
    int *counts[2] = {&t->ncode, &t->npro};
    for (int l = 0; l < 2; l++) { /* the body reads the prologue, not back */
        hl_instr *code = lists[l];
        int n = *counts[l], m = n;
        for (int i = n - 1; i >= 0; i--) {
            hl_instr *in = &code[i];
            if (live[in->d] || (in->x >= 0 && live[in->x])) {
                live[in->a] = 1;
                if (in->b >= 0)
                    live[in->b] = 1;
                code[--m] = *in; /* compact toward the end, keeping order */
            }
        }
        if (m > 0)
            memmove(code, code + m, (size_t)(n - m) * sizeof *code);
        *counts[l] = n - m;
    }
    free(live);
}

/* Fill the double constants: the prologue in Arb at 128 bits, rounded once,
 * so that a folded log(2) is the correctly rounded double. */
static int fold_constants(hl_tape *t, hl_error *err)
{
    arb_ptr r = _arb_vec_init(t->nregs);
    hl_tape_consts_arb(r, 128, t);
    int status = HL_OK;
    for (int i = 0; i < t->nregs; i++) {
        if (!t->isconst[i])
            continue;
        if (!arf_is_finite(arb_midref(r + i))) {
            status = hl_error_set(err, HL_EDOM, NULL, -1, 0,
                                  "a constant subexpression is not finite");
            break;
        }
        /* A wide ball around a finite value: the constant sits where its
         * value jumps and 128 bits cannot say on which side (atan2(sin(pi),
         * -1) is on atan2's cut, where the sign of an exact zero decides). */
        if (!arb_is_finite(r + i) || mag_cmp_2exp_si(arb_radref(r + i), -80) > 0) {
            status = hl_error_set(err, HL_EDOM, NULL, -1, 0,
                                  "a constant subexpression cannot be decided: it lies on a "
                                  "discontinuity (e.g. atan2 on its cut y = 0, x < 0); write "
                                  "its value");
            break;
        }
        t->rd[i] = arf_get_d(arb_midref(r + i), ARF_RND_NEAR);
    }
    _arb_vec_clear(r, t->nregs);
    return status;
}

hl_status hl_tape_new(hl_tape **out, const hl_expr *const *outs, int nout,
                      const char *const *inputs, int nin, hl_error *err)
{
    *out = NULL;
    if (nin < 0 || nout < 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "negative input or output count");
    hl_tape *t = hl_xcalloc(1, sizeof *t);
    comp c = {0};
    c.t = t;
    c.inputs = inputs;
    c.err = err;
    hl_memo_init(&c.exprs);
    map_init(&c.leaves);
    map_init(&c.ins);
    t->nin = nin;
    t->nout = nout;
    for (int i = 0; i < nin; i++)
        new_reg(&c, 0);
    t->outreg = hl_xcalloc((size_t)nout + 1, sizeof *t->outreg);
    int status = HL_OK;
    for (int j = 0; j < nout && status == HL_OK; j++)
        status = compile_reg(&c, outs[j], &t->outreg[j]);
    for (int i = 0; i < c.nval; i++)
        fmpq_clear(c.vscale + i);
    free(c.vreg);
    free(c.vscale);
    free(c.leafof);
    free(c.def);
    hl_memo_clear(&c.exprs);
    free(c.leaves.s);
    free(c.ins.s);
    if (status == HL_OK) {
        prune(t);
        t->rd = hl_xcalloc((size_t)t->nregs + 1, sizeof *t->rd);
        status = fold_constants(t, err);
    }
    if (status != HL_OK) {
        hl_tape_free(t);
        return status;
    }
    *out = t;
    return HL_OK;
}

void hl_tape_free(hl_tape *t)
{
    if (t == NULL)
        return;
    for (int i = 0; i < t->nleaf; i++)
        fmpq_clear(t->leaf[i].q);
    free(t->leaf);
    free(t->outreg);
    free(t->code);
    free(t->pro);
    free(t->isconst);
    free(t->rd);
    hl_tape_native_clear(t);
    hl_tape_jit_clear(t);
    free(t->td);
    hl_prog_free(t->tprog);
    hl_prog_free(t->pprog);
    hl_arb_em_free(t->aem);
    if (t->ra)
        _arb_vec_clear(t->ra, t->nregs);
    if (t->ta)
        _arb_vec_clear(t->ta, (slong)t->tacap);
    free(t);
}

int hl_tape_ninputs(const hl_tape *t) { return t->nin; }
int hl_tape_noutputs(const hl_tape *t) { return t->nout; }
int hl_tape_nops(const hl_tape *t) { return t->ncode; }
int hl_tape_nregs(const hl_tape *t) { return t->nregs; }

static const char *const op_names[HL_OP_COUNT] = {
    "NEG",  "ADD",  "SUB",  "MUL",  "DIV",  "SQR",   "ADDK",  "SUBK",   "KSUB",
    "MULK", "DIVK", "KDIV", "POWK", "SQRT", "EXP",   "LOG",   "SINCOS", "SINHCOSH",
    "TAN",  "TANH", "ATAN", "ASIN", "ACOS", "ASINH", "ATAN2", "POW3H",
};

const char *hl_op_name(hl_op op)
{
    return (unsigned)op < HL_OP_COUNT ? op_names[op] : "?";
}

static void print_code(hl_buf *b, const char *title, const hl_instr *code, int n)
{
    hl_buf_printf(b, "%s:\n", title);
    for (int i = 0; i < n; i++) {
        const hl_instr *in = &code[i];
        hl_buf_printf(b, "  r%d", in->d);
        if (in->x >= 0)
            hl_buf_printf(b, ",r%d", in->x);
        hl_buf_printf(b, " = %s r%d", hl_op_name((hl_op)in->op), in->a);
        if (in->b >= 0)
            hl_buf_printf(b, " r%d", in->b);
        hl_buf_putc(b, '\n');
    }
}

char *hl_tape_print(const hl_tape *t)
{
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_printf(&b, "inputs r0..r%d\nconstants:", t->nin - 1);
    for (int i = 0; i < t->nleaf; i++) {
        if (t->leaf[i].is_pi) {
            hl_buf_printf(&b, " r%d=pi", t->leaf[i].reg);
        } else {
            char *s = fmpq_get_str(NULL, 10, t->leaf[i].q);
            hl_buf_printf(&b, " r%d=%s", t->leaf[i].reg, s);
            flint_free(s);
        }
    }
    hl_buf_putc(&b, '\n');
    print_code(&b, "prologue", t->pro, t->npro);
    print_code(&b, "body", t->code, t->ncode);
    hl_buf_puts(&b, "outputs:");
    for (int j = 0; j < t->nout; j++)
        hl_buf_printf(&b, " r%d", t->outreg[j]);
    hl_buf_putc(&b, '\n');
    return hl_buf_take(&b);
}
