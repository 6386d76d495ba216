/* The orbits of `hamlie section` on several threads, each orbit with its
 * crossings and, with --chaos, its MEGNO <Y> (chaos.h).
 *
 * hl_system, hl_run and hl_chaos are used by one thread at a time, so every
 * thread builds its own from the command's texts (cli_system from the
 * options, the surface, the scheme's name).  Orbits are handed out one at a
 * time; each one's results are kept apart and gathered in orbit order
 * afterwards, so the output is the same bytes with any number of threads.
 * The calling thread shows the progress (orbits done of M) and turns Ctrl-C
 * into a stop that every running orbit sees at its next progress check. */
#ifndef HAMLIE_CLI_SECTION_ORBITS_H
#define HAMLIE_CLI_SECTION_ORBITS_H

#include "cli/crossings.h"
#include "hamlie/section.h"

/* <Y> above this at the end of the orbit's span: chaotic.  Regular orbits
 * have <Y> -> 2 from either side (-> 0 near a stable periodic orbit, which
 * is why the test is one-sided) with oscillations decaying like 1/t.  A
 * chaotic orbit's <Y> grows like lambda t / 2; 0.5 above 2 is passed by
 * t ~ 5 / lambda, while a torus never gets there.  Measured on 180
 * Henon-Heiles orbits at E = 1/12, 1/8, 1/6 over spans of ~3000 (the
 * figures of docs/sections.md): regular 0.61 .. 2.09, chaotic 5.5 and up. */
#define SECTION_CHAOS_THRESHOLD 2.5
/* Below this span <Y> has not separated regular from chaotic reliably. */
#define SECTION_CHAOS_MIN_SPAN 1000.0

/* What every thread needs to build its objects and run its orbits. */
typedef struct section_job {
    const cli_opts *o;   /* -H, --pairs, --param: the system's texts */
    const char *surface; /* "x=0" */
    hl_event_dir dir;
    double E;
    const char *scheme;   /* NULL: the adaptive Taylor run */
    hl_section_opts opts; /* tol (adaptive), dt, t_max */
    long ncross;          /* crossings per orbit */
    int chaos;            /* compute <Y> per orbit */
    double chaos_tol;     /* its integrator's tolerance */
    const double *zs;     /* M seeds of n2 values */
    int M, n2;
} section_job;

/* One orbit's results. */
typedef struct section_orbit {
    crossings table; /* its crossings (the orbit's index in column 0) */
    double max_dH;   /* max |H - E| over them */
    double span;     /* the time of its last crossing (or where it stopped) */
    double megno;    /* <Y> over [0, span]; NaN without --chaos or on failure */
    int chaotic;     /* 1 chaotic, 0 regular, -1 not classified */
    int done;        /* run to its end (not cut by an interrupt) */
    int failed;      /* the orbit (or its <Y>) failed: why says */
    hl_status status; /* and its status */
    char why[320];
} section_orbit;

/* Run every orbit of job on nthreads threads (>= 1) into orbits[M]
 * (zeroed by the caller; free them with section_orbits_free).  progress
 * (cli.h, begun by the caller) shows the orbits done.  Returns CLI_OK;
 * CLI_INTERRUPTED after Ctrl-C (the orbits finished before have done = 1,
 * the others are cut and have done = 0); CLI_ERROR after the message when
 * a thread's objects cannot be built (before any orbit runs). */
int section_orbits_run(const section_job *job, section_orbit *orbits, int nthreads,
                       cli_progress *progress);
void section_orbits_free(section_orbit *orbits, int M);

/* The crossings' CSV (crossings.h's columns) with two more: the orbit's
 * mean_Y and chaotic (1, 0, or empty when not classified).  Written to
 * PATH.tmp and renamed ("-": standard output).  CLI_OK, or CLI_ERROR after
 * the message (nothing left under PATH). */
int section_write_chaos_csv(const crossings *table, const section_orbit *orbits, hl_system *sys,
                            const char *path);


#endif
