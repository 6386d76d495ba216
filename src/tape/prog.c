/* The double interpreter: the rules recorded into flat programs, and the
 * loop that runs them (see prog_impl.h for why it records).
 *
 * While recording, a value is a location: a coefficient in the register
 * file, a constant, a temporary of the current rule call, or a kept value
 * of the current instruction, written as index * 4 + space.  Locations
 * become pointers when the program is finished.  A value stored (or kept)
 * right after the operation that made it is written there directly by that
 * operation, so most stores cost nothing.
 *
 * Over 800 lines for a reason: the recorder's choices (a convolution's
 * kind, its pairing, its post-operations) and the loop that runs them share
 * one private micro-op layout; split, that layout would become a header
 * every change touches twice. */
#define _GNU_SOURCE /* sincos */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "rules/rule.h"
#include "tape/prog_impl.h"

enum { SP_REG, SP_CONST, SP_TEMP, SP_KEEP };
#define LOC(space, index) ((long)(index)*4 + (space))
#define LOC_SPACE(l) ((int)((l)&3))
#define LOC_INDEX(l) ((l) >> 2)

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
    M_CONV_WEIGHTED,
    M_CONV_INTW,
    M_CONV_SYM,
    M_CONV_PAIR,  /* an integer-weighted convolution and its partner's lanes */
    M_CONV_LANES, /* a partner: its lanes are summed already */
    M_END
} mcode;

/* A micro-operation: *d = a op b (op c); M_CALL: arg is the hl_pfn;
 * M_SINCOS: *d = sin a, *c = cos a (glibc's sincos gives sin's and cos's
 * bits); M_CONV: *d = the convolution cv[arg]. */
typedef struct mop {
    int code, arg;
    double *d;
    const double *a, *b, *c;
} mop;

/* The same while recording, with locations. */
typedef struct rop {
    int code, arg;
    long d, a, b, c;
} rop;

/* How a convolution's terms read: x[j] y[k-j], (w x[j]) y[k-j], or a
 * square's pairs (2 x[j]) x[k-j].  In the order of the M_CONV codes. */
enum { CV_PLAIN, CV_WEIGHTED, CV_INTW, CV_SYM };

/* A fresh term (rule.h): (w *p) *q, w a constant (F_CONST) or wa j + wb
 * of the run (F_RUN).  A plain term p q is a constant one with w = 1 (1 p
 * is p exactly, so the bits agree and the loop has one branch less). */
enum { F_CONST, F_RUN };
typedef struct fresh {
    const double *p, *q;
    long lp, lq; /* while recording */
    int how, j;
    double w;
} fresh;

/* A convolution: the known terms j = jl..jh (pairs when CV_SYM) in four
 * lanes, the middle term x[k/2]^2 after them when mid, then the fresh
 * terms. */
/* An operation on a convolution's sum right after it (a product by 1/k, a
 * subtraction from a[k], ...), run in the same micro-operation: s = s op *b
 * (or *b - s when rev), written to *d. */
typedef struct post {
    int code, rev;
    const double *b;
    double *d;
    long lb, ld; /* while recording */
} post;
#define NPOST 4

typedef struct mconv {
    const double *x, *y, *wa, *wb;
    int npost;
    post post[NPOST];
    long lx, ly, lwa, lwb; /* while recording */
    int kind, k, jl, jh, mid, nf;
    int npair; /* the known terms before the middle one: max(jh - jl + 1, 0) */
    /* Two convolutions of one rule call over the same x, weights and range
     * (sin's and cos's, say) read w[j] x[j] once: the first one's loop sums
     * the known terms of both, and leaves the second's lanes in its lane[]
     * (the known terms read no coefficient k, which is all a rule call
     * writes, so summing them early changes no bit).  partner: the second's
     * index + 1 in the first, 0 otherwise; lanes_done in the second. */
    int partner, lanes_done;
    double lane[4];
    long ia, ib; /* CV_INTW: the weights wa, wb are these small integers, */
    double *w;   /* and w[j] = ia j + ib for j = jl..jh */
    long lw;     /* while recording: w's offset in the table of weights */
    /* CV_WEIGHTED: wa, wb are values of the run (a^c's c + 1), the same at
     * every step of a flow; w[j] = wa j + wb is computed again only when
     * their bits differ from the ones w was computed for (wa_w, wb_w). */
    int w_valid;
    double wa_w, wb_w;
    fresh f[2];
} mconv;

