/* _hamlie.System: an hl_system (ham.h) and the §2 calls on it — the
 * generator, brackets, integrals, involution, the Jacobian's rank, canonical
 * maps and Lie series.  Formulas come in as hamlie text and go out as text
 * in the SymPy style. */
#include "binding.h"

#include <stdlib.h>

#include "hamlie/report.h"

/* ---- helpers ------------------------------------------------------------------ */

void system_lock(SystemObject *self)
{
    if (!PyThread_acquire_lock(self->lock, NOWAIT_LOCK)) {
        Py_BEGIN_ALLOW_THREADS
        PyThread_acquire_lock(self->lock, WAIT_LOCK);
        Py_END_ALLOW_THREADS
    }
}

void system_unlock(SystemObject *self)
{
    PyThread_release_lock(self->lock);
}

PyObject *alg_str(const hl_alg *a, hl_system *sys)
{
    return take_str(hl_format_alg(a, hl_system_ctx(sys), hl_system_pool(sys), HL_STYLE_SYMPY));
}

PyObject *alg_list(const hl_alg *a, int m, hl_system *sys)
{
    PyObject *list = PyList_New(m);
    for (int i = 0; list != NULL && i < m; i++) {
        PyObject *s = alg_str(&a[i], sys);
        if (s == NULL)
            Py_CLEAR(list);
        else
            PyList_SET_ITEM(list, i, s);
    }
    return list;
}

const char *phase_name(hl_system *sys, int i)
{
    int N = hl_system_ndof(sys);
    return i < N ? hl_system_coord(sys, i) : hl_system_momentum(sys, i - N);
}

static PyObject *names_list(hl_system *sys, const char *(*name)(const hl_system *, int), int n)
{
    PyObject *list = PyList_New(n);
    for (int i = 0; list != NULL && i < n; i++) {
        PyObject *s = PyUnicode_FromString(name(sys, i));
        if (s == NULL)
            Py_CLEAR(list);
        else
            PyList_SET_ITEM(list, i, s);
    }
    return list;
}

/* A sequence of str as a malloc'd array of UTF-8 pointers (borrowed from the
 * items, which the caller's `seq` keeps alive); *n its length. */
static const char **text_array(PyObject *seq_in, const char *what, PyObject **seq, int *n)
{
    *seq = PySequence_Fast(seq_in, "expected a list of formulas (str)");
    if (*seq == NULL)
        return NULL;
    Py_ssize_t len = PySequence_Fast_GET_SIZE(*seq);
    if (len > 10000) {
        PyErr_Format(PyExc_ValueError, "too many %s (%zd; at most 10000)", what, len);
        Py_CLEAR(*seq);
        return NULL;
    }
    const char **t = calloc((size_t)len + 1, sizeof *t);
    if (t == NULL) {
        Py_CLEAR(*seq);
        return (const char **)PyErr_NoMemory();
    }
    for (Py_ssize_t i = 0; i < len; i++)
        if (arg_text(PySequence_Fast_GET_ITEM(*seq, i), what, 0, &t[i]) < 0) {
            free(t);
            Py_CLEAR(*seq);
            return NULL;
        }
    *n = (int)len;
    return t;
}

/* ---- construction ------------------------------------------------------------- */

static PyObject *System_new(PyTypeObject *type, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"H", "pairs", "params", "step", "extra", NULL};
    PyObject *Ho = Py_None, *pairso = Py_None, *paramso = Py_None, *stepo = Py_None,
             *extrao = Py_None;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|OOOOO", kwlist, &Ho, &pairso, &paramso, &stepo,
                                     &extrao))
        return NULL;
    hl_system_spec spec = {0};
    if (arg_text(Ho, "H", 1, &spec.H) < 0 || arg_text(pairso, "pairs", 1, &spec.pairs) < 0 ||
        arg_text(paramso, "params", 1, &spec.params) < 0 ||
        arg_text(stepo, "step", 1, &spec.step) < 0)
        return NULL;
    PyObject *seq = NULL;
    const char **extra = NULL;
    int nextra = 0;
    if (extrao != Py_None && (extra = text_array(extrao, "extra formulas", &seq, &nextra)) == NULL)
        return NULL;
    spec.extra = extra;
    SystemObject *self = (SystemObject *)type->tp_alloc(type, 0);
    if (self != NULL && (self->lock = PyThread_allocate_lock()) == NULL) {
        Py_CLEAR(self);
        PyErr_NoMemory();
    }
    if (self != NULL) {
        hl_error err;
        hl_error_clear(&err);
        hl_status st;
        Py_BEGIN_ALLOW_THREADS
        st = hl_system_new(&self->sys, &spec, &err);
        Py_END_ALLOW_THREADS
        if (st != HL_OK) {
            self->sys = NULL;
            Py_CLEAR(self);
            raise_hl_error(&err, st);
        }
    }
    free(extra);
    Py_XDECREF(seq);
    return (PyObject *)self;
}

