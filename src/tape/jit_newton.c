/* Newton's method, compiled (hl_newton_jit in hamlie/tape.h), by libgccjit:
 * int hl_jit_newton(const double *x, double *U, int *iters, double *last,
 *                   double *Z):
 * newton.c's hl_newton_solve as one function, the same operations in the
 * same order: the three tapes inlined (each with its own register locals),
 * U in locals, the LU factors in local arrays (partial pivoting indexes
 * them at run time); with an output tape, its last values in Z (newton.c's
 * zprev, so hl_newton_output reads them after either). */
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "tape/jit_cache_impl.h"
#include "tape/jit_impl.h"
#include "tape/tape_impl.h"

#ifdef HAMLIE_HAVE_GCCJIT

typedef struct nj {
    gcc_jit_context *c;
    gcc_jit_function *fun;
    gcc_jit_type *dbl, *intt;
    jit T[4]; /* start, F, FJ, and Z (hl_newton_set_output) */
    gcc_jit_rvalue *x, *U, *iters, *last;
    gcc_jit_lvalue **u;                 /* m locals: the iterate */
    gcc_jit_rvalue **uv;                /* and their values */
    gcc_jit_lvalue *A, *b, *dinv, *piv; /* local arrays */
    gcc_jit_lvalue *it, *fresh, *prev, *ratio, *dn, *un, *r, *tmp;
    gcc_jit_lvalue *zprev, *zd, *zs; /* with Z: its last values, move, size */
    gcc_jit_function *fabs_;
    int m, nx, ntapes;
    int nblk;
} nj;

static gcc_jit_rvalue *ND(nj *N, double v)
{
    return gcc_jit_context_new_rvalue_from_double(N->c, N->dbl, v);
}
static gcc_jit_rvalue *NI(nj *N, int v)
{
    return gcc_jit_context_new_rvalue_from_int(N->c, N->intt, v);
}
static gcc_jit_rvalue *RVL(gcc_jit_lvalue *l)
{
    return gcc_jit_lvalue_as_rvalue(l);
}
static gcc_jit_lvalue *AT(nj *N, gcc_jit_lvalue *arr, gcc_jit_rvalue *i)
{
    return gcc_jit_context_new_array_access(N->c, NULL, RVL(arr), i);
}
static gcc_jit_lvalue *ATI(nj *N, gcc_jit_lvalue *arr, int i)
{
    return AT(N, arr, NI(N, i));
}
static gcc_jit_rvalue *OP(nj *N, enum gcc_jit_binary_op op, gcc_jit_rvalue *a, gcc_jit_rvalue *b)
{
    return gcc_jit_context_new_binary_op(N->c, NULL, op, N->dbl, a, b);
}
static gcc_jit_rvalue *CMP(nj *N, enum gcc_jit_comparison op, gcc_jit_rvalue *a, gcc_jit_rvalue *b)
{
    return gcc_jit_context_new_comparison(N->c, NULL, op, a, b);
}
static gcc_jit_rvalue *FABS(nj *N, gcc_jit_rvalue *a)
{
    return gcc_jit_context_new_call(N->c, NULL, N->fabs_, 1, &a);
}
static gcc_jit_block *BLK(nj *N)
{
    char name[32];
    snprintf(name, sizeof name, "b%d", N->nblk++);
    return gcc_jit_function_new_block(N->fun, name);
}
static void SET(gcc_jit_block *blk, gcc_jit_lvalue *l, gcc_jit_rvalue *v)
{
    gcc_jit_block_add_assignment(blk, NULL, l, v);
}

/* 0.0 exactly when every v[i] is finite (sum of v - v), else NaN */
static gcc_jit_rvalue *finite_sum(nj *N, gcc_jit_rvalue **v, int n)
{
    gcc_jit_rvalue *acc = ND(N, 0);
    for (int i = 0; i < n; i++)
        acc = OP(N, GCC_JIT_BINARY_OP_PLUS, acc, OP(N, GCC_JIT_BINARY_OP_MINUS, v[i], v[i]));
    return acc;
}

