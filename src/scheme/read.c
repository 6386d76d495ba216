/* The scheme language: vector equations read and instantiated at once.
 *
 * A small recursive-descent reader on the expression language's tokenizer
 * (src/expr/lex.h), with ',' handled here (the expression language has no
 * commas).  Every value is a scalar or an N-vector of expressions; the
 * grammar and precedences are those of hl_parse (unary minus looser than ^,
 * ^ right associative). */
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "expr/lex.h"
#include "scheme/scheme_impl.h"

enum { TK_COMMA = 100 };

typedef struct vv {
    int vec;              /* 1: N components; 0: a scalar */
    const hl_expr **c;    /* N or 1 entries (in the reader's arena) */
} vv;

typedef struct stage {
    char *name;
    int u0;               /* index of its first unknown */
} stage;

typedef struct rd {
    hl_lexer lx;
    int kind, pos, len;   /* the current token */
    const char *src;
    sb *b;
    const scheme_frame *f;
    hl_system *sys;
    hl_pool *pool;
    int N;
    const hl_expr **Qs, **Ps; /* the next point's symbols */
    stage *st;
    int nst;
    int in_int;            /* inside int(s, ...): s is the scalar HL_SCHEME_S */
    const char *svar;
    int svar_len;
    void **arena;
    int narena, carena;
    hl_error *err;
} rd;

static const hl_expr **alloc_c(rd *r, int n)
{
    if (r->narena == r->carena) {
        r->carena = 2 * r->carena + 16;
        r->arena = hl_xrealloc(r->arena, (size_t)r->carena * sizeof *r->arena);
    }
    const hl_expr **c = hl_xmalloc((size_t)(n > 0 ? n : 1) * sizeof *c);
    r->arena[r->narena++] = c;
    return c;
}

static int dim(const rd *r, const vv *v) { return v->vec ? r->N : 1; }
static const hl_expr *comp(const vv *v, int j) { return v->c[v->vec ? j : 0]; }

static int next(rd *r)
{
    const char *s = r->src;
    int i = r->lx.pos;
    while (s[i] == ' ' || s[i] == '\t' || s[i] == '\n' || s[i] == '\r')
        i++;
    if (s[i] == ',') {
        r->lx.pos = i + 1;
        r->kind = TK_COMMA, r->pos = i, r->len = 1;
        return HL_OK;
    }
    int st = hl_lex_next(&r->lx, r->err);
    if (st != HL_OK) {
        if (r->err)
            r->err->src = r->src;
        return st;
    }
    r->kind = (int)r->lx.tok.kind, r->pos = r->lx.tok.pos, r->len = r->lx.tok.len;
    return HL_OK;
}

static int fail(rd *r, int pos, int len, const char *fmt, const char *arg)
{
    return hl_error_set(r->err, HL_EPARSE, r->src, pos, len > 0 ? len : 1, fmt, arg);
}

static int expect(rd *r, int kind, const char *what)
{
    if (r->kind != kind) {
        char t[48];
        hl_token tk = {(hl_tok_kind)(r->kind == TK_COMMA ? HL_TK_NAME : r->kind), r->pos, r->len};
        hl_lex_text(t, sizeof t, r->src, tk);
        char msg[96];
        snprintf(msg, sizeof msg, "expected %s, found '%%s'", what);
        return fail(r, r->pos, r->len, msg, t);
    }
    return next(r);
}

static int name_is(const rd *r, int pos, int len, const char *s)
{
    return (int)strlen(s) == len && memcmp(r->src + pos, s, (size_t)len) == 0;
}

/* ---- combining values --------------------------------------------------- */

typedef const hl_expr *(*binop)(hl_pool *, const hl_expr *, const hl_expr *);

static vv combine(rd *r, binop op, const vv *a, const vv *b)
{
    vv out = {a->vec || b->vec, NULL};
    int n = dim(r, &out);
    out.c = alloc_c(r, n);
    for (int j = 0; j < n; j++)
        out.c[j] = op(r->pool, comp(a, j), comp(b, j));
    return out;
}

static vv scalar(rd *r, const hl_expr *e)
{
    vv out = {0, alloc_c(r, 1)};
    out.c[0] = e;
    return out;
}

static vv vector_of(rd *r, const hl_expr *const *c)
{
    vv out = {1, alloc_c(r, r->N)};
    for (int j = 0; j < r->N; j++)
        out.c[j] = c[j];
    return out;
}

/* expression e of the system's point, at the point (a, b) */
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

/* ---- grammar --------------------------------------------------------------- */

static int expr(rd *r, vv *out);

