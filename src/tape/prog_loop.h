/* The double interpreter's loop, included twice by prog_run.c: once with
 * the scalar sums of the known terms, once with the vector ones (AVX2).
 * Before including: RUN (the function's name), RUN_TARGET (its target
 * attribute), KNOWN_PLAIN, KNOWN_TABLE, KNOWN_PAIR (the sums), FMA (fma or
 * its scalar stand-in, prog_fma.h) and FMA_ODE2 (M_DIVIDE2's two). */

#define CAT_(a, b) a##b
#define CAT(a, b) CAT_(a, b)

/* a convolution: its known sum, if it has known terms, then its fresh terms */
static inline __attribute__((always_inline)) RUN_TARGET double CAT(RUN, _plain)(const mop *o)
{
    return add_fresh(o->m, KNOWN_PLAIN(o));
}

static inline __attribute__((always_inline)) RUN_TARGET double CAT(RUN, _table)(const mop *o)
{
    return add_fresh(o->m, KNOWN_TABLE(o));
}

/* Threaded code: each op holds its handler's address (hl_prog_bind), so a
 * step is one indirect jump, which the branch predictor learns per handler
 * in the fixed sequence; the program of each coefficient ends with M_END,
 * so there is no test of the end at every op, and M_END goes on to the next
 * coefficient's program while k < kend (one call for a whole recursion, not
 * a call and its register saves per coefficient).  Called with p = NULL,
 * gives the handlers' addresses in the order of mcode. */
static RUN_TARGET void RUN(const hl_prog *p, int k, int kend, int ode, const void *const **labels)
{
    static const void *const go[] = {&&mov,     &&neg,    &&add,    &&sub,     &&mul,
                                     &&div,     &&fma_,   &&call_,  &&sincos_, &&conv_,
                                     &&conv_t,  &&conv_w, &&conv_p, &&conv_l,  &&conv_0,
                                     &&conv_t0, &&ode_,   &&divide, &&divide2, &&end};
    _Static_assert(sizeof go / sizeof *go == M_END + 1, "a handler per mcode");
    if (p == NULL) {
        *labels = go;
        return;
    }
    const mop *o = p->op + p->start[k];
#define NEXT() goto *(++o)->go
    goto * o->go;
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
    *o->d = FMA(*o->a, *o->b, *o->c);
    NEXT();
call_:
    *o->d = hl_pfn_eval(o->arg, *o->a, *o->b);
    NEXT();
sincos_:
    sincos(*o->a, o->d, (double *)o->c);
    NEXT();
conv_:
    conv_post(o->m, CAT(RUN, _plain)(o), o->d);
    NEXT();
conv_t:
    conv_post(o->m, CAT(RUN, _table)(o), o->d);
    NEXT();
conv_w:
    conv_run_weights(o->m);
    conv_post(o->m, CAT(RUN, _table)(o), o->d);
    NEXT();
conv_p : {
    mconv *m = o->m; /* it writes its partner's known sum */
    conv_post(m, add_fresh(m, KNOWN_PAIR(o)), o->d);
    NEXT();
}
conv_l:
    conv_post(o->m, add_fresh(o->m, o->m->known), o->d);
    NEXT();
conv_0:
    *o->d = CAT(RUN, _plain)(o);
    NEXT();
conv_t0:
    *o->d = CAT(RUN, _table)(o);
    NEXT();
ode_:
    if (!ode)
        return;
    NEXT();
divide:
    *o->d = FMA(*o->a, *o->b, *o->a * *o->c);
    NEXT();
divide2 : {
    const double f0 = *o->a, f1 = *o->c, hi = o->b[0], lo = o->b[1];
    FMA_ODE2(o->d, o->d + o->arg, f0, f1, hi, lo);
    NEXT();
}
end:
    if (++k < kend) { /* the next coefficient's program, in the same call */
        o = p->op + p->start[k];
        goto * o->go;
    }
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
#undef FMA
#undef FMA_ODE2
