/* Reading a sweep's spec (sweep.h): the system's variables, the points, the
 * parameter values crossed, the schemes and the steps; the members counted
 * and the columns named.  Every error points into the field at fault. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "base/buf.h"
#include "hamlie/flow.h"
#include "sweep/sweep_impl.h"

/* Changes whenever a sweep's results could change for the same spec. */
#define SWEEP_FORMAT "hamlie 0.1.0 sweep 1"

static char *dup_or_null(const char *s)
{
    return s != NULL ? hl_xstrdup(s) : NULL;
}

static void copy_spec(hl_sweep *sw, const hl_sweep_spec *spec)
{
    sw->spec = *spec;
    sw->spec.H = dup_or_null(spec->H);
    sw->spec.pairs = dup_or_null(spec->pairs);
    sw->spec.params = dup_or_null(spec->params);
    sw->spec.grid = dup_or_null(spec->grid);
    sw->spec.points_csv = dup_or_null(spec->points_csv);
    sw->spec.points_csv_name = dup_or_null(spec->points_csv_name);
    sw->spec.random = dup_or_null(spec->random);
    sw->spec.schemes = dup_or_null(spec->schemes);
    sw->spec.dts = dup_or_null(spec->dts);
    sw->spec.event = dup_or_null(spec->event);
    if (!(sw->spec.tol > 0))
        sw->spec.tol = 1e-15;
}

/* ---- parameters ----------------------------------------------------------- */

/* "k=1,2,eps=0:0.1:11": each name's values, numbers and ranges a:b:n. */
static hl_status read_params(hl_sweep *sw, hl_system *bare, hl_error *err)
{
    const char *text = sw->spec.params;
    sweep_item *it;
    int n, st = sweep_items(&it, &n, text, "params", err);
    sw->nparamsets = 1;
    if (st != HL_OK)
        return st;
    sw->param = hl_xcalloc((size_t)n, sizeof *sw->param);
    for (int k = 0; st == HL_OK && k < n; k++) {
        sweep_param *p = &sw->param[sw->nparam++];
        p->name = hl_xcalloc((size_t)it[k].name_len + 1, 1);
        memcpy(p->name, text + it[k].name, (size_t)it[k].name_len);
        int known = 0;
        for (int i = 0; i < hl_system_nparams(bare); i++)
            known |= strcmp(hl_system_param(bare, i), p->name) == 0;
        for (int j = 0; j < k; j++)
            if (strcmp(sw->param[j].name, p->name) == 0)
                st = hl_error_set(err, HL_EINVAL, text, it[k].name, it[k].name_len,
                                  "params: '%s' is given twice", p->name);
        if (st == HL_OK && !known)
            st = hl_error_set(err, HL_EINVAL, text, it[k].name, it[k].name_len,
                              "params: '%s' is not a parameter of H", p->name);
        sweep_axis ax = {0, NULL, 0};
        for (int j = 0; st == HL_OK && j < it[k].nval; j++) {
            /* the grid's reader of numbers and ranges, on a one-axis grid */
            st = sweep_axis_values(&ax, text, it[k].val[j], it[k].val_len[j], "params", err);
        }
        p->v = ax.v;
        p->n = ax.n;
        if (st == HL_OK && (double)sw->nparamsets * (double)p->n > HL_SWEEP_MAX_MEMBERS)
            st = hl_error_set(err, HL_ELIMIT, text, it[k].name, it[k].name_len,
                              "params: more than %ld sets of values", HL_SWEEP_MAX_MEMBERS);
        if (st == HL_OK)
            sw->nparamsets *= p->n;
    }
    sweep_items_free(it, n);
    return st;
}

double sweep_param_value(const hl_sweep *sw, long paramset, int i)
{
    for (int k = sw->nparam - 1; k > i; k--) /* the last parameter varies fastest */
        paramset /= sw->param[k].n;
    return sw->param[i].v[paramset % sw->param[i].n];
}

