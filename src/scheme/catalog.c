/* The catalog: language texts for the schemes the language says well, C
 * generators for the others (Butcher tableaux, Lie series, compositions,
 * Itoh-Abe and Gonzalez discrete gradients). */
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "scheme/scheme_impl.h"

#define S_SYMP HL_SCHEME_SYMPLECTIC
#define S_H HL_SCHEME_PRESERVES_H
#define S_IMPL HL_SCHEME_IMPLICIT
#define S_SEP HL_SCHEME_SEPARABLE
#define S_OSC HL_SCHEME_OSCILLATOR
#define S_QUAD HL_SCHEME_QUADRATIC

typedef struct entry {
    hl_scheme_info info;
    const char *text; /* NULL: a generator */
} entry;

/* Symplectic Euler as in Hairer-Lubich-Wanner, Geometric Numerical
 * Integration, eq. (VI.3.1) and its adjoint: "a" is implicit in p (explicit
 * for separable H: first p, then q), "b" implicit in q. */
static const entry catalog[] = {
    {{"euler", "explicit Euler: Z = z + D J grad H(z)", 1, 0},
     "Q = q + D*Hp(q, p); P = p - D*Hq(q, p)"},
    {{"symplectic-euler-a",
      "symplectic Euler, HLW (VI.3.1): P = p - D Hq(q, P), Q = q + D Hp(q, P)", 1,
      S_SYMP | S_IMPL | S_SEP},
     "P = p - D*Hq(q, P); Q = q + D*Hp(q, P)"},
    {{"symplectic-euler-b",
      "symplectic Euler, the adjoint of -a: Q = q + D Hp(Q, p), P = p - D Hq(Q, p)", 1,
      S_SYMP | S_IMPL | S_SEP},
     "Q = q + D*Hp(Q, p); P = p - D*Hq(Q, p)"},
    {{"stormer-verlet-kdk", "Stormer-Verlet, velocity form (kick-drift-kick), HLW (VI.3.4)", 2,
      S_SYMP | S_IMPL | S_SEP},
     "ph = p - D/2*Hq(q, ph); Q = q + D/2*(Hp(q, ph) + Hp(Q, ph)); P = ph - D/2*Hq(Q, ph)"},
    {{"stormer-verlet-dkd", "Stormer-Verlet, position form (drift-kick-drift), HLW (VI.3.5)", 2,
      S_SYMP | S_IMPL | S_SEP},
     "qh = q + D/2*Hp(qh, p); P = p - D/2*(Hq(qh, p) + Hq(qh, P)); Q = qh + D/2*Hp(qh, P)"},
    {{"implicit-midpoint", "implicit midpoint rule", 2, S_SYMP | S_IMPL},
     "Q = q + D*Hp((q+Q)/2, (p+P)/2); P = p - D*Hq((q+Q)/2, (p+P)/2)"},
    {{"rk4", "classical Runge-Kutta of order 4", 4, 0}, NULL},
    {{"gauss2", "Gauss-Legendre Runge-Kutta, 2 stages", 4, S_SYMP | S_IMPL}, NULL},
    {{"gauss3", "Gauss-Legendre Runge-Kutta, 3 stages", 6, S_SYMP | S_IMPL}, NULL},
    {{"avf", "average vector field (Quispel-McLaren): (Z-z)/D = int_0^1 J grad H(z+s(Z-z)) ds",
      2, S_H | S_IMPL},
     "Q = q + D*int(s, Hp(q + s*(Q-q), p + s*(P-p))); "
     "P = p - D*int(s, Hq(q + s*(Q-q), p + s*(P-p)))"},
    {{"gonzalez", "Gonzalez midpoint discrete gradient", 2, S_H | S_IMPL}, NULL},
    {{"itoh-abe", "Itoh-Abe coordinate-increment discrete gradient (q_1..q_N, p_1..p_N)", 1,
      S_H | S_IMPL},
     NULL},
    {{"lieN",
      "Lie series exp(D g) z truncated after D^N: lie1 (explicit Euler), lie2, ..., lie20",
      HL_SCHEME_ORDER_N, 0},
     NULL},
    {{"yoshida4", "Yoshida's order-4 composition of Stormer-Verlet (kick-drift-kick)", 4,
      S_SYMP | S_IMPL | S_SEP},
     NULL},
    {{"exact-rotation", "the paper's exact scheme for H = (p^2 + x^2)/2 (one dof only)",
      HL_SCHEME_EXACT,
      S_SYMP | S_H | S_OSC},
     "Q = q*cos(D) + p*sin(D); P = p*cos(D) - q*sin(D)"},
    {{"exact",
      "the exact flow in closed form, for H quadratic in the phase variables (any N; "
      "parameters allowed in uncoupled pairs; coupled pairs by normal modes)",
      HL_SCHEME_EXACT, S_SYMP | S_H | S_QUAD},
     NULL},
    {{"paper-euler", "the paper's Euler method: (Q-q)/D = Hp(q, p), (P-p)/D = -Hq(q, p)", 1, 0},
     "(Q-q)/D = Hp(q, p); (P-p)/D = -Hq(q, p)"},
    {{"paper-dg",
      "the paper's discrete gradient for H = (p^2 + x^2)/2 (one dof only): "
      "(X-x)/D = (P^2-p^2)/(2(P-p)), (P-p)/D = -(X^2-x^2)/(2(X-x))",
      2, S_SYMP | S_H | S_IMPL | S_OSC},
     "(Q-q)/D = (P^2-p^2)/(2*(P-p)); (P-p)/D = -(Q^2-q^2)/(2*(Q-q))"},
};

