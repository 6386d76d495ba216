/* The Taylor integrator in Arb (see hamlie/flow.h).  The driver mirrors
 * flow.c; order and step come from the same functions (flow_impl.h), the
 * step computed in double from the coefficients' midpoints: it need not be
 * accurate, only the polynomial sum must be. */
#include <math.h>
#include <stdlib.h>

#include "base/buf.h"
#include "flow/flow_impl.h"
#include "hamlie/flow.h"

struct hl_flow_arb {
    hl_tape *f;
    int n, p;
    slong prec;
    double ln_tol;  /* -digits * ln 10 */
    arb_ptr coef;   /* n * (p+1) */
    arb_ptr zt;     /* n */
    arb_ptr dz, fz; /* n each: P'(h) and f(P(h)), to check a step */
    double ln_eps;  /* the log of the current step's tolerance */
    int check;      /* the current step is to be checked (hl_flow_shrink) */
    arb_t h, tau, rem;
    long nsteps;
    hl_flow_pace pace; /* to stop where the steps shrink forever */
};

hl_status hl_flow_arb_new(hl_flow_arb **out, hl_tape *f, double digits, hl_error *err)
{
    *out = NULL;
    int n = hl_tape_ninputs(f);
    if (n != hl_tape_noutputs(f) || n == 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "a flow needs a tape with as many outputs as inputs (%d inputs, %d outputs)",
                            n, hl_tape_noutputs(f));
    if (!(digits >= 1) || !(digits <= 2 * HL_FLOW_MAX_ORDER / 2.3))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "digits must be between 1 and %d (got %g)", (int)(2 * HL_FLOW_MAX_ORDER / 2.3),
                            digits);
    hl_flow_arb *fl = hl_xcalloc(1, sizeof *fl);
    fl->f = f;
    fl->n = n;
    fl->ln_tol = -digits * log(10.0);
    fl->p = hl_flow_order_for(fl->ln_tol);
    fl->prec = (slong)ceil(digits * log2(10.0)) + 32;
    fl->coef = _arb_vec_init((slong)n * (fl->p + 1));
    fl->zt = _arb_vec_init(n);
    fl->dz = _arb_vec_init(n);
    fl->fz = _arb_vec_init(n);
    arb_init(fl->h);
    arb_init(fl->tau);
    arb_init(fl->rem);
    *out = fl;
    return HL_OK;
}

void hl_flow_arb_free(hl_flow_arb *fl)
{
    if (fl == NULL)
        return;
    _arb_vec_clear(fl->coef, (slong)fl->n * (fl->p + 1));
    _arb_vec_clear(fl->zt, fl->n);
    _arb_vec_clear(fl->dz, fl->n);
    _arb_vec_clear(fl->fz, fl->n);
    arb_clear(fl->h);
    arb_clear(fl->tau);
    arb_clear(fl->rem);
    free(fl);
}

int hl_flow_arb_order(const hl_flow_arb *fl) { return fl->p; }
slong hl_flow_arb_prec(const hl_flow_arb *fl) { return fl->prec; }
long hl_flow_arb_nsteps(const hl_flow_arb *fl) { return fl->nsteps; }

static double mid_d(const arb_t x)
{
    return arf_get_d(arb_midref(x), ARF_RND_NEAR);
}

static void horner(arb_ptr z, const hl_flow_arb *fl, const arb_t h)
{
    const int S = fl->p + 1;
    for (int i = 0; i < fl->n; i++) {
        arb_srcptr c = fl->coef + (size_t)i * S;
        arb_set(z + i, c + fl->p);
        for (int k = fl->p - 1; k >= 0; k--) {
            arb_mul(z + i, z + i, h, fl->prec);
            arb_add(z + i, z + i, c + k, fl->prec);
        }
        arb_get_mid_arb(z + i, z + i); /* see flow.h: midpoints only */
    }
}

