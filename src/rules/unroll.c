/* hl_conv_unrolled: a convolution as a sequence of the emitter's own
 * products and sums, in hl_conv_plan's order (see rule.h for the forms of
 * the terms), so that code built from it does the interpreter's operations. */
#include <stdlib.h>

#include "base/buf.h"
#include "rules/unroll.h"

/* (w x[j]) y[k-j] when weighted, x[j] y[k-j] when not; the fresh x[k] term
 * (j = k > 0) as (w y[0]) x[k] or x[k] y[0], so that x[k], computed last,
 * enters through a single product */
static hl_ev term(hl_em *E, const hl_conv *c, int j, int fresh)
{
    int sym_pair = c->sym && 2 * j < c->k;
    hl_ev w = {0};
    if (c->weighted)
        w = EV_ADD(E, EV_MUL(E, c->wa, EV_NUM(E, j, 1)), c->wb);
    else if (sym_pair)
        w = EV_NUM(E, 2, 1);
    int weighted = c->weighted || sym_pair;
    if (fresh && j == c->k && c->k > 0) {
        hl_ev xk = EV_COEF(E, c->x, c->k), y0 = EV_COEF(E, c->y, 0);
        return weighted ? EV_MUL(E, EV_MUL(E, w, y0), xk) : EV_MUL(E, xk, y0);
    }
    hl_ev xj = EV_COEF(E, c->x, j), ykj = EV_COEF(E, c->y, c->k - j);
    return weighted ? EV_MUL(E, EV_MUL(E, w, xj), ykj) : EV_MUL(E, xj, ykj);
}

/* a + b where either may be absent */
static hl_ev plus(hl_em *E, hl_ev a, int has_a, hl_ev b, int has_b, int *has)
{
    *has = has_a || has_b;
    if (has_a && has_b)
        return EV_ADD(E, a, b);
    return has_a ? a : b;
}

hl_ev hl_conv_unrolled(hl_em *E, const hl_conv *c, int *has)
{
    int cap = c->hi >= c->lo ? c->hi - c->lo + 1 : 1;
    int *idx = hl_xmalloc((size_t)cap * sizeof *idx),
        *lane = hl_xmalloc((size_t)cap * sizeof *lane);
    int n, nf, fresh[2];
    hl_conv_plan(c, idx, lane, &n, fresh, &nf);
    hl_ev l[4] = {{0}};
    int used[4] = {0};
    for (int i = 0; i < n; i++) {
        hl_ev t = term(E, c, idx[i], 0);
        l[lane[i]] = used[lane[i]] ? EV_ADD(E, l[lane[i]], t) : t;
        used[lane[i]] = 1;
    }
    free(idx);
    free(lane);
    int h01, h23;
    hl_ev p01 = plus(E, l[0], used[0], l[1], used[1], &h01);
    hl_ev p23 = plus(E, l[2], used[2], l[3], used[3], &h23);
    hl_ev s = plus(E, p01, h01, p23, h23, has);
    for (int i = 0; i < nf; i++)
        s = plus(E, s, *has, term(E, c, fresh[i], 1), 1, has);
    return s;
}