#define NCAT ((int)(sizeof catalog / sizeof *catalog))

int hl_scheme_catalog_count(void) { return NCAT; }

const hl_scheme_info *hl_scheme_catalog(int i)
{
    return i >= 0 && i < NCAT ? &catalog[i].info : NULL;
}

/* The members of the family lieN, one info each (their order is N). */
#define LIE_INFO(n) {"lie" #n, "Lie series exp(D g) z truncated after D^" #n, n, 0}
static const hl_scheme_info lie_info[HL_SCHEME_LIE_MAX] = {
    LIE_INFO(1),  LIE_INFO(2),  LIE_INFO(3),  LIE_INFO(4),  LIE_INFO(5),
    LIE_INFO(6),  LIE_INFO(7),  LIE_INFO(8),  LIE_INFO(9),  LIE_INFO(10),
    LIE_INFO(11), LIE_INFO(12), LIE_INFO(13), LIE_INFO(14), LIE_INFO(15),
    LIE_INFO(16), LIE_INFO(17), LIE_INFO(18), LIE_INFO(19), LIE_INFO(20)};

/* "lie<digits>": N (any value, to be checked against the range), or 0 when
 * name is not of that shape. */
static long lie_order(const char *name)
{
    if (strncmp(name, "lie", 3) != 0 || name[3] < '0' || name[3] > '9')
        return 0;
    long n = 0;
    for (const char *c = name + 3; *c; c++) {
        if (*c < '0' || *c > '9')
            return 0;
        n = n < 1000000 ? 10 * n + (*c - '0') : n; /* big is out of range anyway */
    }
    return n > 0 ? n : -1;
}

/* Names a user may reasonably type for a catalog scheme: plain Störmer–Verlet
 * is the velocity (kick-drift-kick) form, as in HLW and most codes. */
static const struct {
    const char *alias, *name;
} aliases[] = {{"stormer-verlet", "stormer-verlet-kdk"}, {"verlet", "stormer-verlet-kdk"}};

static const entry *find(const char *name)
{
    for (size_t i = 0; i < sizeof aliases / sizeof aliases[0]; i++)
        if (strcmp(aliases[i].alias, name) == 0)
            name = aliases[i].name;
    for (int i = 0; i < NCAT; i++)
        if (strcmp(catalog[i].info.name, name) == 0)
            return &catalog[i];
    return NULL;
}

const hl_scheme_info *hl_scheme_lookup(const char *name)
{
    long n = lie_order(name);
    if (n >= 1 && n <= HL_SCHEME_LIE_MAX)
        return &lie_info[n - 1];
    const entry *e = find(name);
    return e ? &e->info : NULL;
}

const char *hl_scheme_text(const char *name)
{
    const entry *e = find(name);
    return e ? e->text : NULL;
}

/* ---- reading a language text for a system -------------------------------- */

/* step_word: the step's name in the text, "D" in the catalog's texts, the
 * system's step name in the user's. */
