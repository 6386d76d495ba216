/* What every command shares: errors with a caret, the all-or-nothing output,
 * building the system from the options, the JSON "symbols" block. */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"

int cli_fail(const hl_error *err)
{
    if (err->status == HL_ESTOP) { /* by the progress callback: an interrupt */
        fprintf(stderr, "hamlie: interrupted: %s\n", err->msg);
        return CLI_INTERRUPTED;
    }
    fprintf(stderr, "hamlie: error: %s\n", err->msg[0] ? err->msg : hl_status_string(err->status));
    if (err->src == NULL)
        return CLI_ERROR;
    if (err->pos < 0) { /* about the formula as a whole: show it */
        fprintf(stderr, "  %s\n", err->src);
        return CLI_ERROR;
    }
    /* The formula on one line, then a caret under the bad spot: count
     * characters, not bytes, so UTF-8 before the spot keeps it aligned. */
    fputs("  ", stderr);
    for (const char *c = err->src; *c; c++)
        fputc(*c == '\t' || *c == '\n' ? ' ' : *c, stderr);
    fputs("\n  ", stderr);
    int n = (int)strlen(err->src), pos = err->pos > n ? n : err->pos;
    for (int i = 0; i < pos; i++)
        if (((unsigned char)err->src[i] & 0xC0) != 0x80)
            fputc(' ', stderr);
    fputc('^', stderr);
    for (int i = 1; i < err->len && pos + i < n; i++)
        if (((unsigned char)err->src[pos + i] & 0xC0) != 0x80)
            fputc('~', stderr);
    fputc('\n', stderr);
    return CLI_ERROR;
}

int cli_emit(hl_buf *out, int code)
{
    if (out->len > 0 && fwrite(out->s, 1, out->len, stdout) != out->len)
        code = CLI_ERROR;
    if (fflush(stdout) != 0 || ferror(stdout))
        code = CLI_ERROR;
    if (code == CLI_ERROR)
        fprintf(stderr, "hamlie: error: writing to standard output failed\n");
    hl_buf_clear(out);
    return code;
}

int cli_emit_results(hl_buf *out, int code, hl_system *sys)
{
    double unprinted = hl_alg_ctx_unprinted(hl_system_ctx(sys));
    if (unprinted == 0)
        return cli_emit(out, code);
    hl_error err;
    hl_error_set(&err, HL_ELIMIT, NULL, -1, 0,
                 "result too large to print: %.0f terms and operators written out (limit %d)",
                 unprinted, HL_PRINT_MAX_NODES);
    hl_buf_clear(out);
    return cli_fail(&err);
}

int cli_system(hl_system **sys, const cli_opts *o, const char *const *extra)
{
    hl_system_spec spec = {o->H, o->pairs, o->params, extra, o->step};
    hl_error err;
    hl_error_clear(&err);
    if (hl_system_new(sys, &spec, &err) != HL_OK) {
        if (err.src != NULL && o->pairs != NULL && err.src == o->pairs)
            hl_error_prefix(&err, "in --pairs");
        else if (err.src != NULL && o->params != NULL && err.src == o->params)
            hl_error_prefix(&err, "in --param");
        else if (err.src != NULL && o->step != NULL && err.src == o->step)
            hl_error_prefix(&err, "in --step");
        return cli_fail(&err);
    }
    return CLI_OK;
}

static void json_names(hl_json *j, const char *key, hl_system *sys,
                       const char *(*get)(const hl_system *, int), int n)
{
    hl_json_key(j, key);
    hl_json_array_begin(j);
    for (int i = 0; i < n; i++)
        hl_json_string(j, get(sys, i));
    hl_json_array_end(j);
}

