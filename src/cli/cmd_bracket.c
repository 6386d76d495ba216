/* hamlie bracket: {A, B} (paper §2, eq. PB). */
#include <stdlib.h>

#include "cli/cli.h"

static int run(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err)
{
    (void)code; /* always CLI_OK: nothing is checked */
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_pool *pool = hl_system_pool(sys);
    hl_alg a, b, r;
    int st;
    hl_alg_init(&a, ctx);
    hl_alg_init(&b, ctx);
    hl_alg_init(&r, ctx);
    if ((st = hl_system_read_phase(&a, sys, o->args[0], err)) != HL_OK)
        hl_error_prefix(err, "in A");
    else if ((st = hl_system_read_phase(&b, sys, o->args[1], err)) != HL_OK)
        hl_error_prefix(err, "in B");
    else
        st = hl_bracket(&r, &a, &b, sys, err);
    if (st == HL_OK) {
        int zero = hl_alg_is_zero(&r, ctx);
        if (zero) /* shown as 0, even when decided numerically (then said so) */
            hl_alg_zero(&r, ctx);
        if (o->format == CLI_JSON) {
            hl_json j;
            hl_json_init_buf(&j, out);
            hl_json_object_begin(&j);
            hl_json_kv_string(&j, "command", "bracket");
            cli_json_system(&j, sys);
            hl_json_kv_string(&j, "a_input", o->args[0]);
            hl_json_kv_string(&j, "b_input", o->args[1]);
            char *s = hl_format_alg(&a, ctx, pool, HL_STYLE_SYMPY);
            hl_json_kv_string(&j, "a", s);
            free(s);
            s = hl_format_alg(&b, ctx, pool, HL_STYLE_SYMPY);
            hl_json_kv_string(&j, "b", s);
            free(s);
            s = hl_format_alg(&r, ctx, pool, HL_STYLE_SYMPY);
            hl_json_kv_string(&j, "bracket", s);
            free(s);
            hl_json_kv_bool(&j, "is_zero", zero);
            hl_json_kv_bool(&j, "numeric_zero_test", hl_alg_ctx_numeric_used(ctx));
            hl_json_object_end(&j);
            hl_json_finish(&j);
        } else {
            int latex = o->format == CLI_LATEX;
            char *sa = cli_show_input(o->args[0], sys, o->format);
            char *sb = cli_show_input(o->args[1], sys, o->format);
            char *sr = hl_format_alg(&r, ctx, pool, latex ? HL_STYLE_LATEX : HL_STYLE_TEXT);
            hl_buf_printf(out, latex ? "\\{%s, %s\\} = %s\n" : "{%s, %s} = %s\n", sa, sb, sr);
            free(sa), free(sb), free(sr);
            cli_numeric_note(out, sys, o->format);
        }
    }
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&b, ctx);
    hl_alg_clear(&r, ctx);
    return st;
}

/* Without -H, A and B define the variables. */
static int check(const cli_opts *o, const cli_command *cmd, const char **extra)
{
    if (o->nargs != 2)
        return cli_usage(cmd, "bracket wants two functions A and B, got %d argument%s",
                         o->nargs, o->nargs == 1 ? "" : "s");
    extra[0] = o->args[0];
    extra[1] = o->args[1];
    return -1;
}

int cmd_bracket(int argc, char **argv, const cli_command *self)
{
    static const cli_spec spec = {"bracket", CLI_OPT_H, check, run};
    return cli_main(argc, argv, &spec, self);
}
