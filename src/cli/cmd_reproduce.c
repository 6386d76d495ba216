/* hamlie reproduce: the paper's figures and formulas, regenerated and checked
 * (paper.h), with the report written into one folder. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "hamlie/paper.h"

const char cmd_reproduce_help[] =
    "usage: hamlie reproduce [--out DIR] [--format png,svg,pdf] [--json | --latex]\n"
    "\n"
    "Rebuild the study of S. Bertrand's paper from nothing and say where the paper\n"
    "is right and where its print is not:\n"
    "  - the 14 figures (oscillator H = (p^2+x^2)/2, x(0) = 1, p(0) = 0, D = 0.1,\n"
    "    t in [0, 20]; exact scheme, Euler, discrete gradient), each file's data\n"
    "    checked against the scheme's closed form;\n"
    "  - every formula of the paper recomputed exactly and set beside the print:\n"
    "    \"agrees\" or \"differs\" (computed: print - result must simplify to 0), and\n"
    "    where it differs, the correct expression and how hamlie checked it;\n"
    "  - DIR/report.md and DIR/report.tex (a LaTeX fragment to \\input) with the\n"
    "    table and the figures.\n"
    "A short summary is printed.\n"
    "\n"
    "  --out DIR          the output folder (default out/paper; created if missing)\n"
    "  --format LIST      png, svg, pdf or a comma-separated list (default all three)\n"
    "  --json             print the summary as a JSON object\n"
    "  --latex            print the LaTeX fragment (report.tex) instead\n"
    "  -h, --help         show this help\n"
    "\n"
    "Differences with the paper are findings, not failures.\n"
    "Exit status: 0 everything written; 1 written, but a figure's data failed its\n"
    "closed-form check; 2 usage error, or a folder or file that cannot be written\n"
    "(nothing is left half-written: the figures are checked before any file).\n"
    "Example:\n"
    "  hamlie reproduce --out paper --format png\n";

typedef struct repro_opts {
    const char *out, *format;
} repro_opts;

static void found_opt(void *arg, int k, const char *value)
{
    repro_opts *p = arg;
    const char **slot[] = {&p->out, &p->format};
    *slot[k] = value;
}

static void summary_text(hl_buf *b, const repro_opts *p, const char *formats,
                         const hl_paper_figure *figs, const hl_paper_formulas *fs)
{
    int bad = 0, agrees = 0;
    for (int i = 0; i < HL_PAPER_NFIGURES; i++)
        bad += !(figs[i].check <= figs[i].check_tol);
    for (int i = 0; i < fs->n; i++)
        agrees += fs->f[i].verdict == HL_VERDICT_AGREES;
    hl_buf_printf(b, "hamlie reproduce: the paper regenerated in %s/\n\n", p->out);
    hl_buf_printf(b, "figures   %d x %s written; closed-form checks: %d passed, %d failed\n",
                  HL_PAPER_NFIGURES, formats, HL_PAPER_NFIGURES - bad, bad);
    for (int i = 0; i < HL_PAPER_NFIGURES; i++)
        if (!(figs[i].check <= figs[i].check_tol))
            hl_buf_printf(b, "  FAILED  %-14s %s: deviation %.3g > %.3g\n", figs[i].name,
                          figs[i].check_what, figs[i].check, figs[i].check_tol);
    hl_buf_printf(b, "formulas  %d recomputed: %d agree with the paper's print, %d differ\n",
                  fs->n, agrees, fs->n - agrees);
    for (int i = 0; i < fs->n; i++) {
        const hl_paper_formula *f = &fs->f[i];
        if (f->verdict == HL_VERDICT_AGREES)
            continue;
        hl_buf_printf(b, "\n  differs  %s: %s (%s)\n", f->id, f->what, f->paper_eq);
        hl_buf_printf(b, "    paper:   %s\n    correct: %s\n", f->printed, f->computed);
    }
    hl_buf_printf(b, "\nreport    %s/report.md, %s/report.tex\n", p->out, p->out);
}

static void summary_json(hl_buf *b, const repro_opts *p, const char *formats,
                         const hl_paper_figure *figs, const hl_paper_formulas *fs)
{
    hl_json j;
    hl_buf path;
    hl_json_init_buf(&j, b);
    hl_json_object_begin(&j);
    hl_json_kv_string(&j, "command", "reproduce");
    hl_json_kv_string(&j, "out", p->out);
    hl_json_kv_string(&j, "formats", formats);
    hl_json_key(&j, "figures");
    hl_json_array_begin(&j);
    for (int i = 0; i < HL_PAPER_NFIGURES; i++) {
        hl_json_object_begin(&j);
        hl_json_kv_string(&j, "name", figs[i].name);
        hl_json_kv_string(&j, "caption", figs[i].caption);
        hl_json_kv_string(&j, "check_what", figs[i].check_what);
        hl_json_kv_double(&j, "check", figs[i].check);
        hl_json_kv_double(&j, "check_tol", figs[i].check_tol);
        hl_json_kv_bool(&j, "check_passed", figs[i].check <= figs[i].check_tol);
        hl_json_object_end(&j);
    }
    hl_json_array_end(&j);
    hl_json_key(&j, "formulas");
    hl_json_array_begin(&j);
    for (int i = 0; i < fs->n; i++) {
        const hl_paper_formula *f = &fs->f[i];
        hl_json_object_begin(&j);
        hl_json_kv_string(&j, "id", f->id);
        hl_json_kv_string(&j, "what", f->what);
        hl_json_kv_string(&j, "where", f->paper_eq);
        hl_json_kv_string(&j, "printed", f->printed);
        hl_json_kv_string(&j, "computed", f->computed);
        hl_json_kv_string(&j, "verdict", f->verdict == HL_VERDICT_AGREES ? "agrees" : "differs");
        hl_json_kv_string(&j, "how", f->how);
        hl_json_object_end(&j);
    }
    hl_json_array_end(&j);
    hl_buf_init(&path);
    hl_buf_printf(&path, "%s/report.md", p->out);
    hl_json_kv_string(&j, "report_md", path.s);
    hl_buf_clear(&path);
    hl_buf_printf(&path, "%s/report.tex", p->out);
    hl_json_kv_string(&j, "report_tex", path.s);
    hl_buf_clear(&path);
    hl_json_object_end(&j);
    hl_json_finish(&j);
    hl_buf_putc(b, '\n');
}

static int put_file(hl_buf *b, const char *dir, const char *name)
{
    char path[4096];
    snprintf(path, sizeof path, "%s/%s", dir, name);
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return 0;
    char chunk[4096];
    size_t n;
    while ((n = fread(chunk, 1, sizeof chunk, fp)) > 0)
        hl_buf_putn(b, chunk, n);
    fclose(fp);
    return 1;
}

int cmd_reproduce(int argc, char **argv, const cli_command *self)
{
    const cli_command *cmd = self;
    static const cli_own own[] = {{"--out", 0}, {"--format", 0}};
    repro_opts p = {NULL, NULL};
    cli_opts o;
    memset(&o, 0, sizeof o);
    int rc = cli_take_own(&argc, argv, own, 2, found_opt, &p, cmd);
    if (rc >= 0)
        return rc;
    rc = cli_parse(&o, argc, argv, 0, cmd);
    if (rc < 0 && (o.H != NULL || o.pairs != NULL || o.params != NULL || o.step != NULL))
        rc = cli_usage(cmd, "reproduce takes no system options: the paper fixes them");
    if (rc < 0 && o.nargs > 0)
        rc = cli_usage(cmd, "unexpected argument '%s'", o.args[0]);
    if (rc < 0 && p.out != NULL && p.out[0] == '\0')
        rc = cli_usage(cmd, "--out wants a folder");
    if (rc >= 0) {
        cli_opts_clear(&o);
        return rc;
    }
    if (p.out == NULL)
        p.out = "out/paper";
    const char *formats = p.format != NULL ? p.format : "png,svg,pdf";
    hl_error err;
    hl_error_clear(&err);
    hl_paper_formulas fs = {0, NULL};
    hl_paper_figure figs[HL_PAPER_NFIGURES];
    memset(figs, 0, sizeof figs);
    /* the formulas first: they write nothing */
    hl_status st = hl_paper_formulas_compute(&fs, &err);
    if (st == HL_OK)
        st = hl_paper_figures(figs, p.out, formats, &err);
    if (st == HL_OK)
        st = hl_paper_report_write(p.out, &fs, figs, formats, &err);
    if (st != HL_OK) {
        rc = cli_fail(&err);
        hl_paper_formulas_clear(&fs);
        cli_opts_clear(&o);
        return rc;
    }
    int code = CLI_OK;
    for (int i = 0; i < HL_PAPER_NFIGURES; i++)
        if (!(figs[i].check <= figs[i].check_tol))
            code = CLI_FAILS;
    hl_buf out;
    hl_buf_init(&out);
    if (o.format == CLI_JSON)
        summary_json(&out, &p, formats, figs, &fs);
    else if (o.format == CLI_LATEX && !put_file(&out, p.out, "report.tex")) {
        hl_error_set(&err, HL_EIO, NULL, -1, 0, "cannot read back '%s/report.tex'", p.out);
        hl_buf_clear(&out);
        hl_paper_formulas_clear(&fs);
        cli_opts_clear(&o);
        return cli_fail(&err);
    } else if (o.format != CLI_LATEX)
        summary_text(&out, &p, formats, figs, &fs);
    rc = cli_emit(&out, code);
    hl_paper_formulas_clear(&fs);
    cli_opts_clear(&o);
    return rc;
}
