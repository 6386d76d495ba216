/* The disk cache of compiled code.  A process that compiles a tape keeps
 * the shared object in the user's cache directory; the next process with
 * the same program loads it (a dlopen, well under a millisecond) instead
 * of running GCC (70-300 ms), without making a libgccjit context at all.
 *
 * An entry is two files named by a 64-bit hash of the key text:
 *   <hash>.so   the object, as gcc_jit_context_compile_to_file made it;
 *   <hash>.key  the whole key text, then "so <size> <hash of the .so>".
 * The key names everything the generated code can depend on: the site and
 * its options ($HL_JIT_FLAGS, -march), the program's inputs as the builder
 * reads them, GCC's version and libgccjit's file, and the code generator
 * itself as libhamlie's GNU build-id (a rebuilt library changes it, where
 * a version string would not).  A load compares the key text and the
 * object's size and hash before dlopen, so a hash collision, a truncated,
 * zeroed or foreign file, or an entry half replaced by another process
 * means "compile again" and never a crash.  Writers write to a unique
 * temporary name and rename into place: two processes filling the same
 * entry at once both succeed, the last rename wins, and both wrote the
 * same key.
 *
 * The directory: $HAMLIE_CACHE_DIR, else $XDG_CACHE_HOME/hamlie, else
 * ~/.cache/hamlie; HAMLIE_CACHE=off turns the cache off.  If it cannot be
 * written the process compiles in memory as before, with one notice. */
#define _GNU_SOURCE
#include <dirent.h>
#include <dlfcn.h>
#include <errno.h>
#include <fcntl.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include "tape/jit_cache_impl.h"
#include "tape/jit_impl.h"

/* Bumped when the layout of an entry changes. */
#define CACHE_FORMAT "hamlie jit cache 1"

/* The sites' options: opt is libgccjit's -O level (see the NOTE at
 * site_options on how they were chosen), isa whether the host's vector
 * instructions are used. */
static const struct {
    const char *name;
    int opt, isa;
} sites[] = {
    [HL_JIT_SITE_EVAL] = {"eval", 2, 0},
    [HL_JIT_SITE_NEWTON] = {"newton", 2, 0},
    [HL_JIT_SITE_TAYLOR] = {"taylor", 1, 1},
    /* -O2: the lanes' code at -O1 ran at half the speed (bench/taylor_batch.c) */
    [HL_JIT_SITE_BATCH] = {"batch", 2, 1},
};

static struct {
    pthread_mutex_t lock;
    char *wanted; /* the directory the environment names (NULL: off) */
    char *dir;    /* it if usable, else NULL */
    int noticed;  /* the unwritable-directory notice was printed */
    hl_jit_cache_stats stats;
} cache = {PTHREAD_MUTEX_INITIALIZER, NULL, NULL, 0, {0, 0, 0, 0}};

/* ---- the key ------------------------------------------------------------------ */

static uint64_t fnv1a(const void *p, size_t n)
{
    const unsigned char *s = p;
    uint64_t h = 0xcbf29ce484222325u;
    for (size_t i = 0; i < n; i++)
        h = (h ^ s[i]) * 0x100000001b3u;
    return h;
}

static void put_double(hl_buf *b, double x)
{
    uint64_t u;
    memcpy(&u, &x, sizeof u); /* the bits: -0.0 and NaNs stay apart */
    hl_buf_printf(b, " %016llx", (unsigned long long)u);
}

void hl_jit_inputs_tape(hl_buf *b, const hl_tape *t)
{
    hl_buf_printf(b, "tape %d %d %d %d\nout", t->nin, t->nout, t->nregs, t->ncode);
    for (int i = 0; i < t->nout; i++)
        hl_buf_printf(b, " %d", t->outreg[i]);
    hl_buf_puts(b, "\ncode\n");
    for (int i = 0; i < t->ncode; i++) {
        const hl_instr *in = &t->code[i];
        hl_buf_printf(b, "%d %d %d %d %d\n", in->op, in->d, in->a, in->b, in->x);
    }
    /* the builders read the constants as immediates (isconst, rd) */
    hl_buf_puts(b, "const");
    for (int r = 0; r < t->nregs; r++)
        if (t->isconst[r]) {
            hl_buf_printf(b, " %d", r);
            put_double(b, t->rd[r]);
        }
    hl_buf_putc(b, '\n');
}

