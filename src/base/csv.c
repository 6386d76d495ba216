/* The tokenizer of csv.h: lines and trimmed fields as byte spans. */
#include "base/csv.h"

#include <string.h>

static int is_blank(char c)
{
    return c == ' ' || c == '\t' || c == '\r';
}

static void trim(const char *t, int *a, int *b)
{
    while (*a < *b && is_blank(t[*a]))
        ++*a;
    while (*b > *a && is_blank(t[*b - 1]))
        --*b;
}

void hl_csv_init(hl_csv *c, const char *text)
{
    c->text = text;
    c->len = (int)strlen(text);
    c->at = 0;
    c->line = 0;
}

int hl_csv_line(hl_csv *c, int *a, int *b)
{
    while (c->at < c->len) {
        int s = c->at, e = s;
        while (e < c->len && c->text[e] != '\n')
            e++;
        c->at = e + 1;
        c->line++;
        trim(c->text, &s, &e);
        if (s < e && c->text[s] != '#') {
            *a = s, *b = e;
            return 1;
        }
    }
    return 0;
}

int hl_csv_field(const char *text, int b, int *f, int *fa, int *fb)
{
    if (*f > b)
        return 0;
    int e = *f;
    while (e < b && text[e] != ',')
        e++;
    *fa = *f, *fb = e;
    trim(text, fa, fb);
    *f = e + 1;
    return 1;
}

int hl_csv_name(const char *text, int fa, int fb, const char *const *names, int n)
{
    for (int i = 0; i < n; i++)
        if ((int)strlen(names[i]) == fb - fa &&
            strncmp(names[i], text + fa, (size_t)(fb - fa)) == 0)
            return i;
    return -1;
}
