/* Internals shared by the files of src/scheme only. */
#ifndef HAMLIE_SCHEME_IMPL_H
#define HAMLIE_SCHEME_IMPL_H

#include "hamlie/scheme.h"

/* A scheme under construction: unknowns, scalar equations, integrals. */
typedef struct sb {
    hl_scheme *s;
    hl_system *sys;
    hl_pool *pool;
    int cap_u, cap_e, cap_i;
    int neq;
} sb;

/* Starts with the 2N unknowns Q#j (index j) and P#j (index N + j). */
void sb_init(sb *b, hl_system *sys, const char *name);
/* Add an unknown; z0 NULL: derived from the equation that defines it. */
int sb_unknown(sb *b, const char *reserved, const char *display, const hl_expr *z0);
const hl_expr *sb_usym(sb *b, int u);
int sb_find(const sb *b, const char *name); /* index of an unknown, or -1 */
void sb_eq(sb *b, const hl_expr *lhs, const hl_expr *rhs, int defines);
/* The symbol standing for int_0^1 body d(s#). */
const hl_expr *sb_integral(sb *b, const hl_expr *body);
/* Check counts, mark explicit equations, derive values at D = 0; on
 * success *out owns the scheme, else it is freed. */
int sb_finish(hl_scheme **out, sb *b, hl_error *err);
void sb_abort(sb *b);

/* e with the integrals replaced by their integrand at s = 0, D by 0 and the
 * unknowns known at D = 0 by their values (build.c). */
const hl_expr *scheme_at_zero(const hl_scheme *s, hl_pool *pool, const hl_expr *e);

/* Upper-case display name of the image of a phase variable: malloc'd. */
char *scheme_upper(const char *v);

/* The vector reader (read.c).  A frame says what q, p, Q, P, D mean, so a
 * text can be instantiated as one part of a composition. */
typedef struct scheme_frame {
    const hl_expr *const *q, *const *p; /* N each: current point */
    const int *Qu, *Pu;                 /* N each: unknown indices of the next point */
    const hl_expr *D;                   /* the step */
    const char *prefix;                 /* for stage names ("" or "c2.") */
    const char *D_word;                 /* the step's name in the text */
} scheme_frame;

int scheme_read(sb *b, const char *text, const scheme_frame *f, hl_error *err);

/* dH/dq_j, dH/dp_j of the system as expressions (NULL without H). */
/* The numeric value of the integral int_0^1 f ds (f in HL_SCHEME_S), by a
 * rule exact for polynomials of degree 2 HL_SCHEME_GAUSS_NODES - 1 in s
 * (integral.c): Gauss-Legendre; or, if taylor_ok and f is built from
 * polynomials and sin, cos, exp, sinh, cosh of arguments linear in s, and
 * that costs at most half, f's Taylor series at s = 1/2, which computes
 * each function once.  Then *check is an expression free of s whose value,
 * at the step's values, must be at most *bound for the series to be exact
 * to rounding (else NULL, bound infinite). */
const hl_expr *scheme_integral(const hl_expr *f, int taylor_ok, hl_pool *pool,
                               const hl_expr **check, double *bound);
const hl_expr *scheme_dH(hl_system *sys, int j, int wrt_p);
/* The system's point as symbols: v[j] = q_j, v[N + j] = p_j. */
void scheme_point(const hl_expr **v, hl_system *sys);

/* The exact flow of a quadratic H that couples its pairs, in closed form
 * (linear_modes.c): hess (2N x 2N) and g0 (2N) are H's Hessian and its
 * gradient at 0; HL_EUNSUP, naming the reason, where no closed form is made. */
int scheme_linear_modes(hl_alg *images, const hl_alg *hess, const hl_alg *g0, hl_system *sys,
                        hl_error *err);
/* Its normal modes as text (linear_flow.h: hl_scheme_linear_modes). */
int scheme_linear_modes_text(char **text, const hl_alg *hess, const hl_alg *g0, hl_system *sys,
                             hl_error *err);

#endif
