/* The two halves of the hamlie executable: the launcher (launch.c, linked
 * with libc alone) and the module hamlie-cli.so (the commands, main.c and
 * the library behind them, FLINT included), loaded only for a command.
 * launch_gen.c copies the module's texts into launch_table.c at build time,
 * so that --version and --help need no module. */
#ifndef HAMLIE_CLI_LAUNCH_H
#define HAMLIE_CLI_LAUNCH_H

#include <stdio.h>

struct cli_command;

/* ---- the module's entry points (main.c) ---- */

/* The whole command line, as main() was before the split. */
int hamlie_cli_main(int argc, char **argv);
/* The command table (n commands) and the text of `hamlie --help`. */
const struct cli_command *hamlie_cli_table(int *n);
void hamlie_cli_usage(FILE *fp);

#define HAMLIE_CLI_ENTRY "hamlie_cli_main"
#define HAMLIE_CLI_MODULE "hamlie-cli.so"

/* ---- the launcher's copy (launch_table.c, generated) ---- */

extern const char hl_launch_version[];
extern const char hl_launch_usage[];
extern const int hl_launch_ncommands;
extern const char *const hl_launch_names[];
extern const char *const hl_launch_helps[];

#endif
