/* The sweep protocol of hamlie-mpi.so (src/cli/mpi_plugin.h) with a fake
 * sweep: a member's row is bits drawn from its index (NaNs, -0, subnormals
 * included: rows must travel bit for bit), every 37th member fails with a
 * reason naming it, and members take a random while so that chunks finish
 * out of order; enough members that chunks exceed MPI's eager limit (a
 * send then waits for its receive: the protocol must not deadlock).  Run under mpirun with 1, 2 and
 * 4 ranks (cmake/mpi.cmake). t-protocol PLUGIN          every check below t-protocol PLUGIN stop
 * rank 0 stops after 50 results: STOPPED, then abort(0) t-protocol PLUGIN mismatch the last rank
 * runs "another sweep": FAILED, abort(0) Rank 0 checks: every member asked for stored exactly once,
 * its row, status and reason exact, none other stored. */
#include <dlfcn.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli/mpi_plugin.h"

#define NMEMBERS 30000L /* chunks of thousands: past MPI's eager limit */
#define NCOLS 7
#define GROUP 6L /* e.g. 3 schemes x 2 steps */

static int failures;
#define CHECK(cond, ...)                                                                           \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            failures++;                                                                            \
            fprintf(stderr, "FAIL %s:%d: ", __FILE__, __LINE__);                                   \
            fprintf(stderr, __VA_ARGS__);                                                          \
            fputc('\n', stderr);                                                                   \
        }                                                                                          \
    } while (0)

