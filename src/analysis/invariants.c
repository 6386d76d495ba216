/* Invariants of a vector field by exact linear algebra (analysis.h, part 5). */
#include <stdlib.h>
#include <string.h>

#include <flint/fmpq_mat.h>
#include <flint/fmpz_mat.h>
#include <flint/fmpq_poly.h>
#include <flint/fmpz_poly.h>
#include <flint/fmpz_poly_factor.h>

#include "base/buf.h"
#include "hamlie/analysis.h"

/* Monomials in the 2N phase variables: exponent vectors, nv = 2N each. */
typedef struct monos {
    int nv, n, alloc;
    ulong *e;
} monos;

static int monos_find(monos *M, const ulong *e, int add)
{
    for (int i = 0; i < M->n; i++)
        if (memcmp(M->e + (size_t)i * M->nv, e, (size_t)M->nv * sizeof *e) == 0)
            return i;
    if (!add)
        return -1;
    if (M->n == M->alloc) {
        M->alloc = M->alloc ? 2 * M->alloc : 16;
        M->e = hl_xrealloc(M->e, (size_t)M->alloc * M->nv * sizeof *M->e);
    }
    memcpy(M->e + (size_t)M->n * M->nv, e, (size_t)M->nv * sizeof *e);
    return M->n++;
}

/* All exponent vectors with total degree in [lo, hi]. */
static void gen_monos(monos *M, ulong *e, int i, int left, int lo, int total)
{
    if (M->n > HL_INVARIANTS_MAX_MONOMIALS)
        return;
    if (i == M->nv) {
        if (total >= lo)
            monos_find(M, e, 1);
        return;
    }
    for (int k = 0; k <= left; k++) {
        e[i] = (ulong)k;
        gen_monos(M, e, i + 1, left - k, lo, total + k);
    }
    e[i] = 0;
}

static void mono_alg(hl_alg *r, const ulong *e, int nv, hl_alg_ctx *ctx)
{
    hl_alg z;
    hl_error err;
    hl_alg_init(&z, ctx);
    hl_alg_one(r, ctx);
    for (int i = 0; i < nv; i++)
        if (e[i]) {
            hl_alg_gen(&z, i, ctx);
            hl_alg_pow_si(&z, &z, (long)e[i], ctx, &err);
            hl_alg_mul(r, r, &z, ctx);
        }
    hl_alg_clear(&z, ctx);
}

/* Is a a polynomial over Q in the phase variables only (degree <= maxdeg
 * when maxdeg >= 0, every term of degree exactly maxdeg when exact)? */
static int is_phase_poly(const hl_alg *a, int nv, int maxdeg, int exact, hl_alg_ctx *ctx)
{
    const fmpz_mpoly_ctx_struct *mc = hl_alg_ctx_mpoly(ctx);
    if (!fmpz_mpoly_is_fmpz(a->den, mc))
        return 0;
    slong nvars = fmpz_mpoly_ctx_nvars(mc);
    ulong *e = hl_xmalloc((size_t)nvars * sizeof *e);
    int ok = 1;
    for (slong t = 0; ok && t < fmpz_mpoly_length(a->num, mc); t++) {
        fmpz_mpoly_get_term_exp_ui(e, a->num, t, mc);
        ulong deg = 0;
        for (slong x = 0; x < nvars; x++) {
            if (x < nv)
                deg += e[x];
            else if (e[x])
                ok = 0;
        }
        if (maxdeg >= 0 && (deg > (ulong)maxdeg || (exact && deg != (ulong)maxdeg)))
            ok = 0;
    }
    free(e);
    return ok;
}

/* Column j of the matrix: the coefficients of the polynomial a (over rows). */
typedef struct entry {
    int row, col;
    fmpq_t c;
} entry;

static void add_column(entry **E, int *nE, monos *rows, const hl_alg *a, int col, int nv,
                       hl_alg_ctx *ctx)
{
    const fmpz_mpoly_ctx_struct *mc = hl_alg_ctx_mpoly(ctx);
    slong nvars = fmpz_mpoly_ctx_nvars(mc);
    ulong *e = hl_xmalloc((size_t)nvars * sizeof *e);
    fmpz_t den;
    fmpz_init(den);
    fmpz_mpoly_get_fmpz(den, a->den, mc);
    for (slong t = 0; t < fmpz_mpoly_length(a->num, mc); t++) {
        fmpz_mpoly_get_term_exp_ui(e, a->num, t, mc);
        *E = hl_xrealloc(*E, (size_t)(*nE + 1) * sizeof **E);
        entry *x = &(*E)[(*nE)++];
        x->row = monos_find(rows, e, 1); /* only the first nv exponents matter */
        x->col = col;
        fmpq_init(x->c);
        fmpz_mpoly_get_term_coeff_fmpz(fmpq_numref(x->c), a->num, t, mc);
        fmpz_set(fmpq_denref(x->c), den);
        fmpq_canonicalise(x->c);
    }
    fmpz_clear(den);
    free(e);
    (void)nv;
}

