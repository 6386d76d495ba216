/* The libgccjit plumbing that the three compilers share (point evaluation
 * and iteration in jit_eval.c, the Newton solve in jit_newton.c, the
 * Taylor-ODE recursion in jit.c): a context with the options that keep
 * compiled results bitwise those of the interpreter, one compilation that
 * leaves the caller's signal handlers in place, the libm imports.
 *
 * Bitwise: each instruction is the same IEEE operation on the same
 * operands in the same order; the library functions are the same libm
 * symbols, called as opaque imports so that GCC cannot rewrite them
 * (pow(x, 2) -> x*x is not exact for glibc's pow); contraction into FMA is
 * switched off (-ffp-contract=off).  sqrt is GCC's builtin (sqrtsd,
 * correctly rounded like libm's).  When compiling pays: cost.c. */
#include <dirent.h>
#include <errno.h>
#include <pthread.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

#include "base/buf.h"
#include "tape/jit_cache_impl.h"
#include "tape/jit_impl.h"

int hl_jit_host_isa(void)
{
#if defined(__x86_64__) && defined(__GNUC__)
    __builtin_cpu_init();
    int v3 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
             __builtin_cpu_supports("bmi2");
    int v4 = v3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
             __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq");
    return v4 ? 4 : v3 ? 3 : 0;
#else
    return 0;
#endif
}

#ifdef HAMLIE_HAVE_GCCJIT

gcc_jit_function *hl_jit_import1(jit *J, const char *name)
{
    gcc_jit_param *x = gcc_jit_context_new_param(J->c, NULL, J->dbl, "x");
    return gcc_jit_context_new_function(J->c, NULL, GCC_JIT_FUNCTION_IMPORTED, J->dbl, name, 1, &x,
                                        0);
}

gcc_jit_function *hl_jit_import_lib(jit *J, hl_pfn f)
{
    if (f == HL_PFN_SQRT)
        return J->sqrt;
    if (J->lib[f] != NULL)
        return J->lib[f];
    if (hl_pfn_arity(f) == 2) { /* pow(x, y), atan2(y, x) */
        gcc_jit_param *p[2] = {gcc_jit_context_new_param(J->c, NULL, J->dbl, "u"),
                               gcc_jit_context_new_param(J->c, NULL, J->dbl, "v")};
        J->lib[f] = gcc_jit_context_new_function(J->c, NULL, GCC_JIT_FUNCTION_IMPORTED, J->dbl,
                                                 hl_pfn_name(f), 2, p, 0);
    } else
        J->lib[f] = hl_jit_import1(J, hl_pfn_name(f));
    return J->lib[f];
}

gcc_jit_function *hl_jit_import_sincos(jit *J)
{
    if (J->sincos == NULL) {
        gcc_jit_param *p[3] = {gcc_jit_context_new_param(J->c, NULL, J->dbl, "x"),
                               gcc_jit_context_new_param(J->c, NULL, J->dblp, "s"),
                               gcc_jit_context_new_param(J->c, NULL, J->dblp, "c")};
        J->sincos = gcc_jit_context_new_function(J->c, NULL, GCC_JIT_FUNCTION_IMPORTED,
                                                 gcc_jit_context_get_type(J->c, GCC_JIT_TYPE_VOID),
                                                 "sincos", 3, p, 0);
    }
    return J->sincos;
}

/* NOTE: libgccjit runs GCC's driver in process, and the driver installs its
 * own handlers for SIGINT, SIGHUP, SIGTERM and SIGPIPE (GCC's fatal_signal,
 * which kills the process) and SIGCHLD, and leaves them there: a caller's
 * Ctrl-C handler (hamlie run stops cleanly on it) was gone after the first
 * compilation.  They are put back after each compilation, and the signals
 * that stop a job are held meanwhile.  Held is not enough: the driver probes
 * each disposition by setting it to SIG_IGN first, and that discards a held
 * signal, so a Ctrl-C at the wrong moment was lost and the job went on.
 * Hence compile_in_child below, wherever the code goes to a file. */
static int compile_holding_signals(gcc_jit_context *c, const char *path, gcc_jit_result **res)
{
    static const int sigs[] = {SIGINT, SIGHUP, SIGTERM, SIGPIPE, SIGCHLD};
    enum { NSIGS = sizeof sigs / sizeof sigs[0] };
    struct sigaction saved[NSIGS];
    sigset_t hold, prev;
    sigemptyset(&hold);
    sigaddset(&hold, SIGINT);
    sigaddset(&hold, SIGHUP);
    sigaddset(&hold, SIGTERM);
    for (int i = 0; i < NSIGS; i++)
        sigaction(sigs[i], NULL, &saved[i]);
    pthread_sigmask(SIG_BLOCK, &hold, &prev);
    int failed;
    if (path != NULL) {
        gcc_jit_context_compile_to_file(c, GCC_JIT_OUTPUT_KIND_DYNAMIC_LIBRARY, path);
        failed = gcc_jit_context_get_first_error(c) != NULL;
    } else {
        *res = gcc_jit_context_compile(c);
        failed = *res == NULL;
    }
    for (int i = 0; i < NSIGS; i++)
        sigaction(sigs[i], &saved[i], NULL);
    pthread_sigmask(SIG_SETMASK, &prev, NULL);
    return failed ? -1 : 0;
}

/* Compiles c into path in a child process, whose signal handlers are its
 * own: the caller's stay in place and see every signal.  A Ctrl-C from the
 * terminal reaches the child too, which then fails; the caller falls back
 * to the interpreter and stops at its next check.  A failure that was not
 * a signal is compiled again here, for libgccjit's message in c.  The lock:
 * a fork copies only this thread, and the child must not find libgccjit's
 * own lock held by another thread's compilation. */
