/* The lists of figure formats ("png,svg"): hl_figure_count_formats and
 * hl_figure_write read them with one reader, so they agree on every list —
 * what is counted, what is refused, and where the refused name starts. */
#include <string.h>

#include "hamlie/plot.h"
#include "hl_test.h"

typedef struct format_case {
    const char *list;
    int count;    /* -1: refused */
    int pos, len; /* of the refused name in list (-1: none) */
} format_case;

static const format_case cases[] = {
    {"png", 1, -1, 0},     {"png,svg,pdf", 3, -1, 0},  {"PNG, Svg", 2, -1, 0},
    {"png,png", 1, -1, 0}, {" png ,, pdf ", 2, -1, 0}, {"png,gif", -1, 4, 3},
    {"pngx", -1, 0, 4},    {"svg pn", -1, 4, 2},       {"", -1, -1, 0},
    {" , ", -1, -1, 0},    {NULL, -1, -1, 0},
};

static void test_count(void)
{
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const format_case *c = &cases[i];
        const char *shown = c->list != NULL ? c->list : "(null)";
        hl_error err;
        hl_error_clear(&err);
        int n = -7;
        hl_status st = hl_figure_count_formats(&n, c->list, &err);
        if (c->count >= 0) {
            CHECK_MSG(st == HL_OK && n == c->count, "'%s': status %d, count %d, want %d", shown,
                      (int)st, n, c->count);
            continue;
        }
        CHECK_MSG(st == HL_EINVAL, "'%s': status %d, want HL_EINVAL", shown, (int)st);
        CHECK_MSG(err.pos == c->pos && (c->pos < 0 || err.len == c->len),
                  "'%s': refused at %d (+%d), want %d (+%d)", shown, err.pos, err.len, c->pos,
                  c->len);
    }
}

/* hl_figure_write reads the list before it looks at the path, so with an
 * empty path it says "empty figure path" exactly for the lists counted,
 * and for the others what hl_figure_count_formats says. */
static void test_write_agrees(void)
{
    hl_figure *fig = hl_figure_new("t", "x", "y");
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        const format_case *c = &cases[i];
        const char *shown = c->list != NULL ? c->list : "(null)";
        hl_error ec, ew;
        hl_error_clear(&ec);
        hl_error_clear(&ew);
        int n = 0;
        hl_status sc = hl_figure_count_formats(&n, c->list, &ec);
        hl_status sw = hl_figure_write(fig, "", c->list, &ew);
        CHECK_MSG(sw == HL_EINVAL, "'%s': write status %d", shown, (int)sw);
        if (sc == HL_OK)
            CHECK_MSG(strcmp(ew.msg, "empty figure path") == 0, "'%s': write says '%s'", shown,
                      ew.msg);
        else
            CHECK_MSG(strcmp(ew.msg, ec.msg) == 0 && ew.pos == ec.pos,
                      "'%s': write says '%s' at %d, count '%s' at %d", shown, ew.msg, ew.pos,
                      ec.msg, ec.pos);
    }
    hl_figure_free(fig);
}

int main(void)
{
    test_count();
    test_write_agrees();
    return HL_TEST_END();
}
