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
#include "tape/tape_impl.h"

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
    if (t->tcode == NULL)
        t->tcode = hl_xmalloc(((size_t)t->ncode + 1) * sizeof *t->tcode);
    t->tinv = hl_xrealloc(t->tinv, ((size_t)S + 1) * sizeof *t->tinv);
    t->tinv[0] = 0;
    for (int k = 1; k <= S; k++)
        t->tinv[k] = 1.0 / k;
    for (int i = 0; i < t->ncode; i++) {
        const hl_instr *in = &t->code[i];
        hl_tinstr *ti = &t->tcode[i];
        ti->op = in->op;
        ti->d = t->td + (size_t)in->d * S;
        ti->a = t->td + (size_t)in->a * S;
        ti->b = in->b >= 0 ? t->td + (size_t)in->b * S : NULL;
        ti->x = in->x >= 0 ? t->td + (size_t)in->x * S : NULL;
    }
    t->ts = S;
}

/* sum_{j=lo..hi} x[j] y[k-j], with four accumulators: one dependency chain
 * of additions would bound the speed.  (Tried: a switch to fully unrolled
 * bodies per length; faster on Kepler, slower on Henon-Heiles, where most
 * sums are short.) */
static inline double conv(const double *x, const double *y, int lo, int hi, int k)
{
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0;
    int j = lo;
    for (; j + 3 <= hi; j += 4) {
        s0 += x[j] * y[k - j];
        s1 += x[j + 1] * y[k - j - 1];
        s2 += x[j + 2] * y[k - j - 2];
        s3 += x[j + 3] * y[k - j - 3];
    }
    for (; j <= hi; j++)
        s0 += x[j] * y[k - j];
    return (s0 + s1) + (s2 + s3);
}

/* sum_{j=1..k} j x[j] y[k-j] */
static inline double dconv(const double *x, const double *y, int k)
{
    double s0 = 0, s1 = 0, j0 = 1;
    int j = 1;
    for (; j < k; j += 2, j0 += 2) {
        s0 += j0 * x[j] * y[k - j];
        s1 += (j0 + 1) * x[j + 1] * y[k - j - 1];
    }
    if (j == k)
        s0 += j0 * x[j] * y[k - j];
    return s0 + s1;
}

