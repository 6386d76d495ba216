/* The numeric exact flow: matrix exponential for quadratic H, orbit table
 * for 1-dof bounded orbits (see exact.h).
 *
 * Why a table rather than tanh-sinh quadrature of t(q) = int dq/p: the
 * Taylor polynomials of the flow (tape.h) are accurate to round-off over a
 * step, have no endpoint singularity at the turning points, and the same
 * polynomial that gives t(q,p) by Newton's method also maps the advanced
 * time back to (q,p).  The period is found once, as twice the time from the
 * right turning point to the left one (time-reversal symmetry), and the
 * second half of the table is the mirror image (q, -p) of the first, so the
 * table closes exactly. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <arb_mat.h>

#include "hamlie/exact.h"
#include "hamlie/tape.h"
#include "hamlie/flow.h"
#include "base/buf.h"
#include "exact/exact_impl.h"

#define ORD HL_EXACT_SERIES_DEGREE /* Taylor order of the table polynomials (20) */
#define NC (ORD + 1)

struct hl_exact_flow {
    int N, linear;
    /* linear: augmented (2N+1)^2 matrix [[A, b], [0, 0]] and its exp at dt */
    double *Aaug, *E, Edt;
    int have_E;
    /* 1 dof */
    hl_tape *vf, *Ht;
    double L; /* the period of H in q (2 pi), 0 if H is not periodic */
    /* the table: the orbit from its start zs (a turning point of a
     * libration; on a rotation any point, q advancing by Ls a period) */
    int have_tab, kind;
    double zs[2], zslo, Ls, size; /* zs[0] + zslo: double-double; size: the
                                   * orbit's extent in q and p */
    double escale;          /* its energy scale: the largest p dH/dp / 2 */
    double T, Tlo, hs, hslo; /* period T + Tlo, sample spacing hs + hslo */
    /* the last output, its time since the start (double-double) and
     * winding: stepping again from it needs no search */
    double last[2], lth, ltl, lw;
    int have_last;
    int M;
    double *C; /* M + 1 pieces x 2 variables x NC coefficients */
};

static double H_at(hl_exact_flow *f, const double *z)
{
    double h;
    hl_tape_eval_d(&h, z, f->Ht);
    return h;
}

/* ---- linear ------------------------------------------------------------ */

/* Is H quadratic (degree <= 2 in q,p, constant coefficients)?  Fills the
 * augmented matrix when it is. */
static int quadratic_matrix(double *Aaug, int *yes, hl_system *sys, hl_error *err)
{
    int N = hl_system_ndof(sys), n = 2 * N, m = n + 1, st = HL_OK;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    const hl_alg *H = hl_system_H(sys);
    hl_alg *g = hl_alg_vec_new(n, ctx), d2, zero;
    hl_alg *zeros = hl_alg_vec_new(n, ctx);
    int *vars = hl_xmalloc(sizeof(int) * n);
    fmpq_t c;
    fmpq_init(c);
    hl_alg_init(&d2, ctx);
    hl_alg_init(&zero, ctx);
    *yes = 1;
    memset(Aaug, 0, sizeof(double) * m * m);
    for (int a = 0; a < n; a++)
        vars[a] = a < N ? hl_system_var_q(sys, a) : hl_system_var_p(sys, a - N);
    for (int a = 0; a < n && st == HL_OK && *yes; a++) {
        st = hl_alg_diff(&g[a], H, vars[a], ctx, err);
        /* row of A: (J grad H)_i = dH/dp_i (i < N), -dH/dq_i */
        int row = a < N ? a + N : a - N;
        double sgn = a < N ? -1.0 : 1.0;
        for (int b = 0; b < n && st == HL_OK && *yes; b++) {
            st = hl_alg_diff(&d2, &g[a], vars[b], ctx, err);
            if (st == HL_OK && !hl_alg_is_fmpq(&d2, c, ctx))
                *yes = 0;
            else if (st == HL_OK)
                Aaug[row * m + b] = sgn * fmpq_get_d(c);
        }
        if (st == HL_OK && *yes) {
            st = hl_alg_subst(&d2, &g[a], n, vars, zeros, ctx, err);
            if (st == HL_OK && !hl_alg_is_fmpq(&d2, c, ctx))
                *yes = 0;
            else if (st == HL_OK)
                Aaug[row * m + n] = sgn * fmpq_get_d(c);
        }
    }
    fmpq_clear(c);
    hl_alg_clear(&d2, ctx);
    hl_alg_clear(&zero, ctx);
    hl_alg_vec_free(g, n, ctx);
    hl_alg_vec_free(zeros, n, ctx);
    free(vars);
    return st;
}

