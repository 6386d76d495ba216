/* Figures (plot.h), checked as images.
 *
 * Where a curve must land is derived by hand from the documented range rule
 * (data range + 2% margin in x, 5% in y, or in decades on a log axis) and the
 * plot box found in the image itself (the rows and columns that are mostly
 * dark), so the checks do not trust the figure's own idea of its mapping;
 * that mapping (hl_plot_frame) is then checked against the box found. */
#include <dirent.h>
#include <fcntl.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <plplot.h>

#include "hamlie/plot.h"
#include "hl_test.h"

#define W 800
#define H 600

static int is_red(const unsigned char *p)
{
    return p[0] > 180 && p[1] < 110 && p[2] < 110;
}
static int is_blue(const unsigned char *p)
{
    return p[2] > 180 && p[0] < 110 && p[1] < 110;
}
static int is_white(const unsigned char *p)
{
    return p[0] == 255 && p[1] == 255 && p[2] == 255;
}

static const unsigned char *px(const unsigned char *img, int x, int y)
{
    return img + 3 * ((size_t)y * W + (size_t)x);
}

/* Is there a pixel of that kind within r pixels of (x, y)? */
static int near(const unsigned char *img, double x, double y, int r,
                int (*kind)(const unsigned char *))
{
    if (!(fabs(x) < 1e6 && fabs(y) < 1e6))
        return 0;
    for (int j = (int)y - r; j <= (int)y + r; j++)
        for (int i = (int)x - r; i <= (int)x + r; i++)
            if (i >= 0 && j >= 0 && i < W && j < H && kind(px(img, i, j)))
                return 1;
    return 0;
}

/* The plot box: the outermost runs of rows / columns whose middle half is
 * mostly ink (the box lines, antialiased over one or two pixels; tick marks
 * and text never fill half).  Each edge is the centre of its run, in pixel
 * coordinates (pixel i covers [i, i+1)). */
typedef struct box {
    double left, right, top, bottom;
} box;

static int is_ink(const unsigned char *p)
{
    return p[0] < 200 && p[1] < 200 && p[2] < 200;
}

/* full[k]: is line k (row or column) mostly ink?  Edges: centres of the
 * first and last runs. */
static int edges(double *lo, double *hi, const int *full, int n)
{
    int a = 0, b = n - 1;
    while (a < n && !full[a])
        a++;
    while (b >= 0 && !full[b])
        b--;
    if (a >= b)
        return 0;
    int a2 = a, b2 = b;
    while (full[a2 + 1])
        a2++;
    while (full[b2 - 1])
        b2--;
    *lo = 0.5 * (a + a2) + 0.5;
    *hi = 0.5 * (b + b2) + 0.5;
    return b2 - a2 > 50;
}

static int find_box(box *b, const unsigned char *img)
{
    int rows[H], cols[W];
    for (int y = 0; y < H; y++) {
        int n = 0;
        for (int x = W / 4; x < 3 * W / 4; x++)
            n += is_ink(px(img, x, y));
        rows[y] = n > W / 4;
    }
    for (int x = 0; x < W; x++) {
        int n = 0;
        for (int y = H / 4; y < 3 * H / 4; y++)
            n += is_ink(px(img, x, y));
        cols[x] = n > H / 4;
    }
    if (!edges(&b->top, &b->bottom, rows, H) || !edges(&b->left, &b->right, cols, W)) {
        b->top = b->left = 0;
        b->bottom = H - 1;
        b->right = W - 1;
        return 0;
    }
    return 1;
}

/* Pixel of a data point on the box found, the window given by hand. */
static void to_pixel(double *x, double *y, const box *b, const double win[4], double dx,
                     double dy)
{
    *x = b->left + (dx - win[0]) / (win[1] - win[0]) * (b->right - b->left);
    *y = b->bottom - (dy - win[2]) / (win[3] - win[2]) * (b->bottom - b->top);
}

/* Centroid of the pixels of a kind inside a rectangle; 0 if none. */
static int centroid(double *cx, double *cy, const unsigned char *img, int x0, int x1, int y0,
                    int y1, int (*kind)(const unsigned char *))
{
    double sx = 0, sy = 0;
    long n = 0;
    for (int y = y0; y < y1; y++)
        for (int x = x0; x < x1; x++)
            if (kind(px(img, x, y))) {
                sx += x + 0.5;
                sy += y + 0.5;
                n++;
            }
    if (n == 0)
        return 0;
    *cx = sx / n;
    *cy = sy / n;
    return 1;
}