/* dz_i = sum_k k c_i[k] h^(k-1), the derivative of the step's polynomial */
static void horner_derivative(arb_ptr dz, const hl_flow_arb *fl, const arb_t h)
{
    const int S = fl->p + 1;
    for (int i = 0; i < fl->n; i++) {
        arb_srcptr c = fl->coef + (size_t)i * S;
        arb_mul_si(dz + i, c + fl->p, fl->p, fl->prec);
        for (int k = fl->p - 1; k >= 1; k--) {
            arb_mul(dz + i, dz + i, h, fl->prec);
            arb_addmul_si(dz + i, c + k, k, fl->prec);
        }
    }
}

static int step_size(double *h, hl_flow_arb *fl, arb_srcptr z, const arb_t t, hl_error *err)
{
    const int n = fl->n, p = fl->p, S = p + 1;
    for (int i = 0; i < n; i++)
        arb_set(fl->coef + (size_t)i * S, z + i);
    int st = hl_tape_taylor_ode_arb(fl->coef, p, fl->prec, fl->f, err);
    if (st != HL_OK)
        return st;
    const int lo = hl_flow_window_lo(p), nw = p - lo + 1;
    double n0 = 0, win[HL_FLOW_WINDOW] = {0}; /* the norms of the orders lo..p */
    int finite = 1;
    for (int i = 0; i < n; i++) {
        arb_srcptr c = fl->coef + (size_t)i * S, cw = c + lo;
        n0 = fmax(n0, fabs(mid_d(c)));
        for (int j = 0; j < nw; j++) {
            finite &= arb_is_finite(cw + j);
            win[j] = fmax(win[j], fabs(mid_d(cw + j)));
        }
    }
    fl->ln_eps = fl->ln_tol + (n0 > 1 ? log(n0) : 0);
    /* Jorba & Zou's order and step: an Arb step's cost is its products */
    hl_flow_rule rule;
    hl_flow_rule_jz(&rule, fl->ln_tol);
    /* exp may underflow: see hl_flow_step_for */
    *h = finite ? hl_flow_step_for(&fl->check, exp(fl->ln_eps), n0 > 1 ? n0 : 1, &rule, win) : NAN;
    if (isnan(*h))
        return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                            "the solution is not finite (Taylor coefficients overflow) at t = %.17g",
                            mid_d(t));
    if (!(*h > 1e-300) || *h < ldexp(fabs(mid_d(t)), -(int)fl->prec + 4))
        return hl_error_set(err, HL_ENOCONV, NULL, -1, 0, "step size underflow (h = %g) at t = %.17g",
                            *h, mid_d(t));
    return HL_OK;
}

/* A step that the window of coefficients does not vouch for (see
 * flow_impl.h):
 * shorten fl->h (signed by dir) until its defect says the tail past the
 * order is under eps. */
static int check_step(hl_flow_arb *fl, int dir, const arb_t t, hl_error *err)
{
    arb_t inv_eps; /* in Arb: eps itself may be below double's range */
    arb_init(inv_eps);
    arb_set_d(inv_eps, -fl->ln_eps);
    arb_exp(inv_eps, inv_eps, 64);
    int st = HL_OK;
    for (;;) {
        horner(fl->zt, fl, fl->h);
        horner_derivative(fl->dz, fl, fl->h);
        hl_tape_eval_arb(fl->fz, fl->zt, fl->prec, fl->f);
        double defect = 0; /* in units of eps */
        for (int i = 0; i < fl->n; i++) {
            arb_sub(fl->tau, fl->dz + i, fl->fz + i, fl->prec);
            arb_mul(fl->tau, fl->tau, inv_eps, fl->prec);
            double d = arb_is_finite(fl->tau) ? fabs(mid_d(fl->tau)) : INFINITY;
            defect = fmax(defect, d);
        }
        double h = fabs(mid_d(fl->h)), next = hl_flow_shrink(h, defect, 1, fl->p);
        if (next == 0)
            break;
        if (!(next > 1e-300) || next < ldexp(fabs(mid_d(t)), -(int)fl->prec + 4)) {
            st = hl_error_set(err, HL_ENOCONV, NULL, -1, 0,
                              "step size underflow (h = %g) at t = %.17g", next, mid_d(t));
            break;
        }
        arb_set_d(fl->h, dir * next);
    }
    arb_clear(inv_eps);
    return st;
}

