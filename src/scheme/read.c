/* The scheme language (scheme.h): a pass over the formula parser's tree.
 *
 * The text is read by hl_parse_list_ext, the expression grammar with one
 * extension: the language's own calls Hq, Hp, H, dot and int, which
 * language_call (below) checks and turns into placeholder symbols "#k" the
 * grammar cannot spell, keyed to the call in a table.  Then each item's tree
 * is walked once, in post-order, giving every node its value: a scalar or an
 * N-vector of expressions in the scheme's pool (q, p, Q, P and the stages are
 * vectors; arithmetic and functions act componentwise, a scalar combining
 * with every component).  A placeholder's value is made from its arguments'
 * values when the walk reaches it; an integrand is walked on its own, since
 * there its variable means s and not what the same node means outside.
 *
 * The tree lives in a pool of its own: values are made in the scheme's pool,
 * so nothing of the reading (placeholders, the text's names) stays there. */
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "base/memo.h"
#include "scheme/scheme_impl.h"

typedef struct vv {
    int vec;           /* 1: N components; 0: a scalar */
    const hl_expr **c; /* N or 1 entries */
} vv;

typedef struct stage {
    char *name;
    int u0; /* index of its first unknown */
} stage;

typedef enum call_kind { CALL_H, CALL_HQ, CALL_HP, CALL_DOT, CALL_INT } call_kind;

/* One of the language's calls, as the parser met it. */
typedef struct call {
    call_kind kind;
    const hl_expr *a, *b; /* the arguments; int(s, f): a the variable, b f */
    int pos, end;         /* the name's offset and the closing ')''s */
} call;

typedef struct rd {
    const char *src;
    sb *b;
    const scheme_frame *f;
    hl_system *sys;
    hl_pool *pool; /* the scheme's: values */
    hl_pool *tree; /* the parse tree's */
    int N;
    const hl_expr **Qs, **Ps; /* the next point's symbols */
    stage *st;
    int nst;
    call *calls;
    int ncalls;
    hl_memo call_of; /* placeholder node -> index in calls */
    void **arena;    /* the values' storage, freed at the end */
    int narena, carena;
    int item_pos; /* where the item being walked starts */
    hl_error *err;
} rd;

/* One walk: the values of the nodes met so far in one context. */
typedef struct walk {
    rd *r;
    hl_memo values;  /* node -> vv * */
    const char *var; /* inside int(var, ...): the variable's name, else NULL */
} walk;

static vv *new_value(rd *r, int vec)
{
    int n = vec ? r->N : 1;
    if (r->narena == r->carena) {
        r->carena = 2 * r->carena + 16;
        r->arena = hl_xrealloc(r->arena, (size_t)r->carena * sizeof *r->arena);
    }
    vv *v = hl_xmalloc(sizeof *v + (size_t)n * sizeof *v->c);
    v->vec = vec;
    v->c = (const hl_expr **)(v + 1);
    r->arena[r->narena++] = v;
    return v;
}

static int dim(const rd *r, const vv *v) { return v->vec ? r->N : 1; }
static const hl_expr *comp(const vv *v, int j) { return v->c[v->vec ? j : 0]; }

static int name_is(const char *s, int len, const char *word)
{
    return (int)strlen(word) == len && memcmp(s, word, (size_t)len) == 0;
}

static int name_error(const rd *r, hl_status st, int pos, int len, const char *fmt)
{
    char nm[40];
    snprintf(nm, sizeof nm, "%.*s", len > 32 ? 32 : len, r->src + pos);
    return hl_error_set(r->err, st, r->src, pos, len, fmt, nm);
}

/* ---- the language's calls, while parsing ---------------------------------- */

static int call_kind_of(const char *name, int len)
{
    static const char *const names[] = {
        [CALL_H] = "H", [CALL_HQ] = "Hq", [CALL_HP] = "Hp", [CALL_DOT] = "dot", [CALL_INT] = "int"};
    for (int k = 0; k < (int)(sizeof names / sizeof *names); k++)
        if (name_is(name, len, names[k]))
            return k;
    return -1;
}