/* A block that writes U and returns status: the exits of the solve. */
static gcc_jit_block *exit_block(nj *N, int status)
{
    gcc_jit_block *e = BLK(N);
    for (int i = 0; i < N->m; i++)
        gcc_jit_block_add_assignment(
            e, NULL, gcc_jit_context_new_array_access(N->c, NULL, N->U, NI(N, i)), RVL(N->u[i]));
    gcc_jit_block_end_with_return(e, NULL, NI(N, status));
    return e;
}

/* Continue in a fresh block when cond holds, else go to fail. */
static gcc_jit_block *check(nj *N, gcc_jit_block *blk, gcc_jit_rvalue *cond, gcc_jit_block *fail)
{
    gcc_jit_block *ok = BLK(N);
    gcc_jit_block_end_with_conditional(blk, NULL, cond, ok, fail);
    return ok;
}

/* l = max(l, v) as the C code's ternary: if (v > l) l = v. */
static gcc_jit_block *raise_to(nj *N, gcc_jit_block *blk, gcc_jit_lvalue *l, gcc_jit_rvalue *v)
{
    gcc_jit_block *up = BLK(N), *next = BLK(N);
    gcc_jit_block_end_with_conditional(blk, NULL, CMP(N, GCC_JIT_COMPARISON_GT, v, RVL(l)), up,
                                       next);
    SET(up, l, v);
    gcc_jit_block_end_with_jump(up, NULL, next);
    return next;
}

/* Tape k inlined in blk: inputs x (and U when with_u); returns its outputs
 * (malloc'd array of rvalues). */
static gcc_jit_rvalue **inline_tape(nj *N, int k, gcc_jit_block *blk, int with_u)
{
    jit *J = &N->T[k];
    J->blk = blk;
    for (int i = 0; i < N->nx; i++)
        hl_jit_assign(J, i, RVL(gcc_jit_context_new_array_access(N->c, NULL, N->x, NI(N, i))));
    for (int i = 0; with_u && i < N->m; i++)
        hl_jit_assign(J, N->nx + i, RVL(N->u[i]));
    for (int i = 0; i < J->t->ncode; i++)
        hl_jit_emit(J, &J->t->code[i]);
    gcc_jit_rvalue **out = hl_xmalloc((size_t)J->t->nout * sizeof *out);
    for (int j = 0; j < J->t->nout; j++)
        out[j] = hl_jit_val(J, J->t->outreg[j]);
    /* the imports are shared by the tapes */
    for (int q = 0; q < N->ntapes && q < 4; q++)
        if (q != k) {
            memcpy(N->T[q].lib, J->lib, sizeof J->lib);
            N->T[q].sincos = J->sincos;
        }
    return out;
}

#define A_(i, j) AT(N, N->A, NI(N, (i)*m + (j)))

/* lu_factor of newton.c on the local array A; returns the block after it,
 * jumping to singular when a pivot is 0. */
