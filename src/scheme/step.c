/* The numeric reading: one step in double, by tapes. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "base/memo.h"
#include "scheme/scheme_impl.h"

struct hl_scheme_stepper {
    int N, m, nin;
    int all_explicit;
    int iters;
    long steps;
    hl_tape *tape;  /* explicit: z, D -> Z.  Else z, D, U -> F */
    hl_tape *jac;   /* z, D, U -> F and dF/dU (row-major): the two share
                     * their subexpressions (sin and cos of a midpoint) */
    hl_tape *start; /* z, D -> the Newton starting point U0 */
    hl_tape *after; /* z, D, U -> the next point (eliminated unknowns too),
                     * then the Taylor rules' checks (integral.c) */
    double *in, *out, *U;
    hl_newton *nw;  /* the solve of the implicit equations (tape.h) */
    int ncheck;     /* the checks, each to be at most its bound, */
    double *bound;
    hl_scheme_stepper *fallback; /* else the step by this one: Gauss rules */
    long fallbacks;    /* steps it took since the restart */
    int use_fallback;  /* for every step: it took most of them */
    long jit_steps;    /* hl_scheme_stepper_jit's run length, for it too */
    hl_tape *energy;   /* z -> H and its rounding scale (energy_check), for
                        * a scheme that claims to preserve H; else NULL */
    const char *claims; /* that scheme's name (the catalog's) */
    int integrals;      /* its equations have integrals (by numeric rules) */
    double *at, at_energy[2]; /* the last point checked and its H, scale: the
                               * next step starts there */
};

void hl_scheme_stepper_free(hl_scheme_stepper *st)
{
    if (st == NULL)
        return;
    hl_tape_free(st->tape);
    hl_tape_free(st->jac);
    hl_tape_free(st->start);
    hl_tape_free(st->after);
    hl_tape_free(st->energy);
    hl_newton_free(st->nw);
    hl_scheme_stepper_free(st->fallback);
    free(st->in), free(st->out), free(st->U), free(st->bound), free(st->at);
    free(st);
}

int hl_scheme_stepper_iterations(const hl_scheme_stepper *st) { return st->iters; }

long hl_scheme_stepper_fallbacks(const hl_scheme_stepper *st) { return st->fallbacks; }

void hl_scheme_stepper_restart(hl_scheme_stepper *st, long steps)
{
    st->steps = steps;
    st->iters = 0;
    st->fallbacks = 0, st->use_fallback = 0;
}

/* Each step evaluates the step tape once (explicit) or the residual and
 * Jacobian tapes once per Newton iteration; counting one evaluation a step
 * underestimates, so compiling is never chosen where it cannot pay. */
static int jit_if_it_pays(hl_tape *t, long evaluations)
{
    if (t == NULL)
        return 0;
    if (!hl_tape_jit_active(t) && hl_tape_compile_pays(t, HL_COMPILE_EVAL, evaluations))
        hl_tape_jit(t, NULL); /* on failure the interpreter goes on */
    return hl_tape_jit_active(t);
}

int hl_scheme_stepper_jit(hl_scheme_stepper *st, long nsteps)
{
    st->jit_steps = nsteps;
    if (!hl_tape_jit_available())
        return 0;
    if (st->all_explicit)
        return jit_if_it_pays(st->tape, nsteps);
    /* the next point is Newton's output (hl_newton_output): st->after is
     * not evaluated per step.  The fallback (Gauss rules, for the long
     * steps a Taylor rule cannot take) is compiled only if it takes over
     * (fallback_step). */
    if (!hl_newton_jit_active(st->nw) && hl_newton_compile_pays(st->nw, nsteps))
        hl_newton_jit(st->nw, NULL); /* on failure the interpreter goes on */
    if (hl_newton_jit_active(st->nw))
        return 4; /* start, F, FJ and the next point, in one function */
    return jit_if_it_pays(st->tape, nsteps) + jit_if_it_pays(st->jac, nsteps) +
           jit_if_it_pays(st->start, nsteps);
}

/* The equations with each integral replaced by its numeric rule
 * (scheme_integral).  With taylor_ok (an implicit scheme, whose step can be
 * checked and taken again), the Taylor rules' checks and bounds go to
 * chk[0..*nchk-1], bound[]. */
