/* Point evaluation of a tape, in double and in Arb.
 *
 * The double interpreter runs the point rules of src/rules/ recorded once
 * per tape into a flat program over the register file (prog_impl.h):
 * nothing is allocated per call, the constants sit in the register file
 * from compile time. */
#define _GNU_SOURCE /* sincos */
#include <math.h>
#include <string.h>

#include "tape/arb_em_impl.h"
#include "tape/prog_impl.h"

void hl_tape_run_arb(const hl_instr *code, int n, arb_ptr r, slong prec)
{
    hl_arb_em *a = hl_arb_em_new(n);
    hl_arb_em_point(a, code, n, r, prec);
    hl_arb_em_free(a);
}

/* The constant registers of r at prec bits: leaves, then the prologue. */
void hl_tape_consts_arb(arb_ptr r, slong prec, const hl_tape *t)
{
    for (int i = 0; i < t->nleaf; i++) {
        if (t->leaf[i].is_pi)
            arb_const_pi(r + t->leaf[i].reg, prec);
        else
            arb_set_fmpq(r + t->leaf[i].reg, t->leaf[i].q, prec);
    }
    hl_tape_run_arb(t->pro, t->npro, r, prec);
}

void hl_tape_eval_d(double *out, const double *in, hl_tape *t)
{
    if (t->jit_fn != NULL) { /* hl_tape_jit: the same program as machine code */
        t->jit_fn(in, out);
        return;
    }
    double *r = t->rd;
    if (t->nin > 0)
        memcpy(r, in, (size_t)t->nin * sizeof *r);
    if (t->pprog == NULL) /* the point rules, recorded once over rd */
        t->pprog = hl_prog_point(t, r);
    hl_prog_run(t->pprog, 0);
    for (int j = 0; j < t->nout; j++)
        out[j] = r[t->outreg[j]];
}

void hl_tape_eval_arb(arb_ptr out, arb_srcptr in, slong prec, hl_tape *t)
{
    if (t->ra == NULL)
        t->ra = _arb_vec_init(t->nregs);
    if (t->ra_prec != prec) {
        hl_tape_consts_arb(t->ra, prec, t);
        t->ra_prec = prec;
    }
    for (int i = 0; i < t->nin; i++)
        arb_set(t->ra + i, in + i);
    hl_tape_run_arb(t->code, t->ncode, t->ra, prec);
    for (int j = 0; j < t->nout; j++)
        arb_set(out + j, t->ra + t->outreg[j]);
}
