/* Tape point evaluation: random expressions over x, y, z built with the
 * constructors, every op reached, evaluated at random points by the tape (in
 * double and in Arb at 200 bits), by hl_expr_eval_d, and by an independent
 * recursive evaluator written here from libm.  Also: unknown symbols, folding, sharing. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "hl_test.h"
#include "hamlie/tape.h"

#include "tape_gen.h"

static void test_random(void)
{
    hl_pool *P = hl_pool_new();
    int bad = 0, total = 0;
    for (int trial = 0; trial < 400; trial++) {
        const hl_expr *outs[3];
        for (int j = 0; j < 3; j++)
            outs[j] = gen(P, 1 + rnd(4));
        hl_tape *t = NULL;
        hl_error err;
        int st = hl_tape_new(&t, outs, 3, vars, 3, &err);
        CHECK_MSG(st == HL_OK, "tape_new: %s", err.msg);
        if (st != HL_OK)
            continue;
        arb_ptr xin = _arb_vec_init(3), xout = _arb_vec_init(3);
        for (int pt = 0; pt < 5; pt++) {
            double v[3], got[3];
            for (int i = 0; i < 3; i++) {
                v[i] = 2.0 * rnd(1u << 30) / (1u << 30) - 1;
                arb_set_d(xin + i, v[i]);
            }
            hl_tape_eval_d(got, v, t);
            hl_tape_eval_arb(xout, xin, 200, t);
            for (int j = 0; j < 3; j++) {
                double want = ref(outs[j], v), ev = NAN;
                hl_error e2;
                int est = hl_expr_eval_d(&ev, outs[j], 3, vars, v, &e2);
                double mid = arf_get_d(arb_midref(xout + j), ARF_RND_NEAR);
                total++;
                int ok = isfinite(want) && relerr(got[j], want) < 1e-12
                         && est == HL_OK && relerr(got[j], ev) < 1e-12
                         && relerr(mid, want) < 1e-12
                         && mag_cmp_2exp_si(arb_radref(xout + j), -150) < 0;
                if (!ok && bad++ < 5) {
                    char *s = hl_tape_print(t);
                    fprintf(stderr, "output %d at (%g,%g,%g): tape %.17g arb %.17g ref %.17g "
                            "hl_expr_eval_d %.17g\n%s", j, v[0], v[1], v[2], got[j], mid, want, ev, s);
                    free(s);
                }
            }
        }
        _arb_vec_clear(xin, 3);
        _arb_vec_clear(xout, 3);
        hl_tape_free(t);
    }
    CHECK_MSG(bad == 0, "%d of %d random evaluations disagree", bad, total);
    hl_pool_free(P);
}

static void test_errors_and_sharing(void)
{
    hl_pool *P = hl_pool_new();
    hl_error err;
    hl_tape *t = NULL;
    const hl_expr *x = hl_sym(P, "x"), *w = hl_sym(P, "w");
    const hl_expr *e = hl_add(P, x, w);
    CHECK(hl_tape_new(&t, &e, 1, vars, 3, &err) == HL_EINVAL && t == NULL);
    CHECK(strstr(err.msg, "'w'") != NULL);

    /* chains of any depth compile (the compiler walks without recursion):
     * 10^5 levels, far past what a recursion on an 8 MiB stack reaches */
    for (int pass = 0; pass < 2; pass++) {
        int depth = pass == 0 ? 4500 : 100000; /* two levels of nodes each */
        e = x;
        for (int k = 0; k < depth; k++) /* x*y + 1, nested: no two nodes alike */
            e = hl_add(P, hl_mul(P, e, hl_sym(P, "y")), hl_num_si(P, 1));
        int st = hl_tape_new(&t, &e, 1, vars, 3, &err);
        CHECK_MSG(st == HL_OK, "depth %d: %s", depth, err.msg);
        double v[3] = {0.5, 0, 0}, r = 0;
        if (st == HL_OK)
            hl_tape_eval_d(&r, v, t); /* y = 0: the outermost x*y + 1 is 1 */
        CHECK(r == 1);
        hl_tape_free(t);
        t = NULL;
    }

    /* a constant 1/0 is a domain error */
    e = hl_add(P, x, hl_div(P, hl_num_si(P, 1), hl_num_si(P, 0)));
    CHECK(hl_tape_new(&t, &e, 1, vars, 3, &err) == HL_EDOM && t == NULL);

    /* sin(x)^2 + cos(x)^2 + sin(x)*cos(x): one SINCOS, two SQR, one MUL, two ADD */
    const hl_expr *s = hl_call(P, HL_SIN, x), *c = hl_call(P, HL_COS, x);
    const hl_expr *two = hl_num_si(P, 2);
    e = hl_add(P, hl_add(P, hl_pow(P, s, two), hl_pow(P, c, two)), hl_mul(P, s, c));
    CHECK(hl_tape_new(&t, &e, 1, vars, 3, &err) == HL_OK);
    CHECK_MSG(hl_tape_nops(t) == 6, "nops %d", hl_tape_nops(t));
    double in[3] = {0.7, 0, 0}, out;
    hl_tape_eval_d(&out, in, t);
    CHECK(fabs(out - (1 + sin(0.7) * cos(0.7))) < 1e-15);
    hl_tape_free(t);

    /* constants fold: (2*pi + log(3)) * x is one MULK */
    e = hl_mul(P, hl_add(P, hl_mul(P, two, hl_pi(P)), hl_call(P, HL_LOG, hl_num_si(P, 3))), x);
    CHECK(hl_tape_new(&t, &e, 1, vars, 3, &err) == HL_OK);
    CHECK(hl_tape_nops(t) == 1);
    hl_tape_eval_d(&out, in, t);
    CHECK(fabs(out - (2 * M_PI + log(3)) * 0.7) < 1e-15);
    hl_tape_free(t);

    /* x^5 by binary powering: SQR, SQR, MUL */
    e = hl_pow(P, x, hl_num_si(P, 5));
    CHECK(hl_tape_new(&t, &e, 1, vars, 3, &err) == HL_OK);
    CHECK(hl_tape_nops(t) == 3);
    hl_tape_eval_d(&out, in, t);
    CHECK(fabs(out - pow(0.7, 5)) < 1e-16);
    hl_tape_free(t);

    /* rational scales meet instead of costing instructions: (2*x)/2 and
     * -(-x) are x; 2*(x/4)*2 - x is 0; (6*x + 3*y)/3 is 6*(x + y/2)/3:
     * MULK, ADD, and one MULK for the scale left at the output */
    {
        const hl_expr *y = hl_sym(P, "y");
        const hl_expr *outs3[4] = {
            hl_div(P, hl_mul(P, two, x), two), hl_neg(P, hl_neg(P, x)),
            hl_sub(P, hl_mul(P, hl_mul(P, two, hl_div(P, x, hl_num_si(P, 4))), two), x),
            hl_div(P, hl_add(P, hl_mul(P, hl_num_si(P, 6), x), hl_mul(P, hl_num_si(P, 3), y)),
                   hl_num_si(P, 3))};
        CHECK(hl_tape_new(&t, outs3, 4, vars, 3, &err) == HL_OK);
        CHECK_MSG(hl_tape_nops(t) == 3, "scales: %d ops", hl_tape_nops(t));
        double o4[4], in2[3] = {0.7, -1.9, 0};
        hl_tape_eval_d(o4, in2, t);
        CHECK(o4[0] == 0.7 && o4[1] == 0.7 && o4[2] == 0 && fabs(o4[3] - (1.4 - 1.9)) < 1e-15);
        hl_tape_free(t);
    }

    /* an output that is an input, and one that is a constant */
    const hl_expr *outs[2] = {x, two};
    CHECK(hl_tape_new(&t, outs, 2, vars, 3, &err) == HL_OK);
    double o2[2];
    hl_tape_eval_d(o2, in, t);
    CHECK(o2[0] == 0.7 && o2[1] == 2);
    hl_tape_free(t);
    hl_tape_free(NULL);
    hl_pool_free(P);
}

int main(void)
{
    test_random();
    test_errors_and_sharing();
    flint_cleanup();
    return HL_TEST_END();
}
