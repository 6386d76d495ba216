/* The Taylor integrator in double (see hamlie/flow.h). */
#include <float.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "flow/flow_impl.h"
#include "flow/flow_poly.h"
#include "hamlie/event.h"
#include "hamlie/flow.h"

struct hl_flow {
    hl_tape *f;
    int n, p;
    hl_flow_tols tols;
    hl_flow_rule rule; /* the order and the step ratio */
    double *coef;      /* n * (p+1): the step's coefficients where callbacks run */
    const double *cur; /* the current step's coefficients: the tape's, lent, or coef */
    double *zt;   /* n: state at an output time */
    double *dz, *fz; /* n each: P'(h) and f(P(h)), to check a step */
    double *zlo;     /* n: the state's rounding carried (advance) */
    int vec;         /* the loops' build with FMA instructions (flow_poly.h) */
    double eps;      /* the current step's tolerance */
    int check;       /* the current step is to be checked (hl_flow_shrink) */
    long nsteps;
    double native_end; /* hl_flow_native_for's t_end, NAN if not asked */
    double t_probe;    /* the time of the first step since it was asked */
    long n_probe;      /* and nsteps then */
    int native_done;   /* decided (compiled or not) */
    long decide_at;    /* the next nsteps at which native_decide has work */
    hl_flow_pace pace; /* to stop where the steps shrink forever */
    hl_event *ev;      /* hl_flow_set_event's, or NULL */
    hl_flow_fn ev_fn;
    void *ev_arg;
    double *ze; /* n: the state at a crossing */
};

hl_status hl_flow_new(hl_flow **out, hl_tape *f, double atol, double rtol, hl_error *err)
{
    *out = NULL;
    int n = hl_tape_ninputs(f);
    if (n != hl_tape_noutputs(f) || n == 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "a flow needs a tape with as many outputs as inputs (%d inputs, %d outputs)",
                            n, hl_tape_noutputs(f));
    if (!(atol > 0) || !(rtol > 0) || !isfinite(atol) || !isfinite(rtol))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "tolerances must be positive (atol %g, rtol %g)", atol, rtol);
    if (rtol < HL_FLOW_MIN_RTOL)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the tolerance %g is below double precision (%.2g): for more digits use "
                            "the Arb integrator",
                            rtol, HL_FLOW_MIN_RTOL);
    hl_flow *fl = hl_xcalloc(1, sizeof *fl);
    fl->f = f;
    fl->n = n;
    hl_flow_rule_for(&fl->rule, hl_flow_tols_set(&fl->tols, atol, rtol), f);
    fl->p = fl->rule.p;
    fl->coef = hl_xcalloc((size_t)n * (fl->p + 1), sizeof *fl->coef);
    fl->zt = hl_xcalloc((size_t)n, sizeof *fl->zt);
    fl->dz = hl_xcalloc((size_t)n, sizeof *fl->dz);
    fl->fz = hl_xcalloc((size_t)n, sizeof *fl->fz);
    fl->zlo = hl_xcalloc((size_t)n, sizeof *fl->zlo);
    fl->vec = hl_flow_vec_ok();
    fl->native_end = NAN;
    fl->decide_at = LONG_MAX;
    *out = fl;
    return HL_OK;
}

hl_status hl_flow_new_order(hl_flow **out, hl_tape *f, double atol, double rtol, int order,
                            hl_error *err)
{
    hl_status st = hl_flow_new(out, f, atol, rtol, err);
    if (st != HL_OK || order == 0 || order == (*out)->p)
        return st;
    hl_flow *fl = *out;
    if (order < 2 || order > HL_FLOW_MAX_ORDER) {
        hl_flow_free(fl);
        *out = NULL;
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "the order must be 2 to %d (got %d)",
                            HL_FLOW_MAX_ORDER, order);
    }
    hl_flow_rule_at(&fl->rule, fl->rule.ln_tol, order);
    fl->p = order;
    free(fl->coef);
    fl->coef = hl_xcalloc((size_t)fl->n * (order + 1), sizeof *fl->coef);
    return HL_OK;
}

void hl_flow_free(hl_flow *fl)
{
    if (fl == NULL)
        return;
    free(fl->coef);
    free(fl->zt);
    free(fl->dz);
    free(fl->fz);
    free(fl->ze);
    free(fl->zlo);
    free(fl);
}

