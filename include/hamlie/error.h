/* hamlie — status codes and error details shared by every layer.
 *
 * Every fallible function returns an hl_status (0 = success) and, when given
 * a non-NULL hl_error, fills it with a message and, for errors in a formula,
 * the byte position of the offending spot in that formula.  Nothing in the
 * library aborts or prints on bad user input.
 */
#ifndef HAMLIE_ERROR_H
#define HAMLIE_ERROR_H

#ifdef __cplusplus
extern "C" {
#endif

typedef enum hl_status {
    HL_OK = 0,  /* success */
    HL_EPARSE,  /* a formula or option text did not parse */
    HL_EINVAL,  /* well-formed but meaningless here: unknown name, wrong count */
    HL_EDOM,    /* mathematical domain error: division by zero, log(0) */
    HL_ELIMIT,  /* refused: would exceed a resource limit (order, size, depth) */
    HL_ENOMEM,  /* allocation failed */
    HL_EUNSUP,  /* a valid request that hamlie cannot carry out */
    HL_ENOCONV, /* an iteration (Newton, quadrature) did not converge */
    HL_EIO,     /* reading or writing a file failed */
    HL_ESTOP    /* stopped by the caller: its progress callback asked to stop */
} hl_status;

/* The progress of a long computation (a run, a Lie series): the library
 * calls it at a bounded rate with `done` out of `total` (in the call's own
 * units: steps, output rows, orders).  A non-zero return stops the
 * computation, which leaves what it delivered valid and returns HL_ESTOP. */
typedef int (*hl_progress_fn)(double done, double total, void *arg);

#define HL_ERROR_MSG_MAX 512

typedef struct hl_error {
    hl_status status;
    int pos;          /* byte offset of the bad spot in src, or -1 */
    int len;          /* length of the bad span in bytes (>= 1 when pos >= 0) */
    const char *src;  /* the formula pos refers to (borrowed from the caller), or NULL */
    char msg[HL_ERROR_MSG_MAX]; /* lowercase, no trailing full stop, names quoted */
} hl_error;

/* Reset to "no error". */
void hl_error_clear(hl_error *err);

/* Record an error (err may be NULL) and return status, so callers can write
 * `return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "unknown symbol '%s'", s);` */
hl_status hl_error_set(hl_error *err, hl_status status, const char *src, int pos,
                       int len, const char *fmt, ...)
    __attribute__((format(printf, 6, 7)));

/* Prefix the existing message with context: "in integral 2: <old message>". */
void hl_error_prefix(hl_error *err, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* Short English name of a status, e.g. "parse error". */
const char *hl_status_string(hl_status status);

#ifdef __cplusplus
}
#endif

#endif