void hl_jit_inputs_taylor(hl_buf *b, const hl_tape *t, int order)
{
    hl_buf_printf(b, "order %d\n", order);
    hl_jit_inputs_tape(b, t);
}

void hl_jit_inputs_batch(hl_buf *b, const hl_tape *t, int order, int lanes)
{
    hl_jit_inputs_taylor(b, t, order);
    if (lanes > 1) /* the single recursion's key stays as it was */
        hl_buf_printf(b, "lanes %d\n", lanes);
}

void hl_jit_inputs_newton(hl_buf *b, const hl_newton *nw)
{
    hl_buf_printf(b, "newton m %d nx %d nz %d max_iter %d z %d\n", nw->m, nw->nx, nw->nz,
                  nw->max_iter, nw->Z != NULL);
    const hl_tape *tapes[4] = {nw->start, nw->F, nw->FJ, nw->Z};
    for (int k = 0; k < 4; k++)
        if (tapes[k] != NULL)
            hl_jit_inputs_tape(b, tapes[k]);
}

/* The key's lines that do not depend on the program: the same for the
 * whole process, made once. */
static char *process_key;
static pthread_once_t process_key_once = PTHREAD_ONCE_INIT;

static void make_process_key(void)
{
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_puts(&b, CACHE_FORMAT "\nlibhamlie ");
    hl_jit_generator_id(&b);
    /* GCC's version as hamlie was built against it; libgccjit's file, so
     * that an upgrade of it (same version string, other code) is seen */
    hl_buf_puts(&b, "\ngcc " __VERSION__);
#ifdef HL_GCCJIT_LIB
    struct stat st;
    if (stat(HL_GCCJIT_LIB, &st) == 0)
        hl_buf_printf(&b, " libgccjit %ld %lld %lld", (long)st.st_ino, (long long)st.st_size,
                      (long long)st.st_mtim.tv_sec);
#endif
    hl_buf_putc(&b, '\n');
    process_key = hl_buf_take(&b);
}

/* The whole key text of a site's program. */
static char *key_text(hl_jit_site site, const hl_buf *inputs)
{
    pthread_once(&process_key_once, make_process_key);
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_puts(&b, process_key);
    const char *flags = getenv("HL_JIT_FLAGS");
    hl_buf_printf(&b, "site %s -O%d isa %d flags [%s]\n", sites[site].name, sites[site].opt,
                  sites[site].isa ? hl_jit_host_isa() : -1, flags ? flags : "");
    hl_buf_putn(&b, inputs->s ? inputs->s : "", inputs->len);
    return hl_buf_take(&b);
}

/* ---- the directory ------------------------------------------------------------- */

static int cache_off(void)
{
    const char *s = getenv("HAMLIE_CACHE");
    return s != NULL && (strcmp(s, "off") == 0 || strcmp(s, "0") == 0 || strcmp(s, "no") == 0);
}

/* mkdir -p; 0 on success. */
static int make_dirs(const char *path)
{
    char *p = hl_xstrdup(path);
    int rc = 0;
    for (char *s = p + 1; rc == 0; s++) {
        if (*s != '/' && *s != '\0')
            continue;
        char c = *s;
        *s = '\0';
        if (mkdir(p, 0700) != 0 && errno != EEXIST)
            rc = -1;
        *s = c;
        if (c == '\0')
            break;
    }
    free(p);
    return rc;
}

