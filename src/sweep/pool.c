/* hl_sweep_run: the members on POSIX threads.  The members listed are cut
 * into units — runs of consecutive members of one (point, paramset), so the
 * chaos indicators are computed once per unit — handed out one at a time
 * through an atomic counter.  Each thread has its own worker (system, runs,
 * chaos object); results and progress go out one call at a time under a
 * mutex.  A row depends only on its member, never on the thread.  With
 * members to run in SIMD lanes (lanes.c) a unit is several such runs,
 * enough of those members to fill the lanes a few times over, and the worker
 * runs them in lanes before handing the unit's rows out in order. */
#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "sweep/sweep_impl.h"

typedef struct pool {
    const hl_sweep *sw;
    const long *members; /* NULL: 0 .. n-1 */
    long n;
    long *unit; /* nunits + 1 starts in the list */
    long nunits, longest; /* units, and the longest's members */
    atomic_long next; /* the next unit to hand out */
    atomic_int stop;  /* a callback asked to stop */
    pthread_mutex_t lock;
    long done;  /* under lock: members delivered */
    long shown; /* under lock: the progress line's count, which also holds
                   members run in lanes and not yet delivered */
    hl_sweep_fn fn;
    void *fn_arg;
    hl_progress_fn progress;
    void *progress_arg;
} pool;

static long member_at(const pool *p, long i)
{
    return p->members != NULL ? p->members[i] : i;
}

/* Members m and m' are in one group when they share point and paramset. */
static long group_of(const hl_sweep *sw, long m)
{
    return m / ((long)sw->nschemes * sw->ndts);
}

static int in_lanes_at(const pool *p, long i)
{
    return sweep_in_lanes(p->sw, sweep_locate(p->sw, member_at(p, i)).scheme);
}

/* Units of whole groups; with lanes, groups joined until a unit holds
 * `per_unit` members that may run in lanes (per_unit 0: a group each). */
static void cut_units(pool *p, long per_unit)
{
    p->unit = hl_xcalloc((size_t)p->n + 1, sizeof *p->unit);
    p->nunits = 0;
    long lanes = 0; /* in the unit so far */
    for (long i = 0; i < p->n; i++) {
        int new_group =
            i == 0 || group_of(p->sw, member_at(p, i)) != group_of(p->sw, member_at(p, i - 1));
        if (new_group && (i == 0 || lanes >= per_unit)) {
            p->unit[p->nunits++] = i;
            lanes = 0;
        }
        lanes += per_unit > 0 && in_lanes_at(p, i);
    }
    p->unit[p->nunits] = p->n;
    p->longest = 0;
    for (long u = 0; u < p->nunits; u++)
        if (p->unit[u + 1] - p->unit[u] > p->longest)
            p->longest = p->unit[u + 1] - p->unit[u];
}

/* The members per unit that lanes may run, when they may, else 0. */
static long lanes_per_unit(const pool *p, int threads)
{
    if (!sweep_has_lanes(p->sw) || sweep_lanes_mode() == SWEEP_LANES_OFF)
        return 0;
    long lanes = 0;
    for (long i = 0; i < p->n; i++)
        lanes += in_lanes_at(p, i);
    return sweep_lanes_unit(p->sw, lanes, threads);
}

/* The progress line at p->shown; caller locks.  Non-zero: stop. */
static int show(pool *p)
{
    return p->progress != NULL && p->progress((double)p->shown, (double)p->n, p->progress_arg) != 0;
}

/* Members that ran in lanes (sweep_worker_prepare): counted as they run,
 * since their rows are handed out only once the whole unit has run. */
static void ran_in_lanes(long members, void *arg)
{
    pool *p = arg;
    pthread_mutex_lock(&p->lock);
    p->shown += members;
    int stop = show(p);
    pthread_mutex_unlock(&p->lock);
    if (stop)
        atomic_store(&p->stop, 1);
}

