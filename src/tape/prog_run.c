/* The double interpreter's loop: runs the programs prog.c recorded (the
 * layout is prog_ops.h).  A convolution is one micro-operation whose loop
 * runs here in hl_conv_plan's order (rule.h), so interpreted and compiled
 * runs agree bit for bit.
 *
 * Four lanes that start at -0 instead of at their first term: -0 + t is t
 * for every t (+0, -0 and NaN included, in the default rounding), so the
 * first addition gives rule.h's first term exactly, and an empty lane adds
 * nothing to (l0 + l1) + (l2 + l3), as if left out.  So a sum of any length
 * is one loop without special cases, and a convolution without known terms
 * starts its fresh terms from -0, which again gives the first one exactly.
 *
 * Where the processor has AVX2 the four lanes are one vector register:
 * lane i of the vector is lane i of rule.h, and a vector product or sum is
 * four IEEE operations each rounded as its scalar one (AVX2 has no fused
 * multiply-add, so none is contracted), so the bits are those of the
 * scalar lanes in about a third of the instructions.  Without AVX2 they
 * are two pairs of 16-byte vectors (SSE2), the same bits again.  The loop
 * (prog_loop.h) is compiled three times, and the processor picks: with the
 * AVX2 sums; with the two-lane sums and libm's fma (a processor with FMA
 * but not AVX2); with the two-lane sums and prog_fma.h's exact stand-in
 * for fma (a processor without FMA, where libm's fma is a slow emulation). */
#define _GNU_SOURCE /* sincos */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "rules/rule.h"
#include "tape/prog_fma.h"
#include "tape/prog_ops.h"

/* ---- the known terms, two lanes at a time ------------------------------------ */

/* Without AVX2 the four lanes are two pairs (l0, l1) and (l2, l3) of a
 * 16-byte vector (GCC's generic vectors: SSE2 on every x86-64, two scalar
 * operations elsewhere), each element rounded as its scalar operation, so
 * the bits are the scalar lanes'.  The terms (prog_ops.h: mop) are
 * x[j] = a[3 - i], w[j] = c[3 - i], y[k-j] = b[i] for the i-th of four:
 * a pair of x's (or w's) is loaded as it lies and swapped, y's as they lie.
 * The last 1..3 terms: a pair for two, one term into its lane alone
 * (nothing past the terms is read). */
typedef double v2 __attribute__((vector_size(16)));

static inline v2 v2_at(const double *p)
{
    v2 v;
    memcpy(&v, p, sizeof v);
    return v;
}
#define V2_SWAPPED(v) __builtin_shufflevector(v, v, 1, 0)
#define V2_NEG0 ((v2){-0.0, -0.0})

/* (l0 + l1) + (l2 + l3), as the AVX2 loop adds its lanes */
static inline double pairs_added(v2 lo, v2 hi)
{
    return (lo[0] + lo[1]) + (hi[0] + hi[1]);
}

static inline double known_plain(const mop *o)
{
    const double *x = o->a, *y = o->b;
    const int n = o->arg;
    v2 lo = V2_NEG0, hi = V2_NEG0;
    int i = 0;
    for (; i + 4 <= n; i += 4, x -= 4, y += 4) {
        lo += V2_SWAPPED(v2_at(x + 2)) * v2_at(y);
        hi += V2_SWAPPED(v2_at(x)) * v2_at(y + 2);
    }
    const int r = n - i;
    if (r >= 2)
        lo += V2_SWAPPED(v2_at(x + 2)) * v2_at(y);
    if (r == 1)
        lo[0] += x[3] * y[0];
    if (r == 3)
        hi[0] += x[1] * y[2];
    return pairs_added(lo, hi);
}

static inline double known_table(const mop *o)
{
    const double *x = o->a, *y = o->b, *w = o->c;
    const int n = o->arg;
    v2 lo = V2_NEG0, hi = V2_NEG0;
    int i = 0;
    for (; i + 4 <= n; i += 4, x -= 4, y += 4, w -= 4) {
        lo += V2_SWAPPED(v2_at(w + 2) * v2_at(x + 2)) * v2_at(y);
        hi += V2_SWAPPED(v2_at(w) * v2_at(x)) * v2_at(y + 2);
    }
    const int r = n - i;
    if (r >= 2)
        lo += V2_SWAPPED(v2_at(w + 2) * v2_at(x + 2)) * v2_at(y);
    if (r == 1)
        lo[0] += (w[3] * x[3]) * y[0];
    if (r == 3)
        hi[0] += (w[1] * x[1]) * y[2];
    return pairs_added(lo, hi);
}

