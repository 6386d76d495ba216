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
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <arb_mat.h>

#include "hamlie/exact.h"
#include "hamlie/tape.h"
#include "hamlie/flow.h"
#include "base/buf.h"
#include "exact/exact_impl.h"
#include "flow/flow_impl.h"

#define ORD HL_EXACT_SERIES_DEGREE /* Taylor order of the table polynomials (20) */
#define NC (ORD + 1)

struct hl_exact_flow {
    int N, linear;
    /* linear: augmented (2N+1)^2 matrix [[A, b], [0, 0]] and its exp at dt */
    double *Aaug, *E, Edt;
    int have_E;
    /* 1 dof */
    hl_tape *vf, *Ht;
    int have_tab;
    double Etab, T, Tlo, hs, hslo; /* period T + Tlo, sample spacing hs + hslo */
    /* the last output and its time since the turning point (double-double):
     * stepping again from it needs no search, and the time adds exactly */
    double last[2], lth, ltl;
    int have_last;
    int M;
    double *C; /* M samples x 2 variables x NC coefficients */
};

static double H_tape(hl_tape *Ht, const double *z)
{
    double h;
    hl_tape_eval_d(&h, z, Ht);
    return h;
}

static double H_at(hl_exact_flow *f, const double *z)
{
    return H_tape(f->Ht, z);
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

/* ---- 1 dof: orbit table ------------------------------------------------ */

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

/* The step of the Taylor integrator's rule (flow/flow_impl.h) for the
 * coefficients c at z, shortened by its defect where the rule asks. */
static double jz_step(const double *c, const double *z, hl_exact_flow *f)
{
    const int lo = hl_flow_window_lo(ORD);
    double eps = 1e-16 * fmax(1.0, fmax(fabs(z[0]), fabs(z[1]))), win[HL_FLOW_WINDOW];
    for (int k = lo; k <= ORD; k++)
        win[k - lo] = fmax(fabs(c[k]), fabs(c[NC + k]));
    int check;
    double h = hl_flow_step_for(&check, eps, log(eps), win, ORD);
    if (h == INFINITY)
        h = 1; /* no scale from the coefficients: the defect finds one */
    while (check && h > 1e-300) {
        double zh[2], dz[2], fz[2];
        poly_eval(zh, dz, c, h);
        hl_tape_eval_d(fz, zh, f->vf);
        double d0 = fabs(dz[0] - fz[0]), d1 = fabs(dz[1] - fz[1]);
        double next = hl_flow_shrink(h, d0 > d1 || isnan(d0) ? d0 : d1, eps, ORD);
        if (next == 0)
            break;
        h = next;
    }
    return h;
}

int hl_exact_turning_point_(double *qt, double q0, double E, hl_tape *Ht, hl_error *err)
{
    double a = q0, step = 1e-3 * (1 + fabs(q0)), b;
    double z[2] = {q0, 0};
    if (H_tape(Ht, z) > E) /* q0 itself beyond: p != 0 means V(q0) < E */
        return hl_error_set(err, HL_EDOM, NULL, -1, 0, "no turning point: H(q,0) > E at q");
    for (;;) {
        b = a + step;
        z[0] = b;
        double h = H_tape(Ht, z);
        if (!isfinite(h))
            return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                                "H is not finite at q = %g before the turning point", b);
        if (h > E)
            break;
        a = b;
        step *= 2;
        if (fabs(b - q0) > 1e8)
            return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                                "unbounded orbit: H(q,0) does not exceed E = %.17g for q > %g "
                                "(an orbit over the barrier, or on a separatrix if E is the "
                                "barrier's top)",
                                E, q0);
    }
    for (int i = 0; i < 200 && b - a > 0; i++) {
        double c = 0.5 * (a + b);
        if (c <= a || c >= b)
            break;
        z[0] = c;
        if (H_tape(Ht, z) > E)
            b = c;
        else
            a = c;
    }
    *qt = a;
    return HL_OK;
}

