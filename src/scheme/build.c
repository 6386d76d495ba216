/* Building an instantiated scheme: unknowns, scalar equations, integrals;
 * which equations are explicit; the unknowns' values at D = 0. */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "scheme/scheme_impl.h"

char *scheme_upper(const char *v)
{
    char *u = hl_xstrdup(v);
    for (char *c = u; *c; c++)
        *c = (char)toupper((unsigned char)*c);
    return u;
}

void scheme_point(const hl_expr **v, hl_system *sys)
{
    int N = hl_system_ndof(sys);
    hl_pool *pool = hl_system_pool(sys);
    for (int j = 0; j < N; j++) {
        v[j] = hl_sym(pool, hl_system_coord(sys, j));
        v[N + j] = hl_sym(pool, hl_system_momentum(sys, j));
    }
}

const hl_expr *scheme_dH(hl_system *sys, int j, int wrt_p)
{
    const hl_expr *H = hl_system_H_expr(sys);
    if (!hl_system_has_H(sys) || H == NULL)
        return NULL;
    const char *v = wrt_p ? hl_system_momentum(sys, j) : hl_system_coord(sys, j);
    return hl_expr_diff(hl_system_pool(sys), H, v);
}

void hl_scheme_free(hl_scheme *s)
{
    if (s == NULL)
        return;
    for (int i = 0; i < s->m; i++) {
        free(s->unknown[i]);
        free(s->display[i]);
    }
    for (int i = 0; i < s->nint; i++)
        free(s->int_name[i]);
    free(s->unknown), free(s->display), free(s->z0);
    free(s->lhs), free(s->rhs), free(s->defines), free(s->expl);
    free(s->iQ), free(s->iP), free(s->int_name), free(s->int_body);
    free(s->name);
    free(s);
}

/* ---- the builder ---------------------------------------------------------- */

int sb_unknown(sb *b, const char *reserved, const char *display, const hl_expr *z0)
{
    hl_scheme *s = b->s;
    if (s->m == b->cap_u) {
        b->cap_u = 2 * b->cap_u + 8;
        s->unknown = hl_xrealloc(s->unknown, (size_t)b->cap_u * sizeof *s->unknown);
        s->display = hl_xrealloc(s->display, (size_t)b->cap_u * sizeof *s->display);
        s->z0 = hl_xrealloc(s->z0, (size_t)b->cap_u * sizeof *s->z0);
    }
    s->unknown[s->m] = hl_xstrdup(reserved);
    s->display[s->m] = hl_xstrdup(display);
    s->z0[s->m] = z0;
    return s->m++;
}

const hl_expr *sb_usym(sb *b, int u)
{
    return hl_sym(b->pool, b->s->unknown[u]);
}

int sb_find(const sb *b, const char *name)
{
    for (int u = 0; u < b->s->m; u++)
        if (strcmp(b->s->unknown[u], name) == 0)
            return u;
    return -1;
}

void sb_eq(sb *b, const hl_expr *lhs, const hl_expr *rhs, int defines)
{
    hl_scheme *s = b->s;
    if (b->neq == b->cap_e) {
        b->cap_e = 2 * b->cap_e + 8;
        s->lhs = hl_xrealloc(s->lhs, (size_t)b->cap_e * sizeof *s->lhs);
        s->rhs = hl_xrealloc(s->rhs, (size_t)b->cap_e * sizeof *s->rhs);
        s->defines = hl_xrealloc(s->defines, (size_t)b->cap_e * sizeof *s->defines);
    }
    s->lhs[b->neq] = lhs;
    s->rhs[b->neq] = rhs;
    s->defines[b->neq] = defines;
    b->neq++;
}

