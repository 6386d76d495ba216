/* The ODE step of the double back ends written from its contract
 * (tape_impl.h, hl_tape_ode_source) for the tests that run the recursion
 * by hand: z_i[k+1] = f_i[k] / (k+1) rounded once; where input i's
 * derivative is an input j whose own derivative is computed (neither an
 * input nor a constant), f_j[k-1] / (k (k+1)) rounded once.  A division,
 * where the back ends multiply by a split reciprocal: the two agree but
 * within 2^-105 of a rounding boundary (t-native's test_recip_split).
 * Register r's coefficient k is R[r S + k]. */
#ifndef HAMLIE_TAPE_TEST_ODE_REF_H
#define HAMLIE_TAPE_TEST_ODE_REF_H

#include "tape/tape_impl.h"

static void ref_ode_step(double *R, const hl_tape *t, int k, int S)
{
    for (int i = 0; i < t->nin; i++) {
        int j = t->outreg[i];
        int chained = k >= 1 && j < t->nin && t->outreg[j] >= t->nin && !t->isconst[t->outreg[j]];
        R[(size_t)i * S + k + 1] = chained
                                       ? R[(size_t)t->outreg[j] * S + k - 1] / ((double)k * (k + 1))
                                       : R[(size_t)j * S + k] / (k + 1);
    }
}

#endif
