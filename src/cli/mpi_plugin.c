/* hamlie-mpi.so: the sweep protocol of mpi_plugin.h over MPI.  The only
 * file of hamlie that includes mpi.h; it calls nothing of hamlie (the job's
 * callbacks do the sweep), so it is not part of hamlie-cli.so and is built
 * by cmake/mpi.cmake alone.
 *
 * Messages (MPI_BYTE unless said; tags below):
 *   worker -> 0  REQUEST  header {fingerprint, nresults, threads} and the
 *                         results of its last chunk, packed (pack_result:
 *                         the row, the reason and the arrays)
 *   0 -> worker  CHUNK    the members to compute (int64)
 *                DONE     no more work
 * Every request is answered, in order; a worker keeps IN_FLIGHT of them
 * open, so that its next chunk waits for it instead of the reverse.
 *   worker -> 0  ERROR    its compute failed: the reason (text)
 * A STOP is no message: rank 0 stops answering and ends the job (abort),
 * since a worker may be busy with a chunk for minutes. */
#include <errno.h>
#include <mpi.h>
#include <pthread.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli/mpi_plugin.h"

enum { TAG_REQUEST = 11, TAG_CHUNK, TAG_DONE, TAG_ERROR };

/* Each run talks on its own copy of MPI_COMM_WORLD: a worker told "done"
 * may already ask for the next run's work while the master still waits
 * for the others' last results, and that request must not be read as one
 * of this run's. */
static MPI_Comm comm = MPI_COMM_NULL;

/* A chunk holds at most this many members, and at most CHUNK_BYTES of
 * results: a worker's reply stays a few MB whatever the row length. */
#define CHUNK_MAX 4096L
#define CHUNK_BYTES (8L << 20)
/* Chunks shrink as 1/(SHARE * ranks) of what is left (guided scheduling:
 * large chunks early, small ones at the end so no rank idles long). */
#define SHARE 8
/* The master's pause between two empty polls: long enough that an idle
 * master costs no core (1000 polls a second: 0.3 % of one, measured),
 * short next to a chunk; and a worker does not wait for it, since it
 * keeps IN_FLIGHT requests open: the next chunk is there before it has
 * finished this one. */
#define POLL_NS 1000000L
/* ... and after idle polls the pause doubles up to this: on a loaded
 * machine a wake-up costs far more than its 3 us (measured: rank 0's
 * polling took 1 s of CPU in a 72 s sweep at load 20, 7 % of the
 * sweep's CPU).  A worker still does not wait: its second open request
 * covers a chunk (>= 4 groups a thread, milliseconds at the least) */
#define POLL_MAX_NS 8000000L
#define IN_FLIGHT 2

typedef struct request_header {
    uint64_t fingerprint;
    int64_t nresults;
    int32_t threads, pad;
} request_header;

/* ---- results as bytes --------------------------------------------------- */

typedef struct bytes {
    unsigned char *p;
    size_t n, cap;
    int oom;
} bytes;

static int bytes_reserve(bytes *b, size_t more)
{
    if (b->n + more <= b->cap)
        return 0;
    size_t cap = b->cap ? 2 * b->cap : 4096;
    while (cap < b->n + more)
        cap *= 2;
    unsigned char *p = realloc(b->p, cap);
    if (p == NULL) {
        b->oom = 1;
        return -1;
    }
    b->p = p;
    b->cap = cap;
    return 0;
}

static void bytes_put(bytes *b, const void *src, size_t n)
{
    if (n > 0 && bytes_reserve(b, n) == 0) { /* n = 0: src may be NULL (no rows) */
        memcpy(b->p + b->n, src, n);
        b->n += n;
    }
}

/* member (int64), status (int32), reason length (int32), the row, the
 * reason's bytes (a failed member's reason travels, an OK one's is
 * empty), then each kind of array the job carries: rows (int64) and rows
 * * width doubles */
static void pack_result(bytes *b, const hl_sweep_result *r, const cli_mpi_job *job)
{
    int64_t member = r->member;
    int32_t status = (int32_t)r->status;
    size_t len = strnlen(r->reason, HL_SWEEP_REASON - 1);
    int32_t rlen = (int32_t)len;
    bytes_put(b, &member, sizeof member);
    bytes_put(b, &status, sizeof status);
    bytes_put(b, &rlen, sizeof rlen);
    bytes_put(b, r->row, (size_t)job->ncols * sizeof(double));
    bytes_put(b, r->reason, len);
    for (int k = 0; k < HL_SWEEP_NARRAYS; k++)
        if (job->arrays >> k & 1) {
            int64_t rows = r->array[k] != NULL ? r->nrows[k] : 0;
            bytes_put(b, &rows, sizeof rows);
            bytes_put(b, r->array[k], (size_t)rows * (size_t)job->width * sizeof(double));
        }
}

