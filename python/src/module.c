/* _hamlie: the module — its exception, error conversion, the scheme
 * catalog, and the module table.  The System type is in system.c, the
 * error analysis in analysis.c, runs in run.c. */
#include "binding.h"

#include <numpy/arrayobject.h>
#include <stdlib.h>
#include <string.h>

#include "hamlie/scheme.h"

PyObject *hamlie_Error;

/* The position as Python counts it: code points, not UTF-8 bytes. */
static long char_offset(const char *src, int pos)
{
    long n = 0;
    for (int i = 0; i < pos && src[i] != '\0'; i++)
        n += ((unsigned char)src[i] & 0xC0) != 0x80;
    return n;
}

/* "message" and, for a formula, the formula with a caret under the spot,
 * as the command line prints it. */
static PyObject *error_text(const hl_error *err, long cpos)
{
    if (err->src == NULL || err->pos < 0)
        return PyUnicode_FromString(err->msg);
    PyObject *pad = PyUnicode_FromOrdinal(' '), *spaces = NULL, *text = NULL;
    if (pad != NULL)
        spaces = PySequence_Repeat(pad, cpos);
    if (spaces != NULL)
        text = PyUnicode_FromFormat("%s\n    %s\n    %U^", err->msg, err->src, spaces);
    Py_XDECREF(pad);
    Py_XDECREF(spaces);
    return text;
}

static int set_attr(PyObject *o, const char *name, PyObject *v)
{
    if (v == NULL)
        return -1;
    int rc = PyObject_SetAttrString(o, name, v);
    Py_DECREF(v);
    return rc;
}

PyObject *raise_hl_error(const hl_error *err, hl_status st)
{
    if (PyErr_Occurred()) /* a signal handler raised already (HL_ESTOP) */
        return NULL;
    if (st == HL_ENOMEM)
        return PyErr_NoMemory();
    if (st == HL_ESTOP) {
        PyErr_SetString(PyExc_KeyboardInterrupt, "stopped");
        return NULL;
    }
    int has_pos = err->src != NULL && err->pos >= 0;
    long cpos = has_pos ? char_offset(err->src, err->pos) : -1;
    PyObject *text = error_text(err, cpos);
    if (text == NULL)
        return NULL;
    PyObject *e = PyObject_CallOneArg(hamlie_Error, text);
    Py_DECREF(text);
    if (e == NULL)
        return NULL;
    if (set_attr(e, "message", PyUnicode_FromString(err->msg)) < 0 ||
        set_attr(e, "position", has_pos ? PyLong_FromLong(cpos) : Py_NewRef(Py_None)) < 0 ||
        set_attr(e, "source", has_pos ? PyUnicode_FromString(err->src) : Py_NewRef(Py_None)) < 0 ||
        set_attr(e, "status", PyUnicode_FromString(hl_status_string(st))) < 0) {
        Py_DECREF(e);
        return NULL;
    }
    PyErr_SetObject(hamlie_Error, e);
    Py_DECREF(e);
    return NULL;
}

int check_signals_progress(double done, double total, void *arg)
{
    PyGILState_STATE g = PyGILState_Ensure();
    int stop = PyErr_CheckSignals() != 0;
    PyGILState_Release(g);
    return stop;
}

int arg_text(PyObject *o, const char *what, int none_ok, const char **out)
{
    if (o == NULL || (none_ok && o == Py_None)) {
        *out = NULL;
        return 0;
    }
    if (!PyUnicode_Check(o)) {
        PyErr_Format(PyExc_TypeError, "%s must be a str, not %.80s", what, Py_TYPE(o)->tp_name);
        return -1;
    }
    Py_ssize_t len;
    *out = PyUnicode_AsUTF8AndSize(o, &len);
    if (*out == NULL)
        return -1;
    if ((Py_ssize_t)strlen(*out) != len) {
        PyErr_Format(PyExc_ValueError, "%s contains a NUL character", what);
        return -1;
    }
    return 0;
}

PyObject *take_str(char *s)
{
    if (s == NULL)
        Py_RETURN_NONE;
    PyObject *o = PyUnicode_FromString(s);
    free(s);
    return o;
}

