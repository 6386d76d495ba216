/* The run plot's reader of `hamlie run`'s CSV (runplot.h:
 * hl_runplot_read_csv): quoted fields, a header of names, numbers checked
 * field by field with the line and column named in errors, and |H - H0|
 * from the text in Arb when H has more digits than a double holds (a
 * --digits run), so that the energy error is not rounding of the read. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <arb.h>

#include "base/buf.h"
#include "report/runplot_impl.h"

#define RP_MAX_COLS 100000

/* The next field of line s from *pos (CSV: "..." with "" for a quote).
 * Returns the field (malloc'd) and moves *pos past its comma; NULL with
 * *bad set on an unterminated quote. */
static char *next_field(const char *s, size_t *pos, int *bad)
{
    hl_buf b;
    hl_buf_init(&b);
    size_t i = *pos;
    if (s[i] == '"') {
        for (i++;; i++) {
            if (s[i] == '\0') {
                *bad = 1;
                hl_buf_clear(&b);
                return NULL;
            }
            if (s[i] == '"') {
                if (s[i + 1] == '"') {
                    hl_buf_putc(&b, '"');
                    i++;
                    continue;
                }
                i++;
                break;
            }
            hl_buf_putc(&b, s[i]);
        }
        if (s[i] != ',' && s[i] != '\0') {
            *bad = 1;
            hl_buf_clear(&b);
            return NULL;
        }
    } else {
        size_t n = strcspn(s + i, ",");
        hl_buf_putn(&b, s + i, n);
        i += n;
    }
    if (s[i] == ',')
        i++;
    *pos = i;
    return hl_buf_take(&b);
}

static char *trim(char *s)
{
    while (*s == ' ' || *s == '\t')
        s++;
    size_t n = strlen(s);
    while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t'))
        s[--n] = '\0';
    return s;
}

/* A number as `hamlie run` writes it (strtod: also inf, -inf, nan). */
static int parse_number(double *v, const char *s)
{
    char *end;
    if (*s == '\0')
        return 0;
    *v = strtod(s, &end);
    return *end == '\0';
}

/* Read one line (any length) into *line (getline's buffer) without its
 * '\n' / "\r\n"; 0 at the end. */
static int read_line(char **line, size_t *cap, FILE *fp, int *io_error)
{
    ssize_t n = getline(line, cap, fp);
    if (n < 0) {
        if (ferror(fp))
            *io_error = 1;
        return 0;
    }
    if (n > 0 && (*line)[n - 1] == '\n')
        (*line)[--n] = '\0';
    if (n > 0 && (*line)[n - 1] == '\r')
        (*line)[--n] = '\0';
    return 1;
}

/* The header: names, the first "t"; roles are checked at write time. */
static hl_status read_header(char ***names, int *ncols, const char *line, const char *path,
                             hl_error *err)
{
    size_t pos = 0;
    int bad = 0, n = 0;
    char **v = NULL;
    do {
        char *f = next_field(line, &pos, &bad);
        if (f == NULL) {
            for (int i = 0; i < n; i++)
                free(v[i]);
            free(v);
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "%s: line 1, column %d: unterminated quoted name", path, n + 1);
        }
        v = hl_xrealloc(v, (size_t)(n + 1) * sizeof *v);
        char *t = trim(f);
        memmove(f, t, strlen(t) + 1);
        v[n++] = f;
    } while (line[pos] != '\0' && n < RP_MAX_COLS);
    if (line[pos] != '\0') {
        for (int i = 0; i < n; i++)
            free(v[i]);
        free(v);
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0, "%s: line 1: more than %d columns", path,
                            RP_MAX_COLS);
    }
    /* a trailing comma means one more (empty) field */
    if (pos > 0 && line[pos - 1] == ',' && line[pos] == '\0') {
        v = hl_xrealloc(v, (size_t)(n + 1) * sizeof *v);
        v[n++] = hl_xstrdup("");
    }
    hl_status st = HL_OK;
    if (strcmp(v[0], "t") != 0)
        st = hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                          "%s: line 1, column 1: the first column must be 't', not '%s' "
                          "(is this a CSV written by hamlie run?)",
                          path, v[0]);
    for (int i = 0; st == HL_OK && i < n; i++)
        if (v[i][0] == '\0')
            st = hl_error_set(err, HL_EINVAL, NULL, -1, 0, "%s: line 1, column %d: empty name",
                              path, i + 1);
    if (st != HL_OK) {
        for (int i = 0; i < n; i++)
            free(v[i]);
        free(v);
        return st;
    }
    *names = v;
    *ncols = n;
    return HL_OK;
}

/* One data row into values[ncols].  Unquoted fields (all of hamlie run's)
 * are read in place; a quoted one goes through next_field. */
static hl_status read_row(double *values, const char *line, int ncols, char *const *names,
                          const char *path, long lineno, hl_error *err)
{
    size_t pos = 0;
    int bad = 0;
    for (int j = 0; j < ncols; j++) {
        if (j > 0 && (pos == 0 || line[pos - 1] != ','))
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "%s: line %ld: %d values, the header names %d columns", path,
                                lineno, j, ncols);
        const char *s = line + pos;
        size_t n = strcspn(s, ",\"");
        if (s[n] != '"') { /* the fast path: strtod where the field is */
            char *end;
            while (*s == ' ' || *s == '\t')
                s++;
            values[j] = strtod(s, &end);
            while (*end == ' ' || *end == '\t')
                end++;
            if (end != s && (*end == ',' || *end == '\0')) {
                pos = (size_t)(end - line) + (*end == ',');
                continue;
            }
        }
        char *f = next_field(line, &pos, &bad);
        if (f == NULL)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "%s: line %ld, column %d (%s): unterminated quote", path, lineno,
                                j + 1, names[j]);
        int ok = parse_number(&values[j], trim(f));
        if (!ok) {
            hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                         "%s: line %ld, column %d (%s): '%.40s' is not a number", path, lineno,
                         j + 1, names[j], trim(f));
            free(f);
            return HL_EINVAL;
        }
        free(f);
    }
    if (line[pos] != '\0' || (pos > 0 && line[pos - 1] == ',')) {
        int extra = 1;
        for (size_t i = pos; line[i] != '\0'; i++)
            extra += line[i] == ',';
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "%s: line %ld: %d values, the header names %d columns", path, lineno,
                            ncols + extra, ncols);
    }
    return HL_OK;
}

