/* The paper's formulas, recomputed and compared with the print (paper.h).
 *
 * The table is data: each row has the paper's print in hamlie's syntax and a
 * function computing hamlie's value.  The verdict is never written by hand:
 * the print is read into the exact algebra and printed - computed must be 0.
 *
 * Everything the rows need is computed once (struct hl_paper_work): the
 * oscillator H = (p^2+x^2)/2, the paper's three schemes expanded to O(D^9)
 * from their catalog definitions (implicit ones solved order by order), their
 * v_2..v_8 (direct and via K, hl_vfields_compute), and their closed maps,
 * solved here from the paper's printed discrete equations by exact linear
 * algebra (an independent route to the same map).  The relations between K
 * and the v_k are checked on a nonlinear system (explicit Euler on
 * H = (p^2+x^2)/2 + x^3/3), where a linear example could hide a wrong term.
 */
#include <stdlib.h>
#include <string.h>

#include "paper/formulas_impl.h"

/* ---- the rows' computations --------------------------------------------- */

static int f_generator(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                       hl_error *err)
{
    (void)r;
    *how = hl_xstrdup("g = dH/dp d/dx - dH/dx d/dp from H = (p^2+x^2)/2 (hl_generator); "
                      "g(x) = {x, H}, g(p) = {p, H}");
    return hl_generator(&out[0], &out[1], w->osc, err);
}

/* Does the map equal the Lie series exp(D g) z to O(D^n)? */
static int matches_flow(const hl_alg *map, struct hl_paper_work *w, int n)
{
    hl_alg_ctx *ctx = hl_system_ctx(w->osc);
    hl_series *s = hl_series_vec_new(2, 0, ctx);
    hl_alg z, l;
    int ok = 1;
    hl_alg_init(&z, ctx);
    hl_alg_init(&l, ctx);
    for (int i = 0; i < 2 && ok == 1; i++) {
        paper_alg_z(&z, i, w->osc);
        if (hl_lie_series(&l, &z, n - 1, w->osc, NULL) != HL_OK ||
            hl_series_from_alg(&s[i], &l, hl_system_var_D(w->osc), n, ctx, NULL) != HL_OK)
            ok = -1;
    }
    if (ok == 1)
        ok = paper_map_matches_series(map, s, n, w->osc);
    hl_series_vec_free(s, 2, ctx);
    hl_alg_clear(&z, ctx);
    hl_alg_clear(&l, ctx);
    return ok;
}

static int f_exact_map(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                       hl_error *err)
{
    (void)r;
    (void)err;
    hl_alg_ctx *ctx = hl_system_ctx(w->osc);
    int ok = matches_flow(w->exact_map, w, 13);
    hl_alg_set(&out[0], &w->exact_map[0], ctx);
    hl_alg_set(&out[1], &w->exact_map[1], ctx);
    *how = paper_strf("the map of catalog scheme exact-rotation (sec. 3 construction); %s",
                      ok == 1 ? "its Taylor series equals the Lie series exp(D g) z to O(D^13)"
                              : "its Taylor series DIFFERS from the Lie series exp(D g) z");
    return HL_OK;
}

/* (map - z)/D */
static int eqs_of(hl_alg *out, const hl_alg *map, hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg z, D;
    int st = HL_OK;
    hl_alg_init(&z, ctx);
    hl_alg_init(&D, ctx);
    paper_alg_D(&D, sys);
    for (int i = 0; i < 2 && st == HL_OK; i++) {
        paper_alg_z(&z, i, sys);
        hl_alg_sub(&out[i], &map[i], &z, ctx);
        st = hl_alg_div(&out[i], &out[i], &D, ctx, err);
    }
    hl_alg_clear(&z, ctx);
    hl_alg_clear(&D, ctx);
    return st;
}

static int f_exact_eqs(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                       hl_error *err)
{
    (void)r;
    *how = hl_xstrdup("((X - x)/D, (P - p)/D) of the exact map");
    return eqs_of(out, w->exact_map, w->osc, err);
}