int hl_flow_order(const hl_flow *fl) { return fl->p; }

hl_status hl_flow_set_event(hl_flow *fl, hl_event *ev, hl_flow_fn fn, void *arg, hl_error *err)
{
    if (ev != NULL && hl_event_dim(ev) != fl->n)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the event's surface has %d inputs, the flow's state %d values",
                            hl_event_dim(ev), fl->n);
    fl->ev = ev;
    fl->ev_fn = fn;
    fl->ev_arg = arg;
    if (fl->ze == NULL)
        fl->ze = hl_xcalloc((size_t)fl->n, sizeof *fl->ze);
    return HL_OK;
}

void hl_flow_native_for(hl_flow *fl, double t_end)
{
    fl->native_end = t_end;
    fl->t_probe = NAN;
    fl->native_done = 0;
    fl->decide_at = isnan(t_end) ? LONG_MAX : 0;
}

int hl_flow_native_active(const hl_flow *fl)
{
    return fl->native_done == 2;
}

/* The steps foreseen from t to native_end at mean steps of `mean`. */
static long steps_left(const hl_flow *fl, double t, double mean)
{
    double left = fabs(fl->native_end - t) / mean;
    return left < (double)LONG_MAX ? (long)left : LONG_MAX;
}

/* The steps after which code kept in the disk cache may be loaded: past
 * the first steps of a run, which grow from a cautious start (Kepler from
 * perihelion: 41 steps to t = 0.1, 57 to t = 3), so that the step then
 * says how many are left. */
#define KEPT_PROBE 100

/* After the probe steps: compile if the steps foreseen to native_end are
 * many (see flow.h).  But code kept in the disk cache is loaded after
 * KEPT_PROBE steps already, if the steps foreseen at the step's length
 * then repay the load: a run shorter than the probe is native too.  t: the
 * time reached; h: the step's length.  Called only at the steps where it
 * has work, fl->decide_at (the probe's start, KEPT_PROBE and
 * HL_FLOW_NATIVE_PROBE steps on), not at every step: one comparison in the
 * loop instead of a call and its tests. */
static void native_decide(hl_flow *fl, double t, double h)
{
    if (fl->native_done || isnan(fl->native_end)) {
        fl->decide_at = LONG_MAX;
        return;
    }
    if (isnan(fl->t_probe)) {
        fl->t_probe = t;
        fl->n_probe = fl->nsteps;
        fl->decide_at = fl->nsteps + KEPT_PROBE;
        return;
    }
    long done = fl->nsteps - fl->n_probe;
    fl->decide_at = fl->n_probe + HL_FLOW_NATIVE_PROBE;
    if (done == KEPT_PROBE &&
        hl_tape_compile_kept(fl->f, HL_COMPILE_TAYLOR, steps_left(fl, t, h)) &&
        hl_tape_native(fl->f, fl->p, NULL) == HL_OK) {
        fl->native_done = 2;
        fl->decide_at = LONG_MAX;
        return;
    }
    if (done < HL_FLOW_NATIVE_PROBE)
        return;
    double mean = fabs(t - fl->t_probe) / (double)done;
    fl->native_done = 1;
    fl->decide_at = LONG_MAX;
    if (hl_tape_compile_pays(fl->f, HL_COMPILE_TAYLOR, steps_left(fl, t, mean)) &&
        hl_tape_native(fl->f, fl->p, NULL) == HL_OK)
        fl->native_done = 2;
}
long hl_flow_nsteps(const hl_flow *fl) { return fl->nsteps; }

/* The state after a step, z_i = c_i[0] + increment, with the rounding of
 * that sum carried in lo_i to the next step's (compensated summation,
 * Knuth's two-sum): below tolerances of about 1e-14 the error of a long run
 * is these roundings, one per step at the state's scale, and with them
 * carried it is the far smaller roundings of the increments.  The state
 * was added into the even chain before: two roundings a step, and errors
 * 2-4 times heyoka's at the same steps (issue 17).  Returns 1 if every z_i
 * is finite: z - z is 0 or NaN, their sum NaN if one is, tested once
 * (a loop over z after the update was 24 instructions a pendulum step). */