static void check_frame_matches_box(const hl_plot_frame *f, const box *b)
{
    CHECK_MSG(fabs(f->vx0 * W - b->left) < 1.5, "left %g vs %g", f->vx0 * W, b->left);
    CHECK_MSG(fabs(f->vx1 * W - b->right) < 1.5, "right %g vs %g", f->vx1 * W, b->right);
    CHECK_MSG(fabs((1 - f->vy1) * H - b->top) < 1.5, "top %g vs %g", (1 - f->vy1) * H, b->top);
    CHECK_MSG(fabs((1 - f->vy0) * H - b->bottom) < 1.5, "bottom %g vs %g", (1 - f->vy0) * H,
              b->bottom);
}

static unsigned char *render(const hl_figure *fig, hl_plot_frame *frame)
{
    unsigned char *img = malloc((size_t)W * H * 3);
    hl_error err;
    hl_error_clear(&err);
    hl_status st = hl_figure_render_rgb(fig, W, H, img, frame, &err);
    CHECK_MSG(st == HL_OK, "render: %s", err.msg);
    const char *dump = getenv("HL_PLOT_DUMP"); /* a directory: keep the images */
    if (dump != NULL) {
        static int count;
        char name[512];
        snprintf(name, sizeof name, "%s/render-%02d.ppm", dump, count++);
        FILE *fp = fopen(name, "wb");
        if (fp != NULL) {
            fprintf(fp, "P6 %d %d 255\n", W, H);
            fwrite(img, 1, (size_t)W * H * 3, fp);
            fclose(fp);
        }
    }
    return img;
}

/* ---- pure rules ------------------------------------------------------------ */

static void test_rules(void)
{
    unsigned char rgb[3];
    hl_color_rgb(rgb, HL_COLOR_GREEN);
    CHECK(rgb[0] == 0 && rgb[1] == 160 && rgb[2] == 0);
    CHECK(hl_color_from_name("Red") == HL_COLOR_RED);
    CHECK(hl_color_from_name("grey") == HL_COLOR_GRAY);
    CHECK(hl_color_from_name("chartreuse") == -1);
    CHECK_STR(hl_color_name(HL_COLOR_BLUE), "blue");
    CHECK(hl_color_name(HL_COLOR_COUNT) == NULL);

    /* range [-10, 10], frac 0.25: "large" means |y| >= 5 */
    CHECK(hl_plot_is_pole_jump(30, -50, -10, 10, 0.25));
    CHECK(hl_plot_is_pole_jump(-5, 5, -10, 10, 0.25));
    CHECK(!hl_plot_is_pole_jump(-4.9, 50, -10, 10, 0.25)); /* one side small */
    CHECK(!hl_plot_is_pole_jump(30, 50, -10, 10, 0.25));   /* no sign change */
    CHECK(!hl_plot_is_pole_jump(0.1, -0.1, -10, 10, 0.25)); /* a zero crossing */
    CHECK(!hl_plot_is_pole_jump(0, 50, -10, 10, 0.25));
    CHECK(!hl_plot_is_pole_jump(30, -50, -10, 10, 0)); /* rule off */

    hl_error err;
    hl_figure *f = hl_figure_new(NULL, NULL, NULL);
    double x = 0;
    CHECK(hl_figure_add(f, 1, NULL, &x, HL_DRAW_LINE, HL_COLOR_RED, NULL, &err) == HL_EINVAL);
    CHECK(hl_figure_add(f, 1, &x, &x, HL_DRAW_LINE, HL_COLOR_COUNT, NULL, &err) == HL_EINVAL);
    CHECK(hl_figure_add(f, 1, &x, &x, (hl_draw)99, HL_COLOR_RED, NULL, &err) == HL_EINVAL);
    CHECK(hl_figure_set_yclip(f, 1, 1, &err) == HL_EINVAL);
    CHECK(hl_figure_set_size(f, 5, 600, &err) == HL_EINVAL);
    CHECK(hl_figure_set_pole_frac(f, -1, &err) == HL_EINVAL);
    CHECK(hl_figure_nseries(f) == 0);
    unsigned char small[3 * 16 * 16];
    CHECK(hl_figure_render_rgb(f, 8, 8, small, NULL, &err) == HL_EINVAL);
    CHECK(hl_figure_render_rgb(f, 16, 16, NULL, NULL, &err) == HL_EINVAL);
    hl_figure_free(f);
    hl_figure_free(NULL);
}

