/* hamlie errors: the error fields v_k of a scheme (paper §4), computed two
 * ways, the order, the leading error classified, K(D), corrected schemes.
 * This file reads the options and dispatches: the analysis itself is the
 * library's (hl_analysis_compute); errors_text.c and errors_json.c format
 * it, errors_numeric.c is --numeric.  Its own options (--scheme,
 * --equations, --correct) are taken out of argv before the common parser
 * sees the rest, as run does. */
#include <stdlib.h>
#include <string.h>

#include "cli/errors.h"
#include "hamlie/numerr.h"

const char cmd_errors_help[] =
    "usage: hamlie errors -H FORMULA (--scheme NAME | --map MAP | --equations EQS)\n"
    "                     [--order N] [--correct M] [--invariants-degree d] [options]\n"
    "       hamlie errors -H FORMULA (--scheme NAME | --map MAP | --equations EQS)\n"
    "                     --numeric --at 'q=1.3,p=0' [--order N] [--json]\n"
    "\n"
    "Error analysis of a one-step scheme psi_D (paper §4).  The error fields v_k,\n"
    "k = 2..N, are defined by  psi_D - exp(D g) = sum_k D^k/k! v_k  and computed two\n"
    "ways: from the scheme's expansion minus the Lie series, and from\n"
    "K(D) = psi_{-D} o d/dD psi_D alone, order by order; the two must agree.  The\n"
    "order of the scheme is (the least k with v_k != 0) - 1.  The leading field\n"
    "is classified: a time shift c g, parallel to g (lambda(z) g), a scaling, a\n"
    "Hamiltonian field (with its h when polynomial), or general.  For an explicit\n"
    "scheme the map and K(D) are printed in closed form.  Also: invariants of the\n"
    "leading field (--invariants-degree), the time reparametrisation tau(D) when it\n"
    "is c g, and the modified vector field (backward error analysis) with its\n"
    "modified Hamiltonian when polynomial.\n"
    "\n"
    "  -H, --hamiltonian F  the Hamiltonian (required)\n"
    "  --scheme NAME        a scheme of the catalog (hamlie schemes lists them)\n"
    "  --map MAP            an explicit map 'X = ...; P = ...'\n"
    "  --equations EQS      an implicit scheme '(X-x)/D = ...; (P-p)/D = ...'\n"
    "  -n, --order N        compute v_2..v_N (2..40; default 4)\n"
    "  --correct M          also analyse psi_D - sum_{k=2}^M D^k/k! v_k (M <= N)\n"
    "  --invariants-degree d  search polynomial invariants of the leading field up\n"
    "                       to degree d, and Darboux ratios for a linear field\n"
    "                       (0..8, default 2; 0: no search)\n"
    "  --numeric            numeric analysis at the point --at, in double precision:\n"
    "                       the values v_k(z) and K(D)'s Taylor coefficients at z,\n"
    "                       by Taylor mode (no symbolic expansion; any scheme,\n"
    "                       implicit ones solved order by order), the order and\n"
    "                       the leading k (|v_k(z)| above 1e-10 k! times the size\n"
    "                       of the D^k coefficients: round-off).  --order 2..60\n"
    "                       --scheme exact for an H without a closed form (1 dof,\n"
    "                       the orbit by quadrature) is analysed this way only,\n"
    "                       from its own series at z (--order 2..8; K is not\n"
    "                       computed)\n"
    "  --at 'q=1.3,p=0'     the point: every phase variable, a number each\n"
    "  --pairs x:px,y:py    the canonical pairs\n"
    "  --param k=2          give a parameter a value (repeatable)\n"
    "  --json               print a JSON object (schema: docs/json.md)\n"
    "  --latex              print formulas as LaTeX\n"
    "  -h, --help           show this help\n"
    "\n"
    "Exit status: 0 computed; 2 usage or input error (unknown scheme, a scheme\n"
    "that is not consistent or not determined at D = 0, ...).\n"
    "Example: hamlie errors -H '(p^2+x^2)/2' --scheme euler --order 7\n";

static void found_opt(void *arg, int k, const char *value)
{
    err_opts *r = arg;
    const char **slot[] = {&r->scheme, &r->equations, &r->correct_s, &r->invdeg_s, &r->at};
    if (k == 5)
        r->numeric = 1;
    else
        *slot[k] = value;
}

