/* Figures for any run (runplot.h): the CSV reader and the figures.
 *
 * The CSVs are written here from closed forms, in the layout of `hamlie run`
 * (t, x, p, H, sigma, an observer): the oscillator's flow x = cos t,
 * p = -sin t, and Euler's closed form x_n = r^n cos(n a), p_n = -r^n sin(n a)
 * with r = sqrt(1 + D^2), a = atan D.  The figures are rendered in memory
 * and the pixels looked at where the closed forms put the points; bad CSVs
 * must be rejected with the file, the line and the column. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hamlie/plot.h"
#include "hamlie/runplot.h"
#include "hl_test.h"

/* fontconfig (under PLplot's cairo text) keeps process-wide caches that it
 * never frees: not leaks of hamlie's. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void)
{
    return "leak:libfontconfig.so\n";
}

#define W 640
#define H 480
#define D 0.1

static char dir[] = "/tmp/hl-runplot-XXXXXX";

static char *path_of(const char *name)
{
    static char buf[4][600];
    static int k;
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/%s", dir, name);
    return buf[k];
}

static void write_file(const char *name, const char *text)
{
    FILE *fp = fopen(path_of(name), "w");
    CHECK(fp != NULL);
    if (fp == NULL)
        return;
    fputs(text, fp);
    fclose(fp);
}

/* kind 0: the flow; 1: Euler's closed form.  n steps of D. */
static void write_run(const char *name, int kind, int n)
{
    FILE *fp = fopen(path_of(name), "w");
    CHECK(fp != NULL);
    if (fp == NULL)
        return;
    fprintf(fp, "t,x,p,H,sigma,x/p\n");
    for (int k = 0; k <= n; k++) {
        double t = k * D, r = kind ? pow(1 + D * D, 0.5 * k) : 1, a = kind ? k * atan(D) : t;
        double x = r * cos(a), p = -r * sin(a);
        double s = (x - cos(t)) * (x - cos(t)) + (p + sin(t)) * (p + sin(t));
        fprintf(fp, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", t, x, p, 0.5 * (x * x + p * p),
                kind ? s : 1e-30 * (k + 1), x / p);
    }
    fclose(fp);
}

#include "hl_pixels.h"

static long count(const unsigned char *img, color_fn fn)
{
    long n = 0;
    for (size_t i = 0; i < (size_t)W * H; i++)
        n += fn(img + 3 * i);
    return n;
}

/* ---- the reader --------------------------------------------------------- */

/* Reading `text` must fail with status st and a message holding each of the
 * NULL-terminated strings. */
static void bad(const char *text, hl_status st, const char *const *want)
{
    hl_runplot *rp = (hl_runplot *)1;
    hl_error err;
    write_file("bad.csv", text);
    hl_status got = hl_runplot_read_csv(&rp, path_of("bad.csv"), NULL, &err);
    CHECK_MSG(got == st, "status %d, not %d, for:\n%s", got, st, text);
    CHECK(rp == NULL);
    if (got == HL_OK) {
        hl_runplot_free(rp);
        return;
    }
    for (int i = 0; want[i] != NULL; i++)
        CHECK_MSG(strstr(err.msg, want[i]) != NULL, "'%s' not in '%s'", want[i], err.msg);
}

