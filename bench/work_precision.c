/* Work-precision benchmark, hamlie's half: final states of the Taylor
 * integrator (interpreted, compiled to machine code, and in Arb at --digits)
 * and of GSL's rk8pd, on four systems, for a list of tolerances and final
 * times.  It prints raw rows; bench/work_precision.py computes the errors
 * against the exact solutions and draws the figure, and
 * bench/work_precision.sh runs everything (with heyoka and Boost's rkf78).
 *
 * Rows (CSV, no header):
 *   method,system,T,tol,order,steps,ms,compile_ms,z0,z1[,z2,z3]
 * method: hamlie-interp, hamlie-native, hamlie-arb (tol = 10^-digits),
 * rk8pd, ref (Arb at ref digits: the reference where there is no closed
 * form).  ms: integration alone, CPU time, the best of reps runs (Arb: one run);
 * compile_ms: hl_tape_native's time (native only, else 0).  States: %.17g,
 * or digits + 8 digits for Arb.  steps: -1 where not known (rk8pd).
 *
 * Arguments, key=value, any order:
 *   reps=3  T=1e4,1e5  tols=1e-9,...,1e-16  sys=-1 (or 0..3)  digits=20,30
 *   ref=0 (digits of the Arb reference; 0: none)  methods=interp,native,rk8pd,arb
 *   (and terms: a row "terms,system,products,linear,calls,state" of the
 *   tape's cost terms, tape/cost_impl.h; sys=4..9: the zoo's tapes)
 *   order=0 (the Taylor order of hamlie in double; 0: its rule's.  With
 *   another, the step of hl_flow_rule_at: what a step costs against the
 *   order, for the cost model of src/tape/cost.c)
 * The vector fields come from the text of H by hl_tape_hamiltonian (the
 * path a user takes).  GSL is loaded with dlopen (libgsl.so): if it is
 * absent, rk8pd is skipped with a note on stderr. */
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "flow/flow_impl.h" /* hl_flow_new_order */
#include "tape/cost_impl.h" /* hl_tape_taylor_cost_terms */
#include "hamlie/expr.h"
#include "hamlie/flow.h"

#define MAXLIST 32
#define MAXN 6 /* state components, at most */

/* The few GSL declarations used, restated so that the bench builds without
 * GSL's headers (gsl_odeiv2.h; GSL_SUCCESS = 0). */
typedef struct gsl_odeiv2_system {
    int (*function)(double t, const double y[], double dydt[], void *params);
    int (*jacobian)(double t, const double y[], double *dfdy, double dfdt[], void *params);
    size_t dimension;
    void *params;
} gsl_odeiv2_system;
typedef struct gsl_odeiv2_driver gsl_odeiv2_driver;
typedef struct gsl_odeiv2_step_type gsl_odeiv2_step_type;

/* The process's CPU time, not the wall clock: on a machine shared with
 * other jobs a run of 100 ms is preempted many times, and wall-clock
 * figures taken at different minutes compared the load, not the methods. */
static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

/* ---- the systems --------------------------------------------------------- */

typedef struct system {
    const char *name, *H;
    int n;
    double z0[MAXN];
    int (*rhs)(double t, const double *z, double *f, void *arg);
} system_t;

static int osc_f(double t, const double *z, double *f, void *arg)
{
    (void)t, (void)arg;
    f[0] = z[1];
    f[1] = -z[0];
    return 0;
}
static int pen_f(double t, const double *z, double *f, void *arg)
{
    (void)t, (void)arg;
    f[0] = z[1];
    f[1] = -sin(z[0]);
    return 0;
}
static int hh_f(double t, const double *z, double *f, void *arg)
{
    (void)t, (void)arg;
    double x = z[0], y = z[1];
    f[0] = z[2];
    f[1] = z[3];
    f[2] = -x - 2 * x * y;
    f[3] = -y - x * x + y * y;
    return 0;
}
static int kep_f(double t, const double *z, double *f, void *arg)
{
    (void)t, (void)arg;
    double r2 = z[0] * z[0] + z[1] * z[1], r3 = r2 * sqrt(r2);
    f[0] = z[2];
    f[1] = z[3];
    f[2] = -z[0] / r3;
    f[3] = -z[1] / r3;
    return 0;
}

/* The four systems of the work-precision figure (sys=0..3, sys=-1: all
 * four), then tapes of the zoo (tests/zoo/zoo.py) with other mixes of
 * products, calls and state, for the cost of a step against the order
 * (bench/cost_fit.py; sys=4.., no exact solution, no rk8pd). */
