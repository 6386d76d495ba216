/* Parser: precedence climbing over the priority table of prec.h (the scheme
 * of Lua's lparser.c subexpr).
 *
 * Folding, and only this, makes literals literals: '-' applied directly to a
 * number token gives a negative number, and literal / literal gives a number.
 * A parenthesised number is not a literal, so "(2)/3" stays a division and
 * every DAG has a spelling (see print.c).
 *
 * Nesting depth is counted, so deep input is an error and not a crash.  One
 * level is charged for each '(' (group or call), for each exponent, and for
 * each run of unary operators except one that directly follows '(': thus the
 * printer's "x^(-y)" costs what the input "x^-y" cost, and printing never
 * pushes an accepted formula over the limit.  Runs of operators at one
 * level (a sum's terms, a run of minuses) are loops, not recursion: a sum of
 * 10^5 terms costs one level.  HL_PARSE_MAX_DEPTH is the one depth limit of
 * the layer: every other walk is iterative (hl_expr_postorder, print.c).
 *
 * Size is counted too: every node the parser makes is charged, and a
 * formula of more than HL_PARSE_MAX_NODES is refused before anything is
 * computed from it. */
#include <string.h>

#include "base/buf.h"
#include "expr/lex.h"
#include "expr/prec.h"

/* What a parsed operand is, syntactically. */
#define V_TOKEN 1u /* a bare number token: "-" folds into it */
#define V_LIT 2u   /* a literal: folds with "/" */

typedef struct value {
    const hl_expr *e;
    int pos;        /* where the operand starts (errors point at it) */
    unsigned flags; /* V_TOKEN, V_LIT */
} value;

typedef struct parser {
    hl_lexer lx;
    hl_pool *pool;
    const char *src;
    hl_error *err;
    hl_token prev; /* the token before lx.tok */
    int depth;
    long nodes;              /* made so far, against HL_PARSE_MAX_NODES */
    const hl_parse_ext *ext; /* the caller's calls and rules, or NULL */
    int in_args;             /* directly inside a call that takes several arguments */
} parser;

static int subexpr(parser *p, int limit, value *out);

static int next(parser *p)
{
    p->prev = p->lx.tok;
    return hl_lex_next(&p->lx, p->err);
}

/* An error at token t whose message quotes t itself (quote_t) or the token
 * before the current one. */
static int error_at(parser *p, hl_status st, hl_token t, const char *msg, int quote_t)
{
    char text[48];
    hl_lex_text(text, sizeof text, p->src, quote_t ? t : p->prev);
    return hl_error_set(p->err, st, p->src, t.pos, t.len > 0 ? t.len : 1, msg, text);
}

static int enter(parser *p, hl_token at)
{
    if (++p->depth > HL_PARSE_MAX_DEPTH)
        return hl_error_set(p->err, HL_ELIMIT, p->src, at.pos, at.len,
                            "formula nested too deeply (limit %d) at position %d",
                            HL_PARSE_MAX_DEPTH, at.pos + 1);
    return HL_OK;
}

/* Charge n nodes made at token at. */
static int charge(parser *p, long n, hl_token at)
{
    if ((p->nodes += n) > HL_PARSE_MAX_NODES)
        return hl_error_set(p->err, HL_ELIMIT, p->src, at.pos, at.len,
                            "formula too large (more than %d operations) at position %d",
                            HL_PARSE_MAX_NODES, at.pos + 1);
    return HL_OK;
}

static int starts_operand(hl_tok_kind k)
{
    return k == HL_TK_NUM || k == HL_TK_NAME || k == HL_TK_LPAREN || k == HL_TK_PLUS ||
           k == HL_TK_MINUS;
}

/* Error for a token that cannot start an expression. */
static int expected_expression(parser *p)
{
    hl_token t = p->lx.tok;
    if (p->prev.len > 0)
        return error_at(p, HL_EPARSE, t, "expected an expression after '%s'", 0);
    return error_at(p, HL_EPARSE, t, "expected an expression, found '%s'", 1);
}

