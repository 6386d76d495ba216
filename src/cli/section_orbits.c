/* The orbits of `hamlie section` on several threads (see section_orbits.h). */
#include <errno.h>
#include <math.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli/section_orbits.h"
#include "hamlie/chaos.h"

/* The progress is polled this often (seconds) by the calling thread. */
#define POLL_SECONDS 0.05

/* One thread's objects: nothing in them is shared with another thread. */
typedef struct worker {
    struct pool *pool;
    hl_system *sys;
    hl_section *sec;
    hl_scheme *sch;
    hl_run *run;
    hl_chaos *chaos;
    pthread_t tid;
    int started;
} worker;

typedef struct pool {
    const section_job *job;
    section_orbit *orbits;
    atomic_int next; /* the next orbit to hand out */
    atomic_int done; /* orbits finished */
    atomic_int stop; /* set on Ctrl-C: every run stops at its next check */
} pool;

/* ---- building a thread's objects ------------------------------------------- */

static void worker_free(worker *w)
{
    hl_chaos_free(w->chaos);
    hl_run_free(w->run);
    hl_scheme_free(w->sch);
    hl_section_free(w->sec);
    hl_system_free(w->sys);
}

/* CLI_OK, or CLI_ERROR after the message. */
static int worker_build(worker *w, const section_job *job)
{
    hl_error err;
    hl_error_clear(&err);
    if (cli_system(&w->sys, job->o, NULL) != CLI_OK)
        return CLI_ERROR;
    if (hl_section_new(&w->sec, w->sys, job->surface, job->dir, job->E, &err) != HL_OK ||
        (job->scheme != NULL &&
         cli_make_scheme(&w->sch, NULL, NULL, job->scheme, 4, w->sys, &err) != HL_OK) ||
        hl_run_new(&w->run, w->sys, w->sch, &err) != HL_OK ||
        (job->chaos && hl_chaos_new(&w->chaos, w->sys, job->chaos_tol, &err) != HL_OK))
        return cli_fail(&err);
    return CLI_OK;
}

/* ---- one orbit --------------------------------------------------------------- */

typedef struct orbit_ctx {
    section_orbit *orbit;
    long index;
    double E;
} orbit_ctx;

static int keep(const hl_run_crossing *c, void *arg)
{
    orbit_ctx *x = arg;
    crossings_add(&x->orbit->table, x->index, c);
    x->orbit->max_dH = fmax(x->orbit->max_dH, fabs(c->H - x->E));
    x->orbit->span = c->t;
    return 0;
}

/* The runs' progress callback: only the stop matters (the calling thread
 * counts whole orbits). */
static int stop_asked(double done, double total, void *arg)
{
    (void)done, (void)total;
    return atomic_load_explicit(&((pool *)arg)->stop, memory_order_relaxed);
}

/* <Y> over the orbit's span, and its class. */
static void classify(worker *w, section_orbit *orbit, const double *z0)
{
    hl_error err;
    hl_error_clear(&err);
    hl_chaos_result r;
    if (!(orbit->span > 0)) /* no crossing: nothing to measure the span by */
        return;
    if (hl_chaos_run(w->chaos, z0, NULL, orbit->span, 0, NULL, NULL, &r, &err) != HL_OK) {
        if (err.status != HL_ESTOP) {
            orbit->failed = 1;
            orbit->status = err.status;
            snprintf(orbit->why, sizeof orbit->why, "its MEGNO failed: %.280s", err.msg);
        }
        return;
    }
    orbit->megno = r.megno_mean;
    orbit->chaotic = r.megno_mean > SECTION_CHAOS_THRESHOLD;
}

static void run_orbit(worker *w, long i)
{
    const section_job *job = w->pool->job;
    section_orbit *orbit = &w->pool->orbits[i];
    const double *z0 = job->zs + (size_t)i * (size_t)job->n2;
    crossings_init(&orbit->table, job->n2);
    orbit->megno = NAN;
    orbit->chaotic = -1;
    orbit_ctx ctx = {orbit, i, job->E};
    hl_error err;
    hl_error_clear(&err);
    if (hl_section_orbit(w->sec, w->run, z0, job->ncross, &job->opts, keep, &ctx, NULL, &err) !=
        HL_OK) {
        if (err.status == HL_ESTOP)
            return; /* interrupted: not done */
        orbit->failed = 1;
        orbit->status = err.status;
        snprintf(orbit->why, sizeof orbit->why, "%.300s", err.msg);
    } else if (job->chaos)
        classify(w, orbit, z0);
    if (!atomic_load(&w->pool->stop))
        orbit->done = 1;
}

