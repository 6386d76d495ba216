/* Helpers for the scheme tests. */
#ifndef HL_SCHEME_TEST_SCH_H
#define HL_SCHEME_TEST_SCH_H

#include <stdlib.h>
#include <string.h>

#include "hamlie/scheme.h"
#include "hl_test.h"

static inline hl_system *make_system(const char *H)
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

static inline hl_series *new_series(int k, hl_alg_ctx *ctx)
{
    hl_series *Z = malloc((size_t)k * sizeof *Z);
    for (int i = 0; i < k; i++)
        hl_series_init(&Z[i], 0, ctx);
    return Z;
}

static inline void free_series(hl_series *Z, int k, hl_alg_ctx *ctx)
{
    for (int i = 0; i < k; i++)
        hl_series_clear(&Z[i], ctx);
    free(Z);
}

/* Expand; NULL (and the message printed) on failure. */
static inline hl_series *expand(hl_scheme *s, int n)
{
    hl_alg_ctx *ctx = hl_system_ctx(s->sys);
    hl_series *Z = new_series(2 * s->N, ctx);
    hl_error err;
    if (hl_scheme_expand(Z, s, n, &err) != HL_OK) {
        fprintf(stderr, "%s: expand: %s\n", s->name, err.msg);
        free_series(Z, 2 * s->N, ctx);
        return NULL;
    }
    return Z;
}

/* Does series a equal, to its first n coefficients, the Taylor expansion in
 * D of the formula f (read in the system)? */
static inline int series_is(const hl_series *a, const char *f, int n, hl_system *sys)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_alg e;
    hl_series s;
    hl_error err;
    hl_alg_init(&e, ctx);
    hl_series_init(&s, 0, ctx);
    int ok = hl_system_read(&e, sys, f, &err) == HL_OK &&
             hl_series_from_alg(&s, &e, hl_system_var_D(sys), n, ctx, &err) == HL_OK &&
             a->n >= n;
    for (int k = 0; ok && k < n; k++)
        ok = hl_alg_equal(&a->c[k], &s.c[k], ctx);
    hl_alg_clear(&e, ctx);
    hl_series_clear(&s, ctx);
    return ok;
}

#endif