/* ')' closing the '(' at open. */
static int close_paren(parser *p, hl_token open)
{
    if (p->lx.tok.kind != HL_TK_RPAREN)
        return hl_error_set(p->err, HL_EPARSE, p->src, p->lx.tok.pos, 1,
                            "expected ')' to close '(' opened at column %d", open.pos + 1);
    p->depth--;
    return next(p);
}

/* ',' expr: the second argument of a function of two (atan2(y, x)). */
static int second_argument(parser *p, hl_fun f, value *arg2)
{
    int st;
    if (p->lx.tok.kind != HL_TK_COMMA)
        return hl_error_set(p->err, HL_EPARSE, p->src, p->lx.tok.pos, 1,
                            "expected ',': '%s' takes two arguments", hl_fun_name(f));
    if ((st = next(p)))
        return st;
    if (!starts_operand(p->lx.tok.kind))
        return expected_expression(p);
    return subexpr(p, 0, arg2);
}

/* The arguments of a call that may take several, up to its ')': "a, b, c". */
static int argument_list(parser *p, value *args, int *nargs, hl_token open)
{
    int st, saved = p->in_args;
    p->in_args = 1;
    *nargs = 0;
    for (;;) {
        if (*nargs == HL_PARSE_MAX_ARGS) {
            st = hl_error_set(p->err, HL_EPARSE, p->src, p->lx.tok.pos, 1,
                              "too many arguments (at most %d)", HL_PARSE_MAX_ARGS);
            break;
        }
        if (!starts_operand(p->lx.tok.kind)) {
            st = expected_expression(p);
            break;
        }
        if ((st = subexpr(p, 0, &args[(*nargs)++])) || p->lx.tok.kind != HL_TK_COMMA)
            break;
        if ((st = next(p)))
            break;
    }
    p->in_args = saved;
    return st ? st : close_paren(p, open);
}

/* name '(' args ')' for a name that is not a function of the language: the
 * caller's extension makes the node (hl_parse_ext). */
static int extension_call(parser *p, hl_token name, value *v)
{
    hl_token open = p->lx.tok;
    value args[HL_PARSE_MAX_ARGS];
    const hl_expr *arg_e[HL_PARSE_MAX_ARGS];
    int arg_pos[HL_PARSE_MAX_ARGS], nargs, st;
    if ((st = enter(p, open)) || (st = next(p)) || (st = argument_list(p, args, &nargs, open)))
        return st;
    for (int i = 0; i < nargs; i++)
        arg_e[i] = args[i].e, arg_pos[i] = args[i].pos;
    hl_parse_call c = {.src = p->src,
                       .name = p->src + name.pos,
                       .len = name.len,
                       .pos = name.pos,
                       .end = p->prev.pos,
                       .nargs = nargs,
                       .args = arg_e,
                       .arg_pos = arg_pos};
    v->e = NULL;
    if ((st = p->ext->call(&v->e, p->ext->arg, &c, p->err)) == HL_OK && v->e == NULL)
        st = hl_error_set(p->err, HL_EINVAL, p->src, name.pos, name.len, "bad call");
    return st;
}

/* simple := number | 'pi' | symbol | func '(' expr ')' | func2 '(' expr ',' expr ')'
 *         | '(' expr ')' | call (with an extension: name '(' expr {',' expr} ')') */
