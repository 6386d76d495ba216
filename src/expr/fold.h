/* Smart constructors that fold 0 and 1 operands, double negation and
 * rational constants (internal to src/expr: the layer's generated
 * expressions, derivatives and Taylor coefficients, go through them). */
#ifndef HAMLIE_EXPR_FOLD_H
#define HAMLIE_EXPR_FOLD_H

#include "hamlie/expr.h"

int hl_fold_is_num(const hl_expr *e, long v); /* e is the integer v */
const hl_expr *hl_fold_neg(hl_pool *pool, const hl_expr *a);
const hl_expr *hl_fold_add(hl_pool *pool, const hl_expr *a, const hl_expr *b);
const hl_expr *hl_fold_sub(hl_pool *pool, const hl_expr *a, const hl_expr *b);
const hl_expr *hl_fold_mul(hl_pool *pool, const hl_expr *a, const hl_expr *b);
const hl_expr *hl_fold_div(hl_pool *pool, const hl_expr *a, const hl_expr *b);
const hl_expr *hl_fold_pow(hl_pool *pool, const hl_expr *a, const hl_expr *b);

#endif
