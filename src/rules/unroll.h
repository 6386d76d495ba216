/* A convolution written out term by term through the emitter's own calls,
 * for the back ends whose values are code (C text, gccjit): the sum is
 * unrolled when the rule runs, in the order of hl_conv_plan (rule.h). */
#ifndef HAMLIE_RULES_UNROLL_H
#define HAMLIE_RULES_UNROLL_H

#include "rules/rule.h"

/* The sum of c's terms built from em's coef, num, mul and add (a usable
 * hl_em_ops.conv); *has = 0 and an unspecified value for an empty sum. */
hl_ev hl_conv_unrolled(hl_em *em, const hl_conv *c, int *has);

#endif /* HAMLIE_RULES_UNROLL_H */