static void quadrature(const hl_expr **lhs, const hl_expr **rhs, const hl_scheme *s,
                       hl_pool *pool, int taylor_ok, const hl_expr **chk, double *bound,
                       int *nchk)
{
    for (int i = 0; i < s->m; i++)
        lhs[i] = s->lhs[i], rhs[i] = s->rhs[i];
    if (nchk != NULL)
        *nchk = 0;
    if (s->nint == 0)
        return;
    const hl_expr **val = hl_xmalloc((size_t)s->nint * sizeof *val);
    for (int t = 0; t < s->nint; t++) {
        const hl_expr *c;
        double b;
        val[t] = scheme_integral(s->int_body[t], taylor_ok, pool, &c, &b);
        if (c != NULL)
            chk[*nchk] = c, bound[(*nchk)++] = b;
    }
    for (int i = 0; i < s->m; i++) {
        lhs[i] = hl_expr_subst(pool, lhs[i], s->nint, (const char *const *)s->int_name, val);
        rhs[i] = hl_expr_subst(pool, rhs[i], s->nint, (const char *const *)s->int_name, val);
    }
    free(val);
}

/* Explicit: inline the equations in order; outs[0..2N-1] = Q, P. */
static void explicit_map(const hl_expr **outs, const hl_scheme *s, const hl_expr **rhs,
                         hl_pool *pool)
{
    const hl_expr **val = hl_xcalloc((size_t)s->m, sizeof *val);
    const char **names = hl_xmalloc((size_t)s->m * sizeof *names);
    const hl_expr **vals = hl_xmalloc((size_t)s->m * sizeof *vals);
    for (int i = 0; i < s->m; i++) {
        int k = 0;
        for (int u = 0; u < s->m; u++)
            if (val[u] != NULL) {
                names[k] = s->unknown[u];
                vals[k++] = val[u];
            }
        val[s->defines[i]] = hl_expr_subst(pool, rhs[i], k, names, vals);
    }
    for (int j = 0; j < s->N; j++) {
        outs[j] = val[s->iQ[j]];
        outs[s->N + j] = val[s->iP[j]];
    }
    free(val), free(names), free(vals);
}

static int compile_explicit(hl_scheme_stepper *st, const hl_scheme *s, const hl_expr **rhs,
                            const char **inputs, hl_pool *pool, hl_error *err)
{
    const hl_expr **outs = hl_xmalloc((size_t)(2 * s->N) * sizeof *outs);
    explicit_map(outs, s, rhs, pool);
    int rc = hl_tape_new(&st->tape, outs, 2 * s->N, inputs, 2 * s->N + 1, err);
    free(outs);
    return rc;
}

static int is_unknown(const hl_scheme *s, const char *name)
{
    for (int u = 0; u < s->m; u++)
        if (strcmp(s->unknown[u], name) == 0)
            return 1;
    return 0;
}

/* Which nodes depend on an unknown, each node decided once from its
 * operands: the equations' divisors are asked one by one, and a walk per
 * divisor and unknown cost gauss3 on a quadratic H seconds (2 degrees of
 * freedom) to minutes (3). */
typedef struct unknown_deps {
    const hl_scheme *s;
    hl_memo dep; /* node -> .i = 1 if it depends on an unknown */
} unknown_deps;

static int operand_depends(const unknown_deps *w, const hl_expr *x)
{
    return x != NULL && hl_memo_get(&w->dep, x)->i;
}

static int mark_depends(void *arg, const hl_expr *e) /* operands first */
{
    unknown_deps *w = arg;
    if (hl_memo_get(&w->dep, e) == NULL) {
        int d = e->kind == HL_SYM ? is_unknown(w->s, e->name)
                                  : operand_depends(w, e->a) || operand_depends(w, e->b);
        hl_memo_put(&w->dep, e)->i = d;
    }
    return 0;
}

static int depends(unknown_deps *w, const hl_expr *e)
{
    hl_memo_val *v = hl_memo_get(&w->dep, e);
    if (v == NULL) {
        hl_expr_postorder(&e, 1, mark_depends, w);
        v = hl_memo_get(&w->dep, e);
    }
    return v->i;
}

static int has_unknown(const hl_expr *e, const hl_scheme *s)
{
    unknown_deps w = {.s = s};
    hl_memo_init(&w.dep);
    int r = depends(&w, e);
    hl_memo_clear(&w.dep);
    return r;
}

/* Does the divisor d depend on an unknown and vanish at D = 0 (every
 * unknown at its value there)?  Then a quotient by it is 0/0 where the
 * unknowns meet the current point ((P^2 - p^2)/(P - p)), and loses digits
 * near it.  A divisor such as Kepler's |q + D a k|^3 in a Runge-Kutta stage
 * does not vanish there: its equation is kept as written, as its canonical
 * form over the stages swells (gauss3 on 3-D Kepler: over a minute).  A
 * divisor that cannot be read exactly counts as vanishing. */