static void linear_exp(hl_exact_flow *f, double dt)
{
    int m = 2 * f->N + 1;
    slong prec = 128;
    arb_mat_t A, E;
    arb_t h;
    arb_init(h);
    arb_set_d(h, dt);
    arb_mat_init(A, m, m);
    arb_mat_init(E, m, m);
    for (int i = 0; i < m; i++)
        for (int j = 0; j < m; j++) {
            arb_set_d(arb_mat_entry(A, i, j), f->Aaug[i * m + j]);
            arb_mul(arb_mat_entry(A, i, j), arb_mat_entry(A, i, j), h, prec);
        }
    arb_mat_exp(E, A, prec);
    for (int i = 0; i < m; i++)
        for (int j = 0; j < m; j++)
            f->E[i * m + j] = arf_get_d(arb_midref(arb_mat_entry(E, i, j)), ARF_RND_NEAR);
    arb_mat_clear(A);
    arb_mat_clear(E);
    arb_clear(h);
    f->Edt = dt;
    f->have_E = 1;
}

static int linear_step(double *z, double dt, hl_exact_flow *f)
{
    int n = 2 * f->N, m = n + 1;
    if (!f->have_E || f->Edt != dt)
        linear_exp(f, dt);
    double *w = hl_xmalloc(sizeof(double) * n);
    for (int i = 0; i < n; i++) {
        double s = f->E[i * m + n];
        for (int j = 0; j < n; j++)
            s += f->E[i * m + j] * z[j];
        w[i] = s;
    }
    memcpy(z, w, sizeof(double) * n);
    free(w);
    return HL_OK;
}

/* ---- 1 dof: the orbit ---------------------------------------------------- */

static void poly_eval(double *z, double *dz, const double *c, double s)
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
    int event;       /* TRACE_TURN: p crossed 0; TRACE_LAP: q advanced by f->L */
    double t, z[2];  /* the event's time and state */
    double hmin;     /* the smallest step on the way */
    double pmax, qmin, qmax, kin; /* extent, largest p dH/dp / 2 */
    double margin;   /* smallest barrier_margin */
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
        poly_eval(w, dw, c, s);
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
        if (!(h < INFINITY) || n > TRACE_MAX_STEPS ||
            fabs(z[0] - z0[0]) > 1e9 * (1 + fabs(z0[0])))
            return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                                "unbounded orbit: it does not turn back after q = %g%s "
                                "(an escape: the exact flow by quadrature needs a bounded "
                                "orbit or a rotation in a periodic H)",
                                z0[0], f->L > 0 ? "" : " and H is not periodic in q");
        e->hmin = fmin(e->hmin, h);
        poly_eval(zn, NULL, c, h);
        if (!isfinite(zn[0]) || !isfinite(zn[1]))
            return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                                "the orbit through q = %g, p = %g leaves the finite range",
                                z0[0], z0[1]);
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
            poly_eval(e->z, NULL, c, s);
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

void hl_exact_turning_point_arb_(arb_t qt, const arb_t E, double qd, double scale,
                                 double digits, slong prec, hl_tape *Ht, hl_tape *vf)
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
static int build_table(hl_exact_flow *f, const double *z0, hl_error *err)
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
        return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                            "orbit too small (size %g) for the table", f->size);
    if (f->kind == ORBIT_LIBRATION && z0[1] != 0)
        refine_start(z0, 32 + 2 * extra, f);
    double T = f->kind == ORBIT_ROTATION ? b.t : 2 * b.t, Tlo = 0;
    st = refine_period(&T, &Tlo, f->kind == ORBIT_ROTATION ? T : T / 2, 32 + extra, f, err);
    if (st != HL_OK)
        return st;
    double Mf = ceil(2 * T / b.hmin);
    if (!(Mf < 1e7))
        return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                            "the orbit's table would need %g pieces", Mf);
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

/* The winding w of z on a rotation's table, and z's coordinate brought
 * into the table's lap, q - w L_s. */