/* An int() already read whose name lies inside [pos, end]: one nested in it. */
static const call *int_inside(const rd *r, int pos, int end)
{
    for (int i = 0; i < r->ncalls; i++)
        if (r->calls[i].kind == CALL_INT && r->calls[i].pos > pos && r->calls[i].pos < end)
            return &r->calls[i];
    return NULL;
}

static int check_call(rd *r, int kind, const hl_parse_call *c)
{
    if (kind < 0)
        return name_error(r, HL_EINVAL, c->pos, c->len,
                          "unknown function '%s' (the scheme language has Hq, Hp, H, dot, "
                          "int and the elementary functions)");
    if (kind != CALL_DOT && kind != CALL_INT && !hl_system_has_H(r->sys))
        return name_error(r, HL_EINVAL, c->pos, c->len, "'%s' needs a Hamiltonian");
    if (c->nargs < 2)
        return hl_error_set(r->err, HL_EPARSE, r->src, c->end, 1,
                            "expected ',': '%.*s' takes two arguments", c->len, c->name);
    if (c->nargs > 2) { /* at the ',' before the third */
        int comma = c->arg_pos[2] - 1;
        while (comma > 0 && r->src[comma] != ',')
            comma--;
        return hl_error_set(r->err, HL_EPARSE, r->src, comma, 1, "'%.*s' takes two arguments",
                            c->len, c->name);
    }
    if (kind != CALL_INT)
        return HL_OK;
    const hl_expr *v = c->args[0];
    if (v->kind != HL_SYM || v->name[0] == '#')
        return hl_error_set(r->err, HL_EPARSE, r->src, c->arg_pos[0], 1,
                            "expected the integration variable");
    const call *inner = int_inside(r, c->pos, c->end);
    if (inner != NULL)
        return hl_error_set(r->err, HL_EUNSUP, r->src, inner->pos, 3,
                            "an int() inside an int() is not supported");
    return HL_OK;
}

/* hl_parse_ext's call: check c, and stand a placeholder "#k" for it. */
static hl_status language_call(const hl_expr **out, void *arg, const hl_parse_call *c,
                               hl_error *err)
{
    rd *r = arg;
    (void)err; /* r->err is the same */
    int kind = call_kind_of(c->name, c->len), st = check_call(r, kind, c);
    if (st != HL_OK)
        return st;
    r->calls = hl_xrealloc(r->calls, (size_t)(r->ncalls + 1) * sizeof *r->calls);
    r->calls[r->ncalls] = (call){kind, c->args[0], c->args[1], c->pos, c->end};
    char name[24];
    snprintf(name, sizeof name, "#%d", r->ncalls);
    *out = hl_sym(r->tree, name);
    hl_memo_put(&r->call_of, *out)->i = r->ncalls++;
    return HL_OK;
}

/* ---- values of the tree's nodes ----------------------------------------- */

static int visit(void *arg, const hl_expr *e);

static int walk_tree(walk *w, const hl_expr *e, const vv **out)
{
    int st = hl_expr_postorder(&e, 1, visit, w);
    if (st == HL_OK)
        *out = hl_memo_get(&w->values, e)->p;
    return st;
}

/* Expression e of the system's point, at the point (a, b). */
static const hl_expr *at_point(rd *r, const hl_expr *e, const vv *a, const vv *b)
{
    int N = r->N;
    const char **names = hl_xmalloc((size_t)(2 * N) * sizeof *names);
    const hl_expr **vals = hl_xmalloc((size_t)(2 * N) * sizeof *vals);
    for (int j = 0; j < N; j++) {
        names[j] = hl_system_coord(r->sys, j);
        names[N + j] = hl_system_momentum(r->sys, j);
        vals[j] = comp(a, j);
        vals[N + j] = comp(b, j);
    }
    e = hl_expr_subst(r->pool, e, 2 * N, names, vals);
    free(names);
    free(vals);
    return e;
}

/* int(var, f): f walked in a context of its own, then each component's
 * integral over s. */
static int integral(walk *w, const call *c, const vv **out)
{
    rd *r = w->r;
    walk inner = {r, {0}, c->a->name};
    hl_memo_init(&inner.values);
    const vv *f;
    int st = walk_tree(&inner, c->b, &f);
    hl_memo_clear(&inner.values);
    if (st != HL_OK)
        return st;
    vv *v = new_value(r, f->vec);
    for (int j = 0; j < dim(r, f); j++)
        v->c[j] = sb_integral(r->b, f->c[j]);
    *out = v;
    return HL_OK;
}

