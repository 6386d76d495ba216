/* hamlie — numeric error analysis at a point (numerr.h).
 *
 * Method.
 *
 * 1. The scheme at z.  Every value is a truncated power series in D,
 *    x(D) = sum_{k<L} x_k D^k, L = n + 1 + SLACK, with coefficients in the
 *    dual numbers a + b eps (eps^2 = 0; step 3).  The scheme's equations
 *    (expression DAGs over q, p, D, the unknowns and integrals I#k) are
 *    evaluated node by node by the operations' rules (dual.c), each shared
 *    node once.  A quotient by
 *    a series whose first v coefficients are zero (Q - q, D) is taken after
 *    dividing both by D^v (the numerator must vanish there too, as in
 *    (Q - q)/D or (P^2 - p^2)/(P - p)).
 *    Explicit schemes: the equations evaluated in order.  Others: the
 *    unknowns U(D) start at their values at D = 0 and are found order by
 *    order.  With U_{<k} known, U = U_{<k} + D^k X gives
 *    F(U) = F(U_{<k}) + D^k J(D) X + O(D^(2k+s)): the first coefficient of
 *    row i that X reaches is k + s_i, and there it is linear in X.  The
 *    linear map is found by probing (F at X = c e_j minus F at X = 0, over
 *    c, exact for the linear part since the quadratic part starts k orders
 *    later; c a power of 2 of the coefficients' size, else the probe is lost
 *    in rounding when the coefficients grow like R^-k),
 *    s_i is read off the probes, and A X = -[D^(k+s_i)] F_i(U_{<k}) is solved
 *    by Gaussian elimination.  One order per sweep; m + 1 evaluations each.
 *    Integrals int(s, f) use Gauss-Legendre with L/2 + 1 nodes, exact for
 *    the coefficients up to D^(L-1), which are polynomials of degree <= L-1
 *    in s for the schemes of the language (scheme.h).
 *
 * 2. The exact flow: Taylor mode on the Hamiltonian vector field's tape
 *    (hl_tape_taylor_ode_d) gives g^k z / k!, and v_k = k! (psi_k - flow_k).
 *
 * 3. K(D) = (d/dD psi_D)(w(D)), w(D) = psi_{-D}(z): w's coefficients are
 *    psi_k (-1)^k.  Evaluating the scheme at the series point w(D) gives the
 *    total derivative d/dD [psi_D(w(D))] = K(D) + (d psi_D/dz)(w(D)) w'(D).
 *    The second term is a directional derivative: the point is taken as
 *    w(D) + eps w'(D) in dual numbers, whose eps part is exactly that term
 *    (the derivative along w' at fixed D, as a series in D).  So one solve
 *    gives T(D) = psi_D(w(D)) + eps (d psi_D/dz)(w(D)) w'(D) and
 *    K_k = (k + 1) Re T_{k+1} - Eps T_k.  (Putting eps on D instead would
 *    divide by D + eps, whose leading coefficient eps is not invertible.)
 *
 * 4. Leading k and order: v_k is non-zero when its max norm exceeds
 *    HL_NUMERR_REL_TOL * k! * max_i(|psi_k,i| + |flow_k,i|) (numerr.h); for
 *    a series given from elsewhere (hl_numerr_from_series) the size of
 *    order k is at least the upper concave hull of the log sizes at k
 *    (hull_thresholds).
 */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/numeric_impl.h"
#include "base/buf.h"
#include "base/memo.h"
#include "hamlie/numerr.h"
#include "hamlie/tape.h"
#include "rules/rule.h"

#define SLACK 3
#define NUM_MAX_NEST 4 /* integrals inside integrals: not in the language */

/* ---- the evaluator ------------------------------------------------------ */

typedef struct ev {
    const hl_scheme *s;
    int L;
    int nsym;               /* point 2N, D, unknowns m, s# */
    const char **names;
    dn *symval;             /* nsym * L */
    hl_memo memo;           /* expression -> index into the arena */
    size_t used;
    dn *arena;              /* used * L */
    size_t arena_cap;
    int depth;
    hl_error *err;
    int failed;
} ev;