#define NSYS_EXACT 4
static const system_t systems[] = {
    {"oscillator", "(q^2 + p^2)/2", 2, {1, 0}, osc_f},
    {"pendulum", "p^2/2 - cos(q)", 2, {1.3, 0}, pen_f},
    {"henon-heiles",
     "(px^2 + py^2)/2 + (x^2 + y^2)/2 + x^2*y - y^3/3",
     4,
     {0.1, -0.1, 0.05, 0.1},
     hh_f},
    {"kepler", "(px^2 + py^2)/2 - 1/sqrt(x^2 + y^2)", 4, {0.5, 0, 0, 1.7320508075688772}, kep_f},
    {"quartic", "p^2/2 + q^4/4", 2, {1, 0}, NULL},
    {"morse", "p^2/2 + (1 - exp(-q))^2", 2, {-0.5, 0}, NULL},
    {"double-pendulum",
     "(px^2 + 2*py^2 - 2*px*py*cos(x-y))/(2*(1+sin(x-y)^2)) - 2*cos(x) - cos(y)",
     4,
     {0.5, -0.5, 0, 0},
     NULL},
    {"toda-3",
     "(px^2+py^2+pz^2)/2 + exp(x-y) + exp(y-z) + exp(z-x) - 3",
     6,
     {0.5, 0, -0.5, 0.1, -0.2, 0.1},
     NULL},
    {"kepler-3d", "(px^2+py^2+pz^2)/2 - 1/sqrt(x^2+y^2+z^2)", 6, {1, 0, 0, 0, 0.8, 0.4}, NULL},
    {"fpu-beta-3",
     "(px^2+py^2+pz^2)/2 + (x^2 + (y-x)^2 + (z-y)^2 + z^2)/2"
     " + (x^4 + (y-x)^4 + (z-y)^4 + z^4)/4",
     6,
     {0.3, 0, -0.3, 0, 0.2, 0},
     NULL},
};
#define NSYS ((int)(sizeof systems / sizeof systems[0]))

/* NOTE: every method, the Arb runs too, starts from the doubles nearest the
 * initial values (1.3, 0.1, sqrt 3 are not doubles), and
 * bench/work_precision.py computes the exact solutions from those doubles:
 * no method is charged for rounding its initial state (in Kepler's problem
 * 1e-16 in py moves the phase by 5e-11 at t = 1e5). */

static hl_tape *tape_from_H(hl_pool *P, const system_t *S)
{
    /* q, p with one degree of freedom; x, y (z), px, py (pz) with more */
    const char *q1[] = {"q"}, *p1[] = {"p"}, *qs[] = {"x", "y", "z"}, *ps[] = {"px", "py", "pz"};
    const hl_expr *H;
    hl_tape *t = NULL;
    hl_error err;
    int dof = S->n / 2;
    if (hl_parse(&H, P, S->H, &err) != HL_OK ||
        hl_tape_hamiltonian(&t, P, H, dof, dof > 1 ? qs : q1, dof > 1 ? ps : p1, 0, NULL, NULL,
                            &err) != HL_OK) {
        fprintf(stderr, "work_precision: %s\n", err.msg);
        exit(1);
    }
    return t;
}

/* ---- rows ---------------------------------------------------------------- */

static void row_head(const char *method, const system_t *S, double T, double tol, int order,
                     long steps, double ms, double compile_ms)
{
    printf("%s,%s,%g,%g,%d,%ld,%.4f,%.2f", method, S->name, T, tol, order, steps, ms, compile_ms);
}

static void row_double(const char *method, const system_t *S, double T, double tol, int order,
                       long steps, double ms, double compile_ms, const double *z)
{
    row_head(method, S, T, tol, order, steps, ms, compile_ms);
    for (int i = 0; i < S->n; i++)
        printf(",%.17g", z[i]);
    printf("\n");
    fflush(stdout);
}

/* ---- hamlie in double ---------------------------------------------------- */

/* Best of reps runs to T; z: the final state.  Returns the time in ms, or
 * NAN (message on stderr) if the run fails. */
static int forced_order; /* order=P */

static double flow_best(hl_tape *tape, const system_t *S, double T, double tol, int reps, double *z,
                        long *steps, int *order)
{
    double best = INFINITY;
    for (int r = 0; r < reps; r++) {
        hl_flow *fl = NULL;
        hl_error err;
        if (hl_flow_new_order(&fl, tape, tol, tol, forced_order, &err) != HL_OK) {
            fprintf(stderr, "work_precision: %s\n", err.msg);
            return NAN;
        }
        memcpy(z, S->z0, sizeof S->z0);
        double t = 0, t0 = now();
        int st = hl_flow_evolve(fl, &t, T, z, &err);
        best = fmin(best, now() - t0);
        *steps = hl_flow_nsteps(fl);
        *order = hl_flow_order(fl);
        hl_flow_free(fl);
        if (st != HL_OK) {
            fprintf(stderr, "work_precision: %s: %s\n", S->name, err.msg);
            return NAN;
        }
    }
    return 1e3 * best;
}