static void System_dealloc(SystemObject *self)
{
    hl_system_free(self->sys);
    if (self->lock != NULL)
        PyThread_free_lock(self->lock);
    Py_TYPE(self)->tp_free((PyObject *)self);
}

/* ---- what the system is ------------------------------------------------------ */

static PyObject *param_values(hl_system *sys)
{
    PyObject *d = PyDict_New();
    for (int i = 0; d != NULL && i < hl_system_nset(sys); i++) {
        char *s = hl_expr_print(hl_system_set_value(sys, i), HL_STYLE_SYMPY);
        if (dict_put(d, hl_system_set_name(sys, i), take_str(s)) < 0)
            Py_CLEAR(d);
    }
    return d;
}

static PyObject *System_info(SystemObject *self, PyObject *unused)
{
    hl_system *sys = self->sys;
    int N = hl_system_ndof(sys);
    PyObject *d = PyDict_New();
    if (d == NULL)
        return NULL;
    system_lock(self);
    int bad =
        dict_put(d, "coordinates", names_list(sys, hl_system_coord, N)) < 0 ||
        dict_put(d, "momenta", names_list(sys, hl_system_momentum, N)) < 0 ||
        dict_put(d, "parameters", names_list(sys, hl_system_param, hl_system_nparams(sys))) < 0 ||
        dict_put(d, "step", PyUnicode_FromString(hl_system_step(sys))) < 0 ||
        dict_put(d, "parameter_values", param_values(sys)) < 0 ||
        dict_put(d, "H",
                 hl_system_has_H(sys) ? alg_str(hl_system_H(sys), sys) : Py_NewRef(Py_None)) < 0;
    system_unlock(self);
    if (bad)
        Py_CLEAR(d);
    return d;
}

/* ---- §2 ------------------------------------------------------------------------ */

static PyObject *need_H(SystemObject *self)
{
    if (hl_system_has_H(self->sys))
        return Py_None;
    PyErr_SetString(hamlie_Error, "this system has no Hamiltonian");
    return NULL;
}

/* generator() -> (xi, eta): xi_j = dH/dp_j, eta_j = -dH/dq_j as strings */
static PyObject *System_generator(SystemObject *self, PyObject *unused)
{
    if (need_H(self) == NULL)
        return NULL;
    hl_system *sys = self->sys;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int N = hl_system_ndof(sys);
    hl_error err;
    hl_error_clear(&err);
    system_lock(self);
    hl_alg *v = hl_alg_vec_new(2 * N, ctx);
    hl_status st;
    Py_BEGIN_ALLOW_THREADS
    st = hl_generator(v, v + N, sys, &err);
    Py_END_ALLOW_THREADS
    PyObject *r = st == HL_OK ? alg_list(v, 2 * N, sys) : raise_hl_error(&err, st);
    hl_alg_vec_free(v, 2 * N, ctx);
    system_unlock(self);
    return r;
}

/* Read n formulas of the phase variables (the step refused) into f. */
static hl_status read_phase_all(hl_alg *f, const char **text, int n, hl_system *sys, hl_error *err)
{
    hl_status st = HL_OK;
    for (int k = 0; k < n && st == HL_OK; k++)
        if ((st = hl_system_read_phase(&f[k], sys, text[k], err)) != HL_OK && n > 1)
            hl_error_prefix(err, "in formula %d", k + 1);
    return st;
}

/* bracket(f, g) -> {f, g} as a string */
static PyObject *System_bracket(SystemObject *self, PyObject *args)
{
    PyObject *fo, *go;
    const char *t[2];
    if (!PyArg_ParseTuple(args, "OO", &fo, &go) || arg_text(fo, "f", 0, &t[0]) < 0 ||
        arg_text(go, "g", 0, &t[1]) < 0)
        return NULL;
    hl_system *sys = self->sys;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_error err;
    hl_error_clear(&err);
    system_lock(self);
    hl_alg *f = hl_alg_vec_new(3, ctx);
    hl_status st;
    Py_BEGIN_ALLOW_THREADS
    st = read_phase_all(f, t, 2, sys, &err);
    if (st == HL_OK)
        st = hl_bracket(&f[2], &f[0], &f[1], sys, &err);
    Py_END_ALLOW_THREADS
    PyObject *r = st == HL_OK ? alg_str(&f[2], sys) : raise_hl_error(&err, st);
    hl_alg_vec_free(f, 3, ctx);
    system_unlock(self);
    return r;
}

/* What check() computes for n functions, as `hamlie check` does. */
typedef struct checks {
    hl_alg *f, *withH, *inv;
    int *integral;
    int involution, rank, rank_with_H;
} checks;

