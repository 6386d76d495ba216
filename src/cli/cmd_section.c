/* hamlie section: a surface of section.  Orbits seeded on H = E (spread
 * over the allowed region, or listed in a file), N crossings each, written
 * as CSV (crossings.c) and drawn in one figure (report's section plot).
 * The mathematics is in the library (section.h); this file reads options,
 * loops over the orbits and writes. */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/crossings.h"
#include "hamlie/h5.h"
#include "hamlie/section.h"
#include "hamlie/sectionplot.h"

const char cmd_section_help[] =
    "usage: hamlie section -H FORMULA --energy E --surface x=0 [options]\n"
    "\n"
    "A surface of section (Poincare map): orbits on the energy surface H = E,\n"
    "each followed to its first N crossings of the section, all written as CSV\n"
    "(orbit, crossing, t, the state, H) and drawn in one figure.\n"
    "\n"
    "  -H, --hamiltonian F  the Hamiltonian (required)\n"
    "  --energy E           the energy (a number or a constant formula: 1/8)\n"
    "  --surface q=c        the section: a coordinate = a constant (required); its\n"
    "                       conjugate momentum is solved from H = E\n"
    "  --direction D        up (default: the momentum solved > 0), down (< 0), both\n"
    "  --orbits M           orbits spread over the allowed region (default 10): two\n"
    "                       degrees of freedom, along the other coordinate with its\n"
    "                       momentum 0, at the centres of M equal cells\n"
    "  --init-file F        the orbits' points instead: CSV with a header naming the\n"
    "                       other variables (e.g. y,py), one point a line\n"
    "  --crossings N        crossings per orbit (default 100)\n"
    "  --scheme NAME        lie (default: the adaptive Taylor integrator, crossings\n"
    "                       on its step polynomials to round-off) or any scheme of\n"
    "                       the catalog with --dt (crossings on each step's cubic\n"
    "                       Hermite interpolant, local order 4)\n"
    "  --tol TOL            the adaptive integrator's tolerance (default 1e-13)\n"
    "  --dt STEP            the fixed step of --scheme\n"
    "  --t-max T            each orbit's time bound (default 100 N, at least 1000)\n"
    "  --out FILE           the CSV (default: standard output); FILE.h5 an HDF5\n"
    "                       file with the inputs and each orbit's status too\n"
    "  --plot DIR           draw DIR/section.png: the crossings of every orbit, a\n"
    "                       colour per orbit, in the plane of the other coordinate\n"
    "                       and its momentum\n"
    "  --format png,svg,pdf the figure's formats (default png)\n"
    "  --pairs, --param, --json   as for every command\n"
    "\n"
    "An orbit that fails (a blow-up, fewer than N crossings by --t-max) is named\n"
    "on stderr, its crossings kept, and the others go on.\n"
    "Exit status: 0 every orbit done; 1 some orbit failed (the file is written);\n"
    "2 usage or input error (no allowed region, a point where H = E has no\n"
    "solution), or every orbit failed.\n"
    "Example: hamlie section -H '(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3' \\\n"
    "           --energy 1/8 --surface x=0 --orbits 20 --crossings 300 --plot out/\n";

typedef struct sec_opts {
    const char *energy, *surface, *direction, *orbits_s, *init_file, *crossings_s;
    const char *scheme, *tol_s, *dt_s, *tmax_s, *out, *plot, *formats;
    hl_event_dir dir;
    long orbits, ncross;
    double tol, dt, t_max;
} sec_opts;

static void found_opt(void *arg, int k, const char *value)
{
    sec_opts *s = arg;
    const char **slot[] = {&s->energy,      &s->surface, &s->direction, &s->orbits_s, &s->init_file,
                           &s->crossings_s, &s->scheme,  &s->tol_s,     &s->dt_s,     &s->tmax_s,
                           &s->out,         &s->plot,    &s->formats};
    *slot[k] = value;
}

