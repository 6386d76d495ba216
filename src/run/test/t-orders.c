/* Observed global orders against the theoretical ones: each scheme run to
 * t = 2 with three steps h, h/2, h/4 against the Taylor reference; the two
 * observed orders log(e1/e2)/log 2 must be within 0.15 of the order in the
 * literature (HLW): euler 1, symplectic Euler 1, Stormer-Verlet 2, implicit
 * midpoint 2, rk4 4, gauss2 4 (and gauss3 6, avf 2, gonzalez 2, yoshida4 4,
 * lie (n = 4) 4, itoh-abe 2 here, 1 on a non-separable H) on the pendulum
 * from (1.3, 0); and every one of them
 * on Henon-Heiles (E = 1/8) and Kepler (e = 0.5).  The error measure (max
 * over steps of |z_k - z(t_k)|) is also compared with the final-time one. */
#include "run_test.h"

static void order_case(const char *H, const char *init, const char *scheme, double h,
                       double want)
{
    fixture f;
    if (!fixture_new(&f, H, scheme, init))
        return;
    double dts[3] = {h, h / 2, h / 4}, e[3], ef[3], ord[3];
    hl_error err;
    int st = hl_run_orders(e, ef, ord, f.run, f.z0, dts, 3, 2.0, &err);
    CHECK_MSG(st == HL_OK, "%s %s: %s", H, scheme, err.msg);
    if (st == HL_OK) {
        printf("%-20s %-45s errors %.3e %.3e %.3e  orders %.3f %.3f\n", scheme, H, e[0],
               e[1], e[2], ord[1], ord[2]);
        for (int i = 1; i < 3; i++) {
            CHECK_MSG(fabs(ord[i] - want) < 0.15, "%s on %s: observed order %.3f, want %g",
                      scheme, H, ord[i], want);
            /* independent of the driver's arithmetic: recompute from e */
            CHECK(fabs(ord[i] - log(e[i - 1] / e[i]) / log(2.0)) < 1e-12);
        }
        CHECK(ef[2] <= e[2]);
        CHECK(e[2] > 1e-13); /* above the reference's own error */
    }
    fixture_clear(&f);
}

int main(void)
{
    const char *pinit = "q=1.3,p=0";
    order_case(PENDULUM, pinit, "euler", 0.004, 1);
    order_case(PENDULUM, pinit, "symplectic-euler-a", 0.004, 1);
    order_case(PENDULUM, pinit, "symplectic-euler-b", 0.004, 1);
    order_case(PENDULUM, pinit, "stormer-verlet-kdk", 0.05, 2);
    order_case(PENDULUM, pinit, "stormer-verlet-dkd", 0.05, 2);
    order_case(PENDULUM, pinit, "implicit-midpoint", 0.05, 2);
    order_case(PENDULUM, pinit, "rk4", 0.1, 4);
    order_case(PENDULUM, pinit, "gauss2", 0.1, 4);
    order_case(PENDULUM, pinit, "gauss3", 0.2, 6);
    order_case(PENDULUM, pinit, "avf", 0.05, 2);
    order_case(PENDULUM, pinit, "gonzalez", 0.05, 2);
    /* Itoh-Abe is of order 1 in general; for a separable H = T(p) + V(q) in
     * one dof its discrete gradient is ((V(Q)-V(q))/(Q-q), (T(P)-T(p))/(P-p)),
     * the symmetric one of the average vector field: order 2 */
    order_case(PENDULUM, pinit, "itoh-abe", 0.05, 2);
    order_case("(1 + q^2/2)*p^2/2 - cos(q)", pinit, "itoh-abe", 0.004, 1);
    order_case("(1 + q^2/2)*p^2/2 - cos(q)", pinit, "gauss2", 0.1, 4);
    order_case(PENDULUM, pinit, "yoshida4", 0.1, 4);
    order_case(PENDULUM, pinit, "lie4", 0.1, 4); /* the Lie series truncated after D^4 */
    order_case(PENDULUM, pinit, "lie6", 0.2, 6);

    /* every scheme of the catalog that is not for the oscillator only, on
     * Henon-Heiles (E = 1/8: x = 0, y = 0.1, py = 0.3, px from E) and on
     * Kepler (e = 0.5, a = 1, from the pericentre); the steps are chosen in
     * the asymptotic regime and with errors well above the reference's */
    const char *hinit = "x=0,y=0.1,py=0.3,px=sqrt(2*(1/8) - 0.09 - 0.01 + 2*0.1^3/3)";
    const char *kinit = "x=0.5,y=0,px=0,py=sqrt(3)";
    static const struct {
        const char *scheme;
        double hh, kepler, order;
    } every[] = {
        {"euler", 0.004, 0.0005, 1},           {"symplectic-euler-a", 0.004, 0.0005, 1},
        {"symplectic-euler-b", 0.004, 0.0005, 1}, {"stormer-verlet-kdk", 0.05, 0.01, 2},
        {"stormer-verlet-dkd", 0.05, 0.01, 2}, {"implicit-midpoint", 0.05, 0.01, 2},
        {"rk4", 0.1, 0.02, 4},                 {"gauss2", 0.1, 0.02, 4},
        {"gauss3", 0.2, 0.05, 6},              {"avf", 0.05, 0.01, 2},
        {"gonzalez", 0.05, 0.01, 2},           {"yoshida4", 0.1, 0.02, 4},
        {"lie4", 0.1, 0.02, 4},
    };
    for (size_t i = 0; i < sizeof every / sizeof every[0]; i++) {
        order_case(HENON, hinit, every[i].scheme, every[i].hh, every[i].order);
        order_case(KEPLER, kinit, every[i].scheme, every[i].kepler, every[i].order);
    }
    /* Itoh-Abe: order 1 when H is not separable in one dof (see above) */
    order_case(HENON, hinit, "itoh-abe", 0.004, 1);
    order_case(KEPLER, kinit, "itoh-abe", 0.0005, 1);
    return HL_TEST_END();
}