static void ev_init(ev *E, const hl_scheme *s, int L, hl_error *err)
{
    memset(E, 0, sizeof *E);
    E->s = s;
    E->L = L;
    E->err = err;
    int N = s->N, m = s->m;
    E->nsym = 2 * N + 1 + m + 1;
    E->names = hl_xmalloc((size_t)E->nsym * sizeof *E->names);
    for (int j = 0; j < N; j++) {
        E->names[j] = hl_system_coord(s->sys, j);
        E->names[N + j] = hl_system_momentum(s->sys, j);
    }
    E->names[2 * N] = hl_system_step(s->sys);
    for (int i = 0; i < m; i++)
        E->names[2 * N + 1 + i] = s->unknown[i];
    E->names[2 * N + 1 + m] = HL_SCHEME_S;
    E->symval = calloc((size_t)E->nsym * L, sizeof(dn));
    hl_memo_init(&E->memo);
    E->arena_cap = 256;
    E->arena = malloc(E->arena_cap * L * sizeof(dn));
    if (E->symval == NULL || E->arena == NULL)
        abort();
    E->symval[(size_t)2 * N * L + 1] = (dn){1, 0}; /* D */
}

static void ev_clear(ev *E)
{
    free(E->names);
    free(E->symval);
    hl_memo_clear(&E->memo);
    free(E->arena);
}

static void ev_reset(ev *E)
{
    hl_memo_clear(&E->memo);
    hl_memo_init(&E->memo);
    E->used = 0;
}

static dn *sym(ev *E, int i) { return E->symval + (size_t)i * E->L; }

static dn *memo_find(ev *E, const hl_expr *e)
{
    hl_memo_val *v = hl_memo_get(&E->memo, e);
    return v ? E->arena + (size_t)v->l * E->L : NULL;
}

/* A new memo entry for e; returns its index in the arena. */
static size_t memo_add(ev *E, const hl_expr *e)
{
    if (E->used + 1 > E->arena_cap) {
        E->arena_cap *= 2;
        E->arena = realloc(E->arena, E->arena_cap * E->L * sizeof(dn));
        if (E->arena == NULL)
            abort();
    }
    hl_memo_put(&E->memo, e)->l = (long)E->used;
    return E->used++;
}

static int fail(ev *E, int status, const char *msg, const char *arg)
{
    if (!E->failed)
        hl_error_set(E->err, status, NULL, -1, 0, "%s%s%s%s", msg, arg ? " '" : "",
                     arg ? arg : "", arg ? "'" : "");
    E->failed = 1;
    return status;
}

/* ---- series operations (x, a, b: L coefficients) ------------------------- */

static void s_mul(dn *x, const dn *a, const dn *b, int L)
{
    dual_series_op(a == b ? HL_OP_SQR : HL_OP_MUL, L, x, NULL, a, b, 0);
}

/* x = a / b; x must not alias a or b. */
static int s_div(ev *E, dn *x, const dn *a, const dn *b)
{
    int L = E->L, v = 0; /* b's valuation */
    while (v < L && dzero(b[v]))
        v++;
    if (v == L)
        return fail(E, HL_EDOM, "division by a series that is zero", NULL);
    if (b[v].r == 0)
        return fail(E, HL_EDOM, "division by a series with a nilpotent leading term", NULL);
    for (int j = 0; j < v; j++)
        if (fabs(a[j].r) > 1e-13 * (fabs(a[v].r) + 1) || fabs(a[j].e) > 1e-13 * (fabs(a[v].e) + 1))
            return fail(E, HL_EDOM, "division by a series vanishing at D = 0", NULL);
    /* (a/D^v) / (b/D^v); beyond L - v unknown, read by higher orders only */
    memset(x, 0, (size_t)L * sizeof *x);
    dual_series_op(HL_OP_DIV, L - v, x, NULL, a + v, b + v, 0);
    return HL_OK;
}

/* x = a^c for real c, a_0 != 0 */
static int s_powr(ev *E, dn *x, const dn *a, double c)
{
    if (a[0].r == 0)
        return fail(E, HL_EDOM, "non-integer power of a series vanishing at D = 0", NULL);
    if (a[0].r < 0 && c != floor(c))
        return fail(E, HL_EDOM, "non-integer power of a negative value", NULL);
    dual_series_op(HL_OP_POWK, E->L, x, NULL, a, NULL, c);
    return HL_OK;
}