static int compile_in_child(gcc_jit_context *c, const char *path)
{
    pid_t pid = fork();
    if (pid < 0)
        return compile_holding_signals(c, path, NULL);
    if (pid == 0) {
        gcc_jit_context_compile_to_file(c, GCC_JIT_OUTPUT_KIND_DYNAMIC_LIBRARY, path);
        _exit(gcc_jit_context_get_first_error(c) != NULL);
    }
    int status;
    while (waitpid(pid, &status, 0) < 0)
        if (errno != EINTR)
            return compile_holding_signals(c, path, NULL); /* SIGCHLD ignored: no status */
    if (WIFEXITED(status) && WEXITSTATUS(status) == 0)
        return 0;
    return WIFSIGNALED(status) ? -1 : compile_holding_signals(c, path, NULL);
}

/* NOTE: under AddressSanitizer a fork while other threads run (a sweep's,
 * a section's) can leave the child waiting forever on the sanitizer
 * allocator's lock, held by another thread at the fork (glibc's malloc is
 * made safe across fork, the sanitizer's is not): found by cli/mpi's
 * two-thread sweep.  There the compilation stays in process. */
#if defined(__SANITIZE_ADDRESS__)
#define FORK_SAFE_WITH_THREADS 0
#else
#define FORK_SAFE_WITH_THREADS 1
#endif

/* Does this process run other threads?  (/proc/self/task has one entry per
 * thread; without /proc, no.) */
static int other_threads_run(void)
{
    DIR *d = opendir("/proc/self/task");
    if (d == NULL)
        return 0;
    int n = 0;
    for (struct dirent *e; (e = readdir(d)) != NULL;)
        n += e->d_name[0] != '.';
    closedir(d);
    return n > 1;
}

int hl_jit_run_compiler(gcc_jit_context *c, const char *path, gcc_jit_result **res)
{
    static pthread_mutex_t one_at_a_time = PTHREAD_MUTEX_INITIALIZER;
    pthread_mutex_lock(&one_at_a_time);
    int in_child = path != NULL && (FORK_SAFE_WITH_THREADS || !other_threads_run());
    int rc = in_child ? compile_in_child(c, path) : compile_holding_signals(c, path, res);
    pthread_mutex_unlock(&one_at_a_time);
    return rc;
}

/* Extra options from $HL_JIT_FLAGS (space-separated), for experiments such
 * as -march=native (which may contract into FMA and so change results). */
static void add_env_flags(gcc_jit_context *c)
{
    const char *s = getenv("HL_JIT_FLAGS");
    if (s == NULL)
        return;
    char *copy = hl_xmalloc(strlen(s) + 1), *save = NULL;
    strcpy(copy, s);
    for (char *w = strtok_r(copy, " \t", &save); w != NULL; w = strtok_r(NULL, " \t", &save))
        gcc_jit_context_add_command_line_option(c, w); /* copies w */
    free(copy);
}

/* The vector instructions of the machine that runs the code, as the
 * -march level given to GCC (libgccjit does not understand -march=native).
 * Contraction into FMA stays off, so the results are those of plain SSE2
 * code; the wider registers let GCC pair the recurrences' independent
 * products, which bench/taylor_flow.c shows on the longer recursions
 * (Kepler's). */
static void add_host_isa(gcc_jit_context *c)
{
    int level = hl_jit_host_isa();
    if (level == 4)
        gcc_jit_context_add_command_line_option(c, "-march=x86-64-v4");
    else if (level == 3)
        gcc_jit_context_add_command_line_option(c, "-march=x86-64-v3");
}

hl_status hl_jit_context_new(gcc_jit_context **c, int opt, int host_isa, hl_error *err)
{
    *c = NULL;
    if (hl_gccjit_load(err) != HL_OK) /* loaded here, on the first compilation */
        return HL_EUNSUP;
    *c = gcc_jit_context_acquire();
    if (*c == NULL)
        return hl_error_set(err, HL_EUNSUP, NULL, -1, 0, "libgccjit cannot start");
    gcc_jit_context_set_int_option(*c, GCC_JIT_INT_OPTION_OPTIMIZATION_LEVEL, opt);
    gcc_jit_context_set_bool_option(*c, GCC_JIT_BOOL_OPTION_DEBUGINFO, 0);
    /* its diagnostics are not ours to print; the first comes back in err */
    gcc_jit_context_set_bool_print_errors_to_stderr(*c, 0);
    gcc_jit_context_add_command_line_option(*c, "-ffp-contract=off");
    if (host_isa)
        add_host_isa(*c);
    add_env_flags(*c); /* last, so that the caller's options win */
    return HL_OK;
}

void hl_jit_init(jit *J, gcc_jit_context *c, const hl_tape *t)
{
    J->c = c;
    J->t = t;
    J->dbl = gcc_jit_context_get_type(c, GCC_JIT_TYPE_DOUBLE);
    J->dblp = gcc_jit_type_get_pointer(J->dbl);
    J->sqrt = gcc_jit_context_get_builtin_function(c, "__builtin_sqrt");
}

int hl_tape_jit_available(void)
{
    /* not loaded to answer: callers ask before deciding to compile */
    return hl_gccjit_not_failed();
}

#if defined(__SANITIZE_ADDRESS__)
/* libgccjit keeps some 5-10 kB of compiler state per compilation that
 * gcc_jit_context_release and gcc_jit_result_release do not free; in
 * sanitizer builds LeakSanitizer would fail every program that compiles a
 * tape.  Only allocations made inside libgccjit are suppressed. */
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void)
{
    return "leak:libgccjit.so\nleak:libfontconfig.so\n";
}
#endif

#else /* no libgccjit: every compiler reports HL_EUNSUP, the interpreter runs */

int hl_tape_jit_available(void)
{
    return 0;
}

#endif
