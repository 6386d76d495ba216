/* The cache directory as a whole, for `hamlie cache`: what it holds, and
 * emptying it (tape.h: hl_jit_cache_list, hl_jit_cache_clear).
 *
 * Only hamlie's files are touched, recognised by their names (jit_cache.c
 * makes them): <16 hex digits>.key and .so, and the writers' temporaries
 * <16 hex>.so.tmp<pid>.XXXXXX / .key.tmp<pid>.XXXXXX.  A user who points
 * HAMLIE_CACHE_DIR at a folder of their own loses nothing else.
 *
 * Clearing while another process uses the cache is safe, because every
 * reader checks what it reads (jit_cache.c): an entry's key is removed
 * before its object, so a key never vouches for a missing object; a reader
 * that finds half an entry compiles again.  A temporary whose writer is
 * still running is left, or its rename into place would fail mid-write;
 * one whose writer is gone (killed during a compilation) is removed. */
#define _GNU_SOURCE
#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "tape/jit_cache_impl.h"

typedef enum file_kind { NOT_OURS, KEY, OBJECT, TEMP } file_kind;

static int hex16(const char *s)
{
    for (int i = 0; i < 16; i++)
        if (!((s[i] >= '0' && s[i] <= '9') || (s[i] >= 'a' && s[i] <= 'f')))
            return 0;
    return 1;
}

/* What a name in the directory is; for a temporary, *pid its writer. */
static file_kind classify(const char *name, long *pid)
{
    size_t n = strlen(name);
    if (n < 19 || !hex16(name))
        return NOT_OURS;
    const char *rest = name + 16;
    if (strcmp(rest, ".key") == 0)
        return KEY;
    if (strcmp(rest, ".so") == 0)
        return OBJECT;
    const char *tail = strncmp(rest, ".so.tmp", 7) == 0    ? rest + 7
                       : strncmp(rest, ".key.tmp", 8) == 0 ? rest + 8
                                                           : NULL;
    if (tail == NULL)
        return NOT_OURS;
    char *end;
    errno = 0;
    *pid = strtol(tail, &end, 10);
    /* mkstemp's six characters after the pid */
    if (end == tail || errno != 0 || *pid <= 0 || *end != '.' || strlen(end + 1) != 6)
        return NOT_OURS;
    return TEMP;
}

/* 1 if process pid is running (or may be: another user's). */
static int alive(long pid)
{
    return (pid_t)pid == getpid() || kill((pid_t)pid, 0) == 0 || errno == EPERM;
}

/* dir/name's size into *size; 0 if it is gone or not a regular file. */
static int file_size(int dirfd_, const char *name, long long *size)
{
    struct stat st;
    if (fstatat(dirfd_, name, &st, AT_SYMLINK_NOFOLLOW) != 0 || !S_ISREG(st.st_mode))
        return 0;
    *size = (long long)st.st_size;
    return 1;
}

/* The names of hamlie's files in d, keys first (so that clearing removes
 * each key before its object); *n how many.  The caller frees them. */
static char **our_names(DIR *d, size_t *n)
{
    char **v = NULL;
    size_t cap = 0, nkeys = 0;
    *n = 0;
    struct dirent *de;
    while ((de = readdir(d)) != NULL) {
        long pid;
        file_kind k = classify(de->d_name, &pid);
        if (k == NOT_OURS)
            continue;
        if (*n == cap)
            v = hl_xrealloc(v, (cap = cap ? 2 * cap : 64) * sizeof *v);
        v[(*n)++] = hl_xstrdup(de->d_name);
        if (k == KEY) { /* move it up among the keys */
            char *t = v[nkeys];
            v[nkeys++] = v[*n - 1];
            v[*n - 1] = t;
        }
    }
    return v;
}

static void free_names(char **v, size_t n)
{
    for (size_t i = 0; i < n; i++)
        free(v[i]);
    free(v);
}

/* Opens the named directory into l->dir and *d (NULL if it does not exist
 * or the cache is off). */
static hl_status open_dir(hl_jit_cache_listing *l, DIR **d, hl_error *err)
{
    memset(l, 0, sizeof *l);
    *d = NULL;
    l->dir = hl_jit_cache_dir_named();
    if (l->dir == NULL)
        return HL_OK;
    *d = opendir(l->dir);
    if (*d != NULL) {
        l->exists = 1;
        return HL_OK;
    }
    if (errno == ENOENT)
        return HL_OK;
    return hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot read the cache directory %s: %s", l->dir,
                        strerror(errno));
}

hl_status hl_jit_cache_list(hl_jit_cache_listing *l, hl_error *err)
{
    DIR *d;
    hl_status st = open_dir(l, &d, err);
    if (d == NULL)
        return st;
    size_t n;
    char **names = our_names(d, &n);
    for (size_t i = 0; i < n; i++) {
        long long size;
        long pid;
        if (!file_size(dirfd(d), names[i], &size))
            continue; /* removed meanwhile */
        l->files++;
        l->bytes += size;
        l->entries += classify(names[i], &pid) == KEY;
    }
    free_names(names, n);
    closedir(d);
    return HL_OK;
}

hl_status hl_jit_cache_clear(hl_jit_cache_listing *removed, hl_error *err)
{
    hl_jit_cache_listing local;
    hl_jit_cache_listing *l = removed != NULL ? removed : &local;
    DIR *d;
    hl_status st = open_dir(l, &d, err);
    if (d == NULL) {
        if (l == &local)
            hl_jit_cache_listing_clear(l);
        return st;
    }
    size_t n;
    char **names = our_names(d, &n);
    for (size_t i = 0; i < n && st == HL_OK; i++) {
        long pid;
        long long size;
        file_kind k = classify(names[i], &pid);
        if ((k == TEMP && alive(pid)) || !file_size(dirfd(d), names[i], &size))
            continue;
        if (unlinkat(dirfd(d), names[i], 0) != 0) {
            if (errno != ENOENT)
                st = hl_error_set(err, HL_EIO, NULL, -1, 0, "cannot remove %s/%s: %s", l->dir,
                                  names[i], strerror(errno));
            continue;
        }
        l->files++;
        l->bytes += size;
        l->entries += k == KEY;
    }
    free_names(names, n);
    closedir(d);
    if (l == &local)
        hl_jit_cache_listing_clear(l);
    return st;
}

void hl_jit_cache_listing_clear(hl_jit_cache_listing *l)
{
    if (l == NULL)
        return;
    free(l->dir);
    l->dir = NULL;
}
