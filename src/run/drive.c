/* The drivers: a fixed-step run against the dense output of the Taylor
 * integrator, the adaptive run, observed orders. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "run/run_impl.h"

/* Reference times go to the flow in chunks, so memory stays bounded. */
#define CHUNK 65536

/* Steps from which H and the observers are compiled to machine code (a
 * compilation costs 10-20 ms; the interpreter about 30 ns per evaluation
 * more for a small tape). */
#define JIT_MIN_STEPS 200000

typedef struct drive {
    hl_run *r;
    double dt;
    long n, every, k;        /* steps asked, row spacing, last step done */
    hl_run_fn fn;
    void *arg;
    hl_run_stats *s;
    hl_error *err;
    int st;                  /* status of a failure inside the callback */
    int user;                /* the callback's own non-zero return */
} drive;

static void stats_start(hl_run_stats *s, long n)
{
    memset(s, 0, sizeof *s);
    s->nsteps = n;
    s->sigma = s->max_err = s->err_final = NAN;
}

/* Evaluate H and observers at the current state, update the statistics,
 * deliver the row if it is due.  ref: the reference state or NULL. */
static int row(drive *d, long k, const double *ref)
{
    hl_run *r = d->r;
    hl_run_stats *s = d->s;
    int n2 = 2 * r->N;
    hl_tape_eval_d(r->vals, r->z, r->obs);
    double t = (double)k * d->dt, sigma = NAN;
    if (!isfinite(r->vals[0]))
        return hl_error_set(d->err, HL_EDOM, NULL, -1, 0,
                            "blow-up: H is not finite at step %ld, t = %.17g", k, t);
    if (ref != NULL) {
        sigma = 0;
        for (int i = 0; i < n2; i++)
            sigma += (r->z[i] - ref[i]) * (r->z[i] - ref[i]);
        double e = sqrt(sigma);
        s->max_err = k == 0 ? e : fmax(s->max_err, e);
        s->err_final = e;
    }
    if (k == 0)
        s->H0 = r->vals[0];
    s->H = r->vals[0];
    s->max_dH = fmax(s->max_dH, fabs(r->vals[0] - s->H0));
    s->sigma = sigma;
    s->steps = k;
    s->t = t;
    if (d->fn == NULL || !(k % d->every == 0 || k == d->n))
        return HL_OK;
    hl_run_row rw = {k, t, r->z, r->vals[0], r->vals + 1, sigma, ref};
    s->rows++;
    int u = d->fn(&rw, d->arg);
    if (u != 0) {
        d->user = u;
        return u;
    }
    return HL_OK;
}

/* A caller's stepper is not trusted to check its result: a value that is
 * not finite is a blow-up, as for the scheme stepper. */
static int all_finite(const double *z, int n, drive *d, long k, double t)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(z[i]))
            return hl_error_set(d->err, HL_EDOM, NULL, -1, 0,
                                "blow-up: step %ld (t = %.17g, D = %g): the next point is not "
                                "finite",
                                k, t, d->dt);
    return HL_OK;
}

/* Step k-1 -> k of the scheme. */
static int advance(drive *d, long k)
{
    double t = (double)(k - 1) * d->dt;
    if (d->r->step != NULL) {
        hl_run *r = d->r;
        size_t bytes = (size_t)(2 * r->N) * sizeof *r->z;
        memcpy(r->zs, r->z, bytes);
        int st = r->step(r->z, d->dt, r->step_arg, d->err);
        if (st != HL_OK && d->err != NULL)
            hl_error_prefix(d->err, "step %ld (t = %.17g, D = %g)", k, t, d->dt);
        if (st == HL_OK)
            st = all_finite(r->z, 2 * r->N, d, k, t);
        if (st != HL_OK) /* a failed step leaves the state as it was */
            memcpy(r->z, r->zs, bytes);
        return st;
    }
    int st = hl_scheme_step(d->r->stepper, d->r->z, d->dt, t, d->err);
    if (st != HL_OK) {
        if (d->err != NULL && st == HL_EDOM)
            hl_error_prefix(d->err, "blow-up"); /* the message names step and time */
        return st;
    }
    return HL_OK;
}