static int read_long(long *v, const char *s, const char *opt, long lo, long hi,
                     const cli_command *cmd)
{
    char *end;
    errno = 0;
    *v = strtol(s, &end, 10);
    if (*s == '\0' || *end != '\0' || errno != 0 || *v < lo || *v > hi)
        return cli_usage(cmd, "%s wants a whole number from %ld to %ld, not '%s'", opt, lo, hi, s);
    return -1;
}

static int read_double(double *v, const char *s, const char *opt, const cli_command *cmd)
{
    char *end;
    *v = strtod(s, &end);
    if (*s == '\0' || *end != '\0' || !(*v > 0) || !isfinite(*v))
        return cli_usage(cmd, "%s wants a positive number, not '%s'", opt, s);
    return -1;
}

static int adaptive(const sec_opts *s)
{
    return strcmp(s->scheme, "lie") == 0 && s->dt_s == NULL;
}

static int check_opts(void *arg, cli_opts *o, const cli_command *cmd)
{
    sec_opts *s = arg;
    int rc;
    if (o->H == NULL)
        return cli_usage(cmd, "missing -H: the Hamiltonian");
    if (s->energy == NULL || s->surface == NULL)
        return cli_usage(cmd, "missing %s",
                         s->energy == NULL ? "--energy E" : "--surface, e.g. x=0");
    s->dir = HL_EVENT_UP;
    if (s->direction != NULL && crossings_direction(&s->dir, s->direction) != 0)
        return cli_usage(cmd, "--direction wants up, down or both, not '%s'", s->direction);
    if (s->orbits_s != NULL && s->init_file != NULL)
        return cli_usage(cmd, "--orbits spreads the orbits, --init-file lists them: not both");
    s->orbits = 10, s->ncross = 100;
    if (s->orbits_s && (rc = read_long(&s->orbits, s->orbits_s, "--orbits", 1, 100000, cmd)) >= 0)
        return rc;
    if (s->crossings_s &&
        (rc = read_long(&s->ncross, s->crossings_s, "--crossings", 1, 100000000, cmd)) >= 0)
        return rc;
    s->scheme = s->scheme != NULL ? s->scheme : "lie";
    s->tol = 1e-13;
    if (s->tol_s && (rc = read_double(&s->tol, s->tol_s, "--tol", cmd)) >= 0)
        return rc;
    if (s->tol_s != NULL && !adaptive(s))
        return cli_usage(cmd, "--tol is for the adaptive integrator (--scheme lie without --dt)");
    if (s->dt_s && (rc = read_double(&s->dt, s->dt_s, "--dt", cmd)) >= 0)
        return rc;
    if (!adaptive(s) && s->dt_s == NULL)
        return cli_usage(cmd, "--scheme %s needs its step: --dt", s->scheme);
    s->t_max = fmax(1000, 100.0 * (double)s->ncross);
    if (s->tmax_s && (rc = read_double(&s->t_max, s->tmax_s, "--t-max", cmd)) >= 0)
        return rc;
    if (s->formats != NULL && s->plot == NULL)
        return cli_usage(cmd, "--format is for the figure of --plot DIR");
    hl_error err; /* without libhdf5, say so before computing */
    if (hl_h5_is_h5_path(s->out) && hl_h5_available(&err) != HL_OK)
        return cli_fail(&err);
    return -1;
}

/* A constant formula (the energy): its value, or an error pointing into it. */
static int read_energy(double *E, hl_system *sys, const char *text, hl_error *err)
{
    const hl_expr *e;
    int st = hl_parse(&e, hl_system_pool(sys), text, err);
    const char *sym;
    if (st == HL_OK && hl_expr_symbols(e, &sym, 1) > 0) {
        int pos = hl_symbol_pos(text, sym);
        st = hl_error_set(err, HL_EINVAL, text, pos, (int)strlen(sym),
                          "the energy must be a constant, not depend on '%s'", sym);
    }
    if (st == HL_OK && hl_expr_eval_d(E, e, 0, NULL, NULL, err) == HL_OK && !isfinite(*E))
        st = hl_error_set(err, HL_EDOM, text, 0, (int)strlen(text), "the energy is not finite");
    if (st != HL_OK)
        hl_error_prefix(err, "in --energy");
    return st;
}

