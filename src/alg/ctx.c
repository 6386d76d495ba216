/* The algebra context: base symbols, the mpoly context, the atom table.
 *
 * Monomial order: ORD_DEGLEX.  Terms are then stored by total degree
 * descending and, within a degree, in variable order (base symbols before
 * atoms), which is the order a person writes them in; the printer walks the
 * terms as stored unless a series symbol is set (hl_alg_ctx_set_step: then it
 * sorts by powers of that symbol first).  For the sizes hamlie meets, FLINT's
 * multiplication and gcd cost the same under LEX and DEGLEX. */
#include <stdlib.h>
#include <string.h>

#include "alg/alg_internal.h"
#include "base/buf.h"

#define DEFAULT_MAX_ATOMS 32

hl_alg_ctx *hl_alg_ctx_new(int nbase, const char *const *names, int max_atoms)
{
    hl_alg_ctx *ctx = hl_xcalloc(1, sizeof *ctx);
    if (nbase < 0)
        nbase = 0;
    if (max_atoms <= 0)
        max_atoms = DEFAULT_MAX_ATOMS;
    ctx->nbase = nbase;
    ctx->step = -1;
    ctx->max_atoms = max_atoms;
    ctx->names = hl_xcalloc((size_t)nbase + 1, sizeof *ctx->names);
    for (int i = 0; i < nbase; i++)
        ctx->names[i] = hl_xstrdup(names[i]);
    fmpz_mpoly_ctx_init(ctx->mctx, nbase + max_atoms, ORD_DEGLEX);
    ctx->atoms = hl_xcalloc((size_t)max_atoms, sizeof *ctx->atoms);
    ctx->degs = hl_xcalloc((size_t)(nbase + max_atoms), sizeof *ctx->degs);
    return ctx;
}

/* The irreducible factors of an atom's argument, kept with the atom (the
 * printer divides denominators by them first, alg/print.c): a factorization
 * costs ~1.5 million instructions even for x^2 + y^2, and every term of a
 * series is printed by a printer of its own.  The context is const to its
 * users; the cache is not part of its value. */
const struct alg_arg_factors *alg_atom_arg_factors(const hl_alg_ctx *ctx, int k)
{
    alg_atom *at = (alg_atom *)&ctx->atoms[k];
    if (at->arg_factors == NULL) {
        struct alg_arg_factors *af = hl_xmalloc(sizeof *af);
        fmpz_mpoly_factor_init(af->f, ctx->mctx);
        af->ok = fmpz_mpoly_factor(af->f, at->arg.num, ctx->mctx);
        at->arg_factors = af;
    }
    return at->arg_factors;
}

static void arg_factors_free(struct alg_arg_factors *f, const hl_alg_ctx *ctx)
{
    if (f == NULL)
        return;
    fmpz_mpoly_factor_clear(f->f, ctx->mctx);
    free(f);
}

static void atom_clear(alg_atom *at, hl_alg_ctx *ctx)
{
    hl_alg_clear(&at->arg, ctx);
    hl_alg_clear(&at->arg2, ctx);
    fmpz_mpoly_clear(at->rel_rhs, ctx->mctx);
    for (int v = 0; v < ctx->nbase; v++)
        hl_alg_clear(&at->dcache[v], ctx);
    free(at->dcache);
    free(at->dknown);
    free(at->dep);
    arg_factors_free(at->arg_factors, ctx);
}

void hl_alg_ctx_free(hl_alg_ctx *ctx)
{
    if (ctx == NULL)
        return;
    for (int k = 0; k < ctx->natoms; k++)
        atom_clear(&ctx->atoms[k], ctx);
    for (int i = 0; i < ctx->nbase; i++)
        free(ctx->names[i]);
    free(ctx->names);
    free(ctx->atoms);
    free(ctx->degs);
    fmpz_mpoly_ctx_clear(ctx->mctx);
    free(ctx);
}

