/* The paper's 14 figures (paper.h: hl_paper_figures, hl_paper_figure_get).
 *
 * 1. Every figure's data is checked by figures.c against the scheme's closed
 *    form: the deviation must be under its tolerance, and the tolerance must
 *    be small enough to tell the scheme from its nearest wrong alternative
 *    (the discrete gradient from the exact rotation, Euler from a rotation
 *    without growth), computed here.
 * 2. The images: figures are rendered into memory and the pixels are looked
 *    at where the closed forms put the curves: the red unit circle in the
 *    exact phase portrait, Euler's blue dots on the spiral r_n = 1.01^(n/2),
 *    angle n atan(0.1), the discrete gradient's dots at angle n 2 atan(0.05),
 *    no red line across the poles of x/p, the error curves on a log axis at
 *    their closed-form heights.
 * 3. The files: all 14 x png,svg,pdf written (timed), sizes and magic
 *    numbers; a bad format list writes nothing; a bad directory is HL_EIO. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "hamlie/paper.h"
#include "hamlie/plot.h"
#include "hl_test.h"

#define W 640
#define H 480
#define D 0.1

static const char *const names[HL_PAPER_NFIGURES] = {
    "exact-phase",  "exact-x", "exact-p", "exact-error", "euler-phase",
    "euler-x",      "euler-p", "euler-inv", "euler-error", "disgra-phase",
    "disgra-x",     "disgra-p", "disgra-inv", "disgra-error"};

#include "hl_pixels.h"

static int index_of(const char *name)
{
    for (int i = 0; i < HL_PAPER_NFIGURES; i++)
        if (strcmp(names[i], name) == 0)
            return i;
    return -1;
}

/* Render figure `name` into img (W x H); returns its info. */
static hl_paper_figure render(unsigned char *img, hl_plot_frame *fr, const char *name)
{
    hl_error err;
    hl_figure *f = NULL;
    hl_paper_figure info;
    memset(&info, 0, sizeof info);
    int i = index_of(name);
    CHECK(i >= 0);
    CHECK_MSG(hl_paper_figure_get(&f, &info, i, &err) == HL_OK, "%s: %s", name, err.msg);
    memset(img, 0, (size_t)W * H * 3);
    if (f != NULL)
        CHECK_MSG(hl_figure_render_rgb(f, W, H, img, fr, &err) == HL_OK, "%s: %s", name,
                  err.msg);
    CHECK_STR(info.name, name);
    hl_figure_free(f);
    return info;
}

static long count(const unsigned char *img, color_fn fn)
{
    long n = 0;
    for (size_t i = 0; i < (size_t)W * H; i++)
        n += fn(img + 3 * i);
    return n;
}

/* ---- 1. the checks ---------------------------------------------------------- */

