/* One member of a sweep -> one row: the run of its scheme from its point
 * (hl_run_fixed, or hl_run_adaptive for "lie"; several at once in SIMD
 * lanes where that pays: hl_run_adaptive_lanes, hl_run_fixed_batch), the
 * observed order from dt and dt/2, and the chaos indicators of its (point, paramset), computed
 * once and kept while the members of that group follow.  A worker belongs
 * to one thread: it holds a system, the runs and a chaos object per
 * paramset, built when first needed.  A failure is the row's status and
 * reason, never the sweep's. */
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
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
    hl_scheme **sch;      /* nschemes (NULL for "lie") */
    hl_run **run;         /* nschemes */
    hl_chaos *chaos;      /* when spec.chaos */
    hl_run_lanes **lanes; /* nschemes: a lie scheme's lanes, when they pay */
    char *lanes_tried;    /* nschemes: asked once (fixed-step: 1 no, 2 yes) */
} paramset_ctx;

/* The rows of members run in lanes (sweep_worker_prepare), until
 * sweep_member hands them out. */
typedef struct ready_rows {
    long n, cap;
    long *member;
    double *row; /* n * ncols */
    hl_status *status;
    char *reason; /* n * HL_SWEEP_REASON */
} ready_rows;

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
    int lanes_mode; /* SWEEP_LANES_* */
    ready_rows ready;
    sweep_arrays arrays; /* the last member's trajectory and crossings */
};

sweep_worker *sweep_worker_new(const hl_sweep *sw)
{
    sweep_worker *w = hl_xcalloc(1, sizeof *w);
    w->sw = sw;
    w->ctx = hl_xcalloc((size_t)sw->nparamsets, sizeof *w->ctx);
    w->z0 = hl_xcalloc((size_t)(2 * sw->N), sizeof *w->z0);
    w->chaos_point = -1;
    /* the lanes give final rows only: a member's arrays need its own run */
    int arrays = sw->spec.save_every > 0 || sw->spec.event != NULL;
    w->lanes_mode = sweep_has_lanes(sw) && !arrays ? sweep_lanes_mode() : SWEEP_LANES_OFF;
    sweep_arrays_init(&w->arrays, sw);
    return w;
}

