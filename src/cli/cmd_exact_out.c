/* `hamlie exact`'s step-by-step modes' output: each fact printed as a line
 * of text, or with --json put as a field of the document (docs/json.md,
 * "exact"), sections opened and closed as the modes go. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cmd_exact_impl.h"

/* The mode of the current `exact` command (cmd_exact_impl.h): set by its
 * options, read by the writers of every mode. */
exact_mode_state exact_mode;

static void push_level(char kind)
{
    if (kind == '[')
        hl_json_array_begin(exact_mode.j);
    else
        hl_json_object_begin(exact_mode.j);
    exact_mode.kinds[exact_mode.depth++] = kind;
}

void exact_json_close_to(int depth)
{
    while (exact_mode.depth > depth) {
        if (exact_mode.kinds[--exact_mode.depth] == '[')
            hl_json_array_end(exact_mode.j);
        else
            hl_json_object_end(exact_mode.j);
    }
}

/* A new object under the top level (the previous section closed). */
void exact_json_section(const char *key)
{
    if (exact_mode.j == NULL)
        return;
    exact_json_close_to(0);
    hl_json_key(exact_mode.j, key);
    push_level('{');
}

void exact_json_bool(const char *key, int v)
{
    if (exact_mode.j != NULL)
        hl_json_kv_bool(exact_mode.j, key, v);
}

void exact_json_double(const char *key, double v)
{
    if (exact_mode.j != NULL)
        hl_json_kv_double(exact_mode.j, key, v);
}

void exact_json_string(const char *key, const char *v)
{
    if (exact_mode.j != NULL)
        hl_json_kv_string(exact_mode.j, key, v);
}

/* A formula typed in hamlie's syntax as SymPy reads it (as it is when it
 * does not parse, which the tests would catch). */
static char *sympy_of(const char *text, hl_system *sys)
{
    const hl_expr *e = NULL;
    hl_error e2;
    if (hl_parse(&e, hl_system_pool(sys), text, &e2) == HL_OK)
        return hl_expr_print(e, HL_STYLE_SYMPY);
    return hl_xstrdup(text);
}

/* A formula in hamlie's syntax, in JSON only (exact_put_formula also prints it). */
void exact_json_formula(const char *key, const char *text, hl_system *sys)
{
    if (exact_mode.j == NULL)
        return;
    char *s = sympy_of(text, sys);
    hl_json_kv_string(exact_mode.j, key, s);
    free(s);
}

/* An object under the current section: the final state of --init. */
void exact_json_object(const char *key)
{
    if (exact_mode.j == NULL)
        return;
    hl_json_key(exact_mode.j, key);
    push_level('{');
}

void exact_json_arb(const char *key, const arb_struct *x, long ndig)
{
    if (exact_mode.j == NULL)
        return;
    char *s = arb_get_str(x, ndig, ARB_STR_NO_RADIUS);
    hl_json_kv_string(exact_mode.j, key, s);
    flint_free(s);
}

/* "step 3: the generating function ...\n": the line, or in JSON an element
 * {"step": 3, "what": "the generating function ...", "formulas": {...}} of
 * the array "steps", whose formulas exact_put_formula then adds. */
void exact_put_step(hl_buf *out, const char *line)
{
    int n = 0, at = 0;
    if (exact_mode.j == NULL || sscanf(line, "step %d: %n", &n, &at) != 1 || at == 0) {
        hl_buf_puts(out, line);
        return;
    }
    if (exact_mode.depth == 0 || exact_mode.kinds[0] != '[') {
        exact_json_close_to(0);
        hl_json_key(exact_mode.j, "steps");
        push_level('[');
    }
    exact_json_close_to(1);
    push_level('{');
    hl_json_kv_int(exact_mode.j, "step", n);
    char *what = hl_xstrdup(line + at);
    what[strcspn(what, "\n")] = '\0';
    hl_json_kv_string(exact_mode.j, "what", what);
    free(what);
    hl_json_key(exact_mode.j, "formulas");
    push_level('{');
}

void exact_put_formula(hl_buf *out, const char *lhs, const char *rhs, hl_system *sys,
                       const cli_opts *o)
{
    if (exact_mode.j != NULL) {
        char *s = sympy_of(rhs, sys);
        hl_json_kv_string(exact_mode.j, lhs, s);
        free(s);
        return;
    }
    if (o->format == CLI_LATEX) {
        const hl_expr *e = NULL;
        hl_error e2;
        if (hl_parse(&e, hl_system_pool(sys), rhs, &e2) == HL_OK) {
            char *s = hl_expr_print(e, HL_STYLE_LATEX);
            const char *l = strcmp(lhs, "theta") == 0   ? "\\theta"
                            : strcmp(lhs, "gamma") == 0 ? "\\gamma"
                            : strcmp(lhs, "nu") == 0    ? "\\nu"
                                                        : lhs;
            hl_buf_printf(out, "  $%s = %s$\n", l, s);
            free(s);
            return;
        }
    }
    hl_buf_printf(out, "  %s = %s\n", lhs, rhs);
}

void exact_put_images(hl_buf *out, const hl_alg *img, hl_system *sys, const cli_opts *o)
{
    hl_style style = exact_mode.j != NULL     ? HL_STYLE_SYMPY
                     : o->format == CLI_LATEX ? HL_STYLE_LATEX
                                              : HL_STYLE_TEXT;
    for (int i = 0; i < 2 * hl_system_ndof(sys); i++) {
        char *nm = cli_image_name(sys, i);
        char *s = hl_format_alg(&img[i], hl_system_ctx(sys), hl_system_pool(sys), style);
        if (exact_mode.j != NULL)
            hl_json_kv_string(exact_mode.j, nm, s);
        else
            hl_buf_printf(out, "  %s = %s\n", nm, s);
        free(nm), free(s);
    }
}
