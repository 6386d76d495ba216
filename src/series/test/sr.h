/* Helpers for the series tests: read elements and series from text. */
#ifndef HL_SERIES_TEST_SR_H
#define HL_SERIES_TEST_SR_H

#include <stdarg.h>
#include <stdlib.h>

#include "hamlie/series.h"
#include "hl_test.h"

static hl_pool *pool;
static hl_alg_ctx *ctx;

/* r = the element written s (aborts the test on a typo: it is the test's bug) */
static inline void rd(hl_alg *r, const char *s)
{
    const hl_expr *e;
    hl_error err;
    int st = hl_parse(&e, pool, s, &err);
    if (st == HL_OK)
        st = hl_alg_from_expr(r, e, ctx, &err);
    if (st != HL_OK) {
        fprintf(stderr, "cannot read '%s': %s\n", s, err.msg);
        exit(2);
    }
}

/* r = series with n coefficients, the first ones given as strings (NULL-terminated),
 * the rest zero */
static inline void rds(hl_series *r, int n, ...)
{
    va_list ap;
    va_start(ap, n);
    hl_series_zero(r, n, ctx);
    const char *s;
    for (int k = 0; (s = va_arg(ap, const char *)) != NULL; k++)
        if (k < n)
            rd(&r->c[k], s);
    va_end(ap);
}

static inline char *show(const hl_alg *a)
{
    return hl_expr_print(hl_alg_to_expr(a, ctx, pool), HL_STYLE_TEXT);
}

/* Check coefficient k of s equals the element written want. */
#define CHECK_COEF(s, k, want) check_coef(s, k, want, __FILE__, __LINE__)
static inline void check_coef(const hl_series *s, int k, const char *want, const char *file,
                              int line)
{
    hl_alg w;
    hl_alg_init(&w, ctx);
    rd(&w, want);
    int ok = k < s->n && hl_alg_equal(&s->c[k], &w, ctx);
    if (ok) {
        hl_test_passed++;
    } else {
        hl_test_failed++;
        char *g = k < s->n ? show(&s->c[k]) : NULL;
        fprintf(stderr, "%s:%d: coefficient %d: got %s, want %s\n", file, line, k,
                g ? g : "(absent)", want);
        free(g);
    }
    hl_alg_clear(&w, ctx);
}

/* Check two series agree on their first n coefficients (and both have them). */
#define CHECK_SERIES(a, b, n) check_series(a, b, n, __FILE__, __LINE__)
static inline void check_series(const hl_series *a, const hl_series *b, int n, const char *file,
                                int line)
{
    int ok = a->n >= n && b->n >= n;
    int k = 0;
    for (; ok && k < n; k++)
        ok = hl_alg_equal(&a->c[k], &b->c[k], ctx);
    if (ok) {
        hl_test_passed++;
    } else {
        hl_test_failed++;
        fprintf(stderr, "%s:%d: series differ (n = %d, %d, want %d)", file, line, a->n, b->n, n);
        if (k > 0 && k <= a->n && k <= b->n) {
            char *x = show(&a->c[k - 1]), *y = show(&b->c[k - 1]);
            fprintf(stderr, " at D^%d: %s vs %s", k - 1, x, y);
            free(x);
            free(y);
        }
        fputc('\n', stderr);
    }
}

static inline void setup(int nbase, const char *const *names)
{
    pool = hl_pool_new();
    ctx = hl_alg_ctx_new(nbase, names, 0);
}

static inline void teardown(void)
{
    hl_alg_ctx_free(ctx);
    hl_pool_free(pool);
}

#endif
