/* The exact flow of a quadratic H in closed form (linear_flow.c):
 *  - the images equal flows solved by hand: the oscillator's rotation, the
 *    anisotropic oscillator (frequencies 1 and 2), the hyperbolic
 *    H = (p^2 - x^2)/2 (cosh, sinh), the uniform field (q + D p - g D^2/2),
 *    the free particle, and symbolic m, k;
 *  - their D-expansion equals the Lie series exp(D g) z to D^10 (hl_lie_series,
 *    an independent computation) also where no hand form is written: a
 *    mixed x*p term, a 2-dof H with parameters and linear terms;
 *  - two steps of D are one step of 2D (exact composition) and the map is
 *    canonical; the oscillator's map composed n times is the flow at nD;
 *  - a non-quadratic H, and coupled pairs with spiral modes (complex
 *    eigenvalues of A^2: no closed form here), are refused, naming the
 *    reason (coupled pairs with a closed form: t-linear-coupled). */
#include "sch.h"

#define ORDER 10

static void images_of(hl_alg *img, hl_system *sys)
{
    hl_error err;
    int st = hl_scheme_linear_flow(img, sys, &err);
    CHECK_MSG(st == HL_OK, "linear flow: %s", err.msg);
}

/* The images against hand-solved formulas, in the order q_1..q_N, p_1..p_N. */
static void check_hand(const char *H, const char *const *want)
{
    hl_system *sys = make_system(H);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int M = 2 * hl_system_ndof(sys);
    hl_alg *img = hl_alg_vec_new(M, ctx), w;
    hl_alg_init(&w, ctx);
    hl_error err;
    images_of(img, sys);
    for (int i = 0; i < M; i++) {
        int st = hl_system_read(&w, sys, want[i], &err);
        CHECK_MSG(st == HL_OK && hl_alg_equal(&img[i], &w, ctx), "%s: image %d is not %s", H,
                  i, want[i]);
    }
    hl_alg_clear(&w, ctx);
    hl_alg_vec_free(img, M, ctx);
    hl_system_free(sys);
}

