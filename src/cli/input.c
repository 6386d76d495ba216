/* A command's own files and inputs: whole numbers in options, files read
 * and written whole, an error inside a file's text shown at its line, the
 * number of cores (the commands that run many orbits: section, sweep). */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "base/buf.h"
#include "cli/cli.h"

int cli_read_long(long *v, const char *s, const char *opt, long lo, long hi,
                  const cli_command *cmd)
{
    char *end;
    errno = 0;
    long x = strtol(s, &end, 10);
    if (*s == '\0' || *end != '\0' || errno != 0 || x < lo || x > hi)
        return cli_usage(cmd, "%s wants a whole number from %ld to %ld, not '%s'", opt, lo, hi, s);
    *v = x;
    return -1;
}

char *cli_read_file(const char *path)
{
    FILE *fp = fopen(path, "r");
    if (fp == NULL) {
        fprintf(stderr, "hamlie: error: cannot read '%s': %s\n", path, strerror(errno));
        return NULL;
    }
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_read_stream(&b, fp);
    fclose(fp);
    return b.s != NULL ? b.s : hl_xstrdup("");
}

/* An error inside a file's text, shown as FILE:LINE:COL with that line. */
int cli_fail_in_file(hl_error *err, const char *path, const char *text)
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

int cli_cores(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n >= 1 ? (int)n : 1;
}

int cli_write_whole(hl_buf *b, const char *path)
{
    if (strcmp(path, "-") == 0)
        return cli_emit(b, CLI_OK); /* frees b */
    size_t n = strlen(path) + 5;
    char *tmp = hl_xmalloc(n);
    snprintf(tmp, n, "%s.tmp", path);
    FILE *fp = fopen(tmp, "w");
    int rc = CLI_OK;
    if (fp == NULL) {
        fprintf(stderr, "hamlie: error: cannot write '%s': %s\n", tmp, strerror(errno));
        rc = CLI_ERROR;
    } else {
        int bad = fwrite(b->s, 1, b->len, fp) != b->len;
        bad |= fclose(fp) != 0;
        if (bad || rename(tmp, path) != 0) {
            fprintf(stderr, "hamlie: error: writing '%s' failed: %s\n", path, strerror(errno));
            remove(tmp);
            rc = CLI_ERROR;
        }
    }
    free(tmp);
    hl_buf_clear(b);
    return rc;
}