static char *dir_from_env(void)
{
    const char *d = getenv("HAMLIE_CACHE_DIR");
    if (d != NULL && *d)
        return hl_xstrdup(d);
    hl_buf b;
    hl_buf_init(&b);
    const char *xdg = getenv("XDG_CACHE_HOME"), *home = getenv("HOME");
    if (xdg != NULL && *xdg == '/')
        hl_buf_printf(&b, "%s/hamlie", xdg);
    else if (home != NULL && *home)
        hl_buf_printf(&b, "%s/.cache/hamlie", home);
    else
        return NULL;
    return hl_buf_take(&b);
}

char *hl_jit_cache_dir_named(void)
{
    return cache_off() ? NULL : dir_from_env();
}

static void notice(const char *dir, const char *why)
{
    if (cache.noticed)
        return;
    cache.noticed = 1;
    fprintf(stderr,
            "hamlie: note: cannot use the cache directory %s (%s); compiled code is not kept "
            "(HAMLIE_CACHE=off to not try)\n",
            dir, why);
}

/* The directory, or NULL if the cache is off or unusable.  Under lock.
 * Looked up again when the environment names another one (tests and
 * benchmarks change it), then made if missing. */
static const char *cache_dir_locked(void)
{
    char *want = cache_off() ? NULL : dir_from_env();
    if (want == NULL ? cache.wanted == NULL
                     : cache.wanted != NULL && strcmp(want, cache.wanted) == 0) {
        free(want);
        return cache.dir;
    }
    free(cache.wanted), free(cache.dir);
    cache.wanted = want;
    cache.dir = want ? hl_xstrdup(want) : NULL;
    if (cache.dir != NULL && (make_dirs(cache.dir) != 0 || access(cache.dir, W_OK) != 0)) {
        notice(cache.dir, strerror(errno));
        free(cache.dir);
        cache.dir = NULL;
    }
    return cache.dir;
}

int hl_jit_cache_on(void)
{
    pthread_mutex_lock(&cache.lock);
    int on = cache_dir_locked() != NULL;
    pthread_mutex_unlock(&cache.lock);
    return on;
}

void hl_jit_cache_reset(void)
{
    pthread_mutex_lock(&cache.lock);
    free(cache.dir), free(cache.wanted);
    cache.dir = cache.wanted = NULL;
    cache.noticed = 0;
    pthread_mutex_unlock(&cache.lock);
}

void hl_jit_cache_get_stats(hl_jit_cache_stats *s)
{
    pthread_mutex_lock(&cache.lock);
    *s = cache.stats;
    pthread_mutex_unlock(&cache.lock);
}

static void count(long *counter)
{
    pthread_mutex_lock(&cache.lock);
    ++*counter;
    pthread_mutex_unlock(&cache.lock);
}

/* The directory (a copy, NULL if none). */
static char *cache_dir_copy(void)
{
    pthread_mutex_lock(&cache.lock);
    const char *d = cache_dir_locked();
    char *copy = d ? hl_xstrdup(d) : NULL;
    pthread_mutex_unlock(&cache.lock);
    return copy;
}

/* ---- an entry's files ------------------------------------------------------------ */

typedef struct entry {
    char *key;          /* the key text */
    char *so, *keyfile; /* paths; NULL if the cache is off */
} entry;

static void entry_open(entry *e, hl_jit_site site, const hl_buf *inputs)
{
    e->key = key_text(site, inputs);
    e->so = e->keyfile = NULL;
    char *dir = cache_dir_copy();
    if (dir == NULL)
        return;
    hl_buf b;
    hl_buf_init(&b);
    uint64_t h = fnv1a(e->key, strlen(e->key));
    hl_buf_printf(&b, "%s/%016llx.so", dir, (unsigned long long)h);
    e->so = hl_buf_take(&b);
    hl_buf_printf(&b, "%s/%016llx.key", dir, (unsigned long long)h);
    e->keyfile = hl_buf_take(&b);
    free(dir);
}

static void entry_close(entry *e)
{
    free(e->key), free(e->so), free(e->keyfile);
}