static int read_text(hl_scheme **out, const char *name, const char *text, const char *step_word,
                     hl_system *sys, hl_error *err)
{
    sb b;
    sb_init(&b, sys, name);
    int N = hl_system_ndof(sys);
    const hl_expr **pt = hl_xmalloc((size_t)(2 * N + 1) * sizeof *pt);
    scheme_point(pt, sys);
    scheme_frame f = {pt, pt + N, b.s->iQ, b.s->iP, hl_sym(b.pool, hl_system_step(sys)), "",
                      step_word};
    int st = scheme_read(&b, text, &f, err);
    free(pt);
    if (st != HL_OK) {
        sb_abort(&b);
        return st;
    }
    return sb_finish(out, &b, err);
}

hl_status hl_scheme_from_text(hl_scheme **out, const char *def, hl_system *sys, hl_error *err)
{
    *out = NULL;
    return read_text(out, "user", def, hl_system_step(sys), sys, err);
}

/* ---- compositions --------------------------------------------------------- */

hl_status hl_scheme_compose(hl_scheme **out, const char *name, const char *text, int r,
                            const char *const *c, hl_system *sys, hl_error *err)
{
    *out = NULL;
    if (r < 1)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "a composition needs a step");
    sb b;
    sb_init(&b, sys, name);
    int N = hl_system_ndof(sys), st = HL_OK;
    const hl_expr **cur = hl_xmalloc((size_t)(2 * N) * sizeof *cur);
    int *nxt = hl_xmalloc((size_t)(2 * N) * sizeof *nxt);
    scheme_point(cur, sys);
    const hl_expr **z = hl_xmalloc((size_t)(2 * N) * sizeof *z);
    scheme_point(z, sys);
    hl_buf nb;
    hl_buf_init(&nb);
    for (int i = 0; st == HL_OK && i < r; i++) {
        /* the point after part i: the next point for the last part, else new
         * unknowns y<i>q#j, y<i>p#j whose value at D = 0 is z */
        for (int a = 0; a < 2 * N; a++) {
            if (i == r - 1) {
                nxt[a] = a < N ? b.s->iQ[a] : b.s->iP[a - N];
                continue;
            }
            hl_buf_printf(&nb, "y%d%c#%d", i + 1, a < N ? 'q' : 'p', a % N + 1);
            char *res = hl_buf_take(&nb);
            hl_buf_printf(&nb, "y%d%c[%d]", i + 1, a < N ? 'q' : 'p', a % N + 1);
            char *disp = hl_buf_take(&nb);
            nxt[a] = sb_unknown(&b, res, disp, z[a]);
            free(res), free(disp);
        }
        const hl_expr *ci;
        st = hl_parse(&ci, b.pool, c[i], err);
        if (st != HL_OK)
            break;
        hl_buf_printf(&nb, "c%d.", i + 1);
        char *prefix = hl_buf_take(&nb);
        scheme_frame f = {cur, cur + N, nxt, nxt + N,
                          hl_mul(b.pool, ci, hl_sym(b.pool, hl_system_step(sys))), prefix, "D"};
        st = scheme_read(&b, text, &f, err);
        free(prefix);
        for (int a = 0; a < 2 * N; a++)
            cur[a] = sb_usym(&b, nxt[a]);
    }
    hl_buf_clear(&nb);
    free(cur), free(nxt), free(z);
    if (st != HL_OK) {
        sb_abort(&b);
        return st;
    }
    return sb_finish(out, &b, err);
}

/* ---- Runge-Kutta ---------------------------------------------------------- */

static int is_zero_text(const char *s) { return strcmp(s, "0") == 0; }

/* sum_j coef[j]*name_j, "" when every coefficient is zero */
static void lin(hl_buf *t, int s, const char *const *coef, char name)
{
    int any = 0;
    for (int j = 0; j < s; j++) {
        if (is_zero_text(coef[j]))
            continue;
        hl_buf_printf(t, "%s(%s)*%c%d", any ? " + " : "", coef[j], name, j + 1);
        any = 1;
    }
}

static int all_zero(int s, const char *const *coef)
{
    for (int j = 0; j < s; j++)
        if (!is_zero_text(coef[j]))
            return 0;
    return 1;
}

