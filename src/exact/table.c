/* The orbit table of the 1-dof exact flow: following the orbit through a
 * point to its turning point or lap (its kind and start), refining the
 * start and the period in Arb, and sampling one period into M + 1 Taylor
 * polynomial pieces (flow.c then steps on the table).
 *
 * Why a table rather than tanh-sinh quadrature of t(q) = int dq/p: the
 * Taylor polynomials of the flow (tape.h) are accurate to round-off over a
 * step, have no endpoint singularity at the turning points, and the same
 * polynomial that gives t(q,p) by Newton's method also maps the advanced
 * time back to (q,p).  The period is found once, as twice the time from the
 * right turning point to the left one (time-reversal symmetry), and the
 * second half of the table is the mirror image (q, -p) of the first, so the
 * table closes exactly. */
#include <math.h>
#include <string.h>

#include "base/buf.h"
#include "exact/exact_impl.h"
#include "hamlie/flow.h"

void hl_exact_poly_eval_(double *z, double *dz, const double *c, double s)
{
    for (int v = 0; v < 2; v++) {
        const double *cv = c + v * NC;
        double a = cv[ORD], d = 0;
        for (int k = ORD - 1; k >= 0; k--) {
            d = d * s + a;
            a = a * s + cv[k];
        }
        z[v] = a;
        if (dz)
            dz[v] = d;
    }
}

static int taylor_at(double *c, const double *z, hl_exact_flow *f, hl_error *err)
{
    memset(c, 0, sizeof(double) * 2 * NC);
    c[0] = z[0];
    c[NC] = z[1];
    return hl_tape_taylor_ode_d(c, ORD, f->vf, err);
}

/* The step of the polynomials: the truncation |c_k| h^k at most 1e-16 times
 * the first-order change |c_1| h, for k = ORD-3..ORD (so that coefficients
 * that vanish by symmetry do not hide the tail).  Both sides scale with the
 * amplitude, so the step does not depend on it: a tiny orbit is followed as
 * finely, relative to its size, as a large one.  +inf for free motion. */
static double table_step(const double *c)
{
    double n1 = fmax(fabs(c[1]), fabs(c[NC + 1])), h = INFINITY;
    for (int k = ORD - 3; k <= ORD; k++) {
        double a = fmax(fabs(c[k]), fabs(c[NC + k]));
        if (a > 0)
            h = fmin(h, pow(1e-16 * n1 / a, 1.0 / (k - 1)));
    }
    return h * exp(-0.7 / (ORD - 1));
}

/* The energy's distance to the top of a barrier near z, by the quadratic
 * model of V = H(., p) at q: the kinetic part p dH/dp / 2 less V'^2 /
 * (2 |V''|) where V'' < 0 (+inf elsewhere).  At a saddle the model is exact
 * to higher order, so the smallest value along an orbit is its energy
 * distance to the separatrix, without the cancellation of E - V_max. */
static double barrier_margin(const double *z, const double *c, hl_exact_flow *f)
{
    double in[6] = {z[0], 1, 0, z[1], 0, 0}, out[3];
    hl_tape_taylor_d(out, in, 2, f->Ht);
    double V1 = out[1], V2 = 2 * out[2];
    if (!(V2 < 0))
        return INFINITY;
    return fabs(0.5 * z[1] * c[1] - V1 * V1 / (-2 * V2));
}

/* What following an orbit forward in time found. */
enum { TRACE_TURN = 1, TRACE_LAP };
typedef struct trace_end {
    int event;                    /* TRACE_TURN: p crossed 0; TRACE_LAP: q advanced by f->L */
    double t, z[2];               /* the event's time and state */
    double hmin;                  /* the smallest step on the way */
    double pmax, qmin, qmax, kin; /* extent, largest p dH/dp / 2 */
    double margin;                /* smallest barrier_margin */
} trace_end;