static int f_exact_w(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                     hl_error *err)
{
    (void)r;
    (void)err;
    hl_alg_ctx *ctx = hl_system_ctx(w->osc);
    hl_alg t, Dk;
    fmpq_t f;
    hl_alg_init(&t, ctx);
    hl_alg_init(&Dk, ctx);
    fmpq_init(f);
    hl_alg_zero(&out[0], ctx);
    hl_alg_zero(&out[1], ctx);
    for (int k = 2; k <= NV; k++) {
        /* D^k/k! v_k */
        paper_alg_D(&Dk, w->osc);
        hl_alg_pow_si(&Dk, &Dk, k, ctx, NULL);
        fmpz_fac_ui(fmpq_denref(f), (ulong)k);
        fmpz_one(fmpq_numref(f));
        for (int i = 0; i < 2; i++) {
            hl_alg_mul(&t, &Dk, &hl_vfields_v(&w->exact.a->fields, k)[i], ctx);
            hl_alg_scalar_mul_fmpq(&t, &t, f, ctx);
            hl_alg_add(&out[i], &out[i], &t, ctx);
        }
    }
    fmpq_clear(f);
    hl_alg_clear(&t, ctx);
    hl_alg_clear(&Dk, ctx);
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_printf(&b,
                  "sum_{k=2}^{%d} D^k/k! v_k of exact-rotation, v_k computed directly and "
                  "from K: the two %s",
                  NV, paper_agree_text(&w->exact.a->fields));
    *how = hl_buf_take(&b);
    return HL_OK;
}

static void copy2(hl_alg *out, const hl_alg *a, hl_system *sys)
{
    hl_alg_set(&out[0], &a[0], hl_system_ctx(sys));
    hl_alg_set(&out[1], &a[1], hl_system_ctx(sys));
}

static int f_euler_map(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                       hl_error *err)
{
    (void)r;
    (void)err;
    copy2(out, w->euler_map, w->osc);
    *how = hl_xstrdup(w->euler_map_how);
    return HL_OK;
}

static int f_euler_eqs(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                       hl_error *err)
{
    (void)r;
    *how = hl_xstrdup("((X - x)/D, (P - p)/D) of the truncation exp(D g) ~ 1 + D g");
    hl_alg_ctx *ctx = hl_system_ctx(w->osc);
    hl_alg *m = hl_alg_vec_new(2, ctx);
    int st = HL_OK;
    for (int i = 0; i < 2 && st == HL_OK; i++) {
        hl_alg z;
        hl_alg_init(&z, ctx);
        paper_alg_z(&z, i, w->osc);
        st = hl_lie_series(&m[i], &z, 1, w->osc, err);
        hl_alg_clear(&z, ctx);
    }
    if (st == HL_OK)
        st = eqs_of(out, m, w->osc, err);
    hl_alg_vec_free(m, 2, ctx);
    return st;
}

static int f_K(struct hl_paper_work *w, const hl_alg *map, const hl_series *psi, hl_alg *out,
               char **how, hl_error *err)
{
    int st = hl_errors_K_closed(out, map, w->osc, err);
    if (st != HL_OK)
        return st;
    /* the same from the series of the catalog scheme (hl_series_scheme_K) */
    hl_alg_ctx *ctx = hl_system_ctx(w->osc);
    hl_series *K = hl_series_vec_new(2, 0, ctx);
    int vars[2] = {hl_system_var_q(w->osc, 0), hl_system_var_p(w->osc, 0)};
    int ok = hl_series_scheme_K(K, 2, psi, vars, hl_system_var_D(w->osc), ctx, NULL) == HL_OK
                 ? paper_map_matches_series(out, K, K[0].n < K[1].n ? K[0].n : K[1].n, w->osc)
                 : -1;
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_printf(&b, "K = (d/dD psi_D)(psi_{-D}(z)) in closed form from the solved map "
                      "(hl_errors_K_closed); %s the K of the catalog scheme's series "
                      "(O(D^%d))",
                  ok == 1 ? "equals" : ok == 0 ? "DIFFERS from" : "not compared with",
                  K[0].n);
    *how = hl_buf_take(&b);
    hl_series_vec_free(K, 2, ctx);
    return HL_OK;
}

static int f_euler_K(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                     hl_error *err)
{
    (void)r;
    return f_K(w, w->euler_map, w->euler.a->psi, out, how, err);
}

static int f_dg_K(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                  hl_error *err)
{
    (void)r;
    return f_K(w, w->dg_map, w->dg.a->psi, out, how, err);
}