/* ---- a red line y = x and blue dots --------------------------------------------- */

static void test_line_and_dots(void)
{
    hl_error err;
    hl_figure *f = hl_figure_new(NULL, "x", "y");
    double lx[2] = {0, 1}, ly[2] = {0, 1};
    double dx[2] = {0.25, 0.75}, dy[2] = {0.75, 0.25};
    CHECK(hl_figure_add(f, 2, lx, ly, HL_DRAW_LINE, HL_COLOR_RED, NULL, &err) == HL_OK);
    CHECK(hl_figure_add(f, 2, dx, dy, HL_DRAW_DOTS, HL_COLOR_BLUE, NULL, &err) == HL_OK);
    hl_plot_frame fr;
    unsigned char *img = render(f, &fr);

    /* the window by the documented rule: [0,1] + 2% in x, + 5% in y */
    const double win[4] = {-0.02, 1.02, -0.05, 1.05};
    CHECK(fabs(fr.wx0 - win[0]) < 1e-12 && fabs(fr.wx1 - win[1]) < 1e-12);
    CHECK(fabs(fr.wy0 - win[2]) < 1e-12 && fabs(fr.wy1 - win[3]) < 1e-12);
    CHECK(fr.ylog == 0);
    box b;
    CHECK(find_box(&b, img));
    check_frame_matches_box(&fr, &b);

    int bad = 0;
    for (int k = 1; k < 20; k++) {
        double u = k / 20.0, x, y;
        to_pixel(&x, &y, &b, win, u, u);
        if (!near(img, x, y, 1, is_red))
            bad++;
        double fx, fy; /* the frame's own mapping agrees */
        CHECK(hl_plot_frame_pixel(&fr, W, H, u, u, &fx, &fy));
        CHECK(fabs(fx - x) < 1.5 && fabs(fy - y) < 1.5);
    }
    CHECK_MSG(bad == 0, "%d of 19 points of y = x not red", bad);
    double x, y;
    to_pixel(&x, &y, &b, win, 0.9, 0.1); /* far from the line and the dots */
    CHECK(!near(img, x, y, 3, is_red) && is_white(px(img, (int)x, (int)y)));
    to_pixel(&x, &y, &b, win, 0.5, 0.5); /* the line itself: not blue */
    CHECK(!near(img, x, y, 2, is_blue));

    for (int k = 0; k < 2; k++) {
        double cx = NAN, cy = NAN; /* stay NaN if no pixel is found */
        to_pixel(&x, &y, &b, win, dx[k], dy[k]);
        CHECK(centroid(&cx, &cy, img, (int)x - 10, (int)x + 10, (int)y - 10, (int)y + 10,
                       is_blue));
        CHECK_MSG(fabs(cx - x) < 1.0 && fabs(cy - y) < 1.0, "dot %d at (%g,%g), want (%g,%g)",
                  k, cx, cy, x, y);
    }
    /* nothing blue outside the two dots */
    long blue = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++)
            blue += is_blue(px(img, i, j));
    CHECK_MSG(blue > 2 * 20 && blue < 2 * 80, "%ld blue pixels for two dots of radius 3.5", blue);
    free(img);
    hl_figure_free(f);
}

/* ---- log axis --------------------------------------------------------------------- */

