/* Symplectic Euler (both variants) and Stormer-Verlet on non-separable
 * Hamiltonians are implicit (solved order by order) and canonical: the
 * bracket {Q, P} of the truncated series is 1 + O(D^n) — its D-coefficients
 * 1..n-1 vanish (truncation at O(D^n) changes the bracket only at O(D^n)).
 * Explicit Euler on the same H is not: its D^2 coefficient is nonzero,
 * which shows the check can fail. */
#include "sch.h"

#define NC 6

/* D-coefficients of {Q, P} (1 dof): returns the first k in 1..n-1 where it
 * is nonzero, 0 if none, -1 on error; also checks coefficient 0 is 1. */
static int bracket_defect(hl_system *sys, const char *name, int *is_explicit)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_scheme *s;
    hl_error err;
    if (hl_scheme_new(&s, name, 0, sys, &err) != HL_OK) {
        fprintf(stderr, "%s: %s\n", name, err.msg);
        return -1;
    }
    *is_explicit = s->all_explicit;
    hl_series *Z = expand(s, NC);
    hl_scheme_free(s);
    if (Z == NULL)
        return -1;
    hl_alg Q, P, br, c;
    hl_alg_init(&Q, ctx), hl_alg_init(&P, ctx), hl_alg_init(&br, ctx), hl_alg_init(&c, ctx);
    int D = hl_system_var_D(sys), res = 0;
    hl_series_to_alg(&Q, &Z[0], D, ctx);
    hl_series_to_alg(&P, &Z[1], D, ctx);
    if (hl_bracket(&br, &Q, &P, sys, &err) != HL_OK)
        res = -1;
    for (int k = 0; res == 0 && k < NC; k++) {
        if (hl_alg_coeff(&c, &br, D, k, ctx, &err) != HL_OK) {
            res = -1;
            break;
        }
        if (k == 0) {
            hl_alg one;
            hl_alg_init(&one, ctx);
            hl_alg_one(&one, ctx);
            if (!hl_alg_equal(&c, &one, ctx))
                res = -1;
            hl_alg_clear(&one, ctx);
        } else if (!hl_alg_is_zero(&c, ctx))
            res = k;
    }
    hl_alg_clear(&Q, ctx), hl_alg_clear(&P, ctx), hl_alg_clear(&br, ctx), hl_alg_clear(&c, ctx);
    free_series(Z, 2, ctx);
    return res;
}

int main(void)
{
    const char *Hs[] = {"q^2*p^2/2", "(1 + q^2)*p^2/2 + q^2/2"};
    const char *canon[] = {"symplectic-euler-a", "symplectic-euler-b", "stormer-verlet-kdk",
                           "stormer-verlet-dkd", "implicit-midpoint"};
    for (int h = 0; h < 2; h++) {
        hl_system *sys = make_system(Hs[h]);
        for (int i = 0; i < 5; i++) {
            int ex = -1, d = bracket_defect(sys, canon[i], &ex);
            CHECK_MSG(d == 0, "%s on H = %s: {Q,P} - 1 has a D^%d term", canon[i], Hs[h], d);
            CHECK_MSG(ex == 0, "%s on non-separable H = %s should be implicit", canon[i], Hs[h]);
        }
        int ex = -1, d = bracket_defect(sys, "euler", &ex);
        CHECK_MSG(d == 2, "euler on H = %s: first defect at D^%d, want D^2", Hs[h], d);
        CHECK(ex == 1);
        hl_system_free(sys);
    }
    /* on a separable H the same schemes are explicit */
    hl_system *sys = make_system("p^2/2 - cos(q)");
    for (int i = 0; i < 4; i++) {
        int ex = -1, d = bracket_defect(sys, canon[i], &ex);
        CHECK_MSG(d == 0 && ex == 1, "%s on the pendulum: defect %d, explicit %d", canon[i], d,
                  ex);
    }
    hl_system_free(sys);
    return HL_TEST_END();
}
