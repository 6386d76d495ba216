/* hamlie run: a trajectory of a scheme (CSV), its summary, observed orders.
 *
 * The options proper to run are taken out of argv here, before the common
 * parser (cli_parse) sees the rest: opts.c's table has no room for them.
 * The CSV is streamed (a run can have millions of rows) in whole lines
 * (run_csv.c); the summary and the orders table are buffered and printed at
 * the end. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "cli/run.h"
#include "hamlie/exact.h"
#include "hamlie/flow.h"
#include "hamlie/run.h"
#include "hamlie/runplot.h"

const char cmd_run_help[] =
    "usage: hamlie run -H FORMULA (--scheme NAME | --map MAP | --equations EQS)\n"
    "                  --dt STEP --t TIME --init x=1,p=0 [options]\n"
    "\n"
    "Run a one-step scheme with a fixed step from an initial point and write the\n"
    "trajectory as CSV: t, the coordinates and momenta, H, sigma, the observers.\n"
    "sigma = |z_n - z(t_n)|^2 is the squared distance to the exact flow, computed\n"
    "by hamlie's Taylor integrator (tolerance 1e-15) at every t_n = n dt.\n"
    "\n"
    "  -H, --hamiltonian F  the Hamiltonian (required)\n"
    "  --scheme NAME        a scheme of the catalog (hamlie schemes lists them)\n"
    "  --map 'X = ...; P = ...'   the user's explicit map (D is the step)\n"
    "  --equations '...'    the user's implicit scheme, e.g. '(X-x)/D = ...; ...'\n"
    "  -n, --order N        the order of --scheme lie with --dt (1..200, default 4):\n"
    "                       the same as --scheme lieN\n"
    "  --dt STEP            the step (> 0, required for a fixed-step scheme); t/dt\n"
    "                       must be a whole number\n"
    "  --t TIME             the final time (>= 0)\n"
    "  --init x=1,p=0       the initial point (values may be formulas: q=pi/2)\n"
    "  --every K            write every K-th row (and the last; default 1)\n"
    "  --observe F          a column more: any formula in the variables and H\n"
    "                       (repeatable)\n"
    "  --tol TOL            the tolerance of the Taylor integrator (reference, or\n"
    "                       the adaptive run; default 1e-15, at least 5.6e-17)\n"
    "  --no-reference       no reference trajectory: no sigma column (faster)\n"
    "  --orders D1,D2,...   run with each step to --t and print the observed global\n"
    "                       order log(e1/e2)/log(D1/D2) of consecutive steps; e is\n"
    "                       the max over steps of |z_n - z(t_n)| (and at t)\n"
    "  --out FILE           write the CSV to FILE (FILE.tmp, renamed at the end)\n"
    "  --plot DIR           also draw the run's figures into DIR: phase portraits,\n"
    "                       coordinates, |H - H0| and sigma (log), each observer\n"
    "                       (as hamlie plot does from the CSV; rows as --every)\n"
    "  --format png,svg,pdf the figures' formats (default png)\n"
    "  --event G            record the crossings of the surface G = 0 (a formula in\n"
    "                       the variables and H, or 'lhs = rhs'): crossing, t, the\n"
    "                       state, H, in a CSV of their own (docs/commands.md)\n"
    "  --direction D        up (G from < 0 to >= 0), down, or both (default)\n"
    "  --event-stop N       stop the run at the N-th crossing\n"
    "  --events-out FILE    the crossings' CSV (default with --out F: F.events.csv;\n"
    "                       with --json alone they are in the JSON).  The adaptive\n"
    "                       run locates them on its step polynomials to round-off, a\n"
    "                       fixed-step run on each step's cubic Hermite interpolant\n"
    "                       (local order 4)\n"
    "  --pairs, --param     as for every command\n"
    "  --json               print a JSON summary (with --out the CSV goes to FILE,\n"
    "                       without it no CSV is written)\n"
    "  -h, --help           show this help\n"
    "\n"
    "--scheme lie with --tol (and no --dt, or --dt as the output spacing) is the\n"
    "adaptive Taylor (Lie series) integrator; --scheme lie with --dt alone is the\n"
    "fixed-step Lie series truncated after D^n, the same as --scheme lieN with\n"
    "N = n (lie1 .. lie20, always fixed-step).  Without --dt the adaptive run\n"
    "writes 1001 rows.\n"
    "  --digits D           the adaptive integrator in Arb at about D digits (values\n"
    "                       printed with D digits; the initial values are read at\n"
    "                       that precision: py=sqrt(3) is sqrt(3) to D digits)\n"
    "\n"
    "  --progress           show progress on stderr from the start (else after a\n"
    "                       second or two); --quiet: none\n"
    "\n"
    "A run stops at a blow-up (a value not finite) or a Newton failure, with the\n"
    "step and the time; the rows written before stay valid CSV (with --out they\n"
    "are kept in FILE.partial).  Ctrl-C (SIGINT) stops it the same way, after a\n"
    "whole step: the CSV complete to its last row, the --json summary written with\n"
    "\"interrupted\": true.\n"
    "Exit status: 0 the run completed; 2 usage or input error, or the run failed;\n"
    "130 interrupted.\n"
    "Example: hamlie run -H '(p^2+x^2)/2' --scheme euler --dt 0.1 --t 20 --init x=1,p=0\n";

static void found_opt(void *arg, int k, const char *value)
{
    run_opts *r = arg;
    const char **slot[] = {&r->scheme, &r->equations, &r->init, &r->out, &r->orders,
                           &r->dt_s, &r->t_s, &r->tol_s, &r->every_s, &r->digits_s};
    if (k < 10)
        *slot[k] = value;
    else if (k == 10) {
        r->observe = hl_xrealloc(r->observe, (size_t)(r->nobserve + 1) * sizeof *r->observe);
        r->observe[r->nobserve++] = value;
    } else if (k == 11)
        r->no_ref = 1;
    else if (k < 14)
        *(k == 12 ? &r->plot : &r->formats) = value;
    else
        run_events_found(r, k - 14, value);
}

static int parse_double(double *v, const char *s, const char *opt, const cli_command *cmd)
{
    char *end;
    errno = 0;
    *v = strtod(s, &end);
    if (*s == '\0' || *end != '\0')
        return cli_usage(cmd, "%s wants a number, not '%s'", opt, s);
    return -1;
}

static int adaptive(const run_opts *r);

/* The usage checks of run's options, after parsing (cli_begin). */
static int check_opts(void *arg, cli_opts *o, const cli_command *cmd)
{
    run_opts *r = arg;
    int rc = cli_check_scheme_source(o, r->scheme, r->equations, "a run needs a Hamiltonian", cmd);
    if (rc >= 0)
        return rc;
    if (r->digits_s != NULL) {
        if ((rc = parse_double(&r->digits, r->digits_s, "--digits", cmd)) >= 0)
            return rc;
        if (!(r->digits >= 1 && r->digits <= 10000))
            return cli_usage(cmd, "--digits wants a number of digits from 1 to 10000");
        if (r->scheme == NULL || strcmp(r->scheme, "lie") != 0 || r->orders != NULL)
            return cli_usage(cmd, "--digits is for the adaptive integrator: --scheme lie");
    }
    if (r->formats != NULL && r->plot == NULL)
        return cli_usage(cmd, "--format is for the figures of --plot DIR");
    if (r->plot != NULL && (r->orders != NULL || r->digits_s != NULL))
        return cli_usage(cmd, "--plot draws one run in double: not with --orders or --digits");
    if (r->init == NULL)
        return cli_usage(cmd, "missing --init: the initial point, e.g. --init x=1,p=0");
    if (r->t_s == NULL)
        return cli_usage(cmd, "missing --t: the final time");
    if ((rc = parse_double(&r->t, r->t_s, "--t", cmd)) >= 0)
        return rc;
    r->have_dt = r->dt_s != NULL;
    if (r->have_dt && (rc = parse_double(&r->dt, r->dt_s, "--dt", cmd)) >= 0)
        return rc;
    if (!r->have_dt && r->orders == NULL && !adaptive(r))
        return cli_usage(cmd, "missing --dt: a fixed-step scheme needs its step (or --orders "
                              "D1,D2,... for several)");
    if (o->have_order && (r->scheme == NULL || strcmp(r->scheme, "lie") != 0 || adaptive(r)))
        return cli_usage(cmd, "--order is the order of the truncated Lie series: for "
                              "--scheme lie with --dt (and without --tol); a member of the "
                              "family lieN names its own (--scheme lie6)");
    if (o->have_order && (o->order < 1 || o->order > HL_LIE_MAX_ORDER))
        return cli_usage(cmd, "--order must be from 1 to %d, not %d", HL_LIE_MAX_ORDER,
                         o->order);
    r->tol = 1e-15;
    if (r->tol_s != NULL && (rc = parse_double(&r->tol, r->tol_s, "--tol", cmd)) >= 0)
        return rc;
    if (!(r->tol > 0) || !isfinite(r->tol))
        return cli_usage(cmd, "--tol must be positive, not '%s'", r->tol_s);
    if (r->tol < HL_FLOW_MIN_RTOL && r->digits_s == NULL)
        return cli_usage(cmd, "--tol %s is below double precision (%.2g): for more digits use "
                              "--scheme lie --digits %.0f",
                         r->tol_s, HL_FLOW_MIN_RTOL, ceil(-log10(r->tol)));
    r->every = 1;
    if (r->every_s != NULL) {
        char *end;
        r->every = strtol(r->every_s, &end, 10);
        if (*r->every_s == '\0' || *end != '\0' || r->every < 1)
            return cli_usage(cmd, "--every wants a whole number >= 1, not '%s'", r->every_s);
    }
    return run_events_check(r, o, cmd);
}