static void test_log_axis(void)
{
    hl_error err;
    hl_figure *f = hl_figure_new("log", "t", "#gs");
    hl_figure_set_yscale(f, HL_AXIS_AUTO);
    double dx[5] = {0.5, 1.5, 2.5, 1.0, 2.0}, dy[5] = {1e-10, 1e-6, 1e-2, 0.0, -1e-3};
    /* the first four points: three decades apart and a zero (dropped); the
     * negative fifth is used below, where it makes "auto" linear */
    CHECK(hl_figure_add(f, 4, dx, dy, HL_DRAW_DOTS, HL_COLOR_BLUE, NULL, &err) == HL_OK);
    hl_figure_set_legend(f, HL_LEGEND_NONE);
    hl_plot_frame fr;
    unsigned char *img = render(f, &fr);
    CHECK(fr.ylog == 1);
    /* decades -10..-2, 5% of 8 decades of margin: window [-10.4, -1.6] */
    const double win[4] = {0.5 - 0.04, 2.5 + 0.04, -10.4, -1.6};
    CHECK(fabs(fr.wy0 - win[2]) < 1e-12 && fabs(fr.wy1 - win[3]) < 1e-12);
    box b;
    CHECK(find_box(&b, img));
    check_frame_matches_box(&fr, &b);
    double row[3];
    for (int k = 0; k < 3; k++) {
        double x, y, cx, cy = -1;
        to_pixel(&x, &y, &b, win, dx[k], log10(dy[k]));
        CHECK(centroid(&cx, &cy, img, (int)x - 12, (int)x + 12, (int)b.top + 2,
                       (int)b.bottom - 1, is_blue));
        CHECK_MSG(fabs(cy - y) < 1.0, "1e%d at row %g, want %g", (int)log10(dy[k]), cy, y);
        row[k] = cy;
    }
    /* equal steps of 4 decades are equal steps in pixels, 1e-2 on top */
    CHECK(fabs((row[0] - row[1]) - (row[1] - row[2])) < 1.0);
    CHECK(row[2] < row[1] && row[1] < row[0]);
    /* the zero (x = 1) is dropped: no blue in its column band */
    double zx, zy;
    to_pixel(&zx, &zy, &b, win, 1.0, -6);
    double cx, cy;
    CHECK(!centroid(&cx, &cy, img, (int)zx - 6, (int)zx + 6, 0, H, is_blue));
    free(img);

    /* 28 decades: hamlie labels the axis itself (every 5 decades); the
     * mapping is the same: window [-31.4, -0.6], equal steps */
    hl_figure *g = hl_figure_new(NULL, NULL, NULL);
    double wy[3] = {1e-30, 1e-16, 1e-2};
    CHECK(hl_figure_add(g, 3, dx, wy, HL_DRAW_DOTS, HL_COLOR_BLUE, NULL, &err) == HL_OK);
    hl_figure_set_yscale(g, HL_AXIS_LOG);
    img = render(g, &fr);
    const double win2[4] = {0.5 - 0.04, 2.5 + 0.04, -31.4, -0.6};
    CHECK(fabs(fr.wy0 - win2[2]) < 1e-12 && fabs(fr.wy1 - win2[3]) < 1e-12);
    CHECK(find_box(&b, img));
    check_frame_matches_box(&fr, &b);
    for (int k = 0; k < 3; k++) {
        double x, y;
        cy = -1;
        to_pixel(&x, &y, &b, win2, dx[k], log10(wy[k]));
        CHECK(centroid(&cx, &cy, img, (int)x - 12, (int)x + 12, (int)b.top + 2,
                       (int)b.bottom - 1, is_blue));
        CHECK_MSG(fabs(cy - y) < 1.0, "1e%d at row %g, want %g", (int)log10(wy[k]), cy, y);
    }
    free(img);
    hl_figure_free(g);

    /* auto: a negative value keeps the axis linear; 3 decades or less too */
    g = hl_figure_new(NULL, NULL, NULL);
    hl_figure_set_yscale(g, HL_AXIS_AUTO);
    CHECK(hl_figure_add(g, 5, dx, dy, HL_DRAW_LINE, HL_COLOR_RED, NULL, &err) == HL_OK);
    img = render(g, &fr);
    CHECK(fr.ylog == 0);
    free(img);
    hl_figure_free(g);
    g = hl_figure_new(NULL, NULL, NULL);
    hl_figure_set_yscale(g, HL_AXIS_AUTO);
    double y3[2] = {1e-3, 0.99};
    CHECK(hl_figure_add(g, 2, dx, y3, HL_DRAW_LINE, HL_COLOR_RED, NULL, &err) == HL_OK);
    img = render(g, &fr);
    CHECK(fr.ylog == 0);
    free(img);
    hl_figure_free(g);

    /* a line on a log axis with a zero in it: no -inf, drawn on both sides */
    g = hl_figure_new(NULL, NULL, NULL);
    hl_figure_set_yscale(g, HL_AXIS_LOG);
    double lx[5] = {0, 1, 2, 3, 4}, ly[5] = {1e-8, 1e-7, 0, 1e-5, 1e-4};
    CHECK(hl_figure_add(g, 5, lx, ly, HL_DRAW_LINE, HL_COLOR_RED, NULL, &err) == HL_OK);
    img = render(g, &fr);
    CHECK(fr.ylog == 1 && fabs(fr.wy0 - (-8.2)) < 1e-12 && fabs(fr.wy1 - (-3.8)) < 1e-12);
    double x, y;
    CHECK(hl_plot_frame_pixel(&fr, W, H, 0.5, pow(10, -7.5), &x, &y));
    CHECK(near(img, x, y, 1, is_red));
    CHECK(hl_plot_frame_pixel(&fr, W, H, 3.5, pow(10, -4.5), &x, &y));
    CHECK(near(img, x, y, 1, is_red));
    CHECK(!hl_plot_frame_pixel(&fr, W, H, 2, 0, &x, &y));
    CHECK(hl_plot_frame_pixel(&fr, W, H, 2, 1e-6, &x, &y)); /* the gap 1..3 */
    CHECK(!near(img, x, y, 4, is_red));
    free(img);
    hl_figure_free(g);
    hl_figure_free(f);
}

