/* Series maps and §4 of the paper, on the oscillator H = (x^2 + p^2)/2 and
 * the pendulum H = p^2/2 - cos q.  Expected values by hand:
 *  - exp(Dg) x = x cos D + p sin D (the rotation), checked against the
 *    expansion of that closed form;
 *  - Euler psi = (x + Dp, p - Dx): psi - exp(Dg) z = sum D^k/k! v_k with
 *    v_2 = (x, p), v_3 = (p, -x), v_4 = (-x, -p)  (the paper prints
 *    v_3 = p d/dx + x d/dp; the sign of the second component is -x: the
 *    D^3 term of p cos D - x sin D is +x/6);
 *    K(D) = psi_{-D} o d/dD psi_D = (p + D x, -x + D p) exactly;
 *  - discrete gradient = rotation by theta(D) = 2 atan(D/2) (Cayley), so
 *    K(D) = theta'(D) (p, -x) = 4/(4 + D^2) (p, -x), and the errors
 *    v_3 = -1/2 g, v_4 = 2 (x, p), v_5 = 13/2 g as in the paper (by hand from
 *    theta = D - D^3/12 + D^5/80); the paper's display (ErrDG) prints
 *    1 + D^2/(4 + D^2), a sign slip: its own v_3 needs 1 - D^2/(4 + D^2);
 *  - group laws: exp(Dg) o exp(Dg) = exp(2Dg) on the pendulum, and
 *    psi_{-D} o psi_D = id for the discrete gradient;
 *  - for the exact flow K = g exactly. */
#include "sr.h"

enum { VX, VQ, VP, VD };

static const int qx[] = {VX}, px[] = {VP}, qq[] = {VQ}, pp[] = {VP};
static const int vars_x[] = {VX, VP}, vars_q[] = {VQ, VP};

static void lie_pair(hl_series *L, const char *H, const int *qv, const int *pv, int n)
{
    hl_alg h, z;
    hl_error err;
    hl_alg_init(&h, ctx);
    hl_alg_init(&z, ctx);
    rd(&h, H);
    hl_alg_gen(&z, qv[0], ctx);
    CHECK(hl_series_lie(&L[0], &z, &h, 1, qv, pv, n, ctx, &err) == HL_OK);
    hl_alg_gen(&z, pv[0], ctx);
    CHECK(hl_series_lie(&L[1], &z, &h, 1, qv, pv, n, ctx, &err) == HL_OK);
    hl_alg_clear(&h, ctx);
    hl_alg_clear(&z, ctx);
}

static void from(hl_series *s, const char *closed, int n)
{
    hl_alg a;
    hl_error err;
    hl_alg_init(&a, ctx);
    rd(&a, closed);
    CHECK(hl_series_from_alg(s, &a, VD, n, ctx, &err) == HL_OK);
    hl_alg_clear(&a, ctx);
}

/* k! (A - B)_k == want (an element) */
static void check_vk(const hl_series *A, const hl_series *B, int k, const char *want)
{
    hl_alg d, w;
    fmpq_t f;
    hl_alg_init(&d, ctx);
    hl_alg_init(&w, ctx);
    fmpq_init(f);
    hl_alg_sub(&d, &A->c[k], &B->c[k], ctx);
    long fact = 1;
    for (int i = 2; i <= k; i++)
        fact *= i;
    fmpq_set_si(f, fact, 1);
    hl_alg_scalar_mul_fmpq(&d, &d, f, ctx);
    rd(&w, want);
    CHECK_MSG(hl_alg_equal(&d, &w, ctx), "v_%d: want %s", k, want);
    hl_alg_clear(&d, ctx);
    hl_alg_clear(&w, ctx);
    fmpq_clear(f);
}