static int vanishes_at_zero(const hl_expr *d, void *arg)
{
    unknown_deps *w = arg;
    const hl_scheme *s = w->s;
    if (!depends(w, d))
        return 0;
    hl_alg_ctx *ctx = hl_system_ctx(s->sys);
    hl_alg a;
    hl_alg_init(&a, ctx);
    const hl_expr *d0 = scheme_at_zero(s, hl_system_pool(s->sys), d);
    int r = depends(w, d0) || hl_alg_from_expr(&a, d0, ctx, NULL) != HL_OK ||
            hl_alg_is_zero(&a, ctx);
    hl_alg_clear(&a, ctx);
    return r;
}

/* Equations that divide by an expression in the unknowns vanishing at
 * D = 0 (vanishes_at_zero), or all of them, are replaced by their exact canonical form (alg.h), which cancels common
 * factors: the paper's (P^2 - p^2)/(2(P - p)) becomes (P + p)/2, regular
 * where P = p.  The others are kept as written (expanding them would only
 * cost). */
static void simplify(const hl_expr **F, int nF, int all, const hl_scheme *s, hl_pool *pool)
{
    hl_alg_ctx *ctx = hl_system_ctx(s->sys);
    int nb = hl_alg_ctx_nbase(ctx);
    hl_alg_ctx *aux = NULL;
    hl_alg a;
    unknown_deps w = {.s = s};
    hl_memo_init(&w.dep);
    for (int i = 0; i < nF; i++) {
        if (!all && !hl_expr_divides_by(F[i], vanishes_at_zero, &w))
            continue;
        if (aux == NULL) {
            const char **names = hl_xmalloc((size_t)(nb + s->m) * sizeof *names);
            for (int k = 0; k < nb; k++)
                names[k] = hl_alg_ctx_name(ctx, k);
            for (int u = 0; u < s->m; u++)
                names[nb + u] = s->unknown[u];
            aux = hl_alg_ctx_new(nb + s->m, names, 64);
            free(names);
            hl_alg_init(&a, aux);
        }
        if (hl_alg_from_expr(&a, F[i], aux, NULL) == HL_OK)
            F[i] = hl_alg_to_expr(&a, aux, pool);
    }
    hl_memo_clear(&w.dep);
    if (aux) {
        hl_alg_clear(&a, aux);
        hl_alg_ctx_free(aux);
    }
}

/* e with the eliminated unknowns replaced by their values. */
static const hl_expr *subst_known(const hl_expr *e, const hl_expr **val, const hl_scheme *s,
                                  hl_pool *pool)
{
    const char **names = hl_xmalloc((size_t)s->m * sizeof *names);
    const hl_expr **vals = hl_xmalloc((size_t)s->m * sizeof *vals);
    int k = 0;
    for (int v = 0; v < s->m; v++)
        if (val[v] != NULL)
            names[k] = s->unknown[v], vals[k++] = val[v];
    const hl_expr *r = k ? hl_expr_subst(pool, e, k, names, vals) : e;
    free(names), free(vals);
    return r;
}

/* Is the coefficient c of an unknown (free of the unknowns) finite and
 * non-zero at D = 0?  Then -F0/c is regular there as written.  Else, as
 * for (Q - q)/D = p (c = 1/D), it is put in canonical form: Q = q + p D,
 * not (q/D + p) D.  Only then: the canonical form of every value swells
 * when a composition's stages are substituted into one another (yoshida4
 * on a magnetic H, each kick implicit and affine). */
static int regular_at_zero(const hl_expr *c, const hl_scheme *s, hl_pool *pool)
{
    hl_alg_ctx *ctx = hl_system_ctx(s->sys);
    hl_alg a;
    hl_alg_init(&a, ctx);
    const hl_expr *c0 = scheme_at_zero(s, pool, c);
    int r = hl_alg_from_expr(&a, c0, ctx, NULL) == HL_OK && !hl_alg_is_zero(&a, ctx);
    hl_alg_clear(&a, ctx);
    return r;
}

/* How many of the unknowns not yet eliminated e contains. */
static int unknowns_in(const hl_expr *e, const hl_expr **val, const hl_scheme *s)
{
    int n = 0;
    for (int u = 0; u < s->m; u++)
        n += val[u] == NULL && hl_expr_has_symbol(e, s->unknown[u]);
    return n;
}

/* The unknown equation i gives explicitly, and its value: U_u = rhs free of
 * U_u, or an equation affine in its one unknown left with a coefficient free
 * of the unknowns ((Q - q)/D = p gives Q = q + p D).  -1 if none.  An
 * equation in several unknowns is left to Newton even where it is affine
 * (a Runge-Kutta method's stages on a linear field): solving such a system
 * by substitution doubles the values' size with each unknown (gauss3 on a
 * quadratic H coupling 3 pairs: 10 s, 4 pairs: minutes) and loses accuracy
 * (gauss2 and gauss3 on x^2/2 + y^4/4 + x y/4 erred by 1e-12 or failed to
 * compile), where Newton solves a linear system in one iteration.  An unknown
 * another equation has given already is not given twice: equation i then
 * stays an equation in the others (else one unknown is counted twice and
 * another is neither kept nor given: a NULL value, or its name left over). */
