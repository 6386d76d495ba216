/* Growable string buffer and aborting allocators. */
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"

static void out_of_memory(size_t n)
{
    fprintf(stderr, "hamlie: fatal: out of memory allocating %zu bytes\n", n);
    abort();
}

void *hl_xmalloc(size_t n)
{
    void *p = malloc(n ? n : 1);
    if (p == NULL)
        out_of_memory(n);
    return p;
}

void *hl_xcalloc(size_t n, size_t size)
{
    void *p = calloc(n ? n : 1, size ? size : 1);
    if (p == NULL)
        out_of_memory(n * size);
    return p;
}

void *hl_xrealloc(void *p, size_t n)
{
    void *q = realloc(p, n ? n : 1);
    if (q == NULL)
        out_of_memory(n);
    return q;
}

char *hl_xstrdup(const char *s)
{
    size_t n = strlen(s) + 1;
    return memcpy(hl_xmalloc(n), s, n);
}

void hl_buf_init(hl_buf *b)
{
    b->s = NULL;
    b->len = 0;
    b->cap = 0;
}

void hl_buf_clear(hl_buf *b)
{
    free(b->s);
    hl_buf_init(b);
}

static void reserve(hl_buf *b, size_t extra)
{
    size_t need = b->len + extra + 1;
    if (need <= b->cap)
        return;
    size_t cap = b->cap ? b->cap : 64;
    while (cap < need)
        cap *= 2;
    b->s = hl_xrealloc(b->s, cap);
    b->cap = cap;
}

void hl_buf_putn(hl_buf *b, const char *s, size_t n)
{
    reserve(b, n);
    memcpy(b->s + b->len, s, n);
    b->len += n;
    b->s[b->len] = '\0';
}

void hl_buf_puts(hl_buf *b, const char *s)
{
    hl_buf_putn(b, s, strlen(s));
}

void hl_buf_putc(hl_buf *b, char c)
{
    hl_buf_putn(b, &c, 1);
}

void hl_buf_printf(hl_buf *b, const char *fmt, ...)
{
    va_list ap, ap2;
    va_start(ap, fmt);
    va_copy(ap2, ap);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    if (n > 0) {
        reserve(b, (size_t)n);
        vsnprintf(b->s + b->len, (size_t)n + 1, fmt, ap2);
        b->len += (size_t)n;
    }
    va_end(ap2);
}

char *hl_buf_take(hl_buf *b)
{
    char *s = b->s ? b->s : hl_xstrdup("");
    hl_buf_init(b);
    return s;
}

void hl_buf_csv_field(hl_buf *b, const char *s)
{
    if (strpbrk(s, ",\"\n\r") == NULL) {
        hl_buf_puts(b, s);
        return;
    }
    hl_buf_putc(b, '"');
    for (; *s; s++) {
        if (*s == '"')
            hl_buf_putc(b, '"');
        hl_buf_putc(b, *s == '\n' || *s == '\r' ? ' ' : *s);
    }
    hl_buf_putc(b, '"');
}

int hl_buf_read_stream(hl_buf *b, FILE *fp)
{
    char chunk[65536];
    size_t n;
    while ((n = fread(chunk, 1, sizeof chunk, fp)) > 0)
        hl_buf_putn(b, chunk, n);
    return ferror(fp);
}