/* The whole file (NUL-terminated), or NULL; *n its size. */
static char *read_file(const char *path, size_t *n)
{
    FILE *f = fopen(path, "rb");
    if (f == NULL)
        return NULL;
    hl_buf b;
    hl_buf_init(&b);
    int bad = hl_buf_read_stream(&b, f);
    fclose(f);
    *n = b.len;
    char *s = hl_buf_take(&b);
    if (bad) {
        free(s);
        return NULL;
    }
    return s;
}

/* The object's size and hash as the key file states them; 0 if the key
 * file is missing or its key text is not e->key. */
static int key_matches(const entry *e, size_t *so_size, uint64_t *so_hash)
{
    size_t n, klen = strlen(e->key);
    char *text = read_file(e->keyfile, &n);
    unsigned long long h;
    int ok = text != NULL && n > klen && memcmp(text, e->key, klen) == 0 &&
             sscanf(text + klen, "so %zu %llx\n", so_size, &h) == 2;
    free(text);
    *so_hash = ok ? h : 0;
    return ok;
}

/* 1 if the object on disk is the one the key file names. */
static int object_intact(const entry *e, size_t size, uint64_t hash)
{
    size_t n;
    char *bytes = read_file(e->so, &n);
    int ok = bytes != NULL && n == size && fnv1a(bytes, n) == hash;
    free(bytes);
    return ok;
}

int hl_jit_cache_has(hl_jit_site site, const hl_buf *inputs)
{
    if (!hl_tape_jit_available())
        return 0;
    entry e;
    entry_open(&e, site, inputs);
    size_t size;
    uint64_t hash;
    int has = e.keyfile != NULL && key_matches(&e, &size, &hash);
    entry_close(&e);
    return has;
}

#ifdef HAMLIE_HAVE_GCCJIT

struct hl_jit_code {
    void *so;            /* dlopen handle, or */
    gcc_jit_result *res; /* libgccjit's in-memory code */
};

void *hl_jit_code_sym(hl_jit_code *code, const char *name)
{
    return code->so ? dlsym(code->so, name) : gcc_jit_result_get_code(code->res, name);
}

void hl_jit_code_free(hl_jit_code *code)
{
    if (code == NULL)
        return;
    if (code->so)
        dlclose(code->so);
    if (code->res)
        gcc_jit_result_release(code->res);
    free(code);
}

static int verbose(void)
{
    const char *v = getenv("HAMLIE_JIT_VERBOSE");
    return v != NULL && *v && strcmp(v, "0") != 0;
}

static double now_ms(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return ts.tv_sec * 1e3 + ts.tv_nsec * 1e-6;
}

/* The object of a valid entry, loaded and holding entry; else NULL (and a
 * damaged or foreign entry is counted as rejected). */
static hl_jit_code *load(const entry *e, const char *entry_name)
{
    size_t size;
    uint64_t hash;
    if (e->keyfile == NULL || !key_matches(e, &size, &hash))
        return NULL;
    void *so = NULL;
    if (!object_intact(e, size, hash) || (so = dlopen(e->so, RTLD_NOW | RTLD_LOCAL)) == NULL ||
        dlsym(so, entry_name) == NULL) {
        if (so != NULL)
            dlclose(so);
        count(&cache.stats.rejected);
        return NULL;
    }
    utimensat(AT_FDCWD, e->keyfile, NULL, 0); /* used now: the bound keeps it */
    hl_jit_code *code = hl_xcalloc(1, sizeof *code);
    code->so = so;
    return code;
}

/* ---- the bound ------------------------------------------------------------------
 * At most $HAMLIE_CACHE_MAX entries (default CACHE_MAX_ENTRIES, some 60 MB
 * at 20-60 KB an entry); past it the least recently used go: a hit
 * refreshes its key file's time.  Checked after each store, which costs
 * 100 ms or more anyway; the scan, about a millisecond a thousand entries.
 * A process that loses an entry it was about to load compiles again. */
