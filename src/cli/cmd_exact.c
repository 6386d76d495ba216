/* hamlie exact: the exact scheme (paper §3) of a quadratic H in closed form,
 * and the checks that it is the flow; the option handling, and the
 * dispatch to the other modes (cmd_exact_impl.h). */
#include <stdlib.h>

#include <math.h>
#include <string.h>

#include "cli/cmd_exact_impl.h"
#include "hamlie/exact.h"
#include "hamlie/flow.h"
#include "hamlie/run.h"
#include "hamlie/scheme.h"
#include "hamlie/tape.h"


const char cmd_exact_help[] =
    "usage: hamlie exact -H FORMULA [--order N] [options]\n"
    "\n"
    "Print the exact scheme psi_D = exp(D g) in closed form, for H quadratic in\n"
    "the phase variables (any number of uncoupled pairs; parameters allowed):\n"
    "per pair cos and sin of w D (cosh and sinh when w^2 < 0, polynomials when\n"
    "w^2 = 0), w^2 = H_qq H_pp - H_qp^2, with the terms of a uniform field.\n"
    "Coupled pairs (rational coefficients): the same per normal mode, when\n"
    "the minimal polynomial of A^2 is squarefree with real roots and factors\n"
    "of degree <= 2 (A = J Hess H).\n"
    "Then check that it is the flow:\n"
    "  - its expansion in D equals the Lie series exp(D g) z to D^N (so every\n"
    "    error field v_2..v_N vanishes);\n"
    "  - it is canonical ({Q_i, P_j} = delta_ij, the others 0);\n"
    "  - two steps of D are one step of 2D, exactly.\n"
    "It is the catalog's scheme 'exact': hamlie run/errors --scheme exact.\n"
    "\n"
    "  -H, --hamiltonian F  the Hamiltonian (required)\n"
    "  -n, --order N        the order of the Lie-series check (1..40; default 8)\n"
    "  --pairs, --param     as for every command\n"
    "  --json               print a JSON object (schema: docs/json.md)\n"
    "  --latex              print the images as LaTeX\n"
    "  -h, --help           show this help\n"
    "\n"
    "  --steps              the seven steps of §3 for p^2/(2m) + V(q), V of degree\n"
    "                       <= 2: oscillator k q^2/2, uniform field g q, free\n"
    "                       particle (m, k, g numbers or symbols), each printed, then checked\n"
    "                       as an action-angle map and against the closed form\n"
    "  --action-angle MAP   'theta = ...; I = ...; q = ...; p = ...; nu = ...'\n"
    "                       (1 dof): verified ({theta,I} = 1, {I,H} = 0,\n"
    "                       {theta,H} = nu(I), q,p the inverse at points in all\n"
    "                       four quadrants: write the angle atan2(q, p), not\n"
    "                       atan(q/p), which is the angle for p > 0 only),\n"
    "                       then the scheme Q = q(theta + nu D, I), P = p(...)\n"
    "  --init q=..,p=..     1 dof, H not quadratic: the numeric exact scheme by\n"
    "                       the orbit (period T, frequency 2 pi/T) and 8 steps\n"
    "                       of --dt (default 0.5) against the Taylor integrator\n"
    "  --digits D           with --init: the same in Arb at D digits (16..1000):\n"
    "                       the period, 8 steps (each integrates D mod T), against\n"
    "                       the Arb integrator carried over the whole 8 D\n"
    "\n"
    "Exit status: 0 printed and every check holds; 1 a check fails (a wrong\n"
    "action-angle map: the failing condition is named); 2 usage or input\n"
    "error (H not quadratic without --init, coupled pairs without a closed\n"
    "form, unbounded orbit).\n"
    "Example: hamlie exact -H '(px^2+py^2)/2+(x^2+4*y^2)/2'\n"
    "Example: hamlie exact -H 'p^2/2 - cos(q)' --init q=1.3,p=0\n";

typedef struct exact_checks {
    int lie, canonical, group;
} exact_checks;