HL_FLOW_INLINE int advance(double *z, double *lo, const double *coef, int n, int p, double h)
{
    const int S = p + 1;
    double inf_nan = 0;
    for (int i = 0; i < n; i++) {
        const double *c = coef + (size_t)i * S;
        double a = c[0], b = increment(c, p, h, h * h) + lo[i], s = a + b, bv = s - a;
        lo[i] = (a - (s - bv)) + (b - bv);
        z[i] = s;
        inf_nan += s - s;
    }
    return inf_nan == 0;
}
#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

/* advance() two components at a time in the 4 lanes of an AVX2 vector:
 * increment()'s even and odd chains of each side by side, each lane the
 * same fma()s in the same order as the scalar code, so the same bits
 * (flow/t-vec), in about a third of the instructions (the scalar loops were
 * a tenth of a pendulum step's).  A lane pair is (c[k-1], c[k]): (o, e)
 * for p even, (e, o) for p odd, whose odd chain ends one order below
 * (c[1]).  After the chains one fma() gives e h2 (e h2 - 0: the same
 * rounding and sign of zero as h2 * e) and the odd chain's end. */
static HL_FLOW_VEC int advance_vec(double *z, double *lo, const double *coef, int n, int p,
                                   double h)
{
    const int S = p + 1, odd = p & 1;
    const double h2 = h * h;
    const __m256d H2 = _mm256_set1_pd(h2), M = odd ? H2 : _mm256_setr_pd(1, h2, 1, h2);
    const __m128d H = _mm_set1_pd(h);
    __m128d inf_nan = _mm_setzero_pd();
    int i = 0;
    for (; i + 1 < n; i += 2) {
        const double *ca = coef + (size_t)i * S, *cb = ca + S;
        __m256d v = _mm256_loadu2_m128d(cb + p - 1, ca + p - 1);
        for (int k = p - 2; k >= 2 + odd; k -= 2)
            v = _mm256_fmadd_pd(v, H2, _mm256_loadu2_m128d(cb + k - 1, ca + k - 1));
        __m256d add = odd ? _mm256_setr_pd(-0.0, ca[1], -0.0, cb[1]) : _mm256_set1_pd(-0.0);
        v = _mm256_fmadd_pd(v, M, add);
        __m128d va = _mm256_castpd256_pd128(v), vb = _mm256_extractf128_pd(v, 1);
        __m128d x0 = _mm_unpacklo_pd(va, vb), x1 = _mm_unpackhi_pd(va, vb);
        __m128d o = odd ? x1 : x0, e = odd ? x0 : x1;
        /* fma(h, o, h2 e) + lo, then the state added with its rounding kept */
        __m128d A = _mm_setr_pd(ca[0], cb[0]);
        __m128d B = _mm_add_pd(_mm_fmadd_pd(H, o, e), _mm_loadu_pd(lo + i));
        __m128d sum = _mm_add_pd(A, B), bv = _mm_sub_pd(sum, A);
        __m128d err = _mm_add_pd(_mm_sub_pd(A, _mm_sub_pd(sum, bv)), _mm_sub_pd(B, bv));
        _mm_storeu_pd(lo + i, err);
        _mm_storeu_pd(z + i, sum);
        inf_nan = _mm_add_pd(inf_nan, _mm_sub_pd(sum, sum));
    }
    int finite = _mm_movemask_pd(_mm_cmpeq_pd(inf_nan, _mm_setzero_pd())) == 3;
    if (i < n)
        finite &= advance(z + i, lo + i, coef + (size_t)i * S, 1, p, h);
    return finite;
}
#else
static HL_FLOW_VEC int advance_vec(double *z, double *lo, const double *coef, int n, int p,
                                   double h)
{
    return advance(z, lo, coef, n, p, h);
}
#endif
static int advance_plain(double *z, double *lo, const double *coef, int n, int p, double h)
{
    return advance(z, lo, coef, n, p, h);
}

/* One step's coefficients at z, and its size (> 0, maybe +inf). */
static int step_size(double *h, hl_flow *fl, const double *z, double t, hl_error *err)
{
    const int n = fl->n, p = fl->p;
    const double *c;
    int st = hl_tape_taylor_ode_lend(&c, fl->f, z, p, err);
    if (st != HL_OK)
        return st;
    fl->cur = c;
    double win[HL_FLOW_WINDOW]; /* the norms of the orders lo..p */
    double s = hl_flow_scale(&fl->tols, hl_flow_norms(win, c, n, p, 1), &fl->eps);
    *h = hl_flow_step_for(&fl->check, fl->eps, s, &fl->rule, win);
    if (isnan(*h))
        return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                            "the solution is not finite (Taylor coefficients overflow) at t = %.17g", t);
    if (*h < DBL_MIN || *h <= 4 * DBL_EPSILON * fabs(t))
        return hl_error_set(err, HL_ENOCONV, NULL, -1, 0, "step size underflow (h = %g) at t = %.17g",
                            *h, t);
    return HL_OK;
}

