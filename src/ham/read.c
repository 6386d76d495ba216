/* Reading formulas and maps of a system into exact algebra, with errors that
 * point at the offending symbol in the text the user typed. */
#include <ctype.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "ham/ham_impl.h"

static int is_known(const hl_system *sys, const char *s)
{
    if (strcmp(s, sys->step) == 0 || hl_alg_ctx_index(sys->ctx, s) >= 0)
        return 1;
    for (int i = 0; i < sys->nset; i++)
        if (strcmp(sys->set[i].name, s) == 0)
            return 1;
    return 0;
}

static void list_names(hl_buf *b, const char *what, char *const *v, int n)
{
    if (n == 0)
        return;
    hl_buf_printf(b, "%s%s ", b->len ? "; " : "", what);
    for (int i = 0; i < n; i++)
        hl_buf_printf(b, "%s%s", i ? ", " : "", v[i]);
}

static int unknown_symbol(const hl_system *sys, const char *name, const char *src, int offset,
                          hl_error *err)
{
    hl_buf b;
    hl_buf_init(&b);
    list_names(&b, sys->n == 1 ? "coordinate" : "coordinates", sys->q, sys->n);
    list_names(&b, sys->n == 1 ? "momentum" : "momenta", sys->p, sys->n);
    list_names(&b, sys->nparam == 1 ? "parameter" : "parameters", sys->param, sys->nparam);
    int pos = src ? hl_symbol_pos(src + offset, name) : -1;
    hl_error_set(err, HL_EINVAL, pos >= 0 ? src : NULL, pos >= 0 ? pos + offset : -1,
                 (int)strlen(name),
                 "unknown symbol '%s': not a coordinate, momentum or parameter of this "
                 "system (%s)", name, b.s ? b.s : "no variables");
    hl_buf_clear(&b);
    return HL_EINVAL;
}

int ham_read_expr(hl_alg *out, hl_system *sys, const hl_expr *e, const char *src, int offset,
                  hl_error *err)
{
    int k = hl_expr_symbols(e, NULL, 0);
    const char **syms = hl_xmalloc((size_t)(k > 0 ? k : 1) * sizeof *syms);
    hl_expr_symbols(e, syms, k);
    int uses_H = 0, st = HL_OK;
    for (int i = 0; i < k && st == HL_OK; i++) {
        if (strcmp(syms[i], "H") == 0) {
            uses_H = 1;
            if (!sys->has_H) {
                int pos = src ? hl_symbol_pos(src + offset, "H") : -1;
                st = hl_error_set(err, HL_EINVAL, pos >= 0 ? src : NULL,
                                  pos >= 0 ? pos + offset : -1, 1,
                                  "'H' names the Hamiltonian, but none was given "
                                  "(give it with -H)");
            }
        } else if (!is_known(sys, syms[i]))
            st = unknown_symbol(sys, syms[i], src, offset, err);
    }
    free(syms);
    if (st != HL_OK)
        return st;

    /* Substitute H and the set parameters in one simultaneous pass. */
    int m = sys->nset + 1, j = 0;
    const char **names = hl_xmalloc((size_t)m * sizeof *names);
    const hl_expr **vals = hl_xmalloc((size_t)m * sizeof *vals);
    if (uses_H) {
        names[j] = "H";
        vals[j++] = sys->H_expr;
    }
    for (int i = 0; i < sys->nset; i++) {
        names[j] = sys->set[i].name;
        vals[j++] = sys->set[i].val;
    }
    if (j > 0)
        e = hl_expr_subst(sys->pool, e, j, names, vals);
    free(names), free(vals);

    st = hl_alg_from_expr(out, e, sys->ctx, err);
    if (st != HL_OK && err != NULL && err->src == NULL) {
        /* alg knows no text: the error concerns the formula as a whole. */
        err->src = src;
        err->pos = -1;
    }
    return st;
}

hl_status hl_system_read(hl_alg *out, hl_system *sys, const char *formula, hl_error *err)
{
    const hl_expr *e;
    int st = hl_parse(&e, sys->pool, formula, err);
    if (st != HL_OK)
        return st;
    return ham_read_expr(out, sys, e, formula, 0, err);
}

int ham_step_refused(const hl_system *sys, const char *src, int offset, const char *what,
                     hl_error *err)
{
    int pos = src ? hl_symbol_pos(src + offset, sys->step) : -1;
    const char *other = strcmp(sys->step, "h") != 0 ? "h" : "dt";
    return hl_error_set(err, HL_EINVAL, pos >= 0 ? src : NULL, pos >= 0 ? pos + offset : -1,
                        (int)strlen(sys->step),
                        "'%s' is the step's name and cannot appear in %s; if it is a "
                        "parameter (a Morse depth D, say), give the step another name: "
                        "--step %s",
                        sys->step, what, other);
}