struct hl_prog {
    mop *op;
    int *start; /* the program of coefficient k is op[start[k] .. start[k+1]) */
    int nk;
    mconv *cv;
    double *mem; /* constants, temporaries, kept values */
    double *wts; /* the convolutions' integer weights */
};

/* ---- recording ----------------------------------------------------------- */

typedef struct rec {
    hl_em em;
    long base[HL_SLOT_COUNT]; /* the register of each slot (index of coefficient 0) */
    int instr, first_op;      /* the instruction being recorded, its first op */
    long *tloc;               /* where each temporary of this rule call lives */
    int ntemp, tcap, maxtemp;
    rop *ops;
    int nops, opcap;
    mconv *cv;
    int ncv, cvcap;
    double *consts;
    int nconst, constcap;
    double *wts; /* the integer weights of the convolutions */
    long nwts, wcap;
} rec;

static rec *rec_of(hl_em *e)
{
    return (rec *)e;
}
static hl_ev ev_loc(long l)
{
    hl_ev v;
    v.i = l;
    return v;
}

/* the location a value reads from now (a temporary may have moved) */
static long where(const rec *r, hl_ev v)
{
    return LOC_SPACE(v.i) == SP_TEMP ? r->tloc[LOC_INDEX(v.i)] : v.i;
}

static long new_temp(rec *r)
{
    if (r->ntemp == r->tcap) {
        r->tcap = r->tcap ? 2 * r->tcap : 16;
        r->tloc = hl_xrealloc(r->tloc, (size_t)r->tcap * sizeof *r->tloc);
    }
    long l = LOC(SP_TEMP, r->ntemp);
    r->tloc[r->ntemp++] = l;
    if (r->ntemp > r->maxtemp)
        r->maxtemp = r->ntemp;
    return l;
}

static rop *emit(rec *r, int code, int arg, long a, long b, long c)
{
    if (r->nops == r->opcap) {
        r->opcap = r->opcap ? 2 * r->opcap : 256;
        r->ops = hl_xrealloc(r->ops, (size_t)r->opcap * sizeof *r->ops);
    }
    rop *o = &r->ops[r->nops++];
    *o = (rop){code, arg, new_temp(r), a, b, c};
    return o;
}

static rop *last_op(rec *r)
{
    return r->nops > r->first_op ? &r->ops[r->nops - 1] : NULL;
}

/* Where the last convolution's value is now, if the last op is one. */
static long conv_value(rec *r, mconv **m)
{
    rop *last = last_op(r);
    if (last == NULL || last->code != M_CONV)
        return -1;
    *m = &r->cv[last->arg];
    return (*m)->npost ? (*m)->post[(*m)->npost - 1].ld : last->d;
}

/* a op b as a post-operation of the last convolution, when it reads its
 * value (saves a dispatch: the dominant cost of short rules) */
static long try_post(rec *r, int code, long a, long b)
{
    mconv *m;
    long s = conv_value(r, &m);
    if (s < 0 || m->npost == NPOST || (a != s && b != s))
        return -1;
    if (code != M_ADD && code != M_SUB && code != M_MUL && code != M_NEG)
        return -1;
    post *p = &m->post[m->npost++];
    p->code = code;
    p->rev = code == M_SUB && b == s && a != s;
    p->lb = a == s ? b : a;
    p->ld = new_temp(r);
    return p->ld;
}