static hl_status compute_checks(checks *c, const char **text, int n, hl_system *sys, hl_error *err)
{
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_status st = read_phase_all(c->f, text, n, sys, err);
    for (int k = 0; k < n && st == HL_OK; k++) {
        st = hl_check_integral(&c->integral[k], &c->withH[k], &c->f[k], sys, err);
        if (st == HL_OK && c->integral[k]) /* 0, even when decided numerically */
            hl_alg_zero(&c->withH[k], ctx);
    }
    if (st == HL_OK)
        st = hl_check_involution(&c->involution, c->inv, c->f, n, sys, err);
    for (int k = 0; k < n * n && st == HL_OK; k++)
        if (hl_alg_is_zero(&c->inv[k], ctx))
            hl_alg_zero(&c->inv[k], ctx);
    if (st == HL_OK)
        st = hl_jacobian_rank(&c->rank, c->f, n, sys, err);
    if (st == HL_OK) {
        hl_alg_set(&c->f[n], hl_system_H(sys), ctx);
        st = hl_jacobian_rank(&c->rank_with_H, c->f, n + 1, sys, err);
    }
    return st;
}

static PyObject *checks_result(const checks *c, int n, hl_system *sys)
{
    PyObject *integral = PyList_New(n), *inv = PyList_New(n);
    for (int k = 0; integral != NULL && inv != NULL && k < n; k++) {
        PyObject *row = alg_list(c->inv + k * n, n, sys);
        PyList_SET_ITEM(inv, k, row != NULL ? row : Py_NewRef(Py_None));
        PyList_SET_ITEM(integral, k, PyBool_FromLong(c->integral[k]));
    }
    PyObject *withH = alg_list(c->withH, n, sys);
    PyObject *r = NULL;
    if (integral != NULL && inv != NULL && withH != NULL && !PyErr_Occurred())
        r = Py_BuildValue("{sOsOsOsOsisi}", "integral", integral, "bracket_with_H", withH,
                          "involution_brackets", inv, "involution",
                          c->involution ? Py_True : Py_False, "rank", c->rank, "rank_with_H",
                          c->rank_with_H);
    Py_XDECREF(integral);
    Py_XDECREF(inv);
    Py_XDECREF(withH);
    return r;
}

/* check(list of formulas) -> dict (integrals, involution, ranks) */
static PyObject *System_check(SystemObject *self, PyObject *args)
{
    PyObject *lo, *seq;
    int n = 0;
    if (!PyArg_ParseTuple(args, "O", &lo) || need_H(self) == NULL)
        return NULL;
    const char **text = text_array(lo, "integrals", &seq, &n);
    if (text == NULL)
        return NULL;
    hl_system *sys = self->sys;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_error err;
    hl_error_clear(&err);
    system_lock(self);
    checks c = {hl_alg_vec_new(n + 1, ctx),
                hl_alg_vec_new(n, ctx),
                hl_alg_vec_new(n * n, ctx),
                calloc((size_t)n + 1, sizeof(int)),
                0,
                0,
                0};
    hl_status st;
    Py_BEGIN_ALLOW_THREADS
    st = compute_checks(&c, text, n, sys, &err);
    Py_END_ALLOW_THREADS
    PyObject *r = st == HL_OK ? checks_result(&c, n, sys) : raise_hl_error(&err, st);
    hl_alg_vec_free(c.f, n + 1, ctx);
    hl_alg_vec_free(c.withH, n, ctx);
    hl_alg_vec_free(c.inv, n * n, ctx);
    free(c.integral);
    system_unlock(self);
    free(text);
    Py_DECREF(seq);
    return r;
}

/* canonical(map) -> (canonical, 2N x 2N brackets of the images) */
static PyObject *System_canonical(SystemObject *self, PyObject *args)
{
    PyObject *mo;
    const char *map;
    if (!PyArg_ParseTuple(args, "O", &mo) || arg_text(mo, "map", 0, &map) < 0)
        return NULL;
    hl_system *sys = self->sys;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    int m = 2 * hl_system_ndof(sys), canonical = 0;
    hl_error err;
    hl_error_clear(&err);
    system_lock(self);
    hl_alg *img = hl_alg_vec_new(m, ctx), *br = hl_alg_vec_new(m * m, ctx);
    hl_status st;
    Py_BEGIN_ALLOW_THREADS
    st = hl_system_read_map(img, sys, map, &err);
    if (st == HL_OK)
        st = hl_check_canonical(&canonical, br, img, sys, &err);
    Py_END_ALLOW_THREADS
    PyObject *r = NULL;
    if (st != HL_OK)
        raise_hl_error(&err, st);
    else if ((r = PyList_New(m)) != NULL)
        for (int i = 0; i < m; i++) {
            PyObject *row = alg_list(br + i * m, m, sys);
            PyList_SET_ITEM(r, i, row != NULL ? row : Py_NewRef(Py_None));
        }
    hl_alg_vec_free(img, m, ctx);
    hl_alg_vec_free(br, m * m, ctx);
    system_unlock(self);
    if (r != NULL && PyErr_Occurred())
        Py_CLEAR(r);
    return r != NULL ? Py_BuildValue("(NN)", PyBool_FromLong(canonical), r) : NULL;
}

