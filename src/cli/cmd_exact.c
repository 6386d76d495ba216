/* hamlie exact: the exact scheme (paper §3) of a quadratic H in closed form,
 * and the checks that it is the flow. */
#include <stdlib.h>

#include <math.h>
#include <string.h>

#include "cli/cli.h"
#include "hamlie/exact.h"
#include "hamlie/flow.h"
#include "hamlie/run.h"
#include "hamlie/scheme.h"
#include "hamlie/tape.h"

/* The command's own options (taken out of argv before cli_parse). */
static struct {
    const char *init, *aa, *dt, *digits;
    int steps;
    /* --json with --steps, --action-angle, --init: the text goes to a
     * scratch buffer and what it says goes to j as fields (j_*, put_*):
     * sections are objects (the steps an array of objects) under the top
     * level, kinds[] the '{' or '[' of each one open */
    hl_json *j;
    int depth;
    char kinds[4];
} ex;

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

/* ---- issue 6 modes --------------------------------------------------------- */

/* Evaluate an alg at (q, p, D) numerically (the other symbols must not
 * occur). */
static double eval_at(const hl_alg *a, hl_system *sys, double q, double p, double D,
                      hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int nb = hl_alg_ctx_nbase(ctx);
    arb_ptr v = _arb_vec_init(nb);
    arb_t r;
    arb_init(r);
    arb_set_d(v + hl_system_var_q(sys, 0), q);
    arb_set_d(v + hl_system_var_p(sys, 0), p);
    arb_set_d(v + hl_system_var_D(sys), D);
    /* symbolic parameters: the sample values of hl_exact_aa_verify */
    for (int i = 0; i < hl_system_nparams(sys); i++)
        arb_set_d(v + hl_alg_ctx_index(ctx, hl_system_param(sys, i)), 1.3 + 0.17 * i);
    double x = NAN;
    if (hl_alg_eval_arb(r, a, v, 128, ctx, err) == HL_OK)
        x = arf_get_d(arb_midref(r), ARF_RND_NEAR);
    arb_clear(r);
    _arb_vec_clear(v, nb);
    return x;
}

/* ---- --json for the modes that print as they go ------------------------------ */

static void j_push(char kind)
{
    if (kind == '[')
        hl_json_array_begin(ex.j);
    else
        hl_json_object_begin(ex.j);
    ex.kinds[ex.depth++] = kind;
}

static void j_close_to(int depth)
{
    while (ex.depth > depth) {
        if (ex.kinds[--ex.depth] == '[')
            hl_json_array_end(ex.j);
        else
            hl_json_object_end(ex.j);
    }
}

/* A new object under the top level (the previous section closed). */
static void j_section(const char *key)
{
    if (ex.j == NULL)
        return;
    j_close_to(0);
    hl_json_key(ex.j, key);
    j_push('{');
}

static void j_bool(const char *key, int v)
{
    if (ex.j != NULL)
        hl_json_kv_bool(ex.j, key, v);
}

static void j_double(const char *key, double v)
{
    if (ex.j != NULL)
        hl_json_kv_double(ex.j, key, v);
}

static void j_string(const char *key, const char *v)
{
    if (ex.j != NULL)
        hl_json_kv_string(ex.j, key, v);
}

/* A formula typed in hamlie's syntax as SymPy reads it (as it is when it
 * does not parse, which the tests would catch). */
static char *sympy_of(const char *text, hl_system *sys)
{
    const hl_expr *e = NULL;
    hl_error e2;
    if (hl_parse(&e, hl_system_pool(sys), text, &e2) == HL_OK)
        return hl_expr_print(e, HL_STYLE_SYMPY);
    return hl_xstrdup(text);
}

/* A formula in hamlie's syntax, in JSON only (put_formula also prints it). */
static void j_formula(const char *key, const char *text, hl_system *sys)
{
    if (ex.j == NULL)
        return;
    char *s = sympy_of(text, sys);
    hl_json_kv_string(ex.j, key, s);
    free(s);
}

/* An object under the current section: the final state of --init. */
static void j_object(const char *key)
{
    if (ex.j == NULL)
        return;
    hl_json_key(ex.j, key);
    j_push('{');
}

static void j_arb(const char *key, const arb_struct *x, long ndig)
{
    if (ex.j == NULL)
        return;
    char *s = arb_get_str(x, ndig, ARB_STR_NO_RADIUS);
    hl_json_kv_string(ex.j, key, s);
    flint_free(s);
}

/* "step 3: the generating function ...\n": the line, or in JSON an element
 * {"step": 3, "what": "the generating function ...", "formulas": {...}} of
 * the array "steps", whose formulas put_formula then adds. */