/* ---- x/p across its poles ------------------------------------------------------------- */

/* x/p for the oscillator from x = 1, p = 0: x = cos t, p = -sin t. */
static hl_figure *xp_figure(double pole_frac)
{
    enum { N = 2001, M = 63 };
    static double t[N], r[N], tn[M], rn[M];
    hl_error err;
    for (int i = 0; i < N; i++) {
        t[i] = 2 * M_PI * i / (N - 1);
        r[i] = cos(t[i]) / -sin(t[i]); /* ±inf or huge at 0, π, 2π */
    }
    for (int i = 0; i < M; i++) {
        tn[i] = 0.1 * i;
        rn[i] = cos(tn[i]) / -sin(tn[i]);
    }
    hl_figure *f = hl_figure_new("x/p", "t", "x/p");
    hl_figure_add(f, N, t, r, HL_DRAW_LINE, HL_COLOR_RED, NULL, &err);
    hl_figure_add(f, M, tn, rn, HL_DRAW_DOTS, HL_COLOR_BLUE, NULL, &err);
    hl_figure_set_yclip(f, -10, 10, &err);
    hl_figure_set_xclip(f, 0, 2 * M_PI, &err);
    hl_figure_set_legend(f, HL_LEGEND_NONE);
    hl_figure_set_pole_frac(f, pole_frac, &err);
    return f;
}

static long count_band(const unsigned char *img, double x0, double x1, const box *b,
                       int (*kind)(const unsigned char *))
{
    long n = 0;
    for (int y = (int)b->top + 2; y < (int)b->bottom - 1; y++)
        for (int x = (int)x0; x <= (int)x1; x++)
            n += kind(px(img, x, y));
    return n;
}

static void test_poles(void)
{
    hl_figure *f = xp_figure(0.25);
    hl_plot_frame fr;
    unsigned char *img = render(f, &fr);
    box b;
    CHECK(find_box(&b, img));
    CHECK(fabs(fr.wy0 + 10) < 1e-12 && fabs(fr.wy1 - 10) < 1e-12); /* the clip */
    CHECK(fabs(fr.wx0) < 1e-12 && fabs(fr.wx1 - 2 * M_PI) < 1e-12);
    /* |x/p| <= 10 needs |t - π| >= atan(1/10) ≈ 0.0997, about 11 px here:
     * a band of ±5 px around the pole holds no curve unless one crosses it */
    const double win[4] = {0, 2 * M_PI, -10, 10};
    double x, y;
    to_pixel(&x, &y, &b, win, M_PI, 0);
    CHECK_MSG(count_band(img, x - 5, x + 5, &b, is_red) == 0, "red line through the pole");
    CHECK(count_band(img, x - 5, x + 5, &b, is_blue) == 0);
    /* but the curve is there on both sides, near the pole and at the clip */
    to_pixel(&x, &y, &b, win, M_PI - 0.3, -cos(M_PI - 0.3) / sin(M_PI - 0.3));
    CHECK(near(img, x, y, 1, is_red));
    to_pixel(&x, &y, &b, win, M_PI + 0.3, -cos(M_PI + 0.3) / sin(M_PI + 0.3));
    CHECK(near(img, x, y, 1, is_red));
    free(img);
    hl_figure_free(f);

    /* the same with the rule off: a line does cross the band (so the check
     * above can fail) */
    f = xp_figure(0);
    img = render(f, &fr);
    CHECK(find_box(&b, img));
    to_pixel(&x, &y, &b, win, M_PI, 0);
    CHECK(count_band(img, x - 5, x + 5, &b, is_red) > 100);
    free(img);
    hl_figure_free(f);
}

