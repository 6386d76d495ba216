/* One member of a sweep -> one row: the run of its scheme from its point
 * (hl_run_fixed, or hl_run_adaptive for "lie"), the observed order from dt
 * and dt/2, and the chaos indicators of its (point, paramset), computed
 * once and kept while the members of that group follow.  A worker belongs
 * to one thread: it holds a system, the runs and a chaos object per
 * paramset, built when first needed.  A failure is the row's status and
 * reason, never the sweep's. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "sweep/sweep_impl.h"

/* What a paramset needs, built once per worker. */
typedef struct paramset_ctx {
    int built;
    hl_status status; /* of the building: every member of the paramset fails with it */
    char reason[HL_SWEEP_REASON];
    hl_system *sys;
    hl_scheme **sch; /* nschemes (NULL for "lie") */
    hl_run **run;    /* nschemes */
    hl_chaos *chaos; /* when spec.chaos */
} paramset_ctx;

struct sweep_worker {
    const hl_sweep *sw;
    paramset_ctx *ctx; /* nparamsets, built lazily */
    int nbuilt;
    double *z0;
    /* the chaos indicators of the last (point, paramset) */
    long chaos_point, chaos_paramset;
    double megno, mlce;
    hl_status chaos_status;
    char chaos_reason[HL_SWEEP_REASON];
    sweep_arrays arrays; /* the last member's trajectory and crossings */
};

sweep_worker *sweep_worker_new(const hl_sweep *sw)
{
    sweep_worker *w = hl_xcalloc(1, sizeof *w);
    w->sw = sw;
    w->ctx = hl_xcalloc((size_t)sw->nparamsets, sizeof *w->ctx);
    w->z0 = hl_xcalloc((size_t)(2 * sw->N), sizeof *w->z0);
    w->chaos_point = -1;
    sweep_arrays_init(&w->arrays, sw);
    return w;
}

static void ctx_clear(paramset_ctx *c, int nschemes)
{
    for (int i = 0; c->run != NULL && i < nschemes; i++) {
        hl_run_free(c->run[i]);
        hl_scheme_free(c->sch[i]);
    }
    free(c->run);
    free(c->sch);
    hl_chaos_free(c->chaos);
    hl_system_free(c->sys);
    memset(c, 0, sizeof *c);
}

void sweep_worker_free(sweep_worker *w)
{
    if (w == NULL)
        return;
    for (long i = 0; i < w->sw->nparamsets; i++)
        ctx_clear(&w->ctx[i], w->sw->nschemes);
    free(w->ctx);
    free(w->z0);
    sweep_arrays_clear(&w->arrays);
    free(w);
}

/* prefix and the message, cut to HL_SWEEP_REASON - 1 bytes */
static void set_reason(char *reason, const char *prefix, const hl_error *err)
{
    const char *msg = err->msg[0] ? err->msg : hl_status_string(err->status);
    size_t k = 0;
    for (const char *s = prefix; *s && k < HL_SWEEP_REASON - 1; s++)
        reason[k++] = *s;
    for (const char *s = msg; *s && k < HL_SWEEP_REASON - 1; s++)
        reason[k++] = *s;
    reason[k] = '\0';
}

static hl_status build_ctx(paramset_ctx *c, const hl_sweep *sw, long paramset, sweep_arrays *arrays,
                           hl_error *err)
{
    int st = sweep_system(&c->sys, sw, paramset, err);
    c->sch = hl_xcalloc((size_t)sw->nschemes, sizeof *c->sch);
    c->run = hl_xcalloc((size_t)sw->nschemes, sizeof *c->run);
    for (int i = 0; st == HL_OK && i < sw->nschemes; i++) {
        if (strcmp(sw->scheme[i], "lie") != 0)
            st = hl_scheme_new(&c->sch[i], sw->scheme[i], 4, c->sys, err);
        if (st == HL_OK)
            st = hl_run_new(&c->run[i], c->sys, c->sch[i], err);
        if (st == HL_OK)
            hl_run_set_jit(c->run[i], 1); /* as `hamlie run`: the same bits, faster long runs */
        if (st == HL_OK)
            st = sweep_arrays_attach(arrays, c->run[i], err);
    }
    if (st == HL_OK && sw->spec.chaos)
        st = hl_chaos_new(&c->chaos, c->sys, sw->spec.tol, err);
    return st;
}

/* A worker keeps at most this many paramsets built (a system, its schemes'
 * runs, a chaos object each): a sweep over thousands of parameter values
 * then rebuilds as it goes instead of holding them all. */
#define KEPT_PARAMSETS 16

static paramset_ctx *get_ctx(sweep_worker *w, long paramset)
{
    paramset_ctx *c = &w->ctx[paramset];
    if (!c->built && w->nbuilt >= KEPT_PARAMSETS) {
        for (long i = 0; i < w->sw->nparamsets; i++)
            ctx_clear(&w->ctx[i], w->sw->nschemes);
        w->nbuilt = 0;
    }
    if (!c->built) {
        w->nbuilt++;
        hl_error err;
        hl_error_clear(&err);
        c->built = 1;
        c->status = build_ctx(c, w->sw, paramset, &w->arrays, &err);
        if (c->status != HL_OK)
            set_reason(c->reason, "", &err);
    }
    return c;
}