hl_status hl_scheme_rk(hl_scheme **out, const char *name, int s, const char *const *A,
                       const char *const *b, hl_system *sys, hl_error *err)
{
    *out = NULL;
    if (s < 1 || s > 64)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "a tableau needs 1 to 64 stages");
    hl_buf t;
    hl_buf_init(&t);
    for (int i = 0; i < s; i++)
        for (int w = 0; w < 2; w++) {
            hl_buf_printf(&t, "%c%d = %sH%c(", w ? 'l' : 'k', i + 1, w ? "-" : "", w ? 'q' : 'p');
            for (int v = 0; v < 2; v++) {
                hl_buf_printf(&t, "%s%c", v ? ", " : "", v ? 'p' : 'q');
                if (!all_zero(s, A + i * s)) {
                    hl_buf_puts(&t, " + D*(");
                    lin(&t, s, A + i * s, v ? 'l' : 'k');
                    hl_buf_putc(&t, ')');
                }
            }
            hl_buf_puts(&t, "); ");
        }
    for (int w = 0; w < 2; w++) {
        hl_buf_printf(&t, "%c = %c + D*(", w ? 'P' : 'Q', w ? 'p' : 'q');
        lin(&t, s, b, w ? 'l' : 'k');
        hl_buf_puts(&t, w ? ")" : "); ");
    }
    int st = read_text(out, name, t.s, "D", sys, err);
    hl_buf_clear(&t);
    return st;
}

static const char *const rk4_A[] = {"0", "0", "0", "0", "1/2", "0", "0", "0",
                                    "0", "1/2", "0", "0", "0", "0", "1", "0"};
static const char *const rk4_b[] = {"1/6", "1/3", "1/3", "1/6"};
static const char *const gauss2_A[] = {"1/4", "1/4 - sqrt(3)/6", "1/4 + sqrt(3)/6", "1/4"};
static const char *const gauss2_b[] = {"1/2", "1/2"};
static const char *const gauss3_A[] = {
    "5/36",           "2/9 - sqrt(15)/15", "5/36 - sqrt(15)/30",
    "5/36 + sqrt(15)/24", "2/9",            "5/36 - sqrt(15)/24",
    "5/36 + sqrt(15)/30", "2/9 + sqrt(15)/15", "5/36"};
static const char *const gauss3_b[] = {"5/18", "4/9", "5/18"};

/* ---- Lie series ----------------------------------------------------------- */

hl_status hl_scheme_lie(hl_scheme **out, int n, hl_system *sys, hl_error *err)
{
    *out = NULL;
    if (n < 1 || n > HL_LIE_MAX_ORDER)
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0, "Lie series order %d outside 1..%d", n,
                            HL_LIE_MAX_ORDER);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), st = HL_OK;
    char nm[32];
    snprintf(nm, sizeof nm, "lie%d", n);
    sb b;
    sb_init(&b, sys, nm);
    hl_alg *terms = hl_alg_vec_new(n + 1, ctx);
    hl_alg phi;
    hl_alg_init(&phi, ctx);
    const hl_expr *D = hl_sym(b.pool, hl_system_step(sys));
    for (int a = 0; st == HL_OK && a < 2 * N; a++) {
        hl_alg_gen(&phi, a < N ? hl_system_var_q(sys, a) : hl_system_var_p(sys, a - N), ctx);
        st = hl_lie_terms(terms, &phi, n, sys, err);
        const hl_expr *sum = NULL;
        for (int k = 0; st == HL_OK && k <= n; k++) {
            if (hl_alg_is_zero(&terms[k], ctx))
                continue;
            fmpq_t f;
            fmpq_init(f);
            fmpz_one(fmpq_numref(f));
            fmpz_fac_ui(fmpq_denref(f), (ulong)k);
            const hl_expr *t = hl_alg_to_expr(&terms[k], ctx, b.pool);
            if (k > 0)
                t = hl_mul(b.pool, hl_mul(b.pool, hl_num_fmpq(b.pool, f),
                                          hl_pow(b.pool, D, hl_num_si(b.pool, k))),
                           t);
            fmpq_clear(f);
            sum = sum ? hl_add(b.pool, sum, t) : t;
        }
        if (st == HL_OK) {
            int u = a < N ? b.s->iQ[a] : b.s->iP[a - N];
            sb_eq(&b, sb_usym(&b, u), sum ? sum : hl_num_si(b.pool, 0), u);
        }
    }
    hl_alg_clear(&phi, ctx);
    hl_alg_vec_free(terms, n + 1, ctx);
    if (st != HL_OK) {
        sb_abort(&b);
        return st;
    }
    return sb_finish(out, &b, err);
}