static double unwind(double *q, const double *z, const hl_exact_flow *f)
{
    if (f->kind != ORBIT_ROTATION) {
        *q = z[0];
        return 0;
    }
    double w = floor((z[0] - f->zs[0]) / f->Ls);
    *q = fma(-w, f->Ls, z[0]);
    return w;
}

/* Time since the table's start of the point w of the table nearest
 * z = (q, p) (double-double th + lo), the distance from z to it, and
 * H(z) - H(w) to first order, grad H(w) . (z - w) (grad H = (-p', q') on
 * the orbit): the energy offset without the cancellation of H(z) - H(w). */
static double locate(double *lo, double *dist, double *dE, double q, double p,
                     const hl_exact_flow *f)
{
    int best = 0;
    double bd = INFINITY;
    for (int k = 0; k <= f->M; k++) {
        const double *ck = f->C + (size_t)k * 2 * NC;
        double d = hypot(ck[0] - q, ck[NC] - p);
        if (d < bd) {
            bd = d;
            best = k;
        }
    }
    const double *ck = f->C + (size_t)best * 2 * NC;
    double s = 0, w[2], dw[2];
    for (int i = 0; i < 20; i++) {
        poly_eval(w, dw, ck, s);
        double n2 = dw[0] * dw[0] + dw[1] * dw[1];
        double ds = ((w[0] - q) * dw[0] + (w[1] - p) * dw[1]) / n2;
        s -= ds;
        if (!(fabs(ds) > 1e-17 * f->hs))
            break;
    }
    poly_eval(w, dw, ck, s);
    *dist = hypot(w[0] - q, w[1] - p);
    *dE = -dw[1] * (q - w[0]) + dw[0] * (p - w[1]);
    /* best * (hs + hslo) + s in double-double: the rounding of t alone
     * would bias every step by up to an ulp of the period */
    double ph = best * f->hs, pe = fma(best, f->hs, -ph) + best * f->hslo;
    double x = ph + s, bv = x - ph;
    *lo = (ph - (x - bv)) + (s - bv) + pe;
    return x;
}

static void two_sum(double *s, double *e, double a, double b)
{
    double x = a + b, bv = x - a;
    *e = (a - (x - bv)) + (b - bv);
    *s = x;
}

/* uh + ul brought into [0, T + Tlo), *w counting the periods taken off. */
static void wrap_time(double *uh, double *ul, double *w, const hl_exact_flow *f)
{
    if (*uh > f->T || (*uh == f->T && *ul >= f->Tlo)) {
        two_sum(uh, ul, *uh - f->T, *ul - f->Tlo); /* uh - T exact: T <= uh < 2T */
        *w += 1;
    }
    if (*uh < 0) {
        two_sum(uh, ul, *uh + f->T, *ul + f->Tlo);
        *w -= 1;
    }
}

/* Is z on the table's orbit, to rounding?  Its energy within rounding of
 * the orbit's energy scale: near a saddle, where p is small, orbits of
 * energies an ulp apart are far apart (dp = dE / p), so distance alone
 * would reject the table of z's own orbit built from a turning point
 * rounded to double.  And near it: another part of the same energy level
 * (the other well of a double well) is not z's orbit. */
static int on_table(double dist, double dE, double q, double p, const hl_exact_flow *f)
{
    double r = f->size + fabs(q) + fabs(p);
    return dist <= 1e-8 * r && fabs(dE) <= 64 * DBL_EPSILON * f->escale;
}

/* z's time since the table's start, th + tl in [0, T + Tlo) (double-double),
 * and its winding w (rotations), building the table of z's orbit if z is
 * not on the current one. */
static int orbit_time(double *th, double *tl, double *w, const double *z, hl_exact_flow *f,
                      hl_error *err)
{
    if (f->have_last && z[0] == f->last[0] && z[1] == f->last[1]) {
        *th = f->lth;
        *tl = f->ltl;
        *w = f->lw;
        return HL_OK;
    }
    if (!isfinite(z[0]) || !isfinite(z[1]))
        return hl_error_set(err, HL_EDOM, NULL, -1, 0, "the state is not finite");
    double q, dist = INFINITY, dE;
    for (int pass = 0; pass < 2; pass++) {
        if (f->have_tab) {
            *w = unwind(&q, z, f);
            *th = locate(tl, &dist, &dE, q, z[1], f);
            if (on_table(dist, dE, q, z[1], f))
                break;
        }
        if (pass == 1)
            return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                                "the point q = %.17g, p = %.17g is %.3g off its own orbit's "
                                "table",
                                z[0], z[1], dist);
        int st = build_table(f, z, err);
        if (st != HL_OK)
            return st;
    }
    wrap_time(th, tl, w, f);
    return HL_OK;
}

