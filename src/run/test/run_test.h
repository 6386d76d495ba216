/* Shared by the run tests: a system, a scheme and a run in one call. */
#ifndef RUN_TEST_H
#define RUN_TEST_H

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/run.h"

typedef struct fixture {
    hl_system *sys;
    hl_scheme *sch;
    hl_run *run;
    double z0[8];
} fixture;

/* scheme NULL: the adaptive run.  Returns 0 (and reports) on failure. */
static int fixture_new(fixture *f, const char *H, const char *scheme, const char *init)
{
    hl_error err;
    hl_error_clear(&err);
    memset(f, 0, sizeof *f);
    hl_system_spec spec = {H, NULL, NULL, NULL, NULL};
    int st = hl_system_new(&f->sys, &spec, &err);
    if (st == HL_OK && scheme != NULL)
        st = hl_scheme_new(&f->sch, scheme, 0, f->sys, &err);
    if (st == HL_OK)
        st = hl_run_new(&f->run, f->sys, f->sch, &err);
    if (st == HL_OK)
        st = hl_run_init_values(f->z0, f->sys, init, &err);
    CHECK_MSG(st == HL_OK, "%s / %s: %s", H, scheme ? scheme : "adaptive", err.msg);
    return st == HL_OK;
}

static void fixture_clear(fixture *f)
{
    hl_run_free(f->run);
    hl_scheme_free(f->sch);
    hl_system_free(f->sys);
}

#define PENDULUM "p^2/2 - cos(q)"
#define HENON "(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3"
#define KEPLER "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)"
#define OSC "(p^2+x^2)/2"

#endif