/* The inputs' columns and NaN everywhere else. */
static void fill_inputs(const hl_sweep *sw, long m, sweep_where at, const double *z0, double *row)
{
    for (int i = 0; i < sw->ncols; i++)
        row[i] = NAN;
    row[SWEEP_C_MEMBER] = (double)m;
    row[SWEEP_C_POINT] = (double)at.point;
    row[SWEEP_C_PARAMSET] = (double)at.paramset;
    row[SWEEP_C_SCHEME] = at.scheme;
    row[SWEEP_C_DT] = sw->dt[at.dt];
    for (int i = 0; i < sw->nparam; i++)
        row[sw->c_param + i] = sweep_param_value(sw, at.paramset, i);
    for (int i = 0; i < 2 * sw->N; i++)
        row[sw->c_z0 + i] = z0[i];
}

static void fill_stats(const hl_sweep *sw, const hl_run_stats *s, const double *z, double *row)
{
    double *r = row + sw->c_t;
    r[0] = s->t;
    r[1] = (double)s->steps;
    r[2] = s->H0;
    r[3] = s->max_dH;
    r[4] = s->H - s->H0;
    r[5] = s->max_err;
    r[6] = s->err_final;
    for (int i = 0; z != NULL && i < 2 * sw->N; i++)
        row[sw->c_z + i] = z[i];
}

/* The order from the errors at dt and dt/2 (the run at dt done with its
 * reference). */
static hl_status observed_order(double *order, hl_run *run, const hl_run_stats *s1,
                                const double *z0, double dt, double t, hl_error *err)
{
    hl_run_stats s2;
    memset(&s2, 0, sizeof s2);
    int st = hl_run_fixed(run, z0, dt / 2, t, 1, NULL, NULL, &s2, err);
    if (st == HL_OK)
        *order = log(s1->max_err / s2.max_err) / log(2.0);
    else
        hl_error_prefix(err, "the run at dt/2");
    return st;
}

/* The chaos indicators of (point, paramset), kept for the group's members. */
static void chaos_of(sweep_worker *w, paramset_ctx *c, sweep_where at, double *row)
{
    const hl_sweep *sw = w->sw;
    if (w->chaos_point != at.point || w->chaos_paramset != at.paramset) {
        hl_chaos_result res;
        hl_error err;
        hl_error_clear(&err);
        memset(&res, 0, sizeof res);
        w->chaos_status =
            hl_chaos_run(c->chaos, w->z0, NULL, sw->spec.t, 0, NULL, NULL, &res, &err);
        w->megno = w->chaos_status == HL_OK ? res.megno_mean : NAN;
        w->mlce = w->chaos_status == HL_OK ? res.mlce : NAN;
        w->chaos_reason[0] = '\0';
        if (w->chaos_status != HL_OK)
            set_reason(w->chaos_reason, "chaos: ", &err);
        w->chaos_point = at.point;
        w->chaos_paramset = at.paramset;
    }
    row[sw->c_megno] = w->megno;
    row[sw->c_megno + 1] = w->mlce;
}

/* The run of member m; its failure in *status and reason. */
static hl_status run_member(sweep_worker *w, paramset_ctx *c, sweep_where at, double *row,
                            hl_error *err)
{
    const hl_sweep *sw = w->sw;
    hl_run *run = c->run[at.scheme];
    int adaptive = c->sch[at.scheme] == NULL, want_order = sw->spec.order && !adaptive;
    double dt = sw->dt[at.dt], t = sw->spec.t;
    hl_run_set_reference(run, sw->spec.reference || want_order, sw->spec.tol);
    hl_run_stats s;
    memset(&s, 0, sizeof s);
    int st = hl_run_check_start(run, w->z0, err);
    long every = sweep_arrays_every(sw);
    hl_run_fn keep = sweep_arrays_row_fn(sw); /* the trajectory, when asked */
    if (st == HL_OK) {
        sweep_arrays_begin(&w->arrays);
        st = adaptive ? hl_run_adaptive(run, w->z0, sw->spec.tol, dt, t, every, keep, &w->arrays,
                                        &s, err)
                      : hl_run_fixed(run, w->z0, dt, t, every, keep, &w->arrays, &s, err);
        sweep_arrays_end(&w->arrays);
        fill_stats(sw, &s, hl_run_state(run), row);
    }
    if (!sw->spec.reference || adaptive) /* measured only for the order: not shown */
        row[sw->c_t + 5] = row[sw->c_t + 6] = NAN;
    if (st == HL_OK && want_order)
        st = observed_order(&row[sw->c_order], run, &s, w->z0, dt, t, err);
    return st;
}

void sweep_member_arrays(const sweep_worker *w, hl_sweep_result *r)
{
    sweep_arrays_result(&w->arrays, r);
}

void sweep_member(sweep_worker *w, long m, double *row, hl_status *status, char *reason)
{
    const hl_sweep *sw = w->sw;
    sweep_arrays_begin(&w->arrays); /* none for a member that does not run */
    sweep_arrays_end(&w->arrays);
    sweep_where at = sweep_locate(sw, m);
    sweep_point(sw, at.point, w->z0);
    fill_inputs(sw, m, at, w->z0, row);
    reason[0] = '\0';
    paramset_ctx *c = get_ctx(w, at.paramset);
    if (c->status != HL_OK) {
        *status = c->status;
        snprintf(reason, HL_SWEEP_REASON, "%s", c->reason);
        return;
    }
    hl_error err;
    hl_error_clear(&err);
    *status = run_member(w, c, at, row, &err);
    if (*status != HL_OK) {
        set_reason(reason, "", &err);
        return;
    }
    if (sw->spec.chaos) {
        chaos_of(w, c, at, row);
        *status = w->chaos_status;
        snprintf(reason, HL_SWEEP_REASON, "%s", w->chaos_reason);
    }
}
