/* The terms of the cost of a Taylor step (cost.c): what
 * hl_tape_taylor_step_cost counts on a tape, apart, so that
 * bench/cost_fit.py can fit the figures per term on many tapes
 * (bench/work_precision.c methods=terms prints them). */
#ifndef HAMLIE_COST_IMPL_H
#define HAMLIE_COST_IMPL_H

#include "tape/tape_impl.h"

typedef struct hl_taylor_cost_terms {
    double products; /* convolutions a coefficient (a sum of k multiply-adds at order k) */
    double linear;   /* instructions without a convolution (sums, constant factors) */
    double calls;    /* instructions whose order 0 is a call of libm (sin, exp, pow, ...) */
    double state;    /* state components (the tape's inputs) */
} hl_taylor_cost_terms;

void hl_tape_taylor_cost_terms(const hl_tape *t, hl_taylor_cost_terms *terms);

#endif
