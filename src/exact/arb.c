/* The 1-dof exact scheme in high precision (exact.h: hl_exact_arb).
 *
 * Action-angle coordinates make a step of any length cost less than one
 * period: psi_D(z) = orbit(t(z) + (D mod T)), and on a rotation q advances
 * by 2 pi each period.  The double exact flow (flow.c) says what the orbit
 * is — a libration, its turning point; a rotation; an equilibrium — and
 * estimates its period; Newton's method in Arb then refines, each step
 * doubling the digits: for a libration the turning point (H(q, 0) = E) and
 * the half period (p(tau) = 0, H being even in p), for a rotation the
 * period (q(tau) = q0 + 2 pi), with the state at tau from the Arb Taylor
 * integrator (flow.h).  The step is then that integrator over D mod T.
 *
 * Small orbits: E - H(q, 0) cancels about 2 log2(|q| / size) bits, and the
 * integrator's tolerance is absolute below |z| = 1, so both get the digits
 * the orbit's size takes away (orbit_digits). */
#include <math.h>
#include <stdlib.h>

#include "base/buf.h"
#include "exact/exact_impl.h"
#include "hamlie/flow.h"

struct hl_exact_arb {
    hl_tape *vf, *Ht;  /* (dH/dp, -dH/dq) and H over (q, p) */
    hl_flow_arb *fa;   /* at fa_digits, for the orbit of the period below */
    hl_exact_flow *fd; /* the double exact flow, for the estimates */
    double digits, fa_digits;
    slong prec;
    /* the orbit whose period T is known: its energy E (to escale), the
     * double flow's start of it (o.zs) and q's advance a period o.Ls
     * (rotations: two at one energy go opposite ways), kind, and Ls in Arb */
    arb_t E, T, Ls;
    double escale, zs_key, Ls_key;
    int have_T, kind;
};

hl_status hl_exact_arb_new(hl_exact_arb **out, hl_system *sys, double digits, hl_error *err)
{
    *out = NULL;
    if (!(digits >= 16 && digits <= 1000))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "digits must be from 16 to 1000 (got %g)", digits);
    if (hl_system_ndof(sys) != 1)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                            "the exact scheme in high precision is for 1 dof");
    hl_exact_arb *f = hl_xcalloc(1, sizeof *f);
    arb_init(f->E);
    arb_init(f->T);
    arb_init(f->Ls);
    f->digits = f->fa_digits = digits;
    const char *q = hl_system_coord(sys, 0), *p = hl_system_momentum(sys, 0);
    const char *names[2] = {q, p};
    const hl_expr *H = hl_system_H_expr(sys);
    int st = hl_exact_flow_new(&f->fd, sys, err);
    if (st == HL_OK && hl_exact_flow_is_linear(f->fd))
        st = hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                          "H is quadratic: its exact scheme is a closed form (hamlie exact)");
    if (st == HL_OK)
        st = hl_tape_hamiltonian(&f->vf, hl_system_pool(sys), H, 1, &q, &p, 0, NULL, NULL, err);
    if (st == HL_OK)
        st = hl_tape_new(&f->Ht, &H, 1, names, 2, err);
    if (st == HL_OK)
        st = hl_flow_arb_new(&f->fa, f->vf, digits, err);
    if (st != HL_OK) {
        hl_exact_arb_free(f);
        return st;
    }
    f->prec = hl_flow_arb_prec(f->fa);
    *out = f;
    return HL_OK;
}

void hl_exact_arb_free(hl_exact_arb *f)
{
    if (f == NULL)
        return;
    hl_tape_free(f->vf);
    hl_tape_free(f->Ht);
    hl_flow_arb_free(f->fa);
    hl_exact_flow_free(f->fd);
    arb_clear(f->E);
    arb_clear(f->T);
    arb_clear(f->Ls);
    free(f);
}

static double mid_d(const arb_t x)
{
    return arf_get_d(arb_midref(x), ARF_RND_NEAR);
}

/* Has x stopped moving by dx, to 10^-(digits + 2) relative to scale? */
static int settled(const arb_t dx, double scale, const hl_exact_arb *f)
{
    return fabs(mid_d(dx)) <= pow(10.0, -(f->fa_digits + 2)) * scale;
}

/* The integrator at digits plus those the orbit's size takes away from
 * an absolute tolerance (flow.h: absolute below |z| = 1). */