static int f_v(const hl_vfields *e, const char *scheme, const char *closed, hl_system *sys,
               const row_t *r, hl_alg *out, char **how)
{
    copy2(out, hl_vfields_v(e, r->arg), sys);
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_printf(&b,
                  "v_%d of %s: directly (expansion minus the Lie series) and from K alone: "
                  "the two %s; closed form: %s",
                  r->arg, scheme, paper_agree_text(e), closed);
    *how = hl_buf_take(&b);
    return HL_OK;
}

static int f_euler_v(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                     hl_error *err)
{
    (void)err;
    return f_v(&w->euler.a->fields, "paper-euler",
               "psi = sqrt(1+D^2) R(atan D) (tested in t-formulas)", w->osc, r, out, how);
}

static int f_dg_v(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                  hl_error *err)
{
    (void)err;
    return f_v(&w->dg.a->fields, "paper-dg", "psi = R(2 atan(D/2)) (tested in t-formulas)", w->osc,
               r, out, how);
}

static int f_rk4_map(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                     hl_error *err)
{
    (void)r;
    copy2(out, w->euler_map, w->osc);
    hl_errors_correct_map(out, &w->euler.a->fields, 4, w->osc);
    /* against the catalog's RK4 (a Butcher tableau), expanded */
    analysed rk4 = {NULL, NULL};
    int st = paper_expand_catalog(&rk4, "rk4", NULL, 0, w->osc, NV, err);
    int ok = st == HL_OK ? paper_map_matches_series(out, rk4.a->psi, NV + 1, w->osc) : -1;
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_printf(&b, "Euler's map minus D^2/2 v_2 + D^3/6 v_3 + D^4/24 v_4 "
                      "(hl_errors_correct_map); %s catalog rk4 expanded to O(D^%d)",
                  ok == 1 ? "equals" : ok == 0 ? "DIFFERS from" : "not compared with", NV + 1);
    if (st == HL_OK)
        hl_buf_printf(&b, "; rk4 re-analysed: order %d", rk4.a->fields.order);
    *how = hl_buf_take(&b);
    paper_analysed_clear(&rk4);
    return st;
}

static int f_rk4_eqs(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                     hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(w->osc);
    hl_alg *m = hl_alg_vec_new(2, ctx);
    char *h = NULL;
    int st = f_rk4_map(w, r, m, &h, err);
    if (st == HL_OK)
        st = eqs_of(out, m, w->osc, err);
    *how = paper_strf("((X - x)/D, (P - p)/D) of the corrected Euler map; %s", h != NULL ? h : "");
    free(h);
    hl_alg_vec_free(m, 2, ctx);
    return st;
}

static int f_dg_map(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                    hl_error *err)
{
    (void)r;
    (void)err;
    copy2(out, w->dg_map, w->osc);
    *how = hl_xstrdup(w->dg_map_how);
    return HL_OK;
}

/* psi_{-D}(psi_D(z)): the DG map composed with itself at -D */
static int f_dg_inverse(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                        hl_error *err)
{
    (void)r;
    hl_alg_ctx *ctx = hl_system_ctx(w->osc);
    hl_alg *m = hl_alg_vec_new(2, ctx), mD;
    int vD = hl_system_var_D(w->osc), st;
    int vars[2] = {hl_system_var_q(w->osc, 0), hl_system_var_p(w->osc, 0)};
    hl_alg_init(&mD, ctx);
    paper_alg_D(&mD, w->osc);
    hl_alg_neg(&mD, &mD, ctx);
    st = hl_alg_subst(&m[0], &w->dg_map[0], 1, &vD, &mD, ctx, err);
    if (st == HL_OK)
        st = hl_alg_subst(&m[1], &w->dg_map[1], 1, &vD, &mD, ctx, err);
    for (int i = 0; i < 2 && st == HL_OK; i++)
        st = hl_alg_subst(&out[i], &m[i], 2, vars, w->dg_map, ctx, err);
    *how = hl_xstrdup("the solved DG map at -D composed with the map at D (exact substitution)");
    hl_alg_clear(&mD, ctx);
    hl_alg_vec_free(m, 2, ctx);
    return st;
}

