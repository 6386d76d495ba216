/* _hamlie.System.errors: the error analysis of §4 (hl_analysis_compute, the
 * call `hamlie errors` makes) returned as a dict with the keys of
 * `hamlie errors --json` (docs/json.md), every formula a string in the SymPy
 * style, plus the expansion psi(D) itself. */
#include "binding.h"

#include <stdlib.h>

#include "hamlie/analysis.h"
#include "hamlie/report.h"
#include "hamlie/scheme.h"

hl_status make_scheme(hl_scheme **out, const char *name, int param, const char *map,
                      const char *equations, hl_system *sys, hl_error *err)
{
    hl_status st;
    if (map != NULL) {
        if ((st = hl_scheme_from_map(out, map, sys, err)) != HL_OK)
            hl_error_prefix(err, "in map");
    } else if (equations != NULL) {
        if ((st = hl_scheme_from_equations(out, equations, sys, err)) != HL_OK)
            hl_error_prefix(err, "in equations");
    } else
        st = hl_scheme_new(out, name, param, sys, err);
    return st;
}

/* ---- the result as Python values (GIL held) ------------------------------------- */

/* {name: component} of a field of the m phase variables */
static PyObject *field(const hl_alg *v, const hl_analysis *A)
{
    PyObject *d = PyDict_New();
    for (int i = 0; d != NULL && i < A->m; i++)
        if (dict_put(d, A->names[i], alg_str(&v[i], A->sys)) < 0)
            Py_CLEAR(d);
    return d;
}

static const char *kind_name(hl_errfield_kind k)
{
    static const char *const n[] = {"zero",    "time_shift",  "parallel",
                                    "scaling", "hamiltonian", "general"};
    return n[k];
}

static PyObject *leading(const hl_vfields *e, const hl_errfield *F, const hl_analysis *A)
{
    PyObject *d = PyDict_New();
    if (d == NULL)
        return NULL;
    int lam = F->kind == HL_ERRFIELD_TIME_SHIFT || F->kind == HL_ERRFIELD_PARALLEL;
    if (dict_put(d, "k", PyLong_FromLong(e->leading)) < 0 ||
        dict_put(d, "kind", PyUnicode_FromString(kind_name(F->kind))) < 0 ||
        (lam && dict_put(d, "lambda", alg_str(&F->lambda, A->sys)) < 0) ||
        (F->kind == HL_ERRFIELD_SCALING && dict_put(d, "scale", field(F->scale, A)) < 0) ||
        dict_put(d, "hamiltonian", PyBool_FromLong(F->hamiltonian)) < 0 ||
        dict_put(d, "h",
                 F->hamiltonian && F->have_h ? alg_str(&F->h, A->sys) : Py_NewRef(Py_None)) < 0)
        Py_CLEAR(d);
    return d;
}

/* fields, two_ways_agree, order, exact_to_order_computed, leading into d */
static int put_fields(PyObject *d, const hl_vfields *e, const hl_errfield *F, int have_F,
                      const hl_analysis *A)
{
    PyObject *list = PyList_New(0);
    for (int k = 2; list != NULL && k <= e->n; k++) {
        PyObject *f = field(hl_vfields_v(e, k), A);
        if (f == NULL || PyList_Append(list, f) < 0)
            Py_CLEAR(list);
        Py_XDECREF(f);
    }
    return dict_put(d, "fields", list) < 0 ||
           dict_put(d, "two_ways_agree",
                    e->over_budget ? Py_NewRef(Py_None) : PyBool_FromLong(e->agree)) < 0 ||
           dict_put(d, "order", PyLong_FromLong(e->order)) < 0 ||
           dict_put(d, "exact_to_order_computed", PyBool_FromLong(e->leading == 0)) < 0 ||
           dict_put(d, "leading", have_F ? leading(e, F, A) : Py_NewRef(Py_None)) < 0;
}

static PyObject *series_text(const hl_series *s, int skip1, const hl_analysis *A)
{
    hl_alg_ctx *ctx = hl_system_ctx(A->sys);
    hl_alg *c = hl_alg_vec_new(s->n, ctx);
    for (int k = 0; k < s->n; k++)
        if (!(skip1 && k == 1))
            hl_alg_set(&c[k], &s->c[k], ctx);
    char *t = hl_format_series(c, s->n - 1, hl_system_step(A->sys), 0, ctx, hl_system_pool(A->sys),
                               HL_STYLE_SYMPY);
    hl_alg_vec_free(c, s->n, ctx);
    return take_str(t);
}

