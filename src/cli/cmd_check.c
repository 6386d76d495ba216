/* hamlie check: integrals of motion ({I,H} = 0, paper §2), involution
 * ({I_i, I_j} = 0) and functional independence (rank of the Jacobian). */
#include <stdlib.h>

#include "cli/cli.h"

typedef struct check_result {
    int n;
    hl_alg *f;        /* the functions I_1..I_n, then H (n + 1 entries) */
    hl_alg *withH;    /* {I_k, H} */
    int *integral;    /* is I_k an integral? */
    hl_alg *inv;      /* n x n brackets {I_i, I_j} */
    int involution;
    int rank, rank_with_H, H_given; /* H_given: some I_k equals H */
} check_result;

static int compute(check_result *res, hl_system *sys, const cli_opts *o, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int n = o->nintegral, st = HL_OK;
    res->n = n;
    res->f = hl_alg_vec_new(n + 1, ctx);
    res->withH = hl_alg_vec_new(n, ctx);
    res->inv = hl_alg_vec_new(n * n, ctx);
    res->integral = hl_xcalloc((size_t)n, sizeof *res->integral);
    for (int k = 0; k < n && st == HL_OK; k++)
        if ((st = hl_system_read_phase(&res->f[k], sys, o->integral[k], err)) != HL_OK)
            hl_error_prefix(err, "in integral %d", k + 1);
    for (int k = 0; k < n && st == HL_OK; k++) {
        st = hl_check_integral(&res->integral[k], &res->withH[k], &res->f[k], sys, err);
        if (st == HL_OK && res->integral[k]) /* shown as 0, even when decided numerically */
            hl_alg_zero(&res->withH[k], ctx);
    }
    if (st == HL_OK)
        st = hl_check_involution(&res->involution, res->inv, res->f, n, sys, err);
    for (int k = 0; k < n * n && st == HL_OK; k++)
        if (hl_alg_is_zero(&res->inv[k], ctx))
            hl_alg_zero(&res->inv[k], ctx);
    if (st == HL_OK)
        st = hl_jacobian_rank(&res->rank, res->f, n, sys, err);
    if (st == HL_OK) {
        hl_alg_set(&res->f[n], hl_system_H(sys), ctx);
        st = hl_jacobian_rank(&res->rank_with_H, res->f, n + 1, sys, err);
    }
    for (int k = 0; k < n && st == HL_OK; k++)
        if (hl_alg_equal(&res->f[k], hl_system_H(sys), ctx))
            res->H_given = 1;
    return st;
}

static void result_clear(check_result *res, hl_alg_ctx *ctx)
{
    hl_alg_vec_free(res->f, res->n + 1, ctx);
    hl_alg_vec_free(res->withH, res->n, ctx);
    hl_alg_vec_free(res->inv, res->n * res->n, ctx);
    free(res->integral);
}

static int all_integrals(const check_result *res)
{
    for (int k = 0; k < res->n; k++)
        if (!res->integral[k])
            return 0;
    return 1;
}

static void write_json(hl_buf *out, const check_result *res, hl_system *sys, const cli_opts *o)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_pool *pool = hl_system_pool(sys);
    int n = res->n;
    hl_json j;
    char *s;
    hl_json_init_buf(&j, out);
    hl_json_object_begin(&j);
    hl_json_kv_string(&j, "command", "check");
    cli_json_system(&j, sys);
    hl_json_key(&j, "integrals");
    hl_json_array_begin(&j);
    for (int k = 0; k < n; k++) {
        hl_json_object_begin(&j);
        hl_json_kv_string(&j, "input", o->integral[k]);
        s = hl_format_alg(&res->f[k], ctx, pool, HL_STYLE_SYMPY);
        hl_json_kv_string(&j, "function", s);
        free(s);
        s = hl_format_alg(&res->withH[k], ctx, pool, HL_STYLE_SYMPY);
        hl_json_kv_string(&j, "bracket_with_H", s);
        free(s);
        hl_json_kv_bool(&j, "is_integral", res->integral[k]);
        hl_json_object_end(&j);
    }
    hl_json_array_end(&j);
    hl_json_key(&j, "involution");
    hl_json_object_begin(&j);
    hl_json_kv_bool(&j, "in_involution", res->involution);
    hl_json_key(&j, "brackets");
    hl_json_array_begin(&j);
    for (int a = 0; a < n; a++)
        for (int b = a + 1; b < n; b++) {
            hl_json_object_begin(&j);
            hl_json_kv_int(&j, "i", a + 1);
            hl_json_kv_int(&j, "j", b + 1);
            s = hl_format_alg(&res->inv[a * n + b], ctx, pool, HL_STYLE_SYMPY);
            hl_json_kv_string(&j, "value", s);
            free(s);
            hl_json_object_end(&j);
        }
    hl_json_array_end(&j);
    hl_json_object_end(&j);
    hl_json_key(&j, "independence");
    hl_json_object_begin(&j);
    hl_json_kv_int(&j, "rank", res->rank);
    hl_json_kv_int(&j, "count", n);
    hl_json_kv_bool(&j, "independent", res->rank == n);
    hl_json_object_end(&j);
    hl_json_key(&j, "hamiltonian");
    hl_json_object_begin(&j);
    hl_json_kv_bool(&j, "among_integrals", res->H_given);
    hl_json_kv_int(&j, "rank_with_H", res->rank_with_H);
    hl_json_kv_bool(&j, "dependent_on_integrals", res->rank_with_H == res->rank);
    hl_json_object_end(&j);
    hl_json_kv_bool(&j, "all_integrals", all_integrals(res));
    hl_json_kv_bool(&j, "numeric_zero_test", hl_alg_ctx_numeric_used(ctx));
    hl_json_object_end(&j);
    hl_json_finish(&j);
}