/* ---- equal aspect: the unit circle is round ------------------------------------------------- */

static void test_equal_aspect(void)
{
    enum { N = 721 };
    double x[N], y[N];
    hl_error err;
    for (int i = 0; i < N; i++) {
        x[i] = cos(2 * M_PI * i / (N - 1));
        y[i] = sin(2 * M_PI * i / (N - 1));
    }
    for (int eq = 0; eq < 2; eq++) {
        hl_figure *f = hl_figure_new("phase space", "x", "p");
        hl_figure_set_equal_aspect(f, eq);
        CHECK(hl_figure_add(f, N, x, y, HL_DRAW_LINE, HL_COLOR_RED, "exact", &err) == HL_OK);
        hl_figure_set_legend(f, HL_LEGEND_NONE);
        unsigned char *img = render(f, NULL);
        int x0 = W, x1 = -1, y0 = H, y1 = -1;
        for (int j = 0; j < H; j++)
            for (int i = 0; i < W; i++)
                if (is_red(px(img, i, j))) {
                    x0 = i < x0 ? i : x0, x1 = i > x1 ? i : x1;
                    y0 = j < y0 ? j : y0, y1 = j > y1 ? j : y1;
                }
        double wd = x1 - x0, ht = y1 - y0;
        if (eq)
            CHECK_MSG(fabs(wd - ht) <= 2, "circle %g x %g px", wd, ht);
        else
            CHECK_MSG(wd - ht > 50, "stretched circle %g x %g px", wd, ht);
        free(img);
        hl_figure_free(f);
    }
}

/* ---- ranges: constant data, clip outside the data ---------------------------------------------- */

static void test_ranges(void)
{
    hl_error err;
    hl_plot_frame fr;
    double t[3] = {0, 1, 2}, h[3] = {0.5, 0.5, 0.5 + 1e-16};
    hl_figure *f = hl_figure_new(NULL, NULL, NULL);
    CHECK(hl_figure_add(f, 3, t, h, HL_DRAW_DOTS, HL_COLOR_BLUE, NULL, &err) == HL_OK);
    unsigned char *img = render(f, &fr);
    CHECK(fabs(fr.wy0 - 0.45) < 1e-12 && fabs(fr.wy1 - 0.55) < 1e-12);
    free(img);
    hl_figure_free(f);

    /* non-finite values take no part in the range and draw nothing */
    double y[3] = {NAN, 2, INFINITY};
    f = hl_figure_new(NULL, NULL, NULL);
    CHECK(hl_figure_add(f, 3, t, y, HL_DRAW_LINE, HL_COLOR_RED, "l", &err) == HL_OK);
    img = render(f, &fr);
    CHECK(fabs(fr.wy0 - 1.8) < 1e-12 && fabs(fr.wy1 - 2.2) < 1e-12);
    CHECK(fabs(fr.wx0 - 0.9) < 1e-12 && fabs(fr.wx1 - 1.1) < 1e-12);
    free(img);
    hl_figure_free(f);

    /* an empty figure still draws its box on [0, 1] */
    f = hl_figure_new("empty", NULL, NULL);
    img = render(f, &fr);
    CHECK(fr.wx0 == -0.02 && fr.wy1 == 1.05);
    box b;
    CHECK(find_box(&b, img));
    free(img);
    hl_figure_free(f);
}

/* ---- non-blank ----------------------------------------------------------------------------- */

static void test_nonblank(void)
{
    enum { N = 201 };
    double t[N], x[N];
    hl_error err;
    for (int i = 0; i < N; i++) {
        t[i] = 0.1 * i;
        x[i] = cos(t[i]);
    }
    hl_figure *f = hl_figure_new("x(t)", "t", "x");
    hl_figure_add(f, N, t, x, HL_DRAW_LINE, HL_COLOR_RED, "exact", &err);
    hl_figure_add(f, N, t, x, HL_DRAW_DOTS, HL_COLOR_BLUE, "scheme", &err);
    unsigned char *img = render(f, NULL);
    long ink = 0, red = 0, blue = 0;
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            ink += !is_white(px(img, i, j));
            red += is_red(px(img, i, j));
            blue += is_blue(px(img, i, j));
        }
    CHECK_MSG(ink > 20000 && red > 1000 && blue > 5000, "ink %ld red %ld blue %ld", ink, red,
              blue);
    CHECK_MSG(ink < W * H / 4, "ink %ld: mostly not background", ink);
    free(img);
    hl_figure_free(f);
}

