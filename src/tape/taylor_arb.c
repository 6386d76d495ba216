/* Taylor mode in Arb: the same recurrences as taylor.c (see hamlie/tape.h),
 * on arb_t coefficients at prec bits.  Plain convolutions use arb_dot (one
 * rounding per sum); weighted sums use the four scratch arbs of the tape. */
#include <stdlib.h>
#include <string.h>

#include "tape/tape_impl.h"

static void layout_arb(hl_tape *t, int order, slong prec)
{
    int S = order + 1;
    if (t->tas == S && t->ta_prec == prec)
        return;
    size_t need = (size_t)t->nregs * (size_t)S;
    if (need > t->tacap) {
        if (t->ta)
            _arb_vec_clear(t->ta, (slong)t->tacap);
        t->ta = _arb_vec_init((slong)need);
        t->tacap = need;
    }
    _arb_vec_zero(t->ta, (slong)need);
    /* constants at this precision, through a scratch register file */
    arb_ptr r = _arb_vec_init(t->nregs);
    hl_tape_consts_arb(r, prec, t);
    for (int i = 0; i < t->nregs; i++)
        if (t->isconst[i])
            arb_set(t->ta + (size_t)i * S, r + i);
    _arb_vec_clear(r, t->nregs);
    t->tas = S;
    t->ta_prec = prec;
}

/* res = initial -/+ sum_{j=lo..hi} x[j] y[k-j]  (initial may be NULL) */
static void conv(arb_t res, const arb_t initial, int subtract, arb_srcptr x, arb_srcptr y,
                 int lo, int hi, int k, slong prec)
{
    if (hi < lo) {
        if (initial)
            arb_set(res, initial);
        else
            arb_zero(res);
        return;
    }
    arb_dot(res, initial, subtract, x + lo, 1, y + (k - lo), -1, hi - lo + 1, prec);
}

/* sum_{j=lo..hi} w(j) x[j] y[k-j] with integer weights w(j) = wa*j + wb */
static void wconv(arb_t res, arb_srcptr x, arb_srcptr y, int lo, int hi, int k, slong wa,
                  slong wb, arb_t tmp, slong prec)
{
    arb_zero(res);
    for (int j = lo; j <= hi; j++) {
        arb_mul(tmp, x + j, y + k - j, prec);
        arb_addmul_si(res, tmp, wa * j + wb, prec);
    }
}