static int solvable(const hl_expr **value, int i, const hl_expr **val, const hl_scheme *s,
                    const hl_expr **lhs, const hl_expr **rhs, hl_pool *pool)
{
    int u = s->defines[i];
    if (u >= 0 && val[u] == NULL) {
        const hl_expr *r = subst_known(rhs[i], val, s, pool);
        if (!hl_expr_has_symbol(r, s->unknown[u])) {
            *value = r;
            return u;
        }
    }
    const hl_expr *F = subst_known(hl_sub(pool, lhs[i], rhs[i]), val, s, pool);
    if (unknowns_in(F, val, s) != 1)
        return -1; /* coupled to other unknowns: Newton's (see above) */
    for (u = 0; u < s->m; u++) {
        if (val[u] != NULL || !hl_expr_has_symbol(F, s->unknown[u]))
            continue;
        const hl_expr *c = hl_expr_diff(pool, F, s->unknown[u]);
        if (has_unknown(c, s))
            continue;
        const hl_expr *zero = hl_num_si(pool, 0);
        const hl_expr *F0 = hl_expr_subst(pool, F, 1, (const char *const *)&s->unknown[u], &zero);
        *value = hl_neg(pool, hl_div(pool, F0, c));
        if (s->nint == 0 && !regular_at_zero(c, s, pool))
            simplify(value, 1, 1, s, pool);
        return u;
    }
    return -1;
}

/* Unknowns that an equation gives explicitly (solvable) leave the Newton
 * system: val[u] becomes that expression, free of every other eliminated
 * unknown, and gone[i] marks the equation.  These are Q and P of a
 * Runge-Kutta scheme or a discrete gradient: Newton then solves for the
 * stages alone, as one would by hand (gauss2 with one degree of freedom: 4
 * unknowns, not 6); all of them for an explicit scheme written as
 * equations, such as the paper's Euler method.  Returns how many. */
static int eliminate(const hl_expr **val, int *gone, const hl_scheme *s, const hl_expr **lhs,
                     const hl_expr **rhs, hl_pool *pool)
{
    int n = 0, more = 1, *at = hl_xmalloc((size_t)s->m * sizeof *at);
    const hl_expr **vals = hl_xmalloc((size_t)s->m * sizeof *vals);
    while (more) { /* one elimination may make another equation solvable */
        more = 0;
        for (int i = 0; i < s->m; i++) {
            const hl_expr *r;
            int u = gone[i] ? -1 : solvable(&r, i, val, s, lhs, rhs, pool);
            if (u < 0)
                continue;
            int nv = 0; /* the values so far, in one walk: they share much */
            for (int v = 0; v < s->m; v++)
                if (val[v] != NULL)
                    vals[nv] = val[v], at[nv++] = v;
            hl_expr_subst_each(pool, vals, nv, 1, (const char *const *)&s->unknown[u], &r);
            for (int k = 0; k < nv; k++)
                val[at[k]] = vals[k];
            val[u] = r;
            gone[i] = 1;
            n++, more = 1;
        }
    }
    free(at);
    free(vals);
    return n;
}

/* simplify on the eliminated unknowns' values (NULL: kept): the paper's
 * discrete gradient gives X = x + D (P^2 - p^2)/(2(P - p)), 0/0 at P = p
 * until put in canonical form.  Not after quadrature (see compile_newton). */
static void simplify_values(const hl_expr **val, const hl_scheme *s, hl_pool *pool)
{
    if (s->nint > 0)
        return;
    for (int u = 0; u < s->m; u++)
        if (val[u] != NULL)
            simplify(&val[u], 1, 0, s, pool);
}

/* Implicit: F = lhs - rhs over the unknowns kept (eliminate), F with its
 * Jacobian, the start, and the tape that gives the next point from the
 * solution.  inputs: z, D, then room for the kept unknowns' names. */
