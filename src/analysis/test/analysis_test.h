/* Shared by the analysis tests: a system from the text of H, or the test
 * program stops (exit 2) saying why — every test here needs its system. */
#ifndef HL_ANALYSIS_TEST_H
#define HL_ANALYSIS_TEST_H

#include <stdio.h>
#include <stdlib.h>

#include "hamlie/ham.h"

static hl_system *make_system(const char *H)
{
    hl_system *sys;
    hl_error err;
    hl_system_spec spec = {H, NULL, NULL, NULL, NULL};
    if (hl_system_new(&sys, &spec, &err) != HL_OK) {
        fprintf(stderr, "system '%s': %s\n", H, err.msg);
        exit(2);
    }
    return sys;
}

#endif
