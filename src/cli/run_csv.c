/* hamlie run: the trajectory written as it is computed (cli/run.h): the
 * CSV in whole lines through a buffer, to stdout or to --out's FILE.tmp
 * renamed at the end, and the rows --plot keeps for its figures. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "cli/run.h"

void run_csv_flush(csv *c)
{
    if (c->fp != NULL && c->buf.len > 0 && fwrite(c->buf.s, 1, c->buf.len, c->fp) != c->buf.len)
        c->io_error = 1;
    c->buf.len = 0;
    if (c->buf.s != NULL)
        c->buf.s[0] = '\0';
    if (c->fp != NULL && fflush(c->fp) != 0)
        c->io_error = 1;
}

static void csv_num(hl_buf *b, double v)
{
    char s[40];
    s[0] = ',';
    int n = hl_run_fmt(s + 1, v);
    hl_buf_putn(b, s, (size_t)n + 1);
}

/* A row for the figures, in the CSV's column order. */
static int plot_row(csv *c, const hl_run_row *row)
{
    double *v = c->plot_row;
    int n = 0;
    v[n++] = row->t;
    for (int i = 0; i < c->n2; i++)
        v[n++] = row->z[i];
    v[n++] = row->H;
    if (c->sigma)
        v[n++] = row->sigma;
    for (int i = 0; i < c->nobs; i++)
        v[n++] = row->obs[i];
    hl_error err;
    return hl_runplot_add_row(c->plot, v, &err);
}

int run_csv_row(const hl_run_row *row, void *arg)
{
    csv *c = arg;
    if (c->plot != NULL) {
        int st = plot_row(c, row);
        if (st != HL_OK)
            return st;
    }
    if (c->fp == NULL)
        return 0;
    hl_buf *b = &c->buf;
    /* t = k dt is printed in its shortest form when 15 digits give it back */
    char ts[40];
    hl_buf_putn(b, ts, (size_t)hl_run_fmt_short(ts, row->t));
    for (int i = 0; i < c->n2; i++)
        csv_num(b, row->z[i]);
    csv_num(b, row->H);
    if (c->sigma)
        csv_num(b, row->sigma);
    for (int i = 0; i < c->nobs; i++)
        csv_num(b, row->obs[i]);
    hl_buf_putc(b, '\n');
    c->rows++;
    if (b->len >= 1 << 16)
        run_csv_flush(c);
    return c->io_error ? HL_EIO : 0;
}

void run_csv_header(csv *c, hl_system *sys, const run_opts *r)
{
    int N = hl_system_ndof(sys);
    hl_buf_puts(&c->buf, "t");
    for (int i = 0; i < 2 * N; i++) {
        hl_buf_putc(&c->buf, ',');
        hl_buf_csv_field(&c->buf, cli_phase_name(sys, i));
    }
    hl_buf_puts(&c->buf, ",H");
    if (c->sigma)
        hl_buf_puts(&c->buf, ",sigma");
    for (int i = 0; i < r->nobserve; i++) {
        hl_buf_putc(&c->buf, ',');
        hl_buf_csv_field(&c->buf, r->observe[i]);
    }
    hl_buf_putc(&c->buf, '\n');
}

/* ---- --plot --------------------------------------------------------------- */

/* The figures' store, with the CSV's columns; the label names the scheme. */
void run_plot_open(csv *c, hl_system *sys, const run_opts *r, const cli_opts *o)
{
    int N = hl_system_ndof(sys), n = 0;
    const char **names = hl_xmalloc((size_t)(2 * N + 3 + r->nobserve) * sizeof *names);
    names[n++] = "t";
    for (int i = 0; i < 2 * N; i++)
        names[n++] = cli_phase_name(sys, i);
    names[n++] = "H";
    if (c->sigma)
        names[n++] = "sigma";
    for (int i = 0; i < r->nobserve; i++)
        names[n++] = r->observe[i];
    const char *label = r->scheme ? r->scheme : o->map ? "map" : "equations";
    c->plot = hl_runplot_new(label, n, names);
    c->plot_row = hl_xmalloc((size_t)n * sizeof *c->plot_row);
    free(names);
}

/* Draw the figures of a completed run; returns the number of files or -1. */
int run_plot_write(csv *c, const run_opts *r)
{
    hl_runplot_opts po = HL_RUNPLOT_OPTS_DEFAULT;
    if (r->formats != NULL)
        po.formats = r->formats;
    int written = 0;
    hl_error err;
    hl_error_clear(&err);
    if (hl_runplot_write(&c->plot, 1, r->plot, &po, &written, &err) != HL_OK) {
        hl_error_prefix(&err, "in --plot");
        cli_fail(&err);
        return -1;
    }
    return written;
}

void run_plot_close(csv *c)
{
    hl_runplot_free(c->plot);
    free(c->plot_row);
    c->plot = NULL;
    c->plot_row = NULL;
}

int run_open_out(csv *c, const run_opts *r, char **tmpname)
{
    *tmpname = NULL;
    if (r->out == NULL) {
        c->fp = stdout;
        return CLI_OK;
    }
    size_t n = strlen(r->out) + 5;
    *tmpname = hl_xmalloc(n);
    snprintf(*tmpname, n, "%s.tmp", r->out);
    c->fp = fopen(*tmpname, "w");
    if (c->fp == NULL) {
        fprintf(stderr, "hamlie: error: cannot write '%s': %s\n", *tmpname, strerror(errno));
        return CLI_ERROR;
    }
    return CLI_OK;
}

/* Close the CSV: FILE.tmp becomes FILE on success, FILE.partial on failure. */
int run_close_out(csv *c, const run_opts *r, const char *tmpname, int ok, const hl_run_stats *s)
{
    run_csv_flush(c);
    if (tmpname == NULL)
        return c->io_error ? CLI_ERROR : CLI_OK;
    if (fclose(c->fp) != 0)
        c->io_error = 1;
    c->fp = NULL;
    if (c->io_error) {
        fprintf(stderr, "hamlie: error: writing '%s' failed\n", tmpname);
        return CLI_ERROR;
    }
    size_t n = strlen(r->out) + 9;
    char *dst = hl_xmalloc(n);
    snprintf(dst, n, ok ? "%s" : "%s.partial", r->out);
    int rc = CLI_OK;
    if (rename(tmpname, dst) != 0) {
        fprintf(stderr, "hamlie: error: cannot rename '%s' to '%s': %s\n", tmpname, dst,
                strerror(errno));
        rc = CLI_ERROR;
    } else if (!ok)
        fprintf(stderr, "hamlie: note: the %ld rows written (to t = %.17g) are kept in '%s'\n",
                c->rows, s->t, dst);
    free(dst);
    return rc;
}