/* x = a^n, integer n >= 0, by binary powering (exact when a_0 = 0). */
static void s_powi(dn *x, const dn *a, long n, int L, dn *t1, dn *t2)
{
    for (int k = 0; k < L; k++)
        x[k] = (dn){k == 0, 0}, t1[k] = a[k];
    while (n > 0) {
        if (n & 1) {
            s_mul(t2, x, t1, L);
            memcpy(x, t2, (size_t)L * sizeof *x);
        }
        n >>= 1;
        if (n > 0) {
            s_mul(t2, t1, t1, L);
            memcpy(t1, t2, (size_t)L * sizeof *x);
        }
    }
}

static int eval(ev *E, const hl_expr *e, dn **out);

/* int_0^1 body(s) ds by Gauss-Legendre, in a fresh evaluator sharing the
 * symbols' values (the memo must not mix nodes). */
static int integral(ev *E, dn *x, int k)
{
    int L = E->L, G = L / 2 + 1;
    if (E->depth >= NUM_MAX_NEST)
        return fail(E, HL_ELIMIT, "integrals nested too deep", NULL);
    ev F;
    ev_init(&F, E->s, L, E->err);
    memcpy(F.symval, E->symval, (size_t)E->nsym * L * sizeof(dn));
    F.depth = E->depth + 1;
    memset(x, 0, (size_t)L * sizeof *x);
    int st = HL_OK;
    for (int i = 1; i <= G && st == HL_OK; i++) {
        /* Legendre node i on [-1, 1] by Newton from the Chebyshev guess */
        double t = cos(M_PI * (i - 0.25) / (G + 0.5)), dp = 1;
        for (int it = 0; it < 100; it++) {
            double p0 = 1, p1 = t;
            for (int j = 2; j <= G; j++) {
                double p2 = ((2 * j - 1) * t * p1 - (j - 1) * p0) / j;
                p0 = p1, p1 = p2;
            }
            dp = G * (t * p1 - p0) / (t * t - 1);
            double dt = p1 / dp;
            t -= dt;
            if (fabs(dt) < 1e-16)
                break;
        }
        double w = 1.0 / ((1 - t * t) * dp * dp); /* weight on [0,1]: 2/((1-t^2)p'^2)/2 */
        dn *sv = sym(&F, F.nsym - 1);
        memset(sv, 0, (size_t)L * sizeof *sv);
        sv[0].r = (1 + t) / 2;
        ev_reset(&F);
        dn *f;
        if ((st = eval(&F, E->s->int_body[k], &f)) != HL_OK)
            break;
        for (int j = 0; j < L; j++)
            x[j] = dadd(x[j], dscal(f[j], w));
    }
    if (F.failed)
        E->failed = 1;
    ev_clear(&F);
    return st;
}

static int eval_sym(ev *E, dn *x, const char *name)
{
    for (int i = 0; i < E->nsym; i++)
        if (strcmp(E->names[i], name) == 0) {
            memcpy(x, sym(E, i), (size_t)E->L * sizeof *x);
            return HL_OK;
        }
    for (int k = 0; k < E->s->nint; k++)
        if (strcmp(E->s->int_name[k], name) == 0)
            return integral(E, x, k);
    return fail(E, HL_EINVAL, "the symbol has no value (give parameters with --param):", name);
}

/* Is e a rational constant?  Its value in *c. */
static int is_num(const hl_expr *e, double *c, long *ci, int *integer)
{
    if (e->kind == HL_NEG && e->a->kind == HL_NUM) {
        if (!is_num(e->a, c, ci, integer))
            return 0;
        *c = -*c, *ci = -*ci;
        return 1;
    }
    if (e->kind != HL_NUM)
        return 0;
    *c = fmpq_get_d(e->num);
    *integer = fmpz_is_one(fmpq_denref(e->num)) && fmpz_fits_si(fmpq_numref(e->num));
    *ci = *integer ? fmpz_get_si(fmpq_numref(e->num)) : 0;
    return 1;
}

/* The domain of f at a_0, where its rule would divide by zero or leave
 * the reals. */
