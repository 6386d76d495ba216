/* The Taylor integrator on several members at once (flow.h, hl_flow_batch):
 * the members' recursions run side by side in the SIMD lanes of one
 * hl_tape_batch, and each lane steps by its own coefficients exactly as
 * flow.c's driver does, so that each member ends where hl_flow_evolve
 * would have taken it, to the last bit.  A lane whose member is done (or
 * failed) takes the next member waiting: the lanes stay busy until fewer
 * members are left than lanes.
 *
 * NOTE: the polynomial arithmetic is flow_poly.h's, shared with flow.c;
 * advance and add_norms are flow.c's written lane by lane here (the lanes'
 * loops innermost, so that they run side by side): flow/t-batch compares
 * every member with hl_flow_evolve bit for bit, so a change to one of them
 * alone fails it. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "flow/flow_impl.h"
#include "flow/flow_poly.h"
#include "hamlie/flow.h"

/* One lane: the member it integrates and that member's driver state
 * (flow.c's drive, unrolled into a state machine). */
typedef struct lane {
    int member; /* -1: idle */
    double thi, tlo, tend, dir;
    int first;
    long nsteps;
    hl_flow_pace pace;
    /* on a grid (hl_flow_batch_grid): the next output k (at k * dt), the
     * last of the segment and of the member */
    double dt;
    long k, kseg, kend;
} lane;

struct hl_flow_batch {
    hl_tape *f;
    hl_tape_batch *tb;
    int n, p, L;
    hl_flow_tols tols;
    hl_flow_rule rule; /* hl_flow_new's order and step ratio */
    lane *lanes;
    /* by component i and lane l at i * L + l, so that the lanes' sums run
     * side by side: the states, their carried rounding (flow.c's zlo),
     * the states after the step and the rounding they carry */
    double *z, *zlo, *znew, *lonew;
    double *h;            /* L: each lane's step, signed (0: no step) */
    double *coef;         /* n * (p+1): one lane's coefficients, gathered */
    double *zt, *dz, *fz; /* n each: check_step's scratch */
    double *zo;           /* L * n: each lane's last output, contiguous */
    double eps;
    int check;
    int vec; /* the loops' build with FMA instructions (flow_poly.h) */
};

hl_status hl_flow_batch_new(hl_flow_batch **out, hl_tape *f, double atol, double rtol, int lanes,
                            hl_error *err)
{
    *out = NULL;
    hl_flow *single; /* the same checks and order as hl_flow_new */
    hl_status st = hl_flow_new(&single, f, atol, rtol, err);
    if (st != HL_OK)
        return st;
    int p = hl_flow_order(single);
    hl_flow_free(single);
    hl_tape_batch *tb;
    if ((st = hl_tape_batch_new(&tb, f, p, lanes, err)) != HL_OK)
        return st;
    hl_flow_batch *b = hl_xcalloc(1, sizeof *b);
    b->f = f;
    b->tb = tb;
    b->n = hl_tape_ninputs(f);
    b->p = p;
    b->L = lanes;
    hl_flow_rule_for(&b->rule, hl_flow_tols_set(&b->tols, atol, rtol), f);
    b->lanes = hl_xcalloc((size_t)lanes, sizeof *b->lanes);
    for (int l = 0; l < lanes; l++)
        b->lanes[l].member = -1;
    size_t nl = (size_t)b->n * (size_t)lanes;
    b->z = hl_xcalloc(nl, sizeof(double));
    b->zlo = hl_xcalloc(nl, sizeof(double));
    b->znew = hl_xcalloc(nl, sizeof(double));
    b->lonew = hl_xcalloc(nl, sizeof(double));
    b->h = hl_xcalloc((size_t)lanes, sizeof(double));
    b->coef = hl_xcalloc((size_t)b->n * (p + 1), sizeof *b->coef);
    b->zt = hl_xcalloc((size_t)b->n, sizeof *b->zt);
    b->dz = hl_xcalloc((size_t)b->n, sizeof *b->dz);
    b->fz = hl_xcalloc((size_t)b->n, sizeof *b->fz);
    b->zo = hl_xcalloc(nl, sizeof *b->zo);
    b->vec = hl_flow_vec_ok();
    *out = b;
    return HL_OK;
}

