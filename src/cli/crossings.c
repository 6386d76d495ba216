/* The crossings table of run --event and section (see crossings.h). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/crossings.h"
#include "hamlie/h5.h"

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
    for (long i = 0; i < c->nfailed; i++)
        free(c->failures[i].reason);
    free(c->failures);
    c->failures = NULL;
    c->nfailed = 0;
}

void crossings_orbit_failed(crossings *c, long orbit, const hl_error *err)
{
    c->failures = hl_xrealloc(c->failures, (size_t)(c->nfailed + 1) * sizeof *c->failures);
    struct crossings_failure *x = &c->failures[c->nfailed++];
    x->orbit = orbit;
    x->status = err->status != HL_OK ? (int)err->status : (int)HL_EINVAL;
    x->reason = hl_xstrdup(err->msg[0] ? err->msg : hl_status_string(err->status));
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
    return cli_write_whole(&b, path);
}

/* ---- HDF5 ------------------------------------------------------------------ */

/* Column j of the rows (every width-th value from j), NULL when there are none. */
static const double *column(const crossings *c, int j)
{
    return c->n > 0 ? c->rows + j : NULL;
}

static void put_int_column(hl_h5 *f, const crossings *c, const char *name, int j, hl_error *err)
{
    int64_t *v = hl_xmalloc((size_t)(c->n > 0 ? c->n : 1) * sizeof *v);
    for (long k = 0; k < c->n; k++)
        v[k] = (int64_t)crossings_row(c, k)[j];
    hl_h5_int64s(f, name, v, c->n, err);
    free(v);
}

/* "crossings/orbit", "crossings/crossing", "crossings/t", one a variable, "crossings/H" */
static void put_crossings(hl_h5 *f, const crossings *c, hl_system *sys, hl_error *err)
{
    char name[300];
    hl_h5_group(f, "crossings", err);
    put_int_column(f, c, "crossings/orbit", 0, err);
    put_int_column(f, c, "crossings/crossing", 1, err);
    hl_h5_doubles(f, "crossings/t", column(c, 2), c->n, width(c), err);
    for (int i = 0; i < c->n2; i++) {
        snprintf(name, sizeof name, "crossings/%s", cli_phase_name(sys, i));
        hl_h5_doubles(f, name, column(c, 3 + i), c->n, width(c), err);
    }
    hl_h5_doubles(f, "crossings/H", column(c, 3 + c->n2), c->n, width(c), err);
}

/* "orbits/<var>0" the starts, "orbits/crossings", "orbits/status" (0 or the
 * hl_status of its failure), "orbits/reason" ("" or the message) */
static void put_orbits(hl_h5 *f, const crossings *c, hl_system *sys, const crossings_h5_info *info,
                       hl_error *err)
{
    long M = info->norbits;
    char name[300];
    hl_h5_group(f, "orbits", err);
    for (int i = 0; i < c->n2; i++) {
        snprintf(name, sizeof name, "orbits/%s0", cli_phase_name(sys, i));
        hl_h5_doubles(f, name, M > 0 ? info->seeds + i : NULL, M, c->n2, err);
    }
    int64_t *count = hl_xcalloc((size_t)(M > 0 ? M : 1), sizeof *count);
    int64_t *status = hl_xcalloc((size_t)(M > 0 ? M : 1), sizeof *status);
    const char **reason = hl_xcalloc((size_t)(M > 0 ? M : 1), sizeof *reason);
    for (long k = 0; k < c->n; k++) {
        long o = (long)crossings_row(c, k)[0];
        if (o >= 0 && o < M)
            count[o]++;
    }
    for (long k = 0; k < c->nfailed; k++)
        if (c->failures[k].orbit >= 0 && c->failures[k].orbit < M) {
            status[c->failures[k].orbit] = c->failures[k].status;
            reason[c->failures[k].orbit] = c->failures[k].reason;
        }
    hl_h5_int64s(f, "orbits/crossings", count, M, err);
    hl_h5_int64s(f, "orbits/status", status, M, err);
    hl_h5_strings(f, "orbits/reason", reason, M, 0, err);
    free(count), free(status), free(reason);
}

/* The root's attributes: the inputs, the version, the names of the columns. */
static void put_inputs(hl_h5 *f, const crossings *c, hl_system *sys, const crossings_h5_info *info,
                       hl_error *err)
{
    hl_h5_attr_string(f, NULL, "command", info->command, err);
    hl_h5_attr_string(f, NULL, "hamlie_version", HAMLIE_VERSION, err);
    hl_h5_attr_string(f, NULL, "H", info->H, err);
    hl_h5_attr_double(f, NULL, "energy", info->energy, err);
    hl_h5_attr_string(f, NULL, "energy_input", info->energy_input, err);
    hl_h5_attr_string(f, NULL, "surface", info->surface, err);
    hl_h5_attr_string(f, NULL, "direction", info->direction, err);
    hl_h5_attr_string(f, NULL, "scheme", info->scheme, err);
    hl_h5_attr_string(f, NULL, "located_on", info->located_on, err);
    if (info->tol > 0)
        hl_h5_attr_double(f, NULL, "tol", info->tol, err);
    if (info->dt > 0)
        hl_h5_attr_double(f, NULL, "dt", info->dt, err);
    hl_h5_attr_double(f, NULL, "t_max", info->t_max, err);
    hl_h5_attr_long(f, NULL, "orbits", info->norbits, err);
    hl_h5_attr_long(f, NULL, "crossings_per_orbit", info->per_orbit, err);
    const char **names = hl_xmalloc((size_t)(c->n2 + 4) * sizeof *names);
    names[0] = "orbit", names[1] = "crossing", names[2] = "t";
    for (int i = 0; i < c->n2; i++)
        names[3 + i] = cli_phase_name(sys, i);
    names[3 + c->n2] = "H";
    hl_h5_attr_strings(f, NULL, "variables", names + 3, c->n2, err);
    hl_h5_attr_strings(f, NULL, "columns", names, c->n2 + 4, err);
    free(names);
}

int crossings_write_h5(const crossings *c, hl_system *sys, const char *path,
                       const crossings_h5_info *info)
{
    hl_error err;
    hl_error_clear(&err);
    hl_h5 *f;
    if (hl_h5_create(&f, path, &err) != HL_OK)
        return cli_fail(&err);
    put_inputs(f, c, sys, info, &err); /* errors are sticky: checked at the commit */
    put_crossings(f, c, sys, &err);
    put_orbits(f, c, sys, info, &err);
    return hl_h5_commit(f, &err) == HL_OK ? CLI_OK : cli_fail(&err);
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