static int check_domain(ev *E, hl_fun f, dn a0, dn b0)
{
    double w0 = f == HL_SQRT ? a0.r : 1 - a0.r * a0.r; /* sqrt(a), or sqrt(1 - a^2) */
    switch (f) {
    case HL_LOG:
        return a0.r <= 0 ? fail(E, HL_EDOM, "log of a non-positive value", NULL) : HL_OK;
    case HL_TAN:
    case HL_ATAN2: /* by cos a, by a^2 + b^2 */
        if (f == HL_TAN ? cos(a0.r) == 0 : a0.r == 0 && b0.r == 0)
            return fail(E, HL_EDOM, "division by a series vanishing at D = 0", NULL);
        return HL_OK;
    case HL_SQRT:
    case HL_ASIN:
    case HL_ACOS:
        if (w0 == 0)
            return fail(E, HL_EDOM, "non-integer power of a series vanishing at D = 0", NULL);
        return w0 < 0 ? fail(E, HL_EDOM, "non-integer power of a negative value", NULL) : HL_OK;
    default:
        return HL_OK;
    }
}


/* x = f(a, b) (b: atan2's x, else NULL) */
static int eval_fun(ev *E, dn *x, hl_fun f, const dn *a, const dn *b)
{
    int L = E->L, st, second;
    if ((unsigned)f >= HL_FUN_COUNT || (f != HL_ATAN2) != (b == NULL))
        return fail(E, HL_EUNSUP, "function not supported in series", hl_fun_name(f));
    if ((st = check_domain(E, f, a[0], b ? b[0] : a[0])) != HL_OK)
        return st;
    dn *t = hl_xmalloc((size_t)L * sizeof *t);
    hl_op op = hl_fun_op(f, &second);
    if (second)
        dual_series_op(op, L, t, x, a, b, 0);
    else
        dual_series_op(op, L, x, t, a, b, 0);
    free(t);
    return HL_OK;
}

/* *out points into the arena (valid until the next memo_add: copy first). */
static int eval(ev *E, const hl_expr *e, dn **out)
{
    dn *hit = memo_find(E, e);
    if (hit != NULL) {
        *out = hit;
        return HL_OK;
    }
    int L = E->L, st = HL_OK;
    dn *x = hl_xmalloc((size_t)L * sizeof *x), *a = NULL, *b = NULL, *p;
    memset(x, 0, (size_t)L * sizeof *x);
    double c;
    long ci;
    int integer;
    switch (e->kind) {
    case HL_NUM: x[0].r = fmpq_get_d(e->num); break;
    case HL_PI: x[0].r = M_PI; break;
    case HL_SYM: st = eval_sym(E, x, e->name); break;
    case HL_NEG:
    case HL_FUN:
        if ((st = eval(E, e->a, &p)) != HL_OK)
            break;
        a = hl_xmalloc((size_t)2 * L * sizeof *a);
        memcpy(a, p, (size_t)L * sizeof *a);
        b = e->b ? a + L : NULL; /* atan2(y, x) */
        if (b && (st = eval(E, e->b, &p)) == HL_OK)
            memcpy(b, p, (size_t)L * sizeof *b);
        if (st == HL_OK && e->kind == HL_NEG)
            dual_series_op(HL_OP_NEG, L, x, NULL, a, NULL, 0);
        else if (st == HL_OK)
            st = eval_fun(E, x, e->fun, a, b);
        break;
    default: /* binary */
        if ((st = eval(E, e->a, &p)) != HL_OK)
            break;
        a = hl_xmalloc((size_t)2 * L * sizeof *a);
        memcpy(a, p, (size_t)L * sizeof *a);
        b = a + L;
        if (e->kind == HL_POW && is_num(e->b, &c, &ci, &integer)) {
            if (integer && labs(ci) <= 64) {
                dn *t = hl_xmalloc((size_t)4 * L * sizeof *t), *pw = t + 2 * L, *one = t + 3 * L;
                s_powi(ci >= 0 ? x : pw, a, labs(ci), L, t, t + L);
                if (ci < 0) { /* x = 1 / a^|ci| */
                    for (int k = 0; k < L; k++)
                        one[k] = (dn){k == 0, 0};
                    st = s_div(E, x, one, pw);
                }
                free(t);
            } else
                st = s_powr(E, x, a, c);
            break;
        }
        if ((st = eval(E, e->b, &p)) != HL_OK)
            break;
        memcpy(b, p, (size_t)L * sizeof *b);
        switch (e->kind) {
        case HL_ADD:
            dual_series_op(HL_OP_ADD, L, x, NULL, a, b, 0);
            break;
        case HL_SUB:
            dual_series_op(HL_OP_SUB, L, x, NULL, a, b, 0);
            break;
        case HL_MUL: s_mul(x, a, b, L); break;
        case HL_DIV: st = s_div(E, x, a, b); break;
        default: { /* a^b = exp(b log a) */
            dn *t = hl_xmalloc((size_t)2 * L * sizeof *t);
            if ((st = eval_fun(E, t, HL_LOG, a, NULL)) == HL_OK) {
                s_mul(t + L, t, b, L);
                dual_series_op(HL_OP_EXP, L, x, NULL, t + L, NULL, 0);
            }
            free(t);
        }
        }
    }
    if (st == HL_OK)
        for (int k = 0; k < L && st == HL_OK; k++)
            if (!isfinite(x[k].r) || !isfinite(x[k].e))
                st = fail(E, HL_EDOM, "a value is not finite (a pole or overflow at this point)", NULL);
    free(a);
    if (st == HL_OK) {
        size_t i = memo_add(E, e);
        *out = E->arena + i * L;
        memcpy(*out, x, (size_t)L * sizeof *x);
    }
    free(x);
    return st;
}