static void *work(void *arg)
{
    worker *w = arg;
    pool *p = w->pool;
    for (;;) {
        int i = atomic_fetch_add(&p->next, 1);
        if (i >= p->job->M || atomic_load(&p->stop))
            break;
        run_orbit(w, i);
        atomic_fetch_add(&p->done, 1);
    }
    return NULL;
}

/* ---- the pool ---------------------------------------------------------------- */

static void nap(double seconds)
{
    struct timespec ts = {0, (long)(seconds * 1e9)};
    nanosleep(&ts, NULL);
}

/* The calling thread: progress until every orbit is done, Ctrl-C turned
 * into the stop.  Returns 1 when interrupted. */
static int watch(pool *p, cli_progress *progress)
{
    int interrupted = 0;
    while (atomic_load(&p->done) < p->job->M) {
        if (cli_progress_fn(atomic_load(&p->done), p->job->M, progress) != 0) {
            atomic_store(&p->stop, 1);
            interrupted = 1;
            break;
        }
        nap(POLL_SECONDS);
    }
    return interrupted;
}

int section_orbits_run(const section_job *job, section_orbit *orbits, int nthreads,
                       cli_progress *progress)
{
    pool p = {.job = job, .orbits = orbits};
    atomic_init(&p.next, 0);
    atomic_init(&p.done, 0);
    atomic_init(&p.stop, 0);
    if (nthreads > job->M)
        nthreads = job->M;
    worker *ws = hl_xcalloc((size_t)nthreads, sizeof *ws);
    int rc = CLI_OK;
    for (int k = 0; k < nthreads && rc == CLI_OK; k++) {
        ws[k].pool = &p;
        rc = worker_build(&ws[k], job);
        if (rc == CLI_OK) {
            hl_run_set_progress(ws[k].run, stop_asked, &p);
            if (ws[k].chaos != NULL)
                hl_chaos_set_progress(ws[k].chaos, stop_asked, &p);
        }
    }
    for (int k = 0; k < nthreads && rc == CLI_OK; k++) {
        if (pthread_create(&ws[k].tid, NULL, work, &ws[k]) != 0) {
            fprintf(stderr, "hamlie section: error: cannot start thread %d of %d\n", k + 1,
                    nthreads);
            atomic_store(&p.stop, 1);
            rc = CLI_ERROR;
            break;
        }
        ws[k].started = 1;
    }
    if (rc == CLI_OK && watch(&p, progress))
        rc = CLI_INTERRUPTED;
    for (int k = 0; k < nthreads; k++) {
        if (ws[k].started)
            pthread_join(ws[k].tid, NULL);
        worker_free(&ws[k]);
    }
    free(ws);
    return rc;
}

void section_orbits_free(section_orbit *orbits, int M)
{
    for (int i = 0; orbits != NULL && i < M; i++)
        crossings_clear(&orbits[i].table);
}

/* ---- the CSV with the chaos columns -------------------------------------------- */

static void put_chaos_csv(hl_buf *b, const crossings *c, const section_orbit *orbits,
                          hl_system *sys)
{
    hl_buf_puts(b, "orbit,crossing,t");
    for (int i = 0; i < c->n2; i++)
        hl_buf_printf(b, ",%s", cli_phase_name(sys, i));
    hl_buf_puts(b, ",H,mean_Y,chaotic\n");
    char num[40];
    for (long k = 0; k < c->n; k++) {
        const double *r = crossings_row(c, k);
        const section_orbit *o = &orbits[(long)r[0]];
        hl_buf_printf(b, "%ld,%ld", (long)r[0], (long)r[1]);
        for (int i = 2; i < 3 + c->n2 + 1; i++) {
            hl_run_fmt(num, r[i]);
            hl_buf_printf(b, ",%s", num);
        }
        hl_run_fmt(num, o->megno);
        if (o->chaotic >= 0)
            hl_buf_printf(b, ",%s,%d\n", num, o->chaotic);
        else
            hl_buf_printf(b, ",%s,\n", isnan(o->megno) ? "" : num);
    }
}

int section_write_chaos_csv(const crossings *table, const section_orbit *orbits, hl_system *sys,
                            const char *path)
{
    hl_buf b;
    hl_buf_init(&b);
    put_chaos_csv(&b, table, orbits, sys);
    return cli_write_whole(&b, path);
}
