/* Reading a sweep's spec (sweep.h) and its members' inputs:
 *   grid corners and values, exact (a:b:n has b itself as its last value);
 *   the member numbering (step innermost) and the parameter crossing;
 *   random points: SplitMix64 against its published first output, each
 *   point the documented function of (seed, index), the same whatever the
 *   count, within its bounds; a fixed value kept;
 *   CSV points, comments and blank lines skipped;
 *   the columns' names and the fingerprint (same spec, same value; any
 *   change, another);
 *   bad input: the message and the position in the field's text. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "sweep/sweep_impl.h"

static const char *PEND = "p^2/2 - k*cos(q)";

static hl_sweep *make(const hl_sweep_spec *spec)
{
    hl_sweep *sw = NULL;
    hl_error err;
    hl_error_clear(&err);
    int st = hl_sweep_new(&sw, spec, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    return sw;
}

static void test_grid(void)
{
    hl_sweep_spec spec = {.H = "p^2/2 - cos(q)",
                          .grid = "q=-3:3:4, p=-1:1:3,5",
                          .schemes = "stormer-verlet-kdk,rk4",
                          .dts = "0.1,0.05,0.025",
                          .t = 1};
    hl_sweep *sw = make(&spec);
    if (sw == NULL)
        return;
    CHECK(sw->npoints == 16);
    CHECK(hl_sweep_count(sw) == 16 * 2 * 3);
    double z[2];
    sweep_point(sw, 0, z);
    CHECK(z[0] == -3 && z[1] == -1);
    sweep_point(sw, 3, z); /* p varies fastest: -1, 0, 1, 5 */
    CHECK(z[0] == -3 && z[1] == 5);
    sweep_point(sw, 4, z);
    CHECK(z[0] == -1 && z[1] == -1);
    sweep_point(sw, 14, z);
    CHECK(z[0] == 3 && z[1] == 1);
    sweep_point(sw, 15, z);
    CHECK(z[0] == 3 && z[1] == 5);
    /* m = ((point * 1 + 0) * 2 + scheme) * 3 + dt */
    sweep_where w = sweep_locate(sw, (7 * 2 + 1) * 3 + 2);
    CHECK(w.point == 7 && w.paramset == 0 && w.scheme == 1 && w.dt == 2);
    CHECK_STR(hl_sweep_column(sw, 0), "member");
    CHECK_STR(hl_sweep_column(sw, 5), "q0");
    CHECK_STR(hl_sweep_column(sw, 6), "p0");
    CHECK(hl_sweep_column_index(sw, "max_dH") == 10);
    CHECK_STR(hl_sweep_column(sw, hl_sweep_ncols(sw) - 1), "p");
    CHECK(hl_sweep_ncols(sw) == 5 + 2 + 7 + 3 + 2);
    hl_sweep_free(sw);
}

static void test_params(void)
{
    hl_sweep_spec spec = {.H = "p^2/2 - k*cos(q) + eps*q",
                          .params = "k=1,2,eps=0:1:3",
                          .grid = "q=1,p=0",
                          .schemes = "rk4",
                          .dts = "0.5",
                          .t = 1};
    hl_sweep *sw = make(&spec);
    if (sw == NULL)
        return;
    CHECK(sw->nparamsets == 6);
    CHECK(hl_sweep_count(sw) == 6);
    /* paramset 4: k = 2 (the first varies slowest), eps = 0.5 */
    CHECK(sweep_param_value(sw, 4, 0) == 2 && sweep_param_value(sw, 4, 1) == 0.5);
    char *text = sweep_paramset_text(sw, 5);
    CHECK_STR(text, "k=2,eps=1");
    free(text);
    CHECK_STR(hl_sweep_column(sw, 5), "k");
    CHECK_STR(hl_sweep_column(sw, 6), "eps");
    hl_sweep_free(sw);
}

