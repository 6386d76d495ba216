/* Long jobs on standard error: what will be done, how far it got, and the
 * interrupt (Ctrl-C) that stops a job cleanly instead of killing it. */
#include <signal.h>
#include <stdarg.h>
#include <stdio.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli/cli.h"

/* NOTE: set by the handler only; the library's progress callback reports
 * it, so the job stops between two steps with its output whole. */
static volatile sig_atomic_t interrupted;

/* Without --progress, a job says nothing before this many seconds. */
#define QUIET_SECONDS 1.5
/* Seconds between two updates: in place on a terminal, else a line each. */
#define TTY_SECONDS 0.25
#define LINE_SECONDS 10.0
#define LINE_SECONDS_FORCED 1.0

static void on_interrupt(int sig)
{
    (void)sig;
    interrupted = 1;
}

/* SIGINT's disposition before cli_catch_interrupt, put back at the end. */
static struct sigaction before;
static int caught;

static void cli_catch_interrupt(void)
{
    struct sigaction sa;
    if (caught || sigaction(SIGINT, NULL, &before) != 0 || before.sa_handler == SIG_IGN)
        return; /* a job started with SIGINT ignored (nohup, a background job) keeps it so */
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_interrupt;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESETHAND; /* a second Ctrl-C kills at once */
    caught = sigaction(SIGINT, &sa, NULL) == 0;
}

int cli_interrupted(void) { return interrupted != 0; }

static double seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

void cli_progress_begin(cli_progress *p, const char *cmd, const char *unit, int mode)
{
    memset(p, 0, sizeof p[0]);
    p->cmd = cmd;
    p->unit = unit;
    p->mode = mode;
    p->tty = isatty(STDERR_FILENO);
    p->start = p->last = seconds();
    p->estimate = 1;
    cli_catch_interrupt();
}

void cli_progress_say(cli_progress *p, const char *fmt, ...)
{
    if (p->mode == CLI_PROGRESS_OFF)
        return;
    if (p->shown)
        fputs("\r\033[K", stderr);
    p->shown = 0;
    va_list ap;
    fprintf(stderr, "hamlie %s: ", p->cmd);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fputc('\n', stderr);
}

/* "3.2e+06 s (37 days)": a duration a person reads at a glance. */
static void put_duration(double s)
{
    if (s < 120)
        fprintf(stderr, "%.0f s", s);
    else if (s < 7200)
        fprintf(stderr, "%.0f min", s / 60);
    else if (s < 2 * 86400)
        fprintf(stderr, "%.1f h", s / 3600);
    else if (s < 2 * 365.25 * 86400)
        fprintf(stderr, "%.0f days", s / 86400);
    else
        fprintf(stderr, "%.2g years", s / (365.25 * 86400));
}

int cli_progress_fn(double done, double total, void *arg)
{
    cli_progress *p = arg;
    if (interrupted)
        return 1;
    if (p->mode == CLI_PROGRESS_OFF)
        return 0;
    double now = seconds();
    double gap = p->tty ? TTY_SECONDS
                        : p->mode == CLI_PROGRESS_ON ? LINE_SECONDS_FORCED : LINE_SECONDS;
    int first = p->updates == 0;
    if (p->mode == CLI_PROGRESS_AUTO && now - p->start < QUIET_SECONDS)
        return 0;
    if (!first && now - p->last < gap)
        return 0;
    p->last = now;
    p->updates++;
    fprintf(stderr, "%shamlie %s: %s %.0f of %.0f (%.1f%%)", p->tty ? "\r\033[K" : "", p->cmd,
            p->unit, done, total, total > 0 ? 100 * done / total : 100.0);
    if (p->detail[0])
        fprintf(stderr, " %s", p->detail);
    double el = now - p->start;
    if (p->estimate && done > 0 && el > 0.2) {
        fputs(", about ", stderr);
        put_duration((total - done) * el / done);
        fputs(" left", stderr);
    }
    if (!p->tty)
        fputc('\n', stderr);
    p->shown = p->tty;
    fflush(stderr);
    return 0;
}

void cli_progress_end(cli_progress *p)
{
    if (p->shown)
        fputs("\r\033[K", stderr);
    p->shown = 0;
    if (caught)
        sigaction(SIGINT, &before, NULL);
    caught = 0;
}
