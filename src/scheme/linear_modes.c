/* The exact flow z' = A z + b of a quadratic H that couples its pairs, in
 * closed form (called by linear_flow.c for a coupled H).
 *
 * A = J Hess(H) and b = J grad H(0) must be rational.  With M = A^2,
 *   exp(D A) = C(M) + S(M) A,   int_0^D exp(s A) ds = S(M) + K(M) A,
 * C(x) = sum D^2k x^k/(2k)!, S(x) = sum D^(2k+1) x^k/(2k+1)!,
 * K(x) = sum D^(2k+2) x^k/(2k+2)! (entire, so this holds for every A).  When
 * M is diagonalizable, f(M) = sum_mu P_mu f(mu) with P_mu its spectral
 * projectors, and for real mu
 *   mu < 0 (w^2 = -mu):  C = cos wD,   S = sin(wD)/w,   K = (1 - cos wD)/w^2,
 *   mu > 0 (w^2 = mu):   C = cosh wD,  S = sinh(wD)/w,  K = (cosh wD - 1)/w^2,
 *   mu = 0:              C = 1,        S = D,           K = D^2/2.
 * The projectors come from M's minimal polynomial m over Q (FLINT): for
 * each irreducible factor f, E_f = e_f(M) with e_f = 1 mod f, 0 mod m/f
 * (rational); if f = x - r, P_r = E_f; if f is quadratic with real roots
 * mu = alpha +- beta sqrt(d), P_mu = E_f (M - mu')/(mu - mu'), whose
 * entries lie in Q(sqrt d): every coefficient is written a + b sqrt(d)
 * with a, b rational, and the images are read from that text.
 *
 * Refused (HL_EUNSUP, the reason named): symbolic coefficients; m not
 * squarefree (M defective: a resonance with a Jordan block); a factor of
 * degree > 2 (no closed form of its roots here); complex mu (spiral modes).
 * hl_exact_flow computes exp(DA) numerically in every case. */
#include <stdlib.h>
#include <string.h>

#include <flint/fmpq_mat.h>
#include <flint/fmpq_poly.h>
#include <flint/fmpz_factor.h>
#include <flint/fmpz_poly_factor.h>

#include "base/buf.h"
#include "scheme/scheme_impl.h"

/* One eigenvalue mu = alpha + beta sqrt(d) of M (beta = 0: rational) and
 * its projector P = Pa + Pb sqrt(d). */
typedef struct mode {
    fmpz_t d;
    fmpq_t alpha, beta;
    fmpq_mat_t Pa, Pb;
} mode;

static void mode_init(mode *m, int n)
{
    fmpz_init_set_ui(m->d, 1);
    fmpq_init(m->alpha);
    fmpq_init(m->beta);
    fmpq_mat_init(m->Pa, n, n);
    fmpq_mat_init(m->Pb, n, n);
}

static void mode_clear(mode *m)
{
    fmpz_clear(m->d);
    fmpq_clear(m->alpha);
    fmpq_clear(m->beta);
    fmpq_mat_clear(m->Pa);
    fmpq_mat_clear(m->Pb);
}

/* ---- numbers of Q(sqrt d) as text --------------------------------------- */

static void put_q(hl_buf *b, const fmpq_t q)
{
    char *s = fmpq_get_str(NULL, 10, q);
    hl_buf_printf(b, fmpq_sgn(q) < 0 ? "(%s)" : "%s", s);
    flint_free(s);
}

/* "(a + c*sqrt(d))" as one writes it, "(5/2 - sqrt(13)/2)"; a rational with
 * a rational square root is written without sqrt. */
static void put_surd(hl_buf *b, const fmpq_t a, const fmpq_t c, const fmpz_t d)
{
    char *ds = fmpz_get_str(NULL, 10, d);
    hl_buf_puts(b, "(");
    if (!fmpq_is_zero(a) || fmpq_is_zero(c)) { /* inside the parentheses: no more needed */
        char *as = fmpq_get_str(NULL, 10, a);
        hl_buf_puts(b, as);
        flint_free(as);
    }
    if (!fmpq_is_zero(c)) {
        int neg = fmpq_sgn(c) < 0;
        hl_buf_puts(b, !fmpq_is_zero(a) ? (neg ? " - " : " + ") : neg ? "-" : "");
        fmpz_t n;
        fmpz_init(n);
        fmpz_abs(n, fmpq_numref(c));
        if (!fmpz_is_one(n)) {
            char *ns = fmpz_get_str(NULL, 10, n);
            hl_buf_printf(b, "%s*", ns);
            flint_free(ns);
        }
        hl_buf_printf(b, "sqrt(%s)", ds);
        if (!fmpz_is_one(fmpq_denref(c))) {
            char *qs = fmpz_get_str(NULL, 10, fmpq_denref(c));
            hl_buf_printf(b, "/%s", qs);
            flint_free(qs);
        }
        fmpz_clear(n);
    }
    hl_buf_puts(b, ")");
    flint_free(ds);
}