static void trace_record(trace_end *e, const double *z, const double *c, hl_exact_flow *f)
{
    e->pmax = fmax(e->pmax, fabs(z[1]));
    e->qmin = fmin(e->qmin, z[0]);
    e->qmax = fmax(e->qmax, z[0]);
    e->kin = fmax(e->kin, fabs(0.5 * z[1] * c[1]));
    e->margin = fmin(e->margin, barrier_margin(z, c, f));
}

/* The root in (0, h] of component v of the polynomial c minus target, by
 * Newton from the secant guess (g0, gh: the values at 0 and h). */
static double event_root(const double *c, int v, double target, double g0, double gh, double h)
{
    double s = h * g0 / (g0 - gh), w[2], dw[2];
    for (int i = 0; i < 50; i++) {
        hl_exact_poly_eval_(w, dw, c, s);
        double ds = (w[v] - target) / dw[v];
        s -= ds;
        if (!(fabs(ds) > 1e-18 * h))
            break;
    }
    return s;
}

#define TRACE_MAX_STEPS 200000L

/* Follow the orbit from z0 forward in time with the Taylor polynomials
 * until p crosses 0 (a turning point) or, if lap, until q has advanced by
 * the period L of H (a rotation).  HL_EDOM for an orbit that does neither
 * (an escape). */
static int trace(trace_end *e, const double *z0, int lap, hl_exact_flow *f, hl_error *err)
{
    double z[2] = {z0[0], z0[1]}, c[2 * NC], zn[2], t = 0, tc = 0;
    double psign = z0[1] > 0 ? 1 : z0[1] < 0 ? -1 : 0, target = 0, qdir = 0;
    *e = (trace_end){0, 0, {0, 0}, INFINITY, 0, z0[0], z0[0], 0, INFINITY};
    for (long n = 0;; n++) {
        int st = taylor_at(c, z, f, err);
        if (st != HL_OK)
            return st;
        trace_record(e, z, c, f);
        if (n == 0 && lap) {
            qdir = c[1] > 0 ? 1 : -1;
            target = z0[0] + qdir * f->L;
        }
        double h = table_step(c);
        if (!(h < INFINITY) || n > TRACE_MAX_STEPS || fabs(z[0] - z0[0]) > 1e9 * (1 + fabs(z0[0])))
            return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                                "unbounded orbit: it does not turn back after q = %g%s "
                                "(an escape: the exact flow by quadrature needs a bounded "
                                "orbit or a rotation in a periodic H)",
                                z0[0], f->L > 0 ? "" : " and H is not periodic in q");
        e->hmin = fmin(e->hmin, h);
        hl_exact_poly_eval_(zn, NULL, c, h);
        if (!isfinite(zn[0]) || !isfinite(zn[1]))
            return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                                "the orbit through q = %g, p = %g leaves the finite range", z0[0],
                                z0[1]);
        double s = INFINITY;
        int event = 0;
        if (psign != 0 && zn[1] * psign <= 0) {
            s = event_root(c, 1, 0, z[1], zn[1], h);
            event = TRACE_TURN;
        }
        if (lap && (zn[0] - target) * qdir >= 0) {
            double sl = event_root(c, 0, target, z[0] - target, zn[0] - target, h);
            if (sl < s)
                s = sl, event = TRACE_LAP;
        }
        if (event) {
            e->event = event;
            e->t = t + (s - tc);
            hl_exact_poly_eval_(e->z, NULL, c, s);
            if (event == TRACE_TURN)
                e->z[1] = 0;
            return HL_OK;
        }
        double y = h - tc, tn = t + y; /* Kahan-compensated time */
        tc = (tn - t) - y;
        t = tn;
        z[0] = zn[0];
        z[1] = zn[1];
        if (psign == 0)
            psign = z[1] > 0 ? 1 : -1;
    }
}

/* z = the table's start zs (q in double-double), in Arb. */
static void start_arb(arb_ptr z, const hl_exact_flow *f)
{
    arb_t lo;
    arb_init(lo);
    arb_set_d(z + 0, f->zs[0]);
    arb_set_d(lo, f->zslo);
    arb_add(z + 0, z + 0, lo, ARF_PREC_EXACT);
    arb_set_d(z + 1, f->zs[1]);
    arb_clear(lo);
}

