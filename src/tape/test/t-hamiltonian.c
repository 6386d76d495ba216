/* hl_tape_hamiltonian: the vector field (dH/dp, -dH/dq) of three
 * Hamiltonians, with a parameter substituted, against hand-written fields at
 * random points; and hl_tape_eval_d against hl_expr_eval_d on the same H. */
#include <math.h>
#include <stdlib.h>

#include "hl_test.h"
#include "hamlie/tape.h"

static hl_pool *P;

static double urand(void)
{
    return 2.0 * rand() / RAND_MAX - 1;
}

static void check_field(const char *label, const hl_expr *H, int N, const char *const *q,
                        const char *const *p, int npar, const char *const *par,
                        const hl_expr *const *val, void (*want)(double *f, const double *z))
{
    hl_tape *t = NULL;
    hl_error err;
    int st = hl_tape_hamiltonian(&t, P, H, N, q, p, npar, par, val, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", label, err.msg);
    if (st != HL_OK)
        return;
    CHECK(hl_tape_ninputs(t) == 2 * N && hl_tape_noutputs(t) == 2 * N);
    int bad = 0;
    for (int trial = 0; trial < 50; trial++) {
        double z[8], got[8], w[8];
        for (int i = 0; i < 2 * N; i++)
            z[i] = urand() + (i == 0 ? 2 : 0); /* keep Kepler's x away from 0 */
        hl_tape_eval_d(got, z, t);
        want(w, z);
        for (int i = 0; i < 2 * N; i++)
            if (fabs(got[i] - w[i]) > 1e-13 * (1 + fabs(w[i])))
                bad++;
    }
    CHECK_MSG(bad == 0, "%s: %d components differ", label, bad);
    hl_tape_free(t);
}

static void pendulum_field(double *f, const double *z)
{
    f[0] = z[1];
    f[1] = -2.0 / 3 * sin(z[0]);
}

static void henon_heiles_field(double *f, const double *z)
{
    double x = z[0], y = z[1];
    f[0] = z[2];
    f[1] = z[3];
    f[2] = -x - 2 * x * y;
    f[3] = -y - x * x + y * y;
}

static void kepler_field(double *f, const double *z)
{
    double r3 = pow(z[0] * z[0] + z[1] * z[1], 1.5);
    f[0] = z[2];
    f[1] = z[3];
    f[2] = -z[0] / r3;
    f[3] = -z[1] / r3;
}

int main(void)
{
    P = hl_pool_new();
    const hl_expr *two = hl_num_si(P, 2), *half = hl_num_frac(P, 1, 2);
    const hl_expr *q = hl_sym(P, "q"), *p = hl_sym(P, "p"), *k = hl_sym(P, "k");
    const hl_expr *x = hl_sym(P, "x"), *y = hl_sym(P, "y");
    const hl_expr *px = hl_sym(P, "px"), *py = hl_sym(P, "py");

    /* pendulum H = p^2/2 - k cos q, k = 2/3 */
    const hl_expr *H = hl_sub(P, hl_mul(P, half, hl_pow(P, p, two)),
                              hl_mul(P, k, hl_call(P, HL_COS, q)));
    const char *qn[] = {"q"}, *pn[] = {"p"}, *kn[] = {"k"};
    const hl_expr *kv[] = {hl_num_frac(P, 2, 3)};
    check_field("pendulum", H, 1, qn, pn, 1, kn, kv, pendulum_field);

    /* a parameter left without a value is an unknown symbol */
    hl_tape *t = NULL;
    hl_error err;
    CHECK(hl_tape_hamiltonian(&t, P, H, 1, qn, pn, 0, NULL, NULL, &err) == HL_EINVAL);
    CHECK(t == NULL);

    /* Henon-Heiles H = (px^2+py^2)/2 + (x^2+y^2)/2 + x^2 y - y^3/3 */
    const hl_expr *kin = hl_div(P, hl_add(P, hl_pow(P, px, two), hl_pow(P, py, two)), two);
    H = hl_add(P, hl_add(P, kin, hl_div(P, hl_add(P, hl_pow(P, x, two), hl_pow(P, y, two)), two)),
               hl_sub(P, hl_mul(P, hl_pow(P, x, two), y),
                      hl_div(P, hl_pow(P, y, hl_num_si(P, 3)), hl_num_si(P, 3))));
    const char *q2[] = {"x", "y"}, *p2[] = {"px", "py"};
    check_field("henon-heiles", H, 2, q2, p2, 0, NULL, NULL, henon_heiles_field);

    /* tape value of H itself vs the reference evaluator */
    const char *all[] = {"x", "y", "px", "py"};
    CHECK(hl_tape_new(&t, &H, 1, all, 4, &err) == HL_OK);
    for (int i = 0; i < 20; i++) {
        double z[4] = {urand(), urand(), urand(), urand()}, a, b;
        hl_tape_eval_d(&a, z, t);
        CHECK(hl_expr_eval_d(&b, H, 4, all, z, &err) == HL_OK);
        CHECK(fabs(a - b) < 1e-14);
    }
    hl_tape_free(t);

    /* Kepler H = (px^2+py^2)/2 - 1/sqrt(x^2+y^2) */
    H = hl_sub(P, kin, hl_div(P, hl_num_si(P, 1),
                              hl_call(P, HL_SQRT, hl_add(P, hl_pow(P, x, two), hl_pow(P, y, two)))));
    check_field("kepler", H, 2, q2, p2, 0, NULL, NULL, kepler_field);

    hl_pool_free(P);
    flint_cleanup();
    return HL_TEST_END();
}
