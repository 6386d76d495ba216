/* Internal to src/run/. */
#ifndef HAMLIE_RUN_IMPL_H
#define HAMLIE_RUN_IMPL_H

#include "hamlie/flow.h"
#include "hamlie/run.h"

struct hl_run {
    hl_system *sys;
    int N;
    const hl_scheme *scheme;    /* borrowed; NULL for the adaptive run */
    hl_scheme_stepper *stepper; /* NULL for the adaptive run */
    hl_run_step_fn step;        /* a caller's stepper instead (hl_run_new_stepper) */
    void *step_arg;
    double *zs;                 /* the state before a caller's step */
    const char **names;         /* q_1..q_N, p_1..p_N (borrowed from sys) */
    const hl_expr **outs;       /* H, then the observers */
    int nout;
    hl_tape *obs;               /* outs over names; rebuilt when stale */
    hl_tape *vf;                /* the Hamiltonian vector field, for the reference */
    int ref_on;
    int jit;                    /* compile obs to machine code for long runs */
    hl_tape *fused;             /* explicit step and H: z, D -> Z, H(z) (drive.c) */
    int fused_failed;           /* no fused tape for this scheme */
    int lanes;                  /* hl_run_set_lanes (0: the default) */
    hl_tape_iter_batch *lane_loop; /* the fused tape over lanes (batch.c), or NULL */
    long lanes_refused;         /* the most member-steps the cost model refused lanes (batch.c) */
    double ref_tol;
    double *z, *ref, *vals;     /* state, reference, H and observers */
    hl_progress_fn progress;    /* the caller's, or NULL (hl_run_set_progress) */
    void *progress_arg;
    hl_tape *ev_tape; /* the surface g (hl_run_event), or NULL */
    hl_event *ev;
    hl_run_crossing_fn ev_fn;
    void *ev_arg;
    long ev_stop;   /* stop after this many crossings (0: never) */
    int ev_stopped; /* the last run stopped so */
    double *ev_z;   /* 4 * 2N: z and f at the step's start, f at its end, a crossing */
    double ev_g;    /* g at the step's start */
};

/* hl_run_crossing_'s return when the run has its ev_stop crossings: not a
 * status (the run then returns HL_OK). */
#define HL_RUN_EV_STOP 0x4556

const hl_expr *hl_run_resolve_(hl_system *sys, const hl_expr *e);
/* A crossing at (t, z): counted in s, delivered; 0, the callback's
 * non-zero return, or HL_RUN_EV_STOP. */
int hl_run_crossing_(hl_run *r, double t, const double *z, hl_run_stats *s);
/* The crossings of the fixed step k-1 -> k (r->z is z_k); k = 0 starts. */
int hl_run_event_step_(hl_run *r, long k, double dt, hl_run_stats *s);

int hl_run_compile_(hl_run *r, hl_error *err);

/* The fused tape z, D -> Z, H(z) of an explicit scheme (drive.c), built on
 * first use; NULL for an implicit scheme, a caller's stepper or the
 * adaptive run. */
hl_tape *hl_run_fused_(hl_run *r);

/* The caller's progress callback when `done` steps (or output rows; a
 * fraction between two rows) have reached *next, then *next = done +
 * spacing; HL_ESTOP (with the step, n and t in the message) when it asks to
 * stop. */
int hl_run_progress_(hl_run *r, double *next, double spacing, double done, long n, double t,
                     hl_error *err);

#endif