void hl_exact_turning_point_arb_(arb_t qt, const arb_t E, double qd, double scale, double digits,
                                 slong prec, hl_tape *Ht, hl_tape *vf)
{
    arb_ptr z = _arb_vec_init(2), v = _arb_vec_init(2);
    arb_t h, dq;
    arb_init(h);
    arb_init(dq);
    arb_set_d(qt, qd);
    double tol = pow(10.0, -(digits + 2)) * scale;
    for (int it = 0; it < 12; it++) {
        arb_set(z, qt);
        hl_tape_eval_arb(h, z, prec, Ht);
        hl_tape_eval_arb(v, z, prec, vf); /* v[1] = -dH/dq */
        arb_sub(h, h, E, prec);
        arb_div(dq, h, v + 1, prec); /* -(H - E)/(dH/dq) */
        arb_add(qt, qt, dq, prec);
        arb_get_mid_arb(qt, qt);
        if (!(fabs(arf_get_d(arb_midref(dq), ARF_RND_NEAR)) > tol))
            break;
    }
    _arb_vec_clear(z, 2);
    _arb_vec_clear(v, 2);
    arb_clear(h);
    arb_clear(dq);
}

/* A libration's table starts at the turning point ahead of z0, which the
 * double trace finds rounded to double: that moves the table's energy by
 * an ulp of V there, and near a separatrix such an ulp is a large part of
 * the energy's distance to it (the period grows as its log).  So the start
 * is refined to double-double, by Newton in Arb on H(q, 0) = H(z0). */
static void refine_start(const double *z0, double digits, hl_exact_flow *f)
{
    slong prec = (slong)ceil(digits * log2(10.0)) + 32;
    arb_ptr z = _arb_vec_init(2);
    arb_t E, qt;
    arb_init(E);
    arb_init(qt);
    arb_set_d(z, z0[0]);
    arb_set_d(z + 1, z0[1]);
    hl_tape_eval_arb(E, z, prec, f->Ht);
    hl_exact_turning_point_arb_(qt, E, f->zs[0], f->size, digits, prec, f->Ht, f->vf);
    double qh = arf_get_d(arb_midref(qt), ARF_RND_NEAR);
    arb_set_d(E, qh);
    arb_sub(qt, qt, E, prec);
    double ql = arf_get_d(arb_midref(qt), ARF_RND_NEAR);
    if (isfinite(qh) && isfinite(ql)) {
        f->zs[0] = qh;
        f->zslo = ql;
    }
    _arb_vec_clear(z, 2);
    arb_clear(E);
    arb_clear(qt);
}

/* The period in double-double: one Newton step on the event at tau (p = 0
 * for a libration, q = q_s + L_s for a rotation) from zs, with the state
 * from the Arb integrator at `digits`.  Why: an error of one ulp in T
 * becomes a phase error of t/T ulps, 1e-13 after a thousand time units. */
static int refine_period(double *T, double *Tlo, double tau0, double digits, hl_exact_flow *f,
                         hl_error *err)
{
    hl_flow_arb *fa = NULL;
    int st = hl_flow_arb_new(&fa, f->vf, digits, err);
    if (st != HL_OK)
        return st;
    int rot = f->kind == ORBIT_ROTATION, v = rot ? 0 : 1;
    slong prec = hl_flow_arb_prec(fa);
    arb_t t, t1, tau;
    arb_ptr z = _arb_vec_init(2), dz = _arb_vec_init(2);
    arb_init(t);
    arb_init(t1);
    arb_init(tau);
    arb_set_d(t1, tau0);
    start_arb(z, f);
    st = hl_flow_arb_evolve(fa, t, t1, z, err);
    if (st == HL_OK) {
        hl_tape_eval_arb(dz, z, prec, f->vf);
        if (rot) { /* q(tau) - q_s - L_s */
            arb_set_d(t, f->zs[0]);
            arb_sub(z, z, t, prec);
            arb_set_d(t, f->Ls);
            arb_sub(z, z, t, prec);
        }
        arb_div(tau, z + v, dz + v, prec);
        arb_sub(tau, t1, tau, prec);
        if (!rot)
            arb_mul_2exp_si(tau, tau, 1);
        *T = arf_get_d(arb_midref(tau), ARF_RND_NEAR);
        arb_set_d(t1, *T);
        arb_sub(t, tau, t1, prec);
        *Tlo = arf_get_d(arb_midref(t), ARF_RND_NEAR);
        if (!isfinite(*T) || !(*T > 0))
            st = hl_error_set(err, HL_EDOM, NULL, -1, 0, "the period is not finite");
    }
    _arb_vec_clear(z, 2);
    _arb_vec_clear(dz, 2);
    arb_clear(t);
    arb_clear(t1);
    arb_clear(tau);
    hl_flow_arb_free(fa);
    return st;
}

