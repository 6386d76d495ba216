/* `hamlie sweep` across the ranks of an MPI job: the command's side of the
 * plugin hamlie-mpi.so (mpi_plugin.h says why a plugin, and the protocol).
 * cmd_sweep.c calls three hooks:
 *   cli_sweep_mpi_begin   under a launcher (or --mpi): loads the plugin,
 *                         MPI_Init; the ranks but 0 compute what rank 0
 *                         hands out and return their exit status here
 *   cli_sweep_mpi_serve   rank 0, in place of the threaded run: the table
 *                         and the journal fed from every rank, progress
 *   cli_sweep_mpi_end     rank 0, last: finalize after a whole run; after
 *                         an interrupt or an error, end the job (the other
 *                         ranks may be busy or waiting: abort)
 * Rank 0 keeps everything the threaded command keeps (table, journal,
 * output, --resume), so the file is the same bit for bit. */
#define _GNU_SOURCE /* dladdr: where this module lies */
#include <dlfcn.h>
#include <fcntl.h>
#include <limits.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"
#include "cli/mpi_plugin.h"

static struct {
    const cli_mpi_api *api; /* NULL: not under MPI */
    hl_sweep *sw;
    int rank, size, threads;
    int ran;     /* rank 0 served a run (else the workers still wait for one) */
    int outcome; /* of that run */
} mpi;

int cli_mpi_launched(void)
{
    return getenv("OMPI_COMM_WORLD_SIZE") != NULL || getenv("PMIX_RANK") != NULL ||
           getenv("PMI_SIZE") != NULL;
}