/* ---- the catalog ----------------------------------------------------------- */

int dict_put(PyObject *d, const char *key, PyObject *v)
{
    if (v == NULL)
        return -1;
    int rc = PyDict_SetItemString(d, key, v);
    Py_DECREF(v);
    return rc;
}

static PyObject *flag(unsigned flags, unsigned bit)
{
    return PyBool_FromLong((flags & bit) != 0);
}

/* One record as `hamlie schemes --json` writes it (docs/json.md). */
static PyObject *scheme_record(const hl_scheme_info *in)
{
    PyObject *d = PyDict_New();
    if (d == NULL)
        return NULL;
    int family = in->order == HL_SCHEME_ORDER_N, exact = in->order == HL_SCHEME_EXACT;
    unsigned f = in->flags;
    if (dict_put(d, "name", PyUnicode_FromString(in->name)) < 0 ||
        dict_put(d, "order", family || exact ? Py_NewRef(Py_None) : PyLong_FromLong(in->order)) <
            0 ||
        (family && dict_put(d, "order_range", Py_BuildValue("[ii]", 1, HL_SCHEME_LIE_MAX)) < 0) ||
        dict_put(d, "exact", PyBool_FromLong(exact)) < 0 ||
        dict_put(d, "symplectic", flag(f, HL_SCHEME_SYMPLECTIC)) < 0 ||
        dict_put(d, "preserves_H", flag(f, HL_SCHEME_PRESERVES_H)) < 0 ||
        dict_put(d, "implicit", flag(f, HL_SCHEME_IMPLICIT)) < 0 ||
        dict_put(d, "explicit_if_separable", flag(f, HL_SCHEME_SEPARABLE)) < 0 ||
        dict_put(d, "oscillator_only", flag(f, HL_SCHEME_OSCILLATOR)) < 0 ||
        dict_put(d, "quadratic_only", flag(f, HL_SCHEME_QUADRATIC)) < 0 ||
        dict_put(d, "description", PyUnicode_FromString(in->description)) < 0 ||
        dict_put(d, "text",
                 hl_scheme_text(in->name) ? PyUnicode_FromString(hl_scheme_text(in->name))
                                          : Py_NewRef(Py_None)) < 0) {
        Py_DECREF(d);
        return NULL;
    }
    return d;
}

static PyObject *mod_schemes(PyObject *mod, PyObject *unused)
{
    int n = hl_scheme_catalog_count();
    PyObject *list = PyList_New(n);
    for (int i = 0; list != NULL && i < n; i++) {
        PyObject *r = scheme_record(hl_scheme_catalog(i));
        if (r == NULL)
            Py_CLEAR(list);
        else
            PyList_SET_ITEM(list, i, r);
    }
    return list;
}

static PyMethodDef module_methods[] = {
    {"schemes", mod_schemes, METH_NOARGS,
     "schemes() -> list of dict: the catalog of one-step schemes (as `hamlie schemes --json`)"},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef module_def = {
    PyModuleDef_HEAD_INIT,
    .m_name = "_hamlie",
    .m_doc = "hamlie's C library (libhamlie) from Python: the layer under the hamlie package",
    .m_size = -1,
    .m_methods = module_methods,
};

PyMODINIT_FUNC PyInit__hamlie(void)
{
    import_array();
    if (PyType_Ready(&System_Type) < 0)
        return NULL;
    PyObject *m = PyModule_Create(&module_def);
    if (m == NULL)
        return NULL;
    hamlie_Error = PyErr_NewExceptionWithDoc(
        "hamlie.Error",
        "An error of hamlie's library: .message, .position (in .source, code points; "
        "None when the error is not in a formula), .status",
        PyExc_ValueError, NULL);
    if (hamlie_Error == NULL || PyModule_AddObjectRef(m, "Error", hamlie_Error) < 0 ||
        PyModule_AddObjectRef(m, "System", (PyObject *)&System_Type) < 0 ||
        PyModule_AddIntConstant(m, "LIE_MAX_ORDER", HL_LIE_MAX_ORDER) < 0) {
        Py_DECREF(m);
        return NULL;
    }
    return m;
}
