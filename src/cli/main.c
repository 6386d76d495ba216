/* hamlie: the command table and the top-level options (git.c style: one
 * static table, one file per command).  Built into the module hamlie-cli.so,
 * which the launcher (launch.c) loads for every command; the launcher
 * answers --version and --help itself from a copy of this table's texts
 * made at build time (launch_gen.c), so they are written here only. */
#include <stdio.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/launch.h"
#include "hamlie/tape.h"

#define COMMON_OPTIONS                                                          \
    "  --pairs x:px,y:py  the canonical pairs (default: inferred from the names:\n" \
    "                     px,py.. with x,y..; p1..pN with q1..qN; p with q, else x)\n" \
    "  --param k=2        give a parameter a constant value (repeatable; other\n" \
    "                     symbols stay symbolic parameters)\n"                    \
    "  --step NAME        the step's name (default D; e.g. --step h when D is a\n" \
    "                     parameter such as a Morse depth)\n"                    \
    "  --json             print a JSON object (schema: docs/json.md)\n"         \
    "  --latex            print formulas as LaTeX\n"                             \
    "  -h, --help         show this help\n"                                      \
    "\n"                                                                       \
    "Formulas use + - * / ^ (or **), sin cos tan exp log sqrt atan asin acos\n" \
    "sinh cosh tanh asinh, atan2(y, x) (the angle of (x, y), in (-pi, pi]), pi;\n" \
    "D is the step (--step renames it), H names the Hamiltonian.\n"

static const cli_command commands[] = {
    {"generator", cmd_generator, "the evolution generator g of a Hamiltonian",
     "usage: hamlie generator -H FORMULA [options]\n"
     "\n"
     "Print the evolution generator (paper §2)\n"
     "  g = sum_j dH/dp_j d/dq_j - dH/dq_j d/dp_j,  so that g(phi) = {phi, H}.\n"
     "\n"
     "  -H, --hamiltonian F  the Hamiltonian (required)\n" COMMON_OPTIONS "\n"
     "Exit status: 0 computed; 2 usage or input error.\n"
     "Example: hamlie generator -H '(p^2+x^2)/2'   prints  𝔤 = p ∂/∂x − x ∂/∂p\n"},
    {"bracket", cmd_bracket, "the Poisson bracket {A, B} of two functions",
     "usage: hamlie bracket [-H FORMULA] [options] A B\n"
     "\n"
     "Print the Poisson bracket {A, B} = sum_j dA/dq_j dB/dp_j - dB/dq_j dA/dp_j,\n"
     "simplified.  In A and B, H names the Hamiltonian given with -H.\n"
     "\n"
     "  -H, --hamiltonian F  the Hamiltonian (needed when A or B mention H); with -H\n"
     "                       the variables come from H, else from A and B\n" COMMON_OPTIONS "\n"
     "Exit status: 0 computed; 2 usage or input error.\n"
     "Example: hamlie bracket -H '(px^2+py^2)/2 - 1/sqrt(x^2+y^2)' 'x*py - y*px' H\n"},
    {"check", cmd_check, "check integrals of motion, involution and independence",
     "usage: hamlie check -H FORMULA --integral I [--integral I2 ...] [options]\n"
     "\n"
     "For each given function I, compute {I, H} and say whether I is an integral\n"
     "of motion.  Also report the pairwise brackets {I_i, I_j} (involution), the\n"
     "rank of the Jacobian of the functions (functional independence), and\n"
     "whether H is among them or functionally dependent on them.\n"
     "\n"
     "  -H, --hamiltonian F  the Hamiltonian (required)\n"
     "  --integral F         a function to check (repeatable, at least one)\n" COMMON_OPTIONS "\n"
     "Exit status: 0 every function is an integral of motion; 1 computed, but some\n"
     "function is not an integral; 2 usage or input error.  (Involution and\n"
     "independence are reported, not required.)\n"},
    {"canonical", cmd_canonical, "check that a map (Q, P) = f(q, p; D) is canonical",
     "usage: hamlie canonical --map 'X = ...; P = ...' [-H FORMULA] [options]\n"
     "\n"
     "Compute every bracket {Q_i, P_j}, {Q_i, Q_j}, {P_i, P_j} of the images and\n"
     "compare them with delta_ij and 0, for every value of the step D.  The images\n"
     "are named by the variable in upper case (X for x, PX for px) or with a prime\n"
     "(x'), or are given in the order q_1..q_N, p_1..p_N.  Without -H the\n"
     "variables are inferred from the right-hand sides of the map.\n"
     "\n"
     "  --map MAP            the images, separated by ';' (required)\n"
     "  -H, --hamiltonian F  a Hamiltonian, if the map mentions H\n" COMMON_OPTIONS "\n"
     "Exit status: 0 the map is canonical; 1 computed, but it is not canonical;\n"
     "2 usage or input error.\n"
     "Example: hamlie canonical --map 'X = x + D*p; P = p - D*x'\n"},
    {"lie", cmd_lie, "the Lie series exp(D g) phi to a given order in D",
     "usage: hamlie lie -H FORMULA --order N [--of F ...] [--terms] [options]\n"
     "\n"
     "Print exp(D g) phi = sum_k D^k/k! g^k phi up to D^N, grouped by powers of D,\n"
     "for each phase variable (default) or for each function given with --of.\n"
     "\n"
     "  -H, --hamiltonian F  the Hamiltonian (required)\n"
     "  -n, --order N        the order in D (0..200; default 4)\n"
     "  --of F               the function phi (repeatable)\n"
     "  --terms              also print the terms g^k phi themselves\n"
     "  --progress, --quiet  progress on stderr from the start, or none (default:\n"
     "                       after a second or two)\n" COMMON_OPTIONS "\n"
     "A series whose terms grow past 2000000 terms is stopped with a message.\n"
     "Ctrl-C (SIGINT) stops it; nothing is printed.\n"
     "Exit status: 0 computed; 2 usage or input error (an order above the limit);\n"
     "130 interrupted.\n"
     "Example: hamlie lie -H 'p^2/2 - cos(q)' --order 6\n"},
    {"run", cmd_run, "run a scheme: a trajectory (CSV), its errors, observed orders", cmd_run_help},
    {"section", cmd_section, "surfaces of section: orbits on H = E, their crossings (CSV, figure)",
     cmd_section_help},
    {"schemes", cmd_schemes, "the catalog of one-step schemes", cmd_schemes_help},
    {"plot", cmd_plot, "figures of runs (CSV from hamlie run), compared", cmd_plot_help},
    {"errors", cmd_errors, "error analysis of a scheme: v_k, order, K(D) (paper §4)",
     cmd_errors_help},
    {"exact", cmd_exact, "the exact scheme of a quadratic H in closed form, checked (§3)",
     cmd_exact_help},
    {"chaos", cmd_chaos, "chaos indicators of an orbit: MEGNO, FLI, Lyapunov exponent", cmd_chaos_help},
    {"sweep", cmd_sweep,
     "many runs at once: points x parameters x schemes x steps, on every core",
     cmd_sweep_help},
    {"reproduce", cmd_reproduce, "the paper's figures and formulas, regenerated and checked",
     cmd_reproduce_help},
};