void cli_json_system(hl_json *j, hl_system *sys)
{
    int n = hl_system_ndof(sys);
    hl_json_key(j, "symbols");
    hl_json_object_begin(j);
    json_names(j, "coordinates", sys, hl_system_coord, n);
    json_names(j, "momenta", sys, hl_system_momentum, n);
    json_names(j, "parameters", sys, hl_system_param, hl_system_nparams(sys));
    hl_json_kv_string(j, "step", hl_system_step(sys));
    hl_json_object_end(j);
    hl_json_key(j, "parameter_values");
    hl_json_object_begin(j);
    for (int i = 0; i < hl_system_nset(sys); i++) {
        char *s = hl_expr_print(hl_system_set_value(sys, i), HL_STYLE_SYMPY);
        hl_json_kv_string(j, hl_system_set_name(sys, i), s);
        free(s);
    }
    hl_json_object_end(j);
    if (hl_system_has_H(sys)) {
        char *s = hl_format_alg(hl_system_H(sys), hl_system_ctx(sys), hl_system_pool(sys),
                                HL_STYLE_SYMPY);
        hl_json_kv_string(j, "H", s);
        free(s);
    } else {
        hl_json_key(j, "H");
        hl_json_null(j);
    }
}

void cli_numeric_note(hl_buf *out, hl_system *sys, cli_format f)
{
    if (!hl_alg_ctx_numeric_used(hl_system_ctx(sys)))
        return;
    const char *note = "a zero above was decided by a numeric test at random points "
                       "(Arb, high precision), not proved exactly";
    if (f == CLI_LATEX)
        hl_buf_printf(out, "%% note: %s\n", note);
    else
        hl_buf_printf(out, "note: %s\n", note);
}

char *cli_show_input(const char *text, hl_system *sys, cli_format f)
{
    if (f == CLI_LATEX) {
        const hl_expr *e;
        if (hl_parse(&e, hl_system_pool(sys), text, NULL) == HL_OK)
            return hl_expr_print(e, HL_STYLE_LATEX);
    }
    /* As typed, without the spaces around it. */
    while (isspace((unsigned char)*text))
        text++;
    size_t n = strlen(text);
    while (n > 0 && isspace((unsigned char)text[n - 1]))
        n--;
    char *s = hl_xmalloc(n + 1);
    memcpy(s, text, n);
    s[n] = '\0';
    return s;
}

char *cli_image_name(hl_system *sys, int a)
{
    int n = hl_system_ndof(sys);
    char *s = hl_xstrdup(a < n ? hl_system_coord(sys, a) : hl_system_momentum(sys, a - n));
    for (char *c = s; *c; c++)
        *c = (char)toupper((unsigned char)*c);
    return s;
}

/* Which of own[] is argument a ("--dt" or "--dt=0.1")?  -1 if none. */
static int own_index(const char *a, const cli_own *own, int n, const char **inline_value)
{
    for (int k = 0; k < n; k++) {
        size_t l = strlen(own[k].name);
        if (strncmp(a, own[k].name, l) != 0)
            continue;
        if (a[l] == '\0' || (a[l] == '=' && own[k].kind != CLI_OWN_FLAG)) {
            *inline_value = a[l] == '=' ? a + l + 1 : NULL;
            return k;
        }
    }
    return -1;
}

int cli_take_own(int *argc, char **argv, const cli_own *own, int n,
                 void (*found)(void *arg, int k, const char *value), void *arg,
                 const cli_command *cmd)
{
    const char **given = hl_xcalloc((size_t)(n > 0 ? n : 1), sizeof *given);
    int kept = 0, rc = -1;
    for (int i = 0; i < *argc && rc < 0; i++) {
        const char *a = argv[i], *val = NULL;
        if (i > 0 && strcmp(a, "--") == 0) {
            while (i < *argc)
                argv[kept++] = argv[i++];
            break;
        }
        int k = i > 0 ? own_index(a, own, n, &val) : -1;
        if (k < 0) {
            argv[kept++] = argv[i];
            continue;
        }
        if (own[k].kind != CLI_OWN_FLAG && val == NULL) {
            if (i + 1 >= *argc) {
                rc = cli_usage(cmd, "option '%s' needs a value", a);
                break;
            }
            val = argv[++i];
        }
        if (own[k].kind == CLI_OWN_VALUE &&
            (rc = cli_once(&given[k], val, own[k].name, cmd)) >= 0)
            break;
        found(arg, k, val);
    }
    free(given);
    if (rc >= 0)
        return rc;
    argv[kept] = NULL;
    *argc = kept;
    return -1;
}