/* The period in double-double: one Newton step on p(tau) = 0 at the half
 * period tau, with p(tau) from the Arb integrator at 32 digits.  Why: an
 * error of one ulp in T becomes a phase error of t/T ulps, 1e-13 after a
 * thousand time units; the table itself is only read modulo T. */
static int refine_period(double *T, double *Tlo, double qt, double half, hl_exact_flow *f,
                         hl_error *err)
{
    hl_flow_arb *fa = NULL;
    int st = hl_flow_arb_new(&fa, f->vf, 32, err);
    if (st != HL_OK)
        return st;
    slong prec = hl_flow_arb_prec(fa);
    arb_t t, t1, tau;
    arb_ptr z = _arb_vec_init(2);
    arb_init(t);
    arb_init(t1);
    arb_init(tau);
    arb_set_d(t1, half);
    arb_set_d(z + 0, qt);
    st = hl_flow_arb_evolve(fa, t, t1, z, err);
    if (st == HL_OK) {
        double zd[2] = {arf_get_d(arb_midref(z + 0), ARF_RND_NEAR), 0}, v[2];
        hl_tape_eval_d(v, zd, f->vf);
        if (!(v[1] != 0) || !isfinite(v[1]))
            st = hl_error_set(err, HL_EDOM, NULL, -1, 0,
                              "separatrix: no force at the left turning point");
        else {
            arb_div_si(tau, z + 1, 1, prec);
            arb_set_d(t, v[1]);
            arb_div(tau, z + 1, t, prec); /* p / p' */
            arb_sub(tau, t1, tau, prec);
            arb_mul_2exp_si(tau, tau, 1);
            *T = arf_get_d(arb_midref(tau), ARF_RND_NEAR);
            arb_sub_ui(t, tau, 0, prec);
            arb_set_d(t1, *T);
            arb_sub(t, tau, t1, prec);
            *Tlo = arf_get_d(arb_midref(t), ARF_RND_NEAR);
        }
    }
    _arb_vec_clear(z, 2);
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

/* zs[2k], zs[2k+1] = z(k T / M) for k = 0..M/2, from the turning point. */
static int sample_half(double *zs, double qt, double T, double Tlo, int M, hl_exact_flow *f,
                       hl_error *err)
{
    hl_flow_arb *fa = NULL;
    int st = hl_flow_arb_new(&fa, f->vf, 24, err);
    if (st != HL_OK)
        return st;
    slong prec = hl_flow_arb_prec(fa);
    int n = M / 2 + 1;
    arb_ptr ts = _arb_vec_init(n), z0 = _arb_vec_init(2);
    arb_t h, lo, t0;
    arb_init(h);
    arb_init(lo);
    arb_init(t0);
    arb_set_d(h, T);
    arb_set_d(lo, Tlo);
    arb_add(h, h, lo, prec);
    arb_div_si(h, h, M, prec);
    for (int k = 0; k < n; k++)
        arb_mul_si(ts + k, h, k, prec);
    arb_set_d(z0 + 0, qt);
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

static int build_table(hl_exact_flow *f, const double *z0, hl_error *err)
{
    double E = H_at(f, z0), qt = 0, z[2], c[2 * NC], dz[2];
    int st = hl_exact_turning_point_(&qt, z0[0], E, f->Ht, err);
    if (st != HL_OK)
        return st;
    z[0] = qt;
    z[1] = 0;
    st = taylor_at(c, z, f, err);
    if (st != HL_OK)
        return st;
    /* Separatrix: the force at the turning point vanishes. */
    if (fabs(c[NC + 1]) < 1e-12 * fmax(1.0, fabs(qt)))
        return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                            "separatrix: the force vanishes at the turning point q = %.17g "
                            "(infinite period)",
                            qt);
    if (c[NC + 1] > 0)
        return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                            "not a bounded orbit: the force at the turning point pushes outwards");
    /* Half period: integrate until p turns non-negative. */
    double t = 0, tc = 0, hmin = INFINITY;
    long nsteps = 0;
    for (;;) {
        double h = jz_step(c, z, f);
        if (!(h > 0) || ++nsteps > 10000000L)
            return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                                "period not found (separatrix or unbounded orbit?)");
        hmin = fmin(hmin, h);
        double zn[2];
        poly_eval(zn, NULL, c, h);
        if (nsteps > 1 && zn[1] >= 0) {
            /* root of p(s) in (0, h] by Newton from the secant guess */
            double s = h * (-z[1]) / (zn[1] - z[1]);
            for (int i = 0; i < 50; i++) {
                poly_eval(zn, dz, c, s);
                double ds = zn[1] / dz[1];
                s -= ds;
                if (fabs(ds) <= 1e-18 * h)
                    break;
            }
            /* t + tc + s, Kahan-compensated */
            double y = s - tc;
            t = t + y;
            break;
        }
        double y = h - tc, tn = t + y;
        tc = (tn - t) - y;
        t = tn;
        z[0] = zn[0];
        z[1] = zn[1];
        if (!isfinite(z[0]) || !isfinite(z[1]))
            return hl_error_set(err, HL_EDOM, NULL, -1, 0, "orbit left the finite range");
        st = taylor_at(c, z, f, err);
        if (st != HL_OK)
            return st;
    }
    double T = 2 * t, Tlo = 0;
    st = refine_period(&T, &Tlo, qt, t, f, err);
    if (st != HL_OK)
        return st;
    int M = (int)ceil(2 * T / hmin);
    if (M < 8)
        M = 8;
    M += M % 2;
    double hs = T / M;
    free(f->C);
    f->C = hl_xmalloc(sizeof(double) * M * 2 * NC);
    /* first half from the Arb integrator (so that the samples are right to
     * the last bit: errors in them are not averaged out), second half mirrored */
    double *zs = hl_xmalloc(sizeof(double) * 2 * (M / 2 + 1));
    st = sample_half(zs, qt, T, Tlo, M, f, err);
    for (int k = 0; k <= M / 2 && st == HL_OK; k++) {
        double zk[2] = {zs[2 * k], k == 0 || k == M / 2 ? 0 : zs[2 * k + 1]};
        st = taylor_at(f->C + (size_t)k * 2 * NC, zk, f, err);
        if (st == HL_OK && k > 0 && k < M / 2) {
            zk[1] = -zk[1];
            st = taylor_at(f->C + (size_t)(M - k) * 2 * NC, zk, f, err);
        }
    }
    free(zs);
    if (st != HL_OK)
        return st;
    f->Etab = E;
    f->T = T;
    f->Tlo = Tlo;
    f->hs = hs;
    f->hslo = (fma(-hs, M, T) + Tlo) / M;
    f->have_last = 0;
    f->M = M;
    f->have_tab = 1;
    return HL_OK;
}

