/* The Arb back end of the rules (arb_em.c): the Arb interpreters of
 * taylor_arb.c and eval.c run each instruction's rule through it. */
#ifndef HAMLIE_TAPE_ARB_EM_IMPL_H
#define HAMLIE_TAPE_ARB_EM_IMPL_H

#include "tape/tape_impl.h"

typedef struct hl_arb_em hl_arb_em;

/* An emitter for programs of up to ninstr instructions (their kept values). */
hl_arb_em *hl_arb_em_new(int ninstr);
void hl_arb_em_free(hl_arb_em *a); /* NULL is a no-op */

/* Coefficient k of every instruction of code[0..n-1] over the register file
 * r (stride S), at prec bits.  Run k = 0 first: it fills the kept values. */
void hl_arb_em_taylor(hl_arb_em *a, const hl_instr *code, int n, arb_ptr r, int S, int k,
                      slong prec);

/* The point values of code[0..n-1] over r (one arb per register). */
void hl_arb_em_point(hl_arb_em *a, const hl_instr *code, int n, arb_ptr r, slong prec);

#endif /* HAMLIE_TAPE_ARB_EM_IMPL_H */
