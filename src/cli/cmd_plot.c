/* hamlie plot: figures of runs written by `hamlie run` (runplot.h). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "cli/cli.h"
#include "hamlie/runplot.h"

const char cmd_plot_help[] =
    "usage: hamlie plot RUN.csv [MORE.csv ...] --out DIR [--format png,svg,pdf]\n"
    "                   [--phase A:B] [--json | --latex]\n"
    "\n"
    "Draw the figures of one or more runs written by hamlie run (its CSV: t, the\n"
    "coordinates and momenta, H, sigma, the observers).  Several files are\n"
    "compared on each figure (one colour and marker each, the file names in the\n"
    "legend); they must have the same columns.  Into DIR (created if missing):\n"
    "  phase-Q-P          the phase portrait of each canonical pair (Q, P)\n"
    "  time-V             each coordinate and momentum in time\n"
    "  energy-error       |H - H0| in time, log scale\n"
    "  sigma              sigma = |z_n - z(t_n)|^2 in time, log scale (if present)\n"
    "  observer-K-F       each observer F in time\n"
    "A run of at most 400 rows is drawn as markers, a longer one as a line.\n"
    "\n"
    "  --out DIR          the folder for the figures (required)\n"
    "  --format LIST      png, svg, pdf or a comma-separated list (default png)\n"
    "  --phase A:B        one projection instead of every pair: any two columns,\n"
    "                     e.g. x:px or x:y\n"
    "  --size WxH         the PNG size in pixels (SVG, PDF: points; default 800x600)\n"
    "  --json             print the files written as a JSON object\n"
    "  --latex            print a LaTeX fragment including the figures\n"
    "  -h, --help         show this help\n"
    "\n"
    "Errors in a CSV name the file, the line and the column.\n"
    "Exit status: 0 written; 2 usage or input error (a bad CSV, a file that\n"
    "cannot be written).\n"
    "Example:\n"
    "  hamlie run -H 'p^2/2 - cos(q)' --scheme verlet --dt 0.1 --t 50 --init q=2,p=0 \\\n"
    "      --out verlet.csv\n"
    "  hamlie run -H 'p^2/2 - cos(q)' --scheme rk4 --dt 0.1 --t 50 --init q=2,p=0 \\\n"
    "      --out rk4.csv\n"
    "  hamlie plot verlet.csv rk4.csv --out figs --format png,pdf\n";

typedef struct plot_opts {
    const char *out, *format, *phase, *size;
} plot_opts;

static void found_opt(void *arg, int k, const char *value)
{
    plot_opts *p = arg;
    const char **slot[] = {&p->out, &p->format, &p->phase, &p->size};
    *slot[k] = value;
}

/* The extension a LaTeX document includes best: pdf, else png (svg needs a
 * package). */
static const char *latex_ext(const char *formats)
{
    const char *want[] = {"pdf", "png", "svg"};
    for (int k = 0; k < 3; k++)
        for (const char *s = formats; *s;) {
            size_t n = strcspn(s, ",");
            if (n == 3 && strncasecmp(s, want[k], 3) == 0)
                return want[k];
            s += n + (s[n] == ',');
        }
    return "png";
}

