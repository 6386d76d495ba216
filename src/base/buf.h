/* Growable string buffer (internal to the library and the CLI).
 *
 * Every layer that writes text (printers, JSON, LaTeX, CSV headers) appends
 * to one of these; hl_buf_take hands the malloc'd string to the caller.
 * Allocation failure aborts with a message (see expr.h on memory).
 */
#ifndef HAMLIE_BASE_BUF_H
#define HAMLIE_BASE_BUF_H

#include <stddef.h>
#include <stdio.h>

typedef struct hl_buf {
    char *s;    /* always NUL-terminated once anything was appended */
    size_t len; /* bytes used, not counting the NUL */
    size_t cap;
} hl_buf;

void hl_buf_init(hl_buf *b);
void hl_buf_clear(hl_buf *b);                    /* frees */
void hl_buf_putc(hl_buf *b, char c);
void hl_buf_puts(hl_buf *b, const char *s);
/* s as one CSV field: as it is, or quoted (quotes doubled) when it holds a
 * comma, a quote or a line break; a line break is written as a space, so
 * that every record stays one line for line-based readers. */
void hl_buf_csv_field(hl_buf *b, const char *s);
/* Append everything left in fp (read in large chunks); returns
 * ferror(fp): nonzero when reading failed. */
int hl_buf_read_stream(hl_buf *b, FILE *fp);
void hl_buf_putn(hl_buf *b, const char *s, size_t n);
void hl_buf_printf(hl_buf *b, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
char *hl_buf_take(hl_buf *b);                    /* returns the string ("" if empty), resets b */

/* Allocation that aborts with a message instead of returning NULL. */
void *hl_xmalloc(size_t n);
void *hl_xcalloc(size_t n, size_t size);
void *hl_xrealloc(void *p, size_t n);
char *hl_xstrdup(const char *s);

#endif
