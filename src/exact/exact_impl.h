/* Internal to src/exact/. */
#ifndef HAMLIE_EXACT_IMPL_H
#define HAMLIE_EXACT_IMPL_H

#include "hamlie/exact.h"
#include "hamlie/tape.h"

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

#endif