/* A step that the window of coefficients does not vouch for (see
 * flow_impl.h):
 * shorten *h until its defect says the tail past the order is under eps. */
static int check_step(double *h, hl_flow *fl, double dir, double t, hl_error *err)
{
    const int n = fl->n;
    for (;;) {
        poly_at(fl->vec, fl->zt, fl->cur, n, fl->p, dir * *h);
        poly_derivative_at(fl->vec, fl->dz, fl->cur, n, fl->p, dir * *h);
        hl_tape_eval_d(fl->fz, fl->zt, fl->f);
        double defect = 0;
        for (int i = 0; i < n; i++) {
            double d = fabs(fl->dz[i] - fl->fz[i]);
            defect = d > defect || isnan(d) ? d : defect;
        }
        double next = hl_flow_shrink(*h, defect, fl->eps, fl->p);
        if (next == 0)
            return HL_OK;
        if (next <= 4 * DBL_EPSILON * fabs(t) || next < DBL_MIN)
            return hl_error_set(err, HL_ENOCONV, NULL, -1, 0,
                                "step size underflow (h = %g) at t = %.17g", next, t);
        *h = next;
    }
}

/* The state at tau on the current step's polynomial (an
 * hl_event_state_fn): tau counts along the direction of integration. */
typedef struct on_step {
    const hl_flow *fl;
    double dir;
} on_step;

static void step_state(double *z, double tau, void *arg)
{
    const on_step *o = arg;
    poly_at(o->fl->vec, z, o->fl->cur, o->fl->n, o->fl->p, o->dir * tau);
}

/* The step's coefficients into the flow's own buffer: the tape lends its
 * registers only until its next Taylor call, which the event's search or a
 * caller's callback may make (the same tape, another order). */
static void own_coefficients(hl_flow *fl)
{
    if (fl->cur == fl->coef)
        return;
    memcpy(fl->coef, fl->cur, (size_t)fl->n * (fl->p + 1) * sizeof *fl->coef);
    fl->cur = fl->coef;
}

/* Whether the step of length h from thi + tlo has work for step_outputs: an
 * event to look for, or the next output time ts[j] inside the step. */
static inline int step_has_outputs(const hl_flow *fl, int j, double thi, double tlo, double h,
                                   double dir, const double *ts, int nts)
{
    return fl->ev != NULL || (j < nts && dir * ((ts[j] - thi) - tlo) <= h);
}

/* What falls inside the current step of length h from (thi + tlo, z): the
 * output times ts[*j..] and the crossings of the event, in the order of
 * time (an output at a crossing's time first).  A non-zero return of a
 * callback is returned; if it was the event's, z and the time are left at
 * the crossing.  Called only where step_has_outputs. */
static int step_outputs(hl_flow *fl, int *j, double *thi, double *tlo, double *z, double h,
                        double dir, const double *ts, int nts, hl_flow_fn fn, void *arg)
{
    on_step o = {fl, dir};
    own_coefficients(fl); /* before the event's tape or a callback runs */
    double ta = 0, ga = fl->ev != NULL ? hl_event_value(fl->ev, z) : 0, tc = h;
    for (;;) {
        int hit = fl->ev != NULL && hl_event_first_taylor(fl->ev, fl->cur, fl->p, dir, h,
                                                          step_state, &o, ta, ga, &tc, fl->ze);
        double lim = hit ? tc : h;
        int st;
        for (double tau; *j < nts && (tau = dir * ((ts[*j] - *thi) - *tlo)) <= lim; ++*j) {
            poly_at(fl->vec, fl->zt, fl->cur, fl->n, fl->p, dir * tau);
            if ((st = fn(ts[*j], fl->zt, arg)) != 0)
                return st;
        }
        if (!hit)
            return 0;
        double tcross = *thi + (*tlo + dir * tc);
        if (fl->ev_fn != NULL && (st = fl->ev_fn(tcross, fl->ze, fl->ev_arg)) != 0) {
            memcpy(z, fl->ze, (size_t)fl->n * sizeof *z);
            time_add(thi, tlo, dir * tc);
            return st;
        }
        ta = tc;
        ga = hl_event_value(fl->ev, fl->ze);
    }
}