hl_status hl_system_read_phase(hl_alg *out, hl_system *sys, const char *formula, hl_error *err)
{
    const hl_expr *e;
    int st = hl_parse(&e, sys->pool, formula, err);
    if (st != HL_OK)
        return st;
    if (hl_expr_has_symbol(e, sys->step))
        return ham_step_refused(sys, formula, 0, "a function of the phase variables", err);
    return ham_read_expr(out, sys, e, formula, 0, err);
}

/* ---- maps ------------------------------------------------------------------- */

/* Does the left side `lhs` name the image of variable `v`?  "X" or "Px" or
 * "PX" for x, px; "x_" stands for x' (primes are turned into '_' before
 * parsing, which keeps every position). */
static int names_image_of(const char *lhs, const char *v)
{
    size_t n = strlen(v);
    if (strlen(lhs) == n + 1 && strncmp(lhs, v, n) == 0 && lhs[n] == '_')
        return 1;
    if (strlen(lhs) != n)
        return 0;
    int all_upper = 1, first_upper = 1;
    for (size_t i = 0; i < n; i++) {
        if (lhs[i] != (char)toupper((unsigned char)v[i]))
            all_upper = 0;
        char want = i == 0 ? (char)toupper((unsigned char)v[i]) : v[i];
        if (lhs[i] != want)
            first_upper = 0;
    }
    return (all_upper || first_upper) && strcmp(lhs, v) != 0;
}

static const char *var_name(const hl_system *sys, int a)
{
    return a < sys->n ? sys->q[a] : sys->p[a - sys->n];
}

/* Where the right side of item it starts: after its '=' (so that a symbol
 * error points into the right side, not at the left side's name). */
static int rhs_offset(const char *src, const hl_eqn *it)
{
    if (it->rhs == NULL)
        return it->pos;
    const char *eq = strchr(src + it->pos, '=');
    return eq ? (int)(eq - src) + 1 : it->pos;
}

static int match_items(int *which, const hl_system *sys, const hl_eqn *items, int n,
                       const char *src, hl_error *err)
{
    int N2 = 2 * sys->n, named = 0;
    for (int i = 0; i < n; i++)
        named += items[i].rhs != NULL;
    if (named != 0 && named != n)
        return hl_error_set(err, HL_EPARSE, src, items[named ? 0 : 0].pos, 1,
                            "either name every image (X = ...; P = ...) or none");
    if (n != N2)
        return hl_error_set(err, HL_EINVAL, src, -1, 0,
                            "the map gives %d image%s; this system has %d phase variables",
                            n, n == 1 ? "" : "s", N2);
    for (int a = 0; a < N2; a++)
        which[a] = -1;
    if (named == 0) {
        for (int a = 0; a < N2; a++)
            which[a] = a;
        return HL_OK;
    }
    for (int i = 0; i < n; i++) {
        const hl_expr *l = items[i].lhs;
        int a = -1;
        if (l->kind == HL_SYM)
            for (int b = 0; b < N2 && a < 0; b++)
                if (names_image_of(l->name, var_name(sys, b)))
                    a = b;
        if (a < 0) {
            hl_buf b;
            hl_buf_init(&b);
            for (int v = 0; v < N2; v++) {
                char *u = hl_xstrdup(var_name(sys, v));
                for (char *c = u; *c; c++)
                    *c = (char)toupper((unsigned char)*c);
                hl_buf_printf(&b, "%s%s", v ? ", " : "", u);
                free(u);
            }
            hl_error_set(err, HL_EINVAL, src, items[i].pos, 1,
                         "the left side must name the image of a phase variable "
                         "(%s, or the variable's name with a prime)", b.s);
            hl_buf_clear(&b);
            return HL_EINVAL;
        }
        if (which[a] >= 0)
            return hl_error_set(err, HL_EINVAL, src, items[i].pos, 1,
                                "image of '%s' given twice", var_name(sys, a));
        which[a] = i;
    }
    return HL_OK;
}

/* While the system's symbols are inferred from a map: the left sides of a
 * map's named images, so that a right side's use of an earlier image (see
 * chain_images) is no symbol of the system.  Each right side gets the
 * earlier ones substituted by name as written. */
