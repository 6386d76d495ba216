/* The printers' length-only entry (internal: the alg layer's printer asks
 * which of two forms of a sum is shorter, many times over one DAG). */
#ifndef HAMLIE_EXPR_PRINT_IMPL_H
#define HAMLIE_EXPR_PRINT_IMPL_H

#include <stddef.h>

#include "base/memo.h"
#include "hamlie/expr.h"

/* strlen(hl_expr_print(e, style)) without writing it out: each node is
 * measured once and its length kept in memo (value .l), so forms that share
 * subexpressions cost only their new nodes.  One memo serves one style. */
size_t hl_expr_print_len(const hl_expr *e, hl_style style, hl_memo *memo);

#endif
