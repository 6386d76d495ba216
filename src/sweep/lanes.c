/* Which members of a sweep share SIMD lanes, and when (issue 15 part 5).
 * The one place that groups members for lanes: the lie members (the
 * Taylor integrator's batch, run.h's hl_run_adaptive_lanes) and the
 * fixed-step ones (hl_run_fixed_batch's compiled loop, same_dt).  A group
 * holds members of one paramset (one system, one tape) and one scheme; the
 * lanes give each member its own run's bits, so the grouping, and whether
 * lanes are used at all, only moves time: the table is the same either
 * way. */
#include <stdlib.h>
#include <string.h>

#include "hamlie/tape.h"
#include "sweep/sweep_impl.h"

/* A round of the lanes across paramsets is kept to whole rounds up to this
 * many members; beyond it (a sweep over many parameter values) a unit or
 * chunk holds whole points only, and lanes may run part empty. */
#define LANES_ROUND_MAX 256

int sweep_lanes_mode(void)
{
    const char *s = getenv("HAMLIE_SWEEP_BATCH");
    if (s != NULL && strcmp(s, "0") == 0)
        return SWEEP_LANES_OFF;
    if (s != NULL && strcmp(s, "1") == 0)
        return SWEEP_LANES_ON;
    return SWEEP_LANES_AUTO;
}

int sweep_is_lie(const hl_sweep *sw, int scheme)
{
    return strcmp(sw->scheme[scheme], "lie") == 0;
}

int sweep_has_lie(const hl_sweep *sw)
{
    for (int i = 0; i < sw->nschemes; i++)
        if (sweep_is_lie(sw, i))
            return 1;
    return 0;
}

int sweep_in_lanes(const hl_sweep *sw, int scheme)
{
    /* --reference and --order make a fixed-step member's row of more than
     * its run at dt (a reference run beside it, a run at dt/2): lanes hold
     * only the run itself */
    return sweep_is_lie(sw, scheme) || (!sw->spec.reference && !sw->spec.order);
}

int sweep_has_lanes(const hl_sweep *sw)
{
    for (int i = 0; i < sw->nschemes; i++)
        if (sweep_in_lanes(sw, i))
            return 1;
    return 0;
}

static int same_key(sweep_where a, sweep_where b, int same_dt)
{
    return a.paramset == b.paramset && a.scheme == b.scheme && (!same_dt || a.dt == b.dt);
}

long sweep_lane_groups(const hl_sweep *sw, const long *list, long n,
                       int (*fits)(const hl_sweep *sw, sweep_where at), int same_dt, long *order,
                       long *start)
{
    /* taken[i]: list[i] already placed (or does not fit); a small unit's
     * members, so the quadratic scan costs nothing beside their runs */
    char *taken = calloc((size_t)n + 1, 1);
    long placed = 0, ngroups = 0;
    for (long i = 0; i < n; i++) {
        sweep_where at = sweep_locate(sw, list[i]);
        if (taken[i] || !fits(sw, at))
            continue;
        start[ngroups++] = placed;
        for (long j = i; j < n; j++) {
            if (taken[j])
                continue;
            sweep_where bt = sweep_locate(sw, list[j]);
            if (fits(sw, bt) && same_key(at, bt, same_dt)) {
                taken[j] = 1;
                order[placed++] = j;
            }
        }
    }
    start[ngroups] = placed;
    free(taken);
    return ngroups;
}

int sweep_lanes_width(const hl_sweep *sw)
{
    /* lie members run in SWEEP_LANES lanes, fixed-step ones in the
     * machine's (hl_run_fixed_batch: 8 with AVX-512); both powers of 2, so
     * the wider is a multiple of the other */
    int width = 1;
    for (int i = 0; i < sw->nschemes; i++) {
        int w = !sweep_in_lanes(sw, i) ? 1
                : sweep_is_lie(sw, i)  ? SWEEP_LANES
                                       : hl_tape_lanes_native();
        width = w > width ? w : width;
    }
    return width;
}

/* The lane members of a round of every group's lanes: width points of
 * each paramset (a group is one paramset's, and consecutive members run
 * through the paramsets before the next point), when that is a modest
 * number; else width points. */
static long lanes_round(const hl_sweep *sw)
{
    long per_point = 0;
    for (int i = 0; i < sw->nschemes; i++)
        per_point += sweep_in_lanes(sw, i) ? sw->ndts : 0;
    long round = (long)sweep_lanes_width(sw) * (per_point > 0 ? per_point : 1);
    return round * sw->nparamsets <= LANES_ROUND_MAX ? round * sw->nparamsets : round;
}

long sweep_lanes_unit(const hl_sweep *sw, long lane_members, int threads)
{
    /* a few units per thread, so that the threads end together; each a
     * whole number of rounds of the lanes: a group of B members takes
     * ceil(B / lanes) rounds, and a round's idle lanes cost as much as
     * busy ones (B = 4 in 8 lanes: twice the time per member) */
    long u = lane_members / ((long)threads * 4);
    long round = lanes_round(sw);
    long most = round > 64 ? round : 64 / round * round;
    u = (u + round - 1) / round * round;
    return u < round ? round : u > most ? most : u;
}

long hl_sweep_chunk_quantum(const hl_sweep *sw)
{
    long group = (long)sw->nschemes * sw->ndts;
    if (!sweep_has_lanes(sw) || sweep_lanes_mode() == SWEEP_LANES_OFF)
        return group;
    long points = sweep_lanes_width(sw);
    if (group * points * sw->nparamsets <= LANES_ROUND_MAX)
        points *= sw->nparamsets;
    return group * points;
}
