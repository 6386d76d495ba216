/* The reproduction report (paper.h: hl_paper_report_write): dir/report.md and
 * dir/report.tex, each written to a temporary file in dir and renamed, so a
 * reader never sees half a report. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/buf.h"
#include "hamlie/paper.h"
#include "hamlie/plot.h"

/* A Markdown table cell: no '|' or newline may break the row. */
static void md_cell(hl_buf *b, const char *s, int code)
{
    hl_buf_puts(b, code ? " `" : " ");
    for (; s != NULL && *s != '\0'; s++) {
        if (*s == '|')
            hl_buf_puts(b, code ? "\\|" : "\\|");
        else if (*s == '\n')
            hl_buf_putc(b, ' ');
        else if (*s == '`' && code)
            hl_buf_putc(b, '\'');
        else
            hl_buf_putc(b, *s);
    }
    hl_buf_puts(b, code ? "` |" : " |");
}

/* Text for LaTeX's text mode. */
static void tex_text(hl_buf *b, const char *s)
{
    for (; s != NULL && *s != '\0'; s++) {
        switch (*s) {
        case '\\': hl_buf_puts(b, "\\textbackslash{}"); break;
        case '{': case '}': case '_': case '&': case '%': case '$': case '#':
            hl_buf_putc(b, '\\');
            hl_buf_putc(b, *s);
            break;
        case '^': hl_buf_puts(b, "\\^{}"); break;
        case '~': hl_buf_puts(b, "\\textasciitilde{}"); break;
        case '<': hl_buf_puts(b, "\\textless{}"); break;
        case '>': hl_buf_puts(b, "\\textgreater{}"); break;
        case '|': hl_buf_puts(b, "\\textbar{}"); break;
        default: hl_buf_putc(b, *s);
        }
    }
}

/* The first of the formats that is "want", else the first one given. */
static void pick_format(char *out, size_t n, const char *formats, const char *want)
{
    const char *f = formats != NULL ? formats : "png";
    const char *hit = strstr(f, want);
    if (hit != NULL && (hit == f || hit[-1] == ',')) {
        snprintf(out, n, "%s", want);
        return;
    }
    size_t len = strcspn(f, ",");
    snprintf(out, n, "%.*s", (int)(len < n ? len : n - 1), f);
}

static void build_md(hl_buf *b, const hl_paper_formulas *fs, const hl_paper_figure *figs,
                     const char *formats)
{
    int agrees = 0;
    for (int i = 0; i < fs->n; i++)
        agrees += fs->f[i].verdict == HL_VERDICT_AGREES;
    hl_buf_puts(b, "# S. Bertrand, algebraic discretization: the paper reproduced by hamlie\n\n");
    hl_buf_printf(b,
                  "Every formula of the paper recomputed by hamlie and set beside the paper's "
                  "print: %d agree, %d differ.  The verdict is computed: the print, read into "
                  "hamlie's exact algebra, minus hamlie's result must simplify to 0.  Where "
                  "they differ, hamlie's column is the correct expression.  Oscillator "
                  "H = (p^2+x^2)/2; D is the step.\n\n",
                  agrees, fs->n - agrees);
    hl_buf_puts(b, "## Formulas\n\n");
    hl_buf_puts(b, "| formula | where | the paper's print | hamlie's result | verdict | "
                   "how hamlie checked it |\n");
    hl_buf_puts(b, "|---|---|---|---|---|---|\n");
    for (int i = 0; i < fs->n; i++) {
        const hl_paper_formula *f = &fs->f[i];
        hl_buf_puts(b, "|");
        hl_buf_printf(b, " **%s**: ", f->id);
        md_cell(b, f->what, 0);
        md_cell(b, f->paper_eq, 0);
        md_cell(b, f->printed, 1);
        md_cell(b, f->computed, 1);
        hl_buf_printf(b, " %s |", f->verdict == HL_VERDICT_AGREES ? "agrees" : "**differs**");
        md_cell(b, f->how, 0);
        hl_buf_putc(b, '\n');
    }
    if (figs == NULL)
        return;
    char ext[16];
    pick_format(ext, sizeof ext, formats, "png");
    hl_buf_puts(b, "\n## Figures\n\n");
    hl_buf_puts(b, "x(0) = 1, p(0) = 0, D = 0.1, t in [0, 20]; the exact solution as a red "
                   "line, the scheme as blue dots.  Each figure's data is checked against "
                   "the scheme's closed form.\n\n");
    for (int i = 0; i < HL_PAPER_NFIGURES; i++) {
        const hl_paper_figure *g = &figs[i];
        hl_buf_printf(b, "### %s\n\n![%s](%s.%s)\n\n", g->name, g->caption, g->name, ext);
        hl_buf_printf(b, "Closed-form check (%s): largest deviation %.3g, tolerance %.3g: "
                         "%s.\n\n",
                      g->check_what != NULL ? g->check_what : "", g->check, g->check_tol,
                      g->check <= g->check_tol ? "passed" : "**FAILED**");
    }
}

