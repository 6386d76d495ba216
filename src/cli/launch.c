/* The hamlie executable: a launcher linked with libc alone.  It answers
 * `--version`, `--help` and `help CMD` from texts copied out of main.c at
 * build time (launch_table.c), and for anything else loads the commands,
 * the module hamlie-cli.so, and hands it argv.  Why: the module needs FLINT
 * (Debian's is bound at load time and brings NTL and libstdc++), some 5 ms
 * before main, which questions about hamlie itself should not pay.
 *
 * The module is looked for beside the executable (the build tree), then at
 * HAMLIE_CLI_MODULE_DIR relative to it (the install: bin/ -> lib/hamlie/). */
#include <dlfcn.h>
#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/launch.h"

#ifndef HAMLIE_CLI_MODULE_DIR
#define HAMLIE_CLI_MODULE_DIR "../lib/hamlie"
#endif

enum { EXIT_USAGE = 2 }; /* main.c's CLI_ERROR */

static int finish_stdout(void)
{
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "hamlie: error: writing to standard output failed\n");
        return EXIT_USAGE;
    }
    return 0;
}

/* `hamlie help [CMD]`, as main.c answers it. */
static int help(int argc, char **argv)
{
    if (argc < 3) {
        fputs(hl_launch_usage, stdout);
        return finish_stdout();
    }
    for (int i = 0; i < hl_launch_ncommands; i++)
        if (strcmp(hl_launch_names[i], argv[2]) == 0) {
            fputs(hl_launch_helps[i], stdout);
            return finish_stdout();
        }
    fprintf(stderr, "hamlie: error: unknown command '%s' (see hamlie --help)\n", argv[2]);
    return EXIT_USAGE;
}

/* The questions answered here; -1 for a command (the module's job). */
static int answer_here(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "hamlie: error: no command given\n\n");
        fputs(hl_launch_usage, stderr);
        return EXIT_USAGE;
    }
    if (strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        fputs(hl_launch_usage, stdout);
        return finish_stdout();
    }
    if (strcmp(argv[1], "--version") == 0) {
        printf("hamlie %s\n", hl_launch_version);
        return finish_stdout();
    }
    if (strcmp(argv[1], "help") == 0)
        return help(argc, argv);
    return -1;
}

/* The module's path in buf: beside the executable, else at the install's
 * relative place; 0 if neither file exists (buf: the last one tried). */
static int find_module(char *buf, size_t size, char *dir, size_t dirsize)
{
    ssize_t n = readlink("/proc/self/exe", dir, dirsize - 1);
    if (n <= 0) {
        snprintf(buf, size, "%s (/proc/self/exe unreadable)", HAMLIE_CLI_MODULE);
        return 0;
    }
    dir[n] = '\0';
    char *slash = strrchr(dir, '/');
    if (slash != NULL)
        *slash = '\0';
    snprintf(buf, size, "%s/%s", dir, HAMLIE_CLI_MODULE);
    if (access(buf, F_OK) == 0)
        return 1;
    snprintf(buf, size, "%s/%s/%s", dir, HAMLIE_CLI_MODULE_DIR, HAMLIE_CLI_MODULE);
    return access(buf, F_OK) == 0;
}

static int run_module(int argc, char **argv)
{
    char path[PATH_MAX + 64], dir[PATH_MAX];
    if (!find_module(path, sizeof path, dir, sizeof dir)) {
        fprintf(stderr,
                "hamlie: error: cannot find the commands' module %s (is hamlie installed whole?)\n",
                path);
        return EXIT_USAGE;
    }
    /* global: code compiled at run time (libgccjit, cc) calls libm by name,
     * found among the module's libraries as it was in the old executable */
    void *module = dlopen(path, RTLD_LAZY | RTLD_GLOBAL);
    if (module == NULL) {
        fprintf(stderr, "hamlie: error: cannot load %s: %s\n", path, dlerror());
        return EXIT_USAGE;
    }
    int (*entry)(int, char **);
    *(void **)&entry = dlsym(module, HAMLIE_CLI_ENTRY);
    if (entry == NULL) {
        fprintf(stderr, "hamlie: error: %s lacks %s\n", path, HAMLIE_CLI_ENTRY);
        return EXIT_USAGE;
    }
    return entry(argc, argv);
}

#if defined(__SANITIZE_ADDRESS__)
/* LeakSanitizer asks the executable, at start, for its suppressions; the
 * module's (jit_common.c's, for the library's own programs) comes too late.
 * The same list: caches libgccjit and fontconfig keep for the process. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void)
{
    return "leak:libgccjit.so\nleak:libfontconfig.so\n";
}
#endif

int main(int argc, char **argv)
{
    int status = answer_here(argc, argv);
    return status >= 0 ? status : run_module(argc, argv);
}