static void test_random(void)
{
    /* SplitMix64 from state 0: the first output, as published */
    CHECK(sweep_splitmix64(0) == 0xE220A8397B1DCDAFULL);
    hl_sweep_spec spec = {.H = "(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3",
                          .random = "x=0, y=-0.4:0.6, px=-1:1, py=0.25",
                          .nrandom = 1000,
                          .seed = 42,
                          .schemes = "lie",
                          .t = 1};
    hl_sweep *a = make(&spec);
    spec.nrandom = 10;
    hl_sweep *b = make(&spec);
    spec.seed = 43;
    hl_sweep *c = make(&spec);
    if (a == NULL || b == NULL || c == NULL)
        return;
    CHECK(hl_sweep_count(a) == 1000 && hl_sweep_count(b) == 10);
    double za[4], zb[4], zc[4];
    int inside = 1;
    for (long i = 0; i < 1000; i++) {
        sweep_point(a, i, za);
        inside &=
            za[0] == 0 && za[1] >= -0.4 && za[1] < 0.6 && za[2] >= -1 && za[2] < 1 && za[3] == 0.25;
    }
    CHECK(inside);
    sweep_point(a, 7, za);
    sweep_point(b, 7, zb);
    sweep_point(c, 7, zc);
    CHECK(memcmp(za, zb, sizeof za) == 0);   /* the count does not move a point */
    CHECK(za[1] != zc[1] && za[2] != zc[2]); /* the seed does */
    /* y of point 7 (variable 1 of 2N = 4): the construction of points.c */
    uint64_t x = sweep_splitmix64(42 ^ sweep_splitmix64(7 * 4 + 1));
    CHECK(za[1] == -0.4 + 1.0 * ((double)(x >> 11) * 0x1.0p-53));
    hl_sweep_free(a);
    hl_sweep_free(b);
    hl_sweep_free(c);
}

static void test_csv(void)
{
    hl_sweep_spec spec = {.H = "p^2/2 - cos(q)",
                          .points_csv = "# two points\np, q\n0.5, 1\n\n# more\n-1e-3,2.5\n",
                          .schemes = "euler",
                          .dts = "0.25",
                          .t = 1};
    hl_sweep *sw = make(&spec);
    if (sw == NULL)
        return;
    CHECK(hl_sweep_count(sw) == 2);
    double z[2];
    sweep_point(sw, 1, z);
    CHECK(z[0] == 2.5 && z[1] == -1e-3);
    hl_sweep_free(sw);
}

static void test_fingerprint(void)
{
    hl_sweep_spec spec = {
        .H = "p^2/2 - cos(q)", .grid = "q=0:1:3,p=0", .schemes = "rk4", .dts = "0.1", .t = 1};
    hl_sweep *a = make(&spec), *b = make(&spec);
    spec.t = 2;
    hl_sweep *c = make(&spec);
    spec.t = 1;
    spec.chaos = 1;
    hl_sweep *d = make(&spec);
    if (a && b && c && d) {
        CHECK(hl_sweep_fingerprint(a) == hl_sweep_fingerprint(b));
        CHECK(hl_sweep_fingerprint(a) != hl_sweep_fingerprint(c));
        CHECK(hl_sweep_fingerprint(a) != hl_sweep_fingerprint(d));
    }
    hl_sweep_free(a);
    hl_sweep_free(b);
    hl_sweep_free(c);
    hl_sweep_free(d);
}

/* ---- bad input: message and position ------------------------------------- */

typedef struct bad_case {
    const char *grid, *random, *params, *schemes, *dts, *csv;
    const char *want_msg; /* a substring */
    int want_pos;         /* in the field at fault; -1: no position */
} bad_case;

