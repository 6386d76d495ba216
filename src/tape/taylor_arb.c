/* Taylor mode in Arb: the rules of src/rules/ (as taylor.c runs them in
 * double) on arb_t coefficients at prec bits, through the Arb emitter. */
#include <stdlib.h>
#include <string.h>

#include "tape/arb_em_impl.h"

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

/* Coefficient k of every body register: each instruction's rule through
 * the Arb emitter (arb_em.c). */
static void step_arb(hl_tape *t, int k, slong prec)
{
    if (t->aem == NULL)
        t->aem = hl_arb_em_new(t->ncode);
    hl_arb_em_taylor(t->aem, t->code, t->ncode, t->ta, t->tas, k, prec);
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