/* A file's whole text, or NULL after the message. */
static char *slurp(const char *path)
{
    FILE *fp = fopen(path, "r");
    if (fp == NULL) {
        fprintf(stderr, "hamlie: error: cannot read '%s': %s\n", path, strerror(errno));
        return NULL;
    }
    hl_buf b;
    hl_buf_init(&b);
    char chunk[4096];
    size_t n;
    while ((n = fread(chunk, 1, sizeof chunk, fp)) > 0)
        hl_buf_putn(&b, chunk, n);
    fclose(fp);
    if (b.s == NULL)
        return hl_xstrdup("");
    return b.s;
}

/* An error inside a file's text, shown as FILE:LINE:COL with that line. */
static int fail_in_file(hl_error *err, const char *path, const char *text)
{
    if (err->src != text || err->pos < 0)
        return cli_fail(err);
    int line = 1, start = 0;
    for (int i = 0; i < err->pos && text[i]; i++)
        if (text[i] == '\n')
            line++, start = i + 1;
    int end = start;
    while (text[end] && text[end] != '\n')
        end++;
    char *one = hl_xmalloc((size_t)(end - start + 1));
    memcpy(one, text + start, (size_t)(end - start));
    one[end - start] = '\0';
    err->src = one;
    err->pos -= start;
    hl_error_prefix(err, "%s:%d:%d", path, line, err->pos + 1);
    int rc = cli_fail(err);
    free(one);
    return rc;
}

/* ---- the orbits ------------------------------------------------------------- */

typedef struct job {
    crossings table;
    long orbit;
    double max_dH, E;
} job;

static int keep(const hl_run_crossing *c, void *arg)
{
    job *j = arg;
    crossings_add(&j->table, j->orbit, c);
    j->max_dH = fmax(j->max_dH, fabs(c->H - j->E));
    return 0;
}

/* Every orbit; the failures named on stderr.  Returns how many failed. */
static int run_orbits(job *j, hl_section *sec, hl_run *run, const double *zs, int M,
                      const sec_opts *s, int n2)
{
    hl_section_opts opts = {adaptive(s) ? s->tol : 0, s->dt, s->t_max};
    int failed = 0;
    for (int i = 0; i < M; i++) {
        hl_error err;
        hl_error_clear(&err);
        j->orbit = i;
        long before = j->table.n;
        if (hl_section_orbit(sec, run, zs + (size_t)i * n2, s->ncross, &opts, keep, j, NULL,
                             &err) != HL_OK) {
            fprintf(stderr, "hamlie section: orbit %d failed after %ld crossings: %s\n", i,
                    j->table.n - before, err.msg);
            crossings_orbit_failed(&j->table, i, &err);
            failed++;
        }
    }
    return failed;
}

/* The figure: the other coordinate against its momentum. */
static int draw(const job *j, hl_system *sys, hl_section *sec, const sec_opts *s, int M)
{
    int N = hl_system_ndof(sys), o = hl_section_coord(sec) == 0 ? (N > 1 ? 1 : 0) : 0;
    size_t *counts = hl_xcalloc((size_t)M, sizeof *counts);
    double **xs = hl_xcalloc((size_t)M, sizeof *xs), **ys = hl_xcalloc((size_t)M, sizeof *ys);
    for (long k = 0; k < j->table.n; k++) {
        const double *r = crossings_row(&j->table, k);
        int i = (int)r[0];
        xs[i] = hl_xrealloc(xs[i], (counts[i] + 1) * sizeof **xs);
        ys[i] = hl_xrealloc(ys[i], (counts[i] + 1) * sizeof **ys);
        xs[i][counts[i]] = r[3 + o];
        ys[i][counts[i]++] = r[3 + N + o];
    }
    char title[512];
    snprintf(title, sizeof title, "%s: H = %s, %s (%s)", adaptive(s) ? "Taylor" : s->scheme,
             s->energy, s->surface, crossings_direction_name(s->dir));
    hl_error err;
    hl_error_clear(&err);
    int st = hl_section_plot_write(s->plot, s->formats ? s->formats : "png", title,
                                   hl_system_coord(sys, o), hl_system_momentum(sys, o), M, counts,
                                   (const double *const *)xs, (const double *const *)ys, &err);
    for (int i = 0; i < M; i++)
        free(xs[i]), free(ys[i]);
    free(xs), free(ys), free(counts);
    return st == HL_OK ? CLI_OK : cli_fail(&err);
}