static int call_value(walk *w, const call *c, const vv **out)
{
    rd *r = w->r;
    if (c->kind == CALL_INT)
        return integral(w, c, out);
    const vv *a, *b;
    int st = walk_tree(w, c->a, &a);
    if (st == HL_OK)
        st = walk_tree(w, c->b, &b);
    if (st != HL_OK)
        return st;
    vv *v = new_value(r, c->kind == CALL_HQ || c->kind == CALL_HP);
    if (c->kind == CALL_H) {
        v->c[0] = at_point(r, hl_system_H_expr(r->sys), a, b);
    } else if (c->kind == CALL_DOT) {
        v->c[0] = NULL;
        for (int j = 0; j < r->N; j++) {
            const hl_expr *t = hl_mul(r->pool, comp(a, j), comp(b, j));
            v->c[0] = v->c[0] ? hl_add(r->pool, v->c[0], t) : t;
        }
    } else {
        for (int j = 0; j < r->N; j++)
            v->c[j] = at_point(r, scheme_dH(r->sys, j, c->kind == CALL_HP), a, b);
    }
    *out = v;
    return HL_OK;
}

static const vv *scalar(rd *r, const hl_expr *e)
{
    vv *v = new_value(r, 0);
    v->c[0] = e;
    return v;
}

static const vv *vector_of(rd *r, const hl_expr *const *c)
{
    vv *v = new_value(r, 1);
    memcpy(v->c, c, (size_t)r->N * sizeof *c);
    return v;
}

static int stage_index(const rd *r, const char *name, int len)
{
    for (int i = 0; i < r->nst; i++)
        if (name_is(name, len, r->st[i].name))
            return i;
    return -1;
}

/* Where the walk's unknown name appears first in the item being walked,
 * skipping the integrals in which it is the variable. */
static int occurrence(const rd *r, const char *name)
{
    int from = r->item_pos;
    for (;;) {
        int at = hl_symbol_pos(r->src + from, name);
        if (at < 0)
            return -1;
        at += from;
        int bound = -1;
        for (int i = 0; i < r->ncalls && bound < 0; i++) {
            const call *c = &r->calls[i];
            if (c->kind == CALL_INT && c->pos < at && at < c->end && strcmp(c->a->name, name) == 0)
                bound = c->end;
        }
        if (bound < 0)
            return at;
        from = bound + 1;
    }
}

/* The phase variables, the step and the stages (vectors or scalars). */
static const vv *frame_name(rd *r, const char *name)
{
    const scheme_frame *f = r->f;
    int len = (int)strlen(name), i;
    if (strcmp(name, "q") == 0 || strcmp(name, "p") == 0)
        return vector_of(r, name[0] == 'q' ? f->q : f->p);
    if (strcmp(name, "Q") == 0 || strcmp(name, "P") == 0)
        return vector_of(r, name[0] == 'Q' ? r->Qs : r->Ps);
    if (strcmp(name, f->D_word) == 0)
        return scalar(r, f->D);
    if ((i = stage_index(r, name, len)) >= 0) {
        vv *v = new_value(r, 1);
        for (int j = 0; j < r->N; j++)
            v->c[j] = sb_usym(r->b, r->st[i].u0 + j);
        return v;
    }
    return NULL;
}

static int symbol_value(walk *w, const hl_expr *e, const vv **out)
{
    rd *r = w->r;
    const hl_memo_val *k = hl_memo_get(&r->call_of, e);
    if (k != NULL)
        return call_value(w, &r->calls[k->i], out);
    if (w->var != NULL && strcmp(e->name, w->var) == 0) {
        *out = scalar(r, hl_sym(r->pool, HL_SCHEME_S));
        return HL_OK;
    }
    if ((*out = frame_name(r, e->name)) != NULL)
        return HL_OK;
    for (int i = 0; i < hl_system_nparams(r->sys); i++)
        if (strcmp(e->name, hl_system_param(r->sys, i)) == 0) {
            *out = scalar(r, hl_sym(r->pool, e->name));
            return HL_OK;
        }
    for (int i = 0; i < hl_system_nset(r->sys); i++)
        if (strcmp(e->name, hl_system_set_name(r->sys, i)) == 0) {
            *out = scalar(r, hl_system_set_value(r->sys, i));
            return HL_OK;
        }
    int at = occurrence(r, e->name);
    return hl_error_set(r->err, HL_EINVAL, r->src, at, at >= 0 ? (int)strlen(e->name) : 0,
                        "unknown name '%.32s' (a scheme knows q, p, Q, P, D, its stages, the "
                        "system's parameters, and the integration variable inside int)",
                        e->name);
}