/* ---- files --------------------------------------------------------------------------------- */

static unsigned char *slurp(const char *path, size_t *n)
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return NULL;
    fseek(fp, 0, SEEK_END);
    long len = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    unsigned char *s = malloc((size_t)len + 1);
    *n = fread(s, 1, (size_t)len, fp);
    s[*n] = 0;
    fclose(fp);
    return s;
}

static int count_entries(const char *dir)
{
    DIR *d = opendir(dir);
    int n = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL)
        n += e->d_name[0] != '.';
    closedir(d);
    return n;
}

static unsigned be32(const unsigned char *p)
{
    return (unsigned)p[0] << 24 | (unsigned)p[1] << 16 | (unsigned)p[2] << 8 | p[3];
}

static void test_files(void)
{
    char dir[] = "/tmp/hl-plot-XXXXXX", path[512];
    char base[700], file[800];
    CHECK(mkdtemp(dir) != NULL);
    hl_error err;
    hl_figure *f = hl_figure_new("#gs(x,p), #gD = 0.1", "t", "σ");
    double t[3] = {0, 1, 2}, y[3] = {1e-3, 1e-9, 1e-16};
    hl_figure_add(f, 3, t, y, HL_DRAW_LINE, HL_COLOR_BLACK, "σ(x,p)", &err);
    hl_figure_add(f, 3, t, y, HL_DRAW_DOTS, HL_COLOR_GREEN, "σ(2H)", &err);
    hl_figure_set_yscale(f, HL_AXIS_AUTO);

    /* PLplot prints nothing on success: watch fds 1 and 2 */
    snprintf(path, sizeof path, "%s/../%s.out", dir, dir + 5);
    fflush(stdout);
    fflush(stderr);
    int save1 = dup(1), save2 = dup(2);
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC, 0600);
    dup2(fd, 1);
    dup2(fd, 2);
    snprintf(base, sizeof base, "%s/fig", dir);
    hl_status st = hl_figure_write(f, base, "png, SVG,pdf", &err);
    unsigned char *img = malloc((size_t)W * H * 3);
    hl_status st2 = hl_figure_render_rgb(f, W, H, img, NULL, &err);
    fflush(stdout);
    fflush(stderr);
    dup2(save1, 1);
    dup2(save2, 2);
    close(save1), close(save2), close(fd);
    struct stat sb;
    CHECK(stat(path, &sb) == 0 && sb.st_size == 0);
    unlink(path);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    CHECK(st2 == HL_OK);
    free(img);

    size_t n;
    snprintf(file, sizeof file, "%s.png", base);
    unsigned char *s = slurp(file, &n);
    CHECK(s != NULL && n > 33);
    if (s && n > 33) {
        CHECK(memcmp(s, "\x89PNG\r\n\x1a\n", 8) == 0);
        CHECK(memcmp(s + 12, "IHDR", 4) == 0);
        CHECK(be32(s + 16) == 800 && be32(s + 20) == 600);
        CHECK(s[24] == 8); /* bit depth */
    }
    free(s);
    snprintf(file, sizeof file, "%s.svg", base);
    s = slurp(file, &n);
    CHECK(s != NULL && (strncmp((char *)s, "<?xml", 5) == 0 || strncmp((char *)s, "<svg", 4) == 0));
    CHECK(s != NULL && strstr((char *)s, "<path") != NULL);
    CHECK(s != NULL && strstr((char *)s, "width=\"800pt\"") != NULL);
    free(s);
    snprintf(file, sizeof file, "%s.pdf", base);
    s = slurp(file, &n);
    CHECK(s != NULL && n > 20 && memcmp(s, "%PDF", 4) == 0);
    if (s && n > 20) {
        size_t e = n;
        while (e > 0 && (s[e - 1] == '\n' || s[e - 1] == '\r'))
            e--;
        CHECK(e >= 5 && memcmp(s + e - 5, "%%EOF", 5) == 0);
    }
    free(s);
    CHECK(count_entries(dir) == 3); /* no temporary left */

    /* a different size */
    CHECK(hl_figure_set_size(f, 321, 123, &err) == HL_OK);
    snprintf(base, sizeof base, "%s/small", dir);
    CHECK(hl_figure_write(f, base, "png", &err) == HL_OK);
    snprintf(file, sizeof file, "%s.png", base);
    s = slurp(file, &n);
    CHECK(s != NULL && n > 24 && be32(s + 16) == 321 && be32(s + 20) == 123);
    free(s);
    unlink(file);

    /* unwritable: the parent is a regular file (fails for root too) */
    snprintf(file, sizeof file, "%s/afile", dir);
    fclose(fopen(file, "w"));
    snprintf(base, sizeof base, "%s/afile/fig", dir);
    hl_error_clear(&err);
    CHECK(hl_figure_write(f, base, "png,svg,pdf", &err) == HL_EIO);
    CHECK_MSG(strstr(err.msg, "afile/fig.png") != NULL, "message: %s", err.msg);
    snprintf(base, sizeof base, "%s/no/such/dir/fig", dir);
    CHECK(hl_figure_write(f, base, "svg", &err) == HL_EIO);
    CHECK(strstr(err.msg, "dir/fig.svg") != NULL);
    if (geteuid() != 0) {
        char ro[600];
        /* non-root only: root writes into mode 0500 directories */
        snprintf(ro, sizeof ro, "%s/ro", dir);
        mkdir(ro, 0500);
        snprintf(base, sizeof base, "%s/fig", ro);
        CHECK(hl_figure_write(f, base, "pdf", &err) == HL_EIO);
        CHECK(count_entries(ro) == 0);
        rmdir(ro);
    }
    /* bad format lists are refused before anything is written */
    snprintf(base, sizeof base, "%s/x", dir);
    CHECK(hl_figure_write(f, base, "png,gif", &err) == HL_EINVAL);
    CHECK(strstr(err.msg, "'gif'") != NULL);
    CHECK(hl_figure_write(f, base, " , ", &err) == HL_EINVAL);
    CHECK(hl_figure_write(f, "", "png", &err) == HL_EINVAL);
    CHECK(count_entries(dir) == 4); /* fig.png, fig.svg, fig.pdf, afile */

    const char *names[] = {"fig.png", "fig.svg", "fig.pdf", "afile"};
    for (int k = 0; k < 4; k++) {
        snprintf(file, sizeof file, "%s/%s", dir, names[k]);
        CHECK(unlink(file) == 0);
    }
    CHECK(rmdir(dir) == 0);
    hl_figure_free(f);
}

