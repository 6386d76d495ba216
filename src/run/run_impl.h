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
    double ref_tol;
    double *z, *ref, *vals;     /* state, reference, H and observers */
    hl_progress_fn progress;    /* the caller's, or NULL (hl_run_set_progress) */
    void *progress_arg;
};

int hl_run_compile_(hl_run *r, hl_error *err);

/* The caller's progress callback when `done` steps (or output rows; a
 * fraction between two rows) have reached *next, then *next = done +
 * spacing; HL_ESTOP (with the step, n and t in the message) when it asks to
 * stop. */
int hl_run_progress_(hl_run *r, double *next, double spacing, double done, long n, double t,
                     hl_error *err);

#endif