/* Where a result is unpacked: aligned copies of the message's bytes. */
typedef struct unpacked {
    double *row;
    double *v[HL_SWEEP_NARRAYS];
    size_t cap[HL_SWEEP_NARRAYS]; /* doubles */
} unpacked;

/* The arrays from p + at (n bytes in all); the new offset, 0 if malformed
 * or -1 without memory. */
static long unpack_arrays(const unsigned char *p, size_t at, size_t n, const cli_mpi_job *job,
                          hl_sweep_result *r, unpacked *u)
{
    size_t width = (size_t)job->width;
    for (int k = 0; k < HL_SWEEP_NARRAYS; k++) {
        r->nrows[k] = 0;
        r->array[k] = NULL;
        if (!(job->arrays >> k & 1))
            continue;
        int64_t rows;
        if (n < at + sizeof rows)
            return 0;
        memcpy(&rows, p + at, sizeof rows);
        at += sizeof rows;
        if (rows < 0 || width == 0 || (uint64_t)rows > (n - at) / (width * sizeof(double)))
            return 0;
        size_t len = (size_t)rows * width;
        if (len > u->cap[k]) {
            double *v = realloc(u->v[k], len * sizeof *v);
            if (v == NULL)
                return -1;
            u->v[k] = v;
            u->cap[k] = len;
        }
        if (len > 0) /* u->v[k] may still be NULL */
            memcpy(u->v[k], p + at, len * sizeof(double));
        at += len * sizeof(double);
        r->nrows[k] = (long)rows;
        r->array[k] = u->v[k];
    }
    return (long)at;
}

/* One result from p (n bytes left) into r (its row and arrays in u); the
 * bytes used, 0 if the message is malformed, -1 without memory. */
static long unpack_result(const unsigned char *p, size_t n, const cli_mpi_job *job,
                          hl_sweep_result *r, unpacked *u)
{
    int64_t member;
    int32_t status, rlen;
    size_t fixed =
        sizeof member + sizeof status + sizeof rlen + (size_t)job->ncols * sizeof(double);
    if (n < fixed)
        return 0;
    memcpy(&member, p, sizeof member);
    memcpy(&status, p + 8, sizeof status);
    memcpy(&rlen, p + 12, sizeof rlen);
    if (rlen < 0 || rlen >= HL_SWEEP_REASON || n < fixed + (size_t)rlen)
        return 0;
    memcpy(u->row, p + 16, (size_t)job->ncols * sizeof(double));
    memcpy(r->reason, p + fixed, (size_t)rlen);
    r->reason[rlen] = '\0';
    r->member = (long)member;
    r->status = (hl_status)status;
    r->row = u->row;
    return unpack_arrays(p, fixed + (size_t)rlen, n, job, r, u);
}

/* ---- the master --------------------------------------------------------- */

typedef struct master {
    const cli_mpi_job *job;
    int size;
    pthread_mutex_t lock; /* the fields below, and job->store */
    long next;            /* the first of job->todo not handed out */
    int stop;             /* an interrupt, a store's refusal or an error: end now */
    int failed;
    char msg[256];
    int local_running;
    /* the master's sends under way (main thread only): it never waits for
     * a worker, which may be busy with a chunk while its next one (the
     * answer to its second open request) is sent, and may itself be
     * sending results: two blocking sends would wait for each other */
    MPI_Request *sends;
    int64_t **send_bufs;
    int nsends, capsends;
} master;

/* The next chunk for a rank with `threads` threads: todo[*first ..
 * *first + n), whole groups; n = 0 when nothing is left.  Caller locks. */
static long next_chunk(master *m, int threads, long *first)
{
    const cli_mpi_job *job = m->job;
    long left = job->ntodo - m->next;
    if (left <= 0 || m->stop)
        return 0;
    long bytes_cap = CHUNK_BYTES / (24 + 8L * job->ncols + job->member_bytes);
    long want = left / (SHARE * (long)m->size);
    /* a rank's threads share a chunk by groups: a few groups each */
    long least = 4L * (threads > 0 ? threads : 1) * job->group;
    if (want < least)
        want = least;
    if (want > CHUNK_MAX)
        want = CHUNK_MAX;
    if (want > bytes_cap)
        want = bytes_cap > 0 ? bytes_cap : 1;
    if (want > left)
        want = left;
    /* to the end of the last group begun (a group may exceed the caps) */
    const long *t = job->todo + m->next;
    while (want < left && t[want] / job->group == t[want - 1] / job->group)
        want++;
    *first = m->next;
    m->next += want;
    return want;
}