int hl_alg_ctx_nbase(const hl_alg_ctx *ctx) { return ctx->nbase; }
int hl_alg_ctx_natoms(const hl_alg_ctx *ctx) { return ctx->natoms; }
const fmpz_mpoly_ctx_struct *hl_alg_ctx_mpoly(const hl_alg_ctx *ctx) { return ctx->mctx; }
int hl_alg_ctx_numeric_used(const hl_alg_ctx *ctx) { return ctx->numeric_used; }
void hl_alg_ctx_reset_numeric_used(hl_alg_ctx *ctx) { ctx->numeric_used = 0; }
double hl_alg_ctx_unprinted(const hl_alg_ctx *ctx) { return ctx->unprinted; }

void hl_alg_ctx_note_unprinted(hl_alg_ctx *ctx, double nodes)
{
    if (nodes > ctx->unprinted)
        ctx->unprinted = nodes;
}
int hl_alg_ctx_step(const hl_alg_ctx *ctx) { return ctx->step; }

void hl_alg_ctx_set_step(hl_alg_ctx *ctx, int var)
{
    ctx->step = (var >= 0 && var < ctx->nbase) ? var : -1;
}

const char *hl_alg_ctx_name(const hl_alg_ctx *ctx, int i)
{
    return (i >= 0 && i < ctx->nbase) ? ctx->names[i] : NULL;
}

int hl_alg_ctx_index(const hl_alg_ctx *ctx, const char *name)
{
    for (int i = 0; i < ctx->nbase; i++)
        if (strcmp(ctx->names[i], name) == 0)
            return i;
    return -1;
}

int alg_poly_has_var(const fmpz_mpoly_t p, int v, const hl_alg_ctx *ctx)
{
    return fmpz_mpoly_degree_si(p, v, ctx->mctx) > 0;
}

static void or_mask(unsigned char *dep, const fmpz_mpoly_t p, const hl_alg_ctx *ctx)
{
    if (fmpz_mpoly_is_fmpz(p, ctx->mctx))
        return;
    fmpz_mpoly_degrees_si(ctx->degs, p, ctx->mctx);
    for (int v = 0; v < ctx->nbase; v++)
        dep[v] |= ctx->degs[v] > 0;
    for (int k = 0; k < ctx->natoms; k++)
        if (ctx->degs[ctx->nbase + k] > 0)
            for (int v = 0; v < ctx->nbase; v++)
                dep[v] |= ctx->atoms[k].dep[v];
}

/* With the atom table: an atom depends on the base symbols of its
 * arguments, which this mask collects when the atom is made. */
int alg_depends_mask(unsigned char *dep, const hl_alg *a, const hl_alg_ctx *ctx)
{
    for (int v = 0; v < ctx->nbase; v++)
        dep[v] = 0;
    or_mask(dep, a->num, ctx);
    or_mask(dep, a->den, ctx);
    int any = 0;
    for (int v = 0; v < ctx->nbase; v++)
        any |= dep[v];
    return any;
}

static int poly_has_atoms(const fmpz_mpoly_t p, const hl_alg_ctx *ctx)
{
    if (fmpz_mpoly_is_fmpz(p, ctx->mctx))
        return 0;
    fmpz_mpoly_degrees_si(ctx->degs, p, ctx->mctx);
    for (int k = 0; k < ctx->natoms; k++)
        if (ctx->degs[ctx->nbase + k] > 0)
            return 1;
    return 0;
}

static int same_alg(const hl_alg *a, const hl_alg *b, const hl_alg_ctx *ctx)
{
    return fmpz_mpoly_equal(a->num, b->num, ctx->mctx) && fmpz_mpoly_equal(a->den, b->den, ctx->mctx);
}

static int atom_matches(const alg_atom *at, alg_atom_kind kind, long q, const hl_alg *arg,
                        const hl_alg *arg2, const hl_alg_ctx *ctx)
{
    if (at->kind != kind || at->q != q)
        return 0;
    if (kind == ATOM_PI)
        return 1;
    return same_alg(&at->arg, arg, ctx) && (arg2 == NULL || same_alg(&at->arg2, arg2, ctx));
}

/* The base symbols and atoms the second argument brings (ATOM_ATAN2). */
static void atom_add_arg2(alg_atom *at, const hl_alg *arg2, hl_alg_ctx *ctx)
{
    unsigned char *dep2 = hl_xcalloc((size_t)ctx->nbase + 1, 1);
    hl_alg_set(&at->arg2, arg2, ctx);
    alg_depends_mask(dep2, arg2, ctx);
    for (int v = 0; v < ctx->nbase; v++)
        at->dep[v] |= dep2[v];
    free(dep2);
    at->nested |= poly_has_atoms(arg2->num, ctx) || poly_has_atoms(arg2->den, ctx);
}

