/* Internal to src/exact/. */
#ifndef HAMLIE_EXACT_IMPL_H
#define HAMLIE_EXACT_IMPL_H

#include "hamlie/exact.h"
#include "hamlie/tape.h"

/* 1 dof: the right turning point, the first q > q0 with H(q,0) = E (Ht: the
 * tape of H over q, p), by doubling steps then bisection, in double.
 * HL_EDOM if none within a large range (an unbounded orbit). */
int hl_exact_turning_point_(double *qt, double q0, double E, hl_tape *Ht, hl_error *err);

#endif
