/* Figures written to files: the list of formats, each file drawn into a
 * fresh temporary beside its final name and renamed (so a failed drawing
 * leaves no half-written figure), and the output folder made. */
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <sys/stat.h>
#include <unistd.h>

#include "base/buf.h"
#include "report/plot_impl.h"

static const struct {
    const char *ext, *dev;
} formats_known[] = {{"png", "pngcairo"}, {"svg", "svgcairo"}, {"pdf", "pdfcairo"}};
#define NFORMATS 3

/* Parse "png,svg,pdf" into want[]; HL_EINVAL on an unknown or empty list. */
static hl_status parse_formats(int want[NFORMATS], const char *formats, hl_error *err)
{
    int any = 0;
    memset(want, 0, NFORMATS * sizeof *want);
    if (formats == NULL)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no figure format given");
    const char *p = formats;
    while (*p) {
        while (*p == ' ' || *p == ',')
            p++;
        size_t len = strcspn(p, ", ");
        if (len == 0)
            break;
        int k;
        for (k = 0; k < NFORMATS; k++)
            if (strlen(formats_known[k].ext) == len &&
                strncasecmp(p, formats_known[k].ext, len) == 0)
                break;
        if (k == NFORMATS)
            return hl_error_set(err, HL_EINVAL, formats, (int)(p - formats), (int)len,
                                "unknown figure format '%.*s' (png, svg, pdf)", (int)len, p);
        want[k] = any = 1;
        p += len;
    }
    if (!any)
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "no figure format given");
    return HL_OK;
}

/* Create a fresh temporary file beside final; its name goes to tmp. */
static hl_status make_temp(char **tmp, const char *final, hl_error *err)
{
    static unsigned counter;
    hl_buf b;
    for (int tries = 0; tries < 100; tries++) {
        hl_buf_init(&b);
        hl_buf_printf(&b, "%s.tmp%ld.%u", final, (long)getpid(), counter++);
        int fd = open(b.s, O_WRONLY | O_CREAT | O_EXCL, 0666);
        if (fd >= 0) {
            close(fd);
            *tmp = hl_buf_take(&b);
            return HL_OK;
        }
        int e = errno;
        hl_buf_clear(&b);
        if (e != EEXIST)
            return hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write '%s': %s", final,
                                strerror(e));
    }
    return hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write '%s': no free temporary name",
                        final);
}

static hl_status write_one(const hl_figure *fig, const char *path, int k, hl_error *err)
{
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_printf(&b, "%s.%s", path, formats_known[k].ext);
    char *final = hl_buf_take(&b), *tmp = NULL;
    hl_status st = make_temp(&tmp, final, err);
    if (st == HL_OK) {
        st = hl_plot_draw_file_(fig, formats_known[k].dev, tmp, err);
        struct stat sb;
        if (st == HL_OK && (stat(tmp, &sb) != 0 || sb.st_size == 0))
            st = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write '%s': PLplot wrote nothing",
                              final);
        else if (st != HL_OK)
            hl_error_prefix(err, "writing '%s'", final);
        if (st == HL_OK && rename(tmp, final) != 0)
            st = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot write '%s': %s", final,
                              strerror(errno));
        if (st != HL_OK)
            unlink(tmp);
    }
    free(tmp);
    free(final);
    return st;
}

hl_status hl_figure_write(const hl_figure *fig, const char *path, const char *formats,
                          hl_error *err)
{
    int want[NFORMATS];
    hl_status st = parse_formats(want, formats, err);
    if (st != HL_OK)
        return st;
    if (path == NULL || *path == '\0')
        return hl_error_set(err, HL_EINVAL, NULL, -1, 0, "empty figure path");
    for (int k = 0; k < NFORMATS && st == HL_OK; k++)
        if (want[k])
            st = write_one(fig, path, k, err);
    return st;
}

/* By the one reader of format lists that hl_figure_write uses, so that the
 * two cannot disagree on what a list means. */
hl_status hl_figure_count_formats(int *n, const char *formats, hl_error *err)
{
    int want[NFORMATS];
    *n = 0;
    hl_status st = parse_formats(want, formats, err);
    for (int k = 0; k < NFORMATS && st == HL_OK; k++)
        *n += want[k];
    return st;
}

hl_status hl_figure_mkdir(const char *dir, hl_error *err)
{
    char *d = hl_xstrdup(dir);
    hl_status st = HL_OK;
    for (char *s = d + 1; *s && st == HL_OK; s++) {
        if (*s != '/')
            continue;
        *s = '\0';
        if (mkdir(d, 0777) != 0 && errno != EEXIST)
            st = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot create directory '%s': %s", d,
                              strerror(errno));
        *s = '/';
    }
    struct stat sb;
    if (st == HL_OK && mkdir(d, 0777) != 0 &&
        !(errno == EEXIST && stat(d, &sb) == 0 && S_ISDIR(sb.st_mode)))
        st = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot create directory '%s': %s", d,
                          errno == EEXIST ? "a file of that name exists" : strerror(errno));
    free(d);
    return st;
}