/* Hands one result out, under the lock; counted: ran_in_lanes showed it. */
static void deliver(pool *p, const hl_sweep_result *r, int counted)
{
    pthread_mutex_lock(&p->lock);
    p->done++;
    p->shown += !counted;
    int stop = p->fn != NULL && p->fn(r, p->fn_arg) != 0;
    if (!stop && !counted)
        stop = show(p);
    pthread_mutex_unlock(&p->lock);
    if (stop)
        atomic_store(&p->stop, 1);
}

static void *work(void *arg)
{
    pool *p = arg;
    sweep_worker *w = sweep_worker_new(p->sw);
    double *row = hl_xcalloc((size_t)p->sw->ncols, sizeof *row);
    long *list = hl_xcalloc((size_t)p->longest + 1, sizeof *list);
    hl_sweep_result r;
    memset(&r, 0, sizeof r);
    r.row = row;
    for (;;) {
        long u = atomic_fetch_add(&p->next, 1);
        if (u >= p->nunits || atomic_load(&p->stop))
            break;
        for (long i = p->unit[u]; i < p->unit[u + 1]; i++)
            list[i - p->unit[u]] = member_at(p, i);
        sweep_worker_prepare(w, list, p->unit[u + 1] - p->unit[u], ran_in_lanes, p);
        for (long i = p->unit[u]; i < p->unit[u + 1] && !atomic_load(&p->stop); i++) {
            r.member = member_at(p, i);
            int counted = sweep_member(w, r.member, row, &r.status, r.reason);
            sweep_member_arrays(w, &r);
            deliver(p, &r, counted);
        }
    }
    free(row);
    free(list);
    sweep_worker_free(w);
    return NULL;
}

static hl_status check_members(const hl_sweep *sw, const long *members, long n, int threads,
                               hl_error *err)
{
    if (n < 0 || threads < 1)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "a sweep runs n >= 0 members on at least one thread (%ld, %d)", n,
                            threads);
    if (members == NULL && n > sw->count)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "%ld members asked of %ld", n, sw->count);
    for (long i = 0; members != NULL && i < n; i++)
        if (members[i] < 0 || members[i] >= sw->count)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no member %ld (0 .. %ld)", members[i],
                                sw->count - 1);
    return HL_OK;
}

/* Start the threads (the caller's thread is the first worker); a thread
 * that cannot start leaves its share to the others. */
static hl_status run_threads(pool *p, int threads, hl_error *err)
{
    pthread_t *tid = hl_xcalloc((size_t)threads, sizeof *tid);
    int started = 0;
    for (int i = 1; i < threads; i++) {
        if (pthread_create(&tid[started], NULL, work, p) != 0)
            break;
        started++;
    }
    work(p);
    for (int i = 0; i < started; i++)
        pthread_join(tid[i], NULL);
    free(tid);
    if (atomic_load(&p->stop))
        return hl_error_set(err, HL_ESTOP, NULL, -1, 0,
                            "the sweep stopped after %ld of %ld members", p->done, p->n);
    return HL_OK;
}

hl_status hl_sweep_run(hl_sweep *sw, const long *members, long n, int threads, hl_sweep_fn fn,
                       void *fn_arg, hl_progress_fn progress, void *progress_arg, hl_error *err)
{
    int st = check_members(sw, members, n, threads, err);
    if (st != HL_OK)
        return st;
    pool p;
    memset(&p, 0, sizeof p);
    p.sw = sw;
    p.members = members;
    p.n = n;
    p.fn = fn;
    p.fn_arg = fn_arg;
    p.progress = progress;
    p.progress_arg = progress_arg;
    atomic_init(&p.next, 0);
    atomic_init(&p.stop, 0);
    pthread_mutex_init(&p.lock, NULL);
    cut_units(&p, lanes_per_unit(&p, threads));
    if (threads > p.nunits)
        threads = p.nunits > 0 ? (int)p.nunits : 1;
    st = run_threads(&p, threads, err);
    pthread_mutex_destroy(&p.lock);
    free(p.unit);
    return st;
}