static gcc_jit_block *build_lu(nj *N, gcc_jit_block *blk, gcc_jit_block *singular)
{
    int m = N->m;
    gcc_jit_rvalue *mm = NI(N, m);
    for (int c = 0; c < m; c++) {
        SET(blk, N->r, NI(N, c));
        for (int i = c + 1; i < m; i++) {
            /* r*m + c */
            gcc_jit_rvalue *rc = gcc_jit_context_new_binary_op(
                N->c, NULL, GCC_JIT_BINARY_OP_PLUS, N->intt,
                gcc_jit_context_new_binary_op(N->c, NULL, GCC_JIT_BINARY_OP_MULT, N->intt,
                                              RVL(N->r), mm),
                NI(N, c));
            gcc_jit_block *up = BLK(N), *next = BLK(N);
            gcc_jit_block_end_with_conditional(blk, NULL,
                                               CMP(N, GCC_JIT_COMPARISON_GT, FABS(N, RVL(A_(i, c))),
                                                   FABS(N, RVL(AT(N, N->A, rc)))),
                                               up, next);
            SET(up, N->r, NI(N, i));
            gcc_jit_block_end_with_jump(up, NULL, next);
            blk = next;
        }
        SET(blk, ATI(N, N->piv, c), RVL(N->r));
        gcc_jit_rvalue *rm = gcc_jit_context_new_binary_op(N->c, NULL, GCC_JIT_BINARY_OP_MULT,
                                                           N->intt, RVL(N->r), mm);
        for (int j = 0; j < m; j++) {
            gcc_jit_lvalue *rj = AT(N, N->A,
                                    gcc_jit_context_new_binary_op(
                                        N->c, NULL, GCC_JIT_BINARY_OP_PLUS, N->intt, rm, NI(N, j)));
            SET(blk, N->tmp, RVL(rj));
            SET(blk, rj, RVL(A_(c, j)));
            SET(blk, A_(c, j), RVL(N->tmp));
        }
        blk = check(N, blk, CMP(N, GCC_JIT_COMPARISON_GT, FABS(N, RVL(A_(c, c))), ND(N, 0)),
                    singular);
        SET(blk, ATI(N, N->dinv, c), OP(N, GCC_JIT_BINARY_OP_DIVIDE, ND(N, 1), RVL(A_(c, c))));
        for (int i = c + 1; i < m; i++) {
            SET(blk, N->tmp, OP(N, GCC_JIT_BINARY_OP_MULT, RVL(A_(i, c)), RVL(ATI(N, N->dinv, c))));
            SET(blk, A_(i, c), RVL(N->tmp));
            for (int j = c + 1; j < m; j++)
                SET(blk, A_(i, j),
                    OP(N, GCC_JIT_BINARY_OP_MINUS, RVL(A_(i, j)),
                       OP(N, GCC_JIT_BINARY_OP_MULT, RVL(N->tmp), RVL(A_(c, j)))));
        }
    }
    return blk;
}

/* lu_apply of newton.c: b = A^-1 b. */
static void build_apply(nj *N, gcc_jit_block *blk)
{
    int m = N->m;
    for (int c = 0; c < m; c++) {
        gcc_jit_lvalue *bp = AT(N, N->b, RVL(ATI(N, N->piv, c)));
        SET(blk, N->tmp, RVL(bp));
        SET(blk, bp, RVL(ATI(N, N->b, c)));
        SET(blk, ATI(N, N->b, c), RVL(N->tmp));
        for (int i = c + 1; i < m; i++)
            SET(blk, ATI(N, N->b, i),
                OP(N, GCC_JIT_BINARY_OP_MINUS, RVL(ATI(N, N->b, i)),
                   OP(N, GCC_JIT_BINARY_OP_MULT, RVL(A_(i, c)), RVL(ATI(N, N->b, c)))));
    }
    for (int i = m - 1; i >= 0; i--) {
        SET(blk, N->tmp, RVL(ATI(N, N->b, i)));
        for (int j = i + 1; j < m; j++)
            SET(blk, N->tmp,
                OP(N, GCC_JIT_BINARY_OP_MINUS, RVL(N->tmp),
                   OP(N, GCC_JIT_BINARY_OP_MULT, RVL(A_(i, j)), RVL(ATI(N, N->b, j)))));
        SET(blk, ATI(N, N->b, i),
            OP(N, GCC_JIT_BINARY_OP_MULT, RVL(N->tmp), RVL(ATI(N, N->dinv, i))));
    }
}

#undef A_

/* int hl_jit_newton(x, U, iters, last, Z) and its locals: the iterate u,
 * the LU arrays, the loop's scalars, each tape's register locals. */
