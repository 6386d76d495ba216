/* A Hamiltonian system: which symbols are coordinates, momenta, parameters;
 * the expression pool and the exact-algebra context that go with them.
 *
 * The pairing of coordinates with momenta comes from --pairs, or else from
 * the names (ham.h gives the rules).  Symbols that are neither are
 * parameters: symbolic, or substituted by the constant given with --param.
 */
#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "ham/ham_impl.h"

/* A growing list of distinct names, in order of first appearance. */
typedef struct namelist {
    int n, cap;
    char **s;
} namelist;

static int names_find(const namelist *l, const char *s)
{
    for (int i = 0; i < l->n; i++)
        if (strcmp(l->s[i], s) == 0)
            return i;
    return -1;
}

static void names_add(namelist *l, const char *s)
{
    if (names_find(l, s) >= 0)
        return;
    if (l->n == l->cap) {
        l->cap = l->cap ? 2 * l->cap : 8;
        l->s = hl_xrealloc(l->s, (size_t)l->cap * sizeof *l->s);
    }
    l->s[l->n++] = hl_xstrdup(s);
}

static void names_clear(namelist *l)
{
    for (int i = 0; i < l->n; i++)
        free(l->s[i]);
    free(l->s);
    l->n = l->cap = 0;
    l->s = NULL;
}

static void names_of_expr(namelist *l, const hl_expr *e, const char *step)
{
    int k = hl_expr_symbols(e, NULL, 0);
    if (k <= 0)
        return;
    const char **v = hl_xmalloc((size_t)k * sizeof *v);
    hl_expr_symbols(e, v, k);
    for (int i = 0; i < k; i++)
        if (strcmp(v[i], step) != 0 && strcmp(v[i], "H") != 0)
            names_add(l, v[i]);
    free(v);
}

/* Names that cannot be a phase variable or a parameter (nor the step). */
static const char *reserved_why(const char *step, const char *s, int len)
{
    if (step != NULL && (int)strlen(step) == len && strncmp(s, step, (size_t)len) == 0)
        return "it is the step's name";
    if (len == 1 && s[0] == 'H')
        return "'H' names the Hamiltonian";
    if (len == 2 && s[0] == 'p' && s[1] == 'i')
        return "'pi' is the constant pi";
    if (hl_fun_lookup(s, len) >= 0)
        return "it is the name of a function";
    return NULL;
}

static int ident_len(const char *s)
{
    int i = 0;
    if (!isalpha((unsigned char)s[0]))
        return 0;
    while (isalnum((unsigned char)s[i]) || s[i] == '_')
        i++;
    return i;
}

static int skip_space(const char *s, int i)
{
    while (s[i] == ' ' || s[i] == '\t')
        i++;
    return i;
}

/* Read one name at s[*i] for an option text; error naming what was wanted. */
static int read_name(char **out, const hl_system *sys, const char *src, int *i,
                     const char *what, hl_error *err)
{
    *i = skip_space(src, *i);
    int len = ident_len(src + *i);
    if (len == 0)
        return hl_error_set(err, HL_EPARSE, src, *i, 1, "expected %s here", what);
    const char *why = reserved_why(sys->step, src + *i, len);
    if (why != NULL)
        return hl_error_set(err, HL_EINVAL, src, *i, len, "'%.*s' cannot be %s: %s", len,
                            src + *i, what, why);
    *out = hl_xmalloc((size_t)len + 1);
    memcpy(*out, src + *i, (size_t)len);
    (*out)[len] = '\0';
    *i = skip_space(src, *i + len);
    return HL_OK;
}

static int phase_index(const hl_system *sys, const char *s)
{
    for (int j = 0; j < sys->n; j++)
        if (strcmp(sys->q[j], s) == 0 || strcmp(sys->p[j], s) == 0)
            return j;
    return -1;
}

static void add_pair(hl_system *sys, char *q, char *p)
{
    sys->q = hl_xrealloc(sys->q, (size_t)(sys->n + 1) * sizeof *sys->q);
    sys->p = hl_xrealloc(sys->p, (size_t)(sys->n + 1) * sizeof *sys->p);
    sys->q[sys->n] = q;
    sys->p[sys->n] = p;
    sys->n++;
}

