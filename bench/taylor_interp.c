/* Benchmark: the double Taylor interpreter alone, hl_tape_taylor_ode_d at
 * order 19 (the flow's order at tolerance 1e-15) on the vector fields of
 * bench/taylor_flow.c written by hand (1 pendulum, 2 Henon-Heiles,
 * 3 Kepler), so that builds whose flows take different step counts compare
 * per call.  Uses only the public API that the old interpreter (a4ae1ce,
 * issue 14's "before") has too, so the same file builds against both:
 *   cc -O2 bench/taylor_interp.c -I OLD/include OLD/build/libhamlie.a \
 *      -lflint-arb -lflint -lmpfr -lgmp -lm -ldl
 * Arguments: [rounds] [calls per round] [system 1..3 or 0 for all]
 * [libhamlie.so ...].  Prints per system: ns per call, the best round's (a
 * loaded machine only ever adds time), and a checksum of the coefficients
 * (equal across builds that compute the same bits).
 *
 * With shared libraries named, each is loaded on its own (RTLD_DEEPBIND:
 * its calls stay inside it) and the builds take turns round by round in
 * this one process, so a change of the machine's load or clock between
 * two process runs cannot favour one; the line then also gives the median
 * of the rounds and the build's name (bench/run-interp.sh --so). */
#define _GNU_SOURCE /* RTLD_DEEPBIND */
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "hamlie/expr.h"
#include "hamlie/tape.h"

#define ORDER 19
#define MAX_BUILDS 8

/* The public calls the bench makes, from this binary or from a loaded build. */
typedef struct api {
    const char *name;
    hl_pool *(*pool_new)(void);
    void (*pool_free)(hl_pool *);
    const hl_expr *(*num_si)(hl_pool *, long);
    const hl_expr *(*num_frac)(hl_pool *, long, unsigned long);
    const hl_expr *(*sym)(hl_pool *, const char *);
    const hl_expr *(*neg)(hl_pool *, const hl_expr *);
    const hl_expr *(*call)(hl_pool *, hl_fun, const hl_expr *);
    const hl_expr *(*add)(hl_pool *, const hl_expr *, const hl_expr *);
    const hl_expr *(*sub)(hl_pool *, const hl_expr *, const hl_expr *);
    const hl_expr *(*mul)(hl_pool *, const hl_expr *, const hl_expr *);
    const hl_expr *(*pow)(hl_pool *, const hl_expr *, const hl_expr *);
    hl_status (*tape_new)(hl_tape **, const hl_expr *const *, int, const char *const *, int,
                          hl_error *);
    hl_status (*taylor_ode_d)(double *, int, hl_tape *, hl_error *);
    void (*tape_free)(hl_tape *);
} api;

static api linked_api(void)
{
    return (api){"linked",     hl_pool_new,
                 hl_pool_free, hl_num_si,
                 hl_num_frac,  hl_sym,
                 hl_neg,       hl_call,
                 hl_add,       hl_sub,
                 hl_mul,       hl_pow,
                 hl_tape_new,  hl_tape_taylor_ode_d,
                 hl_tape_free};
}

static void *need(void *lib, const char *path, const char *sym)
{
    void *f = dlsym(lib, sym);
    if (f == NULL) {
        fprintf(stderr, "taylor_interp: %s has no %s\n", path, sym);
        exit(1);
    }
    return f;
}

/* A build loaded from its shared library; named by its file, or by the
 * folder that holds its build folder (OLD/build/libhamlie.so is "OLD"). */
