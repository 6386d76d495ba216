/* Chaos indicators of one orbit (chaos.h): the run of the extended ODE in
 * chunks, delta renormalised between them, and the indicators read from
 * the state.
 *
 * The first chunk [0, t1] runs without b (b' = 2 a k / c is 0/0 at s = 0;
 * chaos_impl.h) and B(t1) = int_0^t1 2 A(s)/s ds is taken by composite
 * Gauss-Legendre on the chunk's dense output, one panel per Taylor step of
 * that chunk (within which the solution is a polynomial, so the rule is
 * close to exact).  B(t1) is small anyway (Y(s) ~ r(0) s near 0), and it
 * enters <Y>(t) divided by t. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "chaos/chaos_impl.h"

struct hl_chaos {
    hl_system *sys;
    int n; /* 2N */
    double tol;
    hl_tape *full, *first; /* with b, and without (the first chunk) */
    hl_progress_fn progress;
    void *progress_arg;
};

/* Gauss-Legendre nodes per panel of the first chunk. */
#define GL_NODES 12
/* Chunk lengths: the first, and the limits of the adaptation (below). */
#define CHUNK_FIRST 1.0
#define CHUNK_MAX 64.0

hl_status hl_chaos_new(hl_chaos **out, hl_system *sys, double tol, hl_error *err)
{
    *out = NULL;
    if (!(tol >= HL_FLOW_MIN_RTOL) || !isfinite(tol))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "tolerance %g out of range (%.2g .. finite)", tol, HL_FLOW_MIN_RTOL);
    hl_chaos *c = hl_xcalloc(1, sizeof *c);
    c->sys = sys;
    c->n = 2 * hl_system_ndof(sys);
    c->tol = tol;
    hl_status st = chaos_tape(&c->full, sys, 1, err);
    if (st == HL_OK)
        st = chaos_tape(&c->first, sys, 0, err);
    if (st != HL_OK) {
        hl_chaos_free(c);
        return st;
    }
    *out = c;
    return HL_OK;
}

void hl_chaos_set_progress(hl_chaos *chaos, hl_progress_fn fn, void *arg)
{
    chaos->progress = fn;
    chaos->progress_arg = arg;
}

void hl_chaos_free(hl_chaos *chaos)
{
    if (chaos == NULL)
        return;
    hl_tape_free(chaos->full);
    hl_tape_free(chaos->first);
    free(chaos);
}

/* ---- Gauss-Legendre ------------------------------------------------------ */

/* Nodes x[i] in (-1, 1) and weights w[i] of the m-point rule (Newton on
 * P_m from the Chebyshev-like guesses; m is small, so this is cheap). */
static void gauss_legendre(double *x, double *w, int m)
{
    for (int i = 0; i < m; i++) {
        double t = cos(M_PI * (i + 0.75) / (m + 0.5)), dp = 1;
        for (int it = 0; it < 100; it++) {
            double p0 = 1, p1 = t;
            for (int k = 2; k <= m; k++) {
                double p2 = ((2 * k - 1) * t * p1 - (k - 1) * p0) / k;
                p0 = p1;
                p1 = p2;
            }
            dp = m * (t * p1 - p0) / (t * t - 1);
            double dt = p1 / dp;
            t -= dt;
            if (fabs(dt) < 1e-16)
                break;
        }
        x[i] = t;
        w[i] = 2 / ((1 - t * t) * dp * dp);
    }
}

/* ---- the run ------------------------------------------------------------- */

typedef struct chaos_state {
    double *X;     /* the extended state */
    double t, T;   /* time reached, t_end */
    double logsum; /* log |delta| / |delta0| at the last renormalisation */
    double fli;
    long nsteps;
} chaos_state;

static void indicators(hl_chaos_result *r, const chaos_state *s, int n, hl_status status)
{
    double t = s->t, T2 = s->T * s->T;
    r->t = t;
    r->megno = t > 0 ? 2 * T2 * s->X[CHAOS_A(n)] / t : 0;
    r->megno_mean = t > 0 ? T2 * s->X[CHAOS_B(n)] / t : 0;
    r->fli = s->fli;
    r->mlce = t > 0 ? s->logsum / t : 0;
    r->nsteps = s->nsteps;
    r->status = status;
}