#define CACHE_MAX_ENTRIES 2000

typedef struct aged {
    char *stem; /* <dir>/<hash>, without .key */
    struct timespec used;
} aged;

static int less_recent(const void *a, const void *b)
{
    const struct timespec *x = &((const aged *)a)->used, *y = &((const aged *)b)->used;
    if (x->tv_sec != y->tv_sec)
        return x->tv_sec < y->tv_sec ? -1 : 1;
    return (x->tv_nsec > y->tv_nsec) - (x->tv_nsec < y->tv_nsec);
}

static long max_entries(void)
{
    const char *s = getenv("HAMLIE_CACHE_MAX");
    char *end;
    long n = s ? strtol(s, &end, 10) : 0;
    return s && *s && *end == '\0' && n > 0 ? n : CACHE_MAX_ENTRIES;
}

/* The entries of dir (by their key files), with the time each was used. */
static aged *list_entries(const char *dir, size_t *n)
{
    DIR *d = opendir(dir);
    aged *v = NULL;
    size_t cap = 0;
    *n = 0;
    struct dirent *de;
    while (d != NULL && (de = readdir(d)) != NULL) {
        size_t len = strlen(de->d_name);
        if (len != 20 || strcmp(de->d_name + 16, ".key") != 0)
            continue;
        hl_buf b;
        hl_buf_init(&b);
        hl_buf_printf(&b, "%s/%.16s", dir, de->d_name);
        char *stem = hl_buf_take(&b);
        hl_buf_printf(&b, "%s.key", stem);
        struct stat st;
        int ok = stat(b.s, &st) == 0;
        hl_buf_clear(&b);
        if (!ok) {
            free(stem);
            continue;
        }
        if (*n == cap)
            v = hl_xrealloc(v, (cap = cap ? 2 * cap : 64) * sizeof *v);
        v[(*n)++] = (aged){stem, st.st_mtim};
    }
    if (d != NULL)
        closedir(d);
    return v;
}

static void prune(const entry *e)
{
    char *dir = hl_xstrdup(e->keyfile);
    *strrchr(dir, '/') = '\0';
    size_t n;
    aged *v = list_entries(dir, &n);
    long max = max_entries();
    if ((long)n > max) {
        qsort(v, n, sizeof *v, less_recent);
        for (size_t i = 0; i < n - (size_t)max; i++) {
            hl_buf b;
            hl_buf_init(&b);
            hl_buf_printf(&b, "%s.key", v[i].stem);
            unlink(b.s); /* the key first: no key vouches for a missing object */
            hl_buf_clear(&b);
            hl_buf_printf(&b, "%s.so", v[i].stem);
            unlink(b.s);
            hl_buf_clear(&b);
        }
    }
    for (size_t i = 0; i < n; i++)
        free(v[i].stem);
    free(v);
    free(dir);
}

/* A unique temporary file beside final (its name in *tmp), or -1. */
static int temp_beside(const char *final, char **tmp)
{
    hl_buf b;
    hl_buf_init(&b);
    hl_buf_printf(&b, "%s.tmp%ld.XXXXXX", final, (long)getpid());
    *tmp = hl_buf_take(&b);
    int fd = mkstemp(*tmp);
    if (fd < 0) {
        free(*tmp);
        *tmp = NULL;
    }
    return fd;
}

/* The key file: the key text, then the object's size and hash. */
static int write_key(const entry *e, size_t so_size, uint64_t so_hash)
{
    char *tmp;
    int fd = temp_beside(e->keyfile, &tmp);
    if (fd < 0)
        return -1;
    FILE *f = fdopen(fd, "w");
    int ok = f != NULL && fputs(e->key, f) >= 0 &&
             fprintf(f, "so %zu %016llx\n", so_size, (unsigned long long)so_hash) > 0;
    ok = (f != NULL ? fclose(f) == 0 : (close(fd), 0)) && ok;
    ok = ok && rename(tmp, e->keyfile) == 0;
    if (!ok)
        unlink(tmp);
    free(tmp);
    return ok ? 0 : -1;
}