static void test_read(void)
{
    hl_runplot *rp = NULL;
    hl_error err;
    write_run("flow.csv", 0, 200);
    CHECK_MSG(hl_runplot_read_csv(&rp, path_of("flow.csv"), NULL, &err) == HL_OK, "%s",
              err.msg);
    CHECK(hl_runplot_nrows(rp) == 201);
    CHECK_STR(hl_runplot_label(rp), "flow");
    hl_runplot_free(rp);
    CHECK(hl_runplot_read_csv(&rp, path_of("flow.csv"), "my label", &err) == HL_OK);
    CHECK_STR(hl_runplot_label(rp), "my label");
    hl_runplot_free(rp);
    hl_runplot_free(NULL);

    /* accepted: inf, nan, CRLF, blank lines, a quoted name with a comma */
    write_file("ok.csv", "t,x,p,H,\"a,b\"\r\n0,1,0,0.5,inf\r\n\r\n0.1,nan,-inf,0.5,1e-3\n\n");
    CHECK_MSG(hl_runplot_read_csv(&rp, path_of("ok.csv"), NULL, &err) == HL_OK, "%s", err.msg);
    CHECK(hl_runplot_nrows(rp) == 2);
    hl_runplot_free(rp);

    const char *e1[] = {"bad.csv", "line 3", "column 2", "(x)", "'abc'", NULL};
    bad("t,x,p,H\n0,1,0,0.5\n0.1,abc,0,0.5\n", HL_EINVAL, e1);
    const char *e2[] = {"bad.csv", "line 4", "3 values", "4 columns", NULL};
    bad("t,x,p,H\n0,1,0,0.5\n0.1,1,0,0.5\n0.2,1,0\n", HL_EINVAL, e2);
    const char *e3[] = {"line 2", "5 values", "4 columns", NULL};
    bad("t,x,p,H\n0,1,0,0.5,7\n", HL_EINVAL, e3);
    const char *e4[] = {"line 2", "column 4", "(H)", NULL};
    bad("t,x,p,H\n0,1,0,\n", HL_EINVAL, e4); /* an empty value */
    const char *e5[] = {"line 1", "column 1", "'time'", NULL};
    bad("time,x,p,H\n0,1,0,0.5\n", HL_EINVAL, e5);
    const char *e6[] = {"empty file", NULL};
    bad("", HL_EINVAL, e6);
    const char *e7[] = {"no data rows", NULL};
    bad("t,x,p,H\n\n", HL_EINVAL, e7);
    const char *e8[] = {"line 1", "column 5", "unterminated", NULL};
    bad("t,x,p,H,\"abc\n0,1,0,0.5,1\n", HL_EINVAL, e8);
    const char *e9[] = {"line 2", "column 3", "(p)", "'0.5x'", NULL};
    bad("t,x,p,H\n0,1,0.5x,0.5\n", HL_EINVAL, e9);

    CHECK(hl_runplot_read_csv(&rp, path_of("missing.csv"), NULL, &err) == HL_EIO);
    CHECK(strstr(err.msg, "missing.csv") != NULL);
}

/* ---- the figures -------------------------------------------------------- */

static int find(char **names, int n, const char *name)
{
    for (int i = 0; i < n; i++)
        if (strcmp(names[i], name) == 0)
            return i;
    return -1;
}

