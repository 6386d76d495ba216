/* hl_sweep_write: the table as CSV (or HDF5 through sweep_h5.c), written to
 * a temporary file beside the target and renamed when complete, so an
 * error leaves nothing half-written; the arrays in CSV sidecars beside it
 * (long format: member, t, the state).  Numbers are printed by hl_run_fmt
 * (17 digits: they read back exactly), so the same table gives the same
 * bytes. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/buf.h"
#include "hamlie/h5.h"
#include "sweep/sweep_impl.h"

static void put_row(hl_buf *b, const hl_sweep *sw, const hl_sweep_table *tab, long m)
{
    const double *row = hl_sweep_table_row(tab, m);
    char num[40];
    for (int c = 0; c < sw->ncols; c++) {
        if (c > 0)
            hl_buf_putc(b, ',');
        if (c == SWEEP_C_SCHEME)
            hl_buf_csv_field(b, sw->scheme[(int)row[c]]);
        else if (c == SWEEP_C_DT)
            hl_buf_putn(b, num, (size_t)hl_run_fmt_short(num, row[c]));
        else
            hl_buf_putn(b, num, (size_t)hl_run_fmt(num, row[c]));
    }
    hl_status st = hl_sweep_table_status(tab, m);
    hl_buf_putc(b, ',');
    hl_buf_puts(b, st == HL_OK ? "ok" : hl_status_string(st));
    hl_buf_putc(b, ',');
    hl_buf_csv_field(b, hl_sweep_table_reason(tab, m));
    hl_buf_putc(b, '\n');
}

/* Rows are formatted in blocks and written as they fill, so a large sweep
 * needs no second copy of its table in text. */
#define BLOCK_BYTES (1 << 20)

static int write_csv_fp(FILE *fp, const hl_sweep *sw, const hl_sweep_table *tab)
{
    hl_buf b;
    hl_buf_init(&b);
    for (int c = 0; c < sw->ncols; c++) {
        if (c > 0)
            hl_buf_putc(&b, ',');
        hl_buf_csv_field(&b, sw->col[c]);
    }
    hl_buf_puts(&b, ",status,reason\n");
    int ok = 1;
    for (long m = 0; ok && m < sw->count; m++) {
        put_row(&b, sw, tab, m);
        if (b.len >= BLOCK_BYTES || m == sw->count - 1) {
            ok = fwrite(b.s, 1, b.len, fp) == b.len;
            hl_buf_clear(&b);
            hl_buf_init(&b);
        }
    }
    if (ok && b.len > 0)
        ok = fwrite(b.s, 1, b.len, fp) == b.len;
    hl_buf_clear(&b);
    return ok && fflush(fp) == 0;
}

/* The array of kind in long format: member, t, the state; one line a row,
 * members in order. */
static void put_array_rows(hl_buf *b, const hl_sweep *sw, const hl_sweep_table *tab, long m,
                           int kind)
{
    long rows;
    const double *v = hl_sweep_table_array(tab, m, kind, &rows);
    int width = hl_sweep_array_width(sw);
    char num[40];
    for (long i = 0; i < rows; i++, v += width) {
        hl_buf_printf(b, "%ld,", m);
        /* a sample's time is k*dt: short when exact, as run writes it */
        hl_buf_putn(
            b, num,
            (size_t)(kind == HL_SWEEP_TRAJ ? hl_run_fmt_short(num, v[0]) : hl_run_fmt(num, v[0])));
        for (int c = 1; c < width; c++) {
            hl_buf_putc(b, ',');
            hl_buf_putn(b, num, (size_t)hl_run_fmt(num, v[c]));
        }
        hl_buf_putc(b, '\n');
    }
}

static int write_array_fp(FILE *fp, const hl_sweep *sw, const hl_sweep_table *tab, int kind)
{
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_puts(&b, "member,t");
    for (int i = 0; i < 2 * sw->N; i++) {
        hl_buf_putc(&b, ',');
        hl_buf_csv_field(&b, sw->var[i]);
    }
    hl_buf_putc(&b, '\n');
    int ok = 1;
    for (long m = 0; ok && m < sw->count; m++) {
        put_array_rows(&b, sw, tab, m, kind);
        if (b.len >= BLOCK_BYTES) {
            ok = fwrite(b.s, 1, b.len, fp) == b.len;
            b.len = 0;
        }
    }
    if (ok && b.len > 0)
        ok = fwrite(b.s, 1, b.len, fp) == b.len;
    hl_buf_clear(&b);
    return ok && fflush(fp) == 0;
}

/* One file to a temporary name beside path (*tmp, caller renames or
 * removes it): the table (kind -1) or an array. */
