/* Internals of the exact-algebra layer, shared by the files of src/alg only.
 *
 * Variables of the mpoly context: 0..nbase-1 are the base symbols, nbase+k
 * is atom k.  Atoms are numbered in creation order and an atom's argument
 * only involves older atoms, so every elimination runs from the newest atom
 * to the oldest.
 */
#ifndef HAMLIE_ALG_INTERNAL_H
#define HAMLIE_ALG_INTERNAL_H

#include <flint/fmpz_mpoly.h>
#include <flint/fmpz_mpoly_factor.h>
#include <flint/flint.h>

#include "hamlie/alg.h"

typedef enum alg_atom_kind {
    ATOM_SQRT, /* r, r^2 = arg (a polynomial) */
    ATOM_ROOT, /* w, w^q = arg (a polynomial), q >= 3 */
    ATOM_SIN,  /* s, s^2 = 1 - c^2 with c its partner */
    ATOM_COS,  /* c, no relation of its own */
    ATOM_EXP,
    ATOM_LOG,
    ATOM_ATAN,
    ATOM_ASIN,
    ATOM_ACOS,
    ATOM_PI,
    ATOM_ATAN2 /* atan2(arg, arg2): the angle of (arg2, arg) */
} alg_atom_kind;

typedef struct alg_atom {
    alg_atom_kind kind;
    long q;            /* ATOM_ROOT: the root's degree */
    hl_alg arg;        /* canonical argument (unused for ATOM_PI) */
    hl_alg arg2;       /* ATOM_ATAN2: the second argument (x of atan2(y, x)) */
    int var;           /* its mpoly variable */
    int partner;       /* sin <-> cos: the other atom's index, else -1 */
    int family;        /* atoms of one family are handled exactly together */
    int nested;        /* the argument involves atoms */
    /* relation var^rel_deg = rel_rhs; rel_deg = 0 when there is none */
    int rel_deg;
    fmpz_mpoly_t rel_rhs;
    unsigned char *dep;    /* dep[v]: does it depend on base symbol v? */
    hl_alg *dcache;        /* d(atom)/d(base v), valid when dknown[v] */
    unsigned char *dknown;
    struct alg_arg_factors *arg_factors; /* arg.num factored, NULL until asked */
} alg_atom;

struct hl_alg_ctx {
    fmpz_mpoly_ctx_t mctx;
    int nbase;
    char **names;
    int max_atoms;
    int natoms;
    alg_atom *atoms; /* max_atoms slots, never moved */
    int numeric_used;
    double unprinted; /* the largest result too large to print, or 0 */
    int step;        /* print order: the series symbol, or -1 (print.c) */
    slong *degs;     /* scratch: nvars degrees */
};

static inline int alg_nvars(const hl_alg_ctx *ctx) { return ctx->nbase + ctx->max_atoms; }

/* Atom k of variable v, or NULL for a base symbol. */
static inline const alg_atom *alg_var_atom(const hl_alg_ctx *ctx, int v)
{
    return v >= ctx->nbase ? &ctx->atoms[v - ctx->nbase] : NULL;
}

/* ---- print.c ---- */
/* The irreducible factors of atom k's argument (ok: FLINT factored it),
 * computed on first use and kept with the atom (ctx.c). */
struct alg_arg_factors {
    int ok;
    fmpz_mpoly_factor_t f;
};
const struct alg_arg_factors *alg_atom_arg_factors(const hl_alg_ctx *ctx, int k);

/* ---- ctx.c ---- */
/* Find or make the atom (kind, q, arg); sets *var.  arg must be canonical
 * and already normalised by the caller (sign convention, polynomial for
 * roots).  For SIN/COS both atoms of the pair are made. */
int alg_atom_get(int *var, alg_atom_kind kind, long q, const hl_alg *arg, hl_alg_ctx *ctx,
                 hl_error *err);
/* The same for an atom of two arguments (ATOM_ATAN2). */
int alg_atom_get2(int *var, alg_atom_kind kind, long q, const hl_alg *arg, const hl_alg *arg2,
                  hl_alg_ctx *ctx, hl_error *err);
/* Does the polynomial p involve variable v? */
int alg_poly_has_var(const fmpz_mpoly_t p, int v, const hl_alg_ctx *ctx);
/* dep[v] = 1 for the base symbols v that a involves, also through its
 * atoms; returns 1 if there is any. */
int alg_depends_mask(unsigned char *dep, const hl_alg *a, const hl_alg_ctx *ctx);

/* ---- ratfun.c ---- */
/* Reduce a polynomial by the atom relations; returns nonzero if it changed. */
int alg_reduce(fmpz_mpoly_t p, hl_alg_ctx *ctx);
/* Bring num/den (den != 0) to canonical form. */
void alg_canonicalise(hl_alg *a, hl_alg_ctx *ctx);
void alg_set_poly(hl_alg *r, const fmpz_mpoly_t p, hl_alg_ctx *ctx); /* r = p, canonical */
void alg_set_var(hl_alg *r, int v, hl_alg_ctx *ctx);                   /* r = variable v */
/* HL_ELIMIT if the coefficients of a^n would be too long to compute
 * exactly (about n log2 of the largest coefficient of a), else HL_OK. */
int alg_check_pow_size(const hl_alg *a, unsigned long n, const hl_alg_ctx *ctx, hl_error *err);

#endif