/* The componentwise value of an operator or function node. */
static const vv *apply(rd *r, const hl_expr *e, const vv *a, const vv *b)
{
    vv *v = new_value(r, a->vec || (b != NULL && b->vec));
    for (int j = 0; j < dim(r, v); j++) {
        const hl_expr *x = comp(a, j), *y = b != NULL ? comp(b, j) : NULL;
        switch (e->kind) {
        case HL_NEG:
            v->c[j] = hl_neg(r->pool, x);
            break;
        case HL_ADD:
            v->c[j] = hl_add(r->pool, x, y);
            break;
        case HL_SUB:
            v->c[j] = hl_sub(r->pool, x, y);
            break;
        case HL_MUL:
            v->c[j] = hl_mul(r->pool, x, y);
            break;
        case HL_DIV:
            v->c[j] = hl_div(r->pool, x, y);
            break;
        case HL_POW:
            v->c[j] = hl_pow(r->pool, x, y);
            break;
        default:
            v->c[j] = y != NULL ? hl_call2(r->pool, e->fun, x, y) : hl_call(r->pool, e->fun, x);
        }
    }
    return v;
}

static const vv *known(const walk *w, const hl_expr *e)
{
    return e != NULL ? hl_memo_get(&w->values, e)->p : NULL;
}

/* hl_expr_postorder's visit: the value of e from its operands'. */
static int visit(void *arg, const hl_expr *e)
{
    walk *w = arg;
    if (hl_memo_get(&w->values, e) != NULL) /* met in an enclosing walk */
        return HL_OK;
    const vv *v = NULL;
    int st = HL_OK;
    switch (e->kind) {
    case HL_NUM:
        v = scalar(w->r, hl_num_fmpq(w->r->pool, e->num));
        break;
    case HL_PI:
        v = scalar(w->r, hl_pi(w->r->pool));
        break;
    case HL_SYM:
        st = symbol_value(w, e, &v);
        break;
    default:
        v = apply(w->r, e, known(w, e->a), known(w, e->b));
    }
    if (st == HL_OK)
        hl_memo_put(&w->values, e)->p = (void *)v;
    return st;
}

/* ---- items ---------------------------------------------------------------- */

/* Which vector unknown is v exactly (Q, P or a stage): index of its first
 * component's unknown, or -1. */
static int whole_unknown(rd *r, const vv *v)
{
    if (!v->vec)
        return -1;
    int u0 = -1;
    for (int j = 0; j < r->N; j++) {
        const hl_expr *e = v->c[j];
        if (e->kind != HL_SYM)
            return -1;
        int u = sb_find(r->b, e->name);
        if (u < 0 || (j > 0 && u != u0 + j))
            return -1;
        if (j == 0)
            u0 = u;
    }
    return u0;
}

static int item(rd *r, walk *w, const hl_eqn *it)
{
    const vv *l, *rr;
    r->item_pos = it->pos;
    int st = walk_tree(w, it->lhs, &l);
    if (st == HL_OK)
        st = walk_tree(w, it->rhs, &rr);
    if (st != HL_OK)
        return st;
    if (l->vec != rr->vec && r->N != 1)
        return hl_error_set(r->err, HL_EINVAL, r->src, it->pos, 1,
                            "one side of this equation is a vector and the other a scalar");
    int u0 = whole_unknown(r, l), n = l->vec || rr->vec ? r->N : 1;
    for (int j = 0; j < n; j++)
        sb_eq(r->b, comp(l, j), comp(rr, j), u0 >= 0 ? u0 + j : -1);
    return HL_OK;
}