static void master_fail(master *m, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void master_fail(master *m, const char *fmt, ...)
{
    if (!m->failed) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(m->msg, sizeof m->msg, fmt, ap);
        va_end(ap);
        m->failed = 1;
    }
    m->stop = 1;
}

/* job->store under the lock; non-zero once the sweep must stop */
static int master_store(master *m, const hl_sweep_result *r)
{
    pthread_mutex_lock(&m->lock);
    if (m->job->store(m->job->arg, r) != 0)
        m->stop = 1;
    int stop = m->stop;
    pthread_mutex_unlock(&m->lock);
    return stop;
}

static int local_emit(const hl_sweep_result *r, void *arg)
{
    return master_store(arg, r);
}

/* Rank 0's own share: chunks from the same dispenser, computed on this
 * thread while the main thread serves the others. */
static void *local_loop(void *arg)
{
    master *m = arg;
    const cli_mpi_job *job = m->job;
    char msg[200];
    for (;;) {
        long first;
        pthread_mutex_lock(&m->lock);
        long n = next_chunk(m, job->threads, &first);
        pthread_mutex_unlock(&m->lock);
        if (n == 0)
            break;
        msg[0] = '\0';
        if (job->compute(job->arg, job->todo + first, n, local_emit, m, msg, sizeof msg) != 0) {
            pthread_mutex_lock(&m->lock);
            master_fail(m, "rank 0: %s", msg);
            pthread_mutex_unlock(&m->lock);
            break;
        }
    }
    pthread_mutex_lock(&m->lock);
    m->local_running = 0;
    pthread_mutex_unlock(&m->lock);
    return NULL;
}

/* Sends that have completed are forgotten, their buffers freed. */
static void reap_sends(master *m)
{
    for (int i = 0; i < m->nsends;) {
        int done = 0;
        MPI_Test(&m->sends[i], &done, MPI_STATUS_IGNORE);
        if (!done) {
            i++;
            continue;
        }
        free(m->send_bufs[i]);
        m->nsends--;
        m->sends[i] = m->sends[m->nsends];
        m->send_bufs[i] = m->send_bufs[m->nsends];
    }
}

/* A chunk (buf: n members, owned from here on; NULL and 0 for "done") on
 * its way to dest without waiting; 0, or -1 without memory. */
static int post_send(master *m, int dest, int64_t *buf, long n)
{
    if (m->nsends == m->capsends) {
        int cap = m->capsends ? 2 * m->capsends : 16;
        MPI_Request *r = realloc(m->sends, (size_t)cap * sizeof *r);
        if (r != NULL)
            m->sends = r;
        int64_t **b = realloc(m->send_bufs, (size_t)cap * sizeof *b);
        if (b != NULL)
            m->send_bufs = b;
        if (r == NULL || b == NULL) {
            free(buf);
            return -1;
        }
        m->capsends = cap;
    }
    MPI_Isend(buf, (int)n, MPI_INT64_T, dest, buf != NULL ? TAG_CHUNK : TAG_DONE, comm,
              &m->sends[m->nsends]);
    m->send_bufs[m->nsends++] = buf;
    return 0;
}

static int send_chunk(master *m, int dest, int threads)
{
    long first;
    pthread_mutex_lock(&m->lock);
    long n = next_chunk(m, threads, &first);
    pthread_mutex_unlock(&m->lock);
    int64_t *members = n > 0 ? malloc((size_t)n * sizeof *members) : NULL;
    for (long i = 0; members != NULL && i < n; i++)
        members[i] = m->job->todo[first + i];
    if ((n > 0 && members == NULL) || post_send(m, dest, members, n) != 0) {
        pthread_mutex_lock(&m->lock);
        master_fail(m, "no memory for a chunk of %ld members", n);
        pthread_mutex_unlock(&m->lock);
    }
    return n > 0;
}

/* A worker's request: its results stored, its next chunk sent.  Returns
 * whether the worker goes on (0: it was told "done", or the sweep stops). */