static void build_tex(hl_buf *b, const hl_paper_formulas *fs, const hl_paper_figure *figs,
                      const char *formats)
{
    hl_buf_puts(b, "% The paper reproduced by hamlie (hamlie reproduce): a fragment to \\input.\n"
                   "% Needs \\usepackage{graphicx,array,amsfonts,amssymb}.\n");
    hl_buf_puts(b, "\\begin{center}\n\\footnotesize\n"
                   "\\begin{tabular}{>{\\raggedright}p{0.16\\linewidth}"
                   ">{\\raggedright}p{0.24\\linewidth}>{\\raggedright}p{0.24\\linewidth}"
                   "l>{\\raggedright\\arraybackslash}p{0.2\\linewidth}}\n");
    hl_buf_puts(b, "\\hline\nformula & the paper's print & hamlie's result & verdict & how "
                   "checked \\\\\n\\hline\n");
    for (int i = 0; i < fs->n; i++) {
        const hl_paper_formula *f = &fs->f[i];
        hl_buf_puts(b, "\\texttt{");
        tex_text(b, f->id);
        hl_buf_puts(b, "}: ");
        tex_text(b, f->what);
        hl_buf_puts(b, " (");
        tex_text(b, f->paper_eq);
        hl_buf_printf(b, ") & $%s$ & $%s$ & %s & ", f->printed_latex, f->computed_latex,
                      f->verdict == HL_VERDICT_AGREES ? "agrees" : "\\textbf{differs}");
        tex_text(b, f->how);
        hl_buf_puts(b, " \\\\\n\\hline\n");
    }
    hl_buf_puts(b, "\\end{tabular}\n\\end{center}\n");
    if (figs == NULL)
        return;
    char ext[16];
    pick_format(ext, sizeof ext, formats, "pdf");
    for (int i = 0; i < HL_PAPER_NFIGURES; i++) {
        const hl_paper_figure *g = &figs[i];
        hl_buf_printf(b, "\\begin{figure}[h!]\n\\centering\n"
                         "\\includegraphics[width=0.6\\linewidth]{%s.%s}\n\\caption{",
                      g->name, ext);
        tex_text(b, g->caption);
        hl_buf_puts(b, " Closed-form check (");
        tex_text(b, g->check_what);
        hl_buf_printf(b, "): deviation $%.3g$, tolerance $%.3g$.}\n\\label{hamlie-%s}\n"
                         "\\end{figure}\n",
                      g->check, g->check_tol, g->name);
    }
}

/* dir/name through dir/.name.tmp and rename. */
static int write_atomic(const char *dir, const char *name, const hl_buf *b, hl_error *err)
{
    hl_buf path, tmp;
    int st = HL_OK;
    hl_buf_init(&path);
    hl_buf_init(&tmp);
    hl_buf_printf(&path, "%s/%s", dir, name);
    hl_buf_printf(&tmp, "%s/.%s.%ld.tmp", dir, name, (long)getpid());
    FILE *fp = fopen(tmp.s, "w");
    if (fp == NULL)
        st = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write '%s': %s", path.s,
                          strerror(errno));
    else {
        int bad = b->len > 0 && fwrite(b->s, 1, b->len, fp) != b->len;
        bad |= fclose(fp) != 0;
        if (bad || rename(tmp.s, path.s) != 0) {
            st = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write '%s': %s", path.s,
                              strerror(errno));
            remove(tmp.s);
        }
    }
    hl_buf_clear(&path);
    hl_buf_clear(&tmp);
    return st;
}

hl_status hl_paper_report_write(const char *dir, const hl_paper_formulas *fs,
                                const hl_paper_figure *figs, const char *formats,
                                hl_error *err)
{
    if (dir == NULL || fs == NULL)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no directory or no formulas");
    int st = hl_figure_mkdir(dir, err);
    if (st != HL_OK)
        return (hl_status)st;
    hl_buf md, tex;
    hl_buf_init(&md);
    hl_buf_init(&tex);
    build_md(&md, fs, figs, formats);
    build_tex(&tex, fs, figs, formats);
    st = write_atomic(dir, "report.md", &md, err);
    if (st == HL_OK)
        st = write_atomic(dir, "report.tex", &tex, err);
    hl_buf_clear(&md);
    hl_buf_clear(&tex);
    return (hl_status)st;
}
