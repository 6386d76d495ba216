/* Reading the points of a section from CSV text (see hamlie/section.h:
 * hl_section_read_points), with the tokenizer the sweep's reader uses too
 * (base/csv.h). */
#include <errno.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "base/csv.h"
#include "hamlie/section.h"

typedef struct reader {
    hl_section *s;
    hl_system *sys;
    const char *text;
    int N, solved, j; /* 2N values; the solved index; the section's q_j */
    int ncol;
    int *col; /* column -> variable index */
    hl_error *err;
} reader;

static const char *var_name(hl_system *sys, int i)
{
    int N = hl_system_ndof(sys);
    return i < N ? hl_system_coord(sys, i) : hl_system_momentum(sys, i - N);
}

/* The header line [a, b): the columns' variables. */
static int read_header(reader *r, int a, int b)
{
    char *seen = hl_xcalloc((size_t)(2 * r->N), 1);
    const char **names = hl_xcalloc((size_t)(2 * r->N), sizeof *names);
    for (int i = 0; i < 2 * r->N; i++)
        names[i] = var_name(r->sys, i);
    int st = HL_OK, fa, fb;
    for (int f = a; st == HL_OK && hl_csv_field(r->text, b, &f, &fa, &fb);) {
        int var = hl_csv_name(r->text, fa, fb, names, 2 * r->N);
        if (var < 0)
            st = hl_error_set(r->err, HL_EINVAL, r->text, fa, fb > fa ? fb - fa : 1,
                              "'%.*s' is not a variable of the system", fb - fa, r->text + fa);
        else if (var == r->solved)
            st = hl_error_set(r->err, HL_EINVAL, r->text, fa, fb - fa,
                              "'%s' is solved from H = E: leave its column out",
                              var_name(r->sys, var));
        else if (seen[var])
            st = hl_error_set(r->err, HL_EINVAL, r->text, fa, fb - fa, "'%s' is given twice",
                              var_name(r->sys, var));
        if (st != HL_OK)
            break;
        seen[var] = 1;
        r->col = hl_xrealloc(r->col, (size_t)(r->ncol + 1) * sizeof *r->col);
        r->col[r->ncol++] = var;
    }
    free(names);
    for (int i = 0; st == HL_OK && i < 2 * r->N; i++)
        if (!seen[i] && i != r->solved && i != r->j)
            st = hl_error_set(r->err, HL_EINVAL, r->text, a, b > a ? b - a : 1,
                              "no column for '%s' (the header names the point's variables)",
                              var_name(r->sys, i));
    free(seen);
    return st;
}

/* One point from the line [a, b) into z. */
static int read_point(reader *r, int a, int b, double *z)
{
    memset(z, 0, (size_t)(2 * r->N) * sizeof *z);
    z[r->j] = hl_section_value(r->s);
    int k = 0, fa, fb;
    for (int f = a; k <= r->ncol && hl_csv_field(r->text, b, &f, &fa, &fb); k++) {
        if (k == r->ncol)
            return hl_error_set(r->err, HL_EINVAL, r->text, fa, fb > fa ? fb - fa : 1,
                                "%d values expected, more given", r->ncol);
        char buf[64];
        int len = fb - fa < 63 ? fb - fa : 63;
        memcpy(buf, r->text + fa, (size_t)len);
        buf[len] = '\0';
        char *end;
        errno = 0;
        double v = strtod(buf, &end);
        if (fb == fa || *end != '\0' || fb - fa > 63 || !isfinite(v))
            return hl_error_set(r->err, HL_EPARSE, r->text, fa, fb > fa ? fb - fa : 1,
                                "expected a finite number for '%s'", var_name(r->sys, r->col[k]));
        if (r->col[k] == r->j && v != z[r->j])
            return hl_error_set(r->err, HL_EINVAL, r->text, fa, fb - fa,
                                "the point is not on the section: %s = %.17g, not %.17g",
                                var_name(r->sys, r->j), v, z[r->j]);
        z[r->col[k]] = v;
    }
    if (k < r->ncol)
        return hl_error_set(r->err, HL_EINVAL, r->text, b, 1, "%d values expected, %d given",
                            r->ncol, k);
    return HL_OK;
}

hl_status hl_section_read_points(hl_section *s, const char *text, double **zs, int *n,
                                 hl_error *err)
{
    *zs = NULL;
    *n = 0;
    reader r = {s, NULL, text, 0, 0, hl_section_coord(s), 0, NULL, err};
    r.sys = hl_section_system(s);
    r.N = hl_system_ndof(r.sys);
    r.solved = hl_section_momentum(s);
    int st = HL_OK, header = 0, len = (int)strlen(text), ta, tb;
    double *pts = NULL;
    hl_csv c;
    hl_csv_init(&c, text);
    while (st == HL_OK && hl_csv_line(&c, &ta, &tb)) {
        if (!header) {
            st = read_header(&r, ta, tb);
            header = 1;
        } else if (*n >= HL_SECTION_MAX_POINTS) {
            st = hl_error_set(err, HL_ELIMIT, text, ta, 1, "more than %d points",
                              HL_SECTION_MAX_POINTS);
        } else {
            pts = hl_xrealloc(pts, (size_t)(*n + 1) * (size_t)(2 * r.N) * sizeof *pts);
            double *z = pts + (size_t)*n * (size_t)(2 * r.N);
            st = read_point(&r, ta, tb, z);
            if (st == HL_OK && (st = hl_section_complete(s, z, err)) != HL_OK)
                hl_error_prefix(err, "the point on line %d", c.line);
            (*n)++;
        }
    }
    if (st == HL_OK && *n == 0)
        st = hl_error_set(err, HL_EINVAL, text, len, 1,
                          header ? "no points (only the header)" : "no header and no points");
    free(r.col);
    if (st != HL_OK) {
        free(pts);
        *n = 0;
        return st;
    }
    *zs = pts;
    return HL_OK;
}