/* "x:px, y:py" */
static int parse_pairs(hl_system *sys, const char *src, hl_error *err)
{
    int i = 0;
    for (;;) {
        char *q = NULL, *p = NULL;
        int qpos = skip_space(src, i), st;
        if ((st = read_name(&q, sys, src, &i, "a coordinate", err)) != HL_OK)
            return st;
        if (src[i] != ':') {
            free(q);
            return hl_error_set(err, HL_EPARSE, src, i, 1,
                                "expected ':' and the momentum paired with '%.*s'",
                                ident_len(src + qpos), src + qpos);
        }
        i++;
        int ppos = skip_space(src, i);
        if (ident_len(src + ppos) == 0) {
            hl_error_set(err, HL_EINVAL, src, ppos, 1,
                         "momentum missing after '%s:': each pair is coordinate:momentum, "
                         "e.g. %s:p%s", q, q, q);
            free(q);
            return HL_EINVAL;
        }
        if ((st = read_name(&p, sys, src, &i, "a momentum", err)) != HL_OK) {
            free(q);
            return st;
        }
        if (phase_index(sys, q) >= 0 || strcmp(q, p) == 0) {
            hl_error_set(err, HL_EINVAL, src, qpos, (int)strlen(q),
                         "name '%s' used twice in the pairs", q);
            free(q), free(p);
            return HL_EINVAL;
        }
        if (phase_index(sys, p) >= 0) {
            hl_error_set(err, HL_EINVAL, src, ppos, (int)strlen(p),
                         "name '%s' used twice in the pairs", p);
            free(q), free(p);
            return HL_EINVAL;
        }
        add_pair(sys, q, p);
        if (src[i] == '\0')
            return HL_OK;
        if (src[i] != ',')
            return hl_error_set(err, HL_EPARSE, src, i, 1,
                                "expected ',' between pairs (write them as x:px,y:py)");
        i++;
    }
}

/* ---- default pairing ----------------------------------------------------- */

static int is_letter_momentum(const char *s)
{
    return s[0] == 'p' && isalpha((unsigned char)s[1]) && s[2] == '\0' && s[1] != 'p';
}

static int numbered(const char *s, char c)
{
    if (s[0] != c || !isdigit((unsigned char)s[1]))
        return 0;
    for (int i = 1; s[i]; i++)
        if (!isdigit((unsigned char)s[i]))
            return 0;
    return 1;
}

/* The fixed order of inferred coordinates (and of parameters), whatever the
 * order in which H mentions them: x, y, z first; then names with a numeric
 * index (q1, q2, ..., q10), by their letters and then by the index as a
 * number; then the rest by name. */
static int name_class(const char *s, int *stem)
{
    if (s[1] == '\0' && s[0] >= 'x' && s[0] <= 'z')
        return s[0] - 'x';
    int i = (int)strlen(s);
    while (i > 0 && isdigit((unsigned char)s[i - 1]))
        i--;
    *stem = i;
    return i > 0 && s[i] != '\0' ? 3 : 4;
}

/* Decimal digit strings compared as numbers (leading zeros ignored). */
static int cmp_digits(const char *a, const char *b)
{
    while (*a == '0' && a[1] != '\0')
        a++;
    while (*b == '0' && b[1] != '\0')
        b++;
    size_t la = strlen(a), lb = strlen(b);
    if (la != lb)
        return la < lb ? -1 : 1;
    return strcmp(a, b);
}

static int cmp_names(const char *a, const char *b)
{
    int sa = 0, sb = 0, ca = name_class(a, &sa), cb = name_class(b, &sb);
    if (ca != cb)
        return ca - cb;
    if (ca == 3) {
        int c = strncmp(a, b, (size_t)(sa < sb ? sa : sb));
        if (c == 0 && sa != sb)
            c = sa - sb;
        if (c == 0)
            c = cmp_digits(a + sa, b + sb);
        if (c != 0)
            return c;
    }
    return strcmp(a, b);
}

