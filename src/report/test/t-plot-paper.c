/* The paper's 14 figures (§4: oscillator H = (p²+x²)/2, x(0) = 1, p(0) = 0,
 * Δ = 0.1, t in [0, 20]; exact solution a red line, the scheme blue dots),
 * drawn from closed forms and the three iteration maps written out here:
 *   exact     X = x cos Δ + p sin Δ,            P = p cos Δ − x sin Δ
 *   Euler     X = x + Δ p,                      P = p − Δ x
 *   disc.grad X = (4x + 4Δp − Δ²x) / (4 + Δ²),  P = (4p − 4Δx − Δ²p) / (4 + Δ²)
 * Each figure is written as PNG, SVG and PDF (timed; the times are printed),
 * and rendered into memory, where the colours it must show are counted.
 * Set HAMLIE_FIGURE_DIR to keep the files there; otherwise a temporary
 * directory is used and removed. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "hamlie/plot.h"
#include "hl_test.h"

#define W 800
#define H 600
#define D 0.1
#define NS 201   /* scheme points: t = nΔ, n = 0..200 */
#define NC 2001  /* exact curve samples, dt = 0.01 */

enum { EXACT, EULER, DISGRA };

static double ts[NS], xs[3][NS], ps[3][NS]; /* the three schemes */
static double tc[NC], xc[NC], pc[NC];       /* exact curve */

static void run_schemes(void)
{
    double c = cos(D), s = sin(D), q = 4 + D * D;
    for (int k = 0; k < 3; k++) {
        xs[k][0] = 1;
        ps[k][0] = 0;
    }
    for (int n = 0; n < NS; n++)
        ts[n] = n * D;
    for (int n = 0; n + 1 < NS; n++) {
        double x = xs[EXACT][n], p = ps[EXACT][n];
        xs[EXACT][n + 1] = x * c + p * s;
        ps[EXACT][n + 1] = p * c - x * s;
        x = xs[EULER][n], p = ps[EULER][n];
        xs[EULER][n + 1] = x + D * p;
        ps[EULER][n + 1] = p - D * x;
        x = xs[DISGRA][n], p = ps[DISGRA][n];
        xs[DISGRA][n + 1] = (4 * x + 4 * D * p - D * D * x) / q;
        ps[DISGRA][n + 1] = (4 * p - 4 * D * x - D * D * p) / q;
    }
    for (int i = 0; i < NC; i++) {
        tc[i] = 20.0 * i / (NC - 1);
        xc[i] = cos(tc[i]);
        pc[i] = -sin(tc[i]);
    }
}

static int is_red(const unsigned char *p) { return p[0] > 180 && p[1] < 110 && p[2] < 110; }
static int is_blue(const unsigned char *p) { return p[2] > 180 && p[0] < 110 && p[1] < 110; }
static int is_green(const unsigned char *p) { return p[1] > 120 && p[0] < 80 && p[2] < 80; }
static int is_black(const unsigned char *p) { return p[0] < 60 && p[1] < 60 && p[2] < 60; }

typedef struct need {
    int red, blue, black, green; /* pixels of each the figure must have (at least) */
} need;

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static long file_size(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 ? (long)sb.st_size : -1;
}

static const char *outdir;
static char tmpdir[] = "/tmp/hl-paper-XXXXXX";
static double total_time;

/* Write, check the files, render, count colours; then free the figure. */
static void finish(hl_figure *f, const char *name, need nd)
{
    hl_error err;
    char base[512], file[600];
    snprintf(base, sizeof base, "%s/%s", outdir, name);
    double t0 = now();
    hl_status st = hl_figure_write(f, base, "png,svg,pdf", &err);
    double dt = now() - t0;
    total_time += dt;
    CHECK_MSG(st == HL_OK, "%s: %s", name, err.msg);
    long sz[3];
    const char *ext[3] = {"png", "svg", "pdf"};
    for (int k = 0; k < 3; k++) {
        snprintf(file, sizeof file, "%s.%s", base, ext[k]);
        sz[k] = file_size(file);
        CHECK_MSG(sz[k] > 1000, "%s: %ld bytes", file, sz[k]);
    }
    printf("%-16s png+svg+pdf %7.1f ms  (%ld, %ld, %ld bytes)\n", name, 1e3 * dt, sz[0],
           sz[1], sz[2]);

    unsigned char *img = malloc((size_t)W * H * 3);
    CHECK(hl_figure_render_rgb(f, W, H, img, NULL, &err) == HL_OK);
    long red = 0, blue = 0, black = 0, green = 0, ink = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) {
        const unsigned char *p = img + 3 * i;
        red += is_red(p), blue += is_blue(p), black += is_black(p), green += is_green(p);
        ink += !(p[0] == 255 && p[1] == 255 && p[2] == 255);
    }
    CHECK_MSG(red >= nd.red && blue >= nd.blue && black >= nd.black && green >= nd.green &&
                  ink > 10000,
              "%s: red %ld blue %ld black %ld green %ld ink %ld", name, red, blue, black,
              green, ink);
    /* colours the figure does not use are absent (legend included) */
    if (nd.red == 0)
        CHECK_MSG(red == 0, "%s: %ld red pixels", name, red);
    if (nd.green == 0)
        CHECK_MSG(green == 0, "%s: %ld green pixels", name, green);
    free(img);
    hl_figure_free(f);
}