#define NCOMMANDS ((int)(sizeof commands / sizeof commands[0]))

static const cli_command *cli_find(const char *name)
{
    for (int i = 0; i < NCOMMANDS; i++)
        if (strcmp(commands[i].name, name) == 0)
            return &commands[i];
    return NULL;
}

static void usage(FILE *fp)
{
    fprintf(fp, "usage: hamlie COMMAND [options]\n"
                "       hamlie help COMMAND | --help | --version\n\n"
                "Lie-group/algebra study of time-independent Hamiltonian systems.\n\n"
                "Commands:\n");
    for (int i = 0; i < NCOMMANDS; i++)
        fprintf(fp, "  %-10s %s\n", commands[i].name, commands[i].summary);
    fprintf(fp, "\nEvery command takes --help, --json and --latex.\n"
                "Exit status: 0 computed (and, for check and canonical, every property\n"
                "holds); 1 computed but a checked property fails; 2 usage or input error.\n");
}

static int finish_stdout(void)
{
    if (fflush(stdout) != 0 || ferror(stdout)) {
        fprintf(stderr, "hamlie: error: writing to standard output failed\n");
        return CLI_ERROR;
    }
    return CLI_OK;
}

const cli_command *hamlie_cli_table(int *n)
{
    *n = NCOMMANDS;
    return commands;
}

void hamlie_cli_usage(FILE *fp)
{
    usage(fp);
}

/* What hamlie could not load and did without, said once the command is
 * done (the library reports it; printing is the command line's job). */
static void note_missing_libraries(void)
{
    const char *why = hl_tape_jit_load_error();
    if (why != NULL)
        fprintf(stderr, "hamlie: note: %s\n", why);
}

int hamlie_cli_main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "hamlie: error: no command given\n\n");
        usage(stderr);
        return CLI_ERROR;
    }
    const char *name = argv[1];
    if (strcmp(name, "--help") == 0 || strcmp(name, "-h") == 0) {
        usage(stdout);
        return finish_stdout();
    }
    if (strcmp(name, "--version") == 0) {
        printf("hamlie %s\n", HAMLIE_VERSION);
        return finish_stdout();
    }
    if (strcmp(name, "help") == 0) {
        if (argc < 3) {
            usage(stdout);
            return finish_stdout();
        }
        const cli_command *c = cli_find(argv[2]);
        if (c == NULL) {
            fprintf(stderr, "hamlie: error: unknown command '%s' (see hamlie --help)\n", argv[2]);
            return CLI_ERROR;
        }
        fputs(c->help, stdout);
        return finish_stdout();
    }
    const cli_command *c = cli_find(name);
    if (c == NULL) {
        fprintf(stderr, "hamlie: error: unknown command '%s' (see hamlie --help)\n", name);
        return CLI_ERROR;
    }
    int status = c->fn(argc - 1, argv + 1, c);
    note_missing_libraries();
    return status;
}