/* The first step's length at z0 (flow.c's step_size, without the check
 * of its defect): 0 if it cannot be taken. */
static double first_step(hl_tape *f, int p, double atol, double rtol, const double *z0)
{
    const int n = hl_tape_ninputs(f), S = p + 1;
    double *c = hl_xcalloc((size_t)n * S, sizeof *c), win[HL_FLOW_WINDOW], eps;
    for (int i = 0; i < n; i++)
        c[(size_t)i * S] = z0[i];
    int ok = hl_tape_taylor_ode_d(c, p, f, NULL) == HL_OK, check;
    hl_flow_tols tols;
    hl_flow_rule rule;
    hl_flow_rule_for(&rule, hl_flow_tols_set(&tols, atol, rtol), f);
    double s = hl_flow_scale(&tols, hl_flow_norms(win, c, n, p, 1), &eps);
    double h = ok ? hl_flow_step_for(&check, eps, s, &rule, win) : 0;
    free(c);
    return h > 0 ? h : 0; /* NaN: 0 */
}

int hl_flow_batch_pays(hl_tape *f, double atol, double rtol, int lanes, long members,
                       const double *z0, double t)
{
    hl_flow *single;
    if (members <= 0 || hl_flow_new(&single, f, atol, rtol, NULL) != HL_OK)
        return 0;
    int p = hl_flow_order(single);
    hl_flow_free(single);
    double h = first_step(f, p, atol, rtol, z0);
    double steps = h > 0 ? ceil(fabs(t) / h) : 0; /* +inf: at rest, one step */
    double uses = fmin(steps * (double)members, 1e18);
    return steps > 0 && hl_tape_batch_pays(f, p, lanes, (long)fmax(uses, 1));
}

void hl_flow_batch_free(hl_flow_batch *b)
{
    if (b == NULL)
        return;
    free(b->lanes);
    free(b->z);
    free(b->zlo);
    free(b->znew);
    free(b->lonew);
    free(b->h);
    free(b->coef);
    free(b->zt);
    free(b->dz);
    free(b->fz);
    free(b->zo);
    hl_tape_batch_free(b->tb);
    free(b);
}

int hl_flow_batch_order(const hl_flow_batch *b)
{
    return b->p;
}
int hl_flow_batch_lanes(const hl_flow_batch *b)
{
    return b->L;
}
int hl_flow_batch_compiled(const hl_flow_batch *b)
{
    return hl_tape_batch_compiled(b->tb);
}

/* flow.c's advance for every lane at once, lane l by its own step h[l]
 * (the same operations per lane; the lanes' loops are innermost, so that
 * the compiler runs them side by side: AL lanes, a constant) */
HL_FLOW_INLINE void advance_lanes(double *z, double *lo, const double *coef, const double *h, int n,
                                  int p, const int AL)
{
    const int S = p + 1, top_e = p & ~1, top_o = (p - 1) | 1;
    double h2[HL_TAPE_BATCH_MAX_LANES], e[HL_TAPE_BATCH_MAX_LANES], o[HL_TAPE_BATCH_MAX_LANES];
    for (int l = 0; l < AL; l++)
        h2[l] = h[l] * h[l];
    for (int i = 0; i < n; i++) {
        const double *c = coef + (size_t)i * S * AL;
        for (int l = 0; l < AL; l++) {
            e[l] = c[top_e * AL + l];
            o[l] = top_o <= p ? c[top_o * AL + l] : 0;
        }
        for (int k = top_e - 2; k >= 2; k -= 2)
            for (int l = 0; l < AL; l++)
                e[l] = fma(e[l], h2[l], c[k * AL + l]);
        for (int k = top_o - 2; k >= 1; k -= 2)
            for (int l = 0; l < AL; l++)
                o[l] = fma(o[l], h2[l], c[k * AL + l]);
        for (int l = 0; l < AL; l++) {
            double a = c[l], b = fma(h[l], o[l], h2[l] * e[l]) + lo[i * AL + l], s = a + b,
                   bv = s - a;
            lo[i * AL + l] = (a - (s - bv)) + (b - bv);
            z[i * AL + l] = s;
        }
    }
}