/* {name: psi_i(D) to O(D^(n+1))} */
static PyObject *expansion(const hl_analysis *A)
{
    PyObject *d = PyDict_New();
    for (int i = 0; d != NULL && i < A->m; i++)
        if (dict_put(d, A->names[i], series_text(&A->psi[i], 0, A)) < 0)
            Py_CLEAR(d);
    return d;
}

/* K's D^k coefficients, one field each */
static PyObject *K_coefficients(const hl_analysis *A)
{
    if (A->K_series == NULL)
        Py_RETURN_NONE;
    hl_alg_ctx *ctx = hl_system_ctx(A->sys);
    hl_alg *c = hl_alg_vec_new(A->m, ctx);
    PyObject *list = PyList_New(0);
    for (int k = 0; list != NULL && k < A->n; k++) {
        for (int i = 0; i < A->m; i++)
            hl_alg_set(&c[i], &A->K_series[i].c[k], ctx);
        PyObject *f = field(c, A);
        if (f == NULL || PyList_Append(list, f) < 0)
            Py_CLEAR(list);
        Py_XDECREF(f);
    }
    hl_alg_vec_free(c, A->m, ctx);
    return list;
}

static PyObject *invariants(const hl_analysis *A)
{
    if (!(A->have_leading && A->invariants_degree > 0 && A->inv_poly_applicable))
        Py_RETURN_NONE;
    return Py_BuildValue("{sisNsN}", "degree", A->invariants_degree, "polynomial",
                         alg_list(A->inv_poly, A->n_inv_poly, A->sys), "rational",
                         A->inv_darboux_applicable
                             ? alg_list(A->inv_darboux, A->n_inv_darboux, A->sys)
                             : Py_NewRef(Py_None));
}

static PyObject *modified(const hl_analysis *A)
{
    PyObject *fields = PyList_New(0);
    for (int k = 1; fields != NULL && k <= A->nmod; k++) {
        PyObject *f = field(A->mod_fields + k * A->m, A);
        if (f == NULL || PyList_Append(fields, f) < 0)
            Py_CLEAR(fields);
        Py_XDECREF(f);
    }
    if (fields == NULL)
        return NULL;
    return Py_BuildValue("{sisNsN}", "terms", A->nmod, "fields", fields, "hamiltonians",
                         A->mod_H_all ? alg_list(A->mod_H + 1, A->nmod, A->sys)
                                      : Py_NewRef(Py_None));
}

static PyObject *time_part(const hl_analysis *A)
{
    if (!A->tried_tau)
        Py_RETURN_NONE;
    PyObject *d = PyDict_New();
    if (d == NULL)
        return NULL;
    int bad =
        dict_put(d, "pure_time_translation", PyBool_FromLong(A->tau_ok)) < 0 ||
        dict_put(d, "fails_at", A->tau_ok ? Py_NewRef(Py_None) : PyLong_FromLong(A->tau_fail)) <
            0 ||
        (A->tau_ok && (dict_put(d, "tau_series", series_text(&A->tau, 0, A)) < 0 ||
                       dict_put(d, "W_series", series_text(&A->tau, 1, A)) < 0)) ||
        (A->tau_closed && (dict_put(d, "tau", alg_str(&A->tau_forms[0], A->sys)) < 0 ||
                           dict_put(d, "tan_half_tau", alg_str(&A->tau_forms[1], A->sys)) < 0)) ||
        (A->have_D2 && dict_put(d, "double_step", alg_str(&A->tau_forms[2], A->sys)) < 0) ||
        dict_put(d, "closed_form_from_series", PyBool_FromLong(A->tau_series_only)) < 0;
    if (bad)
        Py_CLEAR(d);
    return d;
}

static PyObject *corrected(const hl_analysis *A)
{
    if (!A->correct)
        Py_RETURN_NONE;
    PyObject *d = PyDict_New();
    if (d == NULL || dict_put(d, "subtracted_up_to", PyLong_FromLong(A->correct)) < 0 ||
        (A->cmap != NULL && dict_put(d, "map", field(A->cmap, A)) < 0) ||
        put_fields(d, &A->cfields, &A->cleading, A->have_cleading, A) < 0)
        Py_CLEAR(d);
    return d;
}

