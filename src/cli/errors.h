/* hamlie errors: what its files share (cmd_errors.c parses and dispatches,
 * errors_text.c and errors_json.c format the library's hl_analysis,
 * errors_numeric.c is the --numeric path). */
#ifndef HAMLIE_CLI_ERRORS_H
#define HAMLIE_CLI_ERRORS_H

#include "cli/cli.h"
#include "hamlie/analysis.h"
#include "hamlie/scheme.h"

/* errors' own options, as given. */
typedef struct err_opts {
    const char *scheme, *equations, *correct_s, *invdeg_s, *at;
    int correct, invdeg, numeric;
} err_opts;

/* Where the scheme comes from ("catalog", "map", "equations") and its text
 * as given (the name, the map, the equations). */
const char *errors_source(const err_opts *r, const cli_opts *o);
const char *errors_input(const err_opts *r, const cli_opts *o);

/* The scheme of the options (--scheme, --map or --equations); the error
 * says which option when the text does not read. */
hl_status errors_make_scheme(hl_scheme **s, const err_opts *r, const cli_opts *o, hl_system *sys,
                             hl_error *err);

/* The symbolic analysis as text (CLI_TEXT) or LaTeX, and as JSON. */
void errors_write_text(hl_buf *out, const hl_analysis *A, const char *input, cli_format f);
void errors_write_json(hl_buf *out, const hl_analysis *A, const char *source, const char *input);

/* tau(D) (W = 0) or W(D) = tau(D) - D (W = 1) as a series, malloc'd. */
char *errors_tau_text(const hl_analysis *A, int W, hl_style st);

/* --scheme exact for an H whose exact flow has no closed form: analysed
 * only at a point (--numeric). */
int errors_numeric_exact(const err_opts *r, hl_system *sys);

/* The whole --numeric path once the system is built: -1 with the output in
 * out, else the exit code. */
int errors_run_numeric(hl_buf *out, hl_system *sys, int order, const err_opts *r, const cli_opts *o,
                       const cli_command *cmd);

#endif