/* Both known sums of a pair (mconv), w[j] x[j] read and multiplied once;
 * the second's left in its known. */
static double known_pair(const mop *o)
{
    const double *x = o->a, *y = o->b, *w = o->c, *z = o->m->z;
    const int n = o->arg;
    v2 lo = V2_NEG0, hi = V2_NEG0, lo2 = V2_NEG0, hi2 = V2_NEG0;
    int i = 0;
    for (; i + 4 <= n; i += 4, x -= 4, y += 4, z += 4, w -= 4) {
        v2 wx_lo = V2_SWAPPED(v2_at(w + 2) * v2_at(x + 2));
        v2 wx_hi = V2_SWAPPED(v2_at(w) * v2_at(x));
        lo += wx_lo * v2_at(y), hi += wx_hi * v2_at(y + 2);
        lo2 += wx_lo * v2_at(z), hi2 += wx_hi * v2_at(z + 2);
    }
    const int r = n - i;
    if (r >= 2) {
        v2 wx_lo = V2_SWAPPED(v2_at(w + 2) * v2_at(x + 2));
        lo += wx_lo * v2_at(y), lo2 += wx_lo * v2_at(z);
    }
    if (r == 1) {
        double wx = w[3] * x[3];
        lo[0] += wx * y[0], lo2[0] += wx * z[0];
    }
    if (r == 3) {
        double wx = w[1] * x[1];
        hi[0] += wx * y[2], hi2[0] += wx * z[2];
    }
    o->m->second->known = pairs_added(lo2, hi2);
    return pairs_added(lo, hi);
}

/* ---- the known terms, four at a time ----------------------------------------- */

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define HAVE_VEC 1
/* fma: the ODE step's fma is then one instruction, not a call; the same
 * correctly rounded result.  The file is compiled with -ffp-contract=off
 * (CMakeLists.txt), so that no a * b + c of the sums is fused. */
#define VEC __attribute__((target("avx2,fma")))

/* Terms j, j-1, j-2, j-3 in lanes 0..3: x (and w) read from x + j - 3 and
 * reversed, y[k-j..k-j+3] as they lie.  The last 1..3 terms (j down to jl,
 * r of them) are read under a mask (what is past them is never touched):
 * x's from the top of the four at x + j - 3, y's from the bottom at
 * y + k - j; the lanes past r get -0, which adds nothing. */
static const long long lane_mask[4][4] = {
    {0, 0, 0, 0}, {-1, 0, 0, 0}, {-1, -1, 0, 0}, {-1, -1, -1, 0}};
static const long long top_mask[4][4] = {
    {0, 0, 0, 0}, {0, 0, 0, -1}, {0, 0, -1, -1}, {0, -1, -1, -1}};

#define LOAD4(p) _mm256_loadu_pd(p)
/* (p[3], p[2], p[1], p[0]): x[j], x[j-1], x[j-2], x[j-3] from p = x + j - 3 */
#define REVERSED(v) _mm256_permute4x64_pd(v, 0x1b)
#define MASK(t, r) _mm256_loadu_si256((const __m256i *)t[r])
#define RLOAD4(p, r) _mm256_maskload_pd(p, MASK(lane_mask, r))
#define RLOAD4_TOP(p, r) _mm256_maskload_pd(p, MASK(top_mask, r))
/* the lanes past r to -0: +0 there (a masked product) with the sign set */
#define PAST_R(v, r)                                                                               \
    _mm256_or_pd(v, _mm256_andnot_pd(_mm256_castsi256_pd(MASK(lane_mask, r)), _mm256_set1_pd(-0.0)))

static inline VEC double lanes_added(__m256d acc)
{
    __m256d pairs = acc + _mm256_permute_pd(acc, 0x5); /* l0+l1, ., l2+l3, . */
    return _mm256_cvtsd_f64(pairs) + _mm_cvtsd_f64(_mm256_extractf128_pd(pairs, 1));
}

static inline VEC double known_plain_vec(const mop *o)
{
    const double *x = o->a, *y = o->b;
    const int n = o->arg;
    __m256d acc = _mm256_set1_pd(-0.0);
    int i = 0;
    for (; i + 4 <= n; i += 4, x -= 4, y += 4)
        acc += REVERSED(LOAD4(x)) * LOAD4(y);
    int r = n - i;
    if (r > 0)
        acc += PAST_R(REVERSED(RLOAD4_TOP(x, r)) * RLOAD4(y, r), r);
    return lanes_added(acc);
}

