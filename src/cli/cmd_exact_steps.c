/* `hamlie exact --steps` and `--action-angle`: §3 of the paper carried out
 * by steps for H = p^2/(2m) + V(q), V of degree <= 2 (each step printed,
 * then the action-angle map checked and the scheme compared with the closed
 * form), and a user's action-angle map verified and turned into the
 * scheme. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cmd_exact_impl.h"
#include "hamlie/exact.h"
#include "hamlie/scheme.h"

/* Evaluate an alg at (q, p, D) numerically (the other symbols must not
 * occur). */
static double eval_at(const hl_alg *a, hl_system *sys, double q, double p, double D, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int nb = hl_alg_ctx_nbase(ctx);
    arb_ptr v = _arb_vec_init(nb);
    arb_t r;
    arb_init(r);
    arb_set_d(v + hl_system_var_q(sys, 0), q);
    arb_set_d(v + hl_system_var_p(sys, 0), p);
    arb_set_d(v + hl_system_var_D(sys), D);
    /* symbolic parameters: the sample values of hl_exact_aa_verify */
    for (int i = 0; i < hl_system_nparams(sys); i++)
        arb_set_d(v + hl_alg_ctx_index(ctx, hl_system_param(sys, i)), 1.3 + 0.17 * i);
    double x = NAN;
    if (hl_alg_eval_arb(r, a, v, 128, ctx, err) == HL_OK)
        x = arf_get_d(arb_midref(r), ARF_RND_NEAR);
    arb_clear(r);
    _arb_vec_clear(v, nb);
    return x;
}

/* Q, P of a map against the closed form at sample points in every
 * quadrant and on the axes. */
static int agree_with_closed(int *ok, double *maxd, const hl_alg *img, hl_system *sys,
                             hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg *cf = hl_alg_vec_new(2, ctx);
    int st = hl_scheme_linear_flow(cf, sys, err);
    static const double pts[][3] = {{0.3, 0.8, 0.5},   {-1.2, 0.4, 2.0},  {0.7, 2.0, -3.1},
                                    {-0.6, -0.9, 1.3}, {0.5, -0.3, -0.7}, {-0.8, 0, 0.9},
                                    {0, -0.7, 2.5}};
    *ok = st == HL_OK;
    *maxd = 0;
    for (int i = 0; i < (int)(sizeof pts / sizeof *pts) && *ok; i++)
        for (int v = 0; v < 2; v++) {
            double a = eval_at(&img[v], sys, pts[i][0], pts[i][1], pts[i][2], err);
            double b = eval_at(&cf[v], sys, pts[i][0], pts[i][1], pts[i][2], err);
            double d = fabs(a - b);
            *maxd = isfinite(d) ? fmax(*maxd, d) : INFINITY;
        }
    *ok = *ok && *maxd < 1e-12;
    hl_alg_vec_free(cf, 2, ctx);
    return st;
}

int exact_run_aa(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err)
{
    hl_exact_aa aa;
    int st = hl_exact_aa_read(&aa, sys, exact_mode.aa, err);
    if (st != HL_OK) {
        hl_error_prefix(err, "in --action-angle");
        return st;
    }
    int ok = 0;
    char why[400];
    st = hl_exact_aa_verify(&ok, why, sizeof why, &aa, sys, err);
    if (st != HL_OK)
        return st;
    exact_json_bool("verified", ok);
    exact_json_string("rejected_because", ok ? NULL : why);
    if (!ok) {
        hl_buf_printf(out, "action-angle map rejected: %s\n", why);
        *code = CLI_FAILS;
        return HL_OK;
    }
    hl_buf_puts(out, "action-angle map verified: {theta, I} = 1, {I, H} = 0, "
                     "{theta, H} = nu(I), q and p the inverse (at points in all four "
                     "quadrants)\n");
    hl_alg *img = hl_alg_vec_new(2, hl_system_ctx(sys));
    st = hl_exact_aa_scheme(img, &aa, sys, err);
    if (st == HL_OK) {
        hl_buf_printf(out, "exact scheme Q = q(theta + nu %s, I), P = p(theta + nu %s, I):\n",
                      hl_system_step(sys), hl_system_step(sys));
        exact_json_section("scheme");
        exact_put_images(out, img, sys, o);
        *code = CLI_OK;
    }
    hl_alg_vec_free(img, 2, hl_system_ctx(sys));
    return st;
}