/* The catalog's "exact" expanded in D equals exp(D g) z to D^ORDER. */
static void check_lie(const char *H)
{
    hl_system *sys = make_system(H);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int M = 2 * hl_system_ndof(sys);
    hl_scheme *s = NULL;
    hl_error err;
    int st = hl_scheme_new(&s, "exact", 0, sys, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", H, err.msg);
    hl_series *Z = st == HL_OK ? expand(s, ORDER + 1) : NULL;
    CHECK(Z != NULL);
    for (int i = 0; Z != NULL && i < M; i++) {
        hl_alg z, lie;
        hl_series ls;
        hl_alg_init(&z, ctx);
        hl_alg_init(&lie, ctx);
        hl_series_init(&ls, 0, ctx);
        hl_alg_gen(&z, i, ctx);
        int ok = hl_lie_series(&lie, &z, ORDER, sys, &err) == HL_OK &&
                 hl_series_from_alg(&ls, &lie, hl_system_var_D(sys), ORDER + 1, ctx, &err) ==
                     HL_OK;
        for (int k = 0; ok && k <= ORDER; k++)
            ok = hl_alg_equal(&Z[i].c[k], &ls.c[k], ctx);
        CHECK_MSG(ok, "%s: component %d differs from the Lie series", H, i);
        hl_series_clear(&ls, ctx);
        hl_alg_clear(&z, ctx);
        hl_alg_clear(&lie, ctx);
    }
    if (Z)
        free_series(Z, M, ctx);
    hl_scheme_free(s);
    hl_system_free(sys);
}

/* psi_D o psi_D = psi_2D exactly, and the map is canonical. */
static void check_group(const char *H)
{
    hl_system *sys = make_system(H);
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int M = 2 * hl_system_ndof(sys), iD = hl_system_var_D(sys);
    hl_alg *img = hl_alg_vec_new(M, ctx), *two = hl_alg_vec_new(M, ctx),
           *br = hl_alg_vec_new(M * M, ctx), twoD, r;
    hl_alg_init(&twoD, ctx);
    hl_alg_init(&r, ctx);
    int *vars = malloc((size_t)M * sizeof *vars);
    for (int i = 0; i < M; i++)
        vars[i] = i;
    hl_error err;
    images_of(img, sys);
    hl_alg_gen(&twoD, iD, ctx);
    hl_alg_add(&twoD, &twoD, &twoD, ctx);
    for (int i = 0; i < M; i++) {
        int ok = hl_alg_subst(&two[i], &img[i], M, vars, img, ctx, &err) == HL_OK &&
                 hl_alg_subst(&r, &img[i], 1, &iD, &twoD, ctx, &err) == HL_OK &&
                 hl_alg_equal(&two[i], &r, ctx);
        CHECK_MSG(ok, "%s: two steps of D are not one of 2D (component %d)", H, i);
    }
    int canonical = 0;
    CHECK(hl_check_canonical(&canonical, br, img, sys, &err) == HL_OK && canonical);
    free(vars);
    hl_alg_clear(&twoD, ctx);
    hl_alg_clear(&r, ctx);
    hl_alg_vec_free(img, M, ctx);
    hl_alg_vec_free(two, M, ctx);
    hl_alg_vec_free(br, M * M, ctx);
    hl_system_free(sys);
}

/* The oscillator's map applied n times (composed symbolically) is the
 * flow at nD, n = 2..5: x(nD) = x cos nD + p sin nD exactly (issue 6). */
static void check_power(void)
{
    hl_system *s = make_system("(p^2+x^2)/2");
    hl_alg_ctx *ctx = hl_system_ctx(s);
    hl_error err;
    int vars[2] = {hl_system_var_q(s, 0), hl_system_var_p(s, 0)};
    hl_alg *im = hl_alg_vec_new(2, ctx), *pw = hl_alg_vec_new(2, ctx), *w = hl_alg_vec_new(2, ctx);
    hl_alg t[2];
    hl_alg_init(&t[0], ctx);
    hl_alg_init(&t[1], ctx);
    images_of(im, s);
    hl_alg_set(&pw[0], &im[0], ctx);
    hl_alg_set(&pw[1], &im[1], ctx);
    for (int n = 2; n <= 5; n++) {
        for (int i = 0; i < 2; i++) /* pw o im: pw with (x, p) -> im */
            CHECK(hl_alg_subst(&t[i], &pw[i], 2, vars, im, ctx, &err) == HL_OK);
        hl_alg_swap(&pw[0], &t[0], ctx);
        hl_alg_swap(&pw[1], &t[1], ctx);
        char map[200];
        snprintf(map, sizeof map, "X = x*cos(%d*D) + p*sin(%d*D); P = p*cos(%d*D) - x*sin(%d*D)",
                 n, n, n, n);
        CHECK(hl_system_read_map(w, s, map, &err) == HL_OK);
        CHECK_MSG(hl_alg_equal(&pw[0], &w[0], ctx) && hl_alg_equal(&pw[1], &w[1], ctx),
                  "%d steps of D != x(%dD)", n, n);
    }
    hl_alg_clear(&t[0], ctx);
    hl_alg_clear(&t[1], ctx);
    hl_alg_vec_free(im, 2, ctx);
    hl_alg_vec_free(pw, 2, ctx);
    hl_alg_vec_free(w, 2, ctx);
    hl_system_free(s);
}

static void check_refused(const char *H, int want, const char *msg)
{
    hl_system *sys = make_system(H);
    int M = 2 * hl_system_ndof(sys);
    hl_alg *img = hl_alg_vec_new(M, hl_system_ctx(sys));
    hl_error err;
    int st = hl_scheme_linear_flow(img, sys, &err);
    CHECK_MSG(st == want && strstr(err.msg, msg) != NULL, "%s: status %d, '%s'", H, st,
              st == HL_OK ? "" : err.msg);
    hl_alg_vec_free(img, M, hl_system_ctx(sys));
    hl_system_free(sys);
}

int main(void)
{
    static const char *const osc[] = {"x*cos(D) + p*sin(D)", "p*cos(D) - x*sin(D)"};
    check_hand("(p^2+x^2)/2", osc);
    static const char *const aniso[] = {"x*cos(D) + px*sin(D)", "y*cos(2*D) + py*sin(2*D)/2",
                                        "px*cos(D) - x*sin(D)", "py*cos(2*D) - 2*y*sin(2*D)"};
    check_hand("(px^2+py^2)/2 + (x^2+4*y^2)/2", aniso);
    static const char *const hyper[] = {"x*cosh(D) + p*sinh(D)", "p*cosh(D) + x*sinh(D)"};
    check_hand("(p^2-x^2)/2", hyper);
    static const char *const field[] = {"q + D*p - g*D^2/2", "p - g*D"};
    check_hand("p^2/2 + g*q", field);
    static const char *const free_[] = {"q + D*p/m", "p"};
    check_hand("p^2/(2*m) + 0*q", free_); /* 0*q: q names the coordinate */
    static const char *const mk[] = {"x*cos(sqrt(k/m)*D) + p*sin(sqrt(k/m)*D)/sqrt(k*m)",
                                     "p*cos(sqrt(k/m)*D) - x*sqrt(k*m)*sin(sqrt(k/m)*D)"};
    check_hand("p^2/(2*m) + k*x^2/2", mk);

    const char *lie[] = {"(p^2+x^2)/2", "(p^2-x^2)/2", "p^2/2 + x*p + x^2", "p^2/2 + x*p",
                         "(px^2+py^2)/2 + (k*x^2 + y^2)/2 + a*x + b*py", "p^2/2 + g*q"};
    for (size_t i = 0; i < sizeof lie / sizeof *lie; i++)
        check_lie(lie[i]);

    const char *group[] = {"(p^2+x^2)/2", "(p^2-x^2)/2", "(px^2+py^2)/2 + (x^2+4*y^2)/2",
                           "p^2/2 + g*q", "p^2/2 + x*p + x^2"};
    for (size_t i = 0; i < sizeof group / sizeof *group; i++)
        check_group(group[i]);

    check_power();
    check_refused("p^2/2 - cos(q)", HL_EINVAL, "not quadratic");
    check_refused("(px^2-py^2)/2 + x*y", HL_EUNSUP, "complex eigenvalues");
    return HL_TEST_END();
}
