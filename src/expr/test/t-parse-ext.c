/* The parser with an extension (hl_parse_list_ext): calls of names that are
 * not functions of the language reach the hook with their arguments and
 * positions, the hook's node stands in the tree, its refusal is the parse's
 * error; equations-only lists; the messages and positions of bad calls. */
#include <stdio.h>
#include <string.h>

#include "hl_test.h"
#include "sx.h"

#define MAX_CALLS 8

typedef struct seen_call {
    char name[16];
    int pos, end, nargs;
    const hl_expr *args[HL_PARSE_MAX_ARGS];
    int arg_pos[HL_PARSE_MAX_ARGS];
} seen_call;

typedef struct hook {
    hl_pool *pool;
    seen_call calls[MAX_CALLS];
    int n;
} hook;

/* Records the call and stands "#k" for it; refuses the name "bad". */
static hl_status record(const hl_expr **out, void *arg, const hl_parse_call *c, hl_error *err)
{
    hook *h = arg;
    if (c->len == 3 && memcmp(c->name, "bad", 3) == 0)
        return hl_error_set(err, HL_EINVAL, c->src, c->pos, c->len, "no calls of 'bad'");
    if (h->n == MAX_CALLS)
        return hl_error_set(err, HL_ELIMIT, c->src, c->pos, c->len, "test: too many calls");
    seen_call *s = &h->calls[h->n];
    snprintf(s->name, sizeof s->name, "%.*s", c->len, c->name);
    s->pos = c->pos, s->end = c->end, s->nargs = c->nargs;
    for (int i = 0; i < c->nargs; i++)
        s->args[i] = c->args[i], s->arg_pos[i] = c->arg_pos[i];
    char name[8];
    snprintf(name, sizeof name, "#%d", h->n++);
    *out = hl_sym(h->pool, name);
    return HL_OK;
}

static void check_calls(void)
{
    hl_pool *pool = hl_pool_new();
    hook h = {.pool = pool};
    hl_parse_ext ext = {record, &h, 0};
    hl_eqn items[4];
    hl_error err;
    int n = -1;
    /*                 0         1         2         3
     *                 0123456789012345678901234567890123456 */
    const char *src = "Y = f(x, y + 1, g(z))*2; h(-1/2); atan2(y, x)";
    CHECK_MSG(hl_parse_list_ext(items, 4, &n, pool, src, &ext, &err) == HL_OK, "%s", err.msg);
    CHECK(n == 3 && h.n == 3);
    /* g(z) ends first, so it is #0 */
    CHECK_STR(h.calls[0].name, "g");
    CHECK(h.calls[0].pos == 16 && h.calls[0].end == 19 && h.calls[0].nargs == 1);
    CHECK(h.calls[0].args[0] == sx(pool, "z") && h.calls[0].arg_pos[0] == 18);
    CHECK_STR(h.calls[1].name, "f");
    CHECK(h.calls[1].pos == 4 && h.calls[1].end == 20 && h.calls[1].nargs == 3);
    CHECK(h.calls[1].args[0] == sx(pool, "x") && h.calls[1].args[1] == sx(pool, "(add y 1)"));
    CHECK(h.calls[1].args[2] == sx(pool, "#0"));
    CHECK(h.calls[1].arg_pos[0] == 6 && h.calls[1].arg_pos[1] == 9 && h.calls[1].arg_pos[2] == 16);
    CHECK(items[0].lhs == sx(pool, "Y") && items[0].rhs == sx(pool, "(mul #1 2)"));
    /* arguments are formulas like any other: -1/2 folds to a number */
    CHECK_STR(h.calls[2].name, "h");
    CHECK(h.calls[2].nargs == 1 && h.calls[2].args[0] == sx(pool, "-1/2"));
    CHECK(items[1].lhs == sx(pool, "#2") && items[1].rhs == NULL && items[1].pos == 25);
    /* the language's own functions do not reach the hook */
    CHECK(items[2].lhs == sx(pool, "(atan2 y x)"));

    /* the hook's refusal is the parse's error, at the hook's position */
    CHECK(hl_parse_list_ext(items, 4, &n, pool, "Y = 1 + bad(x)", &ext, &err) == HL_EINVAL);
    CHECK(err.pos == 8 && n == 0);
    CHECK_STR(err.msg, "no calls of 'bad'");
    hl_pool_free(pool);
}

