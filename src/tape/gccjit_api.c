/* libgccjit loaded on first use: dlopen and the table of gccjit_api.h
 * filled once per process.  Linking libgccjit made every command pay for
 * it (some 12 ms of loading and relocating GCC before main), while only
 * long runs compile.  When it cannot be loaded the compilers report
 * HL_EUNSUP with the reason and the interpreter runs, as it always did
 * when compiling failed. */
#define HL_GCCJIT_API_IMPL /* the real names here, not the table's macros */
#include <dlfcn.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/lib.h"
#include "hamlie/tape.h"
#include "tape/gccjit_api.h"

#ifdef HAMLIE_HAVE_GCCJIT

hl_gccjit_api hl_gccjit;

#define DEFAULT_LIB "libgccjit.so.0"

static pthread_once_t load_once = PTHREAD_ONCE_INIT;
static atomic_int load_failed; /* set once, under load_once; read by anyone */
static char load_why[400];     /* the reason, when load_failed */

/* Every function of the table, or the first one missing (NULL if none). */
static const char *resolve_all(void *lib)
{
    const char *missing = NULL;
#define HL_GCCJIT_RESOLVE(name)                                                                    \
    hl_gccjit.name = (__typeof__(hl_gccjit.name))dlsym(lib, #name);                                \
    if (hl_gccjit.name == NULL && missing == NULL)                                                 \
        missing = #name;
    HL_GCCJIT_FUNCTIONS(HL_GCCJIT_RESOLVE)
#undef HL_GCCJIT_RESOLVE
    return missing;
}

/* The library named by $HAMLIE_GCCJIT_LIB, else the soname, else the file
 * CMake found at build time (when it is not on the loader's path). */
#ifdef HAMLIE_GCCJIT_PATH
#define FALLBACK_LIB HAMLIE_GCCJIT_PATH
#else
#define FALLBACK_LIB NULL
#endif

static void load(void)
{
    const char *name;
    void *lib = hl_lib_open("HAMLIE_GCCJIT_LIB", DEFAULT_LIB, FALLBACK_LIB, &name);
    if (lib == NULL) {
        load_failed = 1;
        snprintf(load_why, sizeof load_why,
                 "%s not found: install libgccjit0 / libgccjit-12-dev; running interpreted", name);
        return;
    }
    const char *missing = resolve_all(lib);
    if (missing != NULL) {
        /* an older libgccjit: use none of it (the handle stays, harmless) */
        load_failed = 1;
        snprintf(load_why, sizeof load_why, "%s lacks %s (too old?); running interpreted", name,
                 missing);
    }
}

hl_status hl_gccjit_load(hl_error *err)
{
    pthread_once(&load_once, load);
    if (load_failed)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "%s", load_why);
    return HL_OK;
}

int hl_gccjit_not_failed(void)
{
    return !load_failed;
}

const char *hl_tape_jit_load_error(void)
{
    return load_failed ? load_why : NULL;
}

#else /* built without libgccjit: nothing to load, nothing to report */

const char *hl_tape_jit_load_error(void)
{
    return NULL;
}

#endif