static void declare_newton(nj *N, const hl_newton *nw)
{
    gcc_jit_context *c = N->c;
    int m = nw->m;
    gcc_jit_type *cdblp = gcc_jit_type_get_pointer(gcc_jit_type_get_const(N->dbl));
    gcc_jit_type *dblp = gcc_jit_type_get_pointer(N->dbl);
    gcc_jit_param *prm[5] = {
        gcc_jit_context_new_param(c, NULL, cdblp, "x"),
        gcc_jit_context_new_param(c, NULL, dblp, "U"),
        gcc_jit_context_new_param(c, NULL, gcc_jit_type_get_pointer(N->intt), "iters"),
        gcc_jit_context_new_param(c, NULL, dblp, "last"),
        gcc_jit_context_new_param(c, NULL, dblp, "Z")};
    N->fun = gcc_jit_context_new_function(c, NULL, GCC_JIT_FUNCTION_EXPORTED, N->intt,
                                          "hl_jit_newton", 5, prm, 0);
    N->x = gcc_jit_param_as_rvalue(prm[0]), N->U = gcc_jit_param_as_rvalue(prm[1]);
    N->iters = gcc_jit_param_as_rvalue(prm[2]), N->last = gcc_jit_param_as_rvalue(prm[3]);
    static const char *prefix[4] = {"s", "f", "j", "z"};
    for (int k = 0; k < N->ntapes; k++) {
        N->T[k].fun = N->fun;
        hl_jit_new_locals(&N->T[k], prefix[k]);
    }
    N->u = hl_xmalloc((size_t)m * sizeof *N->u);
    N->uv = hl_xmalloc((size_t)m * sizeof *N->uv);
    for (int i = 0; i < m; i++) {
        char name[32];
        snprintf(name, sizeof name, "u%d", i);
        N->u[i] = gcc_jit_function_new_local(N->fun, NULL, N->dbl, name);
        N->uv[i] = RVL(N->u[i]);
    }
    gcc_jit_type *amm = gcc_jit_context_new_array_type(c, NULL, N->dbl, m * m);
    gcc_jit_type *am = gcc_jit_context_new_array_type(c, NULL, N->dbl, m);
    gcc_jit_type *ai = gcc_jit_context_new_array_type(c, NULL, N->intt, m);
    N->A = gcc_jit_function_new_local(N->fun, NULL, amm, "A");
    N->b = gcc_jit_function_new_local(N->fun, NULL, am, "bv");
    N->dinv = gcc_jit_function_new_local(N->fun, NULL, am, "dinv");
    N->piv = gcc_jit_function_new_local(N->fun, NULL, ai, "piv");
    N->it = gcc_jit_function_new_local(N->fun, NULL, N->intt, "it");
    N->fresh = gcc_jit_function_new_local(N->fun, NULL, N->intt, "fresh");
    N->r = gcc_jit_function_new_local(N->fun, NULL, N->intt, "r");
    N->prev = gcc_jit_function_new_local(N->fun, NULL, N->dbl, "prev");
    N->ratio = gcc_jit_function_new_local(N->fun, NULL, N->dbl, "ratio");
    N->dn = gcc_jit_function_new_local(N->fun, NULL, N->dbl, "dn");
    N->un = gcc_jit_function_new_local(N->fun, NULL, N->dbl, "un");
    N->tmp = gcc_jit_function_new_local(N->fun, NULL, N->dbl, "tmp");
    if (nw->Z != NULL) {
        N->zprev = gcc_jit_param_as_lvalue(prm[4]);
        N->zd = gcc_jit_function_new_local(N->fun, NULL, N->dbl, "zd");
        N->zs = gcc_jit_function_new_local(N->fun, NULL, N->dbl, "zs");
    }
}

/* The entry: U0 = start(x), finite, and Z there; the loop's counters.
 * Returns the block where it jumps to the loop. */
static gcc_jit_block *newton_entry(nj *N, const hl_newton *nw)
{
    int m = nw->m;
    gcc_jit_block *blk = BLK(N);
    SET(blk, gcc_jit_rvalue_dereference(N->iters, NULL), NI(N, 0));
    SET(blk, gcc_jit_rvalue_dereference(N->last, NULL), ND(N, INFINITY));
    gcc_jit_rvalue **u0 = inline_tape(N, 0, blk, 0);
    for (int i = 0; i < m; i++)
        SET(blk, N->u[i], u0[i]);
    free(u0);
    blk = check(N, blk, CMP(N, GCC_JIT_COMPARISON_EQ, finite_sum(N, N->uv, m), ND(N, 0)),
                exit_block(N, HL_NEWTON_START));
    if (nw->Z != NULL) {
        gcc_jit_rvalue **z0 = inline_tape(N, 3, blk, 1);
        for (int i = 0; i < nw->nz; i++)
            SET(blk, ATI(N, N->zprev, i), z0[i]);
        free(z0);
    }
    SET(blk, N->prev, ND(N, INFINITY));
    SET(blk, N->ratio, ND(N, 0));
    SET(blk, N->fresh, NI(N, 0));
    SET(blk, N->it, NI(N, 0));
    return blk;
}

