/* The run object: the stepper, H and the observers compiled to one tape,
 * the vector field for the reference, and reading initial values. */
#include <errno.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "run/run_impl.h"

/* Replace H and the set parameters by their values. */
static const hl_expr *resolve(hl_system *sys, const hl_expr *e)
{
    hl_pool *pool = hl_system_pool(sys);
    int ns = hl_system_nset(sys);
    const char **names = hl_xmalloc((size_t)(ns + 1) * sizeof *names);
    const hl_expr **vals = hl_xmalloc((size_t)(ns + 1) * sizeof *vals);
    for (int i = 0; i < ns; i++)
        names[i] = hl_system_set_name(sys, i), vals[i] = hl_system_set_value(sys, i);
    int n = ns;
    if (hl_system_has_H(sys))
        names[n] = "H", vals[n++] = hl_system_H_expr(sys);
    const hl_expr *r = hl_expr_subst(pool, e, n, names, vals);
    free(names), free(vals);
    return r;
}

const hl_expr *hl_run_resolve_(hl_system *sys, const hl_expr *e)
{
    return resolve(sys, e);
}

hl_status hl_run_new(hl_run **out, hl_system *sys, const hl_scheme *scheme, hl_error *err)
{
    *out = NULL;
    if (!hl_system_has_H(sys))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "a run needs a Hamiltonian");
    if (hl_system_nparams(sys) > 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "parameter '%s' has no value (give it one to run)",
                            hl_system_param(sys, 0));
    hl_run *r = hl_xcalloc(1, sizeof *r);
    r->sys = sys;
    r->N = hl_system_ndof(sys);
    r->names = hl_xmalloc((size_t)(2 * r->N) * sizeof *r->names);
    for (int j = 0; j < r->N; j++) {
        r->names[j] = hl_system_coord(sys, j);
        r->names[r->N + j] = hl_system_momentum(sys, j);
    }
    r->outs = hl_xmalloc(sizeof *r->outs);
    r->outs[0] = hl_system_H_expr(sys);
    r->nout = 1;
    r->ref_on = 1;
    r->ref_tol = 1e-15;
    r->z = hl_xcalloc((size_t)(2 * r->N), sizeof *r->z);
    r->ref = hl_xcalloc((size_t)(2 * r->N), sizeof *r->ref);
    int st = HL_OK;
    r->scheme = scheme;
    if (scheme != NULL)
        st = hl_scheme_stepper_new(&r->stepper, scheme, err);
    if (st == HL_OK)
        st = hl_tape_hamiltonian(&r->vf, hl_system_pool(sys), hl_system_H_expr(sys), r->N,
                                 r->names, r->names + r->N, 0, NULL, NULL, err);
    if (st != HL_OK) {
        hl_run_free(r);
        return st;
    }
    *out = r;
    return HL_OK;
}

hl_status hl_run_new_stepper(hl_run **out, hl_system *sys, hl_run_step_fn step, void *arg,
                             hl_error *err)
{
    *out = NULL;
    if (step == NULL)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no step function");
    int st = hl_run_new(out, sys, NULL, err);
    if (st == HL_OK) {
        (*out)->step = step;
        (*out)->step_arg = arg;
        (*out)->zs = hl_xcalloc((size_t)(2 * (*out)->N), sizeof *(*out)->zs);
    }
    return st;
}

void hl_run_free(hl_run *r)
{
    if (r == NULL)
        return;
    hl_scheme_stepper_free(r->stepper);
    hl_tape_free(r->obs);
    hl_tape_iter_batch_free(r->lane_loop); /* before the tape it borrows */
    hl_tape_free(r->fused);
    hl_tape_free(r->vf);
    hl_event_free(r->ev); /* hl_run_event's */
    hl_tape_free(r->ev_tape);
    free(r->ev_z);
    free(r->names), free(r->outs), free(r->z), free(r->ref), free(r->vals), free(r->zs);
    free(r);
}

int hl_run_nobservers(const hl_run *r) { return r->nout - 1; }