/* r = v(phi) = sum_i v_i d phi / d z_i */
static int apply_field(hl_alg *r, const hl_alg *v, const hl_alg *phi, int nv, hl_alg_ctx *ctx,
                       hl_error *err)
{
    hl_alg d;
    hl_alg_init(&d, ctx);
    hl_alg_zero(r, ctx);
    int st = HL_OK;
    for (int i = 0; i < nv && st == HL_OK; i++)
        if ((st = hl_alg_diff(&d, phi, i, ctx, err)) == HL_OK) {
            hl_alg_mul(&d, &d, &v[i], ctx);
            hl_alg_add(r, r, &d, ctx);
        }
    hl_alg_clear(&d, ctx);
    return st;
}

/* Nullspace of the matrix (rows x cols) given by entries: basis vectors as
 * polynomials sum_j x_j cols[j]. */
static void nullspace_polys(hl_alg **out, int *count, entry *E, int nE, int nrows,
                            const monos *cols, hl_alg_ctx *ctx)
{
    int nc = cols->n;
    fmpq_mat_t A;
    fmpz_mat_t Z, N;
    fmpq_mat_init(A, nrows > 0 ? nrows : 1, nc);
    for (int i = 0; i < nE; i++)
        fmpq_add(fmpq_mat_entry(A, E[i].row, E[i].col), fmpq_mat_entry(A, E[i].row, E[i].col),
                 E[i].c);
    fmpz_mat_init(Z, fmpq_mat_nrows(A), nc);
    fmpq_mat_get_fmpz_mat_rowwise(Z, NULL, A);
    fmpz_mat_init(N, nc, nc);
    slong k = fmpz_mat_nullspace(N, Z);
    *count = (int)k;
    *out = k > 0 ? hl_alg_vec_new((int)k, ctx) : NULL;
    hl_alg t;
    hl_alg_init(&t, ctx);
    fmpq_t c;
    fmpq_init(c);
    for (slong b = 0; b < k; b++)
        for (int j = 0; j < nc; j++)
            if (!fmpz_is_zero(fmpz_mat_entry(N, j, b))) {
                mono_alg(&t, cols->e + (size_t)j * cols->nv, cols->nv, ctx);
                fmpz_set(fmpq_numref(c), fmpz_mat_entry(N, j, b));
                fmpz_one(fmpq_denref(c));
                hl_alg_scalar_mul_fmpq(&t, &t, c, ctx);
                hl_alg_add(&(*out)[b], &(*out)[b], &t, ctx);
            }
    fmpq_clear(c);
    hl_alg_clear(&t, ctx);
    fmpq_mat_clear(A);
    fmpz_mat_clear(Z);
    fmpz_mat_clear(N);
}

static void entries_free(entry *E, int nE)
{
    for (int i = 0; i < nE; i++)
        fmpq_clear(E[i].c);
    free(E);
}

/* Keep only the phi with v(phi) == 0 (exact check). */
static int keep_checked(hl_alg *phi, int *count, const hl_alg *v, int nv, hl_alg_ctx *ctx,
                        hl_error *err)
{
    hl_alg r;
    hl_alg_init(&r, ctx);
    int k = 0, st = HL_OK;
    for (int i = 0; i < *count && st == HL_OK; i++) {
        st = apply_field(&r, v, &phi[i], nv, ctx, err);
        if (st == HL_OK && hl_alg_is_zero(&r, ctx))
            hl_alg_swap(&phi[k++], &phi[i], ctx);
    }
    hl_alg_clear(&r, ctx);
    if (st == HL_OK && k != *count)
        st = hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                          "internal error: an invariant from the nullspace fails v(phi) = 0");
    return st;
}

hl_status hl_field_poly_invariants(hl_alg **out, int *count, int *applicable, const hl_alg *v,
                                   int degree, hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int nv = 2 * hl_system_ndof(sys), st = HL_OK;
    *out = NULL;
    *count = 0;
    *applicable = degree >= 1;
    for (int i = 0; i < nv && *applicable; i++)
        *applicable = is_phase_poly(&v[i], nv, -1, 0, ctx);
    if (!*applicable)
        return HL_OK;
    monos cols = {nv, 0, 0, NULL}, rows = {nv, 0, 0, NULL};
    ulong *e = hl_xcalloc((size_t)nv, sizeof *e);
    gen_monos(&cols, e, 0, degree, 1, 0);
    free(e);
    if (cols.n > HL_INVARIANTS_MAX_MONOMIALS) {
        free(cols.e);
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0,
                            "too many monomials of degree <= %d (limit %d)", degree,
                            HL_INVARIANTS_MAX_MONOMIALS);
    }
    entry *E = NULL;
    int nE = 0;
    hl_alg m, r;
    hl_alg_init(&m, ctx);
    hl_alg_init(&r, ctx);
    for (int j = 0; j < cols.n && st == HL_OK; j++) {
        mono_alg(&m, cols.e + (size_t)j * nv, nv, ctx);
        if ((st = apply_field(&r, v, &m, nv, ctx, err)) == HL_OK)
            add_column(&E, &nE, &rows, &r, j, nv, ctx);
    }
    if (st == HL_OK) {
        nullspace_polys(out, count, E, nE, rows.n, &cols, ctx);
        st = keep_checked(*out, count, v, nv, ctx, err);
    }
    hl_alg_clear(&m, ctx);
    hl_alg_clear(&r, ctx);
    entries_free(E, nE);
    free(cols.e);
    free(rows.e);
    return st;
}

