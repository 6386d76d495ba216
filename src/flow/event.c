/* Events: a crossing of g(z) = 0 located on an interpolant (see
 * hamlie/event.h). */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "hamlie/event.h"

struct hl_event {
    hl_tape *g;
    int n;
    hl_event_dir dir;
    double *buf; /* hl_event_first_taylor's: 3 cap scratch, cap^2 weights */
    int cap;
    double *grad, g0; /* hl_event_set_affine's, or NULL */
};

hl_status hl_event_new(hl_event **out, hl_tape *g, hl_event_dir dir, hl_error *err)
{
    *out = NULL;
    if (hl_tape_noutputs(g) != 1 || hl_tape_ninputs(g) < 1)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "an event needs one formula g of the state (a tape with %d outputs)",
                            hl_tape_noutputs(g));
    if (dir != HL_EVENT_UP && dir != HL_EVENT_DOWN && dir != HL_EVENT_BOTH)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "unknown event direction %d", (int)dir);
    hl_event *ev = hl_xcalloc(1, sizeof *ev);
    ev->g = g;
    ev->n = hl_tape_ninputs(g);
    ev->dir = dir;
    *out = ev;
    return HL_OK;
}

void hl_event_free(hl_event *ev)
{
    if (ev != NULL)
        free(ev->buf), free(ev->grad);
    free(ev);
}

void hl_event_set_affine(hl_event *ev, const double *grad, double g0)
{
    if (ev->grad == NULL)
        ev->grad = hl_xmalloc((size_t)ev->n * sizeof *ev->grad);
    memcpy(ev->grad, grad, (size_t)ev->n * sizeof *grad);
    ev->g0 = g0;
}

int hl_event_dim(const hl_event *ev)
{
    return ev->n;
}

hl_event_dir hl_event_direction(const hl_event *ev)
{
    return ev->dir;
}

double hl_event_value(hl_event *ev, const double *z)
{
    double g;
    hl_tape_eval_d(&g, z, ev->g);
    return g;
}

int hl_event_crosses(const hl_event *ev, double ga, double gb)
{
    int up = ga < 0 && gb >= 0, down = ga > 0 && gb <= 0;
    return ev->dir == HL_EVENT_UP ? up : ev->dir == HL_EVENT_DOWN ? down : up || down;
}

/* g at tau along the interpolant; z receives the state there */
static double g_at(hl_event *ev, hl_event_state_fn state, void *arg, double tau, double *z)
{
    state(z, tau, arg);
    return hl_event_value(ev, z);
}

/* The root of g along state in [lo, hi], where glo and ghi differ in sign
 * (ghi may be 0): the end of the last bracket on ghi's side.  Illinois
 * false position (superlinear on a smooth g) with a bisection when a few
 * steps have not halved the bracket (a g flat on one side makes false
 * position crawl); the bracket closes to one rounding of tau. */
static double narrow(hl_event *ev, hl_event_state_fn state, void *arg, double lo, double hi,
                     double glo, double ghi, double *z)
{
    int side = 0;
    double checkpoint = hi - lo;
    for (int it = 1; it <= 400 && ghi != 0; it++) {
        double width = hi - lo;
        if (width <= 2 * DBL_EPSILON * fmax(fabs(lo), fabs(hi)) || width < DBL_MIN)
            break;
        int bisect = it % 4 == 0 && width > checkpoint / 2;
        if (it % 4 == 0)
            checkpoint = width;
        double m = bisect ? lo + width / 2 : hi - ghi * (width / (ghi - glo));
        if (!(m > lo && m < hi))
            m = lo + width / 2;
        double gm = g_at(ev, state, arg, m, z);
        if (gm == 0 || (gm > 0) == (ghi > 0)) {
            hi = m, ghi = gm;
            if (side == 1)
                glo /= 2; /* Illinois: the stale end weighs less */
            side = 1;
        } else {
            lo = m, glo = gm;
            if (side == -1)
                ghi /= 2;
            side = -1;
        }
    }
    state(z, hi, arg);
    return hi;
}

int hl_event_first(hl_event *ev, hl_event_state_fn state, void *arg, double a, double b, double ga,
                   double *tau, double *z)
{
    double ta = a;
    for (int i = 1; i <= HL_EVENT_SAMPLES; i++) {
        double tb = i == HL_EVENT_SAMPLES ? b : a + (b - a) * i / HL_EVENT_SAMPLES;
        double gb = g_at(ev, state, arg, tb, z);
        if (hl_event_crosses(ev, ga, gb)) {
            *tau = narrow(ev, state, arg, ta, tb, ga, gb, z);
            return 1;
        }
        ta = tb, ga = gb;
    }
    return 0;
}

/* ---- fixed-step: the cubic Hermite interpolant --------------------------- */

typedef struct hermite {
    const double *z0, *f0, *z1, *f1;
    double dt;
    int n;
} hermite;