static int cmp_name_ptrs(const void *a, const void *b)
{
    return cmp_names(*(char *const *)a, *(char *const *)b);
}

/* Put inferred pairs in the fixed order of their coordinates (insertion
 * sort: a handful of pairs, and q and p move together). */
static void sort_pairs(hl_system *sys)
{
    for (int i = 1; i < sys->n; i++)
        for (int j = i; j > 0 && cmp_names(sys->q[j - 1], sys->q[j]) > 0; j--) {
            char *q = sys->q[j], *p = sys->p[j];
            sys->q[j] = sys->q[j - 1], sys->p[j] = sys->p[j - 1];
            sys->q[j - 1] = q, sys->p[j - 1] = p;
        }
}

static int infer_pairs(hl_system *sys, const namelist *syms, const char *Hsrc, hl_error *err)
{
    /* px, py, ...: momenta named after their coordinates. */
    for (int i = 0; i < syms->n; i++) {
        const char *s = syms->s[i];
        char q[2] = {0, 0};
        if (is_letter_momentum(s))
            q[0] = s[1];
        else if (strlen(s) == 1 && isalpha((unsigned char)s[0])) {
            char pn[3] = {'p', s[0], 0};
            if (names_find(syms, pn) >= 0 && is_letter_momentum(pn))
                q[0] = s[0];
        }
        if (q[0] && phase_index(sys, q) < 0) {
            char pn[3] = {'p', q[0], 0};
            add_pair(sys, hl_xstrdup(q), hl_xstrdup(pn));
        }
    }
    if (sys->n > 0) {
        sort_pairs(sys);
        return HL_OK;
    }

    /* q1..qN with p1..pN, in the order of the index. */
    namelist k = {0, 0, NULL};
    for (int i = 0; i < syms->n; i++)
        if (numbered(syms->s[i], 'q') || numbered(syms->s[i], 'p')) {
            char buf[64];
            snprintf(buf, sizeof buf, "q%s", syms->s[i] + 1);
            names_add(&k, buf);
        }
    if (k.n > 0) {
        qsort(k.s, (size_t)k.n, sizeof *k.s, cmp_name_ptrs);
        for (int i = 0; i < k.n; i++) {
            char buf[64];
            snprintf(buf, sizeof buf, "p%s", k.s[i] + 1);
            add_pair(sys, hl_xstrdup(k.s[i]), hl_xstrdup(buf));
        }
        names_clear(&k);
        return HL_OK;
    }

    /* p with q, else p with x. */
    int hp = names_find(syms, "p") >= 0, hq = names_find(syms, "q") >= 0;
    int hx = names_find(syms, "x") >= 0;
    if (hq) {
        add_pair(sys, hl_xstrdup("q"), hl_xstrdup("p"));
        return HL_OK;
    }
    if (hp && hx) {
        add_pair(sys, hl_xstrdup("x"), hl_xstrdup("p"));
        return HL_OK;
    }
    if (hp) {
        int pos = Hsrc ? hl_symbol_pos(Hsrc, "p") : -1;
        return hl_error_set(err, HL_EINVAL, pos >= 0 ? Hsrc : NULL, pos, 1,
                            "cannot infer the coordinate paired with momentum 'p' "
                            "(neither 'q' nor 'x' appears); name it with --pairs, "
                            "e.g. --pairs q:p");
    }
    hl_buf b;
    hl_buf_init(&b);
    for (int i = 0; i < syms->n; i++)
        hl_buf_printf(&b, "%s'%s'", i ? ", " : "", syms->s[i]);
    hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                 "cannot tell coordinates from momenta among the symbols %s; "
                 "name the pairs with --pairs, e.g. --pairs q:p or --pairs x:px,y:py",
                 syms->n ? b.s : "(none)");
    hl_buf_clear(&b);
    return HL_EINVAL;
}

/* ---- parameters ------------------------------------------------------------ */

static int set_index(const hl_system *sys, const char *s)
{
    for (int i = 0; i < sys->nset; i++)
        if (strcmp(sys->set[i].name, s) == 0)
            return i;
    return -1;
}