static void test_figures(void)
{
    hl_runplot *runs[2] = {NULL, NULL};
    hl_error err;
    write_run("euler.csv", 1, 200);
    CHECK(hl_runplot_read_csv(&runs[0], path_of("flow.csv"), "exact", &err) == HL_OK);
    CHECK(hl_runplot_read_csv(&runs[1], path_of("euler.csv"), NULL, &err) == HL_OK);
    if (runs[0] == NULL || runs[1] == NULL)
        return;
    hl_figure **figs;
    char **names;
    int nfig;
    hl_runplot_opts o = HL_RUNPLOT_OPTS_DEFAULT;
    CHECK_MSG(hl_runplot_figures(&figs, &names, &nfig, runs, 2, &o, &err) == HL_OK, "%s",
              err.msg);
    const char *want[] = {"phase-x-p", "time-x", "time-p", "energy-error", "sigma",
                          "observer-1-x_p"};
    CHECK(nfig == 6);
    for (int i = 0; i < 6; i++)
        CHECK_MSG(find(names, nfig, want[i]) >= 0, "no figure %s", want[i]);

    unsigned char *img = malloc((size_t)W * H * 3);
    hl_plot_frame fr;
    /* the phase portrait: the first run (blue dots) on the unit circle, the
     * second (red squares) on Euler's spiral */
    int i = find(names, nfig, "phase-x-p");
    CHECK(i >= 0 && hl_figure_render_rgb(figs[i], W, H, img, &fr, &err) == HL_OK);
    /* (both start at (1, 0), where the second run is drawn over the first) */
    CHECK(near(img, &fr, 1, 0, 2, is_red) >= 4);
    CHECK(near(img, &fr, cos(3.0), -sin(3.0), 2, is_blue) >= 4);
    CHECK(near(img, &fr, cos(4.7), -sin(4.7), 2, is_blue) >= 4);
    for (int n = 50; n <= 200; n += 50) {
        double r = pow(1 + D * D, 0.5 * n), a = n * atan(D);
        CHECK_MSG(near(img, &fr, r * cos(a), -r * sin(a), 2, is_red) >= 4, "euler n = %d", n);
    }
    CHECK(near(img, &fr, 0, 0, 5, is_red) == 0 && near(img, &fr, 0, 0, 5, is_blue) == 0);
    /* spans of x and p compare: equal aspect, a unit is as long in x as in p */
    double ax, ay, bx, by, cx, cy;
    CHECK(hl_plot_frame_pixel(&fr, W, H, 0, 0, &ax, &ay));
    CHECK(hl_plot_frame_pixel(&fr, W, H, 1, 0, &bx, &by));
    CHECK(hl_plot_frame_pixel(&fr, W, H, 0, 1, &cx, &cy));
    CHECK_MSG(fabs((bx - ax) - (ay - cy)) < 1.5, "aspect: %g vs %g", bx - ax, ay - cy);
    /* the energy error: log axis; the flow's |H - H0| is 0 to rounding (not
     * drawn at -inf), Euler's (r^(2n) - 1)/2 */
    i = find(names, nfig, "energy-error");
    CHECK(i >= 0 && hl_figure_render_rgb(figs[i], W, H, img, &fr, &err) == HL_OK);
    CHECK(fr.ylog == 1);
    for (int n = 20; n <= 200; n += 60) {
        double dh = 0.5 * (pow(1 + D * D, n) - 1);
        CHECK_MSG(near(img, &fr, n * D, dh, 2, is_red) >= 4, "energy error n = %d", n);
    }
    /* sigma on a log axis: the flow's 1e-30 (k + 1) at its height */
    i = find(names, nfig, "sigma");
    CHECK(i >= 0 && hl_figure_render_rgb(figs[i], W, H, img, &fr, &err) == HL_OK);
    CHECK(fr.ylog == 1 && fr.wy0 < -29 && fr.wy1 > 0);
    CHECK(near(img, &fr, 10, 1e-30 * 101, 2, is_blue) >= 4);
    hl_runplot_figures_free(figs, names, nfig);

    /* x/p has poles (p = 0 at t = k pi, |x/p| up to 1e16 or inf): the axis
     * keeps the middle of the data.  For the flow alone, -cot t sampled
     * evenly, the 95th percentile is about cot(0.05 pi) = 6.3: an axis of
     * about +-12.6 (plus margins), not +-1e16 */
    CHECK(hl_runplot_figures(&figs, &names, &nfig, runs, 1, &o, &err) == HL_OK);
    i = find(names, nfig, "observer-1-x_p");
    CHECK(i >= 0 && hl_figure_render_rgb(figs[i], W, H, img, &fr, &err) == HL_OK);
    CHECK_MSG(fr.wy1 > 8 && fr.wy1 < 30 && fr.wy0 < -8 && fr.wy0 > -30, "x/p range %g..%g",
              fr.wy0, fr.wy1);
    CHECK(near(img, &fr, 1.0, -1 / tan(1.0), 2, is_blue) >= 4);
    CHECK(near(img, &fr, 2.0, -1 / tan(2.0), 2, is_blue) >= 4);
    hl_runplot_figures_free(figs, names, nfig);

    /* a long run is a line: 2001 rows of the flow, blue, through (0, 1) */
    write_run("long.csv", 0, 2000);
    hl_runplot *lr = NULL;
    CHECK(hl_runplot_read_csv(&lr, path_of("long.csv"), NULL, &err) == HL_OK);
    o.phase = "x:p";
    CHECK(hl_runplot_figures(&figs, &names, &nfig, &lr, 1, &o, &err) == HL_OK);
    CHECK(nfig == 6 && strcmp(names[0], "phase-x-p") == 0);
    CHECK(hl_figure_render_rgb(figs[0], W, H, img, &fr, &err) == HL_OK);
    CHECK(near(img, &fr, 0, 1, 1, is_blue) > 0 && near(img, &fr, -1, 0, 1, is_blue) > 0);
    CHECK(near(img, &fr, M_SQRT1_2, -M_SQRT1_2, 1, is_blue) > 0);
    CHECK(count(img, is_red) == 0);
    hl_runplot_figures_free(figs, names, nfig);

    /* --phase: any two columns; unknown ones are named */
    o.phase = "p:x/p";
    CHECK(hl_runplot_figures(&figs, &names, &nfig, runs, 2, &o, &err) == HL_OK);
    CHECK(nfig == 6 && strcmp(names[0], "phase-p-x_p") == 0);
    hl_runplot_figures_free(figs, names, nfig);
    o.phase = "x:zz";
    CHECK(hl_runplot_figures(&figs, &names, &nfig, runs, 2, &o, &err) == HL_EINVAL);
    CHECK(strstr(err.msg, "x:zz") != NULL && strstr(err.msg, "columns: t, x, p") != NULL);
    CHECK(figs == NULL && nfig == 0);
    o.phase = "xp";
    CHECK(hl_runplot_figures(&figs, &names, &nfig, runs, 2, &o, &err) == HL_EINVAL);
    o.phase = NULL;

    /* writing: 6 figures x 2 formats, files whole and of their kind */
    o.formats = "png,svg";
    int written = -1;
    char *out = path_of("figs/sub");
    CHECK_MSG(hl_runplot_write(runs, 2, out, &o, &written, &err) == HL_OK, "%s", err.msg);
    CHECK(written == 12);
    for (int k = 0; k < 6; k++) {
        char f[700];
        unsigned char head[8] = {0};
        snprintf(f, sizeof f, "%s/%s.png", out, want[k]);
        FILE *fp = fopen(f, "rb");
        CHECK_MSG(fp != NULL, "%s missing", f);
        if (fp != NULL) {
            CHECK(fread(head, 1, 8, fp) == 8 && memcmp(head, "\x89PNG\r\n\x1a\n", 8) == 0);
            fseek(fp, 0, SEEK_END);
            CHECK(ftell(fp) > 3000);
            fclose(fp);
        }
        unlink(f);
        snprintf(f, sizeof f, "%s/%s.svg", out, want[k]);
        struct stat sb;
        CHECK(stat(f, &sb) == 0 && sb.st_size > 3000);
        unlink(f);
    }
    rmdir(out);
    rmdir(path_of("figs"));
    /* plot.h's reading of the list: spaces, case, a format named twice */
    o.formats = " PNG, png";
    CHECK(hl_runplot_write(runs, 2, out, &o, &written, &err) == HL_OK && written == 6);
    for (int k = 0; k < 6; k++) {
        char f[700];
        snprintf(f, sizeof f, "%s/%s.png", out, want[k]);
        CHECK_MSG(unlink(f) == 0, "%s", f);
    }
    rmdir(out);
    rmdir(path_of("figs"));
    o.formats = "png,jpg";
    CHECK(hl_runplot_write(runs, 2, out, &o, &written, &err) == HL_EINVAL && written == 0);
    CHECK(strstr(err.msg, "jpg") != NULL);
    struct stat sb;
    CHECK(stat(path_of("figs"), &sb) != 0); /* nothing created */
    o.formats = "png";
    write_file("file", "x");
    CHECK(hl_runplot_write(runs, 2, path_of("file"), &o, &written, &err) == HL_EIO);
    unlink(path_of("file"));

    /* runs with different columns are not compared */
    write_file("other.csv", "t,x,p,H\n0,1,0,0.5\n");
    hl_runplot *other = NULL;
    CHECK(hl_runplot_read_csv(&other, path_of("other.csv"), NULL, &err) == HL_OK);
    hl_runplot *mixed[2] = {runs[0], other};
    CHECK(hl_runplot_write(mixed, 2, out, &o, &written, &err) == HL_EINVAL);
    CHECK(strstr(err.msg, "different columns") != NULL);
    CHECK(hl_runplot_write(runs, 0, out, &o, &written, &err) == HL_EINVAL);
    hl_runplot_free(other);
    free(img);
    hl_runplot_free(lr);
    hl_runplot_free(runs[0]);
    hl_runplot_free(runs[1]);
}