char *sweep_paramset_text(const hl_sweep *sw, long paramset)
{
    if (sw->nparam == 0)
        return NULL;
    hl_buf b;
    hl_buf_init(&b);
    for (int i = 0; i < sw->nparam; i++) {
        char num[32];
        hl_run_fmt(num, sweep_param_value(sw, paramset, i));
        hl_buf_printf(&b, "%s%s=%s", i ? "," : "", sw->param[i].name, num);
    }
    return hl_buf_take(&b);
}

/* ---- schemes and steps ---------------------------------------------------- */

/* The item of a comma list that starts at a: [*ta, *tb), without its
 * spaces.  Returns where it ends (its comma, or len). */
static int list_field(const char *text, int len, int a, int *ta, int *tb)
{
    int b = a;
    while (b < len && text[b] != ',')
        b++;
    *ta = a, *tb = b;
    while (*ta < *tb && text[*ta] == ' ')
        ++*ta;
    while (*tb > *ta && text[*tb - 1] == ' ')
        --*tb;
    return b;
}

static hl_status read_schemes(hl_sweep *sw, hl_system *sys, hl_error *err)
{
    const char *text = sw->spec.schemes;
    if (text == NULL)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no scheme: name one or more");
    int len = (int)strlen(text), st = HL_OK;
    for (int a = 0; st == HL_OK && a <= len;) {
        int ta, tb, b = list_field(text, len, a, &ta, &tb);
        char *name = hl_xcalloc((size_t)(tb - ta) + 1, 1);
        memcpy(name, text + ta, (size_t)(tb - ta));
        sw->scheme = hl_xrealloc(sw->scheme, (size_t)(sw->nschemes + 1) * sizeof *sw->scheme);
        sw->scheme[sw->nschemes++] = name;
        if (ta == tb)
            st = hl_error_set(err, HL_EPARSE, text, ta < len ? ta : (len ? len - 1 : 0), 1,
                              "schemes: an empty name");
        for (int j = 0; st == HL_OK && j < sw->nschemes - 1; j++)
            if (strcmp(sw->scheme[j], name) == 0)
                st = hl_error_set(err, HL_EINVAL, text, ta, tb - ta, "schemes: '%s' is given twice",
                                  name);
        if (st == HL_OK && strcmp(name, "lie") != 0) {
            hl_scheme *s = NULL;
            hl_error e;
            hl_error_clear(&e);
            if (hl_scheme_new(&s, name, 4, sys, &e) != HL_OK)
                st = hl_error_set(err, e.status, text, ta, tb - ta, "schemes: %s", e.msg);
            hl_scheme_free(s);
        }
        a = b + 1;
    }
    return st;
}

static int any_fixed(const hl_sweep *sw)
{
    for (int i = 0; i < sw->nschemes; i++)
        if (strcmp(sw->scheme[i], "lie") != 0)
            return 1;
    return 0;
}

static hl_status read_dts(hl_sweep *sw, hl_error *err)
{
    const char *text = sw->spec.dts;
    if (!(sw->spec.t > 0) || !isfinite(sw->spec.t))
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the final time t must be positive and "
                            "finite, not %g",
                            sw->spec.t);
    if (text == NULL) {
        if (any_fixed(sw))
            return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                                "no step: a fixed-step scheme needs dt (one or more)");
        sw->dt = hl_xcalloc(1, sizeof *sw->dt);
        sw->dt[sw->ndts++] = sw->spec.t;
        return HL_OK;
    }
    int len = (int)strlen(text), st = HL_OK;
    for (int a = 0; st == HL_OK && a <= len;) {
        int ta, tb, b = list_field(text, len, a, &ta, &tb);
        double dt = 0;
        long n;
        hl_error e;
        hl_error_clear(&e);
        st = sweep_number(&dt, text, ta, tb - ta, "dt", err);
        if (st == HL_OK && hl_run_nsteps(&n, dt, sw->spec.t, &e) != HL_OK)
            st = hl_error_set(err, e.status, text, ta, tb - ta, "dt: %s", e.msg);
        sw->dt = hl_xrealloc(sw->dt, (size_t)(sw->ndts + 1) * sizeof *sw->dt);
        sw->dt[sw->ndts++] = dt;
        a = b + 1;
    }
    return st;
}