static void write_output(hl_buf *out, cli_format f, const plot_opts *p, const char *formats,
                         hl_runplot *const *runs, char *const *files, int nruns,
                         char *const *names, int nfig, int written)
{
    if (f == CLI_JSON) {
        hl_json j;
        hl_json_init_buf(&j, out);
        hl_json_object_begin(&j);
        hl_json_kv_string(&j, "command", "plot");
        hl_json_kv_string(&j, "out", p->out);
        hl_json_kv_string(&j, "formats", formats);
        hl_json_key(&j, "runs");
        hl_json_array_begin(&j);
        for (int r = 0; r < nruns; r++) {
            hl_json_object_begin(&j);
            hl_json_kv_string(&j, "file", files[r]);
            hl_json_kv_string(&j, "label", hl_runplot_label(runs[r]));
            hl_json_kv_int(&j, "rows", (long)hl_runplot_nrows(runs[r]));
            hl_json_kv_double(&j, "max_abs_dH", hl_runplot_max_dH(runs[r]));
            hl_json_object_end(&j);
        }
        hl_json_array_end(&j);
        hl_json_key(&j, "figures");
        hl_json_array_begin(&j);
        for (int i = 0; i < nfig; i++)
            hl_json_string(&j, names[i]);
        hl_json_array_end(&j);
        hl_json_kv_int(&j, "files_written", written);
        hl_json_object_end(&j);
        hl_json_finish(&j);
        return;
    }
    if (f == CLI_LATEX) {
        const char *ext = latex_ext(formats);
        for (int i = 0; i < nfig; i++)
            hl_buf_printf(out,
                          "\\begin{figure}[h!]\n\\centering\n"
                          "\\includegraphics[width=0.7\\textwidth]{%s/%s.%s}\n"
                          "\\caption{\\texttt{%s}}\n\\end{figure}\n",
                          p->out, names[i], ext, names[i]);
        return;
    }
    hl_buf_printf(out, "%d run%s (", nruns, nruns == 1 ? "" : "s");
    for (int r = 0; r < nruns; r++)
        hl_buf_printf(out, "%s%s: %zu rows", r ? ", " : "", hl_runplot_label(runs[r]),
                      hl_runplot_nrows(runs[r]));
    hl_buf_printf(out, "); wrote %d files to %s:\n", written, p->out);
    for (int i = 0; i < nfig; i++)
        hl_buf_printf(out, "  %s.{%s}\n", names[i], formats);
}

int cmd_plot(int argc, char **argv, const cli_command *self)
{
    const cli_command *cmd = self;
    static const cli_own own[] = {{"--out", 0}, {"--format", 0}, {"--phase", 0}, {"--size", 0}};
    plot_opts p = {NULL, NULL, NULL, NULL};
    cli_opts o;
    memset(&o, 0, sizeof o);
    int rc = cli_take_own(&argc, argv, own, 4, found_opt, &p, cmd);
    if (rc >= 0)
        return rc;
    rc = cli_parse(&o, argc, argv, 0, cmd);
    if (rc < 0 && (o.H != NULL || o.pairs != NULL || o.params != NULL || o.step != NULL))
        rc = cli_usage(cmd, "plot takes no system options: the CSV files say everything");
    if (rc < 0 && o.nargs == 0)
        rc = cli_usage(cmd, "give at least one CSV file written by hamlie run");
    if (rc < 0 && p.out == NULL)
        rc = cli_usage(cmd, "missing --out: the folder for the figures");
    int w = 0, h = 0;
    if (rc < 0 && p.size != NULL) {
        char x, end;
        if (sscanf(p.size, "%d%c%d%c", &w, &x, &h, &end) != 3 || (x != 'x' && x != 'X') ||
            w < 16 || w > 10000 || h < 16 || h > 10000)
            rc = cli_usage(cmd, "--size wants WxH in pixels from 16 to 10000, e.g. 640x480, "
                                "not '%s'", p.size);
    }
    if (rc >= 0) {
        cli_opts_clear(&o);
        return rc;
    }
    const char *formats = p.format != NULL ? p.format : "png";
    hl_error err;
    hl_error_clear(&err);
    int n = o.nargs;
    hl_runplot **runs = hl_xcalloc((size_t)n, sizeof *runs);
    hl_status st = HL_OK;
    for (int r = 0; r < n && st == HL_OK; r++)
        st = hl_runplot_read_csv(&runs[r], o.args[r], NULL, &err);
    hl_runplot_opts ro = {formats, p.phase, w, h};
    int written = 0, nfig = 0;
    hl_figure **figs = NULL;
    char **names = NULL;
    if (st == HL_OK)
        st = hl_runplot_write(runs, n, p.out, &ro, &written, &err);
    if (st == HL_OK) /* the names of what was written (cheap: no drawing) */
        st = hl_runplot_figures(&figs, &names, &nfig, runs, n, &ro, &err);
    if (st != HL_OK)
        rc = cli_fail(&err);
    else {
        hl_buf out;
        hl_buf_init(&out);
        write_output(&out, o.format, &p, formats, runs, o.args, n, names, nfig, written);
        rc = cli_emit(&out, CLI_OK);
    }
    hl_runplot_figures_free(figs, names, nfig);
    for (int r = 0; r < n; r++)
        hl_runplot_free(runs[r]);
    free(runs);
    cli_opts_clear(&o);
    return rc;
}
