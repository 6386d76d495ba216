/* The library's one memo: a map from a pointer (an expression node, an
 * algebra element, ...) to a value, so that walks over a DAG visit each node
 * once.  Internal to the library; every layer uses this one. */
#ifndef HAMLIE_BASE_MEMO_H
#define HAMLIE_BASE_MEMO_H

#include <stddef.h>

struct hl_expr;

typedef union hl_memo_val {
    const struct hl_expr *e;
    void *p;
    double d;
    long l;
    int i;
} hl_memo_val;

typedef struct hl_memo {
    const void **keys; /* open addressing; NULL = empty */
    hl_memo_val *vals;
    size_t cap, count;    /* cap a power of two */
} hl_memo;

void hl_memo_init(hl_memo *m);
void hl_memo_clear(hl_memo *m);

/* The value stored for key, or NULL. */
hl_memo_val *hl_memo_get(const hl_memo *m, const void *key);

/* The slot for key, created (zeroed) if absent.  The pointer is valid until
 * the next hl_memo_put. */
hl_memo_val *hl_memo_put(hl_memo *m, const void *key);

#endif /* HAMLIE_BASE_MEMO_H */