static void put_step(hl_buf *out, const char *line)
{
    int n = 0, at = 0;
    if (ex.j == NULL || sscanf(line, "step %d: %n", &n, &at) != 1 || at == 0) {
        hl_buf_puts(out, line);
        return;
    }
    if (ex.depth == 0 || ex.kinds[0] != '[') {
        j_close_to(0);
        hl_json_key(ex.j, "steps");
        j_push('[');
    }
    j_close_to(1);
    j_push('{');
    hl_json_kv_int(ex.j, "step", n);
    char *what = hl_xstrdup(line + at);
    what[strcspn(what, "\n")] = '\0';
    hl_json_kv_string(ex.j, "what", what);
    free(what);
    hl_json_key(ex.j, "formulas");
    j_push('{');
}

static void put_formula(hl_buf *out, const char *lhs, const char *rhs, hl_system *sys,
                        const cli_opts *o)
{
    if (ex.j != NULL) {
        char *s = sympy_of(rhs, sys);
        hl_json_kv_string(ex.j, lhs, s);
        free(s);
        return;
    }
    if (o->format == CLI_LATEX) {
        const hl_expr *e = NULL;
        hl_error e2;
        if (hl_parse(&e, hl_system_pool(sys), rhs, &e2) == HL_OK) {
            char *s = hl_expr_print(e, HL_STYLE_LATEX);
            const char *l = strcmp(lhs, "theta") == 0   ? "\\theta"
                            : strcmp(lhs, "gamma") == 0 ? "\\gamma"
                            : strcmp(lhs, "nu") == 0    ? "\\nu"
                                                        : lhs;
            hl_buf_printf(out, "  $%s = %s$\n", l, s);
            free(s);
            return;
        }
    }
    hl_buf_printf(out, "  %s = %s\n", lhs, rhs);
}

static void put_images(hl_buf *out, const hl_alg *img, hl_system *sys, const cli_opts *o)
{
    hl_style style = ex.j != NULL ? HL_STYLE_SYMPY
                     : o->format == CLI_LATEX ? HL_STYLE_LATEX : HL_STYLE_TEXT;
    for (int i = 0; i < 2 * hl_system_ndof(sys); i++) {
        char *nm = cli_image_name(sys, i);
        char *s = hl_format_alg(&img[i], hl_system_ctx(sys), hl_system_pool(sys), style);
        if (ex.j != NULL)
            hl_json_kv_string(ex.j, nm, s);
        else
            hl_buf_printf(out, "  %s = %s\n", nm, s);
        free(nm), free(s);
    }
}

/* Q, P of a map against the closed form at sample points in every
 * quadrant and on the axes. */
static int agree_with_closed(int *ok, double *maxd, const hl_alg *img, hl_system *sys,
                             hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg *cf = hl_alg_vec_new(2, ctx);
    int st = hl_scheme_linear_flow(cf, sys, err);
    static const double pts[][3] = {{0.3, 0.8, 0.5},  {-1.2, 0.4, 2.0}, {0.7, 2.0, -3.1},
                                    {-0.6, -0.9, 1.3}, {0.5, -0.3, -0.7}, {-0.8, 0, 0.9},
                                    {0, -0.7, 2.5}};
    *ok = st == HL_OK;
    *maxd = 0;
    for (int i = 0; i < (int)(sizeof pts / sizeof *pts) && *ok; i++)
        for (int v = 0; v < 2; v++) {
            double a = eval_at(&img[v], sys, pts[i][0], pts[i][1], pts[i][2], err);
            double b = eval_at(&cf[v], sys, pts[i][0], pts[i][1], pts[i][2], err);
            double d = fabs(a - b);
            *maxd = isfinite(d) ? fmax(*maxd, d) : INFINITY;
        }
    *ok = *ok && *maxd < 1e-12;
    hl_alg_vec_free(cf, 2, ctx);
    return st;
}

static int run_aa(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err)
{
    hl_exact_aa aa;
    int st = hl_exact_aa_read(&aa, sys, ex.aa, err);
    if (st != HL_OK) {
        hl_error_prefix(err, "in --action-angle");
        return st;
    }
    int ok = 0;
    char why[400];
    st = hl_exact_aa_verify(&ok, why, sizeof why, &aa, sys, err);
    if (st != HL_OK)
        return st;
    j_bool("verified", ok);
    j_string("rejected_because", ok ? NULL : why);
    if (!ok) {
        hl_buf_printf(out, "action-angle map rejected: %s\n", why);
        *code = CLI_FAILS;
        return HL_OK;
    }
    hl_buf_puts(out, "action-angle map verified: {theta, I} = 1, {I, H} = 0, "
                     "{theta, H} = nu(I), q and p the inverse (at points in all four "
                     "quadrants)\n");
    hl_alg *img = hl_alg_vec_new(2, hl_system_ctx(sys));
    st = hl_exact_aa_scheme(img, &aa, sys, err);
    if (st == HL_OK) {
        hl_buf_printf(out, "exact scheme Q = q(theta + nu %s, I), P = p(theta + nu %s, I):\n",
                      hl_system_step(sys), hl_system_step(sys));
        j_section("scheme");
        put_images(out, img, sys, o);
        *code = CLI_OK;
    }
    hl_alg_vec_free(img, 2, hl_system_ctx(sys));
    return st;
}

