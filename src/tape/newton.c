/* Simplified Newton's method on tapes (see hl_newton in hamlie/tape.h): the
 * interpreter's solve; jit.c builds the same solve as one compiled function
 * (hl_newton_jit), operation for operation. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "tape/tape_impl.h"

hl_status hl_newton_new(hl_newton **out, hl_tape *start, hl_tape *F, hl_tape *FJ, int max_iter,
                        hl_error *err)
{
    *out = NULL;
    int nx = hl_tape_ninputs(start), m = hl_tape_noutputs(start);
    if (m < 1 || hl_tape_ninputs(F) != nx + m || hl_tape_noutputs(F) != m ||
        hl_tape_ninputs(FJ) != nx + m || hl_tape_noutputs(FJ) != m + m * m || max_iter < 1)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "Newton: tapes of the wrong shape (start %d -> %d, F %d -> %d, "
                            "FJ %d -> %d)",
                            nx, m, hl_tape_ninputs(F), hl_tape_noutputs(F), hl_tape_ninputs(FJ),
                            hl_tape_noutputs(FJ));
    hl_newton *nw = hl_xcalloc(1, sizeof *nw);
    nw->start = start, nw->F = F, nw->FJ = FJ;
    nw->nx = nx, nw->m = m, nw->max_iter = max_iter;
    nw->in = hl_xmalloc((size_t)(nx + m) * sizeof *nw->in);
    nw->out = hl_xmalloc((size_t)(m + m * m) * sizeof *nw->out);
    nw->A = hl_xmalloc((size_t)(m * m) * sizeof *nw->A);
    nw->b = hl_xmalloc((size_t)m * sizeof *nw->b);
    nw->dinv = hl_xmalloc((size_t)m * sizeof *nw->dinv);
    nw->piv = hl_xmalloc((size_t)m * sizeof *nw->piv);
    *out = nw;
    return HL_OK;
}

void hl_newton_free(hl_newton *nw)
{
    if (nw == NULL)
        return;
    hl_newton_jit_clear(nw);
    free(nw->in), free(nw->out), free(nw->A), free(nw->b), free(nw->dinv), free(nw->piv);
    free(nw->z), free(nw->zprev);
    free(nw);
}

void hl_newton_set_output(hl_newton *nw, hl_tape *Z)
{
    hl_newton_jit_clear(nw); /* the compiled solve tests U */
    nw->Z = Z;
    nw->nz = hl_tape_noutputs(Z);
    free(nw->z), free(nw->zprev);
    nw->z = hl_xmalloc(((size_t)nw->nz + 1) * sizeof *nw->z);
    nw->zprev = hl_xmalloc(((size_t)nw->nz + 1) * sizeof *nw->zprev);
}

/* The convergence test of hl_newton_solve on d (the move) and s (the size,
 * >= 1); ratio: this correction over the last. */
static int converged(double d, double s, double ratio)
{
    return d <= 4 * DBL_EPSILON * s || (d <= 1e-12 * s && ratio >= 0.5);
}

/* max |Z - Zprev| and max(1, |Z|) at the current U (in holds x, U); Z
 * becomes Zprev. */
static void output_move(double *d, double *s, hl_newton *nw)
{
    hl_tape_eval_d(nw->z, nw->in, nw->Z);
    *d = 0, *s = 1;
    for (int i = 0; i < nw->nz; i++) {
        double a = fabs(nw->z[i] - nw->zprev[i]), b = fabs(nw->z[i]);
        *d = a > *d ? a : *d;
        *s = b > *s ? b : *s;
        nw->zprev[i] = nw->z[i];
    }
}

int hl_newton_unknowns(const hl_newton *nw) { return nw->m; }

const double *hl_newton_output(const hl_newton *nw) { return nw->zprev; }

/* A = LU in place with partial pivoting (piv: the row swaps; dinv: the
 * reciprocals of U's diagonal, so that solving multiplies); 0 if singular.
 * Every operation is also done when a multiplier is 0, as the compiled
 * solve does (jit.c), so that both give the same bits. */
