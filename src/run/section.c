/* Surfaces of section: seeding on H = E and the crossings of each orbit
 * (see hamlie/section.h). */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "hamlie/section.h"

struct hl_section {
    hl_system *sys;
    char *surface;
    hl_event_dir dir;
    double E, c;
    int N, j;   /* q_j = c */
    hl_tape *H; /* H over q then p */
    double *z;  /* 2N scratch */
};

static const char *var_name(hl_system *sys, int i)
{
    int N = hl_system_ndof(sys);
    return i < N ? hl_system_coord(sys, i) : hl_system_momentum(sys, i - N);
}

hl_status hl_section_new(hl_section **out, hl_system *sys, const char *surface, hl_event_dir dir,
                         double E, hl_error *err)
{
    *out = NULL;
    if (!isfinite(E))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "the energy must be finite (E = %g)", E);
    hl_run_surface_info info;
    int st = hl_run_surface(&info, sys, surface, err);
    if (st != HL_OK)
        return st;
    int N = hl_system_ndof(sys);
    if (info.var < 0 || info.var >= N)
        return hl_error_set(err, HL_EINVAL, surface, 0, (int)strlen(surface),
                            "a surface of section is 'coordinate = constant' (e.g. %s=0), so "
                            "that the conjugate momentum can be solved from H = E",
                            hl_system_coord(sys, 0));
    const char **names = hl_xmalloc((size_t)(2 * N) * sizeof *names);
    for (int i = 0; i < 2 * N; i++)
        names[i] = var_name(sys, i);
    const hl_expr *H = hl_system_H_expr(sys);
    hl_tape *tape = NULL;
    st = hl_tape_new(&tape, &H, 1, names, 2 * N, err);
    free(names);
    if (st != HL_OK)
        return st;
    hl_section *s = hl_xcalloc(1, sizeof *s);
    s->sys = sys;
    s->surface = hl_xstrdup(surface);
    s->dir = dir;
    s->E = E;
    s->c = info.value;
    s->N = N;
    s->j = info.var;
    s->H = tape;
    s->z = hl_xcalloc((size_t)(2 * N), sizeof *s->z);
    *out = s;
    return HL_OK;
}

void hl_section_free(hl_section *s)
{
    if (s == NULL)
        return;
    hl_tape_free(s->H);
    free(s->surface);
    free(s->z);
    free(s);
}

int hl_section_coord(const hl_section *s)
{
    return s->j;
}
int hl_section_momentum(const hl_section *s)
{
    return s->N + s->j;
}
double hl_section_value(const hl_section *s)
{
    return s->c;
}

hl_system *hl_section_system(const hl_section *s)
{
    return s->sys;
}
hl_event_dir hl_section_direction(const hl_section *s)
{
    return s->dir;
}
double hl_section_energy(const hl_section *s)
{
    return s->E;
}

/* H(z) - E with z[i] = v */
static double excess(hl_section *s, double *z, int i, double v)
{
    z[i] = v;
    double h;
    hl_tape_eval_d(&h, z, s->H);
    return h - s->E;
}

/* "(y = 0.1, py = 0)": the point without the solved momentum */
static void describe(hl_buf *b, hl_section *s, const double *z)
{
    int first = 1;
    for (int i = 0; i < 2 * s->N; i++)
        if (i != s->N + s->j) {
            hl_buf_printf(b, "%s%s = %.17g", first ? "" : ", ", var_name(s->sys, i), z[i]);
            first = 0;
        }
}