static int orbit_digits(hl_exact_arb *f, const hl_exact_orbit *o, const double *zd,
                        hl_error *err)
{
    double zmax = fmax(fabs(zd[0]) + o->size, fabs(zd[1]) + o->size);
    double d = f->digits + (o->size > 0 ? fmax(0, log10(fmax(1, zmax) / o->size)) : 0);
    d = fmin(ceil(d), 1000);
    if (d == f->fa_digits)
        return HL_OK;
    hl_flow_arb_free(f->fa);
    f->fa = NULL;
    int st = hl_flow_arb_new(&f->fa, f->vf, d, err);
    f->fa_digits = d;
    f->prec = st == HL_OK ? hl_flow_arb_prec(f->fa) : f->prec;
    return st;
}

/* The precision for energies: E - H(q, 0) cancels twice the digits the
 * orbit's size took (orbit_digits), so those are added once more. */
static slong energy_prec(const hl_exact_arb *f)
{
    return f->prec + (slong)ceil((f->fa_digits - f->digits) * log2(10.0));
}

/* Newton on H(q, 0) = E from the double turning point qd. */
static void turning_point(arb_t qt, const arb_t E, double qd, double scale, hl_exact_arb *f)
{
    hl_exact_turning_point_arb_(qt, E, qd, scale, f->fa_digits, energy_prec(f), f->Ht, f->vf);
}

/* Newton on the event at tau from z0: p(tau) = 0 (libration from a
 * turning point: tau is half the period) or q(tau) = q0 + Ls (rotation:
 * tau is the period), from the double estimate tau0. */
static int event_time(arb_t tau, arb_srcptr z0, double tau0, double scale, hl_exact_arb *f,
                      hl_error *err)
{
    int rot = f->kind == ORBIT_ROTATION, v = rot ? 0 : 1;
    arb_ptr z = _arb_vec_init(2), dz = _arb_vec_init(2);
    arb_t t, dtau;
    arb_init(t);
    arb_init(dtau);
    arb_set_d(tau, tau0);
    int st = HL_OK;
    for (int it = 0; it < 12 && st == HL_OK; it++) {
        _arb_vec_set(z, z0, 2);
        arb_zero(t);
        if ((st = hl_flow_arb_evolve(f->fa, t, tau, z, err)) != HL_OK)
            break;
        hl_tape_eval_arb(dz, z, f->prec, f->vf); /* (q', p') */
        if (rot) {
            arb_sub(z, z, z0, f->prec);
            arb_sub(z, z, f->Ls, f->prec);
        }
        arb_div(dtau, z + v, dz + v, f->prec);
        arb_sub(tau, tau, dtau, f->prec);
        arb_get_mid_arb(tau, tau);
        if (settled(dtau, scale, f))
            break;
    }
    _arb_vec_clear(z, 2);
    _arb_vec_clear(dz, 2);
    arb_clear(t);
    arb_clear(dtau);
    return st;
}

/* The period at an equilibrium: the limit of small orbits, 2 pi / omega
 * with omega^2 = H_pp H_qq - H_pq H_qp (+inf if not positive). */
static void equilibrium_period(arb_t T, arb_srcptr z, hl_exact_arb *f)
{
    arb_ptr in = _arb_vec_init(4), dq = _arb_vec_init(4), dp = _arb_vec_init(4);
    arb_t w2;
    arb_init(w2);
    arb_set(in + 0, z), arb_one(in + 1), arb_set(in + 2, z + 1);
    hl_tape_taylor_arb(dq, in, 1, f->prec, f->vf); /* d/dq (H_p, -H_q) */
    arb_zero(in + 1), arb_one(in + 3);
    hl_tape_taylor_arb(dp, in, 1, f->prec, f->vf); /* d/dp */
    arb_mul(w2, dp + 1, dq + 3, f->prec);
    arb_neg(w2, w2);
    arb_addmul(w2, dq + 1, dp + 3, f->prec);
    if (arb_is_positive(w2)) {
        arb_sqrt(w2, w2, f->prec);
        arb_const_pi(T, f->prec);
        arb_mul_2exp_si(T, T, 1);
        arb_div(T, T, w2, f->prec);
    } else
        arb_pos_inf(T);
    _arb_vec_clear(in, 4), _arb_vec_clear(dq, 4), _arb_vec_clear(dp, 4);
    arb_clear(w2);
}

