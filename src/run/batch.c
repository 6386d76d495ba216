/* A fixed-step run of many members at once (hl_run_fixed_batch, run.h):
 * the members of an explicit scheme step side by side in the SIMD lanes of
 * one compiled loop, the fused tape of hl_run_fixed's own fast path
 * (drive.c) over lanes (tape.h, hl_tape_iter_batch), so that each member
 * ends with the bits that hl_run_fixed gives it alone; where lanes do not
 * apply or do not pay, the members go through hl_run_fixed one after the
 * other.
 *
 * A lane holds a member until it has taken its n steps, then takes the next
 * member waiting; a lane with no member left repeats a busy lane's state
 * (its results are dropped).  The loop stops before a step at which some
 * lane's step or H is not finite: that lane's member is run again alone by
 * hl_run_fixed, whose fast path stops there too and hands the step to the
 * scheme's stepper, so that the failure (its step, time, message and the
 * statistics up to it) is exactly the single run's; the other lanes go on
 * from where they are. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "run/run_impl.h"

/* NOTE: the lanes' loop costs about what the scalar loop costs to compile
 * and saves more per member-step than the scalar loop does over the
 * stepper, so the scalar loop's break-even counted in member-steps
 * (hl_tape_compile_pays) is a safe bound for it. */

hl_status hl_run_set_lanes(hl_run *r, int lanes, hl_error *err)
{
    if (lanes < 0 || lanes > HL_TAPE_BATCH_MAX_LANES || (lanes & (lanes - 1)) != 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "lanes must be 0 (the default) or a power of 2 from 1 to %d (not %d)",
                            HL_TAPE_BATCH_MAX_LANES, lanes);
    r->lanes = lanes;
    return HL_OK;
}

static int lanes_wanted(const hl_run *r)
{
    return r->lanes > 0 ? r->lanes : hl_tape_lanes_native();
}

/* The loop over lanes, compiled, if members can share it: an explicit
 * scheme's run as hl_run_fixed's fast path would take it (no reference,
 * events or progress callback; machine code on) and B * n member-steps
 * enough to pay for compiling it — or the loop already compiled in r: its
 * cost is paid, and asking again per call would make a small batch after
 * large ones (a sweep's last members, an MPI rank's small chunk) run one
 * member at a time, each in the interpreter.  A refusal is kept: the model
 * asked again for as many member-steps or fewer would refuse again (it
 * looks up the disk cache, a file, each time).  NULL: one member at a
 * time. */
static hl_tape_iter_batch *lane_loop(hl_run *r, long B, long n)
{
    int L = lanes_wanted(r);
    if (L < 2 || B < 2 || r->stepper == NULL || r->ref_on || r->ev != NULL || r->progress != NULL ||
        !r->jit || !hl_tape_jit_available())
        return NULL;
    if (r->lane_loop != NULL && hl_tape_iter_batch_lanes(r->lane_loop) == L &&
        hl_tape_iter_batch_compiled(r->lane_loop))
        return r->lane_loop;
    if (B * n <= r->lanes_refused) /* the model's answer grows with the steps: no again */
        return NULL;
    hl_tape *fused = hl_run_fused_(r);
    if (fused == NULL || !hl_tape_compile_pays(fused, HL_COMPILE_LOOP, B * n)) {
        r->lanes_refused = B * n; /* asking looks up the disk cache: once is enough */
        return NULL;
    }
    if (r->lane_loop != NULL && hl_tape_iter_batch_lanes(r->lane_loop) != L) {
        hl_tape_iter_batch_free(r->lane_loop);
        r->lane_loop = NULL;
    }
    if (r->lane_loop == NULL && hl_tape_iter_batch_new(&r->lane_loop, fused, L, 1, NULL) != HL_OK)
        return NULL;
    return hl_tape_iter_batch_compiled(r->lane_loop) ? r->lane_loop : NULL;
}

/* ---- the members' bookkeeping ----------------------------------------------------- */

typedef struct batch {
    hl_run *r;
    hl_tape_iter_batch *loop;
    hl_tape *fused;  /* the tape the loop iterates */
    int L, n2;       /* lanes; 2N */
    long B, n, next; /* members, steps, the next member to start */
    double dt, t;
    const double *z0;
    double *z;
    hl_run_stats *stats;
    hl_status *status;
    hl_error *errs;   /* the caller's, or NULL: then */
    hl_error scratch; /* each member's error, */
    hl_error first;   /* and the first failing member's (the lowest index) */
    long nfirst;      /* its index, or B */
    long *member;     /* by lane: its member, or -1 */
    long *k;          /* by lane: steps done */
    double *w0, *dev; /* by lane: H0 and max |H - H0| so far */
} batch;

