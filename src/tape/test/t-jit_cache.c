/* The disk cache of compiled code (jit_cache.c), in a temporary
 * HAMLIE_CACHE_DIR: a cold compilation writes an entry, a warm one loads it
 * without compiling (the counters), and both give the interpreter's bits;
 * a truncated, zeroed or foreign object and a key file whose text differs
 * are recompiled (and the entry repaired), never loaded; past
 * HAMLIE_CACHE_MAX entries the least recently used goes; two processes
 * filling the same entry at once both get right code and leave a valid
 * entry; an unusable directory and HAMLIE_CACHE=off compile in memory.
 * The cost model: a kept program compiles for a single use, a program not
 * kept only for long enough runs.  Without libgccjit: a note, a pass. */
#include <fcntl.h>
#include <glob.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "hl_test.h"
#include "hamlie/tape.h"
#include "tape/jit_cache_impl.h"
#include "tape/tape_impl.h"

static const char *const vars[] = {"x", "y", "z"};
static char dir[64];

/* A tape with libm calls, a division and constants: (p, q) -> a pendulum
 * step with a parameter c = z; `variant` changes a constant. */
static hl_tape *make_tape(hl_pool *P, int variant)
{
    const hl_expr *x = hl_sym(P, "x"), *y = hl_sym(P, "y"), *z = hl_sym(P, "z");
    const hl_expr *f[3] = {
        hl_add(P, x, hl_mul(P, z, y)),
        hl_sub(P, y, hl_mul(P, z, hl_call(P, HL_SIN, hl_add(P, x, hl_num_si(P, 1 + variant))))),
        hl_div(P, hl_call(P, HL_EXP, hl_neg(P, hl_mul(P, y, y))), hl_add(P, z, hl_num_si(P, 3))),
    };
    hl_tape *t = NULL;
    hl_error err;
    CHECK_MSG(hl_tape_new(&t, f, 3, vars, 3, &err) == HL_OK, "%s", err.msg);
    return t;
}

static hl_jit_cache_stats stats(void)
{
    hl_jit_cache_stats s;
    hl_jit_cache_get_stats(&s);
    return s;
}

/* The compiled evaluation of a fresh tape against the interpreter's, bit
 * for bit, at a few points; 1 if equal. */
static int jit_matches_interpreter(hl_pool *P, int variant)
{
    hl_tape *t = make_tape(P, variant);
    static const double pts[3][3] = {{0.3, -1.2, 0.1}, {2.5, 0.7, 0.01}, {-7.0, 3.0, 1.5}};
    double want[3][3], got[3][3];
    for (int k = 0; k < 3; k++)
        hl_tape_eval_d(want[k], pts[k], t);
    hl_error err;
    int ok = hl_tape_jit(t, &err) == HL_OK && hl_tape_jit_active(t);
    CHECK_MSG(ok, "hl_tape_jit: %s", err.msg);
    for (int k = 0; k < 3 && ok; k++) {
        hl_tape_eval_d(got[k], pts[k], t);
        ok = memcmp(got[k], want[k], sizeof want[k]) == 0;
    }
    hl_tape_free(t);
    return ok;
}

/* The cache's files matching pattern (e.g. "*.so"); their count. */
static int files(const char *pattern, char paths[][128], int max)
{
    char pat[128];
    snprintf(pat, sizeof pat, "%s/%s", dir, pattern);
    glob_t g;
    int n = 0;
    if (glob(pat, 0, NULL, &g) == 0) {
        for (size_t i = 0; i < g.gl_pathc && n < max; i++)
            snprintf(paths[n++], 128, "%s", g.gl_pathv[i]);
        globfree(&g);
    }
    return n;
}

static void use_dir(const char *d)
{
    setenv("HAMLIE_CACHE_DIR", d, 1);
    hl_jit_cache_reset();
}

