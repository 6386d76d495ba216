/* The double interpreter's loop, included twice by prog_run.c: once with
 * the scalar sums of the known terms, once with the vector ones (AVX2).
 * Before including: RUN (the function's name), RUN_TARGET (its target
 * attribute), KNOWN_PLAIN, KNOWN_TABLE, KNOWN_PAIR (the sums). */

#define CAT_(a, b) a##b
#define CAT(a, b) CAT_(a, b)

/* a convolution: its known sum, if it has known terms, then its fresh terms */
static inline __attribute__((always_inline)) RUN_TARGET double CAT(RUN, _plain)(const mconv *m)
{
    return add_fresh(m, KNOWN_PLAIN(m));
}

static inline __attribute__((always_inline)) RUN_TARGET double CAT(RUN, _table)(const mconv *m)
{
    return add_fresh(m, KNOWN_TABLE(m));
}

/* Computed goto, not a switch: one indirect jump per handler, so the
 * branch predictor learns each op's successor in the fixed sequence; the
 * program of each coefficient ends with M_END, so a step is one load and
 * one jump. */
static RUN_TARGET void RUN(const hl_prog *p, int k)
{
    static const void *const go[] = {&&mov,    &&neg,    &&add,    &&sub,     &&mul,
                                     &&div,    &&fma_,   &&call_,  &&sincos_, &&conv_,
                                     &&conv_t, &&conv_w, &&conv_p, &&conv_l,  &&end};
    mconv *cv = p->cv; /* a pair's first convolution writes its partner's known sum */
    const mop *o = p->op + p->start[k];
#define NEXT() goto *go[(++o)->code]
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
    conv_post(&cv[o->arg], CAT(RUN, _plain)(&cv[o->arg]), o->d);
    NEXT();
conv_t:
    conv_post(&cv[o->arg], CAT(RUN, _table)(&cv[o->arg]), o->d);
    NEXT();
conv_w:
    conv_run_weights(&cv[o->arg]);
    conv_post(&cv[o->arg], CAT(RUN, _table)(&cv[o->arg]), o->d);
    NEXT();
conv_p : {
    mconv *m = &cv[o->arg];
    conv_post(m, add_fresh(m, KNOWN_PAIR(m, &cv[m->partner - 1])), o->d);
    NEXT();
}
conv_l:
    conv_post(&cv[o->arg], add_fresh(&cv[o->arg], cv[o->arg].known), o->d);
    NEXT();
end:
    return;
#undef NEXT
}

#undef CAT
#undef CAT_
#undef RUN
#undef RUN_TARGET
#undef KNOWN_PLAIN
#undef KNOWN_TABLE
#undef KNOWN_PAIR
