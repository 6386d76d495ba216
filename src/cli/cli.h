/* The hamlie command line: shared declarations of src/cli/. */
#ifndef HAMLIE_CLI_H
#define HAMLIE_CLI_H

#include "base/buf.h"
#include "hamlie/ham.h"
#include "hamlie/report.h"
#include "hamlie/scheme.h"

#define HAMLIE_VERSION "0.1.0"

/* Exit codes (documented in every --help). */
enum { CLI_OK = 0, CLI_FAILS = 1, CLI_ERROR = 2, CLI_INTERRUPTED = 130 /* 128 + SIGINT */ };

typedef struct cli_command {
    const char *name;
    int (*fn)(int argc, char **argv, const struct cli_command *self);
    const char *summary; /* one line for `hamlie --help` */
    const char *help;    /* the full text for `hamlie help NAME` */
} cli_command;


/* Which options a command accepts beyond the common ones
 * (--pairs, --param, --json, --latex, --help). */
enum {
    CLI_OPT_H = 1 << 0,        /* -H, --hamiltonian */
    CLI_OPT_INTEGRAL = 1 << 1, /* --integral (repeatable) */
    CLI_OPT_MAP = 1 << 2,      /* --map */
    CLI_OPT_ORDER = 1 << 3,    /* --order, -n */
    CLI_OPT_OF = 1 << 4,       /* --of (repeatable) */
    CLI_OPT_TERMS = 1 << 5,    /* --terms */
    CLI_OPT_PROGRESS = 1 << 6  /* --progress, --quiet */
};

/* --progress forces the progress lines, --quiet silences them; by default
 * a job says how far it got once it has run for a second or two. */
enum { CLI_PROGRESS_AUTO, CLI_PROGRESS_ON, CLI_PROGRESS_OFF };

typedef enum cli_format { CLI_TEXT, CLI_JSON, CLI_LATEX } cli_format;

typedef struct cli_opts {
    const char *H, *pairs, *map;
    const char *step;         /* --step NAME, or NULL ("D") */
    char *params;             /* every --param joined with ',', or NULL */
    cli_format format;
    const char **integral;    /* --integral values */
    int nintegral;
    const char **of;          /* --of values */
    int nof;
    int order, have_order, terms;
    int progress;             /* CLI_PROGRESS_* */
    char **args;              /* positional arguments */
    int nargs;
} cli_opts;

/* Parse argv (argv[0] is the command's name).  Returns -1 to go on, or the
 * exit code when done: 0 after printing --help, 2 after a usage error. */
int cli_parse(cli_opts *o, int argc, char **argv, unsigned accept, const cli_command *cmd);
void cli_opts_clear(cli_opts *o);