static inline __attribute__((always_inline)) void advance_all(hl_flow_batch *b)
{
    const double *c = hl_tape_batch_coefs(b->tb);
    memcpy(b->lonew, b->zlo, (size_t)b->n * b->L * sizeof *b->zlo);
    switch (b->L) { /* the lane count a constant: the loops become vectors */
    case 1:
        advance_lanes(b->znew, b->lonew, c, b->h, b->n, b->p, 1);
        break;
    case 2:
        advance_lanes(b->znew, b->lonew, c, b->h, b->n, b->p, 2);
        break;
    case 4:
        advance_lanes(b->znew, b->lonew, c, b->h, b->n, b->p, 4);
        break;
    case 8:
        advance_lanes(b->znew, b->lonew, c, b->h, b->n, b->p, 8);
        break;
    default:
        advance_lanes(b->znew, b->lonew, c, b->h, b->n, b->p, HL_TAPE_BATCH_MAX_LANES);
    }
}
static HL_FLOW_VEC void advance_all_vec(hl_flow_batch *b)
{
    advance_all(b);
}
static void advance_all_plain(hl_flow_batch *b)
{
    advance_all(b);
}

/* ---- one lane's step ---------------------------------------------------------- */

/* lane l's coefficients out of the batch into b->coef (flow.c's layout) */
static void gather(hl_flow_batch *b, int l)
{
    const int S = b->p + 1, L = b->L;
    const double *z = hl_tape_batch_coefs(b->tb);
    for (int i = 0; i < b->n; i++)
        for (int k = 0; k < S; k++)
            b->coef[(size_t)i * S + k] = z[((size_t)i * S + k) * L + l];
}

/* flow.c's step_size on lane l's coefficients, where they are */
static int step_size(double *h, hl_flow_batch *b, int l, double t, hl_error *err)
{
    const int n = b->n, p = b->p, L = b->L;
    const double *c = hl_tape_batch_coefs(b->tb) + l;
    double win[HL_FLOW_WINDOW];
    double s = hl_flow_scale(&b->tols, hl_flow_norms(win, c, n, p, L), &b->eps);
    *h = hl_flow_step_for(&b->check, b->eps, s, &b->rule, win);
    if (isnan(*h))
        return hl_error_set(
            err, HL_EDOM, NULL, -1, 0,
            "the solution is not finite (Taylor coefficients overflow) at t = %.17g", t);
    if (*h < DBL_MIN || *h <= 4 * DBL_EPSILON * fabs(t))
        return hl_error_set(err, HL_ENOCONV, NULL, -1, 0,
                            "step size underflow (h = %g) at t = %.17g", *h, t);
    return HL_OK;
}

/* flow.c's check_step */
static int check_step(double *h, hl_flow_batch *b, double dir, double t, hl_error *err)
{
    const int n = b->n;
    for (;;) {
        poly_at(b->vec, b->zt, b->coef, n, b->p, dir * *h);
        poly_derivative_at(b->vec, b->dz, b->coef, n, b->p, dir * *h);
        hl_tape_eval_d(b->fz, b->zt, b->f);
        double defect = 0;
        for (int i = 0; i < n; i++) {
            double d = fabs(b->dz[i] - b->fz[i]);
            defect = d > defect || isnan(d) ? d : defect;
        }
        double next = hl_flow_shrink(*h, defect, b->eps, b->p);
        if (next == 0)
            return HL_OK;
        if (next <= 4 * DBL_EPSILON * fabs(t) || next < DBL_MIN)
            return hl_error_set(err, HL_ENOCONV, NULL, -1, 0,
                                "step size underflow (h = %g) at t = %.17g", next, t);
        *h = next;
    }
}

/* Lane l's step from its coefficients (flow.c's drive, the first half of
 * one turn of its loop): b->h[l], signed.  *st != HL_OK if it fails. */
