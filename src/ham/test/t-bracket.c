/* Property tests of the Poisson bracket and the generator on random
 * polynomial, rational and trigonometric functions of 2 degrees of freedom:
 * antisymmetry, Jacobi identity, Leibniz rule; g is a derivation and
 * g(phi) = {phi, H}; canonical relations {q_i, p_j} = delta_ij. */
#include "ham_test.h"

static unsigned long rng = 12345;

static long rnd(long n) /* 0..n-1, a fixed-seed LCG: reproducible failures */
{
    rng = rng * 6364136223846793005UL + 1442695040888963407UL;
    return (long)((rng >> 33) % (unsigned long)n);
}

/* A random polynomial: a few terms c * z1^e1 ... with |c| <= 3, degree <= 2
 * in each of q1, q2, p1, p2. */
static void rand_poly(hl_alg *r, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg t, z;
    hl_alg_init(&t, ctx);
    hl_alg_init(&z, ctx);
    hl_alg_zero(r, ctx);
    int nterms = 1 + (int)rnd(4);
    for (int k = 0; k < nterms; k++) {
        hl_alg_set_si(&t, rnd(7) - 3, ctx);
        for (int v = 0; v < 4; v++) {
            long e = rnd(3);
            hl_alg_gen(&z, v, ctx);
            for (long i = 0; i < e; i++)
                hl_alg_mul(&t, &t, &z, ctx);
        }
        hl_alg_add(r, r, &t, ctx);
    }
    hl_alg_clear(&t, ctx);
    hl_alg_clear(&z, ctx);
}

/* kind 0: polynomial; 1: polynomial / (1 + polynomial^2) (never zero);
 * 2: polynomial times sin(q1) plus polynomial times cos(p2). */
static void rand_elem(hl_alg *r, hl_system *sys, int kind)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg a, b;
    hl_alg_init(&a, ctx);
    hl_alg_init(&b, ctx);
    rand_poly(r, sys);
    if (kind == 1) {
        rand_poly(&a, sys);
        hl_alg_mul(&a, &a, &a, ctx);
        hl_alg_one(&b, ctx);
        hl_alg_add(&a, &a, &b, ctx);
        hl_alg_div(r, r, &a, ctx, NULL);
    } else if (kind == 2) {
        rd(&a, sys, "sin(q1)");
        hl_alg_mul(r, r, &a, ctx);
        rand_poly(&b, sys);
        rd(&a, sys, "cos(p2)");
        hl_alg_mul(&b, &b, &a, ctx);
        hl_alg_add(r, r, &b, ctx);
    }
    hl_alg_clear(&a, ctx);
    hl_alg_clear(&b, ctx);
}

static hl_alg_ctx *C;
static hl_system *S;

static hl_alg br(const hl_alg *a, const hl_alg *b)
{
    hl_alg r;
    hl_alg_init(&r, C);
    int st = hl_bracket(&r, a, b, S, NULL);
    CHECK(st == HL_OK);
    CHECK(hl_alg_is_canonical(&r, C));
    return r;
}