static void euler(void)
{
    const int n = 7;
    hl_series L[2], psi[2], K[2], s;
    hl_error err;
    for (int i = 0; i < 2; i++) {
        hl_series_init(&L[i], 0, ctx);
        hl_series_init(&psi[i], 0, ctx);
        hl_series_init(&K[i], 0, ctx);
    }
    hl_series_init(&s, 0, ctx);
    lie_pair(L, "(x^2 + p^2)/2", qx, px, n);
    from(&s, "x*cos(D) + p*sin(D)", n);
    CHECK_SERIES(&L[0], &s, n);
    from(&s, "p*cos(D) - x*sin(D)", n);
    CHECK_SERIES(&L[1], &s, n);

    rds(&psi[0], n, "x", "p", NULL);
    rds(&psi[1], n, "p", "-x", NULL);
    for (int j = 0; j < 2; j++) {
        check_vk(&psi[j], &L[j], 0, "0");
        check_vk(&psi[j], &L[j], 1, "0");
    }
    check_vk(&psi[0], &L[0], 2, "x");
    check_vk(&psi[1], &L[1], 2, "p");
    check_vk(&psi[0], &L[0], 3, "p");
    check_vk(&psi[1], &L[1], 3, "-x");
    check_vk(&psi[0], &L[0], 4, "-x");
    check_vk(&psi[1], &L[1], 4, "-p");

    CHECK(hl_series_scheme_K(K, 2, psi, vars_x, VD, ctx, &err) == HL_OK);
    CHECK(K[0].n == n - 1 && K[1].n == n - 1);
    rds(&s, n - 1, "p", "x", NULL);
    CHECK_SERIES(&K[0], &s, n - 1);
    rds(&s, n - 1, "-x", "p", NULL);
    CHECK_SERIES(&K[1], &s, n - 1);

    /* the exact flow has K = g: (p, -x) with nothing after */
    CHECK(hl_series_scheme_K(K, 2, L, vars_x, VD, ctx, &err) == HL_OK);
    rds(&s, n - 1, "p", NULL);
    CHECK_SERIES(&K[0], &s, n - 1);
    rds(&s, n - 1, "-x", NULL);
    CHECK_SERIES(&K[1], &s, n - 1);

    for (int i = 0; i < 2; i++) {
        hl_series_clear(&L[i], ctx);
        hl_series_clear(&psi[i], ctx);
        hl_series_clear(&K[i], ctx);
    }
    hl_series_clear(&s, ctx);
}

static void discrete_gradient(void)
{
    const int n = 9;
    hl_series L[2], psi[2], K[2], back[2], id[2], s;
    hl_error err;
    for (int i = 0; i < 2; i++) {
        hl_series_init(&L[i], 0, ctx);
        hl_series_init(&psi[i], 0, ctx);
        hl_series_init(&K[i], 0, ctx);
        hl_series_init(&back[i], 0, ctx);
        hl_series_init(&id[i], 0, ctx);
    }
    hl_series_init(&s, 0, ctx);
    hl_eqn eqs[2];
    int m;
    const char *unk[] = {"X", "P"};
    hl_alg z0[2];
    hl_alg_init(&z0[0], ctx);
    hl_alg_init(&z0[1], ctx);
    hl_alg_gen(&z0[0], VX, ctx);
    hl_alg_gen(&z0[1], VP, ctx);
    CHECK(hl_parse_list(eqs, 2, &m, pool, "(X-x)/D = (P+p)/2; (P-p)/D = -(X+x)/2", &err) == HL_OK);
    CHECK(hl_series_solve(psi, 2, eqs, unk, z0, "D", n, ctx, &err) == HL_OK);

    lie_pair(L, "(x^2 + p^2)/2", qx, px, n);
    check_vk(&psi[0], &L[0], 2, "0");
    check_vk(&psi[0], &L[0], 3, "-p/2");
    check_vk(&psi[1], &L[1], 3, "x/2");
    check_vk(&psi[0], &L[0], 4, "2*x");
    check_vk(&psi[1], &L[1], 4, "2*p");
    check_vk(&psi[0], &L[0], 5, "13*p/2");
    check_vk(&psi[1], &L[1], 5, "-13*x/2");

    CHECK(hl_series_scheme_K(K, 2, psi, vars_x, VD, ctx, &err) == HL_OK);
    from(&s, "4*p/(4 + D^2)", n - 1);
    CHECK_SERIES(&K[0], &s, n - 1);
    from(&s, "-4*x/(4 + D^2)", n - 1);
    CHECK_SERIES(&K[1], &s, n - 1);

    /* psi_{-D} o psi_D = id */
    hl_series_reflect(&back[0], &psi[0], ctx);
    hl_series_reflect(&back[1], &psi[1], ctx);
    CHECK(hl_series_compose(id, 2, back, 2, vars_x, psi, VD, ctx, &err) == HL_OK);
    rds(&s, n, "x", NULL);
    CHECK_SERIES(&id[0], &s, n);
    rds(&s, n, "p", NULL);
    CHECK_SERIES(&id[1], &s, n);

    for (int i = 0; i < 2; i++) {
        hl_series_clear(&L[i], ctx);
        hl_series_clear(&psi[i], ctx);
        hl_series_clear(&K[i], ctx);
        hl_series_clear(&back[i], ctx);
        hl_series_clear(&id[i], ctx);
        hl_alg_clear(&z0[i], ctx);
    }
    hl_series_clear(&s, ctx);
}

