/* The disk cache of compiled code (jit_cache.c): what the three libgccjit
 * compilers (jit_eval.c, jit_newton.c, jit_taylor.c) build is kept as a
 * shared object in the user's cache directory, under a key that names
 * everything the generated code depends on, and loaded by the next process
 * instead of compiled again.  cost.c asks whether an entry is there. */
#ifndef HAMLIE_JIT_CACHE_IMPL_H
#define HAMLIE_JIT_CACHE_IMPL_H

#include "base/buf.h"
#include "tape/tape_impl.h"

/* The three compile sites; each has its optimization level and whether it
 * uses the host's vector instructions (one table in jit_cache.c, so that
 * the key and the context are made from the same figures). */
typedef enum hl_jit_site {
    HL_JIT_SITE_EVAL,   /* hl_tape_jit: point evaluation and the loops */
    HL_JIT_SITE_NEWTON, /* hl_newton_jit */
    HL_JIT_SITE_TAYLOR, /* hl_tape_jit_taylor: the recursion of one order */
    HL_JIT_SITE_BATCH,  /* hl_tape_batch_new: that recursion over lanes (jit_batch.c) */
} hl_jit_site;

/* What each site's builder reads, as text: the part of the key that is the
 * program (appended to b). */
void hl_jit_inputs_tape(hl_buf *b, const hl_tape *t);
void hl_jit_inputs_taylor(hl_buf *b, const hl_tape *t, int order);
/* the Taylor recursion over lanes (jit_batch.c; lanes 1: the single's) */
void hl_jit_inputs_batch(hl_buf *b, const hl_tape *t, int order, int lanes);
void hl_jit_inputs_newton(hl_buf *b, const hl_newton *nw);

/* 1 if the cache is on and holds a valid-looking entry for these inputs
 * (its key text equal; the object itself is checked when loaded). */
int hl_jit_cache_has(hl_jit_site site, const hl_buf *inputs);

/* Counters since the process started (tests, HAMLIE_JIT_VERBOSE). */
typedef struct hl_jit_cache_stats {
    long hits;     /* loaded from the cache, no compilation */
    long compiles; /* compilations (kept in the cache or not) */
    long stored;   /* of which written to the cache */
    long rejected; /* entries found damaged or not matching: recompiled */
} hl_jit_cache_stats;
void hl_jit_cache_get_stats(hl_jit_cache_stats *s);

/* The -march level of the machine (x86-64-v3: 3, v4: 4, else 0) that
 * the Taylor recursion is compiled for (jit_common.c). */
int hl_jit_host_isa(void);

/* The code generator's identity: libhamlie's GNU build-id, in hex
 * (jit_cache_id.c; appended to b). */
void hl_jit_generator_id(hl_buf *b);

/* The directory the environment names for the cache (not made, not
 * checked; see jit_cache.c), or NULL when HAMLIE_CACHE=off or no home is
 * known.  The caller frees it. */
char *hl_jit_cache_dir_named(void);

/* 1 if the cache is on and its directory usable (made if missing). */
int hl_jit_cache_on(void);

/* Forget the directory and the notice (tests). */
void hl_jit_cache_reset(void);

#ifdef HAMLIE_HAVE_GCCJIT
#include <libgccjit.h>

/* Compiled code: a shared object loaded from the cache, or libgccjit's
 * in-memory result when the cache is off. */
typedef struct hl_jit_code hl_jit_code;
void *hl_jit_code_sym(hl_jit_code *code, const char *name);
void hl_jit_code_free(hl_jit_code *code); /* NULL is fine */

/* Builds the site's functions into c from arg. */
typedef void (*hl_jit_build_fn)(gcc_jit_context *c, const void *arg);

/* The compiled code for inputs: from the cache if it holds them (no
 * libgccjit context made), else built by build(c, arg), compiled, kept in
 * the cache when it is on, loaded.  entry must be one of its functions;
 * what names the program in messages.  HL_EUNSUP with libgccjit's first
 * error if compilation fails. */
hl_status hl_jit_obtain(hl_jit_code **code, hl_jit_site site, const hl_buf *inputs,
                        hl_jit_build_fn build, const void *arg, const char *entry, const char *what,
                        hl_error *err);
#endif

#endif