/* No state leaks between figures: the same figure renders to the same bytes
 * before and after a different one (log axis, equal aspect, other colours),
 * and the caller's current PLplot stream is left as it was. */
static void test_no_leak(void)
{
    hl_error err;
    double t[4] = {0, 1, 2, 3}, y[4] = {1, -2, 0.5, 3}, z[4] = {1e-9, 1e-3, 1e-1, 1e-6};
    hl_figure *a = hl_figure_new("a", "t", "y"), *b = hl_figure_new("b", "t", "#gs");
    hl_figure_add(a, 4, t, y, HL_DRAW_LINE, HL_COLOR_RED, "line", &err);
    hl_figure_add(a, 4, t, y, HL_DRAW_SQUARES, HL_COLOR_PURPLE, "squares", &err);
    hl_figure_add(b, 4, t, z, HL_DRAW_TRIANGLES, HL_COLOR_ORANGE, "tri", &err);
    hl_figure_set_yscale(b, HL_AXIS_LOG);
    hl_figure_set_equal_aspect(b, 1);
    PLINT s0, s1;
    plgstrm(&s0);
    unsigned char *i1 = render(a, NULL);
    unsigned char *i2 = render(b, NULL);
    unsigned char *i3 = render(a, NULL);
    plgstrm(&s1);
    CHECK(s0 == s1);
    CHECK(memcmp(i1, i3, (size_t)W * H * 3) == 0);
    CHECK(memcmp(i1, i2, (size_t)W * H * 3) != 0);
    free(i1), free(i2), free(i3);
    hl_figure_free(a);
    hl_figure_free(b);
}

int main(void)
{
    test_rules();
    test_line_and_dots();
    test_log_axis();
    test_poles();
    test_equal_aspect();
    test_ranges();
    test_nonblank();
    test_files();
    test_no_leak();
    return HL_TEST_END();
}
