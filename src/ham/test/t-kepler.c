/* Planar Kepler H = (px^2 + py^2)/2 - 1/r, r = sqrt(x^2 + y^2).
 * Classical facts (any mechanics text, e.g. Goldstein §3.9):
 *   L = x py - y px and the Runge-Lenz vector A = p x L e_z - r_vec/r,
 *   A1 = py L - x/r, A2 = -px L - y/r, are integrals;
 *   {L, A1} = A2, {L, A2} = -A1 (A is a vector under rotations);
 *   {A1, A2} = -2 H L  (the so(3) relations at negative energy).
 * Also: (H, L, A1, A2) has rank 3 (A^2 = 1 + 2 H L^2 ties them), (L, A1) rank 2. */
#include "ham_test.h"

#define A1 "py*(x*py - y*px) - x/sqrt(x^2+y^2)"
#define A2 "-px*(x*py - y*px) - y/sqrt(x^2+y^2)"

int main(void)
{
    hl_system *sys = sys_new("(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", NULL);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    CHECK(hl_system_ndof(sys) == 2);
    CHECK_STR(hl_system_coord(sys, 0), "x");
    CHECK_STR(hl_system_momentum(sys, 1), "py");

    hl_alg f[4], r, inv[9];
    for (int i = 0; i < 4; i++)
        hl_alg_init(&f[i], ctx);
    for (int i = 0; i < 9; i++)
        hl_alg_init(&inv[i], ctx);
    hl_alg_init(&r, ctx);
    rd(&f[0], sys, "x*py - y*px");
    rd(&f[1], sys, A1);
    rd(&f[2], sys, A2);
    rd(&f[3], sys, "H");

    int yes = 0;
    const char *name[4] = {"L", "A1", "A2", "H"};
    for (int i = 0; i < 4; i++) {
        CHECK(hl_check_integral(&yes, &r, &f[i], sys, NULL) == HL_OK);
        CHECK_MSG(yes && hl_alg_is_zero(&r, ctx), "%s is an integral", name[i]);
    }
    /* a non-integral for contrast: {x, H} = px */
    hl_alg x;
    hl_alg_init(&x, ctx);
    rd(&x, sys, "x");
    CHECK(hl_check_integral(&yes, &r, &x, sys, NULL) == HL_OK);
    CHECK(!yes && eq_formula(&r, sys, "px"));

    /* L and H in involution */
    hl_alg LH[2];
    hl_alg_init(&LH[0], ctx), hl_alg_init(&LH[1], ctx);
    hl_alg_set(&LH[0], &f[0], ctx);
    hl_alg_set(&LH[1], &f[3], ctx);
    int all = 0;
    CHECK(hl_check_involution(&all, inv, LH, 2, sys, NULL) == HL_OK);
    CHECK(all);

    /* L, A1, A2: not in involution; the brackets are the so(3) relations */
    CHECK(hl_check_involution(&all, inv, f, 3, sys, NULL) == HL_OK);
    CHECK(!all);
    CHECK_MSG(eq_formula(&inv[0 * 3 + 1], sys, A2), "{L, A1} = A2");
    CHECK_MSG(eq_formula(&inv[0 * 3 + 2], sys, "-(" A1 ")"), "{L, A2} = -A1");
    CHECK_MSG(eq_formula(&inv[1 * 3 + 2], sys, "-2*H*(x*py - y*px)"), "{A1, A2} = -2 H L");
    CHECK_MSG(eq_formula(&inv[2 * 3 + 1], sys, "2*H*(x*py - y*px)"), "{A2, A1} = 2 H L");
    CHECK(hl_alg_is_zero(&inv[1 * 3 + 1], ctx));

    /* independence */
    int rank = -1;
    CHECK(hl_jacobian_rank(&rank, f, 2, sys, NULL) == HL_OK);
    CHECK_MSG(rank == 2, "rank(L, A1) = %d", rank);
    CHECK(hl_jacobian_rank(&rank, f, 4, sys, NULL) == HL_OK);
    CHECK_MSG(rank == 3, "rank(L, A1, A2, H) = %d", rank);
    hl_alg twoL[2];
    hl_alg_init(&twoL[0], ctx), hl_alg_init(&twoL[1], ctx);
    hl_alg_set(&twoL[0], &f[0], ctx);
    hl_alg_mul(&twoL[1], &f[0], &f[0], ctx); /* L and L^2: dependent */
    CHECK(hl_jacobian_rank(&rank, twoL, 2, sys, NULL) == HL_OK);
    CHECK_MSG(rank == 1, "rank(L, L^2) = %d", rank);

    if (hl_alg_ctx_numeric_used(ctx))
        printf("note: the numeric zero test was used\n");
    for (int i = 0; i < 4; i++)
        hl_alg_clear(&f[i], ctx);
    for (int i = 0; i < 9; i++)
        hl_alg_clear(&inv[i], ctx);
    hl_alg_clear(&twoL[0], ctx), hl_alg_clear(&twoL[1], ctx);
    hl_alg_clear(&LH[0], ctx), hl_alg_clear(&LH[1], ctx);
    hl_alg_clear(&r, ctx), hl_alg_clear(&x, ctx);
    hl_system_free(sys);
    return HL_TEST_END();
}