static hl_error *err_of(batch *b, long i)
{
    hl_error *e = b->errs != NULL ? &b->errs[i] : &b->scratch;
    hl_error_clear(e);
    return e;
}

/* Member i's status is st: without the caller's errors, the first failing
 * member's message is kept for the call's. */
static void set_status(batch *b, long i, hl_status st)
{
    b->status[i] = st;
    if (st != HL_OK && b->errs == NULL && i < b->nfirst) {
        b->first = b->scratch;
        b->nfirst = i;
    }
}

/* Row 0 of member i as hl_run_fixed makes it (drive.c: start, row): the
 * statistics at t = 0 (zeroed if it cannot start), z = z0.  0 if it
 * cannot start (status and error set). */
static int start_member(batch *b, long i, hl_run_stats *s)
{
    const double *z0 = b->z0 + i * b->n2;
    memmove(b->z + i * b->n2, z0, (size_t)b->n2 * sizeof *b->z); /* z may be z0 */
    memset(s, 0, sizeof *s);
    set_status(b, i, hl_run_check_start(b->r, z0, err_of(b, i))); /* H at z0 into r->vals */
    if (b->status[i] != HL_OK)
        return 0;
    s->nsteps = b->n;
    s->sigma = s->max_err = s->err_final = NAN;
    s->H0 = s->H = b->r->vals[0];
    s->max_dH = fmax(0, fabs(s->H - s->H0));
    return 1;
}

/* Member i alone, through hl_run_fixed. */
static void alone(batch *b, long i)
{
    hl_run_stats s;
    if (start_member(b, i, &s)) {
        hl_status st =
            hl_run_fixed(b->r, b->z0 + i * b->n2, b->dt, b->t, 1, NULL, NULL, &s, err_of(b, i));
        set_status(b, i, st);
        memcpy(b->z + i * b->n2, hl_run_state(b->r), (size_t)b->n2 * sizeof *b->z);
    }
    if (b->stats != NULL)
        b->stats[i] = s;
}

/* Lane l takes the next member that starts; -1 when none is left. */
static void fill_lane(batch *b, int l)
{
    double *zs = hl_tape_iter_batch_state(b->loop);
    b->member[l] = -1;
    while (b->next < b->B) {
        long i = b->next++;
        hl_run_stats s;
        if (!start_member(b, i, &s)) {
            if (b->stats != NULL)
                b->stats[i] = s;
            continue;
        }
        if (b->stats != NULL)
            b->stats[i] = s;
        b->member[l] = i;
        b->k[l] = 0;
        b->w0[l] = s.H0;
        b->dev[l] = s.max_dH;
        for (int c = 0; c < b->n2; c++)
            zs[(size_t)c * b->L + l] = b->z0[i * b->n2 + c];
        zs[(size_t)b->n2 * b->L + l] = b->dt;
        return;
    }
}

/* A lane without a member repeats lane `from`'s state, so that it computes
 * nothing that could stop the loop on its own. */
static void copy_lane(batch *b, int l, int from)
{
    double *zs = hl_tape_iter_batch_state(b->loop);
    for (int c = 0; c <= b->n2; c++)
        zs[(size_t)c * b->L + l] = zs[(size_t)c * b->L + from];
    b->w0[l] = b->w0[from];
    b->dev[l] = b->dev[from];
}

/* Lane l's member has taken its n steps: row n as hl_run_fixed makes it
 * (H at the final state by the run's tape of H and the observers). */
static void finish_lane(batch *b, int l)
{
    long i = b->member[l];
    hl_run *r = b->r;
    double *z = b->z + i * b->n2;
    const double *zs = hl_tape_iter_batch_state(b->loop);
    for (int c = 0; c < b->n2; c++)
        z[c] = zs[(size_t)c * b->L + l];
    b->member[l] = -1;
    hl_tape_eval_d(r->vals, z, r->obs);
    if (!isfinite(r->vals[0])) { /* a blow-up in the last state: its message is the run's */
        alone(b, i);
        return;
    }
    b->status[i] = HL_OK;
    if (b->stats != NULL) {
        hl_run_stats *s = &b->stats[i];
        s->H = r->vals[0];
        s->max_dH = fmax(b->dev[l], fabs(s->H - s->H0));
        s->steps = b->n;
        s->t = (double)b->n * b->dt;
    }
}

/* After the loop stopped short: the lanes whose next step (or H) is not
 * finite give their members to hl_run_fixed.  Returns how many. */