int cli_mpi_env_rank(void)
{
    const char *names[] = {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"};
    for (size_t i = 0; i < sizeof names / sizeof names[0]; i++) {
        const char *v = getenv(names[i]);
        if (v != NULL && v[0] != '\0')
            return atoi(v);
    }
    return 0;
}

int cli_mpi_quiet_begin(void)
{
    if (!cli_mpi_launched() || cli_mpi_env_rank() == 0)
        return -1;
    fflush(stderr);
    int saved = dup(STDERR_FILENO), null = open("/dev/null", O_WRONLY);
    if (saved >= 0 && null >= 0)
        dup2(null, STDERR_FILENO);
    if (null >= 0)
        close(null);
    return saved;
}

void cli_mpi_quiet_end(int saved)
{
    if (saved < 0)
        return;
    fflush(stderr);
    dup2(saved, STDERR_FILENO);
    close(saved);
}

int cli_mpi_default_threads(int cores)
{
    const char *local = getenv("OMPI_COMM_WORLD_LOCAL_SIZE");
    if (local == NULL)
        local = getenv("MPI_LOCALNRANKS"); /* MPICH's Hydra */
    int ranks = local != NULL ? atoi(local) : 1;
    int threads = cores / (ranks > 0 ? ranks : 1);
    return threads > 0 ? threads : 1;
}

/* The plugin beside this module (hamlie-cli.so), or $HAMLIE_MPI_PLUGIN. */
static void plugin_path(char *buf, size_t size)
{
    const char *env = getenv("HAMLIE_MPI_PLUGIN");
    Dl_info info;
    if (env != NULL && env[0] != '\0') {
        snprintf(buf, size, "%s", env);
        return;
    }
    if (dladdr((void *)cli_mpi_launched, &info) != 0 && info.dli_fname != NULL) {
        const char *slash = strrchr(info.dli_fname, '/');
        int dir = slash != NULL ? (int)(slash - info.dli_fname) : 1;
        snprintf(buf, size, "%.*s/%s", dir, slash != NULL ? info.dli_fname : ".", CLI_MPI_PLUGIN);
        return;
    }
    snprintf(buf, size, "%s", CLI_MPI_PLUGIN);
}

static const cli_mpi_api *load_plugin(void)
{
    char path[PATH_MAX + 32];
    plugin_path(path, sizeof path);
    /* global: Open MPI's own components, loaded later, look for libmpi's
     * symbols in the global scope */
    void *h = dlopen(path, RTLD_NOW | RTLD_GLOBAL);
    if (h == NULL) {
        fprintf(stderr,
                "hamlie: error: running under MPI needs the plugin %s, which cannot be "
                "loaded: %s (was hamlie built with MPI? Debian: libopenmpi-dev)\n",
                path, dlerror());
        return NULL;
    }
    cli_mpi_entry_fn entry;
    *(void **)&entry = dlsym(h, CLI_MPI_ENTRY);
    const cli_mpi_api *api = entry != NULL ? entry() : NULL;
    if (api == NULL || api->version != CLI_MPI_VERSION) {
        fprintf(stderr, "hamlie: error: %s is not hamlie's MPI plugin of version %d\n", path,
                CLI_MPI_VERSION);
        return NULL;
    }
    return api;
}

/* Members per group: a chunk never splits one.  The sweep's chunk quantum
 * (sweep.h): whole points, so a point's chaos indicators are computed once,
 * and whole rounds of the SIMD lanes, so that a rank's lanes run full (a
 * chunk of 2 points in 8 lanes costs what 8 points cost).  Only the speed
 * depends on it, never a row. */
static long group_size(const hl_sweep *sw)
{
    long group = hl_sweep_chunk_quantum(sw);
    return group > 0 ? group : 1;
}

typedef struct serve_ctx {
    hl_sweep *sw;
    hl_sweep_table *tab;
    hl_sweep_journal *journal;
    cli_progress *progress;
    long total;
} serve_ctx;

/* The job's compute: the members on this rank's threads.  A stop asked by
 * emit is no failure. */
static int compute(void *arg, const long *members, long n, hl_sweep_fn emit, void *emit_arg,
                   char *msg, size_t msgsize)
{
    serve_ctx *c = arg;
    hl_error err;
    hl_error_clear(&err);
    hl_status st = hl_sweep_run(c->sw, members, n, mpi.threads, emit, emit_arg, NULL, NULL, &err);
    if (st == HL_OK || st == HL_ESTOP)
        return 0;
    snprintf(msg, msgsize, "%s", err.msg);
    return 1;
}

static cli_mpi_job job_of(serve_ctx *c)
{
    unsigned arrays = 0;
    for (int k = 0; k < HL_SWEEP_NARRAYS; k++)
        arrays |= (unsigned)(hl_sweep_has_array(c->sw, k) != 0) << k;
    long traj_bytes = hl_sweep_traj_rows_max(c->sw) * hl_sweep_array_width(c->sw) * 8;
    cli_mpi_job job = {.ncols = hl_sweep_ncols(c->sw),
                       .arrays = arrays,
                       .width = hl_sweep_array_width(c->sw),
                       .member_bytes = traj_bytes,
                       .group = group_size(c->sw),
                       .threads = mpi.threads,
                       .fingerprint = hl_sweep_fingerprint(c->sw),
                       .compute = compute,
                       .arg = c};
    /* measured in docs/sweep-at-scale.md: computing on rank 0 too pays */
    const char *idle = getenv("HAMLIE_MPI_MASTER_IDLE");
    job.master_idle = idle != NULL && strcmp(idle, "1") == 0;
    return job;
}

int cli_sweep_mpi_begin(hl_sweep *sw, int forced, long *threads, int threads_given)
{
    if (!forced && !cli_mpi_launched())
        return -1;
    const cli_mpi_api *api = load_plugin();
    if (api == NULL)
        return CLI_ERROR;
    char msg[256] = "";
    if (api->init(&mpi.rank, &mpi.size, msg, sizeof msg) != 0) {
        fprintf(stderr, "hamlie: error: MPI: %s\n", msg);
        return CLI_ERROR;
    }
    mpi.api = api;
    mpi.sw = sw;
    if (!threads_given)
        *threads = cli_mpi_default_threads((int)*threads);
    mpi.threads = (int)*threads;
    if (mpi.rank == 0)
        return -1;
    serve_ctx c = {.sw = sw};
    cli_mpi_job job = job_of(&c);
    int outcome = api->run(&job, msg, sizeof msg);
    if (outcome == CLI_MPI_FAILED) { /* rank 0 hears it too and ends the job */
        fprintf(stderr, "hamlie: error: rank %d: %s\n", mpi.rank, msg);
        return CLI_ERROR;
    }
    api->finalize();
    mpi.api = NULL;
    return CLI_OK;
}

/* ---- rank 0 ----------------------------------------------------------------- */

static volatile sig_atomic_t terminated;

static void on_terminate(int sig)
{
    (void)sig;
    terminated = 1;
}

/* mpirun passes a Ctrl-C on as SIGTERM: stop as for SIGINT.  Polled
 * between messages, after a worker's chunk of results has been stored:
 * the journal's records are flushed here, once a chunk (deferred). */
static int stopped(void *arg)
{
    serve_ctx *c = arg;
    if (c->journal != NULL && hl_sweep_journal_flush(c->journal) != 0)
        return 1;
    return terminated || cli_interrupted();
}

static int store(void *arg, const hl_sweep_result *r)
{
    serve_ctx *c = arg;
    hl_sweep_table_store(r, c->tab);
    if (c->journal != NULL && hl_sweep_journal_append(r, c->journal) != 0)
        return 1;
    return cli_progress_fn((double)hl_sweep_table_done(c->tab), (double)c->total, c->progress) ||
           terminated;
}

/* The members not in the table (all of them unless resumed). */
static long *todo_of(const hl_sweep *sw, const hl_sweep_table *tab, long *n)
{
    long count = hl_sweep_count(sw);
    long *todo = malloc((size_t)(count > 0 ? count : 1) * sizeof *todo);
    *n = 0;
    for (long m = 0; todo != NULL && m < count; m++)
        if (!hl_sweep_table_has(tab, m))
            todo[(*n)++] = m;
    return todo;
}

int cli_sweep_mpi_active(void)
{
    return mpi.api != NULL;
}

int cli_sweep_mpi_serve(hl_sweep *sw, hl_sweep_table *tab, hl_sweep_journal *journal,
                        const char *out, int progress_mode)
{
    serve_ctx c = {.sw = sw, .tab = tab, .journal = journal, .total = hl_sweep_count(sw)};
    long ntodo;
    long *todo = todo_of(sw, tab, &ntodo);
    if (todo == NULL) {
        fprintf(stderr, "hamlie: error: no memory for the list of members\n");
        return CLI_ERROR;
    }
    cli_progress p;
    cli_progress_begin(&p, "sweep", "member", progress_mode);
    c.progress = &p;
    struct sigaction sa, before;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_terminate;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGTERM, &sa, &before);
    if (progress_mode == CLI_PROGRESS_ON || ntodo < c.total)
        cli_progress_say(&p, "%ld members on %d rank%s of %d thread%s%s", ntodo, mpi.size,
                         mpi.size == 1 ? "" : "s", mpi.threads, mpi.threads == 1 ? "" : "s",
                         ntodo < c.total ? " (the others done before)" : "");
    if (journal != NULL)
        hl_sweep_journal_defer(journal); /* flushed in stopped(), a chunk at a time */
    cli_mpi_job job = job_of(&c);
    job.todo = todo;
    job.ntodo = ntodo;
    job.store = store;
    job.stopped = stopped;
    char msg[256] = "";
    mpi.ran = 1;
    mpi.outcome = mpi.api->run(&job, msg, sizeof msg);
    cli_progress_end(&p);
    sigaction(SIGTERM, &before, NULL);
    free(todo);
    long done = hl_sweep_table_done(tab);
    if (mpi.outcome == CLI_MPI_FAILED) {
        fprintf(stderr, "hamlie: error: %s\n", msg);
        return CLI_ERROR;
    }
    if (journal != NULL && hl_sweep_journal_failed(journal)) {
        fprintf(stderr, "hamlie: error: writing the journal of '%s' failed\n", out);
        mpi.outcome = CLI_MPI_FAILED;
        return CLI_ERROR;
    }
    if (mpi.outcome == CLI_MPI_STOPPED) {
        fprintf(stderr, "hamlie sweep: interrupted after %ld of %ld members", done, c.total);
        if (journal != NULL)
            fprintf(stderr,
                    "; '%s.journal' keeps them: the same command with --resume "
                    "continues\n",
                    out);
        else
            fputs(" (nothing written: --out FILE keeps a journal to resume)\n", stderr);
        return CLI_INTERRUPTED;
    }
    return -1;
}

int cli_sweep_mpi_end(int rc)
{
    if (mpi.api == NULL)
        return rc;
    if (!mpi.ran) { /* rank 0 failed before the run: the others wait for one, of nothing */
        serve_ctx c = {.sw = mpi.sw};
        cli_mpi_job job = job_of(&c);
        char msg[256];
        mpi.ran = 1;
        mpi.outcome = mpi.api->run(&job, msg, sizeof msg);
    }
    fflush(stdout);
    fflush(stderr);
    if (mpi.outcome != CLI_MPI_DONE)
        mpi.api->abort(rc); /* the journal is closed: only the ranks go */
    mpi.api->finalize();
    mpi.api = NULL;
    return rc;
}