static hl_figure *two(const char *title, const char *yl, const char *xl, const double *xe,
                      const double *ye, size_t ne, const double *xn, const double *yn,
                      const char *scheme)
{
    hl_error err;
    hl_figure *f = hl_figure_new(title, xl, yl);
    CHECK(hl_figure_add(f, ne, xe, ye, HL_DRAW_LINE, HL_COLOR_RED, "exact", &err) == HL_OK);
    CHECK(hl_figure_add(f, NS, xn, yn, HL_DRAW_DOTS, HL_COLOR_BLUE, scheme, &err) == HL_OK);
    return f;
}

static void common_figures(int k, const char *prefix, const char *scheme)
{
    char name[64], title[128];
    need nd = {500, 2000, 0, 0};
    hl_figure *f;

    snprintf(title, sizeof title, "%s: phase space, #gD = 0.1", scheme);
    f = two(title, "p", "x", xc, pc, NC, xs[k], ps[k], scheme);
    hl_figure_set_equal_aspect(f, 1);
    snprintf(name, sizeof name, "%s-phase", prefix);
    finish(f, name, nd);

    snprintf(title, sizeof title, "%s: x(t)", scheme);
    f = two(title, "x", "t", tc, xc, NC, ts, xs[k], scheme);
    hl_figure_set_legend(f, HL_LEGEND_BOTTOM_RIGHT);
    snprintf(name, sizeof name, "%s-x", prefix);
    finish(f, name, nd);

    snprintf(title, sizeof title, "%s: p(t)", scheme);
    f = two(title, "p", "t", tc, pc, NC, ts, ps[k], scheme);
    hl_figure_set_legend(f, HL_LEGEND_BOTTOM_RIGHT);
    snprintf(name, sizeof name, "%s-p", prefix);
    finish(f, name, nd);
}

/* σ(x,p) at t = nΔ against the exact solution. */
static void sigma_xp(double *out, int k)
{
    for (int n = 0; n < NS; n++) {
        double dx = cos(ts[n]) - xs[k][n], dp = -sin(ts[n]) - ps[k][n];
        out[n] = dx * dx + dp * dp;
    }
}

static void test_exact(void)
{
    hl_error err;
    double sg[NS];
    common_figures(EXACT, "exact", "exact scheme");
    sigma_xp(sg, EXACT);
    hl_figure *f = hl_figure_new("exact scheme: error in phase space", "t", "#gs(x,p)");
    hl_figure_set_yscale(f, HL_AXIS_AUTO);
    CHECK(hl_figure_add(f, NS, ts, sg, HL_DRAW_LINE, HL_COLOR_BLACK, "#gs(x,p)", &err) ==
          HL_OK);
    hl_figure_set_legend(f, HL_LEGEND_BOTTOM_RIGHT);
    finish(f, "exact-error", (need){0, 0, 300, 0});
}

