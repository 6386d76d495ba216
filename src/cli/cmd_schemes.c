/* hamlie schemes: the catalog of one-step schemes (scheme.h). */
#include <stdlib.h>

#include "cli/cli.h"
#include "hamlie/scheme.h"

const char cmd_schemes_help[] =
    "usage: hamlie schemes [--json | --latex]\n"
    "\n"
    "List the catalog of schemes usable with --scheme NAME (run, errors): name,\n"
    "theoretical order, whether the scheme is symplectic, preserves H exactly,\n"
    "is implicit (for a general H), and a description.  Schemes marked\n"
    "'oscillator' are defined only for H = (p^2 + x^2)/2.  stormer-verlet and\n"
    "verlet are other names of stormer-verlet-kdk.  lieN is a family: name a\n"
    "member by its order, lie1 (explicit Euler) to lie20 (run --scheme lie alone\n"
    "is the adaptive Taylor integrator).\n"
    "\n"
    "  --json             print a JSON object (schema: docs/json.md)\n"
    "  --latex            print the table as a LaTeX tabular\n"
    "  -h, --help         show this help\n"
    "\n"
    "Exit status: 0 listed; 2 usage error.\n";

static const char *yes(unsigned flags, unsigned bit) { return (flags & bit) ? "yes" : "no"; }

static void order_text(char *s, size_t n, const hl_scheme_info *in)
{
    if (in->order == HL_SCHEME_EXACT)
        snprintf(s, n, "exact");
    else if (in->order == HL_SCHEME_ORDER_N)
        snprintf(s, n, "N");
    else
        snprintf(s, n, "%d", in->order);
}

static void write_json(hl_buf *out)
{
    hl_json j;
    hl_json_init_buf(&j, out);
    hl_json_object_begin(&j);
    hl_json_kv_string(&j, "command", "schemes");
    hl_json_key(&j, "schemes");
    hl_json_array_begin(&j);
    for (int i = 0; i < hl_scheme_catalog_count(); i++) {
        const hl_scheme_info *in = hl_scheme_catalog(i);
        hl_json_object_begin(&j);
        hl_json_kv_string(&j, "name", in->name);
        if (in->order == HL_SCHEME_EXACT || in->order == HL_SCHEME_ORDER_N) {
            hl_json_key(&j, "order");
            hl_json_null(&j);
        } else
            hl_json_kv_int(&j, "order", in->order);
        if (in->order == HL_SCHEME_ORDER_N) { /* a family: its members' orders */
            hl_json_key(&j, "order_range");
            hl_json_array_begin(&j);
            hl_json_int(&j, 1);
            hl_json_int(&j, HL_SCHEME_LIE_MAX);
            hl_json_array_end(&j);
        }
        hl_json_kv_bool(&j, "exact", in->order == HL_SCHEME_EXACT);
        hl_json_kv_bool(&j, "symplectic", (in->flags & HL_SCHEME_SYMPLECTIC) != 0);
        hl_json_kv_bool(&j, "preserves_H", (in->flags & HL_SCHEME_PRESERVES_H) != 0);
        hl_json_kv_bool(&j, "implicit", (in->flags & HL_SCHEME_IMPLICIT) != 0);
        hl_json_kv_bool(&j, "explicit_if_separable", (in->flags & HL_SCHEME_SEPARABLE) != 0);
        hl_json_kv_bool(&j, "oscillator_only", (in->flags & HL_SCHEME_OSCILLATOR) != 0);
        hl_json_kv_bool(&j, "quadratic_only", (in->flags & HL_SCHEME_QUADRATIC) != 0);
        hl_json_kv_string(&j, "description", in->description);
        hl_json_object_end(&j);
    }
    hl_json_array_end(&j);
    hl_json_object_end(&j);
    hl_json_finish(&j);
}

static void latex_escape(hl_buf *out, const char *s)
{
    for (; *s; s++) {
        if (*s == '_' || *s == '&' || *s == '%' || *s == '#' || *s == '$' || *s == '{' ||
            *s == '}')
            hl_buf_printf(out, "\\%c", *s);
        else if (*s == '^')
            hl_buf_puts(out, "\\^{}");
        else
            hl_buf_printf(out, "%c", *s);
    }
}

static void write_table(hl_buf *out, int latex)
{
    char ord[16];
    if (latex)
        hl_buf_puts(out, "\\begin{tabular}{lrllll}\n"
                         "name & order & symplectic & preserves $H$ & implicit & description \\\\\n"
                         "\\hline\n");
    else
        hl_buf_printf(out, "%-20s %-6s %-10s %-11s %-9s %s\n", "name", "order", "symplectic",
                      "preserves H", "implicit", "description");
    for (int i = 0; i < hl_scheme_catalog_count(); i++) {
        const hl_scheme_info *in = hl_scheme_catalog(i);
        unsigned f = in->flags;
        order_text(ord, sizeof ord, in);
        const char *impl = (f & HL_SCHEME_IMPLICIT)
                               ? ((f & HL_SCHEME_SEPARABLE) ? "yes*" : "yes")
                               : "no";
        if (latex) {
            hl_buf_puts(out, "\\texttt{");
            latex_escape(out, in->name);
            hl_buf_printf(out, "} & %s & %s & %s & %s & ", ord, yes(f, HL_SCHEME_SYMPLECTIC),
                          yes(f, HL_SCHEME_PRESERVES_H), impl);
            latex_escape(out, in->description);
            hl_buf_puts(out, (f & HL_SCHEME_OSCILLATOR) ? " (oscillator only) \\\\\n" : " \\\\\n");
        } else
            hl_buf_printf(out, "%-20s %-6s %-10s %-11s %-9s %s%s\n", in->name, ord,
                          yes(f, HL_SCHEME_SYMPLECTIC), yes(f, HL_SCHEME_PRESERVES_H), impl,
                          in->description, (f & HL_SCHEME_OSCILLATOR) ? " (oscillator only)" : "");
    }
    if (latex)
        hl_buf_puts(out, "\\end{tabular}\n");
    else
        hl_buf_puts(out, "yes*: implicit for a general H, explicit when H = T(p) + V(q)\n");
}

int cmd_schemes(int argc, char **argv, const cli_command *self)
{
    const cli_command *cmd = self;
    cli_opts o;
    int rc = cli_parse(&o, argc, argv, 0, cmd);
    if (rc < 0 && o.nargs > 0)
        rc = cli_usage(cmd, "unexpected argument '%s'", o.args[0]);
    if (rc < 0 && (o.H != NULL || o.pairs != NULL || o.params != NULL || o.step != NULL))
        rc = cli_usage(cmd, "schemes takes no system options");
    if (rc < 0) {
        hl_buf out;
        hl_buf_init(&out);
        if (o.format == CLI_JSON)
            write_json(&out);
        else
            write_table(&out, o.format == CLI_LATEX);
        rc = cli_emit(&out, CLI_OK);
        hl_buf_clear(&out);
    }
    cli_opts_clear(&o);
    return rc;
}
