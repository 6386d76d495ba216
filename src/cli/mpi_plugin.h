/* The MPI plugin: `hamlie sweep` spread over the ranks of an MPI job.
 *
 * Why a plugin: libmpi costs every process that loads it some 10 ms, and on
 * some systems MPI_Init fails outside a launcher; neither libhamlie nor
 * hamlie-cli.so may link it.  hamlie-mpi.so (mpi_plugin.c, the only file
 * that includes mpi.h; built by cmake/mpi.cmake when MPI is found) is
 * loaded by sweep_mpi.c only under mpirun or with --mpi.  It links nothing
 * of hamlie: it moves bytes and calls back through cli_mpi_job, so one copy
 * of the library serves the whole process.
 *
 * The protocol (docs/sweep-at-scale.md):  rank 0 is the master.  It holds
 * the members still to do (all of them, or those a journal lacks), hands
 * them out in chunks of whole groups (job.group consecutive members share
 * a point) to whoever asks — dynamic balancing, the chunks shrinking as
 * the work runs out — and receives each chunk's results (member, status,
 * reason, row) with the next request.  Every result goes through
 * job.store, one call at a time, on rank 0.  Rank 0 also computes chunks
 * itself on a thread of its own unless job.master_idle (its main thread
 * only serves, sleeping between polls, so it does not burn a core).  The
 * other ranks compute what they are given with job.compute and ask again
 * (two requests open each: the next chunk is there when one is done),
 * until the master answers "done", or ends the job after a stop.
 *
 * A rank's rows travel as bytes: the ranks must share the double format
 * and byte order (one cluster); each request carries the worker's sweep
 * fingerprint and the master refuses another sweep's. */
#ifndef HAMLIE_CLI_MPI_PLUGIN_H
#define HAMLIE_CLI_MPI_PLUGIN_H

#include <stddef.h>
#include <stdint.h>

#include "hamlie/sweep.h" /* hl_sweep_result, hl_sweep_fn: types only */

#define CLI_MPI_PLUGIN "hamlie-mpi.so"
#define CLI_MPI_ENTRY "hamlie_mpi_plugin" /* const cli_mpi_api *hamlie_mpi_plugin(void) */
#define CLI_MPI_VERSION 2

/* What the protocol needs of the sweep; the callbacks' arg is job.arg. */
typedef struct cli_mpi_job {
    int ncols;   /* doubles in a row */
    /* the arrays of a result (sweep.h, "Arrays"): bit k set when kind k
     * travels; width doubles a row; about how many bytes of them a member
     * gives (for chunk sizes; 0: unknown or none) */
    unsigned arrays;
    int width;
    long member_bytes;
    long group;  /* members per group (>= 1): chunks hold whole groups */
    int threads; /* this rank's compute threads (chunk sizes) */
    uint64_t fingerprint;
    int master_idle; /* rank 0 only serves */
    /* rank 0: the members to compute, ascending */
    const long *todo;
    long ntodo;
    /* any rank: runs members[0 .. n) and calls emit once per member, one
     * call at a time; stops early when emit returns non-zero.  0, or
     * non-zero with the reason in msg. */
    int (*compute)(void *arg, const long *members, long n, hl_sweep_fn emit, void *emit_arg,
                   char *msg, size_t msgsize);
    /* rank 0: one result, from any rank, one call at a time; non-zero
     * stops the sweep (as an interrupt does) */
    int (*store)(void *arg, const hl_sweep_result *r);
    /* rank 0: polled between messages; non-zero stops the sweep (Ctrl-C) */
    int (*stopped)(void *arg);
    void *arg;
} cli_mpi_job;

/* cli_mpi_api.run's outcomes */
enum {
    CLI_MPI_DONE = 0,    /* every member computed (rank 0: stored) */
    CLI_MPI_STOPPED = 1, /* stopped: an interrupt on rank 0, or the master said so */
    CLI_MPI_FAILED = -1  /* an error, said in msg */
};

typedef struct cli_mpi_api {
    int version; /* CLI_MPI_VERSION */
    /* MPI_Init_thread (funneled: only the calling thread talks MPI); 0, or
     * -1 with the reason in msg */
    int (*init)(int *rank, int *size, char *msg, size_t msgsize);
    /* the sweep protocol above, on every rank */
    int (*run)(const cli_mpi_job *job, char *msg, size_t msgsize);
    /* after a whole run on every rank */
    void (*finalize)(void);
    /* ends every rank of the job (after a stop or an error on rank 0: the
     * others may be waiting for it) */
    void (*abort)(int code);
} cli_mpi_api;

typedef const cli_mpi_api *(*cli_mpi_entry_fn)(void);

/* ---- the command's side (sweep_mpi.c) ---------------------------------- */

/* Whether this process runs under an MPI launcher (OMPI_COMM_WORLD_SIZE,
 * PMIX_RANK or PMI_SIZE in the environment). */
int cli_mpi_launched(void);

/* This process's rank from the launcher's environment (0 outside one). */
int cli_mpi_env_rank(void);
/* Every rank reads the same command line, so a usage or input error would
 * be said once per rank: on ranks but 0 of a launched job, standard error
 * goes to /dev/null until cli_mpi_quiet_end (the exit status is the same
 * on every rank; rank 0 says why).  Returns what quiet_end restores (-1:
 * nothing was silenced). */
int cli_mpi_quiet_begin(void);
void cli_mpi_quiet_end(int saved);

/* Threads per rank when the user gave none: the cores divided among the
 * ranks of this node (OMPI_COMM_WORLD_LOCAL_SIZE), at least 1. */
int cli_mpi_default_threads(int cores);

/* cmd_sweep.c's hooks.  First, with the sweep built on every rank: -1
 * when not under MPI (nor forced by --mpi) and on rank 0, which goes on;
 * otherwise the exit status of this rank's part (the others compute here,
 * or the plugin could not be loaded: CLI_ERROR).  *threads: when not
 * given, the cores divided among this node's ranks. */
int cli_sweep_mpi_begin(hl_sweep *sw, int forced, long *threads, int threads_given);
/* Whether begin started MPI (rank 0 then serves instead of running). */
int cli_sweep_mpi_active(void);
/* Rank 0, in place of the threaded run: the members the table lacks
 * handed out, every result stored in tab and journal (may be NULL) with
 * progress; -1 when all are done, else the exit status (said on stderr:
 * CLI_INTERRUPTED, CLI_ERROR). */
int cli_sweep_mpi_serve(hl_sweep *sw, hl_sweep_table *tab, hl_sweep_journal *journal,
                        const char *out, int progress_mode);
/* Rank 0, with the command's exit status, once the file is written or not:
 * returns it after MPI_Finalize, or ends the whole job with it (abort)
 * after an interrupt or an error, the journal being closed.  A no-op but
 * for MPI. */
int cli_sweep_mpi_end(int rc);

#endif
