/* Internal to src/exact/. */
#ifndef HAMLIE_EXACT_IMPL_H
#define HAMLIE_EXACT_IMPL_H

#include "hamlie/exact.h"
#include "hamlie/tape.h"

#define ORD HL_EXACT_SERIES_DEGREE /* Taylor order of the table polynomials (20) */
#define NC (ORD + 1)

/* The double exact flow (exact.h): flow.c steps it, linear.c and table.c fill
 * it. */
struct hl_exact_flow {
    int N, linear;
    /* linear: augmented (2N+1)^2 matrix [[A, b], [0, 0]] and its exp at dt */
    double *Aaug, *E, Edt;
    int have_E;
    /* 1 dof */
    hl_tape *vf, *Ht;
    double L; /* the period of H in q (2 pi), 0 if H is not periodic */
    /* the table: the orbit from its start zs (a turning point of a
     * libration; on a rotation any point, q advancing by Ls a period) */
    int have_tab, kind;
    double zs[2], zslo, Ls, size; /* zs[0] + zslo: double-double; size: the
                                   * orbit's extent in q and p */
    double escale;                /* its energy scale: the largest p dH/dp / 2 */
    double T, Tlo, hs, hslo;      /* period T + Tlo, sample spacing hs + hslo */
    /* the last output, its time since the start (double-double) and
     * winding: stepping again from it needs no search */
    double last[2], lth, ltl, lw;
    int have_last;
    int M;
    double *C; /* M + 1 pieces x 2 variables x NC coefficients */
};

/* 1 dof: the orbit through z as the double flow tabulates it (building its
 * table): its kind, its start zs (the turning point a libration's table
 * starts from; a rotation's own z; an equilibrium itself), q's advance Ls
 * over a period of a rotation (0 otherwise), the period T (an
 * equilibrium's: the limit of small orbits, +inf if unstable) and the
 * orbit's extent in q and p. */
enum { ORBIT_EQUILIBRIUM = 0, ORBIT_LIBRATION = 1, ORBIT_ROTATION = 2 };
typedef struct hl_exact_orbit {
    int kind;
    double zs[2], Ls, T, size;
} hl_exact_orbit;

int hl_exact_orbit_(hl_exact_orbit *o, const double *z, hl_exact_flow *f, hl_error *err);

/* Newton on H(q, 0) = E in Arb at prec from qd, until a step is below
 * 10^-(digits + 2) scale (Ht: H over (q, p); vf: (dH/dp, -dH/dq)). */
void hl_exact_turning_point_arb_(arb_t qt, const arb_t E, double qd, double scale,
                                 double digits, slong prec, hl_tape *Ht, hl_tape *vf);

/* (dH/dp, -dH/dq) at z (1 dof). */
void hl_exact_flow_gradient_(double *v, const double *z, hl_exact_flow *f);

/* ---- linear.c: quadratic H --------------------------------------------- */

/* Is H quadratic (degree <= 2 in q,p, constant coefficients)?  *yes, and
 * when it is the augmented (2N+1)^2 matrix [[A, b], [0, 0]] in Aaug. */
int hl_exact_linear_matrix_(double *Aaug, int *yes, hl_system *sys, hl_error *err);

/* z = exp(dt A) (z, 1), the exponential kept for the next step of the same dt. */
int hl_exact_linear_step_(double *z, double dt, hl_exact_flow *f);

/* coef[k 2N + i] = (A^k (z, 1))_i / k!, k = 0..n: the series of exp(D A). */
void hl_exact_linear_series_(double *coef, const double *z, int n, const hl_exact_flow *f);

/* ---- table.c: the orbit table of 1 dof ------------------------------------ */

/* z (and dz/ds when dz is not NULL) of the table polynomial c (2 x NC
 * coefficients) at s. */
void hl_exact_poly_eval_(double *z, double *dz, const double *c, double s);

/* Build the table of the orbit through z0 (not an equilibrium): its kind,
 * start, period and pieces in f. */
int hl_exact_table_build_(hl_exact_flow *f, const double *z0, hl_error *err);

#endif