const hl_expr *sb_integral(sb *b, const hl_expr *body)
{
    hl_scheme *s = b->s;
    if (s->nint == b->cap_i) {
        b->cap_i = 2 * b->cap_i + 4;
        s->int_name = hl_xrealloc(s->int_name, (size_t)b->cap_i * sizeof *s->int_name);
        s->int_body = hl_xrealloc(s->int_body, (size_t)b->cap_i * sizeof *s->int_body);
    }
    hl_buf nb;
    hl_buf_init(&nb);
    hl_buf_printf(&nb, "I#%d", s->nint + 1);
    s->int_name[s->nint] = hl_buf_take(&nb);
    s->int_body[s->nint] = body;
    return hl_sym(b->pool, s->int_name[s->nint++]);
}

void sb_init(sb *b, hl_system *sys, const char *name)
{
    memset(b, 0, sizeof *b);
    b->sys = sys;
    b->pool = hl_system_pool(sys);
    hl_scheme *s = hl_xcalloc(1, sizeof *s);
    b->s = s;
    s->sys = sys;
    s->name = hl_xstrdup(name);
    int N = hl_system_ndof(sys);
    s->N = N;
    s->iQ = hl_xmalloc((size_t)(N > 0 ? N : 1) * sizeof *s->iQ);
    s->iP = hl_xmalloc((size_t)(N > 0 ? N : 1) * sizeof *s->iP);
    hl_buf nb;
    hl_buf_init(&nb);
    for (int w = 0; w < 2; w++)
        for (int j = 0; j < N; j++) {
            const char *v = w ? hl_system_momentum(sys, j) : hl_system_coord(sys, j);
            char *up = scheme_upper(v);
            hl_buf_printf(&nb, "%s#%d", w ? "P" : "Q", j + 1);
            char *res = hl_buf_take(&nb);
            int u = sb_unknown(b, res, strcmp(up, v) ? up : res, hl_sym(b->pool, v));
            (w ? s->iP : s->iQ)[j] = u;
            free(res);
            free(up);
        }
    hl_buf_clear(&nb);
}

void sb_abort(sb *b)
{
    hl_scheme_free(b->s);
    b->s = NULL;
}

/* Symbols of e, with each integral's symbol replaced by those of its body. */
static int depends_only_on_before(const hl_scheme *s, const hl_expr *e, const int *defined_at,
                                  int i, int depth)
{
    int n = hl_expr_symbols(e, NULL, 0);
    const char **names = hl_xmalloc((size_t)(n > 0 ? n : 1) * sizeof *names);
    hl_expr_symbols(e, names, n);
    int ok = 1;
    for (int k = 0; ok && k < n; k++) {
        for (int u = 0; u < s->m; u++)
            if (strcmp(names[k], s->unknown[u]) == 0) {
                ok = defined_at[u] >= 0 && defined_at[u] < i;
                break;
            }
        for (int t = 0; ok && t < s->nint && depth == 0; t++)
            if (strcmp(names[k], s->int_name[t]) == 0)
                ok = depends_only_on_before(s, s->int_body[t], defined_at, i, 1);
    }
    free(names);
    return ok;
}

static void mark_explicit(hl_scheme *s)
{
    int *defined_at = hl_xmalloc((size_t)s->m * sizeof *defined_at);
    for (int u = 0; u < s->m; u++)
        defined_at[u] = -1;
    for (int i = 0; i < s->m; i++) {
        int u = s->defines[i];
        if (u >= 0 && defined_at[u] >= 0)
            s->defines[i] = -1; /* defined twice: only the first one counts */
        else if (u >= 0)
            defined_at[u] = i;
    }
    s->all_explicit = 1;
    for (int i = 0; i < s->m; i++) {
        s->expl[i] = s->defines[i] >= 0 &&
                     depends_only_on_before(s, s->rhs[i], defined_at, i, 0);
        s->all_explicit &= s->expl[i];
    }
    free(defined_at);
}

/* e with the integrals replaced by their integrand at s = 0 (the value at
 * D = 0 of an integrand that depends on s only through s*O(D)), D by 0 and
 * the unknowns known at D = 0 by their values. */
