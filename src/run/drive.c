/* The drivers: a fixed-step run against the dense output of the Taylor
 * integrator, the adaptive run, observed orders. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "run/run_impl.h"

/* Reference times go to the flow in chunks, so memory stays bounded. */
#define CHUNK 65536

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
    double progress_next;    /* the step at which progress is reported next */
    double progress_spacing;
    double probe_t;          /* adaptive: a time between two rows (or NAN), */
    double *probe_z;         /* where the state goes for the next call */
    int fixed;               /* a fixed-step run: events on the Hermite cubic */
} drive;

static int finish(hl_run *r, hl_run_stats *s, const drive *d, int st);

/* Steps between two calls of the progress callback in a fixed-step run
 * (a call costs about as much as a step; a step at least 10 ns), and the
 * longest stretch of the compiled loop between two. */
#define PROGRESS_STEPS 1024
#define PROGRESS_FUSED_STEPS 65536
/* The adaptive run with a progress callback: Taylor steps between two
 * calls, and the first span of time tried, in rows. */
#define PROBE_STEPS 1024
#define PROBE_FIRST_SPAN 0x1p-40 /* rows may be 1e9 apart: start small, double */

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
    if (d->fixed && r->ev != NULL) { /* the crossings before this row */
        int e = hl_run_event_step_(r, k, d->dt, s);
        if (e != 0) {
            d->user = e == HL_RUN_EV_STOP ? 0 : e;
            return e;
        }
    }
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
    if (d->fn != NULL && (k % d->every == 0 || k == d->n)) {
        hl_run_row rw = {k, t, r->z, r->vals[0], r->vals + 1, sigma, ref};
        s->rows++;
        int u = d->fn(&rw, d->arg);
        if (u != 0) {
            d->user = u;
            return u;
        }
    }
    return hl_run_progress_(r, &d->progress_next, d->progress_spacing, (double)k, d->n, t,
                            d->err);
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
    if (r->jit) /* a long reference compiles its recursion */
        hl_flow_native_for(fl, (double)d->n * d->dt);
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

/* ---- the fast path of a long fixed-step run without the reference --------
 * An explicit scheme's step and H are compiled into one tape z, D -> (Z,
 * H(z)), where the step and the energy of the state it leaves share their
 * subexpressions (the pendulum's sin q and cos q are one sincos), and it is
 * iterated in machine code from one delivered row to the next, max |H - H0|
 * kept in the loop (hl_tape_iterate_watch): no call, no copy per step.  At
 * a value that is not finite the loop stops before that step and the
 * scheme's stepper takes over, so failures read as on the slow path. */

/* The fused tape, built on first use; NULL if the scheme has none
 * (implicit) or it cannot be built. */
hl_tape *hl_run_fused_(hl_run *r)
{
    if (r->scheme == NULL || r->fused_failed)
        return NULL;
    if (r->fused == NULL) {
        int n2 = 2 * r->N;
        const hl_expr **outs = hl_xmalloc((size_t)(n2 + 1) * sizeof *outs);
        const char **in = hl_xmalloc((size_t)(n2 + 1) * sizeof *in);
        memcpy(in, r->names, (size_t)n2 * sizeof *in);
        in[n2] = hl_system_step(r->sys);
        outs[n2] = r->outs[0];
        if (hl_scheme_step_exprs(outs, r->scheme, NULL) != HL_OK ||
            hl_tape_new(&r->fused, outs, n2 + 1, in, n2 + 1, NULL) != HL_OK)
            r->fused_failed = 1;
        free(outs), free(in);
    }
    return r->fused;
}

/* The fused tape, compiled, if this run should use it. */
static int fused_ready(hl_run *r, long nsteps)
{
    if (!r->jit || !hl_tape_jit_available() || hl_run_fused_(r) == NULL)
        return 0;
    if (hl_tape_jit_active(r->fused))
        return 1;
    if (!hl_tape_compile_pays(r->fused, HL_COMPILE_LOOP, nsteps))
        return 0;
    if (hl_tape_jit(r->fused, NULL) != HL_OK) {
        r->fused_failed = 1; /* the tape stays: a batch (batch.c) may borrow it */
        return 0;
    }
    return 1;
}

/* Steps 1.. on the fused tape, rows where due; returns the last step
 * reached (d->n when all went well), *st the status of the rows. */