static int compile_newton(hl_scheme_stepper *st, const hl_scheme *s, const hl_expr **lhs,
                          const hl_expr **rhs, const hl_expr *const *chk, const char **inputs,
                          hl_pool *pool, hl_error *err)
{
    int m = s->m, N = s->N, nz = 2 * N + 1;
    const hl_expr **val = hl_xcalloc((size_t)m, sizeof *val);
    int *gone = hl_xcalloc((size_t)m, sizeof *gone), *keep = hl_xmalloc((size_t)m * sizeof *keep);
    int mk = m - eliminate(val, gone, s, lhs, rhs, pool), k = 0;
    simplify_values(val, s, pool);
    if (mk == 0) { /* every unknown given explicitly: a map after all */
        const hl_expr **Z = hl_xmalloc((size_t)(2 * N) * sizeof *Z);
        for (int j = 0; j < N; j++)
            Z[j] = val[s->iQ[j]], Z[N + j] = val[s->iP[j]];
        int rc = hl_tape_new(&st->tape, Z, 2 * N, inputs, nz, err);
        st->all_explicit = 1;
        st->m = 0;
        free(Z), free(val), free(gone), free(keep);
        return rc;
    }
    for (int u = 0; u < m; u++)
        if (val[u] == NULL)
            inputs[nz + k] = s->unknown[u], keep[k++] = u;
    const char **names = hl_xmalloc((size_t)m * sizeof *names);
    const hl_expr **vals = hl_xmalloc((size_t)m * sizeof *vals);
    int ne = 0;
    for (int u = 0; u < m; u++)
        if (val[u] != NULL)
            names[ne] = s->unknown[u], vals[ne++] = val[u];
    const hl_expr **outs =
        hl_xmalloc((size_t)(mk + mk * mk + 2 * N + st->ncheck) * sizeof *outs);
    k = 0;
    for (int i = 0; i < m; i++)
        if (!gone[i])
            outs[k++] = hl_expr_subst(pool, hl_sub(pool, lhs[i], rhs[i]), ne, names, vals);
    /* Not after quadrature: an integrand is regular where the unknowns meet
     * the current point, and over a common denominator the Gauss sum of a
     * rational H swells into a huge polynomial with huge coefficients. */
    if (s->nint == 0)
        simplify(outs, mk, 0, s, pool);
    for (int i = 0; i < mk; i++)
        for (int u = 0; u < mk; u++)
            outs[mk + i * mk + u] = hl_expr_diff(pool, outs[i], s->unknown[keep[u]]);
    int rc = hl_tape_new(&st->tape, outs, mk, inputs, nz + mk, err);
    if (rc == HL_OK)
        rc = hl_tape_new(&st->jac, outs, mk + mk * mk, inputs, nz + mk, err);
    /* the next point from the solution */
    for (int j = 0; j < 2 * N && rc == HL_OK; j++) {
        int u = j < N ? s->iQ[j] : s->iP[j - N];
        outs[j] = val[u] != NULL ? val[u] : hl_sym(pool, s->unknown[u]);
    }
    for (int i = 0; i < st->ncheck; i++)
        outs[2 * N + i] = hl_expr_subst(pool, chk[i], ne, names, vals);
    if (rc == HL_OK)
        rc = hl_tape_new(&st->after, outs, 2 * N + st->ncheck, inputs, nz + mk, err);
    /* the start: the next point by explicit Euler; any other unknown (a
     * stage, a rate (Q - q)/D) its value at D = 0 taken at Euler's
     * half step, where a rate is to O(D^2) (Gonzalez: 6 Newton iterations
     * a step -> 3-4 on the pendulum, D = 0.01) and a stage no worse */
    const hl_expr *D = hl_sym(pool, hl_system_step(s->sys));
    const char **zn = hl_xmalloc((size_t)(2 * N) * sizeof *zn);
    const hl_expr **half = hl_xmalloc((size_t)(2 * N) * sizeof *half);
    for (int j = 0; j < N; j++) {
        zn[j] = hl_system_coord(s->sys, j), zn[N + j] = hl_system_momentum(s->sys, j);
        if (!hl_system_has_H(s->sys))
            continue;
        const hl_expr *hD = hl_mul(pool, hl_num_frac(pool, 1, 2), D);
        half[j] = hl_add(pool, hl_sym(pool, zn[j]), hl_mul(pool, hD, scheme_dH(s->sys, j, 1)));
        half[N + j] =
            hl_sub(pool, hl_sym(pool, zn[N + j]), hl_mul(pool, hD, scheme_dH(s->sys, j, 0)));
    }
    for (int i = 0; i < mk && rc == HL_OK; i++) {
        int u = keep[i];
        outs[i] = s->z0[u];
        if (hl_system_has_H(s->sys))
            outs[i] = hl_expr_subst(pool, s->z0[u], 2 * N, zn, half);
        for (int j = 0; j < N && hl_system_has_H(s->sys); j++) {
            if (u == s->iQ[j])
                outs[i] = hl_add(pool, s->z0[u], hl_mul(pool, D, scheme_dH(s->sys, j, 1)));
            if (u == s->iP[j])
                outs[i] = hl_sub(pool, s->z0[u], hl_mul(pool, D, scheme_dH(s->sys, j, 0)));
        }
    }
    free(zn), free(half);
    if (rc == HL_OK)
        rc = hl_tape_new(&st->start, outs, mk, inputs, nz, err);
    if (rc == HL_OK)
        rc = hl_newton_new(&st->nw, st->start, st->tape, st->jac, HL_SCHEME_NEWTON_MAX, err);
    if (rc == HL_OK) /* converged when the next point is, to rounding */
        hl_newton_set_output(st->nw, st->after);
    st->m = mk;
    free(outs), free(val), free(gone), free(keep), free(names), free(vals);
    return rc;
}