/* Re-point an error found in a copy of part of src back into src. */
static void shift_error(hl_error *err, const char *src, int offset)
{
    if (err == NULL)
        return;
    err->src = src;
    if (err->pos >= 0)
        err->pos += offset;
}

/* "k=2, m=1/2": each name must be a parameter of the system (in syms, not a
 * phase variable); each value a constant. */
static int parse_params(hl_system *sys, const char *src, const namelist *syms, hl_error *err)
{
    int i = 0;
    for (;;) {
        char *name = NULL;
        int npos = skip_space(src, i), st;
        if ((st = read_name(&name, sys, src, &i, "a parameter name", err)) != HL_OK)
            return st;
        int len = (int)strlen(name);
        if (phase_index(sys, name) >= 0) {
            hl_error_set(err, HL_EINVAL, src, npos, len,
                         "'%s' is a phase variable of this system, not a parameter", name);
            free(name);
            return HL_EINVAL;
        }
        if (names_find(syms, name) < 0) {
            hl_error_set(err, HL_EINVAL, src, npos, len,
                         "no symbol '%s' in the system's formulas", name);
            free(name);
            return HL_EINVAL;
        }
        if (set_index(sys, name) >= 0) {
            hl_error_set(err, HL_EINVAL, src, npos, len,
                         "parameter '%s' given a value twice", name);
            free(name);
            return HL_EINVAL;
        }
        if (src[i] != '=') {
            free(name);
            return hl_error_set(err, HL_EPARSE, src, i, 1,
                                "expected '=' and a value (write --param k=2)");
        }
        i++;
        int vpos = i, vend = i;
        while (src[vend] && src[vend] != ',')
            vend++;
        char *text = hl_xmalloc((size_t)(vend - vpos) + 1);
        memcpy(text, src + vpos, (size_t)(vend - vpos));
        text[vend - vpos] = '\0';
        const hl_expr *val = NULL;
        st = hl_parse(&val, sys->pool, text, err);
        if (st != HL_OK) {
            shift_error(err, src, vpos);
            hl_error_prefix(err, "value of parameter '%s'", name);
            free(text), free(name);
            return st;
        }
        const char *first = NULL;
        if (hl_expr_symbols(val, &first, 1) > 0) {
            int p = hl_symbol_pos(text, first);
            hl_error_set(err, HL_EINVAL, src, p >= 0 ? vpos + p : vpos, (int)strlen(first),
                         "the value of parameter '%s' is not a constant: it mentions '%s'",
                         name, first);
            free(text), free(name);
            return HL_EINVAL;
        }
        free(text);
        sys->set = hl_xrealloc(sys->set, (size_t)(sys->nset + 1) * sizeof *sys->set);
        sys->set[sys->nset].name = name;
        sys->set[sys->nset].val = val;
        sys->nset++;
        if (src[vend] == '\0')
            return HL_OK;
        i = vend + 1;
    }
}

/* A value like 1/(1-1) parses; catch it now, pointing at the --param text. */
static int check_param_values(hl_system *sys, const char *src, hl_error *err)
{
    hl_alg t;
    hl_alg_init(&t, sys->ctx);
    int st = HL_OK;
    for (int i = 0; i < sys->nset && st == HL_OK; i++) {
        st = hl_alg_from_expr(&t, sys->set[i].val, sys->ctx, err);
        if (st != HL_OK) {
            int p = hl_symbol_pos(src, sys->set[i].name);
            if (err) {
                err->src = src;
                err->pos = p;
                err->len = (int)strlen(sys->set[i].name);
            }
            hl_error_prefix(err, "value of parameter '%s'", sys->set[i].name);
        }
    }
    hl_alg_clear(&t, sys->ctx);
    return st;
}

/* ---- construction ------------------------------------------------------------ */