/* Is q a square of Q?  If so r = its root (r may not alias q). */
static int q_sqrt(fmpq_t r, const fmpq_t q)
{
    if (fmpq_sgn(q) < 0 || !fmpz_is_square(fmpq_numref(q)) ||
        !fmpz_is_square(fmpq_denref(q)))
        return 0;
    fmpz_sqrt(fmpq_numref(r), fmpq_numref(q));
    fmpz_sqrt(fmpq_denref(r), fmpq_denref(q));
    return 1;
}

/* Sign of a + c sqrt(d), d > 0. */
static int surd_sgn(const fmpq_t a, const fmpq_t c, const fmpz_t d)
{
    int sa = fmpq_sgn(a), sc = fmpq_sgn(c);
    if (sc == 0 || sa == sc)
        return sa != 0 ? sa : sc;
    if (sa == 0)
        return sc;
    fmpq_t a2, c2;
    fmpq_init(a2);
    fmpq_init(c2);
    fmpq_mul(a2, a, a);
    fmpq_mul(c2, c, c);
    fmpq_mul_fmpz(c2, c2, d);
    int cmp = fmpq_cmp(a2, c2);
    fmpq_clear(a2);
    fmpq_clear(c2);
    return cmp > 0 ? sa : sc;
}

/* The text of w = sqrt(a + c sqrt(d)) > 0: denested to x + y sqrt(d) with
 * x, y rational when that exists (x^2 = (a +- sqrt(a^2 - d c^2))/2),
 * a rational root written as a number. */
static void put_root(hl_buf *b, const fmpq_t a, const fmpq_t c, const fmpz_t d)
{
    fmpq_t r2, r, x2, x, y;
    fmpq_init(r2);
    fmpq_init(r);
    fmpq_init(x2);
    fmpq_init(x);
    fmpq_init(y);
    int done = 0;
    if (fmpq_is_zero(c)) {
        if ((done = q_sqrt(x, a)))
            put_q(b, x);
    } else {
        fmpq_mul(r2, c, c);
        fmpq_mul_fmpz(r2, r2, d);
        fmpq_mul(x2, a, a);
        fmpq_sub(r2, x2, r2);
        for (int s = 1; !done && s >= -1 && q_sqrt(r, r2); s -= 2) {
            if (s < 0)
                fmpq_neg(r, r);
            fmpq_add(x2, a, r);
            fmpq_div_2exp(x2, x2, 1);
            if (fmpq_sgn(x2) > 0 && q_sqrt(x, x2)) {
                fmpq_div(y, c, x);
                fmpq_div_2exp(y, y, 1); /* 2 x y = c */
                if (surd_sgn(x, y, d) < 0) {
                    fmpq_neg(x, x);
                    fmpq_neg(y, y);
                }
                put_surd(b, x, y, d);
                done = 1;
            }
        }
    }
    if (!done) {
        hl_buf_puts(b, "sqrt");
        put_surd(b, a, c, d);
    }
    fmpq_clear(r2);
    fmpq_clear(r);
    fmpq_clear(x2);
    fmpq_clear(x);
    fmpq_clear(y);
}

/* ---- the decomposition ------------------------------------------------ */

/* r = p(X) for a square rational matrix X (Horner). */
static void poly_of_mat(fmpq_mat_t r, const fmpq_poly_t p, const fmpq_mat_t X)
{
    fmpq_t c;
    fmpq_init(c);
    fmpq_mat_zero(r);
    for (slong k = fmpq_poly_degree(p); k >= 0; k--) {
        fmpq_mat_mul(r, r, X);
        fmpq_poly_get_coeff_fmpq(c, p, k);
        for (slong i = 0; i < fmpq_mat_nrows(r); i++)
            fmpq_add(fmpq_mat_entry(r, i, i), fmpq_mat_entry(r, i, i), c);
    }
    fmpq_clear(c);
}

