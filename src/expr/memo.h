/* A map from nodes to results, so walks over a DAG visit each node once
 * (internal to src/expr). */
#ifndef HAMLIE_EXPR_MEMO_H
#define HAMLIE_EXPR_MEMO_H

#include <stddef.h>
#include "hamlie/expr.h"

typedef union hl_memo_val {
    const hl_expr *e;
    double d;
    int i;
} hl_memo_val;

typedef struct hl_memo {
    const hl_expr **keys; /* open addressing; NULL = empty */
    hl_memo_val *vals;
    size_t cap, count;    /* cap a power of two */
} hl_memo;

void hl_memo_init(hl_memo *m);
void hl_memo_clear(hl_memo *m);

/* The value stored for key, or NULL. */
hl_memo_val *hl_memo_get(const hl_memo *m, const hl_expr *key);

/* The slot for key, created (zeroed) if absent.  The pointer is valid until
 * the next hl_memo_put. */
hl_memo_val *hl_memo_put(hl_memo *m, const hl_expr *key);

#endif