/* ---- columns -------------------------------------------------------------- */

static void add_col(hl_sweep *sw, const char *fmt, const char *name)
{
    char buf[256];
    snprintf(buf, sizeof buf, fmt, name);
    sw->col = hl_xrealloc(sw->col, (size_t)(sw->ncols + 1) * sizeof *sw->col);
    sw->col[sw->ncols++] = hl_xstrdup(buf);
}

static void name_columns(hl_sweep *sw)
{
    static const char *const head[] = {"member", "point", "paramset", "scheme", "dt"};
    static const char *const mid[] = {"t", "steps", "H0", "max_dH", "dH", "max_err", "err"};
    for (int i = 0; i < 5; i++)
        add_col(sw, "%s", head[i]);
    sw->c_param = sw->ncols;
    for (int i = 0; i < sw->nparam; i++)
        add_col(sw, "%s", sw->param[i].name);
    sw->c_z0 = sw->ncols;
    for (int i = 0; i < 2 * sw->N; i++)
        add_col(sw, "%s0", sw->var[i]);
    sw->c_t = sw->ncols;
    for (int i = 0; i < 7; i++)
        add_col(sw, "%s", mid[i]);
    sw->c_order = sw->ncols;
    add_col(sw, "%s", "order");
    sw->c_megno = sw->ncols;
    add_col(sw, "%s", "megno");
    add_col(sw, "%s", "mlce");
    sw->c_z = sw->ncols;
    for (int i = 0; i < 2 * sw->N; i++)
        add_col(sw, "%s", sw->var[i]);
}

/* ---- fingerprint: FNV-1a over everything that decides the results --------- */

static uint64_t fnv(uint64_t h, const void *p, size_t n)
{
    const unsigned char *c = p;
    for (size_t i = 0; i < n; i++)
        h = (h ^ c[i]) * 0x100000001B3ULL;
    return h;
}

static uint64_t fnv_str(uint64_t h, const char *s)
{
    unsigned char tag = s != NULL; /* NULL and "" differ */
    h = fnv(h, &tag, 1);
    return s != NULL ? fnv(h, s, strlen(s) + 1) : h;
}

static uint64_t fingerprint(const hl_sweep *sw)
{
    const hl_sweep_spec *s = &sw->spec;
    uint64_t h = fnv_str(0xCBF29CE484222325ULL, SWEEP_FORMAT);
    const char *texts[] = {s->H,          s->pairs,  s->params,  s->grid,
                           s->points_csv, s->random, s->schemes, s->dts};
    for (size_t i = 0; i < sizeof texts / sizeof texts[0]; i++)
        h = fnv_str(h, texts[i]);
    long nr = s->random != NULL ? s->nrandom : 0;
    h = fnv(h, &nr, sizeof nr);
    uint64_t seed = s->random != NULL ? s->seed : 0;
    h = fnv(h, &seed, sizeof seed);
    h = fnv(h, &s->t, sizeof s->t);
    h = fnv(h, &s->tol, sizeof s->tol);
    int flags[3] = {s->reference != 0, s->order != 0, s->chaos != 0};
    h = fnv(h, flags, sizeof flags);
    if (s->save_every > 0 || s->event != NULL) { /* a sweep without arrays keeps its print */
        h = fnv(h, &s->save_every, sizeof s->save_every);
        h = fnv_str(h, s->event);
        h = fnv(h, &s->direction, sizeof s->direction);
    }
    return h;
}

/* ---- the sweep ------------------------------------------------------------ */

static hl_status read_points(hl_sweep *sw, hl_error *err)
{
    const hl_sweep_spec *s = &sw->spec;
    int sources = (s->grid != NULL) + (s->points_csv != NULL) + (s->random != NULL);
    if (sources != 1)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                            "the points come from exactly one of a grid, a CSV file and random "
                            "bounds (%d given)",
                            sources);
    if (s->grid != NULL) {
        sw->source = SWEEP_GRID;
        return sweep_read_grid(sw, s->grid, err);
    }
    if (s->random != NULL) {
        sw->source = SWEEP_RANDOM;
        return sweep_read_random(sw, s->random, err);
    }
    sw->source = SWEEP_CSV;
    int st = sweep_read_csv(sw, s->points_csv, err);
    if (st != HL_OK && s->points_csv_name != NULL)
        hl_error_prefix(err, "%s", s->points_csv_name);
    return st;
}

