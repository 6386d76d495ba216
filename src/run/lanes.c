/* hl_run_adaptive for many members at once (run.h, hl_run_lanes): the
 * Taylor integrator's batch (flow.h, hl_flow_batch_grid) runs the members
 * in SIMD lanes with outputs at the rows' times k*dt, and each member's
 * rows are measured here as drive.c's row() measures the single run's: H
 * at every row, max |H - H0| over them, the last good row's time, step and
 * H, the state at the last row, the same messages.  The grid's segments
 * are drive.c's CHUNK, the rows per hl_flow_run call of the single run,
 * so that each member's steps, and so its bits, are the single run's.
 *
 * NOTE: drive.c's row() and hl_run_adaptive's chunking are mirrored here,
 * not shared (drive.c's are tied to its one-run driver); sweep/t-lanes
 * compares every member with hl_run_adaptive bit for bit, so a change to
 * one alone fails it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "run/run_impl.h"

/* drive.c's CHUNK: the rows of one hl_flow_run call */
#define ROWS_PER_CALL 65536

struct hl_run_lanes {
    hl_run *r;
    hl_flow_batch *fb;
};

int hl_run_lanes_pay(hl_run *r, double tol, int lanes, long members, const double *z0, double t)
{
    return r->ev == NULL && r->progress == NULL &&
           hl_flow_batch_pays(r->vf, tol, tol, lanes, members, z0, t);
}

hl_status hl_run_lanes_new(hl_run_lanes **out, hl_run *r, double tol, int lanes, hl_error *err)
{
    *out = NULL;
    if (r->scheme != NULL || r->step != NULL || r->ev != NULL || r->progress != NULL)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                            "lanes run the adaptive integrator only, without events or progress");
    if (!(tol > 0) || !isfinite(tol))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the tolerance must be positive (tol = %g)", tol);
    hl_flow_batch *fb;
    int st = hl_flow_batch_new(&fb, r->vf, tol, tol, lanes, err);
    if (st != HL_OK)
        return st;
    hl_run_lanes *ls = hl_xcalloc(1, sizeof *ls);
    ls->r = r;
    ls->fb = fb;
    *out = ls;
    return HL_OK;
}

void hl_run_lanes_free(hl_run_lanes *ls)
{
    if (ls == NULL)
        return;
    hl_flow_batch_free(ls->fb);
    free(ls);
}

int hl_run_lanes_compiled(const hl_run_lanes *ls)
{
    return hl_flow_batch_compiled(ls->fb);
}

/* The members' rows as they come (the batch's callback's argument). */
typedef struct rows {
    hl_run *r;
    const double *dt;
    double *z; /* B * 2N: each member's last row */
    hl_run_stats *s;
} rows;

/* drive.c's row() for member i at row k: H there, the statistics. */
static int row_at(rows *w, int i, long k, double t, const double *z, hl_error *err)
{
    hl_run *r = w->r;
    hl_run_stats *s = &w->s[i];
    memcpy(w->z + (size_t)i * 2 * r->N, z, (size_t)(2 * r->N) * sizeof *z);
    hl_tape_eval_d(r->vals, z, r->obs);
    if (!isfinite(r->vals[0]))
        return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                            "blow-up: H is not finite at step %ld, t = %.17g", k, t);
    if (k == 0)
        s->H0 = r->vals[0];
    s->H = r->vals[0];
    s->max_dH = fmax(s->max_dH, fabs(r->vals[0] - s->H0));
    s->steps = k;
    s->t = t;
    return HL_OK;
}

static int grid_row(int member, long k, double t, const double *z, hl_error *err, void *arg)
{
    return row_at(arg, member, k, t, z, err);
}

/* Member i's start, as hl_run_adaptive's before its first hl_flow_run: its
 * rows counted, the point checked, row 0.  k1: its last row. */
static hl_status start_member(rows *w, int i, const double *z0, double t, long *k1, hl_error *err)
{
    hl_run *r = w->r;
    int st = hl_run_nsteps(k1, w->dt[i], t, err);
    if (st == HL_OK)
        st = hl_run_check_start(r, z0, err);
    if (st != HL_OK)
        return st;
    hl_run_stats *s = &w->s[i];
    memset(s, 0, sizeof *s);
    s->nsteps = *k1;
    s->sigma = s->max_err = s->err_final = NAN;
    return row_at(w, i, 0, 0, z0, err);
}

hl_status hl_run_adaptive_lanes(hl_run_lanes *ls, int B, const double *z0, const double *dt,
                                double t, double *z, hl_run_stats *stats, hl_status *status,
                                hl_error *errs)
{
    hl_run *r = ls->r;
    const size_t n2 = (size_t)(2 * r->N);
    rows w = {r, dt, z, stats};
    long *k0 = hl_xcalloc((size_t)B + 1, sizeof *k0), *k1 = hl_xcalloc((size_t)B + 1, sizeof *k1);
    long *steps = hl_xcalloc((size_t)B + 1, sizeof *steps);
    hl_status *started = hl_xcalloc((size_t)B + 1, sizeof *started);
    hl_error *eb = hl_xcalloc((size_t)B + 1, sizeof *eb); /* the batch's errors */
    double *zb = hl_xcalloc((B + 1) * n2, sizeof *zb);    /* the batch's states */
    memcpy(zb, z0, B * n2 * sizeof *zb);
    for (int i = 0; i < B; i++) {
        hl_error_clear(&errs[i]);
        started[i] = start_member(&w, i, z0 + i * n2, t, &k1[i], &errs[i]);
        if (started[i] != HL_OK)
            k1[i] = 0; /* the batch finishes it at once, without a step */
    }
    hl_error err;
    hl_flow_batch_grid(ls->fb, B, dt, k0, k1, ROWS_PER_CALL, zb, grid_row, &w, status, steps, eb,
                       &err);
    hl_status first = HL_OK;
    for (int i = 0; i < B; i++) {
        if (started[i] != HL_OK) { /* the batch had nothing to do: its error stays */
            status[i] = started[i];
        } else {
            errs[i] = eb[i];
            stats[i].ref_steps = steps[i];
            stats[i].failed = status[i] != HL_OK;
        }
        first = first == HL_OK ? status[i] : first;
    }
    free(k0), free(k1), free(steps), free(started), free(eb), free(zb);
    return first;
}