static void test_checks(void)
{
    hl_paper_figure figs[HL_PAPER_NFIGURES];
    hl_error err;
    memset(figs, 0, sizeof figs);
    CHECK_MSG(hl_paper_figures(figs, NULL, NULL, &err) == HL_OK, "%s", err.msg);
    for (int i = 0; i < HL_PAPER_NFIGURES; i++) {
        CHECK_STR(figs[i].name, names[i]);
        CHECK(figs[i].caption != NULL && figs[i].check_what != NULL);
        CHECK_MSG(isfinite(figs[i].check) && figs[i].check >= 0 &&
                      figs[i].check <= figs[i].check_tol,
                  "%s: check %.3g > tol %.3g (%s)", names[i], figs[i].check, figs[i].check_tol,
                  figs[i].check_what);
        printf("%-13s check %.3g (tol %.0g): %s\n", names[i], figs[i].check, figs[i].check_tol,
               figs[i].check_what);
    }
    /* The tolerances can fail: the nearest wrong closed forms are far away.
     * Discrete gradient vs the exact rotation: |z_200| angle differs by
     * 200 (D - 2 atan(D/2)) ~ 0.0167; Euler vs a rotation by atan(D) with
     * no growth: relative 1 - 1.01^(-100) ~ 0.63; vs a rotation by D with the
     * growth: 200 (D - atan D) ~ 0.066. */
    double dg_vs_exact = 2 * sin(100 * (D - 2 * atan(D / 2)));
    double eu_vs_growth = 1 - pow(1 + D * D, -100);
    double eu_vs_angle = 2 * sin(100 * (D - atan(D)));
    for (int i = 0; i < HL_PAPER_NFIGURES; i++) {
        CHECK_MSG(figs[i].check_tol < 1e-3 * fmin(dg_vs_exact, fmin(eu_vs_growth, eu_vs_angle)),
                  "%s: tolerance %g cannot tell the scheme from a wrong one", names[i],
                  figs[i].check_tol);
    }
    /* The exact scheme's checks are at round-off. */
    CHECK(figs[0].check < 1e-13 && figs[3].check < 1e-13);
    /* Euler's check is of 2H_n = (1+D^2)^n: named so in its text. */
    CHECK(strstr(figs[4].check_what, "(1+D^2)^n") != NULL);
    CHECK(strstr(figs[9].check_what, "2 atan(D/2)") != NULL);

    hl_figure *f = (hl_figure *)1;
    CHECK(hl_paper_figure_get(&f, NULL, HL_PAPER_NFIGURES, &err) == HL_EINVAL && f == NULL);
    CHECK(hl_paper_figure_get(&f, NULL, -1, &err) == HL_EINVAL);
}

/* ---- 2. the images ---------------------------------------------------------- */

static void test_phase_images(unsigned char *img)
{
    hl_plot_frame fr;
    /* exact: the red circle through (±1, 0), (0, ±1); the dots hide the
     * circle where they sit (every 0.1 rad), so look at a 7x7 box */
    render(img, &fr, "exact-phase");
    CHECK(count(img, is_red) > 200 && count(img, is_blue) > 1000);
    const double pts[][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}, {M_SQRT1_2, M_SQRT1_2}};
    for (int k = 0; k < 5; k++) {
        int red = near(img, &fr, pts[k][0], pts[k][1], 3, is_red);
        int blue = near(img, &fr, pts[k][0], pts[k][1], 3, is_blue);
        CHECK_MSG(red + blue > 3, "exact-phase: no curve at (%g, %g): red %d blue %d", pts[k][0],
                  pts[k][1], red, blue);
    }
    /* the square of equal aspect: x and y units of the same pixel length */
    double ax, ay, bx, by, cx, cy;
    CHECK(hl_plot_frame_pixel(&fr, W, H, 0, 0, &ax, &ay));
    CHECK(hl_plot_frame_pixel(&fr, W, H, 1, 0, &bx, &by));
    CHECK(hl_plot_frame_pixel(&fr, W, H, 0, 1, &cx, &cy));
    CHECK_MSG(fabs((bx - ax) - (ay - cy)) < 2, "not equal aspect: %g vs %g", bx - ax, ay - cy);
    /* nothing far off the circle: the origin and (0.5, 0) are white */
    CHECK(near(img, &fr, 0.5, 0.0, 3, is_red) == 0 && near(img, &fr, 0.5, 0.0, 3, is_blue) == 0);

    /* Euler: blue dots on the closed-form spiral, none on the unit circle far
     * from the start (at n = 150 the radius is 1.01^75 = 2.11) */
    render(img, &fr, "euler-phase");
    for (int n = 50; n <= 150; n += 50) {
        double r = pow(1 + D * D, 0.5 * n), a = n * atan(D);
        int blue = near(img, &fr, r * cos(a), -r * sin(a), 2, is_blue);
        CHECK_MSG(blue >= 5, "euler-phase: no dot at n = %d (%d blue pixels)", n, blue);
        /* where the exact scheme would be: nothing blue */
        blue = near(img, &fr, cos(n * D), -sin(n * D), 2, is_blue);
        CHECK_MSG(blue == 0, "euler-phase: a dot on the circle at t = %g", n * D);
    }
    /* the red circle is there too (at (0, 1), where no Euler dot is) */
    CHECK(near(img, &fr, 0, 1, 2, is_red) > 0);

    /* discrete gradient: the dots at angle n 2 atan(D/2) on the unit circle */
    render(img, &fr, "disgra-phase");
    for (int n = 25; n <= 200; n += 25) {
        double a = n * 2 * atan(D / 2);
        CHECK_MSG(near(img, &fr, cos(a), -sin(a), 2, is_blue) >= 5, "disgra-phase: n = %d", n);
    }
}