static int simpleexp(parser *p, value *v)
{
    hl_token t = p->lx.tok;
    int st;

    v->pos = t.pos;
    v->flags = 0;
    if ((st = charge(p, 1, t)))
        return st;
    switch (t.kind) {
    case HL_TK_NUM:
        v->e = hl_num_fmpq(p->pool, p->lx.num);
        v->flags = V_TOKEN | V_LIT;
        return next(p);
    case HL_TK_LPAREN: {
        int saved = p->in_args;
        p->in_args = 0;
        if ((st = enter(p, t)) || (st = next(p)) || (st = subexpr(p, 0, v)))
            return st;
        p->in_args = saved;
        v->pos = t.pos;
        v->flags = 0; /* "(2)" is a number but not a literal */
        return close_paren(p, t);
    }
    case HL_TK_NAME:
        break;
    default:
        return expected_expression(p);
    }

    const char *name = p->src + t.pos;
    int f = hl_fun_lookup(name, t.len);
    if ((st = next(p)))
        return st;
    if (f < 0 && p->lx.tok.kind == HL_TK_LPAREN && p->ext != NULL && p->ext->call != NULL)
        return extension_call(p, t, v);
    if (f < 0 && p->lx.tok.kind == HL_TK_LPAREN)
        return error_at(p, HL_EPARSE, t, "unknown function '%s'", 1);
    if (f < 0) {
        if (t.len == 2 && memcmp(name, "pi", 2) == 0) {
            v->e = hl_pi(p->pool);
        } else {
            char *s = hl_xmalloc((size_t)t.len + 1);
            memcpy(s, name, (size_t)t.len);
            s[t.len] = '\0';
            v->e = hl_sym(p->pool, s);
            free(s);
        }
        return HL_OK;
    }
    hl_token open = p->lx.tok;
    if (open.kind != HL_TK_LPAREN)
        return hl_error_set(p->err, HL_EPARSE, p->src, open.pos, open.len,
                            "expected '(' after '%s'", hl_fun_name((hl_fun)f));
    value arg, arg2;
    int saved = p->in_args;
    p->in_args = hl_fun_arity((hl_fun)f) > 1;
    if ((st = enter(p, open)) || (st = next(p)) || (st = subexpr(p, 0, &arg)))
        return st;
    p->in_args = saved;
    if (hl_fun_arity((hl_fun)f) == 1) {
        if (p->lx.tok.kind == HL_TK_COMMA)
            return hl_error_set(p->err, HL_EPARSE, p->src, p->lx.tok.pos, 1,
                                "'%s' takes one argument", hl_fun_name((hl_fun)f));
        if ((st = close_paren(p, open)))
            return st;
        v->e = hl_call(p->pool, (hl_fun)f, arg.e);
        return HL_OK;
    }
    if ((st = second_argument(p, (hl_fun)f, &arg2)) || (st = close_paren(p, open)))
        return st;
    v->e = hl_call2(p->pool, (hl_fun)f, arg.e, arg2.e);
    return HL_OK;
}

static int binary_kind(hl_tok_kind k)
{
    switch (k) {
    case HL_TK_PLUS: return HL_ADD;
    case HL_TK_MINUS: return HL_SUB;
    case HL_TK_STAR: return HL_MUL;
    case HL_TK_SLASH: return HL_DIV;
    case HL_TK_POW: return HL_POW;
    default: return -1;
    }
}

/* A run of unary operators and the operand they apply to (tighter than
 * * and /, looser than ^).  Read in a loop, so "------x" costs one level. */
static int unary(parser *p, value *v)
{
    hl_token first = p->lx.tok;
    int negs = 0, st;
    int free_level = p->prev.kind == HL_TK_LPAREN && p->prev.len > 0;

    if (!free_level && (st = enter(p, first)))
        return st;
    while (p->lx.tok.kind == HL_TK_MINUS || p->lx.tok.kind == HL_TK_PLUS) {
        negs += p->lx.tok.kind == HL_TK_MINUS;
        if ((st = charge(p, 1, p->lx.tok)) || (st = next(p)))
            return st;
    }
    if (!starts_operand(p->lx.tok.kind))
        return expected_expression(p);
    if ((st = subexpr(p, HL_PREC_UNARY, v)))
        return st;
    if (negs > 0 && (v->flags & V_TOKEN)) { /* "-3" is a number */
        fmpq_t x;
        fmpq_init(x);
        fmpq_neg(x, v->e->num);
        v->e = hl_num_fmpq(p->pool, x);
        fmpq_clear(x);
        v->flags = V_LIT;
        negs--;
    } else {
        v->flags &= ~V_TOKEN;
    }
    for (; negs > 0; negs--) {
        v->e = hl_neg(p->pool, v->e);
        v->flags = 0;
    }
    v->pos = first.pos;
    if (!free_level)
        p->depth--;
    return HL_OK;
}

