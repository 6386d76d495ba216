/* What the files of src/sweep share: the sweep object as read from its spec
 * (spec.c), the members' points (points.c), one member run (member.c) and
 * the writers (write.c, sweep_h5.c). */
#ifndef HAMLIE_SWEEP_IMPL_H
#define HAMLIE_SWEEP_IMPL_H

#include <stdint.h>

#include "hamlie/chaos.h"
#include "hamlie/ham.h"
#include "hamlie/run.h"
#include "hamlie/scheme.h"
#include "hamlie/sweep.h"

/* Where the points come from. */
typedef enum sweep_source { SWEEP_GRID, SWEEP_CSV, SWEEP_RANDOM } sweep_source;

/* One variable's values in a grid ("q=-3:3:200,1": the values of its
 * ranges and numbers in turn), or its bounds in random points (v[0], v[1]
 * for a:b; n = 1 for a fixed value).  Axes are in the order the text names
 * them: the first varies slowest. */
typedef struct sweep_axis {
    int var; /* 0..2N-1 */
    double *v;
    long n;
} sweep_axis;

/* A parameter crossed: its name and values. */
typedef struct sweep_param {
    char *name;
    double *v;
    long n;
} sweep_param;

struct hl_sweep {
    hl_sweep_spec spec; /* its strings are the sweep's own copies */
    int N;              /* degrees of freedom */
    char **var;         /* 2N names: q_1..q_N, p_1..p_N */
    sweep_source source;
    sweep_axis *axis;   /* 2N (grid and random) */
    double *csv_points; /* npoints * 2N (CSV) */
    long npoints;
    sweep_param *param;
    int nparam;
    long nparamsets;
    char **scheme; /* catalog names; "lie" is the adaptive integrator */
    int nschemes;
    double *dt;
    int ndts;
    long count; /* members */
    int ncols;
    char **col; /* column names */
    /* the column index of the first of each block (hl_sweep.h's order) */
    int c_param, c_z0, c_t, c_order, c_megno, c_z;
    uint64_t fingerprint;
    int has_array[HL_SWEEP_NARRAYS]; /* spec.save_every > 0, spec.event != NULL */
};

/* Fixed column indices. */
enum { SWEEP_C_MEMBER, SWEEP_C_POINT, SWEEP_C_PARAMSET, SWEEP_C_SCHEME, SWEEP_C_DT };

/* A member's place: m = ((point * nparamsets + paramset) * nschemes + scheme) * ndts + dt. */
typedef struct sweep_where {
    long point, paramset;
    int scheme, dt;
} sweep_where;
sweep_where sweep_locate(const hl_sweep *sw, long member);

/* The text of paramset k's values ("k=1,eps=0.25", exact doubles) for
 * hl_system_spec.params: the spec's fixed ones are not crossed, so all
 * parameters are named here.  Caller frees.  NULL when there are none. */
char *sweep_paramset_text(const hl_sweep *sw, long paramset);
/* The system with paramset's values (-1: parameters left symbolic). */
hl_status sweep_system(hl_system **sys, const hl_sweep *sw, long paramset, hl_error *err);
double sweep_param_value(const hl_sweep *sw, long paramset, int i);

/* points.c: the start z (2N) of point i; a pure function of (spec, i). */
void sweep_point(const hl_sweep *sw, long i, double *z);
/* Reads the grid / random bounds into sw->axis and counts the points; or
 * the CSV into sw->csv_points.  Errors point into the field's text. */
hl_status sweep_read_grid(hl_sweep *sw, const char *text, hl_error *err);
hl_status sweep_read_random(hl_sweep *sw, const char *text, hl_error *err);
/* Appends to ax a number or the n values of a range a:b:n at [a, a+len). */
hl_status sweep_axis_values(sweep_axis *ax, const char *text, int a, int len, const char *what,
                            hl_error *err);
hl_status sweep_read_csv(hl_sweep *sw, const char *text, hl_error *err);
uint64_t sweep_splitmix64(uint64_t x);

/* The parsed items of a "name=v,v,name=a:b:n" text (spec.c) */
typedef struct sweep_item {
    int name, name_len; /* byte span of the name */
    int nval;
    int *val, *val_len; /* byte spans of each value */
} sweep_item;
hl_status sweep_items(sweep_item **items, int *n, const char *text, const char *what,
                      hl_error *err);
void sweep_items_free(sweep_item *items, int n);
/* A finite number in [pos, pos+len) of text. */
hl_status sweep_number(double *v, const char *text, int pos, int len, const char *what,
                       hl_error *err);

/* member.c: what one thread holds to run members (a system, the schemes'
 * runs and a chaos object per paramset, built when first needed). */
