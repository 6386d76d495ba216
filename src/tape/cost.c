/* When compiling pays. */
#include <limits.h>

#include "tape/tape_impl.h"

/* Figures from bench/tape_jit.c (gcc 12, -O2, x86-64): compile time
 * 25 ms + 0.1 ms per instruction; interpreter about 2.8 ns and compiled
 * code about 0.4 ns per instruction and evaluation. */
long hl_tape_jit_breakeven(const hl_tape *t)
{
    if (!hl_tape_jit_available() || t->ncode == 0)
        return LONG_MAX;
    double compile_ns = 25e6 + 1e5 * t->ncode, gain_ns = 2.4 * t->ncode;
    return (long)(compile_ns / gain_ns);
}