/* The checks that end --steps: dK/dq = p and dK/dI = theta numerically
 * (eps = 1, p > 0; I from Istr at the point), the action-angle map spec
 * through hl_exact_aa_verify, the scheme against the closed form. */
static int steps_check(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, const char *Ks,
                       const char *th, const char *Istr, const char *spec, hl_error *err)
{
    hl_pool *pool = hl_system_pool(sys);
    const char *q = hl_system_coord(sys, 0), *p = hl_system_momentum(sys, 0);
    int st = HL_OK;
    /* checks: dK/dq = p and dK/dI = theta numerically (eps = 1, p > 0);
     * the map through hl_exact_aa_verify; the scheme against the closed form */
    int ok = 1;
    double maxd = 0;
    {
        const hl_expr *Ke = NULL, *te = NULL, *Ie = NULL;
        st = hl_parse(&Ke, pool, Ks, err);
        if (st == HL_OK)
            st = hl_parse(&te, pool, th, err);
        if (st == HL_OK)
            st = hl_parse(&Ie, pool, Istr, err);
        if (st == HL_OK) {
            const char *nm1[] = {"eps"};
            const hl_expr *one[] = {hl_num_si(pool, 1)};
            Ke = hl_expr_subst(pool, Ke, 1, nm1, one);
            const hl_expr *dKdI = hl_expr_diff(pool, Ke, "I");
            const hl_expr *dKdq = hl_expr_diff(pool, Ke, q);
            static const double pts[][2] = {{0.3, 0.8}, {-0.5, 0.2}, {0.1, 1.7}};
            for (int i = 0; i < 3 && st == HL_OK; i++) {
                /* at (q, p): I = I(q, p) */
                const char *names[] = {q, p, "I"};
                double Iv = NAN, a = NAN, b = NAN, c = NAN, vals[3] = {pts[i][0], pts[i][1], 0};
                if (hl_expr_eval_d(&Iv, Ie, 2, names, vals, err) != HL_OK)
                    break; /* symbolic m, k: skip the numeric check of K */
                vals[2] = Iv;
                if (hl_expr_eval_d(&a, dKdq, 3, names, vals, err) != HL_OK ||
                    hl_expr_eval_d(&b, dKdI, 3, names, vals, err) != HL_OK ||
                    hl_expr_eval_d(&c, te, 3, names, vals, err) != HL_OK)
                    break;
                ok = ok && fabs(a - vals[1]) < 1e-12 && fabs(b - c) < 1e-12;
            }
            st = HL_OK;
        }
    }
    hl_exact_aa aa;
    char why[400] = "";
    int aok = 0, cok = 0;
    hl_alg *img = hl_alg_vec_new(2, hl_system_ctx(sys));
    if (st == HL_OK)
        st = hl_exact_aa_read(&aa, sys, spec, err);
    if (st == HL_OK)
        st = hl_exact_aa_verify(&aok, why, sizeof why, &aa, sys, err);
    if (st == HL_OK)
        st = hl_exact_aa_scheme(img, &aa, sys, err);
    if (st == HL_OK)
        st = agree_with_closed(&cok, &maxd, img, sys, err);
    if (st == HL_OK) {
        hl_buf_printf(out, "result: Q = r(theta(q, gamma) + nu %s, gamma), P = s(...):\n",
                      hl_system_step(sys));
        exact_json_section("result");
        exact_put_images(out, img, sys, o);
        hl_alg *cf = hl_alg_vec_new(2, hl_system_ctx(sys));
        st = hl_scheme_linear_flow(cf, sys, err);
        if (st == HL_OK) {
            hl_buf_puts(out, "simplified (the closed form it equals):\n");
            exact_json_section("closed_form");
            exact_put_images(out, cf, sys, o);
        }
        hl_alg_vec_free(cf, 2, hl_system_ctx(sys));
        hl_buf_printf(out, "check dK/dq = p, dK/dI = theta: %s\n", ok ? "yes" : "NO");
        hl_buf_printf(out, "check the action-angle map: %s%s\n", aok ? "yes" : "NO: ", why);
        hl_buf_printf(out, "check the result equals the closed form (max diff %.2g): %s\n", maxd,
                      cok ? "yes" : "NO");
        exact_json_section("checks");
        exact_json_bool("dK_dq_is_p_and_dK_dI_is_theta", ok);
        exact_json_bool("action_angle_map", aok);
        exact_json_string("action_angle_map_rejected_because", aok ? NULL : why);
        exact_json_bool("equals_closed_form", cok);
        exact_json_double("max_difference_from_closed_form", maxd);
        *code = ok && aok && cok ? CLI_OK : CLI_FAILS;
    }
    hl_alg_vec_free(img, 2, hl_system_ctx(sys));
    return st;
}