static int ref_fn(double t, const double *z, void *arg)
{
    drive *d = arg;
    hl_run *r = d->r;
    long k = d->k + 1;
    memcpy(r->ref, z, (size_t)(2 * r->N) * sizeof *z);
    int st = advance(d, k);
    if (st == HL_OK)
        st = row(d, k, z);
    if (st != HL_OK) {
        d->st = st;
        return st;
    }
    d->k = k;
    return 0;
}

static int fixed_ref(drive *d, hl_error *err)
{
    hl_run *r = d->r;
    hl_flow *fl = NULL;
    int st = hl_flow_new(&fl, r->vf, r->ref_tol, r->ref_tol, err);
    if (st != HL_OK)
        return st;
    long cap = d->n < CHUNK ? d->n : CHUNK;
    double *ts = hl_xmalloc((size_t)(cap > 0 ? cap : 1) * sizeof *ts);
    double *zr = hl_xmalloc((size_t)(2 * r->N) * sizeof *zr);
    memcpy(zr, r->ref, (size_t)(2 * r->N) * sizeof *zr);
    while (st == HL_OK && d->k < d->n) {
        long k0 = d->k, m = d->n - k0 < cap ? d->n - k0 : cap;
        for (long i = 0; i < m; i++)
            ts[i] = (double)(k0 + 1 + i) * d->dt;
        hl_error ferr;
        hl_error_clear(&ferr);
        d->st = HL_OK;
        st = hl_flow_run(fl, (double)k0 * d->dt, zr, ts, (int)m, ref_fn, d, &ferr);
        if (st != HL_OK && d->st == HL_OK && d->user == 0) {
            /* the reference itself failed */
            if (err != NULL) {
                *err = ferr;
                hl_error_prefix(err, "the reference (Taylor integrator) failed");
            }
        } else if (d->st != HL_OK)
            st = d->st;
        memcpy(zr, r->ref, (size_t)(2 * r->N) * sizeof *zr);
    }
    d->s->ref_steps = hl_flow_nsteps(fl);
    free(ts), free(zr);
    hl_flow_free(fl);
    return st;
}

static int start(drive *d, hl_run *r, const double *z0, double dt, double t, long every,
                 hl_run_fn fn, void *arg, hl_run_stats *s, hl_error *err)
{
    memset(d, 0, sizeof *d);
    d->r = r, d->dt = dt, d->fn = fn, d->arg = arg, d->s = s, d->err = err;
    d->every = every > 0 ? every : 1;
    int st = hl_run_nsteps(&d->n, dt, t, err);
    if (st == HL_OK)
        st = hl_run_compile_(r, err);
    if (st != HL_OK)
        return st;
    stats_start(s, d->n);
    memcpy(r->z, z0, (size_t)(2 * r->N) * sizeof *z0);
    memcpy(r->ref, z0, (size_t)(2 * r->N) * sizeof *z0);
    return HL_OK;
}

int hl_run_fixed(hl_run *r, const double *z0, double dt, double t, long every,
                 hl_run_fn fn, void *arg, hl_run_stats *stats, hl_error *err)
{
    hl_run_stats local;
    hl_run_stats *s = stats != NULL ? stats : &local;
    drive d;
    if (r->stepper == NULL && r->step == NULL)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "this run has no scheme");
    int st = start(&d, r, z0, dt, t, every, fn, arg, s, err);
    if (st != HL_OK)
        return st;
    /* a fresh stepper for each run: its step count (in its messages)
     * starts at 1 */
    if (r->stepped && r->stepper != NULL) {
        hl_scheme_stepper *fresh = NULL;
        if ((st = hl_scheme_stepper_new(&fresh, r->scheme, err)) != HL_OK)
            return st;
        hl_scheme_stepper_free(r->stepper);
        r->stepper = fresh;
    }
    r->stepped = 1;
    /* H and the observers are evaluated at every step: for long runs
     * machine code (same results bit for bit) pays for its compilation */
    if (r->jit && d.n >= JIT_MIN_STEPS && !hl_tape_jit_active(r->obs) &&
        hl_tape_jit_available())
        hl_tape_jit(r->obs, NULL); /* on failure the interpreter goes on */
    if (r->jit && r->stepper != NULL)
        hl_scheme_stepper_jit(r->stepper, d.n);
    st = row(&d, 0, r->ref_on ? z0 : NULL);
    if (st == HL_OK && r->ref_on)
        st = fixed_ref(&d, err);
    else
        for (long k = 1; st == HL_OK && k <= d.n; k++)
            if ((st = advance(&d, k)) == HL_OK)
                st = row(&d, k, NULL);
    s->failed = st != HL_OK && d.user == 0;
    return d.user != 0 ? d.user : st;
}

