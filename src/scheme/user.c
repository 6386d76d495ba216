/* User schemes written with the system's own scalar names: a map
 * "X = ...; P = ..." or equations "(X-x)/D = (P+p)/2; ...". */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "scheme/scheme_impl.h"

/* Does `name` stand for the next value of variable v?  "X", "Px" or "PX"
 * for x, px; "x_" is x' (primes become '_' before parsing, keeping every
 * position), as in hl_system_read_map. */
static int names_next_of(const char *name, const char *v)
{
    size_t n = strlen(v);
    if (strlen(name) == n + 1 && strncmp(name, v, n) == 0 && name[n] == '_')
        return 1;
    if (strlen(name) != n || strcmp(name, v) == 0)
        return 0;
    int all_upper = 1, first_upper = 1;
    for (size_t i = 0; i < n; i++) {
        if (name[i] != (char)toupper((unsigned char)v[i]))
            all_upper = 0;
        if (name[i] != (i == 0 ? (char)toupper((unsigned char)v[i]) : v[i]))
            first_upper = 0;
    }
    return all_upper || first_upper;
}

typedef struct ureader {
    sb *b;
    hl_system *sys;
    const char *src;  /* as the user wrote it (for positions) */
    hl_error *err;
    int N;
} ureader;

static const char *var_name(hl_system *sys, int a)
{
    int N = hl_system_ndof(sys);
    return a < N ? hl_system_coord(sys, a) : hl_system_momentum(sys, a - N);
}

/* Unknown index of the phase variable whose next value `name` is, or -1. */
static int next_index(ureader *u, const char *name)
{
    for (int a = 0; a < 2 * u->N; a++)
        if (names_next_of(name, var_name(u->sys, a)) &&
            hl_alg_ctx_index(hl_system_ctx(u->sys), name) < 0)
            return a < u->N ? u->b->s->iQ[a] : u->b->s->iP[a - u->N];
    return -1;
}

/* Replace next-point names by the unknowns, H by the Hamiltonian, set
 * parameters by their values; reject any other unknown symbol. */
static int translate(const hl_expr **out, ureader *u, const hl_expr *e, const char *copy)
{
    int n = hl_expr_symbols(e, NULL, 0);
    const char **names = hl_xmalloc((size_t)(n > 0 ? n : 1) * sizeof *names);
    const hl_expr **vals = hl_xmalloc((size_t)(n > 0 ? n : 1) * sizeof *vals);
    hl_expr_symbols(e, names, n);
    hl_alg_ctx *ctx = hl_system_ctx(u->sys);
    int k = 0, st = HL_OK;
    for (int i = 0; i < n && st == HL_OK; i++) {
        int x = next_index(u, names[i]);
        if (x >= 0) {
            vals[k] = sb_usym(u->b, x);
            names[k++] = names[i];
            continue;
        }
        if (strcmp(names[i], "H") == 0 && hl_system_has_H(u->sys)) {
            vals[k] = hl_system_H_expr(u->sys);
            names[k++] = names[i];
            continue;
        }
        int set = -1;
        for (int j = 0; j < hl_system_nset(u->sys); j++)
            if (strcmp(names[i], hl_system_set_name(u->sys, j)) == 0)
                set = j;
        if (set >= 0) {
            vals[k] = hl_system_set_value(u->sys, set);
            names[k++] = names[i];
            continue;
        }
        if (hl_alg_ctx_index(ctx, names[i]) >= 0)
            continue; /* a phase variable, a parameter or D */
        int pos = hl_symbol_pos(copy, names[i]);
        hl_buf l;
        hl_buf_init(&l);
        for (int a = 0; a < 2 * u->N; a++) {
            char *up = scheme_upper(var_name(u->sys, a));
            hl_buf_printf(&l, "%s%s", a ? ", " : "", up);
            free(up);
        }
        st = hl_error_set(u->err, HL_EINVAL, u->src, pos, pos >= 0 ? (int)strlen(names[i]) : 0,
                          "unknown symbol '%s' (the next point is %s, or a name with a prime)",
                          names[i], l.s);
        hl_buf_clear(&l);
    }
    if (st == HL_OK)
        *out = hl_expr_subst(u->b->pool, e, k, names, vals);
    free(names);
    free(vals);
    return st;
}

static int read_user(hl_scheme **out, const char *text, int is_map, hl_system *sys,
                     hl_error *err)
{
    *out = NULL;
    sb b;
    sb_init(&b, sys, is_map ? "user-map" : "user-equations");
    ureader u = {&b, sys, text, err, hl_system_ndof(sys)};
    int max = 2 * u.N + 2;
    for (const char *c = text; *c; c++)
        max += *c == ';';
    char *copy = hl_xstrdup(text);
    for (char *c = copy; *c; c++)
        if (*c == '\'' && c > copy && (isalnum((unsigned char)c[-1]) || c[-1] == '_'))
            *c = '_';
    hl_eqn *items = hl_xmalloc((size_t)max * sizeof *items);
    int n = 0, st = hl_parse_list(items, max, &n, b.pool, copy, err);
    if (st != HL_OK && err != NULL)
        err->src = text;
    for (int i = 0; st == HL_OK && i < n; i++) {
        const hl_eqn *it = &items[i];
        if (it->rhs == NULL) {
            st = hl_error_set(err, HL_EPARSE, text, it->pos, 1,
                              is_map ? "expected 'image = formula'" : "expected an equation");
            break;
        }
        int def = it->lhs->kind == HL_SYM ? next_index(&u, it->lhs->name) : -1;
        if (is_map && def < 0) {
            st = hl_error_set(err, HL_EINVAL, text, it->pos, 1,
                              "the left side of a map item must name the next value of a "
                              "phase variable (X, PX, or x')");
            break;
        }
        const hl_expr *l, *r;
        st = translate(&l, &u, it->lhs, copy);
        if (st == HL_OK)
            st = translate(&r, &u, it->rhs, copy);
        if (st == HL_OK)
            sb_eq(&b, l, r, def);
    }
    free(items);
    free(copy);
    if (st != HL_OK) {
        sb_abort(&b);
        return st;
    }
    st = sb_finish(out, &b, err);
    if (st == HL_OK && is_map)
        for (int i = 0; i < (*out)->m; i++)
            if ((*out)->defines[i] < 0) {
                int d = -1;
                for (int k = 0; k < (*out)->m; k++)
                    if ((*out)->lhs[k] == (*out)->lhs[i] && k < i)
                        d = k;
                hl_scheme_free(*out);
                *out = NULL;
                return hl_error_set(err, HL_EINVAL, text, -1, 0,
                                    "the map gives an image twice (items %d and %d)", d + 1,
                                    i + 1);
            }
    return st;
}

hl_status hl_scheme_from_map(hl_scheme **out, const char *map, hl_system *sys, hl_error *err)
{
    return read_user(out, map, 1, sys, err);
}

hl_status hl_scheme_from_equations(hl_scheme **out, const char *eqs, hl_system *sys, hl_error *err)
{
    return read_user(out, eqs, 0, sys, err);
}
