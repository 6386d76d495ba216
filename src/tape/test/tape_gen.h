/* Shared by the tape tests: random expressions over x, y, z that reach every
 * opcode (gen), and an independent reference evaluator written from libm
 * (ref), so that a tape is never checked against itself. */
#ifndef HL_TAPE_TEST_GEN_H
#define HL_TAPE_TEST_GEN_H

#include <math.h>

#include "hamlie/tape.h"

static const char *const vars[] = {"x", "y", "z"};

/* The reference: straight recursion over the DAG, libm for functions. */
static double ref(const hl_expr *e, const double *v)
{
    switch (e->kind) {
    case HL_NUM: return fmpq_get_d(e->num);
    case HL_PI: return M_PI;
    case HL_SYM:
        for (int i = 0; i < 3; i++)
            if (strcmp(e->name, vars[i]) == 0)
                return v[i];
        return NAN;
    case HL_NEG: return -ref(e->a, v);
    case HL_ADD: return ref(e->a, v) + ref(e->b, v);
    case HL_SUB: return ref(e->a, v) - ref(e->b, v);
    case HL_MUL: return ref(e->a, v) * ref(e->b, v);
    case HL_DIV: return ref(e->a, v) / ref(e->b, v);
    case HL_POW: return pow(ref(e->a, v), ref(e->b, v));
    case HL_FUN: {
        double a = ref(e->a, v);
        switch (e->fun) {
        case HL_ATAN2: return atan2(a, ref(e->b, v));
        case HL_SIN: return sin(a);
        case HL_COS: return cos(a);
        case HL_TAN: return tan(a);
        case HL_EXP: return exp(a);
        case HL_LOG: return log(a);
        case HL_SQRT: return sqrt(a);
        case HL_ATAN: return atan(a);
        case HL_ASIN: return asin(a);
        case HL_ACOS: return acos(a);
        case HL_SINH: return sinh(a);
        case HL_COSH: return cosh(a);
        case HL_TANH: return tanh(a);
        case HL_ASINH: return asinh(a);
        default: return NAN;
        }
    }
    }
    return NAN;
}

static unsigned long rng = 12345;
static unsigned rnd(unsigned n)
{
    rng = rng * 6364136223846793005UL + 1442695040888963407UL;
    return (unsigned)(rng >> 33) % n;
}

/* A random expression whose value stays in the domain of every function
 * (arguments of log/sqrt made positive, of asin/acos kept in (-1, 1)). */
static const hl_expr *gen(hl_pool *P, int depth)
{
    if (depth == 0) {
        switch (rnd(4)) {
        case 0: return hl_num_frac(P, (long)rnd(7) - 3, 1 + rnd(4));
        case 1: return hl_pi(P);
        default: return hl_sym(P, vars[rnd(3)]);
        }
    }
    const hl_expr *a = gen(P, depth - 1), *b = gen(P, depth - 1);
    const hl_expr *one = hl_num_si(P, 1), *two = hl_num_si(P, 2);
    const hl_expr *pos = hl_add(P, one, hl_pow(P, b, two)); /* 1 + b^2 >= 1 */
    const hl_expr *sa = hl_call(P, HL_SIN, a);              /* in [-1, 1] */
    const hl_expr *half = hl_div(P, sa, two);
    const hl_expr *pi = hl_pi(P);
    switch (rnd(28)) {
    case 0: return hl_add(P, a, b);
    case 1: return hl_sub(P, a, b);
    case 2: return hl_mul(P, a, b);
    case 3: return hl_div(P, a, pos);
    case 4: return hl_neg(P, a);
    case 5: return hl_pow(P, a, hl_num_si(P, 2 + (long)rnd(4)));
    case 6: return hl_pow(P, pos, hl_num_si(P, -1 - (long)rnd(3)));
    case 7: { /* k/3, but 3/2 (POW3H) for 3/3 and 0/3 (a constant 1, a trivial case) */
        long k = (long)rnd(9) - 4;
        return hl_pow(P, pos, k == 3 || k == 0 ? hl_num_frac(P, 3, 2) : hl_num_frac(P, k, 3));
    }
    case 8: return hl_pow(P, pos, sa); /* non-constant exponent */
    case 9: return hl_call(P, HL_SQRT, pos);
    case 10: return hl_call(P, HL_EXP, sa);
    case 11: return hl_call(P, HL_LOG, pos);
    case 12: return hl_add(P, sa, hl_call(P, HL_COS, a)); /* shares one SINCOS */
    case 13: return hl_call(P, HL_TAN, half);
    case 14: return hl_call(P, HL_ATAN, a);
    case 15: return hl_call(P, HL_ASIN, half);
    case 16: return hl_call(P, HL_ACOS, half);
    case 17: return hl_call(P, HL_SINH, sa);
    case 18: return hl_call(P, HL_COSH, sa);
    case 19: return hl_call(P, HL_TANH, a);
    case 20: return hl_mul(P, hl_num_frac(P, 3, 7), a); /* a scale */
    case 21: return hl_div(P, a, pi);                   /* DIVK */
    case 22: return hl_sub(P, pi, a);                   /* KSUB */
    case 23: return hl_sub(P, a, pi);                   /* SUBK */
    case 24: return hl_div(P, pi, pos);                 /* KDIV */
    case 25: /* any quadrant; off the cut: a y that is 0 but not folded to 0
              * (sin(pi)) leaves Arb a ball [-pi, pi] where x < 0, and the folder
              * refuses a constant one (issue 14's note) */
        return hl_call2(P, HL_ATAN2, hl_add(P, a, hl_sym(P, vars[1])),
                        hl_add(P, b, hl_sym(P, vars[0])));
    case 26: return hl_call(P, HL_ASINH, a);
    default: return hl_sub(P, hl_num_si(P, 2), hl_div(P, hl_num_si(P, 3), pos)); /* KSUB, KDIV */
    }
}

static double relerr(double got, double want)
{
    return fabs(got - want) / (1 + fabs(want));
}

#endif
