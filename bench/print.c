/* Benchmark: printing large results (issue 17, part 5).  The Lie series of
 * every coordinate of Hénon–Heiles to order 12 and of planar Kepler to order
 * 8 are computed once; then only their printing is timed, as `hamlie lie`
 * prints them: the series in text and in LaTeX, and the JSON form (the
 * series and each coefficient g^k z / k! in SymPy syntax, as JSON strings).
 * Prints, per system and form: bytes written, milliseconds (best of reps)
 * and milliseconds per 10 KB (the goal: well under 1).
 * Argument: [reps] (default 20). */
#define _GNU_SOURCE /* open_memstream */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hamlie/ham.h"
#include "hamlie/report.h"

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

typedef struct lie {
    hl_system *sys;
    int n, order;
    hl_alg **terms; /* terms[v][k] = g^k z_v */
} lie;

static int lie_new(lie *L, const char *H, int order)
{
    hl_system_spec spec = {H, NULL, NULL, NULL, NULL};
    hl_error err;
    hl_error_clear(&err);
    memset(L, 0, sizeof *L);
    if (hl_system_new(&L->sys, &spec, &err) != HL_OK) {
        fprintf(stderr, "print: %s\n", err.msg);
        return 1;
    }
    hl_alg_ctx *ctx = hl_system_ctx(L->sys);
    L->n = 2 * hl_system_ndof(L->sys);
    L->order = order;
    L->terms = calloc((size_t)L->n, sizeof *L->terms);
    hl_alg z;
    hl_alg_init(&z, ctx);
    for (int v = 0; v < L->n; v++) {
        L->terms[v] = hl_alg_vec_new(order + 1, ctx);
        hl_alg_gen(&z, v, ctx);
        if (hl_lie_terms(L->terms[v], &z, order, L->sys, &err) != HL_OK) {
            fprintf(stderr, "print: %s\n", err.msg);
            return 1;
        }
    }
    hl_alg_clear(&z, ctx);
    return 0;
}

static void lie_free(lie *L)
{
    hl_alg_ctx *ctx = hl_system_ctx(L->sys);
    for (int v = 0; v < L->n; v++)
        hl_alg_vec_free(L->terms[v], L->order + 1, ctx);
    free(L->terms);
    hl_system_free(L->sys);
}

enum form { TEXT, LATEX, JSON, NFORMS };
static const char *const form_name[NFORMS] = {"text", "latex", "json"};

/* The series and coefficients of one coordinate as JSON strings. */
static void json_item(hl_json *j, lie *L, int v)
{
    hl_alg_ctx *ctx = hl_system_ctx(L->sys);
    hl_pool *pool = hl_system_pool(L->sys);
    char *s = hl_format_series(L->terms[v], L->order, hl_system_step(L->sys), 1, ctx, pool,
                               HL_STYLE_SYMPY);
    hl_json_object_begin(j);
    hl_json_kv_string(j, "series", s);
    free(s);
    hl_json_key(j, "coefficients");
    hl_json_array_begin(j);
    hl_alg c;
    fmpq_t f;
    hl_alg_init(&c, ctx);
    fmpq_init(f);
    fmpq_one(f);
    for (int k = 0; k <= L->order; k++) {
        if (k > 0)
            fmpz_mul_ui(fmpq_denref(f), fmpq_denref(f), (ulong)k);
        hl_alg_scalar_mul_fmpq(&c, &L->terms[v][k], f, ctx);
        s = hl_format_alg(&c, ctx, pool, HL_STYLE_SYMPY);
        hl_json_string(j, s);
        free(s);
    }
    hl_json_array_end(j);
    hl_json_object_end(j);
    hl_alg_clear(&c, ctx);
    fmpq_clear(f);
}

/* Print every coordinate's series in one form; returns the bytes written. */
static size_t print_once(lie *L, enum form f)
{
    hl_alg_ctx *ctx = hl_system_ctx(L->sys);
    hl_pool *pool = hl_system_pool(L->sys);
    char *out = NULL;
    size_t len = 0;
    FILE *fp = open_memstream(&out, &len);
    hl_json j;
    hl_json_init_file(&j, fp);
    if (f == JSON)
        hl_json_array_begin(&j);
    for (int v = 0; v < L->n; v++) {
        if (f == JSON) {
            json_item(&j, L, v);
            continue;
        }
        char *s = hl_format_series(L->terms[v], L->order, hl_system_step(L->sys), 1, ctx, pool,
                                   f == LATEX ? HL_STYLE_LATEX : HL_STYLE_TEXT);
        fputs(s, fp);
        fputc('\n', fp);
        free(s);
    }
    if (f == JSON) {
        hl_json_array_end(&j);
        hl_json_finish(&j);
    }
    fclose(fp);
    free(out);
    return len;
}

static void bench(const char *name, const char *H, int order, int reps)
{
    lie L;
    if (lie_new(&L, H, order) != 0)
        exit(1);
    for (int f = 0; f < NFORMS; f++) {
        double best = 1e300;
        size_t bytes = 0;
        for (int r = 0; r < reps; r++) {
            double t0 = now();
            bytes = print_once(&L, (enum form)f);
            double t = now() - t0;
            best = t < best ? t : best;
        }
        printf("%-13s %2d %-6s %8zu bytes %8.3f ms %7.3f ms/10KB\n", name, order, form_name[f],
               bytes, 1e3 * best, 1e3 * best / ((double)bytes / 10240));
    }
    lie_free(&L);
}

int main(int argc, char **argv)
{
    int reps = argc > 1 ? atoi(argv[1]) : 20;
    bench("henon-heiles", "(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3", 12, reps);
    bench("kepler", "(px^2+py^2)/2 - 1/sqrt(x^2+y^2)", 8, reps);
    return 0;
}