/* The catalog's "exact" expanded to D^n against exp(D g) z. */
static int check_lie(int *ok, hl_system *sys, int n, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int M = 2 * hl_system_ndof(sys), iD = hl_system_var_D(sys);
    hl_scheme *s = NULL;
    int st = hl_scheme_new(&s, "exact", 0, sys, err);
    hl_series *Z = calloc((size_t)M, sizeof *Z), ls;
    hl_alg z, lie;
    hl_alg_init(&z, ctx);
    hl_alg_init(&lie, ctx);
    hl_series_init(&ls, 0, ctx);
    for (int i = 0; i < M; i++)
        hl_series_init(&Z[i], 0, ctx);
    if (st == HL_OK)
        st = hl_scheme_expand(Z, s, n + 1, err);
    *ok = 1;
    for (int i = 0; i < M && st == HL_OK; i++) {
        hl_alg_gen(&z, i, ctx);
        if ((st = hl_lie_series(&lie, &z, n, sys, err)) == HL_OK)
            st = hl_series_from_alg(&ls, &lie, iD, n + 1, ctx, err);
        for (int k = 0; k <= n && st == HL_OK; k++)
            *ok = *ok && hl_alg_equal(&Z[i].c[k], &ls.c[k], ctx);
    }
    for (int i = 0; i < M; i++)
        hl_series_clear(&Z[i], ctx);
    free(Z);
    hl_series_clear(&ls, ctx);
    hl_alg_clear(&z, ctx);
    hl_alg_clear(&lie, ctx);
    hl_scheme_free(s);
    return st;
}

/* psi_D o psi_D == psi_2D, component by component. */
static int check_group(int *ok, const hl_alg *img, hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int M = 2 * hl_system_ndof(sys), iD = hl_system_var_D(sys), st = HL_OK;
    int *vars = malloc((size_t)M * sizeof *vars);
    for (int i = 0; i < M; i++)
        vars[i] = i;
    hl_alg twice, twoD, r;
    hl_alg_init(&twice, ctx);
    hl_alg_init(&twoD, ctx);
    hl_alg_init(&r, ctx);
    hl_alg_gen(&twoD, iD, ctx);
    hl_alg_add(&twoD, &twoD, &twoD, ctx);
    *ok = 1;
    for (int i = 0; i < M && st == HL_OK; i++) {
        if ((st = hl_alg_subst(&twice, &img[i], M, vars, img, ctx, err)) == HL_OK)
            st = hl_alg_subst(&r, &img[i], 1, &iD, &twoD, ctx, err);
        *ok = *ok && st == HL_OK && hl_alg_equal(&twice, &r, ctx);
    }
    free(vars);
    hl_alg_clear(&twice, ctx);
    hl_alg_clear(&twoD, ctx);
    hl_alg_clear(&r, ctx);
    return st;
}

static void write_out(hl_buf *out, const hl_alg *img, const exact_checks *c, int n,
                      hl_system *sys, const cli_opts *o)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_pool *pool = hl_system_pool(sys);
    int M = 2 * hl_system_ndof(sys);
    char *modes = NULL; /* coupled pairs: the normal modes, else NULL */
    if (hl_scheme_linear_modes(&modes, sys, NULL) != HL_OK)
        modes = NULL;
    if (o->format == CLI_JSON) {
        hl_json j;
        hl_json_init_buf(&j, out);
        hl_json_object_begin(&j);
        hl_json_kv_string(&j, "command", "exact");
        cli_json_system(&j, sys);
        hl_json_key(&j, "map");
        hl_json_object_begin(&j);
        for (int i = 0; i < M; i++) {
            char *nm = cli_image_name(sys, i), *s = hl_format_alg(&img[i], ctx, pool,
                                                                  HL_STYLE_SYMPY);
            hl_json_kv_string(&j, nm, s);
            free(nm), free(s);
        }
        hl_json_object_end(&j);
        hl_json_kv_int(&j, "order_checked", n);
        hl_json_kv_bool(&j, "equals_lie_series", c->lie);
        hl_json_kv_bool(&j, "canonical", c->canonical);
        hl_json_kv_bool(&j, "two_steps_equal_one_of_2D", c->group);
        hl_json_kv_bool(&j, "numeric_zero_test", hl_alg_ctx_numeric_used(ctx));
        if (modes != NULL)
            hl_json_kv_string(&j, "normal_modes", modes);
        hl_json_object_end(&j);
        hl_json_finish(&j);
        free(modes);
        return;
    }
    int latex = o->format == CLI_LATEX;
    if (modes != NULL)
        hl_buf_printf(out, "normal modes: %s\n", modes);
    free(modes);
    hl_buf_puts(out, "exact scheme:\n");
    for (int i = 0; i < M; i++) {
        char *nm = cli_image_name(sys, i);
        char *s = hl_format_alg(&img[i], ctx, pool, latex ? HL_STYLE_LATEX : HL_STYLE_TEXT);
        hl_buf_printf(out, "  %s = %s\n", nm, s);
        free(nm), free(s);
    }
    const char *D = hl_system_step(sys);
    hl_buf_printf(out, "equals exp(%s g) z to %s^%d (v_2..v_%d vanish): %s\n", D, D, n, n,
                  c->lie ? "yes" : "NO");
    hl_buf_printf(out, "canonical: %s\n", c->canonical ? "yes" : "NO");
    hl_buf_printf(out, "two steps of %s = one step of 2%s: %s\n", D, D, c->group ? "yes" : "NO");
    cli_numeric_note(out, sys, o->format);
}

