/* The adaptive run in Arb (--digits): hl_flow_arb with dense output at
 * t_k = T k / n, H and the observers in Arb. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "run/run_impl.h"

slong hl_run_arb_prec(double digits) { return (slong)ceil(digits * 3.3219280948873623) + 32; }

typedef struct drive_arb {
    hl_run *r;
    long k, n, every;
    slong prec;
    hl_run_arb_fn fn;
    void *arg;
    hl_run_stats *s;
    arb_ptr vals;  /* H and the observers */
    arb_t H0, d;
    hl_error *err;
    int st, user;
    double progress_next;
} drive_arb;

static int row_arb(drive_arb *d, long k, const arb_t t, arb_srcptr z)
{
    hl_run *r = d->r;
    hl_tape_eval_arb(d->vals, z, d->prec, r->obs);
    if (!arb_is_finite(d->vals))
        return hl_error_set(d->err, HL_EDOM, NULL, -1, 0,
                            "blow-up: H is not finite at output %ld, t = %.17g", k,
                            arf_get_d(arb_midref(t), ARF_RND_NEAR));
    arb_get_mid_arb(d->vals, d->vals);
    if (k == 0)
        arb_set(d->H0, d->vals);
    arb_sub(d->d, d->vals, d->H0, d->prec);
    hl_run_stats *s = d->s;
    double dH = fabs(arf_get_d(arb_midref(d->d), ARF_RND_NEAR));
    s->max_dH = fmax(s->max_dH, dH);
    s->H0 = arf_get_d(arb_midref(d->H0), ARF_RND_NEAR);
    s->H = arf_get_d(arb_midref(d->vals), ARF_RND_NEAR);
    s->steps = k;
    s->t = arf_get_d(arb_midref(t), ARF_RND_NEAR);
    for (int i = 0; i < 2 * r->N; i++)
        r->z[i] = arf_get_d(arb_midref(z + i), ARF_RND_NEAR);
    if (d->fn != NULL && (k % d->every == 0 || k == d->n)) {
        hl_run_row_arb rw = {k, t, z, d->vals, d->vals + 1};
        s->rows++;
        int u = d->fn(&rw, d->arg);
        if (u != 0) {
            d->user = u;
            return u;
        }
    }
    return hl_run_progress_(r, &d->progress_next, 1, (double)k, d->n, s->t, d->err);
}

static int arb_fn(const arb_t t, arb_srcptr z, void *arg)
{
    drive_arb *d = arg;
    long k = d->k + 1;
    int st = row_arb(d, k, t, z);
    if (st != HL_OK) {
        d->st = st;
        return st;
    }
    d->k = k;
    return 0;
}

hl_status hl_run_adaptive_arb(hl_run *r, arb_srcptr z0, double digits, const char *T, long n,
                              long every, hl_run_arb_fn fn, void *arg, hl_run_stats *stats,
                              hl_error *err)
{
    hl_run_stats local;
    hl_run_stats *s = stats != NULL ? stats : &local;
    memset(s, 0, sizeof *s);
    s->nsteps = n;
    s->sigma = s->max_err = s->err_final = NAN;
    if (!(digits >= 1) || digits > 10000)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "digits must be between 1 and 10000 (digits = %g)", digits);
    if (r->ev != NULL)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                            "events are not located by the Arb integrator (--digits) yet: "
                            "use the double one (--tol), whose crossings are located to "
                            "round-off on its steps' polynomials");
    if (n < 0 || n > 10000000)
        return hl_error_set(err, n < 0 ? HL_EINVAL : HL_ELIMIT, NULL, -1, 0,
                            "%ld outputs: between 0 and 1e7 in Arb", n);
    int st = hl_run_check_start_arb(r, z0, hl_run_arb_prec(digits), err);
    if (st != HL_OK)
        return st;
    drive_arb d;
    memset(&d, 0, sizeof d);
    d.r = r, d.n = n, d.every = every > 0 ? every : 1, d.fn = fn, d.arg = arg, d.s = s;
    d.progress_next = 1;
    d.err = err;
    d.prec = hl_run_arb_prec(digits);
    arb_t Tend, t0;
    arb_init(Tend), arb_init(t0), arb_init(d.H0), arb_init(d.d);
    d.vals = _arb_vec_init(r->nout);
    if (arb_set_str(Tend, T, d.prec) != 0 || !arb_is_finite(Tend) || arb_is_negative(Tend))
        st = hl_error_set(err, HL_EINVAL, NULL, -1, 0, "the final time '%s' is not a number >= 0",
                          T);
    hl_flow_arb *fl = NULL;
    if (st == HL_OK)
        st = hl_flow_arb_new(&fl, r->vf, digits, err);
    if (st == HL_OK)
        st = row_arb(&d, 0, t0, z0);
    if (st == HL_OK && n > 0) {
        arb_ptr ts = _arb_vec_init(n);
        for (long k = 1; k <= n; k++) { /* T k / n, rounded once */
            arb_mul_si(ts + k - 1, Tend, k, d.prec);
            arb_div_si(ts + k - 1, ts + k - 1, n, d.prec);
            arb_get_mid_arb(ts + k - 1, ts + k - 1);
        }
        st = hl_flow_arb_run(fl, t0, z0, ts, (int)n, arb_fn, &d, err);
        if (st != HL_OK && d.st != HL_OK)
            st = d.st;
        _arb_vec_clear(ts, n);
        s->ref_steps = hl_flow_arb_nsteps(fl);
    }
    hl_flow_arb_free(fl);
    _arb_vec_clear(d.vals, r->nout);
    arb_clear(Tend), arb_clear(t0), arb_clear(d.H0), arb_clear(d.d);
    s->failed = st != HL_OK && d.user == 0;
    return d.user != 0 ? d.user : st;
}