/* Report a usage error ("hamlie CMD: <msg>" plus a hint); returns 2. */
int cli_usage(const cli_command *cmd, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* *slot = value for an option that takes one value: given again with
 * another value it is refused (the last one would silently win).  Returns
 * -1, or 2 after the usage message. */
int cli_once(const char **slot, const char *value, const char *opt, const cli_command *cmd);

/* A command's own options, taken out of argv before cli_parse sees the rest
 * (kept in order): "--name VALUE" and "--name=VALUE", or just "--name" for a
 * flag.  Values are taken whole, so "--dt -1" reaches the command's range
 * check; nothing after "--" is taken.  found(arg, k, value) is called for
 * each option own[k] met (value NULL for a flag).  A CLI_OWN_VALUE given twice with different values is refused (cli_once).
 * Returns -1, or 2 after a usage message (an option without its value, or
 * given twice). */
enum {
    CLI_OWN_VALUE = 0, /* --name VALUE, once */
    CLI_OWN_FLAG = 1,  /* --name */
    CLI_OWN_REPEAT = 2 /* --name VALUE, any number of times (--observe) */
};
typedef struct cli_own {
    const char *name;
    int kind; /* CLI_OWN_* */
} cli_own;
int cli_take_own(int *argc, char **argv, const cli_own *own, int n,
                 void (*found)(void *arg, int k, const char *value), void *arg,
                 const cli_command *cmd);

/* The frame of a command that reads options, builds its system and prints
 * one result: parse (--help and usage errors end there), the command's own
 * usage checks, the system, the work, then the output written only on
 * success.
 *   check: -1 to go on, or the exit code after reporting (cli_usage); it
 *          may fill extra[0..2] (NULL-terminated) with formulas that define
 *          the variables when -H is not given (may be NULL: none).
 *   body:  the work; output into out, *code = CLI_OK or CLI_FAILS (a
 *          property checked and found false); an hl_status with err set
 *          on failure (printed by cli_fail, exit 2). */
typedef struct cli_spec {
    const char *name;
    unsigned accept; /* CLI_OPT_* */
    int (*check)(const cli_opts *o, const cli_command *cmd, const char **extra);
    int (*body)(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err);
} cli_spec;
int cli_main(int argc, char **argv, const cli_spec *spec, const cli_command *cmd);

/* The start of a command with options of its own (run, errors): argv is
 * copied into *av (free it after), the own options are taken out
 * (cli_take_own with own/found), the rest parsed (accept), checked (check,
 * -1 to go on or an exit code), and the system built from H alone with at
 * most max_dof degrees of freedom.  o must be zeroed by the caller; *sys is
 * NULL until built.  Returns -1 to go on, else the exit code. */
typedef struct cli_begin_spec {
    const cli_own *own;
    int nown;
    void (*found)(void *arg, int k, const char *value);
    int (*check)(void *arg, cli_opts *o, const cli_command *cmd);
    unsigned accept;
    int max_dof;
} cli_begin_spec;
int cli_begin(char ***av, cli_opts *o, hl_system **sys, int argc, char **argv,
              const cli_command *cmd, const cli_begin_spec *spec, void *arg);

/* The checks every scheme-running command (run, errors) makes first: -H
 * given (else "missing -H: <why_H>"), no positional argument, exactly one
 * of --scheme, --map and --equations.  -1 to go on, or 2 after the usage
 * message. */
int cli_check_scheme_source(const cli_opts *o, const char *scheme, const char *equations,
                            const char *why_H, const cli_command *cmd);

/* ---- a command's own inputs (input.c) ---- */
/* *v from s, a whole number in [lo, hi]; -1, or 2 after the usage message
 * naming opt. */
int cli_read_long(long *v, const char *s, const char *opt, long lo, long hi,
                  const cli_command *cmd);
/* A file's whole text (malloc'd), or NULL after the message. */
char *cli_read_file(const char *path);
/* An error whose err->src is text, the contents of file path, shown as
 * path:LINE:COL with that line and a caret; returns cli_fail's code. */
int cli_fail_in_file(hl_error *err, const char *path, const char *text);
/* The number of cores online (at least 1). */
int cli_cores(void);
/* b's text to path whole: to path.tmp, renamed when all is written (an
 * error leaves nothing under path); "-": standard output (cli_emit).  b is
 * freed.  CLI_OK, or CLI_ERROR after the message. */
int cli_write_whole(hl_buf *b, const char *path);

/* Print an error with its formula and a caret under err->pos; returns 2
 * (CLI_INTERRUPTED for HL_ESTOP: the job was interrupted). */
int cli_fail(const hl_error *err);

/* Write the finished output to stdout and make sure it got there; returns
 * code, or 2 if writing failed. */
int cli_emit(hl_buf *out, int code);

/* cli_emit for output that prints results of sys: refused, with nothing
 * written, when one of them was too large to print (hl_alg_ctx_unprinted). */
int cli_emit_results(hl_buf *out, int code, hl_system *sys);

/* The system of a command from its options; extra formulas count for the
 * inference of the variables.  Prints the error and returns 2 on failure. */
int cli_system(hl_system **sys, const cli_opts *o, const char *const *extra);

/* The "symbols" object and "H" of the JSON output. */
void cli_json_system(hl_json *j, hl_system *sys);

/* The note said when a verdict rests on the numeric zero test. */
void cli_numeric_note(hl_buf *out, hl_system *sys, cli_format f);

/* A formula as typed, shown in a style (LaTeX re-prints the parsed form). */
char *cli_show_input(const char *text, hl_system *sys, cli_format f);

/* Name of phase variable i: q_1..q_N, then p_1..p_N (i < 2N). */
const char *cli_phase_name(const hl_system *sys, int i);

/* Name of the image of phase variable a in a map: x -> X, px -> PX. */
char *cli_image_name(hl_system *sys, int a);

/* x's midpoint with ndig significant digits (arb_get_str, no radius). */
void cli_put_arb(hl_buf *b, const arb_struct *x, long ndig);

/* ---- long jobs (progress.c) ---------------------------------------------
 * On standard error: a line said at the start (cli_progress_say), then
 * "hamlie run: step 1200 of 5000 (24.0%), about 3 s left", in place on a
 * terminal, a line every few seconds otherwise.  cli_progress_fn is an
 * hl_progress_fn (error.h) with the cli_progress as its argument; it
 * returns non-zero once SIGINT was received (cli_progress_begin catches
 * it unless it was ignored, cli_progress_end puts the old handler back; a
 * second one kills), so the library stops between two steps and the
 * command writes what it has, whole, and exits CLI_INTERRUPTED. */
typedef struct cli_progress {
    const char *cmd, *unit; /* "run", "step" */
    int mode;               /* CLI_PROGRESS_* */
    int tty, shown;         /* stderr is a terminal; a line is in place on it */
    int estimate;           /* say the time left (rates that are steady) */
    long updates;
    double start, last;     /* monotonic seconds */
    char detail[96];        /* said after the count: "(q, 1 of 2)" */
} cli_progress;
void cli_progress_begin(cli_progress *p, const char *cmd, const char *unit, int mode);
void cli_progress_say(cli_progress *p, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
int cli_progress_fn(double done, double total, void *arg);
void cli_progress_end(cli_progress *p);
int cli_interrupted(void);

int cmd_generator(int argc, char **argv, const cli_command *self);
int cmd_bracket(int argc, char **argv, const cli_command *self);
int cmd_check(int argc, char **argv, const cli_command *self);
int cmd_canonical(int argc, char **argv, const cli_command *self);
int cmd_lie(int argc, char **argv, const cli_command *self);
int cmd_run(int argc, char **argv, const cli_command *self); extern const char cmd_run_help[];
int cmd_section(int argc, char **argv, const cli_command *self);
extern const char cmd_section_help[];
int cmd_schemes(int argc, char **argv, const cli_command *self); extern const char cmd_schemes_help[];
int cmd_plot(int argc, char **argv, const cli_command *self); extern const char cmd_plot_help[];
int cmd_errors(int argc, char **argv, const cli_command *self); extern const char cmd_errors_help[];
int cmd_reproduce(int argc, char **argv, const cli_command *self); extern const char cmd_reproduce_help[];
int cmd_exact(int argc, char **argv, const cli_command *self); extern const char cmd_exact_help[];
int cmd_chaos(int argc, char **argv, const cli_command *self); extern const char cmd_chaos_help[];
int cmd_cache(int argc, char **argv, const cli_command *self);
extern const char cmd_cache_help[];
int cmd_sweep(int argc, char **argv, const cli_command *self);
extern const char cmd_sweep_help[];

/* The scheme a command was given: --map, else --equations, else the
 * catalog's name (with its parameter, e.g. lie's order); the error says
 * which option it came from. */
hl_status cli_make_scheme(hl_scheme **s, const char *map, const char *equations, const char *name,
                          int param, hl_system *sys, hl_error *err);

#endif