/* Coefficient k of every body register. */
static void step_d(const hl_tape *t, int k)
{
    const double dk = (double)k, ik = t->tinv[k];
    for (const hl_tinstr *i = t->tcode, *end = t->tcode + t->ncode; i < end; i++) {
        double *d = i->d, *x = i->x;
        const double *a = i->a, *b = i->b;
        double s, c;
        switch (i->op) {
        case HL_OP_NEG: d[k] = -a[k]; break;
        case HL_OP_ADD: d[k] = a[k] + b[k]; break;
        case HL_OP_SUB: d[k] = a[k] - b[k]; break;
        case HL_OP_MUL: d[k] = conv(a, b, 0, k, k); break;
        case HL_OP_DIV:
            d[k] = (a[k] - conv(b, d, 1, k, k)) / b[0];
            break;
        case HL_OP_SQR:
            s = 2 * conv(a, a, 0, (k + 1) / 2 - 1, k);
            if (k % 2 == 0)
                s += a[k / 2] * a[k / 2];
            d[k] = s;
            break;
        case HL_OP_ADDK: d[k] = k ? a[k] : a[0] + b[0]; break;
        case HL_OP_SUBK: d[k] = k ? a[k] : a[0] - b[0]; break;
        case HL_OP_KSUB: d[k] = k ? -a[k] : b[0] - a[0]; break;
        case HL_OP_MULK: d[k] = a[k] * b[0]; break;
        case HL_OP_DIVK: d[k] = a[k] / b[0]; break;
        case HL_OP_KDIV:
            d[k] = k ? -conv(a, d, 1, k, k) / a[0] : b[0] / a[0];
            break;
        case HL_OP_POWK:
            if (k == 0) {
                d[0] = pow(a[0], b[0]);
            } else {
                /* with m = k - j: sum_{m=1..k} ((c+1) m - k) a[m] d[k-m] */
                double c1 = b[0] + 1, w0 = c1 - dk, w1 = 2 * c1 - dk, s1 = 0;
                int m = 1;
                s = 0;
                for (; m < k; m += 2, w0 += 2 * c1, w1 += 2 * c1) {
                    s += w0 * a[m] * d[k - m];
                    s1 += w1 * a[m + 1] * d[k - m - 1];
                }
                if (m == k)
                    s += w0 * a[m] * d[0];
                d[k] = (s + s1) / (dk * a[0]);
            }
            break;
        case HL_OP_SQRT:
            d[k] = k ? (a[k] - conv(d, d, 1, k - 1, k)) / (2 * d[0]) : sqrt(a[0]);
            break;
        case HL_OP_EXP:
            if (k == 0) {
                d[0] = exp(a[0]);
            } else {
                d[k] = dconv(a, d, k) * ik;
            }
            break;
        case HL_OP_LOG:
            if (k == 0) {
                d[0] = log(a[0]);
            } else {
                s = dk * a[k];
                for (int j = 1; j < k; j++)
                    s -= (k - j) * a[j] * d[k - j];
                d[k] = s / (dk * a[0]);
            }
            break;
        case HL_OP_SINCOS:
        case HL_OP_SINHCOSH:
            if (k == 0) {
                if (i->op == HL_OP_SINCOS) {
                    sincos(a[0], &d[0], &x[0]);
                } else {
                    d[0] = sinh(a[0]);
                    x[0] = cosh(a[0]);
                }
            } else {
                /* two partial sums each, for the pipeline (see conv) */
                double s1 = 0, c1 = 0, jd = 1;
                int j = 1;
                s = c = 0;
                for (; j < k; j += 2, jd += 2) {
                    double ja = jd * a[j], jb = (jd + 1) * a[j + 1];
                    s += ja * x[k - j];
                    c += ja * d[k - j];
                    s1 += jb * x[k - j - 1];
                    c1 += jb * d[k - j - 1];
                }
                if (j == k) {
                    double ja = jd * a[j];
                    s += ja * x[0];
                    c += ja * d[0];
                }
                s += s1;
                c += c1;
                d[k] = s * ik;
                x[k] = (i->op == HL_OP_SINCOS ? -c : c) * ik;
            }
            break;
        case HL_OP_TAN:
        case HL_OP_TANH:
            if (k == 0) {
                d[0] = i->op == HL_OP_TAN ? tan(a[0]) : tanh(a[0]);
            } else {
                s = dconv(a, x, k);
                d[k] = i->op == HL_OP_TAN ? a[k] + s * ik : a[k] - s * ik;
            }
            s = 2 * conv(d, d, 0, (k + 1) / 2 - 1, k);
            if (k % 2 == 0)
                s += d[k / 2] * d[k / 2];
            x[k] = s;
            break;
        case HL_OP_ATAN:
        case HL_OP_ASIN:
        case HL_OP_ACOS:
            s = conv(a, a, 0, k, k); /* (a*a)[k] */
            if (i->op == HL_OP_ATAN) {
                x[k] = k ? s : 1 + s;
            } else if (k == 0) {
                x[0] = sqrt(1 - s);
            } else {
                x[k] = (-s - conv(x, x, 1, k - 1, k)) / (2 * x[0]);
            }
            if (k == 0) {
                d[0] = i->op == HL_OP_ATAN ? atan(a[0]) : i->op == HL_OP_ASIN ? asin(a[0]) : acos(a[0]);
            } else {
                s = 0;
                for (int j = 1; j < k; j++)
                    s += (k - j) * x[j] * d[k - j];
                d[k] = ((i->op == HL_OP_ACOS ? -dk : dk) * a[k] - s) / (dk * x[0]);
            }
            break;
        case HL_OP_ATAN2:
            x[k] = conv(a, a, 0, k, k) + conv(b, b, 0, k, k);
            if (k == 0) {
                d[0] = atan2(a[0], b[0]);
            } else {
                s = dconv(a, b, k) - dconv(b, a, k); /* (b a' - a b')[k-1] */
                for (int j = 1; j < k; j++)
                    s -= (k - j) * x[j] * d[k - j];
                d[k] = s / (dk * x[0]);
            }
            break;
        }
    }
}

void hl_tape_taylor_d(double *out, const double *in, int order, hl_tape *t)
{
    layout_d(t, order);
    const int S = t->ts;
    for (int i = 0; i < t->nin; i++)
        memcpy(t->td + (size_t)i * S, in + (size_t)i * S, (size_t)S * sizeof *t->td);
    for (int k = 0; k <= order; k++)
        step_d(t, k);
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
        step_d(t, k);
        /* a division, not a multiplication by 1/(k+1): the reciprocal's
         * rounding error has a fixed sign and would drift the phase */
        const double k1 = k + 1;
        for (int i = 0; i < n; i++)
            td[(size_t)i * S + k + 1] = td[(size_t)t->outreg[i] * S + k] / k1;
    }
    memcpy(z, td, (size_t)n * S * sizeof *z);
    return HL_OK;
}
