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
    t->tsplit = hl_xrealloc(t->tsplit, 2 * ((size_t)S + 1) * sizeof *t->tsplit);
    for (int k = 0; k <= S; k++)
        hl_rule_recip_split(&t->tsplit[2 * k], &t->tsplit[2 * k + 1], k + 1);
    hl_prog_free(t->tprog);
    t->tprog = hl_prog_taylor(t, t->td, order);
    t->ts = S;
}

/* z[k+1] = f[k] / (k+1) as fma(f, hi, f lo), hi + lo = 1/(k+1), as the
 * compiled code does (rule.h, hl_rule_recip_split): a division is slow, a
 * product by a rounded 1/(k+1) alone drifts the phase. */
#define ODE_DIVIDE_BODY                                                                            \
    do {                                                                                           \
        double *next = td + k + 1;                                                                 \
        const double *f = td + k;                                                                  \
        if (lo == 0) {                                                                             \
            for (int i = 0; i < n; i++)                                                            \
                next[(size_t)i * S] = f[(size_t)outreg[i] * S] * hi;                               \
            return;                                                                                \
        }                                                                                          \
        for (int i = 0; i < n; i++) {                                                              \
            double fi = f[(size_t)outreg[i] * S];                                                  \
            next[(size_t)i * S] = fma(fi, hi, fi * lo);                                            \
        }                                                                                          \
    } while (0)

static void ode_divide_call(double *td, const int *outreg, int n, int S, int k, double hi,
                            double lo)
{
    ODE_DIVIDE_BODY;
}

#if defined(__x86_64__) && defined(__GNUC__)
/* The same with the fma instruction inline where the processor has one: a
 * fused multiply-add is correctly rounded either way, so the bits agree,
 * and the loop saves a library call per component. */
__attribute__((target("fma"))) static void ode_divide_fma(double *td, const int *outreg, int n,
                                                          int S, int k, double hi, double lo)
{
    ODE_DIVIDE_BODY;
}

static void ode_divide(double *td, const int *outreg, int n, int S, int k, double hi, double lo)
{
    if (__builtin_cpu_supports("fma"))
        ode_divide_fma(td, outreg, n, S, k, hi, lo);
    else
        ode_divide_call(td, outreg, n, S, k, hi, lo);
}
#else
#define ode_divide ode_divide_call
#endif

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

hl_status hl_tape_taylor_ode_d(double *z, int order, hl_tape *t, hl_error *err)
{
    if (t->nin != t->nout)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "an ODE tape needs as many outputs as inputs (%d inputs, %d outputs)",
                            t->nin, t->nout);
    if (order < 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "negative Taylor order %d", order);
    layout_d(t, order);
    const int S = t->ts, n = t->nin;
    double *td = t->td;
    for (int i = 0; i < n; i++)
        td[(size_t)i * S] = z[(size_t)i * S];
    if (t->native_fn != NULL && t->native_order == order) {
        t->native_fn(td);
        memcpy(z, td, (size_t)n * S * sizeof *z);
        return HL_OK;
    }
    for (int k = 0; k < order; k++) {
        hl_prog_run(t->tprog, k);
        ode_divide(td, t->outreg, n, S, k, t->tsplit[2 * k], t->tsplit[2 * k + 1]);
    }
    memcpy(z, td, (size_t)n * S * sizeof *z);
    return HL_OK;
}
