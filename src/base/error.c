/* Status names and hl_error helpers. */
#include <stdarg.h>
#include <stdio.h>
#include <string.h>

#include "hamlie/error.h"

void hl_error_clear(hl_error *err)
{
    if (err == NULL)
        return;
    err->status = HL_OK;
    err->pos = -1;
    err->len = 0;
    err->src = NULL;
    err->msg[0] = '\0';
}

hl_status hl_error_set(hl_error *err, hl_status status, const char *src, int pos, int len,
                       const char *fmt, ...)
{
    va_list ap;

    if (err == NULL)
        return status;
    err->status = status;
    err->src = src;
    err->pos = pos;
    err->len = (pos >= 0 && len < 1) ? 1 : len;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
    return status;
}

void hl_error_prefix(hl_error *err, const char *fmt, ...)
{
    char msg[HL_ERROR_MSG_MAX];
    va_list ap;

    if (err == NULL)
        return;
    va_start(ap, fmt);
    int n = vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    /* append ": <old message>", cut to fit like every message */
    size_t used = n < 0 ? 0 : ((size_t)n < sizeof msg ? (size_t)n : sizeof msg - 1);
    size_t room = sizeof msg - 1 - used;
    size_t old = strlen(err->msg);
    if (room >= 2) {
        memcpy(msg + used, ": ", 2);
        used += 2;
        room -= 2;
        if (old > room)
            old = room;
        memcpy(msg + used, err->msg, old);
        used += old;
    }
    msg[used] = '\0';
    memcpy(err->msg, msg, used + 1);
}

const char *hl_status_string(hl_status status)
{
    switch (status) {
    case HL_OK: return "success";
    case HL_EPARSE: return "parse error";
    case HL_EINVAL: return "invalid input";
    case HL_EDOM: return "domain error";
    case HL_ELIMIT: return "limit exceeded";
    case HL_ENOMEM: return "out of memory";
    case HL_EUNSUP: return "not supported";
    case HL_ENOCONV: return "no convergence";
    case HL_EIO: return "input/output error";
    case HL_ESTOP: return "stopped";
    }
    return "unknown status";
}
