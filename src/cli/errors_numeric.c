/* hamlie errors --numeric --at: the analysis at one point in double
 * precision (numerr.h), parsed, computed and written (text, JSON). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli/errors.h"
#include "hamlie/exact.h"
#include "hamlie/numerr.h"

/* What the numeric path knows of the problem. */
typedef struct at_point {
    hl_system *sys;
    hl_scheme *s; /* NULL for the numeric exact scheme */
    int m, n;
    const char **names;
} at_point;

/* ---- --numeric: the analysis at one point (numerr.h) ---------------------- */

/* z from "q=1.3,p=0": every phase variable once, each a number.  -1, or 2
 * after a usage message. */
static int parse_at(double *z, const char *at, at_point *R, const cli_command *cmd)
{
    int *seen = calloc((size_t)R->m, sizeof *seen);
    char *copy = hl_xstrdup(at), *save = NULL;
    int rc = -1;
    for (char *it = strtok_r(copy, ",", &save); it != NULL && rc < 0;
         it = strtok_r(NULL, ",", &save)) {
        while (*it == ' ')
            it++;
        char *eq = strchr(it, '=');
        if (eq == NULL) {
            rc = cli_usage(cmd, "--at: '%s' is not 'name=value'", it);
            break;
        }
        *eq = '\0';
        char *name = it, *e = name + strlen(name);
        while (e > name && e[-1] == ' ')
            *--e = '\0';
        int i = 0;
        while (i < R->m && strcmp(R->names[i], name) != 0)
            i++;
        if (i == R->m) {
            rc = cli_usage(cmd, "--at: '%s' is not a phase variable of H", name);
            break;
        }
        if (seen[i]) {
            rc = cli_usage(cmd, "--at: '%s' is given twice", name);
            break;
        }
        char *end;
        double v = strtod(eq + 1, &end);
        while (*end == ' ')
            end++;
        if (end == eq + 1 || *end != '\0' || !isfinite(v)) {
            rc = cli_usage(cmd, "--at: the value of '%s' is not a number: '%s'", name, eq + 1);
            break;
        }
        z[i] = v;
        seen[i] = 1;
    }
    for (int i = 0; i < R->m && rc < 0; i++)
        if (!seen[i])
            rc = cli_usage(cmd, "--at: no value for '%s' (give every phase variable)", R->names[i]);
    free(copy);
    free(seen);
    return rc;
}

static void put_num_vec(hl_buf *out, const double *v, at_point *R)
{
    for (int i = 0; i < R->m; i++)
        hl_buf_printf(out, "%s%s = %.17g", i ? ", " : "", R->names[i], v[i]);
}

static void write_numeric_text(hl_buf *out, const hl_numerr *nr, const double *z, at_point *R,
                               const err_opts *r, const cli_opts *o)
{
    int m = R->m;
    hl_buf_printf(out, "scheme: %s\n", errors_input(r, o));
    char *H = hl_format_alg(hl_system_H(R->sys), hl_system_ctx(R->sys), hl_system_pool(R->sys),
                            HL_STYLE_TEXT);
    hl_buf_printf(out, "H = %s", H);
    free(H);
    hl_buf_puts(out, "\nat: ");
    put_num_vec(out, z, R);
    hl_buf_printf(out,
                  "\nnumeric analysis at the point (double precision, Taylor mode) to "
                  "order %d\n",
                  nr->n);
    for (int k = 2; k <= nr->n; k++) {
        hl_buf_printf(out, "v_%d(z) = (", k);
        put_num_vec(out, nr->v + k * m, R);
        hl_buf_printf(out, ")  |v_%d| = %.3g %s threshold %.3g\n", k, nr->vnorm[k],
                      nr->vnorm[k] > nr->thresh[k] ? ">" : "<=", nr->thresh[k]);
    }
    if (nr->leading)
        hl_buf_printf(out,
                      "order: %d (leading error v_%d: the least k with |v_k(z)| above "
                      "round-off)\n",
                      nr->order, nr->leading);
    else
        hl_buf_printf(out, "order: at least %d (no v_k above round-off up to k = %d)\n", nr->order,
                      nr->n);
    hl_buf_puts(out, "round-off threshold for v_k: 1e-10 · k! · max_i(|[D^k] psi_i| + "
                     "|g^k z_i / k!|)\n");
    if (isnan(nr->K[0])) /* a series from elsewhere: hl_numerr_from_series */
        hl_buf_puts(out, "  (at least its upper concave hull in log over k: a coefficient "
                         "that vanishes at z is\n  round-off of its neighbours' size in a "
                         "series not computed exactly)\n");
    if (isnan(nr->K[0])) {
        hl_buf_puts(out, "K(D): not computed (it needs the scheme at other points than z)\n");
        return;
    }
    hl_buf_printf(out, "K(D) = (d/dD psi_D)(psi_{-D}(z)), coefficients to D^%d:\n", nr->n - 1);
    for (int k = 0; k < nr->n; k++) {
        hl_buf_printf(out, "  D^%d: ", k);
        put_num_vec(out, nr->K + k * m, R);
        hl_buf_puts(out, "\n");
    }
}

