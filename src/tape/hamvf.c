/* The Hamiltonian vector field as a tape (kept apart from compile.c so that
 * a program using only tapes does not pull in differentiation). */
#include <stdlib.h>

#include "base/buf.h"
#include "hamlie/tape.h"

hl_status hl_tape_hamiltonian(hl_tape **out, hl_pool *pool, const hl_expr *H, int N,
                              const char *const *q, const char *const *p, int nparams,
                              const char *const *params, const hl_expr *const *vals, hl_error *err)
{
    *out = NULL;
    if (N <= 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "a Hamiltonian needs at least one degree of freedom");
    if (nparams > 0)
        H = hl_expr_subst(pool, H, nparams, params, vals);
    const hl_expr **f = hl_xmalloc(2 * (size_t)N * sizeof *f);
    const char **names = hl_xmalloc(2 * (size_t)N * sizeof *names);
    for (int j = 0; j < N; j++) {
        names[j] = q[j];
        names[N + j] = p[j];
        f[j] = hl_expr_diff(pool, H, p[j]);
        f[N + j] = hl_neg(pool, hl_expr_diff(pool, H, q[j]));
    }
    int status = hl_tape_new(out, f, 2 * N, names, 2 * N, err);
    free(f);
    free(names);
    return status;
}
