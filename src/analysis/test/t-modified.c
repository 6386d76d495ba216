/* Backward error analysis against Hairer-Lubich-Wanner ch. IX, the expected
 * values computed here from H by derivatives (not by the modified-field code).
 *
 * Symmetric BCH with Poisson brackets, by hand.  The Lie operator of a
 * Hamiltonian F is L_F phi = {phi, F}; Jacobi gives [L_F, L_G] = L_{G,F}, so
 * the double brackets keep their sign: [L_X,[L_X,L_Y]] = L_{X,{X,Y}}.  A
 * composition of flows is the product of exponentials in reverse order,
 * which does not matter for a palindrome.  So
 *   log(e^{X/2} e^{Y} e^{X/2}) = X + Y - (1/24)[X,[X,Y]] - (1/12)[Y,[X,Y]]
 * gives H~ = A + B - D^2/24 {A,{A,B}} - D^2/12 {B,{A,B}} for the scheme
 * phi^A_{D/2} o phi^B_D o phi^A_{D/2}.  With T = p^2/2, U = U(q),
 * {f,g} = f_q g_p - f_p g_q:
 *   {U,T} = U' p, {U,{U,T}} = U'^2, {T,{U,T}} = -p^2 U''
 *   velocity Verlet (kick-drift-kick: A = U, B = T):
 *     H~ = H - D^2 U'^2/24 + D^2 p^2 U''/12
 *   {T,U} = -p U', {T,{T,U}} = p^2 U'', {U,{T,U}} = -U'^2
 *   position Verlet (drift-kick-drift: A = T, B = U):
 *     H~ = H - D^2 p^2 U''/24 + D^2 U'^2/12
 * Symplectic Euler (HLW VI.3.1), HLW IX (non-separable H):
 *   H~ = H - D/2 H_p H_q + D^2/12 (H_pp H_q^2 + H_qq H_p^2 + 4 H_pq H_p H_q)
 *   (its separable part re-derived from the non-symmetric BCH
 *   X + Y + [X,Y]/2 + ([X,[X,Y]] + [Y,[Y,X]])/12.)
 * Midpoint rule (HLW IX.1): f~ = f + D^2 (f'f'f/12 - f''(f,f)/24); the
 * average vector field differs by (1/6 - 1/8) f''(Delta,Delta) in its
 * quadrature of f, which cancels the f''(f,f) term: f~ = f + D^2 f'f'f/12.
 * Both are symmetric: f_2 = 0. */
#include <stdlib.h>

#include "hamlie/analysis.h"
#include "hamlie/scheme.h"
#include "hl_test.h"
#include "analysis_test.h"

#define NM 3

/* mf of catalog scheme name, (NM+1)*m entries */
static hl_alg *modified(hl_system *sys, const char *name)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int m = 2 * hl_system_ndof(sys);
    hl_series *Z = malloc((size_t)m * sizeof *Z);
    for (int i = 0; i < m; i++)
        hl_series_init(&Z[i], 0, ctx);
    hl_alg *mf = hl_alg_vec_new((NM + 1) * m, ctx);
    hl_scheme *s;
    hl_error err;
    int st = hl_scheme_new(&s, name, 0, sys, &err);
    if (st == HL_OK)
        st = hl_scheme_expand(Z, s, NM + 1, &err);
    if (st == HL_OK)
        st = hl_modified_field(mf, Z, sys, NM, &err);
    if (st != HL_OK) {
        fprintf(stderr, "%s: %s\n", name, err.msg);
        exit(1);
    }
    hl_scheme_free(s);
    for (int i = 0; i < m; i++)
        hl_series_clear(&Z[i], ctx);
    free(Z);
    return mf;
}

static void rd(hl_alg *a, hl_system *sys, const char *f)
{
    hl_error err;
    if (hl_system_read(a, sys, f, &err) != HL_OK)
        exit(2);
}

static void df(hl_alg *r, const hl_alg *a, int v, hl_system *sys)
{
    hl_error err;
    hl_alg_diff(r, a, v, hl_system_ctx(sys), &err);
}

/* Is the field v (one dof) = J grad h = (h_p, -h_q)? */
static int is_ham(const hl_alg *v, const hl_alg *h, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg a;
    hl_alg_init(&a, ctx);
    df(&a, h, 1, sys);
    int ok = hl_alg_equal(&a, &v[0], ctx);
    df(&a, h, 0, sys);
    hl_alg_neg(&a, &a, ctx);
    ok = ok && hl_alg_equal(&a, &v[1], ctx);
    hl_alg_clear(&a, ctx);
    return ok;
}

