/* hamlie chaos: the chaos indicators of one orbit (chaos.h) — MEGNO, the
 * fast Lyapunov indicator, the maximal Lyapunov exponent — at the final
 * time, or as a time series (CSV) with --every.  The output is buffered
 * and written only when the whole run succeeded. */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "hamlie/chaos.h"
#include "hamlie/flow.h"
#include "hamlie/run.h"

const char cmd_chaos_help[] =
    "usage: hamlie chaos -H FORMULA --init x=1,p=0 --t TIME [options]\n"
    "\n"
    "Integrate an orbit and its variational equations delta' = Df(z) delta\n"
    "(f = J grad H, differentiated symbolically) with the Taylor integrator and\n"
    "print the chaos indicators at TIME:\n"
    "  MEGNO Y(t) = (2/t) int_0^t s r(s) ds, r = delta.delta'/delta.delta, and its\n"
    "  running mean <Y>(t) = (1/t) int_0^t Y ds (Cincotta & Simo 2000): <Y> -> 0\n"
    "  for isochronous orbits, -> 2 for quasi-periodic ones, grows like\n"
    "  lambda t / 2 for chaotic ones;\n"
    "  the fast Lyapunov indicator, sup log(|delta|/|delta0|) (over the\n"
    "  renormalisation checkpoints), and the estimate of the maximal Lyapunov\n"
    "  exponent lambda ~ log(|delta(t)|/|delta0|) / t.\n"
    "\n"
    "  -H, --hamiltonian F  the Hamiltonian (required; every parameter given a\n"
    "                       value with --param)\n"
    "  --init x=1,p=0       the initial point (values may be formulas: q=pi/2)\n"
    "  --t TIME             the final time (> 0)\n"
    "  --tol TOL            the tolerance of the Taylor integrator (default 1e-13,\n"
    "                       at least 5.6e-17)\n"
    "  --delta x=1,p=0      the initial tangent vector (not 0; default a fixed\n"
    "                       generic direction)\n"
    "  --every DT           print a CSV row every DT (and at TIME): t, Y, mean_Y,\n"
    "                       fli, mlce, then the state\n"
    "  --pairs, --param     as for every command\n"
    "  --json               print the final indicators as JSON (not with --every)\n"
    "  --progress, --quiet  progress (time reached) on stderr from the start, or\n"
    "                       none (default: after a second or two)\n"
    "  -h, --help           show this help\n"
    "\n"
    "Ctrl-C (SIGINT) stops the run between two renormalisations: with --every the\n"
    "rows done are written, whole; without, nothing is printed.\n"
    "Exit status: 0 computed; 2 usage or input error, or the run failed (a\n"
    "blow-up: the error says at what time); 130 interrupted.\n"
    "Example: hamlie chaos -H '(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3' \\\n"
    "           --init x=0,y=-0.1,px=0.56803755858823,py=0 --t 1e3\n";

/* The CSV is held in memory until the run is done (nothing half-written). */
#define CHAOS_MAX_ROWS 1e7

typedef struct chaos_opts {
    const char *init, *t_s, *tol_s, *every_s, *delta;
    double t, tol, every;
} chaos_opts;

static void found_opt(void *arg, int k, const char *value)
{
    chaos_opts *c = arg;
    const char **slot[] = {&c->init, &c->t_s, &c->tol_s, &c->every_s, &c->delta};
    *slot[k] = value;
}

static int parse_double(double *v, const char *s, const char *opt, const cli_command *cmd)
{
    char *end;
    errno = 0;
    *v = strtod(s, &end);
    if (*s == '\0' || *end != '\0' || !isfinite(*v))
        return cli_usage(cmd, "%s wants a finite number, not '%s'", opt, s);
    return -1;
}