static hl_ev emit_v(rec *r, int code, int arg, hl_ev a, hl_ev b, hl_ev c)
{
    long la = where(r, a), lb = where(r, b), l = try_post(r, code, la, lb);
    return ev_loc(l >= 0 ? l : emit(r, code, arg, la, lb, where(r, c))->d);
}

static hl_ev rec_num(hl_em *e, long p, long q)
{
    rec *r = rec_of(e);
    double v = (double)p / (double)q;
    for (int i = 0; i < r->nconst; i++)
        if (memcmp(&r->consts[i], &v, sizeof v) == 0)
            return ev_loc(LOC(SP_CONST, i));
    if (r->nconst == r->constcap) {
        r->constcap = r->constcap ? 2 * r->constcap : 32;
        r->consts = hl_xrealloc(r->consts, (size_t)r->constcap * sizeof *r->consts);
    }
    r->consts[r->nconst] = v;
    return ev_loc(LOC(SP_CONST, r->nconst++));
}

static hl_ev rec_coef(hl_em *e, hl_slot s, int j)
{
    return ev_loc(LOC(SP_REG, rec_of(e)->base[s] + j));
}

/* Write v to the location to: by retargeting the operation that made v
 * when it is the last one of this rule call, else by a move. */
static void put(rec *r, long to, hl_ev v)
{
    long id = LOC_SPACE(v.i) == SP_TEMP ? LOC_INDEX(v.i) : -1;
    rop *last = last_op(r);
    mconv *m;
    if (id >= 0 && r->tloc[id] == v.i && conv_value(r, &m) == v.i && m->npost > 0) {
        m->post[m->npost - 1].ld = to;
        r->tloc[id] = to;
        return;
    }
    if (id >= 0 && last && r->tloc[id] == v.i) {
        if (last->d == v.i) {
            last->d = to;
            r->tloc[id] = to;
            return;
        }
        if (last->code == M_SINCOS && last->c == v.i) {
            last->c = to;
            r->tloc[id] = to;
            return;
        }
    }
    emit(r, M_MOV, 0, where(r, v), 0, 0)->d = to;
}

static void rec_store(hl_em *e, hl_slot s, int j, hl_ev v)
{
    rec *r = rec_of(e);
    put(r, LOC(SP_REG, r->base[s] + j), v);
}

static hl_ev rec_add(hl_em *e, hl_ev a, hl_ev b)
{
    return emit_v(rec_of(e), M_ADD, 0, a, b, a);
}
static hl_ev rec_sub(hl_em *e, hl_ev a, hl_ev b)
{
    return emit_v(rec_of(e), M_SUB, 0, a, b, a);
}
static hl_ev rec_mul(hl_em *e, hl_ev a, hl_ev b)
{
    return emit_v(rec_of(e), M_MUL, 0, a, b, a);
}
static hl_ev rec_div(hl_em *e, hl_ev a, hl_ev b)
{
    return emit_v(rec_of(e), M_DIV, 0, a, b, a);
}
static hl_ev rec_neg(hl_em *e, hl_ev a)
{
    return emit_v(rec_of(e), M_NEG, 0, a, a, a);
}
static hl_ev rec_fma(hl_em *e, hl_ev a, hl_ev b, hl_ev c)
{
    return emit_v(rec_of(e), M_FMA, 0, a, b, c);
}

/* cos(a) right after sin(a) joins it: one sincos */
static hl_ev rec_call(hl_em *e, hl_pfn f, hl_ev a, hl_ev b)
{
    rec *r = rec_of(e);
    rop *last = r->nops > r->first_op ? &r->ops[r->nops - 1] : NULL;
    if (f == HL_PFN_COS && last && last->code == M_CALL && last->arg == HL_PFN_SIN &&
        last->a == where(r, a)) {
        last->code = M_SINCOS;
        last->c = new_temp(r);
        return ev_loc(last->c);
    }
    return emit_v(r, M_CALL, (int)f, a, b, a);
}

static void rec_keep(hl_em *e, int slot, hl_ev v)
{
    rec *r = rec_of(e);
    put(r, LOC(SP_KEEP, 2 * r->instr + slot), v);
}