/* Time since the turning point of the table point nearest z. */
static double locate(double *lo, const double *z, hl_exact_flow *f)
{
    int best = 0;
    double bd = INFINITY;
    for (int k = 0; k < f->M; k++) {
        const double *ck = f->C + (size_t)k * 2 * NC;
        double d = hypot(ck[0] - z[0], ck[NC] - z[1]);
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
        double ds = ((w[0] - z[0]) * dw[0] + (w[1] - z[1]) * dw[1]) / n2;
        s -= ds;
        if (fabs(ds) <= 1e-17 * f->hs)
            break;
    }
    /* best * (hs + hslo) + s in double-double: the rounding of t alone
     * would bias every step by up to an ulp of the period */
    double ph = best * f->hs, pe = fma(best, f->hs, -ph) + best * f->hslo;
    double x = ph + s, bv = x - ph;
    *lo = (ph - (x - bv)) + (s - bv) + pe;
    return x;
}

/* dt mod (T + Tlo) in [0, T + Tlo), reduced in double-double (for large dt
 * the rounding of t + dt alone would cost dt * 1e-16). */
static double reduce(double dt, const hl_exact_flow *f)
{
    double k = floor(dt / f->T);
    double r = fma(-k, f->T, dt) - k * f->Tlo;
    while (r >= f->T)
        r -= f->T;
    while (r < 0)
        r += f->T;
    return r;
}