/* Is H = p^2/(2m) + g q (+ a constant), m and g free of q and p?  Then
 * *ms and *gs are their texts (malloc'd). */
static int linear_potential(char **ms, char **gs, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int vq = hl_system_var_q(sys, 0), vp = hl_system_var_p(sys, 0), yes = 0;
    hl_alg *a = hl_alg_vec_new(5, ctx); /* H_p, H_pp, H_pq, H_q, H_qq */
    hl_error err;
    if (hl_alg_diff(&a[0], hl_system_H(sys), vp, ctx, &err) == HL_OK &&
        hl_alg_diff(&a[1], &a[0], vp, ctx, &err) == HL_OK &&
        hl_alg_diff(&a[2], &a[0], vq, ctx, &err) == HL_OK &&
        hl_alg_diff(&a[3], hl_system_H(sys), vq, ctx, &err) == HL_OK &&
        hl_alg_diff(&a[4], &a[3], vq, ctx, &err) == HL_OK) {
        yes =
            !hl_alg_is_zero(&a[1], ctx) && hl_alg_is_zero(&a[2], ctx) && hl_alg_is_zero(&a[4], ctx);
        for (int i = 1; i <= 3; i += 2)
            yes = yes && !hl_alg_depends_on(&a[i], vq, ctx) && !hl_alg_depends_on(&a[i], vp, ctx);
        hl_alg_one(&a[0], ctx);
        if (yes && hl_alg_div(&a[0], &a[0], &a[1], ctx, &err) == HL_OK) { /* m = 1/H_pp */
            *ms = hl_format_alg(&a[0], ctx, hl_system_pool(sys), HL_STYLE_TEXT);
            *gs = hl_format_alg(&a[3], ctx, hl_system_pool(sys), HL_STYLE_TEXT);
        } else
            yes = 0;
    }
    hl_alg_vec_free(a, 5, ctx);
    return yes;
}

/* The seven steps for the free particle (g = 0: I = p, theta = q, an angle
 * that does not come back, nu = I/m) and the uniform field (g != 0: I = H,
 * K = -(2m(I - g q))^(3/2)/(3 m g), theta = dK/dI = -p/g in units of time,
 * nu = 1). */
