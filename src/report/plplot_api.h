/* PLplot through a table of function pointers filled on the first drawing
 * (plplot_api.c), so that a command that draws nothing never loads it:
 * libplplot and its cairo/pango stack cost milliseconds at every start-up.
 *
 * plplot.h maps plline to c_plline and so on; the macros below map those
 * names (and the few without c_) onto the table, so plot_draw.c only
 * includes this header instead of <plplot.h>.  A function missing from
 * HL_PLPLOT_FUNCTIONS fails at link time: add one X(...) and one #define. */
#ifndef HAMLIE_REPORT_PLPLOT_API_H
#define HAMLIE_REPORT_PLPLOT_API_H

#include <plplot.h>

#include "hamlie/error.h"

#define HL_PLPLOT_FUNCTIONS(X)                                                                     \
    X(c_pladv)                                                                                     \
    X(c_plbox)                                                                                     \
    X(c_plcol0)                                                                                    \
    X(c_plend1)                                                                                    \
    X(c_plfill)                                                                                    \
    X(plgDevs)                                                                                     \
    X(c_plgspa)                                                                                    \
    X(c_plgstrm)                                                                                   \
    X(c_plgvpd)                                                                                    \
    X(c_plinit)                                                                                    \
    X(c_pllab)                                                                                     \
    X(c_pllegend)                                                                                  \
    X(c_plline)                                                                                    \
    X(c_plmkstrm)                                                                                  \
    X(c_plmtex)                                                                                    \
    X(plsError)                                                                                    \
    X(plsabort)                                                                                    \
    X(c_plschr)                                                                                    \
    X(c_plscmap0)                                                                                  \
    X(c_plsdev)                                                                                    \
    X(plsexit)                                                                                     \
    X(c_plsfnam)                                                                                   \
    X(c_plsmem)                                                                                    \
    X(c_plspage)                                                                                   \
    X(c_plspause)                                                                                  \
    X(c_plsstrm)                                                                                   \
    X(c_plvpas)                                                                                    \
    X(c_plvpor)                                                                                    \
    X(c_plwidth)                                                                                   \
    X(c_plwind)

typedef struct hl_plplot_api {
#define HL_PLPLOT_SLOT(name) __typeof__(name) *name;
    HL_PLPLOT_FUNCTIONS(HL_PLPLOT_SLOT)
#undef HL_PLPLOT_SLOT
} hl_plplot_api;

extern hl_plplot_api hl_plplot;

/* Load PLplot once per process: $HAMLIE_PLPLOT_LIB if set (tests set a
 * missing one), else libplplot.so.17.  HL_OK when every function of the
 * table was found, else HL_EUNSUP ("libplplot.so.17 not found: install
 * ..."), the same on every later call. */
hl_status hl_plplot_load(hl_error *err);

#ifndef HL_PLPLOT_API_IMPL
#define c_pladv (hl_plplot.c_pladv)
#define c_plbox (hl_plplot.c_plbox)
#define c_plcol0 (hl_plplot.c_plcol0)
#define c_plend1 (hl_plplot.c_plend1)
#define c_plfill (hl_plplot.c_plfill)
#define plgDevs (hl_plplot.plgDevs)
#define c_plgspa (hl_plplot.c_plgspa)
#define c_plgstrm (hl_plplot.c_plgstrm)
#define c_plgvpd (hl_plplot.c_plgvpd)
#define c_plinit (hl_plplot.c_plinit)
#define c_pllab (hl_plplot.c_pllab)
#define c_pllegend (hl_plplot.c_pllegend)
#define c_plline (hl_plplot.c_plline)
#define c_plmkstrm (hl_plplot.c_plmkstrm)
#define c_plmtex (hl_plplot.c_plmtex)
#define plsError (hl_plplot.plsError)
#define plsabort (hl_plplot.plsabort)
#define c_plschr (hl_plplot.c_plschr)
#define c_plscmap0 (hl_plplot.c_plscmap0)
#define c_plsdev (hl_plplot.c_plsdev)
#define plsexit (hl_plplot.plsexit)
#define c_plsfnam (hl_plplot.c_plsfnam)
#define c_plsmem (hl_plplot.c_plsmem)
#define c_plspage (hl_plplot.c_plspage)
#define c_plspause (hl_plplot.c_plspause)
#define c_plsstrm (hl_plplot.c_plsstrm)
#define c_plvpas (hl_plplot.c_plvpas)
#define c_plvpor (hl_plplot.c_plvpor)
#define c_plwidth (hl_plplot.c_plwidth)
#define c_plwind (hl_plplot.c_plwind)
#endif

#endif