/* The table piece for time uh + ul in [0, T + Tlo), and the offset in it. */
static const double *piece(double *s, double uh, double ul, const hl_exact_flow *f)
{
    long k = lround(uh / f->hs);
    k = k < 0 ? 0 : k > f->M ? f->M : k;
    *s = fma(-(double)k, f->hs, uh) - k * f->hslo + ul;
    return f->C + (size_t)k * 2 * NC;
}

/* dt = n (T + Tlo) + r with r in [0, T + Tlo), reduced in double-double
 * (for large dt the rounding of t + dt alone would cost dt * 1e-16). */
static double reduce(double *n, double dt, const hl_exact_flow *f)
{
    double k = floor(dt / f->T);
    double r = fma(-k, f->T, dt) - k * f->Tlo;
    for (; r >= f->T; k++)
        r -= f->T;
    for (; r < 0; k--)
        r += f->T;
    *n = k;
    return r;
}

void hl_exact_flow_gradient_(double *v, const double *z, hl_exact_flow *f)
{
    hl_tape_eval_d(v, z, f->vf);
}

/* The Jacobian J of (dH/dp, -dH/dq) at z, row-major, by Taylor mode. */
static void jacobian(double *J, const double *z, hl_exact_flow *f)
{
    double in[4] = {z[0], 1, z[1], 0}, dq[4], dp[4];
    hl_tape_taylor_d(dq, in, 1, f->vf);
    in[1] = 0, in[3] = 1;
    hl_tape_taylor_d(dp, in, 1, f->vf);
    J[0] = dq[1], J[1] = dp[1], J[2] = dq[3], J[3] = dp[3];
}

/* What z is to the flow:
 *   POINT_EQUILIBRIUM  grad H = 0 exactly: the flow is the identity;
 *   POINT_TINY         on an orbit about a centre ze too small to tabulate
 *                      (its Taylor coefficients and distances underflow)
 *                      but over which the vector field is linear to
 *                      rounding: the flow is the linearised flow, exactly
 *                      the limit of small orbits;
 *   POINT_NEAR_SADDLE  the same about a saddle: z is within rounding of the
 *                      separatrix;
 *   POINT_ORBIT        an orbit to tabulate.
 * Linear to rounding: J the same to rounding at z, ze and the mirror image
 * 2 ze - z (so the field's second derivatives do not act on the orbit);
 * tried only where grad H is small.  ze and J are set for the first three
 * (ze = z, J = 0 at an equilibrium). */
enum { POINT_ORBIT, POINT_EQUILIBRIUM, POINT_TINY, POINT_NEAR_SADDLE };
static int classify(double *ze, double *J, const double *z, hl_exact_flow *f)
{
    double v[2], Jm[4], Je[4];
    hl_exact_flow_gradient_(v, z, f);
    if (v[0] == 0 && v[1] == 0) {
        ze[0] = z[0], ze[1] = z[1];
        memset(J, 0, 4 * sizeof *J);
        return POINT_EQUILIBRIUM;
    }
    if (!(fmax(fabs(v[0]), fabs(v[1])) < 1e-6 * fmax(1, fmax(fabs(z[0]), fabs(z[1])))))
        return POINT_ORBIT;
    jacobian(J, z, f);
    double det = J[0] * J[3] - J[1] * J[2];
    if (!(det != 0) || !isfinite(det))
        return POINT_ORBIT;
    /* one Newton step to grad H = 0: z - J^-1 v */
    ze[0] = z[0] - (J[3] * v[0] - J[1] * v[1]) / det;
    ze[1] = z[1] - (-J[2] * v[0] + J[0] * v[1]) / det;
    double zm[2] = {2 * ze[0] - z[0], 2 * ze[1] - z[1]};
    jacobian(Je, ze, f);
    jacobian(Jm, zm, f);
    double n = fmax(fmax(fabs(J[0]), fabs(J[1])), fmax(fabs(J[2]), fabs(J[3])));
    for (int i = 0; i < 4; i++)
        if (!(fabs(Je[i] - J[i]) <= DBL_EPSILON * n && fabs(Jm[i] - J[i]) <= DBL_EPSILON * n))
            return POINT_ORBIT;
    return det > 0 ? POINT_TINY : POINT_NEAR_SADDLE;
}