/* d = the squarefree part of the positive rational q, t = sqrt(q/d). */
static void squarefree_part(fmpz_t d, fmpq_t t, const fmpq_t q)
{
    fmpz_t n, s;
    fmpz_factor_t f;
    fmpz_init(n);
    fmpz_init(s);
    fmpz_factor_init(f);
    fmpz_mul(n, fmpq_numref(q), fmpq_denref(q)); /* q = n / den^2 */
    fmpz_factor(f, n);
    fmpz_one(d);
    for (slong i = 0; i < f->num; i++)
        if (f->exp[i] % 2)
            fmpz_mul(d, d, f->p + i);
    fmpz_divexact(n, n, d);
    fmpz_sqrt(s, n);
    fmpq_set_fmpz_frac(t, s, fmpq_denref(q));
    fmpz_factor_clear(f);
    fmpz_clear(n);
    fmpz_clear(s);
}

/* Fill modes (up to 2N) from the factors of M's minimal polynomial; HL_EUNSUP
 * naming the reason when the closed form is not available. */
static int decompose(mode *modes, int *nmodes, const fmpq_mat_t Mm, hl_error *err)
{
    int n = (int)fmpq_mat_nrows(Mm), st = HL_OK;
    fmpq_poly_t m, f, cof, G, S, T, e;
    fmpz_poly_t mz;
    fmpz_poly_factor_t fac;
    fmpq_mat_t E, EM;
    fmpq_t b1, c0, disc, t;
    fmpq_poly_init(m);
    fmpq_poly_init(f);
    fmpq_poly_init(cof);
    fmpq_poly_init(G);
    fmpq_poly_init(S);
    fmpq_poly_init(T);
    fmpq_poly_init(e);
    fmpz_poly_init(mz);
    fmpz_poly_factor_init(fac);
    fmpq_mat_init(E, n, n);
    fmpq_mat_init(EM, n, n);
    fmpq_init(b1);
    fmpq_init(c0);
    fmpq_init(disc);
    fmpq_init(t);
    fmpq_mat_minpoly(m, Mm);
    fmpq_poly_get_numerator(mz, m);
    fmpz_poly_factor(fac, mz);
    *nmodes = 0;
    for (slong i = 0; i < fac->num && st == HL_OK; i++) {
        slong deg = fmpz_poly_degree(fac->p + i);
        if (fac->exp[i] > 1)
            st = hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                              "A^2 is not diagonalizable (its minimal polynomial has a "
                              "repeated factor: a resonance with a Jordan block): no closed "
                              "form here; hl_exact_flow computes exp(DA) numerically");
        else if (deg > 2)
            st = hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                              "the normal-mode frequencies are roots of an irreducible "
                              "polynomial of degree %ld%s: no closed form here; "
                              "hl_exact_flow computes exp(DA) numerically",
                              (long)deg, deg == 3 ? " (a cubic)" : "");
    }
    for (slong i = 0; i < fac->num && st == HL_OK; i++) {
        fmpq_poly_set_fmpz_poly(f, fac->p + i);
        fmpq_poly_make_monic(f, f);
        if (fmpq_poly_degree(f) == 2) {
            fmpq_poly_get_coeff_fmpq(b1, f, 1);
            fmpq_poly_get_coeff_fmpq(c0, f, 0);
            fmpq_mul(disc, b1, b1);
            fmpq_mul_2exp(t, c0, 2);
            fmpq_sub(disc, disc, t);
            if (fmpq_sgn(disc) < 0) {
                st = hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                                  "A^2 has complex eigenvalues (spiral modes: the "
                                  "frequencies are neither real nor imaginary): no closed "
                                  "form here; hl_exact_flow computes exp(DA) numerically");
                break;
            }
        }
        /* E_f = e(M), e = cof * (cof^-1 mod f) mod m, cof = m / f */
        if (fac->num == 1) {
            fmpq_mat_one(E);
        } else {
            fmpq_poly_div(cof, m, f);
            fmpq_poly_xgcd(G, S, T, cof, f); /* G = 1 = S cof + T f */
            fmpq_poly_mul(e, S, cof);
            fmpq_poly_rem(e, e, m);
            poly_of_mat(E, e, Mm);
        }
        if (fmpq_poly_degree(f) == 1) {
            mode *md = &modes[(*nmodes)++];
            fmpq_poly_get_coeff_fmpq(md->alpha, f, 0);
            fmpq_neg(md->alpha, md->alpha);
            fmpq_mat_set(md->Pa, E);
            continue;
        }
        /* mu = alpha +- beta sqrt(d), alpha = -b1/2, beta sqrt(d) = sqrt(disc)/2;
         * P_+ = E/2 + (E M - alpha E)/(2 beta d) sqrt(d), P_- its conjugate */
        mode *mp = &modes[(*nmodes)++], *mn = &modes[(*nmodes)++];
        squarefree_part(mp->d, t, disc);
        fmpq_div_2exp(mp->beta, t, 1);
        fmpq_div_2exp(mp->alpha, b1, 1);
        fmpq_neg(mp->alpha, mp->alpha);
        fmpq_mat_mul(EM, E, Mm);
        fmpq_mat_scalar_mul_fmpq(mp->Pa, E, mp->alpha);
        fmpq_mat_sub(mp->Pb, EM, mp->Pa);
        fmpq_mul_fmpz(t, mp->beta, mp->d);
        fmpq_mul_2exp(t, t, 1);
        fmpq_inv(t, t);
        fmpq_mat_scalar_mul_fmpq(mp->Pb, mp->Pb, t);
        fmpq_set_si(t, 1, 2);
        fmpq_mat_scalar_mul_fmpq(mp->Pa, E, t);
        fmpz_set(mn->d, mp->d);
        fmpq_set(mn->alpha, mp->alpha);
        fmpq_neg(mn->beta, mp->beta);
        fmpq_mat_set(mn->Pa, mp->Pa);
        fmpq_mat_neg(mn->Pb, mp->Pb);
    }
    fmpq_poly_clear(m);
    fmpq_poly_clear(f);
    fmpq_poly_clear(cof);
    fmpq_poly_clear(G);
    fmpq_poly_clear(S);
    fmpq_poly_clear(T);
    fmpq_poly_clear(e);
    fmpz_poly_clear(mz);
    fmpz_poly_factor_clear(fac);
    fmpq_mat_clear(E);
    fmpq_mat_clear(EM);
    fmpq_clear(b1);
    fmpq_clear(c0);
    fmpq_clear(disc);
    fmpq_clear(t);
    return st;
}