/* it == 1 || (fresh == 0 && prev < inf && ratio > HL_NEWTON_REFRESH): the
 * Jacobian is evaluated and factored again. */
static gcc_jit_rvalue *refresh_jacobian(nj *N)
{
    gcc_jit_type *boolt = gcc_jit_context_get_type(N->c, GCC_JIT_TYPE_BOOL);
    gcc_jit_rvalue *slow = gcc_jit_context_new_binary_op(
        N->c, NULL, GCC_JIT_BINARY_OP_LOGICAL_AND, boolt,
        CMP(N, GCC_JIT_COMPARISON_LT, RVL(N->prev), ND(N, INFINITY)),
        CMP(N, GCC_JIT_COMPARISON_GT, RVL(N->ratio), ND(N, HL_NEWTON_REFRESH)));
    gcc_jit_rvalue *stale =
        gcc_jit_context_new_binary_op(N->c, NULL, GCC_JIT_BINARY_OP_LOGICAL_AND, boolt,
                                      CMP(N, GCC_JIT_COMPARISON_EQ, RVL(N->fresh), NI(N, 0)), slow);
    return gcc_jit_context_new_binary_op(N->c, NULL, GCC_JIT_BINARY_OP_LOGICAL_OR, boolt,
                                         CMP(N, GCC_JIT_COMPARISON_EQ, RVL(N->it), NI(N, 1)),
                                         stale);
}

/* b = -F(x, U), A = J factored (when refreshed, in block jac) or b alone
 * (in block plain); both go on to after. */
static void newton_residual(nj *N, gcc_jit_block *jac, gcc_jit_block *plain, gcc_jit_block *after,
                            gcc_jit_block *nonfinite)
{
    int m = N->m;
    gcc_jit_rvalue **fj = inline_tape(N, 2, jac, 1);
    for (int i = 0; i < m; i++)
        SET(jac, ATI(N, N->b, i),
            gcc_jit_context_new_unary_op(N->c, NULL, GCC_JIT_UNARY_OP_MINUS, N->dbl, fj[i]));
    for (int i = 0; i < m * m; i++)
        SET(jac, ATI(N, N->A, i), fj[m + i]);
    gcc_jit_rvalue **av = hl_xmalloc((size_t)(m * m + m) * sizeof *av);
    for (int i = 0; i < m * m; i++)
        av[i] = RVL(ATI(N, N->A, i));
    jac =
        check(N, jac, CMP(N, GCC_JIT_COMPARISON_EQ, finite_sum(N, av, m * m), ND(N, 0)), nonfinite);
    jac = build_lu(N, jac, exit_block(N, HL_NEWTON_SINGULAR));
    SET(jac, N->fresh, NI(N, 1));
    /* F finite (its values are in b, negated) */
    jac = check(N, jac, CMP(N, GCC_JIT_COMPARISON_EQ, finite_sum(N, fj, m), ND(N, 0)), nonfinite);
    gcc_jit_block_end_with_jump(jac, NULL, after);
    free(fj), free(av);

    gcc_jit_rvalue **fv = inline_tape(N, 1, plain, 1);
    for (int i = 0; i < m; i++)
        SET(plain, ATI(N, N->b, i),
            gcc_jit_context_new_unary_op(N->c, NULL, GCC_JIT_UNARY_OP_MINUS, N->dbl, fv[i]));
    SET(plain, N->fresh, NI(N, 0));
    plain =
        check(N, plain, CMP(N, GCC_JIT_COMPARISON_EQ, finite_sum(N, fv, m), ND(N, 0)), nonfinite);
    gcc_jit_block_end_with_jump(plain, NULL, after);
    free(fv);
}

/* U += A^-1 b; dn = max |dU|, un = max |U| (from 1); *last = dn; ratio =
 * dn / prev when prev is finite and positive, else 0.  Returns the block
 * after. */