/* A root of H = E in p_j between 0 (excess f0 <= 0) and sign * infinity. */
static int solve_momentum(hl_section *s, double *z, double sign, hl_error *err)
{
    const int i = s->N + s->j;
    double f0 = excess(s, z, i, 0);
    hl_buf b;
    hl_buf_init(&b);
    describe(&b, s, z);
    const char *p = var_name(s->sys, i);
    int st = HL_OK;
    if (!isfinite(f0))
        st = hl_error_set(err, HL_EDOM, NULL, -1, 0, "H is not finite at %s = 0 (%s)", p, b.s);
    else if (f0 > 0)
        st = hl_error_set(err, HL_EDOM, NULL, -1, 0,
                          "H = E has no real solution for %s at (%s): H = %.17g > E = %.17g "
                          "already at %s = 0 (the point is outside the allowed region)",
                          p, b.s, f0 + s->E, s->E, p);
    double lo = 0, hi = 1, fhi = NAN;
    for (int k = 0; st == HL_OK && k < 1100 && !((fhi = excess(s, z, i, sign * hi)) > 0); k++) {
        if (!isfinite(fhi) || hi > 1e300) {
            st = hl_error_set(err, HL_EDOM, NULL, -1, 0,
                              "H = E has no real solution for %s at (%s): H stays below E as "
                              "|%s| grows (or is not finite)",
                              p, b.s, p);
            break;
        }
        lo = hi;
        hi *= 2;
    }
    if (f0 == 0 && st == HL_OK)
        hi = 0;
    /* bisection to round-off: p has no better start than the bracket */
    while (st == HL_OK && hi - lo > 2 * DBL_EPSILON * hi && hi > DBL_MIN) {
        double m = lo + (hi - lo) / 2;
        if (m <= lo || m >= hi)
            break;
        if (excess(s, z, i, sign * m) > 0)
            hi = m;
        else
            lo = m;
    }
    if (st == HL_OK) { /* the end nearer H = E */
        double flo = excess(s, z, i, sign * lo), fh = excess(s, z, i, sign * hi);
        z[i] = sign * (fabs(flo) <= fabs(fh) ? lo : hi);
    }
    hl_buf_clear(&b);
    return st;
}

hl_status hl_section_complete(hl_section *s, double *z, hl_error *err)
{
    z[s->j] = s->c;
    return solve_momentum(s, z, s->dir == HL_EVENT_DOWN ? -1 : 1, err);
}

/* ---- spreading orbits along the line of the other coordinate ------------- */

#define SCAN_POINTS 4001
#define SCAN_R_MAX 1e4

/* H - E on the line: q_j = c, q_o = v, both momenta 0 */
static double line_excess(hl_section *s, int o, double v)
{
    memset(s->z, 0, (size_t)(2 * s->N) * sizeof *s->z);
    s->z[s->j] = s->c;
    double f = excess(s, s->z, o, v);
    return isfinite(f) ? f : INFINITY; /* outside H's domain: not allowed */
}

/* The boundary between a (allowed) and b (not): bisection to round-off. */
static double edge(hl_section *s, int o, double a, double b)
{
    for (int k = 0; k < 200; k++) {
        double m = a + (b - a) / 2;
        if (m == a || m == b)
            break;
        if (line_excess(s, o, m) <= 0)
            a = m;
        else
            b = m;
    }
    return a;
}

/* The minimum of the line's excess near v (golden section on [v-w, v+w]). */
static double line_min(hl_section *s, int o, double v, double w, double *at)
{
    const double g = (sqrt(5) - 1) / 2;
    double a = v - w, b = v + w;
    for (int k = 0; k < 200 && b - a > 4 * DBL_EPSILON * fmax(1, fabs(a)); k++) {
        double c = b - g * (b - a), d = a + g * (b - a);
        if (line_excess(s, o, c) < line_excess(s, o, d))
            b = d;
        else
            a = c;
    }
    *at = (a + b) / 2;
    return line_excess(s, o, *at);
}

/* Of the runs of samples with f <= 0 in f[0..n-1], the bounded one (not
 * touching an end) holding the least f: 1 with [*l, *r], else 0.
 * *unbounded = 1 if a run touches an end. */
static int bounded_run(const double *f, int n, int *l, int *r, int *unbounded)
{
    int found = 0;
    double least = INFINITY;
    *unbounded = 0;
    for (int k = 0; k < n;) {
        if (!(f[k] <= 0)) {
            k++;
            continue;
        }
        int a = k, lo = k;
        for (; k < n && f[k] <= 0; k++)
            lo = f[k] < f[lo] ? k : lo;
        if (a == 0 || k == n)
            *unbounded = 1;
        else if (f[lo] < least)
            least = f[lo], *l = a, *r = k - 1, found = 1;
    }
    return found;
}

/* The allowed interval [*a, *b]: the well (bounded part of H <= E on the
 * line) holding the least H, from scans on [-R, R] with R growing. */