/* ---- the images ------------------------------------------------------- */

/* Append " + (row i of P W . (z, 1)) * fun" to b, nothing when that row
 * is zero.  W has 2N + 1 columns: the phase variables, then the constant. */
static void put_term(hl_buf *b, const mode *md, const fmpq_mat_t W, int i, const char *fun,
                     hl_system *sys)
{
    int n = (int)fmpq_mat_nrows(W), cols = (int)fmpq_mat_ncols(W);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    fmpq_mat_t Wa, Wb;
    fmpq_mat_init(Wa, n, cols);
    fmpq_mat_init(Wb, n, cols);
    fmpq_mat_mul(Wa, md->Pa, W);
    fmpq_mat_mul(Wb, md->Pb, W);
    hl_buf lin;
    hl_buf_init(&lin);
    for (int k = 0; k < cols; k++) {
        const fmpq *a = fmpq_mat_entry(Wa, i, k), *c = fmpq_mat_entry(Wb, i, k);
        if (fmpq_is_zero(a) && fmpq_is_zero(c))
            continue;
        hl_buf_puts(&lin, lin.len ? " + " : "");
        put_surd(&lin, a, c, md->d);
        if (k < n)
            hl_buf_printf(&lin, "*%s", hl_alg_ctx_name(ctx, k));
    }
    if (lin.len)
        hl_buf_printf(b, " + (%s)*(%s)", lin.s, fun);
    hl_buf_clear(&lin);
    fmpq_mat_clear(Wa);
    fmpq_mat_clear(Wb);
}

