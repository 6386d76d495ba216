/* Point evaluation of a tape, in double and in Arb.
 *
 * The double interpreter is one switch in one loop over a flat instruction
 * array: nothing is allocated, the constants sit in the register file from
 * compile time.  (GCC turns the dense switch into a jump table; the loop is
 * shaped so that it could become computed goto if that ever measures
 * faster.) */
#define _GNU_SOURCE /* sincos */
#include <math.h>
#include <string.h>

#include "tape/tape_impl.h"

void hl_tape_run_d(const hl_instr *code, int n, double *r)
{
    for (const hl_instr *i = code, *end = code + n; i < end; i++) {
        switch (i->op) {
        case HL_OP_NEG: r[i->d] = -r[i->a]; break;
        case HL_OP_ADD:
        case HL_OP_ADDK: r[i->d] = r[i->a] + r[i->b]; break;
        case HL_OP_SUB:
        case HL_OP_SUBK: r[i->d] = r[i->a] - r[i->b]; break;
        case HL_OP_KSUB: r[i->d] = r[i->b] - r[i->a]; break;
        case HL_OP_MUL:
        case HL_OP_MULK: r[i->d] = r[i->a] * r[i->b]; break;
        case HL_OP_DIV:
        case HL_OP_DIVK: r[i->d] = r[i->a] / r[i->b]; break;
        case HL_OP_KDIV: r[i->d] = r[i->b] / r[i->a]; break;
        case HL_OP_SQR: r[i->d] = r[i->a] * r[i->a]; break;
        case HL_OP_POWK: r[i->d] = pow(r[i->a], r[i->b]); break;
        case HL_OP_SQRT: r[i->d] = sqrt(r[i->a]); break;
        case HL_OP_EXP: r[i->d] = exp(r[i->a]); break;
        case HL_OP_LOG: r[i->d] = log(r[i->a]); break;
        case HL_OP_SINCOS: sincos(r[i->a], &r[i->d], &r[i->x]); break;
        case HL_OP_SINHCOSH:
            r[i->d] = sinh(r[i->a]);
            r[i->x] = cosh(r[i->a]);
            break;
        case HL_OP_TAN: r[i->d] = tan(r[i->a]); break;
        case HL_OP_TANH: r[i->d] = tanh(r[i->a]); break;
        case HL_OP_ATAN: r[i->d] = atan(r[i->a]); break;
        case HL_OP_ASIN: r[i->d] = asin(r[i->a]); break;
        case HL_OP_ACOS: r[i->d] = acos(r[i->a]); break;
        case HL_OP_ATAN2: r[i->d] = atan2(r[i->a], r[i->b]); break;
        }
    }
}

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
    hl_tape_run_d(t->code, t->ncode, r);
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