static int run_steps_linear(hl_buf *out, int *code, hl_system *sys, const cli_opts *o,
                            const char *ms, const char *gs, hl_error *err)
{
    const char *q = hl_system_coord(sys, 0), *p = hl_system_momentum(sys, 0);
    int free_ = strcmp(gs, "0") == 0;
    /* f[0] with the letters m and g, as printed; f[1] with their values, to check */
    char I[2][2048], K[2][2048], th[2][1024], rq[2][2048], rp[2][1024], nu[2][1024], pf[1024];
    for (int v = 0; v < 2; v++) {
        char m[256], g[256];
        snprintf(m, sizeof m, v ? "(%s)" : "m", ms);
        snprintf(g, sizeof g, v ? "(%s)" : "g", gs);
        if (free_) {
            snprintf(I[v], sizeof I[v], "%s", p);
            snprintf(K[v], sizeof K[v], "I*%s", q);
            snprintf(th[v], sizeof th[v], "%s", q);
            snprintf(rq[v], sizeof rq[v], "theta");
            snprintf(rp[v], sizeof rp[v], "I");
            snprintf(nu[v], sizeof nu[v], "I/%s", m);
        } else {
            snprintf(I[v], sizeof I[v], "%s^2/(2*%s) + %s*%s", p, m, g, q);
            snprintf(K[v], sizeof K[v], "-eps*(2*%s*(I - %s*%s))^(3/2)/(3*%s*%s)", m, g, q, m, g);
            snprintf(th[v], sizeof th[v], "-%s/%s", p, g);
            snprintf(rq[v], sizeof rq[v], "(I - %s^2*theta^2/(2*%s))/%s", g, m, g);
            snprintf(rp[v], sizeof rp[v], "-%s*theta", g);
            snprintf(nu[v], sizeof nu[v], "1");
        }
    }
    if (free_)
        hl_buf_printf(out, "H = %s^2/(2*m), a free particle, with m = %s\n", p, ms);
    else
        hl_buf_printf(out, "H = %s^2/(2*m) + g*%s, a uniform field, with m = %s, g = %s\n", p, q,
                      ms, gs);
    exact_json_section("form");
    exact_json_string("kind", free_ ? "free particle" : "uniform field");
    exact_json_formula("m", ms, sys);
    if (!free_)
        exact_json_formula("g", gs, sys);
    exact_put_step(out, "step 1: the integral of motion as the action\n");
    exact_put_formula(out, "I", I[0], sys, o);
    exact_put_step(out, "step 2: the momentum from I (eps = +1 or -1, the branch)\n");
    snprintf(pf, sizeof pf, free_ ? "I" : "eps*sqrt(2*m*(I - g*%s))", q);
    exact_put_formula(out, p, pf, sys, o);
    exact_put_step(out, "step 3: the generating function K(q, I) = int p dq\n");
    exact_put_formula(out, "K", K[0], sys, o);
    exact_put_step(out, free_ ? "step 4: the angle theta = dK/dI (it does not come back)\n"
                              : "step 4: the angle theta = dK/dI (in units of time)\n");
    exact_put_formula(out, "theta", th[0], sys, o);
    exact_put_step(out, "step 5: the inverse\n");
    exact_put_formula(out, q, rq[0], sys, o);
    exact_put_formula(out, p, rp[0], sys, o);
    exact_put_step(out, "step 6: the frequency nu = {theta, H}\n");
    exact_put_formula(out, "nu", nu[0], sys, o);
    exact_put_step(out, "step 7: the constant of the action\n");
    exact_put_formula(out, "gamma", I[0], sys, o);
    hl_buf spec;
    hl_buf_init(&spec);
    hl_buf_printf(&spec, "theta = %s; I = %s; %s = %s; %s = %s; nu = %s", th[1], I[1], q, rq[1], p,
                  rp[1], nu[1]);
    int st = steps_check(out, code, sys, o, K[1], th[1], I[1], spec.s, err);
    hl_buf_clear(&spec);
    return st;
}

/* Is H = p^2/(2m) + k q^2/2, m and k free of q and p?  *form, and the texts
 * of m and k in *ms, *ks (malloc'd when the derivatives were taken, whatever
 * *form says: the caller frees them). */