static hl_ev rec_kept(hl_em *e, int slot)
{
    return ev_loc(LOC(SP_KEEP, 2 * rec_of(e)->instr + slot));
}

static mconv *new_conv(rec *r)
{
    if (r->ncv == r->cvcap) {
        r->cvcap = r->cvcap ? 2 * r->cvcap : 64;
        r->cv = hl_xrealloc(r->cv, (size_t)r->cvcap * sizeof *r->cv);
    }
    mconv *m = &r->cv[r->ncv++];
    memset(m, 0, sizeof *m);
    return m;
}

/* The plan of hl_conv_plan as a range of known terms (they are consecutive
 * j, the middle term of a square last) and the fresh terms. */
static void conv_shape(mconv *m, const hl_conv *c)
{
    int n = c->hi - c->lo + 1, nk, nf, fr[2];
    int *idx = hl_xmalloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    int *lane = hl_xmalloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    hl_conv_plan(c, idx, lane, &nk, fr, &nf);
    m->mid = c->sym && nk > 0 && 2 * idx[nk - 1] == c->k;
    int np = nk - m->mid;
    m->jl = np > 0 ? idx[0] : 1;
    m->jh = np > 0 ? idx[np - 1] : 0;
    m->nf = nf;
    m->npair = np > 0 ? np : 0;
    for (int i = 0; i < nf; i++)
        m->f[i].j = fr[i];
    free(idx);
    free(lane);
}

/* the value of a constant location, if it is a small integer */
static int small_int(const rec *r, long l, long *v)
{
    if (LOC_SPACE(l) != SP_CONST)
        return 0;
    double d = r->consts[LOC_INDEX(l)];
    *v = (long)d;
    return fabs(d) < 1048576 && d == (double)*v;
}

/* A weight known now: integer weights (every rule's but a^c's) are exact
 * in double, so w = wa j + wb is the integer ia j + ib, rounded as written. */
static void conv_weights(rec *r, mconv *m, const hl_conv *c)
{
    m->kind = c->sym ? CV_SYM : c->weighted ? CV_WEIGHTED : CV_PLAIN;
    if (!c->weighted)
        return;
    m->lwa = where(r, c->wa);
    m->lwb = where(r, c->wb);
    long n = m->jh - m->jl + 1 > 0 ? m->jh - m->jl + 1 : 0;
    if (r->nwts + n > r->wcap) {
        r->wcap = 2 * (r->nwts + n) + 64;
        r->wts = hl_xrealloc(r->wts, (size_t)r->wcap * sizeof *r->wts);
    }
    m->lw = r->nwts - m->jl; /* w[j] = wts[lw + j] */
    if (!small_int(r, m->lwa, &m->ia) || !small_int(r, m->lwb, &m->ib)) {
        r->nwts += n; /* filled by the run (conv_run_weights) */
        return;
    }
    m->kind = CV_INTW;
    for (long j = m->jl; j <= m->jh; j++)
        r->wts[r->nwts++] = (double)(m->ia * j + m->ib);
}

/* The fresh terms as rule.h writes them: a weighted x[k] term (w y[0]) x[k],
 * others (w x[j]) y[k-j]; a square's pair term has w = 2. */
static void conv_fresh(mconv *m, const hl_conv *c, long x, long y)
{
    int k = c->k;
    for (int i = 0; i < m->nf; i++) {
        fresh *f = &m->f[i];
        int j = f->j, x_side = j == k && k > 0;
        f->lp = x_side ? y : x + 4L * j;
        f->lq = x_side ? x + 4L * k : y + 4L * (k - j);
        f->how = c->weighted ? F_RUN : F_CONST;
        f->w = c->sym && 2 * j < k ? 2 : 1;
        if (m->kind == CV_INTW) {
            f->how = F_CONST;
            f->w = (double)(m->ia * j + m->ib);
        }
    }
}