/* ---- solving the scheme --------------------------------------------------- */

static dn *unk(ev *E, int i) { return sym(E, 2 * E->s->N + 1 + i); }

/* F[i*L + k] = lhs_i - rhs_i. */
static int residual(ev *E, dn *F)
{
    const hl_scheme *s = E->s;
    int L = E->L;
    ev_reset(E);
    for (int i = 0; i < s->m; i++) {
        dn *p;
        int st;
        if ((st = eval(E, s->lhs[i], &p)) != HL_OK)
            return st;
        memcpy(F + (size_t)i * L, p, (size_t)L * sizeof *p);
        if ((st = eval(E, s->rhs[i], &p)) != HL_OK)
            return st;
        for (int k = 0; k < L; k++)
            F[(size_t)i * L + k] = dsub(F[(size_t)i * L + k], p[k]);
    }
    return HL_OK;
}

/* Solve A x = b (n x n, duals) by Gaussian elimination, pivoting on |re|. */
static int dsolve(dn *A, dn *x, int n)
{
    for (int c = 0; c < n; c++) {
        int piv = c;
        for (int r = c + 1; r < n; r++)
            if (fabs(A[r * n + c].r) > fabs(A[piv * n + c].r))
                piv = r;
        if (A[piv * n + c].r == 0)
            return -1;
        for (int j = 0; j < n; j++) {
            dn t = A[c * n + j];
            A[c * n + j] = A[piv * n + j], A[piv * n + j] = t;
        }
        dn t = x[c];
        x[c] = x[piv], x[piv] = t;
        for (int r = c + 1; r < n; r++) {
            dn f = ddiv(A[r * n + c], A[c * n + c]);
            for (int j = c; j < n; j++)
                A[r * n + j] = dsub(A[r * n + j], dmul(f, A[c * n + j]));
            x[r] = dsub(x[r], dmul(f, x[c]));
        }
    }
    for (int c = n - 1; c >= 0; c--) {
        for (int j = c + 1; j < n; j++)
            x[c] = dsub(x[c], dmul(A[c * n + j], x[j]));
        x[c] = ddiv(x[c], A[c * n + c]);
    }
    return 0;
}

/* Unknowns at D = 0: z0 at the point's value at D = 0 (coefficient 0). */
static int start(ev *E)
{
    const hl_scheme *s = E->s;
    int L = E->L;
    for (int i = 0; i < s->m; i++)
        memset(unk(E, i), 0, (size_t)L * sizeof(dn));
    ev_reset(E);
    for (int i = 0; i < s->m; i++) {
        dn *p;
        int st = eval(E, s->z0[i], &p);
        if (st != HL_OK)
            return st;
        unk(E, i)[0] = p[0];
    }
    return HL_OK;
}

static int solve_explicit(ev *E)
{
    const hl_scheme *s = E->s;
    ev_reset(E);
    for (int i = 0; i < s->m; i++) {
        dn *p;
        int st = eval(E, s->rhs[i], &p);
        if (st != HL_OK)
            return st;
        memcpy(unk(E, s->defines[i]), p, (size_t)E->L * sizeof *p);
    }
    return HL_OK;
}