static int drop_failing(batch *b)
{
    hl_tape *t = b->fused;
    const double *zs = hl_tape_iter_batch_state(b->loop);
    double *in = hl_xmalloc((size_t)(b->n2 + 1) * 2 * sizeof *in), *out = in + b->n2 + 1;
    int dropped = 0;
    for (int l = 0; l < b->L; l++) {
        if (b->member[l] < 0)
            continue;
        for (int c = 0; c <= b->n2; c++)
            in[c] = zs[(size_t)c * b->L + l];
        hl_tape_eval_d(out, in, t);
        int finite = 1;
        for (int c = 0; c <= b->n2; c++)
            finite &= isfinite(out[c]) != 0;
        if (!finite) {
            alone(b, b->member[l]);
            b->member[l] = -1;
            dropped++;
        }
    }
    free(in);
    return dropped;
}

/* One call of the loop: as many steps as the busy lane with the fewest
 * left needs; then the lanes done or failing let their members go.
 * Returns 0 when no lane is busy. */
static int round_of_steps(batch *b)
{
    int busy = -1;
    long m = 0;
    for (int l = 0; l < b->L; l++) {
        if (b->member[l] < 0)
            fill_lane(b, l);
        if (b->member[l] >= 0 && (busy < 0 || b->n - b->k[l] < m))
            busy = l, m = b->n - b->k[l];
    }
    if (busy < 0)
        return 0;
    for (int l = 0; l < b->L; l++)
        if (b->member[l] < 0)
            copy_lane(b, l, busy);
    long done = hl_tape_iter_batch_watch(b->loop, m, b->w0, b->dev);
    for (int l = 0; l < b->L; l++)
        if (b->member[l] >= 0 && (b->k[l] += done) == b->n)
            finish_lane(b, l);
    if (done < m && drop_failing(b) == 0) /* cannot happen (the same bits); never loop */
        for (int l = 0; l < b->L; l++)
            if (b->member[l] >= 0) {
                alone(b, b->member[l]);
                b->member[l] = -1;
            }
    return 1;
}

static void run_lanes(batch *b)
{
    b->member = hl_xmalloc((size_t)b->L * sizeof *b->member);
    b->k = hl_xcalloc((size_t)b->L, sizeof *b->k);
    b->w0 = hl_xcalloc((size_t)b->L, sizeof *b->w0);
    b->dev = hl_xcalloc((size_t)b->L, sizeof *b->dev);
    for (int l = 0; l < b->L; l++)
        b->member[l] = -1;
    while (round_of_steps(b))
        ;
    free(b->member), free(b->k), free(b->w0), free(b->dev);
}

/* HL_OK, or the first failing member's status with its message in err. */
static hl_status outcome(const batch *b, hl_error *err)
{
    for (long i = 0; i < b->B; i++) {
        if (b->status[i] == HL_OK)
            continue;
        if (err != NULL) {
            const hl_error *e = b->errs != NULL ? &b->errs[i] : &b->first;
            const char *msg = e->msg[0] ? e->msg : hl_status_string(b->status[i]);
            hl_error_set(err, b->status[i], NULL, -1, 0, "member %ld: %s", i, msg);
        }
        return b->status[i];
    }
    return HL_OK;
}

hl_status hl_run_fixed_batch(hl_run *r, long B, const double *z0, double dt, double t, double *z,
                             hl_run_stats *stats, hl_status *status, hl_error *errs, hl_error *err)
{
    if (B < 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "a batch of %ld members", B);
    if (r->stepper == NULL && r->step == NULL)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "this run has no scheme");
    batch b = {.r = r,
               .n2 = 2 * r->N,
               .B = B,
               .dt = dt,
               .t = t,
               .z0 = z0,
               .z = z,
               .stats = stats,
               .status = status,
               .errs = errs,
               .nfirst = B};
    hl_error_clear(&b.first);
    int st = hl_run_nsteps(&b.n, dt, t, err);
    if (st != HL_OK) {
        for (long i = 0; i < B; i++)
            status[i] = st;
        return st;
    }
    b.loop = lane_loop(r, B, b.n);
    if (b.loop != NULL) {
        b.L = hl_tape_iter_batch_lanes(b.loop);
        b.fused = r->fused; /* kept while r lives, even if its own compilation fails */
        run_lanes(&b);
    } else
        for (long i = 0; i < B; i++)
            alone(&b, i);
    return outcome(&b, err);
}

int hl_run_batch_lanes(hl_run *r, long B, double dt, double t)
{
    long n;
    if (hl_run_nsteps(&n, dt, t, NULL) != HL_OK)
        return 1;
    hl_tape_iter_batch *loop = lane_loop(r, B, n);
    return loop != NULL ? hl_tape_iter_batch_lanes(loop) : 1;
}