static int same_known_terms(const mconv *a, const mconv *b)
{
    return a->kind == CV_INTW && b->kind == CV_INTW && a->lx == b->lx && a->ia == b->ia &&
           a->ib == b->ib && a->k == b->k && a->jl == b->jl && a->jh == b->jh && !a->mid &&
           !b->mid && a->npair > 0;
}

/* Make convolution i the partner of an earlier one of this rule call that
 * shares its known terms' x and weights (see mconv). */
static void pair_up(rec *r, int i)
{
    for (int o = r->first_op; o < r->nops; o++) {
        if (r->ops[o].code != M_CONV)
            continue;
        mconv *first = &r->cv[r->ops[o].arg];
        if (first->partner == 0 && !first->lanes_done && same_known_terms(first, &r->cv[i])) {
            first->partner = i + 1;
            r->cv[i].lanes_done = 1;
            return;
        }
    }
}

static hl_ev rec_conv(hl_em *e, const hl_conv *c, int *has)
{
    rec *r = rec_of(e);
    mconv tmp;
    memset(&tmp, 0, sizeof tmp);
    conv_shape(&tmp, c);
    *has = tmp.jh >= tmp.jl || tmp.mid || tmp.nf > 0;
    if (!*has)
        return rec_num(e, 0, 1);
    mconv *m = new_conv(r);
    *m = tmp;
    m->k = c->k;
    m->lx = LOC(SP_REG, r->base[c->x]);
    m->ly = LOC(SP_REG, r->base[c->y]);
    m->lwa = m->lwb = -1;
    conv_weights(r, m, c);
    conv_fresh(m, c, m->lx, m->ly);
    pair_up(r, r->ncv - 1);
    return ev_loc(emit(r, M_CONV, r->ncv - 1, 0, 0, 0)->d);
}

static const hl_em_ops rec_ops = {rec_num,  rec_coef, rec_store, rec_add, rec_sub,
                                  rec_mul,  rec_neg,  rec_div,   rec_fma, rec_call,
                                  rec_conv, rec_keep, rec_kept};

/* Point the slots at instruction i's registers (stride S). */
static void rec_enter(rec *r, const hl_instr *in, int i, int S)
{
    r->instr = i;
    r->first_op = r->nops;
    r->ntemp = 0;
    r->base[HL_SLOT_D] = (long)in->d * S;
    r->base[HL_SLOT_A] = (long)in->a * S;
    r->base[HL_SLOT_B] = in->b >= 0 ? (long)in->b * S : 0;
    r->base[HL_SLOT_X] = in->x >= 0 ? (long)in->x * S : 0;
}

/* ---- finishing: locations to pointers ------------------------------------- */

typedef struct spaces {
    double *reg, *mem;
    int temp0, keep0; /* where temporaries and kept values start in mem */
} spaces;

static double *at(const spaces *s, long l)
{
    switch (LOC_SPACE(l)) {
    case SP_REG:
        return s->reg + LOC_INDEX(l);
    case SP_CONST:
        return s->mem + LOC_INDEX(l);
    case SP_TEMP:
        return s->mem + s->temp0 + LOC_INDEX(l);
    default:
        return s->mem + s->keep0 + LOC_INDEX(l);
    }
}

static int conv_code(const mconv *m)
{
    return m->partner ? M_CONV_PAIR : m->lanes_done ? M_CONV_LANES : M_CONV + m->kind;
}

