/* hamlie — sweeps: many runs of one system at once, each summarised in one
 * row of a table (in the spirit of heyoka's ensemble propagation and
 * DifferentialEquations.jl's EnsembleProblem).
 *
 *   hl_sweep *sw;
 *   hl_sweep_spec spec = {.H = "p^2/2 - cos(q)", .grid = "q=-3:3:200,p=-2.5:2.5:200",
 *                         .schemes = "stormer-verlet-kdk,rk4", .dts = "0.1,0.05", .t = 1e3};
 *   hl_sweep_new(&sw, &spec, err);             // members enumerated, inputs checked
 *   hl_sweep_table *tab = hl_sweep_table_new(sw);
 *   hl_sweep_run(sw, NULL, hl_sweep_count(sw), 2, store, tab, progress, arg, err);
 *   hl_sweep_write(sw, tab, "sweep.h5", err);  // or .csv
 *
 * Members.  The points come from one source: a grid ("q=-3:3:200,p=0"; a
 * range a:b:n is n equally spaced values from a to b inclusive, a single
 * value is one; every variable named once), a CSV text (a header naming
 * every variable, one point a line), or `random` points uniform within
 * bounds ("q=-3:3,p=-1:1", count, seed).  They are crossed with the
 * parameter values (params: "k=1,2,3,eps=0:0.1:11": the values of one name
 * until the next "name="), the schemes (catalog names, "lie" for the
 * adaptive Taylor integrator at tolerance tol) and the steps dts.  Member m
 * is numbered in that nesting, the step innermost:
 *   m = ((point * nparamsets + paramset) * nschemes + scheme) * ndts + dt.
 * A random point is a function of (seed, point index) only (splitmix64),
 * so a member's inputs never depend on who computes it.
 *
 * Results.  Each member is run from its point to t (hl_run_fixed, or
 * hl_run_adaptive for "lie"), with the reference trajectory when
 * spec.reference, and summarised in one row of doubles (the columns below,
 * hl_sweep_ncols / hl_sweep_column) plus a status and a reason.  A member
 * that fails (blow-up, Newton failure, a point outside H's domain) is a row
 * with status != HL_OK, its reason, and the values of its last good step;
 * the sweep goes on.  A member's row depends only on its inputs: the same
 * bits with any number of threads or MPI ranks, in any order.
 *
 * Columns, in order (N degrees of freedom, P parameters):
 *   member, point, paramset, scheme, dt,           indices and the step
 *   <param names>                                  P values
 *   <q_j>0, <p_j>0                                 the start (2N)
 *   t, steps, H0, max_dH, dH,                      time reached, steps, H(0),
 *                                                  max |H - H0|, H - H0 at t
 *   max_sigma, err,                                max |z_k - z(t_k)|^2 and
 *                                                  |z - z(t)| at t (NaN w/o reference)
 *   order,                                         observed order from dt and dt/2
 *                                                  (NaN unless spec.order)
 *   megno, mlce,                                   <Y> and the mLCE at t of the
 *                                                  point (NaN unless spec.chaos)
 *   <q_j>, <p_j>                                   the state at t (2N)
 *
 * Threads: hl_sweep_run gives each thread its own system, runs and chaos
 * object, built from the spec's texts; compiled code is shared through
 * the disk cache (tape.h).  The sweep object itself is read-only while
 * running.
 */
#ifndef HAMLIE_SWEEP_H
#define HAMLIE_SWEEP_H

#include <stdint.h>

#include "hamlie/error.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_sweep_spec {
    const char *H;          /* the Hamiltonian (required) */
    const char *pairs;      /* as hl_system_spec, or NULL */
    const char *params;     /* parameter values to cross, or NULL */
    /* exactly one source of points: */
    const char *grid;       /* "q=-3:3:200,p=0" */
    const char *points_csv; /* the text of a CSV file (header of variable names) */
    const char *points_csv_name; /* its file name, for messages (may be NULL) */
    const char *random;     /* "q=-3:3,p=-1:1": bounds, with nrandom and seed */
    long nrandom;
    uint64_t seed;
    const char *schemes;    /* "stormer-verlet-kdk,rk4" or "lie" (required) */
    const char *dts;        /* "0.1,0.05" (required for fixed-step schemes; for
                               "lie" the output spacing, default t) */
    double t;               /* > 0 */
    double tol;             /* the adaptive integrator's and the reference's tolerance
                               (0: 1e-15) */
    int reference;          /* measure the error against the Taylor reference */
    int order;              /* also run at dt/2 and give the observed order */
    int chaos;              /* MEGNO and mLCE of each point (hl_chaos, tol) */
    /* optional arrays per member (see "Arrays" below): */
    long save_every;   /* > 0: the trajectory every save_every steps (for
                          "lie": output rows of spacing dt), 0: none */
    const char *event; /* a surface "g" or "lhs = rhs" (as hl_run_event): its
                          crossings, or NULL */
    int direction;     /* of the crossings: 1 up, -1 down, 0 both (hl_event_dir) */
} hl_sweep_spec;