static int f_dg_sign(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                     hl_error *err)
{
    (void)r;
    hl_alg_ctx *ctx = hl_system_ctx(w->osc);
    (void)err;
    const hl_analysis *a = w->dg.a;
    int m = a->fields.leading;
    fmpq_t c;
    fmpq_init(c);
    if (a->have_leading && a->leading.kind == HL_ERRFIELD_TIME_SHIFT &&
        hl_alg_is_fmpq(&a->leading.lambda, c, ctx)) {
        hl_alg_set_si(&out[0], fmpq_sgn(c), ctx);
        char *cs = fmpq_get_str(NULL, 10, c);
        hl_buf b;
        hl_buf_init(&b);
        hl_buf_printf(&b, "the leading error v_%d = c g is a time shift with c = %s: psi_D = "
                          "exp((D + c D^%d/%d!) g) + ..., so the point is %s the exact flow",
                      m, cs, m, m, fmpq_sgn(c) < 0 ? "BEHIND" : "ahead of");
        *how = hl_buf_take(&b);
        flint_free(cs);
    } else {
        hl_alg_zero(&out[0], ctx);
        *how = hl_xstrdup("the leading error is not a constant time shift");
    }
    fmpq_clear(c);
    return HL_OK;
}

/* tau, r, D2 of the DG map (hl_errors_time_closed) */
static int dg_time(hl_alg *t3, int *have_D2, struct hl_paper_work *w, hl_error *err)
{
    int ok = 0;
    int st = hl_errors_time_closed(&t3[0], &t3[1], &ok, &t3[2], have_D2, w->dg_map, w->osc, err);
    if (st == HL_OK && !ok)
        st = hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "the DG map is not a rotation");
    return st;
}

static int f_dg_two(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                    hl_error *err)
{
    (void)r;
    hl_alg_ctx *ctx = hl_system_ctx(w->osc);
    hl_alg *t3 = hl_alg_vec_new(3, ctx), *m = hl_alg_vec_new(4, ctx);
    int have = 0, st = dg_time(t3, &have, w, err), ok = 0;
    int vD = hl_system_var_D(w->osc);
    int vars[2] = {hl_system_var_q(w->osc, 0), hl_system_var_p(w->osc, 0)};
    if (st == HL_OK && !have)
        st = hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "no closed step D' for two steps");
    if (st == HL_OK) {
        hl_alg_set(&out[0], &t3[2], ctx);
        /* check: psi_D o psi_D == psi_{D'} by substitution */
        for (int i = 0; i < 2 && st == HL_OK; i++) {
            st = hl_alg_subst(&m[i], &w->dg_map[i], 2, vars, w->dg_map, ctx, err);
            if (st == HL_OK)
                st = hl_alg_subst(&m[2 + i], &w->dg_map[i], 1, &vD, &t3[2], ctx, err);
        }
        ok = st == HL_OK && hl_alg_equal(&m[0], &m[2], ctx) && hl_alg_equal(&m[1], &m[3], ctx);
    }
    *how = paper_strf("tan(tau/2) = M12/(1 + M11) = D/2 for the DG map (a rotation); D' with "
                      "r(D') = 2r/(1 - r^2) (hl_errors_time_closed); psi_D o psi_D = psi_{D'} "
                      "by exact substitution: %s",
                      ok ? "yes" : "NO");
    hl_alg_vec_free(t3, 3, ctx);
    hl_alg_vec_free(m, 4, ctx);
    return st;
}

static int dg_tau_how(char **how, const char *what, struct hl_paper_work *w)
{
    hl_alg_ctx *ctx = hl_system_ctx(w->osc);
    const hl_analysis *an = w->dg.a; /* its tau(D) solved order by order (HL_ANALYSIS_TIME) */
    int ok = an->tried_tau && an->tau_ok;
    const hl_series *tau = &an->tau;
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_printf(&b,
                  "%s; closed form: the DG map is the rotation by tau = 2 atan(D/2) "
                  "(hl_errors_time_closed); independently the series tau(D) with psi = "
                  "exp(tau g) solved order by order from the scheme's expansion %s",
                  what, ok ? "is a pure time shift to O(D^9)" : "FAILED");
    if (ok) {
        /* compare with the Taylor series of 2 atan(D/2) */
        hl_alg a;
        hl_series s;
        hl_alg_init(&a, ctx);
        hl_series_init(&s, 0, ctx);
        int same =
            hl_system_read(&a, w->osc, "2*atan(D/2)", NULL) == HL_OK &&
            hl_series_from_alg(&s, &a, hl_system_var_D(w->osc), tau->n, ctx, NULL) == HL_OK &&
            hl_series_equal(&s, tau, ctx);
        hl_buf_printf(&b, " and %s 2 atan(D/2)", same ? "equals the Taylor series of"
                                                      : "DIFFERS from");
        hl_alg_clear(&a, ctx);
        hl_series_clear(&s, ctx);
    }
    *how = hl_buf_take(&b);
    return HL_OK;
}

