/* PLplot loaded on the first drawing: dlopen and the table of plplot_api.h
 * filled once per process.  Linked, it cost every command its load (PLplot
 * and the libraries behind it) though only `plot` and `reproduce` draw.
 * When it cannot be loaded, drawing reports HL_EUNSUP with the reason and
 * no file is written (plot_file.c writes through a temporary). */
#define HL_PLPLOT_API_IMPL /* the real names here, not the table's macros */
#include <dlfcn.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/lib.h"
#include "hamlie/plot.h"
#include "report/plplot_api.h"

hl_plplot_api hl_plplot;

#define DEFAULT_LIB "libplplot.so.17"

static pthread_once_t load_once = PTHREAD_ONCE_INIT;
static atomic_int load_failed; /* set once, under load_once */
static char load_why[400];     /* the reason, when load_failed */

/* Every function of the table, or the first one missing (NULL if none). */
static const char *resolve_all(void *lib)
{
    const char *missing = NULL;
#define HL_PLPLOT_RESOLVE(name)                                                                    \
    hl_plplot.name = (__typeof__(hl_plplot.name))dlsym(lib, #name);                                \
    if (hl_plplot.name == NULL && missing == NULL)                                                 \
        missing = #name;
    HL_PLPLOT_FUNCTIONS(HL_PLPLOT_RESOLVE)
#undef HL_PLPLOT_RESOLVE
    return missing;
}

static void load(void)
{
    const char *name;
    /* local: its device drivers (cairo.so) name libplplot themselves */
    void *lib = hl_lib_open("HAMLIE_PLPLOT_LIB", DEFAULT_LIB, NULL, &name);
    if (lib == NULL) {
        load_failed = 1;
        snprintf(load_why, sizeof load_why,
                 "%s not found: install libplplot17 and plplot-driver-cairo to draw figures", name);
        return;
    }
    const char *missing = resolve_all(lib);
    if (missing != NULL) {
        load_failed = 1;
        snprintf(load_why, sizeof load_why, "%s lacks %s (not PLplot 5.15?)", name, missing);
    }
}

hl_status hl_plplot_load(hl_error *err)
{
    pthread_once(&load_once, load);
    if (load_failed)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "%s", load_why);
    return HL_OK;
}

hl_status hl_figure_drawable(hl_error *err)
{
    return hl_plplot_load(err);
}
