/* hamlie cache: the disk cache of compiled code (tape.h: hl_jit_cache_list,
 * hl_jit_cache_clear) — where it is, what it holds, and emptying it. */
#include <string.h>

#include "cli/cli.h"
#include "hamlie/tape.h"

const char cmd_cache_help[] =
    "usage: hamlie cache [--clear] [--json]\n"
    "\n"
    "The disk cache of compiled code: machine code that run, section and chaos\n"
    "compiled (with libgccjit) for a system, kept so that the next process with\n"
    "the same program loads it instead of compiling again.  Prints the\n"
    "directory, its entries and their size.  The directory is $HAMLIE_CACHE_DIR,\n"
    "else $XDG_CACHE_HOME/hamlie, else ~/.cache/hamlie; HAMLIE_CACHE=off turns\n"
    "the cache off.\n"
    "\n"
    "  --clear            remove hamlie's files from the directory (entries, and\n"
    "                     temporaries of processes that are gone); other files are\n"
    "                     left.  Safe while other hamlie processes run: one that\n"
    "                     loses an entry compiles again\n"
    "  --json             print a JSON object (schema: docs/json.md)\n"
    "  -h, --help         show this help\n"
    "\n"
    "Exit status: 0 done; 2 usage error, or the directory cannot be read or a\n"
    "file in it cannot be removed.\n";

static void found_opt(void *arg, int k, const char *value)
{
    (void)k, (void)value;
    *(int *)arg = 1;
}

/* "12.3 MB" and the like, for a human */
static void put_size(hl_buf *out, long long bytes)
{
    if (bytes < 1024)
        hl_buf_printf(out, "%lld bytes", bytes);
    else if (bytes < 1024 * 1024)
        hl_buf_printf(out, "%.1f KB", (double)bytes / 1024);
    else
        hl_buf_printf(out, "%.1f MB", (double)bytes / (1024 * 1024));
}

static void write_text(hl_buf *out, const hl_jit_cache_listing *l, int cleared)
{
    if (l->dir == NULL) {
        hl_buf_puts(out, "the cache is off (HAMLIE_CACHE=off, or no home directory)\n");
        return;
    }
    hl_buf_printf(out, "directory: %s%s\n", l->dir, l->exists ? "" : " (not made yet)");
    hl_buf_printf(out, "%s%ld entr%s, %ld file%s, ",
                  cleared ? "removed: " : "entries: ", l->entries, l->entries == 1 ? "y" : "ies",
                  l->files, l->files == 1 ? "" : "s");
    put_size(out, l->bytes);
    hl_buf_putc(out, '\n');
}

static void write_json(hl_buf *out, const hl_jit_cache_listing *l, int cleared)
{
    hl_json j;
    hl_json_init_buf(&j, out);
    hl_json_object_begin(&j);
    hl_json_kv_string(&j, "command", "cache");
    hl_json_key(&j, "directory");
    hl_json_string(&j, l->dir); /* null when the cache is off */
    hl_json_kv_bool(&j, "exists", l->exists);
    hl_json_kv_bool(&j, "cleared", cleared);
    hl_json_kv_int(&j, "entries", l->entries);
    hl_json_kv_int(&j, "files", l->files);
    hl_json_kv_int(&j, "bytes", (long)l->bytes);
    hl_json_object_end(&j);
    hl_json_finish(&j);
}

int cmd_cache(int argc, char **argv, const cli_command *self)
{
    const cli_command *cmd = self;
    static const cli_own own[] = {{"--clear", CLI_OWN_FLAG}};
    int clear = 0;
    cli_opts o;
    memset(&o, 0, sizeof o);
    int rc = cli_take_own(&argc, argv, own, 1, found_opt, &clear, cmd);
    if (rc >= 0)
        return rc;
    rc = cli_parse(&o, argc, argv, 0, cmd);
    if (rc < 0 && o.nargs > 0)
        rc = cli_usage(cmd, "unexpected argument '%s'", o.args[0]);
    if (rc < 0 && (o.H != NULL || o.pairs != NULL || o.params != NULL || o.step != NULL))
        rc = cli_usage(cmd, "cache takes no system options");
    if (rc < 0 && o.format == CLI_LATEX)
        rc = cli_usage(cmd, "cache has no LaTeX output");
    if (rc >= 0) {
        cli_opts_clear(&o);
        return rc;
    }
    hl_jit_cache_listing l;
    hl_error err;
    hl_status st = clear ? hl_jit_cache_clear(&l, &err) : hl_jit_cache_list(&l, &err);
    if (st != HL_OK)
        rc = cli_fail(&err);
    else {
        hl_buf out;
        hl_buf_init(&out);
        if (o.format == CLI_JSON)
            write_json(&out, &l, clear);
        else
            write_text(&out, &l, clear);
        rc = cli_emit(&out, CLI_OK);
        hl_buf_clear(&out);
    }
    hl_jit_cache_listing_clear(&l);
    cli_opts_clear(&o);
    return rc;
}