static int combine(parser *p, int kind, value *a, const value *b)
{
    if (kind == HL_DIV && (a->flags & V_LIT) && (b->flags & V_LIT)) {
        if (fmpq_is_zero(b->e->num)) {
            hl_token z = {HL_TK_NUM, b->pos, 1};
            int end = p->prev.pos + p->prev.len; /* the literal's end */
            z.len = end > b->pos ? end - b->pos : 1;
            return hl_error_set(p->err, HL_EDOM, p->src, z.pos, z.len, "division by zero");
        }
        fmpq_t x;
        fmpq_init(x);
        fmpq_div(x, a->e->num, b->e->num);
        a->e = hl_num_fmpq(p->pool, x);
        fmpq_clear(x);
        a->flags = V_LIT;
        return HL_OK;
    }
    switch (kind) {
    case HL_ADD: a->e = hl_add(p->pool, a->e, b->e); break;
    case HL_SUB: a->e = hl_sub(p->pool, a->e, b->e); break;
    case HL_MUL: a->e = hl_mul(p->pool, a->e, b->e); break;
    case HL_DIV: a->e = hl_div(p->pool, a->e, b->e); break;
    default: a->e = hl_pow(p->pool, a->e, b->e); break;
    }
    a->flags = 0;
    return HL_OK;
}

/* subexpr := (unary | simple) { binop subexpr }, continuing only with
 * operators whose left priority exceeds limit. */
static int subexpr(parser *p, int limit, value *v)
{
    int st, kind;

    if (p->lx.tok.kind == HL_TK_MINUS || p->lx.tok.kind == HL_TK_PLUS)
        st = unary(p, v);
    else
        st = simpleexp(p, v);
    if (st)
        return st;
    while ((kind = binary_kind(p->lx.tok.kind)) >= 0 && hl_prec_table[kind].left > limit) {
        hl_token op = p->lx.tok;
        value rhs;
        if ((st = charge(p, 1, op)) || (st = next(p)))
            return st;
        if (!starts_operand(p->lx.tok.kind))
            return expected_expression(p);
        if (kind == HL_POW && (st = enter(p, op)))
            return st;
        if ((st = subexpr(p, hl_prec_table[kind].right, &rhs)))
            return st;
        if (kind == HL_POW)
            p->depth--;
        if ((st = combine(p, kind, v, &rhs)))
            return st;
    }
    hl_tok_kind k = p->lx.tok.kind;
    if (k == HL_TK_NUM || k == HL_TK_NAME || k == HL_TK_LPAREN) { /* "2x", "x y" */
        char a[48], b[48];
        hl_lex_text(a, sizeof a, p->src, p->prev);
        hl_lex_text(b, sizeof b, p->src, p->lx.tok);
        return hl_error_set(p->err, HL_EPARSE, p->src, p->lx.tok.pos, p->lx.tok.len,
                            p->in_args ? "expected ',' or an operator between '%s' and '%s'"
                                       : "expected an operator between '%s' and '%s'",
                            a, b);
    }
    return HL_OK;
}

/* What may follow a complete expression: the end, or (in lists) ';' '='. */
static int unexpected(parser *p)
{
    hl_token t = p->lx.tok;
    if (t.kind == HL_TK_RPAREN)
        return hl_error_set(p->err, HL_EPARSE, p->src, t.pos, 1, "unmatched ')'");
    if (t.kind == HL_TK_EQ)
        return hl_error_set(p->err, HL_EPARSE, p->src, t.pos, 1,
                            "unexpected '=': an expression is expected here, not an equation");
    if (t.kind == HL_TK_SEMI)
        return hl_error_set(p->err, HL_EPARSE, p->src, t.pos, 1,
                            "unexpected ';': a single expression is expected here");
    return error_at(p, HL_EPARSE, t, "unexpected '%s'", 1);
}

