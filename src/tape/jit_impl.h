/* Internals of the libgccjit back ends, shared by jit_common.c (contexts,
 * compilation, libm imports), jit_eval.c (point evaluation and the
 * iteration loops), jit_newton.c (the Newton solve) and jit.c (the
 * Taylor-ODE recursion).  Only with libgccjit (HAMLIE_HAVE_GCCJIT). */
#ifndef HAMLIE_JIT_IMPL_H
#define HAMLIE_JIT_IMPL_H

#ifdef HAMLIE_HAVE_GCCJIT
#include "tape/gccjit_api.h" /* libgccjit, loaded on first use */

#include "rules/rule.h"
#include "tape/tape_impl.h"

/* One tape being built into a function: its registers as locals. */
typedef struct jit {
    gcc_jit_context *c;
    gcc_jit_type *dbl, *dblp;
    gcc_jit_block *blk;
    gcc_jit_function *fun;
    gcc_jit_lvalue **loc; /* one local per non-constant register */
    gcc_jit_function *lib[HL_PFN_COUNT]; /* libm imports, by point function */
    gcc_jit_function *sqrt, *sincos;
    const hl_tape *t;
    unsigned char *read; /* by register: read by an instruction or an output */
    int split_sincos;    /* sin and cos as two calls (build_loop) */
} jit;

/* ---- jit_common.c ---- */

/* A context at optimization level opt: no debug information, diagnostics
 * kept for the caller (not printed), no contraction into FMA, then
 * $HL_JIT_FLAGS.  With host_isa also the host's vector instructions
 * (hl_jit_host_isa).  HL_EUNSUP if libgccjit cannot start. */
hl_status hl_jit_context_new(gcc_jit_context **c, int opt, int host_isa, hl_error *err);

/* J's types and builtins in context c, for tape t (J->loc, J->read: the
 * caller's). */
void hl_jit_init(jit *J, gcc_jit_context *c, const hl_tape *t);

/* Compiles c, leaving the caller's signal handlers in place: into the
 * shared object path, or with path NULL in memory (*res).  0 on success,
 * -1 with libgccjit's first error in c.  The compile sites go through
 * jit_cache.c's hl_jit_obtain, which calls this. */
int hl_jit_run_compiler(gcc_jit_context *c, const char *path, gcc_jit_result **res);

/* The libm function name (one double argument), the one a rule's point
 * function calls (pow, atan2: two arguments; sqrt: GCC's builtin), and
 * sincos(x, &s, &c), imported once per J. */
gcc_jit_function *hl_jit_import1(jit *J, const char *name);
gcc_jit_function *hl_jit_import_lib(jit *J, hl_pfn f);
gcc_jit_function *hl_jit_import_sincos(jit *J);

/* ---- jit_eval.c: a tape's instructions in J->fun ---- */

/* By register: 1 if an instruction or an output reads it (malloc'd). */
unsigned char *hl_jit_registers_read(const hl_tape *t);
/* Fresh locals of J->fun for the registers that are not constants. */
void hl_jit_new_locals(jit *J, const char *prefix);
/* The value of register r: an immediate for a constant, else its local. */
gcc_jit_rvalue *hl_jit_val(jit *J, int r);
void hl_jit_assign(jit *J, int d, gcc_jit_rvalue *v);
/* One instruction into J->blk, as the interpreter (eval.c) computes it. */
void hl_jit_emit(jit *J, const hl_instr *i);

/* Loop-carried values (jit_eval.c; the scalar and the lane loops): an
 * instruction on an input fed back (sin q) whose twin is the same op on
 * the output fed back to it (sin Q) takes, from the second step on, the
 * twin's value of the step before (the same bits). */
typedef struct carry {
    int i, twin;           /* instruction indices in t->code */
    gcc_jit_lvalue *d, *x; /* the carried values (x: the aux, e.g. cos) */
} carry;
/* The carries of t with nmap inputs fed back (malloc'd, *n of them);
 * marks the twins' registers in read where the carried ones are. */
carry *hl_jit_find_carries(const hl_tape *t, unsigned char *read, int nmap, int *n);
/* cv's index whose instruction is k, or -1. */
int hl_jit_carried(const carry *cv, int n, int k);

#endif
#endif
