/* Optional libraries opened on first use (see lib.h). */
#include <dlfcn.h>
#include <stdlib.h>

#include "base/lib.h"

void *hl_lib_open(const char *env_var, const char *soname, const char *fallback,
                  const char **name)
{
    const char *env = getenv(env_var);
    if (env != NULL && *env != '\0') {
        *name = env; /* the user's choice: no other is tried */
        return dlopen(env, RTLD_LAZY | RTLD_LOCAL);
    }
    *name = soname;
    void *lib = dlopen(soname, RTLD_LAZY | RTLD_LOCAL);
    if (lib == NULL && fallback != NULL)
        lib = dlopen(fallback, RTLD_LAZY | RTLD_LOCAL);
    return lib;
}
