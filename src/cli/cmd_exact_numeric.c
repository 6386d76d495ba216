/* `hamlie exact --init` (and --digits): the numeric exact scheme of a 1-dof
 * H that is not quadratic — the orbit's period, and eight steps against
 * the Taylor integrator (in Arb: against the Arb integrator carried over
 * the whole time). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cmd_exact_impl.h"
#include "hamlie/exact.h"
#include "hamlie/flow.h"
#include "hamlie/run.h"
#include "hamlie/tape.h"

/* --init with --digits: the same in Arb (exact.h: hl_exact_arb), against
 * the Arb integrator carried over the whole time and the double scheme. */
static int run_numeric_arb(hl_buf *out, int *code, hl_system *sys, double dt, const double *zd8,
                           hl_error *err)
{
    char *end;
    double digits = strtod(exact_mode.digits, &end);
    if (*end || !(digits >= 16 && digits <= 1000))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "--digits must be from 16 to 1000");
    hl_exact_arb *f = NULL;
    int st = hl_exact_arb_new(&f, sys, digits, err);
    if (st != HL_OK)
        return st;
    slong prec = (slong)ceil(digits * log2(10.0)) + 32;
    arb_ptr z = _arb_vec_init(2), w = _arb_vec_init(2);
    arb_t T, h, t, t1, d;
    arb_init(T), arb_init(h), arb_init(t), arb_init(t1), arb_init(d);
    st = hl_run_init_values_arb(z, sys, exact_mode.init, prec, err);
    if (st == HL_OK)
        st = hl_exact_arb_period(T, z, f, err);
    int nd = (int)digits;
    if (st == HL_OK) {
        hl_buf_printf(out, "in Arb at %d digits: period T = ", nd);
        cli_put_arb(out, T, nd);
        hl_buf_puts(out, "\n");
        exact_json_section("arb");
        exact_json_double("digits", nd);
        exact_json_arb("period", T, nd);
    }
    _arb_vec_set(w, z, 2);
    arb_set_d(h, dt);
    for (int n = 1; n <= 8 && st == HL_OK; n++)
        st = hl_exact_arb_step(z, h, f, err);
    /* the Arb integrator over the whole 8 dt (the check of the reduction mod T) */
    hl_tape *vf = NULL;
    hl_flow_arb *fa = NULL;
    const char *q = hl_system_coord(sys, 0), *p = hl_system_momentum(sys, 0);
    if (st == HL_OK)
        st = hl_tape_hamiltonian(&vf, hl_system_pool(sys), hl_system_H_expr(sys), 1, &q, &p, 0,
                                 NULL, NULL, err);
    if (st == HL_OK)
        st = hl_flow_arb_new(&fa, vf, digits, err);
    arb_mul_si(t1, h, 8, prec);
    if (st == HL_OK)
        st = hl_flow_arb_evolve(fa, t, t1, w, err);
    if (st == HL_OK) {
        double dmax = 0, ddouble = 0;
        hl_buf_printf(out, "after 8 exact steps of %s = %g in Arb:", hl_system_step(sys), dt);
        exact_json_object("final_state");
        for (int i = 0; i < 2; i++) {
            char *nm = cli_image_name(sys, i);
            hl_buf_printf(out, " %s = ", nm);
            cli_put_arb(out, z + i, nd);
            exact_json_arb(nm, z + i, nd);
            free(nm);
            arb_sub(d, z + i, w + i, prec);
            dmax = fmax(dmax, fabs(arf_get_d(arb_midref(d), ARF_RND_NEAR)));
            ddouble = fmax(ddouble, fabs(zd8[i] - arf_get_d(arb_midref(z + i), ARF_RND_NEAR)));
        }
        hl_buf_printf(out, "\nmax difference from the Arb integrator over t = %g: %.3g\n", 8 * dt,
                      dmax);
        hl_buf_printf(out, "max difference of the double exact scheme from it: %.3g\n", ddouble);
        exact_json_close_to(1);
        exact_json_double("max_difference_from_arb_integrator", dmax);
        exact_json_double("max_difference_of_double_scheme", ddouble);
        *code = dmax < pow(10.0, 5 - digits) * 8 * fmax(1.0, fabs(dt)) ? CLI_OK : CLI_FAILS;
    }
    hl_flow_arb_free(fa);
    hl_tape_free(vf);
    hl_exact_arb_free(f);
    _arb_vec_clear(z, 2), _arb_vec_clear(w, 2);
    arb_clear(T), arb_clear(h), arb_clear(t), arb_clear(t1), arb_clear(d);
    return st;
}

