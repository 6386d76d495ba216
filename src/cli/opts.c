/* Option parsing shared by every command (getopt_long per command). */
#include <errno.h>
#include <getopt.h>
#include <limits.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"

enum {
    O_PAIRS = 256, O_STEP, O_PARAM, O_JSON, O_LATEX, O_INTEGRAL, O_MAP, O_OF, O_TERMS,
    O_PROGRESS, O_QUIET
};

int cli_usage(const cli_command *cmd, const char *fmt, ...)
{
    va_list ap;
    fprintf(stderr, "hamlie %s: error: ", cmd->name);
    va_start(ap, fmt);
    vfprintf(stderr, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\n(see hamlie %s --help)\n", cmd->name);
    return CLI_ERROR;
}

void cli_opts_clear(cli_opts *o)
{
    free(o->params);
    free(o->integral);
    free(o->of);
    free(o->args);
    memset(o, 0, sizeof *o);
}

static void push(const char ***v, int *n, const char *s)
{
    *v = hl_xrealloc(*v, (size_t)(*n + 1) * sizeof **v);
    (*v)[(*n)++] = s;
}

static int parse_order(cli_opts *o, const char *s, const cli_command *cmd)
{
    char *end;
    errno = 0;
    long v = strtol(s, &end, 10);
    if (*s == '\0' || *end != '\0')
        return cli_usage(cmd, "--order wants a whole number, not '%s'", s);
    if (errno == ERANGE || v > INT_MAX || v < INT_MIN)
        v = v < 0 ? INT_MIN : INT_MAX; /* refused later, with the limit named */
    o->order = (int)v;
    o->have_order = 1;
    return -1;
}

static int parse_opts(cli_opts *o, int argc, char **argv, unsigned accept,
                      const cli_command *cmd);

int cli_once(const char **slot, const char *value, const char *opt, const cli_command *cmd)
{
    if (*slot != NULL && strcmp(*slot, value) != 0)
        return cli_usage(cmd, "%s given twice ('%s', then '%s'): give it once", opt, *slot,
                         value);
    *slot = value;
    return -1;
}

static int takes(unsigned accept, unsigned bit, const char *opt, const cli_command *cmd)
{
    if (accept & bit)
        return -1;
    return cli_usage(cmd, "option '%s' does not apply to '%s'", opt, cmd->name);
}

/* Does this option take its value in the next argument? */
static int wants_value(const char *a)
{
    static const char *const with_value[] = {"--hamiltonian", "--pairs", "--step", "--param",
                                             "--integral", "--map", "--order", "--of"};
    if (strcmp(a, "-H") == 0 || strcmp(a, "-n") == 0)
        return 1;
    for (size_t i = 0; i < sizeof with_value / sizeof with_value[0]; i++)
        if (strcmp(a, with_value[i]) == 0)
            return 1;
    return 0;
}

/* A formula may start with '-' ("-px*L - y/r"): an argument that starts with
 * '-' but not with an option letter of hamlie (-H, -n, -h, --) is a formula,
 * not an option.  Such arguments are hidden from getopt behind a copy that
 * does not start with '-' (first[i] != 0 marks them). */
static char **hide_formulas(int argc, char **argv, char *first)
{
    char **av = hl_xmalloc((size_t)(argc + 1) * sizeof *av);
    int rest = 0;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        av[i] = argv[i];
        first[i] = 0;
        if (i == 0)
            continue;
        if (!rest && strcmp(a, "--") == 0) {
            rest = 1;
            continue;
        }
        if (!rest && wants_value(a) && i + 1 < argc) {
            i++;
            av[i] = argv[i];
            first[i] = 0;
            continue;
        }
        if (!rest && a[0] == '-' && a[1] != '\0' && strchr("Hnh-", a[1]) == NULL) {
            first[i] = a[0];
            av[i] = hl_xstrdup(a);
            av[i][0] = 'F'; /* any non-dash; restored from argv below */
        }
    }
    av[argc] = NULL;
    return av;
}

int cli_parse(cli_opts *o, int argc, char **argv, unsigned accept, const cli_command *cmd)
{
    char *hidden = hl_xmalloc((size_t)argc + 1);
    char **av = hide_formulas(argc, argv, hidden);
    char **orig = hl_xmalloc((size_t)(argc + 1) * sizeof *orig);
    memcpy(orig, av, (size_t)(argc + 1) * sizeof *orig);
    int rc = parse_opts(o, argc, av, accept, cmd);
    /* getopt permuted av; map hidden copies back to the user's text. */
    for (int k = 0; k < o->nargs; k++)
        for (int i = 0; i < argc; i++)
            if (hidden[i] && o->args[k] == orig[i])
                o->args[k] = argv[i];
    for (int i = 0; i < argc; i++)
        if (hidden[i])
            free(orig[i]);
    free(orig), free(av), free(hidden);
    return rc;
}