static api loaded_api(const char *path)
{
    void *lib = dlopen(path, RTLD_NOW | RTLD_LOCAL | RTLD_DEEPBIND);
    if (lib == NULL) {
        fprintf(stderr, "taylor_interp: %s\n", dlerror());
        exit(1);
    }
    char *name = strdup(path), *slash = strrchr(name, '/');
    api a;
    a.name = slash != NULL ? slash + 1 : name;
    if (strncmp(a.name, "libhamlie.so", 12) == 0 && slash != NULL) {
        for (int cut = 0; cut < 2 && (slash = strrchr(name, '/')) != NULL; cut++)
            *slash = '\0';
        a.name = (slash = strrchr(name, '/')) != NULL ? slash + 1 : name;
    }
#define LOAD(field, sym) *(void **)&a.field = need(lib, path, sym)
    LOAD(pool_new, "hl_pool_new"), LOAD(pool_free, "hl_pool_free");
    LOAD(num_si, "hl_num_si"), LOAD(num_frac, "hl_num_frac"), LOAD(sym, "hl_sym");
    LOAD(neg, "hl_neg"), LOAD(call, "hl_call"), LOAD(add, "hl_add"), LOAD(sub, "hl_sub");
    LOAD(mul, "hl_mul"), LOAD(pow, "hl_pow"), LOAD(tape_new, "hl_tape_new");
    LOAD(taylor_ode_d, "hl_tape_taylor_ode_d"), LOAD(tape_free, "hl_tape_free");
#undef LOAD
    return a;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static hl_tape *make_tape(const api *A, hl_pool *P, int which, const double **z0, int *n)
{
    static const double zp[] = {1.3, 0}, zh[] = {0.1, -0.2, 0.3, 0.25}, zk[] = {0.5, 0, 0, 1.5};
    const hl_expr *two = A->num_si(P, 2);
    const hl_expr *x = A->sym(P, "x"), *y = A->sym(P, "y");
    const hl_expr *px = A->sym(P, "px"), *py = A->sym(P, "py");
    const char *n2[] = {"x", "px"}, *n4[] = {"x", "y", "px", "py"};
    const hl_expr *f[4];
    *n = 4;
    if (which == 1) {
        f[0] = px, f[1] = A->neg(P, A->call(P, HL_SIN, x)), *n = 2, *z0 = zp;
    } else if (which == 2) {
        f[0] = px, f[1] = py, *z0 = zh;
        f[2] = A->sub(P, A->neg(P, x), A->mul(P, A->mul(P, two, x), y));
        f[3] = A->add(P, A->sub(P, A->neg(P, y), A->pow(P, x, two)), A->pow(P, y, two));
    } else {
        const hl_expr *r3i =
            A->pow(P, A->add(P, A->pow(P, x, two), A->pow(P, y, two)), A->num_frac(P, -3, 2));
        f[0] = px, f[1] = py, *z0 = zk;
        f[2] = A->neg(P, A->mul(P, x, r3i));
        f[3] = A->neg(P, A->mul(P, y, r3i));
    }
    hl_tape *t = NULL;
    hl_error err;
    if (A->tape_new(&t, f, *n, *n == 2 ? n2 : n4, *n, &err) != HL_OK) {
        fprintf(stderr, "taylor_interp: %s\n", err.msg);
        exit(1);
    }
    return t;
}

/* a sum that changes with any bit of any coefficient */
static unsigned long long checksum(const double *z, int m)
{
    unsigned long long h = 1469598103934665603ull;
    for (int i = 0; i < m; i++) {
        unsigned long long b;
        memcpy(&b, &z[i], sizeof b);
        h = (h ^ b) * 1099511628211ull;
    }
    return h;
}

/* One build's state for one system. */
typedef struct run {
    const api *A;
    hl_pool *P;
    hl_tape *t;
    int n;
    double z[4 * (ORDER + 1)];
    double *ns; /* every round's ns per call */
} run;

static void run_init(run *r, const api *A, int which, int rounds)
{
    const double *z0;
    memset(r, 0, sizeof *r);
    r->A = A;
    r->P = A->pool_new();
    r->t = make_tape(A, r->P, which, &z0, &r->n);
    for (int i = 0; i < r->n; i++)
        r->z[i * (ORDER + 1)] = z0[i];
    r->ns = calloc((size_t)rounds, sizeof *r->ns);
}

static double run_round(run *r, long calls)
{
    hl_error err;
    double t0 = now();
    for (long c = 0; c < calls; c++)
        r->A->taylor_ode_d(r->z, ORDER, r->t, &err);
    return 1e9 * (now() - t0) / (double)calls;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* The builds take turns, round by round. */
static void bench_system(const api *builds, int nb, int which, int rounds, long calls)
{
    static const char *const names[] = {"", "pendulum", "henon-heiles", "kepler"};
    run r[MAX_BUILDS];
    for (int b = 0; b < nb; b++)
        run_init(&r[b], &builds[b], which, rounds);
    for (int i = 0; i < rounds; i++)
        for (int b = 0; b < nb; b++)
            r[b].ns[i] = run_round(&r[b], calls);
    for (int b = 0; b < nb; b++) {
        qsort(r[b].ns, (size_t)rounds, sizeof *r[b].ns, by_value);
        unsigned long long h = checksum(r[b].z, r[b].n * (ORDER + 1));
        if (nb == 1 && strcmp(builds[b].name, "linked") == 0)
            printf("%-13s %8.1f ns/call  checksum %016llx\n", names[which], r[b].ns[0], h);
        else
            printf("%-13s %-16s min %8.1f  median %8.1f ns/call  checksum %016llx\n", names[which],
                   builds[b].name, r[b].ns[0], r[b].ns[rounds / 2], h);
        r[b].A->tape_free(r[b].t);
        r[b].A->pool_free(r[b].P);
        free(r[b].ns);
    }
}

int main(int argc, char **argv)
{
    int rounds = argc > 1 ? atoi(argv[1]) : 5;
    long calls = argc > 2 ? atol(argv[2]) : 20000;
    int only = argc > 3 ? atoi(argv[3]) : 0;
    api builds[MAX_BUILDS];
    int nb = 0;
    for (int i = 4; i < argc && nb < MAX_BUILDS; i++)
        builds[nb++] = loaded_api(argv[i]);
    if (nb == 0)
        builds[nb++] = linked_api();
    if (rounds < 1)
        rounds = 1;
    for (int s = 1; s <= 3; s++)
        if (only == 0 || only == s)
            bench_system(builds, nb, s, rounds, calls);
    return 0;
}