static gcc_jit_block *newton_correction(nj *N, gcc_jit_block *blk, gcc_jit_block *nonfinite)
{
    build_apply(N, blk);
    SET(blk, N->dn, ND(N, 0));
    SET(blk, N->un, ND(N, 1));
    for (int i = 0; i < N->m; i++) {
        SET(blk, N->u[i], OP(N, GCC_JIT_BINARY_OP_PLUS, RVL(N->u[i]), RVL(ATI(N, N->b, i))));
        blk = raise_to(N, blk, N->dn, FABS(N, RVL(ATI(N, N->b, i))));
        blk = raise_to(N, blk, N->un, FABS(N, RVL(N->u[i])));
    }
    blk = check(N, blk, CMP(N, GCC_JIT_COMPARISON_EQ, finite_sum(N, N->uv, N->m), ND(N, 0)),
                nonfinite);
    SET(blk, gcc_jit_rvalue_dereference(N->last, NULL), RVL(N->dn));
    gcc_jit_block *div = BLK(N), *zero = BLK(N), *next = BLK(N);
    gcc_jit_block_end_with_conditional(
        blk, NULL,
        gcc_jit_context_new_binary_op(N->c, NULL, GCC_JIT_BINARY_OP_LOGICAL_AND,
                                      gcc_jit_context_get_type(N->c, GCC_JIT_TYPE_BOOL),
                                      CMP(N, GCC_JIT_COMPARISON_LT, RVL(N->prev), ND(N, INFINITY)),
                                      CMP(N, GCC_JIT_COMPARISON_GT, RVL(N->prev), ND(N, 0))),
        div, zero);
    SET(div, N->ratio, OP(N, GCC_JIT_BINARY_OP_DIVIDE, RVL(N->dn), RVL(N->prev)));
    gcc_jit_block_end_with_jump(div, NULL, next);
    SET(zero, N->ratio, ND(N, 0));
    gcc_jit_block_end_with_jump(zero, NULL, next);
    return next;
}

/* The convergence test on the move, of U (dn, un) or of Z (zd, zs:
 * newton.c's output_move): move <= 4 eps size || (move <= 1e-12 size &&
 * ratio >= 0.5) returns HL_NEWTON_OK, else back to loop. */
static void newton_converged(nj *N, const hl_newton *nw, gcc_jit_block *blk, gcc_jit_block *loop)
{
    gcc_jit_lvalue *mv = N->dn, *sz = N->un;
    if (nw->Z != NULL) {
        gcc_jit_rvalue **zv = inline_tape(N, 3, blk, 1);
        SET(blk, N->zd, ND(N, 0));
        SET(blk, N->zs, ND(N, 1));
        for (int i = 0; i < nw->nz; i++) {
            SET(blk, N->tmp, zv[i]);
            blk = raise_to(
                N, blk, N->zd,
                FABS(N, OP(N, GCC_JIT_BINARY_OP_MINUS, RVL(N->tmp), RVL(ATI(N, N->zprev, i)))));
            blk = raise_to(N, blk, N->zs, FABS(N, RVL(N->tmp)));
            SET(blk, ATI(N, N->zprev, i), RVL(N->tmp));
        }
        free(zv);
        mv = N->zd, sz = N->zs;
    }
    gcc_jit_type *boolt = gcc_jit_context_get_type(N->c, GCC_JIT_TYPE_BOOL);
    gcc_jit_rvalue *done = gcc_jit_context_new_binary_op(
        N->c, NULL, GCC_JIT_BINARY_OP_LOGICAL_OR, boolt,
        CMP(N, GCC_JIT_COMPARISON_LE, RVL(mv),
            OP(N, GCC_JIT_BINARY_OP_MULT, ND(N, 4 * DBL_EPSILON), RVL(sz))),
        gcc_jit_context_new_binary_op(N->c, NULL, GCC_JIT_BINARY_OP_LOGICAL_AND, boolt,
                                      CMP(N, GCC_JIT_COMPARISON_LE, RVL(mv),
                                          OP(N, GCC_JIT_BINARY_OP_MULT, ND(N, 1e-12), RVL(sz))),
                                      CMP(N, GCC_JIT_COMPARISON_GE, RVL(N->ratio), ND(N, 0.5))));
    gcc_jit_block *again = BLK(N);
    gcc_jit_block_end_with_conditional(blk, NULL, done, exit_block(N, HL_NEWTON_OK), again);
    SET(again, N->prev, RVL(N->dn));
    gcc_jit_block_end_with_jump(again, NULL, loop);
}

