/* The catalog's claims measured, not read: for every scheme on the pendulum
 * and on Henon-Heiles (and the oscillator-only ones on the oscillator),
 * expanded to O(D^NC):
 *  - "preserves H" <=> H(Q, P) - H(q, p) vanishes to O(D^NC);
 *  - "symplectic"  <=> the brackets {Z_a, Z_b} of the truncated series are
 *    J + O(D^NC) (truncation changes them only at O(D^NC)).
 * NC = max(7, order + 2): a defect of a scheme of order r starts at
 * D^(r+1) at the latest, inside the window.
 * Both directions are checked, so a flag that is missing or over-claimed
 * fails.  Also the catalog's bookkeeping: unique names, lookup, texts. */
#include "sch.h"

static int NC = 7; /* per scheme: past its order, so an O(D^(order+1)) defect shows */

/* First k < NC with a nonzero D^k coefficient of H(Q,P) - H(q,p), or 0. */
static int energy_defect(hl_system *sys, const hl_series *Z)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), nb = hl_alg_ctx_nbase(ctx), D = hl_system_var_D(sys);
    const char **names = malloc((size_t)nb * sizeof *names);
    hl_series *vals = new_series(nb, ctx);
    hl_alg g;
    hl_alg_init(&g, ctx);
    for (int i = 0; i < nb; i++) {
        names[i] = hl_alg_ctx_name(ctx, i);
        if (i < 2 * N)
            hl_series_set(&vals[i], &Z[i], ctx);
        else if (i == D) {
            hl_series_zero(&vals[i], NC, ctx);
            hl_alg_one(&vals[i].c[1], ctx);
        } else {
            hl_alg_gen(&g, i, ctx);
            hl_series_set_alg(&vals[i], &g, NC, ctx);
        }
    }
    hl_series h;
    hl_series_init(&h, 0, ctx);
    hl_error err;
    int res = -1;
    if (hl_series_eval_expr(&h, hl_system_H_expr(sys), nb, names, vals, NC, ctx, &err) == HL_OK) {
        hl_series_set_alg(&vals[0], hl_system_H(sys), NC, ctx);
        hl_series_sub(&h, &h, &vals[0], ctx);
        int v = hl_series_valuation(&h, ctx);
        res = v >= NC ? 0 : v;
    }
    hl_series_clear(&h, ctx);
    hl_alg_clear(&g, ctx);
    free_series(vals, nb, ctx);
    free(names);
    return res;
}

/* First k < NC where some bracket {Z_a, Z_b} differs from J at D^k, or 0. */
static int symplectic_defect(hl_system *sys, const hl_series *Z)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys), M = 2 * N, D = hl_system_var_D(sys), first = 0;
    hl_alg *z = hl_alg_vec_new(M, ctx);
    hl_alg br, c;
    hl_alg_init(&br, ctx);
    hl_alg_init(&c, ctx);
    hl_error err;
    for (int a = 0; a < M; a++)
        hl_series_to_alg(&z[a], &Z[a], D, ctx);
    for (int a = 0; a < M; a++)
        for (int b = a + 1; b < M; b++) {
            if (hl_bracket(&br, &z[a], &z[b], sys, &err) != HL_OK)
                return -1;
            for (int k = 0; k < NC; k++) {
                if (hl_alg_coeff(&c, &br, D, k, ctx, &err) != HL_OK)
                    return -1;
                int want = k == 0 && b == a + N; /* {q_j, p_j} = 1 */
                hl_alg w;
                hl_alg_init(&w, ctx);
                hl_alg_set_si(&w, want, ctx);
                if (!hl_alg_equal(&c, &w, ctx) && (first == 0 || k < first))
                    first = k == 0 ? -1 : k;
                hl_alg_clear(&w, ctx);
            }
        }
    hl_alg_vec_free(z, M, ctx);
    hl_alg_clear(&br, ctx);
    hl_alg_clear(&c, ctx);
    return first;
}

static void claims(hl_system *sys, const hl_scheme_info *info, const char *label)
{
    hl_scheme *s;
    hl_error err;
    NC = info->order + 2 > 7 ? info->order + 2 : 7;
    if (hl_scheme_new(&s, info->name, 0, sys, &err) != HL_OK) {
        CHECK_MSG(0, "%s on %s: %s", info->name, label, err.msg);
        return;
    }
    hl_series *Z = expand(s, NC);
    CHECK_MSG(Z != NULL, "%s", info->name);
    if (Z) {
        int e = energy_defect(sys, Z), y = symplectic_defect(sys, Z);
        int says_h = (info->flags & HL_SCHEME_PRESERVES_H) != 0;
        int says_y = (info->flags & HL_SCHEME_SYMPLECTIC) != 0;
        printf("%-20s %-13s first defect (0 = none to D^%d): energy D^%d, symplectic D^%d\n",
               info->name, label, NC - 1, e, y);
        CHECK_MSG(e >= 0 && (e == 0) == says_h, "%s on %s: energy defect at D^%d, flag %d",
                  info->name, label, e, says_h);
        CHECK_MSG(y >= 0 && (y == 0) == says_y, "%s on %s: symplectic defect at D^%d, flag %d",
                  info->name, label, y, says_y);
        free_series(Z, 2 * s->N, hl_system_ctx(sys));
    }
    hl_scheme_free(s);
}

int main(void)
{
    hl_system *pend = make_system("p^2/2 - cos(q)");
    hl_system *hh = make_system("(px^2 + py^2)/2 + (x^2 + y^2)/2 + x^2*y - y^3/3");
    hl_system *osc = make_system("(p^2 + x^2)/2");
    int n = hl_scheme_catalog_count();
    for (int i = 0; i < n; i++) {
        const hl_scheme_info *info = hl_scheme_catalog(i);
        CHECK(hl_scheme_lookup(info->name) == info);
        CHECK(info->description && strlen(info->description) > 10);
        for (int j = 0; j < i; j++)
            CHECK(strcmp(hl_scheme_catalog(j)->name, info->name) != 0);
        if (info->order == HL_SCHEME_ORDER_N) { /* the family lieN: some members */
            static const char *const members[] = {"lie1", "lie4"};
            for (int m = 0; m < 2; m++) {
                const hl_scheme_info *mi = hl_scheme_lookup(members[m]);
                CHECK(mi != NULL && mi->order == members[m][3] - '0');
                if (mi != NULL)
                    claims(pend, mi, "pendulum");
            }
            continue;
        }
        if (info->flags & (HL_SCHEME_OSCILLATOR | HL_SCHEME_QUADRATIC)) {
            claims(osc, info, "oscillator");
            continue;
        }
        claims(pend, info, "pendulum");
        claims(hh, info, "henon-heiles");
    }
    CHECK(hl_scheme_catalog(n) == NULL && hl_scheme_lookup("nope") == NULL);
    CHECK(hl_scheme_lookup("lie0") == NULL && hl_scheme_lookup("lie21") == NULL &&
          hl_scheme_lookup("lie20") != NULL && hl_scheme_lookup("lie20")->order == 20);
    CHECK(hl_scheme_text("rk4") == NULL && hl_scheme_text("avf") != NULL);
    hl_system_free(pend);
    hl_system_free(hh);
    hl_system_free(osc);
    return HL_TEST_END();
}