static long fixed_fused(drive *d, int *st)
{
    hl_run *r = d->r;
    int n2 = 2 * r->N;
    size_t bytes = (size_t)n2 * sizeof *r->z;
    double *in = hl_xmalloc(bytes + sizeof *in), *save = hl_xmalloc(bytes);
    long k = 0;
    *st = HL_OK;
    while (*st == HL_OK && k < d->n) {
        long next = d->fn == NULL ? d->n : (k / d->every + 1) * d->every;
        long m = (next > d->n ? d->n : next) - k;
        if (r->progress != NULL && m > PROGRESS_FUSED_STEPS)
            m = PROGRESS_FUSED_STEPS;
        memcpy(save, r->z, bytes);
        memcpy(in, r->z, bytes);
        in[n2] = d->dt;
        long done = hl_tape_iterate_watch(in, m, d->s->H0, &d->s->max_dH, r->fused);
        if (done > 0 && done < m) {
            /* state k + done has an H or a step that is not finite: back
             * to the state before it, so that the stepper retakes that
             * step and the failure reads as on the stepper's path */
            memcpy(in, save, bytes);
            hl_tape_iterate_watch(in, --done, d->s->H0, &d->s->max_dH, r->fused);
        }
        memcpy(r->z, in, bytes);
        if (done > 0) /* a delivered row if done == m, else only the statistics */
            *st = row(d, k + done, NULL);
        k += done;
        if (done < m)
            break;
    }
    free(in), free(save);
    return k;
}

static int start(drive *d, hl_run *r, const double *z0, double dt, double t, long every,
                 hl_run_fn fn, void *arg, hl_run_stats *s, hl_error *err)
{
    memset(d, 0, sizeof *d);
    d->r = r, d->dt = dt, d->fn = fn, d->arg = arg, d->s = s, d->err = err;
    d->every = every > 0 ? every : 1;
    d->progress_next = 1;
    d->progress_spacing = r->scheme != NULL || r->step != NULL ? PROGRESS_STEPS : 1;
    int st = hl_run_nsteps(&d->n, dt, t, err);
    if (st == HL_OK)
        st = hl_run_check_start(r, z0, err);
    if (st != HL_OK)
        return st;
    stats_start(s, d->n);
    memcpy(r->z, z0, (size_t)(2 * r->N) * sizeof *z0);
    memcpy(r->ref, z0, (size_t)(2 * r->N) * sizeof *z0);
    r->ev_stopped = 0;
    return HL_OK;
}

hl_status hl_run_fixed(hl_run *r, const double *z0, double dt, double t, long every, hl_run_fn fn,
                       void *arg, hl_run_stats *stats, hl_error *err)
{
    hl_run_stats local;
    hl_run_stats *s = stats != NULL ? stats : &local;
    drive d;
    if (r->stepper == NULL && r->step == NULL)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "this run has no scheme");
    int st = start(&d, r, z0, dt, t, every, fn, arg, s, err);
    if (st != HL_OK)
        return st;
    d.fixed = 1;
    /* each run counts its steps (in messages) from 1 */
    if (r->stepper != NULL)
        hl_scheme_stepper_restart(r->stepper, 0);
    /* fused only where rows are sparse: a row every step or few gains
     * nothing from the loop, and would pay its compilation */
    int fused = !r->ref_on && r->stepper != NULL && (d.fn == NULL || d.every >= 16) &&
                r->ev == NULL && fused_ready(r, d.n);
    /* H and the observers are evaluated at every row, and at every step
     * unless fused: for long runs machine code (same results bit for bit)
     * pays for its compilation */
    long evals = fused ? (d.fn != NULL ? d.n / d.every : 1) : d.n;
    if (r->jit && !hl_tape_jit_active(r->obs) &&
        hl_tape_compile_pays(r->obs, HL_COMPILE_EVAL, evals))
        hl_tape_jit(r->obs, NULL); /* on failure the interpreter goes on */
    if (r->jit && r->stepper != NULL && !fused)
        hl_scheme_stepper_jit(r->stepper, d.n);
    st = row(&d, 0, r->ref_on ? z0 : NULL);
    if (st == HL_OK && r->ref_on)
        st = fixed_ref(&d, err);
    else if (st == HL_OK) {
        long k = 0;
        if (fused) {
            k = fixed_fused(&d, &st);
            hl_scheme_stepper_restart(r->stepper, k);
        }
        for (k++; st == HL_OK && k <= d.n; k++)
            if ((st = advance(&d, k)) == HL_OK)
                st = row(&d, k, NULL);
    }
    return finish(r, s, &d, st);
}