static int serve_request(master *m, int source, const unsigned char *p, size_t n, unpacked *u)
{
    request_header h;
    const cli_mpi_job *job = m->job;
    if (n < sizeof h) {
        pthread_mutex_lock(&m->lock);
        master_fail(m, "rank %d sent a malformed request (%zu bytes)", source, n);
        pthread_mutex_unlock(&m->lock);
        return 0;
    }
    memcpy(&h, p, sizeof h);
    if (h.fingerprint != job->fingerprint) {
        pthread_mutex_lock(&m->lock);
        master_fail(m,
                    "rank %d runs another sweep (fingerprint %016llx, rank 0's %016llx): the "
                    "same hamlie, options and input files are needed on every node",
                    source, (unsigned long long)h.fingerprint,
                    (unsigned long long)job->fingerprint);
        pthread_mutex_unlock(&m->lock);
        return 0;
    }
    size_t at = sizeof h;
    for (int64_t i = 0; i < h.nresults; i++) {
        hl_sweep_result r;
        long used = unpack_result(p + at, n - at, job, &r, u);
        if (used <= 0) {
            pthread_mutex_lock(&m->lock);
            if (used < 0)
                master_fail(m, "no memory for a result of rank %d", source);
            else
                master_fail(m, "rank %d sent a malformed result (%lld of %lld)", source,
                            (long long)i, (long long)h.nresults);
            pthread_mutex_unlock(&m->lock);
            return 0;
        }
        at += (size_t)used;
        if (master_store(m, &r))
            return 0;
    }
    return send_chunk(m, source, h.threads);
}

static int master_should_stop(master *m)
{
    pthread_mutex_lock(&m->lock);
    if (!m->stop && m->job->stopped != NULL && m->job->stopped(m->job->arg))
        m->stop = 1;
    int stop = m->stop;
    pthread_mutex_unlock(&m->lock);
    return stop;
}

static int master_local_running(master *m)
{
    pthread_mutex_lock(&m->lock);
    int running = m->local_running;
    pthread_mutex_unlock(&m->lock);
    return running;
}

/* The pause before the next poll: back to POLL_NS after a message, else
 * doubled up to POLL_MAX_NS. */
static void pause_poll(long *pause_ns)
{
    struct timespec ts = {0, *pause_ns};
    nanosleep(&ts, NULL);
    *pause_ns = *pause_ns * 2 < POLL_MAX_NS ? *pause_ns * 2 : POLL_MAX_NS;
}

/* A message from any worker, or none after a pause.  1 when a request was
 * answered "done", 2 when a worker gave up (an error), 0 otherwise; the
 * worker in *source. */
static int serve_one(master *m, bytes *in, unpacked *u, int *source, long *pause_ns)
{
    int flag = 0, count = 0;
    MPI_Status st;
    reap_sends(m);
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, comm, &flag, &st);
    if (!flag) {
        pause_poll(pause_ns);
        return 0;
    }
    *pause_ns = POLL_NS;
    MPI_Get_count(&st, MPI_BYTE, &count);
    *source = st.MPI_SOURCE;
    in->n = 0;
    if (bytes_reserve(in, (size_t)count + 1) != 0) {
        pthread_mutex_lock(&m->lock);
        master_fail(m, "no memory for a message of %d bytes from rank %d", count, st.MPI_SOURCE);
        pthread_mutex_unlock(&m->lock);
        return 0;
    }
    MPI_Recv(in->p, count, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, comm, MPI_STATUS_IGNORE);
    if (st.MPI_TAG == TAG_ERROR) {
        in->p[count] = '\0';
        pthread_mutex_lock(&m->lock);
        master_fail(m, "rank %d: %s", st.MPI_SOURCE, (char *)in->p);
        pthread_mutex_unlock(&m->lock);
        return 2;
    }
    if (st.MPI_TAG != TAG_REQUEST) {
        pthread_mutex_lock(&m->lock);
        master_fail(m, "rank %d sent an unknown message (tag %d)", st.MPI_SOURCE, st.MPI_TAG);
        pthread_mutex_unlock(&m->lock);
        return 0;
    }
    return !serve_request(m, st.MPI_SOURCE, in->p, (size_t)count, u);
}

