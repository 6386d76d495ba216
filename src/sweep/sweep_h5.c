/* hl_sweep_write's HDF5 branch: the table in an HDF5 file through the
 * writer of h5.h (temporary file renamed when complete, same table -> same
 * bytes).  The layout (docs/sweep.md, "The HDF5 file"):
 *   /summary/<column>   one 1-D dataset per column of the table, member
 *                       order; member, point, paramset and scheme as
 *                       int64 (scheme indexes the root's "schemes"), the
 *                       others float64, NaN where the CSV has NaN
 *   /summary/status     int64: 0, or the member's hl_status
 *   /summary/reason     strings: "" or why the member failed
 *   /trajectories, /crossings   (when the sweep gives them) "data": a
 *                       rows x (2 + 2N) float64 matrix, one row a sample:
 *                       member, t, the state (its "columns" attribute
 *                       names them); "offsets": int64, members + 1 values,
 *                       member m's rows being data[offsets[m]:offsets[m+1]]
 *   /  attributes       the spec's texts and numbers, the scheme names, the
 *                       column names, the status names, hamlie's version,
 *                       the fingerprint */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "hamlie/h5.h"
#include "sweep/sweep_impl.h"

#ifndef HAMLIE_VERSION_TEXT /* set by CMake from the project's version */
#define HAMLIE_VERSION_TEXT "unknown"
#endif

/* The columns that hold indices: whole numbers, stored as int64. */
static int index_column(int c)
{
    return c == SWEEP_C_MEMBER || c == SWEEP_C_POINT || c == SWEEP_C_PARAMSET ||
           c == SWEEP_C_SCHEME;
}

static void put_column(hl_h5 *f, const hl_sweep *sw, const hl_sweep_table *tab, int c,
                       void *scratch, hl_error *err)
{
    long n = hl_sweep_count(sw);
    char name[300];
    snprintf(name, sizeof name, "summary/%s", hl_sweep_column(sw, c));
    if (index_column(c)) {
        int64_t *v = scratch;
        for (long m = 0; m < n; m++)
            v[m] = (int64_t)hl_sweep_table_row(tab, m)[c];
        hl_h5_int64s(f, name, v, n, err);
    } else {
        double *v = scratch;
        for (long m = 0; m < n; m++)
            v[m] = hl_sweep_table_row(tab, m)[c];
        hl_h5_doubles(f, name, v, n, 1, err);
    }
}

/* "summary/<column>" for every column, "summary/status", "summary/reason" */
static void put_summary(hl_h5 *f, const hl_sweep *sw, const hl_sweep_table *tab, hl_error *err)
{
    long n = hl_sweep_count(sw);
    size_t room = (size_t)(n > 0 ? n : 1);
    void *scratch = hl_xmalloc(room * sizeof(double)); /* a column at a time */
    hl_h5_group(f, "summary", err);
    for (int c = 0; c < hl_sweep_ncols(sw); c++)
        put_column(f, sw, tab, c, scratch, err);
    int64_t *status = scratch;
    for (long m = 0; m < n; m++)
        status[m] = (int64_t)hl_sweep_table_status(tab, m);
    hl_h5_int64s(f, "summary/status", status, n, err);
    free(scratch);
    const char **reason = hl_xmalloc(room * sizeof *reason);
    for (long m = 0; m < n; m++)
        reason[m] = hl_sweep_table_reason(tab, m);
    hl_h5_strings(f, "summary/reason", reason, n, 0, err);
    free(reason);
}

/* A text attribute when the spec gives it (NULL texts are left out). */
static void put_text(hl_h5 *f, const char *name, const char *value, hl_error *err)
{
    if (value != NULL)
        hl_h5_attr_string(f, NULL, name, value, err);
}

/* The spec: what was asked, as given. */
static void put_spec(hl_h5 *f, const hl_sweep_spec *spec, hl_error *err)
{
    put_text(f, "H", spec->H, err);
    put_text(f, "pairs", spec->pairs, err);
    put_text(f, "params", spec->params, err);
    put_text(f, "grid", spec->grid, err);
    put_text(f, "points_file", spec->points_csv_name, err);
    if (spec->random != NULL) {
        char seed[32];
        snprintf(seed, sizeof seed, "%" PRIu64, spec->seed); /* 64 bits: as text */
        hl_h5_attr_string(f, NULL, "random", spec->random, err);
        hl_h5_attr_long(f, NULL, "nrandom", spec->nrandom, err);
        hl_h5_attr_string(f, NULL, "seed", seed, err);
    }
    put_text(f, "schemes_input", spec->schemes, err);
    put_text(f, "dts", spec->dts, err);
    hl_h5_attr_double(f, NULL, "t", spec->t, err);
    hl_h5_attr_double(f, NULL, "tol", spec->tol > 0 ? spec->tol : 1e-15, err);
    hl_h5_attr_long(f, NULL, "reference", spec->reference != 0, err);
    hl_h5_attr_long(f, NULL, "order", spec->order != 0, err);
    hl_h5_attr_long(f, NULL, "chaos", spec->chaos != 0, err);
}