/* {"q": 1.3, "p": 0}: one number per phase variable */
static void json_point(hl_json *j, const double *v, const at_point *R)
{
    hl_json_object_begin(j);
    for (int i = 0; i < R->m; i++)
        hl_json_kv_double(j, R->names[i], v[i]);
    hl_json_object_end(j);
}

/* the points from..to, the k-th at v + k * m */
static void json_points(hl_json *j, const double *v, int from, int to, const at_point *R)
{
    hl_json_array_begin(j);
    for (int k = from; k <= to; k++)
        json_point(j, v + k * R->m, R);
    hl_json_array_end(j);
}

static void json_numeric_fields(hl_json *j, const hl_numerr *nr, const at_point *R)
{
    hl_json_key(j, "fields");
    hl_json_array_begin(j);
    for (int k = 2; k <= nr->n; k++) {
        hl_json_object_begin(j);
        hl_json_kv_int(j, "k", k);
        hl_json_key(j, "v");
        json_point(j, nr->v + k * R->m, R);
        hl_json_kv_double(j, "norm", nr->vnorm[k]);
        hl_json_kv_double(j, "threshold", nr->thresh[k]);
        hl_json_kv_bool(j, "nonzero", nr->vnorm[k] > nr->thresh[k]);
        hl_json_object_end(j);
    }
    hl_json_array_end(j);
}

static void write_numeric_json(hl_buf *b, const hl_numerr *nr, const double *z, at_point *R,
                               const err_opts *r, const cli_opts *o)
{
    hl_json j;
    hl_json_init_buf(&j, b);
    hl_json_object_begin(&j);
    hl_json_kv_string(&j, "command", "errors");
    hl_json_kv_string(&j, "mode", "numeric");
    cli_json_system(&j, R->sys);
    hl_json_kv_bool(&j, "numeric_zero_test", 0);
    hl_json_key(&j, "scheme");
    hl_json_object_begin(&j);
    hl_json_kv_string(&j, "source", errors_source(r, o));
    hl_json_kv_string(&j, "name", R->s != NULL ? R->s->name : r->scheme);
    hl_json_kv_string(&j, "input", errors_input(r, o));
    hl_json_kv_bool(&j, "explicit", R->s == NULL || R->s->all_explicit);
    hl_json_object_end(&j);
    hl_json_key(&j, "at");
    json_point(&j, z, R);
    hl_json_kv_int(&j, "order_computed", nr->n);
    json_numeric_fields(&j, nr, R);
    hl_json_kv_int(&j, "order", nr->order);
    hl_json_key(&j, "leading");
    if (nr->leading)
        hl_json_int(&j, nr->leading);
    else
        hl_json_null(&j);
    hl_json_kv_bool(&j, "exact_to_order_computed", !nr->leading);
    hl_json_key(&j, "K_coefficients");
    json_points(&j, nr->K, 0, nr->n - 1, R);
    hl_json_key(&j, "flow_coefficients");
    json_points(&j, nr->flow, 0, nr->n, R);
    hl_json_object_end(&j);
    hl_json_finish(&j);
}

