/* A member's optional arrays (sweep.h, "Arrays"): its trajectory, sampled
 * by the run's row callback every save_every steps, and the crossings of
 * spec.event, delivered by the run's event (hl_run_event).  One collector
 * per thread, reused from member to member; rows are t then the state. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "sweep/sweep_impl.h"

int hl_sweep_array_width(const hl_sweep *sw)
{
    return 1 + 2 * sw->N;
}

int hl_sweep_has_array(const hl_sweep *sw, int kind)
{
    return kind >= 0 && kind < HL_SWEEP_NARRAYS && sw->has_array[kind];
}

long hl_sweep_traj_rows_max(const hl_sweep *sw)
{
    if (!sw->has_array[HL_SWEEP_TRAJ])
        return 0;
    long most = 0;
    for (int i = 0; i < sw->ndts; i++) {
        long n = 0;
        hl_error err;
        hl_error_clear(&err);
        if (hl_run_nsteps(&n, sw->dt[i], sw->spec.t, &err) != HL_OK)
            continue;
        /* row 0, every save_every-th, and the last */
        long rows = n / sw->spec.save_every + 2;
        most = rows > most ? rows : most;
    }
    return most;
}

hl_status sweep_check_event(const hl_sweep *sw, hl_system *sys, hl_error *err)
{
    const hl_sweep_spec *s = &sw->spec;
    if (s->save_every < 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "save_every: a trajectory row every K >= 1 steps (0: none), not %ld",
                            s->save_every);
    if (s->direction < -1 || s->direction > 1)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "direction: 1 (up), -1 (down) or 0 (both), not %d", s->direction);
    if (s->event == NULL)
        return HL_OK;
    hl_run_surface_info info;
    int st = hl_run_surface(&info, sys, s->event, err);
    if (st != HL_OK)
        hl_error_prefix(err, "event");
    return st;
}

void sweep_arrays_init(sweep_arrays *a, const hl_sweep *sw)
{
    memset(a, 0, sizeof *a);
    a->sw = sw;
}

void sweep_arrays_clear(sweep_arrays *a)
{
    for (int k = 0; k < HL_SWEEP_NARRAYS; k++)
        free(a->v[k]);
    memset(a, 0, sizeof *a);
}

static void add_row(sweep_arrays *a, int kind, double t, const double *z)
{
    int w = hl_sweep_array_width(a->sw);
    if (a->n[kind] == a->cap[kind]) {
        a->cap[kind] = a->cap[kind] ? 2 * a->cap[kind] : 64;
        a->v[kind] = hl_xrealloc(a->v[kind], (size_t)a->cap[kind] * (size_t)w * sizeof(double));
    }
    double *row = a->v[kind] + (size_t)a->n[kind]++ * (size_t)w;
    row[0] = t;
    memcpy(row + 1, z, (size_t)(w - 1) * sizeof *z);
}

static int on_crossing(const hl_run_crossing *c, void *arg)
{
    sweep_arrays *a = arg;
    if (a->on)
        add_row(a, HL_SWEEP_CROSS, c->t, c->z);
    return 0;
}

static int on_row(const hl_run_row *row, void *arg)
{
    sweep_arrays *a = arg;
    if (a->on)
        add_row(a, HL_SWEEP_TRAJ, row->t, row->z);
    return 0;
}

hl_status sweep_arrays_attach(sweep_arrays *a, hl_run *run, hl_error *err)
{
    const hl_sweep_spec *s = &a->sw->spec;
    if (s->event == NULL)
        return HL_OK;
    return hl_run_event(run, s->event, (hl_event_dir)s->direction, 0, on_crossing, a, err);
}

void sweep_arrays_begin(sweep_arrays *a)
{
    for (int k = 0; k < HL_SWEEP_NARRAYS; k++)
        a->n[k] = 0;
    a->on = 1;
}

void sweep_arrays_end(sweep_arrays *a)
{
    a->on = 0;
}

hl_run_fn sweep_arrays_row_fn(const hl_sweep *sw)
{
    return sw->has_array[HL_SWEEP_TRAJ] ? on_row : NULL;
}

long sweep_arrays_every(const hl_sweep *sw)
{
    return sw->has_array[HL_SWEEP_TRAJ] ? sw->spec.save_every : 1;
}

void sweep_arrays_result(const sweep_arrays *a, hl_sweep_result *r)
{
    for (int k = 0; k < HL_SWEEP_NARRAYS; k++) {
        r->nrows[k] = a->sw->has_array[k] ? a->n[k] : 0;
        r->array[k] = r->nrows[k] > 0 ? a->v[k] : NULL;
    }
}
