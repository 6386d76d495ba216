/* Internals of the numeric error analysis (numeric.c): dual numbers and
 * their power series, computed by the rules of src/rules (dual.c). */
#ifndef HAMLIE_ANALYSIS_NUMERIC_IMPL_H
#define HAMLIE_ANALYSIS_NUMERIC_IMPL_H

#include "hamlie/tape.h"

/* a + b eps, eps^2 = 0 */
typedef struct dn {
    double r, e;
} dn;

static inline dn dmul(dn a, dn b)
{
    return (dn){a.r * b.r, a.r * b.e + a.e * b.r};
}
static inline dn dadd(dn a, dn b)
{
    return (dn){a.r + b.r, a.e + b.e};
}
static inline dn dsub(dn a, dn b)
{
    return (dn){a.r - b.r, a.e - b.e};
}
static inline dn dscal(dn a, double c)
{
    return (dn){a.r * c, a.e * c};
}
static inline dn ddiv(dn a, dn b)
{
    return (dn){a.r / b.r, (a.e * b.r - a.r * b.e) / (b.r * b.r)};
}
static inline int dzero(dn a)
{
    return a.r == 0 && a.e == 0;
}

/* d = op(a, b) on series of L coefficients, by the operation's rule; x is
 * the rule's second series (cos beside sin, ...; scratch if NULL), c the
 * constant of a^c.  The caller checks the domain first. */
void dual_series_op(hl_op op, int L, dn *d, dn *x, const dn *a, const dn *b, double c);

#endif /* HAMLIE_ANALYSIS_NUMERIC_IMPL_H */
