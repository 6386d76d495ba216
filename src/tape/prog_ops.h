/* The layout of a recorded program, shared by the recorder (prog.c) and the
 * loop that runs it (prog_run.c); nothing outside those two files reads it.
 * See prog_impl.h for why the double interpreter records. */
#ifndef HAMLIE_TAPE_PROG_OPS_H
#define HAMLIE_TAPE_PROG_OPS_H

#include "tape/prog_impl.h"

typedef enum mcode {
    M_MOV,
    M_NEG,
    M_ADD,
    M_SUB,
    M_MUL,
    M_DIV,
    M_FMA,
    M_CALL,
    M_SINCOS,
    M_CONV, /* while recording; a program runs M_CONV + the convolution's kind */
    M_CONV_TABLE,
    M_CONV_WEIGHTED,
    M_CONV_PAIR,  /* a tabled convolution and its partner's known sum */
    M_CONV_LANES, /* a partner: its known sum is done already */
    M_CONV_BARE,  /* M_CONV_PLAIN, M_CONV_TABLE without post-operations */
    M_CONV_TABLE_BARE,
    M_ODE,     /* a plain run (hl_prog_run) ends here; an ODE run goes on */
    M_DIVIDE,  /* *d = fma(*a, *b, *a * *c): the ODE step f/(k+1), b + c = 1/(k+1) */
    M_DIVIDE2, /* the same for two outputs: *d from *a, d[arg] from *c; hi, lo = b[0], b[1] */
    M_END      /* closes the program of each coefficient */
} mcode;

/* How a convolution's known terms read: x[j] y[k-j], or (w[j] x[j]) y[k-j]
 * with w from a table (weights known when recording: integers, a^c's
 * (c+1) j - k, a square's 2 for a pair and 1 for the middle term
 * x[k/2] x[k/2], which (1 x) x gives bit for bit), or with w = wa j + wb of
 * values of the run.  In the order of the M_CONV codes. */
enum { CV_PLAIN, CV_TABLE, CV_WEIGHTED };

typedef struct mconv mconv;

/* A micro-operation: *d = a op b (op c); M_CALL: arg is the hl_pfn;
 * M_SINCOS: *d = sin a, *c = cos a (glibc's sincos gives sin's and cos's
 * bits); M_CONV: *d = the convolution m (cv[arg] while recording).  go: the
 * address of code's handler in the loop that runs the program (threaded
 * code: a step is one indirect jump, no table).
 *
 * A convolution's op also holds where its known terms start, so that
 * their loads are two deep (op, data), as in the old switch, not four
 * (op, index, field, data): the loop's time goes into such chains of
 * dependent loads (bench/taylor_interp.c: each level fewer took 5-8 % per
 * call on all three systems).  Then arg is the number of known terms (<= 0
 * for none), a = x + jh - 3 and c = w + jh - 3 (the first four x[j] and
 * w[j], j = jh down), b = y + k - jh (their y[k-j]); the known sum walks a
 * and c down, b up. */
typedef struct mop {
    const void *go;
    int code, arg;
    double *d;
    const double *a, *b, *c;
    mconv *m;
} mop;

/* A fresh term (rule.h): (w *p) *q, w its weight (1 for a plain term: 1 p is
 * p exactly, so the bits agree and the loop has one branch less).  For
 * CV_WEIGHTED, w is computed again with the table. */
typedef struct fresh {
    const double *p, *q;
    long lp, lq; /* while recording */
    int j;
    double w;
} fresh;

/* An operation on a convolution's sum right after it (a product by 1/k, a
 * subtraction from a[k], ...), run in the same micro-operation: s = s op *b
 * (P_RSUB: *b - s), written to *d. */
enum { P_ADD = 1, P_SUB, P_RSUB, P_MUL, P_NEG, P_N };
typedef struct post {
    int code;
    const double *b;
    double *d;
    long lb, ld; /* while recording */
} post;
#define NPOST 4

/* A convolution: the known terms j = jl..jh (none when jh < jl) summed in
 * four lanes, then the fresh terms. */
struct mconv {
    const double *x, *y, *wa, *wb;
    double *w; /* CV_TABLE, CV_WEIGHTED: w[j] for j = jl..jh */
    int kind, k, jl, jh, nf;
    fresh f[2];
    int npost, shape; /* shape: 0 without posts, code0 for one, code0 + P_N code1 for more */
    post post[NPOST];
    /* Two convolutions of one rule call over the same x, weights and range
     * (sin's and cos's, say) read w[j] x[j] once: the first one sums the
     * known terms of both and leaves the second's sum in its known (the
     * known terms read no coefficient k, which is all a rule call writes,
     * so summing them early changes no bit).  partner: the second's index
     * + 1 in the first, 0 otherwise; known_done in the second. */
    int partner, known_done;
    mconv *second;   /* the partner itself (cv[partner - 1]), for the run */
    const double *z; /* the partner's y + k - jh (mop) */
    double known;
    /* CV_WEIGHTED: wa, wb are values of the run, the same at every step of
     * a flow; w[j] = wa j + wb is computed again only when their bits
     * differ from the ones w was computed for (wa_w, wb_w). */
    int w_valid;
    double wa_w, wb_w;
    long lx, ly, lwa, lwb, lw; /* while recording (lw: w's offset in the table) */
};

struct hl_prog {
    /* this processor's loop: the programs of k .. kend - 1; ode: go on past M_ODE */
    void (*run)(const hl_prog *p, int k, int kend, int ode, const void *const **labels);
    mop *op;
    int nop;
    int *start; /* the program of coefficient k is op[start[k] ..], up to its M_END */
    int nk;
    mconv *cv;
    double *mem; /* constants, temporaries, kept values */
    double *wts; /* the convolutions' weights */
};

/* Choose the loop for this processor and point each op at its handler
 * (prog_run.c); after the ops are final. */
void hl_prog_bind(hl_prog *p);

#endif /* HAMLIE_TAPE_PROG_OPS_H */