static int collect_symbols(namelist *syms, hl_system *sys, const hl_system_spec *spec,
                           const hl_expr **H, hl_error *err)
{
    int st;
    if (spec->H != NULL) {
        if ((st = hl_parse(H, sys->pool, spec->H, err)) != HL_OK)
            return st;
        if (hl_expr_has_symbol(*H, "H"))
            return hl_error_set(err, HL_EINVAL, spec->H, hl_symbol_pos(spec->H, "H"), 1,
                                "the Hamiltonian cannot refer to 'H'");
        if (hl_expr_has_symbol(*H, sys->step))
            return ham_step_refused(sys, spec->H, 0, "the Hamiltonian", err);
        names_of_expr(syms, *H, sys->step);
    }
    for (int k = 0; spec->extra != NULL && spec->extra[k] != NULL; k++) {
        const char *src = spec->extra[k];
        int max = 2;
        for (const char *c = src; *c; c++)
            max += *c == ';';
        hl_eqn *items = hl_xmalloc((size_t)max * sizeof *items);
        int n = 0;
        char *copy = hl_xstrdup(src);
        /* x' on a left side is a name with a prime: same length with '_'. */
        for (char *c = copy; *c; c++)
            if (*c == '\'' && c > copy && (isalnum((unsigned char)c[-1]) || c[-1] == '_'))
                *c = '_';
        st = hl_parse_list(items, max, &n, sys->pool, copy, err);
        if (st != HL_OK) {
            shift_error(err, src, 0);
            free(items), free(copy);
            return st;
        }
        ham_chain_images(items, n, sys->pool); /* an earlier image is no symbol */
        for (int i = 0; i < n; i++)
            names_of_expr(syms, items[i].rhs ? items[i].rhs : items[i].lhs, sys->step);
        free(items), free(copy);
    }
    return HL_OK;
}

static int build_ctx(hl_system *sys, const namelist *syms)
{
    for (int i = 0; i < syms->n; i++)
        if (phase_index(sys, syms->s[i]) < 0 && set_index(sys, syms->s[i]) < 0) {
            sys->param = hl_xrealloc(sys->param, (size_t)(sys->nparam + 1) * sizeof *sys->param);
            sys->param[sys->nparam++] = hl_xstrdup(syms->s[i]);
        }
    if (sys->nparam > 1)
        qsort(sys->param, (size_t)sys->nparam, sizeof *sys->param, cmp_name_ptrs);
    int nb = 2 * sys->n + sys->nparam + 1;
    const char **names = hl_xmalloc((size_t)nb * sizeof *names);
    for (int j = 0; j < sys->n; j++) {
        names[j] = sys->q[j];
        names[sys->n + j] = sys->p[j];
    }
    for (int i = 0; i < sys->nparam; i++)
        names[2 * sys->n + i] = sys->param[i];
    names[nb - 1] = sys->step;
    sys->ctx = hl_alg_ctx_new(nb, names, 0);
    hl_alg_ctx_set_step(sys->ctx, nb - 1); /* print by powers of the step */
    free(names);
    return sys->ctx != NULL ? HL_OK : HL_ENOMEM;
}

static const hl_expr *subst_params(hl_system *sys, const hl_expr *e)
{
    if (sys->nset == 0)
        return e;
    const char **names = hl_xmalloc((size_t)sys->nset * sizeof *names);
    const hl_expr **vals = hl_xmalloc((size_t)sys->nset * sizeof *vals);
    for (int i = 0; i < sys->nset; i++) {
        names[i] = sys->set[i].name;
        vals[i] = sys->set[i].val;
    }
    e = hl_expr_subst(sys->pool, e, sys->nset, names, vals);
    free(names), free(vals);
    return e;
}

/* The step's name from the spec: a name that is no function, H or pi. */
static int set_step(hl_system *sys, const char *name, hl_error *err)
{
    if (name == NULL)
        name = "D";
    int len = ident_len(name);
    if (len == 0 || name[len] != '\0')
        return hl_error_set(err, HL_EINVAL, name, len, 1,
                            "the step's name must be a name (letters, digits, '_'), "
                            "like D or h");
    const char *why = reserved_why(NULL, name, len);
    if (why != NULL)
        return hl_error_set(err, HL_EINVAL, name, 0, len,
                            "'%s' cannot be the step's name: %s", name, why);
    sys->step = hl_xstrdup(name);
    return HL_OK;
}

