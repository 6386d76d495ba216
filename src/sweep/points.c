/* The members' starting points: a grid, random points within bounds, or the
 * lines of a CSV text.  A point is a pure function of the spec and its
 * index (random ones through splitmix64 of (seed, index)), so it never
 * depends on which thread or rank computes it. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "sweep/sweep_impl.h"

/* Steele, Lea & Flood's SplitMix64 finaliser (as in java.util.SplittableRandom). */
uint64_t sweep_splitmix64(uint64_t x)
{
    x += 0x9E3779B97F4A7C15ULL;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
    return x ^ (x >> 31);
}

/* A uniform double in [0, 1) for variable var of point i. */
static double uniform(const hl_sweep *sw, long i, int var)
{
    uint64_t x = sweep_splitmix64(
        sw->spec.seed ^ sweep_splitmix64((uint64_t)i * (uint64_t)(2 * sw->N) + (uint64_t)var));
    return (double)(x >> 11) * 0x1.0p-53;
}

void sweep_point(const hl_sweep *sw, long i, double *z)
{
    int n2 = 2 * sw->N;
    if (sw->source == SWEEP_CSV) {
        memcpy(z, sw->csv_points + (size_t)i * (size_t)n2, (size_t)n2 * sizeof *z);
        return;
    }
    if (sw->source == SWEEP_RANDOM) {
        for (int k = 0; k < n2; k++) {
            const sweep_axis *ax = &sw->axis[k];
            z[ax->var] =
                ax->n == 1 ? ax->v[0] : ax->v[0] + (ax->v[1] - ax->v[0]) * uniform(sw, i, ax->var);
        }
        return;
    }
    for (int k = n2 - 1; k >= 0; k--) { /* the last axis varies fastest */
        const sweep_axis *ax = &sw->axis[k];
        z[ax->var] = ax->v[i % ax->n];
        i /= ax->n;
    }
}

/* The variable named by [a, a+len) of text, or -1. */
static int find_var(const hl_sweep *sw, const char *text, int a, int len)
{
    for (int i = 0; i < 2 * sw->N; i++)
        if ((int)strlen(sw->var[i]) == len && strncmp(sw->var[i], text + a, (size_t)len) == 0)
            return i;
    return -1;
}

/* Each variable named once: the axes' variables from the items' names. */
static hl_status name_axes(hl_sweep *sw, const sweep_item *it, int n, const char *text,
                           const char *what, hl_error *err)
{
    int n2 = 2 * sw->N;
    char *seen = hl_xcalloc((size_t)n2, 1);
    int st = HL_OK;
    for (int k = 0; st == HL_OK && k < n; k++) {
        int v = find_var(sw, text, it[k].name, it[k].name_len);
        if (v < 0)
            st = hl_error_set(err, HL_EINVAL, text, it[k].name, it[k].name_len,
                              "%s: '%.*s' is not a variable of the system", what, it[k].name_len,
                              text + it[k].name);
        else if (seen[v])
            st = hl_error_set(err, HL_EINVAL, text, it[k].name, it[k].name_len,
                              "%s: '%s' is given twice", what, sw->var[v]);
        else {
            seen[v] = 1;
            sw->axis[k].var = v;
        }
    }
    for (int v = 0; st == HL_OK && v < n2; v++)
        if (!seen[v])
            st = hl_error_set(
                err, HL_EINVAL, text, (int)strlen(text) - 1 > 0 ? (int)strlen(text) - 1 : 0, 1,
                "%s: no value for '%s' (every variable is named once)", what, sw->var[v]);
    free(seen);
    return st;
}

/* Split [a, a+len) at ':' into at most 3 parts; returns the count (4: too many). */
static int split_colons(const char *text, int a, int len, int *pa, int *pl)
{
    int k = 0, s = a;
    for (int i = a; i <= a + len; i++)
        if (i == a + len || text[i] == ':') {
            if (k == 3)
                return 4;
            pa[k] = s;
            pl[k++] = i - s;
            s = i + 1;
        }
    return k;
}

/* The values of one name are kept (80 MB at most): a sweep of more points
 * than this along one axis would not finish anyway. */
#define SWEEP_MAX_AXIS_VALUES 10000000L

/* The count n of a:b:n: a whole number >= 0. */
static hl_status range_count(long *n, const char *text, int a, int len, const char *what,
                             hl_error *err)
{
    double c;
    int st = sweep_number(&c, text, a, len, what, err);
    if (st == HL_OK && (c != floor(c) || c < 0 || c > HL_SWEEP_MAX_MEMBERS))
        st = hl_error_set(err, HL_EINVAL, text, a, len,
                          "%s: the count of a range a:b:n is a whole number from 0 to %ld", what,
                          HL_SWEEP_MAX_MEMBERS);
    *n = (long)c;
    if (st == HL_OK && *n == 0)
        st = hl_error_set(err, HL_EINVAL, text, a, len, "%s: a range of 0 points", what);
    return st;
}

