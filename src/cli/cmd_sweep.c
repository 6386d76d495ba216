/* hamlie sweep: many runs of one system at once (sweep.h), on every core.
 * This file reads the options into a sweep spec, runs the members not yet
 * in the journal, and writes the table (CSV or HDF5) whole, then the maps
 * of --plot.  The mathematics is in the library. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "cli/cli.h"
#include "cli/crossings.h"
#include "cli/mpi_plugin.h"
#include "hamlie/h5.h"
#include "hamlie/sweep.h"
#include "hamlie/sweepplot.h"

const char cmd_sweep_help[] =
    "usage: hamlie sweep -H FORMULA (--grid G | --init-file F | --random B --count M)\n"
    "                    --scheme S1,S2 --dt D1,D2 --t T [options]\n"
    "\n"
    "Many runs at once, each summarised in one row: the members are the points\n"
    "crossed with the parameter values, the schemes and the steps (the step\n"
    "innermost: member = ((point * paramsets + paramset) * schemes + scheme) *\n"
    "steps + step).  Rows are in member order and the same with any number of\n"
    "threads.\n"
    "\n"
    "  -H, --hamiltonian F  the Hamiltonian (required)\n"
    "  --grid G             'q=-3:3:200,p=0': a:b:n is n values from a to b\n"
    "                       inclusive, a number is one; every variable named once\n"
    "                       (the first varies slowest)\n"
    "  --init-file F        the points from a CSV file: a header naming every\n"
    "                       variable, one point a line\n"
    "  --random B           'q=-3:3,p=-1:1': --count M points uniform within the\n"
    "                       bounds (a number fixes a variable), from --seed S\n"
    "                       (default 1): point i depends only on (S, i)\n"
    "  --param k=1,2,eps=0:0.1:11  parameter values crossed (repeatable)\n"
    "  --scheme S1,S2       schemes of the catalog; lie is the adaptive Taylor\n"
    "                       integrator at --tol\n"
    "  --dt D1,D2           the steps (each must divide --t; for lie alone optional)\n"
    "  --t T                the final time\n"
    "  --tol TOL            the adaptive integrator's, the reference's and the chaos\n"
    "                       indicators' tolerance (default 1e-15)\n"
    "  --reference          also the error against the Taylor reference (max_err,\n"
    "                       err); --no-reference (the default) leaves them NaN\n"
    "  --order              the observed order from dt and dt/2 (runs each member\n"
    "                       twice, against the reference)\n"
    "  --chaos              MEGNO <Y> and the mLCE of each point at --t\n"
    "  --save-every K       also each member's trajectory, every K-th step (and the\n"
    "                       last; for lie every K-th row of spacing --dt)\n"
    "  --event G            also each member's crossings of the surface G = 0 (a\n"
    "                       formula in the variables, or 'lhs = rhs'), located as by\n"
    "                       run --event\n"
    "  --direction D        up (G from < 0 to >= 0), down, or both (default)\n"
    "  --threads N          threads (default: every core; under mpirun, the cores\n"
    "                       shared among the node's ranks)\n"
    "  --mpi                spread the members over the ranks of an MPI job (the\n"
    "                       default under mpirun; docs/sweep-at-scale.md)\n"
    "  --out FILE           FILE.csv or FILE.h5 (default: CSV on standard output);\n"
    "                       the arrays in FILE.h5, or beside FILE.csv in\n"
    "                       FILE-traj.csv and FILE-cross.csv (member, t, the state)\n"
    "  --resume             continue an interrupted sweep from FILE.journal\n"
    "  --plot DIR           for a grid in two variables, a map per scheme and step\n"
    "                       of log10 max_dH (and of MEGNO with --chaos)\n"
    "  --format png,svg,pdf the maps' formats (default png)\n"
    "  --pairs, --progress, --quiet   as for every command\n"
    "\n"
    "Columns: member, point, paramset, scheme, dt, the parameters, the start\n"
    "(q0, p0), t, steps, H0, max_dH, dH, max_err, err, order, megno, mlce, the\n"
    "state at t, then status and reason.  A member that fails (a blow-up, a\n"
    "Newton failure, a point outside H's domain) is recorded with its reason\n"
    "and the others go on.  With --out, each result is also appended to\n"
    "FILE.journal as it completes: after Ctrl-C (or a kill) --resume runs only\n"
    "the members missing and gives the same file.\n"
    "Exit status: 0 every member done; 1 some member failed (named on stderr,\n"
    "the file written); 2 usage or input error; 130 interrupted.\n"
    "Example: hamlie sweep -H 'p^2/2 - cos(q)' --grid 'q=-3:3:50,p=-2:2:50' \\\n"
    "           --scheme stormer-verlet-kdk,rk4 --dt 0.1,0.05 --t 100 --out s.csv\n";

typedef struct sweep_opts {
    const char *grid, *init_file, *random, *count_s, *seed_s, *scheme, *dt_s, *t_s, *tol_s;
    const char *threads_s, *out, *plot, *formats;
    const char *save_every_s, *event, *direction_s;
    char *params; /* every --param joined with ',' */
    int reference, no_reference, order, chaos, resume, mpi;
    long count, threads, save_every;
    hl_event_dir direction;
    unsigned long long seed;
    double t, tol;
} sweep_opts;

