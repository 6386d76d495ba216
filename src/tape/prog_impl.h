/* The double interpreter's recorded programs (prog.c records them,
 * prog_run.c runs them; their layout is prog_ops.h).
 *
 * The rules of src/rules/ say what to compute through an emitter; calling
 * them (through function pointers, per term) at every step would cost more
 * than the arithmetic.  So the interpreter runs them ONCE per layout
 * through a recording emitter, which writes for each coefficient k a flat
 * list of micro-operations with resolved pointers (into the Taylor register
 * file, the constants, a few temporaries, and the values each instruction
 * keeps from k = 0), and then executes that list with threaded code (each
 * op holds its handler's address).  A convolution is one micro-operation
 * whose loop runs in C in hl_conv_plan's order, so interpreted and
 * compiled runs agree bit for bit. */
#ifndef HAMLIE_TAPE_PROG_IMPL_H
#define HAMLIE_TAPE_PROG_IMPL_H

#include "tape/tape_impl.h"

typedef struct hl_prog hl_prog;

/* The Taylor programs of coefficients 0..order of t's body over the
 * register file td (stride order + 1, constants already in place).  When t
 * has as many outputs as inputs, the program of each k < order also holds
 * the ODE step z[k+1] = f[k] / (k+1) (rule.h: fma(f, hi, f lo)), run by
 * hl_prog_run_ode only: in the loop it costs no call, no loop of its own. */
hl_prog *hl_prog_taylor(const hl_tape *t, double *td, int order);

/* The point program of t's body over the register file r (one double per
 * register). */
hl_prog *hl_prog_point(const hl_tape *t, double *r);

/* Run the program of coefficient k (0 for a point program). */
void hl_prog_run(const hl_prog *p, int k);

/* The ODE recursion: run the programs of coefficients 0 .. kend - 1 (kend
 * <= order), each followed by its ODE step to k + 1 (hl_prog_taylor), in
 * one call of the loop. */
void hl_prog_run_ode(const hl_prog *p, int kend);

void hl_prog_free(hl_prog *p); /* NULL is a no-op */

/* The loop that runs p: "avx2" or "scalar" (either scalar one: with the
 * fma instruction or without; prog_run.c, HAMLIE_NO_AVX2, HAMLIE_NO_FMA). */
const char *hl_prog_loop(const hl_prog *p);

#endif /* HAMLIE_TAPE_PROG_IMPL_H */
