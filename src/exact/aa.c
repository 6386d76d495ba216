/* A user's action-angle map, read and verified (§3 of the paper, steps
 * 3-7 given by the user instead of derived).
 *
 * Conditions, checked in this order, the first failure named:
 *   1. {theta, I} = 1                    (canonical pair)
 *   2. {I, H} = 0                        (I an integral)
 *   3. {theta, H} = nu(I(q,p))           (the frequency a function of I alone)
 *   4. q(theta(q,p), I(q,p)) = q, same for p  (the inverse)
 * 1-3 are exact (derivatives of the angle's atan/atan2/acos are algebraic).
 * 4 is checked numerically at sample points in all four quadrants and on
 * the axes (turning points p = 0, and q = 0 with p < 0, the cut of
 * atan2(q, p)): 1-3 are local, blind to the branch of the angle, and an
 * angle given by atan(q/p) is an inverse for p > 0 only (sqrt(q^2+p^2)
 * sin(atan(q/p)) is q sign(p)); atan2(q, p) is the angle everywhere. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "hamlie/exact.h"

static int alg_of(hl_alg *r, const hl_expr *e, hl_system *sys, hl_error *err)
{
    return hl_alg_from_expr(r, e, hl_system_ctx(sys), err);
}

hl_status hl_exact_aa_read(hl_exact_aa *aa, hl_system *sys, const char *spec, hl_error *err)
{
    memset(aa, 0, sizeof *aa);
    if (hl_system_ndof(sys) != 1)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                            "action-angle maps are handled for 1 degree of freedom");
    hl_eqn eq[8];
    int n = 0;
    hl_pool *pool = hl_system_pool(sys);
    int st = hl_parse_list(eq, 8, &n, pool, spec, err);
    if (st != HL_OK)
        return st;
    const char *qn = hl_system_coord(sys, 0), *pn = hl_system_momentum(sys, 0);
    for (int i = 0; i < n; i++) {
        const hl_expr *l = eq[i].lhs;
        if (l == NULL || l->kind != HL_SYM)
            return hl_error_set(err, HL_EPARSE, spec, eq[i].pos, 0,
                                "expected 'name = formula' (theta, I, %s, %s, nu)", qn, pn);
        const char *nm = l->name;
        if (strcmp(nm, "theta") == 0)
            aa->theta = eq[i].rhs;
        else if (strcmp(nm, "I") == 0)
            aa->I = eq[i].rhs;
        else if (strcmp(nm, qn) == 0)
            aa->q = eq[i].rhs;
        else if (strcmp(nm, pn) == 0)
            aa->p = eq[i].rhs;
        else if (strcmp(nm, "nu") == 0)
            aa->nu = eq[i].rhs;
        else
            return hl_error_set(err, HL_EINVAL, spec, eq[i].pos, 0,
                                "unknown item '%s' (expected theta, I, %s, %s, nu)", nm, qn,
                                pn);
    }
    const char *miss = !aa->theta ? "theta" : !aa->I ? "I" : !aa->q ? qn : !aa->p ? pn
                     : !aa->nu  ? "nu"
                                : NULL;
    if (miss != NULL)
        return hl_error_set(err, HL_EINVAL, spec, -1, 0, "the action-angle map lacks '%s'",
                            miss);
    /* The map is of phase space alone: the step in it would be taken for the
     * step, not for a parameter of that name. */
    const char *step = hl_system_step(sys);
    for (int i = 0; i < n; i++)
        if (hl_expr_has_symbol(eq[i].rhs, step))
            return hl_error_set(err, HL_EINVAL, spec, hl_symbol_pos(spec, step),
                                (int)strlen(step),
                                "'%s' is the step's name and cannot appear in the "
                                "action-angle map; if it is a parameter, give the step "
                                "another name (--step h)",
                                step);
    return HL_OK;
}

/* e with theta -> th, I -> act (expressions). */
static const hl_expr *in_qp(hl_pool *pool, const hl_expr *e, const hl_expr *th,
                            const hl_expr *act)
{
    const char *names[2] = {"theta", "I"};
    const hl_expr *vals[2] = {th, act};
    return hl_expr_subst(pool, e, 2, names, vals);
}