/* Orders 1..kmax of the unknowns, by probing the linear map at each order. */
static int solve_implicit(ev *E, int kmax)
{
    const hl_scheme *s = E->s;
    int m = s->m, L = E->L, st;
    dn *F0 = hl_xmalloc((size_t)m * L * sizeof *F0), *F1 = hl_xmalloc((size_t)m * L * sizeof *F1);
    dn *A = hl_xmalloc((size_t)m * m * sizeof *A), *x = hl_xmalloc((size_t)m * sizeof *x);
    dn *dif = hl_xmalloc((size_t)m * m * L * sizeof *dif);
    int *row = hl_xmalloc((size_t)m * sizeof *row);
    if ((st = start(E)) != HL_OK)
        goto done;
    for (int k = 1; k <= kmax; k++) {
        if ((st = residual(E, F0)) != HL_OK)
            goto done;
        /* the probe's size: near the coefficients' own, so that it is not
         * lost in rounding against them (they grow like R^-k for a radius
         * of convergence R); a power of 2, so that dividing by it is exact */
        double big = 1;
        for (int i = 0; i < m; i++) {
            big = fmax(big, fabs(unk(E, i)[k - 1].r));
            for (int t = k - 1; t <= k + 1 && t < L; t++)
                big = fmax(big, fabs(F0[(size_t)i * L + t].r));
        }
        double c = ldexp(1, ilogb(big) + 1);
        for (int j = 0; j < m; j++) {
            unk(E, j)[k].r = c;
            st = residual(E, F1);
            unk(E, j)[k].r = 0;
            if (st != HL_OK)
                goto done;
            for (int i = 0; i < m; i++)
                for (int t = 0; t < L; t++)
                    dif[((size_t)i * m + j) * L + t] =
                        dscal(dsub(F1[(size_t)i * L + t], F0[(size_t)i * L + t]), 1 / c);
        }
        for (int i = 0; i < m; i++) { /* row i's first coefficient reached */
            row[i] = L;
            for (int j = 0; j < m; j++)
                for (int t = 0; t < row[i]; t++)
                    if (dif[((size_t)i * m + j) * L + t].r != 0) {
                        row[i] = t;
                        break;
                    }
            if (row[i] == L) {
                st = hl_error_set(E->err, HL_ENOCONV, NULL, -1, 0,
                                  "equation %d does not determine the unknowns at order D^%d "
                                  "at this point", i + 1, k);
                goto done;
            }
            for (int j = 0; j < m; j++)
                A[i * m + j] = dif[((size_t)i * m + j) * L + row[i]];
            x[i] = dscal(F0[(size_t)i * L + row[i]], -1);
        }
        if (dsolve(A, x, m) != 0) {
            st = hl_error_set(E->err, HL_ENOCONV, NULL, -1, 0,
                              "the linear system for the D^%d coefficients is singular at "
                              "this point", k);
            goto done;
        }
        for (int j = 0; j < m; j++)
            unk(E, j)[k] = x[j];
    }
done:
    free(F0), free(F1), free(A), free(x), free(dif), free(row);
    return st;
}

/* The scheme at the point whose coordinates are the series pt[i*L ..]; the
 * images (Q, P) into out[i*L + k]. */
static int run_scheme(dn *out, const hl_scheme *s, const dn *pt, int L, hl_error *err)
{
    ev E;
    ev_init(&E, s, L, err);
    int N = s->N, st;
    for (int i = 0; i < 2 * N; i++)
        memcpy(sym(&E, i), pt + (size_t)i * L, (size_t)L * sizeof *pt);
    if (s->all_explicit)
        st = solve_explicit(&E);
    else
        st = solve_implicit(&E, L - 1 - SLACK + 1); /* orders 1..n + 1 */
    if (st == HL_OK)
        for (int j = 0; j < N; j++) {
            memcpy(out + (size_t)j * L, unk(&E, s->iQ[j]), (size_t)L * sizeof *out);
            memcpy(out + (size_t)(N + j) * L, unk(&E, s->iP[j]), (size_t)L * sizeof *out);
        }
    ev_clear(&E);
    return st;
}

