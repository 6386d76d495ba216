/* The crossings table of run --event and section (see crossings.h). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/crossings.h"

void crossings_init(crossings *c, int n2)
{
    memset(c, 0, sizeof *c);
    c->n2 = n2;
}

void crossings_clear(crossings *c)
{
    free(c->rows);
    c->rows = NULL;
    c->n = c->cap = 0;
}

static int width(const crossings *c)
{
    return 3 + c->n2 + 1;
}

void crossings_add(crossings *c, long orbit, const hl_run_crossing *x)
{
    if (c->n == c->cap) {
        c->cap = c->cap ? 2 * c->cap : 256;
        c->rows = hl_xrealloc(c->rows, (size_t)c->cap * (size_t)width(c) * sizeof *c->rows);
    }
    double *r = c->rows + (size_t)c->n++ * (size_t)width(c);
    r[0] = (double)orbit;
    r[1] = (double)x->i;
    r[2] = x->t;
    memcpy(r + 3, x->z, (size_t)c->n2 * sizeof *r);
    r[3 + c->n2] = x->H;
}

const double *crossings_row(const crossings *c, long i)
{
    return c->rows + (size_t)i * (size_t)width(c);
}

static void put_csv(hl_buf *b, const crossings *c, hl_system *sys, int with_orbit)
{
    hl_buf_printf(b, "%scrossing,t", with_orbit ? "orbit," : "");
    for (int i = 0; i < c->n2; i++)
        hl_buf_printf(b, ",%s", cli_phase_name(sys, i));
    hl_buf_printf(b, ",H\n");
    char num[40];
    for (long k = 0; k < c->n; k++) {
        const double *r = crossings_row(c, k);
        if (with_orbit)
            hl_buf_printf(b, "%ld,", (long)r[0]);
        hl_buf_printf(b, "%ld", (long)r[1]);
        for (int i = 2; i < width(c); i++) {
            hl_run_fmt(num, r[i]);
            hl_buf_printf(b, ",%s", num);
        }
        hl_buf_putc(b, '\n');
    }
}

int crossings_write_csv(const crossings *c, hl_system *sys, const char *path, int with_orbit)
{
    hl_buf b;
    hl_buf_init(&b);
    put_csv(&b, c, sys, with_orbit);
    int rc = CLI_OK;
    if (strcmp(path, "-") == 0) {
        rc = cli_emit(&b, CLI_OK); /* frees b */
        return rc;
    }
    size_t n = strlen(path) + 5;
    char *tmp = hl_xmalloc(n);
    snprintf(tmp, n, "%s.tmp", path);
    FILE *fp = fopen(tmp, "w");
    if (fp == NULL) {
        fprintf(stderr, "hamlie: error: cannot write '%s': %s\n", tmp, strerror(errno));
        rc = CLI_ERROR;
    } else {
        int bad = fwrite(b.s, 1, b.len, fp) != b.len;
        bad |= fclose(fp) != 0;
        if (bad || rename(tmp, path) != 0) {
            fprintf(stderr, "hamlie: error: writing '%s' failed: %s\n", path, strerror(errno));
            remove(tmp);
            rc = CLI_ERROR;
        }
    }
    free(tmp);
    hl_buf_clear(&b);
    return rc;
}

void crossings_json(const crossings *c, hl_json *j, const char *key, hl_system *sys, int with_orbit)
{
    hl_json_key(j, key);
    hl_json_array_begin(j);
    for (long k = 0; k < c->n; k++) {
        const double *r = crossings_row(c, k);
        hl_json_object_begin(j);
        if (with_orbit)
            hl_json_kv_int(j, "orbit", (long)r[0]);
        hl_json_kv_int(j, "crossing", (long)r[1]);
        hl_json_kv_double(j, "t", r[2]);
        hl_json_key(j, "state");
        hl_json_object_begin(j);
        for (int i = 0; i < c->n2; i++)
            hl_json_kv_double(j, cli_phase_name(sys, i), r[3 + i]);
        hl_json_object_end(j);
        hl_json_kv_double(j, "H", r[3 + c->n2]);
        hl_json_object_end(j);
    }
    hl_json_array_end(j);
}

int crossings_direction(hl_event_dir *dir, const char *s)
{
    static const struct {
        const char *name;
        hl_event_dir dir;
    } names[] = {{"up", HL_EVENT_UP}, {"down", HL_EVENT_DOWN}, {"both", HL_EVENT_BOTH}};
    for (int i = 0; i < 3; i++)
        if (strcmp(s, names[i].name) == 0) {
            *dir = names[i].dir;
            return 0;
        }
    return -1;
}

const char *crossings_direction_name(hl_event_dir dir)
{
    return dir == HL_EVENT_UP ? "up" : dir == HL_EVENT_DOWN ? "down" : "both";
}