hl_status hl_scheme_step_exprs(const hl_expr **Z, const hl_scheme *s, hl_error *err)
{
    hl_pool *pool = hl_system_pool(s->sys);
    int m = s->m, N = s->N, st = HL_OK;
    const hl_expr **lhs = hl_xmalloc((size_t)m * sizeof *lhs);
    const hl_expr **rhs = hl_xmalloc((size_t)m * sizeof *rhs);
    quadrature(lhs, rhs, s, pool, 0, NULL, NULL, NULL);
    if (s->all_explicit)
        explicit_map(Z, s, rhs, pool);
    else { /* explicit if every unknown can be eliminated (the paper's Euler) */
        const hl_expr **val = hl_xcalloc((size_t)m, sizeof *val);
        int *gone = hl_xcalloc((size_t)m, sizeof *gone);
        if (eliminate(val, gone, s, lhs, rhs, pool) < m)
            st = hl_error_set(err, HL_EINVAL, NULL, -1, 0, "the scheme '%s' is implicit",
                              s->name);
        else
            simplify_values(val, s, pool);
        for (int j = 0; j < N && st == HL_OK; j++)
            Z[j] = val[s->iQ[j]], Z[N + j] = val[s->iP[j]];
        free(val), free(gone);
    }
    free(lhs), free(rhs);
    return st;
}

/* e's terms as a sum (a - b: a and b, as only their sizes count); with
 * terms NULL, n counts them. */
static void sum_terms(const hl_expr **terms, int *n, const hl_expr *e)
{
    if (e->kind == HL_ADD || e->kind == HL_SUB) {
        sum_terms(terms, n, e->a);
        sum_terms(terms, n, e->b);
    } else if (e->kind == HL_NEG)
        sum_terms(terms, n, e->a);
    else if (terms != NULL)
        terms[(*n)++] = e;
    else
        (*n)++;
}

/* The tape z -> H, and the size of the rounding in a difference of two
 * values of H: the sum of |each term of H| and of |z_j dH/dz_j| (a
 * relative change of z_j by one ulp moves H by about its |z_j dH/dz_j|;
 * the terms' sizes cover their cancellation, as -1/r + p^2/2 near
 * Kepler's collision).  Only for a catalog scheme that claims to preserve
 * H: its step is checked against that claim (energy_check). */
static int energy_tape(hl_scheme_stepper *st, const hl_scheme *s, const char **inputs,
                       hl_error *err)
{
    const hl_scheme_info *info = hl_scheme_lookup(s->name);
    const hl_expr *H = hl_system_H_expr(s->sys);
    if (info == NULL || !(info->flags & HL_SCHEME_PRESERVES_H) || !hl_system_has_H(s->sys) ||
        H == NULL)
        return HL_OK;
    hl_pool *pool = hl_system_pool(s->sys);
    st->claims = info->name, st->integrals = s->nint > 0;
    int n = 0;
    sum_terms(NULL, &n, H);
    const hl_expr **terms = hl_xmalloc((size_t)(n + 2 * s->N) * sizeof *terms);
    n = 0;
    sum_terms(terms, &n, H);
    for (int j = 0; j < 2 * s->N; j++) {
        const hl_expr *v = hl_sym(pool, inputs[j]);
        terms[n++] = hl_mul(pool, v, scheme_dH(s->sys, j % s->N, j >= s->N));
    }
    const hl_expr *scale = NULL;
    for (int i = 0; i < n; i++) {
        const hl_expr *a = hl_call(pool, HL_SQRT, hl_mul(pool, terms[i], terms[i]));
        scale = scale ? hl_add(pool, scale, a) : a;
    }
    const hl_expr *outs[2] = {H, scale};
    int rc = hl_tape_new(&st->energy, outs, 2, inputs, 2 * s->N, err);
    st->at = hl_xcalloc((size_t)(2 * s->N), sizeof *st->at);
    st->at[0] = NAN; /* no point yet */
    free(terms);
    return rc;
}

/* The stepper with Taylor rules for the integrals where taylor_ok and they
 * are cheaper (their checks in st->after), else Gauss rules. */
