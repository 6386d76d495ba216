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
#include "cli/section_orbits.h"
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
    "  --chaos              also the chaos indicator of every orbit: MEGNO <Y>\n"
    "                       (as `hamlie chaos`, the Taylor integrator at --tol)\n"
    "                       from its seed over its time span (to its last\n"
    "                       crossing); chaotic when <Y> > 2.5 (regular orbits\n"
    "                       tend to 2, or less, chaotic ones grow like lambda t/2;\n"
    "                       reliable for spans of 1000 or more).  The CSV gains\n"
    "                       the columns mean_Y and chaotic (1/0), the figure\n"
    "                       two colours (blue regular, red chaotic), the summary\n"
    "                       the fraction of chaotic orbits\n"
    "  --threads N          orbits on N threads (default: every core); the output\n"
    "                       is the same with any N\n"
    "  --progress, --quiet  progress (orbits done) on stderr from the start, or\n"
    "                       none (default: after a second or two)\n"
    "  --pairs, --param, --json   as for every command\n"
    "\n"
    "An orbit that fails (a blow-up, fewer than N crossings by --t-max) is named\n"
    "on stderr, its crossings kept, and the others go on.  Ctrl-C (SIGINT) stops\n"
    "the orbits: those finished are written, whole, the others left out.\n"
    "Exit status: 0 every orbit done; 1 some orbit failed (the file is written);\n"
    "2 usage or input error (no allowed region, a point where H = E has no\n"
    "solution), or every orbit failed; 130 interrupted.\n"
    "Example: hamlie section -H '(px^2+py^2)/2 + (x^2+y^2)/2 + x^2*y - y^3/3' \\\n"
    "           --energy 1/8 --surface x=0 --orbits 20 --crossings 300 --plot out/\n";

typedef struct sec_opts {
    const char *energy, *surface, *direction, *orbits_s, *init_file, *crossings_s;
    const char *scheme, *tol_s, *dt_s, *tmax_s, *out, *plot, *formats;
    const char *threads_s;
    int chaos;
    hl_event_dir dir;
    long orbits, ncross, threads;
    double tol, dt, t_max;
} sec_opts;

