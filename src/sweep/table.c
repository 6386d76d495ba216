/* The table of a sweep's results in member order: one row of doubles, a
 * status and a reason per member, and its arrays when the sweep gives
 * them, filled as results arrive in any order. */
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "sweep/sweep_impl.h"

struct hl_sweep_table {
    long count;
    int ncols;
    double *rows;          /* count * ncols */
    unsigned char *has;    /* count */
    unsigned char *status; /* count: hl_status */
    char **reason;         /* count: NULL for "" */
    long done;
    int width;                        /* of an array's row */
    double **array[HL_SWEEP_NARRAYS]; /* count each, for the kinds the sweep gives */
    long *nrows[HL_SWEEP_NARRAYS];
};

hl_sweep_table *hl_sweep_table_new(const hl_sweep *sw)
{
    hl_sweep_table *tab = calloc(1, sizeof *tab);
    if (tab == NULL)
        return NULL;
    tab->count = sw->count;
    tab->ncols = sw->ncols;
    size_t n = (size_t)(sw->count > 0 ? sw->count : 1);
    tab->rows = malloc(n * (size_t)sw->ncols * sizeof *tab->rows);
    tab->has = calloc(n, 1);
    tab->status = calloc(n, 1);
    tab->reason = calloc(n, sizeof *tab->reason);
    int fail = tab->rows == NULL || tab->has == NULL || tab->status == NULL || tab->reason == NULL;
    tab->width = hl_sweep_array_width(sw);
    for (int k = 0; k < HL_SWEEP_NARRAYS; k++)
        if (sw->has_array[k]) {
            tab->array[k] = calloc(n, sizeof *tab->array[k]);
            tab->nrows[k] = calloc(n, sizeof *tab->nrows[k]);
            fail |= tab->array[k] == NULL || tab->nrows[k] == NULL;
        }
    if (fail) {
        hl_sweep_table_free(tab);
        return NULL;
    }
    return tab;
}

void hl_sweep_table_free(hl_sweep_table *tab)
{
    if (tab == NULL)
        return;
    for (long i = 0; tab->reason != NULL && i < tab->count; i++)
        free(tab->reason[i]);
    free(tab->reason);
    free(tab->rows);
    free(tab->has);
    free(tab->status);
    for (int k = 0; k < HL_SWEEP_NARRAYS; k++) {
        for (long i = 0; tab->array[k] != NULL && i < tab->count; i++)
            free(tab->array[k][i]);
        free(tab->array[k]);
        free(tab->nrows[k]);
    }
    free(tab);
}

/* r's arrays, copied into the table (replacing what member m had). */
static void store_arrays(hl_sweep_table *tab, const hl_sweep_result *r)
{
    long m = r->member;
    for (int k = 0; k < HL_SWEEP_NARRAYS; k++) {
        if (tab->array[k] == NULL)
            continue;
        free(tab->array[k][m]);
        tab->array[k][m] = NULL;
        tab->nrows[k][m] = r->array[k] != NULL ? r->nrows[k] : 0;
        size_t bytes = (size_t)tab->nrows[k][m] * (size_t)tab->width * sizeof(double);
        if (bytes > 0) {
            tab->array[k][m] = hl_xmalloc(bytes);
            memcpy(tab->array[k][m], r->array[k], bytes);
        }
    }
}

int hl_sweep_table_store(const hl_sweep_result *r, void *arg)
{
    hl_sweep_table *tab = arg;
    if (r->member < 0 || r->member >= tab->count)
        return 0;
    long m = r->member;
    memcpy(tab->rows + (size_t)m * (size_t)tab->ncols, r->row,
           (size_t)tab->ncols * sizeof *tab->rows);
    tab->done += !tab->has[m];
    tab->has[m] = 1;
    tab->status[m] = (unsigned char)r->status;
    free(tab->reason[m]);
    tab->reason[m] = r->reason[0] ? hl_xstrdup(r->reason) : NULL;
    store_arrays(tab, r);
    return 0;
}

int hl_sweep_table_has(const hl_sweep_table *tab, long m)
{
    return m >= 0 && m < tab->count && tab->has[m];
}

const double *hl_sweep_table_row(const hl_sweep_table *tab, long m)
{
    return hl_sweep_table_has(tab, m) ? tab->rows + (size_t)m * (size_t)tab->ncols : NULL;
}

hl_status hl_sweep_table_status(const hl_sweep_table *tab, long m)
{
    return hl_sweep_table_has(tab, m) ? (hl_status)tab->status[m] : HL_EINVAL;
}

const char *hl_sweep_table_reason(const hl_sweep_table *tab, long m)
{
    return hl_sweep_table_has(tab, m) && tab->reason[m] != NULL ? tab->reason[m] : "";
}

long hl_sweep_table_done(const hl_sweep_table *tab)
{
    return tab->done;
}

const double *hl_sweep_table_array(const hl_sweep_table *tab, long m, int kind, long *nrows)
{
    *nrows = 0;
    if (kind < 0 || kind >= HL_SWEEP_NARRAYS || tab->array[kind] == NULL ||
        !hl_sweep_table_has(tab, m))
        return NULL;
    *nrows = tab->nrows[kind][m];
    return tab->array[kind][m];
}