static void write_text(hl_buf *out, const check_result *res, hl_system *sys, const cli_opts *o)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_pool *pool = hl_system_pool(sys);
    int n = res->n, latex = o->format == CLI_LATEX;
    hl_style st = latex ? HL_STYLE_LATEX : HL_STYLE_TEXT;
    const char *cm = latex ? "% " : "";
    char *s;

    s = cli_show_input(o->H, sys, o->format);
    hl_buf_printf(out, "H = %s\n", s);
    free(s);
    for (int k = 0; k < n; k++) {
        s = cli_show_input(o->integral[k], sys, o->format);
        hl_buf_printf(out, latex ? "I_{%d} = %s\n" : "I%d = %s\n", k + 1, s);
        free(s);
    }
    for (int k = 0; k < n; k++) {
        s = hl_format_alg(&res->withH[k], ctx, pool, st);
        hl_buf_printf(out, latex ? "\\{I_{%d}, H\\} = %s" : "{I%d, H} = %s", k + 1, s);
        hl_buf_printf(out, "%s%s\n", latex ? "  % " : "    ",
                      res->integral[k] ? "an integral of motion" : "NOT an integral of motion");
        free(s);
    }
    for (int a = 0; a < n; a++)
        for (int b = a + 1; b < n; b++) {
            s = hl_format_alg(&res->inv[a * n + b], ctx, pool, st);
            hl_buf_printf(out, latex ? "\\{I_{%d}, I_{%d}\\} = %s\n" : "{I%d, I%d} = %s\n",
                          a + 1, b + 1, s);
            free(s);
        }
    if (n > 1)
        hl_buf_printf(out, "%sinvolution: %s\n", cm,
                      res->involution ? "yes, every pair commutes"
                                      : "no, some pair does not commute");
    hl_buf_printf(out, "%sindependence: the Jacobian of the %d function%s has rank %d: %s\n", cm,
                  n, n == 1 ? "" : "s", res->rank,
                  res->rank == n ? "functionally independent" : "functionally dependent");
    if (res->H_given)
        hl_buf_printf(out, "%sH: among the functions checked\n", cm);
    else if (res->rank_with_H == res->rank)
        hl_buf_printf(out, "%sH: not among the functions checked, but functionally dependent "
                      "on them (adding H keeps the rank %d)\n", cm, res->rank);
    else
        hl_buf_printf(out, "%sH: not among the functions checked, and independent of them "
                      "(with H the rank is %d)\n", cm, res->rank_with_H);
    int nint = 0;
    for (int k = 0; k < n; k++)
        nint += res->integral[k];
    if (nint == n)
        hl_buf_printf(out, "%sverdict: %s integrals of motion\n", cm,
                      n == 1 ? "it is one of the" : "all are");
    else
        hl_buf_printf(out, "%sverdict: %d of %d %s not an integral of motion\n", cm, n - nint, n,
                      n - nint == 1 ? "is" : "are");
    cli_numeric_note(out, sys, o->format);
}

static int check(const cli_opts *o, const cli_command *cmd, const char **extra)
{
    (void)extra; /* H alone defines the system: a symbol of an integral that
                  * is not in it is a mistake to point at, not a parameter */
    if (o->H == NULL)
        return cli_usage(cmd, "missing -H: check needs a Hamiltonian");
    if (o->nintegral == 0)
        return cli_usage(cmd, "nothing to check: give at least one --integral");
    if (o->nargs > 0)
        return cli_usage(cmd, "unexpected argument '%s' (give functions with --integral)",
                         o->args[0]);
    return -1;
}

static int run(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err)
{
    check_result res = {0};
    int st = compute(&res, sys, o, err);
    if (st == HL_OK) {
        if (o->format == CLI_JSON)
            write_json(out, &res, sys, o);
        else
            write_text(out, &res, sys, o);
        *code = all_integrals(&res) ? CLI_OK : CLI_FAILS;
    }
    result_clear(&res, hl_system_ctx(sys));
    return st;
}

int cmd_check(int argc, char **argv, const cli_command *self)
{
    static const cli_spec spec = {"check", CLI_OPT_H | CLI_OPT_INTEGRAL, check, run};
    return cli_main(argc, argv, &spec, self);
}
