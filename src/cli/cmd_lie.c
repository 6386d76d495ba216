/* hamlie lie: the Lie series exp(D g) phi = sum_k D^k/k! g^k phi (paper §2). */
#include <stdio.h>
#include <stdlib.h>

#include "cli/cli.h"

/* One function phi: its text (or variable name) and its terms g^k phi. */
typedef struct lie_item {
    const char *text;
    int is_var;
    hl_alg *terms;
} lie_item;

static void write_item(hl_buf *out, hl_json *j, const lie_item *it, int order, hl_system *sys,
                       const cli_opts *o)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_pool *pool = hl_system_pool(sys);
    if (o->format == CLI_JSON) {
        hl_alg c;
        fmpq_t f;
        hl_alg_init(&c, ctx);
        fmpq_init(f);
        hl_json_object_begin(j);
        hl_json_kv_string(j, "input", it->text);
        char *s = hl_format_alg(&it->terms[0], ctx, pool, HL_STYLE_SYMPY);
        hl_json_kv_string(j, "function", s);
        free(s);
        s = hl_format_series(it->terms, order, hl_system_step(sys), 1, ctx, pool,
                             HL_STYLE_SYMPY);
        hl_json_kv_string(j, "series", s);
        free(s);
        hl_json_key(j, "coefficients");
        hl_json_array_begin(j);
        fmpq_one(f);
        for (int k = 0; k <= order && !cli_interrupted(); k++) { /* big: Ctrl-C stops */
            if (k > 0) {
                fmpz_mul_ui(fmpq_denref(f), fmpq_denref(f), (ulong)k); /* f = 1/k! */
            }
            hl_alg_scalar_mul_fmpq(&c, &it->terms[k], f, ctx);
            s = hl_format_alg(&c, ctx, pool, HL_STYLE_SYMPY);
            hl_json_string(j, s);
            free(s);
        }
        hl_json_array_end(j);
        if (o->terms) {
            hl_json_key(j, "terms");
            hl_json_array_begin(j);
            for (int k = 0; k <= order; k++) {
                s = hl_format_alg(&it->terms[k], ctx, pool, HL_STYLE_SYMPY);
                hl_json_string(j, s);
                free(s);
            }
            hl_json_array_end(j);
        }
        hl_json_object_end(j);
        hl_alg_clear(&c, ctx);
        fmpq_clear(f);
        return;
    }
    int latex = o->format == CLI_LATEX;
    hl_style st = latex ? HL_STYLE_LATEX : HL_STYLE_TEXT;
    char *phi = it->is_var ? (latex ? hl_symbol_latex(it->text) : hl_xstrdup(it->text))
                           : cli_show_input(it->text, sys, o->format);
    const char *wrap = it->is_var ? "%s" : (latex ? "\\left(%s\\right)" : "(%s)");
    const char *D = hl_system_step(sys);
    char *s = hl_format_series(it->terms, order, D, 1, ctx, pool, st);
    char *Dl = latex ? hl_symbol_latex(D) : hl_xstrdup(D);
    hl_buf_printf(out, latex ? "\\exp(%s\\,\\mathfrak{g})\\, " : "exp(%s 𝔤) ", Dl);
    hl_buf_printf(out, wrap, phi);
    hl_buf_printf(out, " = %s", s);
    hl_buf_printf(out, latex ? " + O(%s^{%d})\n" : " + O(%s^%d)\n", Dl, order + 1);
    free(Dl);
    free(s);
    if (o->terms)
        for (int k = 0; k <= order; k++) {
            s = hl_format_alg(&it->terms[k], ctx, pool, st);
            hl_buf_printf(out, latex ? "  \\mathfrak{g}^{%d} " : "  𝔤^%d ", k);
            hl_buf_printf(out, wrap, phi);
            hl_buf_printf(out, " = %s\n", s);
            free(s);
        }
    free(phi);
}

/* From this order the series says what it computes before it starts: it
 * may take a while (Kepler to order 200: minutes). */
#define PLAN_ORDER 60