static hl_prog *finish(rec *r, double *reg, int ncode, int *start, int nk)
{
    hl_prog *p = hl_xcalloc(1, sizeof *p);
    spaces s = {reg, NULL, r->nconst, r->nconst + r->maxtemp};
    p->mem = hl_xcalloc((size_t)s.keep0 + 2 * (size_t)ncode + 1, sizeof *p->mem);
    s.mem = p->mem;
    if (r->nconst > 0) /* consts is NULL when there are none */
        memcpy(p->mem, r->consts, (size_t)r->nconst * sizeof *p->mem);
    p->op = hl_xmalloc(((size_t)r->nops + 1) * sizeof *p->op);
    for (int i = 0; i < r->nops; i++) {
        const rop *o = &r->ops[i];
        int code = o->code == M_CONV ? conv_code(&r->cv[o->arg]) : o->code;
        p->op[i] = (mop){code, o->arg, at(&s, o->d), at(&s, o->a), at(&s, o->b), at(&s, o->c)};
    }
    p->cv = r->cv;
    p->wts = r->wts ? r->wts : hl_xmalloc(1);
    for (int i = 0; i < r->ncv; i++) {
        mconv *m = &p->cv[i];
        m->w = p->wts + m->lw;
        m->x = at(&s, m->lx);
        m->y = at(&s, m->ly);
        m->wa = m->lwa >= 0 ? at(&s, m->lwa) : NULL;
        m->wb = m->lwb >= 0 ? at(&s, m->lwb) : NULL;
        for (int j = 0; j < m->npost; j++) {
            m->post[j].b = at(&s, m->post[j].lb);
            m->post[j].d = at(&s, m->post[j].ld);
        }
        for (int j = 0; j < m->nf; j++) {
            m->f[j].p = at(&s, m->f[j].lp);
            m->f[j].q = at(&s, m->f[j].lq);
        }
    }
    p->start = start;
    p->nk = nk;
    free(r->ops);
    free(r->consts);
    free(r->tloc);
    return p;
}

static void rec_init(rec *r)
{
    memset(r, 0, sizeof *r);
    r->em.ops = &rec_ops;
}

hl_prog *hl_prog_taylor(const hl_tape *t, double *td, int order)
{
    rec r;
    rec_init(&r);
    int S = order + 1, *start = hl_xmalloc(((size_t)S + 1) * sizeof *start);
    for (int k = 0; k <= order; k++) {
        start[k] = r.nops;
        for (int i = 0; i < t->ncode; i++) {
            rec_enter(&r, &t->code[i], i, S);
            hl_rule_of((hl_op)t->code[i].op)->taylor(&r.em, k);
        }
    }
    start[S] = r.nops;
    return finish(&r, td, t->ncode, start, S);
}

hl_prog *hl_prog_point(const hl_tape *t, double *reg)
{
    rec r;
    rec_init(&r);
    int *start = hl_xmalloc(2 * sizeof *start);
    start[0] = 0;
    for (int i = 0; i < t->ncode; i++) {
        rec_enter(&r, &t->code[i], i, 1);
        hl_rule_of((hl_op)t->code[i].op)->point(&r.em);
    }
    start[1] = r.nops;
    return finish(&r, reg, t->ncode, start, 1);
}

void hl_prog_free(hl_prog *p)
{
    if (p == NULL)
        return;
    free(p->op);
    free(p->start);
    free(p->cv);
    free(p->mem);
    free(p->wts);
    free(p);
}

/* ---- running ---------------------------------------------------------------- */


/* The known terms j = jl..jh into lanes l0..l3 by position, each lane
 * starting with its first term (0 + t would turn a -0 into +0). */
#define LANES(TERM) LANES_BY(SET1, ADD1, TERM)
#define SET1(i, j, TERM) (l##i = TERM(j))
#define ADD1(i, j, TERM) (l##i += TERM(j))
#define LANES_BY(SET, ADD, TERM)                                                                   \
    do {                                                                                           \
        int j = jl;                                                                                \
        if (jh - jl + 1 >= 4) {                                                                    \
            SET(0, j, TERM), SET(1, j + 1, TERM), SET(2, j + 2, TERM), SET(3, j + 3, TERM);        \
            for (j += 4; j + 3 <= jh; j += 4)                                                      \
                ADD(0, j, TERM), ADD(1, j + 1, TERM), ADD(2, j + 2, TERM), ADD(3, j + 3, TERM);    \
            if (j <= jh)                                                                           \
                ADD(0, j, TERM);                                                                   \
            if (j + 1 <= jh)                                                                       \
                ADD(1, j + 1, TERM);                                                               \
            if (j + 2 <= jh)                                                                       \
                ADD(2, j + 2, TERM);                                                               \
        } else {                                                                                   \
            if (j <= jh)                                                                           \
                SET(0, j, TERM);                                                                   \
            if (j + 1 <= jh)                                                                       \
                SET(1, j + 1, TERM);                                                               \
            if (j + 2 <= jh)                                                                       \
                SET(2, j + 2, TERM);                                                               \
        }                                                                                          \
    } while (0)