/* Interpreted, then compiled (on a fresh tape each: a compiled tape stays
 * compiled). */
static void run_hamlie(hl_pool *P, const system_t *S, double T, double tol, int reps, int interp,
                       int native)
{
    double z[MAXN];
    long steps = 0;
    int order = 0;
    if (interp) {
        hl_tape *tape = tape_from_H(P, S);
        double ms = flow_best(tape, S, T, tol, reps, z, &steps, &order);
        if (!isnan(ms))
            row_double("hamlie-interp", S, T, tol, order, steps, ms, 0, z);
        hl_tape_free(tape);
    }
    if (native) {
        hl_tape *tape = tape_from_H(P, S);
        hl_flow *fl = NULL;
        hl_error err;
        if (hl_flow_new_order(&fl, tape, tol, tol, forced_order, &err) != HL_OK) {
            fprintf(stderr, "work_precision: %s\n", err.msg);
            hl_tape_free(tape);
            return;
        }
        order = hl_flow_order(fl);
        hl_flow_free(fl);
        double c0 = now();
        if (hl_tape_native(tape, order, &err) != HL_OK) {
            fprintf(stderr, "work_precision: no native code: %s\n", err.msg);
            hl_tape_free(tape);
            return;
        }
        double compile_ms = 1e3 * (now() - c0);
        double ms = flow_best(tape, S, T, tol, reps, z, &steps, &order);
        if (!isnan(ms))
            row_double("hamlie-native", S, T, tol, order, steps, ms, compile_ms, z);
        hl_tape_free(tape);
    }
}

/* The tape's terms of the cost of a Taylor step (tape/cost_impl.h):
 *   terms,system,products,linear,calls,state */
static void row_terms(hl_pool *P, const system_t *S)
{
    hl_tape *tape = tape_from_H(P, S);
    hl_taylor_cost_terms c;
    hl_tape_taylor_cost_terms(tape, &c);
    printf("terms,%s,%g,%g,%g,%g\n", S->name, c.products, c.linear, c.calls, c.state);
    hl_tape_free(tape);
}

/* ---- hamlie in Arb ------------------------------------------------------- */

/* One run at digits; method "hamlie-arb" or "ref". */
static void run_arb(hl_pool *P, const system_t *S, double T, double digits, const char *method)
{
    hl_tape *tape = tape_from_H(P, S);
    hl_flow_arb *fa = NULL;
    hl_error err;
    if (hl_flow_arb_new(&fa, tape, digits, &err) != HL_OK) {
        fprintf(stderr, "work_precision: %s\n", err.msg);
        hl_tape_free(tape);
        return;
    }
    arb_ptr z = _arb_vec_init(S->n);
    arb_t t, t1;
    arb_init(t);
    arb_init(t1);
    for (int i = 0; i < S->n; i++)
        arb_set_d(z + i, S->z0[i]);
    arb_set_d(t1, T);
    double t0 = now();
    int st = hl_flow_arb_evolve(fa, t, t1, z, &err);
    double ms = 1e3 * (now() - t0);
    if (st != HL_OK) {
        fprintf(stderr, "work_precision: arb %s: %s\n", S->name, err.msg);
    } else {
        row_head(method, S, T, pow(10, -digits), hl_flow_arb_order(fa), hl_flow_arb_nsteps(fa), ms,
                 0);
        for (int i = 0; i < S->n; i++) {
            char *s = arb_get_str(z + i, (slong)digits + 8, ARB_STR_NO_RADIUS);
            printf(",%s", s);
            flint_free(s);
        }
        printf("\n");
        fflush(stdout);
    }
    arb_clear(t);
    arb_clear(t1);
    _arb_vec_clear(z, S->n);
    hl_flow_arb_free(fa);
    hl_tape_free(tape);
}

/* ---- GSL rk8pd, through dlopen ------------------------------------------- */

static gsl_odeiv2_driver *(*p_alloc)(const gsl_odeiv2_system *, const gsl_odeiv2_step_type *,
                                     double, double, double);
static int (*p_apply)(gsl_odeiv2_driver *, double *, double, double *);
static void (*p_free)(gsl_odeiv2_driver *);
static const gsl_odeiv2_step_type *const *p_rk8pd;

static int load_gsl(void)
{
    void *cblas = dlopen("libgslcblas.so.0", RTLD_NOW | RTLD_GLOBAL);
    void *h = dlopen("libgsl.so.27", RTLD_NOW);
    if (h == NULL)
        h = dlopen("libgsl.so", RTLD_NOW);
    if (h == NULL || cblas == NULL)
        return 0;
    *(void **)&p_alloc = dlsym(h, "gsl_odeiv2_driver_alloc_y_new");
    *(void **)&p_apply = dlsym(h, "gsl_odeiv2_driver_apply");
    *(void **)&p_free = dlsym(h, "gsl_odeiv2_driver_free");
    *(void **)&p_rk8pd = dlsym(h, "gsl_odeiv2_step_rk8pd");
    return p_alloc && p_apply && p_free && p_rk8pd;
}

