/* The reproduction report (paper.h: hl_paper_report_write).
 *
 * The real formula table is written with 14 stand-in figures (one of them
 * with a failed check) and the files are read back: every row present with
 * the verdict the table computed, hamlie's result and the print in the row;
 * the figures as Markdown images (.png) and \includegraphics (.pdf); LaTeX
 * that looks valid (braces balanced outside escapes, one tabular, figure
 * environments paired); no temporary file left behind; a directory that
 * cannot be created is HL_EIO and writes nothing. */
#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "hamlie/paper.h"
#include "hl_test.h"

static char *slurp(const char *path)
{
    FILE *fp = fopen(path, "rb");
    if (fp == NULL)
        return NULL;
    fseek(fp, 0, SEEK_END);
    long n = ftell(fp);
    fseek(fp, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    s[fread(s, 1, (size_t)n, fp)] = '\0';
    fclose(fp);
    return s;
}

static int count(const char *s, const char *needle)
{
    int n = 0;
    for (const char *p = strstr(s, needle); p != NULL; p = strstr(p + 1, needle))
        n++;
    return n;
}

/* The Markdown line of row id (starts "| **id**"), copied. */
static char *md_line(const char *md, const char *id)
{
    char key[128];
    snprintf(key, sizeof key, "| **%s**:", id);
    const char *p = strstr(md, key);
    if (p == NULL)
        return NULL;
    size_t n = strcspn(p, "\n");
    char *l = malloc(n + 1);
    memcpy(l, p, n);
    l[n] = '\0';
    return l;
}

/* Braces balanced, not counting \{ \} ; never below 0. */
static int braces_ok(const char *s)
{
    int depth = 0;
    for (; *s; s++) {
        if (*s == '\\' && s[1] != '\0') {
            s++;
            continue;
        }
        if (*s == '%') { /* comment to end of line */
            while (*s && *s != '\n')
                s++;
            if (!*s)
                break;
            continue;
        }
        depth += *s == '{';
        depth -= *s == '}';
        if (depth < 0)
            return 0;
    }
    return depth == 0;
}

static int tmp_files(const char *dir)
{
    DIR *d = opendir(dir);
    int n = 0;
    struct dirent *e;
    if (d == NULL)
        return -1;
    while ((e = readdir(d)) != NULL)
        n += strstr(e->d_name, ".tmp") != NULL;
    closedir(d);
    return n;
}

int main(void)
{
    hl_error err;
    hl_paper_formulas fs;
    int st = hl_paper_formulas_compute(&fs, &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    if (st != HL_OK)
        return HL_TEST_END();

    static char names[HL_PAPER_NFIGURES][32];
    hl_paper_figure figs[HL_PAPER_NFIGURES];
    for (int i = 0; i < HL_PAPER_NFIGURES; i++) {
        snprintf(names[i], sizeof names[i], "fig-%d", i);
        figs[i] = (hl_paper_figure){names[i], "a caption with x_n & 100% {braces}", 1e-15,
                                    1e-12, "2H_n = (1+D^2)^n"};
    }
    figs[5].check = 1.0; /* a failed closed-form check must show */

    char dir[] = "/tmp/hl-t-report-XXXXXX";
    CHECK(mkdtemp(dir) != NULL);
    char sub[256], path[300];
    snprintf(sub, sizeof sub, "%s/a/b", dir); /* created by the writer */
    st = hl_paper_report_write(sub, &fs, figs, "png,svg,pdf", &err);
    CHECK_MSG(st == HL_OK, "%s", err.msg);
    snprintf(path, sizeof path, "%s/report.md", sub);
    char *md = slurp(path);
    snprintf(path, sizeof path, "%s/report.tex", sub);
    char *tex = slurp(path);
    CHECK(md != NULL && tex != NULL);
    if (md != NULL && tex != NULL) {
        int ndiff = 0;
        for (int i = 0; i < fs.n; i++) {
            const hl_paper_formula *f = &fs.f[i];
            char *l = md_line(md, f->id);
            CHECK_MSG(l != NULL, "row %s missing from report.md", f->id);
            if (l != NULL) {
                int differs = strstr(l, "| **differs** |") != NULL;
                int agrees = strstr(l, "| agrees |") != NULL;
                CHECK_MSG(differs + agrees == 1 &&
                              differs == (f->verdict == HL_VERDICT_DIFFERS),
                          "%s: %s", f->id, l);
                /* the print and the result are there (no '|' in them to escape) */
                if (strchr(f->computed, '|') == NULL)
                    CHECK(strstr(l, f->computed) != NULL);
                if (strchr(f->printed, '|') == NULL)
                    CHECK(strstr(l, f->printed) != NULL);
                free(l);
            }
            ndiff += f->verdict == HL_VERDICT_DIFFERS;
            CHECK(strstr(tex, f->computed_latex) != NULL);
            CHECK(strstr(tex, f->printed_latex) != NULL);
        }
        CHECK(ndiff > 0);
        CHECK(count(tex, "\\textbf{differs}") == ndiff);
        CHECK(count(tex, " & agrees & ") == fs.n - ndiff);
        /* a table row per formula in each file */
        CHECK(count(md, "\n| **") == fs.n);
        CHECK(count(tex, "\\\\\n\\hline") == fs.n + 1);
        /* figures */
        CHECK(count(md, "![") == HL_PAPER_NFIGURES);
        CHECK(strstr(md, "](fig-13.png)") != NULL);
        CHECK(count(md, "**FAILED**") == 1);
        CHECK(count(tex, "\\includegraphics") == HL_PAPER_NFIGURES);
        CHECK(strstr(tex, "{fig-0.pdf}") != NULL);
        CHECK(count(tex, "\\begin{figure}") == count(tex, "\\end{figure}"));
        /* valid-looking LaTeX */
        CHECK(braces_ok(tex));
        CHECK(count(tex, "\\begin{tabular}") == 1 && count(tex, "\\end{tabular}") == 1);
        CHECK(strstr(tex, "100\\% \\{braces\\}") != NULL && strstr(tex, "x\\_n \\&") != NULL);
        CHECK(count(tex, "$") % 2 == count(tex, "\\$") % 2);
    }
    CHECK(tmp_files(sub) == 0);
    free(md);
    free(tex);

    /* without figures: no figure section; a png-less format list falls back */
    st = hl_paper_report_write(sub, &fs, NULL, NULL, &err);
    CHECK(st == HL_OK);
    snprintf(path, sizeof path, "%s/report.md", sub);
    md = slurp(path);
    CHECK(md != NULL && strstr(md, "## Figures") == NULL && strstr(md, "![") == NULL);
    free(md);
    st = hl_paper_report_write(sub, &fs, figs, "svg", &err);
    md = slurp(path);
    CHECK(st == HL_OK && md != NULL && strstr(md, "](fig-0.svg)") != NULL);
    free(md);

    /* a directory that cannot be created: HL_EIO, nothing written */
    snprintf(path, sizeof path, "%s/report.md/x", sub); /* under a regular file */
    st = hl_paper_report_write(path, &fs, figs, "png", &err);
    CHECK(st == HL_EIO && strstr(err.msg, "report.md/x") != NULL);
    st = hl_paper_report_write("/proc/hamlie-no/such", &fs, figs, "png", &err);
    CHECK(st == HL_EIO);

    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0);
    hl_paper_formulas_clear(&fs);
    return HL_TEST_END();
}