hl_status hl_exact_aa_verify(int *ok, char *why, size_t whylen, const hl_exact_aa *aa,
                             hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_pool *pool = hl_system_pool(sys);
    hl_alg th, act, br, nu, one;
    hl_alg_init(&th, ctx);
    hl_alg_init(&act, ctx);
    hl_alg_init(&br, ctx);
    hl_alg_init(&nu, ctx);
    hl_alg_init(&one, ctx);
    *ok = 1;
    why[0] = 0;
    int st = alg_of(&th, aa->theta, sys, err);
    if (st == HL_OK)
        st = alg_of(&act, aa->I, sys, err);
    if (st == HL_OK)
        st = hl_bracket(&br, &th, &act, sys, err);
    if (st == HL_OK) {
        hl_alg_one(&one, ctx);
        hl_alg_sub(&br, &br, &one, ctx);
        if (!hl_alg_is_zero(&br, ctx)) {
            *ok = 0;
            snprintf(why, whylen, "{theta, I} = 1 fails: not a canonical pair");
        }
    }
    if (st == HL_OK && *ok) {
        int yes = 0;
        st = hl_check_integral(&yes, &br, &act, sys, err);
        if (st == HL_OK && !yes) {
            *ok = 0;
            snprintf(why, whylen, "{I, H} = 0 fails: I is not an integral of motion");
        }
    }
    if (st == HL_OK && *ok) {
        st = hl_generator_apply(&br, &th, sys, err); /* {theta, H} */
        if (st == HL_OK)
            st = alg_of(&nu, in_qp(pool, aa->nu, aa->theta, aa->I), sys, err);
        if (st == HL_OK) {
            hl_alg_sub(&br, &br, &nu, ctx);
            if (!hl_alg_is_zero(&br, ctx)) {
                *ok = 0;
                snprintf(why, whylen,
                         "{theta, H} = nu(I) fails: the angle does not advance at the "
                         "frequency nu(I)");
            }
        }
    }
    /* 4: the inverse, numerically at points in every quadrant and on the
     * axes; symbolic parameters take the values 1.3, 1.47, 1.64, ...
     * (positive: masses, stiffnesses) */
    static const double pts[][2] = {{0.3, 0.8},  {-0.7, 0.4}, {1.1, 1.3}, {0.05, 0.6},
                                    {-0.6, -0.9}, {0.5, -0.3}, {0.8, 0},  {-0.6, 0},
                                    {0, -0.7}};
    const int npts = (int)(sizeof pts / sizeof *pts);
    int np = hl_system_nparams(sys) < 14 ? hl_system_nparams(sys) : 14;
    const char *names[16] = {hl_system_coord(sys, 0), hl_system_momentum(sys, 0)};
    double pv[16];
    for (int i = 0; i < np; i++) {
        names[2 + i] = hl_system_param(sys, i);
        pv[2 + i] = 1.3 + 0.17 * i;
    }
    const hl_expr *inv[2] = {in_qp(pool, aa->q, aa->theta, aa->I),
                             in_qp(pool, aa->p, aa->theta, aa->I)};
    for (int i = 0; st == HL_OK && *ok && i < npts; i++)
        for (int v = 0; v < 2 && *ok; v++) {
            double val = NAN, *vals = pv;
            vals[0] = pts[i][0];
            vals[1] = pts[i][1];
            if (hl_expr_eval_d(&val, inv[v], 2 + np, names, vals, err) != HL_OK ||
                !(fabs(val - vals[v]) <= 1e-12 * (1 + fabs(vals[v])))) {
                *ok = 0;
                snprintf(why, whylen,
                         "the inverse fails: %s(theta(q,p), I(q,p)) = %.17g, not %g at "
                         "(%s, %s) = (%g, %g)",
                         names[v], val, vals[v], names[0], names[1], vals[0], vals[1]);
            }
        }
    hl_alg_clear(&th, ctx);
    hl_alg_clear(&act, ctx);
    hl_alg_clear(&br, ctx);
    hl_alg_clear(&nu, ctx);
    hl_alg_clear(&one, ctx);
    return st;
}

hl_status hl_exact_aa_scheme(hl_alg *images, const hl_exact_aa *aa, hl_system *sys, hl_error *err)
{
    hl_pool *pool = hl_system_pool(sys);
    /* theta -> theta(q,p) + nu(I(q,p)) D, I -> I(q,p) */
    const hl_expr *nu = in_qp(pool, aa->nu, aa->theta, aa->I);
    const hl_expr *th = hl_add(pool, aa->theta, hl_mul(pool, nu, hl_sym(pool, hl_system_step(sys))));
    int st = alg_of(&images[0], in_qp(pool, aa->q, th, aa->I), sys, err);
    if (st == HL_OK)
        st = alg_of(&images[1], in_qp(pool, aa->p, th, aa->I), sys, err);
    return st;
}