static void found_opt(void *arg, int k, const char *value)
{
    sec_opts *s = arg;
    const char **slot[] = {&s->energy,      &s->surface, &s->direction, &s->orbits_s, &s->init_file,
                           &s->crossings_s, &s->scheme,  &s->tol_s,     &s->dt_s,     &s->tmax_s,
                           &s->out,         &s->plot,    &s->formats,   &s->threads_s};
    if (k == 14)
        s->chaos = 1;
    else
        *slot[k] = value;
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
    if (s->orbits_s && (rc = cli_read_long(&s->orbits, s->orbits_s, "--orbits", 1, 100000, cmd)) >= 0)
        return rc;
    if (s->crossings_s &&
        (rc = cli_read_long(&s->ncross, s->crossings_s, "--crossings", 1, 100000000, cmd)) >= 0)
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
    s->threads = cli_cores();
    if (s->threads_s && (rc = cli_read_long(&s->threads, s->threads_s, "--threads", 1, 1024, cmd)) >= 0)
        return rc;
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

/* ---- the orbits ------------------------------------------------------------- */

typedef struct job {
    crossings table;
    double max_dH, E;
    section_orbit *orbits; /* each orbit's results (their crossings gathered in table) */
    int M, failed, done;
    int classified, chaotic, short_spans; /* with --chaos */
} job;

/* The orbits' results in orbit order: crossings into j->table, the
 * failures named on stderr (in that order too: nothing depends on the
 * threads), the classes counted. */
static void gather(job *j)
{
    for (int i = 0; i < j->M; i++) {
        const section_orbit *r = &j->orbits[i];
        if (!r->done)
            continue; /* cut by an interrupt */
        j->done++;
        if (r->failed) {
            fprintf(stderr, "hamlie section: orbit %d failed after %ld crossings: %s\n", i,
                    r->table.n, r->why);
            j->failed++;
            hl_error why; /* its status and reason in the HDF5 file */
            hl_error_clear(&why);
            why.status = r->status;
            snprintf(why.msg, sizeof why.msg, "%s", r->why);
            crossings_orbit_failed(&j->table, i, &why);
        }
        for (long k = 0; k < r->table.n; k++) {
            const double *row = crossings_row(&r->table, k);
            hl_run_crossing x = {(long)row[1], row[2], row + 3, row[3 + r->table.n2]};
            crossings_add(&j->table, i, &x);
        }
        j->max_dH = fmax(j->max_dH, r->max_dH);
        if (r->chaotic >= 0) {
            j->classified++;
            j->chaotic += r->chaotic;
            j->short_spans += r->span < SECTION_CHAOS_MIN_SPAN;
        }
    }
}

/* Every orbit, on the threads.  CLI_OK, CLI_INTERRUPTED or CLI_ERROR. */
static int run_orbits(job *j, const double *zs, const sec_opts *s, const cli_opts *o, int n2)
{
    section_job sj = {o,
                      s->surface,
                      s->dir,
                      j->E,
                      adaptive(s) ? NULL : s->scheme,
                      {adaptive(s) ? s->tol : 0, s->dt, s->t_max},
                      s->ncross,
                      s->chaos,
                      s->tol,
                      zs,
                      j->M,
                      n2};
    cli_progress p;
    cli_progress_begin(&p, "section", "orbit", o->progress);
    if (o->progress == CLI_PROGRESS_ON)
        cli_progress_say(&p, "%d orbits of %ld crossings on %ld thread%s%s", j->M, s->ncross,
                         s->threads, s->threads > 1 ? "s" : "", s->chaos ? ", with MEGNO" : "");
    int rc = section_orbits_run(&sj, j->orbits, (int)s->threads, &p);
    cli_progress_end(&p);
    if (rc != CLI_ERROR)
        gather(j);
    return rc;
}

/* ---- the figure --------------------------------------------------------------- */

/* The classes of the figure with --chaos, drawn in this order. */
enum { CLASS_CHAOTIC, CLASS_REGULAR, CLASS_UNKNOWN, NCLASSES };

static hl_status draw_classes(const job *j, const char *title, const char *xl, const char *yl,
                              const size_t *counts, double **xs, double **ys, const sec_opts *s,
                              hl_error *err)
{
    int *cls = hl_xmalloc((size_t)j->M * sizeof *cls);
    for (int i = 0; i < j->M; i++)
        cls[i] = j->orbits[i].chaotic == 1   ? CLASS_CHAOTIC
                 : j->orbits[i].chaotic == 0 ? CLASS_REGULAR
                                             : CLASS_UNKNOWN;
    static const hl_color colors[NCLASSES] = {HL_COLOR_RED, HL_COLOR_BLUE, HL_COLOR_GRAY};
    char lab[NCLASSES][80];
    snprintf(lab[0], sizeof lab[0], "chaotic, <Y> > %g: %d", SECTION_CHAOS_THRESHOLD, j->chaotic);
    snprintf(lab[1], sizeof lab[1], "regular: %d", j->classified - j->chaotic);
    snprintf(lab[2], sizeof lab[2], "not classified: %d", j->done - j->classified);
    const char *labels[NCLASSES] = {lab[0], lab[1], j->done > j->classified ? lab[2] : NULL};
    hl_status st = hl_section_plot_classes_write(
        s->plot, s->formats ? s->formats : "png", title, xl, yl, j->M, counts,
        (const double *const *)xs, (const double *const *)ys, cls, NCLASSES, colors, labels, err);
    free(cls);
    return st;
}

/* The figure: the other coordinate against its momentum. */
static int draw(const job *j, hl_system *sys, hl_section *sec, const sec_opts *s)
{
    int M = j->M, N = hl_system_ndof(sys), o = hl_section_coord(sec) == 0 ? (N > 1 ? 1 : 0) : 0;
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
    const char *xl = hl_system_coord(sys, o), *yl = hl_system_momentum(sys, o);
    hl_status st = s->chaos ? draw_classes(j, title, xl, yl, counts, xs, ys, s, &err)
                            : hl_section_plot_write(s->plot, s->formats ? s->formats : "png", title,
                                                    xl, yl, M, counts, (const double *const *)xs,
                                                    (const double *const *)ys, &err);
    for (int i = 0; i < M; i++)
        free(xs[i]), free(ys[i]);
    free(xs), free(ys), free(counts);
    return st == HL_OK ? CLI_OK : cli_fail(&err);
}

/* ---- the outputs -------------------------------------------------------------- */

static double chaotic_fraction(const job *j)
{
    return j->classified > 0 ? (double)j->chaotic / j->classified : NAN;
}

static void put_json_chaos(hl_json *js, const job *j)
{
    hl_json_key(js, "chaos");
    hl_json_object_begin(js);
    hl_json_kv_string(js, "indicator", "MEGNO <Y> at the time of the orbit's last crossing");
    hl_json_kv_double(js, "threshold", SECTION_CHAOS_THRESHOLD);
    hl_json_kv_int(js, "classified", j->classified);
    hl_json_kv_int(js, "chaotic", j->chaotic);
    hl_json_kv_double(js, "chaotic_fraction", chaotic_fraction(j));
    hl_json_kv_int(js, "spans_below_1000", j->short_spans);
    hl_json_object_end(js);
}

static void put_json(hl_buf *out, hl_system *sys, const sec_opts *s, const cli_opts *o,
                     const job *j, const double *zs, int interrupted)
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
    hl_json_kv_int(&js, "orbits", j->M);
    hl_json_kv_int(&js, "crossings_per_orbit", s->ncross);
    hl_json_kv_int(&js, "crossings", j->table.n);
    hl_json_kv_int(&js, "failed_orbits", j->failed);
    hl_json_kv_bool(&js, "interrupted", interrupted);
    hl_json_kv_int(&js, "orbits_done", j->done);
    hl_json_kv_double(&js, "max_abs_H_minus_E", j->max_dH);
    if (s->chaos)
        put_json_chaos(&js, j);
    hl_json_key(&js, "seeds");
    hl_json_array_begin(&js);
    int n2 = 2 * hl_system_ndof(sys);
    for (int i = 0; i < j->M; i++) {
        hl_json_object_begin(&js);
        for (int v = 0; v < n2; v++)
            hl_json_kv_double(&js, cli_phase_name(sys, v), zs[(size_t)i * n2 + v]);
        if (s->chaos) {
            const section_orbit *r = &j->orbits[i];
            hl_json_kv_double(&js, "mean_Y", r->megno);
            hl_json_kv_string(&js, "class",
                              r->chaotic == 1   ? "chaotic"
                              : r->chaotic == 0 ? "regular"
                                                : "not classified");
        }
        hl_json_object_end(&js);
    }
    hl_json_array_end(&js);
    hl_json_kv_string(&js, "out", s->out);
    hl_json_kv_string(&js, "plot", s->plot);
    hl_json_object_end(&js);
    hl_json_finish(&js);
}

