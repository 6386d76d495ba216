/* hamlie's CPython extension (_hamlie): what its files share.
 *
 * The extension is thin on purpose: it turns Python arguments into the C
 * library's calls and the library's results into plain Python values —
 * formulas as strings in the SymPy style (expr.h: HL_STYLE_SYMPY), numbers as
 * floats, trajectories as NumPy arrays the library fills directly.  The
 * package python/hamlie/ turns the strings into SymPy expressions.
 *
 * Threads: every computation runs with the GIL released.  An hl_system is
 * not safe to use from two threads at once (its pool and algebra context
 * grow), so each System object has its own lock, taken before the GIL is
 * released (system_lock).
 */
#ifndef HAMLIE_PY_BINDING_H
#define HAMLIE_PY_BINDING_H

#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <pythread.h>

#include "hamlie/error.h"
#include "hamlie/ham.h"

/* One NumPy API table for the whole extension (module.c imports it). */
#define PY_ARRAY_UNIQUE_SYMBOL hamlie_py_ARRAY_API
#define NPY_NO_DEPRECATED_API NPY_1_7_API_VERSION

typedef struct {
    PyObject_HEAD hl_system *sys;
    PyThread_type_lock lock;
} SystemObject;

extern PyTypeObject System_Type;
extern PyObject *hamlie_Error; /* hamlie.Error, a ValueError */

/* Raise the library's error as a Python exception and return NULL:
 * hamlie.Error (message, position, source, status) for bad input,
 * MemoryError for HL_ENOMEM, KeyboardInterrupt for HL_ESTOP after a signal. */
PyObject *raise_hl_error(const hl_error *err, hl_status st);
/* d[key] = v, stealing v; -1 (an exception set) if v is NULL or the store fails */
int dict_put(PyObject *d, const char *key, PyObject *v);

/* Take the System's lock, releasing the GIL while waiting for it. */
void system_lock(SystemObject *self);
void system_unlock(SystemObject *self);

/* A str (or None when none_ok) argument as UTF-8; NULL with TypeError. */
int arg_text(PyObject *o, const char *what, int none_ok, const char **out);

/* A malloc'd string as a Python str (NULL string: None); frees s. */
PyObject *take_str(char *s);

/* Formula helpers (system.c): an element in the SymPy style, a vector of m. */
PyObject *alg_str(const hl_alg *a, hl_system *sys);
PyObject *alg_list(const hl_alg *a, int m, hl_system *sys);
/* The phase variables' names: q_1..q_N, p_1..p_N. */
const char *phase_name(hl_system *sys, int i);

/* The progress callback that lets Ctrl-C stop a long call: it takes the GIL
 * briefly and asks Python whether a signal is pending. */
int check_signals_progress(double done, double total, void *arg);

/* Methods defined in analysis.c and run.c. */
PyObject *System_errors(SystemObject *self, PyObject *args, PyObject *kw);
PyObject *System_run(SystemObject *self, PyObject *args, PyObject *kw);
/* Build a scheme from (name, param) or a map or equations (analysis.c). */
struct hl_scheme;
hl_status make_scheme(struct hl_scheme **out, const char *name, int param, const char *map,
                      const char *equations, hl_system *sys, hl_error *err);

#endif
