/* Events in runs: the surface from its text, crossings found on the step's
 * polynomial (the adaptive run, flow.h) or on the cubic Hermite
 * interpolant of each fixed step (event.h), delivered with H, and the stop
 * after N of them. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "run/run_impl.h"

static const char *var_name(hl_system *sys, int j)
{
    int N = hl_system_ndof(sys);
    return j < N ? hl_system_coord(sys, j) : hl_system_momentum(sys, j - N);
}

hl_status hl_run_surface(hl_run_surface_info *out, hl_system *sys, const char *surface,
                         hl_error *err)
{
    memset(out, 0, sizeof *out);
    out->var = -1;
    hl_pool *pool = hl_system_pool(sys);
    hl_eqn eq[2];
    int n = 0;
    int st = hl_parse_list(eq, 2, &n, pool, surface, err);
    if (st == HL_OK && n != 1)
        return hl_error_set(err, HL_EPARSE, surface, eq[1].pos, 1,
                            "a surface is one formula g (g = 0) or one equation lhs = rhs");
    if (st != HL_OK)
        return st;
    const hl_expr *lhs = hl_run_resolve_(sys, eq[0].lhs);
    const hl_expr *rhs = eq[0].rhs != NULL ? hl_run_resolve_(sys, eq[0].rhs) : NULL;
    const hl_expr *g = rhs != NULL ? hl_sub(pool, lhs, rhs) : lhs;
    const char *syms[64];
    int ns = hl_expr_symbols(g, syms, 64), N = hl_system_ndof(sys), nvars = 0;
    for (int i = 0; i < ns && i < 64; i++) {
        int known = 0;
        for (int j = 0; j < 2 * N; j++)
            known |= strcmp(syms[i], var_name(sys, j)) == 0;
        if (!known) {
            int pos = hl_symbol_pos(surface, syms[i]);
            return hl_error_set(err, HL_EINVAL, surface, pos, pos >= 0 ? (int)strlen(syms[i]) : 0,
                                "unknown symbol '%s' in the surface (not a variable, H, or a "
                                "parameter with a value)",
                                syms[i]);
        }
        nvars++;
    }
    if (nvars == 0)
        return hl_error_set(err, HL_EINVAL, surface, 0,
                            (int)strlen(surface) > 0 ? (int)strlen(surface) : 1,
                            "the surface does not depend on the state: it is never crossed");
    out->g = g;
    /* x = c (or c = x): a coordinate section, which section seeding needs */
    const hl_expr *var = lhs->kind == HL_SYM                  ? lhs
                         : rhs != NULL && rhs->kind == HL_SYM ? rhs
                                                              : NULL;
    const hl_expr *val = var == lhs ? rhs : lhs;
    if (var != NULL && val != NULL && hl_expr_symbols(val, syms, 1) == 0 &&
        hl_expr_eval_d(&out->value, val, 0, NULL, NULL, NULL) == HL_OK && isfinite(out->value))
        for (int j = 0; j < 2 * N; j++)
            if (strcmp(var->name, var_name(sys, j)) == 0)
                out->var = j;
    return HL_OK;
}

static void event_clear(hl_run *r)
{
    hl_event_free(r->ev);
    hl_tape_free(r->ev_tape);
    free(r->ev_z);
    r->ev = NULL;
    r->ev_tape = NULL;
    r->ev_z = NULL;
}

/* A surface whose every first derivative is a number (q = c, a plane) is
 * affine: the event then skips the Taylor-mode pass of its tape. */
static void declare_affine(hl_event *ev, hl_tape *tape, const hl_expr *g, hl_run *r)
{
    int n2 = 2 * r->N;
    double *grad = hl_xmalloc((size_t)n2 * sizeof *grad),
           *zero = hl_xcalloc((size_t)n2, sizeof *zero);
    int affine = 1;
    for (int i = 0; i < n2 && affine; i++) {
        const hl_expr *d = hl_expr_diff(hl_system_pool(r->sys), g, r->names[i]);
        affine = d->kind == HL_NUM && hl_expr_eval_d(&grad[i], d, 0, NULL, NULL, NULL) == HL_OK &&
                 isfinite(grad[i]);
    }
    double g0;
    hl_tape_eval_d(&g0, zero, tape);
    if (affine && isfinite(g0))
        hl_event_set_affine(ev, grad, g0);
    free(grad), free(zero);
}

hl_status hl_run_event(hl_run *r, const char *surface, hl_event_dir dir, long stop_after,
                       hl_run_crossing_fn fn, void *arg, hl_error *err)
{
    hl_run_surface_info info;
    int st = hl_run_surface(&info, r->sys, surface, err);
    if (st != HL_OK)
        return st;
    hl_tape *g = NULL;
    hl_event *ev = NULL;
    st = hl_tape_new(&g, &info.g, 1, r->names, 2 * r->N, err);
    if (st == HL_OK)
        st = hl_event_new(&ev, g, dir, err);
    if (st == HL_OK)
        declare_affine(ev, g, info.g, r);
    if (st != HL_OK) {
        hl_tape_free(g);
        return st;
    }
    event_clear(r);
    r->ev_tape = g;
    r->ev = ev;
    r->ev_fn = fn;
    r->ev_arg = arg;
    r->ev_stop = stop_after > 0 ? stop_after : 0;
    int n2 = 2 * r->N;
    r->ev_z = hl_xcalloc((size_t)(4 * n2), sizeof *r->ev_z);
    return HL_OK;
}

int hl_run_event_order(const hl_run *r)
{
    return r->stepper == NULL && r->step == NULL ? 0 : HL_EVENT_HERMITE_ORDER;
}

int hl_run_crossing_(hl_run *r, double t, const double *z, hl_run_stats *s)
{
    hl_tape_eval_d(r->vals, z, r->obs);
    hl_run_crossing c = {s->crossings, t, z, r->vals[0]};
    s->crossings++;
    s->t_crossing = t;
    int u = r->ev_fn != NULL ? r->ev_fn(&c, r->ev_arg) : 0;
    if (u != 0)
        return u;
    if (r->ev_stop > 0 && s->crossings >= r->ev_stop) {
        r->ev_stopped = 1;
        return HL_RUN_EV_STOP;
    }
    return 0;
}

/* Fixed step k-1 -> k: ev_z holds z_{k-1} and f_{k-1} (g_{k-1} in ev_g);
 * r->z is z_k.  The crossings in between, on the Hermite cubic, each
 * search going on from the last crossing.  k = 0 only keeps z_0. */
int hl_run_event_step_(hl_run *r, long k, double dt, hl_run_stats *s)
{
    int n2 = 2 * r->N;
    double *zp = r->ev_z, *fp = zp + n2, *f = fp + n2, *zc = f + n2;
    hl_tape_eval_d(f, r->z, r->vf);
    double t0 = (double)(k - 1) * dt, ta = 0, ga = r->ev_g, tau;
    while (k > 0 && ta < dt && hl_event_hermite(r->ev, zp, fp, r->z, f, dt, ta, ga, &tau, zc)) {
        int st = hl_run_crossing_(r, t0 + tau, zc, s);
        if (st != 0)
            return st;
        ta = tau;
        ga = hl_event_value(r->ev, zc);
    }
    memcpy(zp, r->z, (size_t)n2 * sizeof *zp);
    memcpy(fp, f, (size_t)n2 * sizeof *fp);
    r->ev_g = hl_event_value(r->ev, r->z);
    return 0;
}
