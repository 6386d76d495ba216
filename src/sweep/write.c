/* hl_sweep_write: the table as CSV (or HDF5 through sweep_h5.c), written to
 * a temporary file beside the target and renamed when complete, so an
 * error leaves nothing half-written.  Numbers are printed by hl_run_fmt
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

hl_status sweep_write_csv(const hl_sweep *sw, const hl_sweep_table *tab, const char *path,
                          hl_error *err)
{
    if (strcmp(path, "-") == 0)
        return write_csv_fp(stdout, sw, tab)
                   ? HL_OK
                   : hl_error_set(err, HL_EIO, NULL, -1, 0, "writing to standard output failed");
    size_t n = strlen(path) + 16;
    char *tmp = hl_xmalloc(n);
    snprintf(tmp, n, "%s.tmpXXXXXX", path);
    int fd = mkstemp(tmp);
    if (fd >= 0) { /* mkstemp's 0600 would keep the file from its owner's group */
        mode_t mask = umask(0);
        umask(mask);
        fchmod(fd, 0666 & ~mask);
    }
    FILE *fp = fd >= 0 ? fdopen(fd, "w") : NULL;
    int st = HL_OK;
    if (fp == NULL) {
        st = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write '%s': %s", path, strerror(errno));
        if (fd >= 0) {
            close(fd);
            remove(tmp);
        }
    } else {
        int ok = write_csv_fp(fp, sw, tab);
        int e = errno;
        ok = fclose(fp) == 0 && ok;
        if (ok && rename(tmp, path) != 0) {
            e = errno;
            ok = 0;
        }
        if (!ok) {
            remove(tmp);
            st = hl_error_set(err, HL_EIO, NULL, -1, 0, "writing '%s' failed: %s", path,
                              strerror(e));
        }
    }
    free(tmp);
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