static int at_equilibrium(arb_srcptr z, hl_exact_arb *f)
{
    arb_ptr v = _arb_vec_init(2);
    hl_tape_eval_arb(v, z, f->prec, f->vf);
    int yes = arb_is_zero(v) && arb_is_zero(v + 1);
    _arb_vec_clear(v, 2);
    return yes;
}

/* The period of the orbit through z (energy E), from the double flow's
 * orbit o. */
static int orbit_period(arb_srcptr z, const arb_t E, const hl_exact_orbit *o, hl_exact_arb *f,
                        hl_error *err)
{
    f->kind = o->kind;
    if (o->kind == ORBIT_EQUILIBRIUM) {
        if (!at_equilibrium(z, f))
            return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                                "the point is an equilibrium in double precision only");
        equilibrium_period(f->T, z, f);
        return HL_OK;
    }
    int st = HL_OK;
    arb_ptr zs = _arb_vec_init(2);
    arb_t tau;
    arb_init(tau);
    if (o->kind == ORBIT_ROTATION) {
        arb_const_pi(f->Ls, f->prec);
        arb_mul_2exp_si(f->Ls, f->Ls, 1);
        if (o->Ls < 0)
            arb_neg(f->Ls, f->Ls);
        _arb_vec_set(zs, z, 2);
        st = event_time(f->T, zs, o->T, o->T, f, err);
    } else {
        turning_point(zs, E, o->zs[0], o->size, f);
        st = event_time(tau, zs, o->T / 2, o->T, f, err);
        arb_mul_2exp_si(f->T, tau, 1);
    }
    _arb_vec_clear(zs, 2);
    arb_clear(tau);
    return st;
}

hl_status hl_exact_arb_period(arb_t T, arb_srcptr z, hl_exact_arb *f, hl_error *err)
{
    double zd[2] = {mid_d(z), mid_d(z + 1)};
    hl_exact_orbit o;
    int st = hl_exact_orbit_(&o, zd, f->fd, err);
    if (st == HL_OK && o.kind != ORBIT_EQUILIBRIUM)
        st = orbit_digits(f, &o, zd, err);
    if (st != HL_OK)
        return st;
    arb_t E, d;
    arb_init(E);
    arb_init(d);
    hl_tape_eval_arb(E, z, energy_prec(f), f->Ht);
    arb_get_mid_arb(E, E);
    arb_sub(d, E, f->E, energy_prec(f));
    /* the orbit's energy scale: |grad H| times its size */
    double v[2];
    hl_exact_flow_gradient_(v, zd, f->fd);
    double escale = fmax(fabs(v[0]), fabs(v[1])) * o.size;
    if (!f->have_T || f->kind != o.kind || o.kind == ORBIT_EQUILIBRIUM ||
        f->zs_key != o.zs[0] || f->Ls_key != o.Ls || !settled(d, fmin(escale, f->escale), f)) {
        f->have_T = 0;
        st = orbit_period(z, E, &o, f, err);
        f->have_T = st == HL_OK;
        f->escale = escale;
        f->zs_key = o.zs[0];
        f->Ls_key = o.Ls;
        arb_set(f->E, E);
    }
    if (st == HL_OK)
        arb_set(T, f->T);
    arb_clear(E);
    arb_clear(d);
    return st;
}

hl_status hl_exact_arb_step(arb_ptr z, const arb_t dt, hl_exact_arb *f, hl_error *err)
{
    arb_t T, r, k, t;
    arb_init(T);
    arb_init(r);
    arb_init(k);
    arb_init(t);
    int st = hl_exact_arb_period(T, z, f, err);
    if (st == HL_OK && f->kind != ORBIT_EQUILIBRIUM) { /* r = dt - T floor(dt / T), in [0, T) */
        arb_div(k, dt, T, f->prec);
        arf_floor(arb_midref(k), arb_midref(k));
        mag_zero(arb_radref(k));
        arb_submul(r, k, T, f->prec);
        arb_add(r, r, dt, f->prec);
        arb_get_mid_arb(r, r);
        st = hl_flow_arb_evolve(f->fa, t, r, z, err);
        if (st == HL_OK && f->kind == ORBIT_ROTATION) { /* k laps */
            arb_addmul(z, k, f->Ls, f->prec);
            arb_get_mid_arb(z, z);
        }
    }
    arb_clear(T);
    arb_clear(r);
    arb_clear(k);
    arb_clear(t);
    return st;
}