static hl_status system_for(hl_system **sys, const hl_sweep *sw, long paramset, hl_error *err)
{
    char *params = paramset >= 0 ? sweep_paramset_text(sw, paramset) : NULL;
    hl_system_spec ss = {sw->spec.H, sw->spec.pairs, params, NULL, NULL};
    int st = hl_system_new(sys, &ss, err);
    free(params);
    return st;
}

hl_status sweep_system(hl_system **sys, const hl_sweep *sw, long paramset, hl_error *err)
{
    return system_for(sys, sw, paramset, err);
}

static hl_status read_all(hl_sweep *sw, hl_error *err)
{
    hl_system *bare = NULL, *sys = NULL;
    if (sw->spec.H == NULL)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "a sweep needs a Hamiltonian");
    int st = system_for(&bare, sw, -1, err);
    if (st == HL_OK) {
        sw->N = hl_system_ndof(bare);
        sw->var = hl_xcalloc((size_t)(2 * sw->N), sizeof *sw->var);
        for (int i = 0; i < 2 * sw->N; i++)
            sw->var[i] = hl_xstrdup(i < sw->N ? hl_system_coord(bare, i)
                                              : hl_system_momentum(bare, i - sw->N));
    }
    sw->nparamsets = 1;
    if (st == HL_OK && sw->spec.params != NULL)
        st = read_params(sw, bare, err);
    if (st == HL_OK)
        st = read_points(sw, err);
    if (st == HL_OK)
        st = system_for(&sys, sw, 0, err);
    if (st == HL_OK)
        st = read_schemes(sw, sys, err);
    if (st == HL_OK)
        st = read_dts(sw, err);
    if (st == HL_OK)
        st = sweep_check_event(sw, sys, err);
    if (st == HL_OK && sw->spec.chaos) { /* a symbolic parameter left: said now, not per member */
        hl_chaos *c = NULL;
        st = hl_chaos_new(&c, sys, sw->spec.tol, err);
        hl_chaos_free(c);
    }
    hl_system_free(bare);
    hl_system_free(sys);
    return st;
}

static hl_status count_members(hl_sweep *sw, hl_error *err)
{
    double total = (double)sw->npoints * (double)sw->nparamsets * sw->nschemes * sw->ndts;
    if (total > HL_SWEEP_MAX_MEMBERS)
        return hl_error_set(err, HL_ELIMIT, NULL, -1, 0, "%.3g members: more than %ld", total,
                            HL_SWEEP_MAX_MEMBERS);
    sw->count = (long)total;
    return HL_OK;
}

/* An error in a field points into the sweep's copy, about to be freed:
 * into the caller's text instead (the same bytes). */
static void point_at_callers_text(hl_error *err, const hl_sweep *sw, const hl_sweep_spec *spec)
{
    if (err == NULL || err->src == NULL)
        return;
    const char *const mine[] = {sw->spec.H,       sw->spec.pairs,      sw->spec.params,
                                sw->spec.grid,    sw->spec.points_csv, sw->spec.random,
                                sw->spec.schemes, sw->spec.dts,        sw->spec.event};
    const char *const theirs[] = {spec->H,       spec->pairs,      spec->params,
                                  spec->grid,    spec->points_csv, spec->random,
                                  spec->schemes, spec->dts,        spec->event};
    int found = 0;
    for (size_t i = 0; i < sizeof mine / sizeof mine[0]; i++)
        if (mine[i] != NULL && err->src == mine[i]) {
            err->src = theirs[i];
            found = 1;
        }
    if (!found) /* a text of the sweep's own making (a system's): no position to show */
        err->src = NULL, err->pos = -1;
}

