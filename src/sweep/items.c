/* The small language of a sweep's fields: "name=v,v,name=a:b:n" split into
 * items (a name and its values, each a byte span of the text), so that
 * every error can point at the spot in the text. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "hamlie/expr.h"
#include "sweep/sweep_impl.h"

static int is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

static void trim(const char *t, int *a, int *b)
{
    while (*a < *b && is_blank(t[*a]))
        ++*a;
    while (*b > *a && is_blank(t[*b - 1]))
        --*b;
}

static void add_value(sweep_item *it, int a, int b)
{
    it->val = hl_xrealloc(it->val, (size_t)(it->nval + 1) * sizeof *it->val);
    it->val_len = hl_xrealloc(it->val_len, (size_t)(it->nval + 1) * sizeof *it->val_len);
    it->val[it->nval] = a;
    it->val_len[it->nval++] = b - a;
}

/* One comma-separated token [a, b): a new item "name=value" or one more
 * value of the last item. */
static hl_status take_token(sweep_item **items, int *n, const char *text, int a, int b,
                            const char *what, hl_error *err)
{
    trim(text, &a, &b);
    if (a == b)
        return hl_error_set(err, HL_EPARSE, text, a, 1, "%s: an empty entry", what);
    const char *eq = memchr(text + a, '=', (size_t)(b - a));
    if (eq == NULL) {
        if (*n == 0)
            return hl_error_set(err, HL_EPARSE, text, a, b - a,
                                "%s: expected name=value, not '%.*s'", what, b - a, text + a);
        add_value(&(*items)[*n - 1], a, b);
        return HL_OK;
    }
    int na = a, nb = (int)(eq - text), va = nb + 1, vb = b;
    trim(text, &na, &nb);
    trim(text, &va, &vb);
    if (na == nb)
        return hl_error_set(err, HL_EPARSE, text, nb, 1, "%s: a name is missing before '='", what);
    if (va == vb)
        return hl_error_set(err, HL_EPARSE, text, va < (int)strlen(text) ? va : nb, 1,
                            "%s: a value is missing after '%.*s='", what, nb - na, text + na);
    *items = hl_xrealloc(*items, (size_t)(*n + 1) * sizeof **items);
    sweep_item *it = &(*items)[(*n)++];
    memset(it, 0, sizeof *it);
    it->name = na;
    it->name_len = nb - na;
    add_value(it, va, vb);
    return HL_OK;
}

hl_status sweep_items(sweep_item **items, int *n, const char *text, const char *what, hl_error *err)
{
    *items = NULL;
    *n = 0;
    int len = (int)strlen(text), st = HL_OK;
    if (len == 0)
        return hl_error_set(err, HL_EPARSE, text, 0, 1, "%s is empty", what);
    for (int a = 0; st == HL_OK && a <= len;) {
        int b = a;
        while (b < len && text[b] != ',')
            b++;
        st = take_token(items, n, text, a, b, what, err);
        a = b + 1;
    }
    if (st != HL_OK) {
        sweep_items_free(*items, *n);
        *items = NULL;
        *n = 0;
    }
    return st;
}

void sweep_items_free(sweep_item *items, int n)
{
    for (int i = 0; i < n; i++) {
        free(items[i].val);
        free(items[i].val_len);
    }
    free(items);
}

/* A value that is not a plain number: a constant formula (pi/2, 1/8,
 * sqrt(2)), as run's initial values take.  buf holds the item alone. */
static hl_status constant_formula(double *v, const char *buf, const char *text, int pos, int len,
                                  const char *what, hl_error *err)
{
    hl_pool *pool = hl_pool_new();
    const hl_expr *e;
    const char *sym;
    hl_error e1;
    hl_error_clear(&e1);
    hl_status st = hl_parse(&e, pool, buf, &e1);
    if (st != HL_OK)
        st = hl_error_set(err, HL_EPARSE, text, pos + (e1.pos > 0 ? e1.pos : 0), 1,
                          "%s: expected a number or a constant formula, not '%s': %s", what, buf,
                          e1.msg);
    else if (hl_expr_symbols(e, &sym, 1) > 0)
        st = hl_error_set(err, HL_EINVAL, text, pos + hl_symbol_pos(buf, sym), (int)strlen(sym),
                          "%s: expected a number or a constant formula, not '%s' (it depends "
                          "on '%s')",
                          what, buf, sym);
    else if ((st = hl_expr_eval_d(v, e, 0, NULL, NULL, &e1)) != HL_OK)
        st = hl_error_set(err, st, text, pos, len, "%s: '%s': %s", what, buf, e1.msg);
    hl_pool_free(pool);
    return st;
}

hl_status sweep_number(double *v, const char *text, int pos, int len, const char *what,
                       hl_error *err)
{
    char buf[256];
    if (len <= 0 || len > 255)
        return hl_error_set(err, HL_EPARSE, text, pos, len > 0 ? len : 1, "%s: expected a number",
                            what);
    memcpy(buf, text + pos, (size_t)len);
    buf[len] = '\0';
    char *end;
    errno = 0;
    *v = strtod(buf, &end);
    if (end == buf || *end != '\0') {
        hl_status st = constant_formula(v, buf, text, pos, len, what, err);
        if (st != HL_OK)
            return st;
    }
    if (!isfinite(*v))
        return hl_error_set(err, HL_EDOM, text, pos, len, "%s: '%s' is not finite", what, buf);
    return HL_OK;
}