static void found_opt(void *arg, int k, const char *value)
{
    sweep_opts *s = arg;
    const char **slot[] = {&s->grid,   &s->init_file, &s->random, &s->count_s, &s->seed_s,
                           &s->scheme, &s->dt_s,      &s->t_s,    &s->tol_s,   &s->threads_s,
                           &s->out,    &s->plot,      &s->formats};
    int *flag[] = {&s->reference, &s->no_reference, &s->order, &s->chaos, &s->resume, &s->mpi};
    const char **arrays[] = {&s->save_every_s, &s->event, &s->direction_s};
    if (k < 13)
        *slot[k] = value;
    else if (k < 19)
        *flag[k - 13] = 1;
    else if (k > 19)
        *arrays[k - 20] = value;
    else { /* --param, repeatable: joined as one list */
        size_t n = (s->params ? strlen(s->params) + 1 : 0) + strlen(value) + 1;
        char *p = hl_xmalloc(n);
        snprintf(p, n, "%s%s%s", s->params ? s->params : "", s->params ? "," : "", value);
        free(s->params);
        s->params = p;
    }
}

static int read_double(double *v, const char *s, const char *opt, const cli_command *cmd)
{
    char *end;
    errno = 0;
    *v = strtod(s, &end);
    if (*s == '\0' || *end != '\0' || !isfinite(*v))
        return cli_usage(cmd, "%s wants a finite number, not '%s'", opt, s);
    return -1;
}

static int check_numbers(sweep_opts *s, const cli_command *cmd)
{
    int rc;
    if (s->t_s == NULL)
        return cli_usage(cmd, "missing --t: the final time");
    if ((rc = read_double(&s->t, s->t_s, "--t", cmd)) >= 0)
        return rc;
    if (!(s->t > 0))
        return cli_usage(cmd, "--t must be positive, not '%s'", s->t_s);
    s->tol = 1e-15;
    if (s->tol_s != NULL && (rc = read_double(&s->tol, s->tol_s, "--tol", cmd)) >= 0)
        return rc;
    s->threads = cli_cores();
    if (s->threads_s != NULL &&
        (rc = cli_read_long(&s->threads, s->threads_s, "--threads", 1, 1024, cmd)) >= 0)
        return rc;
    if (s->count_s != NULL &&
        (rc = cli_read_long(&s->count, s->count_s, "--count", 1, HL_SWEEP_MAX_MEMBERS, cmd)) >= 0)
        return rc;
    s->seed = 1;
    if (s->seed_s != NULL) {
        char *end;
        errno = 0;
        s->seed = strtoull(s->seed_s, &end, 10);
        if (*s->seed_s == '\0' || *end != '\0' || errno != 0 || s->seed_s[0] == '-')
            return cli_usage(cmd, "--seed wants a whole number >= 0, not '%s'", s->seed_s);
    }
    return -1;
}

