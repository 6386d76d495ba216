/* The printers' length-only entry (internal: the alg layer's printer asks
 * which of two forms of a sum is shorter, many times over one DAG). */
#ifndef HAMLIE_EXPR_PRINT_IMPL_H
#define HAMLIE_EXPR_PRINT_IMPL_H

#include <stddef.h>

#include "base/buf.h"
#include "hamlie/expr.h"

/* strlen(hl_expr_print(e, style)), written into scratch (an hl_buf kept
 * by the caller, so that many lengths cost no allocation). */
size_t hl_expr_print_len(const hl_expr *e, hl_style style, hl_buf *scratch);

#endif
