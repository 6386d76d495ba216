/* What the rule files of src/tape/rules/ share: the shorthands for the
 * operands and a few recurring pieces (see rule.h for the contract). */
#ifndef HAMLIE_RULES_IMPL_H
#define HAMLIE_RULES_IMPL_H

#include "rules/rule.h"

#define D HL_SLOT_D
#define A HL_SLOT_A
#define B HL_SLOT_B
#define X HL_SLOT_X

/* Keep slots: the reciprocal of the divisor's coefficient 0, and a second
 * value (a ratio) for the fresh term of a quotient. */
enum { KEEP_INV = 0, KEEP_RATIO = 1 };

/* The sum of a convolution of x and y over j = lo..hi at k, weighted by
 * wa j + wb when weighted. */
static inline hl_ev rule_conv(hl_em *E, hl_slot x, hl_slot y, int lo, int hi, int k, int *has)
{
    hl_conv c = {x, y, lo, hi, k, 0, {0}, {0}, 0};
    return E->ops->conv(E, &c, has);
}

static inline hl_ev rule_wconv(hl_em *E, hl_slot x, hl_slot y, int lo, int hi, int k, hl_ev wa,
                               hl_ev wb, int *has)
{
    hl_conv c = {x, y, lo, hi, k, 1, wa, wb, 0};
    return E->ops->conv(E, &c, has);
}

/* (x*x)[k] over j = lo..k-lo, by symmetry */
static inline hl_ev rule_sqr(hl_em *E, hl_slot x, int lo, int k, int *has)
{
    hl_conv c = {x, x, lo, k - lo, k, 0, {0}, {0}, 1};
    return E->ops->conv(E, &c, has);
}

/* sum_{j=1..k} j x[j] y[k-j]: the derivative-times-series sum of
 * exp, sin/cos and tan */
static inline hl_ev rule_dconv(hl_em *E, hl_slot x, hl_slot y, int k, int *has)
{
    return rule_wconv(E, x, y, 1, k, k, EV_NUM(E, 1, 1), EV_NUM(E, 0, 1), has);
}

/* sum_{j=1..k-1} (k-j) x[j] y[k-j]: the inverse functions' sum */
static inline hl_ev rule_kconv(hl_em *E, hl_slot x, hl_slot y, int k, int *has)
{
    return rule_wconv(E, x, y, 1, k - 1, k, EV_NUM(E, -1, 1), EV_NUM(E, k, 1), has);
}

/* v - s when the sum s has terms, else v */
static inline hl_ev rule_minus(hl_em *E, hl_ev v, hl_ev s, int has)
{
    return has ? EV_SUB(E, v, s) : v;
}

/* keep 1/v */
static inline hl_ev rule_keep_inverse(hl_em *E, hl_ev v)
{
    hl_ev inv = EV_DIV(E, EV_NUM(E, 1, 1), v);
    EV_KEEP(E, KEEP_INV, inv);
    return inv;
}

/* a^c's recurrence at k > 0 (pow.c), shared with a^(3/2): stores d[k]
 * from c1 = c + 1 and the kept 1/a[0] and c d[0]/a[0] */
void rule_pow_step(hl_em *E, int k, hl_ev c1);

/* asin, acos, asinh (asin.c): d' = sign a'/x, x = sqrt(1 + a2_sign a^2);
 * point computes D[0] */
void rule_root_inverse(hl_em *E, int k, void (*point)(hl_em *), int a2_sign, int sign);

/* The rules, by file. */
extern const hl_rule hl_rule_neg, hl_rule_add, hl_rule_sub, hl_rule_addk, hl_rule_subk,
    hl_rule_ksub, hl_rule_mulk, hl_rule_divk; /* linear.c */
extern const hl_rule hl_rule_mul, hl_rule_sqr;   /* mul.c */
extern const hl_rule hl_rule_div, hl_rule_kdiv;  /* div.c */
extern const hl_rule hl_rule_powk;               /* pow.c */
extern const hl_rule hl_rule_pow3h;              /* pow3h.c */
extern const hl_rule hl_rule_sqrt;               /* sqrt.c */
extern const hl_rule hl_rule_exp;                /* exp.c */
extern const hl_rule hl_rule_log;                /* log.c */
extern const hl_rule hl_rule_sincos, hl_rule_sinhcosh; /* sincos.c */
extern const hl_rule hl_rule_tan, hl_rule_tanh;  /* tan.c */
extern const hl_rule hl_rule_atan;               /* atan.c */
extern const hl_rule hl_rule_asin, hl_rule_acos; /* asin.c */
extern const hl_rule hl_rule_asinh;              /* asinh.c */
extern const hl_rule hl_rule_atan2;              /* atan2.c */

#endif /* HAMLIE_RULES_IMPL_H */