/* --scheme exact for an H whose exact flow has no closed form here: the
 * numeric exact scheme of exact.h (hl_exact_flow), analysed from its own
 * series at the point. */
int errors_numeric_exact(const err_opts *r, hl_system *sys)
{
    return r->scheme != NULL && strcmp(r->scheme, "exact") == 0 &&
           !hl_scheme_linear_flow_applies(sys);
}

static int exact_numerr(hl_numerr *nr, at_point *R, const double *z, hl_error *err)
{
    hl_exact_flow *f = NULL;
    double *psi = hl_xmalloc((size_t)(R->n + 1) * R->m * sizeof *psi);
    int st = hl_exact_flow_new(&f, R->sys, err);
    /* beyond this order the coefficients show the orbit table's pieces
     * (exact.h), not an error of the scheme: refused rather than reported */
    if (st == HL_OK && !hl_exact_flow_is_linear(f) && R->n > HL_EXACT_SERIES_ACCURATE)
        st = hl_error_set(err, HL_ELIMIT, NULL, -1, 0,
                          "its series comes from the orbit table's Taylor pieces of degree "
                          "%d and is accurate to round-off up to D^%d: --order at most %d, "
                          "not %d",
                          HL_EXACT_SERIES_DEGREE, HL_EXACT_SERIES_ACCURATE,
                          HL_EXACT_SERIES_ACCURATE, R->n);
    if (st == HL_OK)
        st = hl_exact_flow_series(psi, z, R->n, f, err);
    if (st == HL_OK)
        st = hl_numerr_from_series(nr, R->sys, z, psi, R->n, err);
    if (st != HL_OK)
        hl_error_prefix(err, "the exact scheme");
    hl_exact_flow_free(f);
    free(psi);
    return st;
}

static int run_numeric(hl_buf *out, at_point *R, const err_opts *r, const cli_opts *o,
                       const cli_command *cmd)
{
    double *z = hl_xmalloc((size_t)R->m * sizeof *z);
    int rc = parse_at(z, r->at, R, cmd);
    hl_error err;
    hl_error_clear(&err);
    hl_numerr nr;
    memset(&nr, 0, sizeof nr);
    if (rc < 0 && errors_numeric_exact(r, R->sys)) {
        if (exact_numerr(&nr, R, z, &err) != HL_OK)
            rc = cli_fail(&err);
    } else {
        if (rc < 0 && errors_make_scheme(&R->s, r, o, R->sys, &err) != HL_OK)
            rc = cli_fail(&err);
        if (rc < 0 && hl_numerr_compute(&nr, R->s, z, R->n, &err) != HL_OK) {
            hl_error_prefix(&err, "numeric analysis");
            rc = cli_fail(&err);
        }
    }
    if (rc < 0) {
        if (o->format == CLI_JSON)
            write_numeric_json(out, &nr, z, R, r, o);
        else
            write_numeric_text(out, &nr, z, R, r, o);
    }
    hl_numerr_clear(&nr);
    free(z);
    return rc;
}

int errors_run_numeric(hl_buf *out, hl_system *sys, int order, const err_opts *r, const cli_opts *o,
                       const cli_command *cmd)
{
    int N = hl_system_ndof(sys);
    at_point R = {sys, NULL, 2 * N, order, NULL};
    R.names = hl_xmalloc((size_t)R.m * sizeof *R.names);
    for (int i = 0; i < R.m; i++)
        R.names[i] = cli_phase_name(sys, i);
    int rc = run_numeric(out, &R, r, o, cmd);
    hl_scheme_free(R.s);
    free(R.names);
    return rc;
}