/* ---- Itoh-Abe ------------------------------------------------------------- */

/* Coordinates in the order q_1..q_N, p_1..p_N.  The i-th difference quotient
 * (H(Z_1..Z_i, z_i+1..) - H(Z_1..Z_i-1, z_i..)) / (Z_i - z_i) is written as
 * int_0^1 dH/dz_i(Z_<i, z_i + s (Z_i - z_i), z_>i) ds: the same number, and
 * regular where Z_i = z_i. */
static int itoh_abe(hl_scheme **out, hl_system *sys, hl_error *err)
{
    sb b;
    sb_init(&b, sys, "itoh-abe");
    int N = hl_system_ndof(sys), M = 2 * N;
    const hl_expr **z = hl_xmalloc((size_t)M * sizeof *z);
    const hl_expr **v = hl_xmalloc((size_t)M * sizeof *v);
    const char **names = hl_xmalloc((size_t)M * sizeof *names);
    scheme_point(z, sys);
    for (int a = 0; a < M; a++)
        names[a] = z[a]->name;
    const hl_expr *s = hl_sym(b.pool, HL_SCHEME_S), *D = hl_sym(b.pool, hl_system_step(sys));
    const hl_expr **quot = hl_xmalloc((size_t)M * sizeof *quot);
    for (int i = 0; i < M; i++) {
        int ui = i < N ? b.s->iQ[i] : b.s->iP[i - N];
        for (int a = 0; a < M; a++) {
            int ua = a < N ? b.s->iQ[a] : b.s->iP[a - N];
            v[a] = a < i ? sb_usym(&b, ua) : z[a];
        }
        v[i] = hl_add(b.pool, z[i], hl_mul(b.pool, s, hl_sub(b.pool, sb_usym(&b, ui), z[i])));
        const hl_expr *g = scheme_dH(sys, i % N, i >= N);
        quot[i] = sb_integral(&b, hl_expr_subst(b.pool, g, M, names, v));
    }
    for (int j = 0; j < N; j++) {
        int uq = b.s->iQ[j], up = b.s->iP[j];
        sb_eq(&b, sb_usym(&b, uq), hl_add(b.pool, z[j], hl_mul(b.pool, D, quot[N + j])), uq);
        sb_eq(&b, sb_usym(&b, up), hl_sub(b.pool, z[N + j], hl_mul(b.pool, D, quot[j])), up);
    }
    free(z), free(v), free(names), free(quot);
    return sb_finish(out, &b, err);
}

/* ---- Gonzalez ------------------------------------------------------------- */

/* (Z - z)/D = J [grad H(m) + R/|Z - z|^2 (Z - z)], m = (z + Z)/2,
 * R = H(Z) - H(z) - grad H(m).(Z - z).  R/|Z - z|^2 is not a regular
 * function of Z at z, so the unknowns are the rates u = (Q - q)/D,
 * v = (P - p)/D (values dH/dp, -dH/dq at D = 0) and the equations are
 * cleared of the denominator:
 *   D W (u - Hp(m)) = R v,  D W (v + Hq(m)) = -R u,  W = |u|^2 + |v|^2,
 * with R = O(D^3); the series reading divides D^3 out.  R is written as the
 * integral below, which rounds as R and not as H (errors analyses give the
 * same fields; 0.1 s slower at order 5 on the pendulum). */