static void pendulum_group(void)
{
    const int n = 6;
    hl_series L[2], C[2], K[2], s;
    hl_error err;
    for (int i = 0; i < 2; i++) {
        hl_series_init(&L[i], 0, ctx);
        hl_series_init(&C[i], 0, ctx);
        hl_series_init(&K[i], 0, ctx);
    }
    hl_series_init(&s, 0, ctx);
    lie_pair(L, "p^2/2 - cos(q)", qq, pp, n);
    /* by hand: g q = p, g p = -sin q, g^2 q = -sin q, g^2 p = -p cos q */
    CHECK_COEF(&L[0], 1, "p");
    CHECK_COEF(&L[0], 2, "-sin(q)/2");
    CHECK_COEF(&L[1], 2, "-p*cos(q)/2");
    CHECK_COEF(&L[1], 3, "(p^2*sin(q) + sin(q)*cos(q))/6"); /* g^3 p = p^2 sin q + sin q cos q */
    CHECK(hl_series_compose(C, 2, L, 2, vars_q, L, VD, ctx, &err) == HL_OK);
    CHECK(C[0].n == n && C[1].n == n);
    for (int j = 0; j < 2; j++) {
        hl_series_set(&s, &L[j], ctx);
        fmpq_t two;
        fmpq_init(two);
        fmpq_set_si(two, 1, 1);
        for (int k = 0; k < n; k++) { /* exp(2Dg): 2^k c_k */
            hl_alg_scalar_mul_fmpq(&s.c[k], &s.c[k], two, ctx);
            fmpq_mul_2exp(two, two, 1);
        }
        fmpq_clear(two);
        CHECK_SERIES(&C[j], &s, n);
    }
    CHECK(hl_series_scheme_K(K, 2, L, vars_q, VD, ctx, &err) == HL_OK);
    rds(&s, n - 1, "p", NULL);
    CHECK_SERIES(&K[0], &s, n - 1);
    rds(&s, n - 1, "-sin(q)", NULL);
    CHECK_SERIES(&K[1], &s, n - 1);
    /* bad arguments */
    CHECK(hl_series_compose(C, 2, L, 2, vars_q, L, -1, ctx, &err) == HL_EINVAL);
    const int bad[] = {VD, VP};
    CHECK(hl_series_compose(C, 2, L, 2, bad, L, VD, ctx, &err) == HL_EINVAL);
    for (int i = 0; i < 2; i++) {
        hl_series_clear(&L[i], ctx);
        hl_series_clear(&C[i], ctx);
        hl_series_clear(&K[i], ctx);
    }
    hl_series_clear(&s, ctx);
}

int main(void)
{
    const char *names[] = {"x", "q", "p", "D"};
    setup(4, names);
    euler();
    discrete_gradient();
    pendulum_group();
    teardown();
    flint_cleanup();
    return HL_TEST_END();
}