static void lane_size(hl_flow_batch *b, lane *ln, int l, hl_status *st, hl_error *err)
{
    double rem = ln->dir * ((ln->tend - ln->thi) - ln->tlo), h;
    b->h[l] = 0;
    if ((*st = step_size(&h, b, l, ln->thi, err)) != HL_OK)
        return;
    if (h > rem)
        h = rem;
    if (b->check || ln->first) {
        gather(b, l);
        if ((*st = check_step(&h, b, ln->dir, ln->thi, err)) != HL_OK)
            return;
    }
    ln->first = 0;
    b->h[l] = ln->dir * h;
}

/* The second half, after advance_all: lane l's new state kept, its time
 * moved (flow.c's drive, the rest of the turn).  HL_OK, or the status
 * that ends its member. */
static hl_status lane_step(hl_flow_batch *b, lane *ln, int l, hl_error *err)
{
    const int n = b->n, L = b->L;
    double h = ln->dir * b->h[l], rem = ln->dir * ((ln->tend - ln->thi) - ln->tlo);
    int last = h == rem;
    for (int i = 0; i < n; i++)
        if (!isfinite(b->znew[i * L + l]))
            return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                                "the solution is not finite at t = %.17g", ln->thi + ln->dir * h);
    for (int i = 0; i < n; i++) {
        b->z[i * L + l] = b->znew[i * L + l];
        b->zlo[i * L + l] = b->lonew[i * L + l];
    }
    ln->nsteps++;
    if (last) {
        ln->thi = ln->tend;
        ln->tlo = 0;
    } else {
        time_add(&ln->thi, &ln->tlo, ln->dir * h);
    }
    double done;
    if (hl_flow_stalled(&ln->pace, h, &done))
        return hl_flow_no_progress(err, done, ln->thi);
    return HL_OK;
}

/* ---- the members through the lanes ------------------------------------------- */

typedef struct members {
    int B, next;
    double *t;        /* evolve: the times, in and out; grid: out, or NULL */
    const double *t1; /* evolve: the ends */
    const double *dt; /* grid: the spacing (NULL: evolve, no outputs) */
    const long *k0, *k1;
    long segment;
    hl_flow_batch_fn fn;
    void *arg;
    double *z;
    hl_status *status;
    long *nsteps;
    hl_error *errs;
    int failed;     /* the first member (by index) that failed, or B */
    hl_error first; /* and its error */
} members;

static void finish(hl_flow_batch *b, lane *ln, members *m, hl_status st, const hl_error *e)
{
    int i = ln->member, l = (int)(ln - b->lanes);
    for (int c = 0; c < b->n; c++)
        m->z[(size_t)i * b->n + c] = b->z[c * b->L + l];
    if (m->t != NULL)
        m->t[i] = ln->thi + ln->tlo;
    m->status[i] = st;
    if (m->nsteps != NULL)
        m->nsteps[i] = ln->nsteps;
    if (m->errs != NULL) {
        if (st == HL_OK)
            hl_error_clear(&m->errs[i]);
        else
            m->errs[i] = *e;
    }
    if (st != HL_OK && i < m->failed) {
        m->failed = i;
        m->first = *e;
    }
    ln->member = -1;
}

static double *lane_out(hl_flow_batch *b, int l)
{
    return b->zo + (size_t)l * b->n;
}

/* The time of the lane's next output (its grid's k * dt, as
 * hl_run_adaptive writes its output times) */
static double next_out(const lane *ln)
{
    return (double)ln->k * ln->dt;
}

/* flow.c's drive at the top of its loop: the outputs at or before the
 * lane's time, with its state.  0 or the callback's return. */
static int outputs_before(hl_flow_batch *b, lane *ln, int l, members *m, hl_error *e)
{
    if (m->dt == NULL)
        return 0;
    double *zo = lane_out(b, l);
    for (; ln->k <= ln->kseg && ln->dir * ((next_out(ln) - ln->thi) - ln->tlo) <= 0; ln->k++) {
        for (int i = 0; i < b->n; i++)
            zo[i] = b->z[i * b->L + l];
        int st = m->fn(ln->member, ln->k, next_out(ln), zo, e, m->arg);
        if (st != 0)
            return st;
    }
    return 0;
}