static int run_master(const cli_mpi_job *job, int size, char *msg, size_t msgsize)
{
    master m = {.job = job, .size = size};
    pthread_mutex_init(&m.lock, NULL);
    pthread_t local;
    int local_started = 0;
    if (size == 1 || !job->master_idle) {
        m.local_running = 1;
        local_started = pthread_create(&local, NULL, local_loop, &m) == 0;
        if (!local_started) {
            m.local_running = 0;
            master_fail(&m, "cannot start rank 0's compute thread");
        }
    }
    unpacked u = {.row = malloc(((size_t)job->ncols + 1) * sizeof *u.row)};
    bytes in = {0};
    if (u.row == NULL)
        master_fail(&m, "no memory");
    /* a worker is through once each of its open requests was answered "done" */
    int active = size - 1, *dones = calloc((size_t)size, sizeof *dones);
    if (dones == NULL)
        master_fail(&m, "no memory");
    long pause_ns = POLL_NS;
    while ((active > 0 || master_local_running(&m)) && !master_should_stop(&m))
        if (active > 0) {
            int source = 0, served = serve_one(&m, &in, &u, &source, &pause_ns);
            if (served == 2 || (served == 1 && ++dones[source] == IN_FLIGHT))
                active--;
        } else
            pause_poll(&pause_ns);
    if (local_started)
        pthread_join(local, NULL);
    /* every worker takes its answers before it is through; after a stop
     * the sends may never end (the job is ended by an abort): their
     * buffers are left to it, MPI may still read them */
    if (!m.stop) {
        MPI_Waitall(m.nsends, m.sends, MPI_STATUSES_IGNORE);
        for (int i = 0; i < m.nsends; i++)
            free(m.send_bufs[i]);
        free(m.sends);
        free(m.send_bufs);
    }
    free(u.row);
    for (int k = 0; k < HL_SWEEP_NARRAYS; k++)
        free(u.v[k]);
    free(in.p);
    free(dones);
    pthread_mutex_destroy(&m.lock);
    if (m.failed) {
        snprintf(msg, msgsize, "%s", m.msg);
        return CLI_MPI_FAILED;
    }
    return m.stop ? CLI_MPI_STOPPED : CLI_MPI_DONE;
}

/* ---- a worker ----------------------------------------------------------- */

typedef struct worker {
    bytes out;
    const cli_mpi_job *job;
} worker;

static int worker_emit(const hl_sweep_result *r, void *arg)
{
    worker *w = arg;
    pack_result(&w->out, r, w->job);
    if (!w->out.oom)
        ((request_header *)w->out.p)->nresults++; /* the buffer starts with it */
    return w->out.oom;
}

static void worker_request_reset(worker *w, const cli_mpi_job *job)
{
    request_header h = {.fingerprint = job->fingerprint, .threads = job->threads};
    w->out.n = 0;
    bytes_put(&w->out, &h, sizeof h);
}

/* The next chunk into *members (grown as needed): its length, 0 for
 * "done", -1 without memory. */
/* A message from rank 0, waited for in sleeps from 50 us to POLL_NS:
 * Open MPI's blocking MPI_Probe spins a core all the while, and on a
 * loaded machine rank 0's answer may take milliseconds to come. */
static void wait_message(MPI_Status *st)
{
    int flag = 0;
    long pause_ns = 50000;
    MPI_Iprobe(0, MPI_ANY_TAG, comm, &flag, st);
    while (!flag) {
        nanosleep(&(struct timespec){0, pause_ns}, NULL);
        pause_ns = pause_ns * 2 < POLL_NS ? pause_ns * 2 : POLL_NS;
        MPI_Iprobe(0, MPI_ANY_TAG, comm, &flag, st);
    }
}

static int receive_chunk(long **members)
{
    MPI_Status st;
    int n = 0;
    wait_message(&st);
    if (st.MPI_TAG != TAG_CHUNK) { /* TAG_DONE */
        MPI_Recv(NULL, 0, MPI_BYTE, 0, st.MPI_TAG, comm, MPI_STATUS_IGNORE);
        return 0;
    }
    MPI_Get_count(&st, MPI_INT64_T, &n);
    int64_t *chunk = malloc((size_t)n * sizeof *chunk + 1);
    long *grown = realloc(*members, (size_t)n * sizeof **members + 1);
    if (grown != NULL)
        *members = grown;
    if (chunk == NULL || grown == NULL) {
        free(chunk);
        return -1;
    }
    MPI_Recv(chunk, n, MPI_INT64_T, 0, TAG_CHUNK, comm, MPI_STATUS_IGNORE);
    for (int i = 0; i < n; i++)
        (*members)[i] = (long)chunk[i];
    free(chunk);
    return n;
}

/* A request to rank 0, waited for in sleeps: a blocking MPI_Send of a
 * chunk's results (over the eager limit, a few kB) spins a core in Open
 * MPI's progress loop until rank 0's serving thread, which polls every 1-8
 * ms (later on a loaded machine), takes it. */