/* '(' a ',' b ')' after a two-argument function's name */
static int two_args(rd *r, vv *a, vv *b)
{
    int st = expect(r, HL_TK_LPAREN, "'('");
    if (st == HL_OK)
        st = expr(r, a);
    if (st == HL_OK)
        st = expect(r, TK_COMMA, "','");
    if (st == HL_OK)
        st = expr(r, b);
    if (st == HL_OK)
        st = expect(r, HL_TK_RPAREN, "')'");
    return st;
}

static int need_H(rd *r, int pos, int len)
{
    if (hl_system_has_H(r->sys))
        return HL_OK;
    char nm[40];
    snprintf(nm, sizeof nm, "%.*s", len > 32 ? 32 : len, r->src + pos);
    return hl_error_set(r->err, HL_EINVAL, r->src, pos, len, "'%s' needs a Hamiltonian", nm);
}

static int call(rd *r, vv *out, int pos, int len)
{
    int st;
    vv a, b;
    if (name_is(r, pos, len, "Hq") || name_is(r, pos, len, "Hp")) {
        int wrt_p = name_is(r, pos, len, "Hp");
        if ((st = need_H(r, pos, len)) != HL_OK || (st = two_args(r, &a, &b)) != HL_OK)
            return st;
        out->vec = 1;
        out->c = alloc_c(r, r->N);
        for (int j = 0; j < r->N; j++)
            out->c[j] = at_point(r, scheme_dH(r->sys, j, wrt_p), &a, &b);
        return HL_OK;
    }
    if (name_is(r, pos, len, "H")) {
        if ((st = need_H(r, pos, len)) != HL_OK || (st = two_args(r, &a, &b)) != HL_OK)
            return st;
        *out = scalar(r, at_point(r, hl_system_H_expr(r->sys), &a, &b));
        return HL_OK;
    }
    if (name_is(r, pos, len, "dot")) {
        if ((st = two_args(r, &a, &b)) != HL_OK)
            return st;
        const hl_expr *s = NULL;
        for (int j = 0; j < r->N; j++) {
            const hl_expr *t = hl_mul(r->pool, comp(&a, j), comp(&b, j));
            s = s ? hl_add(r->pool, s, t) : t;
        }
        *out = scalar(r, s);
        return HL_OK;
    }
    if (name_is(r, pos, len, "int")) {
        if (r->in_int)
            return hl_error_set(r->err, HL_EUNSUP, r->src, pos, len,
                                "an int() inside an int() is not supported");
        if ((st = expect(r, HL_TK_LPAREN, "'('")) != HL_OK)
            return st;
        if (r->kind != HL_TK_NAME)
            return fail(r, r->pos, r->len, "expected the integration variable%s", "");
        r->svar = r->src + r->pos;
        r->svar_len = r->len;
        if ((st = next(r)) != HL_OK || (st = expect(r, TK_COMMA, "','")) != HL_OK)
            return st;
        r->in_int = 1;
        st = expr(r, &a);
        r->in_int = 0;
        if (st == HL_OK)
            st = expect(r, HL_TK_RPAREN, "')'");
        if (st != HL_OK)
            return st;
        out->vec = a.vec;
        out->c = alloc_c(r, dim(r, &a));
        for (int j = 0; j < dim(r, &a); j++)
            out->c[j] = sb_integral(r->b, a.c[j]);
        return HL_OK;
    }
    int f = hl_fun_lookup(r->src + pos, len);
    if (f < 0) {
        char nm[40];
        snprintf(nm, sizeof nm, "%.*s", len > 32 ? 32 : len, r->src + pos);
        return hl_error_set(r->err, HL_EINVAL, r->src, pos, len,
                            "unknown function '%s' (the scheme language has Hq, Hp, H, dot, "
                            "int and the elementary functions)",
                            nm);
    }
    if ((st = expect(r, HL_TK_LPAREN, "'('")) != HL_OK || (st = expr(r, &a)) != HL_OK ||
        (st = expect(r, HL_TK_RPAREN, "')'")) != HL_OK)
        return st;
    out->vec = a.vec;
    out->c = alloc_c(r, dim(r, &a));
    for (int j = 0; j < dim(r, &a); j++)
        out->c[j] = hl_call(r->pool, (hl_fun)f, a.c[j]);
    return HL_OK;
}

static int stage_index(const rd *r, int pos, int len)
{
    for (int i = 0; i < r->nst; i++)
        if ((int)strlen(r->st[i].name) == len && memcmp(r->st[i].name, r->src + pos, (size_t)len) == 0)
            return i;
    return -1;
}