/* The seven steps for H = p^2/(2m) + k q^2/2 (H = a p^2 + b q^2). */
/* The checks that end --steps: dK/dq = p and dK/dI = theta numerically
 * (eps = 1, p > 0; I from Istr at the point), the action-angle map spec
 * through hl_exact_aa_verify, the scheme against the closed form. */
static int steps_check(hl_buf *out, int *code, hl_system *sys, const cli_opts *o,
                       const char *Ks, const char *th, const char *Istr, const char *spec,
                       hl_error *err)
{
    hl_pool *pool = hl_system_pool(sys);
    const char *q = hl_system_coord(sys, 0), *p = hl_system_momentum(sys, 0);
    int st = HL_OK;
    /* checks: dK/dq = p and dK/dI = theta numerically (eps = 1, p > 0);
     * the map through hl_exact_aa_verify; the scheme against the closed form */
    int ok = 1;
    double maxd = 0;
    {
        const hl_expr *Ke = NULL, *te = NULL, *Ie = NULL;
        st = hl_parse(&Ke, pool, Ks, err);
        if (st == HL_OK)
            st = hl_parse(&te, pool, th, err);
        if (st == HL_OK)
            st = hl_parse(&Ie, pool, Istr, err);
        if (st == HL_OK) {
            const char *nm1[] = {"eps"};
            const hl_expr *one[] = {hl_num_si(pool, 1)};
            Ke = hl_expr_subst(pool, Ke, 1, nm1, one);
            const hl_expr *dKdI = hl_expr_diff(pool, Ke, "I");
            const hl_expr *dKdq = hl_expr_diff(pool, Ke, q);
            static const double pts[][2] = {{0.3, 0.8}, {-0.5, 0.2}, {0.1, 1.7}};
            for (int i = 0; i < 3 && st == HL_OK; i++) {
                /* at (q, p): I = I(q, p) */
                const char *names[] = {q, p, "I"};
                double Iv = NAN, a = NAN, b = NAN, c = NAN, vals[3] = {pts[i][0], pts[i][1], 0};
                if (hl_expr_eval_d(&Iv, Ie, 2, names, vals, err) != HL_OK)
                    break; /* symbolic m, k: skip the numeric check of K */
                vals[2] = Iv;
                if (hl_expr_eval_d(&a, dKdq, 3, names, vals, err) != HL_OK ||
                    hl_expr_eval_d(&b, dKdI, 3, names, vals, err) != HL_OK ||
                    hl_expr_eval_d(&c, te, 3, names, vals, err) != HL_OK)
                    break;
                ok = ok && fabs(a - vals[1]) < 1e-12 && fabs(b - c) < 1e-12;
            }
            st = HL_OK;
        }
    }
    hl_exact_aa aa;
    char why[400] = "";
    int aok = 0, cok = 0;
    hl_alg *img = hl_alg_vec_new(2, hl_system_ctx(sys));
    if (st == HL_OK)
        st = hl_exact_aa_read(&aa, sys, spec, err);
    if (st == HL_OK)
        st = hl_exact_aa_verify(&aok, why, sizeof why, &aa, sys, err);
    if (st == HL_OK)
        st = hl_exact_aa_scheme(img, &aa, sys, err);
    if (st == HL_OK)
        st = agree_with_closed(&cok, &maxd, img, sys, err);
    if (st == HL_OK) {
        hl_buf_printf(out, "result: Q = r(theta(q, gamma) + nu %s, gamma), P = s(...):\n",
                      hl_system_step(sys));
        j_section("result");
        put_images(out, img, sys, o);
        hl_alg *cf = hl_alg_vec_new(2, hl_system_ctx(sys));
        st = hl_scheme_linear_flow(cf, sys, err);
        if (st == HL_OK) {
            hl_buf_puts(out, "simplified (the closed form it equals):\n");
            j_section("closed_form");
            put_images(out, cf, sys, o);
        }
        hl_alg_vec_free(cf, 2, hl_system_ctx(sys));
        hl_buf_printf(out, "check dK/dq = p, dK/dI = theta: %s\n", ok ? "yes" : "NO");
        hl_buf_printf(out, "check the action-angle map: %s%s\n", aok ? "yes" : "NO: ", why);
        hl_buf_printf(out, "check the result equals the closed form (max diff %.2g): %s\n",
                      maxd, cok ? "yes" : "NO");
        j_section("checks");
        j_bool("dK_dq_is_p_and_dK_dI_is_theta", ok);
        j_bool("action_angle_map", aok);
        j_string("action_angle_map_rejected_because", aok ? NULL : why);
        j_bool("equals_closed_form", cok);
        j_double("max_difference_from_closed_form", maxd);
        *code = ok && aok && cok ? CLI_OK : CLI_FAILS;
    }
    hl_alg_vec_free(img, 2, hl_system_ctx(sys));
    return st;
}