struct sample_arg {
    double *zs;
    int k;
};

static int sample_fn(const arb_t t, arb_srcptr z, void *arg)
{
    struct sample_arg *a = arg;
    (void)t;
    a->zs[2 * a->k] = arf_get_d(arb_midref(z + 0), ARF_RND_NEAR);
    a->zs[2 * a->k + 1] = arf_get_d(arb_midref(z + 1), ARF_RND_NEAR);
    a->k++;
    return 0;
}

/* zs[2k], zs[2k+1] = z(k (T + Tlo) / M) for k = 0..n-1, from f->zs, by the
 * Arb integrator (so that the samples are right to the last bit: errors in
 * them are not averaged out). */
static int sample_orbit(double *zs, int n, double digits, hl_exact_flow *f, hl_error *err)
{
    hl_flow_arb *fa = NULL;
    int st = hl_flow_arb_new(&fa, f->vf, digits, err);
    if (st != HL_OK)
        return st;
    slong prec = hl_flow_arb_prec(fa);
    arb_ptr ts = _arb_vec_init(n), z0 = _arb_vec_init(2);
    arb_t h, lo, t0;
    arb_init(h);
    arb_init(lo);
    arb_init(t0);
    arb_set_d(h, f->T);
    arb_set_d(lo, f->Tlo);
    arb_add(h, h, lo, prec);
    arb_div_si(h, h, f->M, prec);
    for (int k = 0; k < n; k++)
        arb_mul_si(ts + k, h, k, prec);
    start_arb(z0, f);
    struct sample_arg a = {zs, 0};
    st = hl_flow_arb_run(fa, t0, z0, ts, n, sample_fn, &a, err);
    _arb_vec_clear(ts, n);
    _arb_vec_clear(z0, 2);
    arb_clear(h);
    arb_clear(lo);
    arb_clear(t0);
    hl_flow_arb_free(fa);
    return st;
}

/* The pieces 0..M: a libration's first half from the samples, the second
 * its mirror image (q, -p) (H even in p), so that the table closes
 * exactly; a rotation's whole period from the samples. */
static int tabulate(double digits, hl_exact_flow *f, hl_error *err)
{
    int M = f->M, rot = f->kind == ORBIT_ROTATION, n = rot ? M + 1 : M / 2 + 1;
    double *zs = hl_xmalloc(sizeof(double) * 2 * n);
    free(f->C);
    f->C = hl_xmalloc(sizeof(double) * (M + 1) * 2 * NC);
    int st = sample_orbit(zs, n, digits, f, err);
    for (int k = 0; k < n && st == HL_OK; k++) {
        int turn = !rot && (k == 0 || k == M / 2);
        double zk[2] = {zs[2 * k], turn ? 0 : zs[2 * k + 1]};
        st = taylor_at(f->C + (size_t)k * 2 * NC, zk, f, err);
        if (st == HL_OK && !rot && k < M / 2) {
            zk[1] = -zk[1];
            st = taylor_at(f->C + (size_t)(M - k) * 2 * NC, zk, f, err);
        }
    }
    free(zs);
    return st;
}