static int stepper_build(hl_scheme_stepper **out, const hl_scheme *s, int taylor_ok,
                         hl_error *err)
{
    *out = NULL;
    hl_pool *pool = hl_system_pool(s->sys);
    int N = s->N, m = s->m;
    hl_scheme_stepper *st = hl_xcalloc(1, sizeof *st);
    st->N = N, st->m = m, st->all_explicit = s->all_explicit;
    st->nin = 2 * N + 1 + m;
    const char **inputs = hl_xmalloc((size_t)st->nin * sizeof *inputs);
    for (int j = 0; j < N; j++) {
        inputs[j] = hl_system_coord(s->sys, j);
        inputs[N + j] = hl_system_momentum(s->sys, j);
    }
    inputs[2 * N] = hl_system_step(s->sys);
    for (int u = 0; u < m; u++)
        inputs[2 * N + 1 + u] = s->unknown[u];
    const hl_expr **lhs = hl_xmalloc((size_t)m * sizeof *lhs);
    const hl_expr **rhs = hl_xmalloc((size_t)m * sizeof *rhs);
    const hl_expr **chk = hl_xmalloc(((size_t)s->nint + 1) * sizeof *chk);
    st->bound = hl_xmalloc(((size_t)s->nint + 1) * sizeof *st->bound);
    quadrature(lhs, rhs, s, pool, taylor_ok && !s->all_explicit, chk, st->bound, &st->ncheck);
    int rc = s->all_explicit ? compile_explicit(st, s, rhs, inputs, pool, err)
                             : compile_newton(st, s, lhs, rhs, chk, inputs, pool, err);
    if (rc == HL_OK)
        rc = energy_tape(st, s, inputs, err);
    free(inputs), free(lhs), free(rhs), free(chk);
    if (rc != HL_OK) {
        hl_error_prefix(err, "compiling the scheme '%s'", s->name);
        hl_scheme_stepper_free(st);
        return rc;
    }
    m = st->m; /* the unknowns Newton solves for */
    st->nin = 2 * N + 1 + m;
    st->in = hl_xmalloc((size_t)st->nin * sizeof *st->in);
    st->out = hl_xmalloc((size_t)(m + m * m + 2 * N) * sizeof *st->out); /* F and J */
    st->U = hl_xmalloc((size_t)m * sizeof *st->U);
    *out = st;
    return HL_OK;
}

hl_status hl_scheme_stepper_new(hl_scheme_stepper **out, const hl_scheme *s, hl_error *err)
{
    int rc = stepper_build(out, s, 1, err);
    hl_scheme_stepper *st = *out;
    if (rc != HL_OK || st->ncheck == 0)
        return rc;
    if (st->all_explicit) { /* a map after elimination: nothing to check it */
        hl_scheme_stepper_free(st);
        return stepper_build(out, s, 0, err);
    }
    rc = stepper_build(&st->fallback, s, 0, err);
    if (rc != HL_OK) {
        hl_scheme_stepper_free(st);
        *out = NULL;
    }
    return rc;
}

static int all_finite(const double *x, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(x[i]))
            return 0;
    return 1;
}

/* Newton (tape.h: hl_newton) from (z, D) in st->in; the messages name the
 * step and the time. */
static int newton(hl_scheme_stepper *st, double D, double t, hl_error *err)
{
    double last;
    hl_newton_status ns = hl_newton_solve(st->U, &st->iters, &last, st->in, st->nw);
    long k = st->steps + 1;
    switch (ns) {
    case HL_NEWTON_OK:
        return HL_OK;
    case HL_NEWTON_START:
        return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                            "step %ld (t = %.17g, D = %g): the starting point is not finite", k,
                            t, D);
    case HL_NEWTON_SINGULAR:
        return hl_error_set(err, HL_ENOCONV, NULL, -1, 0,
                            "step %ld (t = %.17g, D = %g): the Jacobian of the scheme's "
                            "equations is singular (Newton iteration %d)",
                            k, t, D, st->iters);
    case HL_NEWTON_NOCONV:
        return hl_error_set(err, HL_ENOCONV, NULL, -1, 0,
                            "step %ld (t = %.17g, D = %g): Newton did not converge in %d "
                            "iterations (last correction %.3g)",
                            k, t, D, HL_SCHEME_NEWTON_MAX, last);
    default:
        return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                            "step %ld (t = %.17g, D = %g): Newton met a value that is not "
                            "finite (iteration %d)",
                            k, t, D, st->iters);
    }
}

/* The Taylor rules' checks at the step's values (NaN fails them). */
static int within_bounds(const double *c, const hl_scheme_stepper *st)
{
    for (int i = 0; i < st->ncheck; i++)
        if (!(c[i] <= st->bound[i]))
            return 0;
    return 1;
}