/* Compiles c into the entry's object and key file (each written under a
 * temporary name and renamed into place: the object first, then the key
 * that vouches for it); 0 on success, 1 if the directory cannot be written
 * (nothing compiled), -1 if libgccjit failed. */
static int compile_into(const entry *e, gcc_jit_context *c)
{
    char *tmp;
    int fd = temp_beside(e->so, &tmp);
    if (fd < 0) {
        pthread_mutex_lock(&cache.lock);
        notice(e->so, strerror(errno));
        pthread_mutex_unlock(&cache.lock);
        return 1;
    }
    close(fd);
    if (hl_jit_run_compiler(c, tmp, NULL) != 0) {
        unlink(tmp);
        free(tmp);
        return -1;
    }
    size_t n = 0;
    char *bytes = read_file(tmp, &n);
    uint64_t hash = bytes ? fnv1a(bytes, n) : 0;
    free(bytes);
    int rc = bytes != NULL && rename(tmp, e->so) == 0 && write_key(e, n, hash) == 0 ? 0 : 1;
    if (rc != 0)
        unlink(tmp);
    free(tmp);
    return rc;
}

/* The code compiled in memory (the cache off or unwritable). */
static hl_jit_code *compile_in_memory(gcc_jit_context *c)
{
    gcc_jit_result *res = NULL;
    if (hl_jit_run_compiler(c, NULL, &res) != 0)
        return NULL;
    hl_jit_code *code = hl_xcalloc(1, sizeof *code);
    code->res = res;
    return code;
}

/* Builds and compiles (into the cache when it is on), then loads; on
 * failure NULL and err says why. */
static hl_jit_code *compile_and_load(const entry *e, hl_jit_site site, hl_jit_build_fn build,
                                     const void *arg, const char *entry_name, const char *what,
                                     hl_error *err)
{
    gcc_jit_context *c;
    if (hl_jit_context_new(&c, sites[site].opt, sites[site].isa, err) != HL_OK)
        return NULL;
    build(c, arg);
    hl_jit_code *code = NULL;
    int rc = e->so != NULL ? compile_into(e, c) : 1;
    if (rc == 0) {
        count(&cache.stats.stored);
        code = load(e, entry_name);
        prune(e);
    }
    /* not kept (no cache, unwritable, or replaced meanwhile by a damaged
     * file): this process still gets its code */
    if (code == NULL && rc != -1)
        code = compile_in_memory(c);
    if (code != NULL && hl_jit_code_sym(code, entry_name) == NULL) {
        hl_jit_code_free(code);
        code = NULL;
    }
    if (code == NULL) {
        const char *why = gcc_jit_context_get_first_error(c);
        hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "libgccjit failed on %s%s%s", what,
                     why ? ": " : "", why ? why : "");
    }
    gcc_jit_context_release(c);
    return code;
}

hl_status hl_jit_obtain(hl_jit_code **code, hl_jit_site site, const hl_buf *inputs,
                        hl_jit_build_fn build, const void *arg, const char *entry_name,
                        const char *what, hl_error *err)
{
    double t0 = now_ms();
    entry e;
    entry_open(&e, site, inputs);
    *code = load(&e, entry_name);
    int hit = *code != NULL;
    if (hit)
        count(&cache.stats.hits);
    else {
        count(&cache.stats.compiles);
        *code = compile_and_load(&e, site, build, arg, entry_name, what, err);
    }
    if (verbose())
        fprintf(stderr, "hamlie: jit: %s: %s in %.1f ms%s%s%s\n", what,
                hit     ? "loaded from the cache"
                : *code ? "compiled"
                        : "failed",
                now_ms() - t0, e.so ? " (" : "", e.so ? e.so : "", e.so ? ")" : "");
    entry_close(&e);
    return *code != NULL ? HL_OK : HL_EUNSUP;
}

#endif