static int f_dg_W(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                  hl_error *err)
{
    (void)r;
    hl_alg_ctx *ctx = hl_system_ctx(w->osc);
    hl_alg *t3 = hl_alg_vec_new(3, ctx), D;
    int have = 0, st = dg_time(t3, &have, w, err);
    hl_alg_init(&D, ctx);
    paper_alg_D(&D, w->osc);
    if (st == HL_OK)
        hl_alg_sub(&out[0], &t3[0], &D, ctx);
    hl_alg_clear(&D, ctx);
    hl_alg_vec_free(t3, 3, ctx);
    dg_tau_how(how, "W = tau - D for psi = exp((D + W) g)", w);
    return st;
}

static int f_dg_T(struct hl_paper_work *w, const row_t *r, hl_alg *out, char **how,
                  hl_error *err)
{
    (void)r;
    hl_alg_ctx *ctx = hl_system_ctx(w->osc);
    hl_alg *t3 = hl_alg_vec_new(3, ctx);
    int have = 0, st = dg_time(t3, &have, w, err);
    if (st == HL_OK)
        hl_alg_set(&out[0], &t3[0], ctx);
    hl_alg_vec_free(t3, 3, ctx);
    dg_tau_how(how, "T - t = tau, the time the DG step really advances", w);
    return st;
}

/* ---- the table ------------------------------------------------------------ */

