/* Point evaluation of a tape, in double and in Arb.
 *
 * The double interpreter runs the point rules of src/rules/ recorded once
 * per tape into a flat program over the register file (prog_impl.h):
 * nothing is allocated per call, the constants sit in the register file
 * from compile time. */
#define _GNU_SOURCE /* sincos */
#include <math.h>
#include <string.h>

#include "tape/prog_impl.h"

void hl_tape_run_arb(const hl_instr *code, int n, arb_ptr r, slong prec)
{
    for (const hl_instr *i = code, *end = code + n; i < end; i++) {
        arb_ptr d = r + i->d, a = r + i->a, b = i->b >= 0 ? r + i->b : NULL;
        switch (i->op) {
        case HL_OP_NEG: arb_neg(d, a); break;
        case HL_OP_ADD:
        case HL_OP_ADDK: arb_add(d, a, b, prec); break;
        case HL_OP_SUB:
        case HL_OP_SUBK: arb_sub(d, a, b, prec); break;
        case HL_OP_KSUB: arb_sub(d, b, a, prec); break;
        case HL_OP_MUL:
        case HL_OP_MULK: arb_mul(d, a, b, prec); break;
        case HL_OP_DIV:
        case HL_OP_DIVK: arb_div(d, a, b, prec); break;
        case HL_OP_KDIV: arb_div(d, b, a, prec); break;
        case HL_OP_SQR: arb_sqr(d, a, prec); break;
        case HL_OP_POWK: arb_pow(d, a, b, prec); break;
        case HL_OP_SQRT: arb_sqrt(d, a, prec); break;
        case HL_OP_EXP: arb_exp(d, a, prec); break;
        case HL_OP_LOG: arb_log(d, a, prec); break;
        case HL_OP_SINCOS: arb_sin_cos(d, r + i->x, a, prec); break;
        case HL_OP_SINHCOSH: arb_sinh_cosh(d, r + i->x, a, prec); break;
        case HL_OP_TAN: arb_tan(d, a, prec); break;
        case HL_OP_TANH: arb_tanh(d, a, prec); break;
        case HL_OP_ATAN: arb_atan(d, a, prec); break;
        case HL_OP_ASIN: arb_asin(d, a, prec); break;
        case HL_OP_ACOS: arb_acos(d, a, prec); break;
        case HL_OP_ATAN2: arb_atan2(d, a, b, prec); break; /* arb_atan2(r, y, x) */
        }
    }
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
