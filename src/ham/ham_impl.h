/* Internal layout of hl_system (src/ham only). */
#ifndef HAMLIE_HAM_IMPL_H
#define HAMLIE_HAM_IMPL_H

#include "hamlie/ham.h"

/* A parameter given a value with --param: its name and constant value. */
typedef struct ham_setparam {
    char *name;
    const hl_expr *val;
} ham_setparam;

struct hl_system {
    char *step;          /* the step's name ("D" unless the spec says) */
    int n;               /* degrees of freedom */
    char **q, **p;       /* names of coordinates and momenta (n each) */
    int nparam;          /* symbolic parameters */
    char **param;
    int nset;            /* parameters with values */
    ham_setparam *set;
    hl_pool *pool;
    hl_alg_ctx *ctx;     /* base symbols q.., p.., params.., the step */
    int has_H;
    hl_alg H;
    const hl_expr *H_expr; /* terms ordered (hl_expr_ordered), set parameters substituted */
    int have_field;      /* xi, eta computed (lazily, by ham_field) */
    hl_alg *xi, *eta;
};

/* The generator's components xi = dH/dp, eta = -dH/dq, computed once. */
int ham_field(hl_system *sys, hl_error *err);

/* Read an already parsed expression of this system: check its symbols
 * (positions are looked up in src from offset on), substitute H and the set
 * parameters, convert. */
/* Substitute into each named image of a map the images named before it,
 * by the names written on their left sides (read.c; for inferring the
 * system's symbols from a map). */
void ham_chain_images(hl_eqn *items, int n, hl_pool *pool);

int ham_read_expr(hl_alg *out, hl_system *sys, const hl_expr *e, const char *src,
                  int offset, hl_error *err);

/* The error for the step's name found in a formula that cannot hold it
 * (what: "the Hamiltonian", "a function of the phase variables"). */
int ham_step_refused(const hl_system *sys, const char *src, int offset, const char *what,
                     hl_error *err);

#endif
