/* The double interpreter's recorder: the rules run once per layout
 * through an emitter that writes flat programs (see prog_impl.h for why,
 * prog_ops.h for the layout, prog_run.c for the loop that runs them).
 *
 * While recording, a value is a location: a coefficient in the register
 * file, a constant, a temporary of the current rule call, or a kept value
 * of the current instruction, written as index * 4 + space.  Locations
 * become pointers when the program is finished.  A value stored (or kept)
 * right after the operation that made it is written there directly by that
 * operation, so most stores cost nothing.  An operation on constants only
 * (a^c's c + 1, say; a constant register's coefficients are constants) is
 * done here, once: the same IEEE operation, so the same bits, as the
 * compilers' folding. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "rules/rule.h"
#include "tape/prog_ops.h"

enum { SP_REG, SP_CONST, SP_TEMP, SP_KEEP };
#define LOC(space, index) ((long)(index)*4 + (space))
#define LOC_SPACE(l) ((int)((l)&3))
#define LOC_INDEX(l) ((l) >> 2)

/* A micro-operation while recording, with locations. */
typedef struct rop {
    int code, arg;
    long d, a, b, c;
} rop;

/* ---- recording ----------------------------------------------------------- */

typedef struct rec {
    hl_em em;
    const hl_tape *t;
    long base[HL_SLOT_COUNT]; /* the register of each slot (index of coefficient 0) */
    int reg[HL_SLOT_COUNT];   /* the register itself, -1 when the slot has none */
    int instr, first_op;      /* the instruction being recorded, its first op */
    int k_first_op;           /* the first op of the coefficient being recorded */
    long *tloc;               /* where each temporary of this rule call lives */
    int ntemp, tcap, maxtemp;
    rop *ops;
    int nops, opcap;
    mconv *cv;
    int ncv, cvcap;
    double *consts;
    int nconst, constcap;
    double *wts; /* the weights of the convolutions */
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

/* The value of the convolution of op i (its last post-operation's, if any). */
static long conv_value_at(const rec *r, int i)
{
    const mconv *m = &r->cv[r->ops[i].arg];
    return m->npost ? m->post[m->npost - 1].ld : r->ops[i].d;
}

/* Whether op o is one result written to a temporary of this rule call. */
static int writes_temp(const rop *o)
{
    if (o->code > M_FMA && o->code != M_CALL)
        return 0; /* a convolution, sincos (two results), the ends */
    return LOC_SPACE(o->d) == SP_TEMP;
}

/* Whether op o may run before convolution i that precedes it: it writes
 * only a temporary and reads nothing i writes (each op rounds as it would
 * in place: moving one changes no bit, only what it reads). */
static int may_pass(const rec *r, const rop *o, int i)
{
    if (!writes_temp(o))
        return 0;
    const mconv *m = &r->cv[r->ops[i].arg];
    for (int p = -1; p < m->npost; p++) {
        long w = p < 0 ? r->ops[i].d : m->post[p].ld;
        if (o->a == w || o->b == w || o->c == w)
            return 0;
    }
    return 1;
}

/* The convolution a post-operation reading s can join: the last op; or
 * the last one of this rule call before ops that may pass it (it moves
 * after them); or the last op of the coefficient's program when it is a
 * convolution of an earlier rule call whose value is stored in a register
 * (temporaries are the rule call's own; a register stays).  Its index, or
 * -1. */
static int post_target(rec *r, long a, long b)
{
    int i = r->nops - 1;
    while (i >= r->first_op && writes_temp(&r->ops[i]))
        i--;
    int earlier_call = i < r->first_op;
    if (i < r->k_first_op || r->ops[i].code != M_CONV)
        return -1;
    if (earlier_call && (i != r->nops - 1 || LOC_SPACE(conv_value_at(r, i)) != SP_REG))
        return -1;
    for (int j = i + 1; j < r->nops; j++)
        if (!may_pass(r, &r->ops[j], i))
            return -1;
    long s = conv_value_at(r, i);
    return s == a || s == b ? i : -1;
}

/* Move convolution i after the ops that follow it (post_target said they
 * may pass it), into the rule call being recorded. */
static void sink_conv(rec *r, int i)
{
    rop c = r->ops[i];
    memmove(&r->ops[i], &r->ops[i + 1], (size_t)(r->nops - 1 - i) * sizeof *r->ops);
    r->ops[r->nops - 1] = c;
    if (i < r->first_op)
        r->first_op = i;
}

/* a op b as a post-operation of a convolution whose value it reads (saves
 * a dispatch and a trip of the value through memory: the dominant cost of
 * short rules) */
static long try_post(rec *r, int code, long a, long b)
{
    if (code != M_ADD && code != M_SUB && code != M_MUL && code != M_NEG)
        return -1;
    int i = post_target(r, a, b);
    if (i < 0 || r->cv[r->ops[i].arg].npost == NPOST)
        return -1;
    long s = conv_value_at(r, i);
    sink_conv(r, i);
    mconv *m = &r->cv[r->ops[r->nops - 1].arg];
    post *p = &m->post[m->npost++];
    p->code = code == M_ADD      ? P_ADD
              : code == M_MUL    ? P_MUL
              : code == M_NEG    ? P_NEG
              : b == s && a != s ? P_RSUB
                                 : P_SUB;
    p->lb = a == s ? b : a;
    p->ld = new_temp(r);
    return p->ld;
}

static long rec_const(rec *r, double v);

static int is_const(long l)
{
    return LOC_SPACE(l) == SP_CONST;
}

/* a op b (op c) on constants, as the loop would compute it */
static double fold(const rec *r, int code, long a, long b, long c)
{
    double x = r->consts[LOC_INDEX(a)], y = r->consts[LOC_INDEX(b)], z = r->consts[LOC_INDEX(c)];
    switch (code) {
    case M_NEG:
        return -x;
    case M_ADD:
        return x + y;
    case M_SUB:
        return x - y;
    case M_MUL:
        return x * y;
    case M_DIV:
        return x / y;
    default:
        return fma(x, y, z);
    }
}

static hl_ev emit_v(rec *r, int code, int arg, hl_ev a, hl_ev b, hl_ev c)
{
    long la = where(r, a), lb = where(r, b), lc = where(r, c);
    if (code <= M_FMA && code != M_MOV && is_const(la) && is_const(lb) && is_const(lc))
        return ev_loc(rec_const(r, fold(r, code, la, lb, lc)));
    long l = try_post(r, code, la, lb);
    return ev_loc(l >= 0 ? l : emit(r, code, arg, la, lb, lc)->d);
}

static long const_append(rec *r, double v)
{
    if (r->nconst == r->constcap) {
        r->constcap = r->constcap ? 2 * r->constcap : 32;
        r->consts = hl_xrealloc(r->consts, (size_t)r->constcap * sizeof *r->consts);
    }
    r->consts[r->nconst] = v;
    return LOC(SP_CONST, r->nconst++);
}

static long rec_const(rec *r, double v)
{
    for (int i = 0; i < r->nconst; i++)
        if (memcmp(&r->consts[i], &v, sizeof v) == 0)
            return LOC(SP_CONST, i);
    return const_append(r, v);
}

/* v, w in two adjacent constants (M_DIVIDE2 reads hi, lo as b[0], b[1]) */
static long rec_const_pair(rec *r, double v, double w)
{
    for (int i = 0; i + 1 < r->nconst; i++)
        if (memcmp(&r->consts[i], &v, sizeof v) == 0 &&
            memcmp(&r->consts[i + 1], &w, sizeof w) == 0)
            return LOC(SP_CONST, i);
    long l = const_append(r, v);
    const_append(r, w);
    return l;
}

static hl_ev rec_num(hl_em *e, long p, long q)
{
    return ev_loc(rec_const(rec_of(e), (double)p / (double)q));
}

/* a constant register's coefficients are (c, 0, 0, ...) */
static hl_ev rec_coef(hl_em *e, hl_slot s, int j)
{
    rec *r = rec_of(e);
    int reg = r->reg[s];
    if (reg >= 0 && r->t->isconst[reg])
        return ev_loc(rec_const(r, j == 0 ? r->t->rd[reg] : 0.0));
    return ev_loc(LOC(SP_REG, r->base[s] + j));
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

/* The plan of hl_conv_plan as a range of known terms (consecutive j from
 * jh down to jl, a square's middle term first) and the fresh terms. */
static void conv_shape(mconv *m, const hl_conv *c)
{
    int n = c->hi - c->lo + 1, nk, nf, fr[2];
    int *idx = hl_xmalloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    int *lane = hl_xmalloc(sizeof(int) * (size_t)(n > 0 ? n : 1));
    hl_conv_plan(c, idx, lane, &nk, fr, &nf);
    m->jl = nk > 0 ? idx[nk - 1] : 1;
    m->jh = nk > 0 ? idx[0] : 0;
    m->nf = nf;
    for (int i = 0; i < nf; i++)
        m->f[i].j = fr[i];
    free(idx);
    free(lane);
}

/* Room for the weights of terms jl..jh; w(j) is the result's [j - jl]
 * (the run reads wts[lw + j]). */
static double *new_weights(rec *r, mconv *m)
{
    long n = m->jh - m->jl + 1 > 0 ? m->jh - m->jl + 1 : 0;
    if (r->nwts + n > r->wcap) {
        r->wcap = 2 * (r->nwts + n) + 64;
        r->wts = hl_xrealloc(r->wts, (size_t)r->wcap * sizeof *r->wts);
    }
    double *w = r->wts + r->nwts;
    m->lw = r->nwts - m->jl;
    r->nwts += n;
    return w;
}

/* w(j) = wa j + wb, rounded as rule.h says (the loop's W_RUN) */
static double run_weight(double wa, double wb, int j)
{
    return wa * (double)j + wb;
}

/* The weights, in a table when they are known now (see CV_TABLE); a
 * square's: 2 for a pair, 1 for the middle term. */
static void conv_weights(rec *r, mconv *m, const hl_conv *c)
{
    m->kind = c->sym || c->weighted ? CV_TABLE : CV_PLAIN;
    if (c->sym) {
        double *w = new_weights(r, m);
        for (int j = m->jl; j <= m->jh; j++)
            w[j - m->jl] = 2 * j < c->k ? 2 : 1;
    }
    if (!c->weighted)
        return;
    m->lwa = where(r, c->wa);
    m->lwb = where(r, c->wb);
    double *w = new_weights(r, m);
    if (!is_const(m->lwa) || !is_const(m->lwb)) {
        m->kind = CV_WEIGHTED; /* filled by the run (conv_run_weights) */
        return;
    }
    double wa = r->consts[LOC_INDEX(m->lwa)], wb = r->consts[LOC_INDEX(m->lwb)];
    for (int j = m->jl; j <= m->jh; j++)
        w[j - m->jl] = run_weight(wa, wb, j);
}

/* The fresh terms as rule.h writes them: a weighted x[k] term (w y[0]) x[k],
 * others (w x[j]) y[k-j]; a square's pair term has w = 2. */
static void conv_fresh(rec *r, mconv *m, const hl_conv *c, long x, long y)
{
    int k = c->k;
    for (int i = 0; i < m->nf; i++) {
        fresh *f = &m->f[i];
        int j = f->j, x_side = j == k && k > 0;
        f->lp = x_side ? y : x + 4L * j;
        f->lq = x_side ? x + 4L * k : y + 4L * (k - j);
        f->w = c->sym && 2 * j < k ? 2 : 1;
        if (c->weighted && m->kind == CV_TABLE)
            f->w = run_weight(r->consts[LOC_INDEX(m->lwa)], r->consts[LOC_INDEX(m->lwb)], j);
    }
}

static int same_known_terms(const rec *r, const mconv *a, const mconv *b)
{
    if (a->kind != CV_TABLE || b->kind != CV_TABLE || a->lx != b->lx || a->k != b->k ||
        a->jl != b->jl || a->jh != b->jh || a->jh < a->jl)
        return 0;
    size_t n = (size_t)(a->jh - a->jl + 1);
    return memcmp(r->wts + a->lw + a->jl, r->wts + b->lw + b->jl, n * sizeof *r->wts) == 0;
}

/* Make convolution i the partner of an earlier one of this rule call that
 * shares its known terms' x and weights (see mconv). */
static void pair_up(rec *r, int i)
{
    for (int o = r->first_op; o < r->nops; o++) {
        if (r->ops[o].code != M_CONV)
            continue;
        mconv *first = &r->cv[r->ops[o].arg];
        if (first->partner == 0 && !first->known_done && same_known_terms(r, first, &r->cv[i])) {
            first->partner = i + 1;
            r->cv[i].known_done = 1;
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
    *has = tmp.jh >= tmp.jl || tmp.nf > 0;
    if (!*has)
        return rec_num(e, 0, 1);
    mconv *m = new_conv(r);
    *m = tmp;
    m->k = c->k;
    m->lx = LOC(SP_REG, r->base[c->x]);
    m->ly = LOC(SP_REG, r->base[c->y]);
    m->lwa = m->lwb = -1;
    conv_weights(r, m, c);
    conv_fresh(r, m, c, m->lx, m->ly);
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
    r->reg[HL_SLOT_D] = in->d;
    r->reg[HL_SLOT_A] = in->a;
    r->reg[HL_SLOT_B] = in->b;
    r->reg[HL_SLOT_X] = in->x;
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
    if (m->partner || m->known_done)
        return m->partner ? M_CONV_PAIR : M_CONV_LANES;
    if (m->npost == 0 && m->kind != CV_WEIGHTED)
        return m->kind == CV_PLAIN ? M_CONV_BARE : M_CONV_TABLE_BARE;
    return M_CONV + m->kind;
}

/* A convolution's op: its mconv and where its known terms start (mop);
 * nothing is formed from the pointers when there are no known terms. */
static void conv_op(mop *o, mconv *m)
{
    o->m = m;
    o->arg = m->jh - m->jl + 1;
    o->a = o->b = o->c = NULL;
    if (m->partner)
        m->z = NULL;
    if (o->arg <= 0)
        return;
    o->a = m->x + m->jh - 3;
    o->b = m->y + m->k - m->jh;
    if (m->kind != CV_PLAIN)
        o->c = m->w + m->jh - 3;
    if (m->partner)
        m->z = m->second->y + m->k - m->jh;
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
        p->op[i] =
            (mop){NULL, code, o->arg, at(&s, o->d), at(&s, o->a), at(&s, o->b), at(&s, o->c), NULL};
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
        m->second = m->partner ? &p->cv[m->partner - 1] : NULL;
        m->shape = m->npost == 0   ? 0
                   : m->npost == 1 ? m->post[0].code
                                   : m->post[0].code + P_N * m->post[1].code;
        for (int j = 0; j < m->npost; j++) {
            m->post[j].b = at(&s, m->post[j].lb);
            m->post[j].d = at(&s, m->post[j].ld);
        }
        for (int j = 0; j < m->nf; j++) {
            m->f[j].p = at(&s, m->f[j].lp);
            m->f[j].q = at(&s, m->f[j].lq);
        }
    }
    for (int i = 0; i < r->nops; i++)
        if (r->ops[i].code == M_CONV)
            conv_op(&p->op[i], &p->cv[r->ops[i].arg]);
    p->start = start;
    p->nk = nk;
    p->nop = r->nops;
    hl_prog_bind(p);
    free(r->ops);
    free(r->consts);
    free(r->tloc);
    return p;
}

static void rec_init(rec *r, const hl_tape *t)
{
    memset(r, 0, sizeof *r);
    r->em.ops = &rec_ops;
    r->t = t;
}

/* The ODE step after coefficient k's body: z_i[k+1] = f_i[k] / (k+1) as
 * fma(c, hi, c lo) from hl_tape_ode_source's c and hi + lo, c hi when lo
 * is 0, as the compiled code does (rule.h, hl_rule_recip_split): a
 * division is slow, a product by a rounded 1/(k+1) alone drifts the phase.
 * Behind M_ODE, so that a plain run stops before it.  Two outputs in a row
 * with the same hi + lo are one M_DIVIDE2 (a dispatch less). */
static void rec_ode_step(rec *r, const hl_tape *t, int k, int S)
{
    r->first_op = r->nops;
    r->ntemp = 0;
    emit(r, M_ODE, 0, 0, 0, 0)->d = LOC(SP_REG, 0);
    for (int i = 0; i < t->nout; i++) {
        hl_ode_source a, b;
        hl_tape_ode_source(&a, t, i, k);
        long f = LOC(SP_REG, (long)a.reg * S + a.k), d = LOC(SP_REG, (long)i * S + k + 1);
        rop *o;
        if (i + 1 < t->nout)
            hl_tape_ode_source(&b, t, i + 1, k);
        if (a.lo == 0) {
            o = emit(r, M_MUL, 0, f, rec_const(r, a.hi), f);
        } else if (i + 1 < t->nout && b.hi == a.hi && b.lo == a.lo) {
            /* outputs i and i + 1: z_i[k+1] and S further */
            long f1 = LOC(SP_REG, (long)b.reg * S + b.k);
            o = emit(r, M_DIVIDE2, S, f, rec_const_pair(r, a.hi, a.lo), f1);
            i++;
        } else {
            o = emit(r, M_DIVIDE, 0, f, rec_const(r, a.hi), rec_const(r, a.lo));
        }
        o->d = d;
    }
}

/* the end of a coefficient's program: the loop stops there without a test
 * at every operation */
static void rec_end(rec *r)
{
    r->first_op = r->nops;
    emit(r, M_END, 0, 0, 0, 0)->d = LOC(SP_REG, 0);
}

hl_prog *hl_prog_taylor(const hl_tape *t, double *td, int order)
{
    rec r;
    rec_init(&r, t);
    int S = order + 1, *start = hl_xmalloc(((size_t)S + 1) * sizeof *start);
    for (int k = 0; k <= order; k++) {
        start[k] = r.k_first_op = r.nops;
        for (int i = 0; i < t->ncode; i++) {
            rec_enter(&r, &t->code[i], i, S);
            hl_rule_of((hl_op)t->code[i].op)->taylor(&r.em, k);
        }
        if (k < order && t->nin == t->nout)
            rec_ode_step(&r, t, k, S);
        rec_end(&r);
    }
    start[S] = r.nops;
    return finish(&r, td, t->ncode, start, S);
}

hl_prog *hl_prog_point(const hl_tape *t, double *reg)
{
    rec r;
    rec_init(&r, t);
    int *start = hl_xmalloc(2 * sizeof *start);
    start[0] = 0;
    for (int i = 0; i < t->ncode; i++) {
        rec_enter(&r, &t->code[i], i, 1);
        hl_rule_of((hl_op)t->code[i].op)->point(&r.em);
    }
    rec_end(&r);
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