/* More significant digits than a double's 17 ("%.17g" is at most 24
 * characters): the text of a --digits run, read in Arb. */
#define RP_DOUBLE_TEXT 24

static char *copy_n(const char *s, size_t n)
{
    char *c = hl_xmalloc(n + 1);
    memcpy(c, s, n);
    c[n] = '\0';
    return c;
}

/* Field j of an unquoted line (a number field of hamlie run's CSV), its
 * length in *n. */
static const char *field_at(const char *line, int j, size_t *n)
{
    for (; j > 0 && line != NULL; j--) {
        line = strchr(line, ',');
        line = line != NULL ? line + 1 : NULL;
    }
    if (line == NULL)
        return NULL;
    *n = strcspn(line, ",");
    return line;
}

/* |H - H0| from the texts of H and H0 when one has more digits than a
 * double holds (a difference of 1e-30 in H = 0.5 would be 0 in doubles);
 * NAN when both are doubles' texts or Arb cannot read them. */
static double dH_text(const char *h, size_t nh, const char *h0, size_t nh0)
{
    if (h == NULL || h0 == NULL || (nh <= RP_DOUBLE_TEXT && nh0 <= RP_DOUBLE_TEXT))
        return NAN;
    char *a = copy_n(h, nh), *b = copy_n(h0, nh0);
    slong prec = 4 * (slong)(nh > nh0 ? nh : nh0) + 64; /* > log2(10) bits a digit */
    arb_t x, y;
    arb_init(x), arb_init(y);
    double d = NAN;
    if (arb_set_str(x, a, prec) == 0 && arb_set_str(y, b, prec) == 0) {
        arb_sub(x, x, y, prec);
        arb_abs(x, x);
        d = arf_get_d(arb_midref(x), ARF_RND_NEAR);
    }
    arb_clear(x), arb_clear(y);
    free(a), free(b);
    return d;
}

static const char *base_name(const char *path)
{
    const char *s = strrchr(path, '/');
    return s != NULL ? s + 1 : path;
}

hl_status hl_runplot_read_csv(hl_runplot **out, const char *path, const char *label, hl_error *err)
{
    *out = NULL;
    FILE *fp = fopen(path, "r");
    if (fp == NULL)
        return hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot read '%s': %s", path,
                            strerror(errno));
    char *line = NULL;
    size_t cap = 0;
    int io_error = 0, ncols = 0;
    char **names = NULL;
    hl_runplot *rp = NULL;
    hl_status st = HL_OK;
    if (!read_line(&line, &cap, fp, &io_error))
        st = io_error
                 ? hl_error_set(err, HL_EIO, NULL, -1, 0, "reading '%s' failed", path)
                 : hl_error_set(err, HL_EINVAL, NULL, -1, 0, "%s: empty file (no header)", path);
    else
        st = read_header(&names, &ncols, line, path, err);
    if (st == HL_OK) {
        char *lab = NULL;
        if (label == NULL) { /* the base name without its .csv */
            lab = hl_xstrdup(base_name(path));
            size_t n = strlen(lab);
            if (n > 4 && strcasecmp(lab + n - 4, ".csv") == 0)
                lab[n - 4] = '\0';
        }
        rp = hl_runplot_new(label != NULL ? label : lab, ncols, (const char *const *)names);
        free(lab);
        double *values = hl_xmalloc((size_t)ncols * sizeof *values);
        char *H0 = NULL; /* the first row's H, as written */
        size_t nH0 = 0;
        for (long lineno = 2; st == HL_OK && read_line(&line, &cap, fp, &io_error); lineno++) {
            if (trim(line)[0] == '\0')
                continue; /* blank lines (a final newline) */
            st = read_row(values, line, ncols, names, path, lineno, err);
            size_t nH = 0;
            const char *h = rp->iH >= 0 ? field_at(line, rp->iH, &nH) : NULL;
            if (st == HL_OK && h != NULL && H0 == NULL)
                H0 = copy_n(h, nH), nH0 = nH;
            if (st == HL_OK)
                st = hl_runplot_add_row_dH_(rp, values, dH_text(h, nH, H0, nH0), err);
        }
        free(H0);
        free(values);
        if (st == HL_OK && io_error)
            st = hl_error_set(err, HL_EIO, NULL, -1, 0, "reading '%s' failed", path);
        if (st == HL_OK && rp->nrows == 0)
            st = hl_error_set(err, HL_EINVAL, NULL, -1, 0, "%s: no data rows after the header",
                              path);
    }
    for (int i = 0; i < ncols; i++)
        free(names[i]);
    free(names);
    free(line);
    fclose(fp);
    if (st != HL_OK) {
        hl_runplot_free(rp);
        return st;
    }
    *out = rp;
    return HL_OK;
}