static const row_t ROWS[] = {
    {"generator", "the evolution generator of H = (p^2+x^2)/2", "sec. 4.1", HL_PAPER_FIELD, "p; -x",
     f_generator, 0},
    {"exact-map", "exact scheme: the iteration", "sec. 4.1.1; eq. (Exact), sec. 3.2", HL_PAPER_MAP,
     "x*cos(D) + p*sin(D); p*cos(D) - x*sin(D)", f_exact_map, 0},
    {"exact-eqs", "exact scheme: the discrete equations of motion", "sec. 4.1.1", HL_PAPER_EQS,
     "(x*cos(D) + p*sin(D) - x)/D; (p*cos(D) - x*sin(D) - p)/D", f_exact_eqs, 0},
    {"exact-w", "exact scheme: the error w_D (\"null, as expected\")", "sec. 4.1.1", HL_PAPER_FIELD,
     "0; 0", f_exact_w, 0},
    {"euler-eqs", "Euler: the discrete equations of motion", "sec. 4.1.2", HL_PAPER_EQS, "p; -x",
     f_euler_eqs, 0},
    {"euler-map", "Euler: the iteration", "sec. 4.1.2", HL_PAPER_MAP, "x + D*p; p - D*x",
     f_euler_map, 0},
    {"euler-K", "Euler: K(D) = psi_{-D} o d/dD psi_D", "sec. 4.1.2", HL_PAPER_FIELD,
     "p + D*x; D*p - x", f_euler_K, 0},
    {"euler-v2", "Euler: the error field v_2", "sec. 4.1.2", HL_PAPER_FIELD, "x; p", f_euler_v, 2},
    {"euler-v3", "Euler: the error field v_3", "sec. 4.1.2", HL_PAPER_FIELD, "p; x", f_euler_v, 3},
    {"euler-v4", "Euler: the error field v_4", "sec. 4.1.2", HL_PAPER_FIELD, "-x; -p", f_euler_v,
     4},
    {"rk4-map", "Euler corrected by v_2, v_3, v_4 (= RK4): the iteration", "sec. 4.1.2",
     HL_PAPER_MAP, "x + D*p - D^2/2*x - D^3/6*p + D^4/24*x; p - D*x - D^2/2*p + D^3/6*x + D^4/24*p",
     f_rk4_map, 0},
    {"rk4-eqs", "Euler corrected (= RK4): the discrete equations", "sec. 4.1.2", HL_PAPER_EQS,
     "p - D/2*x - D^2/6*p + D^3/24*x; -x - D/2*p + D^2/6*x + D^3/24*p", f_rk4_eqs, 0},
    {"dg-map", "discrete gradient: the iteration", "sec. 4.1.3", HL_PAPER_MAP,
     "(4*x + 4*D*p - D^2*x)/(4 + D^2); (4*p - 4*D*x - D^2*p)/(4 + D^2)", f_dg_map, 0},
    {"dg-inverse", "discrete gradient: psi_{-D} o psi_D = 1", "sec. 4.1.3", HL_PAPER_MAP, "x; p",
     f_dg_inverse, 0},
    {"dg-K", "discrete gradient: K(D) (ErrDG)", "eq. (ErrDG)", HL_PAPER_FIELD,
     "(1 + D^2/(4 + D^2))*p; -(1 + D^2/(4 + D^2))*x", f_dg_K, 0},
    {"dg-v3", "discrete gradient: the error field v_3", "sec. 4.1.3", HL_PAPER_FIELD,
     "-1/2*p; 1/2*x", f_dg_v, 3},
    {"dg-v4", "discrete gradient: the error field v_4", "sec. 4.1.3", HL_PAPER_FIELD, "2*x; 2*p",
     f_dg_v, 4},
    {"dg-v5", "discrete gradient: the error field v_5", "sec. 4.1.3", HL_PAPER_FIELD,
     "13/2*p; -13/2*x", f_dg_v, 5},
    {"dg-ahead", "discrete gradient: \"a point too far in time\" (sign of c in v_3 = c g)",
     "sec. 4.1.3", HL_PAPER_SCALAR, "1", f_dg_sign, 0},
    {"dg-two-steps", "discrete gradient: two steps D = one step D'", "sec. 4.1.3", HL_PAPER_SCALAR,
     "8*D/(4 - D^2)", f_dg_two, 0},
    {"dg-W", "discrete gradient: W(D) with psi_D = exp((D + W(D)) g)", "sec. 4.1.3",
     HL_PAPER_SCALAR, "D - 2*atan(D/2)", f_dg_W, 0},
    {"dg-T", "discrete gradient reparametrised: T - t", "sec. 4.1.3", HL_PAPER_SCALAR,
     "2*atan(D/2)", f_dg_T, 0},
    {"rel-1", "the D^1 relation between K and the v_k", "sec. 4, after eq. (Err)", HL_PAPER_REL,
     "+1 v2", paper_f_rel, 1},
    {"rel-2", "the D^2 relation between K and the v_k", "sec. 4, after eq. (Err)", HL_PAPER_REL,
     "+1 v3 -2 g.v2 +1 v2.g", paper_f_rel, 2},
    {"rel-3", "the D^3 relation between K and the v_k", "sec. 4, after eq. (Err)", HL_PAPER_REL,
     "+1 v4 -3 g.v3 +1 v3.g +3 v2.v2 +3 g.g.v2 +3 v2.g.g", paper_f_rel, 3},
};

#define NROWS ((int)(sizeof ROWS / sizeof *ROWS))

const hl_paper_formula_row *hl_paper_formula_rows(int *n)
{
    *n = NROWS;
    return ROWS;
}

/* ---- formatting ------------------------------------------------------------ */

static char *format_value(const hl_alg *v, hl_paper_kind kind, int k, hl_system *sys,
                          hl_style style)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_pool *pool = hl_system_pool(sys);
    int tex = style == HL_STYLE_LATEX;
    hl_buf b;
    hl_buf_init(&b);
    if (kind == HL_PAPER_FIELD || kind == HL_PAPER_REL) {
        char *s = hl_format_vector_field(2, NAMES, v, ctx, pool, style);
        if (kind == HL_PAPER_REL)
            hl_buf_printf(&b, tex ? "\\partial_\\Delta^{%d}K|_0 = " : "d^%dK/dD^%d(0) = ", k, k);
        hl_buf_puts(&b, s);
        free(s);
    } else if (kind == HL_PAPER_SCALAR) {
        char *s = hl_format_alg(&v[0], ctx, pool, style);
        hl_buf_puts(&b, s);
        free(s);
    } else {
        char *a = hl_format_alg(&v[0], ctx, pool, style), *c = hl_format_alg(&v[1], ctx, pool, style);
        if (kind == HL_PAPER_MAP)
            hl_buf_printf(&b, "X = %s%s P = %s", a, tex ? ",\\quad" : ",", c);
        else
            hl_buf_printf(&b, tex ? "\\frac{X-x}{\\Delta} = %s,\\quad \\frac{P-p}{\\Delta} = %s"
                                  : "(X-x)/D = %s, (P-p)/D = %s",
                          a, c);
        free(a);
        free(c);
    }
    return hl_buf_take(&b);
}