static void test_time_images(unsigned char *img)
{
    hl_plot_frame fr;
    /* Euler x(t): dots at (nD, r_n cos(n atan D)), the red line at cos t */
    render(img, &fr, "euler-x");
    for (int n = 40; n <= 200; n += 40) {
        double r = pow(1 + D * D, 0.5 * n), a = n * atan(D);
        CHECK_MSG(near(img, &fr, n * D, r * cos(a), 2, is_blue) >= 5, "euler-x: n = %d", n);
    }
    CHECK(near(img, &fr, 4.5, cos(4.5), 2, is_red) + near(img, &fr, 4.5, cos(4.5), 2, is_blue) >
          0);
    /* discrete gradient p(t) at t = 20: the dot is late: -sin(200 2 atan(D/2))
     * = -0.93, where the exact p(20) = -0.91: look for blue at the former */
    render(img, &fr, "disgra-p");
    double a = 200 * 2 * atan(D / 2);
    CHECK(near(img, &fr, 20, -sin(a), 2, is_blue) >= 5);

    /* Euler x/p: no red line across the poles t = k pi (the curve leaves
     * [-10, 10] at |t - k pi| = atan(0.1) ~ 0.1: a band of +-2 px is empty) */
    render(img, &fr, "euler-inv");
    CHECK(fr.wy0 >= -10.0001 && fr.wy1 <= 10.0001);
    for (int k = 1; k <= 6; k++) {
        double px0, py0, px1, py1;
        CHECK(hl_plot_frame_pixel(&fr, W, H, k * M_PI, 9, &px0, &py0));
        CHECK(hl_plot_frame_pixel(&fr, W, H, k * M_PI, -9, &px1, &py1));
        long red = 0;
        for (int y = (int)py0; y <= (int)py1; y++)
            for (int x = (int)px0 - 1; x <= (int)px0 + 1; x++)
                red += is_red(img + 3 * ((size_t)y * W + x));
        CHECK_MSG(red == 0, "euler-inv: %ld red pixels across the pole t = %d pi", red, k);
    }
    /* a dot at n = 10: x/p = -cot(10 atan D) = -1.47 */
    CHECK(near(img, &fr, 1.0, -1 / tan(10 * atan(D)), 2, is_blue) >= 5);

    /* the error figures: log axes, curves at the closed-form heights */
    render(img, &fr, "euler-error");
    CHECK(fr.ylog == 1);
    for (int n = 50; n <= 200; n += 50) {
        double r = pow(1 + D * D, 0.5 * n), b = n * atan(D), t = n * D;
        double s = (r - 1) * (r - 1) + 4 * r * pow(sin(0.5 * (b - t)), 2);
        CHECK_MSG(near(img, &fr, t, s, 2, is_black) > 0, "euler-error: sigma(x,p) at n = %d", n);
    }
    {
        double t = 2.0, b = 20 * atan(D), d = 1 / tan(b) - 1 / tan(t);
        CHECK_MSG(near(img, &fr, t, d * d, 2, is_green) > 0, "euler-error: sigma(x/p) at t = 2");
    }
    render(img, &fr, "disgra-error");
    CHECK(fr.ylog == 1);
    for (int n = 50; n <= 200; n += 50) {
        double s = 4 * pow(sin(0.5 * n * (2 * atan(D / 2) - D)), 2);
        CHECK_MSG(near(img, &fr, n * D, s, 2, is_black) > 0, "disgra-error: n = %d", n);
    }
    CHECK(count(img, is_green) > 50);
    render(img, &fr, "exact-error");
    CHECK(fr.ylog == 1 && fr.wy1 < -20); /* sigma below 1e-20 everywhere */
    CHECK(count(img, is_black) > 300);
    /* H of the discrete gradient: flat at 1/2 */
    render(img, &fr, "disgra-inv");
    CHECK(near(img, &fr, 10, 0.5, 2, is_blue) >= 5);
    CHECK(fr.wy0 < 0.5 && fr.wy1 > 0.5 && fr.wy1 - fr.wy0 < 0.2);
}

