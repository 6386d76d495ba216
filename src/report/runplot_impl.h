/* Internal to the run plots of src/report (runplot.c, runplot_csv.c). */
#ifndef HAMLIE_REPORT_RUNPLOT_IMPL_H
#define HAMLIE_REPORT_RUNPLOT_IMPL_H

#include "hamlie/runplot.h"

struct hl_runplot {
    char *label;
    int ncols;
    char **names;
    double *v; /* rows x ncols, row-major */
    size_t nrows, cap;
    int iH;     /* the H column, -1 if none */
    double *dH; /* |H - H0| per row: from the CSV's text in Arb when it has more
                   digits than a double (a --digits run), else in double */
    double max_dH;
};

/* Append a row, with its |H - H0| (NAN: from the values, in double). */
hl_status hl_runplot_add_row_dH_(hl_runplot *rp, const double *values, double dH, hl_error *err);

#endif