const hl_expr *scheme_at_zero(const hl_scheme *s, hl_pool *pool, const hl_expr *e)
{
    int n = s->nint + s->m + 2, k = 0;
    const char **names = hl_xmalloc((size_t)n * sizeof *names);
    const hl_expr **vals = hl_xmalloc((size_t)n * sizeof *vals);
    const hl_expr *zero = hl_num_si(pool, 0);
    const char *s0 = HL_SCHEME_S;
    for (int t = 0; t < s->nint; t++) {
        names[k] = s->int_name[t];
        vals[k++] = hl_expr_subst(pool, s->int_body[t], 1, &s0, &zero);
    }
    e = hl_expr_subst(pool, e, k, names, vals);
    k = 0;
    names[k] = hl_system_step(s->sys);
    vals[k++] = zero;
    for (int u = 0; u < s->m; u++)
        if (s->z0[u] != NULL) {
            names[k] = s->unknown[u];
            vals[k++] = s->z0[u];
        }
    e = hl_expr_subst(pool, e, k, names, vals);
    free(names);
    free(vals);
    return e;
}

/* Values at D = 0 of the unknowns that were not given one: from their
 * defining equations, in as many passes as it takes. */
static int derive_z0(hl_scheme *s, hl_pool *pool, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(s->sys);
    int nb = hl_alg_ctx_nbase(ctx);
    const char **names = hl_xmalloc((size_t)(nb + s->m) * sizeof *names);
    for (int i = 0; i < nb; i++)
        names[i] = hl_alg_ctx_name(ctx, i);
    for (int u = 0; u < s->m; u++)
        names[nb + u] = s->unknown[u];
    hl_alg_ctx *aux = hl_alg_ctx_new(nb + s->m, names, 64);
    free(names);
    hl_alg a;
    hl_alg_init(&a, aux);
    hl_error why;
    hl_error_clear(&why);
    int progress = 1, status = HL_OK;
    while (progress) {
        progress = 0;
        for (int i = 0; i < s->m; i++) {
            int u = s->defines[i];
            if (u < 0 || s->z0[u] != NULL)
                continue;
            const hl_expr *e = scheme_at_zero(s, pool, s->rhs[i]);
            hl_error e2;
            if (hl_alg_from_expr(&a, e, aux, &e2) != HL_OK) {
                why = e2;
                continue;
            }
            int free_of = 1;
            for (int v = 0; v < s->m && free_of; v++)
                free_of = !hl_alg_depends_on(&a, nb + v, aux);
            if (!free_of)
                continue;
            s->z0[u] = hl_alg_to_expr(&a, aux, pool);
            progress = 1;
        }
    }
    for (int u = 0; u < s->m && status == HL_OK; u++)
        if (s->z0[u] == NULL) {
            if (why.status != HL_OK)
                status = hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                      "cannot determine the value of '%s' at D = 0: %s",
                                      s->display[u], why.msg);
            else
                status = hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                      "cannot determine the value of '%s' at D = 0 (give it "
                                      "as the left side of an equation whose right side is "
                                      "known at D = 0)",
                                      s->display[u]);
        }
    hl_alg_clear(&a, aux);
    hl_alg_ctx_free(aux);
    return status;
}

int sb_finish(hl_scheme **out, sb *b, hl_error *err)
{
    hl_scheme *s = b->s;
    *out = NULL;
    if (b->neq != s->m) {
        hl_buf l;
        hl_buf_init(&l);
        for (int u = 0; u < s->m && u < 12; u++)
            hl_buf_printf(&l, "%s%s", u ? ", " : "", s->display[u]);
        if (s->m > 12)
            hl_buf_puts(&l, ", ...");
        hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                     "wrong number of equations: %d scalar equation%s for %d unknowns (%s)",
                     b->neq, b->neq == 1 ? "" : "s", s->m, l.s);
        hl_buf_clear(&l);
        sb_abort(b);
        return HL_EINVAL;
    }
    s->expl = hl_xcalloc((size_t)(s->m > 0 ? s->m : 1), sizeof *s->expl);
    mark_explicit(s);
    int status = derive_z0(s, b->pool, err);
    if (status != HL_OK) {
        sb_abort(b);
        return status;
    }
    *out = s;
    b->s = NULL;
    return HL_OK;
}