static int parse_opts(cli_opts *o, int argc, char **argv, unsigned accept,
                      const cli_command *cmd)
{
    static const struct option longopts[] = {
        {"hamiltonian", required_argument, NULL, 'H'},
        {"pairs", required_argument, NULL, O_PAIRS},
        {"step", required_argument, NULL, O_STEP},
        {"param", required_argument, NULL, O_PARAM},
        {"json", no_argument, NULL, O_JSON},
        {"latex", no_argument, NULL, O_LATEX},
        {"help", no_argument, NULL, 'h'},
        {"integral", required_argument, NULL, O_INTEGRAL},
        {"map", required_argument, NULL, O_MAP},
        {"order", required_argument, NULL, 'n'},
        {"of", required_argument, NULL, O_OF},
        {"terms", no_argument, NULL, O_TERMS},
        {"progress", no_argument, NULL, O_PROGRESS},
        {"quiet", no_argument, NULL, O_QUIET},
        {NULL, 0, NULL, 0},
    };
    hl_buf params;
    const char *order_text = NULL;
    int c, rc = -1;

    memset(o, 0, sizeof *o);
    hl_buf_init(&params);
    optind = 0; /* GNU: full re-initialisation */
    opterr = 0;
    while (rc < 0 && (c = getopt_long(argc, argv, ":H:n:h", longopts, NULL)) != -1) {
        switch (c) {
        case 'H':
            if ((rc = takes(accept, CLI_OPT_H, "-H", cmd)) < 0)
                rc = cli_once(&o->H, optarg, "-H", cmd);
            break;
        case O_PAIRS:
            rc = cli_once(&o->pairs, optarg, "--pairs", cmd);
            break;
        case O_STEP:
            rc = cli_once(&o->step, optarg, "--step", cmd);
            break;
        case O_PARAM:
            hl_buf_printf(&params, "%s%s", params.len ? "," : "", optarg);
            break;
        case O_JSON:
        case O_LATEX: {
            cli_format f = c == O_JSON ? CLI_JSON : CLI_LATEX;
            if (o->format != CLI_TEXT && o->format != f)
                rc = cli_usage(cmd, "--json and --latex cannot be used together");
            o->format = f;
            break;
        }
        case 'h':
            fputs(cmd->help, stdout);
            rc = fflush(stdout) == 0 && !ferror(stdout) ? CLI_OK : CLI_ERROR;
            break;
        case O_INTEGRAL:
            if ((rc = takes(accept, CLI_OPT_INTEGRAL, "--integral", cmd)) < 0)
                push(&o->integral, &o->nintegral, optarg);
            break;
        case O_MAP:
            if ((rc = takes(accept, CLI_OPT_MAP, "--map", cmd)) < 0)
                rc = cli_once(&o->map, optarg, "--map", cmd);
            break;
        case 'n':
            if ((rc = takes(accept, CLI_OPT_ORDER, "--order", cmd)) < 0 &&
                (rc = cli_once(&order_text, optarg, "--order", cmd)) < 0)
                rc = parse_order(o, optarg, cmd);
            break;
        case O_OF:
            if ((rc = takes(accept, CLI_OPT_OF, "--of", cmd)) < 0)
                push(&o->of, &o->nof, optarg);
            break;
        case O_TERMS:
            if ((rc = takes(accept, CLI_OPT_TERMS, "--terms", cmd)) < 0)
                o->terms = 1;
            break;
        case O_PROGRESS:
        case O_QUIET: {
            int m = c == O_PROGRESS ? CLI_PROGRESS_ON : CLI_PROGRESS_OFF;
            if ((rc = takes(accept, CLI_OPT_PROGRESS, argv[optind - 1], cmd)) < 0 &&
                o->progress != CLI_PROGRESS_AUTO && o->progress != m)
                rc = cli_usage(cmd, "--progress and --quiet cannot be used together");
            o->progress = m;
            break;
        }
        case ':':
            rc = cli_usage(cmd, "option '%s' needs a value", argv[optind - 1]);
            break;
        default:
            rc = cli_usage(cmd, "unknown option '%s'", argv[optind - 1]);
            break;
        }
    }
    if (params.len)
        o->params = hl_buf_take(&params);
    hl_buf_clear(&params);
    if (rc >= 0)
        return rc;
    for (int i = optind; i < argc; i++)
        push((const char ***)&o->args, &o->nargs, argv[i]);
    return -1;
}