static void hermite_state(double *z, double tau, void *arg)
{
    const hermite *h = arg;
    double s = tau / h->dt, s2 = s * s, s3 = s2 * s;
    double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = 3 * s2 - 2 * s3, h11 = s3 - s2;
    if (tau == h->dt) { /* the step's end exactly, not its rounding */
        for (int i = 0; i < h->n; i++)
            z[i] = h->z1[i];
        return;
    }
    for (int i = 0; i < h->n; i++)
        z[i] = h00 * h->z0[i] + h01 * h->z1[i] + h->dt * (h10 * h->f0[i] + h11 * h->f1[i]);
}

int hl_event_hermite(hl_event *ev, const double *z0, const double *f0, const double *z1,
                     const double *f1, double dt, double a, double ga, double *tau, double *z)
{
    hermite h = {z0, f0, z1, f1, dt, ev->n};
    return hl_event_first(ev, hermite_state, &h, a, dt, ga, tau, z);
}

/* ---- the Taylor integrator: roots isolated on g's own series -------------- */

/* The isolation bisects at most this deep: two crossings closer than
 * 2^-ISOLATE_DEPTH of a step are the only ones that can still be missed. */
#define ISOLATE_DEPTH 40
/* and looks at no more intervals than this in one step: where the count
 * stays undecided (g within rounding of 0 over much of the step) the
 * bisection would otherwise branch 2^ISOLATE_DEPTH ways; past the budget
 * an interval is judged by its ends, as at the depth limit */
#define ISOLATE_BUDGET 4096

/* c[0..p] := the coefficients of P(l + w x) from those of P(x). */
static void shift_scale(double *c, int p, double l, double w)
{
    if (l != 0)
        for (int i = 0; i < p; i++) /* Taylor shift by l (Horner's scheme, repeated) */
            for (int k = p - 1; k >= i; k--)
                c[k] += l * c[k + 1];
    double wk = 1;
    for (int k = 0; k <= p; k++, wk *= w)
        c[k] *= wk;
}

/* The sign changes of Q's Bernstein coefficients on [0, 1] (c[0..p] in
 * the power basis): an upper bound on the number of roots in (0, 1) with
 * its parity (Descartes' rule after the Moebius map: the Bernstein
 * coefficients are those of (1 + x)^p Q(1 / (1 + x)) up to positive
 * factors).  b_j = sum_{k <= j} C(j, k) / C(p, k) c_k has positive
 * weights <= 1, so its rounding error is at most ~ (p + 1) eps sum |c_k|,
 * unlike the expanded transform's (binomials up to C(p, p/2)).  The ends
 * are Q(0) and Q(1), whose signs are sl and sr (g itself, known).  Returns
 * the count, or -1 when an inner coefficient is within err (noise_of) of
 * 0, too small for its sign to be trusted (the caller bisects).  W: the
 * (p+1)^2 weights. */
static int bernstein_changes(const double *c, int p, const double *W, int sl, int sr, double err)
{
    int changes = 0, last = sl;
    for (int j = 1; j < p; j++) {
        double b = 0;
        for (int k = 0; k <= j; k++)
            b += W[j * (p + 1) + k] * c[k];
        if (fabs(b) <= err)
            return -1;
        int sb = b > 0 ? 1 : -1;
        changes += last != 0 && sb != last;
        last = sb;
    }
    return changes + (last != 0 && sr != 0 && sr != last);
}

/* W[j (p+1) + k] = C(j, k) / C(p, k) for k <= j <= p. */
static void bernstein_weights(double *W, int p)
{
    for (int j = 0; j <= p; j++) {
        double w = 1; /* C(j, 0) / C(p, 0) */
        for (int k = 0; k <= p; k++) {
            W[j * (p + 1) + k] = k <= j ? w : 0;
            w = w * (j - k) / (p - k > 0 ? p - k : 1); /* C(j, k+1)/C(p, k+1) */
        }
    }
}

/* sum |c_k|: a bound of |g| over the interval the series spans */
static double magnitude(const double *c, int p)
{
    double mag = 0;
    for (int k = 0; k <= p; k++)
        mag += fabs(c[k]);
    return mag;
}

/* The rounding noise of Q's values and Bernstein coefficients on [0, 1]. */
static double noise_of(const double *c, int p)
{
    return 4 * (p + 1) * DBL_EPSILON * magnitude(c, p);
}

static int sign_of(double x)
{
    return (x > 0) - (x < 0);
}

/* |P(x)| >= |P_0| - sum_{k>0} |P_k| on [0, 1]: when that is clearly
 * positive P has no root there, and g along the step (which P matches to
 * the integrator's tolerance, far below the margin) none either.  A test
 * of O(p) that spares most steps the O(p^2) isolation and the evaluation
 * at the step's end. */