/* The crossings as CSV; with --chaos each row also carries its orbit's <Y>
 * and class (section_orbits.c's writer). */
static int write_csv(const job *j, hl_system *sys, const sec_opts *s, const char *path)
{
    if (!s->chaos)
        return crossings_write_csv(&j->table, sys, path, 1);
    return section_write_chaos_csv(&j->table, j->orbits, sys, path);
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

/* The summary line (text output). */
static void put_summary(hl_buf *out, const job *j, const sec_opts *s)
{
    hl_buf_printf(out,
                  "%d orbits, %ld crossings (%ld asked each), max |H - E| = %.3g at the "
                  "crossings",
                  j->done, j->table.n, s->ncross, j->max_dH);
    if (s->chaos)
        hl_buf_printf(out, "; chaotic by MEGNO (<Y> > %g): %d of %d orbits, fraction %.3f",
                      SECTION_CHAOS_THRESHOLD, j->chaotic, j->classified, chaotic_fraction(j));
    hl_buf_printf(out, "; wrote them to %s%s%s\n", s->out, s->plot ? "; figure in " : "",
                  s->plot ? s->plot : "");
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
    char *text = cli_read_file(s->init_file);
    if (text == NULL)
        return CLI_ERROR;
    int rc = CLI_OK;
    if (hl_section_read_points(sec, text, zs, M, &err) != HL_OK)
        rc = cli_fail_in_file(&err, s->init_file, text);
    free(text);
    return rc;
}

/* After an interrupt, what was written and what was not. */
static void say_interrupted(const job *j, const sec_opts *s)
{
    fprintf(stderr, "hamlie section: interrupted: %d of %d orbits done%s\n", j->done, j->M,
            j->done > 0 ? "; their crossings written, whole orbits only" : ", nothing written");
}

/* The outputs: figure, CSV, summary.  rc: the orbits' CLI_OK or
 * CLI_INTERRUPTED.  Returns the exit code. */
static int write_outputs(const job *j, hl_system *sys, hl_section *sec, const sec_opts *s,
                         const cli_opts *o, const double *zs, int rc)
{
    int interrupted = rc == CLI_INTERRUPTED;
    if (s->plot != NULL && (rc = draw(j, sys, sec, s)) != CLI_OK)
        return rc;
    int to_stdout = s->out == NULL && o->format != CLI_JSON;
    if (s->out != NULL && hl_h5_is_h5_path(s->out))
        rc = write_h5(j, sys, s, o, j->M, zs);
    else if (s->out != NULL || to_stdout)
        rc = write_csv(j, sys, s, s->out != NULL ? s->out : "-");
    if (rc == CLI_OK && !to_stdout) {
        hl_buf out;
        hl_buf_init(&out);
        if (o->format == CLI_JSON)
            put_json(&out, sys, s, o, j, zs, interrupted);
        else
            put_summary(&out, j, s);
        rc = cli_emit(&out, CLI_OK);
    }
    if (rc == CLI_OK && s->chaos && j->short_spans > 0)
        fprintf(stderr,
                "hamlie section: note: %d orbits end before t = %g, too soon for <Y> to "
                "separate regular from chaotic reliably (more --crossings)\n",
                j->short_spans, SECTION_CHAOS_MIN_SPAN);
    if (rc == CLI_OK && interrupted) {
        say_interrupted(j, s);
        return CLI_INTERRUPTED;
    }
    return rc == CLI_OK && j->failed > 0 ? CLI_FAILS : rc;
}

static int section_body(hl_system *sys, sec_opts *s, const cli_opts *o)
{
    hl_error err;
    hl_error_clear(&err);
    job j;
    memset(&j, 0, sizeof j);
    hl_section *sec = NULL;
    double *zs = NULL;
    int rc = CLI_OK, n2 = 2 * hl_system_ndof(sys);
    if (read_energy(&j.E, sys, s->energy, &err) != HL_OK ||
        hl_section_new(&sec, sys, s->surface, s->dir, j.E, &err) != HL_OK) {
        if (err.src == s->surface)
            hl_error_prefix(&err, "in --surface");
        return cli_fail(&err);
    }
    if ((rc = seeds(&zs, &j.M, sec, s)) != CLI_OK)
        goto done;
    crossings_init(&j.table, n2);
    j.orbits = hl_xcalloc((size_t)j.M, sizeof *j.orbits);
    if ((rc = run_orbits(&j, zs, s, o, n2)) == CLI_ERROR)
        goto done;
    if (rc == CLI_INTERRUPTED && j.done == 0) { /* nothing to write */
        say_interrupted(&j, s);
        goto done;
    }
    if (j.done > 0 && j.failed == j.done && j.table.n == 0) {
        fprintf(stderr, "hamlie section: error: no orbit crossed the section\n");
        rc = CLI_ERROR;
        goto done;
    }
    rc = write_outputs(&j, sys, sec, s, o, zs, rc);
done:
    section_orbits_free(j.orbits, j.M);
    free(j.orbits);
    crossings_clear(&j.table);
    free(zs);
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
                                  {"--format", 0}, {"--threads", 0},   {"--chaos", CLI_OWN_FLAG}};
    static const cli_begin_spec spec = {own,        (int)(sizeof own / sizeof own[0]), found_opt,
                                        check_opts, CLI_OPT_H | CLI_OPT_PROGRESS,      64};
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