/* Integrate from (thi + tlo, z) to tend, calling fn at ts[0..n-1]. */
static int drive(hl_flow *fl, double *thi, double *tlo, double *z, double tend, const double *ts,
                 int nts, hl_flow_fn fn, void *arg, hl_error *err)
{
    const double dir = tend >= *thi ? 1 : -1;
    int j = 0, st, first = 1;
    memset(fl->zlo, 0, (size_t)fl->n * sizeof *fl->zlo); /* z is the caller's */
    for (;;) {
        for (; j < nts && dir * ((ts[j] - *thi) - *tlo) <= 0; j++)
            if ((st = fn(ts[j], z, arg)) != 0)
                return st;
        double rem = dir * ((tend - *thi) - *tlo);
        if (rem <= 0)
            return HL_OK;
        double h;
        if ((st = step_size(&h, fl, z, *thi, err)) != HL_OK)
            return st;
        if (h > rem)
            h = rem;
        /* the first step too: a run that starts near a point of symmetry
         * sees tiny orders, not vanishing ones (flow_impl.h) */
        if ((fl->check || first) && (st = check_step(&h, fl, dir, *thi, err)) != HL_OK)
            return st;
        first = 0;
        int last = h == rem;
        if (step_has_outputs(fl, j, *thi, *tlo, h, dir, ts, nts) &&
            (st = step_outputs(fl, &j, thi, tlo, z, h, dir, ts, nts, fn, arg)) != 0)
            return st;
        /* in place: the state before the step is the coefficients' order 0 */
        if (!(fl->vec ? advance_vec : advance_plain)(z, fl->zlo, fl->cur, fl->n, fl->p, dir * h)) {
            for (int i = 0; i < fl->n; i++)
                z[i] = fl->cur[(size_t)i * (fl->p + 1)];
            return hl_error_set(err, HL_EDOM, NULL, -1, 0, "the solution is not finite at t = %.17g",
                                *thi + dir * h);
        }
        if (++fl->nsteps >= fl->decide_at)
            native_decide(fl, *thi + dir * h, h);
        if (last) {
            *thi = tend;
            *tlo = 0;
        } else {
            time_add(thi, tlo, dir * h);
        }
        double done;
        if (hl_flow_stalled(&fl->pace, h, &done))
            return hl_flow_no_progress(err, done, *thi);
    }
}

hl_status hl_flow_evolve(hl_flow *fl, double *t, double t1, double *z, hl_error *err)
{
    if (!isfinite(*t) || !isfinite(t1))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "times must be finite");
    double thi = *t, tlo = 0;
    int st = drive(fl, &thi, &tlo, z, t1, NULL, 0, NULL, NULL, err);
    *t = thi + tlo;
    return st;
}

hl_status hl_flow_run(hl_flow *fl, double t0, const double *z0, const double *ts, int n,
                      hl_flow_fn fn, void *arg, hl_error *err)
{
    if (n <= 0)
        return HL_OK;
    double tend = ts[n - 1], dir = tend >= t0 ? 1 : -1, prev = t0;
    for (int j = 0; j < n; j++) {
        if (!isfinite(ts[j]) || dir * (ts[j] - prev) < 0)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "output times must be finite and monotone from t0 (time %d is %g)",
                                j, ts[j]);
        prev = ts[j];
    }
    double *z = hl_xmalloc((size_t)fl->n * sizeof *z);
    memcpy(z, z0, (size_t)fl->n * sizeof *z);
    double thi = t0, tlo = 0;
    int st = drive(fl, &thi, &tlo, z, tend, ts, n, fn, arg, err);
    free(z);
    return st;
}

typedef struct store {
    double *out;
    int n, i;
} store;

static int store_fn(double t, const double *z, void *arg)
{
    store *s = arg;
    memcpy(s->out + (size_t)s->i++ * s->n, z, (size_t)s->n * sizeof *z);
    return 0;
}

hl_status hl_flow_eval_at(hl_flow *fl, double t0, const double *z0, const double *ts, int n,
                          double *out, hl_error *err)
{
    store s = {out, fl->n, 0};
    return hl_flow_run(fl, t0, z0, ts, n, store_fn, &s, err);
}
