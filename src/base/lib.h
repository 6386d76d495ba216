/* Optional libraries loaded on first use (libgccjit, PLplot, HDF5): a
 * command that does not compile, draw or write HDF5 does not pay for them
 * at start-up (issue 17). */
#ifndef HAMLIE_BASE_LIB_H
#define HAMLIE_BASE_LIB_H

/* dlopen (RTLD_LAZY | RTLD_LOCAL) the library named by $env_var when it
 * is set and not empty, else soname, else fallback (the file found at
 * build time, for when it is not on the loader's path; may be NULL).
 * *name: the name tried first, for messages.  NULL when none opens. */
void *hl_lib_open(const char *env_var, const char *soname, const char *fallback,
                  const char **name);

#endif