/* Is H = p^2/(2m) + g q (+ a constant), m and g free of q and p?  Then
 * *ms and *gs are their texts (malloc'd). */
static int linear_potential(char **ms, char **gs, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int vq = hl_system_var_q(sys, 0), vp = hl_system_var_p(sys, 0), yes = 0;
    hl_alg *a = hl_alg_vec_new(5, ctx); /* H_p, H_pp, H_pq, H_q, H_qq */
    hl_error err;
    if (hl_alg_diff(&a[0], hl_system_H(sys), vp, ctx, &err) == HL_OK &&
        hl_alg_diff(&a[1], &a[0], vp, ctx, &err) == HL_OK &&
        hl_alg_diff(&a[2], &a[0], vq, ctx, &err) == HL_OK &&
        hl_alg_diff(&a[3], hl_system_H(sys), vq, ctx, &err) == HL_OK &&
        hl_alg_diff(&a[4], &a[3], vq, ctx, &err) == HL_OK) {
        yes = !hl_alg_is_zero(&a[1], ctx) && hl_alg_is_zero(&a[2], ctx) &&
              hl_alg_is_zero(&a[4], ctx);
        for (int i = 1; i <= 3; i += 2)
            yes = yes && !hl_alg_depends_on(&a[i], vq, ctx) && !hl_alg_depends_on(&a[i], vp, ctx);
        hl_alg_one(&a[0], ctx);
        if (yes && hl_alg_div(&a[0], &a[0], &a[1], ctx, &err) == HL_OK) { /* m = 1/H_pp */
            *ms = hl_format_alg(&a[0], ctx, hl_system_pool(sys), HL_STYLE_TEXT);
            *gs = hl_format_alg(&a[3], ctx, hl_system_pool(sys), HL_STYLE_TEXT);
        } else
            yes = 0;
    }
    hl_alg_vec_free(a, 5, ctx);
    return yes;
}

/* The seven steps for the free particle (g = 0: I = p, theta = q, an angle
 * that does not come back, nu = I/m) and the uniform field (g != 0: I = H,
 * K = -(2m(I - g q))^(3/2)/(3 m g), theta = dK/dI = -p/g in units of time,
 * nu = 1). */
static int run_steps_linear(hl_buf *out, int *code, hl_system *sys, const cli_opts *o,
                            const char *ms, const char *gs, hl_error *err)
{
    const char *q = hl_system_coord(sys, 0), *p = hl_system_momentum(sys, 0);
    int free_ = strcmp(gs, "0") == 0;
    /* f[0] with the letters m and g, as printed; f[1] with their values, to check */
    char I[2][2048], K[2][2048], th[2][1024], rq[2][2048], rp[2][1024], nu[2][1024], pf[1024];
    for (int v = 0; v < 2; v++) {
        char m[256], g[256];
        snprintf(m, sizeof m, v ? "(%s)" : "m", ms);
        snprintf(g, sizeof g, v ? "(%s)" : "g", gs);
        if (free_) {
            snprintf(I[v], sizeof I[v], "%s", p);
            snprintf(K[v], sizeof K[v], "I*%s", q);
            snprintf(th[v], sizeof th[v], "%s", q);
            snprintf(rq[v], sizeof rq[v], "theta");
            snprintf(rp[v], sizeof rp[v], "I");
            snprintf(nu[v], sizeof nu[v], "I/%s", m);
        } else {
            snprintf(I[v], sizeof I[v], "%s^2/(2*%s) + %s*%s", p, m, g, q);
            snprintf(K[v], sizeof K[v], "-eps*(2*%s*(I - %s*%s))^(3/2)/(3*%s*%s)", m, g, q, m, g);
            snprintf(th[v], sizeof th[v], "-%s/%s", p, g);
            snprintf(rq[v], sizeof rq[v], "(I - %s^2*theta^2/(2*%s))/%s", g, m, g);
            snprintf(rp[v], sizeof rp[v], "-%s*theta", g);
            snprintf(nu[v], sizeof nu[v], "1");
        }
    }
    if (free_)
        hl_buf_printf(out, "H = %s^2/(2*m), a free particle, with m = %s\n", p, ms);
    else
        hl_buf_printf(out, "H = %s^2/(2*m) + g*%s, a uniform field, with m = %s, g = %s\n", p, q,
                      ms, gs);
    j_section("form");
    j_string("kind", free_ ? "free particle" : "uniform field");
    j_formula("m", ms, sys);
    if (!free_)
        j_formula("g", gs, sys);
    put_step(out, "step 1: the integral of motion as the action\n");
    put_formula(out, "I", I[0], sys, o);
    put_step(out, "step 2: the momentum from I (eps = +1 or -1, the branch)\n");
    snprintf(pf, sizeof pf, free_ ? "I" : "eps*sqrt(2*m*(I - g*%s))", q);
    put_formula(out, p, pf, sys, o);
    put_step(out, "step 3: the generating function K(q, I) = int p dq\n");
    put_formula(out, "K", K[0], sys, o);
    put_step(out, free_ ? "step 4: the angle theta = dK/dI (it does not come back)\n"
                        : "step 4: the angle theta = dK/dI (in units of time)\n");
    put_formula(out, "theta", th[0], sys, o);
    put_step(out, "step 5: the inverse\n");
    put_formula(out, q, rq[0], sys, o);
    put_formula(out, p, rp[0], sys, o);
    put_step(out, "step 6: the frequency nu = {theta, H}\n");
    put_formula(out, "nu", nu[0], sys, o);
    put_step(out, "step 7: the constant of the action\n");
    put_formula(out, "gamma", I[0], sys, o);
    hl_buf spec;
    hl_buf_init(&spec);
    hl_buf_printf(&spec, "theta = %s; I = %s; %s = %s; %s = %s; nu = %s", th[1], I[1], q, rq[1],
                  p, rp[1], nu[1]);
    int st = steps_check(out, code, sys, o, K[1], th[1], I[1], spec.s, err);
    hl_buf_clear(&spec);
    return st;
}