/* The names: schemes (summary/scheme indexes them), columns, statuses. */
static void put_names(hl_h5 *f, const hl_sweep *sw, hl_error *err)
{
    int ns = hl_sweep_nschemes(sw), nc = hl_sweep_ncols(sw);
    const char **names = hl_xmalloc((size_t)(ns > nc ? ns : nc) * sizeof *names);
    for (int i = 0; i < ns; i++)
        names[i] = hl_sweep_scheme(sw, i);
    hl_h5_attr_strings(f, NULL, "schemes", names, ns, err);
    for (int c = 0; c < nc; c++)
        names[c] = hl_sweep_column(sw, c);
    hl_h5_attr_strings(f, NULL, "columns", names, nc, err);
    free(names);
    const char *status[HL_ESTOP + 1];
    for (int s = 0; s <= HL_ESTOP; s++)
        status[s] = s == HL_OK ? "ok" : hl_status_string((hl_status)s);
    hl_h5_attr_strings(f, NULL, "status_names", status, HL_ESTOP + 1, err);
}

/* One kind of array as a ragged table: data (member, t, state) in member
 * order and the offsets of each member's rows. */
static void put_array(hl_h5 *f, const hl_sweep *sw, const hl_sweep_table *tab, int kind,
                      hl_error *err)
{
    const char *group = kind == HL_SWEEP_TRAJ ? "trajectories" : "crossings";
    long n = hl_sweep_count(sw), total = 0, rows;
    int width = hl_sweep_array_width(sw), cols = width + 1;
    int64_t *offsets = hl_xmalloc((size_t)(n + 1) * sizeof *offsets);
    for (long m = 0; m < n; m++) {
        offsets[m] = total;
        hl_sweep_table_array(tab, m, kind, &rows);
        total += rows;
    }
    offsets[n] = total;
    double *data = hl_xmalloc((size_t)(total > 0 ? total : 1) * (size_t)cols * sizeof *data);
    for (long m = 0; m < n; m++) {
        const double *v = hl_sweep_table_array(tab, m, kind, &rows);
        for (long i = 0; i < rows; i++) {
            double *out = data + (size_t)(offsets[m] + i) * (size_t)cols;
            out[0] = (double)m;
            memcpy(out + 1, v + (size_t)i * (size_t)width, (size_t)width * sizeof *v);
        }
    }
    char name[64];
    snprintf(name, sizeof name, "%s/data", group);
    hl_h5_group(f, group, err);
    hl_h5_matrix(f, name, data, total, cols, err);
    free(data);
    const char **names = hl_xmalloc((size_t)cols * sizeof *names);
    names[0] = "member";
    names[1] = "t";
    for (int i = 0; i < 2 * sw->N; i++)
        names[2 + i] = hl_sweep_column(sw, sw->c_z + i); /* the variables' names */
    hl_h5_attr_strings(f, name, "columns", names, cols, err);
    free(names);
    snprintf(name, sizeof name, "%s/offsets", group);
    hl_h5_int64s(f, name, offsets, n + 1, err);
    free(offsets);
    const hl_sweep_spec *spec = hl_sweep_get_spec(sw);
    if (kind == HL_SWEEP_TRAJ)
        hl_h5_attr_long(f, group, "save_every", spec->save_every, err);
    else {
        static const char *const dir[] = {"down", "both", "up"};
        hl_h5_attr_string(f, group, "event", spec->event, err);
        hl_h5_attr_string(f, group, "direction", dir[spec->direction + 1], err);
    }
}

hl_status hl_sweep_write_h5(const hl_sweep *sw, const hl_sweep_table *tab, const char *path,
                            hl_error *err)
{
    hl_h5 *f;
    hl_status st = hl_h5_create(&f, path, err);
    if (st != HL_OK)
        return st;
    char fp[32];
    snprintf(fp, sizeof fp, "%016" PRIx64, hl_sweep_fingerprint(sw));
    /* errors are sticky in the writer: checked once, at the commit */
    hl_h5_attr_string(f, NULL, "command", "sweep", err);
    hl_h5_attr_string(f, NULL, "hamlie_version", HAMLIE_VERSION_TEXT, err);
    hl_h5_attr_string(f, NULL, "fingerprint", fp, err);
    hl_h5_attr_long(f, NULL, "members", hl_sweep_count(sw), err);
    put_spec(f, hl_sweep_get_spec(sw), err);
    put_names(f, sw, err);
    put_summary(f, sw, tab, err);
    for (int k = 0; k < HL_SWEEP_NARRAYS; k++)
        if (hl_sweep_has_array(sw, k))
            put_array(f, sw, tab, k, err);
    return hl_h5_commit(f, err);
}