static void test_cold_warm(hl_pool *P)
{
    hl_jit_cache_stats s0 = stats();
    CHECK(jit_matches_interpreter(P, 0));
    hl_jit_cache_stats s1 = stats();
    CHECK(s1.compiles == s0.compiles + 1 && s1.stored == s0.stored + 1 && s1.hits == s0.hits);
    char p[4][128];
    CHECK(files("*.so", p, 4) == 1 && files("*.key", p, 4) == 1);
    CHECK(files("*.tmp*", p, 4) == 0);
    /* another tape of the same program: loaded, not compiled */
    CHECK(jit_matches_interpreter(P, 0));
    hl_jit_cache_stats s2 = stats();
    CHECK(s2.compiles == s1.compiles && s2.hits == s1.hits + 1);
    /* another constant: another program, compiled */
    CHECK(jit_matches_interpreter(P, 1));
    CHECK(stats().compiles == s2.compiles + 1 && files("*.so", p, 4) == 2);
}

/* Damages the object of variant 0's entry (mode: 0 truncate, 1 zero, 2
 * replace by variant 1's object), then checks it is recompiled, not
 * loaded, and the entry repaired. */
static void damage_and_check(hl_pool *P, const char *so, const char *foreign, int mode)
{
    struct stat st;
    stat(so, &st);
    if (mode == 0)
        CHECK(truncate(so, st.st_size / 2) == 0);
    else if (mode == 1) {
        int fd = open(so, O_WRONLY);
        char *zeros = calloc(1, (size_t)st.st_size);
        CHECK(fd >= 0 && write(fd, zeros, (size_t)st.st_size) == st.st_size);
        close(fd);
        free(zeros);
    } else {
        char cmd[400];
        snprintf(cmd, sizeof cmd, "cp '%s' '%s'", foreign, so);
        CHECK(system(cmd) == 0);
    }
    hl_jit_cache_stats s0 = stats();
    CHECK(jit_matches_interpreter(P, 0));
    hl_jit_cache_stats s1 = stats();
    CHECK_MSG(s1.rejected == s0.rejected + 1 && s1.compiles == s0.compiles + 1,
              "mode %d: rejected %ld -> %ld", mode, s0.rejected, s1.rejected);
    CHECK(jit_matches_interpreter(P, 0)); /* repaired: a hit again */
    CHECK(stats().hits == s1.hits + 1 && stats().compiles == s1.compiles);
}

/* The only entry in the directory: its .so and .key paths. */
static void only_entry(char *so, char *key)
{
    char p[4][128];
    CHECK(files("*.so", p, 4) == 1);
    strcpy(so, p[0]);
    CHECK(files("*.key", p, 4) == 1);
    strcpy(key, p[0]);
}

static void test_damage(hl_pool *P)
{
    char so[128], key[128], foreign[160];
    /* variant 1's object kept aside, as a foreign one */
    char cmd[512];
    snprintf(cmd, sizeof cmd, "rm -f '%s'/*", dir);
    CHECK(system(cmd) == 0);
    CHECK(jit_matches_interpreter(P, 1));
    only_entry(so, key);
    snprintf(foreign, sizeof foreign, "%s.foreign", dir);
    snprintf(cmd, sizeof cmd, "mv '%s' '%s' && rm -f '%s'/*", so, foreign, dir);
    CHECK(system(cmd) == 0);
    CHECK(jit_matches_interpreter(P, 0));
    only_entry(so, key);
    for (int mode = 0; mode < 3; mode++)
        damage_and_check(P, so, foreign, mode);
    remove(foreign);
    /* the key text differs (a hash collision, as it would look): not a
     * hit, compiled, the key rewritten */
    FILE *f = fopen(key, "r+");
    CHECK(f != NULL && fputs("hamlie jit cache 0", f) >= 0);
    fclose(f);
    hl_jit_cache_stats s0 = stats();
    CHECK(jit_matches_interpreter(P, 0));
    CHECK(stats().compiles == s0.compiles + 1 && stats().hits == s0.hits);
    CHECK(jit_matches_interpreter(P, 0));
    CHECK(stats().hits == s0.hits + 1);
}