static PyObject *analysis_dict(const hl_analysis *A)
{
    PyObject *d = PyDict_New();
    if (d == NULL)
        return NULL;
    int bad = dict_put(d, "scheme", PyUnicode_FromString(A->scheme->name)) < 0 ||
              dict_put(d, "explicit", PyBool_FromLong(A->closed)) < 0 ||
              dict_put(d, "order_computed", PyLong_FromLong(A->n)) < 0 ||
              dict_put(d, "expansion", expansion(A)) < 0 ||
              dict_put(d, "map", A->closed ? field(A->map, A) : Py_NewRef(Py_None)) < 0 ||
              (A->map_omitted[0] &&
               dict_put(d, "map_omitted", PyUnicode_FromString(A->map_omitted)) < 0) ||
              put_fields(d, &A->fields, &A->leading, A->have_leading, A) < 0 ||
              dict_put(d, "K", A->have_K ? field(A->K, A) : Py_NewRef(Py_None)) < 0 ||
              dict_put(d, "K_coefficients", K_coefficients(A)) < 0 ||
              dict_put(d, "invariants", invariants(A)) < 0 ||
              dict_put(d, "modified", modified(A)) < 0 || dict_put(d, "time", time_part(A)) < 0 ||
              dict_put(d, "corrected", corrected(A)) < 0 ||
              dict_put(d, "numeric_zero_test",
                       PyBool_FromLong(hl_alg_ctx_numeric_used(hl_system_ctx(A->sys)))) < 0;
    if (bad)
        Py_CLEAR(d);
    return d;
}

/* ---- the call ----------------------------------------------------------------------- */

static int read_opts(hl_analysis_opts *o, int order, int correct, int invdeg)
{
    hl_analysis_opts_default(o);
    if (order < 2 || order > HL_ANALYSIS_MAX_ORDER) {
        PyErr_Format(PyExc_ValueError, "order must be in 2..%d, not %d", HL_ANALYSIS_MAX_ORDER,
                     order);
        return -1;
    }
    if (correct != 0 && (correct < 2 || correct > order)) {
        PyErr_Format(PyExc_ValueError, "correct must be 0 or in 2..order (%d), not %d", order,
                     correct);
        return -1;
    }
    if (invdeg < 0 || invdeg > 8) {
        PyErr_Format(PyExc_ValueError, "invariants must be in 0..8, not %d", invdeg);
        return -1;
    }
    o->order = order;
    o->correct = correct;
    o->invariants_degree = invdeg;
    return 0;
}

PyObject *System_errors(SystemObject *self, PyObject *args, PyObject *kw)
{
    static char *kwlist[] = {"scheme", "map", "equations", "order", "correct", "invariants", NULL};
    PyObject *so = Py_None, *mo = Py_None, *eo = Py_None;
    int order = 4, correct = 0, invdeg = 2;
    const char *name, *map, *eqs;
    hl_analysis_opts opts;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|OOOiii", kwlist, &so, &mo, &eo, &order, &correct,
                                     &invdeg) ||
        arg_text(so, "scheme", 1, &name) < 0 || arg_text(mo, "map", 1, &map) < 0 ||
        arg_text(eo, "equations", 1, &eqs) < 0 || read_opts(&opts, order, correct, invdeg) < 0)
        return NULL;
    if ((name != NULL) + (map != NULL) + (eqs != NULL) != 1)
        return PyErr_Format(PyExc_TypeError, "give one of scheme, map and equations");
    hl_error err;
    hl_error_clear(&err);
    hl_scheme *s = NULL;
    hl_analysis *A = NULL;
    system_lock(self);
    hl_status st;
    Py_BEGIN_ALLOW_THREADS
    st = make_scheme(&s, name, 0, map, eqs, self->sys, &err);
    if (st == HL_OK)
        st = hl_analysis_compute(&A, &opts, s, self->sys, &err);
    Py_END_ALLOW_THREADS
    PyObject *r = st == HL_OK ? analysis_dict(A) : raise_hl_error(&err, st);
    hl_analysis_free(A);
    hl_scheme_free(s);
    system_unlock(self);
    return r;
}