static int run_steps(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err)
{
    if (hl_system_ndof(sys) != 1)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                            "--steps is for 1 degree of freedom (H = p^2/(2m) + k q^2/2)");
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_pool *pool = hl_system_pool(sys);
    int vq = hl_system_var_q(sys, 0), vp = hl_system_var_p(sys, 0), st;
    hl_alg d, e, z;
    hl_alg_init(&d, ctx);
    hl_alg_init(&e, ctx);
    hl_alg_init(&z, ctx);
    char *ms = NULL, *ks = NULL;
    int form = 1;
    /* a = H_pp/2, b = H_qq/2; H_qp, H_q(0), H_p(0) must vanish */
    st = hl_alg_diff(&d, hl_system_H(sys), vp, ctx, err);
    if (st == HL_OK)
        st = hl_alg_diff(&e, &d, vp, ctx, err);
    if (st == HL_OK) {
        hl_alg_set_si(&z, 1, ctx);
        st = hl_alg_div(&z, &z, &e, ctx, err); /* m = 1 / H_pp */
    }
    if (st == HL_OK) {
        ms = hl_format_alg(&z, ctx, pool, HL_STYLE_TEXT);
        form = !hl_alg_depends_on(&e, vq, ctx) && !hl_alg_depends_on(&e, vp, ctx);
        st = hl_alg_diff(&e, &d, vq, ctx, err);
        form = form && hl_alg_is_zero(&e, ctx);
    }
    if (st == HL_OK)
        st = hl_alg_diff(&d, hl_system_H(sys), vq, ctx, err);
    if (st == HL_OK)
        st = hl_alg_diff(&e, &d, vq, ctx, err);
    if (st == HL_OK) {
        ks = hl_format_alg(&e, ctx, pool, HL_STYLE_TEXT);
        form = form && !hl_alg_depends_on(&e, vq, ctx) && !hl_alg_depends_on(&e, vp, ctx);
        hl_alg_zero(&z, ctx);
        st = hl_alg_subst(&z, &d, 1, &vq, &z, ctx, err); /* H_q at q = 0: no field */
        form = form && hl_alg_is_zero(&z, ctx) && !hl_alg_is_zero(&e, ctx);
    }
    hl_alg_clear(&d, ctx);
    hl_alg_clear(&e, ctx);
    hl_alg_clear(&z, ctx);
    char *lm = NULL, *lg = NULL;
    if (st == HL_OK && !form && linear_potential(&lm, &lg, sys)) {
        free(ms), free(ks);
        st = run_steps_linear(out, code, sys, o, lm, lg, err);
        free(lm), free(lg);
        return st;
    }
    if (st == HL_OK && !form)
        st = hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                          "--steps carries out §3 for H = p^2/(2m) + V(q) with V of degree "
                          "<= 2 (oscillator, uniform field, free particle); for another "
                          "quadratic H use the closed form (without --steps)");
    if (st != HL_OK) {
        free(ms), free(ks);
        return st;
    }
    const char *q = hl_system_coord(sys, 0), *p = hl_system_momentum(sys, 0);
    char m[128], k[128];
    snprintf(m, sizeof m, "(%s)", ms);
    snprintf(k, sizeof k, "(%s)", ks);
    free(ms), free(ks);
    hl_buf f;
    hl_buf_init(&f);