/* At most HAMLIE_CACHE_MAX entries: the least recently used goes. */
static void test_bound(hl_pool *P)
{
    char cmd[256];
    snprintf(cmd, sizeof cmd, "rm -f '%s'/*", dir);
    CHECK(system(cmd) == 0);
    setenv("HAMLIE_CACHE_MAX", "2", 1);
    char p[8][128];
    CHECK(jit_matches_interpreter(P, 3));
    /* file times tick in milliseconds (coarse clocks): apart by more */
    CHECK(jit_matches_interpreter(P, 4));
    usleep(50000);
    CHECK(jit_matches_interpreter(P, 3)); /* a hit: 3 used after 4 */
    usleep(50000);
    hl_jit_cache_stats s0 = stats();
    CHECK(jit_matches_interpreter(P, 5)); /* a third entry: 4 goes */
    CHECK(files("*.key", p, 8) == 2 && files("*.so", p, 8) == 2);
    CHECK(jit_matches_interpreter(P, 3));
    CHECK(stats().hits == s0.hits + 1 && stats().compiles == s0.compiles + 1);
    CHECK(jit_matches_interpreter(P, 4)); /* gone: compiled again */
    CHECK(stats().compiles == s0.compiles + 2);
    unsetenv("HAMLIE_CACHE_MAX");
}

/* Two processes compile variant 2 into the empty entry at once. */
static void test_concurrent(hl_pool *P)
{
    pid_t kids[2];
    for (int k = 0; k < 2; k++)
        if ((kids[k] = fork()) == 0)
            _exit(jit_matches_interpreter(P, 2) && stats().compiles >= 1 ? 0 : 1);
    for (int k = 0; k < 2; k++) {
        int status = -1;
        waitpid(kids[k], &status, 0);
        CHECK_MSG(WIFEXITED(status) && WEXITSTATUS(status) == 0, "child %d: status %d", k, status);
    }
    char p[8][128];
    CHECK(files("*.tmp*", p, 8) == 0);
    hl_jit_cache_stats s0 = stats();
    CHECK(jit_matches_interpreter(P, 2));
    CHECK(stats().hits == s0.hits + 1);
}

/* No directory to write (a path under a file) and HAMLIE_CACHE=off: code
 * compiled in memory, nothing stored. */
static void test_no_cache(hl_pool *P)
{
    char under_file[128];
    snprintf(under_file, sizeof under_file, "%s/file", dir);
    FILE *f = fopen(under_file, "w");
    fclose(f);
    strcat(under_file, "/cache");
    use_dir(under_file);
    hl_jit_cache_stats s0 = stats();
    CHECK(jit_matches_interpreter(P, 0));
    CHECK(stats().compiles == s0.compiles + 1 && stats().stored == s0.stored);
    CHECK(!hl_jit_cache_on());
    use_dir(dir);
    setenv("HAMLIE_CACHE", "off", 1);
    hl_jit_cache_reset();
    s0 = stats();
    CHECK(jit_matches_interpreter(P, 0)); /* kept, but not looked at */
    CHECK(stats().compiles == s0.compiles + 1 && stats().hits == s0.hits);
    unsetenv("HAMLIE_CACHE");
    hl_jit_cache_reset();
}