static hl_status write_temp(char **tmp, const char *path, const hl_sweep *sw,
                            const hl_sweep_table *tab, int kind, hl_error *err)
{
    size_t n = strlen(path) + 16;
    *tmp = hl_xmalloc(n);
    snprintf(*tmp, n, "%s.tmpXXXXXX", path);
    int fd = mkstemp(*tmp);
    if (fd >= 0) { /* mkstemp's 0600 would keep the file from its owner's group */
        mode_t mask = umask(0);
        umask(mask);
        fchmod(fd, 0666 & ~mask);
    }
    FILE *fp = fd >= 0 ? fdopen(fd, "w") : NULL;
    if (fp == NULL) {
        int e = errno;
        if (fd >= 0) {
            close(fd);
            remove(*tmp);
        }
        free(*tmp);
        *tmp = NULL;
        return hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write '%s': %s", path, strerror(e));
    }
    int ok = kind < 0 ? write_csv_fp(fp, sw, tab) : write_array_fp(fp, sw, tab, kind);
    int e = errno;
    ok = fclose(fp) == 0 && ok;
    if (ok)
        return HL_OK;
    remove(*tmp);
    free(*tmp);
    *tmp = NULL;
    return hl_error_set(err, HL_EIO, NULL, -1, 0, "writing '%s' failed: %s", path, strerror(e));
}

char *hl_sweep_array_path(const char *path, int kind)
{
    const char *slash = strrchr(path, '/'), *base = slash != NULL ? slash + 1 : path;
    const char *dot = strrchr(base, '.');
    int stem = (int)(dot != NULL && dot > base ? dot - path : (long)strlen(path));
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_printf(&b, "%.*s-%s%s", stem, path, kind == HL_SWEEP_TRAJ ? "traj" : "cross",
                  dot != NULL && dot > base ? dot : ".csv");
    return hl_buf_take(&b);
}

/* The table and its sidecars: all written to temporary names, then renamed
 * (the table last), so that an error leaves none of them. */
hl_status sweep_write_csv(const hl_sweep *sw, const hl_sweep_table *tab, const char *path,
                          hl_error *err)
{
    int arrays = sw->has_array[HL_SWEEP_TRAJ] || sw->has_array[HL_SWEEP_CROSS];
    if (strcmp(path, "-") == 0 && arrays)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the arrays go to files beside the table's: name it (not '-')");
    if (strcmp(path, "-") == 0)
        return write_csv_fp(stdout, sw, tab)
                   ? HL_OK
                   : hl_error_set(err, HL_EIO, NULL, -1, 0, "writing to standard output failed");
    char *name[HL_SWEEP_NARRAYS + 1] = {NULL}, *tmp[HL_SWEEP_NARRAYS + 1] = {NULL};
    int st = HL_OK;
    for (int k = 0; st == HL_OK && k < HL_SWEEP_NARRAYS; k++)
        if (sw->has_array[k]) {
            name[k] = hl_sweep_array_path(path, k);
            st = write_temp(&tmp[k], name[k], sw, tab, k, err);
        }
    name[HL_SWEEP_NARRAYS] = hl_xstrdup(path);
    if (st == HL_OK)
        st = write_temp(&tmp[HL_SWEEP_NARRAYS], path, sw, tab, -1, err);
    int renamed = 0; /* files in place: removed again if a later one fails */
    for (int k = 0; k <= HL_SWEEP_NARRAYS; k++) {
        if (tmp[k] == NULL || st != HL_OK)
            continue;
        if (rename(tmp[k], name[k]) == 0)
            renamed |= 1 << k;
        else
            st = hl_error_set(err, HL_EIO, NULL, -1, 0, "writing '%s' failed: %s", name[k],
                              strerror(errno));
    }
    for (int k = 0; k <= HL_SWEEP_NARRAYS; k++) {
        if (st != HL_OK && tmp[k] != NULL)
            remove(renamed >> k & 1 ? name[k] : tmp[k]);
        free(tmp[k]);
        free(name[k]);
    }
    return st;
}

hl_status hl_sweep_write(const hl_sweep *sw, const hl_sweep_table *tab, const char *path,
                         hl_error *err)
{
    if (hl_sweep_table_done(tab) != sw->count)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the table has %ld of the sweep's %ld members: nothing written",
                            hl_sweep_table_done(tab), sw->count);
    if (hl_h5_is_h5_path(path)) /* .h5 or .hdf5 */
        return hl_sweep_write_h5(sw, tab, path, err);
    return sweep_write_csv(sw, tab, path, err);
}