static int check_opts(void *arg, cli_opts *o, const cli_command *cmd)
{
    chaos_opts *c = arg;
    int rc;
    if (o->H == NULL)
        return cli_usage(cmd, "missing -H: the Hamiltonian of the orbit");
    if (o->nargs > 0)
        return cli_usage(cmd, "unexpected argument '%s'", o->args[0]);
    if (c->init == NULL)
        return cli_usage(cmd, "missing --init: the initial point, e.g. --init x=1,p=0");
    if (c->t_s == NULL)
        return cli_usage(cmd, "missing --t: the final time");
    if ((rc = parse_double(&c->t, c->t_s, "--t", cmd)) >= 0)
        return rc;
    if (!(c->t > 0))
        return cli_usage(cmd, "--t must be positive, not '%s'", c->t_s);
    c->tol = 1e-13;
    if (c->tol_s != NULL && (rc = parse_double(&c->tol, c->tol_s, "--tol", cmd)) >= 0)
        return rc;
    if (!(c->tol >= HL_FLOW_MIN_RTOL))
        return cli_usage(cmd, "--tol must be at least %.2g, not '%s'", HL_FLOW_MIN_RTOL, c->tol_s);
    c->every = 0;
    if (c->every_s != NULL) {
        if ((rc = parse_double(&c->every, c->every_s, "--every", cmd)) >= 0)
            return rc;
        if (!(c->every > 0))
            return cli_usage(cmd, "--every must be positive, not '%s'", c->every_s);
        if (o->format == CLI_JSON)
            return cli_usage(cmd, "--every writes CSV: not with --json");
        if (c->t / c->every > CHAOS_MAX_ROWS)
            return cli_usage(cmd, "--every %s would write more than %g rows: a larger one, please",
                             c->every_s, CHAOS_MAX_ROWS);
    }
    return -1;
}

/* ---- output ---------------------------------------------------------------- */

typedef struct csv_sink {
    hl_buf *out;
    int n; /* 2N */
} csv_sink;

static void csv_header(hl_buf *out, hl_system *sys)
{
    hl_buf_puts(out, "t,Y,mean_Y,fli,mlce");
    for (int i = 0; i < 2 * hl_system_ndof(sys); i++)
        hl_buf_printf(out, ",%s", cli_phase_name(sys, i));
    hl_buf_putc(out, '\n');
}

static int csv_row(const hl_chaos_result *r, const double *z, void *arg)
{
    csv_sink *s = arg;
    hl_buf_printf(s->out, "%.17g,%.17g,%.17g,%.17g,%.17g", r->t, r->megno, r->megno_mean, r->fli,
                  r->mlce);
    for (int i = 0; i < s->n; i++)
        hl_buf_printf(s->out, ",%.17g", z[i]);
    hl_buf_putc(s->out, '\n');
    return 0;
}

static void print_text(hl_buf *out, const hl_chaos_result *r)
{
    hl_buf_printf(out, "at t = %.17g (%ld Taylor steps):\n", r->t, r->nsteps);
    hl_buf_printf(out, "MEGNO Y = %.10g\n", r->megno);
    hl_buf_printf(out, "MEGNO mean <Y> = %.10g\n", r->megno_mean);
    hl_buf_printf(out, "fast Lyapunov indicator = %.10g\n", r->fli);
    hl_buf_printf(out, "maximal Lyapunov exponent ~ %.10g\n", r->mlce);
}

static void print_json(hl_buf *out, hl_system *sys, const cli_opts *o, const chaos_opts *c,
                       const hl_chaos_result *r)
{
    hl_json j;
    hl_json_init_buf(&j, out);
    hl_json_object_begin(&j);
    hl_json_kv_string(&j, "command", "chaos");
    cli_json_system(&j, sys);
    hl_json_kv_string(&j, "H_input", o->H);
    hl_json_kv_double(&j, "t", r->t);
    hl_json_kv_bool(&j, "numeric_zero_test", hl_alg_ctx_numeric_used(hl_system_ctx(sys)));
    hl_json_kv_double(&j, "tol", c->tol);
    hl_json_kv_int(&j, "steps", r->nsteps);
    hl_json_kv_double(&j, "megno", r->megno);
    hl_json_kv_double(&j, "megno_mean", r->megno_mean);
    hl_json_kv_double(&j, "fli", r->fli);
    hl_json_kv_double(&j, "mlce", r->mlce);
    hl_json_object_end(&j);
    hl_json_finish(&j);
}