static int flow_coeffs(double *flow, hl_system *sys, const double *z, int n, hl_error *err)
{
    int N = hl_system_ndof(sys), ns = hl_system_nset(sys);
    const char **q = hl_xmalloc((size_t)(2 * N + ns + 1) * sizeof *q), **p = q + N,
               **pn = q + 2 * N;
    const hl_expr **pv = hl_xmalloc((size_t)(ns + 1) * sizeof *pv);
    for (int j = 0; j < N; j++)
        q[j] = hl_system_coord(sys, j), p[j] = hl_system_momentum(sys, j);
    for (int i = 0; i < ns; i++)
        pn[i] = hl_system_set_name(sys, i), pv[i] = hl_system_set_value(sys, i);
    hl_tape *tape = NULL;
    int st = hl_tape_hamiltonian(&tape, hl_system_pool(sys), hl_system_H_expr(sys), N, q, p,
                                 ns, pn, pv, err);
    double *zz = NULL;
    if (st == HL_OK) {
        zz = hl_xmalloc((size_t)2 * N * (n + 1) * sizeof *zz);
        for (int i = 0; i < 2 * N; i++)
            zz[i * (n + 1)] = z[i];
        st = hl_tape_taylor_ode_d(zz, n, tape, err);
    }
    if (st == HL_OK)
        for (int i = 0; i < 2 * N; i++)
            for (int k = 0; k <= n; k++)
                flow[k * 2 * N + i] = zz[i * (n + 1) + k];
    free(zz);
    hl_tape_free(tape);
    free(q);
    free(pv);
    return st;
}

void hl_numerr_clear(hl_numerr *r)
{
    free(r->psi);
    free(r->flow);
    free(r->v);
    free(r->K);
    free(r->vnorm);
    free(r->thresh);
    memset(r, 0, sizeof *r);
}

/* r's arrays for order n and 2N phase variables; the checks of the order
 * and of H. */
static int numerr_start(hl_numerr *r, hl_system *sys, int n, hl_error *err)
{
    memset(r, 0, sizeof *r);
    if (n < 2 || n > HL_NUMERR_MAX_ORDER)
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0, "the order must be 2..%d, not %d",
                            HL_NUMERR_MAX_ORDER, n);
    if (!hl_system_has_H(sys))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "the error analysis needs H");
    int m2 = 2 * hl_system_ndof(sys);
    r->N = m2 / 2, r->n = n;
    r->psi = calloc((size_t)(n + 1) * m2, sizeof(double));
    r->flow = calloc((size_t)(n + 1) * m2, sizeof(double));
    r->v = calloc((size_t)(n + 1) * m2, sizeof(double));
    r->K = calloc((size_t)n * m2, sizeof(double));
    r->vnorm = calloc((size_t)n + 1, sizeof(double));
    r->thresh = calloc((size_t)n + 1, sizeof(double));
    if (!r->psi || !r->flow || !r->v || !r->K || !r->vnorm || !r->thresh)
        abort();
    return HL_OK;
}

/* The least k >= 2 with v_k above its threshold, and the order. */
static void find_leading(hl_numerr *r)
{
    r->leading = 0;
    for (int k = 2; k <= r->n && r->leading == 0; k++)
        if (r->vnorm[k] > r->thresh[k])
            r->leading = k;
    r->order = r->leading ? r->leading - 1 : r->n;
}

/* v_k = k! (psi_k - flow_k), their thresholds, the leading k and the order,
 * from r->psi; the flow's coefficients by Taylor mode. */
static int fields(hl_numerr *r, hl_system *sys, const double *z, hl_error *err)
{
    int m2 = 2 * r->N, n = r->n;
    int st = flow_coeffs(r->flow, sys, z, n, err);
    if (st != HL_OK)
        return st;
    double fact = 1;
    for (int k = 0; k <= n; k++) {
        if (k > 0)
            fact *= k;
        double scale = 1e-300;
        for (int i = 0; i < m2; i++) {
            double a = r->psi[k * m2 + i], b = r->flow[k * m2 + i];
            r->v[k * m2 + i] = k < 2 ? 0 : fact * (a - b);
            scale = fmax(scale, fabs(a) + fabs(b));
            r->vnorm[k] = fmax(r->vnorm[k], fabs(r->v[k * m2 + i]));
        }
        r->thresh[k] = HL_NUMERR_REL_TOL * fact * scale;
    }
    find_leading(r);
    return HL_OK;
}