/* The orbit through z0 (not an equilibrium): its kind and start (a
 * turning point, or z0 itself on a rotation) in f, and in b the trace of
 * half a libration's period from its start, or of a rotation's lap. */
static int find_orbit(trace_end *b, const double *z0, hl_exact_flow *f, hl_error *err)
{
    trace_end a;
    int st = HL_OK;
    a.event = TRACE_TURN;
    a.z[0] = z0[0];
    a.z[1] = 0;
    if (z0[1] != 0) /* the first turning point ahead, or a lap */
        st = trace(&a, z0, f->L > 0, f, err);
    if (st != HL_OK)
        return st;
    if (a.event == TRACE_LAP) {
        f->kind = ORBIT_ROTATION;
        f->zslo = 0;
        f->zs[0] = z0[0];
        f->zs[1] = z0[1];
        f->Ls = a.z[0] - z0[0] > 0 ? f->L : -f->L;
        *b = a;
    } else {
        f->kind = ORBIT_LIBRATION;
        f->zslo = 0;
        f->zs[0] = a.z[0];
        f->zs[1] = 0;
        f->Ls = 0;
        st = trace(b, f->zs, 0, f, err); /* half a period */
        if (st != HL_OK)
            return st;
        if (z0[1] != 0)
            b->margin = fmin(b->margin, a.margin);
    }
    /* 2^-40: closer than that, the rounding of the state alone moves the
     * period by more than 1e-4 of itself (T grows as log(1 / margin)) */
    if (b->margin <= 0x1p-40 * b->kin)
        return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                            "separatrix: the orbit through q = %.17g, p = %.17g is within "
                            "rounding (%.2g of its energy scale) of the energy of an unstable "
                            "equilibrium or of the potential's top at infinity: its period is "
                            "infinite, or too long to tell from rounding, and there is no "
                            "exact flow to compute",
                            z0[0], z0[1], b->margin / b->kin);
    return HL_OK;
}

/* Build the table of the orbit through z0 (not an equilibrium): its start,
 * period and pieces. */
int hl_exact_table_build_(hl_exact_flow *f, const double *z0, hl_error *err)
{
    trace_end b;
    f->have_tab = 0;
    f->have_last = 0;
    int st = find_orbit(&b, z0, f, err);
    if (st != HL_OK)
        return st;
    f->size = f->kind == ORBIT_ROTATION ? fmax(f->L, b.pmax) : fmax(b.qmax - b.qmin, b.pmax);
    f->escale = b.kin;
    /* the Arb integrator's tolerance is absolute below |z| = 1: digits
     * enough for 24 of them relative to the orbit's size */
    double zmax = fmax(fmax(fabs(b.qmin), fabs(b.qmax)), b.pmax);
    double extra = fmax(0, log10(fmax(1, zmax) / f->size));
    if (!(extra < 300))
        return hl_error_set(err, HL_EDOM, NULL, -1, 0, "orbit too small (size %g) for the table",
                            f->size);
    if (f->kind == ORBIT_LIBRATION && z0[1] != 0)
        refine_start(z0, 32 + 2 * extra, f);
    double T = f->kind == ORBIT_ROTATION ? b.t : 2 * b.t, Tlo = 0;
    st = refine_period(&T, &Tlo, f->kind == ORBIT_ROTATION ? T : T / 2, 32 + extra, f, err);
    if (st != HL_OK)
        return st;
    double Mf = ceil(2 * T / b.hmin);
    if (!(Mf < 1e7))
        return hl_error_set(err, HL_EDOM, NULL, -1, 0, "the orbit's table would need %g pieces",
                            Mf);
    int M = Mf < 8 ? 8 : (int)Mf;
    M += M % 2;
    f->T = T;
    f->Tlo = Tlo;
    f->M = M;
    f->hs = T / M;
    f->hslo = (fma(-f->hs, M, T) + Tlo) / M;
    st = tabulate(24 + extra, f, err);
    f->have_tab = st == HL_OK;
    return st;
}