static int lu_factor(double *A, int *piv, double *dinv, int m)
{
    for (int c = 0; c < m; c++) {
        int r = c;
        for (int i = c + 1; i < m; i++)
            if (fabs(A[i * m + c]) > fabs(A[r * m + c]))
                r = i;
        piv[c] = r;
        for (int j = 0; j < m; j++) {
            double t = A[r * m + j];
            A[r * m + j] = A[c * m + j], A[c * m + j] = t;
        }
        if (!(fabs(A[c * m + c]) > 0))
            return 0;
        dinv[c] = 1 / A[c * m + c];
        for (int i = c + 1; i < m; i++) {
            double f = A[i * m + c] *= dinv[c];
            for (int j = c + 1; j < m; j++)
                A[i * m + j] -= f * A[c * m + j];
        }
    }
    return 1;
}

/* b = A^{-1} b with the factors of lu_factor. */
static void lu_apply(const double *A, const int *piv, const double *dinv, double *b, int m)
{
    for (int c = 0; c < m; c++) {
        double t = b[piv[c]];
        b[piv[c]] = b[c], b[c] = t;
        for (int i = c + 1; i < m; i++)
            b[i] -= A[i * m + c] * b[c];
    }
    for (int i = m - 1; i >= 0; i--) {
        double s = b[i];
        for (int j = i + 1; j < m; j++)
            s -= A[i * m + j] * b[j];
        b[i] = s * dinv[i];
    }
}

static int all_finite(const double *x, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(x[i]))
            return 0;
    return 1;
}

hl_newton_status hl_newton_solve(double *U, int *iters, double *last_dn, const double *x,
                                 hl_newton *nw)
{
    if (nw->jit_fn != NULL)
        return (hl_newton_status)nw->jit_fn(x, U, iters, last_dn, nw->zprev);
    int m = nw->m, nx = nw->nx;
    double *in = nw->in, *A = nw->A, *b = nw->b, *out = nw->out;
    *iters = 0;
    *last_dn = INFINITY;
    hl_tape_eval_d(U, x, nw->start);
    if (!all_finite(U, m))
        return HL_NEWTON_START;
    memcpy(in, x, (size_t)nx * sizeof *in);
    if (nw->Z != NULL) {
        memcpy(in + nx, U, (size_t)m * sizeof *U);
        hl_tape_eval_d(nw->zprev, in, nw->Z);
    }
    double last = INFINITY, ratio = 0;
    int fresh = 0; /* the factored Jacobian is at the current iterate */
    for (int it = 1; it <= nw->max_iter; it++) {
        *iters = it;
        memcpy(in + nx, U, (size_t)m * sizeof *U);
        if (it == 1 || (!fresh && last < INFINITY && ratio > HL_NEWTON_REFRESH)) {
            hl_tape_eval_d(out, in, nw->FJ); /* F, then the Jacobian */
            memcpy(A, out + m, (size_t)(m * m) * sizeof *A);
            if (!all_finite(A, m * m))
                return HL_NEWTON_NONFINITE;
            if (!lu_factor(A, nw->piv, nw->dinv, m))
                return HL_NEWTON_SINGULAR;
            fresh = 1;
        } else {
            hl_tape_eval_d(out, in, nw->F);
            fresh = 0;
        }
        if (!all_finite(out, m))
            return HL_NEWTON_NONFINITE;
        for (int i = 0; i < m; i++)
            b[i] = -out[i];
        lu_apply(A, nw->piv, nw->dinv, b, m);
        double dn = 0, un = 1;
        for (int i = 0; i < m; i++) {
            U[i] += b[i];
            double ab = fabs(b[i]), au = fabs(U[i]);
            dn = ab > dn ? ab : dn;
            un = au > un ? au : un;
        }
        if (!all_finite(U, m))
            return HL_NEWTON_NONFINITE;
        *last_dn = dn;
        ratio = last < INFINITY && last > 0 ? dn / last : 0;
        /* converged: the correction is at rounding level; or the corrections
         * are tiny and no longer shrink (rounding in F itself: the Gonzalez
         * remainder R is a difference of O(1) terms that is O(D^3)).  Not on
         * an estimate of the error left from the contraction: that stops one
         * iteration early, and the discrete gradients' H then drifts 100x
         * faster (AVF on the pendulum, D = 0.1, 1e4 steps: 3e-13 against
         * 4e-15) */
        if (nw->Z != NULL) {
            double d, sz;
            memcpy(in + nx, U, (size_t)m * sizeof *U);
            output_move(&d, &sz, nw);
            if (converged(d, sz, ratio))
                return HL_NEWTON_OK;
        } else if (converged(dn, un, ratio))
            return HL_NEWTON_OK;
        last = dn;
    }
    return HL_NEWTON_NOCONV;
}
