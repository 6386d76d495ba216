/* The 1-dof exact scheme in high precision (exact.h: hl_exact_arb).
 *
 * Action-angle coordinates make a step of any length cost less than one
 * period: psi_D(z) = orbit(t(z) + (D mod T)).  In Arb the period is found
 * as twice the time from the right turning point to the left one (H is even
 * in p): the turning point by Newton on H(q, 0) = E, the half period by
 * Newton on p(tau) = 0 with p(tau) from the Arb Taylor integrator (flow.h)
 * and p' = -dH/dq at the end point.  Both start from the double estimates
 * of flow.c, so each Newton step doubles the digits: two or three steps for
 * 30-60 digits.  The step is then the Arb integrator over D mod T. */
#include <math.h>
#include <stdlib.h>

#include "base/buf.h"
#include "exact/exact_impl.h"
#include "hamlie/flow.h"

struct hl_exact_arb {
    hl_tape *vf, *Ht;    /* (dH/dp, -dH/dq) and H over (q, p) */
    hl_flow_arb *fa;
    hl_exact_flow *fd;   /* the double exact flow, for the estimates */
    double digits;
    slong prec;
    arb_t E, T;          /* the energy whose period T is known */
    int have_T;
};

int hl_exact_arb_new(hl_exact_arb **out, hl_system *sys, double digits, hl_error *err)
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
    f->digits = digits;
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
    free(f);
}

/* Has x stopped moving by dx, to 10^-(digits + 2) relative? */
static int settled(const arb_t dx, const arb_t x, const hl_exact_arb *f)
{
    double a = fabs(arf_get_d(arb_midref(dx), ARF_RND_NEAR));
    double b = fabs(arf_get_d(arb_midref(x), ARF_RND_NEAR));
    return a <= pow(10.0, -(f->digits + 2)) * fmax(b, 1.0);
}

/* Newton on H(q, 0) = E from the double turning point of the orbit through
 * zd, z rounded to double (its own energy: E rounded could put zd beyond
 * the turning point). */
static int turning_point(arb_t qt, const arb_t E, const double *zd, hl_exact_arb *f,
                         hl_error *err)
{
    double qd, Ed;
    hl_tape_eval_d(&Ed, zd, f->Ht);
    int st = hl_exact_turning_point_(&qd, zd[0], Ed, f->Ht, err);
    if (st != HL_OK)
        return st;
    arb_ptr z = _arb_vec_init(2), v = _arb_vec_init(2);
    arb_t h, dq;
    arb_init(h);
    arb_init(dq);
    arb_set_d(qt, qd);
    for (int it = 0; it < 12; it++) {
        arb_set(z, qt);
        hl_tape_eval_arb(h, z, f->prec, f->Ht);
        hl_tape_eval_arb(v, z, f->prec, f->vf); /* v[1] = -dH/dq */
        arb_sub(h, h, E, f->prec);
        arb_div(dq, h, v + 1, f->prec);       /* -(H - E)/(dH/dq) */
        arb_add(qt, qt, dq, f->prec);
        arb_get_mid_arb(qt, qt);
        if (settled(dq, qt, f))
            break;
    }
    _arb_vec_clear(z, 2);
    _arb_vec_clear(v, 2);
    arb_clear(h);
    arb_clear(dq);
    return HL_OK;
}

/* The period of the orbit of energy E, from the turning point qt: Newton on
 * p(tau) = 0 from the double half period. */
static int period(arb_t T, const arb_t qt, double Td, hl_exact_arb *f, hl_error *err)
{
    arb_ptr z = _arb_vec_init(2), v = _arb_vec_init(2);
    arb_t tau, t, dtau;
    arb_init(tau);
    arb_init(t);
    arb_init(dtau);
    arb_set_d(tau, Td / 2);
    int st = HL_OK;
    for (int it = 0; it < 12 && st == HL_OK; it++) {
        arb_set(z, qt);
        arb_zero(z + 1);
        arb_zero(t);
        if ((st = hl_flow_arb_evolve(f->fa, t, tau, z, err)) != HL_OK)
            break;
        hl_tape_eval_arb(v, z, f->prec, f->vf); /* p' = v[1] */
        arb_div(dtau, z + 1, v + 1, f->prec);
        arb_sub(tau, tau, dtau, f->prec);
        arb_get_mid_arb(tau, tau);
        if (settled(dtau, tau, f))
            break;
    }
    arb_mul_2exp_si(T, tau, 1);
    _arb_vec_clear(z, 2);
    _arb_vec_clear(v, 2);
    arb_clear(tau);
    arb_clear(t);
    arb_clear(dtau);
    return st;
}

int hl_exact_arb_period(arb_t T, arb_srcptr z, hl_exact_arb *f, hl_error *err)
{
    arb_t E, d;
    arb_init(E);
    arb_init(d);
    hl_tape_eval_arb(E, z, f->prec, f->Ht);
    arb_get_mid_arb(E, E);
    arb_sub(d, E, f->E, f->prec);
    int st = HL_OK;
    if (!f->have_T || !settled(d, E, f)) {
        double zd[2] = {arf_get_d(arb_midref(z), ARF_RND_NEAR),
                        arf_get_d(arb_midref(z + 1), ARF_RND_NEAR)},
               Td;
        arb_t qt;
        arb_init(qt);
        st = hl_exact_flow_period(&Td, zd, f->fd, err);
        if (st == HL_OK)
            st = turning_point(qt, E, zd, f, err);
        if (st == HL_OK)
            st = period(f->T, qt, Td, f, err);
        arb_clear(qt);
        f->have_T = st == HL_OK;
        arb_set(f->E, E);
    }
    if (st == HL_OK)
        arb_set(T, f->T);
    arb_clear(E);
    arb_clear(d);
    return st;
}

int hl_exact_arb_step(arb_ptr z, const arb_t dt, hl_exact_arb *f, hl_error *err)
{
    arb_t T, r, k, t;
    arb_init(T);
    arb_init(r);
    arb_init(k);
    arb_init(t);
    int st = hl_exact_arb_period(T, z, f, err);
    if (st == HL_OK) { /* r = dt - T floor(dt / T), in [0, T) */
        arb_div(k, dt, T, f->prec);
        arf_floor(arb_midref(k), arb_midref(k));
        mag_zero(arb_radref(k));
        arb_submul(r, k, T, f->prec);
        arb_add(r, r, dt, f->prec);
        arb_get_mid_arb(r, r);
        st = hl_flow_arb_evolve(f->fa, t, r, z, err);
    }
    arb_clear(T);
    arb_clear(r);
    arb_clear(k);
    arb_clear(t);
    return st;
}