/* The status of a run that ended with st: HL_OK if it stopped after its
 * crossings (hl_run_event), the callback's own return, or st. */
static int finish(hl_run *r, hl_run_stats *s, const drive *d, int st)
{
    s->event_stop = r->ev_stopped;
    if (r->ev_stopped)
        return HL_OK;
    s->failed = st != HL_OK && d->user == 0;
    return d->user != 0 ? d->user : st;
}

/* ---- the adaptive run --------------------------------------------------- */

/* A crossing found by the flow on its step's polynomial. */
static int adaptive_cross(double t, const double *z, void *arg)
{
    drive *d = arg;
    int e = hl_run_crossing_(d->r, t, z, d->s);
    if (e != 0) {
        d->user = e == HL_RUN_EV_STOP ? 0 : e;
        d->st = e;
    }
    return e;
}

static int adaptive_fn(double t, const double *z, void *arg)
{
    drive *d = arg;
    if (t == d->probe_t) { /* not a row: the progress between two */
        double always = -INFINITY;
        memcpy(d->probe_z, z, (size_t)(2 * d->r->N) * sizeof *z);
        d->st = hl_run_progress_(d->r, &always, 0, (double)d->k + (t - (double)d->k * d->dt) / d->dt,
                                 d->n, t, d->err);
        return d->st;
    }
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

hl_status hl_run_adaptive(hl_run *r, const double *z0, double tol, double dt, double t, long every,
                          hl_run_fn fn, void *arg, hl_run_stats *stats, hl_error *err)
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
    if (r->jit) /* a long run compiles its recursion */
        hl_flow_native_for(fl, t);
    if (r->ev != NULL && (st = hl_flow_set_event(fl, r->ev, adaptive_cross, &d, err)) != HL_OK) {
        hl_flow_free(fl);
        return st;
    }
    st = row(&d, 0, NULL);
    double *zr = hl_xmalloc((size_t)(2 * r->N) * sizeof *zr);
    long cap = d.n < CHUNK ? d.n : CHUNK;
    double *ts = hl_xmalloc((size_t)(cap + 1) * sizeof *ts);
    size_t bytes = (size_t)(2 * r->N) * sizeof *zr;
    memcpy(zr, r->z, bytes);
    d.probe_z = zr;
    /* NOTE: rows far apart (t = 1e12 in 1000 rows) would leave the progress
     * callback silent for hours: with one, a call of the integrator covers
     * at most `span` of time, ending at a probe between two rows where the
     * callback is called and the next call starts; span is doubled or
     * halved so that a call takes about PROBE_STEPS Taylor steps, from step
     * counts (not clocks: a run is reproducible).  Without a callback a call
     * runs CHUNK rows, as always. */
    double ta = 0, span = r->progress != NULL ? dt * PROBE_FIRST_SPAN : INFINITY;
    while (st == HL_OK && d.k < d.n) {
        long m = 0;
        double tb = fmin(ta + span, (double)d.n * dt);
        for (long k = d.k + 1; k <= d.n && m < cap && (double)k * dt <= tb; k++)
            ts[m++] = (double)k * dt;
        int probe = r->progress != NULL && m < cap && (m == 0 || ts[m - 1] < tb);
        if (probe)
            ts[m++] = tb;
        d.probe_t = probe ? tb : NAN;
        d.st = HL_OK;
        long steps0 = hl_flow_nsteps(fl);
        st = hl_flow_run(fl, ta, zr, ts, (int)m, adaptive_fn, &d, err);
        if (st != HL_OK && d.st != HL_OK)
            st = d.st;
        long used = hl_flow_nsteps(fl) - steps0;
        span = used < PROBE_STEPS / 4 ? 2 * span : used > 4 * PROBE_STEPS ? span / 2 : span;
        ta = probe ? tb : (double)d.k * dt;
        if (!probe)
            memcpy(zr, r->z, bytes);
    }
    s->ref_steps = hl_flow_nsteps(fl);
    free(ts), free(zr);
    hl_flow_free(fl);
    return finish(r, s, &d, st);
}

/* ---- observed orders ---------------------------------------------------- */

hl_status hl_run_orders(double *errmax, double *errfinal, double *order, hl_run *r,
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