static int near_saddle_error(const double *z, hl_error *err)
{
    return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                        "separatrix: the point q = %.17g, p = %.17g is within rounding of an "
                        "unstable equilibrium: there is no exact flow to compute",
                        z[0], z[1]);
}

/* z advanced by dt on the linearised flow about the centre ze: exp(dt J) =
 * cos(w dt) I + sin(w dt)/w J (J traceless, J^2 = -w^2 I, w^2 = det J). */
static void tiny_step(double *z, double dt, const double *ze, const double *J)
{
    double w = sqrt(J[0] * J[3] - J[1] * J[2]), C = cos(w * dt), S = sin(w * dt) / w;
    double d[2] = {z[0] - ze[0], z[1] - ze[1]};
    z[0] = ze[0] + C * d[0] + S * (J[0] * d[0] + J[1] * d[1]);
    z[1] = ze[1] + C * d[1] + S * (J[2] * d[0] + J[3] * d[1]);
}

static int orbit_step(double *z, double dt, hl_exact_flow *f, hl_error *err)
{
    double ze[2], J[4];
    /* the last output is on the table: no need to ask */
    int kind = f->have_last && z[0] == f->last[0] && z[1] == f->last[1] ? POINT_ORBIT
                                                                        : classify(ze, J, z, f);
    if (kind == POINT_NEAR_SADDLE)
        return near_saddle_error(z, err);
    if (kind == POINT_EQUILIBRIUM)
        return HL_OK;
    if (kind == POINT_TINY) {
        tiny_step(z, dt, ze, J);
        return HL_OK;
    }
    double th, tl, w, n;
    int st = orbit_time(&th, &tl, &w, z, f, err);
    if (st != HL_OK)
        return st;
    /* u = t + (dt mod period), then once more mod period, in double-double */
    double uh, ul;
    two_sum(&uh, &ul, th, reduce(&n, dt, f));
    ul += tl;
    two_sum(&uh, &ul, uh, ul);
    w += n;
    wrap_time(&uh, &ul, &w, f);
    double s;
    const double *c = piece(&s, uh, ul, f);
    poly_eval(z, NULL, c, s);
    if (w != 0)
        z[0] = fma(w, f->Ls, z[0]);
    f->last[0] = z[0];
    f->last[1] = z[1];
    f->lth = uh;
    f->ltl = ul;
    f->lw = w;
    f->have_last = 1;
    return HL_OK;
}

/* The step's series at z, from the step's own construction: the step is a
 * time shift along the tabulated orbit, psi_D(z) = P(s + D) with P the
 * table's polynomial piece for z's time t(z) and s the offset of t(z) in
 * it (orbit_step for dt = D, the same piece while t(z) + D stays in it), so
 * [D^k] psi_D(z) = sum_{j >= k} binom(j, k) c_j s^(j-k): the piece
 * re-expanded at s.  Nothing here is the Taylor series at z: compared with
 * the flow's, it checks the action-angle map (z's time on the table) and the
 * piece (its samples, its coefficients) at every order.  The pieces have
 * degree ORD, so the series stops there; its coefficient k also carries the
 * piece's truncation, about binom(ORD+1, k) |s / rho|^(ORD+1-k) relative
 * (rho the radius of convergence), which grows with k (figures in exact.h). */