#define F(...) (hl_buf_clear(&f), hl_buf_printf(&f, __VA_ARGS__), f.s)
    int unit = strcmp(m, "(1)") == 0 && strcmp(k, "(1)") == 0;
    if (unit)
        hl_buf_printf(out, "H = (%s^2 + %s^2)/2: m = k = 1\n", p, q);
    else
        hl_buf_printf(out, "H = %s^2/(2*m) + k*%s^2/2 with m = %.*s, k = %.*s\n", p, q,
                      (int)strlen(m) - 2, m + 1, (int)strlen(k) - 2, k + 1);
    j_section("form");
    j_string("kind", "oscillator");
    j_formula("m", m, sys);
    j_formula("k", k, sys);
    put_step(out, "step 1: the integral of motion as the action\n");
    put_formula(out, "I", unit ? F("(%s^2 + %s^2)/2", p, q) : F("%s^2/(2*m) + k*%s^2/2", p, q),
                sys, o);
    put_step(out, "step 2: the momentum from I (eps = +1 or -1, the branch)\n");
    put_formula(out, p, unit ? F("eps*sqrt(2*I - %s^2)", q) : F("eps*sqrt(2*m*I - m*k*%s^2)", q),
                sys, o);
    put_step(out, "step 3: the generating function K(q, I) = int p dq\n");
    put_formula(out, "K",
                unit ? F("eps*(%s/2*sqrt(2*I - %s^2) + I*atan(%s/sqrt(2*I - %s^2)))", q, q, q, q)
                     : F("eps*(%s/2*sqrt(2*m*I - m*k*%s^2) + I*sqrt(m/k)*atan(%s*sqrt(m*k)/"
                         "sqrt(2*m*I - m*k*%s^2)))", q, q, q, q),
                sys, o);
    /* dK/dI = atan(q/p) on either branch of p; atan2 joins the branches
     * across p = 0 (it differs from atan by a constant, pi, where p < 0) */
    put_step(out, "step 4: the angle theta = dK/dI (in units of time; atan2 continues it "
                     "across p = 0)\n");
    put_formula(out, "theta",
                unit ? F("atan2(%s, %s)", q, p) : F("sqrt(m/k)*atan2(sqrt(m*k)*%s, %s)", q, p), sys,
                o);
    put_step(out, "step 5: the inverse\n");
    put_formula(out, q, unit ? "sqrt(2*I)*sin(theta)" : "sqrt(2*I/k)*sin(sqrt(k/m)*theta)", sys, o);
    put_formula(out, p, unit ? "sqrt(2*I)*cos(theta)" : "sqrt(2*m*I)*cos(sqrt(k/m)*theta)", sys, o);
    put_step(out, "step 6: the frequency nu = {theta, H}\n");
    put_formula(out, "nu", "1", sys, o);
    put_step(out, "step 7: the constant of the action\n");
    put_formula(out, "gamma", unit ? F("(%s^2 + %s^2)/2", p, q) : F("%s^2/(2*m) + k*%s^2/2", p, q),
                sys, o);
    /* the same formulas with the values of m and k, for the checks */
    char *Ks = hl_xstrdup(F("eps*(%s/2*sqrt(2*%s*I - %s*%s*%s^2) + I*sqrt(%s/%s)*"
                      "atan(%s*sqrt(%s*%s)/sqrt(2*%s*I - %s*%s*%s^2)))",
                      q, m, m, k, q, m, k, q, m, k, m, m, k, q));
    char *th = hl_xstrdup(F("sqrt(%s/%s)*atan2(sqrt(%s*%s)*%s, %s)", m, k, m, k, q, p));
    char *rq = hl_xstrdup(F("sqrt(2*I/%s)*sin(sqrt(%s/%s)*theta)", k, k, m));
    char *rp = hl_xstrdup(F("sqrt(2*%s*I)*cos(sqrt(%s/%s)*theta)", m, k, m));
    hl_buf_clear(&f);
#undef F
    char *spec = NULL;
    {
        hl_buf sb;
        hl_buf_init(&sb);
        hl_buf_printf(&sb, "theta = %s; I = %s^2/(2*%s) + %s*%s^2/2; %s = %s; %s = %s; nu = 1",
                      th, p, m, k, q, q, rq, p, rp);
        spec = hl_buf_take(&sb);
    }
    char Istr[300];
    snprintf(Istr, sizeof Istr, "%s^2/(2*%s) + %s*%s^2/2", p, m, k, q);
    st = steps_check(out, code, sys, o, Ks, th, Istr, spec, err);
    free(spec), free(Ks), free(th), free(rq), free(rp);
    return st;
}

/* --init with --digits: the same in Arb (exact.h: hl_exact_arb), against
 * the Arb integrator carried over the whole time and the double scheme. */