/* 1 dof, not quadratic: the orbit's period and a few steps against the
 * Taylor integrator. */
int exact_run_numeric(hl_buf *out, int *code, hl_system *sys, const cli_opts *o, hl_error *err)
{
    (void)o;
    int N = hl_system_ndof(sys);
    double z[2 * 8], r[2 * 8];
    if (N > 8)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "--init: at most 8 dof here");
    double dt = 0.5;
    if (exact_mode.dt != NULL) {
        char *end;
        dt = strtod(exact_mode.dt, &end);
        if (*end || !isfinite(dt) || dt == 0)
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "--dt must be a non-zero number");
    }
    int st = hl_run_init_values(z, sys, exact_mode.init, err);
    if (st != HL_OK) {
        hl_error_prefix(err, "in --init");
        return st;
    }
    memcpy(r, z, sizeof(double) * 2 * N);
    hl_exact_flow *f = NULL;
    st = hl_exact_flow_new(&f, sys, err);
    if (st != HL_OK)
        return st;
    double T = NAN;
    if (!hl_exact_flow_is_linear(f)) {
        st = hl_exact_flow_period(&T, z, f, err);
        if (st == HL_OK)
            hl_buf_printf(out,
                          "orbit through the initial point: period T = %.17g, "
                          "frequency 2 pi/T = %.17g\n",
                          T, 2 * M_PI / T);
    } else
        hl_buf_printf(out, "H quadratic: the exact step is exp(%s A) (matrix exponential)\n",
                      hl_system_step(sys));
    exact_json_section("orbit");
    exact_json_bool("quadratic", hl_exact_flow_is_linear(f));
    exact_json_double("period", T);
    exact_json_double("frequency", 2 * M_PI / T);
    /* reference: the Taylor integrator at 1e-15 */
    hl_tape *tape = NULL;
    hl_flow *fl = NULL;
    const char *nq[8], *np[8];
    for (int j = 0; j < N; j++)
        nq[j] = hl_system_coord(sys, j), np[j] = hl_system_momentum(sys, j);
    if (st == HL_OK)
        st = hl_tape_hamiltonian(&tape, hl_system_pool(sys), hl_system_H_expr(sys), N, nq, np, 0,
                                 NULL, NULL, err);
    if (st == HL_OK)
        st = hl_flow_new(&fl, tape, 1e-15, 1e-15, err);
    double maxd = 0, t = 0;
    for (int n = 1; n <= 8 && st == HL_OK; n++) {
        st = hl_exact_flow_step(z, dt, f, err);
        if (st == HL_OK)
            st = hl_flow_evolve(fl, &t, n * dt, r, err);
        for (int i = 0; i < 2 * N && st == HL_OK; i++)
            maxd = fmax(maxd, fabs(z[i] - r[i]));
    }
    if (st == HL_OK) {
        hl_buf_printf(out, "after 8 exact steps of %s = %g:", hl_system_step(sys), dt);
        for (int i = 0; i < 2 * N; i++) {
            char *nm = cli_image_name(sys, i);
            hl_buf_printf(out, " %s = %.17g", nm, z[i]);
            free(nm);
        }
        hl_buf_printf(out, "\nmax difference from the Taylor integrator (tol 1e-15): %.3g\n", maxd);
        exact_json_section("exact_steps");
        exact_json_double("dt", dt);
        exact_json_double("count", 8);
        exact_json_object("final_state");
        for (int i = 0; i < 2 * N; i++) {
            char *nm = cli_image_name(sys, i);
            exact_json_double(nm, z[i]);
            free(nm);
        }
        exact_json_close_to(1);
        exact_json_double("max_difference_from_taylor", maxd);
        exact_json_double("taylor_tol", 1e-15);
        *code = maxd < 1e-11 ? CLI_OK : CLI_FAILS;
    }
    if (st == HL_OK && exact_mode.digits != NULL) {
        int c2 = CLI_OK;
        st = run_numeric_arb(out, &c2, sys, dt, z, err);
        if (c2 != CLI_OK)
            *code = c2;
    }
    hl_flow_free(fl);
    hl_tape_free(tape);
    hl_exact_flow_free(f);
    return st;
}