void ham_chain_images(hl_eqn *items, int n, hl_pool *pool)
{
    const char **names = hl_xmalloc((size_t)(n > 0 ? n : 1) * sizeof *names);
    const hl_expr **vals = hl_xmalloc((size_t)(n > 0 ? n : 1) * sizeof *vals);
    int k = 0;
    for (int i = 0; i < n && items[i].rhs != NULL && items[i].lhs->kind == HL_SYM; i++) {
        if (k > 0)
            items[i].rhs = hl_expr_subst(pool, items[i].rhs, k, names, vals);
        names[k] = items[i].lhs->name;
        vals[k++] = items[i].rhs;
    }
    free(names);
    free(vals);
}

/* A named image may use the images named before it, as a scheme's stages
 * do ("P = p - D*sin(q); Q = q + D*P", symplectic Euler), under any of the
 * image's names (P, p'): each right side gets the earlier images
 * substituted, in the order written.  A name that is also a symbol of the
 * system (a parameter P) stays that symbol.  which[a]: item of variable a. */
static void chain_images(hl_eqn *items, int n, const int *which, hl_system *sys)
{
    int N2 = 2 * sys->n;
    const char **names = hl_xmalloc((size_t)N2 * 3 * sizeof *names);
    const hl_expr **vals = hl_xmalloc((size_t)N2 * 3 * sizeof *vals);
    for (int i = 1; i < n && items[i].rhs != NULL; i++) {
        int k = hl_expr_symbols(items[i].rhs, NULL, 0), m = 0;
        const char **syms = hl_xmalloc((size_t)(k > 0 ? k : 1) * sizeof *syms);
        hl_expr_symbols(items[i].rhs, syms, k);
        for (int s = 0; s < k; s++)
            for (int a = 0; a < N2 && m < 3 * N2; a++)
                if (which[a] < i && !is_known(sys, syms[s]) &&
                    names_image_of(syms[s], var_name(sys, a))) {
                    names[m] = syms[s];
                    vals[m++] = items[which[a]].rhs;
                }
        if (m > 0)
            items[i].rhs = hl_expr_subst(sys->pool, items[i].rhs, m, names, vals);
        free(syms);
    }
    free(names);
    free(vals);
}

/* x' left in a right side after the chaining names an image given later
 * (or never): an implicit map, or images out of order.  copy is the map
 * with primes as '_', at the same positions. */
static int image_used_early(const hl_system *sys, const hl_eqn *items, int n, const char *map,
                            const char *copy, hl_error *err)
{
    for (int a = 0; a < 2 * sys->n; a++) {
        char primed[256];
        snprintf(primed, sizeof primed, "%s_", var_name(sys, a));
        for (int i = 0; i < n; i++) {
            const hl_expr *e = items[i].rhs ? items[i].rhs : items[i].lhs;
            if (hl_expr_has_symbol(e, primed))
                return hl_error_set(err, HL_EINVAL, map, hl_symbol_pos(copy, primed), 1,
                                    "%s' is used before its image is given: give the images "
                                    "in the order they are computed (an implicit map is a "
                                    "scheme: errors --equations)",
                                    var_name(sys, a));
        }
    }
    return HL_OK;
}

hl_status hl_system_read_map(hl_alg *images, hl_system *sys, const char *map, hl_error *err)
{
    int N2 = 2 * sys->n, max = N2 + 2, n = 0;
    for (const char *c = map; *c; c++)
        max += *c == ';';
    char *copy = hl_xstrdup(map);
    for (char *c = copy; *c; c++)
        if (*c == '\'' && c > copy && (isalnum((unsigned char)c[-1]) || c[-1] == '_'))
            *c = '_';
    hl_eqn *items = hl_xmalloc((size_t)max * sizeof *items);
    int *which = hl_xmalloc((size_t)(N2 > 0 ? N2 : 1) * sizeof *which);
    int st = hl_parse_list(items, max, &n, sys->pool, copy, err);
    if (st != HL_OK && err != NULL)
        err->src = map;
    if (st == HL_OK)
        st = match_items(which, sys, items, n, map, err);
    if (st == HL_OK)
        chain_images(items, n, which, sys);
    if (st == HL_OK)
        st = image_used_early(sys, items, n, map, copy, err);
    for (int a = 0; a < N2 && st == HL_OK; a++) {
        const hl_eqn *it = &items[which[a]];
        const hl_expr *e = it->rhs ? it->rhs : it->lhs;
        st = ham_read_expr(&images[a], sys, e, map, rhs_offset(copy, it), err);
        if (st != HL_OK)
            hl_error_prefix(err, "in the image of '%s'", var_name(sys, a));
    }
    free(items), free(which), free(copy);
    return st;
}