static int oscillator_form(int *form, char **ms, char **ks, hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_pool *pool = hl_system_pool(sys);
    int vq = hl_system_var_q(sys, 0), vp = hl_system_var_p(sys, 0), st;
    hl_alg d, e, z;
    hl_alg_init(&d, ctx);
    hl_alg_init(&e, ctx);
    hl_alg_init(&z, ctx);
    *form = 1;
    /* a = H_pp/2, b = H_qq/2; H_qp, H_q(0), H_p(0) must vanish */
    st = hl_alg_diff(&d, hl_system_H(sys), vp, ctx, err);
    if (st == HL_OK)
        st = hl_alg_diff(&e, &d, vp, ctx, err);
    if (st == HL_OK) {
        hl_alg_set_si(&z, 1, ctx);
        st = hl_alg_div(&z, &z, &e, ctx, err); /* m = 1 / H_pp */
    }
    if (st == HL_OK) {
        *ms = hl_format_alg(&z, ctx, pool, HL_STYLE_TEXT);
        *form = !hl_alg_depends_on(&e, vq, ctx) && !hl_alg_depends_on(&e, vp, ctx);
        st = hl_alg_diff(&e, &d, vq, ctx, err);
        *form = *form && hl_alg_is_zero(&e, ctx);
    }
    if (st == HL_OK)
        st = hl_alg_diff(&d, hl_system_H(sys), vq, ctx, err);
    if (st == HL_OK)
        st = hl_alg_diff(&e, &d, vq, ctx, err);
    if (st == HL_OK) {
        *ks = hl_format_alg(&e, ctx, pool, HL_STYLE_TEXT);
        *form = *form && !hl_alg_depends_on(&e, vq, ctx) && !hl_alg_depends_on(&e, vp, ctx);
        hl_alg_zero(&z, ctx);
        st = hl_alg_subst(&z, &d, 1, &vq, &z, ctx, err); /* H_q at q = 0: no field */
        *form = *form && hl_alg_is_zero(&z, ctx) && !hl_alg_is_zero(&e, ctx);
    }
    hl_alg_clear(&d, ctx);
    hl_alg_clear(&e, ctx);
    hl_alg_clear(&z, ctx);
    return st;
}

/* The seven steps for H = p^2/(2m) + k q^2/2 (H = a p^2 + b q^2), m and k
 * the texts ms, ks. */