static void step_arb(hl_tape *t, int k, slong prec)
{
    const int S = t->tas;
    arb_ptr ta = t->ta;
    arb_ptr s = t->tmp[0], c = t->tmp[1], u = t->tmp[2], w = t->tmp[3];
#define R(reg) (ta + (size_t)(reg) * S)
    for (const hl_instr *i = t->code, *end = t->code + t->ncode; i < end; i++) {
        arb_ptr d = R(i->d), a = R(i->a);
        arb_ptr b = i->b >= 0 ? R(i->b) : NULL, x = i->x >= 0 ? R(i->x) : NULL;
        switch (i->op) {
        case HL_OP_NEG: arb_neg(d + k, a + k); break;
        case HL_OP_ADD: arb_add(d + k, a + k, b + k, prec); break;
        case HL_OP_SUB: arb_sub(d + k, a + k, b + k, prec); break;
        case HL_OP_MUL: conv(d + k, NULL, 0, a, b, 0, k, k, prec); break;
        case HL_OP_DIV:
            conv(s, a + k, 1, b, d, 1, k, k, prec);
            arb_div(d + k, s, b, prec);
            break;
        case HL_OP_SQR:
            conv(s, NULL, 0, a, a, 0, (k + 1) / 2 - 1, k, prec);
            arb_mul_2exp_si(s, s, 1);
            if (k % 2 == 0)
                arb_addmul(s, a + k / 2, a + k / 2, prec);
            arb_swap(d + k, s);
            break;
        case HL_OP_ADDK:
            if (k) arb_set(d + k, a + k); else arb_add(d, a, b, prec);
            break;
        case HL_OP_SUBK:
            if (k) arb_set(d + k, a + k); else arb_sub(d, a, b, prec);
            break;
        case HL_OP_KSUB:
            if (k) arb_neg(d + k, a + k); else arb_sub(d, b, a, prec);
            break;
        case HL_OP_MULK: arb_mul(d + k, a + k, b, prec); break;
        case HL_OP_DIVK: arb_div(d + k, a + k, b, prec); break;
        case HL_OP_KDIV:
            if (k == 0) {
                arb_div(d, b, a, prec);
            } else {
                conv(s, NULL, 0, a, d, 1, k, k, prec);
                arb_div(d + k, s, a, prec);
                arb_neg(d + k, d + k);
            }
            break;
        case HL_OP_POWK:
            if (k == 0) {
                arb_pow(d, a, b, prec);
            } else {
                /* sum_{j<k} (c(k-j) - j) a[k-j] d[j] */
                arb_zero(s);
                for (int j = 0; j < k; j++) {
                    arb_mul_si(u, b, k - j, prec);
                    arb_sub_si(u, u, j, prec);
                    arb_mul(w, a + k - j, d + j, prec);
                    arb_addmul(s, u, w, prec);
                }
                arb_mul_si(u, a, k, prec);
                arb_div(d + k, s, u, prec);
            }
            break;
        case HL_OP_SQRT:
            if (k == 0) {
                arb_sqrt(d, a, prec);
            } else {
                conv(s, a + k, 1, d, d, 1, k - 1, k, prec);
                arb_div(s, s, d, prec);
                arb_mul_2exp_si(d + k, s, -1);
            }
            break;
        case HL_OP_EXP:
            if (k == 0) {
                arb_exp(d, a, prec);
            } else {
                wconv(s, a, d, 1, k, k, 1, 0, u, prec);
                arb_div_si(d + k, s, k, prec);
            }
            break;
        case HL_OP_LOG:
            if (k == 0) {
                arb_log(d, a, prec);
            } else {
                wconv(s, a, d, 1, k - 1, k, -1, k, u, prec); /* sum (k-j) a[j] d[k-j] */
                arb_mul_si(c, a + k, k, prec);
                arb_sub(s, c, s, prec);
                arb_mul_si(c, a, k, prec);
                arb_div(d + k, s, c, prec);
            }
            break;
        case HL_OP_SINCOS:
        case HL_OP_SINHCOSH:
            if (k == 0) {
                if (i->op == HL_OP_SINCOS)
                    arb_sin_cos(d, x, a, prec);
                else
                    arb_sinh_cosh(d, x, a, prec);
            } else {
                wconv(s, a, x, 1, k, k, 1, 0, u, prec);
                wconv(c, a, d, 1, k, k, 1, 0, u, prec);
                arb_div_si(d + k, s, k, prec);
                arb_div_si(x + k, c, i->op == HL_OP_SINCOS ? -k : k, prec);
            }
            break;
        case HL_OP_TAN:
        case HL_OP_TANH:
            if (k == 0) {
                if (i->op == HL_OP_TAN)
                    arb_tan(d, a, prec);
                else
                    arb_tanh(d, a, prec);
            } else {
                wconv(s, a, x, 1, k, k, 1, 0, u, prec);
                arb_div_si(s, s, k, prec);
                if (i->op == HL_OP_TAN)
                    arb_add(d + k, a + k, s, prec);
                else
                    arb_sub(d + k, a + k, s, prec);
            }
            conv(s, NULL, 0, d, d, 0, (k + 1) / 2 - 1, k, prec);
            arb_mul_2exp_si(s, s, 1);
            if (k % 2 == 0)
                arb_addmul(s, d + k / 2, d + k / 2, prec);
            arb_swap(x + k, s);
            break;
        case HL_OP_ATAN:
        case HL_OP_ASIN:
        case HL_OP_ACOS:
            conv(s, NULL, 0, a, a, 0, k, k, prec); /* (a*a)[k] */
            if (i->op == HL_OP_ATAN) {
                if (k == 0)
                    arb_add_si(x, s, 1, prec);
                else
                    arb_swap(x + k, s);
            } else if (k == 0) {
                arb_sub_si(s, s, 1, prec);
                arb_neg(s, s);
                arb_sqrt(x, s, prec);
            } else {
                conv(c, s, 0, x, x, 1, k - 1, k, prec);
                arb_neg(c, c);
                arb_div(c, c, x, prec);
                arb_mul_2exp_si(x + k, c, -1);
            }
            if (k == 0) {
                if (i->op == HL_OP_ATAN)
                    arb_atan(d, a, prec);
                else if (i->op == HL_OP_ASIN)
                    arb_asin(d, a, prec);
                else
                    arb_acos(d, a, prec);
            } else {
                wconv(s, x, d, 1, k - 1, k, -1, k, u, prec); /* sum (k-j) x[j] d[k-j] */
                arb_mul_si(c, a + k, i->op == HL_OP_ACOS ? -k : k, prec);
                arb_sub(s, c, s, prec);
                arb_mul_si(c, x, k, prec);
                arb_div(d + k, s, c, prec);
            }
            break;
        case HL_OP_ATAN2:
            conv(s, NULL, 0, a, a, 0, k, k, prec);
            conv(x + k, s, 0, b, b, 0, k, k, prec); /* (a*a)[k] + (b*b)[k] */
            if (k == 0) {
                arb_atan2(d, a, b, prec);
            } else {
                wconv(s, a, b, 1, k, k, 1, 0, u, prec); /* sum j a[j] b[k-j] */
                wconv(c, b, a, 1, k, k, 1, 0, u, prec);
                arb_sub(s, s, c, prec);
                wconv(c, x, d, 1, k - 1, k, -1, k, u, prec); /* sum (k-j) x[j] d[k-j] */
                arb_sub(s, s, c, prec);
                arb_mul_si(c, x, k, prec);
                arb_div(d + k, s, c, prec);
            }
            break;
        }
    }
#undef R
}

void hl_tape_taylor_arb(arb_ptr out, arb_srcptr in, int order, slong prec, hl_tape *t)
{
    layout_arb(t, order, prec);
    const int S = t->tas;
    for (int i = 0; i < t->nin; i++)
        _arb_vec_set(t->ta + (size_t)i * S, in + (size_t)i * S, S);
    for (int k = 0; k <= order; k++)
        step_arb(t, k, prec);
    for (int j = 0; j < t->nout; j++)
        _arb_vec_set(out + (size_t)j * S, t->ta + (size_t)t->outreg[j] * S, S);
}

hl_status hl_tape_taylor_ode_arb(arb_ptr z, int order, slong prec, hl_tape *t, hl_error *err)
{
    if (t->nin != t->nout)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "an ODE tape needs as many outputs as inputs (%d inputs, %d outputs)",
                            t->nin, t->nout);
    if (order < 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "negative Taylor order %d", order);
    layout_arb(t, order, prec);
    const int S = t->tas, n = t->nin;
    arb_ptr ta = t->ta;
    for (int i = 0; i < n; i++)
        arb_set(ta + (size_t)i * S, z + (size_t)i * S);
    for (int k = 0; k < order; k++) {
        step_arb(t, k, prec);
        for (int i = 0; i < n; i++)
            arb_div_si(ta + (size_t)i * S + k + 1, ta + (size_t)t->outreg[i] * S + k, k + 1, prec);
    }
    _arb_vec_set(z, ta, (slong)n * S);
    return HL_OK;
}
