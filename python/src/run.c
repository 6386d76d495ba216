/* _hamlie.System.run: a trajectory (run.h) into NumPy arrays that the row
 * callback fills directly, with the GIL released for the whole run; the
 * adaptive run in Arb (digits=) returns its values as decimal strings for
 * mpmath.  The choice of runner is `hamlie run`'s: "lie" with tol, digits
 * or no dt is the adaptive Taylor integrator; "exact" beyond a quadratic H
 * is the exact flow of exact.h; anything else a scheme's stepper. */
#define NO_IMPORT_ARRAY /* module.c imports the NumPy API */
#include "binding.h"

#include <math.h>
#include <numpy/arrayobject.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hamlie/exact.h"
#include "hamlie/run.h"
#include "hamlie/scheme.h"

typedef struct run_args {
    const char *scheme, *map, *eqs, *init, *T_text;
    const char **observe;
    int nobs, order, reference;
    double dt, t, tol, ref_tol, digits;
    int have_dt, have_tol, have_digits;
    long every;
} run_args;

static int adaptive(const run_args *a)
{
    return a->scheme != NULL && strcmp(a->scheme, "lie") == 0 &&
           (a->have_tol || a->have_digits || !a->have_dt);
}

/* ---- the rows, into arrays (no GIL needed: nothing else sees them yet) ---- */

typedef struct sink {
    long cap, rows;
    int n2, nobs, overflow;
    double *t, *z, *H, *sigma, *obs;
} sink;

static int sink_row(const hl_run_row *row, void *arg)
{
    sink *s = arg;
    if (s->rows >= s->cap) { /* cannot happen when cap is rows_for's count */
        s->overflow = 1;
        return HL_ELIMIT;
    }
    long k = s->rows++;
    s->t[k] = row->t;
    memcpy(s->z + k * s->n2, row->z, (size_t)s->n2 * sizeof(double));
    s->H[k] = row->H;
    s->sigma[k] = row->sigma;
    if (s->nobs > 0)
        memcpy(s->obs + k * s->nobs, row->obs, (size_t)s->nobs * sizeof(double));
    return 0;
}

/* The rows the runner delivers for n steps (run.h: k % every == 0, and the
 * last step). */
static long rows_for(long n, long every)
{
    return n / every + 1 + (n % every != 0);
}

static PyObject *new_array(int nd, long rows, int cols, double **data)
{
    npy_intp dims[2] = {rows, cols};
    PyObject *a = PyArray_SimpleNew(nd, dims, NPY_DOUBLE);
    *data = a != NULL ? (double *)PyArray_DATA((PyArrayObject *)a) : NULL;
    return a;
}

/* The first `rows` rows of a (a view) in place of a. */
static int trim(PyObject **a, long rows)
{
    PyObject *v = PySequence_GetSlice(*a, 0, rows);
    Py_SETREF(*a, v);
    return v != NULL ? 0 : -1;
}

/* ---- the summary -------------------------------------------------------------- */