/* newton.c's hl_newton_solve: entry, then the loop (it < max_iter, else
 * no convergence): the residual, the Jacobian when due, the correction,
 * the test. */
static void build_newton(nj *N, const hl_newton *nw)
{
    declare_newton(N, nw);
    gcc_jit_block *blk = newton_entry(N, nw);
    gcc_jit_block *loop = BLK(N), *nonfinite = exit_block(N, HL_NEWTON_NONFINITE);
    gcc_jit_block_end_with_jump(blk, NULL, loop);
    blk = check(N, loop, CMP(N, GCC_JIT_COMPARISON_LT, RVL(N->it), NI(N, nw->max_iter)),
                exit_block(N, HL_NEWTON_NOCONV));
    gcc_jit_block_add_assignment_op(blk, NULL, N->it, GCC_JIT_BINARY_OP_PLUS, NI(N, 1));
    SET(blk, gcc_jit_rvalue_dereference(N->iters, NULL), RVL(N->it));
    gcc_jit_block *jac = BLK(N), *plain = BLK(N), *after = BLK(N);
    gcc_jit_block_end_with_conditional(blk, NULL, refresh_jacobian(N), jac, plain);
    newton_residual(N, jac, plain, after, nonfinite);
    blk = newton_correction(N, after, nonfinite);
    newton_converged(N, nw, blk, loop);
    free(N->uv), free(N->u);
}

/* The solve of nw in context c (hl_jit_build_fn). */
static void build(gcc_jit_context *c, const void *arg)
{
    const hl_newton *nw = arg;
    nj N = {.c = c, .m = nw->m, .nx = nw->nx, .ntapes = nw->Z != NULL ? 4 : 3};
    N.dbl = gcc_jit_context_get_type(c, GCC_JIT_TYPE_DOUBLE);
    N.intt = gcc_jit_context_get_type(c, GCC_JIT_TYPE_INT);
    N.fabs_ = gcc_jit_context_get_builtin_function(c, "__builtin_fabs");
    hl_tape *tapes[4] = {nw->start, nw->F, nw->FJ, nw->Z};
    for (int k = 0; k < N.ntapes; k++) {
        jit *J = &N.T[k];
        hl_jit_init(J, c, tapes[k]);
        J->loc = hl_xcalloc((size_t)tapes[k]->nregs + 1, sizeof *J->loc);
        J->read = hl_jit_registers_read(tapes[k]);
    }
    build_newton(&N, nw);
    for (int k = 0; k < N.ntapes; k++)
        free(N.T[k].loc), free(N.T[k].read);
}

hl_status hl_newton_jit(hl_newton *nw, hl_error *err)
{
    if (nw->m > 16)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0,
                            "compiled Newton: %d unknowns (at most 16)", nw->m);
    hl_buf inputs;
    hl_buf_init(&inputs);
    hl_jit_inputs_newton(&inputs, nw);
    hl_jit_code *code;
    hl_status st = hl_jit_obtain(&code, HL_JIT_SITE_NEWTON, &inputs, build, nw, "hl_jit_newton",
                                 "Newton", err);
    hl_buf_clear(&inputs);
    if (st != HL_OK)
        return st;
    hl_newton_jit_clear(nw);
    nw->jit_result = code;
    *(void **)&nw->jit_fn = hl_jit_code_sym(code, "hl_jit_newton");
    return HL_OK;
}

void hl_newton_jit_clear(hl_newton *nw)
{
    hl_jit_code_free(nw->jit_result);
    nw->jit_result = NULL;
    nw->jit_fn = NULL;
}

#else /* no libgccjit: hl_newton_solve runs newton.c's interpreter */

hl_status hl_newton_jit(hl_newton *nw, hl_error *err)
{
    (void)nw;
    return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "hamlie was built without libgccjit");
}

void hl_newton_jit_clear(hl_newton *nw)
{
    nw->jit_result = NULL;
    nw->jit_fn = NULL;
}

#endif

int hl_newton_jit_active(const hl_newton *nw)
{
    return nw->jit_fn != NULL;
}