static uint64_t splitmix64(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

static void member_row(long m, double *row)
{
    for (int c = 0; c < NCOLS; c++) {
        uint64_t bits = splitmix64((uint64_t)m * NCOLS + (uint64_t)c);
        if (c == 1)
            bits = (uint64_t)m; /* a subnormal (0 for member 0) */
        if (c == 2)
            bits = 0x7ff8000000000000ULL | (uint64_t)m; /* a NaN carrying m */
        memcpy(&row[c], &bits, sizeof bits);
    }
}

static int member_fails(long m)
{
    return m % 37 == 5;
}

typedef struct fake {
    int rank;
    long stored_count, stop_after;
    unsigned char *stored; /* rank 0: times each member was stored */
} fake;

static int fake_compute(void *arg, const long *members, long n, hl_sweep_fn emit, void *emit_arg,
                        char *msg, size_t msgsize)
{
    fake *f = arg;
    double row[NCOLS];
    for (long i = 0; i < n; i++) {
        uint64_t draw = splitmix64((uint64_t)members[i] ^ (uint64_t)f->rank);
        struct timespec ts = {0, (long)(draw % 40000)};
        if (draw % 8 == 0) /* some members take a while: out of order */
            nanosleep(&ts, NULL);
        hl_sweep_result r = {.member = members[i], .status = HL_OK, .row = row};
        member_row(members[i], row);
        if (member_fails(members[i])) {
            r.status = HL_EDOM;
            snprintf(r.reason, sizeof r.reason, "member %ld blew up", members[i]);
        }
        if (emit(&r, emit_arg) != 0)
            return 0; /* told to stop: not a failure */
    }
    (void)msg, (void)msgsize;
    return 0;
}

static int fake_store(void *arg, const hl_sweep_result *r)
{
    fake *f = arg;
    double want[NCOLS];
    CHECK(r->member >= 0 && r->member < NMEMBERS, "member %ld out of range", r->member);
    if (r->member < 0 || r->member >= NMEMBERS)
        return 1;
    f->stored[r->member]++;
    f->stored_count++;
    member_row(r->member, want);
    CHECK(memcmp(want, r->row, sizeof want) == 0, "member %ld: row differs", r->member);
    char reason[HL_SWEEP_REASON] = "";
    if (member_fails(r->member))
        snprintf(reason, sizeof reason, "member %ld blew up", r->member);
    CHECK(r->status == (member_fails(r->member) ? HL_EDOM : HL_OK), "member %ld: status %d",
          r->member, (int)r->status);
    CHECK(strcmp(reason, r->reason) == 0, "member %ld: reason '%s'", r->member, r->reason);
    return f->stop_after > 0 && f->stored_count >= f->stop_after;
}

static int never_stopped(void *arg)
{
    return 0;
}

/* One run of the protocol over todo (rank 0's; NULL: none); on rank 0
 * checks that exactly the members of todo were stored. */
static int run_job(const cli_mpi_api *api, fake *f, const long *todo, long ntodo, int idle,
                   uint64_t fingerprint)
{
    cli_mpi_job job = {.ncols = NCOLS,
                       .group = GROUP,
                       .threads = 1,
                       .fingerprint = fingerprint,
                       .master_idle = idle,
                       .todo = todo,
                       .ntodo = ntodo,
                       .compute = fake_compute,
                       .store = fake_store,
                       .stopped = never_stopped,
                       .arg = f};
    char msg[256] = "";
    if (f->rank == 0) {
        memset(f->stored, 0, NMEMBERS);
        f->stored_count = 0;
    }
    int outcome = api->run(&job, msg, sizeof msg);
    if (f->rank == 0 && outcome == CLI_MPI_DONE) {
        long k = 0;
        for (long m = 0; m < NMEMBERS; m++) {
            int want = k < ntodo && todo[k] == m;
            k += want;
            CHECK(f->stored[m] == want, "member %ld stored %d times, want %d", m, f->stored[m],
                  want);
        }
    }
    if (outcome == CLI_MPI_FAILED)
        fprintf(stderr, "rank %d: %s\n", f->rank, msg);
    return outcome;
}

static const cli_mpi_api *load(const char *path)
{
    void *h = dlopen(path, RTLD_NOW | RTLD_GLOBAL);
    if (h == NULL) {
        fprintf(stderr, "cannot load %s: %s\n", path, dlerror());
        exit(1);
    }
    cli_mpi_entry_fn entry;
    *(void **)&entry = dlsym(h, CLI_MPI_ENTRY);
    if (entry == NULL || entry()->version != CLI_MPI_VERSION) {
        fprintf(stderr, "%s: no %s of version %d\n", path, CLI_MPI_ENTRY, CLI_MPI_VERSION);
        exit(1);
    }
    return entry();
}

/* the journal's case: a few members done, some groups half done */
static long resume_todo(long *todo)
{
    long n = 0;
    for (long m = 0; m < NMEMBERS; m++)
        if (!(m < 500 || (m % 11 == 3) || (m / GROUP) % 5 == 2))
            todo[n++] = m;
    return n;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: t-protocol PLUGIN [stop|mismatch]\n");
        return 2;
    }
    const cli_mpi_api *api = load(argv[1]);
    const char *mode = argc > 2 ? argv[2] : "all";
    int size = 0;
    fake f = {0};
    char msg[256];
    if (api->init(&f.rank, &size, msg, sizeof msg) != 0) {
        fprintf(stderr, "init: %s\n", msg);
        return 1;
    }
    f.stored = calloc(NMEMBERS, 1);
    long *todo = malloc(NMEMBERS * sizeof *todo);
    for (long m = 0; m < NMEMBERS; m++)
        todo[m] = m;
    int rank0 = f.rank == 0;
    if (strcmp(mode, "stop") == 0) {
        f.stop_after = 50;
        int outcome = run_job(api, &f, rank0 ? todo : NULL, rank0 ? NMEMBERS : 0, 0, 42);
        if (rank0) {
            CHECK(outcome == CLI_MPI_STOPPED, "stop: outcome %d", outcome);
            CHECK(f.stored_count >= 50 && f.stored_count < NMEMBERS, "stop: %ld stored",
                  f.stored_count);
            printf("stop: %ld members stored, %d failures\n", f.stored_count, failures);
            fflush(stdout);
            api->abort(failures ? 1 : 0); /* the workers wait for an answer */
        }
        for (;;) /* a worker waits until the abort ends it */
            nanosleep(&(struct timespec){1, 0}, NULL);
    }
    if (strcmp(mode, "mismatch") == 0) {
        uint64_t fp = f.rank == size - 1 && size > 1 ? 43 : 42;
        int outcome = run_job(api, &f, rank0 ? todo : NULL, rank0 ? NMEMBERS : 0, 0, fp);
        if (rank0) {
            CHECK(outcome == (size > 1 ? CLI_MPI_FAILED : CLI_MPI_DONE), "mismatch: outcome %d",
                  outcome);
            printf("mismatch: %d failures\n", failures);
            fflush(stdout);
            api->abort(failures ? 1 : 0);
        }
        for (;;)
            nanosleep(&(struct timespec){1, 0}, NULL);
    }
    /* every member; then a resume's members; then none; then the master idle */
    CHECK(run_job(api, &f, todo, rank0 ? NMEMBERS : 0, 0, 42) == CLI_MPI_DONE, "full run");
    long *part = malloc(NMEMBERS * sizeof *part);
    long npart = resume_todo(part);
    CHECK(run_job(api, &f, part, rank0 ? npart : 0, 0, 42) == CLI_MPI_DONE, "resumed run");
    CHECK(run_job(api, &f, todo, 0, 0, 42) == CLI_MPI_DONE, "empty run");
    CHECK(run_job(api, &f, todo, rank0 ? NMEMBERS : 0, 1, 42) == CLI_MPI_DONE, "idle master");
    if (rank0)
        printf("rank 0 of %d: %d failures\n", size, failures);
    api->finalize();
    free(part);
    free(todo);
    free(f.stored);
    return failures != 0;
}