/* --save-every, --event and --direction: the arrays go to files */
static int check_arrays(sweep_opts *s, const cli_command *cmd)
{
    int rc;
    if (s->save_every_s != NULL &&
        (rc = cli_read_long(&s->save_every, s->save_every_s, "--save-every", 1, 1000000000000L,
                            cmd)) >= 0)
        return rc;
    if (s->direction_s != NULL && s->event == NULL)
        return cli_usage(cmd, "--direction is for the crossings of --event G");
    s->direction = HL_EVENT_BOTH;
    if (s->direction_s != NULL && crossings_direction(&s->direction, s->direction_s) != 0)
        return cli_usage(cmd, "--direction wants up, down or both, not '%s'", s->direction_s);
    if ((s->save_every_s != NULL || s->event != NULL) && s->out == NULL)
        return cli_usage(cmd, "--save-every and --event write arrays to files: name one with "
                              "--out FILE.h5 or FILE.csv");
    return -1;
}

static int check_opts(void *arg, cli_opts *o, const cli_command *cmd)
{
    sweep_opts *s = arg;
    if (o->H == NULL)
        return cli_usage(cmd, "missing -H: the Hamiltonian of the members");
    if (o->nargs > 0)
        return cli_usage(cmd, "unexpected argument '%s'", o->args[0]);
    int sources = (s->grid != NULL) + (s->init_file != NULL) + (s->random != NULL);
    if (sources != 1)
        return cli_usage(cmd, "the points come from exactly one of --grid, --init-file and "
                              "--random");
    if (s->random != NULL && s->count_s == NULL)
        return cli_usage(cmd, "--random needs --count M: the number of points");
    if (s->random == NULL && (s->count_s != NULL || s->seed_s != NULL))
        return cli_usage(cmd, "--count and --seed are for --random");
    if (s->scheme == NULL)
        return cli_usage(cmd, "missing --scheme: one or more schemes (lie: the adaptive "
                              "Taylor integrator)");
    if (s->reference && s->no_reference)
        return cli_usage(cmd, "--reference or --no-reference, not both");
    if (s->resume && s->out == NULL)
        return cli_usage(cmd, "--resume continues the sweep of --out FILE: name it");
    if (s->formats != NULL && s->plot == NULL)
        return cli_usage(cmd, "--format is for the maps of --plot DIR");
    int rc = check_arrays(s, cmd);
    if (rc >= 0)
        return rc;
    hl_error err; /* without libhdf5, say so before computing (and journaling) */
    if (hl_h5_is_h5_path(s->out) && hl_h5_available(&err) != HL_OK)
        return cli_fail(&err);
    return check_numbers(s, cmd);
}

/* ---- running ---------------------------------------------------------------- */

typedef struct sink {
    hl_sweep_table *tab;
    hl_sweep_journal *journal;
    long failed; /* members that failed, named on stderr */
    const hl_sweep *sw;
    cli_progress *progress;
    long before, total; /* done before this run (resumed), all members */
} sink;

#define NAMED_FAILURES 10

static int on_result(const hl_sweep_result *r, void *arg)
{
    sink *k = arg;
    hl_sweep_table_store(r, k->tab);
    return k->journal != NULL ? hl_sweep_journal_append(r, k->journal) : 0;
}

static int on_progress(double done, double total, void *arg)
{
    sink *k = arg;
    (void)total;
    return cli_progress_fn((double)k->before + done, (double)k->total, k->progress);
}

/* The failures named on stderr (the first few, then a count). */
static long say_failures(const hl_sweep *sw, const hl_sweep_table *tab)
{
    long failed = 0;
    int col_point = 1;
    for (long m = 0; m < hl_sweep_count(sw); m++) {
        if (hl_sweep_table_status(tab, m) == HL_OK)
            continue;
        if (++failed <= NAMED_FAILURES) {
            const double *row = hl_sweep_table_row(tab, m);
            fprintf(stderr, "hamlie sweep: member %ld (point %.0f, %s, dt %g) failed: %s\n", m,
                    row[col_point], hl_sweep_scheme(sw, (int)row[3]), row[4],
                    hl_sweep_table_reason(tab, m));
        }
    }
    if (failed > NAMED_FAILURES)
        fprintf(stderr, "hamlie sweep: ... %ld members failed in all\n", failed);
    return failed;
}

