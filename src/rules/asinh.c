/* asinh(a), with X = sqrt(1 + a^2).  From x d' = a':
 *   x[k] = ((a*a)[k] - sum_{j=1..k-1} x[j] x[k-j]) / (2 x[0])   (the sqrt rule on 1 + a^2),
 *   d[k] = (k a[k] - sum_{j=1..k-1} (k-j) x[j] d[k-j]) / (k x[0]):
 * asin's recurrence with 1 + a^2 for 1 - a^2 (asin.c, rule_root_inverse). */
#include "rules/rules_impl.h"

static void asinh_point(hl_em *E) { EV_STORE(E, D, 0, EV_CALL(E, HL_PFN_ASINH, EV_COEF(E, A, 0))); }

static void asinh_taylor(hl_em *E, int k) { rule_root_inverse(E, k, asinh_point, 1, 1); }
const hl_rule hl_rule_asinh = {"asinh", asinh_point, asinh_taylor};