static char *printed_text(const row_t *r)
{
    hl_buf b;
    hl_buf_init(&b);
    const char *semi = strchr(r->printed, ';');
    int n1 = semi != NULL ? (int)(semi - r->printed) : (int)strlen(r->printed);
    const char *second = semi != NULL ? semi + 1 : "";
    while (*second == ' ')
        second++;
    switch (r->kind) {
    case HL_PAPER_FIELD:
        hl_buf_printf(&b, "(%.*s) d/dx + (%s) d/dp", n1, r->printed, second);
        break;
    case HL_PAPER_MAP:
        hl_buf_printf(&b, "X = %.*s, P = %s", n1, r->printed, second);
        break;
    case HL_PAPER_EQS:
        hl_buf_printf(&b, "(X-x)/D = %.*s, (P-p)/D = %s", n1, r->printed, second);
        break;
    case HL_PAPER_REL:
        hl_buf_printf(&b, "d^%dK/dD^%d(0) = %s", r->arg, r->arg, r->printed);
        break;
    default:
        hl_buf_puts(&b, r->printed);
    }
    return hl_buf_take(&b);
}

/* The relation's print in LaTeX: "+1 v3 -2 g.v2" -> v_3 - 2\,\mathfrak{g}\circ v_2 */
static char *rel_latex(const row_t *r)
{
    hl_buf b;
    char *copy = hl_xstrdup(r->printed), *save = NULL;
    int first = 1;
    hl_buf_init(&b);
    hl_buf_printf(&b, "\\partial_\\Delta^{%d}K|_0 = ", r->arg);
    for (char *tok = strtok_r(copy, " ", &save); tok != NULL; tok = strtok_r(NULL, " ", &save)) {
        char *word = strtok_r(NULL, " ", &save);
        long c = strtol(tok, NULL, 10);
        if (word == NULL)
            break;
        hl_buf_puts(&b, c < 0 ? " - " : first ? "" : " + ");
        if (labs(c) != 1)
            hl_buf_printf(&b, "%ld\\,", labs(c));
        for (const char *p = word; *p != '\0'; p++) {
            if (*p == 'g')
                hl_buf_puts(&b, "\\mathfrak{g}");
            else if (*p == 'v')
                hl_buf_printf(&b, "v_{%c}", *++p);
            else if (*p == '.')
                hl_buf_puts(&b, "\\circ ");
        }
        first = 0;
    }
    free(copy);
    return hl_buf_take(&b);
}

/* ---- computing the table -------------------------------------------------- */

