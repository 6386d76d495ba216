/* The Taylor-ODE recursion of several members at once (tape.h,
 * hl_tape_batch): jit_taylor.c's emitter with every value a vector of
 * lanes doubles, compiled through the disk cache; lane by lane through
 * hl_tape_taylor_ode_d where it cannot be compiled (the same bits). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "tape/tape_impl.h"

struct hl_tape_batch {
    hl_tape *t;
    int order, lanes, n;
    double *z;             /* n * (order+1) * lanes, aligned (tape.h) */
    void *code;            /* the compiled recursion, or NULL */
    void (*fn)(double *R); /* and its entry */
    double *one;           /* n * (order+1): one lane, for the interpreter */
};

static int power_of_two(int x)
{
    return x > 0 && (x & (x - 1)) == 0;
}

/* as emit_c.c's limit: a larger program takes too long to compile */
static int too_large(const hl_tape *t, int order)
{
    return (double)t->ncode * (order + 1) * (order + 1) / 2 > 4e6;
}

hl_status hl_tape_batch_new(hl_tape_batch **out, hl_tape *t, int order, int lanes, hl_error *err)
{
    *out = NULL;
    if (t->nin != t->nout || t->nin == 0)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "a batch needs a tape with as many outputs as inputs (%d inputs, %d "
                            "outputs)",
                            t->nin, t->nout);
    if (!power_of_two(lanes) || lanes > HL_TAPE_BATCH_MAX_LANES)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "lanes must be a power of 2 from 1 to %d (not %d)",
                            HL_TAPE_BATCH_MAX_LANES, lanes);
    if (order < 0 || order > 100000)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "Taylor order %d out of range", order);
    hl_tape_batch *b = hl_xcalloc(1, sizeof *b);
    b->t = t;
    b->order = order;
    b->lanes = lanes;
    b->n = t->nin;
    size_t nz = (size_t)b->n * (size_t)(order + 1) * (size_t)lanes;
    /* a vector of lanes doubles is aligned to its size */
    size_t align = (size_t)lanes * sizeof(double) < 16 ? 16 : (size_t)lanes * sizeof(double);
    b->z = aligned_alloc(align, (nz * sizeof(double) + align - 1) / align * align);
    if (b->z == NULL) { /* as hl_xmalloc: allocation failure aborts */
        fprintf(stderr, "hamlie: out of memory (%zu bytes)\n", nz * sizeof(double));
        abort();
    }
    memset(b->z, 0, nz * sizeof(double));
    b->one = hl_xcalloc((size_t)b->n * (size_t)(order + 1), sizeof *b->one);
    if (hl_tape_jit_available() && !too_large(t, order) &&
        hl_tape_jit_taylor_lanes(&b->code, &b->fn, t, order, lanes, NULL) != HL_OK) {
        b->code = NULL;
        b->fn = NULL;
    }
    *out = b;
    return HL_OK;
}

void hl_tape_batch_free(hl_tape_batch *b)
{
    if (b == NULL)
        return;
    if (b->code != NULL)
        hl_tape_jit_release(b->code);
    free(b->z);
    free(b->one);
    free(b);
}

int hl_tape_batch_lanes(const hl_tape_batch *b)
{
    return b->lanes;
}
int hl_tape_batch_order(const hl_tape_batch *b)
{
    return b->order;
}
int hl_tape_batch_compiled(const hl_tape_batch *b)
{
    return b->fn != NULL;
}
double *hl_tape_batch_coefs(hl_tape_batch *b)
{
    return b->z;
}

/* lane l through the interpreter: gathered, run, scattered back */
static void ode_lane(hl_tape_batch *b, int l)
{
    const int S = b->order + 1, L = b->lanes;
    for (int i = 0; i < b->n; i++)
        b->one[(size_t)i * S] = b->z[(size_t)i * S * L + l];
    hl_tape_taylor_ode_d(b->one, b->order, b->t, NULL); /* square: cannot fail */
    for (int i = 0; i < b->n; i++)
        for (int k = 1; k < S; k++)
            b->z[((size_t)i * S + k) * L + l] = b->one[(size_t)i * S + k];
}

void hl_tape_batch_ode(hl_tape_batch *b)
{
    if (b->fn != NULL) {
        b->fn(b->z);
        return;
    }
    for (int l = 0; l < b->lanes; l++)
        ode_lane(b, l);
}