#define T_PLAIN(j) (x[j] * y[k - (j)])
#define W_RUN(j) (wa * (double)(j) + wb)
#define T_INTW(j) (w[j] * x[j] * y[k - (j)])
#define T_SYM(j) (2 * x[j] * x[k - (j)])

static inline double fresh_term(const mconv *m, const fresh *f)
{
    double w = f->how == F_RUN ? *m->wa * (double)f->j + *m->wb : f->w;
    return (w * *f->p) * *f->q;
}

/* the lanes added, then the middle and fresh terms */
static inline __attribute__((always_inline)) double conv_tail(const mconv *m, double l0, double l1,
                                                              double l2, double l3)
{
    int n = m->npair;
    if (m->mid) {
        double t = m->x[m->k / 2] * m->x[m->k / 2];
        switch (n % 4) {
        case 0:
            l0 = n < 4 ? t : l0 + t;
            break;
        case 1:
            l1 = n < 4 ? t : l1 + t;
            break;
        case 2:
            l2 = n < 4 ? t : l2 + t;
            break;
        default:
            l3 = n < 4 ? t : l3 + t;
            break;
        }
        n++;
    }
    double s = n >= 4 ? (l0 + l1) + (l2 + l3) : n == 3 ? (l0 + l1) + l2 : n == 2 ? l0 + l1 : l0;
    /* at most two fresh terms (x's and y's): written out, no loop */
    const fresh *f = m->f, *end = m->f + m->nf;
    if (n == 0) /* a sum of one term is that term (0 + t would lose a -0) */
        s = fresh_term(m, f++);
    if (f < end)
        s += fresh_term(m, f++);
    if (f < end)
        s += fresh_term(m, f);
    return s;
}

static double conv_plain(const mconv *m)
{
    const double *x = m->x, *y = m->y;
    const int k = m->k, jl = m->jl, jh = m->jh;
    double l0 = 0, l1 = 0, l2 = 0, l3 = 0;
    LANES(T_PLAIN);
    return conv_tail(m, l0, l1, l2, l3);
}

static inline __attribute__((always_inline)) double conv_intw(const mconv *m)
{
    const double *x = m->x, *y = m->y;
    const int k = m->k, jl = m->jl, jh = m->jh;
    const double *w = m->w;
    double l0 = 0, l1 = 0, l2 = 0, l3 = 0;
    LANES(T_INTW);
    return conv_tail(m, l0, l1, l2, l3);
}

/* Both sums of a pair (mconv): w[j] x[j] once, times y[k-j] and z[k-j]. */
#define SET2(i, j, TERM) (wx = w[j] * x[j], l##i = wx * y[k - (j)], u##i = wx * z[k - (j)])
#define ADD2(i, j, TERM) (wx = w[j] * x[j], l##i += wx * y[k - (j)], u##i += wx * z[k - (j)])

static double conv_pair(const mconv *m, mconv *second)
{
    const double *x = m->x, *y = m->y, *z = second->y, *w = m->w;
    const int k = m->k, jl = m->jl, jh = m->jh;
    double l0 = 0, l1 = 0, l2 = 0, l3 = 0, u0 = 0, u1 = 0, u2 = 0, u3 = 0, wx;
    LANES_BY(SET2, ADD2, _);
    second->lane[0] = u0, second->lane[1] = u1, second->lane[2] = u2, second->lane[3] = u3;
    return conv_tail(m, l0, l1, l2, l3);
}

