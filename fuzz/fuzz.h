/* Shared by the fuzz targets: the input as a C string, and the contract of
 * every failure (a status, a message, a position inside the text). */
#ifndef HAMLIE_FUZZ_H
#define HAMLIE_FUZZ_H

#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "hamlie/error.h"

/* Inputs past this are cut: libFuzzer runs with -max_len=4096 anyway, and
 * CTest's replay must not take longer than the fuzzer did. */
#define FUZZ_MAX_INPUT 4096

/* The input as a NUL-terminated string (an embedded NUL ends it early). */
static inline char *fuzz_string(const uint8_t *data, size_t size)
{
    if (size > FUZZ_MAX_INPUT)
        size = FUZZ_MAX_INPUT;
    char *s = malloc(size + 1);
    memcpy(s, data, size);
    s[size] = '\0';
    return s;
}

/* A failure must say what failed and point inside the text it read (or just
 * past its end); anything else is a bug the fuzzer reports as a crash. */
static inline void fuzz_check_error(int status, const hl_error *err, const char *src)
{
    if (status == 0)
        return;
    if (err->msg[0] == '\0' || (int)err->status != status)
        abort();
    if (err->src == src && (err->pos < -1 || err->pos > (int)strlen(src)))
        abort();
}

#endif