static int gonzalez(hl_scheme **out, hl_system *sys, hl_error *err)
{
    sb b;
    sb_init(&b, sys, "gonzalez");
    hl_pool *pool = b.pool;
    int N = hl_system_ndof(sys), M = 2 * N;
    const hl_expr **z = hl_xmalloc((size_t)M * sizeof *z);
    const hl_expr **w = hl_xmalloc((size_t)M * sizeof *w);
    const hl_expr **mid = hl_xmalloc((size_t)M * sizeof *mid);
    const hl_expr **line = hl_xmalloc((size_t)M * sizeof *line);
    const char **names = hl_xmalloc((size_t)M * sizeof *names);
    int *uw = hl_xmalloc((size_t)M * sizeof *uw);
    scheme_point(z, sys);
    for (int a = 0; a < M; a++)
        names[a] = z[a]->name;
    const hl_expr *D = hl_sym(pool, hl_system_step(sys)), *half = hl_num_frac(pool, 1, 2);
    hl_buf nb;
    hl_buf_init(&nb);
    for (int a = 0; a < M; a++) {
        int j = a % N;
        const hl_expr *g = scheme_dH(sys, j, a < N); /* u_j -> dH/dp_j, v_j -> -dH/dq_j */
        hl_buf_printf(&nb, "%c#%d", a < N ? 'u' : 'v', j + 1);
        char *res = hl_buf_take(&nb);
        hl_buf_printf(&nb, "%c[%d]", a < N ? 'u' : 'v', j + 1);
        char *disp = hl_buf_take(&nb);
        uw[a] = sb_unknown(&b, res, disp, a < N ? g : hl_neg(pool, g));
        free(res), free(disp);
        w[a] = sb_usym(&b, uw[a]);
    }
    hl_buf_clear(&nb);
    /* the increments d_a = D w_a, the midpoint, the segment z + s d */
    const hl_expr *W = NULL, *s = hl_sym(pool, HL_SCHEME_S);
    for (int a = 0; a < M; a++) {
        const hl_expr *d = hl_mul(pool, D, w[a]);
        mid[a] = hl_add(pool, z[a], hl_mul(pool, half, d));
        line[a] = hl_add(pool, z[a], hl_mul(pool, s, d));
        const hl_expr *sq = hl_pow(pool, w[a], hl_num_si(pool, 2));
        W = W ? hl_add(pool, W, sq) : sq;
    }
    const hl_expr **gm = hl_xmalloc((size_t)M * sizeof *gm); /* grad H(m): q part, p part */
    for (int a = 0; a < M; a++)
        gm[a] = hl_expr_subst(pool, scheme_dH(sys, a % N, a >= N), M, names, mid);
    /* R = int_0^1 (grad H(z + s d) - grad H(m)).d ds: the same number as
     * H(Z) - H(z) - grad H(m).d, without the difference of O(1) values that
     * is O(D^3) (the numeric reading's Taylor rule at s = 1/2 has no term of
     * order 0 at all: grad H(m) - grad H(m) is the node 0) */
    const hl_expr *body = NULL;
    for (int a = 0; a < M; a++) {
        const hl_expr *g = hl_expr_subst(pool, scheme_dH(sys, a % N, a >= N), M, names, line);
        const hl_expr *t = hl_mul(pool, hl_sub(pool, g, gm[a]), hl_mul(pool, D, w[a]));
        body = body ? hl_add(pool, body, t) : t;
    }
    const hl_expr *R = sb_integral(&b, body);
    const hl_expr *DW = hl_mul(pool, D, W);
    for (int j = 0; j < N; j++) {
        const hl_expr *u = w[j], *v = w[N + j];
        sb_eq(&b, hl_mul(pool, DW, hl_sub(pool, u, gm[N + j])), hl_mul(pool, R, v), -1);
        sb_eq(&b, hl_mul(pool, DW, hl_add(pool, v, gm[j])), hl_neg(pool, hl_mul(pool, R, u)),
              -1);
    }
    for (int a = 0; a < M; a++) {
        int u = a < N ? b.s->iQ[a] : b.s->iP[a - N];
        sb_eq(&b, sb_usym(&b, u), hl_add(pool, z[a], hl_mul(pool, D, w[a])), u);
    }
    free(z), free(w), free(mid), free(line), free(names), free(uw), free(gm);
    return sb_finish(out, &b, err);
}

/* ---- instantiation ---------------------------------------------------------- */

/* Is H exactly (p^2 + q^2)/2 with one degree of freedom? */
static int is_oscillator(hl_system *sys)
{
    if (hl_system_ndof(sys) != 1 || !hl_system_has_H(sys))
        return 0;
    hl_pool *pool = hl_system_pool(sys);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    const hl_expr *q = hl_sym(pool, hl_system_coord(sys, 0));
    const hl_expr *p = hl_sym(pool, hl_system_momentum(sys, 0));
    const hl_expr *two = hl_num_si(pool, 2);
    const hl_expr *h = hl_div(pool, hl_add(pool, hl_pow(pool, p, two), hl_pow(pool, q, two)), two);
    hl_alg a;
    hl_alg_init(&a, ctx);
    int yes = hl_alg_from_expr(&a, h, ctx, NULL) == HL_OK &&
              hl_alg_equal(&a, hl_system_H(sys), ctx);
    hl_alg_clear(&a, ctx);
    return yes;
}