static void two_sum(double *s, double *e, double a, double b)
{
    double x = a + b, bv = x - a;
    *e = (a - (x - bv)) + (b - bv);
    *s = x;
}

/* z's time since the turning point, th + tl in [0, T + Tlo) (double-double),
 * building the table for z's energy if need be. */
static int orbit_time(double *th, double *tl, const double *z, hl_exact_flow *f,
                      hl_error *err)
{
    double E = H_at(f, z);
    if (!isfinite(E))
        return hl_error_set(err, HL_EDOM, NULL, -1, 0, "H is not finite at the state");
    if (!f->have_tab || fabs(E - f->Etab) > 64 * 2.2e-16 * fmax(1.0, fabs(E))) {
        int st = build_table(f, z, err);
        if (st != HL_OK)
            return st;
    }
    *tl = 0;
    if (f->have_last && z[0] == f->last[0] && z[1] == f->last[1]) {
        *th = f->lth;
        *tl = f->ltl;
        return HL_OK;
    }
    *th = locate(tl, z, f);
    if (*th < 0)
        two_sum(th, tl, *th + f->T, *tl + f->Tlo);
    if (*th >= f->T)
        two_sum(th, tl, *th - f->T, *tl - f->Tlo);
    return HL_OK;
}

/* The table piece for time uh + ul in [0, T + Tlo), and the offset in it. */
static const double *piece(double *s, double uh, double ul, const hl_exact_flow *f)
{
    long k = lround(uh / f->hs);
    *s = fma(-(double)k, f->hs, uh) - k * f->hslo + ul;
    return f->C + (size_t)(k % f->M) * 2 * NC;
}

static int orbit_step(double *z, double dt, hl_exact_flow *f, hl_error *err)
{
    double th, tl;
    int st = orbit_time(&th, &tl, z, f, err);
    if (st != HL_OK)
        return st;
    /* u = t + (dt mod period), then once more mod period, in double-double */
    double uh, ul;
    two_sum(&uh, &ul, th, reduce(dt, f));
    ul += tl;
    two_sum(&uh, &ul, uh, ul);
    if (uh > f->T || (uh == f->T && ul >= f->Tlo)) {
        uh -= f->T; /* exact: T <= uh < 2T */
        ul -= f->Tlo;
        two_sum(&uh, &ul, uh, ul);
    }
    if (uh < 0) {
        two_sum(&uh, &ul, uh + f->T, ul + f->Tlo);
    }
    double s;
    const double *c = piece(&s, uh, ul, f);
    poly_eval(z, NULL, c, s);
    f->last[0] = z[0];
    f->last[1] = z[1];
    f->lth = uh;
    f->ltl = ul;
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
    double th, tl, s;
    int st = orbit_time(&th, &tl, z, f, err);
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
    return HL_OK;
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

/* ---- public -------------------------------------------------------------- */

int hl_exact_flow_new(hl_exact_flow **out, hl_system *sys, hl_error *err)
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

int hl_exact_flow_step(double *z, double dt, void *flow, hl_error *err)
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

int hl_exact_flow_series(double *coef, const double *z, int n, hl_exact_flow *f, hl_error *err)
{
    if (n < 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "negative order %d", n);
    if (f->linear) {
        linear_series(coef, z, n, f);
        return HL_OK;
    }
    return orbit_series(coef, z, n, f, err);
}

int hl_exact_flow_period(double *T, const double *z, hl_exact_flow *f, hl_error *err)
{
    if (f->linear)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                            "the period is given for 1-dof orbit tables only");
    double E = H_at(f, z);
    if (!f->have_tab || fabs(E - f->Etab) > 64 * 2.2e-16 * fmax(1.0, fabs(E))) {
        int st = build_table(f, z, err);
        if (st != HL_OK)
            return st;
    }
    *T = f->T;
    return HL_OK;
}
