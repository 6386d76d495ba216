/* Fuzz target for the expression parser and printers: any input must parse
 * or fail cleanly; what parses must print in every style, and the text
 * style must parse back to the same pointer. */
#include <stdio.h>

#include "fuzz.h"
#include "hamlie/expr.h"

#define MAX_ITEMS 16

static void check_roundtrip(hl_pool *pool, const hl_expr *e)
{
    char *s = hl_expr_print(e, HL_STYLE_TEXT);
    const hl_expr *back = NULL;
    hl_error err;
    if (hl_parse(&back, pool, s, &err) != HL_OK || back != e) {
        fprintf(stderr, "round trip failed: \"%s\": %s\n", s, err.msg);
        abort();
    }
    free(s);
    for (int st = HL_STYLE_LATEX; st <= HL_STYLE_C; st++)
        free(hl_expr_print(e, (hl_style)st));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char *src = fuzz_string(data, size);
    hl_pool *pool = hl_pool_new();
    hl_error err;
    const hl_expr *e;
    int st = hl_parse(&e, pool, src, &err);
    fuzz_check_error(st, &err, src);
    if (st == HL_OK)
        check_roundtrip(pool, e);

    hl_eqn items[MAX_ITEMS];
    int n;
    st = hl_parse_list(items, MAX_ITEMS, &n, pool, src, &err);
    fuzz_check_error(st, &err, src);
    if (st == HL_OK) {
        for (int i = 0; i < n; i++) {
            check_roundtrip(pool, items[i].lhs);
            if (items[i].rhs)
                check_roundtrip(pool, items[i].rhs);
        }
    }
    hl_symbol_pos(src, "x");
    hl_pool_free(pool);
    free(src);
    return 0;
}