static int do_row(hl_paper_formula *f, struct hl_paper_work *w, const row_t *r, hl_error *err)
{
    hl_system *sys = r->kind == HL_PAPER_REL ? w->cub : w->osc;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int ncomp = r->kind == HL_PAPER_SCALAR ? 1 : 2;
    hl_alg *pv = hl_alg_vec_new(2, ctx), *cv = hl_alg_vec_new(2, ctx);
    char *how = NULL;
    int st, nterms = 0;
    char *fixed = NULL; /* a relation's corrected print */
    f->id = r->id;
    f->what = r->what;
    f->paper_eq = r->paper_eq;
    f->printed = printed_text(r);
    if (r->kind == HL_PAPER_REL)
        st = paper_eval_rel(pv, &nterms, w, 0, r->printed, -1, err);
    else
        st = paper_read_comps(pv, ncomp, sys, r->printed, err);
    if (st != HL_OK)
        hl_error_prefix(err, "the print of '%s'", r->id);
    if (st == HL_OK && (st = r->compute(w, r, cv, &how, err)) != HL_OK)
        hl_error_prefix(err, "computing '%s'", r->id);
    if (st == HL_OK) {
        int same = 1;
        for (int i = 0; i < ncomp; i++)
            same = same && hl_alg_equal(&pv[i], &cv[i], ctx);
        if (same && r->kind == HL_PAPER_REL) /* and on the other test schemes */
            same = paper_rel_holds(w, r->printed, -1, r->arg, 1);
        f->verdict = same ? HL_VERDICT_AGREES : HL_VERDICT_DIFFERS;
        if (!same && r->kind == HL_PAPER_REL) {
            /* say by how much: left side minus the print's right side */
            hl_alg *d = hl_alg_vec_new(2, ctx);
            hl_alg_sub(&d[0], &cv[0], &pv[0], ctx);
            hl_alg_sub(&d[1], &cv[1], &pv[1], ctx);
            char *ds = hl_format_vector_field(2, NAMES, d, ctx, hl_system_pool(sys),
                                              HL_STYLE_TEXT);
            hl_buf b;
            hl_buf_init(&b);
            hl_buf_printf(&b, "%s; for %s the left side minus the print's right side "
                              "is %s, so the printed relation does not hold",
                          how, REL_NAMES[0], ds);
            int j = paper_rel_sign_fix(w, r->printed, r->arg, nterms);
            if (j >= 0) {
                char *tj = paper_rel_term(r->printed, j);
                hl_buf_printf(&b, "; it holds for both test schemes with the sign of the "
                                  "term '%s' changed (found by trying each sign)",
                              tj);
                free(tj);
                fixed = paper_rel_flipped(r->printed, j);
            } else
                hl_buf_puts(&b, "; no single sign change makes it hold");
            free(ds);
            free(how);
            how = hl_buf_take(&b);
            hl_alg_vec_free(d, 2, ctx);
        }
        f->printed_latex = r->kind == HL_PAPER_REL
                               ? rel_latex(r)
                               : format_value(pv, r->kind, r->arg, sys, HL_STYLE_LATEX);
        f->computed = format_value(cv, r->kind, r->arg, sys, HL_STYLE_TEXT);
        if (fixed != NULL) {
            /* the correct relation is the result; its value goes to "how" */
            row_t rr = *r;
            rr.printed = fixed;
            free(f->computed);
            f->computed = printed_text(&rr);
            f->computed_latex = rel_latex(&rr);
        } else if (r->kind == HL_PAPER_REL) {
            /* the value is on the rows' test system: say so */
            hl_buf b;
            hl_buf_init(&b);
            hl_buf_printf(&b, "%s on %s, H = (p^2+x^2)/2 + x^3/3", f->computed, REL_NAMES[0]);
            if (!same) {
                char *ps = hl_format_vector_field(2, NAMES, pv, ctx, hl_system_pool(sys),
                                                  HL_STYLE_TEXT);
                hl_buf_printf(&b, ", where the print's right side is %s", ps);
                free(ps);
            }
            free(f->computed);
            f->computed = hl_buf_take(&b);
        }
        if (f->computed_latex == NULL)
            f->computed_latex = format_value(cv, r->kind, r->arg, sys, HL_STYLE_LATEX);
        f->how = how;
        how = NULL;
    }
    free(how);
    free(fixed);
    hl_alg_vec_free(pv, 2, ctx);
    hl_alg_vec_free(cv, 2, ctx);
    return st;
}

hl_status hl_paper_formulas_compute_rows(hl_paper_formulas *out,
                                         const hl_paper_formula_row *rows, int n,
                                         hl_error *err)
{
    struct hl_paper_work w;
    int st = paper_work_init(&w, err);
    out->n = 0;
    out->f = hl_xcalloc((size_t)(n > 0 ? n : 1), sizeof *out->f);
    for (int i = 0; i < n && st == HL_OK; i++) {
        st = do_row(&out->f[i], &w, &rows[i], err);
        out->n = i + 1;
    }
    paper_work_clear(&w);
    if (st != HL_OK)
        hl_paper_formulas_clear(out);
    return (hl_status)st;
}

hl_status hl_paper_formulas_compute(hl_paper_formulas *out, hl_error *err)
{
    return hl_paper_formulas_compute_rows(out, ROWS, NROWS, err);
}

void hl_paper_formulas_clear(hl_paper_formulas *fs)
{
    if (fs == NULL)
        return;
    for (int i = 0; i < fs->n; i++) {
        free(fs->f[i].printed);
        free(fs->f[i].printed_latex);
        free(fs->f[i].computed);
        free(fs->f[i].computed_latex);
        free(fs->f[i].how);
    }
    free(fs->f);
    fs->f = NULL;
    fs->n = 0;
}