/* ---- the adaptive run --------------------------------------------------- */

static int adaptive_fn(double t, const double *z, void *arg)
{
    drive *d = arg;
    long k = d->k + 1;
    memcpy(d->r->z, z, (size_t)(2 * d->r->N) * sizeof *z);
    int st = row(d, k, NULL);
    if (st != HL_OK) {
        d->st = st;
        return st;
    }
    d->k = k;
    return 0;
}

int hl_run_adaptive(hl_run *r, const double *z0, double tol, double dt, double t,
                    long every, hl_run_fn fn, void *arg, hl_run_stats *stats,
                    hl_error *err)
{
    hl_run_stats local;
    hl_run_stats *s = stats != NULL ? stats : &local;
    drive d;
    if (!(tol > 0) || !isfinite(tol))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the tolerance must be positive (tol = %g)", tol);
    int st = start(&d, r, z0, dt, t, every, fn, arg, s, err);
    if (st != HL_OK)
        return st;
    hl_flow *fl = NULL;
    if ((st = hl_flow_new(&fl, r->vf, tol, tol, err)) != HL_OK)
        return st;
    st = row(&d, 0, NULL);
    double *zr = hl_xmalloc((size_t)(2 * r->N) * sizeof *zr);
    long cap = d.n < CHUNK ? d.n : CHUNK;
    double *ts = hl_xmalloc((size_t)(cap > 0 ? cap : 1) * sizeof *ts);
    while (st == HL_OK && d.k < d.n) {
        long k0 = d.k, m = d.n - k0 < cap ? d.n - k0 : cap;
        for (long i = 0; i < m; i++)
            ts[i] = (double)(k0 + 1 + i) * dt;
        memcpy(zr, r->z, (size_t)(2 * r->N) * sizeof *zr);
        d.st = HL_OK;
        st = hl_flow_run(fl, (double)k0 * dt, zr, ts, (int)m, adaptive_fn, &d, err);
        if (st != HL_OK && d.st != HL_OK)
            st = d.st;
    }
    s->ref_steps = hl_flow_nsteps(fl);
    free(ts), free(zr);
    hl_flow_free(fl);
    s->failed = st != HL_OK && d.user == 0;
    return d.user != 0 ? d.user : st;
}

/* ---- observed orders ---------------------------------------------------- */

int hl_run_orders(double *errmax, double *errfinal, double *order, hl_run *r,
                  const double *z0, const double *dts, int n, double t, hl_error *err)
{
    int on = r->ref_on;
    r->ref_on = 1;
    int st = HL_OK;
    double prev = NAN;
    for (int i = 0; i < n && st == HL_OK; i++) {
        hl_run_stats s;
        st = hl_run_fixed(r, z0, dts[i], t, 1, NULL, NULL, &s, err);
        if (st != HL_OK) {
            if (err != NULL)
                hl_error_prefix(err, "with dt = %g", dts[i]);
            break;
        }
        if (errmax != NULL)
            errmax[i] = s.max_err;
        if (errfinal != NULL)
            errfinal[i] = s.err_final;
        if (order != NULL)
            order[i] = i == 0 ? NAN : log(prev / s.max_err) / log(dts[i - 1] / dts[i]);
        prev = s.max_err;
    }
    r->ref_on = on;
    return st;
}