static int is_zero_field(const hl_alg *v, int m, hl_alg_ctx *ctx)
{
    for (int i = 0; i < m; i++)
        if (!hl_alg_is_zero(&v[i], ctx))
            return 0;
    return 1;
}

int main(void)
{
    hl_error err;
    /* ---- Stormer-Verlet on H = p^2/2 + U, U = q^4/4 - q^2/2 ---- */
    hl_system *sys = make_system("p^2/2 + q^4/4 - q^2/2");
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg h, w;
    hl_alg_init(&h, ctx);
    hl_alg_init(&w, ctx);
    hl_alg *mf = modified(sys, "stormer-verlet-kdk");
    CHECK(is_ham(&mf[2], hl_system_H(sys), sys)); /* f_1 = f */
    CHECK(is_zero_field(&mf[4], 2, ctx));
    rd(&h, sys, "-(q^3 - q)^2/24 + p^2*(3*q^2 - 1)/12");
    CHECK(is_ham(&mf[6], &h, sys));
    hl_errfield F;
    CHECK(hl_errfield_classify(&F, &mf[6], sys, &err) == HL_OK && F.hamiltonian && F.have_h);
    CHECK(hl_alg_equal(&F.h, &h, ctx));
    hl_errfield_clear(&F, sys);
    hl_alg_vec_free(mf, 2 * (NM + 1), ctx);
    mf = modified(sys, "stormer-verlet-dkd");
    CHECK(is_zero_field(&mf[4], 2, ctx));
    rd(&h, sys, "-p^2*(3*q^2 - 1)/24 + (q^3 - q)^2/12");
    CHECK(is_ham(&mf[6], &h, sys));
    hl_alg_vec_free(mf, 2 * (NM + 1), ctx);

    /* ---- symplectic Euler on a non-separable H ---- */
    hl_system *se = make_system("(p^2 + q^2)/2 + p^2*q^2/2 + p*q^3");
    hl_alg_ctx *sc = hl_system_ctx(se);
    hl_alg Hp, Hq, Hpp, Hqq, Hpq, t, u;
    hl_alg *all[] = {&Hp, &Hq, &Hpp, &Hqq, &Hpq, &t, &u};
    for (int i = 0; i < 7; i++)
        hl_alg_init(all[i], sc);
    const hl_alg *H = hl_system_H(se);
    df(&Hp, H, 1, se);
    df(&Hq, H, 0, se);
    df(&Hpp, &Hp, 1, se);
    df(&Hqq, &Hq, 0, se);
    df(&Hpq, &Hp, 0, se);
    mf = modified(se, "symplectic-euler-a");
    hl_alg h2, h3;
    hl_alg_init(&h2, sc);
    hl_alg_init(&h3, sc);
    fmpq_t c;
    fmpq_init(c);
    hl_alg_mul(&h2, &Hp, &Hq, sc);
    fmpq_set_si(c, -1, 2);
    hl_alg_scalar_mul_fmpq(&h2, &h2, c, sc); /* -H_p H_q/2 */
    hl_alg_mul(&t, &Hq, &Hq, sc);
    hl_alg_mul(&h3, &Hpp, &t, sc);
    hl_alg_mul(&t, &Hp, &Hp, sc);
    hl_alg_mul(&t, &Hqq, &t, sc);
    hl_alg_add(&h3, &h3, &t, sc);
    hl_alg_mul(&t, &Hpq, &Hp, sc);
    hl_alg_mul(&t, &t, &Hq, sc);
    fmpq_set_si(c, 4, 1);
    hl_alg_scalar_mul_fmpq(&t, &t, c, sc);
    hl_alg_add(&h3, &h3, &t, sc);
    fmpq_set_si(c, 1, 12);
    hl_alg_scalar_mul_fmpq(&h3, &h3, c, sc);
    CHECK(is_ham(&mf[2], H, se));
    CHECK(is_ham(&mf[4], &h2, se));
    CHECK(is_ham(&mf[6], &h3, se));
    hl_alg_vec_free(mf, 2 * (NM + 1), sc);

    /* ---- midpoint and AVF on the pendulum: f'f'f and f''(f,f) ---- */
    hl_system *pe = make_system("p^2/2 - cos(q)");
    hl_alg_ctx *pc = hl_system_ctx(pe);
    hl_alg f[2], J[4], ffa[2], fff[2], d2, s1;
    for (int i = 0; i < 2; i++) {
        hl_alg_init(&f[i], pc);
        hl_alg_init(&ffa[i], pc);
        hl_alg_init(&fff[i], pc);
    }
    for (int i = 0; i < 4; i++)
        hl_alg_init(&J[i], pc);
    hl_alg_init(&d2, pc);
    hl_alg_init(&s1, pc);
    CHECK(hl_generator(&f[0], &f[1], pe, &err) == HL_OK);
    for (int i = 0; i < 2; i++)
        for (int l = 0; l < 2; l++)
            df(&J[2 * i + l], &f[i], l, pe);
    for (int i = 0; i < 2; i++) { /* ffa = f'f */
        hl_alg_mul(&ffa[i], &J[2 * i], &f[0], pc);
        hl_alg_mul(&s1, &J[2 * i + 1], &f[1], pc);
        hl_alg_add(&ffa[i], &ffa[i], &s1, pc);
    }
    for (int i = 0; i < 2; i++) { /* fff = f'f'f */
        hl_alg_mul(&fff[i], &J[2 * i], &ffa[0], pc);
        hl_alg_mul(&s1, &J[2 * i + 1], &ffa[1], pc);
        hl_alg_add(&fff[i], &fff[i], &s1, pc);
    }
    hl_alg want_avf[2], want_mid[2];
    for (int i = 0; i < 2; i++) {
        hl_alg_init(&want_avf[i], pc);
        hl_alg_init(&want_mid[i], pc);
        fmpq_set_si(c, 1, 12);
        hl_alg_scalar_mul_fmpq(&want_avf[i], &fff[i], c, pc);
        /* f''(f,f)_i = sum_{l,m} d^2 f_i/dz_l dz_m f_l f_m */
        hl_alg ffs;
        hl_alg_init(&ffs, pc);
        for (int l = 0; l < 2; l++)
            for (int mm = 0; mm < 2; mm++) {
                df(&d2, &J[2 * i + l], mm, pe);
                hl_alg_mul(&d2, &d2, &f[l], pc);
                hl_alg_mul(&d2, &d2, &f[mm], pc);
                hl_alg_add(&ffs, &ffs, &d2, pc);
            }
        fmpq_set_si(c, -1, 24);
        hl_alg_scalar_mul_fmpq(&ffs, &ffs, c, pc);
        hl_alg_add(&want_mid[i], &want_avf[i], &ffs, pc);
        if (i == 1) /* f = (p, -sin q): f''(f,f) = (0, p^2 sin q); the expectations differ */
            CHECK(!hl_alg_is_zero(&ffs, pc));
        hl_alg_clear(&ffs, pc);
    }
    mf = modified(pe, "avf");
    CHECK(is_zero_field(&mf[4], 2, pc));
    CHECK(hl_alg_equal(&mf[6], &want_avf[0], pc) && hl_alg_equal(&mf[7], &want_avf[1], pc));
    hl_alg_vec_free(mf, 2 * (NM + 1), pc);
    mf = modified(pe, "implicit-midpoint");
    CHECK(is_zero_field(&mf[4], 2, pc));
    CHECK(hl_alg_equal(&mf[6], &want_mid[0], pc) && hl_alg_equal(&mf[7], &want_mid[1], pc));
    hl_alg_vec_free(mf, 2 * (NM + 1), pc);

    for (int i = 0; i < 2; i++) {
        hl_alg_clear(&f[i], pc);
        hl_alg_clear(&ffa[i], pc);
        hl_alg_clear(&fff[i], pc);
        hl_alg_clear(&want_avf[i], pc);
        hl_alg_clear(&want_mid[i], pc);
    }
    for (int i = 0; i < 4; i++)
        hl_alg_clear(&J[i], pc);
    hl_alg_clear(&d2, pc);
    hl_alg_clear(&s1, pc);
    hl_system_free(pe);
    for (int i = 0; i < 7; i++)
        hl_alg_clear(all[i], sc);
    hl_alg_clear(&h2, sc);
    hl_alg_clear(&h3, sc);
    fmpq_clear(c);
    hl_system_free(se);
    hl_alg_clear(&h, ctx);
    hl_alg_clear(&w, ctx);
    hl_system_free(sys);
    return HL_TEST_END();
}
