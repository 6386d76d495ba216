/* Test helper: random expression DAGs from a fixed-seed generator, with
 * every kind, negative and fractional numbers in every position, and
 * sharing (an operand may be a node made earlier). */
#ifndef HL_TEST_GEN_H
#define HL_TEST_GEN_H

#include <stdint.h>
#include "hamlie/expr.h"

typedef struct gen {
    uint64_t s;
    const hl_expr *made[64]; /* recent nodes, reused to make a DAG */
    int nmade;
    int small; /* no 31-digit numbers (for checks in double precision) */
} gen;

static uint64_t gen_next(gen *g) /* splitmix64 */
{
    uint64_t z = (g->s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static int gen_int(gen *g, int n) { return (int)(gen_next(g) % (uint64_t)n); }

static const char *const gen_names[] = {"x", "y", "px", "q_1", "omega", "D", "e", "E"};

static const hl_expr *gen_num(gen *g, hl_pool *pool)
{
    switch (gen_int(g, g->small ? 5 : 6)) {
    case 0: return hl_num_si(pool, gen_int(g, 4));                 /* 0..3 */
    case 1: return hl_num_si(pool, -1 - gen_int(g, 5));            /* negative */
    case 2: return hl_num_frac(pool, 1 + gen_int(g, 7), 2 + (unsigned long)gen_int(g, 5));
    case 3: return hl_num_frac(pool, -1 - gen_int(g, 7), 2 + (unsigned long)gen_int(g, 5));
    case 4: return hl_num_si(pool, gen_int(g, 1000));
    default: {
        fmpq_t q; /* a big one */
        fmpq_init(q);
        fmpz_set_ui(fmpq_numref(q), 10);
        fmpz_pow_ui(fmpq_numref(q), fmpq_numref(q), 30);
        fmpz_add_ui(fmpq_numref(q), fmpq_numref(q), 7);
        if (gen_int(g, 2))
            fmpz_neg(fmpq_numref(q), fmpq_numref(q));
        fmpz_set_ui(fmpq_denref(q), gen_int(g, 2) ? 1 : 3);
        fmpq_canonicalise(q);
        const hl_expr *e = hl_num_fmpq(pool, q);
        fmpq_clear(q);
        return e;
    }
    }
}

static const hl_expr *gen_expr(gen *g, hl_pool *pool, int depth)
{
    const hl_expr *e;
    int k = depth <= 0 ? gen_int(g, 3) : gen_int(g, 14);
    if (k >= 3 && g->nmade > 0 && gen_int(g, 8) == 0)
        return g->made[gen_int(g, g->nmade)];
    switch (k) {
    case 0: e = gen_num(g, pool); break;
    case 1: e = hl_sym(pool, gen_names[gen_int(g, 8)]); break;
    case 2: e = gen_int(g, 4) ? gen_num(g, pool) : hl_pi(pool); break;
    case 3: case 4: e = hl_neg(pool, gen_expr(g, pool, depth - 1)); break;
    case 5: e = hl_add(pool, gen_expr(g, pool, depth - 1), gen_expr(g, pool, depth - 1)); break;
    case 6: e = hl_sub(pool, gen_expr(g, pool, depth - 1), gen_expr(g, pool, depth - 1)); break;
    case 7: e = hl_mul(pool, gen_expr(g, pool, depth - 1), gen_expr(g, pool, depth - 1)); break;
    case 8: e = hl_div(pool, gen_expr(g, pool, depth - 1), gen_expr(g, pool, depth - 1)); break;
    case 9: case 10:
        e = hl_pow(pool, gen_expr(g, pool, depth - 1), gen_expr(g, pool, depth - 1));
        break;
    default: {
        hl_fun f = (hl_fun)gen_int(g, HL_FUN_COUNT);
        const hl_expr *a = gen_expr(g, pool, depth - 1);
        e = hl_fun_arity(f) == 2 ? hl_call2(pool, f, a, gen_expr(g, pool, depth - 1))
                                 : hl_call(pool, f, a);
    }
    }
    if (g->nmade < 64)
        g->made[g->nmade++] = e;
    else
        g->made[gen_int(g, 64)] = e;
    return e;
}

#endif
