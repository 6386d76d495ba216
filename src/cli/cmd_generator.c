/* hamlie generator: g = sum_j dH/dp_j d/dq_j - dH/dq_j d/dp_j (paper §2). */
#include <stdlib.h>

#include "cli/cli.h"

static int run(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err)
{
    (void)code; /* always CLI_OK: nothing is checked */
    cli_format f = o->format;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_pool *pool = hl_system_pool(sys);
    int n = hl_system_ndof(sys);
    hl_alg *c = hl_alg_vec_new(2 * n, ctx); /* xi_1..xi_N, eta_1..eta_N */
    int st = hl_generator(c, c + n, sys, err);
    if (st == HL_OK) {
        const char **names = hl_xmalloc((size_t)(2 * n) * sizeof *names);
        for (int j = 0; j < n; j++) {
            names[j] = hl_system_coord(sys, j);
            names[n + j] = hl_system_momentum(sys, j);
        }
        if (f == CLI_JSON) {
            hl_json j;
            hl_json_init_buf(&j, out);
            hl_json_object_begin(&j);
            hl_json_kv_string(&j, "command", "generator");
            cli_json_system(&j, sys);
            hl_json_key(&j, "generator");
            hl_json_vector_field(&j, 2 * n, names, c, ctx, pool, HL_STYLE_SYMPY);
            hl_json_kv_bool(&j, "numeric_zero_test", hl_alg_ctx_numeric_used(ctx));
            hl_json_object_end(&j);
            hl_json_finish(&j);
        } else {
            char *s = hl_format_vector_field(2 * n, names, c, ctx, pool,
                                             f == CLI_LATEX ? HL_STYLE_LATEX : HL_STYLE_TEXT);
            hl_buf_printf(out, f == CLI_LATEX ? "\\mathfrak{g} = %s\n" : "𝔤 = %s\n", s);
            free(s);
            cli_numeric_note(out, sys, f);
        }
        free(names);
    }
    hl_alg_vec_free(c, 2 * n, ctx);
    return st;
}

static int check(const cli_opts *o, const cli_command *cmd, const char **extra)
{
    (void)extra;
    if (o->H == NULL)
        return cli_usage(cmd, "missing -H: the generator needs a Hamiltonian");
    if (o->nargs > 0)
        return cli_usage(cmd, "unexpected argument '%s'", o->args[0]);
    return -1;
}

int cmd_generator(int argc, char **argv, const cli_command *self)
{
    static const cli_spec spec = {"generator", CLI_OPT_H, check, run};
    return cli_main(argc, argv, &spec, self);
}
