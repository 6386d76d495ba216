/* Shared by the alg tests: one pool and context per test program, and rd(),
 * which reads a formula into an element and says on stderr what it could
 * not read (t-atoms reads inputs meant to fail, so it keeps a quiet one). */
#ifndef HL_ALG_TEST_H
#define HL_ALG_TEST_H

#include <stdio.h>

#include "hamlie/alg.h"

static hl_pool *pool;
static hl_alg_ctx *ctx;

static int rd(hl_alg *r, const char *s)
{
    const hl_expr *e;
    hl_error err;
    hl_error_clear(&err);
    int st = hl_parse(&e, pool, s, &err);
    if (st == HL_OK)
        st = hl_alg_from_expr(r, e, ctx, &err);
    if (st != HL_OK)
        fprintf(stderr, "cannot read '%s': %s\n", s, err.msg);
    return st;
}

#endif