static int run_mode(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err)
{
    if (exact_mode.aa != NULL)
        return exact_run_aa(out, code, sys, o, err);
    if (exact_mode.steps)
        return exact_run_steps(out, code, sys, o, err);
    return exact_run_numeric(out, code, sys, o, err);
}

/* The modes in JSON: their text into a scratch buffer, their fields into
 * the document (docs/json.md, "exact"). */
static int run_json(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err)
{
    hl_json j;
    hl_buf text;
    hl_buf_init(&text);
    hl_json_init_buf(&j, out);
    hl_json_object_begin(&j);
    hl_json_kv_string(&j, "command", "exact");
    cli_json_system(&j, sys);
    const exact_mode_state *m = &exact_mode;
    hl_json_kv_string(&j, "mode", m->aa != NULL ? "action_angle" : m->steps ? "steps" : "init");
    if (m->aa != NULL || m->steps) { /* the names the formulas use besides the system's */
        hl_json_key(&j, "formula_symbols");
        hl_json_array_begin(&j);
        static const char *const names[] = {"I", "theta", "eps", "gamma", "nu", "m", "k", "g"};
        for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
            hl_json_string(&j, names[i]);
        hl_json_array_end(&j);
    }
    exact_mode.j = &j;
    exact_mode.depth = 0;
    int st = run_mode(&text, code, sys, o, err);
    exact_json_close_to(0);
    exact_mode.j = NULL;
    hl_json_kv_bool(&j, "all_checks_hold", *code == CLI_OK);
    hl_json_kv_bool(&j, "numeric_zero_test", hl_alg_ctx_numeric_used(hl_system_ctx(sys)));
    hl_json_object_end(&j);
    hl_json_finish(&j);
    hl_buf_clear(&text);
    return st;
}

static int run(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err)
{
    if (exact_mode.aa != NULL || exact_mode.steps || exact_mode.init != NULL)
        return o->format == CLI_JSON ? run_json(out, code, sys, o, err)
                                     : run_mode(out, code, sys, o, err);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int M = 2 * hl_system_ndof(sys), n = o->have_order ? o->order : 8;
    hl_alg *img = hl_alg_vec_new(M, ctx), *br = hl_alg_vec_new(M * M, ctx);
    exact_checks c = {0, 0, 0};
    int st = hl_scheme_linear_flow(img, sys, err);
    if (st == HL_OK)
        st = check_lie(&c.lie, sys, n, err);
    if (st == HL_OK)
        st = hl_check_canonical(&c.canonical, br, img, sys, err);
    if (st == HL_OK)
        st = check_group(&c.group, img, sys, err);
    if (st == HL_OK) {
        write_out(out, img, &c, n, sys, o);
        *code = c.lie && c.canonical && c.group ? CLI_OK : CLI_FAILS;
    }
    hl_alg_vec_free(img, M, ctx);
    hl_alg_vec_free(br, M * M, ctx);
    return st;
}

static int check(const cli_opts *o, const cli_command *cmd, const char **extra)
{
    (void)extra; /* H alone defines the system */
    if (o->H == NULL)
        return cli_usage(cmd, "missing -H: the exact scheme needs a Hamiltonian");
    if (o->nargs > 0)
        return cli_usage(cmd, "unexpected argument '%s'", o->args[0]);
    if (o->have_order && (o->order < 1 || o->order > 40))
        return cli_usage(cmd, "--order must be from 1 to 40, not %d", o->order);
    return -1;
}

static void found_opt(void *arg, int k, const char *value)
{
    (void)arg;
    if (k == 0)
        exact_mode.init = value;
    else if (k == 1)
        exact_mode.aa = value;
    else if (k == 2)
        exact_mode.dt = value;
    else if (k == 3)
        exact_mode.steps = 1;
    else
        exact_mode.digits = value;
}

int cmd_exact(int argc, char **argv, const cli_command *self)
{
    static const cli_spec spec = {"exact", CLI_OPT_H | CLI_OPT_ORDER, check, run};
    static const cli_own own[] = {
        {"--init", 0}, {"--action-angle", 0}, {"--dt", 0}, {"--steps", 1}, {"--digits", 0}};
    memset(&exact_mode, 0, sizeof exact_mode);
    char **av = hl_xmalloc((size_t)(argc + 1) * sizeof *av);
    memcpy(av, argv, (size_t)(argc + 1) * sizeof *av);
    int ac = argc;
    int rc = cli_take_own(&ac, av, own, 5, found_opt, NULL, self);
    if (rc < 0)
        rc = cli_main(ac, av, &spec, self);
    free(av);
    return rc;
}