/* delta back to length 1; returns log of the factor taken out. */
static double renormalise(chaos_state *s, int n)
{
    double *d = s->X + n, nn = 0;
    for (int i = 0; i < n; i++)
        nn += d[i] * d[i];
    double norm = sqrt(nn);
    for (int i = 0; i < n; i++)
        d[i] /= norm;
    double g = log(norm);
    s->logsum += g;
    if (s->logsum > s->fli)
        s->fli = s->logsum;
    return g;
}

/* The first chunk [0, t1] by the tape without b; b(t1) by quadrature. */
static hl_status first_chunk(hl_chaos *c, chaos_state *s, double t1, hl_error *err)
{
    int n = c->n, dim = CHAOS_DIM_NO_B(n);
    hl_flow *flow = NULL;
    hl_status st = hl_flow_new(&flow, c->first, c->tol, c->tol, err);
    if (st != HL_OK)
        return st;
    double *X0 = hl_xmalloc((size_t)dim * sizeof *X0);
    memcpy(X0, s->X, (size_t)dim * sizeof *X0);
    double t = 0;
    st = hl_flow_evolve(flow, &t, t1, s->X, err);
    s->nsteps += hl_flow_nsteps(flow);
    int panels = 2 * (int)(hl_flow_nsteps(flow) > 0 ? hl_flow_nsteps(flow) : 1);
    if (st == HL_OK) {
        double x[GL_NODES], w[GL_NODES], h = t1 / panels;
        gauss_legendre(x, w, GL_NODES);
        double *ts = hl_xmalloc((size_t)panels * GL_NODES * sizeof *ts);
        double *out = hl_xmalloc((size_t)panels * GL_NODES * dim * sizeof *out);
        for (int p = 0; p < panels; p++)
            for (int i = 0; i < GL_NODES; i++) /* ascending: x[] is descending */
                ts[p * GL_NODES + i] = h * (p + 0.5 * (1 - x[i]));
        st = hl_flow_eval_at(flow, 0, X0, ts, panels * GL_NODES, out, err);
        double b = 0;
        for (int j = 0; st == HL_OK && j < panels * GL_NODES; j++) /* b' = 2 a / s, T-free */
            b += 0.5 * h * w[j % GL_NODES] * 2 * out[j * dim + CHAOS_A(n)] / ts[j];
        s->X[CHAOS_B(n)] = b;
        free(ts);
        free(out);
    }
    s->t = t;
    free(X0);
    hl_flow_free(flow);
    return st;
}

/* The next chunk's length: about one e-fold of |delta| (so the tangent
 * vector stays of order 1 next to z in the error test), at most twice the
 * last, at most CHUNK_MAX. */
static double next_chunk(double h, double growth)
{
    double g = fabs(growth), next = 2 * h;
    if (g * next > 1)
        next = h / g;
    if (next > CHUNK_MAX)
        next = CHUNK_MAX;
    return next > 1e-6 * h ? next : 1e-6 * h;
}

static hl_status check_run(const hl_chaos *c, const double *z0, const double *delta0, double t_end,
                           double every, hl_error *err)
{
    if (!(t_end > 0) || !isfinite(t_end))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "the final time must be positive, not %g",
                            t_end);
    if (!(every >= 0) || !isfinite(every))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the output spacing must be positive (or 0: none), not %g", every);
    for (int i = 0; i < c->n; i++)
        if (!isfinite(z0[i]))
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "initial value %d is not finite",
                                i + 1);
    if (delta0 == NULL)
        return HL_OK;
    double nn = 0;
    for (int i = 0; i < c->n; i++) {
        if (!isfinite(delta0[i]))
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "tangent vector component %d is not finite", i + 1);
        nn += delta0[i] * delta0[i];
    }
    if (!(nn > 0) || !isfinite(nn))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the initial tangent vector is 0 (or its length under- or "
                            "overflows): it needs a direction");
    return HL_OK;
}