void hl_run_set_reference(hl_run *r, int on, double tol)
{
    r->ref_on = on;
    if (tol > 0)
        r->ref_tol = tol;
}

const double *hl_run_state(const hl_run *r) { return r->z; }

void hl_run_set_jit(hl_run *r, int on) { r->jit = on; }

void hl_run_set_progress(hl_run *r, hl_progress_fn fn, void *arg)
{
    r->progress = fn;
    r->progress_arg = arg;
}

int hl_run_progress_(hl_run *r, double *next, double spacing, double done, long n, double t,
                     hl_error *err)
{
    if (r->progress == NULL || done < *next)
        return HL_OK;
    *next = done + spacing;
    if (r->progress(done, (double)n, r->progress_arg) == 0)
        return HL_OK;
    return hl_error_set(err, HL_ESTOP, NULL, -1, 0, "stopped at step %ld of %ld (t = %.17g)",
                        (long)done, n, t);
}

static int is_var(const hl_run *r, const char *name)
{
    for (int i = 0; i < 2 * r->N; i++)
        if (strcmp(r->names[i], name) == 0)
            return 1;
    return 0;
}

hl_status hl_run_observe(hl_run *r, const char *formula, hl_error *err)
{
    const hl_expr *e;
    int st = hl_parse(&e, hl_system_pool(r->sys), formula, err);
    if (st != HL_OK)
        return st;
    e = resolve(r->sys, e);
    const char *syms[64];
    int ns = hl_expr_symbols(e, syms, 64);
    for (int i = 0; i < ns && i < 64; i++)
        if (!is_var(r, syms[i])) {
            int pos = hl_symbol_pos(formula, syms[i]);
            return hl_error_set(err, HL_EINVAL, formula, pos, pos >= 0 ? (int)strlen(syms[i]) : 0,
                                "unknown symbol '%s' (not a variable, H, or a parameter "
                                "with a value)", syms[i]);
        }
    r->outs = hl_xrealloc(r->outs, (size_t)(r->nout + 1) * sizeof *r->outs);
    r->outs[r->nout++] = e;
    hl_tape_free(r->obs);
    r->obs = NULL;
    return HL_OK;
}

int hl_run_compile_(hl_run *r, hl_error *err)
{
    if (r->obs != NULL)
        return HL_OK;
    free(r->vals);
    r->vals = hl_xcalloc((size_t)r->nout, sizeof *r->vals);
    return hl_tape_new(&r->obs, r->outs, r->nout, r->names, 2 * r->N, err);
}

/* ---- the initial point in H's domain ------------------------------------ */

/* "the initial point (q = -1, p = 1) is outside H's domain: H is not finite
 * there"; at(i) is the i-th coordinate as text. */
static int outside_domain(const hl_run *r, char *(*at)(const void *z, int i), const void *z,
                          hl_error *err)
{
    hl_buf b;
    hl_buf_init(&b);
    for (int i = 0; i < 2 * r->N; i++) {
        char *v = at(z, i);
        hl_buf_printf(&b, "%s%s = %s", i ? ", " : "", r->names[i], v);
        free(v);
    }
    int st = hl_error_set(err, HL_EDOM, NULL, -1, 0,
                          "the initial point (%s) is outside H's domain: H is not finite there",
                          b.s);
    hl_buf_clear(&b);
    return st;
}

static char *double_at(const void *z, int i)
{
    char s[40];
    hl_run_fmt_short(s, ((const double *)z)[i]);
    return hl_xstrdup(s);
}

static char *arb_at(const void *z, int i)
{
    char *f = arb_get_str((arb_srcptr)z + i, 17, ARB_STR_NO_RADIUS);
    char *s = hl_xstrdup(f);
    flint_free(f);
    return s;
}

hl_status hl_run_check_start(hl_run *r, const double *z0, hl_error *err)
{
    int st = hl_run_compile_(r, err);
    if (st != HL_OK)
        return st;
    hl_tape_eval_d(r->vals, z0, r->obs);
    return isfinite(r->vals[0]) ? HL_OK : outside_domain(r, double_at, z0, err);
}