/* lie_terms(phi, order) -> [g^k phi for k = 0..order] as strings */
static PyObject *System_lie_terms(SystemObject *self, PyObject *args)
{
    PyObject *po;
    const char *phi_text;
    int order;
    if (!PyArg_ParseTuple(args, "Oi", &po, &order) || arg_text(po, "phi", 0, &phi_text) < 0 ||
        need_H(self) == NULL)
        return NULL;
    if (order < 0 || order > HL_LIE_MAX_ORDER)
        return PyErr_Format(PyExc_ValueError, "order must be in 0..%d, not %d", HL_LIE_MAX_ORDER,
                            order);
    hl_system *sys = self->sys;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_error err;
    hl_error_clear(&err);
    system_lock(self);
    hl_alg *t = hl_alg_vec_new(order + 2, ctx); /* t[order + 1]: phi */
    hl_status st;
    Py_BEGIN_ALLOW_THREADS
    st = hl_system_read_phase(&t[order + 1], sys, phi_text, &err);
    if (st == HL_OK)
        st = hl_lie_terms_watched(t, &t[order + 1], order, sys, check_signals_progress, NULL, &err);
    Py_END_ALLOW_THREADS
    PyObject *r = st == HL_OK ? alg_list(t, order + 1, sys) : raise_hl_error(&err, st);
    hl_alg_vec_free(t, order + 2, ctx);
    system_unlock(self);
    return r;
}

/* read(formula) -> the formula as hamlie reads it (parameters set) */
static PyObject *System_read(SystemObject *self, PyObject *args)
{
    PyObject *fo;
    const char *text;
    if (!PyArg_ParseTuple(args, "O", &fo) || arg_text(fo, "formula", 0, &text) < 0)
        return NULL;
    hl_system *sys = self->sys;
    hl_alg_ctx *ctx = hl_system_ctx(sys);
    hl_error err;
    hl_error_clear(&err);
    system_lock(self);
    hl_alg a;
    hl_alg_init(&a, ctx);
    hl_status st = hl_system_read(&a, sys, text, &err);
    PyObject *r = st == HL_OK ? alg_str(&a, sys) : raise_hl_error(&err, st);
    hl_alg_clear(&a, ctx);
    system_unlock(self);
    return r;
}

static PyMethodDef System_methods[] = {
    {"info", (PyCFunction)System_info, METH_NOARGS,
     "info() -> dict: coordinates, momenta, parameters, step, parameter_values, H"},
    {"generator", (PyCFunction)System_generator, METH_NOARGS,
     "generator() -> [dH/dp_1.., -dH/dq_1..] (strings, SymPy syntax)"},
    {"bracket", (PyCFunction)System_bracket, METH_VARARGS, "bracket(f, g) -> {f, g}"},
    {"check", (PyCFunction)System_check, METH_VARARGS,
     "check(formulas) -> dict: integrals, brackets with H, involution, ranks"},
    {"canonical", (PyCFunction)System_canonical, METH_VARARGS,
     "canonical(map) -> (bool, matrix of the images' brackets)"},
    {"lie_terms", (PyCFunction)System_lie_terms, METH_VARARGS,
     "lie_terms(phi, order) -> [g^k phi, k = 0..order]"},
    {"read", (PyCFunction)System_read, METH_VARARGS, "read(formula) -> the formula as read"},
    {"errors", (PyCFunction)(void (*)(void))System_errors, METH_VARARGS | METH_KEYWORDS,
     "errors(scheme=, map=, equations=, order=, correct=, invariants=) -> dict (hamlie errors)"},
    {"run", (PyCFunction)(void (*)(void))System_run, METH_VARARGS | METH_KEYWORDS,
     "run(...) -> dict of NumPy arrays (hamlie run)"},
    {NULL, NULL, 0, NULL}};

PyTypeObject System_Type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "_hamlie.System",
    .tp_basicsize = sizeof(SystemObject),
    .tp_dealloc = (destructor)System_dealloc,
    .tp_flags = Py_TPFLAGS_DEFAULT | Py_TPFLAGS_BASETYPE,
    .tp_doc = "System(H=None, pairs=None, params=None, step=None, extra=None): an hl_system",
    .tp_methods = System_methods,
    .tp_new = System_new,
};
