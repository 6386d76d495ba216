/* hamlie canonical: is the map (Q, P) = f(q, p; D) canonical for every D,
 * {Q_i, P_j} = delta_ij, {Q_i, Q_j} = {P_i, P_j} = 0 (paper §2)? */
#include <stdlib.h>

#include "cli/cli.h"

typedef struct pair_ix { int a, b; long want; } pair_ix;

/* The brackets to show, in the order {Q_i,P_j}, {Q_i,Q_j}, {P_i,P_j}. */
static int list_pairs(pair_ix *v, int N)
{
    int m = 0;
    for (int i = 0; i < N; i++)
        for (int j = 0; j < N; j++)
            v[m++] = (pair_ix){i, N + j, i == j};
    for (int i = 0; i < N; i++)
        for (int j = i + 1; j < N; j++)
            v[m++] = (pair_ix){i, j, 0};
    for (int i = 0; i < N; i++)
        for (int j = i + 1; j < N; j++)
            v[m++] = (pair_ix){N + i, N + j, 0};
    return m;
}

static void write_out(hl_buf *out, hl_system *sys, const hl_alg *img, hl_alg *br,
                      int canonical, cli_format f)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_pool *pool = hl_system_pool(sys);
    int N = hl_system_ndof(sys), N2 = 2 * N;
    pair_ix *v = hl_xmalloc((size_t)(N2 * N2 + 1) * sizeof *v);
    int m = list_pairs(v, N);
    char **names = hl_xmalloc((size_t)N2 * sizeof *names);
    hl_alg d;
    hl_alg_init(&d, ctx);
    for (int a = 0; a < N2; a++)
        names[a] = cli_image_name(sys, a);

    hl_json j;
    if (f == CLI_JSON) {
        hl_json_init_buf(&j, out);
        hl_json_object_begin(&j);
        hl_json_kv_string(&j, "command", "canonical");
        cli_json_system(&j, sys);
        hl_json_key(&j, "map");
        hl_json_array_begin(&j);
    }
    for (int a = 0; a < N2; a++) {
        const char *var = a < N ? hl_system_coord(sys, a) : hl_system_momentum(sys, a - N);
        char *s = hl_format_alg(&img[a], ctx, pool,
                                f == CLI_JSON ? HL_STYLE_SYMPY
                                : f == CLI_LATEX ? HL_STYLE_LATEX : HL_STYLE_TEXT);
        if (f == CLI_JSON) {
            hl_json_object_begin(&j);
            hl_json_kv_string(&j, "variable", var);
            hl_json_kv_string(&j, "name", names[a]);
            hl_json_kv_string(&j, "image", s);
            hl_json_object_end(&j);
        } else if (f == CLI_LATEX) {
            char *l = hl_symbol_latex(names[a]);
            hl_buf_printf(out, "%s = %s\n", l, s);
            free(l);
        } else
            hl_buf_printf(out, "%s = %s\n", names[a], s);
        free(s);
    }
    if (f == CLI_JSON) {
        hl_json_array_end(&j);
        hl_json_key(&j, "brackets");
        hl_json_array_begin(&j);
    }
    for (int k = 0; k < m; k++) {
        hl_alg *x = &br[v[k].a * N2 + v[k].b];
        hl_alg_set_si(&d, v[k].want, ctx);
        hl_alg_sub(&d, x, &d, ctx);
        int ok = hl_alg_is_zero(&d, ctx);
        if (ok) /* show the exact value, even when the zero was decided numerically */
            hl_alg_set_si(x, v[k].want, ctx);
        if (f == CLI_JSON) {
            char *s = hl_format_alg(x, ctx, pool, HL_STYLE_SYMPY);
            hl_json_object_begin(&j);
            hl_json_kv_string(&j, "a", names[v[k].a]);
            hl_json_kv_string(&j, "b", names[v[k].b]);
            hl_json_kv_string(&j, "value", s);
            hl_json_kv_int(&j, "expected", v[k].want);
            hl_json_kv_bool(&j, "ok", ok);
            hl_json_object_end(&j);
            free(s);
        } else if (f == CLI_LATEX) {
            char *s = hl_format_alg(x, ctx, pool, HL_STYLE_LATEX);
            char *la = hl_symbol_latex(names[v[k].a]), *lb = hl_symbol_latex(names[v[k].b]);
            hl_buf_printf(out, "\\{%s, %s\\} = %s", la, lb, s);
            if (!ok)
                hl_buf_printf(out, "  %% should be %ld", v[k].want);
            hl_buf_puts(out, "\n");
            free(s), free(la), free(lb);
        } else {
            char *s = hl_format_alg(x, ctx, pool, HL_STYLE_TEXT);
            hl_buf_printf(out, "{%s, %s} = %s", names[v[k].a], names[v[k].b], s);
            if (!ok)
                hl_buf_printf(out, "    should be %ld", v[k].want);
            hl_buf_puts(out, "\n");
            free(s);
        }
    }
    if (f == CLI_JSON) {
        hl_json_array_end(&j);
        hl_json_kv_bool(&j, "canonical", canonical);
        hl_json_kv_bool(&j, "numeric_zero_test", hl_alg_ctx_numeric_used(ctx));
        hl_json_object_end(&j);
        hl_json_finish(&j);
    } else {
        if (canonical)
            hl_buf_printf(out, "%scanonical for every %s\n", f == CLI_LATEX ? "% " : "",
                          hl_system_step(sys));
        else
            hl_buf_printf(out, "%snot canonical\n", f == CLI_LATEX ? "% " : "");
        cli_numeric_note(out, sys, f);
    }
    for (int a = 0; a < N2; a++)
        free(names[a]);
    free(names);
    free(v);
    hl_alg_clear(&d, ctx);
}

/* Without -H, the map's right sides define the variables. */
static int check(const cli_opts *o, const cli_command *cmd, const char **extra)
{
    if (o->map == NULL)
        return cli_usage(cmd, "missing --map: say the images, e.g. --map 'X = x + D*p; P = p'");
    if (o->nargs > 0)
        return cli_usage(cmd, "unexpected argument '%s'", o->args[0]);
    extra[0] = o->map;
    return -1;
}

static int run(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N2 = 2 * hl_system_ndof(sys), canonical = 0, st;
    hl_alg *img = hl_alg_vec_new(N2, ctx), *br = hl_alg_vec_new(N2 * N2, ctx);
    if ((st = hl_system_read_map(img, sys, o->map, err)) == HL_OK)
        st = hl_check_canonical(&canonical, br, img, sys, err);
    if (st == HL_OK) {
        write_out(out, sys, img, br, canonical, o->format);
        *code = canonical ? CLI_OK : CLI_FAILS;
    } else if (err->src == o->map)
        hl_error_prefix(err, "in --map");
    hl_alg_vec_free(img, N2, ctx);
    hl_alg_vec_free(br, N2 * N2, ctx);
    return st;
}

int cmd_canonical(int argc, char **argv, const cli_command *self)
{
    static const cli_spec spec = {"canonical", CLI_OPT_H | CLI_OPT_MAP, check, run};
    return cli_main(argc, argv, &spec, self);
}