static void put_json(hl_buf *out, hl_system *sys, const sec_opts *s, const cli_opts *o,
                     const job *j, int M, int failed, const double *zs)
{
    hl_json js;
    hl_json_init_buf(&js, out);
    hl_json_object_begin(&js);
    hl_json_kv_string(&js, "command", "section");
    cli_json_system(&js, sys);
    hl_json_kv_string(&js, "H_input", o->H);
    hl_json_kv_double(&js, "energy", j->E);
    hl_json_kv_string(&js, "surface", s->surface);
    hl_json_kv_string(&js, "direction", crossings_direction_name(s->dir));
    hl_json_kv_string(&js, "scheme", adaptive(s) ? "lie (adaptive Taylor)" : s->scheme);
    hl_json_kv_string(&js, "located_on", adaptive(s) ? "taylor-polynomial" : "hermite-cubic");
    hl_json_kv_double(&js, adaptive(s) ? "tol" : "dt", adaptive(s) ? s->tol : s->dt);
    hl_json_kv_int(&js, "orbits", M);
    hl_json_kv_int(&js, "crossings_per_orbit", s->ncross);
    hl_json_kv_int(&js, "crossings", j->table.n);
    hl_json_kv_int(&js, "failed_orbits", failed);
    hl_json_kv_double(&js, "max_abs_H_minus_E", j->max_dH);
    hl_json_key(&js, "seeds");
    hl_json_array_begin(&js);
    int n2 = 2 * hl_system_ndof(sys);
    for (int i = 0; i < M; i++) {
        hl_json_object_begin(&js);
        for (int v = 0; v < n2; v++)
            hl_json_kv_double(&js, cli_phase_name(sys, v), zs[(size_t)i * n2 + v]);
        hl_json_object_end(&js);
    }
    hl_json_array_end(&js);
    hl_json_kv_string(&js, "out", s->out);
    hl_json_kv_string(&js, "plot", s->plot);
    hl_json_object_end(&js);
    hl_json_finish(&js);
}

/* --out FILE.h5: the crossings, the orbits and the inputs (crossings.c). */
static int write_h5(const job *j, hl_system *sys, const sec_opts *s, const cli_opts *o, int M,
                    const double *zs)
{
    crossings_h5_info info = {.command = "section",
                              .H = o->H,
                              .energy_input = s->energy,
                              .surface = s->surface,
                              .direction = crossings_direction_name(s->dir),
                              .scheme = adaptive(s) ? "lie (adaptive Taylor)" : s->scheme,
                              .located_on = adaptive(s) ? "taylor-polynomial" : "hermite-cubic",
                              .energy = j->E,
                              .tol = adaptive(s) ? s->tol : 0,
                              .dt = adaptive(s) ? 0 : s->dt,
                              .t_max = s->t_max,
                              .norbits = M,
                              .per_orbit = s->ncross,
                              .seeds = zs};
    return crossings_write_h5(&j->table, sys, s->out, &info);
}

/* The seeds: spread, or read from --init-file.  CLI_OK or the exit code. */
static int seeds(double **zs, int *M, hl_section *sec, const sec_opts *s)
{
    hl_error err;
    hl_error_clear(&err);
    if (s->init_file == NULL) {
        *M = (int)s->orbits;
        *zs = hl_xmalloc((size_t)*M * 4 * sizeof **zs);
        if (hl_section_spread(sec, *zs, *M, NULL, NULL, &err) != HL_OK)
            return cli_fail(&err);
        return CLI_OK;
    }
    char *text = slurp(s->init_file);
    if (text == NULL)
        return CLI_ERROR;
    int rc = CLI_OK;
    if (hl_section_read_points(sec, text, zs, M, &err) != HL_OK)
        rc = fail_in_file(&err, s->init_file, text);
    free(text);
    return rc;
}