static int name(rd *r, vv *out, int pos, int len)
{
    const scheme_frame *f = r->f;
    int i;
    if (r->in_int && len == r->svar_len && memcmp(r->src + pos, r->svar, (size_t)len) == 0) {
        *out = scalar(r, hl_sym(r->pool, HL_SCHEME_S));
        return HL_OK;
    }
    if (name_is(r, pos, len, "q") || name_is(r, pos, len, "p")) {
        *out = vector_of(r, name_is(r, pos, len, "q") ? f->q : f->p);
        return HL_OK;
    }
    if (name_is(r, pos, len, "Q") || name_is(r, pos, len, "P")) {
        *out = vector_of(r, name_is(r, pos, len, "Q") ? r->Qs : r->Ps);
        return HL_OK;
    }
    if (name_is(r, pos, len, f->D_word)) {
        *out = scalar(r, f->D);
        return HL_OK;
    }
    if (name_is(r, pos, len, "pi")) {
        *out = scalar(r, hl_pi(r->pool));
        return HL_OK;
    }
    if ((i = stage_index(r, pos, len)) >= 0) {
        out->vec = 1;
        out->c = alloc_c(r, r->N);
        for (int j = 0; j < r->N; j++)
            out->c[j] = sb_usym(r->b, r->st[i].u0 + j);
        return HL_OK;
    }
    for (i = 0; i < hl_system_nparams(r->sys); i++)
        if (name_is(r, pos, len, hl_system_param(r->sys, i))) {
            *out = scalar(r, hl_sym(r->pool, hl_system_param(r->sys, i)));
            return HL_OK;
        }
    for (i = 0; i < hl_system_nset(r->sys); i++)
        if (name_is(r, pos, len, hl_system_set_name(r->sys, i))) {
            *out = scalar(r, hl_system_set_value(r->sys, i));
            return HL_OK;
        }
    char nm[40];
    snprintf(nm, sizeof nm, "%.*s", len > 32 ? 32 : len, r->src + pos);
    return hl_error_set(r->err, HL_EINVAL, r->src, pos, len,
                        "unknown name '%s' (a scheme knows q, p, Q, P, D, its stages, the "
                        "system's parameters, and the integration variable inside int)",
                        nm);
}

static int unary(rd *r, vv *out);

static int atom(rd *r, vv *out)
{
    int st, pos = r->pos, len = r->len;
    switch (r->kind) {
    case HL_TK_NUM:
        *out = scalar(r, hl_num_fmpq(r->pool, r->lx.num));
        return next(r);
    case HL_TK_LPAREN:
        if ((st = next(r)) != HL_OK || (st = expr(r, out)) != HL_OK)
            return st;
        return expect(r, HL_TK_RPAREN, "')'");
    case HL_TK_NAME:
        if ((st = next(r)) != HL_OK)
            return st;
        if (r->kind == HL_TK_LPAREN)
            return call(r, out, pos, len);
        return name(r, out, pos, len);
    default:
        return expect(r, -1, "a number, a name or '('");
    }
}

static int power(rd *r, vv *out)
{
    int st = atom(r, out);
    if (st != HL_OK || r->kind != HL_TK_POW)
        return st;
    vv e;
    if ((st = next(r)) != HL_OK || (st = unary(r, &e)) != HL_OK)
        return st;
    *out = combine(r, hl_pow, out, &e);
    return HL_OK;
}

static int unary(rd *r, vv *out)
{
    if (r->kind == HL_TK_MINUS || r->kind == HL_TK_PLUS) {
        int neg = r->kind == HL_TK_MINUS, st;
        if ((st = next(r)) != HL_OK || (st = unary(r, out)) != HL_OK)
            return st;
        if (neg) {
            vv v = {out->vec, alloc_c(r, dim(r, out))};
            for (int j = 0; j < dim(r, out); j++)
                v.c[j] = hl_neg(r->pool, out->c[j]);
            *out = v;
        }
        return HL_OK;
    }
    return power(r, out);
}

static int term(rd *r, vv *out)
{
    int st = unary(r, out);
    while (st == HL_OK && (r->kind == HL_TK_STAR || r->kind == HL_TK_SLASH)) {
        binop op = r->kind == HL_TK_STAR ? hl_mul : hl_div;
        vv b;
        if ((st = next(r)) != HL_OK || (st = unary(r, &b)) != HL_OK)
            return st;
        *out = combine(r, op, out, &b);
    }
    return st;
}

static int expr(rd *r, vv *out)
{
    int st = term(r, out);
    while (st == HL_OK && (r->kind == HL_TK_PLUS || r->kind == HL_TK_MINUS)) {
        binop op = r->kind == HL_TK_PLUS ? hl_add : hl_sub;
        vv b;
        if ((st = next(r)) != HL_OK || (st = term(r, &b)) != HL_OK)
            return st;
        *out = combine(r, op, out, &b);
    }
    return st;
}