static int drive(hl_flow_arb *fl, arb_t t, arb_ptr z, const arb_t tend, arb_srcptr ts, int nts,
                 hl_flow_arb_fn fn, void *arg, hl_error *err)
{
    const slong prec = fl->prec;
    const int dir = arf_cmp(arb_midref(tend), arb_midref(t)) >= 0 ? 1 : -1;
    int j = 0, st, first = 1;
    for (;;) {
        for (; j < nts; j++) {
            arb_sub(fl->tau, ts + j, t, prec);
            if (dir * arf_sgn(arb_midref(fl->tau)) > 0)
                break;
            if ((st = fn(ts + j, z, arg)) != 0)
                return st;
        }
        arb_sub(fl->rem, tend, t, prec);
        if (dir < 0)
            arb_neg(fl->rem, fl->rem);
        if (arf_sgn(arb_midref(fl->rem)) <= 0)
            return HL_OK;
        double hd;
        if ((st = step_size(&hd, fl, z, t, err)) != HL_OK)
            return st;
        int last = hd >= mid_d(fl->rem);
        if (last)
            arb_set(fl->h, fl->rem);
        else
            arb_set_d(fl->h, hd);
        if (fl->check || first) { /* the first step too: see flow.c */
            if (dir < 0)
                arb_neg(fl->h, fl->h);
            if ((st = check_step(fl, dir, t, err)) != HL_OK)
                return st;
            if (dir < 0)
                arb_neg(fl->h, fl->h);
            last = arb_equal(fl->h, fl->rem);
            first = 0;
        }
        for (; j < nts; j++) {
            arb_sub(fl->tau, ts + j, t, prec); /* signed offset into the step */
            arb_get_mid_arb(fl->tau, fl->tau);
            if (arf_cmpabs(arb_midref(fl->tau), arb_midref(fl->h)) > 0)
                break;
            horner(fl->zt, fl, fl->tau);
            if ((st = fn(ts + j, fl->zt, arg)) != 0)
                return st;
        }
        if (dir < 0)
            arb_neg(fl->h, fl->h);
        horner(fl->zt, fl, fl->h);
        for (int i = 0; i < fl->n; i++)
            if (!arb_is_finite(fl->zt + i))
                return hl_error_set(err, HL_EDOM, NULL, -1, 0, "the solution is not finite at t = %.17g",
                                    mid_d(t));
        _arb_vec_set(z, fl->zt, fl->n);
        fl->nsteps++;
        if (last)
            arb_set(t, tend);
        else
            arb_add(t, t, fl->h, prec);
        double done;
        if (hl_flow_stalled(&fl->pace, fabs(mid_d(fl->h)), &done))
            return hl_flow_no_progress(err, done, mid_d(t));
    }
}

hl_status hl_flow_arb_evolve(hl_flow_arb *fl, arb_t t, const arb_t t1, arb_ptr z, hl_error *err)
{
    if (!arb_is_finite(t) || !arb_is_finite(t1))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "times must be finite");
    return drive(fl, t, z, t1, NULL, 0, NULL, NULL, err);
}

hl_status hl_flow_arb_run(hl_flow_arb *fl, const arb_t t0, arb_srcptr z0, arb_srcptr ts, int n,
                          hl_flow_arb_fn fn, void *arg, hl_error *err)
{
    if (n <= 0)
        return HL_OK;
    int dir = arf_cmp(arb_midref(ts + n - 1), arb_midref(t0)) >= 0 ? 1 : -1;
    for (int j = 0; j < n; j++) {
        const arb_struct *prev = j ? ts + j - 1 : t0;
        if (!arb_is_finite(ts + j) || dir * arf_cmp(arb_midref(ts + j), arb_midref(prev)) < 0)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "output times must be finite and monotone from t0 (time %d)", j);
    }
    arb_ptr z = _arb_vec_init(fl->n);
    arb_t t;
    arb_init(t);
    arb_set(t, t0);
    _arb_vec_set(z, z0, fl->n);
    int st = drive(fl, t, z, ts + n - 1, ts, n, fn, arg, err);
    arb_clear(t);
    _arb_vec_clear(z, fl->n);
    return st;
}
