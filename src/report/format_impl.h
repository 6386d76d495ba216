/* Internal to the report layer and its tests. */
#ifndef HAMLIE_REPORT_FORMAT_IMPL_H
#define HAMLIE_REPORT_FORMAT_IMPL_H

/* Nonzero: formulas always go through the expression DAG (hl_alg_to_expr,
 * hl_expr_print), never the direct path for polynomials; the tests compare
 * the two (format.c). */
extern int hl_format_no_direct;

#endif