static int section_body(hl_system *sys, sec_opts *s, const cli_opts *o)
{
    hl_error err;
    hl_error_clear(&err);
    job j;
    memset(&j, 0, sizeof j);
    hl_section *sec = NULL;
    hl_scheme *sch = NULL;
    hl_run *run = NULL;
    double *zs = NULL;
    int M = 0, rc = CLI_OK, n2 = 2 * hl_system_ndof(sys);
    if (read_energy(&j.E, sys, s->energy, &err) != HL_OK ||
        hl_section_new(&sec, sys, s->surface, s->dir, j.E, &err) != HL_OK) {
        if (err.src == s->surface)
            hl_error_prefix(&err, "in --surface");
        return cli_fail(&err);
    }
    if ((rc = seeds(&zs, &M, sec, s)) != CLI_OK)
        goto done;
    if ((!adaptive(s) && cli_make_scheme(&sch, NULL, NULL, s->scheme, 4, sys, &err) != HL_OK) ||
        hl_run_new(&run, sys, sch, &err) != HL_OK) {
        rc = cli_fail(&err);
        goto done;
    }
    crossings_init(&j.table, n2);
    int failed = run_orbits(&j, sec, run, zs, M, s, n2);
    if (failed == M && j.table.n == 0) {
        fprintf(stderr, "hamlie section: error: no orbit crossed the section\n");
        rc = CLI_ERROR;
        goto done;
    }
    if (s->plot != NULL && (rc = draw(&j, sys, sec, s, M)) != CLI_OK)
        goto done;
    int to_stdout = s->out == NULL && o->format != CLI_JSON;
    if (s->out != NULL && hl_h5_is_h5_path(s->out))
        rc = write_h5(&j, sys, s, o, M, zs);
    else if (s->out != NULL || to_stdout)
        rc = crossings_write_csv(&j.table, sys, s->out != NULL ? s->out : "-", 1);
    if (rc == CLI_OK && !to_stdout) {
        hl_buf out;
        hl_buf_init(&out);
        if (o->format == CLI_JSON)
            put_json(&out, sys, s, o, &j, M, failed, zs);
        else
            hl_buf_printf(&out,
                          "%d orbits, %ld crossings (%ld asked each), max |H - E| = %.3g at "
                          "the crossings; wrote them to %s%s%s\n",
                          M, j.table.n, s->ncross, j.max_dH, s->out, s->plot ? "; figure in " : "",
                          s->plot ? s->plot : "");
        rc = cli_emit(&out, CLI_OK);
    }
    if (rc == CLI_OK && failed > 0)
        rc = CLI_FAILS;
done:
    crossings_clear(&j.table);
    free(zs);
    hl_run_free(run);
    hl_scheme_free(sch);
    hl_section_free(sec);
    return rc;
}

int cmd_section(int argc, char **argv, const cli_command *cmd)
{
    sec_opts s;
    cli_opts o;
    memset(&s, 0, sizeof s);
    memset(&o, 0, sizeof o);
    static const cli_own own[] = {{"--energy", 0}, {"--surface", 0},   {"--direction", 0},
                                  {"--orbits", 0}, {"--init-file", 0}, {"--crossings", 0},
                                  {"--scheme", 0}, {"--tol", 0},       {"--dt", 0},
                                  {"--t-max", 0},  {"--out", 0},       {"--plot", 0},
                                  {"--format", 0}};
    static const cli_begin_spec spec = {
        own, (int)(sizeof own / sizeof own[0]), found_opt, check_opts, CLI_OPT_H, 64};
    char **av;
    hl_system *sys = NULL;
    int rc = cli_begin(&av, &o, &sys, argc, argv, cmd, &spec, &s);
    if (rc < 0)
        rc = section_body(sys, &s, &o);
    hl_system_free(sys);
    cli_opts_clear(&o);
    free(av);
    return rc;
}