static const struct {
    const char *src;
    int status, pos;
    const char *msg;
} bad[] = {
    {"Y = f(x y)", HL_EPARSE, 8, "expected ',' or an operator between 'x' and 'y'"},
    {"Y = f(x, (y z))", HL_EPARSE, 12, "expected an operator between 'y' and 'z'"},
    {"Y = f(x, sin(y z))", HL_EPARSE, 15, "expected an operator between 'y' and 'z'"},
    {"Y = atan2(x y)", HL_EPARSE, 12, "expected ',' or an operator between 'x' and 'y'"},
    {"Y = sin(x y)", HL_EPARSE, 10, "expected an operator between 'x' and 'y'"},
    {"Y = f()", HL_EPARSE, 6, "expected an expression after '('"},
    {"Y = f(x,)", HL_EPARSE, 8, "expected an expression after ','"},
    {"Y = f(x", HL_EPARSE, 7, "expected ')' to close '(' opened at column 6"},
    {"Y = f(1, 2, 3, 4, 5, 6, 7, 8, 9)", HL_EPARSE, 30, "too many arguments (at most 8)"},
    {"Y", HL_EPARSE, 1, "expected '=', found 'end of formula'"},
    {"Y = 1; Z; W = 2", HL_EPARSE, 8, "expected '=', found ';'"},
    {"Y = 1; Z W = 2", HL_EPARSE, 9, "expected an operator between 'Z' and 'W'"},
};

static void check_bad(void)
{
    hl_pool *pool = hl_pool_new();
    hook h = {.pool = pool};
    hl_parse_ext ext = {record, &h, 1};
    hl_eqn items[4];
    for (size_t i = 0; i < sizeof bad / sizeof *bad; i++) {
        hl_error err;
        int n = -1;
        h.n = 0;
        int st = hl_parse_list_ext(items, 4, &n, pool, bad[i].src, &ext, &err);
        CHECK_MSG(st == bad[i].status && err.pos == bad[i].pos, "\"%s\": status %d pos %d (%s)",
                  bad[i].src, st, err.pos, err.msg);
        CHECK_STR(err.msg, bad[i].msg);
        CHECK(err.src == bad[i].src && n == 0);
    }
    hl_pool_free(pool);
}

/* Without a hook, calls are what they always were; equations-only alone. */
static void check_without_hook(void)
{
    hl_pool *pool = hl_pool_new();
    hl_eqn items[4];
    hl_error err;
    int n = -1;
    hl_parse_ext eq_only = {NULL, NULL, 1};
    CHECK(hl_parse_list_ext(items, 4, &n, pool, "Y = f(x)", &eq_only, &err) == HL_EPARSE);
    CHECK(err.pos == 4);
    CHECK_STR(err.msg, "unknown function 'f'");
    CHECK(hl_parse_list_ext(items, 4, &n, pool, "Y = x; Z", NULL, &err) == HL_OK && n == 2);
    CHECK(items[1].lhs == sx(pool, "Z") && items[1].rhs == NULL);
    hl_pool_free(pool);
}

/* A call is a level of nesting like a parenthesis: deep input is refused. */
static void check_depth(void)
{
    hl_pool *pool = hl_pool_new();
    hook h = {.pool = pool};
    hl_parse_ext ext = {record, &h, 0};
    char src[4 * (HL_PARSE_MAX_DEPTH + 10) + 8];
    int k = 0;
    for (int i = 0; i < HL_PARSE_MAX_DEPTH + 1; i++)
        k += sprintf(src + k, "f(");
    k += sprintf(src + k, "x");
    for (int i = 0; i < HL_PARSE_MAX_DEPTH + 1; i++)
        k += sprintf(src + k, ")");
    hl_eqn items[1];
    hl_error err;
    int n;
    CHECK(hl_parse_list_ext(items, 1, &n, pool, src, &ext, &err) == HL_ELIMIT);
    CHECK(h.n == 0); /* refused before any call was made */
    hl_pool_free(pool);
}

int main(void)
{
    check_calls();
    check_bad();
    check_without_hook();
    check_depth();
    return HL_TEST_END();
}