/* The texts of C, S, K (header) at mode md, in the step named D. */
static void mode_funs(hl_buf *C, hl_buf *S, hl_buf *K, const mode *md, const char *D)
{
    int sg = surd_sgn(md->alpha, md->beta, md->d);
    if (sg == 0) {
        hl_buf_puts(C, "1");
        hl_buf_puts(S, D);
        hl_buf_printf(K, "%s^2/2", D);
        return;
    }
    fmpq_t a, c; /* w^2 = |mu| = a + c sqrt(d) */
    fmpq_init(a);
    fmpq_init(c);
    fmpq_mul_si(a, md->alpha, sg);
    fmpq_mul_si(c, md->beta, sg);
    hl_buf w, w2;
    hl_buf_init(&w);
    hl_buf_init(&w2);
    put_root(&w, a, c, md->d);
    put_surd(&w2, a, c, md->d);
    const char *cf = sg < 0 ? "cos" : "cosh", *sf = sg < 0 ? "sin" : "sinh";
    hl_buf_printf(C, "%s(%s*%s)", cf, w.s, D);
    hl_buf_printf(S, "%s(%s*%s)/%s", sf, w.s, D, w.s);
    if (sg < 0)
        hl_buf_printf(K, "(1 - cos(%s*%s))/%s", w.s, D, w2.s);
    else
        hl_buf_printf(K, "(cosh(%s*%s) - 1)/%s", w.s, D, w2.s);
    hl_buf_clear(&w);
    hl_buf_clear(&w2);
    fmpq_clear(a);
    fmpq_clear(c);
}

/* The first pair coupled to another (for the messages). */
static void coupled_pair(int *j, int *k, const hl_alg *hess, int N, hl_alg_ctx *ctx)
{
    int M = 2 * N;
    for (int a = 0; a < M; a++)
        for (int b = 0; b < M; b++)
            if (a % N != b % N && !hl_alg_is_zero(&hess[a * M + b], ctx)) {
                *j = a % N < b % N ? a % N : b % N;
                *k = a % N < b % N ? b % N : a % N;
                return;
            }
    *j = 0;
    *k = N > 1 ? 1 : 0;
}

/* A = J Hess and b = J grad H(0) as rational matrices; 0 if symbolic. */
static int rational_field(fmpq_mat_t A, fmpq_mat_t b, const hl_alg *hess, const hl_alg *g0,
                          int N, hl_alg_ctx *ctx)
{
    int M = 2 * N, ok = 1;
    for (int i = 0; i < M && ok; i++) {
        int src = i < N ? N + i : i - N; /* q' = H_p, p' = -H_q */
        for (int k = 0; k < M && ok; k++)
            ok = hl_alg_is_fmpq(&hess[src * M + k], fmpq_mat_entry(A, i, k), ctx);
        ok = ok && hl_alg_is_fmpq(&g0[src], fmpq_mat_entry(b, i, 0), ctx);
        if (ok && i >= N) {
            for (int k = 0; k < M; k++)
                fmpq_neg(fmpq_mat_entry(A, i, k), fmpq_mat_entry(A, i, k));
            fmpq_neg(fmpq_mat_entry(b, i, 0), fmpq_mat_entry(b, i, 0));
        }
    }
    return ok;
}

/* The rational field z' = A z + b of H, M = A^2 and its modes. */
static int field_modes(mode *modes, int *nmodes, fmpq_mat_t A, fmpq_mat_t b, fmpq_mat_t Mm,
                       const hl_alg *hess, const hl_alg *g0, hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), j, k;
    coupled_pair(&j, &k, hess, N, ctx);
    if (!rational_field(A, b, hess, g0, N, ctx))
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                            "H couples the pairs of %s and %s and has symbolic coefficients: "
                            "the closed form of coupled pairs needs rational ones",
                            hl_system_coord(sys, j), hl_system_coord(sys, k));
    fmpq_mat_mul(Mm, A, A);
    return decompose(modes, nmodes, Mm, err);
}

