/* The members' points from CSV text: a header naming every variable once,
 * then one point a line ('#' lines and blank lines skipped), read with the
 * tokenizer the section's reader uses too (base/csv.h); errors point at
 * the field in the text. */
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "base/csv.h"
#include "sweep/sweep_impl.h"

typedef struct csv_reader {
    hl_sweep *sw;
    const char *text;
    int *col; /* column -> variable */
    hl_error *err;
} csv_reader;

static hl_status read_header(csv_reader *r, int a, int b)
{
    int n2 = 2 * r->sw->N, ncol = 0, st = HL_OK, fa, fb;
    char *seen = hl_xcalloc((size_t)n2, 1);
    r->col = hl_xcalloc((size_t)n2, sizeof *r->col);
    for (int f = a; st == HL_OK && hl_csv_field(r->text, b, &f, &fa, &fb);) {
        int var = hl_csv_name(r->text, fa, fb, (const char *const *)r->sw->var, n2);
        if (var < 0)
            st = hl_error_set(r->err, HL_EINVAL, r->text, fa, fb > fa ? fb - fa : 1,
                              "'%.*s' is not a variable of the system", fb - fa, r->text + fa);
        else if (seen[var])
            st = hl_error_set(r->err, HL_EINVAL, r->text, fa, fb - fa, "'%s' is given twice",
                              r->sw->var[var]);
        else {
            seen[var] = 1;
            r->col[ncol++] = var;
        }
    }
    for (int i = 0; st == HL_OK && i < n2; i++)
        if (!seen[i])
            st =
                hl_error_set(r->err, HL_EINVAL, r->text, a, b > a ? b - a : 1,
                             "no column for '%s' (the header names every variable)", r->sw->var[i]);
    free(seen);
    return st;
}

static hl_status read_point(csv_reader *r, int a, int b, double *z)
{
    int n2 = 2 * r->sw->N, k = 0, fa, fb;
    for (int f = a; hl_csv_field(r->text, b, &f, &fa, &fb); k++) {
        if (k == n2)
            return hl_error_set(r->err, HL_EINVAL, r->text, fa, fb > fa ? fb - fa : 1,
                                "%d values expected, more given", n2);
        int st = sweep_number(&z[r->col[k]], r->text, fa, fb - fa, r->sw->var[r->col[k]], r->err);
        if (st != HL_OK)
            return st;
    }
    if (k < n2)
        return hl_error_set(r->err, HL_EINVAL, r->text, b > a ? b - 1 : a, 1,
                            "%d values expected, %d given", n2, k);
    return HL_OK;
}

hl_status sweep_read_csv(hl_sweep *sw, const char *text, hl_error *err)
{
    csv_reader r = {sw, text, NULL, err};
    int st = HL_OK, header = 0, len = (int)strlen(text), n2 = 2 * sw->N, ta, tb;
    long n = 0, cap = 0;
    hl_csv c;
    hl_csv_init(&c, text);
    while (st == HL_OK && hl_csv_line(&c, &ta, &tb)) {
        if (!header) {
            st = read_header(&r, ta, tb);
            header = 1;
        } else if (n >= HL_SWEEP_MAX_MEMBERS) {
            st = hl_error_set(err, HL_ELIMIT, text, ta, 1, "more than %ld points",
                              HL_SWEEP_MAX_MEMBERS);
        } else {
            if (n == cap) {
                cap = cap ? 2 * cap : 64;
                sw->csv_points =
                    hl_xrealloc(sw->csv_points, (size_t)cap * (size_t)n2 * sizeof(double));
            }
            st = read_point(&r, ta, tb, sw->csv_points + (size_t)n * (size_t)n2);
            n++;
        }
    }
    free(r.col);
    if (st == HL_OK && n == 0)
        st = hl_error_set(err, HL_EINVAL, text, len > 0 ? len - 1 : 0, 1,
                          header ? "no points after the header"
                                 : "no header: the first line names the variables");
    sw->npoints = n;
    return st;
}