#define FAR_MARGIN 1e-6
static int far_from_zero(const double *P, int p)
{
    double rest = 0;
    for (int k = 1; k <= p; k++)
        rest += fabs(P[k]);
    return fabs(P[0]) - rest > FAR_MARGIN * (fabs(P[0]) + rest);
}

typedef struct isolate {
    hl_event *ev;
    hl_event_state_fn state;
    void *arg;
    const double *P, *W; /* g's series in sigma = tau / h over the step; the weights */
    int p;
    double h, *c; /* the step; p + 1 scratch */
    double *z;
    double noise; /* g's rounding noise: noise_of the whole step's series */
    int budget;   /* intervals left to look at (ISOLATE_BUDGET) */
    double found; /* the crossing just found, where the search resumes; -1: none */
} isolate;

/* The first crossing in (l, r] (in units of the step; gl, gr: g at l h and
 * r h), by bisection while the count is not 0 or 1; 1 with *tau. */
static int isolate_first(isolate *s, double l, double r, double gl, double gr, int depth,
                         double *tau)
{
    memcpy(s->c, s->P, (size_t)(s->p + 1) * sizeof *s->c);
    shift_scale(s->c, s->p, l, r - l);
    /* g = 0 exactly at l (just after a crossing): the side g goes to from
     * there, by the first non-zero derivative, so that a second crossing
     * right after it counts */
    for (int k = 1; gl == 0 && k <= s->p; k++)
        gl = s->c[k];
    /* g within rounding of 0 over the whole interval (an orbit that lies
     * in the surface, at an equilibrium on it): no sign to change */
    if (magnitude(s->c, s->p) <= s->noise)
        return 0;
    int v = bernstein_changes(s->c, s->p, s->W, sign_of(gl), sign_of(gr), noise_of(s->c, s->p));
    if (v == 0 && !hl_event_crosses(s->ev, gl, gr))
        return 0;
    /* g within its noise of 0 at l, l a crossing just found: narrowing
     * from there would find the noise's sign changes next to it, so the
     * interval is halved until g at its left end stands clear.  Only
     * there: at a step's start g's sign is the one the last step ended
     * with, and a crossing close after it is real (x = 1 - 1e-12 on a
     * long step, where g's noise is 1e-13) */
    int noisy = l == s->found && fabs(gl) <= s->noise;
    int last = depth >= ISOLATE_DEPTH || --s->budget <= 0;
    if ((v == 0 || v == 1 || last) && (!noisy || last)) {
        if (!hl_event_crosses(s->ev, gl, gr) || noisy)
            return 0; /* one root going the other way, none after all, or noise */
        *tau = narrow(s->ev, s->state, s->arg, l * s->h, r * s->h, gl, gr, s->z);
        return 1;
    }
    double m = l + (r - l) / 2;
    double gm = g_at(s->ev, s->state, s->arg, m * s->h, s->z);
    return isolate_first(s, l, m, gl, gm, depth + 1, tau) ||
           isolate_first(s, m, r, gm, gr, depth + 1, tau);
}

/* G[0..p]: the series of an affine g along the state's coef. */
static void affine_series(double *G, const hl_event *ev, const double *coef, int p)
{
    for (int k = 0; k <= p; k++)
        G[k] = k == 0 ? ev->g0 : 0;
    for (int i = 0; i < ev->n; i++) {
        double a = ev->grad[i];
        if (a == 0)
            continue;
        const double *c = coef + (size_t)i * (size_t)(p + 1);
        for (int k = 0; k <= p; k++)
            G[k] += a * c[k];
    }
}

int hl_event_first_taylor(hl_event *ev, const double *coef, int p, double dir, double h,
                          hl_event_state_fn state, void *arg, double a, double ga, double *tau,
                          double *z)
{
    if (ev->cap != p + 1) { /* scratch, and the weights of this order */
        ev->cap = p + 1;
        ev->buf = hl_xrealloc(ev->buf, (3 + (size_t)ev->cap) * (size_t)ev->cap * sizeof *ev->buf);
        bernstein_weights(ev->buf + 3 * ev->cap, p);
    }
    double *G = ev->buf, *P = G + ev->cap;
    if (ev->grad != NULL)
        affine_series(G, ev, coef, p);
    else
        hl_tape_taylor_d(G, coef, p, ev->g);
    double hk = 1;
    for (int k = 0; k <= p; k++, hk *= dir * h)
        P[k] = G[k] * hk;
    if (a == 0 && far_from_zero(P, p))
        return 0; /* most steps: g stays well away from the surface */
    isolate s = {ev,
                 state,
                 arg,
                 P,
                 ev->buf + 3 * ev->cap,
                 p,
                 h,
                 P + ev->cap,
                 z,
                 noise_of(P, p),
                 ISOLATE_BUDGET,
                 a > 0 ? a / h : -1};
    double gb = g_at(ev, state, arg, h, z);
    return isolate_first(&s, a / h, 1, ga, gb, 0, tau);
}
