/* hamlie — writing results: JSON, and formulas in the styles of expr.h.
 *
 * The JSON writer appends to an hl_buf or a FILE*, with commas, nesting and
 * string escaping handled for the caller; the CLI writes into a buffer and
 * prints it only once the whole computation has succeeded.
 *
 * Formatting functions return malloc'd strings owned by the caller.
 */
#ifndef HAMLIE_REPORT_H
#define HAMLIE_REPORT_H

#include <stdio.h>

#include "hamlie/alg.h"
#include "hamlie/expr.h"

#ifdef __cplusplus
extern "C" {
#endif

/* ---- JSON ------------------------------------------------------------- */

/* The library's string builder (internal; C11 allows repeating the typedef). */
typedef struct hl_buf hl_buf;

#define HL_JSON_MAX_DEPTH 32

typedef struct hl_json {
    hl_buf *buf;     /* one of buf and fp is the sink */
    FILE *fp;
    int depth;
    int count[HL_JSON_MAX_DEPTH]; /* values written so far at each level */
    int after_key;   /* a key was written, its value comes next */
    int pretty;      /* indent two spaces per level (default on) */
    int error;       /* nesting misuse or a failed write */
} hl_json;

void hl_json_init_buf(hl_json *j, hl_buf *b);
void hl_json_init_file(hl_json *j, FILE *fp);

void hl_json_object_begin(hl_json *j);
void hl_json_object_end(hl_json *j);
void hl_json_array_begin(hl_json *j);
void hl_json_array_end(hl_json *j);
void hl_json_key(hl_json *j, const char *key);       /* inside an object */
void hl_json_string(hl_json *j, const char *s);      /* NULL writes null */
void hl_json_int(hl_json *j, long v);
void hl_json_double(hl_json *j, double v);          /* 17 digits; null if not finite */
void hl_json_bool(hl_json *j, int v);
void hl_json_null(hl_json *j);

/* Convenience: key and value in one call. */
void hl_json_kv_string(hl_json *j, const char *key, const char *s);
void hl_json_kv_int(hl_json *j, const char *key, long v);
void hl_json_kv_double(hl_json *j, const char *key, double v);
void hl_json_kv_bool(hl_json *j, const char *key, int v);

/* Write the final newline; nonzero if the document was not well nested or a
 * write failed. */
int hl_json_finish(hl_json *j);

/* Append s to b as a JSON string literal (quotes included). */
void hl_json_escape(hl_buf *b, const char *s);

/* ---- formulas ----------------------------------------------------------- */

/* An element written the way a person would (hl_alg_to_expr), in a style. */
char *hl_format_alg(const hl_alg *a, hl_alg_ctx *ctx, hl_pool *pool, hl_style style);

/* A vector field sum_i c_i d/d(names[i]):
 *   HL_STYLE_TEXT   p ∂/∂x − x ∂/∂p   (Unicode; sums parenthesised)
 *   HL_STYLE_LATEX  p \frac{\partial}{\partial x} - x \frac{\partial}{\partial p}
 * Zero components are left out; the zero field is "0". */
char *hl_format_vector_field(int n, const char *const *names, const hl_alg *c,
                             hl_alg_ctx *ctx, hl_pool *pool, hl_style style);

/* The same as a JSON object {"x": "p", "p": "-x"} (every component, in the
 * given style, normally HL_STYLE_SYMPY). */
void hl_json_vector_field(hl_json *j, int n, const char *const *names, const hl_alg *c,
                          hl_alg_ctx *ctx, hl_pool *pool, hl_style style);

/* A series in the symbol var grouped by its powers:
 *   sum_{k=0..order} var^k / k! * terms[k]    (factorial != 0: a Lie series)
 *   sum_{k=0..order} var^k * terms[k]         (factorial == 0)
 * e.g. "x + D*p - D^2/2*x".  Zero terms are left out; all zero gives "0". */
char *hl_format_series(const hl_alg *terms, int order, const char *var, int factorial,
                       hl_alg_ctx *ctx, hl_pool *pool, hl_style style);

#ifdef __cplusplus
}
#endif

#endif