/* Column roles: N = 2 (x, y, px, py), built with add_row; layouts that are
 * not hamlie run's are refused. */
static void test_roles(void)
{
    hl_error err;
    const char *names[] = {"t", "x", "y", "px", "py", "H"};
    hl_runplot *rp = hl_runplot_new("hh", 6, names);
    for (int k = 0; k < 5; k++) {
        double v[6] = {k * 0.1, 1, 2, 3, 4, 5};
        CHECK(hl_runplot_add_row(rp, v, &err) == HL_OK);
    }
    CHECK(hl_runplot_nrows(rp) == 5);
    CHECK(hl_runplot_add_row(rp, NULL, &err) == HL_EINVAL);
    hl_figure **figs;
    char **fn;
    int n;
    hl_runplot_opts o = HL_RUNPLOT_OPTS_DEFAULT;
    CHECK(hl_runplot_figures(&figs, &fn, &n, &rp, 1, &o, &err) == HL_OK);
    /* phase-x-px, phase-y-py, 4 coordinates, energy error; no sigma */
    CHECK(n == 7);
    if (n == 7) {
        CHECK_STR(fn[0], "phase-x-px");
        CHECK_STR(fn[1], "phase-y-py");
        CHECK_STR(fn[5], "time-py");
        CHECK_STR(fn[6], "energy-error");
    }
    /* x spans 0..4, px 0..0.4: more than a factor 4, no equal aspect */
    hl_plot_frame fr;
    unsigned char *img = malloc((size_t)W * H * 3);
    hl_runplot_figures_free(figs, fn, n);
    hl_runplot_free(rp);
    rp = hl_runplot_new("hh", 6, names);
    for (int k = 0; k < 5; k++) {
        double v[6] = {k * 0.1, k, 0, 0.1 * k, 0, 5};
        CHECK(hl_runplot_add_row(rp, v, &err) == HL_OK);
    }
    CHECK(hl_runplot_figures(&figs, &fn, &n, &rp, 1, &o, &err) == HL_OK);
    CHECK(n == 7 && hl_figure_render_rgb(figs[0], W, H, img, &fr, &err) == HL_OK);
    /* (with equal aspect a 10:1 window would squeeze the box to a strip) */
    CHECK_MSG(fr.vx1 - fr.vx0 > 0.5 && fr.vy1 - fr.vy0 > 0.5, "box %g x %g", fr.vx1 - fr.vx0,
              fr.vy1 - fr.vy0);
    free(img);
    hl_runplot_figures_free(figs, fn, n);
    hl_runplot_free(rp);

    /* a blow-up is not clipped as a pole would be: g = e^(2t) leaves the
     * middle range at the end and never comes back; the axis reaches e^40 */
    const char *gn[] = {"t", "x", "p", "H", "g"};
    rp = hl_runplot_new("g", 5, gn);
    for (int k = 0; k <= 200; k++) {
        double v[5] = {0.1 * k, 1, 0, 0.5, exp(0.2 * k)};
        CHECK(hl_runplot_add_row(rp, v, &err) == HL_OK);
    }
    CHECK(hl_runplot_figures(&figs, &fn, &n, &rp, 1, &o, &err) == HL_OK);
    img = malloc((size_t)W * H * 3);
    CHECK(n == 5 && strcmp(fn[4], "observer-1-g") == 0);
    CHECK(n == 5 && hl_figure_render_rgb(figs[4], W, H, img, &fr, &err) == HL_OK);
    CHECK_MSG(fr.wy1 >= exp(40), "e^(2t) clipped at %g", fr.wy1);
    free(img);
    hl_runplot_figures_free(figs, fn, n);
    hl_runplot_free(rp);

    /* the legend goes to an empty corner: x = t fills the bottom left and
     * the top right of time-x, the top left is the first empty one */
    const char *ln[] = {"t", "x", "p", "H"};
    hl_runplot *two[2] = {hl_runplot_new("a", 4, ln), hl_runplot_new("b", 4, ln)};
    for (int r = 0; r < 2; r++)
        for (int k = 0; k <= 100; k++) {
            double v[4] = {0.1 * k, 0.1 * k + 0.01 * r, 0, 0.5};
            CHECK(hl_runplot_add_row(two[r], v, &err) == HL_OK);
        }
    CHECK(hl_runplot_figures(&figs, &fn, &n, two, 2, &o, &err) == HL_OK);
    CHECK(n == 4 && strcmp(fn[1], "time-x") == 0);
    img = malloc((size_t)W * H * 3);
    CHECK(n == 4 && hl_figure_render_rgb(figs[1], W, H, img, &fr, &err) == HL_OK);
    long corner[4] = {0, 0, 0, 0}; /* blue pixels: top left, top right, bottom left, right */
    for (int j = 0; j < H; j++)
        for (int i = 0; i < W; i++) {
            double fx = ((double)i / W - fr.vx0) / (fr.vx1 - fr.vx0);
            double fy = (1 - (double)j / H - fr.vy0) / (fr.vy1 - fr.vy0);
            if (fx < 0 || fx > 1 || fy < 0 || fy > 1 || !is_blue(img + 3 * ((size_t)j * W + i)))
                continue;
            if (fy > 0.8 && fx < 0.35)
                corner[0]++;
            else if (fy > 0.8 && fx > 0.65)
                corner[1]++;
            else if (fy < 0.2 && fx < 0.35)
                corner[2]++;
            else if (fy < 0.2 && fx > 0.65)
                corner[3]++;
        }
    /* the data's blue is in the top right and bottom left; the legend's
     * markers make the top left blue; the bottom right stays white */
    CHECK_MSG(corner[0] > 20 && corner[3] == 0, "blue by corner: %ld %ld %ld %ld", corner[0],
              corner[1], corner[2], corner[3]);
    free(img);
    hl_runplot_figures_free(figs, fn, n);
    hl_runplot_free(two[0]);
    hl_runplot_free(two[1]);

    const char *noH[] = {"t", "x", "p", "E"};
    rp = hl_runplot_new("a", 4, noH);
    double v[4] = {0, 1, 0, 0.5};
    CHECK(hl_runplot_add_row(rp, v, &err) == HL_OK);
    CHECK(hl_runplot_figures(&figs, &fn, &n, &rp, 1, &o, &err) == HL_EINVAL);
    CHECK(strstr(err.msg, "no column 'H'") != NULL);
    hl_runplot_free(rp);
    const char *odd[] = {"t", "x", "p", "z", "H"};
    rp = hl_runplot_new("a", 5, odd);
    double v5[5] = {0, 1, 0, 0, 0.5};
    CHECK(hl_runplot_add_row(rp, v5, &err) == HL_OK);
    CHECK(hl_runplot_figures(&figs, &fn, &n, &rp, 1, &o, &err) == HL_EINVAL);
    CHECK(strstr(err.msg, "pairs") != NULL);
    hl_runplot_free(rp);
}

int main(void)
{
    CHECK(mkdtemp(dir) != NULL);
    test_read();
    test_figures();
    test_roles();
    const char *files[] = {"flow.csv", "euler.csv", "long.csv", "ok.csv", "bad.csv",
                           "other.csv"};
    for (int i = 0; i < 6; i++)
        unlink(path_of(files[i]));
    CHECK(rmdir(dir) == 0);
    return HL_TEST_END();
}