static inline VEC double known_table_vec(const mop *o)
{
    const double *x = o->a, *y = o->b, *w = o->c;
    const int n = o->arg;
    __m256d acc = _mm256_set1_pd(-0.0);
    int i = 0;
    for (; i + 4 <= n; i += 4, x -= 4, y += 4, w -= 4)
        acc += REVERSED(LOAD4(w) * LOAD4(x)) * LOAD4(y);
    int r = n - i;
    if (r > 0) {
        __m256d wx = REVERSED(RLOAD4_TOP(w, r) * RLOAD4_TOP(x, r));
        acc += PAST_R(wx * RLOAD4(y, r), r);
    }
    return lanes_added(acc);
}

static VEC double known_pair_vec(const mop *o)
{
    const double *x = o->a, *y = o->b, *w = o->c, *z = o->m->z;
    const int n = o->arg;
    __m256d acc = _mm256_set1_pd(-0.0), acc2 = acc;
    int i = 0;
    for (; i + 4 <= n; i += 4, x -= 4, y += 4, z += 4, w -= 4) {
        __m256d wx = REVERSED(LOAD4(w) * LOAD4(x));
        acc += wx * LOAD4(y);
        acc2 += wx * LOAD4(z);
    }
    int r = n - i;
    if (r > 0) {
        __m256d wx = REVERSED(RLOAD4_TOP(w, r) * RLOAD4_TOP(x, r));
        acc += PAST_R(wx * RLOAD4(y, r), r);
        acc2 += PAST_R(wx * RLOAD4(z, r), r);
    }
    o->m->second->known = lanes_added(acc2);
    return lanes_added(acc);
}
#else
#define HAVE_VEC 0
#endif

/* ---- the rest of a convolution --------------------------------------------- */

/* The fresh terms (w *p) *q added to the known sum s. */
static inline __attribute__((always_inline)) double add_fresh(const mconv *m, double s)
{
    const fresh *f = m->f;
    if (m->nf > 0)
        s += (f[0].w * *f[0].p) * *f[0].q;
    if (m->nf > 1)
        s += (f[1].w * *f[1].p) * *f[1].q;
    return s;
}

static int same_bits(double a, double b)
{
    return memcmp(&a, &b, sizeof a) == 0;
}

/* w[j] = wa j + wb for the run's wa, wb, rounded as rule.h says, and the
 * fresh terms' weights; kept while wa and wb keep their bits. */
static void conv_run_weights(mconv *m)
{
    const double wa = *m->wa, wb = *m->wb;
    if (m->w_valid && same_bits(wa, m->wa_w) && same_bits(wb, m->wb_w))
        return;
    for (int j = m->jl; j <= m->jh; j++)
        m->w[j] = wa * (double)j + wb;
    for (int i = 0; i < m->nf; i++)
        m->f[i].w = wa * (double)m->f[i].j + wb;
    m->wa_w = wa, m->wb_w = wb, m->w_valid = 1;
}

/* s op b for a post-operation's code (prog_ops.h: P_*) */
#define POST_OP(c, s, b)                                                                           \
    ((c) == P_ADD    ? (s) + (b)                                                                   \
     : (c) == P_SUB  ? (s) - (b)                                                                   \
     : (c) == P_RSUB ? (b) - (s)                                                                   \
     : (c) == P_MUL  ? (s) * (b)                                                                   \
                     : -(s))
#define POST1(c) (*m->post[0].d = s = POST_OP(c, s, *m->post[0].b))
#define POST2(c) (*m->post[1].d = s = POST_OP(c, s, *m->post[1].b))
#define CASE1(c0)                                                                                  \
    case c0:                                                                                       \
        POST1(c0);                                                                                 \
        return;
#define CASE2(c0, c1)                                                                              \
    case c0 + P_N *c1:                                                                             \
        POST1(c0), POST2(c1);                                                                      \
        break;
#define CASES2(c0)                                                                                 \
    CASE2(c0, P_ADD) CASE2(c0, P_SUB) CASE2(c0, P_RSUB) CASE2(c0, P_MUL) CASE2(c0, P_NEG)

/* The operations recorded after the sum s, run in the same micro-op: the
 * first one or two by their codes' pair (m->shape), written out; the rest
 * of a longer chain in a loop. */
