/* Helpers shared by the tests of src/ham. */
#ifndef HAM_TEST_H
#define HAM_TEST_H

#include <stdio.h>
#include <stdlib.h>

#include "hamlie/ham.h"
#include "hl_test.h"

/* A system from H (and optional pairs); exits the test on failure. */
static inline hl_system *sys_new(const char *H, const char *pairs)
{
    hl_system_spec spec = {H, pairs, NULL, NULL, NULL};
    hl_system *sys = NULL;
    hl_error err;
    hl_error_clear(&err);
    if (hl_system_new(&sys, &spec, &err) != HL_OK) {
        fprintf(stderr, "cannot make system '%s': %s\n", H ? H : "(none)", err.msg);
        exit(1);
    }
    return sys;
}

/* Read a formula of the system into a (initialised) element; exits on failure. */
static inline void rd(hl_alg *a, hl_system *sys, const char *f)
{
    hl_error err;
    hl_error_clear(&err);
    if (hl_system_read(a, sys, f, &err) != HL_OK) {
        fprintf(stderr, "cannot read '%s': %s\n", f, err.msg);
        exit(1);
    }
}

/* Is the element a equal to the formula f? Prints both when not. */
static inline int eq_formula(const hl_alg *a, hl_system *sys, const char *f)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg b;
    hl_alg_init(&b, ctx);
    rd(&b, sys, f);
    int ok = hl_alg_equal(a, &b, ctx);
    if (!ok) {
        char *s = hl_expr_print(hl_alg_to_expr(a, ctx, hl_system_pool(sys)), HL_STYLE_TEXT);
        fprintf(stderr, "  got  %s\n  want %s\n", s, f);
        free(s);
    }
    hl_alg_clear(&b, ctx);
    return ok;
}

#endif
