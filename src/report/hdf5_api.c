/* HDF5 loaded on first use: dlopen and the tables of hdf5_api.h filled
 * once per process.  Linked, libhdf5 and the 36 libraries behind it cost
 * every command their loading, though only `section --out f.h5` and
 * `sweep --out f.h5` write HDF5.  When it cannot be loaded, the writer
 * (h5.c) reports HL_EUNSUP with the reason and no file is written. */
#define HL_HDF5_API_IMPL /* the real names here, not the table's macros */
#include <dlfcn.h>
#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>

#include "base/lib.h"
#include "report/hdf5_api.h"

hl_hdf5_api hl_hdf5;

#define DEFAULT_LIB "libhdf5_serial.so.103"

static pthread_once_t load_once = PTHREAD_ONCE_INIT;
static atomic_int load_failed; /* set once, under load_once */
static char load_why[400];     /* the reason, when load_failed */

/* Every name of the tables, or the first one missing (NULL if none). */
static const char *resolve_all(void *lib)
{
    const char *missing = NULL;
#define HL_HDF5_RESOLVE(name)                                                                      \
    hl_hdf5.name = (__typeof__(hl_hdf5.name))dlsym(lib, #name);                                    \
    if (hl_hdf5.name == NULL && missing == NULL)                                                   \
        missing = #name;
    HL_HDF5_FUNCTIONS(HL_HDF5_RESOLVE)
    HL_HDF5_GLOBALS(HL_HDF5_RESOLVE)
#undef HL_HDF5_RESOLVE
    return missing;
}

/* $HAMLIE_HDF5_LIB, else the soname, else the file CMake found at build
 * time (when it is not on the loader's path). */
#ifdef HAMLIE_HDF5_PATH
#define FALLBACK_LIB HAMLIE_HDF5_PATH
#else
#define FALLBACK_LIB NULL
#endif

static void load(void)
{
    const char *name;
    void *lib = hl_lib_open("HAMLIE_HDF5_LIB", DEFAULT_LIB, FALLBACK_LIB, &name);
    if (lib == NULL) {
        load_failed = 1;
        snprintf(load_why, sizeof load_why,
                 "%s not found: install libhdf5-103-1 (Debian) to write HDF5 files", name);
        return;
    }
    const char *missing = resolve_all(lib);
    if (missing != NULL) {
        load_failed = 1;
        snprintf(load_why, sizeof load_why, "%s lacks %s (not HDF5 1.10.7 or later?)", name,
                 missing);
        return;
    }
    /* the predefined types' globals are set by H5open; HDF5 prints its
     * error stack to stderr unless told not to, and hamlie says itself
     * what failed */
    if (hl_hdf5.H5open() < 0 || hl_hdf5.H5Eset_auto2(H5E_DEFAULT, NULL, NULL) < 0) {
        load_failed = 1;
        snprintf(load_why, sizeof load_why, "%s: H5open failed", name);
    }
}

hl_status hl_hdf5_load(hl_error *err)
{
    pthread_once(&load_once, load);
    if (load_failed)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "%s", load_why);
    return HL_OK;
}
