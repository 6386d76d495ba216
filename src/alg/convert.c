/* Expression DAG -> canonical element, memoised over shared subexpressions.
 * The nodes are converted in post-order (hl_expr_postorder), so each finds
 * its operands in the memo and nothing recurses: a sum of 10^5 terms is a
 * chain 10^5 deep. */
#include <stdlib.h>

#include "alg/alg_internal.h"
#include "base/buf.h"
#include "base/memo.h"

typedef struct convert_walk {
    hl_memo m; /* node -> its element, an hl_alg * owned here */
    hl_alg_ctx *ctx;
    hl_error *err;
} convert_walk;

static void memo_free(convert_walk *w)
{
    for (size_t i = 0; i < w->m.cap; i++)
        if (w->m.keys[i] != NULL) {
            hl_alg_clear(w->m.vals[i].p, w->ctx);
            free(w->m.vals[i].p);
        }
    hl_memo_clear(&w->m);
}

static int convert(hl_alg *r, const hl_expr *e, convert_walk *w);

/* r = value of e, through the memo. */
static int value(hl_alg *r, const hl_expr *e, convert_walk *w)
{
    const hl_memo_val *known = hl_memo_get(&w->m, e);
    if (known != NULL) {
        hl_alg_set(r, known->p, w->ctx);
        return HL_OK;
    }
    int status = convert(r, e, w);
    if (status != HL_OK)
        return status;
    hl_alg *v = hl_xmalloc(sizeof *v);
    hl_alg_init(v, w->ctx);
    hl_alg_set(v, r, w->ctx);
    hl_memo_put(&w->m, e)->p = v;
    return HL_OK;
}

static int convert(hl_alg *r, const hl_expr *e, convert_walk *w)
{
    hl_alg_ctx *ctx = w->ctx;
    hl_error *err = w->err;
    int status = HL_OK;
    hl_alg a, b;
    switch (e->kind) {
    case HL_NUM:
        hl_alg_set_fmpq(r, e->num, ctx);
        return HL_OK;
    case HL_SYM: {
        int i = hl_alg_ctx_index(ctx, e->name);
        if (i < 0)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "unknown symbol '%s'", e->name);
        hl_alg_gen(r, i, ctx);
        return HL_OK;
    }
    case HL_PI: return hl_alg_pi(r, ctx, err);
    case HL_FUN:
        if (e->b != NULL)
            break; /* atan2(y, x): both operands, below */
        /* fall through */
    case HL_NEG:
        hl_alg_init(&a, ctx);
        status = value(&a, e->a, w);
        if (status == HL_OK) {
            if (e->kind == HL_NEG)
                hl_alg_neg(r, &a, ctx);
            else
                status = hl_alg_apply(r, e->fun, &a, ctx, err);
        }
        hl_alg_clear(&a, ctx);
        return status;
    default:
        break;
    }
    hl_alg_init(&a, ctx);
    hl_alg_init(&b, ctx);
    status = value(&a, e->a, w);
    if (status == HL_OK)
        status = value(&b, e->b, w);
    if (status == HL_OK) {
        switch (e->kind) {
        case HL_ADD: hl_alg_add(r, &a, &b, ctx); break;
        case HL_SUB: hl_alg_sub(r, &a, &b, ctx); break;
        case HL_MUL: hl_alg_mul(r, &a, &b, ctx); break;
        case HL_DIV: status = hl_alg_div(r, &a, &b, ctx, err); break;
        case HL_POW: status = hl_alg_pow(r, &a, &b, ctx, err); break;
        case HL_FUN: status = hl_alg_apply2(r, e->fun, &a, &b, ctx, err); break;
        default: status = hl_error_set(err, HL_EINVAL, NULL, -1, 0, "bad expression node");
        }
    }
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&b, ctx);
    return status;
}

static int convert_node(void *arg, const hl_expr *e)
{
    convert_walk *w = arg;
    hl_alg t;
    hl_alg_init(&t, w->ctx);
    int status = value(&t, e, w);
    hl_alg_clear(&t, w->ctx);
    return status;
}

hl_status hl_alg_from_expr(hl_alg *r, const hl_expr *e, hl_alg_ctx *ctx, hl_error *err)
{
    convert_walk w = {{0}, ctx, err};
    hl_memo_init(&w.m);
    int status = hl_expr_postorder(&e, 1, convert_node, &w);
    hl_alg t;
    hl_alg_init(&t, ctx);
    if (status == HL_OK)
        status = value(&t, e, &w);
    if (status == HL_OK)
        hl_alg_swap(r, &t, ctx);
    hl_alg_clear(&t, ctx);
    memo_free(&w);
    return status;
}