static void test_laws(int kind, int rounds)
{
    for (int it = 0; it < rounds; it++) {
        hl_alg a, b, c, t, u, v, w;
        hl_alg_init(&a, C), hl_alg_init(&b, C), hl_alg_init(&c, C);
        hl_alg_init(&w, C);
        rand_elem(&a, S, kind);
        rand_elem(&b, S, kind);
        rand_elem(&c, S, (kind + it) % 3);

        /* antisymmetry {a,b} = -{b,a} */
        t = br(&a, &b);
        u = br(&b, &a);
        hl_alg_add(&w, &t, &u, C);
        CHECK_MSG(hl_alg_is_zero(&w, C), "antisymmetry, kind %d round %d", kind, it);
        hl_alg_clear(&t, C), hl_alg_clear(&u, C);

        /* Jacobi {a,{b,c}} + {b,{c,a}} + {c,{a,b}} = 0 */
        hl_alg bc = br(&b, &c), ca = br(&c, &a), ab = br(&a, &b);
        t = br(&a, &bc);
        u = br(&b, &ca);
        v = br(&c, &ab);
        hl_alg_add(&w, &t, &u, C);
        hl_alg_add(&w, &w, &v, C);
        CHECK_MSG(hl_alg_is_zero(&w, C), "Jacobi, kind %d round %d", kind, it);
        hl_alg_clear(&t, C), hl_alg_clear(&u, C), hl_alg_clear(&v, C);
        hl_alg_clear(&bc, C), hl_alg_clear(&ca, C), hl_alg_clear(&ab, C);

        /* Leibniz {a, b c} = {a,b} c + b {a,c} */
        hl_alg prod;
        hl_alg_init(&prod, C);
        hl_alg_mul(&prod, &b, &c, C);
        t = br(&a, &prod);
        u = br(&a, &b);
        v = br(&a, &c);
        hl_alg_mul(&u, &u, &c, C);
        hl_alg_mul(&v, &v, &b, C);
        hl_alg_add(&w, &u, &v, C);
        hl_alg_sub(&w, &w, &t, C);
        CHECK_MSG(hl_alg_is_zero(&w, C), "Leibniz, kind %d round %d", kind, it);
        hl_alg_clear(&t, C), hl_alg_clear(&u, C), hl_alg_clear(&v, C);

        /* g is a derivation: g(bc) = b g(c) + c g(b); and g(a) = {a, H} */
        hl_alg_init(&t, C), hl_alg_init(&u, C), hl_alg_init(&v, C);
        CHECK(hl_generator_apply(&t, &prod, S, NULL) == HL_OK);
        CHECK(hl_generator_apply(&u, &b, S, NULL) == HL_OK);
        CHECK(hl_generator_apply(&v, &c, S, NULL) == HL_OK);
        hl_alg_mul(&u, &u, &c, C);
        hl_alg_mul(&v, &v, &b, C);
        hl_alg_add(&w, &u, &v, C);
        CHECK_MSG(hl_alg_equal(&w, &t, C), "derivation, kind %d round %d", kind, it);
        CHECK(hl_generator_apply(&t, &a, S, NULL) == HL_OK);
        hl_alg_clear(&u, C);
        u = br(&a, hl_system_H(S));
        CHECK_MSG(hl_alg_equal(&t, &u, C), "g(a) = {a,H}, kind %d round %d", kind, it);
        hl_alg_clear(&t, C), hl_alg_clear(&u, C), hl_alg_clear(&v, C);
        hl_alg_clear(&prod, C);
        hl_alg_clear(&a, C), hl_alg_clear(&b, C), hl_alg_clear(&c, C), hl_alg_clear(&w, C);
    }
}

static void test_canonical_relations(void)
{
    hl_alg zi, zj, r;
    hl_alg_init(&zi, C), hl_alg_init(&zj, C), hl_alg_init(&r, C);
    for (int i = 0; i < 4; i++)
        for (int j = 0; j < 4; j++) {
            hl_alg_gen(&zi, i, C);
            hl_alg_gen(&zj, j, C);
            CHECK(hl_bracket(&r, &zi, &zj, S, NULL) == HL_OK);
            /* base order q1 q2 p1 p2: {q_i, p_i} = 1, {p_i, q_i} = -1, else 0 */
            long want = (i < 2 && j == i + 2) ? 1 : (i >= 2 && j == i - 2) ? -1 : 0;
            fmpq_t c;
            fmpq_init(c);
            CHECK_MSG(hl_alg_is_fmpq(&r, c, C) && fmpq_equal_si(c, want),
                      "{z%d, z%d} should be %ld", i, j, want);
            fmpq_clear(c);
        }
    hl_alg_clear(&zi, C), hl_alg_clear(&zj, C), hl_alg_clear(&r, C);
}

int main(int argc, char **argv)
{
    int mult = argc > 1 ? atoi(argv[1]) : 1; /* longer runs: t-bracket 10 */
    S = sys_new("(p1^2 + p2^2)/2 + q1^2*q2 - cos(q2)", NULL);
    C = hl_system_ctx(S);
    CHECK(hl_system_ndof(S) == 2);
    CHECK_STR(hl_system_coord(S, 0), "q1");
    CHECK_STR(hl_system_momentum(S, 1), "p2");
    test_canonical_relations();
    test_laws(0, 20 * mult);
    test_laws(1, 8 * mult);
    test_laws(2, 8 * mult);
    hl_system_free(S);
    return HL_TEST_END();
}