static int orbit_series(double *coef, const double *z, int n, hl_exact_flow *f, hl_error *err)
{
    if (n > ORD)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                            "the exact scheme's orbit table is made of Taylor polynomials of "
                            "degree %d in time: its series stops at D^%d (asked for D^%d)",
                            ORD, ORD, n);
    double ze[2], J[4];
    int kind = classify(ze, J, z, f);
    if (kind == POINT_NEAR_SADDLE)
        return near_saddle_error(z, err);
    if (kind != POINT_ORBIT) { /* J^k (z - ze) / k! */
        double d[2] = {z[0] - ze[0], z[1] - ze[1]};
        coef[0] = z[0];
        coef[1] = z[1];
        for (int k = 1; k <= n; k++) {
            double a = (J[0] * d[0] + J[1] * d[1]) / k, b = (J[2] * d[0] + J[3] * d[1]) / k;
            coef[2 * k] = d[0] = a;
            coef[2 * k + 1] = d[1] = b;
        }
        return HL_OK;
    }
    double th, tl, w, s;
    int st = orbit_time(&th, &tl, &w, z, f, err);
    if (st != HL_OK)
        return st;
    const double *c = piece(&s, th, tl, f);
    for (int v = 0; v < 2; v++)
        for (int k = 0; k <= n; k++) {
            /* sum_{j=k..ORD} binom(j, k) c_j s^(j-k), by Horner from the top */
            double a = 0, b = 1; /* b = binom(j, k), j from k up */
            for (int j = k + 1; j <= ORD; j++)
                b = b * j / (j - k);
            for (int j = ORD; j >= k; j--) {
                a = a * s + b * c[v * NC + j];
                if (j > k)
                    b = b * (j - k) / j;
            }
            coef[k * 2 + v] = a;
        }
    if (w != 0)
        coef[0] = fma(w, f->Ls, coef[0]);
    return HL_OK;
}

/* The period at an equilibrium (or on an orbit about it small enough for
 * its linearised flow): the limit of small orbits, 2 pi / omega with
 * omega^2 = det J = H_pp H_qq - H_pq H_qp; +inf where that is not positive
 * (an unstable equilibrium is a fixed point of no period). */
static double equilibrium_period(const double *z, hl_exact_flow *f)
{
    double J[4];
    jacobian(J, z, f);
    double w2 = J[0] * J[3] - J[1] * J[2];
    return w2 > 0 ? 2 * M_PI / sqrt(w2) : INFINITY;
}

/* (A^k (z, 1))/k! with the augmented matrix: the series of exp(D A). */
static void linear_series(double *coef, const double *z, int n, const hl_exact_flow *f)
{
    int m2 = 2 * f->N, m = m2 + 1;
    double *x = hl_xmalloc(sizeof(double) * m), *y = hl_xmalloc(sizeof(double) * m);
    memcpy(x, z, sizeof(double) * m2);
    x[m2] = 1;
    memcpy(coef, z, sizeof(double) * m2);
    for (int k = 1; k <= n; k++) {
        for (int i = 0; i < m; i++) {
            double t = 0;
            for (int j = 0; j < m; j++)
                t += f->Aaug[i * m + j] * x[j];
            y[i] = t / k;
        }
        memcpy(x, y, sizeof(double) * m);
        memcpy(coef + (size_t)k * m2, x, sizeof(double) * m2);
    }
    free(x), free(y);
}

/* Is H periodic in q with period 2 pi (a rotation is then a periodic
 * motion of q mod 2 pi)?  Checked at a few points, to rounding. */
static int periodic_in_q(hl_exact_flow *f)
{
    static const double pts[][2] = {{0.3, 0.7}, {-0.45, 1.1}, {1.2, -0.2}, {2.9, 0.4}};
    for (int i = 0; i < 4; i++) {
        double a[2] = {pts[i][0], pts[i][1]}, b[2] = {pts[i][0] + 2 * M_PI, pts[i][1]};
        double ha = H_at(f, a), hb = H_at(f, b);
        if (!isfinite(ha) || !(fabs(ha - hb) <= 1e-13 * fmax(1.0, fabs(ha))))
            return 0;
    }
    return 1;
}

/* ---- public -------------------------------------------------------------- */