/* flow.c's step_outputs (without events): the outputs inside lane l's
 * step, on the step's polynomial.  0 or the callback's return. */
static int outputs_in_step(hl_flow_batch *b, lane *ln, int l, members *m, hl_error *e)
{
    if (m->dt == NULL)
        return 0;
    double h = ln->dir * b->h[l], tau;
    double *zo = lane_out(b, l);
    int gathered = 0;
    for (; ln->k <= ln->kseg && (tau = ln->dir * ((next_out(ln) - ln->thi) - ln->tlo)) <= h;
         ln->k++) {
        if (!gathered)
            gather(b, l), gathered = 1;
        poly_at(b->vec, zo, b->coef, b->n, b->p, ln->dir * tau);
        int st = m->fn(ln->member, ln->k, next_out(ln), zo, e, m->arg);
        if (st != 0)
            return st;
    }
    return 0;
}

/* The lane's member from (thi, its state), as a call of flow.c's drive
 * begins: the carried rounding and the first step's check afresh. */
static void begin(hl_flow_batch *b, lane *ln, int l, const double *z)
{
    for (int c = 0; c < b->n; c++) {
        b->z[c * b->L + l] = z[c];
        b->zlo[c * b->L + l] = 0;
    }
    ln->tlo = 0;
    ln->dir = ln->tend >= ln->thi ? 1 : -1;
    ln->first = 1;
}

/* The next segment of a grid member: from its last output, as
 * hl_run_adaptive's next hl_flow_run (the pace goes on, as the flow's). */
static void next_segment(hl_flow_batch *b, lane *ln, int l, members *m)
{
    long left = ln->kend - ln->kseg;
    ln->thi = (double)ln->kseg * ln->dt;
    ln->kseg += m->segment > 0 && m->segment < left ? m->segment : left;
    ln->tend = (double)ln->kseg * ln->dt;
    begin(b, ln, l, lane_out(b, l));
}

/* The lane between two steps: its outputs due, and when its segment is
 * at its end, the next one or the member finished.  1 if it still needs
 * a step. */
static int settle(hl_flow_batch *b, lane *ln, members *m)
{
    int l = (int)(ln - b->lanes);
    for (;;) {
        hl_error e;
        int st = outputs_before(b, ln, l, m, &e);
        if (st != 0) {
            finish(b, ln, m, st, &e);
            return 0;
        }
        if (ln->dir * ((ln->tend - ln->thi) - ln->tlo) > 0)
            return 1;
        if (m->dt == NULL || ln->kseg >= ln->kend) {
            finish(b, ln, m, HL_OK, NULL);
            return 0;
        }
        next_segment(b, ln, l, m);
    }
}

/* Lane ln takes the next member that needs a step (members already at
 * their end, or with times that are not finite, finish at once). */
static void take_next(hl_flow_batch *b, lane *ln, members *m)
{
    int l = (int)(ln - b->lanes);
    while (ln->member < 0 && m->next < m->B) {
        int i = m->next++;
        ln->member = i;
        const double *z = m->z + (size_t)i * b->n;
        if (m->dt != NULL) {
            ln->dt = m->dt[i];
            ln->k = m->k0[i] + 1;
            ln->kseg = ln->kend = m->k0[i];
            ln->thi = ln->tend = (double)m->k0[i] * ln->dt;
            memcpy(lane_out(b, l), z, (size_t)b->n * sizeof *z);
        } else {
            ln->thi = m->t[i];
            ln->tend = m->t1[i];
        }
        begin(b, ln, l, z);
        ln->nsteps = 0;
        ln->pace = (hl_flow_pace){0};
        hl_error e;
        if (!isfinite(ln->thi) || !isfinite(ln->tend))
            finish(b, ln, m, hl_error_set(&e, HL_EINVAL, NULL, -1, 0, "times must be finite"), &e);
        else if (m->dt != NULL &&
                 !(ln->dt > 0 && m->k1[i] >= m->k0[i] && isfinite((double)m->k1[i] * ln->dt)))
            finish(b, ln, m,
                   hl_error_set(&e, HL_EINVAL, NULL, -1, 0,
                                "a grid needs dt > 0 and k1 >= k0, its times finite"),
                   &e);
        else {
            ln->kend = m->dt != NULL ? m->k1[i] : 0;
            settle(b, ln, m);
        }
    }
}