/* The step by the Gauss rules, counted as this stepper's.  When they take
 * most steps (long ones, all beyond a Taylor rule's reach), they take all
 * the next ones, compiled if this stepper was (decided by counts, so a run
 * is reproducible). */
static int fallback_step(hl_scheme_stepper *st, double *z, double D, double t, hl_error *err)
{
    st->fallback->steps = st->steps;
    int rc = hl_scheme_step(st->fallback, z, D, t, err);
    st->iters = st->fallback->iters;
    if (rc != HL_OK)
        return rc;
    st->steps++, st->fallbacks++;
    if (!st->use_fallback && st->fallbacks >= 64 && 2 * st->fallbacks >= st->steps) {
        st->use_fallback = 1;
        if (st->jit_steps > st->steps)
            hl_scheme_stepper_jit(st->fallback, st->jit_steps - st->steps);
    }
    return HL_OK;
}

/* Rounding error allowed in H(Z) - H(z), in units of the scale of
 * energy_tape: a step that solves a discrete gradient's equations to
 * rounding changes H by a few such units. */
#define ENERGY_ULPS 256

/* A scheme that claims to preserve H and whose step Z changes it by more
 * than rounding has not solved its equations (the Gauss rule of an
 * integral whose segment passes near a singularity of H, as AVF's near
 * Kepler's collision): refused, naming the step, rather than a result. */
static int energy_check(hl_scheme_stepper *st, const double *z, const double *Z, double D,
                        double t, hl_error *err)
{
    if (st->energy == NULL)
        return HL_OK;
    size_t n = (size_t)(2 * st->N) * sizeof *z;
    double a[2], b[2];
    if (memcmp(z, st->at, n) == 0)
        memcpy(a, st->at_energy, sizeof a);
    else
        hl_tape_eval_d(a, z, st->energy);
    hl_tape_eval_d(b, Z, st->energy);
    memcpy(st->at, Z, n), memcpy(st->at_energy, b, sizeof b);
    double dH = fabs(b[0] - a[0]), tol = ENERGY_ULPS * DBL_EPSILON * fmax(a[1], b[1]);
    if (dH <= tol)
        return HL_OK;
    return hl_error_set(err, HL_ENOCONV, NULL, -1, 0,
                        "step %ld (t = %.17g, D = %g): the scheme '%s' preserves H, but this step "
                        "changes it from %.17g to %.17g (by %.3g, rounding allows %.3g): its "
                        "equations are not solved to rounding here%s",
                        st->steps + 1, t, D, st->claims, a[0], b[0], dH, tol,
                        st->ncheck > 0 || st->integrals
                            ? " (an integral by a rule not accurate near a singularity of H?)"
                            : "");
}

hl_status hl_scheme_step(hl_scheme_stepper *st, double *z, double D, double t, hl_error *err)
{
    int N = st->N;
    memcpy(st->in, z, (size_t)(2 * N) * sizeof *z);
    st->in[2 * N] = D;
    st->iters = 0;
    if (st->all_explicit) {
        hl_tape_eval_d(st->out, st->in, st->tape);
        if (!all_finite(st->out, 2 * N))
            return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                                "step %ld (t = %.17g, D = %g): the next point is not finite",
                                st->steps + 1, t, D);
        if (energy_check(st, z, st->out, D, t, err) != HL_OK)
            return HL_ENOCONV;
        memcpy(z, st->out, (size_t)(2 * N) * sizeof *z);
    } else {
        if (st->use_fallback)
            return fallback_step(st, z, D, t, err);
        int rc = newton(st, D, t, err);
        if (rc != HL_OK && st->fallback != NULL) /* a Taylor rule far out of reach? */
            return fallback_step(st, z, D, t, err);
        if (rc != HL_OK)
            return rc;
        /* the next point: Newton's convergence test has just computed it */
        const double *Z = hl_newton_output(st->nw);
        if (Z != NULL && !within_bounds(Z + 2 * N, st))
            return fallback_step(st, z, D, t, err);
        if (Z == NULL) {
            memcpy(st->in + 2 * N + 1, st->U, (size_t)st->m * sizeof *st->U);
            hl_tape_eval_d(st->out, st->in, st->after);
            Z = st->out;
        }
        if (!all_finite(Z, 2 * N))
            return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                                "step %ld (t = %.17g, D = %g): the next point is not finite",
                                st->steps + 1, t, D);
        if (energy_check(st, z, Z, D, t, err) != HL_OK)
            return st->fallback ? fallback_step(st, z, D, t, err) : HL_ENOCONV;
        memcpy(z, Z, (size_t)(2 * N) * sizeof *z);
    }
    st->steps++;
    return HL_OK;
}