/* ---- equations ------------------------------------------------------------ */

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

static int item(rd *r)
{
    vv l, rr;
    int pos = r->pos, st = expr(r, &l);
    if (st != HL_OK)
        return st;
    if (r->kind != HL_TK_EQ)
        return expect(r, HL_TK_EQ, "'='");
    if ((st = next(r)) != HL_OK || (st = expr(r, &rr)) != HL_OK)
        return st;
    if (l.vec != rr.vec && r->N != 1)
        return hl_error_set(r->err, HL_EINVAL, r->src, pos, 1,
                            "one side of this equation is a vector and the other a scalar");
    int u0 = whole_unknown(r, &l), n = l.vec || rr.vec ? r->N : 1;
    for (int j = 0; j < n; j++)
        sb_eq(r->b, comp(&l, j), comp(&rr, j), u0 >= 0 ? u0 + j : -1);
    return HL_OK;
}

static int reserved(const rd *r, int pos, int len)
{
    static const char *const words[] = {"q", "p", "Q", "P", "pi", "H", "Hq", "Hp",
                                        "dot", "int"};
    for (size_t i = 0; i < sizeof words / sizeof *words; i++)
        if (name_is(r, pos, len, words[i]))
            return 1;
    if (name_is(r, pos, len, r->f->D_word))
        return 1;
    return hl_fun_lookup(r->src + pos, len) >= 0;
}

/* First pass: every item "name = ..." with a name that is not reserved
 * introduces a stage (N unknowns). */
static int find_stages(rd *r)
{
    int st, at_start = 1;
    hl_buf nb;
    hl_buf_init(&nb);
    while ((st = next(r)) == HL_OK && r->kind != HL_TK_EOF) {
        if (at_start && r->kind == HL_TK_NAME) {
            int pos = r->pos, len = r->len;
            if ((st = next(r)) != HL_OK)
                break;
            if (r->kind == HL_TK_EQ && !reserved(r, pos, len)) {
                if (stage_index(r, pos, len) >= 0) {
                    char nm[40];
                    snprintf(nm, sizeof nm, "%.*s", len > 32 ? 32 : len, r->src + pos);
                    st = hl_error_set(r->err, HL_EINVAL, r->src, pos, len,
                                      "stage '%s' is defined twice", nm);
                    break;
                }
                r->st = hl_xrealloc(r->st, (size_t)(r->nst + 1) * sizeof *r->st);
                stage *sg = &r->st[r->nst++];
                hl_buf_putn(&nb, r->src + pos, (size_t)len);
                sg->name = hl_buf_take(&nb);
                sg->u0 = r->b->s->m;
                for (int j = 0; j < r->N; j++) {
                    hl_buf_printf(&nb, "%s%s#%d", r->f->prefix, sg->name, j + 1);
                    char *res = hl_buf_take(&nb);
                    if (r->N == 1)
                        hl_buf_printf(&nb, "%s%s", r->f->prefix, sg->name);
                    else
                        hl_buf_printf(&nb, "%s%s[%d]", r->f->prefix, sg->name, j + 1);
                    char *disp = hl_buf_take(&nb);
                    sb_unknown(r->b, res, disp, NULL);
                    free(res);
                    free(disp);
                }
            }
        }
        at_start = r->kind == HL_TK_SEMI;
    }
    hl_buf_clear(&nb);
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
    r.N = hl_system_ndof(b->sys);
    r.err = err;
    r.Qs = hl_xmalloc((size_t)(2 * r.N) * sizeof *r.Qs);
    r.Ps = r.Qs + r.N;
    for (int j = 0; j < r.N; j++) {
        r.Qs[j] = sb_usym(b, f->Qu[j]);
        r.Ps[j] = sb_usym(b, f->Pu[j]);
    }
    hl_lex_init(&r.lx, text, 0);
    int st = find_stages(&r);
    hl_lex_clear(&r.lx);
    if (st == HL_OK) {
        hl_lex_init(&r.lx, text, 1);
        st = next(&r);
        while (st == HL_OK && r.kind != HL_TK_EOF) {
            st = item(&r);
            if (st == HL_OK && r.kind == HL_TK_SEMI)
                st = next(&r);
            else if (st == HL_OK && r.kind != HL_TK_EOF)
                st = expect(&r, HL_TK_SEMI, "';' or the end");
        }
        hl_lex_clear(&r.lx);
    }
    for (int i = 0; i < r.narena; i++)
        free(r.arena[i]);
    for (int i = 0; i < r.nst; i++)
        free(r.st[i].name);
    free(r.arena);
    free(r.st);
    free(r.Qs);
    return st;
}
