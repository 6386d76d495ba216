/* hamlie — surfaces of section (Poincare maps) of an autonomous H: orbits
 * seeded on the energy surface H = E and their crossings of a coordinate
 * section q_j = c, collected by the events of run.h.
 *
 *   hl_section *s;
 *   hl_section_new(&s, sys, "x=0", HL_EVENT_UP, 0.125, err);
 *   hl_section_spread(s, zs, 60, err);       // or hl_section_complete per point
 *   hl_section_orbit(s, run, zs + 4*i, 500, opts, fn, arg, &stats, err);
 *
 * Seeding.  On the section q_j = c the momentum p_j conjugate to q_j is the
 * one solved for, from H(z) = E, with the sign of the direction (> 0 for
 * HL_EVENT_UP and HL_EVENT_BOTH, < 0 for HL_EVENT_DOWN: for a kinetic
 * energy p^2/2 that is the direction in which q_j crosses c).  The root is
 * bracketed from p_j = 0 outwards (doubling) and closed by bisection to
 * round-off; there is no real solution where H(p_j = 0) > E (the point is
 * outside the allowed region) or H stays below E as |p_j| grows: HL_EDOM,
 * the message naming the point.
 * With two degrees of freedom, hl_section_spread spreads M orbits along
 * the line of the other coordinate q_o (p_o = 0): over the interval around
 * the minimum of H(q_j = c, q_o, 0, 0) where it is <= E (searched on
 * [-R, R], R = 1, 10, .. 1e4, its ends found by bisection), at the centres
 * of M equal cells, so that no orbit starts on the boundary (p_j = 0).
 * HL_EDOM when E is below the minimum of H on that line.
 *
 * The section and the system are borrowed; the surface text is copied.
 */
#ifndef HAMLIE_SECTION_H
#define HAMLIE_SECTION_H

#include "hamlie/error.h"
#include "hamlie/event.h"
#include "hamlie/ham.h"
#include "hamlie/run.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct hl_section hl_section;

/* surface: "q_j = c" (or "c = q_j") with q_j a coordinate of the system
 * and c a constant formula; errors point into it (hl_run_surface).  E must
 * be finite. */
hl_status hl_section_new(hl_section **out, hl_system *sys, const char *surface, hl_event_dir dir,
                         double E, hl_error *err);
void hl_section_free(hl_section *s); /* NULL is a no-op */

int hl_section_coord(const hl_section *s);    /* j: the section is q_j = c */
int hl_section_momentum(const hl_section *s); /* N + j: the index solved for */
double hl_section_value(const hl_section *s); /* c */
hl_system *hl_section_system(const hl_section *s);
hl_event_dir hl_section_direction(const hl_section *s);
double hl_section_energy(const hl_section *s);

/* z (2N, q then p): q_j is set to c and p_j solved from H = E (above);
 * the other values are the caller's. */
hl_status hl_section_complete(hl_section *s, double *z, hl_error *err);

/* zs[i*2N ..] for i < M, completed (above).  Two degrees of freedom only
 * (HL_EINVAL otherwise: give the points).  *lo, *hi (may be NULL): the
 * allowed interval of q_o found. */
hl_status hl_section_spread(hl_section *s, double *zs, int M, double *lo, double *hi,
                            hl_error *err);

/* Points listed by the user, as CSV text: a header naming the columns (the
 * variables other than the solved momentum p_j; q_j may be a column, whose
 * values must then be c), one point a line, '#' lines and blank lines
 * skipped.  Each point is completed (above).  *zs (malloc'd, *n points of
 * 2N) on success.  Errors point into text (err->src = text, err->pos the
 * byte): an unknown or repeated name, a missing column, a value that is
 * not a finite number, a line with too few or too many values, no points,
 * more than HL_SECTION_MAX_POINTS; a point without a real solution names
 * its line. */
#define HL_SECTION_MAX_POINTS 1000000
hl_status hl_section_read_points(hl_section *s, const char *text, double **zs, int *n,
                                 hl_error *err);

/* How an orbit is integrated: tol > 0 the adaptive Taylor run (crossings
 * on its polynomials), else the run's fixed-step scheme with step dt (the
 * Hermite cubic).  t_max bounds each orbit's time (rounded up to a whole
 * number of steps). */
typedef struct hl_section_opts {
    double tol, dt, t_max;
} hl_section_opts;

/* The first n crossings of the orbit from z0, delivered to fn (run.h's
 * crossings: i, t, z, H).  run must have been made for the section's
 * system (its scheme the one wanted; the adaptive run ignores it); its
 * event is set here.  stats (may be NULL) describe the run; fewer than n
 * crossings by t_max is HL_ENOCONV ("orbit: 12 of 500 crossings by t =
 * ...: is the surface crossed?"), after the crossings found were
 * delivered. */
hl_status hl_section_orbit(hl_section *s, hl_run *run, const double *z0, long n,
                           const hl_section_opts *opts, hl_run_crossing_fn fn, void *arg,
                           hl_run_stats *stats, hl_error *err);

#ifdef __cplusplus
}
#endif

#endif