typedef struct sweep_worker sweep_worker;
sweep_worker *sweep_worker_new(const hl_sweep *sw);
void sweep_worker_free(sweep_worker *w);
/* Runs member m into row (ncols values), its status and reason (the
 * chaos columns of (point, paramset) are kept for the group's members).
 * Returns 1 if sweep_worker_prepare had run it in lanes, else 0. */
int sweep_member(sweep_worker *w, long m, double *row, hl_status *status, char *reason);

/* Runs the members among list[0..n-1] (a work unit) that may share SIMD
 * lanes (lanes.c: lie members, and fixed-step ones without --reference or
 * --order) in lanes where that pays, keeping their rows for sweep_member. */
typedef void sweep_ran_fn(long members, void *arg);
/* ran (may be NULL) is told, after each group that ran in lanes, how many
 * members it ran: the progress line moves as they run, not a unit at a
 * time. */
void sweep_worker_prepare(sweep_worker *w, const long *list, long n, sweep_ran_fn *ran,
                          void *ran_arg);
/* The members this process has run in lanes (tests): lie members in
 * lanes, fixed-step ones in a batch whose compiled loop runs lanes. */
long sweep_lanes_members(void);

/* lanes.c: which members share SIMD lanes.  HAMLIE_SWEEP_BATCH=0 never,
 * =1 always (where they can: the same rows either way), else where the
 * cost model says they pay. */
enum { SWEEP_LANES_OFF, SWEEP_LANES_ON, SWEEP_LANES_AUTO };
#define SWEEP_LANES 4 /* AVX2's 4 doubles (8 lanes gained 6% more, bench/taylor_batch.sh) */
int sweep_lanes_mode(void);
int sweep_is_lie(const hl_sweep *sw, int scheme);
int sweep_has_lie(const hl_sweep *sw);
/* 1 if the scheme's members may run in lanes: lie ones, and fixed-step
 * ones when the sweep has neither --reference nor --order. */
int sweep_in_lanes(const hl_sweep *sw, int scheme);
int sweep_has_lanes(const hl_sweep *sw);
/* The members of list[0..n-1] that fit (fits), in groups of one paramset
 * and scheme (and dt if same_dt), each in list order: order[] their
 * positions in list, group after group, start[g] group g's first (start
 * has ngroups + 1 entries; both hold n + 1).  Returns ngroups. */
long sweep_lane_groups(const hl_sweep *sw, const long *list, long n,
                       int (*fits)(const hl_sweep *sw, sweep_where at), int same_dt, long *order,
                       long *start);
/* The points of one round of the widest lanes the sweep's members use
 * (1 if none may). */
int sweep_lanes_width(const hl_sweep *sw);
/* How many members that may run in lanes a work unit should hold: a
 * multiple of a round of the lanes, so that they run full. */
long sweep_lanes_unit(const hl_sweep *sw, long lane_members, int threads);
/* arrays.c: a thread's collector of one member's arrays (sweep.h,
 * "Arrays"): the trajectory rows of its run's callback and the crossings
 * of the run's event, while on (the runs for the order at dt/2 give none). */
typedef struct sweep_arrays {
    const hl_sweep *sw;
    int on;
    double *v[HL_SWEEP_NARRAYS];
    long n[HL_SWEEP_NARRAYS], cap[HL_SWEEP_NARRAYS]; /* rows */
} sweep_arrays;
void sweep_arrays_init(sweep_arrays *a, const hl_sweep *sw);
void sweep_arrays_clear(sweep_arrays *a);
/* The event of spec.event on run (a no-op without one), its crossings to a. */
hl_status sweep_arrays_attach(sweep_arrays *a, hl_run *run, hl_error *err);
/* Collecting from an empty start / no more. */
void sweep_arrays_begin(sweep_arrays *a);
void sweep_arrays_end(sweep_arrays *a);
/* What the run's driver takes for the trajectory: the callback (NULL
 * without save_every; its arg is a) and the row spacing. */
hl_run_fn sweep_arrays_row_fn(const hl_sweep *sw);
long sweep_arrays_every(const hl_sweep *sw);
/* r's arrays: a's (valid until the next begin). */
void sweep_arrays_result(const sweep_arrays *a, hl_sweep_result *r);
/* member.c: the arrays of the member w ran last, into r. */
void sweep_member_arrays(const sweep_worker *w, hl_sweep_result *r);
/* spec.c: checks the event's text on sys (errors point into it). */
hl_status sweep_check_event(const hl_sweep *sw, hl_system *sys, hl_error *err);

/* write.c / sweep_h5.c */
hl_status sweep_write_csv(const hl_sweep *sw, const hl_sweep_table *tab, const char *path,
                          hl_error *err);
hl_status hl_sweep_write_h5(const hl_sweep *sw, const hl_sweep_table *tab, const char *path,
                            hl_error *err);

#endif
