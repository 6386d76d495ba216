/* Long-time energy behaviour on the pendulum from (1.3, 0):
 *   Stormer-Verlet (kick-drift-kick and drift-kick-drift), dt = 0.01,
 *   10^6 steps: the energy error is bounded, not growing: the max of
 *   |H - H0| over the last 10^5 steps is no larger than 1.1 times the max
 *   over the first 10^5 (a secular drift of even 1e-3 of the bound per
 *   10^5 steps would fail), and both are O(dt^2);
 *   rk4 for contrast (not symplectic): its error does grow (dissipative
 *   drift): at dt = 0.05 over 10^6 steps, by more than 5 times;
 *   avf and gonzalez (discrete gradients) keep H to round-off: |H - H0| <
 *   1e-13 over 10^4 steps at dt = 0.01; at dt = 0.1 (where Verlet's is
 *   1e-3) avf 1e-13, gonzalez 1e-12. */
#include "run_test.h"

typedef struct window {
    long n;
    double first, last; /* max |H - H0| over the first / last 10^5 steps */
    double H0;
} window;

static int window_fn(const hl_run_row *row, void *arg)
{
    window *w = arg;
    if (row->k == 0)
        w->H0 = row->H;
    double d = fabs(row->H - w->H0);
    if (row->k <= 100000)
        w->first = fmax(w->first, d);
    if (row->k > w->n - 100000)
        w->last = fmax(w->last, d);
    return 0;
}

static window long_run(const char *scheme, double dt, long n)
{
    window w = {n, 0, 0, 0};
    fixture f;
    if (!fixture_new(&f, PENDULUM, scheme, "q=1.3,p=0"))
        return w;
    hl_run_set_reference(f.run, 0, 0);
    hl_error err;
    hl_run_stats s;
    int st = hl_run_fixed(f.run, f.z0, dt, (double)n * dt, 1, window_fn, &w, &s, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", scheme, err.msg);
    CHECK(s.steps == n && s.max_dH >= fmax(w.first, w.last));
    printf("%-20s dt = %g, %ld steps: max |dH| first 1e5 %.4e, last 1e5 %.4e\n", scheme, dt, n,
           w.first, w.last);
    fixture_clear(&f);
    return w;
}

static void conserves(const char *scheme, double dt, double bound)
{
    fixture f;
    if (!fixture_new(&f, PENDULUM, scheme, "q=1.3,p=0"))
        return;
    hl_run_set_reference(f.run, 0, 0);
    hl_error err;
    hl_run_stats s;
    int st = hl_run_fixed(f.run, f.z0, dt, 1e4 * dt, 1, NULL, NULL, &s, &err);
    CHECK_MSG(st == HL_OK, "%s: %s", scheme, err.msg);
    printf("%-20s dt = %g, 1e4 steps: max |dH| = %.3e\n", scheme, dt, s.max_dH);
    CHECK_MSG(s.steps == 10000 && s.max_dH < bound, "%s at dt = %g: max |dH| = %.3e", scheme,
              dt, s.max_dH);
    fixture_clear(&f);
}

int main(void)
{
    const long n = 1000000;
    window v = long_run("stormer-verlet-kdk", 0.01, n);
    CHECK_MSG(v.last <= 1.1 * v.first, "Verlet energy error grows: %.4e -> %.4e", v.first,
              v.last);
    CHECK(v.first > 1e-6 && v.first < 1e-4); /* O(dt^2) with a constant near 0.1 */
    window v2 = long_run("stormer-verlet-dkd", 0.01, n);
    CHECK_MSG(v2.last <= 1.1 * v2.first, "Verlet (dkd) energy error grows: %.4e -> %.4e",
              v2.first, v2.last);
    window r = long_run("rk4", 0.05, n);
    CHECK_MSG(r.last > 5 * r.first, "rk4 energy error does not grow: %.4e -> %.4e", r.first,
              r.last);
    conserves("avf", 0.01, 1e-13);
    conserves("gonzalez", 0.01, 1e-13);
    /* at dt = 0.1 gonzalez's difference quotient (H(Z) - H(z)) / |Z - z|^2
     * loses more digits: 2.2e-13 measured; still round-off, not O(dt^2) */
    conserves("avf", 0.1, 1e-13);
    conserves("gonzalez", 0.1, 1e-12);
    return HL_TEST_END();
}