static void atom_init(alg_atom *at, alg_atom_kind kind, long q, const hl_alg *arg, int family,
                      hl_alg_ctx *ctx)
{
    int k = (int)(at - ctx->atoms);
    memset(at, 0, sizeof *at);
    at->kind = kind;
    at->q = q;
    at->var = ctx->nbase + k;
    at->partner = -1;
    at->family = family;
    hl_alg_init(&at->arg, ctx);
    hl_alg_init(&at->arg2, ctx);
    if (arg != NULL)
        hl_alg_set(&at->arg, arg, ctx);
    fmpz_mpoly_init(at->rel_rhs, ctx->mctx);
    at->dep = hl_xcalloc((size_t)ctx->nbase + 1, 1);
    at->dknown = hl_xcalloc((size_t)ctx->nbase + 1, 1);
    at->dcache = hl_xcalloc((size_t)ctx->nbase + 1, sizeof *at->dcache);
    for (int v = 0; v < ctx->nbase; v++)
        hl_alg_init(&at->dcache[v], ctx);
    if (arg != NULL) {
        alg_depends_mask(at->dep, arg, ctx);
        at->nested = poly_has_atoms(arg->num, ctx) || poly_has_atoms(arg->den, ctx);
    }
}

int alg_atom_get(int *var, alg_atom_kind kind, long q, const hl_alg *arg, hl_alg_ctx *ctx,
                 hl_error *err)
{
    return alg_atom_get2(var, kind, q, arg, NULL, ctx, err);
}

int alg_atom_get2(int *var, alg_atom_kind kind, long q, const hl_alg *arg, const hl_alg *arg2,
                  hl_alg_ctx *ctx, hl_error *err)
{
    alg_atom_kind look = kind == ATOM_COS ? ATOM_SIN : kind;
    for (int k = 0; k < ctx->natoms; k++) {
        const alg_atom *at = &ctx->atoms[k];
        if (atom_matches(at, look, q, arg, arg2, ctx)) {
            *var = kind == ATOM_COS ? ctx->atoms[at->partner].var : at->var;
            return HL_OK;
        }
    }
    int need = (look == ATOM_SIN) ? 2 : 1;
    if (ctx->natoms + need > ctx->max_atoms)
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0,
                            "too many functions and roots (the limit is %d)", ctx->max_atoms);
    int k = ctx->natoms;
    alg_atom *at = &ctx->atoms[k];
    atom_init(at, look, q, arg, k, ctx);
    if (arg2 != NULL)
        atom_add_arg2(at, arg2, ctx);
    switch (look) {
    case ATOM_SQRT:
        at->rel_deg = 2;
        fmpz_mpoly_set(at->rel_rhs, arg->num, ctx->mctx);
        break;
    case ATOM_ROOT:
        at->rel_deg = (int)q;
        fmpz_mpoly_set(at->rel_rhs, arg->num, ctx->mctx);
        break;
    case ATOM_SIN: {
        alg_atom *co = &ctx->atoms[k + 1];
        atom_init(co, ATOM_COS, q, arg, k, ctx);
        at->partner = k + 1;
        co->partner = k;
        /* s^2 = 1 - c^2: sin is the one kept to degree <= 1 */
        fmpz_mpoly_gen(at->rel_rhs, co->var, ctx->mctx);
        fmpz_mpoly_mul(at->rel_rhs, at->rel_rhs, at->rel_rhs, ctx->mctx);
        fmpz_mpoly_neg(at->rel_rhs, at->rel_rhs, ctx->mctx);
        fmpz_mpoly_add_si(at->rel_rhs, at->rel_rhs, 1, ctx->mctx);
        at->rel_deg = 2;
        break;
    }
    default:
        break;
    }
    ctx->natoms += need;
    *var = kind == ATOM_COS ? ctx->atoms[k + 1].var : at->var;
    return HL_OK;
}