static int run(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err)
{
    int order = o->have_order ? o->order : 4;
    (void)code; /* always CLI_OK: nothing is checked */
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), n = o->nof ? o->nof : 2 * N, st = HL_OK;
    lie_item *it = hl_xcalloc((size_t)n, sizeof *it);
    hl_alg phi;
    hl_alg_init(&phi, ctx);
    for (int i = 0; i < n; i++)
        it[i].terms = hl_alg_vec_new(order + 1 > 0 ? order + 1 : 1, ctx);
    cli_progress p;
    cli_progress_begin(&p, "lie", "order", o->progress);
    p.estimate = 0; /* each order costs more than the one before */
    if (o->progress == CLI_PROGRESS_ON || order >= PLAN_ORDER)
        cli_progress_say(&p, "the Lie series of %d function%s to order %d", n, n > 1 ? "s" : "",
                         order);
    for (int i = 0; i < n && st == HL_OK; i++) {
        if (o->nof) {
            it[i].text = o->of[i];
            if ((st = hl_system_read_phase(&phi, sys, o->of[i], err)) != HL_OK) {
                hl_error_prefix(err, "in --of");
                break;
            }
        } else {
            it[i].is_var = 1;
            it[i].text = i < N ? hl_system_coord(sys, i) : hl_system_momentum(sys, i - N);
            hl_alg_gen(&phi, i, ctx);
        }
        snprintf(p.detail, sizeof p.detail, "for %.40s (%d of %d)", it[i].text, i + 1, n);
        st = hl_lie_terms_watched(it[i].terms, &phi, order, sys, cli_progress_fn, &p, err);
    }
    if (st == HL_OK) {
        hl_json j;
        if (o->format == CLI_JSON) {
            hl_json_init_buf(&j, out);
            hl_json_object_begin(&j);
            hl_json_kv_string(&j, "command", "lie");
            cli_json_system(&j, sys);
            hl_json_kv_int(&j, "order", order);
            hl_json_key(&j, "series");
            hl_json_array_begin(&j);
        }
        for (int i = 0; i < n && !cli_interrupted(); i++)
            write_item(out, &j, &it[i], order, sys, o);
        if (o->format == CLI_JSON) {
            hl_json_array_end(&j);
            hl_json_kv_bool(&j, "numeric_zero_test", hl_alg_ctx_numeric_used(ctx));
            hl_json_object_end(&j);
            hl_json_finish(&j);
        } else
            cli_numeric_note(out, sys, o->format);
        /* an interrupt while the result was formatted: nothing is printed */
        if (cli_interrupted())
            st = hl_error_set(err, HL_ESTOP, NULL, -1, 0,
                              "while the result was written (nothing printed)");
    }
    cli_progress_end(&p);
    for (int i = 0; i < n; i++)
        hl_alg_vec_free(it[i].terms, order + 1 > 0 ? order + 1 : 1, ctx);
    free(it);
    hl_alg_clear(&phi, ctx);
    return st;
}

static int check(const cli_opts *o, const cli_command *cmd, const char **extra)
{
    (void)extra; /* H alone defines the system */
    if (o->H == NULL)
        return cli_usage(cmd, "missing -H: the Lie series needs a Hamiltonian");
    if (o->nargs > 0)
        return cli_usage(cmd, "unexpected argument '%s' (give functions with --of)", o->args[0]);
    if (o->have_order && o->order < 0)
        return cli_usage(cmd, "--order must be at least 0, not %d", o->order);
    if (o->have_order && o->order > HL_LIE_MAX_ORDER) {
        fprintf(stderr, "hamlie: error: --order %d refused: the Lie series is limited to "
                        "order %d\n", o->order, HL_LIE_MAX_ORDER);
        return CLI_ERROR;
    }
    return -1;
}

int cmd_lie(int argc, char **argv, const cli_command *self)
{
    static const cli_spec spec = {"lie", CLI_OPT_H | CLI_OPT_ORDER | CLI_OPT_OF | CLI_OPT_TERMS |
                                             CLI_OPT_PROGRESS,
                                  check, run};
    return cli_main(argc, argv, &spec, self);
}
