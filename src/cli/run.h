/* hamlie run: what its files share (cmd_run.c runs and summarises,
 * run_csv.c writes the trajectory: the CSV, streamed, and the rows kept
 * for --plot). */
#ifndef HAMLIE_CLI_RUN_H
#define HAMLIE_CLI_RUN_H

#include <stdio.h>

#include "cli/cli.h"
#include "hamlie/run.h"
#include "hamlie/runplot.h"

/* The options proper to run. */
typedef struct run_opts {
    const char *scheme, *equations, *init, *out, *orders, *plot, *formats;
    const char *dt_s, *t_s, *tol_s, *every_s, *digits_s;
    const char **observe;
    int nobserve, no_ref;
    double dt, t, tol, digits;
    long every;
    int have_dt;
    /* --event (run_events.c) */
    const char *event, *direction, *event_stop_s, *events_out;
    hl_event_dir dir;
    long event_stop;
    char *events_path;       /* where the crossings go (NULL: the JSON only) */
    struct crossings *cross; /* the crossings found */
} run_opts;

typedef struct csv {
    FILE *fp;
    hl_buf buf; /* whole lines waiting to be written */
    int n2, nobs, sigma;
    int io_error;
    long rows;
    hl_runplot *plot; /* --plot: the rows kept for the figures, or NULL */
    double *plot_row; /* 1 + n2 + 1 + sigma + nobs values */
} csv;

/* The CSV's header line: t, the phase variables, H, sigma, the observers. */
void run_csv_header(csv *c, hl_system *sys, const run_opts *r);
/* An hl_run_row_fn: the row into the CSV (and the figures' store). */
int run_csv_row(const hl_run_row *row, void *arg);
/* Write the whole lines waiting; io_error on failure. */
void run_csv_flush(csv *c);

/* The figures' store with the CSV's columns; draw them (the number of files,
 * or -1 after the message); free it. */
void run_plot_open(csv *c, hl_system *sys, const run_opts *r, const cli_opts *o);
int run_plot_write(csv *c, const run_opts *r);
void run_plot_close(csv *c);

/* --event, --direction, --event-stop, --events-out (k = 0..3 of them) */
#define RUN_EVENT_OPTS 4
void run_events_found(run_opts *r, int k, const char *value);
/* Their usage checks (-1 to go on, else the exit code); where the
 * crossings go. */
int run_events_check(run_opts *r, const cli_opts *o, const cli_command *cmd);
/* The run's event, with r->cross to keep its crossings. */
int run_events_setup(hl_run *run, const run_opts *r, hl_system *sys, hl_error *err);
/* After a run that completed: the crossings' file (CLI_OK or CLI_ERROR),
 * and the line that says what was written. */
int run_events_write(const run_opts *r, hl_system *sys);
void run_events_say(hl_buf *out, const run_opts *r, const hl_run_stats *s, const hl_run *run);
void run_events_json(hl_json *j, const run_opts *r, hl_system *sys, const hl_run *run,
                     const hl_run_stats *s);
void run_events_free(run_opts *r);

/* The CSV's file: stdout, or --out's FILE.tmp, renamed to FILE on success
 * and FILE.partial on failure (close).  CLI_OK or CLI_ERROR. */
int run_open_out(csv *c, const run_opts *r, char **tmpname);
int run_close_out(csv *c, const run_opts *r, const char *tmpname, int ok, const hl_run_stats *s);

#endif
