/* How many rows a second rank 0 of `mpirun hamlie sweep` takes in: the
 * protocol of hamlie-mpi.so with members that cost nothing, so the rate is
 * that of the messages and of storing the rows in a table (and, with
 * JOURNAL, of appending each to a file, flushed once per message between
 * polls, as sweep_mpi.c does with the journal).  Rank 0 only serves (master idle).  For
 * docs/sweep-at-scale.md. mpirun -np K bench-sweep_mpi_rate PLUGIN NCOLS MEMBERS [JOURNAL] prints:
 * members, ncols, seconds, rows/s, MB/s of rows received, and rank 0's CPU seconds and rows per CPU
 * second (the machine may be shared: the CPU figure is the one that says what rank 0 can take). */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <time.h>

#include "cli/mpi_plugin.h"

typedef struct rate {
    int ncols;
    double *table;
    FILE *journal;
    int pending; /* records not flushed */
    long stored;
} rate;

static int instant(void *arg, const long *members, long n, hl_sweep_fn emit, void *emit_arg,
                   char *msg, size_t msgsize)
{
    rate *r = arg;
    double row[256];
    for (long i = 0; i < n; i++) {
        for (int c = 0; c < r->ncols; c++)
            row[c] = (double)members[i] + c;
        hl_sweep_result res = {.member = members[i], .status = HL_OK, .row = row};
        if (emit(&res, emit_arg) != 0)
            return 0;
    }
    (void)msg, (void)msgsize;
    return 0;
}

static int store(void *arg, const hl_sweep_result *res)
{
    rate *r = arg;
    memcpy(r->table + (size_t)res->member * (size_t)r->ncols, res->row,
           (size_t)r->ncols * sizeof(double));
    r->stored++;
    if (r->journal != NULL) { /* as the journal: a record, flushed by between() */
        fwrite(&res->member, sizeof res->member, 1, r->journal);
        fwrite(res->row, sizeof(double), (size_t)r->ncols, r->journal);
        r->pending = 1;
    }
    return 0;
}

/* Polled between messages (job.stopped): a message's records flushed at
 * once, as sweep_mpi.c's stopped() flushes the journal. */
static int between(void *arg)
{
    rate *r = arg;
    if (r->pending)
        fflush(r->journal);
    r->pending = 0;
    return 0;
}

static double cpu_seconds(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
           (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
}

static double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: bench-sweep_mpi_rate PLUGIN NCOLS MEMBERS [JOURNAL]\n");
        return 2;
    }
    void *h = dlopen(argv[1], RTLD_NOW | RTLD_GLOBAL);
    cli_mpi_entry_fn entry;
    *(void **)&entry = h != NULL ? dlsym(h, CLI_MPI_ENTRY) : NULL;
    if (entry == NULL) {
        fprintf(stderr, "cannot load %s\n", argv[1]);
        return 1;
    }
    const cli_mpi_api *api = entry();
    rate r = {.ncols = atoi(argv[2])};
    long members = atol(argv[3]);
    if (r.ncols < 1 || r.ncols > 256 || members < 1)
        return 2;
    int rank, size;
    char msg[256];
    if (api->init(&rank, &size, msg, sizeof msg) != 0)
        return 1;
    long *todo = NULL;
    if (rank == 0) {
        todo = malloc((size_t)members * sizeof *todo);
        r.table = malloc((size_t)members * (size_t)r.ncols * sizeof(double));
        for (long m = 0; m < members; m++)
            todo[m] = m;
        r.journal = argc > 4 ? fopen(argv[4], "wb") : NULL;
        if (r.journal != NULL)
            setvbuf(r.journal, NULL, _IOFBF, 1 << 16); /* as journal.c */
    }
    cli_mpi_job job = {.ncols = r.ncols,
                       .group = 1,
                       .threads = 1,
                       .fingerprint = 7,
                       .master_idle = 1,
                       .todo = todo,
                       .ntodo = rank == 0 ? members : 0,
                       .compute = instant,
                       .store = store,
                       .stopped = r.journal != NULL ? between : NULL,
                       .arg = &r};
    double t0 = seconds(), c0 = cpu_seconds();
    int outcome = api->run(&job, msg, sizeof msg);
    double el = seconds() - t0, cpu = cpu_seconds() - c0;
    if (rank == 0) {
        printf("members %ld ncols %d ranks %d seconds %.3f rows/s %.3g MB/s %.3g; rank 0 CPU "
               "%.3f s, rows per CPU s %.3g%s\n",
               r.stored, r.ncols, size, el, (double)r.stored / el,
               (double)r.stored * r.ncols * 8 / el / 1e6, cpu, (double)r.stored / cpu,
               r.journal ? " (journal)" : "");
        if (r.journal != NULL)
            fclose(r.journal);
    }
    api->finalize();
    free(todo);
    free(r.table);
    return outcome != CLI_MPI_DONE;
}