/* The default tangent vector: alternating signs, decreasing sizes, so that
 * it is not along a symmetry of common Hamiltonians (all equal, or a
 * coordinate axis). */
static void default_delta(double *d, int n)
{
    for (int i = 0; i < n; i++)
        d[i] = (i % 2 ? -1.0 : 1.0) / (1.0 + 0.37 * i);
}

static void start_state(chaos_state *s, const hl_chaos *c, const double *z0, const double *delta0,
                        double t_end)
{
    int n = c->n;
    memset(s, 0, sizeof *s);
    s->X = hl_xcalloc((size_t)CHAOS_DIM(n), sizeof *s->X);
    s->T = t_end;
    memcpy(s->X, z0, (size_t)n * sizeof *z0);
    if (delta0 != NULL)
        memcpy(s->X + n, delta0, (size_t)n * sizeof *delta0);
    else
        default_delta(s->X + n, n);
    s->X[CHAOS_K(n)] = 1 / t_end;
    renormalise(s, n);
    s->logsum = s->fli = 0; /* measured from |delta0| */
}

/* The k-th output time: k every, or t_end when that is at or past it (a
 * k every that misses t_end by rounding, 3 * 0.3 < 0.9, is t_end: no
 * second row a rounding error before the last). */
static double next_output(int k, double every, double t_end)
{
    double tk = k * every;
    return every > 0 && tk < t_end * (1 - 1e-12) ? tk : t_end;
}

hl_status hl_chaos_run(hl_chaos *c, const double *z0, const double *delta0, double t_end,
                       double every, hl_chaos_fn fn, void *arg, hl_chaos_result *res, hl_error *err)
{
    hl_status st = check_run(c, z0, delta0, t_end, every, err);
    if (st != HL_OK)
        return st;
    int n = c->n;
    chaos_state s;
    start_state(&s, c, z0, delta0, t_end);
    double next_out = next_output(1, every, t_end);
    double h = CHUNK_FIRST < next_out ? CHUNK_FIRST : next_out;
    st = first_chunk(c, &s, h, err);
    hl_flow *flow = NULL;
    if (st == HL_OK)
        st = hl_flow_new(&flow, c->full, c->tol, c->tol, err);
    if (st == HL_OK)
        hl_flow_native_for(flow, t_end);
    for (int k = 1; st == HL_OK;) {
        h = next_chunk(h, renormalise(&s, n));
        if (s.t >= next_out) { /* an output time (the end, or a multiple of every) */
            hl_chaos_result r;
            indicators(&r, &s, n, HL_OK);
            if (s.t >= t_end)
                break;
            if (fn != NULL && fn(&r, s.X, arg) != 0) {
                st = hl_error_set(err, HL_ESTOP, NULL, -1, 0, "stopped at t = %g", s.t);
                break;
            }
            next_out = next_output(++k, every, t_end);
        }
        if (c->progress != NULL && c->progress(s.t, t_end, c->progress_arg) != 0) {
            st = hl_error_set(err, HL_ESTOP, NULL, -1, 0, "interrupted at t = %g", s.t);
            break;
        }
        double t1 = s.t + h < next_out ? s.t + h : next_out;
        long before = hl_flow_nsteps(flow);
        st = hl_flow_evolve(flow, &s.t, t1, s.X, err);
        s.nsteps += hl_flow_nsteps(flow) - before;
    }
    hl_chaos_result r;
    indicators(&r, &s, n, st);
    if (st == HL_OK && fn != NULL && every > 0 && fn(&r, s.X, arg) != 0)
        st = r.status = hl_error_set(err, HL_ESTOP, NULL, -1, 0, "stopped at t = %g", s.t);
    if (res != NULL)
        *res = r;
    hl_flow_free(flow);
    free(s.X);
    return st;
}