/* eps_abs = eps_rel = tol, as heyoka's and hamlie's one tolerance */
static void run_rk8pd(const system_t *S, double T, double tol, int reps)
{
    gsl_odeiv2_system gs = {S->rhs, NULL, (size_t)S->n, NULL};
    double best = INFINITY, z[MAXN];
    for (int r = 0; r < reps; r++) {
        gsl_odeiv2_driver *d = p_alloc(&gs, *p_rk8pd, 1e-3, tol, tol);
        memcpy(z, S->z0, sizeof z);
        double t = 0, t0 = now();
        int st = p_apply(d, &t, T, z);
        best = fmin(best, now() - t0);
        p_free(d);
        if (st != 0) {
            fprintf(stderr, "work_precision: rk8pd %s tol %g: status %d at t = %g\n", S->name, tol,
                    st, t);
            return;
        }
    }
    row_double("rk8pd", S, T, tol, 8, -1, 1e3 * best, 0, z);
}

/* ---- arguments ----------------------------------------------------------- */

static int parse_list(const char *s, double *v)
{
    int n = 0;
    for (char *end; *s && n < MAXLIST; s = *end ? end + 1 : end) {
        v[n++] = strtod(s, &end);
        if (end == s)
            return n - 1;
    }
    return n;
}

typedef struct opts {
    int reps, sys, nT, ntol, ndig;
    double T[MAXLIST], tol[MAXLIST], dig[MAXLIST], ref;
    char methods[128];
} opts;

static void parse_args(opts *o, int argc, char **argv)
{
    *o = (opts){.reps = 3, .sys = -1, .ref = 0};
    o->nT = parse_list("1e4,1e5", o->T);
    o->ntol = parse_list("1e-9,1e-10,1e-11,1e-12,1e-13,1e-14,1e-15,1e-16", o->tol);
    o->ndig = parse_list("20,30", o->dig);
    strcpy(o->methods, "interp,native,rk8pd,arb");
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = strchr(a, '=');
        if (v == NULL) {
            fprintf(stderr, "work_precision: expected key=value, got '%s'\n", a);
            exit(2);
        }
        v++;
        if (!strncmp(a, "reps=", 5))
            o->reps = atoi(v) > 0 ? atoi(v) : 1;
        else if (!strncmp(a, "T=", 2))
            o->nT = parse_list(v, o->T);
        else if (!strncmp(a, "tols=", 5))
            o->ntol = parse_list(v, o->tol);
        else if (!strncmp(a, "digits=", 7))
            o->ndig = parse_list(v, o->dig);
        else if (!strncmp(a, "sys=", 4))
            o->sys = atoi(v);
        else if (!strncmp(a, "ref=", 4))
            o->ref = atof(v);
        else if (!strncmp(a, "order=", 6))
            forced_order = atoi(v);
        else if (!strncmp(a, "methods=", 8))
            snprintf(o->methods, sizeof o->methods, "%s", v);
        else {
            fprintf(stderr, "work_precision: unknown option '%s'\n", a);
            exit(2);
        }
    }
}

static int wants(const opts *o, const char *m)
{
    return strstr(o->methods, m) != NULL;
}

int main(int argc, char **argv)
{
    opts o;
    parse_args(&o, argc, argv);
    int have_gsl = wants(&o, "rk8pd") && load_gsl();
    if (wants(&o, "rk8pd") && !have_gsl)
        fprintf(stderr, "work_precision: libgsl not found, rk8pd skipped\n");
    hl_pool *P = hl_pool_new();
    for (int s = 0; s < NSYS; s++) {
        if (o.sys >= 0 ? s != o.sys : s >= NSYS_EXACT)
            continue;
        const system_t *S = &systems[s];
        if (wants(&o, "terms"))
            row_terms(P, S);
        for (int iT = 0; iT < o.nT; iT++) {
            if (o.ref > 0)
                run_arb(P, S, o.T[iT], o.ref, "ref");
            for (int i = 0; i < o.ntol; i++) {
                run_hamlie(P, S, o.T[iT], o.tol[i], o.reps, wants(&o, "interp"),
                           wants(&o, "native"));
                if (have_gsl && S->rhs != NULL)
                    run_rk8pd(S, o.T[iT], o.tol[i], o.reps);
            }
            for (int i = 0; wants(&o, "arb") && i < o.ndig; i++)
                run_arb(P, S, o.T[iT], o.dig[i], "hamlie-arb");
        }
    }
    hl_pool_free(P);
    flint_cleanup();
    return 0;
}