static void send_request(const bytes *out)
{
    MPI_Request req;
    int done = 0;
    long pause_ns = 50000;
    MPI_Isend(out->p, (int)out->n, MPI_BYTE, 0, TAG_REQUEST, comm, &req);
    MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    while (!done) {
        nanosleep(&(struct timespec){0, pause_ns}, NULL);
        pause_ns = pause_ns * 2 < POLL_NS ? pause_ns * 2 : POLL_NS;
        MPI_Test(&req, &done, MPI_STATUS_IGNORE);
    }
}

static int worker_fails(const char *why, char *msg, size_t msgsize)
{
    snprintf(msg, msgsize, "%s", why);
    MPI_Send(msg, (int)strlen(msg), MPI_BYTE, 0, TAG_ERROR, comm);
    return CLI_MPI_FAILED;
}

/* IN_FLIGHT requests open from the start, and one more with each chunk's
 * results: every request is answered (a chunk, or "done" once the work
 * is handed out), so the worker is through when none is open. */
static int run_worker(const cli_mpi_job *job, char *msg, size_t msgsize)
{
    worker w = {.job = job};
    long *members = NULL;
    int outcome = CLI_MPI_DONE, open = 0;
    worker_request_reset(&w, job);
    for (; open < IN_FLIGHT && !w.out.oom; open++)
        send_request(&w.out);
    while (open > 0 && outcome == CLI_MPI_DONE) {
        int n = receive_chunk(&members);
        open--;
        if (n == 0)
            continue;
        char why[200] = "";
        worker_request_reset(&w, job);
        if (n < 0 || w.out.oom)
            outcome = worker_fails("no memory for a chunk", msg, msgsize);
        else if (job->compute(job->arg, members, n, worker_emit, &w, why, sizeof why) != 0 &&
                 !w.out.oom)
            outcome = worker_fails(why, msg, msgsize);
        else if (w.out.oom)
            outcome = worker_fails("no memory for a chunk's results", msg, msgsize);
        else {
            send_request(&w.out);
            open++;
        }
    }
    free(members);
    free(w.out.p);
    return outcome;
}

/* ---- the interface ------------------------------------------------------ */

static int plugin_init(int *rank, int *size, char *msg, size_t msgsize)
{
    int provided = 0;
    if (MPI_Init_thread(NULL, NULL, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
        snprintf(msg, msgsize, "MPI_Init_thread failed");
        return -1;
    }
    MPI_Comm_rank(MPI_COMM_WORLD, rank);
    MPI_Comm_size(MPI_COMM_WORLD, size);
    if (provided < MPI_THREAD_FUNNELED) {
        snprintf(msg, msgsize, "this MPI offers no thread support (MPI_THREAD_FUNNELED)");
        return -1;
    }
    return 0;
}

static int plugin_run(const cli_mpi_job *job, char *msg, size_t msgsize)
{
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (job->ncols < 0 || job->group < 1) {
        snprintf(msg, msgsize, "a job with %d columns and groups of %ld", job->ncols, job->group);
        return CLI_MPI_FAILED;
    }
    MPI_Comm_dup(MPI_COMM_WORLD, &comm);
    int outcome = rank == 0 ? run_master(job, size, msg, msgsize) : run_worker(job, msg, msgsize);
    if (outcome == CLI_MPI_DONE)
        MPI_Comm_free(&comm); /* else the job is ended by an abort, messages pending */
    return outcome;
}

/* The ranks done first wait here for rank 0 to write the file: in a
 * barrier polled with pauses, since MPI_Finalize's own wait spins (10 %
 * of a core here) and the ranks may share the node with others' work. */
static void plugin_finalize(void)
{
    MPI_Request req;
    int done = 0;
    MPI_Ibarrier(MPI_COMM_WORLD, &req);
    while (!done) {
        MPI_Test(&req, &done, MPI_STATUS_IGNORE);
        if (!done)
            nanosleep(&(struct timespec){0, POLL_NS}, NULL);
    }
    MPI_Finalize();
}

static void plugin_abort(int code)
{
    MPI_Abort(MPI_COMM_WORLD, code);
}

static const cli_mpi_api api = {
    .version = CLI_MPI_VERSION,
    .init = plugin_init,
    .run = plugin_run,
    .finalize = plugin_finalize,
    .abort = plugin_abort,
};

const cli_mpi_api *hamlie_mpi_plugin(void);
const cli_mpi_api *hamlie_mpi_plugin(void)
{
    return &api;
}