/* The members not in the table yet (all of them for a fresh sweep). */
static long *missing(const hl_sweep *sw, const hl_sweep_table *tab, long *n)
{
    long count = hl_sweep_count(sw);
    long *m = hl_xmalloc((size_t)(count > 0 ? count : 1) * sizeof *m);
    *n = 0;
    for (long i = 0; i < count; i++)
        if (!hl_sweep_table_has(tab, i))
            m[(*n)++] = i;
    return m;
}

static int file_exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* Can out be written?  Checked before any member runs: a sweep of hours
 * must not end in "cannot write". */
static int check_out(const char *out, int resume)
{
    size_t n = strlen(out) + 16;
    char *j = hl_xmalloc(n);
    snprintf(j, n, "%s.journal", out);
    int rc = -1;
    if (!resume && file_exists(j)) {
        fprintf(stderr,
                "hamlie: error: '%s' holds an interrupted sweep's results: --resume continues "
                "it (or remove it to start afresh)\n",
                j);
        rc = CLI_ERROR;
    }
    free(j);
    return rc;
}

static int run_all(hl_sweep *sw, sink *k, const sweep_opts *s, const cli_opts *o)
{
    long n;
    long *members = missing(sw, k->tab, &n);
    cli_progress p;
    cli_progress_begin(&p, "sweep", "member", o->progress);
    k->progress = &p;
    k->before = hl_sweep_count(sw) - n;
    k->total = hl_sweep_count(sw);
    if (o->progress == CLI_PROGRESS_ON || k->before > 0)
        cli_progress_say(&p, "%ld members on %ld threads%s", n, s->threads,
                         k->before > 0 ? " (the others done before)" : "");
    hl_error err;
    hl_error_clear(&err);
    int st = hl_sweep_run(sw, members, n, (int)s->threads, on_result, k, on_progress, k, &err);
    cli_progress_end(&p);
    free(members);
    if (st == HL_ESTOP && k->journal != NULL && hl_sweep_journal_failed(k->journal)) {
        fprintf(stderr, "hamlie: error: writing the journal of '%s' failed\n", s->out);
        return CLI_ERROR;
    }
    if (st == HL_ESTOP) {
        fprintf(stderr, "hamlie sweep: interrupted after %ld of %ld members",
                hl_sweep_table_done(k->tab), hl_sweep_count(sw));
        if (s->out != NULL)
            fprintf(stderr,
                    "; '%s.journal' keeps them: the same command with --resume "
                    "continues\n",
                    s->out);
        else
            fputs(" (nothing written: --out FILE keeps a journal to resume)\n", stderr);
        return CLI_INTERRUPTED;
    }
    return st == HL_OK ? -1 : cli_fail(&err);
}

int sweep_plot(const hl_sweep *sw, const hl_sweep_table *tab, const char *dir, const char *formats);
int sweep_plot_check(const hl_sweep *sw);

static int sweep_body(hl_sweep *sw, const sweep_opts *s, const cli_opts *o)
{
    if (s->plot != NULL) { /* before hours of work: can the maps be drawn at all? */
        hl_error err;
        hl_error_clear(&err);
        if (hl_figure_drawable(&err) != HL_OK)
            return cli_fail(&err);
        int rc = sweep_plot_check(sw);
        if (rc >= 0)
            return rc;
    }
    int rc = s->out != NULL ? check_out(s->out, s->resume) : -1;
    if (rc >= 0)
        return rc;
    sink k;
    memset(&k, 0, sizeof k);
    k.sw = sw;
    k.tab = hl_sweep_table_new(sw);
    hl_error err;
    hl_error_clear(&err);
    if (k.tab == NULL)
        return hl_error_set(&err, HL_ENOMEM, NULL, -1, 0, "no memory for the table"),
               cli_fail(&err);
    if (s->out != NULL &&
        hl_sweep_journal_open(&k.journal, sw, s->out, s->resume, k.tab, &err) != HL_OK)
        rc = cli_fail(&err);
    if (rc < 0) /* under mpirun, rank 0 hands the members out instead */
        rc = cli_sweep_mpi_active()
                 ? cli_sweep_mpi_serve(sw, k.tab, k.journal, s->out, o->progress)
                 : run_all(sw, &k, s, o);
    if (rc < 0 && hl_sweep_write(sw, k.tab, s->out != NULL ? s->out : "-", &err) != HL_OK)
        rc = cli_fail(&err);
    if (rc < 0 && s->plot != NULL)
        rc = sweep_plot(sw, k.tab, s->plot, s->formats != NULL ? s->formats : "png");
    hl_sweep_journal_close(k.journal, rc < 0); /* kept unless the file is whole */
    if (rc < 0)
        rc = say_failures(sw, k.tab) > 0 ? CLI_FAILS : CLI_OK;
    hl_sweep_table_free(k.tab);
    return rc;
}