hl_status sweep_axis_values(sweep_axis *ax, const char *text, int a, int len, const char *what,
                            hl_error *err)
{
    int pa[3] = {0}, pl[3] = {0}, k = split_colons(text, a, len, pa, pl);
    if (k == 2 || k == 4)
        return hl_error_set(err, HL_EPARSE, text, a, len,
                            "%s: expected a number or a range a:b:n, not '%.*s'", what, len,
                            text + a);
    double lo, hi = 0;
    long n = 1;
    int st = sweep_number(&lo, text, pa[0], pl[0], what, err);
    if (st == HL_OK && k == 3 && (st = sweep_number(&hi, text, pa[1], pl[1], what, err)) == HL_OK)
        st = range_count(&n, text, pa[2], pl[2], what, err);
    if (st == HL_OK && ax->n + n > SWEEP_MAX_AXIS_VALUES)
        st = hl_error_set(err, HL_ELIMIT, text, a, len, "%s: more than %ld values of one name",
                          what, SWEEP_MAX_AXIS_VALUES);
    if (st != HL_OK)
        return st;
    ax->v = hl_xrealloc(ax->v, (size_t)(ax->n + n) * sizeof *ax->v);
    for (long i = 0; i < n; i++) /* the last one is b itself, not a sum's rounding */
        ax->v[ax->n + i] = i == n - 1 && n > 1
                               ? hi
                               : lo + (double)i * ((hi - lo) / (double)(n - 1 > 0 ? n - 1 : 1));
    ax->n += n;
    return HL_OK;
}

static hl_status count_points(hl_sweep *sw, const char *text, hl_error *err)
{
    double total = 1;
    for (int k = 0; k < 2 * sw->N; k++)
        total *= (double)sw->axis[k].n;
    if (total > HL_SWEEP_MAX_MEMBERS)
        return hl_error_set(err, HL_ELIMIT, text, 0, (int)strlen(text),
                            "%.3g points: more than %ld", total, HL_SWEEP_MAX_MEMBERS);
    sw->npoints = (long)total;
    return HL_OK;
}

hl_status sweep_read_grid(hl_sweep *sw, const char *text, hl_error *err)
{
    sweep_item *it;
    int n, st = sweep_items(&it, &n, text, "grid", err);
    if (st != HL_OK)
        return st;
    sw->axis = hl_xcalloc((size_t)(2 * sw->N > n ? 2 * sw->N : n), sizeof *sw->axis);
    st = name_axes(sw, it, n, text, "grid", err);
    for (int k = 0; st == HL_OK && k < n; k++)
        for (int j = 0; st == HL_OK && j < it[k].nval; j++)
            st = sweep_axis_values(&sw->axis[k], text, it[k].val[j], it[k].val_len[j], "grid", err);
    sweep_items_free(it, n);
    return st == HL_OK ? count_points(sw, text, err) : (hl_status)st;
}

/* Random bounds a:b (a <= b) or one fixed value. */
static hl_status random_bounds(sweep_axis *ax, const sweep_item *it, const char *text,
                               hl_error *err)
{
    if (it->nval != 1)
        return hl_error_set(err, HL_EPARSE, text, it->val[1], it->val_len[1],
                            "random: one range a:b or one value per variable");
    int pa[3] = {0}, pl[3] = {0}, k = split_colons(text, it->val[0], it->val_len[0], pa, pl);
    if (k > 2)
        return hl_error_set(err, HL_EPARSE, text, it->val[0], it->val_len[0],
                            "random: expected bounds a:b or a number, not '%.*s'", it->val_len[0],
                            text + it->val[0]);
    ax->v = hl_xcalloc(2, sizeof *ax->v);
    ax->n = k;
    int st = sweep_number(&ax->v[0], text, pa[0], pl[0], "random", err);
    if (st == HL_OK && k == 2)
        st = sweep_number(&ax->v[1], text, pa[1], pl[1], "random", err);
    if (st == HL_OK && k == 2 && !(ax->v[0] <= ax->v[1]))
        st = hl_error_set(err, HL_EINVAL, text, it->val[0], it->val_len[0],
                          "random: the bounds a:b need a <= b");
    return st;
}

hl_status sweep_read_random(hl_sweep *sw, const char *text, hl_error *err)
{
    sweep_item *it;
    int n, st = sweep_items(&it, &n, text, "random", err);
    if (st != HL_OK)
        return st;
    sw->axis = hl_xcalloc((size_t)(2 * sw->N > n ? 2 * sw->N : n), sizeof *sw->axis);
    st = name_axes(sw, it, n, text, "random", err);
    for (int k = 0; st == HL_OK && k < n; k++)
        st = random_bounds(&sw->axis[k], &it[k], text, err);
    sweep_items_free(it, n);
    if (st == HL_OK && !(sw->spec.nrandom >= 1 && sw->spec.nrandom <= HL_SWEEP_MAX_MEMBERS))
        st = hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                          "random points need a count from 1 to %ld, not %ld", HL_SWEEP_MAX_MEMBERS,
                          sw->spec.nrandom);
    sw->npoints = sw->spec.nrandom;
    return st;
}