static void ctx_clear(paramset_ctx *c, int nschemes)
{
    for (int i = 0; c->run != NULL && i < nschemes; i++) {
        hl_run_lanes_free(c->lanes[i]);
        hl_run_free(c->run[i]);
        hl_scheme_free(c->sch[i]);
    }
    free(c->run);
    free(c->sch);
    free(c->lanes);
    free(c->lanes_tried);
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
    free(w->ready.member), free(w->ready.row), free(w->ready.status), free(w->ready.reason);
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
    c->lanes = hl_xcalloc((size_t)sw->nschemes, sizeof *c->lanes);
    c->lanes_tried = hl_xcalloc((size_t)sw->nschemes, 1);
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

/* ---- members in lanes ------------------------------------------------------- */

static int fits_lie(const hl_sweep *sw, sweep_where at)
{
    return sweep_is_lie(sw, at.scheme);
}

static int fits_fixed(const hl_sweep *sw, sweep_where at)
{
    return !sweep_is_lie(sw, at.scheme) && sweep_in_lanes(sw, at.scheme);
}

/* Lanes' code is compiled one thread at a time: with the disk cache the
 * first thread compiles and the others load its code, instead of each
 * compiling it. */
static pthread_mutex_t making = PTHREAD_MUTEX_INITIALIZER;

/* The lanes of (paramset, lie scheme): made the first time they pay for
 * the sweep's members of that pair (from the first step at z0), or never. */
static hl_run_lanes *lanes_for(sweep_worker *w, paramset_ctx *c, int scheme, const double *z0)
{
    const hl_sweep *sw = w->sw;
    if (c->lanes_tried[scheme])
        return c->lanes[scheme];
    c->lanes_tried[scheme] = 1;
    long members = sw->npoints * sw->ndts; /* of this paramset and scheme */
    if (w->lanes_mode == SWEEP_LANES_AUTO &&
        !hl_run_lanes_pay(c->run[scheme], sw->spec.tol, SWEEP_LANES, members, z0, sw->spec.t))
        return NULL;
    hl_error err;
    pthread_mutex_lock(&making);
    if (hl_run_lanes_new(&c->lanes[scheme], c->run[scheme], sw->spec.tol, SWEEP_LANES, &err) !=
        HL_OK)
        c->lanes[scheme] = NULL; /* the members run one at a time */
    pthread_mutex_unlock(&making);
    return c->lanes[scheme];
}

/* A slot for member m's row among the ready ones. */
static long ready_slot(sweep_worker *w, long m)
{
    ready_rows *r = &w->ready;
    int nc = w->sw->ncols;
    if (r->n == r->cap) {
        r->cap = r->cap ? 2 * r->cap : 64;
        r->member = hl_xrealloc(r->member, (size_t)r->cap * sizeof *r->member);
        r->row = hl_xrealloc(r->row, (size_t)r->cap * nc * sizeof *r->row);
        r->status = hl_xrealloc(r->status, (size_t)r->cap * sizeof *r->status);
        r->reason = hl_xrealloc(r->reason, (size_t)r->cap * HL_SWEEP_REASON);
    }
    r->member[r->n] = m;
    r->reason[r->n * HL_SWEEP_REASON] = '\0';
    return r->n++;
}

/* 1 and member m's row, status and reason if the lanes ran it. */
static int take_ready(sweep_worker *w, long m, double *row, hl_status *status, char *reason)
{
    ready_rows *r = &w->ready;
    for (long i = 0; i < r->n; i++)
        if (r->member[i] == m) {
            memcpy(row, r->row + i * w->sw->ncols, (size_t)w->sw->ncols * sizeof *row);
            *status = r->status[i];
            memcpy(reason, r->reason + i * HL_SWEEP_REASON, HL_SWEEP_REASON);
            return 1;
        }
    return 0;
}

static atomic_long lanes_members; /* run in lanes by this process */

long sweep_lanes_members(void)
{
    return atomic_load(&lanes_members);
}

/* How a group of nb members (scheme at.scheme; nb > 0) runs side by side:
 * from z0 (dt[j] each) into z, s, st and errs as run_member's runs; the
 * members that ran in lanes are counted. */
typedef void lanes_call(paramset_ctx *c, const hl_sweep *sw, sweep_where at, int nb,
                        const double *z0, const double *dt, double *z, hl_run_stats *s,
                        hl_status *st, hl_error *errs);

static void lie_lanes(paramset_ctx *c, const hl_sweep *sw, sweep_where at, int nb, const double *z0,
                      const double *dt, double *z, hl_run_stats *s, hl_status *st, hl_error *errs)
{
    hl_run_adaptive_lanes(c->lanes[at.scheme], nb, z0, dt, sw->spec.t, z, s, st, errs);
    atomic_fetch_add(&lanes_members, nb);
}

/* Whether a fixed-step scheme's members run in lanes, decided once per
 * worker for the sweep's members of (paramset, scheme), as lanes_for does
 * for lie: asked per group, the cost model would see each unit's few
 * members alone, and an MPI rank's small chunk would run one member at a
 * time where the threads' larger units ran in lanes.  The loop is compiled
 * (or loaded) under the lock; a "no" is kept as one lane. */
static int fixed_lanes_decided(paramset_ctx *c, const hl_sweep *sw, int scheme, double dt)
{
    hl_run *run = c->run[scheme];
    if (c->lanes_tried[scheme])
        return c->lanes_tried[scheme] > 1;
    long members = sw->npoints * sw->ndts; /* of this paramset and scheme */
    pthread_mutex_lock(&making);
    int lanes = hl_run_batch_lanes(run, members, dt, sw->spec.t);
    pthread_mutex_unlock(&making);
    if (lanes < 2)
        hl_run_set_lanes(run, 1, NULL); /* never asked again */
    c->lanes_tried[scheme] = lanes > 1 ? 2 : 1;
    return lanes > 1;
}

/* The group shares dt (fits_fixed's groups); hl_run_fixed_batch runs it in
 * lanes where its compiled loop pays, else one member at a time. */
static void fixed_lanes(paramset_ctx *c, const hl_sweep *sw, sweep_where at, int nb,
                        const double *z0, const double *dt, double *z, hl_run_stats *s,
                        hl_status *st, hl_error *errs)
{
    hl_run *run = c->run[at.scheme];
    hl_run_set_reference(run, 0, sw->spec.tol); /* as run_member: sweep_in_lanes */
    int lanes = fixed_lanes_decided(c, sw, at.scheme, dt[0]);
    hl_run_fixed_batch(run, nb, z0, dt[0], sw->spec.t, z, s, st, errs, NULL);
    if (lanes && nb > 1)
        atomic_fetch_add(&lanes_members, nb);
}

/* Members ms[0..B-1] of one paramset and scheme side by side (call): each
 * row as run_member makes it. */
static void run_in_lanes(sweep_worker *w, paramset_ctx *c, lanes_call *call, const long *ms, int B)
{
    const hl_sweep *sw = w->sw;
    const int n2 = 2 * sw->N, nc = sw->ncols;
    double *z0 = hl_xcalloc((size_t)B * n2 + 1, sizeof *z0),
           *z = hl_xcalloc((size_t)B * n2 + 1, sizeof *z);
    double *dt = hl_xcalloc((size_t)B + 1, sizeof *dt);
    long *slot = hl_xcalloc((size_t)B + 1, sizeof *slot);
    hl_run_stats *s = hl_xcalloc((size_t)B + 1, sizeof *s);
    hl_status *st = hl_xcalloc((size_t)B + 1, sizeof *st);
    hl_error *errs = hl_xcalloc((size_t)B + 1, sizeof *errs);
    int nb = 0;
    for (int j = 0; j < B; j++) { /* as run_member: the start checked first */
        sweep_where at = sweep_locate(sw, ms[j]);
        long k = ready_slot(w, ms[j]);
        double *row = w->ready.row + k * nc;
        sweep_point(sw, at.point, z0 + (size_t)nb * n2);
        fill_inputs(sw, ms[j], at, z0 + (size_t)nb * n2, row);
        hl_error err;
        w->ready.status[k] = hl_run_check_start(c->run[at.scheme], z0 + (size_t)nb * n2, &err);
        if (w->ready.status[k] != HL_OK) {
            set_reason(w->ready.reason + k * HL_SWEEP_REASON, "", &err);
            continue;
        }
        dt[nb] = sw->dt[at.dt];
        slot[nb++] = k;
    }
    if (nb > 0)
        call(c, sw, sweep_locate(sw, ms[0]), nb, z0, dt, z, s, st, errs);
    for (int j = 0; j < nb; j++) {
        double *row = w->ready.row + slot[j] * nc;
        fill_stats(sw, &s[j], z + (size_t)j * n2, row);
        row[sw->c_t + 5] = row[sw->c_t + 6] = NAN; /* no reference in lanes */
        w->ready.status[slot[j]] = st[j];
        if (st[j] != HL_OK)
            set_reason(w->ready.reason + slot[j] * HL_SWEEP_REASON, "", &errs[j]);
    }
    free(z0), free(z), free(dt), free(slot), free(s), free(st), free(errs);
}

/* Group g's members into ms (*B of them) and their paramset's ctx; NULL
 * if its setup failed (sweep_member gives each member that failure). */
static paramset_ctx *lane_group(sweep_worker *w, const long *list, const long *order,
                                const long *start, long g, long *ms, int *B)
{
    *B = (int)(start[g + 1] - start[g]);
    for (int j = 0; j < *B; j++)
        ms[j] = list[order[start[g] + j]];
    paramset_ctx *c = get_ctx(w, sweep_locate(w->sw, ms[0]).paramset);
    return c->status == HL_OK ? c : NULL;
}

void sweep_worker_prepare(sweep_worker *w, const long *list, long n, sweep_ran_fn *ran,
                          void *ran_arg)
{
    const hl_sweep *sw = w->sw;
    w->ready.n = 0;
    if (w->lanes_mode == SWEEP_LANES_OFF || n <= 0)
        return;
    long *order = hl_xcalloc((size_t)n + 1, sizeof *order);
    long *start = hl_xcalloc((size_t)n + 2, sizeof *start);
    long *ms = hl_xcalloc((size_t)n + 1, sizeof *ms);
    int B;
    long ng = sweep_lane_groups(sw, list, n, fits_lie, 0, order, start);
    for (long g = 0; g < ng; g++) {
        paramset_ctx *c = lane_group(w, list, order, start, g, ms, &B);
        if (c == NULL)
            continue;
        sweep_where at = sweep_locate(sw, ms[0]);
        sweep_point(sw, at.point, w->z0);
        if (lanes_for(w, c, at.scheme, w->z0) != NULL) {
            run_in_lanes(w, c, lie_lanes, ms, B);
            if (ran != NULL)
                ran(B, ran_arg);
        }
    }
    ng = sweep_lane_groups(sw, list, n, fits_fixed, 1 /* same dt */, order, start);
    for (long g = 0; g < ng; g++) {
        paramset_ctx *c = lane_group(w, list, order, start, g, ms, &B);
        if (c == NULL)
            continue;
        run_in_lanes(w, c, fixed_lanes, ms, B);
        if (ran != NULL)
            ran(B, ran_arg);
    }
    free(order), free(start), free(ms);
}

void sweep_member_arrays(const sweep_worker *w, hl_sweep_result *r)
{
    sweep_arrays_result(&w->arrays, r);
}

int sweep_member(sweep_worker *w, long m, double *row, hl_status *status, char *reason)
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
        return 0;
    }
    int ready = take_ready(w, m, row, status, reason);
    if (!ready) {
        hl_error err;
        hl_error_clear(&err);
        *status = run_member(w, c, at, row, &err);
        if (*status != HL_OK)
            set_reason(reason, "", &err);
    }
    if (*status == HL_OK && sw->spec.chaos) {
        chaos_of(w, c, at, row);
        *status = w->chaos_status;
        snprintf(reason, HL_SWEEP_REASON, "%s", w->chaos_reason);
    }
    return ready;
}