/* The usage checks of errors' options, after parsing (cli_begin). */
static int check_opts(void *arg, cli_opts *o, const cli_command *cmd)
{
    err_opts *r = arg;
    int rc = cli_check_scheme_source(o, r->scheme, r->equations,
                                     "the error analysis needs a Hamiltonian", cmd);
    if (rc >= 0)
        return rc;
    if (!o->have_order)
        o->order = 4;
    if (r->numeric && r->at == NULL)
        return cli_usage(cmd, "--numeric needs the point: --at 'q=1.3,p=0'");
    if (!r->numeric && r->at != NULL)
        return cli_usage(cmd, "--at is the point of the numeric analysis: add --numeric");
    if (r->numeric && (r->correct_s != NULL || r->invdeg_s != NULL))
        return cli_usage(cmd, "--correct and --invariants-degree are symbolic: not with "
                              "--numeric");
    int maxn = r->numeric ? HL_NUMERR_MAX_ORDER : HL_ANALYSIS_MAX_ORDER;
    if (o->order < 2 || o->order > maxn)
        return cli_usage(cmd, "--order must be between 2 and %d, not %d", maxn, o->order);
    if (r->correct_s != NULL) {
        char *end;
        long v = strtol(r->correct_s, &end, 10);
        if (*r->correct_s == '\0' || *end != '\0')
            return cli_usage(cmd, "--correct wants a whole number, not '%s'", r->correct_s);
        if (v < 2 || v > o->order)
            return cli_usage(cmd, "--correct must be between 2 and the order %d, not %s",
                             o->order, r->correct_s);
        r->correct = (int)v;
    }
    r->invdeg = 2;
    if (r->invdeg_s != NULL) {
        char *end;
        long v = strtol(r->invdeg_s, &end, 10);
        if (*r->invdeg_s == '\0' || *end != '\0' || v < 0 || v > 8)
            return cli_usage(cmd, "--invariants-degree wants a whole number 0..8, not '%s'",
                             r->invdeg_s);
        r->invdeg = (int)v;
    }
    return -1;
}

/* The symbolic analysis (hl_analysis_compute), formatted: -1 with the
 * output in out, else the exit code. */
static int run_symbolic(hl_buf *out, hl_system *sys, const err_opts *r, const cli_opts *o)
{
    hl_analysis_opts ao;
    hl_analysis_opts_default(&ao);
    ao.order = o->order;
    ao.correct = r->correct;
    ao.invariants_degree = r->invdeg;
    hl_scheme *s = NULL;
    hl_analysis *A = NULL;
    hl_error err;
    hl_error_clear(&err);
    int rc = -1;
    if (errors_make_scheme(&s, r, o, sys, &err) != HL_OK ||
        hl_analysis_compute(&A, &ao, s, sys, &err) != HL_OK)
        rc = cli_fail(&err);
    else if (o->format == CLI_JSON)
        errors_write_json(out, A, errors_source(r, o), errors_input(r, o));
    else
        errors_write_text(out, A, errors_input(r, o), o->format);
    hl_analysis_free(A);
    hl_scheme_free(s);
    return rc;
}

int cmd_errors(int argc, char **argv, const cli_command *self)
{
    const cli_command *cmd = self;
    err_opts r;
    cli_opts o;
    hl_system *sys = NULL;
    memset(&r, 0, sizeof r);
    memset(&o, 0, sizeof o);
    /* errors' own options, in found_opt's order; the rest goes to cli_parse */
    static const cli_own own[] = {
        {"--scheme", 0},  {"--equations", 0},         {"--correct", 0},
        {"--invariants-degree", 0}, {"--at", 0}, {"--numeric", 1}};
    static const cli_begin_spec spec = {own, 6, found_opt, check_opts,
                                        CLI_OPT_H | CLI_OPT_MAP | CLI_OPT_ORDER, 64};
    char **av;
    int rc = cli_begin(&av, &o, &sys, argc, argv, cmd, &spec, &r);
    hl_buf out;
    hl_buf_init(&out);
    if (rc < 0 && !r.numeric && errors_numeric_exact(&r, sys))
        rc = cli_usage(cmd,
                       "the exact scheme of this H is numeric (action-angle by "
                       "quadrature, exact.h): analyse it at a point with --numeric "
                       "--at '%s=...,%s=...'",
                       hl_system_coord(sys, 0), hl_system_momentum(sys, 0));
    else if (rc < 0 && r.numeric) {
        if ((rc = errors_run_numeric(&out, sys, o.order, &r, &o, cmd)) < 0)
            rc = cli_emit(&out, CLI_OK);
    } else if (rc < 0 && (rc = run_symbolic(&out, sys, &r, &o)) < 0)
        rc = cli_emit_results(&out, CLI_OK, sys);
    hl_buf_clear(&out);
    hl_system_free(sys);
    cli_opts_clear(&o);
    free(av);
    return rc;
}