hl_status hl_exact_flow_new(hl_exact_flow **out, hl_system *sys, hl_error *err)
{
    *out = NULL;
    if (!hl_system_has_H(sys))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "the exact flow needs a Hamiltonian");
    if (hl_system_nparams(sys) > 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "parameter '%s' needs a value for the numeric exact flow",
                            hl_system_param(sys, 0));
    int N = hl_system_ndof(sys), m = 2 * N + 1, quad = 0;
    hl_exact_flow *f = hl_xcalloc(1, sizeof *f);
    f->N = N;
    f->Aaug = hl_xmalloc(sizeof(double) * m * m);
    int st = quadratic_matrix(f->Aaug, &quad, sys, err);
    if (st == HL_OK && quad) {
        f->linear = 1;
        f->E = hl_xmalloc(sizeof(double) * m * m);
    } else if (st == HL_OK && N != 1) {
        st = hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                          "no exact flow for a non-quadratic H with %d degrees of freedom "
                          "(only 1 dof is handled by quadrature)",
                          N);
    } else if (st == HL_OK) {
        const char *names[2] = {hl_system_coord(sys, 0), hl_system_momentum(sys, 0)};
        const hl_expr *Hx = hl_system_H_expr(sys);
        st = hl_tape_hamiltonian(&f->vf, hl_system_pool(sys), Hx, 1, names, names + 1, 0, NULL,
                                 NULL, err);
        if (st == HL_OK)
            st = hl_tape_new(&f->Ht, &Hx, 1, names, 2, err);
        /* time-reversal symmetry, checked at a few points */
        static const double pts[][2] = {{0.3, 0.7}, {-0.45, 1.1}, {1.2, -0.2}};
        for (int i = 0; st == HL_OK && i < 3; i++) {
            double a[2] = {pts[i][0], pts[i][1]}, b[2] = {pts[i][0], -pts[i][1]};
            double ha = H_at(f, a), hb = H_at(f, b);
            if (isfinite(ha) && fabs(ha - hb) > 1e-12 * fmax(1.0, fabs(ha)))
                st = hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                                  "the 1-dof exact flow needs H(q,p) = H(q,-p)");
        }
        if (st == HL_OK)
            f->L = periodic_in_q(f) ? 2 * M_PI : 0;
    }
    if (st != HL_OK) {
        hl_exact_flow_free(f);
        return st;
    }
    *out = f;
    return HL_OK;
}

void hl_exact_flow_free(hl_exact_flow *f)
{
    if (f == NULL)
        return;
    free(f->Aaug);
    free(f->E);
    free(f->C);
    hl_tape_free(f->vf);
    hl_tape_free(f->Ht);
    free(f);
}

int hl_exact_flow_is_linear(const hl_exact_flow *f)
{
    return f->linear;
}

hl_status hl_exact_flow_step(double *z, double dt, void *flow, hl_error *err)
{
    hl_exact_flow *f = flow;
    if (!isfinite(dt))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "step is not finite");
    if (f->linear)
        return linear_step(z, dt, f);
    double w[2] = {z[0], z[1]};
    int st = orbit_step(w, dt, f, err);
    if (st == HL_OK) {
        z[0] = w[0];
        z[1] = w[1];
    }
    return st;
}

hl_status hl_exact_flow_series(double *coef, const double *z, int n, hl_exact_flow *f,
                               hl_error *err)
{
    if (n < 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "negative order %d", n);
    if (f->linear) {
        linear_series(coef, z, n, f);
        return HL_OK;
    }
    return orbit_series(coef, z, n, f, err);
}

hl_status hl_exact_flow_period(double *T, const double *z, hl_exact_flow *f, hl_error *err)
{
    if (f->linear)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                            "the period is given for 1-dof orbit tables only");
    hl_exact_orbit o;
    int st = hl_exact_orbit_(&o, z, f, err);
    if (st == HL_OK)
        *T = o.T;
    return st;
}

int hl_exact_orbit_(hl_exact_orbit *o, const double *z, hl_exact_flow *f, hl_error *err)
{
    if (f->linear)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "a quadratic H has no orbit table");
    double ze[2], J[4];
    int kind = classify(ze, J, z, f);
    if (kind == POINT_NEAR_SADDLE)
        return near_saddle_error(z, err);
    if (kind == POINT_EQUILIBRIUM) {
        *o = (hl_exact_orbit){ORBIT_EQUILIBRIUM, {z[0], z[1]}, 0, equilibrium_period(z, f), 0};
        return HL_OK;
    }
    if (kind == POINT_TINY) { /* the turning point of the linearised orbit */
        double d[2] = {z[0] - ze[0], z[1] - ze[1]};
        double a = hypot(d[0], sqrt(J[1] / -J[2]) * d[1]);
        *o = (hl_exact_orbit){ORBIT_LIBRATION, {ze[0] + a, 0}, 0, equilibrium_period(ze, f),
                              2 * a};
        return HL_OK;
    }
    double th, tl, w;
    int st = orbit_time(&th, &tl, &w, z, f, err);
    if (st == HL_OK)
        *o = (hl_exact_orbit){f->kind, {f->zs[0], f->zs[1]}, f->Ls, f->T, f->size};
    return st;
}