static double conv_lanes(const mconv *m)
{
    return conv_tail(m, m->lane[0], m->lane[1], m->lane[2], m->lane[3]);
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* w[j] = wa j + wb for the run's wa, wb, rounded as rule.h says; kept
 * while wa and wb keep their bits. */
static void conv_run_weights(mconv *m)
{
    const double wa = *m->wa, wb = *m->wb;
    if (m->w_valid && same_bits(wa, m->wa_w) && same_bits(wb, m->wb_w))
        return;
    for (int j = m->jl; j <= m->jh; j++)
        m->w[j] = W_RUN(j);
    m->wa_w = wa, m->wb_w = wb, m->w_valid = 1;
}

static double conv_weighted(mconv *m)
{
    conv_run_weights(m);
    return conv_intw(m);
}

static double conv_sym(const mconv *m)
{
    const double *x = m->x;
    const int k = m->k, jl = m->jl, jh = m->jh;
    double l0 = 0, l1 = 0, l2 = 0, l3 = 0;
    LANES(T_SYM);
    return conv_tail(m, l0, l1, l2, l3);
}

/* The operations recorded after the sum s, run in the same micro-op. */
static inline __attribute__((always_inline)) void conv_post(const mconv *m, double s, double *d)
{
    *d = s;
    for (int i = 0; i < m->npost; i++) {
        const post *p = &m->post[i];
        double b = *p->b;
        switch (p->code) {
        case M_ADD:
            s = s + b;
            break;
        case M_SUB:
            s = p->rev ? b - s : s - b;
            break;
        case M_MUL:
            s = s * b;
            break;
        default:
            s = -s;
            break;
        }
        *p->d = s;
    }
}

/* Computed goto, not a switch: one indirect jump per handler, so the
 * branch predictor learns each op's successor in the fixed sequence. */
void hl_prog_run(const hl_prog *p, int k)
{
    static const void *const go[] = {&&mov,    &&neg,    &&add,     &&sub,   &&mul,    &&div,
                                     &&fma_,   &&call_,  &&sincos_, &&conv_, &&conv_w, &&conv_iw,
                                     &&conv_s, &&conv_p, &&conv_l,  &&end};
    mconv *cv = p->cv; /* a pair's first convolution writes its partner's lanes */
    const mop *o = p->op + p->start[k], *stop = p->op + p->start[k + 1];
#define NEXT() goto *go[++o < stop ? o->code : M_END]
    if (o == stop)
        return;
    goto *go[o->code];
mov:
    *o->d = *o->a;
    NEXT();
neg:
    *o->d = -*o->a;
    NEXT();
add:
    *o->d = *o->a + *o->b;
    NEXT();
sub:
    *o->d = *o->a - *o->b;
    NEXT();
mul:
    *o->d = *o->a * *o->b;
    NEXT();
div:
    *o->d = *o->a / *o->b;
    NEXT();
fma_:
    *o->d = fma(*o->a, *o->b, *o->c);
    NEXT();
call_:
    *o->d = hl_pfn_eval(o->arg, *o->a, *o->b);
    NEXT();
sincos_:
    sincos(*o->a, o->d, (double *)o->c);
    NEXT();
conv_:
    conv_post(&cv[o->arg], conv_plain(&cv[o->arg]), o->d);
    NEXT();
conv_w:
    conv_post(&cv[o->arg], conv_weighted(&cv[o->arg]), o->d);
    NEXT();
conv_iw:
    conv_post(&cv[o->arg], conv_intw(&cv[o->arg]), o->d);
    NEXT();
conv_s:
    conv_post(&cv[o->arg], conv_sym(&cv[o->arg]), o->d);
    NEXT();
conv_p:
    conv_post(&cv[o->arg], conv_pair(&cv[o->arg], &cv[cv[o->arg].partner - 1]), o->d);
    NEXT();
conv_l:
    conv_post(&cv[o->arg], conv_lanes(&cv[o->arg]), o->d);
    NEXT();
end:
    return;
#undef NEXT
}
