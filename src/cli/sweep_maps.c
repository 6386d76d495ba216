/* hamlie sweep --plot: for a grid in two variables, a map per scheme, step
 * (and paramset) of log10 max |H - H0| and, with --chaos, of MEGNO <Y>
 * (report's sweep plot). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "hamlie/sweep.h"
#include "hamlie/sweepplot.h"

int sweep_plot(const hl_sweep *sw, const hl_sweep_table *tab, const char *dir, const char *formats);

/* The two start columns that vary over the points (the grid's axes). */
static int grid_axes(const hl_sweep *sw, const hl_sweep_table *tab, int *cx, int *cy)
{
    int z0 = hl_sweep_column_index(sw, "t") - 2 * hl_sweep_ndof(sw), found = 0;
    for (int c = z0; c < z0 + 2 * hl_sweep_ndof(sw); c++) {
        double first = hl_sweep_table_row(tab, 0)[c];
        int varies = 0;
        for (long m = 1; m < hl_sweep_count(sw) && !varies; m++)
            varies = hl_sweep_table_row(tab, m)[c] != first;
        if (varies && found < 2)
            *(found == 0 ? cx : cy) = c;
        found += varies;
    }
    return found == 2;
}

typedef struct map_set {
    int cx, cy, nschemes;
    double *xs, *ys, *vs;
    size_t n;
} map_set;

/* The members of one (paramset, scheme, dt) into the arrays; value column
 * c, log10 of it when logs. */
static void gather(map_set *ms, const hl_sweep *sw, const hl_sweep_table *tab, const double *key,
                   int c, int logs)
{
    ms->n = 0;
    for (long m = 0; m < hl_sweep_count(sw); m++) {
        const double *row = hl_sweep_table_row(tab, m);
        if (row[2] != key[0] || row[3] != key[1] || row[4] != key[2])
            continue;
        double v = row[c];
        ms->xs[ms->n] = row[ms->cx];
        ms->ys[ms->n] = row[ms->cy];
        ms->vs[ms->n++] = hl_sweep_table_status(tab, m) != HL_OK ? NAN : logs ? log10(v) : v;
    }
}

static int draw_one(map_set *ms, const hl_sweep *sw, const hl_sweep_table *tab, const double *row,
                    const char *dir, const char *formats, int megno)
{
    const char *scheme = hl_sweep_scheme(sw, (int)row[3]);
    char name[256], title[300], tail[64] = "";
    if (row[2] > 0)
        snprintf(tail, sizeof tail, "-paramset%.0f", row[2]);
    snprintf(name, sizeof name, "%s-%s-dt%g%s", megno ? "megno" : "max_dH", scheme, row[4], tail);
    snprintf(title, sizeof title, "%s, %s, dt = %g%s", megno ? "MEGNO <Y>" : "log10 max |H - H0|",
             scheme, row[4], tail);
    gather(ms, sw, tab, row + 2, hl_sweep_column_index(sw, megno ? "megno" : "max_dH"), !megno);
    hl_error err;
    hl_error_clear(&err);
    if (hl_sweep_plot_write(dir, formats, name, title, hl_sweep_column(sw, ms->cx),
                            hl_sweep_column(sw, ms->cy), ms->n, ms->xs, ms->ys, ms->vs,
                            &err) != HL_OK)
        return cli_fail(&err);
    return -1;
}

int sweep_plot(const hl_sweep *sw, const hl_sweep_table *tab, const char *dir, const char *formats)
{
    map_set ms;
    memset(&ms, 0, sizeof ms);
    if (hl_sweep_get_spec(sw)->grid == NULL || !grid_axes(sw, tab, &ms.cx, &ms.cy)) {
        fprintf(stderr, "hamlie: error: --plot draws maps of a grid in two variables\n");
        return CLI_ERROR;
    }
    size_t n = (size_t)hl_sweep_count(sw);
    ms.xs = hl_xmalloc(n * sizeof *ms.xs);
    ms.ys = hl_xmalloc(n * sizeof *ms.ys);
    ms.vs = hl_xmalloc(n * sizeof *ms.vs);
    int rc = -1, chaos = hl_sweep_get_spec(sw)->chaos, maps = 0;
    /* the first point's members name every (paramset, scheme, dt) once */
    for (long m = 0; rc < 0 && m < hl_sweep_count(sw); m++) {
        const double *row = hl_sweep_table_row(tab, m);
        if (row[1] != 0)
            break;
        rc = draw_one(&ms, sw, tab, row, dir, formats, 0);
        if (rc < 0 && chaos)
            rc = draw_one(&ms, sw, tab, row, dir, formats, 1);
        maps += 1 + chaos;
    }
    if (rc < 0)
        fprintf(stderr, "hamlie sweep: drew %d maps in %s\n", maps, dir);
    free(ms.xs);
    free(ms.ys);
    free(ms.vs);
    return rc;
}