static void test_euler(void)
{
    hl_error err;
    double rc[NC], rn[NS], sg[NS], si[NS];
    common_figures(EULER, "euler", "Euler");

    /* the invariant x/p: poles where p = 0; a clipped range, no line across */
    for (int i = 0; i < NC; i++)
        rc[i] = xc[i] / pc[i];
    for (int n = 0; n < NS; n++)
        rn[n] = xs[EULER][n] / ps[EULER][n];
    hl_figure *f = two("Euler: the invariant x/p", "x/p", "t", tc, rc, NC, ts, rn, "Euler");
    CHECK(hl_figure_set_yclip(f, -10, 10, &err) == HL_OK);
    hl_figure_set_legend(f, HL_LEGEND_NONE);
    hl_plot_frame fr;
    unsigned char *img = malloc((size_t)W * H * 3);
    CHECK(hl_figure_render_rgb(f, W, H, img, &fr, &err) == HL_OK);
    /* the exact curve's poles t = kπ: no red in a ±4 px band (the curve
     * leaves |x/p| <= 10 at |t − kπ| = atan(0.1) ≈ 0.1, about 4 px here) */
    for (int k = 1; k <= 6; k++) {
        double px0, py0, px1, py1;
        CHECK(hl_plot_frame_pixel(&fr, W, H, k * M_PI, 9.5, &px0, &py0));
        CHECK(hl_plot_frame_pixel(&fr, W, H, k * M_PI, -9.5, &px1, &py1));
        long red = 0;
        for (int y = (int)py0; y <= (int)py1; y++)
            for (int x = (int)px0 - 2; x <= (int)px0 + 2; x++)
                red += is_red(img + 3 * ((size_t)y * W + x));
        CHECK_MSG(red == 0, "%ld red pixels across the pole t = %dπ", red, k);
    }
    free(img);
    finish(f, "euler-inv", (need){500, 1000, 0, 0});

    sigma_xp(sg, EULER);
    for (int n = 0; n < NS; n++) {
        double d = cos(ts[n]) / -sin(ts[n]) - rn[n];
        si[n] = d * d;
    }
    f = hl_figure_new("Euler: errors", "t", "#gs");
    hl_figure_set_yscale(f, HL_AXIS_AUTO);
    CHECK(hl_figure_add(f, NS, ts, sg, HL_DRAW_LINE, HL_COLOR_BLACK, "#gs(x,p)", &err) ==
          HL_OK);
    CHECK(hl_figure_add(f, NS, ts, si, HL_DRAW_LINE, HL_COLOR_GREEN, "#gs(x/p)", &err) ==
          HL_OK);
    hl_figure_set_legend(f, HL_LEGEND_BOTTOM_RIGHT);
    finish(f, "euler-error", (need){0, 0, 300, 300});
}

static void test_disgra(void)
{
    hl_error err;
    double hc[NC], hn[NS], sg[NS], sh[NS];
    common_figures(DISGRA, "disgra", "discrete gradient");
    for (int i = 0; i < NC; i++)
        hc[i] = 0.5 * (xc[i] * xc[i] + pc[i] * pc[i]);
    for (int n = 0; n < NS; n++)
        hn[n] = 0.5 * (xs[DISGRA][n] * xs[DISGRA][n] + ps[DISGRA][n] * ps[DISGRA][n]);
    hl_figure *f = two("discrete gradient: H(t)", "H", "t", tc, hc, NC, ts, hn,
                       "discrete gradient");
    finish(f, "disgra-inv", (need){50, 2000, 0, 0}); /* dots hide most of the line */

    sigma_xp(sg, DISGRA);
    for (int n = 0; n < NS; n++) {
        double d = 1 - 2 * hn[n]; /* p(t)² + x(t)² = 1 exactly */
        sh[n] = d * d;
    }
    f = hl_figure_new("discrete gradient: errors", "t", "#gs");
    hl_figure_set_yscale(f, HL_AXIS_AUTO);
    CHECK(hl_figure_add(f, NS, ts, sg, HL_DRAW_LINE, HL_COLOR_BLACK, "#gs(x,p)", &err) ==
          HL_OK);
    CHECK(hl_figure_add(f, NS, ts, sh, HL_DRAW_LINE, HL_COLOR_GREEN, "#gs(2H)", &err) ==
          HL_OK);
    hl_figure_set_legend(f, HL_LEGEND_BOTTOM_RIGHT);
    finish(f, "disgra-error", (need){0, 0, 300, 100});
}

int main(void)
{
    outdir = getenv("HAMLIE_FIGURE_DIR");
    if (outdir == NULL || *outdir == '\0') {
        outdir = mkdtemp(tmpdir);
        CHECK(outdir != NULL);
        if (outdir == NULL)
            return HL_TEST_END();
    }
    run_schemes();
    test_exact();
    test_euler();
    test_disgra();
    printf("14 figures x 3 formats: %.1f ms\n", 1e3 * total_time);
    if (outdir == tmpdir) {
        const char *names[] = {"exact-phase", "exact-x", "exact-p", "exact-error",
                               "euler-phase", "euler-x", "euler-p", "euler-inv",
                               "euler-error", "disgra-phase", "disgra-x", "disgra-p",
                               "disgra-inv", "disgra-error"};
        const char *ext[] = {"png", "svg", "pdf"};
        char file[600];
        for (int i = 0; i < 14; i++)
            for (int k = 0; k < 3; k++) {
                snprintf(file, sizeof file, "%s/%s.%s", tmpdir, names[i], ext[k]);
                CHECK(unlink(file) == 0);
            }
        CHECK(rmdir(tmpdir) == 0);
    }
    return HL_TEST_END();
}
