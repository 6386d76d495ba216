/* A small JSON writer: the caller says begin/end/key/value, the writer puts
 * the commas, the indentation and the escapes. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "base/buf.h"
#include "hamlie/report.h"

static int needs_escape(unsigned char c)
{
    return c < 0x20 || c == '"' || c == '\\';
}

/* Runs of characters that need no escape (nearly all of a formula) are
 * copied in one piece, not a character at a time. */
void hl_json_escape(hl_buf *b, const char *s)
{
    hl_buf_putc(b, '"');
    for (const unsigned char *c = (const unsigned char *)s; *c; c++) {
        const unsigned char *run = c;
        while (*c && !needs_escape(*c))
            c++; /* UTF-8 passes through: JSON is UTF-8 */
        hl_buf_putn(b, (const char *)run, (size_t)(c - run));
        if (*c == '\0')
            break;
        switch (*c) {
        case '"': hl_buf_puts(b, "\\\""); break;
        case '\\': hl_buf_puts(b, "\\\\"); break;
        case '\n': hl_buf_puts(b, "\\n"); break;
        case '\t': hl_buf_puts(b, "\\t"); break;
        case '\r': hl_buf_puts(b, "\\r"); break;
        case '\b': hl_buf_puts(b, "\\b"); break;
        case '\f': hl_buf_puts(b, "\\f"); break;
        default:
            hl_buf_printf(b, "\\u%04x", *c);
        }
    }
    hl_buf_putc(b, '"');
}

static void emit(hl_json *j, const char *s, size_t n)
{
    if (j->buf != NULL)
        hl_buf_putn(j->buf, s, n);
    else if (j->fp != NULL && fwrite(s, 1, n, j->fp) != n)
        j->error = 1;
}

static void emits(hl_json *j, const char *s)
{
    emit(j, s, strlen(s));
}

static void init(hl_json *j)
{
    j->depth = 0;
    memset(j->count, 0, sizeof j->count);
    j->after_key = 0;
    j->pretty = 1;
    j->error = 0;
}

void hl_json_init_buf(hl_json *j, hl_buf *b)
{
    init(j);
    j->buf = b;
    j->fp = NULL;
}

void hl_json_init_file(hl_json *j, FILE *fp)
{
    init(j);
    j->buf = NULL;
    j->fp = fp;
}

static void newline(hl_json *j)
{
    if (!j->pretty)
        return;
    emits(j, "\n");
    for (int i = 0; i < j->depth; i++)
        emits(j, "  ");
}

/* Before any value: a comma and a new line unless it follows its key. */
static void before_value(hl_json *j)
{
    if (j->after_key) {
        j->after_key = 0;
        return;
    }
    if (j->depth > 0) {
        if (j->count[j->depth - 1] > 0)
            emits(j, ",");
        newline(j);
        j->count[j->depth - 1]++;
    } else if (j->count[0]++ > 0)
        j->error = 1; /* two top-level values */
}

static void json_open(hl_json *j, const char *c)
{
    before_value(j);
    emits(j, c);
    if (j->depth + 1 >= HL_JSON_MAX_DEPTH) {
        j->error = 1;
        return;
    }
    j->depth++;
    j->count[j->depth - 1] = 0;
}

static void json_close(hl_json *j, const char *c)
{
    if (j->depth == 0 || j->after_key) {
        j->error = 1;
        return;
    }
    int empty = j->count[j->depth - 1] == 0;
    j->depth--;
    if (!empty)
        newline(j);
    emits(j, c);
}

void hl_json_object_begin(hl_json *j) { json_open(j, "{"); }
void hl_json_object_end(hl_json *j) { json_close(j, "}"); }
void hl_json_array_begin(hl_json *j) { json_open(j, "["); }
void hl_json_array_end(hl_json *j) { json_close(j, "]"); }

static void put_string(hl_json *j, const char *s)
{
    hl_buf b;
    hl_buf_init(&b);
    hl_json_escape(&b, s);
    emit(j, b.s, b.len);
    hl_buf_clear(&b);
}

void hl_json_key(hl_json *j, const char *key)
{
    if (j->after_key)
        j->error = 1;
    before_value(j);
    put_string(j, key);
    emits(j, j->pretty ? ": " : ":");
    j->after_key = 1;
}

void hl_json_string(hl_json *j, const char *s)
{
    if (s == NULL) {
        hl_json_null(j);
        return;
    }
    before_value(j);
    put_string(j, s);
}

void hl_json_int(hl_json *j, long v)
{
    char s[32];
    before_value(j);
    snprintf(s, sizeof s, "%ld", v);
    emits(j, s);
}

void hl_json_double(hl_json *j, double v)
{
    char s[32];
    before_value(j);
    if (isfinite(v))
        snprintf(s, sizeof s, "%.17g", v);
    emits(j, isfinite(v) ? s : "null");
}

void hl_json_bool(hl_json *j, int v)
{
    before_value(j);
    emits(j, v ? "true" : "false");
}

void hl_json_null(hl_json *j)
{
    before_value(j);
    emits(j, "null");
}

void hl_json_kv_string(hl_json *j, const char *key, const char *s)
{
    hl_json_key(j, key);
    hl_json_string(j, s);
}

void hl_json_kv_int(hl_json *j, const char *key, long v)
{
    hl_json_key(j, key);
    hl_json_int(j, v);
}

void hl_json_kv_double(hl_json *j, const char *key, double v)
{
    hl_json_key(j, key);
    hl_json_double(j, v);
}

void hl_json_kv_bool(hl_json *j, const char *key, int v)
{
    hl_json_key(j, key);
    hl_json_bool(j, v);
}

int hl_json_finish(hl_json *j)
{
    emits(j, "\n");
    if (j->depth != 0 || j->after_key)
        j->error = 1;
    return j->error;
}