static inline __attribute__((always_inline)) void conv_post(const mconv *m, double s, double *d)
{
    *d = s;
    switch (m->shape) {
    case 0:
        return;
        CASE1(P_ADD)
        CASE1(P_SUB)
        CASE1(P_RSUB) CASE1(P_MUL) CASE1(P_NEG) CASES2(P_ADD) CASES2(P_SUB) CASES2(P_RSUB)
            CASES2(P_MUL) CASES2(P_NEG)
    }
    for (int i = 2; i < m->npost; i++) {
        const post *p = &m->post[i];
        *p->d = s = POST_OP(p->code, s, *p->b);
    }
}

/* ---- the loop ------------------------------------------------------------------ */

/* M_DIVIDE2, the ODE step of two outputs, with the fma instruction */
#define FMA_ODE2_BY(fma_, d0, d1, f0, f1, hi, lo)                                                  \
    (*(d0) = fma_(f0, hi, (f0) * (lo)), *(d1) = fma_(f1, hi, (f1) * (lo)))

#define RUN run_scalar
#define RUN_TARGET
#define KNOWN_PLAIN known_plain
#define KNOWN_TABLE known_table
#define KNOWN_PAIR known_pair
#define FMA fma
#define FMA_ODE2(d0, d1, f0, f1, hi, lo) FMA_ODE2_BY(fma, d0, d1, f0, f1, hi, lo)
#include "tape/prog_loop.h"

#define RUN run_no_fma
#define RUN_TARGET
#define KNOWN_PLAIN known_plain
#define KNOWN_TABLE known_table
#define KNOWN_PAIR known_pair
#define FMA prog_fma
#define FMA_ODE2(d0, d1, f0, f1, hi, lo) FMA_ODE2_BY(prog_fma, d0, d1, f0, f1, hi, lo)
#include "tape/prog_loop.h"

#if HAVE_VEC
#define RUN run_vec
#define RUN_TARGET VEC
#define KNOWN_PLAIN known_plain_vec
#define KNOWN_TABLE known_table_vec
#define KNOWN_PAIR known_pair_vec
#define FMA fma
#define FMA_ODE2(d0, d1, f0, f1, hi, lo) FMA_ODE2_BY(fma, d0, d1, f0, f1, hi, lo)
#include "tape/prog_loop.h"
#endif

/* Whether the environment variable name is set to anything but empty or
 * "0".  Read once per name: a program's loop is chosen when it is bound. */
static int env_set(const char *name, int *cache)
{
    /* threads may race here: all write the same value */
    int v = __atomic_load_n(cache, __ATOMIC_RELAXED);
    if (v < 0) {
        const char *s = getenv(name);
        v = s != NULL && s[0] != '\0' && strcmp(s, "0") != 0;
        __atomic_store_n(cache, v, __ATOMIC_RELAXED);
    }
    return v;
}

/* HAMLIE_NO_AVX2=1 runs a scalar loop on processors that have AVX2 too, and
 * HAMLIE_NO_FMA=1 the one of processors without FMA (and so without the
 * AVX2 loop, which has the fma instruction), so that the tests cover the
 * paths of the processors without them (CMakeLists.txt: the "-scalar"
 * tests). */
#if HAVE_VEC
static int avx2_allowed(void)
{
    static int no = -1;
    return !env_set("HAMLIE_NO_AVX2", &no);
}
#endif

static int fma_allowed(void)
{
    static int no = -1;
    if (env_set("HAMLIE_NO_FMA", &no))
        return 0;
#if defined(__x86_64__) && defined(__GNUC__)
    return __builtin_cpu_supports("fma");
#elif defined(FP_FAST_FMA)
    return 1;
#else
    return 0;
#endif
}

void hl_prog_bind(hl_prog *p)
{
    void (*run)(const hl_prog *, int, int, int, const void *const **) =
        fma_allowed() ? run_scalar : run_no_fma;
#if HAVE_VEC
    if (run == run_scalar && __builtin_cpu_supports("avx2") && avx2_allowed())
        run = run_vec;
#endif
    const void *const *go;
    run(NULL, 0, 0, 0, &go);
    for (int i = 0; i < p->nop; i++)
        p->op[i].go = go[p->op[i].code];
    p->run = run;
}

const char *hl_prog_loop(const hl_prog *p)
{
#if HAVE_VEC
    if (p->run == run_vec)
        return "avx2";
#endif
    return "scalar";
}

void hl_prog_run(const hl_prog *p, int k)
{
    p->run(p, k, k + 1, 0, NULL);
}

void hl_prog_run_ode(const hl_prog *p, int kend)
{
    if (kend > 0)
        p->run(p, 0, kend, 1, NULL);
}
