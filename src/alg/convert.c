/* Expression DAG -> canonical element, memoised over shared subexpressions.
 * The nodes are converted in post-order (hl_expr_postorder), so each finds
 * its operands in the memo and nothing recurses: a sum of 10^5 terms is a
 * chain 10^5 deep. */
#include <stdint.h>
#include <stdlib.h>

#include "alg/alg_internal.h"
#include "base/buf.h"

typedef struct memo_entry {
    const hl_expr *key;
    hl_alg val;
} memo_entry;

typedef struct memo {
    memo_entry *slot;
    size_t nslots, count; /* nslots a power of two */
} memo;

static size_t memo_hash(const hl_expr *e, size_t n)
{
    return (size_t)(((uintptr_t)e >> 4) * 0x9e3779b97f4a7c15ULL) & (n - 1);
}

static memo_entry *memo_find(memo *m, const hl_expr *e)
{
    size_t j = memo_hash(e, m->nslots);
    while (m->slot[j].key != NULL && m->slot[j].key != e)
        j = (j + 1) & (m->nslots - 1);
    return &m->slot[j];
}

static void memo_grow(memo *m)
{
    memo old = *m;
    m->nslots *= 2;
    m->slot = hl_xcalloc(m->nslots, sizeof *m->slot);
    for (size_t i = 0; i < old.nslots; i++)
        if (old.slot[i].key != NULL)
            *memo_find(m, old.slot[i].key) = old.slot[i]; /* moves the hl_alg */
    free(old.slot);
}

static void memo_clear(memo *m, hl_alg_ctx *ctx)
{
    for (size_t i = 0; i < m->nslots; i++)
        if (m->slot[i].key != NULL)
            hl_alg_clear(&m->slot[i].val, ctx);
    free(m->slot);
}

static int convert(hl_alg *r, const hl_expr *e, memo *m, hl_alg_ctx *ctx, hl_error *err);

/* r = value of e, through the memo. */
static int value(hl_alg *r, const hl_expr *e, memo *m, hl_alg_ctx *ctx, hl_error *err)
{
    memo_entry *me = memo_find(m, e);
    if (me->key != NULL) {
        hl_alg_set(r, &me->val, ctx);
        return HL_OK;
    }
    int status = convert(r, e, m, ctx, err);
    if (status != HL_OK)
        return status;
    if (2 * (m->count + 1) > m->nslots)
        memo_grow(m);
    me = memo_find(m, e);
    me->key = e;
    hl_alg_init(&me->val, ctx);
    hl_alg_set(&me->val, r, ctx);
    m->count++;
    return HL_OK;
}

static int convert(hl_alg *r, const hl_expr *e, memo *m, hl_alg_ctx *ctx, hl_error *err)
{
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
        status = value(&a, e->a, m, ctx, err);
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
    status = value(&a, e->a, m, ctx, err);
    if (status == HL_OK)
        status = value(&b, e->b, m, ctx, err);
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

typedef struct convert_walk {
    memo m;
    hl_alg_ctx *ctx;
    hl_error *err;
} convert_walk;

static int convert_node(void *arg, const hl_expr *e)
{
    convert_walk *w = arg;
    hl_alg t;
    hl_alg_init(&t, w->ctx);
    int status = value(&t, e, &w->m, w->ctx, w->err);
    hl_alg_clear(&t, w->ctx);
    return status;
}

hl_status hl_alg_from_expr(hl_alg *r, const hl_expr *e, hl_alg_ctx *ctx, hl_error *err)
{
    convert_walk w = {{hl_xcalloc(64, sizeof(memo_entry)), 64, 0}, ctx, err};
    int status = hl_expr_postorder(&e, 1, convert_node, &w);
    hl_alg t;
    hl_alg_init(&t, ctx);
    if (status == HL_OK)
        status = value(&t, e, &w.m, ctx, err);
    if (status == HL_OK)
        hl_alg_swap(r, &t, ctx);
    hl_alg_clear(&t, ctx);
    memo_clear(&w.m, ctx);
    return status;
}