static int run_steps_oscillator(hl_buf *out, int *code, hl_system *sys, const cli_opts *o,
                                const char *ms, const char *ks, hl_error *err)
{
    const char *q = hl_system_coord(sys, 0), *p = hl_system_momentum(sys, 0);
    char m[128], k[128];
    snprintf(m, sizeof m, "(%s)", ms);
    snprintf(k, sizeof k, "(%s)", ks);
    hl_buf f;
    hl_buf_init(&f);
#define F(...) (hl_buf_clear(&f), hl_buf_printf(&f, __VA_ARGS__), f.s)
    int unit = strcmp(m, "(1)") == 0 && strcmp(k, "(1)") == 0;
    if (unit)
        hl_buf_printf(out, "H = (%s^2 + %s^2)/2: m = k = 1\n", p, q);
    else
        hl_buf_printf(out, "H = %s^2/(2*m) + k*%s^2/2 with m = %.*s, k = %.*s\n", p, q,
                      (int)strlen(m) - 2, m + 1, (int)strlen(k) - 2, k + 1);
    exact_json_section("form");
    exact_json_string("kind", "oscillator");
    exact_json_formula("m", m, sys);
    exact_json_formula("k", k, sys);
    exact_put_step(out, "step 1: the integral of motion as the action\n");
    exact_put_formula(out, "I",
                      unit ? F("(%s^2 + %s^2)/2", p, q) : F("%s^2/(2*m) + k*%s^2/2", p, q), sys, o);
    exact_put_step(out, "step 2: the momentum from I (eps = +1 or -1, the branch)\n");
    exact_put_formula(
        out, p, unit ? F("eps*sqrt(2*I - %s^2)", q) : F("eps*sqrt(2*m*I - m*k*%s^2)", q), sys, o);
    exact_put_step(out, "step 3: the generating function K(q, I) = int p dq\n");
    exact_put_formula(
        out, "K",
        unit ? F("eps*(%s/2*sqrt(2*I - %s^2) + I*atan(%s/sqrt(2*I - %s^2)))", q, q, q, q)
             : F("eps*(%s/2*sqrt(2*m*I - m*k*%s^2) + I*sqrt(m/k)*atan(%s*sqrt(m*k)/"
                 "sqrt(2*m*I - m*k*%s^2)))",
                 q, q, q, q),
        sys, o);
    /* dK/dI = atan(q/p) on either branch of p; atan2 joins the branches
     * across p = 0 (it differs from atan by a constant, pi, where p < 0) */
    exact_put_step(out, "step 4: the angle theta = dK/dI (in units of time; atan2 continues it "
                        "across p = 0)\n");
    exact_put_formula(
        out, "theta",
        unit ? F("atan2(%s, %s)", q, p) : F("sqrt(m/k)*atan2(sqrt(m*k)*%s, %s)", q, p), sys, o);
    exact_put_step(out, "step 5: the inverse\n");
    exact_put_formula(out, q, unit ? "sqrt(2*I)*sin(theta)" : "sqrt(2*I/k)*sin(sqrt(k/m)*theta)",
                      sys, o);
    exact_put_formula(out, p, unit ? "sqrt(2*I)*cos(theta)" : "sqrt(2*m*I)*cos(sqrt(k/m)*theta)",
                      sys, o);
    exact_put_step(out, "step 6: the frequency nu = {theta, H}\n");
    exact_put_formula(out, "nu", "1", sys, o);
    exact_put_step(out, "step 7: the constant of the action\n");
    exact_put_formula(out, "gamma",
                      unit ? F("(%s^2 + %s^2)/2", p, q) : F("%s^2/(2*m) + k*%s^2/2", p, q), sys, o);
    /* the same formulas with the values of m and k, for the checks */
    char *Ks = hl_xstrdup(F("eps*(%s/2*sqrt(2*%s*I - %s*%s*%s^2) + I*sqrt(%s/%s)*"
                            "atan(%s*sqrt(%s*%s)/sqrt(2*%s*I - %s*%s*%s^2)))",
                            q, m, m, k, q, m, k, q, m, k, m, m, k, q));
    char *th = hl_xstrdup(F("sqrt(%s/%s)*atan2(sqrt(%s*%s)*%s, %s)", m, k, m, k, q, p));
    char *rq = hl_xstrdup(F("sqrt(2*I/%s)*sin(sqrt(%s/%s)*theta)", k, k, m));
    char *rp = hl_xstrdup(F("sqrt(2*%s*I)*cos(sqrt(%s/%s)*theta)", m, k, m));
    hl_buf_clear(&f);
#undef F
    char *spec = NULL;
    {
        hl_buf sb;
        hl_buf_init(&sb);
        hl_buf_printf(&sb, "theta = %s; I = %s^2/(2*%s) + %s*%s^2/2; %s = %s; %s = %s; nu = 1", th,
                      p, m, k, q, q, rq, p, rp);
        spec = hl_buf_take(&sb);
    }
    char Istr[300];
    snprintf(Istr, sizeof Istr, "%s^2/(2*%s) + %s*%s^2/2", p, m, k, q);
    int st = steps_check(out, code, sys, o, Ks, th, Istr, spec, err);
    free(spec), free(Ks), free(th), free(rq), free(rp);
    return st;
}

int exact_run_steps(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err)
{
    if (hl_system_ndof(sys) != 1)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                            "--steps is for 1 degree of freedom (H = p^2/(2m) + k q^2/2)");
    char *ms = NULL, *ks = NULL, *lm = NULL, *lg = NULL;
    int form = 1;
    int st = oscillator_form(&form, &ms, &ks, sys, err);
    if (st == HL_OK && form)
        st = run_steps_oscillator(out, code, sys, o, ms, ks, err);
    else if (st == HL_OK && linear_potential(&lm, &lg, sys))
        st = run_steps_linear(out, code, sys, o, lm, lg, err);
    else if (st == HL_OK)
        st = hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                          "--steps carries out §3 for H = p^2/(2m) + V(q) with V of degree "
                          "<= 2 (oscillator, uniform field, free particle); for another "
                          "quadratic H use the closed form (without --steps)");
    free(ms), free(ks), free(lm), free(lg);
    return st;
}
