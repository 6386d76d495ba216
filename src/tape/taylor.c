/* Taylor mode in double: truncated power series arithmetic, one coefficient
 * at a time, so that the ODE recursion z^[k+1] = f(z)^[k] / (k+1) can feed
 * coefficient k+1 of the inputs before coefficient k+1 of anything is
 * needed.  The recurrence of each op is documented in hamlie/tape.h; the
 * references are Jorba & Zou, Experiment. Math. 14 (2005) 99-117, and
 * Hairer, Norsett & Wanner, Solving ODEs I, section I.8.
 *
 * Layout: register r's coefficients are td[r*S .. r*S + S-1], S = order+1.
 * Constant registers hold (c, 0, 0, ...), written when the layout changes. */
#define _GNU_SOURCE /* sincos */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "rules/rule.h"
#include "tape/prog_impl.h"

/* Lay the register file out for this order and record the rules over it
 * (prog_impl.h): once per order, not once per call. */
static void layout_d(hl_tape *t, int order)
{
    int S = order + 1;
    if (t->ts == S)
        return;
    size_t need = (size_t)t->nregs * (size_t)S;
    if (need > t->tdcap) {
        free(t->td);
        t->td = hl_xmalloc((need ? need : 1) * sizeof *t->td);
        t->tdcap = need;
    }
    memset(t->td, 0, need * sizeof *t->td);
    for (int i = 0; i < t->nregs; i++)
        if (t->isconst[i])
            t->td[(size_t)i * S] = t->rd[i];
    hl_prog_free(t->tprog);
    t->tprog = hl_prog_taylor(t, t->td, order);
    t->ts = S;
}

void hl_tape_taylor_d(double *out, const double *in, int order, hl_tape *t)
{
    layout_d(t, order);
    const int S = t->ts;
    for (int i = 0; i < t->nin; i++)
        memcpy(t->td + (size_t)i * S, in + (size_t)i * S, (size_t)S * sizeof *t->td);
    for (int k = 0; k <= order; k++)
        hl_prog_run(t->tprog, k);
    for (int j = 0; j < t->nout; j++)
        memcpy(out + (size_t)j * S, t->td + (size_t)t->outreg[j] * S, (size_t)S * sizeof *out);
}

/* NOTE: the two divisions in a row, z_j[k] = f_j[k-1] / k and then z_i[k+1]
 * = z_j[k] / (k+1), were some 7 cycles each of the 29 from one coefficient
 * of q to the next but one on Henon-Heiles (each order waits for the last);
 * with one, the steps ran 1-14 % faster (the oscillator most, Kepler least;
 * docs/work-precision.md, session 13).  A product by a rounded 1/(k+1)
 * alone is faster still, but its error is the same every step and drifts
 * the phase (the oscillator's error at tol 1e-16 went from 1e-14 to 7e-13
 * over t = 1e5). */
void hl_tape_ode_source(hl_ode_source *src, const hl_tape *t, int i, int k)
{
    int j = t->outreg[i], n = k + 1;
    src->reg = j;
    src->k = k;
    if (k >= 1 && j < t->nin && t->outreg[j] >= t->nin && !t->isconst[t->outreg[j]]) {
        src->reg = t->outreg[j];
        src->k = k - 1;
        n = k * (k + 1);
    }
    hl_rule_recip_split(&src->hi, &src->lo, n);
}

/* The recursion with the state's order 0 in the input registers; the
 * coefficients stay in the register file (inputs first: register i's row
 * is input i's). */
static inline __attribute__((always_inline)) hl_status
run_ode(hl_tape *t, const double *z, size_t stride, int order, hl_error *err)
{
    if (t->nin != t->nout)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "an ODE tape needs as many outputs as inputs (%d inputs, %d outputs)",
                            t->nin, t->nout);
    if (order < 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "negative Taylor order %d", order);
    if (t->ts != order + 1) /* the call was a sixth of the copies this saves */
        layout_d(t, order);
    const int S = t->ts, n = t->nin;
    double *td = t->td;
    for (int i = 0; i < n; i++)
        td[(size_t)i * S] = z[(size_t)i * stride];
    if (t->native_fn != NULL && t->native_order == order)
        t->native_fn(td);
    else
        hl_prog_run_ode(t->tprog, order); /* k = 0 .. order-1, z[k+1] = f[k] / (k+1) */
    return HL_OK;
}

hl_status hl_tape_taylor_ode_d(double *z, int order, hl_tape *t, hl_error *err)
{
    hl_status st = run_ode(t, z, (size_t)order + 1, order, err);
    if (st == HL_OK)
        memcpy(z, t->td, (size_t)t->nin * t->ts * sizeof *z);
    return st;
}

hl_status hl_tape_taylor_ode_lend(const double **rows, hl_tape *t, const double *z, int order,
                                  hl_error *err)
{
    hl_status st = run_ode(t, z, 1, order, err);
    *rows = st == HL_OK ? t->td : NULL;
    return st;
}