typedef struct hl_sweep hl_sweep;

/* Reads and checks the spec, enumerates the members.  Errors point into the
 * text at fault (err->src is that field's string): a grid with no points
 * ("q=1:0:0"), a name that is not a variable, a variable given twice or
 * missing, a bound that is not finite, an unknown scheme, a step that does
 * not divide t, more than HL_SWEEP_MAX_MEMBERS members. */
#define HL_SWEEP_MAX_MEMBERS 2000000000L
hl_status hl_sweep_new(hl_sweep **out, const hl_sweep_spec *spec, hl_error *err);
void hl_sweep_free(hl_sweep *sw); /* NULL is a no-op */

long hl_sweep_count(const hl_sweep *sw);
int hl_sweep_ncols(const hl_sweep *sw);
const char *hl_sweep_column(const hl_sweep *sw, int c);
/* The index of the column named name, or -1. */
int hl_sweep_column_index(const hl_sweep *sw, const char *name);
int hl_sweep_ndof(const hl_sweep *sw); /* N: the start and the state are 2N columns */
/* The points and point i's start z (2N values, q then p): a function of
 * the spec and i alone. */
long hl_sweep_npoints(const hl_sweep *sw);
void hl_sweep_point(const hl_sweep *sw, long i, double *z);
int hl_sweep_nschemes(const hl_sweep *sw);
const char *hl_sweep_scheme(const hl_sweep *sw, int i);
const hl_sweep_spec *hl_sweep_get_spec(const hl_sweep *sw); /* its own copies */
/* A hash of everything that decides the results (spec texts and numbers,
 * hamlie's version): a journal or file of another sweep is refused. */
uint64_t hl_sweep_fingerprint(const hl_sweep *sw);

/* Arrays.  With spec.save_every, a member also gives its trajectory: the
 * rows of hl_run_fixed / hl_run_adaptive at every save_every-th step (and
 * the last); with spec.event, the crossings of the surface in the
 * direction (hl_run_event: on the Taylor polynomial for "lie", on the
 * cubic Hermite interpolant of each step otherwise).  Each is a list of
 * rows of hl_sweep_array_width values: t, then the state (q then p).  A
 * failed member's arrays end at its last good step.  Kinds: */
enum { HL_SWEEP_TRAJ = 0, HL_SWEEP_CROSS = 1, HL_SWEEP_NARRAYS = 2 };
/* 1 + 2N */
int hl_sweep_array_width(const hl_sweep *sw);
/* Whether the sweep gives arrays of kind (HL_SWEEP_TRAJ, HL_SWEEP_CROSS). */
int hl_sweep_has_array(const hl_sweep *sw, int kind);
/* The most trajectory rows a member can give (0 without save_every):
 * for sizing buffers and chunks; crossings are not bounded. */
long hl_sweep_traj_rows_max(const hl_sweep *sw);

#define HL_SWEEP_REASON 160
typedef struct hl_sweep_result {
    long member;
    hl_status status;
    char reason[HL_SWEEP_REASON]; /* "" when status == HL_OK */
    const double *row;            /* hl_sweep_ncols values */
    /* the arrays (nrows[k] rows of hl_sweep_array_width values each; 0 and
     * NULL for a kind the sweep does not give) */
    long nrows[HL_SWEEP_NARRAYS];
    const double *array[HL_SWEEP_NARRAYS];
} hl_sweep_result;

/* Called once per member as it completes (in any order, one call at a
 * time: the caller needs no lock); a non-zero return stops the sweep (the
 * members running finish, no new one starts; HL_ESTOP). */
typedef int (*hl_sweep_fn)(const hl_sweep_result *r, void *arg);

