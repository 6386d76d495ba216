/* A convolution written out term by term through the emitter's own calls,
 * for the back ends whose values are code (C text, gccjit): the sum is
 * unrolled when the rule runs, in the order of hl_conv_plan (rule.h). */
#ifndef HAMLIE_RULES_UNROLL_H
#define HAMLIE_RULES_UNROLL_H

#include "rules/rule.h"

/* The sum of c's terms built from em's coef, num, mul and add (a usable
 * hl_em_ops.conv); *has = 0 and an unspecified value for an empty sum. */
hl_ev hl_conv_unrolled(hl_em *em, const hl_conv *c, int *has);

/* One term of c at j, as hl_conv_unrolled makes it (fresh: j's term read
 * as a fresh one, the x[k] term's product taken as (w y[0]) x[k]); for a
 * back end that makes the known terms its own way and the fresh ones so. */
hl_ev hl_conv_term(hl_em *em, const hl_conv *c, int j, int fresh);

/* a + b where either may be absent (has_a, has_b); *has whether any is */
hl_ev hl_conv_plus(hl_em *em, hl_ev a, int has_a, hl_ev b, int has_b, int *has);

#endif /* HAMLIE_RULES_UNROLL_H */
