/* What the files of src/chaos share: the layout of the extended ODE. */
#ifndef HAMLIE_CHAOS_IMPL_H
#define HAMLIE_CHAOS_IMPL_H

#include "hamlie/chaos.h"
#include "hamlie/flow.h"
#include "hamlie/tape.h"

/* The extended state, n = 2N (chaos_tape):
 *   X[0 .. n)      z = (q, p)
 *   X[n .. 2n)     delta
 *   X[2n]          k = 1/T           k' = 0
 *   X[2n+1]        c = s/T           c' = k          (the clock: Y' depends on s)
 *   X[2n+2]        a = A/T^2         a' = c r k      (A = int_0^s u r(u) du)
 *   X[2n+3]        b = B/T^2         b' = 2 a k / c  (B = int_0^s Y(u) du)
 * with r = delta . delta' / delta . delta.  The scale T = t_end keeps every
 * extra component of order 1 (c <= 1, a and b of the order of the Lyapunov
 * exponent), because the integrator's error test is relative to the largest
 * component: an unscaled clock of 1e3 would loosen it a thousandfold for z.
 * k is a component (not a constant of the tape) so that one tape serves
 * every t_end.  b' is 0/0 at s = 0, so the first chunk runs without b
 * (CHAOS_NO_B components) and gets B by quadrature (chaos.c). */
#define CHAOS_K(n) (2 * (n))
#define CHAOS_C(n) (2 * (n) + 1)
#define CHAOS_A(n) (2 * (n) + 2)
#define CHAOS_B(n) (2 * (n) + 3)
#define CHAOS_DIM(n) (2 * (n) + 4)
#define CHAOS_DIM_NO_B(n) (2 * (n) + 3)

/* The extended ODE of H as a tape, with b (full) or without. */
hl_status chaos_tape(hl_tape **out, hl_system *sys, int with_b, hl_error *err);

#endif