static int run_numeric_arb(hl_buf *out, int *code, hl_system *sys, double dt,
                           const double *zd8, hl_error *err)
{
    char *end;
    double digits = strtod(ex.digits, &end);
    if (*end || !(digits >= 16 && digits <= 1000))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "--digits must be from 16 to 1000");
    hl_exact_arb *f = NULL;
    int st = hl_exact_arb_new(&f, sys, digits, err);
    if (st != HL_OK)
        return st;
    slong prec = (slong)ceil(digits * log2(10.0)) + 32;
    arb_ptr z = _arb_vec_init(2), w = _arb_vec_init(2);
    arb_t T, h, t, t1, d;
    arb_init(T), arb_init(h), arb_init(t), arb_init(t1), arb_init(d);
    st = hl_run_init_values_arb(z, sys, ex.init, prec, err);
    if (st == HL_OK)
        st = hl_exact_arb_period(T, z, f, err);
    int nd = (int)digits;
    if (st == HL_OK) {
        hl_buf_printf(out, "in Arb at %d digits: period T = ", nd);
        cli_put_arb(out, T, nd);
        hl_buf_puts(out, "\n");
        j_section("arb");
        j_double("digits", nd);
        j_arb("period", T, nd);
    }
    _arb_vec_set(w, z, 2);
    arb_set_d(h, dt);
    for (int n = 1; n <= 8 && st == HL_OK; n++)
        st = hl_exact_arb_step(z, h, f, err);
    /* the Arb integrator over the whole 8 dt (the check of the reduction mod T) */
    hl_tape *vf = NULL;
    hl_flow_arb *fa = NULL;
    const char *q = hl_system_coord(sys, 0), *p = hl_system_momentum(sys, 0);
    if (st == HL_OK)
        st = hl_tape_hamiltonian(&vf, hl_system_pool(sys), hl_system_H_expr(sys), 1, &q, &p, 0,
                                 NULL, NULL, err);
    if (st == HL_OK)
        st = hl_flow_arb_new(&fa, vf, digits, err);
    arb_mul_si(t1, h, 8, prec);
    if (st == HL_OK)
        st = hl_flow_arb_evolve(fa, t, t1, w, err);
    if (st == HL_OK) {
        double dmax = 0, ddouble = 0;
        hl_buf_printf(out, "after 8 exact steps of %s = %g in Arb:", hl_system_step(sys), dt);
        j_object("final_state");
        for (int i = 0; i < 2; i++) {
            char *nm = cli_image_name(sys, i);
            hl_buf_printf(out, " %s = ", nm);
            cli_put_arb(out, z + i, nd);
            j_arb(nm, z + i, nd);
            free(nm);
            arb_sub(d, z + i, w + i, prec);
            dmax = fmax(dmax, fabs(arf_get_d(arb_midref(d), ARF_RND_NEAR)));
            ddouble = fmax(ddouble, fabs(zd8[i] - arf_get_d(arb_midref(z + i), ARF_RND_NEAR)));
        }
        hl_buf_printf(out, "\nmax difference from the Arb integrator over t = %g: %.3g\n",
                      8 * dt, dmax);
        hl_buf_printf(out, "max difference of the double exact scheme from it: %.3g\n", ddouble);
        j_close_to(1);
        j_double("max_difference_from_arb_integrator", dmax);
        j_double("max_difference_of_double_scheme", ddouble);
        *code = dmax < pow(10.0, 5 - digits) * 8 * fmax(1.0, fabs(dt)) ? CLI_OK : CLI_FAILS;
    }
    hl_flow_arb_free(fa);
    hl_tape_free(vf);
    hl_exact_arb_free(f);
    _arb_vec_clear(z, 2), _arb_vec_clear(w, 2);
    arb_clear(T), arb_clear(h), arb_clear(t), arb_clear(t1), arb_clear(d);
    return st;
}

/* 1 dof, not quadratic: the orbit's period and a few steps against the
 * Taylor integrator. */
