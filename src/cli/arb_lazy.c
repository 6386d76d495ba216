/* Arb (libflint-arb) loaded on first use, inside hamlie-cli.so only.
 *
 * Most commands never compute a ball: `lie`, `bracket`, `errors` ... work
 * in exact algebra and doubles.  Linked, Debian's libflint-arb (built
 * BIND_NOW) cost every command its loading and ~1,500 forced symbol
 * lookups, about 1.8 ms of a 12 ms `hamlie lie` (issue 17).  So the module
 * is linked without it (cmake/launcher.cmake), and this file defines each
 * Arb function the module calls as a forwarder: the first call opens the
 * library (once per process, safe from several threads) and fills a table;
 * every call then jumps through the table (a predictable branch and a tail
 * jump, a nanosecond against the tens an Arb operation takes).
 *
 * The forwarders are hidden: the module is opened RTLD_GLOBAL, and Arb's
 * own calls between its functions must not come back through them.  The
 * library, its tests and the benchmarks link Arb as before.
 *
 * A call to an Arb function not listed here fails the module's link
 * ("undefined reference to arb_foo", -z defs): add one line to
 * ARB_FUNCTIONS, in the order of its declaration in arb.h; the compiler
 * checks the prototype against the header's. */
#include <dlfcn.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>

#include <arb.h>
#include <arb_mat.h>

#include "base/lib.h"

/* V(name, params, args) returns void, R(type, name, params, args) a value. */
#define ARB_FUNCTIONS(V, R)                                                                        \
    V(_arb_vec_clear, (arb_ptr v, slong n), (v, n))                                                \
    R(arb_ptr, _arb_vec_init, (slong n), (n))                                                      \
    V(_arf_demote, (arf_t x), (x))                                                                 \
    V(arb_abs, (arb_t y, const arb_t x), (y, x))                                                   \
    V(arb_acos, (arb_t z, const arb_t x, slong prec), (z, x, prec))                                \
    V(arb_add, (arb_t z, const arb_t x, const arb_t y, slong prec), (z, x, y, prec))               \
    V(arb_addmul, (arb_t z, const arb_t x, const arb_t y, slong prec), (z, x, y, prec))            \
    V(arb_addmul_si, (arb_t z, const arb_t x, slong y, slong prec), (z, x, y, prec))               \
    V(arb_asin, (arb_t z, const arb_t x, slong prec), (z, x, prec))                                \
    V(arb_asinh, (arb_t z, const arb_t x, slong prec), (z, x, prec))                               \
    V(arb_atan, (arb_t z, const arb_t x, slong prec), (z, x, prec))                                \
    V(arb_atan2, (arb_t z, const arb_t b, const arb_t a, slong prec), (z, b, a, prec))             \
    V(arb_clear, (arb_t x), (x))                                                                   \
    V(arb_const_pi, (arb_t z, slong prec), (z, prec))                                              \
    R(int, arb_contains_zero, (const arb_t x), (x))                                                \
    V(arb_cos, (arb_t c, const arb_t x, slong prec), (c, x, prec))                                 \
    V(arb_cosh, (arb_t z, const arb_t x, slong prec), (z, x, prec))                                \
    V(arb_div, (arb_t z, const arb_t x, const arb_t y, slong prec), (z, x, y, prec))               \
    V(arb_div_si, (arb_t z, const arb_t x, slong y, slong prec), (z, x, y, prec))                  \
    V(arb_div_ui, (arb_t z, const arb_t x, ulong y, slong prec), (z, x, y, prec))                  \
    V(arb_dot,                                                                                     \
      (arb_t res, const arb_t initial, int subtract, arb_srcptr x, slong xstep, arb_srcptr y,      \
       slong ystep, slong len, slong prec),                                                        \
      (res, initial, subtract, x, xstep, y, ystep, len, prec))                                     \
    V(arb_exp, (arb_t z, const arb_t x, slong prec), (z, x, prec))                                 \
    V(arb_fmpz_div_fmpz, (arb_t z, const fmpz_t x, const fmpz_t y, slong prec), (z, x, y, prec))   \
    R(char *, arb_get_str, (const arb_t x, slong n, ulong flags), (x, n, flags))                   \
    R(int, arb_is_finite, (const arb_t x), (x))                                                    \
    R(int, arb_is_negative, (const arb_t x), (x))                                                  \
    R(int, arb_is_positive, (const arb_t x), (x))                                                  \
    V(arb_log, (arb_t z, const arb_t x, slong prec), (z, x, prec))                                 \
    V(arb_mat_clear, (arb_mat_t mat), (mat))                                                       \
    V(arb_mat_exp, (arb_mat_t B, const arb_mat_t A, slong prec), (B, A, prec))                     \
    V(arb_mat_init, (arb_mat_t mat, slong r, slong c), (mat, r, c))                                \
    V(arb_mul, (arb_t z, const arb_t x, const arb_t y, slong prec), (z, x, y, prec))               \
    V(arb_mul_2exp_si, (arb_t y, const arb_t x, slong e), (y, x, e))                               \
    V(arb_mul_si, (arb_t z, const arb_t x, slong y, slong prec), (z, x, y, prec))                  \
    V(arb_neg, (arb_t y, const arb_t x), (y, x))                                                   \
    V(arb_one, (arb_t f), (f))                                                                     \
    V(arb_pow, (arb_t z, const arb_t x, const arb_t y, slong prec), (z, x, y, prec))               \
    V(arb_pow_ui, (arb_t y, const arb_t b, ulong e, slong prec), (y, b, e, prec))                  \
    V(arb_root_ui, (arb_t z, const arb_t x, ulong k, slong prec), (z, x, k, prec))                 \
    V(arb_set, (arb_t x, const arb_t y), (x, y))                                                   \
    V(arb_set_d, (arb_t x, double y), (x, y))                                                      \
    V(arb_set_fmpz, (arb_t x, const fmpz_t y), (x, y))                                             \
    V(arb_set_si, (arb_t x, slong y), (x, y))                                                      \
    R(int, arb_set_str, (arb_t res, const char *inp, slong prec), (res, inp, prec))                \
    V(arb_set_ui, (arb_t x, ulong y), (x, y))                                                      \
    V(arb_sin, (arb_t s, const arb_t x, slong prec), (s, x, prec))                                 \
    V(arb_sinh, (arb_t z, const arb_t x, slong prec), (z, x, prec))                                \
    V(arb_sqrt, (arb_t z, const arb_t x, slong prec), (z, x, prec))                                \
    V(arb_sub, (arb_t z, const arb_t x, const arb_t y, slong prec), (z, x, y, prec))               \
    V(arb_submul, (arb_t z, const arb_t x, const arb_t y, slong prec), (z, x, y, prec))            \
    V(arb_tan, (arb_t y, const arb_t x, slong prec), (y, x, prec))                                 \
    V(arb_tanh, (arb_t y, const arb_t x, slong prec), (y, x, prec))                                \
    V(arb_zero, (arb_t x), (x))                                                                    \
    R(int, arf_cmp, (const arf_t x, const arf_t y), (x, y))                                        \
    R(int, arf_cmpabs, (const arf_t x, const arf_t y), (x, y))                                     \
    R(int, arf_equal, (const arf_t x, const arf_t y), (x, y))                                      \
    V(arf_floor, (arf_t z, const arf_t x), (z, x))                                                 \
    R(double, arf_get_d, (const arf_t x, arf_rnd_t rnd), (x, rnd))                                 \
    R(int, mag_cmp_2exp_si, (const mag_t x, slong e), (x, e))

