/* The table of rules (one per hl_op) and what every double back end must
 * share to agree bit for bit: the order of a convolution's terms and the
 * division of the Taylor-ODE step (rule.h). */
#include <math.h>

#include "rules/rules_impl.h"

static const hl_rule *const table[HL_OP_COUNT] = {
    [HL_OP_NEG] = &hl_rule_neg,       [HL_OP_ADD] = &hl_rule_add,
    [HL_OP_SUB] = &hl_rule_sub,       [HL_OP_MUL] = &hl_rule_mul,
    [HL_OP_DIV] = &hl_rule_div,       [HL_OP_SQR] = &hl_rule_sqr,
    [HL_OP_ADDK] = &hl_rule_addk,     [HL_OP_SUBK] = &hl_rule_subk,
    [HL_OP_KSUB] = &hl_rule_ksub,     [HL_OP_MULK] = &hl_rule_mulk,
    [HL_OP_DIVK] = &hl_rule_divk,     [HL_OP_KDIV] = &hl_rule_kdiv,
    [HL_OP_POWK] = &hl_rule_powk,     [HL_OP_SQRT] = &hl_rule_sqrt,
    [HL_OP_EXP] = &hl_rule_exp,       [HL_OP_LOG] = &hl_rule_log,
    [HL_OP_SINCOS] = &hl_rule_sincos, [HL_OP_SINHCOSH] = &hl_rule_sinhcosh,
    [HL_OP_TAN] = &hl_rule_tan,       [HL_OP_TANH] = &hl_rule_tanh,
    [HL_OP_ATAN] = &hl_rule_atan,     [HL_OP_ASIN] = &hl_rule_asin,
    [HL_OP_ACOS] = &hl_rule_acos,     [HL_OP_ASINH] = &hl_rule_asinh,
    [HL_OP_ATAN2] = &hl_rule_atan2,   [HL_OP_POW3H] = &hl_rule_pow3h,
};

const hl_rule *hl_rule_of(hl_op op) { return op >= 0 && op < HL_OP_COUNT ? table[op] : NULL; }

void hl_rule_recip_split(double *hi, double *lo, int n)
{
    *hi = 1.0 / n;
    *lo = fma(-*hi, (double)n, 1.0) / n; /* the residual 1 - hi n is exact */
}

/* A term is fresh when it reads a coefficient k: x[j] at j = k, y[k-j] at
 * j = 0.  Compiled code can add everything else before those are known,
 * which is why they come last. */
static int is_fresh(const hl_conv *c, int j) { return j == c->k || j == 0; }

static void add_term(const hl_conv *c, int j, int *idx, int *lane, int *n, int fresh[2], int *nf)
{
    if (is_fresh(c, j)) {
        fresh[(*nf)++] = j;
    } else {
        idx[*n] = j;
        lane[*n] = *n % 4;
        (*n)++;
    }
}

/* The known terms from the highest j down.  In every recurrence y is the
 * result's own series (D or X) and x an operand made earlier, so y[k-1],
 * the value made last, is read at the lowest j: added last in its lane, it
 * waits for three additions and the fresh terms, not for a whole lane of
 * them (Taylor-interpreter time per call, pendulum/Henon-Heiles/Kepler,
 * against from the lowest j up: see bench/taylor_interp.c and the
 * commit).  A square's middle term x[k/2]^2 is the highest j, so it comes
 * first, then the pairs j < k - j. */
void hl_conv_plan(const hl_conv *c, int *idx, int *lane, int *n, int fresh[2], int *nf)
{
    *n = *nf = 0;
    int top = c->sym && c->hi > c->k / 2 ? c->k / 2 : c->hi;
    for (int j = top; j >= c->lo; j--)
        add_term(c, j, idx, lane, n, fresh, nf); /* x's fresh term (j = k) before y's (j = 0) */
}