int scheme_linear_modes_text(char **text, const hl_alg *hess, const hl_alg *g0, hl_system *sys,
                             hl_error *err)
{
    int M = 2 * hl_system_ndof(sys), nmodes = 0;
    fmpq_mat_t A, b, Mm;
    fmpq_mat_init(A, M, M);
    fmpq_mat_init(b, M, 1);
    fmpq_mat_init(Mm, M, M);
    mode *modes = malloc((size_t)M * sizeof *modes);
    for (int i = 0; i < M; i++)
        mode_init(&modes[i], M);
    int st = field_modes(modes, &nmodes, A, b, Mm, hess, g0, sys, err);
    hl_buf t;
    hl_buf_init(&t);
    for (int m = 0; m < nmodes && st == HL_OK; m++) {
        const mode *md = &modes[m];
        int sg = surd_sgn(md->alpha, md->beta, md->d);
        hl_buf_puts(&t, m ? "; " : "");
        if (sg == 0) {
            hl_buf_puts(&t, "free (w = 0)");
            continue;
        }
        fmpq_t a, c; /* w^2 = |mu| = a + c sqrt(d) */
        fmpq_init(a);
        fmpq_init(c);
        fmpq_mul_si(a, md->alpha, sg);
        fmpq_mul_si(c, md->beta, sg);
        hl_buf_puts(&t, sg < 0 ? "elliptic w = " : "hyperbolic w = ");
        put_root(&t, a, c, md->d);
        fmpq_clear(a);
        fmpq_clear(c);
    }
    *text = st == HL_OK ? hl_buf_take(&t) : NULL;
    hl_buf_clear(&t);
    for (int i = 0; i < M; i++)
        mode_clear(&modes[i]);
    free(modes);
    fmpq_mat_clear(A);
    fmpq_mat_clear(b);
    fmpq_mat_clear(Mm);
    return st;
}

int scheme_linear_modes(hl_alg *images, const hl_alg *hess, const hl_alg *g0, hl_system *sys,
                        hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), M = 2 * N, st = HL_OK, nmodes = 0;
    fmpq_mat_t A, b, Mm, WC, WS, WK, Ab;
    fmpq_mat_init(A, M, M);
    fmpq_mat_init(b, M, 1);
    fmpq_mat_init(Mm, M, M);
    fmpq_mat_init(WC, M, M + 1);
    fmpq_mat_init(WS, M, M + 1);
    fmpq_mat_init(WK, M, M + 1);
    fmpq_mat_init(Ab, M, 1);
    mode *modes = malloc((size_t)M * sizeof *modes);
    for (int i = 0; i < M; i++)
        mode_init(&modes[i], M);
    if ((st = field_modes(modes, &nmodes, A, b, Mm, hess, g0, sys, err)) != HL_OK)
        goto done;
    /* W_C = [I | 0], W_S = [A | b], W_K = [0 | A b]: the coefficient of
     * C, S, K in the image is P W (z, 1). */
    fmpq_mat_mul(Ab, A, b);
    for (int i = 0; i < M; i++) {
        fmpq_one(fmpq_mat_entry(WC, i, i));
        for (int c = 0; c < M; c++)
            fmpq_set(fmpq_mat_entry(WS, i, c), fmpq_mat_entry(A, i, c));
        fmpq_set(fmpq_mat_entry(WS, i, M), fmpq_mat_entry(b, i, 0));
        fmpq_set(fmpq_mat_entry(WK, i, M), fmpq_mat_entry(Ab, i, 0));
    }
    const char *D = hl_alg_ctx_name(ctx, hl_system_var_D(sys));
    for (int i = 0; i < M && st == HL_OK; i++) {
        hl_buf t;
        hl_buf_init(&t);
        hl_buf_puts(&t, "0");
        for (int m = 0; m < nmodes; m++) {
            hl_buf C, S, K;
            hl_buf_init(&C);
            hl_buf_init(&S);
            hl_buf_init(&K);
            mode_funs(&C, &S, &K, &modes[m], D);
            put_term(&t, &modes[m], WC, i, C.s, sys);
            put_term(&t, &modes[m], WS, i, S.s, sys);
            put_term(&t, &modes[m], WK, i, K.s, sys);
            hl_buf_clear(&C);
            hl_buf_clear(&S);
            hl_buf_clear(&K);
        }
        st = hl_system_read(&images[i], sys, t.s, err);
        hl_buf_clear(&t);
    }
done:
    for (int i = 0; i < M; i++)
        mode_clear(&modes[i]);
    free(modes);
    fmpq_mat_clear(A);
    fmpq_mat_clear(b);
    fmpq_mat_clear(Mm);
    fmpq_mat_clear(WC);
    fmpq_mat_clear(WS);
    fmpq_mat_clear(WK);
    fmpq_mat_clear(Ab);
    return st;
}
