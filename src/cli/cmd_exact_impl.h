/* Internal to `hamlie exact` (src/cli/cmd_exact*.c): the command's own
 * options, the modes that carry out §3 by steps (--steps, --action-angle;
 * cmd_exact_steps.c) and the numeric exact scheme (--init, --digits;
 * cmd_exact_numeric.c), and their output (cmd_exact_out.c), which prints
 * text as it goes or, with --json, puts the same facts as fields. */
#ifndef HAMLIE_CLI_CMD_EXACT_IMPL_H
#define HAMLIE_CLI_CMD_EXACT_IMPL_H

#include <arb.h>

#include "cli/cli.h"

/* The command's own options (taken out of argv before cli_parse). */
typedef struct exact_mode_state {
    const char *init, *aa, *dt, *digits;
    int steps;
    /* --json with --steps, --action-angle, --init: the text goes to a
     * scratch buffer and what it says goes to j as fields (exact_json_*,
     * exact_put_*): sections are objects (the steps an array of objects)
     * under the top level, kinds[] the '{' or '[' of each one open */
    hl_json *j;
    int depth;
    char kinds[4];
} exact_mode_state;

extern exact_mode_state exact_mode;

/* ---- the modes: *code CLI_OK when every check holds, else CLI_FAILS ---- */

/* --action-angle MAP: the user's map verified, then the scheme it gives. */
int exact_run_aa(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err);

/* --steps: the seven steps of §3 for p^2/(2m) + V(q), V of degree <= 2. */
int exact_run_steps(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err);

/* --init (and --digits): the numeric exact scheme against the integrators. */
int exact_run_numeric(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err);

/* ---- output: JSON fields (no-ops without --json) ------------------------- */

/* Close the open sections down to depth (0: the top level). */
void exact_json_close_to(int depth);
/* A new object under the top level (the previous section closed). */
void exact_json_section(const char *key);
/* An object under the current section (closed by exact_json_close_to). */
void exact_json_object(const char *key);
void exact_json_bool(const char *key, int v);
void exact_json_double(const char *key, double v);
void exact_json_string(const char *key, const char *v);
/* A formula in hamlie's syntax, written as SymPy reads it. */
void exact_json_formula(const char *key, const char *text, hl_system *sys);
void exact_json_arb(const char *key, const arb_struct *x, long ndig);

/* ---- output: text, or the same as JSON fields ---------------------------- */

/* "step 3: ...\n": the line, or an element of the JSON array "steps". */
void exact_put_step(hl_buf *out, const char *line);
/* "  lhs = rhs" (LaTeX with --latex), or the field lhs of the step. */
void exact_put_formula(hl_buf *out, const char *lhs, const char *rhs, hl_system *sys,
                       const cli_opts *o);
/* The images Q, P of a map, one a line or as fields. */
void exact_put_images(hl_buf *out, const hl_alg *img, hl_system *sys, const cli_opts *o);

#endif