int cli_main(int argc, char **argv, const cli_spec *spec, const cli_command *cmd)
{
    const char *extra[3] = {NULL, NULL, NULL};
    hl_system *sys = NULL;
    cli_opts o;
    hl_error err;
    hl_buf out;
    int rc = cli_parse(&o, argc, argv, spec->accept, cmd);

    if (rc < 0 && spec->check)
        rc = spec->check(&o, cmd, extra);
    if (rc < 0) /* with -H, H alone defines the system */
        rc = cli_system(&sys, &o, o.H || extra[0] == NULL ? NULL : extra);
    if (rc == CLI_OK && sys != NULL) { /* not after --help */
        int code = CLI_OK;
        hl_error_clear(&err);
        hl_buf_init(&out);
        rc = spec->body(&out, &code, sys, &o, &err) == HL_OK
                 ? cli_emit_results(&out, code, sys)
                 : cli_fail(&err);
        hl_buf_clear(&out);
    }
    hl_system_free(sys);
    cli_opts_clear(&o);
    return rc;
}

const char *cli_phase_name(const hl_system *sys, int i)
{
    int N = hl_system_ndof(sys);
    return i < N ? hl_system_coord(sys, i) : hl_system_momentum(sys, i - N);
}

int cli_check_scheme_source(const cli_opts *o, const char *scheme, const char *equations,
                            const char *why_H, const cli_command *cmd)
{
    if (o->H == NULL)
        return cli_usage(cmd, "missing -H: %s", why_H);
    if (o->nargs > 0)
        return cli_usage(cmd, "unexpected argument '%s'", o->args[0]);
    int nsrc = (scheme != NULL) + (o->map != NULL) + (equations != NULL);
    if (nsrc != 1)
        return cli_usage(cmd, nsrc == 0 ? "give a scheme: --scheme NAME, --map or --equations"
                                        : "give only one of --scheme, --map and --equations");
    return -1;
}

int cli_begin(char ***av, cli_opts *o, hl_system **sys, int argc, char **argv,
              const cli_command *cmd, const cli_begin_spec *spec, void *arg)
{
    *sys = NULL;
    *av = hl_xmalloc((size_t)(argc + 1) * sizeof **av);
    memcpy(*av, argv, (size_t)argc * sizeof **av);
    int ac = argc;
    int rc = cli_take_own(&ac, *av, spec->own, spec->nown, spec->found, arg, cmd);
    if (rc < 0)
        rc = cli_parse(o, ac, *av, spec->accept, cmd);
    if (rc < 0)
        rc = spec->check(arg, o, cmd);
    if (rc < 0) {
        rc = cli_system(sys, o, NULL); /* H alone defines the system */
        rc = rc == CLI_OK ? -1 : rc;
    }
    if (rc < 0 && hl_system_ndof(*sys) > spec->max_dof) {
        fprintf(stderr, "hamlie: error: %s handles at most %d degrees of freedom\n", cmd->name,
                spec->max_dof);
        rc = CLI_ERROR;
    }
    return rc;
}

void cli_put_arb(hl_buf *b, const arb_struct *x, long ndig)
{
    char *str = arb_get_str(x, ndig, ARB_STR_NO_RADIUS);
    hl_buf_puts(b, str);
    flint_free(str);
}

hl_status cli_make_scheme(hl_scheme **s, const char *map, const char *equations, const char *name,
                          int param, hl_system *sys, hl_error *err)
{
    hl_status st;
    if (map != NULL) {
        if ((st = hl_scheme_from_map(s, map, sys, err)) != HL_OK)
            hl_error_prefix(err, "in --map");
    } else if (equations != NULL) {
        if ((st = hl_scheme_from_equations(s, equations, sys, err)) != HL_OK)
            hl_error_prefix(err, "in --equations");
    } else
        st = hl_scheme_new(s, name, param, sys, err);
    return st;
}