/* --init or --delta read as a point of the system; errors point into it. */
static int read_point(double *z, hl_system *sys, const char *text, const char *opt)
{
    hl_error err;
    hl_error_clear(&err);
    if (hl_run_init_values(z, sys, text, &err) == HL_OK)
        return -1;
    if (err.src == NULL) {
        err.src = text;
        err.pos = -1;
    }
    hl_error_prefix(&err, "in %s", opt);
    return cli_fail(&err);
}

/* Ctrl-C: the rows done (whole) with --every, else nothing; exit 130. */
static int interrupted(hl_buf *out, const chaos_opts *c, const hl_chaos_result *r)
{
    int rc = CLI_INTERRUPTED;
    if (c->every > 0)
        rc = cli_emit(out, CLI_INTERRUPTED);
    fprintf(stderr, "hamlie chaos: interrupted at t = %.17g of %.17g%s\n", r->t, c->t,
            c->every > 0 ? "; the rows before written" : "; nothing printed");
    return rc;
}

static int compute(hl_system *sys, const cli_opts *o, const chaos_opts *c, const double *z0,
                   const double *d0)
{
    hl_error err;
    hl_error_clear(&err);
    hl_chaos *ch = NULL;
    hl_buf out;
    hl_buf_init(&out);
    csv_sink sink = {&out, 2 * hl_system_ndof(sys)};
    hl_chaos_result r;
    int rc;
    if (c->every > 0)
        csv_header(&out, sys);
    cli_progress p;
    cli_progress_begin(&p, "chaos", "time", o->progress);
    hl_status st = hl_chaos_new(&ch, sys, c->tol, &err);
    if (st == HL_OK) {
        hl_chaos_set_progress(ch, cli_progress_fn, &p);
        st = hl_chaos_run(ch, z0, d0, c->t, c->every, c->every > 0 ? csv_row : NULL, &sink, &r,
                          &err);
    }
    cli_progress_end(&p);
    if (st == HL_ESTOP) {
        rc = interrupted(&out, c, &r);
    } else if (st != HL_OK) {
        rc = cli_fail(&err);
    } else {
        if (c->every > 0)
            ; /* the rows are written */
        else if (o->format == CLI_JSON)
            print_json(&out, sys, o, c, &r);
        else
            print_text(&out, &r);
        rc = cli_emit(&out, CLI_OK);
    }
    hl_chaos_free(ch);
    hl_buf_clear(&out);
    return rc;
}

int cmd_chaos(int argc, char **argv, const cli_command *self)
{
    chaos_opts c;
    cli_opts o;
    memset(&c, 0, sizeof c);
    memset(&o, 0, sizeof o);
    static const cli_own own[] = {
        {"--init", 0}, {"--t", 0}, {"--tol", 0}, {"--every", 0}, {"--delta", 0}};
    static const cli_begin_spec spec = {own,        (int)(sizeof own / sizeof own[0]), found_opt,
                                        check_opts, CLI_OPT_H | CLI_OPT_PROGRESS,      64};
    char **av;
    hl_system *sys;
    int rc = cli_begin(&av, &o, &sys, argc, argv, self, &spec, &c);
    double z0[2 * 64], d0[2 * 64];
    if (rc < 0)
        rc = read_point(z0, sys, c.init, "--init");
    if (rc < 0 && c.delta != NULL)
        rc = read_point(d0, sys, c.delta, "--delta");
    if (rc < 0)
        rc = compute(sys, &o, &c, z0, c.delta != NULL ? d0 : NULL);
    hl_system_free(sys);
    cli_opts_clear(&o);
    free(av);
    return rc;
}