/* Rational roots of the characteristic polynomial of A. */
static int rational_roots(fmpq **roots, const fmpq_mat_t A)
{
    fmpq_poly_t cp;
    fmpz_poly_t z;
    fmpz_poly_factor_t f;
    fmpq_poly_init(cp);
    fmpz_poly_init(z);
    fmpz_poly_factor_init(f);
    fmpq_mat_charpoly(cp, A);
    fmpq_poly_get_numerator(z, cp);
    fmpz_poly_factor(f, z);
    int n = 0;
    *roots = hl_xmalloc((size_t)(f->num + 1) * sizeof **roots);
    for (slong i = 0; i < f->num; i++)
        if (fmpz_poly_degree(f->p + i) == 1) {
            fmpq_init(*roots + n);
            fmpz_neg(fmpq_numref(*roots + n), f->p[i].coeffs + 0);
            fmpz_set(fmpq_denref(*roots + n), f->p[i].coeffs + 1);
            fmpq_canonicalise(*roots + n);
            n++;
        }
    fmpq_poly_clear(cp);
    fmpz_poly_clear(z);
    fmpz_poly_factor_clear(f);
    return n;
}

hl_status hl_field_darboux_invariants(hl_alg **out, int *count, int *applicable, const hl_alg *v,
                                      int degree, hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int nv = 2 * hl_system_ndof(sys), st = HL_OK;
    *out = NULL;
    *count = 0;
    *applicable = degree >= 1;
    for (int i = 0; i < nv && *applicable; i++)
        *applicable = is_phase_poly(&v[i], nv, 1, 1, ctx);
    if (!*applicable)
        return HL_OK;
    hl_alg m, r;
    hl_alg_init(&m, ctx);
    hl_alg_init(&r, ctx);
    for (int d = 1; d <= degree && st == HL_OK && *count == 0; d++) {
        monos cols = {nv, 0, 0, NULL};
        ulong *e = hl_xcalloc((size_t)nv, sizeof *e);
        gen_monos(&cols, e, 0, d, d, 0);
        free(e);
        if (cols.n > HL_INVARIANTS_MAX_MONOMIALS) {
            free(cols.e);
            break;
        }
        /* A: v acting on the homogeneous polynomials of degree d */
        entry *E = NULL;
        int nE = 0;
        monos rows = {nv, 0, 0, NULL};
        for (int j = 0; j < cols.n; j++)
            monos_find(&rows, cols.e + (size_t)j * nv, 1); /* rows in the order of cols */
        for (int j = 0; j < cols.n && st == HL_OK; j++) {
            mono_alg(&m, cols.e + (size_t)j * nv, nv, ctx);
            if ((st = apply_field(&r, v, &m, nv, ctx, err)) == HL_OK)
                add_column(&E, &nE, &rows, &r, j, nv, ctx);
        }
        fmpq_mat_t A;
        fmpq_mat_init(A, cols.n, cols.n);
        for (int i = 0; i < nE; i++)
            fmpq_set(fmpq_mat_entry(A, E[i].row, E[i].col), E[i].c);
        fmpq *roots;
        int nr = st == HL_OK ? rational_roots(&roots, A) : 0;
        if (st != HL_OK)
            roots = NULL;
        for (int k = 0; k < nr && st == HL_OK; k++) {
            /* eigenvectors: nullspace of A - lambda I, as entries */
            entry *F = hl_xmalloc((size_t)(nE + cols.n) * sizeof *F);
            int nF = 0;
            for (int i = 0; i < nE; i++) {
                F[nF].row = E[i].row;
                F[nF].col = E[i].col;
                fmpq_init(F[nF].c);
                fmpq_set(F[nF++].c, E[i].c);
            }
            for (int i = 0; i < cols.n; i++) {
                F[nF].row = F[nF].col = i;
                fmpq_init(F[nF].c);
                fmpq_neg(F[nF++].c, roots + k);
            }
            hl_alg *phi;
            int np;
            nullspace_polys(&phi, &np, F, nF, cols.n, &cols, ctx);
            entries_free(F, nF);
            for (int j = 1; j < np && st == HL_OK; j++) {
                *out = hl_xrealloc(*out, (size_t)(*count + 1) * sizeof **out);
                hl_alg_init(&(*out)[*count], ctx);
                st = hl_alg_div(&(*out)[*count], &phi[0], &phi[j], ctx, err);
                (*count)++;
            }
            hl_alg_vec_free(phi, np, ctx);
        }
        for (int k = 0; k < nr; k++)
            fmpq_clear(roots + k);
        free(roots);
        fmpq_mat_clear(A);
        entries_free(E, nE);
        free(cols.e);
        free(rows.e);
    }
    if (st == HL_OK)
        st = keep_checked(*out, count, v, nv, ctx, err);
    hl_alg_clear(&m, ctx);
    hl_alg_clear(&r, ctx);
    return st;
}