#define VOID_FIELD(name, params, args) void(*name) params;
#define VALUE_FIELD(type, name, params, args) type(*name) params;
static struct {
    ARB_FUNCTIONS(VOID_FIELD, VALUE_FIELD)
} arb_fn;

static pthread_once_t load_once = PTHREAD_ONCE_INIT;
static atomic_int loaded; /* set (release) once arb_fn is complete */

/* The soname the module would have been linked with, and the file CMake
 * found (for a library off the loader's path). */
#ifndef HAMLIE_ARB_SONAME
#define HAMLIE_ARB_SONAME "libflint-arb.so.2"
#endif
#ifndef HAMLIE_ARB_PATH
#define HAMLIE_ARB_PATH NULL
#endif

/* Nothing can report an error from inside arb_add: a missing Arb ends the
 * process with the reason and what to install (status 2, as for an
 * unusable set-up). */
static _Noreturn void load_failed(const char *why, const char *name)
{
    fprintf(stderr,
            "hamlie: error: %s%s: this command computes with Arb; install "
            "libflint-arb2 (Debian) or set HAMLIE_ARB_LIB\n",
            why, name);
    exit(2);
}

static void load(void)
{
    const char *name;
    void *lib = hl_lib_open("HAMLIE_ARB_LIB", HAMLIE_ARB_SONAME, HAMLIE_ARB_PATH, &name);
    if (lib == NULL)
        load_failed("cannot load ", name);
#define RESOLVE(name_)                                                                             \
    *(void **)&arb_fn.name_ = dlsym(lib, #name_);                                                  \
    if (arb_fn.name_ == NULL)                                                                      \
        load_failed("no " #name_ " in ", name);
#define RESOLVE_VOID(name_, params, args) RESOLVE(name_)
#define RESOLVE_VALUE(type, name_, params, args) RESOLVE(name_)
    ARB_FUNCTIONS(RESOLVE_VOID, RESOLVE_VALUE)
    atomic_store_explicit(&loaded, 1, memory_order_release);
}

static inline void ensure_loaded(void)
{
    if (!atomic_load_explicit(&loaded, memory_order_acquire))
        pthread_once(&load_once, load);
}

#define HIDDEN __attribute__((visibility("hidden")))
#define FORWARD_VOID(name, params, args)                                                           \
    HIDDEN void name params                                                                        \
    {                                                                                              \
        ensure_loaded();                                                                           \
        arb_fn.name args;                                                                          \
    }
#define FORWARD_VALUE(type, name, params, args)                                                    \
    HIDDEN type name params                                                                        \
    {                                                                                              \
        ensure_loaded();                                                                           \
        return arb_fn.name args;                                                                   \
    }
ARB_FUNCTIONS(FORWARD_VOID, FORWARD_VALUE)