static int allowed_interval(hl_section *s, int o, double *a, double *b, hl_error *err)
{
    static double f[SCAN_POINTS];
    double best = INFINITY, best_v = 0, best_w = 1;
    int unbounded = 0;
    for (double R = 1; R <= SCAN_R_MAX; R *= 10) {
        double step = 2 * R / (SCAN_POINTS - 1);
        int kmin = 0, l, r;
        for (int k = 0; k < SCAN_POINTS; k++) {
            f[k] = line_excess(s, o, -R + step * k);
            kmin = f[k] < f[kmin] ? k : kmin;
        }
        if (f[kmin] < best && kmin > 0 && kmin < SCAN_POINTS - 1)
            best = f[kmin], best_v = -R + step * kmin, best_w = step;
        if (bounded_run(f, SCAN_POINTS, &l, &r, &unbounded)) {
            *a = edge(s, o, -R + step * l, -R + step * (l - 1));
            *b = edge(s, o, -R + step * r, -R + step * (r + 1));
            return HL_OK;
        }
    }
    double at = best_v, m = isfinite(best) ? line_min(s, o, best_v, best_w, &at) : INFINITY;
    if (m <= 0) { /* a well narrower than the scan's spacing */
        *a = edge(s, o, at, at - best_w);
        *b = edge(s, o, at, at + best_w);
        return HL_OK;
    }
    const char *q = var_name(s->sys, o);
    if (unbounded)
        return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                            "no allowed region around a minimum: at E = %.17g, H <= E along %s "
                            "(at %s = %g, momenta 0) only out to |%s| = %g (H unbounded below "
                            "there?); give the points (--init-file)",
                            s->E, q, var_name(s->sys, s->j), s->c, q, SCAN_R_MAX);
    return hl_error_set(err, HL_EDOM, NULL, -1, 0,
                        "no allowed region: E = %.17g is below the minimum of H on the section "
                        "(H >= %.10g along %s at %s = %g, momenta 0; the least at %s = %.6g)",
                        s->E, s->E + m, q, var_name(s->sys, s->j), s->c, q, at);
}

hl_status hl_section_spread(hl_section *s, double *zs, int M, double *lo, double *hi, hl_error *err)
{
    if (s->N != 2)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "orbits are spread over the section for two degrees of freedom "
                            "only (this system has %d): give the points",
                            s->N);
    if (M < 1)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "at least one orbit (not %d)", M);
    int o = 1 - s->j, st;
    double a = 0, b = 0;
    if ((st = allowed_interval(s, o, &a, &b, err)) != HL_OK)
        return st;
    if (lo != NULL)
        *lo = a;
    if (hi != NULL)
        *hi = b;
    for (int i = 0; i < M && st == HL_OK; i++) {
        double *z = zs + (size_t)i * 4;
        memset(z, 0, 4 * sizeof *z);
        z[o] = a + (b - a) * (i + 0.5) / M;
        st = hl_section_complete(s, z, err);
    }
    return st;
}

/* ---- the orbits ------------------------------------------------------------ */

hl_status hl_section_orbit(hl_section *s, hl_run *run, const double *z0, long n,
                           const hl_section_opts *opts, hl_run_crossing_fn fn, void *arg,
                           hl_run_stats *stats, hl_error *err)
{
    hl_run_stats local;
    hl_run_stats *st_ = stats != NULL ? stats : &local;
    if (n < 1)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "at least one crossing (not %ld)", n);
    if (!(opts->t_max > 0) || !isfinite(opts->t_max))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the time bound must be positive (t_max = %g)", opts->t_max);
    int st = hl_run_event(run, s->surface, s->dir, n, fn, arg, err);
    if (st != HL_OK)
        return st;
    hl_run_set_reference(run, 0, 0);
    if (opts->tol > 0)
        st = hl_run_adaptive(run, z0, opts->tol, opts->t_max, opts->t_max, 1, NULL, NULL, st_, err);
    else {
        double steps = ceil(opts->t_max / opts->dt - 1e-9);
        st = hl_run_fixed(run, z0, opts->dt, steps * opts->dt, 1, NULL, NULL, st_, err);
    }
    if (st == HL_OK && st_->crossings < n)
        st = hl_error_set(err, HL_ENOCONV, NULL, -1, 0,
                          "%ld of %ld crossings of %s by t = %g: is the surface crossed in "
                          "this direction? (a longer --t-max?)",
                          st_->crossings, n, s->surface, st_->t);
    return st;
}