/* Is this the adaptive integrator (--scheme lie with --tol, or without --dt)? */
static int adaptive(const run_opts *r)
{
    return r->scheme != NULL && strcmp(r->scheme, "lie") == 0 &&
           (r->tol_s != NULL || r->digits_s != NULL || !r->have_dt) && r->orders == NULL;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- JSON ------------------------------------------------------------------ */

static void json_head(hl_json *j, hl_buf *out, hl_system *sys, const run_opts *r,
                      const cli_opts *o, int interrupted)
{
    hl_json_init_buf(j, out);
    hl_json_object_begin(j);
    hl_json_kv_string(j, "command", "run");
    cli_json_system(j, sys);
    hl_json_kv_string(j, "H_input", o->H);
    hl_json_kv_string(j, "scheme",
                      r->scheme != NULL ? r->scheme : o->map != NULL ? "map" : "equations");
    hl_json_kv_string(j, "integrator", adaptive(r) ? "adaptive-taylor" : "fixed-step");
    hl_json_kv_double(j, "t", r->t);
    hl_json_kv_bool(j, "interrupted", interrupted);
}

/* name -> value of each phase variable, q then p (values: doubles, or the
 * strings of an Arb run) */
static void json_state(hl_json *j, const char *key, hl_system *sys, const double *z,
                       char *const *zs)
{
    int N = hl_system_ndof(sys);
    hl_json_key(j, key);
    hl_json_object_begin(j);
    for (int i = 0; i < 2 * N; i++) {
        const char *name = cli_phase_name(sys, i);
        if (zs != NULL)
            hl_json_kv_string(j, name, zs[i] != NULL ? zs[i] : "");
        else
            hl_json_kv_double(j, name, z[i]);
    }
    hl_json_object_end(j);
}

static void json_end(hl_json *j)
{
    hl_json_object_end(j);
    hl_json_finish(j);
}

/* ---- the two modes ------------------------------------------------------ */

/* The rows --every would give for the steps done (run.h: row k is
 * delivered when k % every == 0 or k == n). */
static long rows_for(long steps, long every, long n)
{
    return steps / every + 1 + (steps == n && n % every != 0);
}

/* Runs from this many steps say what they will do before they start
 * (without --progress): they take a while at any rate. */
#define PLAN_STEPS 100000000L

/* The progress of a run on stderr (cli_progress), said first when the run
 * is long or --progress asks. */
static void start_progress(cli_progress *p, hl_run *run, const run_opts *r, const cli_opts *o,
                           long n, double dt)
{
    int ad = adaptive(r);
    cli_progress_begin(p, "run", ad ? "row" : "step", o->progress);
    hl_run_set_progress(run, cli_progress_fn, p);
    if (o->progress != CLI_PROGRESS_ON && n < PLAN_STEPS)
        return;
    const char *name = r->scheme != NULL ? r->scheme : o->map != NULL ? "the --map scheme"
                                                                     : "the --equations scheme";
    if (r->digits_s != NULL)
        cli_progress_say(p, "%ld rows of the Taylor integrator in Arb at %g digits to t = %s",
                         n + 1, r->digits, r->t_s);
    else if (ad)
        cli_progress_say(p, "%ld rows of the adaptive Taylor integrator (tol %g) to t = %g",
                         n + 1, r->tol, r->t);
    else
        cli_progress_say(p, "%ld steps (%.3g) of %s at dt = %g to t = %g%s", n, (double)n, name,
                         dt, r->t, r->no_ref ? "" : ", each against the reference");
}

/* The one line printed after a run written to --out. */
static void put_summary(hl_buf *out, const hl_run_stats *s, const csv *c, const char *file)
{
    hl_buf_printf(out, "%ld steps to t = %.17g, max |H - H0| = %.3g", s->steps, s->t, s->max_dH);
    if (c->sigma)
        hl_buf_printf(out, ", final sigma = %.3g", s->sigma);
    hl_buf_printf(out, "; wrote %ld rows to %s\n", c->rows, file);
}

/* The Taylor integrator's tolerance is absolute below |z| = 1, as heyoka's
 * (docs/tolerance.md): a state far below 1 is integrated to --tol, not to
 * --tol of its size: the oscillator from p = -1e-100 ended 1.4e-17 from the
 * exact state at t = 1000, 1.4e83 times its amplitude, at the default tol
 * and with exit 0.  Said where it applies: the adaptive run, and the
 * reference of sigma. */
static void note_absolute_tol(const run_opts *r, int ad, const double *z0, int n)
{
    double n0 = 0;
    for (int i = 0; i < n; i++)
        n0 = fmax(n0, fabs(z0[i]));
    if ((!ad && r->no_ref) || !(n0 > 0 && n0 < 1e-3))
        return;
    fprintf(stderr,
            "hamlie run: note: |z| = %.3g at t = 0, and below 1 --tol %g is an absolute "
            "tolerance (as heyoka's), %.3g times the state's size: %s may have few correct digits "
            "relative to it; rescale the variables, or lower --tol\n",
            n0, r->tol, r->tol / n0, ad ? "the run" : "the reference (sigma)");
}

static int do_run(hl_run *run, hl_system *sys, const run_opts *r, const cli_opts *o,
                  const double *z0)
{
    csv c;
    memset(&c, 0, sizeof c);
    hl_buf_init(&c.buf);
    c.n2 = 2 * hl_system_ndof(sys);
    c.nobs = r->nobserve;
    int ad = adaptive(r);
    c.sigma = !ad && !r->no_ref;
    char *tmpname = NULL;
    int rc = CLI_OK;
    double dt = r->have_dt ? r->dt : r->t > 0 ? r->t / 1000 : 1;
    long n = 0;
    hl_error err;
    hl_error_clear(&err);
    if (hl_run_nsteps(&n, dt, r->t, &err) != HL_OK) { /* before any output */
        hl_buf_clear(&c.buf);
        return cli_fail(&err);
    }
    note_absolute_tol(r, ad, z0, c.n2);
    int want_csv = r->out != NULL || o->format != CLI_JSON;
    if (want_csv && (rc = run_open_out(&c, r, &tmpname)) != CLI_OK) {
        free(tmpname);
        hl_buf_clear(&c.buf);
        return rc;
    }
    if (!want_csv)
        c.fp = NULL;
    else
        run_csv_header(&c, sys, r);
    if (r->plot != NULL)
        run_plot_open(&c, sys, r, o);
    hl_run_set_reference(run, !r->no_ref, r->tol);
    hl_run_set_jit(run, 1);
    cli_progress p;
    start_progress(&p, run, r, o, n, dt);
    double w0 = now();
    hl_run_stats s;
    memset(&s, 0, sizeof s);
    /* nothing consumes the rows of --json alone: the runner need not make them */
    int consumed = want_csv || r->plot != NULL || ad;
    int st =
        ad ? hl_run_adaptive(run, z0, r->tol, dt, r->t, r->every, run_csv_row, &c, &s, &err)
           : hl_run_fixed(run, z0, dt, r->t, r->every, consumed ? run_csv_row : NULL, &c, &s, &err);
    if (!consumed)
        s.rows = rows_for(s.steps, r->every, n);
    double wall = now() - w0;
    cli_progress_end(&p);
    int stopped = st == HL_ESTOP, figures = 0;
    if (st == HL_EIO && c.io_error) {
        run_close_out(&c, r, tmpname, 0, &s);
        if (tmpname == NULL)
            fprintf(stderr, "hamlie: error: writing to standard output failed\n");
        rc = CLI_ERROR;
    } else if (st != HL_OK && !stopped) {
        run_csv_flush(&c);
        cli_fail(&err);
        if (s.nsteps > 0 && (s.failed || s.steps > 0))
            fprintf(stderr, "hamlie: the run stopped after step %ld of %ld (t = %.17g)\n",
                    s.steps, s.nsteps, s.t);
        if (want_csv)
            run_close_out(&c, r, tmpname, 0, &s);
        rc = CLI_ERROR;
    } else if (stopped) {
        fprintf(stderr, "hamlie run: interrupted after step %ld of %ld (t = %.17g)\n", s.steps,
                s.nsteps, s.t);
        rc = want_csv ? run_close_out(&c, r, tmpname, 0, &s) : CLI_OK;
    } else {
        /* the figures first: if they cannot be drawn, no CSV file is left */
        figures = c.plot != NULL ? run_plot_write(&c, r) : 0;
        if (figures < 0) {
            if (tmpname != NULL) {
                fclose(c.fp);
                remove(tmpname);
            }
            rc = CLI_ERROR;
        } else
            rc = want_csv ? run_close_out(&c, r, tmpname, 1, &s) : CLI_OK;
        if (rc == CLI_OK)
            rc = run_events_write(r, sys);
        if (rc == CLI_OK && r->out == NULL && o->format != CLI_JSON) { /* stdout has the CSV */
            hl_buf said;
            hl_buf_init(&said);
            run_events_say(&said, r, &s, run);
            fputs(said.s != NULL ? said.s : "", stderr);
            hl_buf_clear(&said);
        }
        if (rc == CLI_OK && c.plot != NULL && o->format != CLI_JSON)
            fprintf(stderr, "hamlie: drew %d figure files in %s\n", figures, r->plot);
    }
    if (rc == CLI_OK && (o->format == CLI_JSON || (r->out != NULL && !stopped))) {
        hl_buf out;
        hl_buf_init(&out);
        if (o->format == CLI_JSON) {
            hl_json j;
            json_head(&j, &out, sys, r, o, stopped);
            hl_json_kv_double(&j, "dt", dt);
            hl_json_kv_int(&j, "steps", s.steps);
            hl_json_kv_int(&j, "rows", s.rows);
            hl_json_kv_double(&j, "final_t", s.t);
            json_state(&j, "final_state", sys, hl_run_state(run), NULL);
            hl_json_kv_double(&j, "H0", s.H0);
            hl_json_kv_double(&j, "H_final", s.H);
            hl_json_kv_double(&j, "max_abs_dH", s.max_dH);
            hl_json_kv_double(&j, "sigma_final", s.sigma);
            hl_json_kv_double(&j, "max_error", s.max_err);
            hl_json_kv_double(&j, "tol", r->tol);
            hl_json_kv_int(&j, "taylor_steps", s.ref_steps);
            hl_json_kv_string(&j, "out", r->out);
            hl_json_kv_string(&j, "plot", r->plot);
            hl_json_kv_int(&j, "figure_files", figures);
            hl_json_kv_double(&j, "wall_time_s", wall);
            run_events_json(&j, r, sys, run, &s);
            json_end(&j);
        } else {
            put_summary(&out, &s, &c, r->out);
            run_events_say(&out, r, &s, run);
        }
        rc = cli_emit(&out, CLI_OK);
    }
    if (rc == CLI_OK && stopped)
        rc = CLI_INTERRUPTED;
    free(tmpname);
    run_plot_close(&c);
    hl_buf_clear(&c.buf);
    return rc;
}

/* A comma-separated list of steps. */
static int read_steps(double **dts, int *n, const char *s, const cli_command *cmd)
{
    *n = 0;
    *dts = NULL;
    const char *p = s;
    while (*p) {
        char *end;
        double v = strtod(p, &end);
        if (end == p || (*end != ',' && *end != '\0'))
            return cli_usage(cmd, "--orders wants steps separated by ',', not '%s'", s);
        *dts = hl_xrealloc(*dts, (size_t)(*n + 1) * sizeof **dts);
        (*dts)[(*n)++] = v;
        p = *end == ',' ? end + 1 : end;
    }
    if (*n < 2)
        return cli_usage(cmd, "--orders wants at least two steps");
    return -1;
}

static int do_orders(hl_run *run, hl_system *sys, const run_opts *r, const cli_opts *o,
                     const double *z0, const cli_command *cmd)
{
    double *dts;
    int n, rc = read_steps(&dts, &n, r->orders, cmd);
    if (rc >= 0) {
        free(dts);
        return rc;
    }
    double *e = hl_xmalloc((size_t)n * sizeof *e), *ef = hl_xmalloc((size_t)n * sizeof *ef);
    double *ord = hl_xmalloc((size_t)n * sizeof *ord);
    hl_error err;
    hl_error_clear(&err);
    hl_run_set_reference(run, 1, r->tol);
    for (int i = 0; i < n; i++)
        e[i] = NAN;
    cli_progress p;
    cli_progress_begin(&p, "run", "step", o->progress);
    hl_run_set_progress(run, cli_progress_fn, &p);
    int st = hl_run_orders(e, ef, ord, run, z0, dts, n, r->t, &err);
    cli_progress_end(&p);
    int stopped = st == HL_ESTOP, all = n;
    if (stopped) { /* the steps done before the interrupt */
        for (n = 0; n < all && !isnan(e[n]);)
            n++;
        fprintf(stderr, "hamlie run: interrupted (%s); the orders of the %d steps done follow\n",
                err.msg, n);
    }
    if (st != HL_OK && !stopped)
        rc = cli_fail(&err);
    else {
        hl_buf out;
        hl_buf_init(&out);
        if (o->format == CLI_JSON) {
            hl_json j;
            json_head(&j, &out, sys, r, o, stopped);
            hl_json_kv_string(&j, "error_measure", "max over steps of |z_n - z(t_n)|_2");
            hl_json_key(&j, "orders");
            hl_json_array_begin(&j);
            for (int i = 0; i < n; i++) {
                hl_json_object_begin(&j);
                hl_json_kv_double(&j, "dt", dts[i]);
                hl_json_kv_double(&j, "max_error", e[i]);
                hl_json_kv_double(&j, "final_error", ef[i]);
                hl_json_kv_double(&j, "order", ord[i]);
                hl_json_kv_double(&j, "order_final",
                                  i ? log(ef[i - 1] / ef[i]) / log(dts[i - 1] / dts[i]) : NAN);
                hl_json_object_end(&j);
            }
            hl_json_array_end(&j);
            json_end(&j);
        } else {
            hl_buf_printf(&out, "observed global order to t = %g (error: max over steps of "
                                "|z_n - z(t_n)|; final: at t)\n", r->t);
            hl_buf_printf(&out, "%-12s %-12s %-7s %-12s %s\n", "dt", "max error", "order",
                          "final error", "order");
            for (int i = 0; i < n; i++) {
                hl_buf_printf(&out, "%-12g %-12.4e ", dts[i], e[i]);
                if (i == 0)
                    hl_buf_printf(&out, "%-7s %-12.4e %s\n", "-", ef[i], "-");
                else
                    hl_buf_printf(&out, "%-7.3f %-12.4e %.3f\n", ord[i], ef[i],
                                  log(ef[i - 1] / ef[i]) / log(dts[i - 1] / dts[i]));
            }
        }
        rc = cli_emit(&out, stopped ? CLI_INTERRUPTED : CLI_OK);
    }
    free(dts), free(e), free(ef), free(ord);
    return rc;
}

/* An error in --init, shown with the --init text (under the value at
 * fault when the error has a position). */
static int init_fail(hl_error *err, const char *init)
{
    if (err->src == NULL) {
        err->src = init;
        err->pos = -1;
    }
    hl_error_prefix(err, "in --init");
    return cli_fail(err);
}

/* ---- --digits: the adaptive run in Arb ------------------------------------- */

typedef struct csv_arb {
    csv c;
    long ndig;
} csv_arb;

static int csv_row_arb(const hl_run_row_arb *row, void *arg)
{
    csv_arb *ca = arg;
    csv *c = &ca->c;
    if (c->fp == NULL)
        return 0;
    hl_buf *b = &c->buf;
    cli_put_arb(b, row->t, ca->ndig);
    for (int i = 0; i < c->n2; i++) {
        hl_buf_putc(b, ',');
        cli_put_arb(b, row->z + i, ca->ndig);
    }
    hl_buf_putc(b, ',');
    cli_put_arb(b, row->H, ca->ndig);
    for (int i = 0; i < c->nobs; i++) {
        hl_buf_putc(b, ',');
        cli_put_arb(b, row->obs + i, ca->ndig);
    }
    hl_buf_putc(b, '\n');
    c->rows++;
    if (b->len >= 1 << 16)
        run_csv_flush(c);
    return c->io_error ? HL_EIO : 0;
}

/* The last row's state as strings (kept by a wrapper around csv_row_arb). */
typedef struct last_arb {
    csv_arb ca;
    int n2;
    char **z;
} last_arb;

static int row_arb_keep(const hl_run_row_arb *row, void *arg)
{
    last_arb *l = arg;
    for (int i = 0; i < l->n2; i++) {
        flint_free(l->z[i]);
        l->z[i] = arb_get_str(row->z + i, l->ca.ndig, ARB_STR_NO_RADIUS);
    }
    return csv_row_arb(row, &l->ca);
}

static int do_run_arb(hl_run *run, hl_system *sys, const run_opts *r, const cli_opts *o)
{
    last_arb l;
    memset(&l, 0, sizeof l);
    csv *c = &l.ca.c;
    hl_buf_init(&c->buf);
    l.n2 = c->n2 = 2 * hl_system_ndof(sys);
    l.z = hl_xcalloc((size_t)l.n2, sizeof *l.z);
    l.ca.ndig = (long)ceil(r->digits);
    c->nobs = r->nobserve;
    hl_error err;
    hl_error_clear(&err);
    double dt = r->have_dt ? r->dt : r->t > 0 ? r->t / 1000 : 1;
    long n = 0;
    int rc = CLI_OK;
    slong prec = hl_run_arb_prec(r->digits);
    arb_ptr z0 = _arb_vec_init(l.n2);
    char *tmpname = NULL;
    int want_csv = r->out != NULL || o->format != CLI_JSON;
    if (hl_run_nsteps(&n, dt, r->t, &err) != HL_OK) {
        rc = cli_fail(&err);
        goto done;
    }
    if (hl_run_init_values_arb(z0, sys, r->init, prec, &err) != HL_OK ||
        hl_run_check_start_arb(run, z0, prec, &err) != HL_OK) {
        rc = init_fail(&err, r->init);
        goto done;
    }
    if (want_csv && (rc = run_open_out(c, r, &tmpname)) != CLI_OK)
        goto done;
    if (want_csv)
        run_csv_header(c, sys, r);
    cli_progress p;
    start_progress(&p, run, r, o, n, dt);
    double w0 = now();
    hl_run_stats s;
    memset(&s, 0, sizeof s);
    int st = hl_run_adaptive_arb(run, z0, r->digits, r->t_s, n, r->every, row_arb_keep, &l, &s,
                                 &err);
    double wall = now() - w0;
    cli_progress_end(&p);
    int stopped = st == HL_ESTOP;
    if (st != HL_OK && !stopped) {
        run_csv_flush(c);
        if (!(st == HL_EIO && c->io_error))
            cli_fail(&err);
        if (want_csv)
            run_close_out(c, r, tmpname, 0, &s);
        rc = CLI_ERROR;
        goto done;
    }
    if (stopped)
        fprintf(stderr, "hamlie run: interrupted after row %ld of %ld (t = %.17g)\n", s.steps,
                n, s.t);
    rc = want_csv ? run_close_out(c, r, tmpname, !stopped, &s) : CLI_OK;
    if (rc == CLI_OK && o->format != CLI_JSON && r->out != NULL && !stopped) {
        hl_buf out;
        hl_buf_init(&out);
        put_summary(&out, &s, c, r->out);
        rc = cli_emit(&out, CLI_OK);
    }
    if (rc == CLI_OK && o->format == CLI_JSON) {
        hl_buf out;
        hl_buf_init(&out);
        hl_json j;
        json_head(&j, &out, sys, r, o, stopped);
        hl_json_kv_double(&j, "digits", r->digits);
        hl_json_kv_int(&j, "outputs", s.steps);
        hl_json_kv_int(&j, "rows", s.rows);
        char ts[40]; /* interrupted: the time of the last row, not --t */
        hl_run_fmt_short(ts, s.t);
        hl_json_kv_string(&j, "final_t", stopped ? ts : r->t_s);
        json_state(&j, "final_state", sys, NULL, l.z);
        hl_json_kv_double(&j, "H0", s.H0);
        hl_json_kv_double(&j, "max_abs_dH", s.max_dH);
        hl_json_kv_int(&j, "taylor_steps", s.ref_steps);
        hl_json_kv_string(&j, "out", r->out);
        hl_json_kv_double(&j, "wall_time_s", wall);
        json_end(&j);
        rc = cli_emit(&out, CLI_OK);
    }
    if (rc == CLI_OK && stopped)
        rc = CLI_INTERRUPTED;
done:
    for (int i = 0; i < l.n2; i++)
        flint_free(l.z[i]);
    free(l.z);
    free(tmpname);
    _arb_vec_clear(z0, l.n2);
    hl_buf_clear(&c->buf);
    return rc;
}

/* --scheme exact beyond the closed form of a quadratic H: the exact flow
 * of exact.h (action-angle by quadrature for one dof) as the run's stepper. */
static int build_exact(hl_run **run, hl_exact_flow **ex, hl_system *sys, hl_error *err)
{
    int st = hl_exact_flow_new(ex, sys, err);
    if (st == HL_OK)
        st = hl_run_new_stepper(run, sys, hl_exact_flow_step, *ex, err);
    return st;
}

static int build(hl_run **run, hl_scheme **sch, hl_exact_flow **ex, hl_system *sys,
                 const run_opts *r, const cli_opts *o, hl_error *err)
{
    int st = HL_OK;
    if (r->scheme != NULL && strcmp(r->scheme, "exact") == 0 &&
        !hl_scheme_linear_flow_applies(sys))
        st = build_exact(run, ex, sys, err);
    else if (!adaptive(r)) {
        st = cli_make_scheme(sch, o->map, r->equations, r->scheme, o->have_order ? o->order : 4,
                             sys, err);
    }
    if (st == HL_OK && *run == NULL)
        st = hl_run_new(run, sys, *sch, err);
    for (int i = 0; st == HL_OK && i < r->nobserve; i++)
        if ((st = hl_run_observe(*run, r->observe[i], err)) != HL_OK)
            hl_error_prefix(err, "in --observe");
    return st == HL_OK ? run_events_setup(*run, r, sys, err) : st;
}

int cmd_run(int argc, char **argv, const cli_command *self)
{
    const cli_command *cmd = self;
    run_opts r;
    cli_opts o;
    memset(&r, 0, sizeof r);
    memset(&o, 0, sizeof o);
    /* run's own options, in found_opt's order (--observe repeats) */
    static const cli_own own[] = {{"--scheme", 0},
                                  {"--equations", 0},
                                  {"--init", 0},
                                  {"--out", 0},
                                  {"--orders", 0},
                                  {"--dt", 0},
                                  {"--t", 0},
                                  {"--tol", 0},
                                  {"--every", 0},
                                  {"--digits", 0},
                                  {"--observe", CLI_OWN_REPEAT},
                                  {"--no-reference", 1},
                                  {"--plot", 0},
                                  {"--format", 0},
                                  {"--event", 0},
                                  {"--direction", 0},
                                  {"--event-stop", 0},
                                  {"--events-out", 0}};
    static const cli_begin_spec spec = {own, (int)(sizeof own / sizeof own[0]), found_opt,
                                        check_opts, CLI_OPT_H | CLI_OPT_MAP | CLI_OPT_ORDER | CLI_OPT_PROGRESS,
                                        64};
    char **av;
    hl_system *sys;
    int rc = cli_begin(&av, &o, &sys, argc, argv, cmd, &spec, &r);
    hl_scheme *sch = NULL;
    hl_run *run = NULL;
    hl_error err;
    hl_error_clear(&err);
    double z0[2 * 64];
    if (rc < 0 && r.digits_s == NULL && hl_run_init_values(z0, sys, r.init, &err) != HL_OK)
        rc = init_fail(&err, r.init);
    hl_exact_flow *ex = NULL;
    if (rc < 0 && build(&run, &sch, &ex, sys, &r, &o, &err) != HL_OK)
        rc = cli_fail(&err);
    /* before any output: a point outside H's domain is not a blow-up */
    if (rc < 0 && r.digits_s == NULL && hl_run_check_start(run, z0, &err) != HL_OK)
        rc = init_fail(&err, r.init);
    if (rc < 0)
        rc = r.orders != NULL    ? do_orders(run, sys, &r, &o, z0, cmd)
             : r.digits_s != NULL ? do_run_arb(run, sys, &r, &o)
                                  : do_run(run, sys, &r, &o, z0);
    hl_run_free(run);
    hl_exact_flow_free(ex);
    hl_scheme_free(sch);
    hl_system_free(sys);
    cli_opts_clear(&o);
    free(r.observe);
    run_events_free(&r);
    free(av);
    return rc;
}