static PyObject *summary(const hl_run_stats *s, double wall, int fixed, hl_run *run, int n2)
{
    PyObject *state = PyList_New(n2);
    const double *z = hl_run_state(run);
    for (int i = 0; state != NULL && i < n2; i++)
        PyList_SET_ITEM(state, i, PyFloat_FromDouble(z[i]));
    if (state == NULL)
        return NULL;
    return Py_BuildValue("{slslslsdsdsdsdsdsdsdslsOsdsNss}", "steps", s->steps, "nsteps", s->nsteps,
                         "rows", s->rows, "t", s->t, "H0", s->H0, "H", s->H, "max_dH", s->max_dH,
                         "sigma", s->sigma, "max_error", s->max_err, "final_error", s->err_final,
                         "ref_steps", s->ref_steps, "failed", s->failed ? Py_True : Py_False,
                         "wall_time_s", wall, "final_state", state, "integrator",
                         fixed ? "fixed-step" : "adaptive-taylor");
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- building the runner (GIL released) --------------------------------------- */

typedef struct runner {
    hl_scheme *scheme;
    hl_exact_flow *exact;
    hl_run *run;
} runner;

static void runner_free(runner *r)
{
    hl_run_free(r->run);
    hl_exact_flow_free(r->exact);
    hl_scheme_free(r->scheme);
}

static hl_status build(runner *r, const run_args *a, hl_system *sys, hl_error *err)
{
    hl_status st = HL_OK;
    if (a->scheme != NULL && strcmp(a->scheme, "exact") == 0 &&
        !hl_scheme_linear_flow_applies(sys)) {
        if ((st = hl_exact_flow_new(&r->exact, sys, err)) == HL_OK)
            st = hl_run_new_stepper(&r->run, sys, hl_exact_flow_step, r->exact, err);
    } else if (!adaptive(a))
        st = make_scheme(&r->scheme, a->scheme, a->order, a->map, a->eqs, sys, err);
    if (st == HL_OK && r->run == NULL)
        st = hl_run_new(&r->run, sys, r->scheme, err);
    for (int i = 0; st == HL_OK && i < a->nobs; i++)
        if ((st = hl_run_observe(r->run, a->observe[i], err)) != HL_OK)
            hl_error_prefix(err, "in observer %d", i + 1);
    if (st == HL_OK) {
        hl_run_set_reference(r->run, a->reference, a->ref_tol);
        hl_run_set_jit(r->run, 1);
        hl_run_set_progress(r->run, check_signals_progress, NULL);
    }
    return st;
}

static hl_status prefix_init(hl_status st, hl_error *err)
{
    if (st != HL_OK)
        hl_error_prefix(err, "in init");
    return st;
}

/* ---- double runs ----------------------------------------------------------------- */

static PyObject *run_double(hl_system *sys, const run_args *a, runner *r, long n, hl_error *err)
{
    int n2 = 2 * hl_system_ndof(sys), ad = adaptive(a);
    double z0[2 * 64];
    sink s = {rows_for(n, a->every), 0, n2, a->nobs, 0, NULL, NULL, NULL, NULL, NULL};
    PyObject *t = new_array(1, s.cap, 1, &s.t), *z = new_array(2, s.cap, n2, &s.z),
             *H = new_array(1, s.cap, 1, &s.H), *sg = new_array(1, s.cap, 1, &s.sigma),
             *obs = new_array(2, s.cap, a->nobs, &s.obs), *res = NULL;
    hl_run_stats stats;
    memset(&stats, 0, sizeof stats);
    hl_status st = HL_OK;
    double wall = 0;
    if (t == NULL || z == NULL || H == NULL || sg == NULL || obs == NULL)
        goto done;
    Py_BEGIN_ALLOW_THREADS
    st = prefix_init(hl_run_init_values(z0, sys, a->init, err), err);
    if (st == HL_OK)
        st = prefix_init(hl_run_check_start(r->run, z0, err), err);
    double w0 = now();
    if (st == HL_OK)
        st = ad ? hl_run_adaptive(r->run, z0, a->tol, a->dt, a->t, a->every, sink_row, &s, &stats,
                                  err)
                : hl_run_fixed(r->run, z0, a->dt, a->t, a->every, sink_row, &s, &stats, err);
    wall = now() - w0;
    Py_END_ALLOW_THREADS
    if (s.overflow) {
        PyErr_Format(PyExc_RuntimeError, "the runner delivered more than the %ld rows expected",
                     s.cap);
        goto done;
    }
    if (st != HL_OK) {
        raise_hl_error(err, st);
        goto done;
    }
    if (trim(&t, s.rows) < 0 || trim(&z, s.rows) < 0 || trim(&H, s.rows) < 0 ||
        trim(&sg, s.rows) < 0 || trim(&obs, s.rows) < 0)
        goto done;
    res = Py_BuildValue("{sOsOsOsOsOsN}", "t", t, "z", z, "H", H, "sigma", sg, "observers", obs,
                        "summary", summary(&stats, wall, !ad, r->run, n2));
done:
    Py_XDECREF(t), Py_XDECREF(z), Py_XDECREF(H), Py_XDECREF(sg), Py_XDECREF(obs);
    return res;
}

/* ---- Arb runs: rows as decimal strings -------------------------------------------- */

typedef struct arb_sink {
    long ndig, rows, cap;
    int width; /* t, 2N values, H, observers */
    int n2, nobs;
    char **s; /* rows * width strings (flint-allocated) */
    int full;
} arb_sink;

static int arb_row(const hl_run_row_arb *row, void *arg)
{
    arb_sink *as = arg;
    if (as->rows >= as->cap) {
        long cap = as->cap ? 2 * as->cap : 64;
        char **s = realloc(as->s, (size_t)cap * (size_t)as->width * sizeof *s);
        if (s == NULL)
            return HL_ENOMEM;
        as->s = s, as->cap = cap;
    }
    char **out = as->s + as->rows * as->width;
    out[0] = arb_get_str(row->t, as->ndig, ARB_STR_NO_RADIUS);
    for (int i = 0; i < as->n2; i++)
        out[1 + i] = arb_get_str(row->z + i, as->ndig, ARB_STR_NO_RADIUS);
    out[1 + as->n2] = arb_get_str(row->H, as->ndig, ARB_STR_NO_RADIUS);
    for (int i = 0; i < as->nobs; i++)
        out[2 + as->n2 + i] = arb_get_str(row->obs + i, as->ndig, ARB_STR_NO_RADIUS);
    as->rows++;
    return 0;
}

static PyObject *arb_rows(const arb_sink *as)
{
    PyObject *rows = PyList_New(as->rows);
    for (long k = 0; rows != NULL && k < as->rows; k++) {
        PyObject *row = PyList_New(as->width);
        for (int i = 0; row != NULL && i < as->width; i++) {
            PyObject *v = PyUnicode_FromString(as->s[k * as->width + i]);
            if (v == NULL)
                Py_CLEAR(row);
            else
                PyList_SET_ITEM(row, i, v);
        }
        if (row == NULL)
            Py_CLEAR(rows);
        else
            PyList_SET_ITEM(rows, k, row);
    }
    return rows;
}

static PyObject *run_arb(hl_system *sys, const run_args *a, runner *r, long n, hl_error *err)
{
    int n2 = 2 * hl_system_ndof(sys);
    arb_sink as = {(long)ceil(a->digits), 0, 0, 2 + n2 + a->nobs, n2, a->nobs, NULL, 0};
    slong prec = hl_run_arb_prec(a->digits);
    arb_ptr z0 = _arb_vec_init(n2);
    hl_run_stats stats;
    memset(&stats, 0, sizeof stats);
    hl_status st;
    double wall;
    Py_BEGIN_ALLOW_THREADS
    st = prefix_init(hl_run_init_values_arb(z0, sys, a->init, prec, err), err);
    if (st == HL_OK)
        st = prefix_init(hl_run_check_start_arb(r->run, z0, prec, err), err);
    double w0 = now();
    if (st == HL_OK)
        st = hl_run_adaptive_arb(r->run, z0, a->digits, a->T_text, n, a->every, arb_row, &as,
                                 &stats, err);
    wall = now() - w0;
    Py_END_ALLOW_THREADS
    PyObject *res = NULL;
    if (st != HL_OK)
        raise_hl_error(err, st);
    else
        res = Py_BuildValue("{sNsN}", "rows_text", arb_rows(&as), "summary",
                            Py_BuildValue("{slslsdsdsdslsd}", "steps", stats.steps, "rows",
                                          stats.rows, "t", stats.t, "H0", stats.H0, "max_dH",
                                          stats.max_dH, "taylor_steps", stats.ref_steps,
                                          "wall_time_s", wall));
    for (long i = 0; i < as.rows * as.width; i++)
        flint_free(as.s[i]);
    free(as.s);
    _arb_vec_clear(z0, n2);
    return res;
}

/* ---- arguments ------------------------------------------------------------------- */

static int number(PyObject *o, const char *what, double *v, int *have)
{
    if (o == Py_None)
        return 0;
    if (PyBool_Check(o) || !PyNumber_Check(o) || PyUnicode_Check(o)) {
        PyErr_Format(PyExc_TypeError, "%s must be a number, not %.80s", what, Py_TYPE(o)->tp_name);
        return -1;
    }
    *v = PyFloat_AsDouble(o);
    if (*v == -1.0 && PyErr_Occurred())
        return -1;
    if (!isfinite(*v)) {
        PyErr_Format(PyExc_ValueError, "%s must be finite, not %R", what, o);
        return -1;
    }
    if (have != NULL)
        *have = 1;
    return 0;
}

static int check_args(run_args *a, hl_system *sys)
{
    if ((a->scheme != NULL) + (a->map != NULL) + (a->eqs != NULL) != 1) {
        PyErr_SetString(PyExc_TypeError, "give one of scheme, map and equations");
        return -1;
    }
    if (a->have_dt && a->dt <= 0) {
        PyErr_Format(PyExc_ValueError, "dt must be positive, not %R", PyFloat_FromDouble(a->dt));
        return -1;
    }
    if (a->t < 0 || (a->have_tol && a->tol <= 0) || a->ref_tol <= 0 || a->every < 1 ||
        (a->have_digits && (a->digits < 1 || a->digits > 100000))) {
        PyErr_SetString(PyExc_ValueError, "need t >= 0, tol > 0, ref_tol > 0, every >= 1 and "
                                          "digits in 1..100000");
        return -1;
    }
    if ((a->have_tol || a->have_digits) && !adaptive(a)) {
        PyErr_SetString(PyExc_ValueError, "tol and digits are for the adaptive integrator: "
                                          "scheme='lie'");
        return -1;
    }
    if (hl_system_ndof(sys) > 64) {
        PyErr_SetString(PyExc_ValueError, "runs take at most 64 degrees of freedom");
        return -1;
    }
    if (!a->have_dt)
        a->dt = a->t > 0 ? a->t / 1000 : 1;
    if (!a->have_tol)
        a->tol = 1e-15;
    return 0;
}

static int parse_args(run_args *a, PyObject *args, PyObject *kw, PyObject **obs_seq)
{
    static char *kwlist[] = {"scheme",  "map",       "equations", "init",   "t",
                             "dt",      "order",     "every",     "tol",    "digits",
                             "observe", "reference", "ref_tol",   "t_text", NULL};
    PyObject *so = Py_None, *mo = Py_None, *eo = Py_None, *io = NULL, *to = NULL, *dto = Py_None,
             *tolo = Py_None, *digo = Py_None, *obso = Py_None, *rto = Py_None, *tto = Py_None;
    memset(a, 0, sizeof *a);
    a->order = 4, a->every = 1, a->reference = 1, a->ref_tol = 1e-15;
    if (!PyArg_ParseTupleAndKeywords(args, kw, "|OOOOOOilOOOpOO", kwlist, &so, &mo, &eo, &io, &to,
                                     &dto, &a->order, &a->every, &tolo, &digo, &obso, &a->reference,
                                     &rto, &tto))
        return -1;
    if (io == NULL || to == NULL) {
        PyErr_SetString(PyExc_TypeError, "run needs init and t");
        return -1;
    }
    if (arg_text(so, "scheme", 1, &a->scheme) < 0 || arg_text(mo, "map", 1, &a->map) < 0 ||
        arg_text(eo, "equations", 1, &a->eqs) < 0 || arg_text(io, "init", 0, &a->init) < 0 ||
        arg_text(tto, "t_text", 1, &a->T_text) < 0 || number(to, "t", &a->t, NULL) < 0 ||
        number(dto, "dt", &a->dt, &a->have_dt) < 0 ||
        number(tolo, "tol", &a->tol, &a->have_tol) < 0 ||
        number(digo, "digits", &a->digits, &a->have_digits) < 0 ||
        number(rto, "ref_tol", &a->ref_tol, NULL) < 0)
        return -1;
    if (obso != Py_None) {
        if ((*obs_seq = PySequence_Fast(obso, "observe must be a list of formulas")) == NULL)
            return -1;
        a->nobs = (int)PySequence_Fast_GET_SIZE(*obs_seq);
        if ((a->observe = calloc((size_t)a->nobs + 1, sizeof *a->observe)) == NULL) {
            PyErr_NoMemory();
            return -1;
        }
        for (int i = 0; i < a->nobs; i++)
            if (arg_text(PySequence_Fast_GET_ITEM(*obs_seq, i), "an observer", 0, &a->observe[i]) <
                0)
                return -1;
    }
    return 0;
}

PyObject *System_run(SystemObject *self, PyObject *args, PyObject *kw)
{
    run_args a;
    PyObject *obs_seq = NULL, *res = NULL;
    if (parse_args(&a, args, kw, &obs_seq) < 0 || check_args(&a, self->sys) < 0) {
        free(a.observe);
        Py_XDECREF(obs_seq);
        return NULL;
    }
    hl_error err;
    hl_error_clear(&err);
    runner r = {NULL, NULL, NULL};
    long n = 0;
    hl_status st;
    system_lock(self);
    Py_BEGIN_ALLOW_THREADS
    st = hl_run_nsteps(&n, a.dt, a.t, &err);
    if (st == HL_OK)
        st = build(&r, &a, self->sys, &err);
    Py_END_ALLOW_THREADS
    if (st != HL_OK)
        raise_hl_error(&err, st);
    else
        res = a.have_digits ? run_arb(self->sys, &a, &r, n, &err)
                            : run_double(self->sys, &a, &r, n, &err);
    runner_free(&r);
    system_unlock(self);
    free(a.observe);
    Py_XDECREF(obs_seq);
    return res;
}