hl_status hl_system_new(hl_system **out, const hl_system_spec *spec, hl_error *err)
{
    hl_system *sys = hl_xcalloc(1, sizeof *sys);
    namelist syms = {0, 0, NULL};
    const hl_expr *H = NULL;
    int st;

    *out = NULL;
    sys->pool = hl_pool_new();
    if ((st = set_step(sys, spec->step, err)) != HL_OK)
        goto fail;
    if ((st = collect_symbols(&syms, sys, spec, &H, err)) != HL_OK)
        goto fail;
    if (spec->pairs != NULL)
        st = parse_pairs(sys, spec->pairs, err);
    else
        st = infer_pairs(sys, &syms, spec->H, err);
    if (st != HL_OK)
        goto fail;
    if (spec->params != NULL && (st = parse_params(sys, spec->params, &syms, err)) != HL_OK)
        goto fail;
    if ((st = build_ctx(sys, &syms)) != HL_OK)
        goto fail;
    hl_alg_init(&sys->H, sys->ctx);
    if (spec->params != NULL && (st = check_param_values(sys, spec->params, err)) != HL_OK)
        goto fail;
    if (H != NULL) {
        /* Terms in a fixed order: how H is written changes no number. */
        H = hl_expr_ordered(sys->pool, H);
        sys->H_expr = subst_params(sys, H);
        if ((st = ham_read_expr(&sys->H, sys, H, spec->H, 0, err)) != HL_OK) {
            hl_error_prefix(err, "in the Hamiltonian");
            goto fail;
        }
        sys->has_H = 1;
    }
    names_clear(&syms);
    *out = sys;
    return HL_OK;
fail:
    names_clear(&syms);
    hl_system_free(sys);
    return st;
}

void hl_system_free(hl_system *sys)
{
    if (sys == NULL)
        return;
    if (sys->ctx != NULL) {
        hl_alg_clear(&sys->H, sys->ctx);
        hl_alg_vec_free(sys->xi, sys->n, sys->ctx);
        hl_alg_vec_free(sys->eta, sys->n, sys->ctx);
        hl_alg_ctx_free(sys->ctx);
    }
    for (int j = 0; j < sys->n; j++)
        free(sys->q[j]), free(sys->p[j]);
    free(sys->q), free(sys->p);
    for (int i = 0; i < sys->nparam; i++)
        free(sys->param[i]);
    free(sys->param);
    for (int i = 0; i < sys->nset; i++)
        free(sys->set[i].name);
    free(sys->set);
    hl_pool_free(sys->pool);
    free(sys->step);
    free(sys);
}

int hl_system_ndof(const hl_system *sys) { return sys->n; }
const char *hl_system_coord(const hl_system *sys, int j) { return sys->q[j]; }
const char *hl_system_momentum(const hl_system *sys, int j) { return sys->p[j]; }
int hl_system_nparams(const hl_system *sys) { return sys->nparam; }
const char *hl_system_param(const hl_system *sys, int i) { return sys->param[i]; }
int hl_system_has_H(const hl_system *sys) { return sys->has_H; }
const char *hl_system_step(const hl_system *sys) { return sys->step; }
hl_alg_ctx *hl_system_ctx(hl_system *sys) { return sys->ctx; }
hl_pool *hl_system_pool(hl_system *sys) { return sys->pool; }
const hl_alg *hl_system_H(const hl_system *sys) { return sys->has_H ? &sys->H : NULL; }
const hl_expr *hl_system_H_expr(const hl_system *sys) { return sys->H_expr; }
int hl_system_var_q(const hl_system *sys, int j) { return j; }
int hl_system_var_p(const hl_system *sys, int j) { return sys->n + j; }
int hl_system_var_D(const hl_system *sys) { return 2 * sys->n + sys->nparam; }

int hl_system_nset(const hl_system *sys) { return sys->nset; }
const char *hl_system_set_name(const hl_system *sys, int i) { return sys->set[i].name; }
const hl_expr *hl_system_set_value(const hl_system *sys, int i) { return sys->set[i].val; }