static int parser_init(parser *p, hl_pool *pool, const char *src, hl_error *err)
{
    hl_error_clear(err);
    hl_lex_init(&p->lx, src, 1);
    p->pool = pool;
    p->src = src;
    p->err = err;
    p->depth = 0;
    p->nodes = 0;
    p->ext = NULL;
    p->in_args = 0;
    memset(&p->prev, 0, sizeof p->prev);
    p->prev.kind = HL_TK_EOF;
    if (strlen(src) > (size_t)1 << 30)
        return hl_error_set(err, HL_ELIMIT, src, -1, 0, "formula longer than 1 GiB");
    return hl_lex_next(&p->lx, err);
}

hl_status hl_parse(const hl_expr **out, hl_pool *pool, const char *src, hl_error *err)
{
    parser p;
    value v;
    int st;

    *out = NULL;
    if ((st = parser_init(&p, pool, src, err)) == HL_OK) {
        if (p.lx.tok.kind == HL_TK_EOF)
            st = hl_error_set(err, HL_EPARSE, src, 0, 1, "empty formula");
        else if ((st = subexpr(&p, 0, &v)) == HL_OK && p.lx.tok.kind != HL_TK_EOF)
            st = unexpected(&p);
    }
    if (st == HL_OK)
        *out = v.e;
    hl_lex_clear(&p.lx);
    return st;
}

/* list := [eqn {';' eqn}] [';'];  eqn := expr ['=' expr] */
static int parse_items(parser *p, hl_eqn *out, int max, int *n)
{
    int st;
    while (p->lx.tok.kind != HL_TK_EOF) {
        hl_token start = p->lx.tok;
        value lhs, rhs;
        if (*n >= max)
            return hl_error_set(p->err, HL_ELIMIT, p->src, start.pos, start.len,
                                "more than %d items", max);
        if ((st = subexpr(p, 0, &lhs)))
            return st;
        out[*n].lhs = lhs.e;
        out[*n].rhs = NULL;
        out[*n].pos = start.pos;
        if (p->ext != NULL && p->ext->equations && p->lx.tok.kind != HL_TK_EQ)
            return error_at(p, HL_EPARSE, p->lx.tok, "expected '=', found '%s'", 1);
        if (p->lx.tok.kind == HL_TK_EQ) {
            if ((st = next(p)) || (st = subexpr(p, 0, &rhs)))
                return st;
            out[*n].rhs = rhs.e;
            if (p->lx.tok.kind == HL_TK_EQ)
                return hl_error_set(p->err, HL_EPARSE, p->src, p->lx.tok.pos, 1,
                                    "only one '=' is allowed in an item");
        }
        ++*n;
        if (p->lx.tok.kind == HL_TK_SEMI) {
            if ((st = next(p)))
                return st;
        } else if (p->lx.tok.kind != HL_TK_EOF) {
            return unexpected(p);
        }
    }
    return HL_OK;
}

hl_status hl_parse_list(hl_eqn *out, int max, int *n, hl_pool *pool, const char *src, hl_error *err)
{
    return hl_parse_list_ext(out, max, n, pool, src, NULL, err);
}

hl_status hl_parse_list_ext(hl_eqn *out, int max, int *n, hl_pool *pool, const char *src,
                            const hl_parse_ext *ext, hl_error *err)
{
    parser p;
    int st, count = 0;

    *n = 0;
    if ((st = parser_init(&p, pool, src, err)) == HL_OK) {
        p.ext = ext;
        st = parse_items(&p, out, max, &count);
    }
    if (st == HL_OK)
        *n = count;
    hl_lex_clear(&p.lx);
    return st;
}

int hl_symbol_pos(const char *src, const char *name)
{
    hl_lexer lx;
    size_t len = strlen(name);
    int found = -1;

    hl_lex_init(&lx, src, 0);
    for (;;) {
        int st = hl_lex_next(&lx, NULL);
        if (st == HL_OK && lx.tok.kind == HL_TK_EOF)
            break;
        if (st == HL_OK && lx.tok.kind == HL_TK_NAME && (size_t)lx.tok.len == len &&
            memcmp(src + lx.tok.pos, name, len) == 0) {
            found = lx.tok.pos;
            break;
        }
        if (lx.pos <= lx.tok.pos) /* a lexer error never stalls, but be sure */
            lx.pos = lx.tok.pos + 1;
    }
    hl_lex_clear(&lx);
    return found;
}
