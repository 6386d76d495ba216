/* Events: a crossing of g(z) = 0 located on an interpolant (see
 * hamlie/event.h). */
#include <float.h>
#include <math.h>
#include <stdlib.h>

#include "base/buf.h"
#include "hamlie/event.h"

struct hl_event {
    hl_tape *g;
    int n;
    hl_event_dir dir;
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
    free(ev);
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
