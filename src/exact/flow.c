/* The numeric exact flow (see exact.h): the public object, and the step on
 * a 1-dof orbit table — where a point is on the table (its time, to
 * double-double), the step as a time shift along it, and its series in D.
 * The table itself is built in table.c; a quadratic H's flow, the matrix
 * exponential, is in linear.c. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "exact/exact_impl.h"

static double H_at(hl_exact_flow *f, const double *z)
{
    double h;
    hl_tape_eval_d(&h, z, f->Ht);
    return h;
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
        hl_exact_poly_eval_(w, dw, ck, s);
        double n2 = dw[0] * dw[0] + dw[1] * dw[1];
        double ds = ((w[0] - q) * dw[0] + (w[1] - p) * dw[1]) / n2;
        s -= ds;
        if (!(fabs(ds) > 1e-17 * f->hs))
            break;
    }
    hl_exact_poly_eval_(w, dw, ck, s);
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
        int st = hl_exact_table_build_(f, z, err);
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
    hl_exact_poly_eval_(z, NULL, c, s);
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
    int st = hl_exact_linear_matrix_(f->Aaug, &quad, sys, err);
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
        return hl_exact_linear_step_(z, dt, f);
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
        hl_exact_linear_series_(coef, z, n, f);
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