int cmd_sweep(int argc, char **argv, const cli_command *cmd)
{
    sweep_opts s;
    cli_opts o;
    memset(&s, 0, sizeof s);
    memset(&o, 0, sizeof o);
    /* in found_opt's order: values, flags, --param, then the arrays' options */
    static const cli_own own[] = {
        {"--grid", 0},       {"--init-file", 0}, {"--random", 0},       {"--count", 0},
        {"--seed", 0},       {"--scheme", 0},    {"--dt", 0},           {"--t", 0},
        {"--tol", 0},        {"--threads", 0},   {"--out", 0},          {"--plot", 0},
        {"--format", 0},     {"--reference", 1}, {"--no-reference", 1}, {"--order", 1},
        {"--chaos", 1},      {"--resume", 1},    {"--mpi", 1},          {"--param", CLI_OWN_REPEAT},
        {"--save-every", 0}, {"--event", 0},     {"--direction", 0}};
    static const cli_begin_spec spec = {own,        (int)(sizeof own / sizeof own[0]), found_opt,
                                        check_opts, CLI_OPT_H | CLI_OPT_PROGRESS,      64};
    char **av;
    hl_system *sys = NULL;
    int quiet = cli_mpi_quiet_begin(); /* under mpirun: errors said by rank 0 alone */
    int rc = cli_begin(&av, &o, &sys, argc, argv, cmd, &spec, &s);
    char *csv = NULL;
    if (rc < 0 && s.init_file != NULL && (csv = cli_read_file(s.init_file)) == NULL)
        rc = CLI_ERROR;
    hl_sweep *sw = NULL;
    hl_sweep_spec sp = {.H = o.H,
                        .pairs = o.pairs,
                        .params = s.params,
                        .grid = s.grid,
                        .points_csv = csv,
                        .points_csv_name = s.init_file,
                        .random = s.random,
                        .nrandom = s.count,
                        .seed = s.seed,
                        .schemes = s.scheme,
                        .dts = s.dt_s,
                        .t = s.t,
                        .tol = s.tol,
                        .reference = s.reference,
                        .order = s.order,
                        .chaos = s.chaos,
                        .save_every = s.save_every,
                        .event = s.event,
                        .direction = (int)s.direction};
    hl_error err;
    hl_error_clear(&err);
    if (rc < 0 && hl_sweep_new(&sw, &sp, &err) != HL_OK) {
        if (csv != NULL && err.src == csv)
            rc = cli_fail_in_file(&err, s.init_file, csv);
        else /* the message names the field: "grid: ...", "schemes: ..." */
            rc = cli_fail(&err);
    }
    cli_mpi_quiet_end(quiet);
    if (rc < 0) /* under mpirun: the ranks but 0 compute in there */
        rc = cli_sweep_mpi_begin(sw, s.mpi, &s.threads, s.threads_s != NULL);
    if (rc < 0)
        rc = cli_sweep_mpi_end(sweep_body(sw, &s, &o));
    hl_sweep_free(sw);
    free(csv);
    free(s.params);
    hl_system_free(sys);
    cli_opts_clear(&o);
    free(av);
    return rc;
}