/* ---- 3. the files ------------------------------------------------------------ */

static long file_head(const char *path, unsigned char *head, size_t n)
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return -1;
    memset(head, 0, n);
    size_t got = fread(head, 1, n, fp);
    (void)got;
    fseek(fp, 0, SEEK_END);
    long sz = ftell(fp);
    fclose(fp);
    return sz;
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static void test_files(void)
{
    char tmpl[] = "/tmp/hl-figs-XXXXXX";
    char *dir = mkdtemp(tmpl);
    CHECK(dir != NULL);
    if (dir == NULL)
        return;
    char sub[600], file[700];
    snprintf(sub, sizeof sub, "%s/a/b", dir); /* created, parents too */
    hl_paper_figure figs[HL_PAPER_NFIGURES];
    hl_error err;
    double t0 = now();
    CHECK_MSG(hl_paper_figures(figs, sub, "png,svg,pdf", &err) == HL_OK, "%s", err.msg);
    printf("14 figures x png,svg,pdf: %.2f s\n", now() - t0);
    const char *ext[3] = {"png", "svg", "pdf"};
    for (int i = 0; i < HL_PAPER_NFIGURES; i++)
        for (int k = 0; k < 3; k++) {
            unsigned char head[512];
            snprintf(file, sizeof file, "%s/%s.%s", sub, names[i], ext[k]);
            long sz = file_head(file, head, sizeof head - 1);
            CHECK_MSG(sz > 3000, "%s: %ld bytes", file, sz);
            if (k == 0)
                CHECK_MSG(memcmp(head, "\x89PNG\r\n\x1a\n", 8) == 0, "%s: not a PNG", file);
            else if (k == 1)
                CHECK_MSG(strstr((char *)head, "<svg") != NULL, "%s: not an SVG", file);
            else
                CHECK_MSG(memcmp(head, "%PDF-", 5) == 0, "%s: not a PDF", file);
            unlink(file);
        }
    rmdir(sub);
    snprintf(sub, sizeof sub, "%s/a", dir);
    rmdir(sub);

    /* a bad format: HL_EINVAL, and no directory created */
    snprintf(sub, sizeof sub, "%s/c", dir);
    CHECK(hl_paper_figures(figs, sub, "png,gif", &err) == HL_EINVAL);
    CHECK(strstr(err.msg, "gif") != NULL);
    CHECK(hl_paper_figures(figs, sub, "", &err) == HL_EINVAL);
    struct stat sb;
    CHECK(stat(sub, &sb) != 0);
    /* a directory that cannot be made (a file is in the way): HL_EIO */
    snprintf(file, sizeof file, "%s/plain", dir);
    FILE *fp = fopen(file, "w");
    CHECK(fp != NULL);
    if (fp != NULL)
        fclose(fp);
    snprintf(sub, sizeof sub, "%s/plain/x", dir);
    CHECK(hl_paper_figures(figs, sub, "png", &err) == HL_EIO);
    CHECK_MSG(strstr(err.msg, "plain") != NULL, "%s", err.msg);
    unlink(file);
    CHECK(rmdir(dir) == 0);
}

int main(void)
{
    unsigned char *img = malloc((size_t)W * H * 3);
    test_checks();
    test_phase_images(img);
    test_time_images(img);
    free(img);
    test_files();
    return HL_TEST_END();
}