static int run_numeric(hl_buf *out, int *code, hl_system *sys, const cli_opts *o,
                       hl_error *err)
{
    (void)o;
    int N = hl_system_ndof(sys);
    double z[2 * 8], r[2 * 8];
    if (N > 8)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "--init: at most 8 dof here");
    double dt = 0.5;
    if (ex.dt != NULL) {
        char *end;
        dt = strtod(ex.dt, &end);
        if (*end || !isfinite(dt) || dt == 0)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "--dt must be a non-zero number");
    }
    int st = hl_run_init_values(z, sys, ex.init, err);
    if (st != HL_OK) {
        hl_error_prefix(err, "in --init");
        return st;
    }
    memcpy(r, z, sizeof(double) * 2 * N);
    hl_exact_flow *f = NULL;
    st = hl_exact_flow_new(&f, sys, err);
    if (st != HL_OK)
        return st;
    double T = NAN;
    if (!hl_exact_flow_is_linear(f)) {
        st = hl_exact_flow_period(&T, z, f, err);
        if (st == HL_OK)
            hl_buf_printf(out, "orbit through the initial point: period T = %.17g, "
                               "frequency 2 pi/T = %.17g\n", T, 2 * M_PI / T);
    } else
        hl_buf_printf(out, "H quadratic: the exact step is exp(%s A) (matrix exponential)\n",
                      hl_system_step(sys));
    j_section("orbit");
    j_bool("quadratic", hl_exact_flow_is_linear(f));
    j_double("period", T);
    j_double("frequency", 2 * M_PI / T);
    /* reference: the Taylor integrator at 1e-15 */
    hl_tape *tape = NULL;
    hl_flow *fl = NULL;
    const char *nq[8], *np[8];
    for (int j = 0; j < N; j++)
        nq[j] = hl_system_coord(sys, j), np[j] = hl_system_momentum(sys, j);
    if (st == HL_OK)
        st = hl_tape_hamiltonian(&tape, hl_system_pool(sys), hl_system_H_expr(sys), N, nq, np,
                                 0, NULL, NULL, err);
    if (st == HL_OK)
        st = hl_flow_new(&fl, tape, 1e-15, 1e-15, err);
    double maxd = 0, t = 0;
    for (int n = 1; n <= 8 && st == HL_OK; n++) {
        st = hl_exact_flow_step(z, dt, f, err);
        if (st == HL_OK)
            st = hl_flow_evolve(fl, &t, n * dt, r, err);
        for (int i = 0; i < 2 * N && st == HL_OK; i++)
            maxd = fmax(maxd, fabs(z[i] - r[i]));
    }
    if (st == HL_OK) {
        hl_buf_printf(out, "after 8 exact steps of %s = %g:", hl_system_step(sys), dt);
        for (int i = 0; i < 2 * N; i++) {
            char *nm = cli_image_name(sys, i);
            hl_buf_printf(out, " %s = %.17g", nm, z[i]);
            free(nm);
        }
        hl_buf_printf(out, "\nmax difference from the Taylor integrator (tol 1e-15): %.3g\n",
                      maxd);
        j_section("exact_steps");
        j_double("dt", dt);
        j_double("count", 8);
        j_object("final_state");
        for (int i = 0; i < 2 * N; i++) {
            char *nm = cli_image_name(sys, i);
            j_double(nm, z[i]);
            free(nm);
        }
        j_close_to(1);
        j_double("max_difference_from_taylor", maxd);
        j_double("taylor_tol", 1e-15);
        *code = maxd < 1e-11 ? CLI_OK : CLI_FAILS;
    }
    if (st == HL_OK && ex.digits != NULL) {
        int c2 = CLI_OK;
        st = run_numeric_arb(out, &c2, sys, dt, z, err);
        if (c2 != CLI_OK)
            *code = c2;
    }
    hl_flow_free(fl);
    hl_tape_free(tape);
    hl_exact_flow_free(f);
    return st;
}

static int run_mode(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err)
{
    if (ex.aa != NULL)
        return run_aa(out, code, sys, o, err);
    if (ex.steps)
        return run_steps(out, code, sys, o, err);
    return run_numeric(out, code, sys, o, err);
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
    hl_json_kv_string(&j, "mode", ex.aa != NULL ? "action_angle" : ex.steps ? "steps" : "init");
    if (ex.aa != NULL || ex.steps) { /* the names the formulas use besides the system's */
        hl_json_key(&j, "formula_symbols");
        hl_json_array_begin(&j);
        static const char *const names[] = {"I", "theta", "eps", "gamma", "nu", "m", "k", "g"};
        for (size_t i = 0; i < sizeof names / sizeof names[0]; i++)
            hl_json_string(&j, names[i]);
        hl_json_array_end(&j);
    }
    ex.j = &j;
    ex.depth = 0;
    int st = run_mode(&text, code, sys, o, err);
    j_close_to(0);
    ex.j = NULL;
    hl_json_kv_bool(&j, "all_checks_hold", *code == CLI_OK);
    hl_json_kv_bool(&j, "numeric_zero_test", hl_alg_ctx_numeric_used(hl_system_ctx(sys)));
    hl_json_object_end(&j);
    hl_json_finish(&j);
    hl_buf_clear(&text);
    return st;
}

static int run(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err)
{
    if (ex.aa != NULL || ex.steps || ex.init != NULL)
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
        ex.init = value;
    else if (k == 1)
        ex.aa = value;
    else if (k == 2)
        ex.dt = value;
    else if (k == 3)
        ex.steps = 1;
    else
        ex.digits = value;
}

int cmd_exact(int argc, char **argv)
{
    static const cli_spec spec = {"exact", CLI_OPT_H | CLI_OPT_ORDER, check, run};
    static const cli_own own[] = {
        {"--init", 0}, {"--action-angle", 0}, {"--dt", 0}, {"--steps", 1}, {"--digits", 0}};
    memset(&ex, 0, sizeof ex);
    char **av = hl_xmalloc((size_t)(argc + 1) * sizeof *av);
    memcpy(av, argv, (size_t)(argc + 1) * sizeof *av);
    int ac = argc;
    int rc = cli_take_own(&ac, av, own, 5, found_opt, NULL, cli_find("exact"));
    if (rc < 0)
        rc = cli_main(ac, av, &spec);
    free(av);
    return rc;
}
