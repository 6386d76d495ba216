/* The cost of a Taylor step against its order (cost.c,
 * hl_tape_taylor_step_ns), which the flow's order choice reads: below the
 * knee it is the quadratic of hl_tape_taylor_step_cost exactly; past it,
 * more, by a term in products p^2 alone (the compiled recursion's size),
 * the same for any tape with the same products; a tape without products
 * never reaches it; and the cost grows with the order. */
#include <math.h>
#include <stdio.h>

#include "tape/test/hamiltonian.h"

static double quadratic(const hl_tape *t, int p)
{
    double c[3];
    hl_tape_taylor_step_cost(t, c);
    return c[0] + c[1] * p + c[2] * p * p;
}

/* What the knee adds at order p */
static double excess(const hl_tape *t, int p)
{
    return hl_tape_taylor_step_ns(t, p) - quadratic(t, p);
}

static void test_monotone(const hl_tape *t, const char *name)
{
    for (int p = 2; p < 60; p++)
        CHECK_MSG(hl_tape_taylor_step_ns(t, p + 1) > hl_tape_taylor_step_ns(t, p),
                  "%s: cost falls from order %d to %d", name, p, p + 1);
}

/* No products (the oscillator: x' = px, px' = -x): no knee at any order */
static void test_no_products(hl_pool *P)
{
    hl_tape *t = test_hamiltonian(P, "(x^2 + px^2)/2", 1);
    for (int p = 2; p <= 200; p++)
        CHECK_MSG(excess(t, p) == 0, "oscillator order %d: excess %g", p, excess(t, p));
    test_monotone(t, "oscillator");
    hl_tape_free(t);
}

/* Kepler's tape: zero below some order, positive from it on, and of the
 * form a (products p^2 - K): K read off two orders predicts a third */
static void test_knee(hl_pool *P)
{
    hl_tape *t = test_hamiltonian(P, "(px^2 + py^2)/2 - 1/sqrt(x^2 + y^2)", 2);
    int knee = 0;
    for (int p = 2; p <= 60 && knee == 0; p++)
        if (excess(t, p) > 0)
            knee = p;
    CHECK_MSG(knee > 10 && knee < 40, "Kepler's knee at order %d", knee);
    for (int p = 2; p < knee; p++)
        CHECK_MSG(excess(t, p) == 0, "order %d below the knee: excess %g", p, excess(t, p));
    /* e(p) = a (P p^2 - K): e(p2) / e(p1) fixes K / P */
    int p1 = knee + 2, p2 = knee + 10, p3 = knee + 25;
    double e1 = excess(t, p1), e2 = excess(t, p2), e3 = excess(t, p3);
    double r = e2 / e1, k = (r * p1 * p1 - (double)p2 * p2) / (r - 1); /* K / P */
    double want = e1 * ((double)p3 * p3 - k) / ((double)p1 * p1 - k);
    CHECK_MSG(fabs(e3 - want) <= 1e-9 * e3, "excess at %d: %g, the form says %g", p3, e3, want);
    CHECK_MSG(k >= (knee - 1) * (knee - 1) && k < knee * knee, "K/P %g, knee %d", k, knee);
    test_monotone(t, "kepler");

    /* the same field written another way: the same products, the same cost */
    hl_tape *u = test_hamiltonian(P, "-1/sqrt(y^2 + x^2) + (py^2 + px^2)/2", 2);
    for (int p = 2; p <= 60; p++)
        CHECK_MSG(hl_tape_taylor_step_ns(u, p) == hl_tape_taylor_step_ns(t, p),
                  "order %d: %g against %g", p, hl_tape_taylor_step_ns(u, p),
                  hl_tape_taylor_step_ns(t, p));
    hl_tape_free(u);
    hl_tape_free(t);
}

/* More products reach the knee at a lower order (Henon-Heiles' 2 products
 * against Kepler's 4.5) */
static void test_knee_moves(hl_pool *P)
{
    hl_tape *k = test_hamiltonian(P, "(px^2 + py^2)/2 - 1/sqrt(x^2 + y^2)", 2);
    hl_tape *h = test_hamiltonian(P, "(px^2 + py^2)/2 + (x^2 + y^2)/2 + x^2*y - y^3/3", 2);
    int pk = 0, ph = 0;
    for (int p = 2; p <= 100; p++) {
        if (pk == 0 && excess(k, p) > 0)
            pk = p;
        if (ph == 0 && excess(h, p) > 0)
            ph = p;
    }
    CHECK_MSG(pk > 0 && ph > pk, "knees: Kepler %d, Henon-Heiles %d", pk, ph);
    printf("knee: Kepler at order %d, Henon-Heiles at %d\n", pk, ph);
    hl_tape_free(k);
    hl_tape_free(h);
}

int main(void)
{
    hl_pool *P = hl_pool_new();
    test_no_products(P);
    test_knee(P);
    test_knee_moves(P);
    hl_pool_free(P);
    return HL_TEST_END();
}