static void test_bad(void)
{
    static const bad_case cases[] = {
        {"q=1:0:0,p=0", NULL, NULL, "rk4", "0.1", NULL, "a range of 0 points", 6},
        {"q=0,x=1", NULL, NULL, "rk4", "0.1", NULL, "'x' is not a variable", 4},
        {"q=0,p=1,q=2", NULL, NULL, "rk4", "0.1", NULL, "'q' is given twice", 8},
        {"q=0", NULL, NULL, "rk4", "0.1", NULL, "no value for 'p'", -2},
        {"q=0,p=inf", NULL, NULL, "rk4", "0.1", NULL, "not finite", 6},
        {"q=0,p=1:2", NULL, NULL, "rk4", "0.1", NULL, "a number or a range a:b:n", 6},
        {"q=0,p=1:2:2.5", NULL, NULL, "rk4", "0.1", NULL, "whole number", 10},
        {"q=0,p=abc", NULL, NULL, "rk4", "0.1", NULL, "expected a number", 6},
        {"q=0,,p=1", NULL, NULL, "rk4", "0.1", NULL, "an empty entry", 4},
        {"=0,p=1", NULL, NULL, "rk4", "0.1", NULL, "a name is missing", 0},
        {"q=0,p=1", NULL, NULL, "rk4,nosuch", "0.1", NULL, "schemes:", 4},
        {"q=0,p=1", NULL, NULL, "rk4", "0.1,0.3", NULL, "not reachable", 4},
        {"q=0,p=1", NULL, NULL, "rk4", "0.1,-1", NULL, "dt:", 4},
        {"q=0,p=1", NULL, "k=1,zz=2", "rk4", "0.1", NULL, "'zz' is not a parameter", 4},
        {NULL, "q=1:0,p=0", NULL, "rk4", "0.1", NULL, "a <= b", 2},
        {NULL, NULL, NULL, "rk4", "0.1", "q,p\n1,2\n3\n", "2 values expected, 1 given", 8},
        {NULL, NULL, NULL, "rk4", "0.1", "q,p,q\n", "'q' is given twice", 4},
        {NULL, NULL, NULL, "rk4", "0.1", "q,p\n", "no points after the header", -2},
        {NULL, NULL, NULL, "rk4", "0.1", "q,p\n1,nan\n", "not finite", 6},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const bad_case *c = &cases[i];
        hl_sweep_spec spec = {.H = PEND,
                              .params = c->params ? c->params : "k=1",
                              .grid = c->grid,
                              .random = c->random,
                              .nrandom = 5,
                              .points_csv = c->csv,
                              .schemes = c->schemes,
                              .dts = c->dts,
                              .t = 1};
        hl_sweep *sw = NULL;
        hl_error err;
        hl_error_clear(&err);
        int st = hl_sweep_new(&sw, &spec, &err);
        CHECK_MSG(st != HL_OK && sw == NULL, "case %zu accepted", i);
        CHECK_MSG(strstr(err.msg, c->want_msg) != NULL, "case %zu: '%s', want '%s'", i, err.msg,
                  c->want_msg);
        if (c->want_pos >= 0) {
            const char *fields[] = {c->grid, c->random, spec.params, c->schemes, c->dts, c->csv};
            int in_field = 0;
            for (int f = 0; f < 6; f++)
                in_field |= fields[f] != NULL && err.src == fields[f];
            CHECK_MSG(in_field && err.pos == c->want_pos, "case %zu: pos %d, want %d (%s)", i,
                      err.pos, c->want_pos, err.msg);
        }
    }
    /* no source, two sources, no scheme, no t */
    hl_sweep_spec none = {.H = PEND, .params = "k=1", .schemes = "rk4", .dts = "0.1", .t = 1};
    hl_sweep *sw = NULL;
    hl_error err;
    CHECK(hl_sweep_new(&sw, &none, &err) == HL_EINVAL && strstr(err.msg, "exactly one"));
    none.grid = "q=0,p=0";
    none.t = 0;
    CHECK(hl_sweep_new(&sw, &none, &err) == HL_EINVAL && strstr(err.msg, "final time"));
    none.t = 1;
    none.params = NULL;
    none.chaos = 1; /* k has no value: said once, not per member */
    CHECK(hl_sweep_new(&sw, &none, &err) != HL_OK);
    none.params = "k=1";
    none.dts = NULL;
    CHECK(hl_sweep_new(&sw, &none, &err) == HL_EINVAL && strstr(err.msg, "no step"));
    hl_sweep_spec big = {.H = PEND,
                         .params = "k=0:1:100000",
                         .grid = "q=0:1:100000,p=0:1:1000",
                         .schemes = "rk4",
                         .dts = "0.1",
                         .t = 1};
    CHECK(hl_sweep_new(&sw, &big, &err) == HL_ELIMIT);
}

int main(void)
{
    test_grid();
    test_params();
    test_random();
    test_csv();
    test_fingerprint();
    test_bad();
    return HL_TEST_END();
}