/* The thresholds of a series from elsewhere (hl_numerr_from_series): the
 * size of order k is taken as the upper concave hull of log(scale_j) over
 * j = 0..n at k (scale_j = thresh_j / (tol j!)), extended by its end
 * segments.  Why: such a series is not computed exactly at zeros, so a
 * coefficient that vanishes at z by symmetry (q = 0 for V = q^4/4:
 * [D^2] = [D^3] = 0) is round-off of the size of its neighbours, not of
 * itself, and would show as a spurious error against a threshold of
 * nothing.  Where log(scale) is concave in k (geometric or factorial
 * decay) the hull is scale itself and nothing changes. */
static void hull_thresholds(hl_numerr *r)
{
    int n = r->n, nv = 0;
    int *h = hl_xmalloc((size_t)(n + 1) * sizeof *h); /* hull vertices */
    double *L = hl_xmalloc((size_t)(n + 1) * sizeof *L), fact = 1;
    for (int k = 0; k <= n; k++) {
        if (k > 0)
            fact *= k;
        double sc = r->thresh[k] / (HL_NUMERR_REL_TOL * fact);
        L[k] = sc > 1e-290 ? log(sc) : -INFINITY;
    }
    for (int k = 0; k <= n; k++) {
        if (L[k] == -INFINITY)
            continue;
        /* pop while the last vertex is not above the chord h[nv-2] -> k */
        while (nv >= 2) {
            int a = h[nv - 2], b = h[nv - 1];
            if ((L[b] - L[a]) * (k - a) > (L[k] - L[a]) * (b - a))
                break;
            nv--;
        }
        h[nv++] = k;
    }
    fact = 1;
    for (int k = 0, seg = 0; k <= n && nv >= 2; k++) {
        if (k > 0)
            fact *= k;
        while (seg < nv - 2 && k > h[seg + 1])
            seg++;
        int a = h[seg], b = h[seg + 1];
        double Lk = L[a] + (L[b] - L[a]) * (k - a) / (b - a);
        r->thresh[k] = fmax(r->thresh[k], HL_NUMERR_REL_TOL * fact * exp(Lk));
    }
    free(h);
    free(L);
    find_leading(r);
}

hl_status hl_numerr_compute(hl_numerr *r, const hl_scheme *s, const double *z, int n, hl_error *err)
{
    int st = numerr_start(r, s->sys, n, err);
    if (st != HL_OK)
        return st;
    int m2 = 2 * s->N, L = n + 1 + SLACK;
    dn *pt = calloc((size_t)m2 * L, sizeof *pt), *img = calloc((size_t)m2 * L, sizeof *img);
    if (!pt || !img)
        abort();
    for (int i = 0; i < m2; i++)
        pt[(size_t)i * L].r = z[i];
    if ((st = run_scheme(img, s, pt, L, err)) != HL_OK)
        goto done;
    for (int i = 0; i < m2; i++)
        for (int k = 0; k <= n; k++)
            r->psi[k * m2 + i] = img[(size_t)i * L + k].r;
    if ((st = fields(r, s->sys, z, err)) != HL_OK)
        goto done;
    /* K: the scheme at w(D) + eps w'(D), w = psi_{-D}(z) */
    memset(pt, 0, (size_t)m2 * L * sizeof *pt);
    for (int i = 0; i < m2; i++)
        for (int k = 0; k <= n; k++) {
            double w = (k & 1 ? -1 : 1) * r->psi[k * m2 + i];
            pt[(size_t)i * L + k].r = w;
            if (k >= 1)
                pt[(size_t)i * L + k - 1].e = k * w;
        }
    if ((st = run_scheme(img, s, pt, L, err)) != HL_OK)
        goto done;
    for (int i = 0; i < m2; i++)
        for (int k = 0; k < n; k++)
            r->K[k * m2 + i] = (k + 1) * img[(size_t)i * L + k + 1].r - img[(size_t)i * L + k].e;
done:
    free(pt);
    free(img);
    return st;
}

hl_status hl_numerr_from_series(hl_numerr *r, hl_system *sys, const double *z, const double *psi,
                                int n, hl_error *err)
{
    int st = numerr_start(r, sys, n, err);
    if (st != HL_OK)
        return st;
    memcpy(r->psi, psi, (size_t)(n + 1) * 2 * r->N * sizeof *psi);
    for (int i = 0; i < n * 2 * r->N; i++)
        r->K[i] = NAN;
    st = fields(r, sys, z, err);
    if (st == HL_OK)
        hull_thresholds(r);
    return st;
}