hl_status hl_sweep_new(hl_sweep **out, const hl_sweep_spec *spec, hl_error *err)
{
    *out = NULL;
    hl_sweep *sw = hl_xcalloc(1, sizeof *sw);
    copy_spec(sw, spec);
    int st = HL_OK;
    if (!(sw->spec.tol >= HL_FLOW_MIN_RTOL) || !isfinite(sw->spec.tol))
        st = hl_error_set(err, HL_EINVAL, NULL, -1, 0,
                          "the tolerance must be finite and at least %.2g, not %g",
                          HL_FLOW_MIN_RTOL, sw->spec.tol);
    if (st == HL_OK)
        st = read_all(sw, err);
    if (st == HL_OK)
        st = count_members(sw, err);
    if (st != HL_OK) {
        point_at_callers_text(err, sw, spec);
        hl_sweep_free(sw);
        return st;
    }
    name_columns(sw);
    sw->has_array[HL_SWEEP_TRAJ] = sw->spec.save_every > 0;
    sw->has_array[HL_SWEEP_CROSS] = sw->spec.event != NULL;
    sw->fingerprint = fingerprint(sw);
    *out = sw;
    return HL_OK;
}

void hl_sweep_free(hl_sweep *sw)
{
    if (sw == NULL)
        return;
    const char *texts[] = {sw->spec.H,      sw->spec.pairs,      sw->spec.params,
                           sw->spec.grid,   sw->spec.points_csv, sw->spec.points_csv_name,
                           sw->spec.random, sw->spec.schemes,    sw->spec.dts,
                           sw->spec.event};
    for (size_t i = 0; i < sizeof texts / sizeof texts[0]; i++)
        free((char *)texts[i]);
    for (int i = 0; sw->var != NULL && i < 2 * sw->N; i++)
        free(sw->var[i]);
    free(sw->var);
    for (int i = 0; sw->axis != NULL && i < 2 * sw->N; i++)
        free(sw->axis[i].v);
    free(sw->axis);
    free(sw->csv_points);
    for (int i = 0; i < sw->nparam; i++) {
        free(sw->param[i].name);
        free(sw->param[i].v);
    }
    free(sw->param);
    for (int i = 0; i < sw->nschemes; i++)
        free(sw->scheme[i]);
    free(sw->scheme);
    free(sw->dt);
    for (int i = 0; i < sw->ncols; i++)
        free(sw->col[i]);
    free(sw->col);
    free(sw);
}

long hl_sweep_count(const hl_sweep *sw)
{
    return sw->count;
}
int hl_sweep_ncols(const hl_sweep *sw)
{
    return sw->ncols;
}
const char *hl_sweep_column(const hl_sweep *sw, int c)
{
    return c >= 0 && c < sw->ncols ? sw->col[c] : NULL;
}
int hl_sweep_nschemes(const hl_sweep *sw)
{
    return sw->nschemes;
}
int hl_sweep_ndof(const hl_sweep *sw)
{
    return sw->N;
}
long hl_sweep_npoints(const hl_sweep *sw)
{
    return sw->npoints;
}
void hl_sweep_point(const hl_sweep *sw, long i, double *z)
{
    if (i >= 0 && i < sw->npoints)
        sweep_point(sw, i, z);
}
int hl_sweep_column_index(const hl_sweep *sw, const char *name)
{
    for (int c = 0; c < sw->ncols; c++)
        if (strcmp(sw->col[c], name) == 0)
            return c;
    return -1;
}
const char *hl_sweep_scheme(const hl_sweep *sw, int i)
{
    return i >= 0 && i < sw->nschemes ? sw->scheme[i] : NULL;
}
const hl_sweep_spec *hl_sweep_get_spec(const hl_sweep *sw)
{
    return &sw->spec;
}
uint64_t hl_sweep_fingerprint(const hl_sweep *sw)
{
    return sw->fingerprint;
}

sweep_where sweep_locate(const hl_sweep *sw, long m)
{
    sweep_where w;
    w.dt = (int)(m % sw->ndts);
    m /= sw->ndts;
    w.scheme = (int)(m % sw->nschemes);
    m /= sw->nschemes;
    w.paramset = m % sw->nparamsets;
    w.point = m / sw->nparamsets;
    return w;
}