static int reserved(const rd *r, const char *name)
{
    static const char *const words[] = {"q", "p", "Q", "P", "pi", "H", "Hq", "Hp", "dot", "int"};
    for (size_t i = 0; i < sizeof words / sizeof *words; i++)
        if (strcmp(name, words[i]) == 0)
            return 1;
    return strcmp(name, r->f->D_word) == 0 || hl_fun_lookup(name, (int)strlen(name)) >= 0;
}

/* Is the item "name = ...", written with the bare name (not "(name) = ")? */
static const char *stage_name(const rd *r, const hl_eqn *it)
{
    if (it->lhs->kind != HL_SYM || reserved(r, it->lhs->name))
        return NULL;
    size_t n = strlen(it->lhs->name);
    return strncmp(r->src + it->pos, it->lhs->name, n) == 0 ? it->lhs->name : NULL;
}

/* Every item "name = ..." with a name that is not reserved introduces a
 * stage (N unknowns), in the order of the text. */
static int find_stages(rd *r, const hl_eqn *items, int n)
{
    hl_buf nb;
    hl_buf_init(&nb);
    int st = HL_OK;
    for (int i = 0; i < n && st == HL_OK; i++) {
        const char *name = stage_name(r, &items[i]);
        int len = name ? (int)strlen(name) : 0;
        if (name == NULL)
            continue;
        if (stage_index(r, name, len) >= 0) {
            st = name_error(r, HL_EINVAL, items[i].pos, len, "stage '%s' is defined twice");
            break;
        }
        r->st = hl_xrealloc(r->st, (size_t)(r->nst + 1) * sizeof *r->st);
        stage *sg = &r->st[r->nst++];
        sg->name = hl_xstrdup(name);
        sg->u0 = r->b->s->m;
        for (int j = 0; j < r->N; j++) {
            hl_buf_printf(&nb, "%s%s#%d", r->f->prefix, name, j + 1);
            char *res = hl_buf_take(&nb);
            if (r->N == 1)
                hl_buf_printf(&nb, "%s%s", r->f->prefix, name);
            else
                hl_buf_printf(&nb, "%s%s[%d]", r->f->prefix, name, j + 1);
            char *disp = hl_buf_take(&nb);
            sb_unknown(r->b, res, disp, NULL);
            free(res);
            free(disp);
        }
    }
    hl_buf_clear(&nb);
    return st;
}

/* Parse the text, find its stages, and walk its items. */
static int read_items(rd *r)
{
    int max = 1;
    for (const char *c = r->src; *c; c++)
        max += *c == ';';
    hl_eqn *items = hl_xmalloc((size_t)max * sizeof *items);
    hl_parse_ext ext = {language_call, r, 1};
    int n = 0, st = hl_parse_list_ext(items, max, &n, r->tree, r->src, &ext, r->err);
    if (st == HL_OK)
        st = find_stages(r, items, n);
    walk w = {r, {0}, NULL};
    hl_memo_init(&w.values);
    for (int i = 0; i < n && st == HL_OK; i++)
        st = item(r, &w, &items[i]);
    hl_memo_clear(&w.values);
    free(items);
    return st;
}

int scheme_read(sb *b, const char *text, const scheme_frame *f, hl_error *err)
{
    rd r;
    memset(&r, 0, sizeof r);
    r.src = text;
    r.b = b;
    r.f = f;
    r.sys = b->sys;
    r.pool = b->pool;
    r.tree = hl_pool_new();
    r.N = hl_system_ndof(b->sys);
    r.err = err;
    r.Qs = hl_xmalloc((size_t)(2 * r.N) * sizeof *r.Qs);
    r.Ps = r.Qs + r.N;
    for (int j = 0; j < r.N; j++) {
        r.Qs[j] = sb_usym(b, f->Qu[j]);
        r.Ps[j] = sb_usym(b, f->Pu[j]);
    }
    hl_memo_init(&r.call_of);
    int st = read_items(&r);
    hl_memo_clear(&r.call_of);
    for (int i = 0; i < r.narena; i++)
        free(r.arena[i]);
    for (int i = 0; i < r.nst; i++)
        free(r.st[i].name);
    free(r.arena);
    free(r.st);
    free(r.calls);
    free(r.Qs);
    hl_pool_free(r.tree);
    return st;
}