/* Runs the members listed (members NULL: 0 .. n-1) on `threads` threads
 * (>= 1).  progress (may be NULL) is called with members done and n after
 * each member, from the thread that finished it, one call at a time; a
 * non-zero return stops the sweep as above.  A member's failure is its
 * row's status, not the call's: the call fails only for the sweep as a
 * whole (no memory, a thread that cannot start, a stop). */
hl_status hl_sweep_run(hl_sweep *sw, const long *members, long n, int threads, hl_sweep_fn fn,
                       void *fn_arg, hl_progress_fn progress, void *progress_arg, hl_error *err);
/* For a caller that hands a sweep out in chunks (the MPI master): members
 * m and m' belong together when m / q == m' / q for this q, a multiple of
 * the members of a point (all schemes and steps): whole rounds of the SIMD
 * lanes (the lanes' width in points, times the paramsets when they are
 * few).  A chunk of whole blocks of q runs its lanes full; a chunk cut
 * elsewhere gives the same rows, only slower (a part-empty round costs a
 * full one). */
long hl_sweep_chunk_quantum(const hl_sweep *sw);

/* ---- the table of results, in member order ----------------------------- */
typedef struct hl_sweep_table hl_sweep_table;
hl_sweep_table *hl_sweep_table_new(const hl_sweep *sw); /* NULL: no memory */
void hl_sweep_table_free(hl_sweep_table *tab);
/* An hl_sweep_fn: stores r in its place (arg: the table). */
int hl_sweep_table_store(const hl_sweep_result *r, void *tab);
int hl_sweep_table_has(const hl_sweep_table *tab, long member);
const double *hl_sweep_table_row(const hl_sweep_table *tab, long member);
hl_status hl_sweep_table_status(const hl_sweep_table *tab, long member);
const char *hl_sweep_table_reason(const hl_sweep_table *tab, long member);
long hl_sweep_table_done(const hl_sweep_table *tab);
/* Member's array of kind: *nrows rows of hl_sweep_array_width values
 * (NULL and 0 when none). */
const double *hl_sweep_table_array(const hl_sweep_table *tab, long member, int kind, long *nrows);

/* The table to path: ".h5" an HDF5 file (its layout in docs/sweep.md), any
 * other name CSV (the columns, then status and reason).  Written to a
 * temporary name beside path and renamed when complete, so an error leaves
 * nothing half-written; the same table gives the same bytes.  The arrays:
 * in the HDF5 file (/trajectories, /crossings); with CSV, in sidecar files
 * beside path (hl_sweep_array_path), which "-" (standard output) cannot
 * have (HL_EINVAL). */
hl_status hl_sweep_write(const hl_sweep *sw, const hl_sweep_table *tab, const char *path,
                         hl_error *err);
/* The CSV sidecar of kind for the table's path: "dir/s.csv" ->
 * "dir/s-traj.csv" / "dir/s-cross.csv" (the suffix after the last '.' of
 * the file name replaced; appended if none).  Caller frees. */
char *hl_sweep_array_path(const char *path, int kind);

/* ---- resuming ------------------------------------------------------------
 * A journal beside the output (path + ".journal") gets each result as it
 * completes (appended, flushed, each record checked by a checksum); it is
 * removed once the output is written.  hl_sweep_journal_load fills the table
 * from a journal left by an interrupted sweep with the same fingerprint
 * (HL_EINVAL, saying so, for another sweep's), ignoring a torn last
 * record. */
typedef struct hl_sweep_journal hl_sweep_journal;
hl_status hl_sweep_journal_open(hl_sweep_journal **out, const hl_sweep *sw, const char *path,
                                int resume, hl_sweep_table *tab, hl_error *err);
int hl_sweep_journal_append(const hl_sweep_result *r, void *journal); /* an hl_sweep_fn */
void hl_sweep_journal_close(hl_sweep_journal *j, int remove_file);
/* Appends from now on are flushed by hl_sweep_journal_flush (and closing)
 * instead of each at once: for a caller that takes in results in batches
 * and flushes once a batch.  A kill loses the records not flushed. */
void hl_sweep_journal_defer(hl_sweep_journal *j);
/* The records appended since the last flush to the file; non-zero (as
 * hl_sweep_journal_failed) if a write failed. */
int hl_sweep_journal_flush(hl_sweep_journal *j);
/* 1 once an append failed (disk full): the sweep was stopped by it. */
int hl_sweep_journal_failed(const hl_sweep_journal *j);

#ifdef __cplusplus
}
#endif

#endif