hl_status hl_run_check_start_arb(hl_run *r, arb_srcptr z0, slong prec, hl_error *err)
{
    int st = hl_run_compile_(r, err);
    if (st != HL_OK)
        return st;
    arb_ptr vals = _arb_vec_init(r->nout);
    hl_tape_eval_arb(vals, z0, prec, r->obs);
    st = arb_is_finite(vals) ? HL_OK : outside_domain(r, arb_at, z0, err);
    _arb_vec_clear(vals, r->nout);
    return st;
}

/* ---- initial values --------------------------------------------------- */

static int var_index(hl_system *sys, const char *s, size_t n)
{
    int N = hl_system_ndof(sys);
    for (int i = 0; i < 2 * N; i++) {
        const char *v = i < N ? hl_system_coord(sys, i) : hl_system_momentum(sys, i - N);
        if (strlen(v) == n && strncmp(v, s, n) == 0)
            return i;
    }
    return -1;
}

/* A constant formula in Arb, from its exact form (rationals stay exact,
 * sqrt(3) is evaluated at prec). */
static int eval_arb(arb_t r, hl_system *sys, const char *text, slong prec, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg a;
    hl_alg_init(&a, ctx);
    int st = hl_system_read(&a, sys, text, err), nb = hl_alg_ctx_nbase(ctx);
    for (int v = 0; st == HL_OK && v < nb; v++)
        if (hl_alg_depends_on(&a, v, ctx))
            st = hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                              "the value must be a constant, not depend on '%s'",
                              hl_alg_ctx_name(ctx, v));
    if (st == HL_OK) {
        arb_ptr vals = _arb_vec_init(nb);
        st = hl_alg_eval_arb(r, &a, vals, prec, ctx, err);
        _arb_vec_clear(vals, nb);
    }
    hl_alg_clear(&a, ctx);
    return st;
}

/* A value read as 0 or as a subnormal double must be 0, or a number whose
 * ball holds 0 (sin(pi)): a tiny number (1e-400) would silently become 0
 * or lose its digits.  Arb decides. */
static int check_underflow(double x, hl_system *sys, const char *text, hl_error *err)
{
    arb_t v;
    arb_init(v);
    int st = eval_arb(v, sys, text, 64, err);
    if (st == HL_OK && !arb_contains_zero(v))
        st = hl_error_set(err, HL_EDOM, NULL, -1, 0,
                          "the value underflows in double precision (|value| < %.3g: read as "
                          "%g); a run in Arb (--digits) keeps it",
                          DBL_MIN, x);
    arb_clear(v);
    return st;
}

/* The value of one item "name = formula" into z[i] (double) and, when za is
 * not NULL, za + i (Arb at prec bits, from the exact form of the formula). */
