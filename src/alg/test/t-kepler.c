/* The Lie series workload of planar Kepler, written with diff/mul/sub:
 * g phi = sum_j dphi/dq_j dH/dp_j - dphi/dp_j dH/dq_j.  Checks: g H = 0 and
 * g L = 0 (L = x py - y px) exactly; g^2 x = -x/(x^2+y^2)^(3/2) exactly;
 * g^k x canonical up to k = 8.  Prints the time of g^8 of x, y, px, py. */
#include <time.h>

#include "hamlie/alg.h"
#include "hl_test.h"

static hl_alg_ctx *ctx;
static hl_alg dH[4];

static void gen_apply(hl_alg *r, const hl_alg *phi)
{
    hl_alg acc, t;
    hl_alg_init(&acc, ctx);
    hl_alg_init(&t, ctx);
    for (int j = 0; j < 2; j++) {
        hl_alg_diff(&t, phi, j, ctx, NULL);
        hl_alg_mul(&t, &t, &dH[2 + j], ctx);
        hl_alg_add(&acc, &acc, &t, ctx);
        hl_alg_diff(&t, phi, 2 + j, ctx, NULL);
        hl_alg_mul(&t, &t, &dH[j], ctx);
        hl_alg_sub(&acc, &acc, &t, ctx);
    }
    hl_alg_swap(r, &acc, ctx);
    hl_alg_clear(&acc, ctx);
    hl_alg_clear(&t, ctx);
}

static int rd(hl_alg *r, hl_pool *pool, const char *s)
{
    const hl_expr *e;
    hl_error err;
    hl_status st = hl_parse(&e, pool, s, &err);
    return st == HL_OK ? hl_alg_from_expr(r, e, ctx, &err) : st;
}

int main(void)
{
    const char *names[] = {"x", "y", "px", "py"};
    hl_pool *pool = hl_pool_new();
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    ctx = hl_alg_ctx_new(4, names, 0);
    hl_alg H, phi, r;
    hl_alg_init(&H, ctx);
    hl_alg_init(&phi, ctx);
    hl_alg_init(&r, ctx);
    CHECK(rd(&H, pool, "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)") == HL_OK);
    for (int i = 0; i < 4; i++) {
        hl_alg_init(&dH[i], ctx);
        CHECK(hl_alg_diff(&dH[i], &H, i, ctx, NULL) == HL_OK);
    }
    long terms = 0;
    int canon = 1;
    for (int z = 0; z < 4; z++) {
        hl_alg_gen(&phi, z, ctx);
        for (int k = 0; k < 8; k++) {
            gen_apply(&phi, &phi);
            canon &= hl_alg_is_canonical(&phi, ctx);
        }
        terms += hl_alg_length(&phi, ctx);
    }
    clock_gettime(CLOCK_MONOTONIC, &t1);
    printf("kepler g^8 of x, y, px, py: %.4f s, %ld terms\n",
           (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec), terms);
    CHECK(canon);

    gen_apply(&r, &H);
    CHECK(fmpz_mpoly_is_zero(r.num, hl_alg_ctx_mpoly(ctx)));
    CHECK(rd(&phi, pool, "x*py - y*px") == HL_OK);
    gen_apply(&r, &phi);
    CHECK(fmpz_mpoly_is_zero(r.num, hl_alg_ctx_mpoly(ctx)));
    hl_alg_gen(&phi, 0, ctx);
    gen_apply(&phi, &phi);
    gen_apply(&phi, &phi);
    CHECK(rd(&r, pool, "-x/(x^2+y^2)^(3/2)") == HL_OK);
    CHECK(fmpz_mpoly_equal(phi.num, r.num, hl_alg_ctx_mpoly(ctx))
          && fmpz_mpoly_equal(phi.den, r.den, hl_alg_ctx_mpoly(ctx)));

    for (int i = 0; i < 4; i++)
        hl_alg_clear(&dH[i], ctx);
    hl_alg_clear(&H, ctx);
    hl_alg_clear(&phi, ctx);
    hl_alg_clear(&r, ctx);
    hl_alg_ctx_free(ctx);
    hl_pool_free(pool);
    return HL_TEST_END();
}