/* the lanes' states as coefficient 0 of the batch; an idle lane repeats
 * a busy one (its result is not read; a real state keeps it finite) */
static void load_states(hl_flow_batch *b, int busy)
{
    const int S = b->p + 1, L = b->L;
    double *z = hl_tape_batch_coefs(b->tb);
    for (int l = 0; l < L; l++) {
        int from = b->lanes[l].member >= 0 ? l : busy;
        for (int i = 0; i < b->n; i++)
            z[(size_t)i * S * L + l] = b->z[i * L + from];
    }
}

/* One turn of every busy lane: the steps' sizes and the outputs inside
 * them, the states advanced side by side, the lanes settled. */
static void turn(hl_flow_batch *b, members *m, int busy)
{
    load_states(b, busy);
    hl_tape_batch_ode(b->tb);
    hl_status st;
    hl_error e;
    for (int l = 0; l < b->L; l++) {
        lane *ln = &b->lanes[l];
        if (ln->member < 0)
            continue;
        lane_size(b, ln, l, &st, &e);
        if (st == HL_OK)
            st = outputs_in_step(b, ln, l, m, &e);
        if (st != HL_OK) {
            b->h[l] = 0; /* no step */
            finish(b, ln, m, st, &e);
        }
    }
    (b->vec ? advance_all_vec : advance_all_plain)(b);
    for (int l = 0; l < b->L; l++) {
        lane *ln = &b->lanes[l];
        if (ln->member < 0)
            continue;
        if ((st = lane_step(b, ln, l, &e)) != HL_OK)
            finish(b, ln, m, st, &e);
        else
            settle(b, ln, m);
    }
}

static hl_status run_members(hl_flow_batch *b, members *m, hl_error *err)
{
    for (;;) {
        int busy = -1;
        for (int l = 0; l < b->L; l++) {
            take_next(b, &b->lanes[l], m);
            if (b->lanes[l].member >= 0)
                busy = l;
        }
        if (busy < 0)
            break;
        turn(b, m, busy);
    }
    if (m->failed == m->B)
        return HL_OK;
    return hl_error_set(err, m->first.status, NULL, -1, 0, "member %d: %s", m->failed,
                        m->first.msg);
}

/* What evolve and grid share of their members: the states and what is
 * told of each; none failed yet */
static members members_of(int B, double *z, hl_status *status, long *nsteps, hl_error *errs)
{
    return (members){.B = B, .z = z, .status = status, .nsteps = nsteps, .errs = errs, .failed = B};
}

hl_status hl_flow_batch_evolve(hl_flow_batch *b, int B, double *t, const double *t1, double *z,
                               hl_status *status, long *nsteps, hl_error *errs, hl_error *err)
{
    if (B < 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "a negative number of members (%d)", B);
    members m = members_of(B, z, status, nsteps, errs);
    m.t = t;
    m.t1 = t1;
    return run_members(b, &m, err);
}

hl_status hl_flow_batch_grid(hl_flow_batch *b, int B, const double *dt, const long *k0,
                             const long *k1, long segment, double *z, hl_flow_batch_fn fn,
                             void *arg, hl_status *status, long *nsteps, hl_error *errs,
                             hl_error *err)
{
    if (B < 0 || fn == NULL)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "a grid needs B >= 0 members (%d) and a callback", B);
    members m = members_of(B, z, status, nsteps, errs);
    m.dt = dt;
    m.k0 = k0;
    m.k1 = k1;
    m.segment = segment;
    m.fn = fn;
    m.arg = arg;
    return run_members(b, &m, err);
}