/* The Taylor recursion: cold, then warm, the interpreter's coefficients. */
static void test_taylor(hl_pool *P)
{
    enum { ORDER = 12, S = ORDER + 1 };
    double want[3 * S], got[3 * S];
    for (int pass = 0; pass < 2; pass++) {
        hl_tape *t = make_tape(P, 0);
        hl_error err;
        memset(want, 0, sizeof want);
        want[0] = 0.4, want[S] = -0.3, want[2 * S] = 0.2;
        memcpy(got, want, sizeof want);
        CHECK(hl_tape_taylor_ode_d(want, ORDER, t, &err) == HL_OK);
        hl_jit_cache_stats s0 = stats();
        CHECK_MSG(hl_tape_native(t, ORDER, &err) == HL_OK, "%s", err.msg);
        CHECK(hl_tape_taylor_ode_d(got, ORDER, t, &err) == HL_OK);
        CHECK(memcmp(got, want, sizeof want) == 0);
        CHECK(pass == 0 ? stats().compiles == s0.compiles + 1
                        : stats().hits == s0.hits + 1 && stats().compiles == s0.compiles);
        /* the cost model: a kept recursion is loaded for a run of
         * 1e5 steps (short of the break-even of a compilation, 1e6, and of
         * the 1/20 of it that pays for one into the cache), not for one
         * step, whose load would cost more than it saves */
        if (pass == 1) {
            CHECK(hl_tape_compile_pays(t, HL_COMPILE_TAYLOR, 100000));
            CHECK(hl_tape_compile_kept(t, HL_COMPILE_TAYLOR, 100000));
            CHECK(!hl_tape_compile_pays(t, HL_COMPILE_TAYLOR, 1));
            CHECK(!hl_tape_compile_kept(t, HL_COMPILE_TAYLOR, 1));
        }
        hl_tape_free(t);
    }
}

/* A program not kept: compiled only for a run long enough (into the
 * cache from a 20th of the break-even); kept: loaded for a run whose uses
 * repay the load (a 40th of the break-even does), not for one use; never
 * for none. */
static void test_cost(hl_pool *P)
{
    CHECK(jit_matches_interpreter(P, 0)); /* kept (compiled if it was not) */
    hl_tape *kept = make_tape(P, 0), *fresh = make_tape(P, 7);
    long b = hl_tape_compile_breakeven(fresh, HL_COMPILE_EVAL);
    CHECK(b > 1000 && b < LONG_MAX);
    CHECK(hl_tape_compile_breakeven(kept, HL_COMPILE_EVAL) == b);
    CHECK(hl_tape_compile_pays(kept, HL_COMPILE_EVAL, b / 40));
    CHECK(hl_tape_compile_kept(kept, HL_COMPILE_EVAL, b / 40));
    CHECK(!hl_tape_compile_pays(kept, HL_COMPILE_EVAL, 1));
    CHECK(!hl_tape_compile_kept(kept, HL_COMPILE_EVAL, 1));
    CHECK(!hl_tape_compile_pays(kept, HL_COMPILE_EVAL, 0));
    CHECK(!hl_tape_compile_pays(fresh, HL_COMPILE_EVAL, b / 40));
    CHECK(!hl_tape_compile_kept(fresh, HL_COMPILE_EVAL, b / 40));
    CHECK(hl_tape_compile_pays(fresh, HL_COMPILE_EVAL, b / 20));
    CHECK(hl_tape_compile_pays(fresh, HL_COMPILE_EVAL, b));
    setenv("HAMLIE_CACHE", "off", 1);
    hl_jit_cache_reset();
    CHECK(!hl_tape_compile_pays(kept, HL_COMPILE_EVAL, b / 40));
    CHECK(!hl_tape_compile_kept(kept, HL_COMPILE_EVAL, b / 40));
    CHECK(!hl_tape_compile_pays(fresh, HL_COMPILE_EVAL, b - 1));
    unsetenv("HAMLIE_CACHE");
    hl_jit_cache_reset();
    hl_tape_free(kept);
    hl_tape_free(fresh);
}

int main(void)
{
    if (!hl_tape_jit_available()) {
        printf("skipped: hamlie was built without libgccjit\n");
        return HL_TEST_END();
    }
    unsetenv("HAMLIE_CACHE");
    unsetenv("HL_JIT_FLAGS");
    snprintf(dir, sizeof dir, "%s/hamlie-cache-XXXXXX", "/tmp");
    CHECK(mkdtemp(dir) != NULL);
    use_dir(dir);
    hl_pool *P = hl_pool_new();
    test_cold_warm(P);
    test_damage(P);
    test_concurrent(P);
    test_bound(P);
    test_taylor(P);
    test_cost(P);
    test_no_cache(P);
    hl_pool_free(P);
    char cmd[128];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    CHECK(system(cmd) == 0);
    return HL_TEST_END();
}
