/* Operator priorities shared by the parser and the printers (the scheme of
 * Lua's lparser.c): a binary operator has a left and a right priority; a
 * right priority below the left one makes it right associative.  The parser
 * continues an operand with an operator only if the operator's left priority
 * is above the current limit; the printers add parentheses exactly where
 * that rule would otherwise regroup, so parse(print(e)) == e. */
#ifndef HAMLIE_EXPR_PREC_H
#define HAMLIE_EXPR_PREC_H

#include "hamlie/expr.h"

#define HL_PREC_UNARY 12 /* -a: looser than ^, tighter than * and / */
#define HL_PREC_ATOM 100 /* numbers, symbols, pi, calls, parentheses */

typedef struct hl_prec {
    unsigned char left, right;
} hl_prec;

/* Indexed by the binary kinds HL_ADD .. HL_POW. */
static const hl_prec hl_prec_table[] = {
    [HL_ADD] = {10, 10}, /* a + b, left associative */
    [HL_SUB] = {10, 10}, /* a - b */
    [HL_MUL] = {11, 11}, /* a * b */
    [HL_DIV] = {11, 11}, /* a / b */
    [HL_POW] = {14, 13}, /* a ^ b, right associative */
};

static inline int hl_is_binary(hl_expr_kind k)
{
    return k == HL_ADD || k == HL_SUB || k == HL_MUL || k == HL_DIV || k == HL_POW;
}

#endif