/* The exact flow of a quadratic H (linear_flow.c), as a map. */
static int exact_flow(hl_scheme **out, hl_system *sys, hl_error *err)
{
    char *map = NULL;
    int st = hl_scheme_linear_flow_map(&map, sys, err);
    if (st == HL_OK)
        st = hl_scheme_from_map(out, map, sys, err);
    free(map);
    return st;
}

/* The member of lieN a name asks for: its order in *n, or an error that
 * gives the range.  "lie" alone takes its order from param (> 0). */
static hl_status lie_member(int *n, const char *name, int param, hl_error *err)
{
    long k = strcmp(name, "lie") == 0 ? param : lie_order(name);
    if (k >= 1 && k <= HL_SCHEME_LIE_MAX) {
        *n = (int)k;
        return HL_OK;
    }
    if (strcmp(name, "lie") == 0 || strcmp(name, "lieN") == 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "'%s' names the family of truncated Lie series: give its order "
                            "N = 1..%d in the name, e.g. lie4 (lie1 is explicit Euler)",
                            name, HL_SCHEME_LIE_MAX);
    return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                        "no scheme '%s': the truncated Lie series lieN exists for "
                        "N = 1..%d (lie1 is explicit Euler; beyond D^%d a step below 1 "
                        "changes no double)",
                        name, HL_SCHEME_LIE_MAX, HL_SCHEME_LIE_MAX);
}

static int is_lie_name(const char *name) { return strncmp(name, "lie", 3) == 0; }

hl_status hl_scheme_new(hl_scheme **out, const char *name, int param, hl_system *sys, hl_error *err)
{
    *out = NULL;
    if (is_lie_name(name)) {
        int n = 0;
        hl_status st = lie_member(&n, name, param, err);
        if (st == HL_OK && !hl_system_has_H(sys))
            st = hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                              "the scheme '%s' needs a Hamiltonian", name);
        return st == HL_OK ? hl_scheme_lie(out, n, sys, err) : st;
    }
    const entry *e = find(name);
    if (e == NULL) {
        hl_buf l;
        hl_buf_init(&l);
        for (int i = 0; i < NCAT; i++)
        {
            hl_buf_printf(&l, "%s%s", i ? ", " : "", catalog[i].info.name);
            if (catalog[i].info.order == HL_SCHEME_ORDER_N)
                hl_buf_printf(&l, " (N = 1..%d)", HL_SCHEME_LIE_MAX);
        }
        hl_error_set(err, HL_EINVAL, NULL, -1, 0, "unknown scheme '%s' (known: %s)", name, l.s);
        hl_buf_clear(&l);
        return HL_EINVAL;
    }
    if (!hl_system_has_H(sys))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the scheme '%s' needs a Hamiltonian", name);
    if ((e->info.flags & S_OSC) && !is_oscillator(sys))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the scheme '%s' is only valid for the one-dof oscillator "
                            "H = (p^2 + q^2)/2 (in the system's names); this system is not it",
                            name);
    if (e->text)
        return read_text(out, name, e->text, "D", sys, err);
    if (strcmp(name, "rk4") == 0)
        return hl_scheme_rk(out, name, 4, rk4_A, rk4_b, sys, err);
    if (strcmp(name, "gauss2") == 0)
        return hl_scheme_rk(out, name, 2, gauss2_A, gauss2_b, sys, err);
    if (strcmp(name, "gauss3") == 0)
        return hl_scheme_rk(out, name, 3, gauss3_A, gauss3_b, sys, err);
    if (strcmp(name, "itoh-abe") == 0)
        return itoh_abe(out, sys, err);
    if (strcmp(name, "gonzalez") == 0)
        return gonzalez(out, sys, err);
    if (strcmp(name, "exact") == 0)
        return exact_flow(out, sys, err);
    if (strcmp(name, "yoshida4") == 0) {
        /* x1 = 1/(2 - 2^(1/3)), x0 = -2^(1/3) x1 */
        static const char *const c[] = {"1/(2 - 2^(1/3))", "-2^(1/3)/(2 - 2^(1/3))",
                                         "1/(2 - 2^(1/3))"};
        return hl_scheme_compose(out, name, find("stormer-verlet-kdk")->text, 3, c, sys, err);
    }
    return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "scheme '%s' has no generator", name);
}