static int init_item(double *z, arb_ptr za, slong prec, char *seen, hl_system *sys,
                     const char *init, int a, int b, hl_error *err)
{
    while (a < b && (init[a] == ' ' || init[a] == '\t'))
        a++;
    const char *eq = memchr(init + a, '=', (size_t)(b - a));
    if (eq == NULL)
        return hl_error_set(err, HL_EPARSE, init, a, b > a ? b - a : 1,
                            "expected 'name=value'");
    int e = (int)(eq - init), ne = e;
    while (ne > a && (init[ne - 1] == ' ' || init[ne - 1] == '\t'))
        ne--;
    int i = var_index(sys, init + a, (size_t)(ne - a));
    if (i < 0)
        return hl_error_set(err, HL_EINVAL, init, a, ne > a ? ne - a : 1,
                            "'%.*s' is not a variable of the system", ne - a, init + a);
    if (seen[i])
        return hl_error_set(err, HL_EINVAL, init, a, ne - a, "'%.*s' is given twice",
                            ne - a, init + a);
    char *text = hl_xmalloc((size_t)(b - e));
    memcpy(text, init + e + 1, (size_t)(b - e - 1));
    text[b - e - 1] = '\0';
    /* a plain number is read by strtod: correctly rounded, where the
     * expression evaluator's 13/10 may be off by an ulp */
    char *end;
    errno = 0;
    z[i] = strtod(text, &end);
    int normal = isfinite(z[i]) && (fabs(z[i]) >= DBL_MIN || (z[i] == 0 && errno == 0));
    while (*end == ' ' || *end == '\t')
        end++;
    if (end != text && *end == '\0' && normal && za == NULL) {
        free(text);
        seen[i] = 1;
        return HL_OK;
    }
    const hl_expr *v;
    int st = hl_parse(&v, hl_system_pool(sys), text, err);
    if (st == HL_OK) {
        v = resolve(sys, v);
        double zi;
        st = hl_expr_eval_d(&zi, v, 0, NULL, NULL, err);
        if (st == HL_OK && !isfinite(zi))
            st = hl_error_set(err, HL_EDOM, NULL, -1, 0, "the value is not finite");
        if (st == HL_OK && !(end != text && *end == '\0' && isfinite(z[i])))
            z[i] = zi;
    }
    if (st == HL_OK && za == NULL && fabs(z[i]) < DBL_MIN)
        st = check_underflow(z[i], sys, text, err);
    if (st == HL_OK && za != NULL)
        st = eval_arb(za + i, sys, text, prec, err);
    free(text);
    if (st != HL_OK && err != NULL) {
        if (err->src == NULL || err->pos < 0)
            err->pos = e + 1, err->len = b - e - 1 > 0 ? b - e - 1 : 1;
        else
            err->pos += e + 1;
        err->src = init;
        hl_error_prefix(err, "in the value of '%.*s'", ne - a, init + a);
    }
    seen[i] = 1;
    return st;
}

static int init_values(double *z, arb_ptr za, slong prec, hl_system *sys, const char *init,
                       hl_error *err)
{
    int N = hl_system_ndof(sys), n = (int)strlen(init), depth = 0, a = 0, st = HL_OK;
    char *seen = hl_xcalloc((size_t)(2 * N), 1);
    for (int i = 0; i <= n && st == HL_OK; i++) {
        char c = init[i];
        if (c == '(')
            depth++;
        else if (c == ')')
            depth--;
        else if ((c == ',' && depth == 0) || c == '\0') {
            st = init_item(z, za, prec, seen, sys, init, a, i, err);
            a = i + 1;
        }
    }
    for (int i = 0; i < 2 * N && st == HL_OK; i++)
        if (!seen[i])
            st = hl_error_set(err, HL_EINVAL, init, -1, 0, "no initial value for '%s'",
                              i < N ? hl_system_coord(sys, i) : hl_system_momentum(sys, i - N));
    free(seen);
    return st;
}

hl_status hl_run_init_values(double *z, hl_system *sys, const char *init, hl_error *err)
{
    return init_values(z, NULL, 0, sys, init, err);
}

hl_status hl_run_init_values_arb(arb_ptr z, hl_system *sys, const char *init, slong prec,
                                 hl_error *err)
{
    double *zd = hl_xmalloc((size_t)(2 * hl_system_ndof(sys)) * sizeof *zd);
    int st = init_values(zd, z, prec, sys, init, err);
    free(zd);
    return st;
}

hl_status hl_run_nsteps(long *n, double dt, double t, hl_error *err)
{
    if (!(dt > 0) || !isfinite(dt))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the step dt must be positive and finite (dt = %g)", dt);
    if (!(t >= 0) || !isfinite(t))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the final time t must be >= 0 and finite (t = %g)", t);
    double s = t / dt, k = nearbyint(s);
    if (s > 1e15)
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0, "too many steps: %.3g", s);
    if (fabs(s - k) > 1e-9 * fmax(1, s))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "t = %g is not reachable with dt = %g: %.2f steps", t, dt, s);
    *n = (long)k;
    return HL_OK;
}
